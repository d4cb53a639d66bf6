//! What the crate needs to know of a kind of light, from its GPU record to its shadows and
//! its reference-model light: [`PhongLightKind`], which the built-in kinds implement
//! ([`built_in`]) as an extension's kind does (`bevy_phong::extension`).

mod built_in;
mod built_in_kinds;
mod directional;
mod disk;
mod gpu_area_light;
mod gpu_light;
#[cfg(test)]
pub(crate) mod line;
mod point;
mod record_cache;
mod rect;
mod spot;

pub use built_in::linear_rgb;
pub(crate) use built_in::local_sphere;
pub use built_in_kinds::BuiltInLights;
pub(crate) use built_in_kinds::{
    BuiltInCaches, BuiltInRegistrar, BuiltInVisitor, is_built_in, register_built_in_kinds,
};
pub use directional::PhongDirectionalLight;
pub use disk::PhongDiskLight;
pub use gpu_area_light::GpuAreaLight;
pub use gpu_light::GpuLight;
pub use point::PhongPointLight;
pub(crate) use record_cache::RecordCache;
pub use rect::PhongRectLight;
pub use spot::PhongSpotLight;

use crate::lights::PhongCookieProjection;
#[cfg(feature = "reference")]
use crate::reference::ReferenceLight;
use crate::shadows::PhongShadowRequest;
use crate::validation::Checker;
use bevy::{
    ecs::component::{Component, Mutable},
    shape::BoundingSphere,
    transform::components::GlobalTransform,
};
use bytemuck::Pod;
#[cfg(feature = "reference")]
use std::sync::Arc;

/// A kind of light: what the crate needs to know of it, from its GPU record to its shadows.
/// The built-in kinds ([`PhongDirectionalLight`](crate::PhongDirectionalLight),
/// [`PhongPointLight`](crate::PhongPointLight), [`PhongSpotLight`](crate::PhongSpotLight),
/// [`PhongRectLight`](crate::PhongRectLight), [`PhongDiskLight`](crate::PhongDiskLight))
/// implement it, and so does a kind an extension adds, whose lights
/// [`PhongLightKindPlugin`](crate::extension::PhongLightKindPlugin) gathers into a GPU
/// buffer of their own.
pub trait PhongLightKind: Component<Mutability = Mutable> {
    /// The record the shader reads for one light: `#[repr(C)]`, a multiple of 16 bytes.
    type Gpu: Pod + Send + Sync;

    /// Whether these lights take a share of
    /// [`PhongLightCulling::epsilon`](crate::PhongLightCulling::epsilon) with the point and spot
    /// lights: then `n`, which ε is divided by, counts them too, and [`Self::reach`] is given the
    /// same per-light ε. Set it when `reach` uses ε, so that ε bounds what all the skipped lights
    /// leave out together. Default `false`.
    const SHARES_EPSILON: bool = false;

    /// The record of this light, placed by its entity's transform.
    fn to_gpu(&self, transform: &GlobalTransform) -> Self::Gpu;

    /// Moves `record`, made by [`Self::to_gpu`] from an equal component, to `transform`,
    /// and returns `true`; a kind that can do so lets a gather keep the placement-free part
    /// of its records (colors, cone terms, reach) while the component stays equal, so a moved
    /// light costs its placement only. The default returns `false`: the gather calls
    /// `to_gpu` again.
    fn place(record: &mut Self::Gpu, transform: &GlobalTransform) -> bool {
        let _ = (record, transform);
        false
    }

    /// How far this light, whose record is `record`, reaches, world units: past it the light
    /// may be skipped. The component holds what limits it (a range) and the record what it
    /// gives (its colors and fall-off as the shader reads them). `epsilon` is the light's
    /// share of
    /// [`PhongLightCulling::epsilon`](crate::PhongLightCulling::epsilon) (linear RGB; `0` for the
    /// exact model, and for a kind without [`Self::SHARES_EPSILON`]): a light that fades may stop
    /// where it falls below it, as the built-in lights do
    /// ([`influence_radius`](crate::extension::influence_radius)). `f32::INFINITY` (the default)
    /// reaches everywhere; `0` leaves the light out of the buffer.
    fn reach(&self, record: &Self::Gpu, epsilon: f32) -> f32 {
        let _ = (record, epsilon);
        f32::INFINITY
    }

    /// Stores the light's [`Self::reach`] in its record, for the shader to cut the light
    /// off there: the one place a record's reach is written (the gather calls it after
    /// [`Self::to_gpu`]). The default stores nothing.
    fn set_reach(record: &mut Self::Gpu, reach: f32) {
        let _ = (record, reach);
    }

    /// A sphere holding every point that the light of `record` lights within `reach` (a
    /// finite [`Self::reach`]), for the per-view light clusters: a kind that gives one is
    /// listed only in the clusters its sphere meets, so a fragment loops only over the
    /// lights that may reach it (see [`crate::extension`], "Clusters"). `None` (the
    /// default): every fragment loops over the light.
    fn bounding_sphere(record: &Self::Gpu, reach: f32) -> Option<BoundingSphere> {
        let _ = (record, reach);
        None
    }

    /// Replaces every invalid field with a valid value, reporting each through `checker`
    /// (a warning and an [`InvalidInput`](crate::InvalidInput) naming the entity and the
    /// field). Run on each light whose component changed, before it is gathered. The
    /// default checks nothing.
    fn validate(&mut self, checker: &mut Checker) {
        let _ = checker;
    }

    /// Whether this light may cast a shadow: only such lights are asked for
    /// [`Self::shadow`] each frame (the crate keeps a list of them, updated when a light
    /// changes), so lights that cast none cost the shadow pass nothing. Default `true`.
    fn casts_shadows(&self) -> bool {
        true
    }

    /// The shadow this light casts, placed by its entity's transform; `None` (the default),
    /// or a request whose settings are off, casts none. See
    /// [`PhongShadowProjection`](crate::extension::PhongShadowProjection) for
    /// the shapes of light that get maps.
    fn shadow(&self, transform: &GlobalTransform) -> Option<PhongShadowRequest> {
        let _ = transform;
        None
    }

    /// How a [`PhongLightCookie`](crate::PhongLightCookie) on this light's entity lays its
    /// image over the light; `None` (the default): the kind takes no cookie, and one on its
    /// entity is ignored. The crate puts the image in its cookie atlas and the cookie's
    /// record after the built-in lights, and hands the record's index to
    /// [`Self::set_cookie`].
    fn cookie_projection(&self) -> Option<PhongCookieProjection> {
        None
    }

    /// Stores the index of the light's cookie record in the built-in light buffer plus one,
    /// or `0` for a light without a cookie this frame. The shader passes the index (minus
    /// one) to `bevy_phong::shaders::cookies::light_cookie(index, world_position)`, which
    /// returns the tint that multiplies the light's colors there (while
    /// `PHONG_LIGHT_COOKIES` is set: some light has a cookie). Kinds without cookies keep
    /// the default, which stores nothing.
    fn set_cookie(record: &mut Self::Gpu, cookie: u32) {
        let _ = (record, cookie);
    }

    /// This light in the crate's reference model ([`crate::reference`], feature `reference`),
    /// placed by its entity's transform: its term in `f64`, as its shader adds it, for tests
    /// that compare a frame with the model
    /// ([`reference_lights`](crate::extension::reference_lights) collects every kind's).
    /// `None` (the default): the model leaves the light out.
    #[cfg(feature = "reference")]
    fn reference_light(&self, transform: &GlobalTransform) -> Option<Arc<dyn ReferenceLight>> {
        let _ = transform;
        None
    }

    /// Stores the light's shadow slot in its record: the index of its first shadow view plus
    /// one, or `0` when it casts no shadow this frame. The shader passes it to
    /// `bevy_phong::shaders::shadows::light_visibility`. Kinds without shadows keep the default,
    /// which stores nothing.
    fn set_shadow(record: &mut Self::Gpu, shadow: u32) {
        let _ = (record, shadow);
    }
}
