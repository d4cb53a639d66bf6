//! The point light as a kind of light ([`PhongLightKind`]): its record, reach, validation,
//! shadow and cookie projection.

use super::PhongPointLight;
use crate::light_kind::built_in::{Placed, built_in_record, fading_reach_kind, intensities};
use crate::light_kind::{GpuLight, PhongLightKind};
use crate::lights::PhongCookieProjection;
#[cfg(feature = "reference")]
use crate::reference::Light;
use crate::shadows::{PhongShadowProjection, PhongShadowRequest};
use crate::validation::Checker;
use bevy::transform::components::GlobalTransform;

impl PhongPointLight {
    /// Its light in the reference model.
    #[cfg(feature = "reference")]
    const REFERENCE: fn(&Self, &GlobalTransform) -> Light = Light::point;

    /// A cookie is a cube map around it.
    fn cookie_mapping(&self) -> PhongCookieProjection {
        PhongCookieProjection::Cube
    }

    /// Its transform sets the position only.
    const PLACED: Placed = Placed {
        position: true,
        direction: false,
    };

    /// The record without its position, shadow slot or reach: intensities, decay and the
    /// whole sphere as its cone (a local light, as the shader reads it).
    fn constants(&self) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        GpuLight {
            reach: f32::MAX,
            outer_versine: GpuLight::WHOLE_SPHERE,
            color,
            specular,
            decay: self.decay.to_array(),
            ..GpuLight::default()
        }
    }
}

/// The point light as a kind: its record, reach, validation and shadow (a cube map).
impl PhongLightKind for PhongPointLight {
    // Written by `built_in_record!` (built_in.rs), as for every built-in kind of `GpuLight`:
    // `type Gpu = GpuLight`, `to_gpu` (`constants`, placed by `place` as `Self::PLACED`
    // says), `casts_shadows`, `set_shadow`, `cookie_projection` (`cookie_mapping`),
    // `set_cookie` and `reference_light` (`Self::REFERENCE`).
    built_in_record!();
    // Written by `fading_reach_kind!` (built_in.rs), as for the spot and point lights:
    // `SHARES_EPSILON = true`, `reach` (`built_in::fading_reach`: its range, shortened to its
    // influence radius for ε), `set_reach` (into the record's `reach`) and `bounding_sphere` (around its
    // position).
    fading_reach_kind!();

    fn validate(&mut self, checker: &mut Checker) {
        checker.color("color", &mut self.color);
        checker.optional_color("specular", &mut self.specular);
        checker.decay(&mut self.decay);
        checker.range(&mut self.range);
        checker.shadows(&mut self.shadows);
    }

    fn shadow(&self, transform: &GlobalTransform) -> Option<PhongShadowRequest> {
        Some(PhongShadowRequest {
            projection: PhongShadowProjection::Omni {
                position: transform.translation(),
            },
            settings: self.shadows,
            reach: self.range.unwrap_or(f32::INFINITY),
        })
    }
}
