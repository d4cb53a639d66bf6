//! What the built-in kinds of light share: each one's record is its placement-free
//! constants, then its placement by the transform ([`built_in_record`]); the kinds that fade
//! with distance share their reach ([`fading_reach_kind`]). Each kind's own part is in its
//! folder, and their list in `built_in_kinds`. The built-in kinds share the scene's light
//! buffer (gathered by `render::gather_lights` through these methods, their constants
//! cached), where an extension's kind gets a buffer of its own
//! ([`PhongLightKindPlugin`](crate::extension::PhongLightKindPlugin)).

use super::GpuLight;
use crate::lights::{influence_radius, light_direction};
use bevy::{
    color::Color, math::Vec3, shape::BoundingSphere, transform::components::GlobalTransform,
};

/// The bounding sphere of a local light's record that reaches `reach` (short of
/// `f32::MAX`, which is unlimited): around its position. Every built-in local kind's.
pub(crate) fn local_sphere(record: &GpuLight, reach: f32) -> Option<BoundingSphere> {
    (reach < f32::MAX).then(|| BoundingSphere::new(Vec3::from(record.position), reach))
}

/// A color's linear RGB components (alpha dropped).
pub fn linear_rgb(color: Color) -> [f32; 3] {
    let linear = color.to_linear();
    [linear.red, linear.green, linear.blue]
}

/// What every built-in kind does alike: its record is its constants (the fields its
/// component alone sets) placed by the transform, its placement can be redone on a cached
/// record, it casts shadows where its `shadows` are on, its reference-model light is
/// `reference::Light`'s constructor `Self::REFERENCE` (unshadowed, without its cookie: the
/// model applies those per light, see `reference::shade_shadowed` and
/// `reference::cookies`), it takes a cookie, and its record
/// holds the shadow slot in `GpuLight::shadow`'s low half and the cookie's in its high half.
macro_rules! built_in_record {
    () => {
        type Gpu = $crate::light_kind::GpuLight;

        fn to_gpu(
            &self,
            transform: &bevy::transform::components::GlobalTransform,
        ) -> $crate::light_kind::GpuLight {
            let mut record = self.constants();
            Self::place(&mut record, transform);
            record
        }

        fn place(
            record: &mut $crate::light_kind::GpuLight,
            transform: &bevy::transform::components::GlobalTransform,
        ) -> bool {
            $crate::light_kind::built_in::place(record, transform, Self::PLACED);
            true
        }

        fn casts_shadows(&self) -> bool {
            self.shadows.enabled
        }

        #[cfg(feature = "reference")]
        fn reference_light(
            &self,
            transform: &bevy::transform::components::GlobalTransform,
        ) -> Option<std::sync::Arc<dyn $crate::reference::ReferenceLight>> {
            Some(std::sync::Arc::new(Self::REFERENCE(self, transform)))
        }

        fn set_shadow(record: &mut $crate::light_kind::GpuLight, shadow: u32) {
            record.set_shadow_slot(shadow);
        }

        fn cookie_projection(&self) -> Option<$crate::lights::PhongCookieProjection> {
            Some(self.cookie_mapping())
        }

        fn set_cookie(record: &mut $crate::light_kind::GpuLight, cookie: u32) {
            record.set_cookie_index(cookie);
        }
    };
}
pub(crate) use built_in_record;

/// What every kind that fades with distance (point, spot) does alike: it shares ε, reaches
/// as far as its range and its influence radius allow, and is clustered where that is a
/// finite sphere, shadow and cookie or not (the clusters' loop applies both).
macro_rules! fading_reach_kind {
    () => {
        const SHARES_EPSILON: bool = true;

        fn reach(&self, record: &$crate::light_kind::GpuLight, epsilon: f32) -> f32 {
            $crate::light_kind::built_in::fading_reach(record, self.range, epsilon)
        }

        fn set_reach(record: &mut $crate::light_kind::GpuLight, reach: f32) {
            record.reach = $crate::light_kind::built_in::stored_reach(reach);
        }

        fn bounding_sphere(
            record: &$crate::light_kind::GpuLight,
            reach: f32,
        ) -> Option<bevy::shape::BoundingSphere> {
            $crate::light_kind::built_in::local_sphere(record, reach)
        }
    };
}
pub(crate) use fading_reach_kind;

/// Which parts of its record a kind's transform sets.
#[derive(Clone, Copy)]
pub(crate) struct Placed {
    pub position: bool,
    pub direction: bool,
}

/// Sets the parts of `record` that `placed` names from `transform`: the position its
/// translation, the direction its `-Z` axis ([`light_direction`]).
pub(crate) fn place(record: &mut GpuLight, transform: &GlobalTransform, placed: Placed) {
    if placed.position {
        record.position = transform.translation().to_array();
    }
    if placed.direction {
        record.direction = light_direction(transform).to_array();
    }
}

/// How far a point or spot light of `record` and `range` reaches for the per-light
/// `epsilon`: its range, shortened to its influence radius (see [`crate::culling`]) from its
/// largest color or specular channel; `f32::INFINITY` for one without a range that ε does
/// not limit, and `0` where it reaches nowhere.
pub(crate) fn fading_reach(record: &GpuLight, range: Option<f32>, epsilon: f32) -> f32 {
    let intensity = brightest_channel(record.color, record.specular);
    unlimited_past_max(range.unwrap_or(f32::INFINITY).min(influence_radius(
        record.decay,
        intensity,
        epsilon,
    )))
}

/// The largest channel of a light's diffuse and specular intensities.
pub(crate) fn brightest_channel(color: [f32; 3], specular: [f32; 3]) -> f32 {
    color.into_iter().chain(specular).fold(0.0, f32::max)
}

/// `reach`, read as unlimited (`f32::INFINITY`) from `f32::MAX` on, where a stored reach
/// means none ([`stored_reach`]).
pub(crate) fn unlimited_past_max(reach: f32) -> f32 {
    if reach >= f32::MAX {
        f32::INFINITY
    } else {
        reach
    }
}

/// `reach` as a record stores it: an unlimited one (`f32::INFINITY`) as `f32::MAX`, which
/// no distance passes.
pub(crate) fn stored_reach(reach: f32) -> f32 {
    reach.min(f32::MAX)
}

/// The diffuse and specular intensities of a light whose specular color may default.
pub(crate) fn intensities(color: Color, specular: Option<Color>) -> ([f32; 3], [f32; 3]) {
    (linear_rgb(color), linear_rgb(specular.unwrap_or(color)))
}
