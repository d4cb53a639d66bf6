//! The directional light as a kind of light ([`PhongLightKind`]): its record, validation,
//! shadow and cookie projection.

use super::PhongDirectionalLight;
use crate::light_kind::built_in::{Placed, built_in_record, intensities};
use crate::light_kind::{GpuLight, PhongLightKind};
use crate::lights::{PhongCookieProjection, light_direction};
#[cfg(feature = "reference")]
use crate::reference::Light;
use crate::shadows::{PhongShadowProjection, PhongShadowRequest};
use crate::validation::Checker;
use bevy::transform::components::GlobalTransform;

impl PhongDirectionalLight {
    /// Its light in the reference model.
    #[cfg(feature = "reference")]
    const REFERENCE: fn(&Self, &GlobalTransform) -> Light = Light::directional;

    /// A cookie lies on its local XY plane.
    fn cookie_mapping(&self) -> PhongCookieProjection {
        PhongCookieProjection::Plane
    }

    /// Its transform sets the direction only.
    const PLACED: Placed = Placed {
        position: false,
        direction: true,
    };

    /// The record without its direction or shadow slot: its intensities.
    fn constants(&self) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        GpuLight {
            color,
            specular,
            ..GpuLight::default()
        }
    }
}

/// The directional light as a kind: its record, its validation and its shadow (cascades per
/// camera along its rays). It reaches everywhere and is never clustered.
impl PhongLightKind for PhongDirectionalLight {
    // Written by `built_in_record!` (built_in.rs), as for every built-in kind of `GpuLight`:
    // `type Gpu = GpuLight`, `to_gpu` (`constants`, placed by `place` as `Self::PLACED`
    // says), `casts_shadows`, `set_shadow`, `cookie_projection` (`cookie_mapping`),
    // `set_cookie` and `reference_light` (`Self::REFERENCE`).
    built_in_record!();

    fn validate(&mut self, checker: &mut Checker) {
        checker.color("color", &mut self.color);
        checker.optional_color("specular", &mut self.specular);
        checker.shadows(&mut self.shadows);
        checker.cascades(&mut self.cascades);
    }

    fn shadow(&self, transform: &GlobalTransform) -> Option<PhongShadowRequest> {
        Some(PhongShadowRequest {
            projection: PhongShadowProjection::Directional {
                direction: light_direction(transform),
                cascades: self.cascades,
            },
            settings: self.shadows,
            reach: f32::INFINITY,
        })
    }
}
