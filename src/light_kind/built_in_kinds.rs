//! The list of the built-in kinds, written once ([`built_in_kinds!`]'s table at the end):
//! each kind's name and type, in the section of the scene's light buffer it is gathered into
//! (reaching everywhere, local, area) and in the order the gather visits them. The table
//! gives the gather's query and change detector of each kind ([`BuiltInLights`]), the record
//! cache of each local and area kind ([`BuiltInCaches`]), the kinds `PhongPlugin` registers
//! ([`register_built_in_kinds`]) and [`is_built_in`]. A new built-in kind is its folder, one
//! row here, and its type exported from the crate's root.

use super::{
    GpuAreaLight, GpuLight, PhongDirectionalLight, PhongDiskLight, PhongLightKind, PhongPointLight,
    PhongRectLight, PhongSpotLight, RecordCache,
};
use crate::lights::{LightChanges, LightQuery, TrackedLightQuery};
use bevy::ecs::system::SystemParam;
use core::any::TypeId;

/// What a gather does with the lights of each built-in kind ([`BuiltInLights`]).
pub(crate) trait BuiltInVisitor {
    /// The lights of a kind that reaches everywhere.
    fn everywhere<L: PhongLightKind<Gpu = GpuLight>>(&mut self, lights: &LightQuery<L>);

    /// The lights of a local kind, with its cache.
    fn local<L: PhongLightKind<Gpu = GpuLight> + Clone + PartialEq>(
        &mut self,
        lights: &TrackedLightQuery<L>,
        cache: &mut RecordCache<L>,
    );

    /// The lights of an area kind, with its cache.
    fn area<L: PhongLightKind<Gpu = GpuAreaLight> + Clone + PartialEq>(
        &mut self,
        lights: &TrackedLightQuery<L>,
        cache: &mut RecordCache<L>,
    );
}

/// What the plugin does with each built-in kind as it is added ([`register_built_in_kinds`]):
/// each is registered as every kind is, and an area kind's reference-model light too.
pub(crate) trait BuiltInRegistrar {
    /// Registers kind `L` (its systems, its reflection).
    fn kind<L: PhongLightKind + bevy::reflect::GetTypeRegistration>(&mut self);

    /// Registers area kind `L`'s reference-model light, collected as an extension kind's.
    fn area_kind<L: PhongLightKind>(&mut self);
}

/// The lights of a kind that reaches everywhere, and whether any changed.
#[derive(SystemParam)]
pub struct EverywhereLights<'w, 's, L: PhongLightKind> {
    lights: LightQuery<'w, 's, L>,
    changes: LightChanges<'w, 's, L>,
}

/// The lights of a local or area kind, each with its change ticks (for its record cache),
/// and whether any changed.
#[derive(SystemParam)]
pub struct TrackedLights<'w, 's, L: PhongLightKind> {
    lights: TrackedLightQuery<'w, 's, L>,
    changes: LightChanges<'w, 's, L>,
}

/// Declares the built-in kinds: see the module's docs.
macro_rules! built_in_kinds {
    (
        everywhere: [$($everywhere:ident: $everywhere_kind:ty),* $(,)?],
        local: [$($local:ident: $local_kind:ty),* $(,)?],
        area: [$($area:ident: $area_kind:ty),* $(,)?] $(,)?
    ) => {
        /// The built-in kinds' lights as the scene's light buffer holds them: the lights that
        /// reach everywhere, then each kind of local light, then each kind of area light,
        /// whose records the gather keeps in a [`RecordCache`] while its component is
        /// unchanged; each kind with its change detector.
        #[derive(SystemParam)]
        pub struct BuiltInLights<'w, 's> {
            $($everywhere: EverywhereLights<'w, 's, $everywhere_kind>,)*
            $($local: TrackedLights<'w, 's, $local_kind>,)*
            $($area: TrackedLights<'w, 's, $area_kind>,)*
        }

        /// The record caches of the built-in local and area kinds (see [`BuiltInLights`]).
        #[derive(Debug, Default)]
        pub(crate) struct BuiltInCaches {
            $($local: RecordCache<$local_kind>,)*
            $($area: RecordCache<$area_kind>,)*
        }

        impl BuiltInLights<'_, '_> {
            /// Whether a light of any built-in kind was added, changed, moved, shown, hidden
            /// or removed since the last run. Every kind's detector is read: each drains its
            /// removals.
            pub(crate) fn changed(&mut self) -> bool {
                let changes = [
                    $(self.$everywhere.changes.any(),)*
                    $(self.$local.changes.any(),)*
                    $(self.$area.changes.any(),)*
                ];
                changes.contains(&true)
            }

            /// Hands `visitor` the lights of each kind that reaches everywhere.
            pub(crate) fn visit_everywhere(&self, visitor: &mut impl BuiltInVisitor) {
                $(visitor.everywhere(&self.$everywhere.lights);)*
            }

            /// Hands `visitor` the lights of each local kind, in the buffer's order, with its
            /// cache.
            pub(crate) fn visit_local(
                &self,
                caches: &mut BuiltInCaches,
                visitor: &mut impl BuiltInVisitor,
            ) {
                $(visitor.local(&self.$local.lights, &mut caches.$local);)*
            }

            /// Hands `visitor` the lights of each area kind, in the buffer's order, with its
            /// cache.
            pub(crate) fn visit_area(
                &self,
                caches: &mut BuiltInCaches,
                visitor: &mut impl BuiltInVisitor,
            ) {
                $(visitor.area(&self.$area.lights, &mut caches.$area);)*
            }
        }

        /// Hands `registrar` each built-in kind, in the buffer's order, and each area kind
        /// again.
        pub(crate) fn register_built_in_kinds(registrar: &mut impl BuiltInRegistrar) {
            $(registrar.kind::<$everywhere_kind>();)*
            $(registrar.kind::<$local_kind>();)*
            $(registrar.kind::<$area_kind>();)*
            $(registrar.area_kind::<$area_kind>();)*
        }

        /// Whether `L` is one of the built-in kinds, which `PhongPlugin` gathers itself.
        pub(crate) fn is_built_in<L: PhongLightKind>() -> bool {
            [
                $(TypeId::of::<$everywhere_kind>(),)*
                $(TypeId::of::<$local_kind>(),)*
                $(TypeId::of::<$area_kind>(),)*
            ]
            .contains(&TypeId::of::<L>())
        }
    };
}

built_in_kinds! {
    everywhere: [directional: PhongDirectionalLight],
    local: [point: PhongPointLight, spot: PhongSpotLight],
    area: [rect: PhongRectLight, disk: PhongDiskLight],
}
