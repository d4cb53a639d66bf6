//! Which light entities give light this frame, and which way they point: the rules every
//! reader of lights shares (the gather of the built-in lights, the shadow requests, the
//! extensions' gathers, the reference model).

use bevy::{
    camera::visibility::InheritedVisibility,
    ecs::{
        change_detection::Ref,
        component::Component,
        entity::Entity,
        lifecycle::RemovedComponents,
        query::{Changed, Or, With},
        system::{Query, SystemParam},
    },
    math::Vec3,
    transform::components::GlobalTransform,
};

/// The lights of kind `L` with the entity, transform and visibility their record is made
/// from.
pub(crate) type LightQuery<'w, 's, L> = Query<
    'w,
    's,
    (
        Entity,
        &'static L,
        &'static GlobalTransform,
        &'static InheritedVisibility,
    ),
>;

/// [`LightQuery`] with each light's change ticks, for readers that keep what they made
/// from a light until it changes.
pub(crate) type TrackedLightQuery<'w, 's, L> = Query<
    'w,
    's,
    (
        Entity,
        Ref<'static, L>,
        &'static GlobalTransform,
        &'static InheritedVisibility,
    ),
>;

/// Whether a light gives light: visible, with a finite transform (a light whose transform
/// is not finite is skipped while it is; see [`crate::validation`]).
pub(crate) fn gives_light(visibility: &InheritedVisibility, transform: &GlobalTransform) -> bool {
    visibility.get() && is_finite_transform(transform)
}

/// The lights in `lights` that give light ([`gives_light`]).
pub(crate) fn lit_lights<'a, L: Component>(
    lights: &'a LightQuery<L>,
) -> impl Iterator<Item = (Entity, &'a L, &'a GlobalTransform)> {
    lights
        .iter()
        .filter(|(_, _, transform, visibility)| gives_light(visibility, transform))
        .map(|(entity, light, transform, _)| (entity, light, transform))
}

/// The light `entity` of `lights`, if it is one and gives light ([`gives_light`]).
pub(crate) fn lit_light<'a, L: Component>(
    lights: &'a LightQuery<L>,
    entity: Entity,
) -> Option<(&'a L, &'a GlobalTransform)> {
    let (_, light, transform, visibility) = lights.get(entity).ok()?;
    gives_light(visibility, transform).then_some((light, transform))
}

/// The lights in `lights` that give light ([`gives_light`]), with their change ticks.
pub(crate) fn lit_tracked_lights<'a, L: Component>(
    lights: &'a TrackedLightQuery<L>,
) -> impl Iterator<Item = (Entity, Ref<'a, L>, &'a GlobalTransform)> {
    lights
        .iter()
        .filter(|(_, _, transform, visibility)| gives_light(visibility, transform))
        .map(|(entity, light, transform, _)| (entity, light, transform))
}

/// Whether a light at `transform` can be gathered: a finite translation and basis.
pub fn is_finite_transform(transform: &GlobalTransform) -> bool {
    let affine = transform.affine();
    affine.translation.is_finite() && affine.matrix3.is_finite()
}

/// The unit vector a light travels along: the entity's world -Z, or zero for a transform
/// that has collapsed it (zero scale). Normalized at any scale: a scale of 1e38 or 1e-30
/// keeps the direction.
pub fn light_direction(transform: &GlobalTransform) -> Vec3 {
    crate::direction::normalize_or_zero(transform.affine().matrix3 * Vec3::NEG_Z)
}

/// Matches the lights of kind `L` whose component, transform or visibility changed.
pub type LightChanged<L> = (
    With<L>,
    Or<(
        Changed<L>,
        Changed<GlobalTransform>,
        Changed<InheritedVisibility>,
    )>,
);

/// Whether any light of kind `L` was added, changed, moved, shown, hidden or removed since
/// the last run of the system that holds this parameter.
#[derive(SystemParam)]
pub struct LightChanges<'w, 's, L: Component> {
    changed: Query<'w, 's, (), LightChanged<L>>,
    removed: RemovedComponents<'w, 's, L>,
}

impl<L: Component> LightChanges<'_, '_, L> {
    /// `true` if any light of kind `L` changed. Call it once per run: it consumes the
    /// removals it has seen.
    pub fn any(&mut self) -> bool {
        let removed = self.removed.read().count() > 0;
        removed || !self.changed.is_empty()
    }
}
