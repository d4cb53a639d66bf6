//! The spot light as a kind of light ([`PhongLightKind`]): its record, reach, validation,
//! shadow and cookie projection.

use super::{PhongSpotLight, cone::spot_cone_terms};
use crate::light_kind::built_in::{Placed, built_in_record, fading_reach_kind, intensities};
use crate::light_kind::{GpuLight, PhongLightKind};
use crate::lights::{PhongCookieProjection, light_direction};
use crate::limits;
#[cfg(feature = "reference")]
use crate::reference::Light;
use crate::shadows::{PhongShadowProjection, PhongShadowRequest};
use crate::validation::Checker;
use bevy::transform::components::GlobalTransform;

impl PhongSpotLight {
    /// Its light in the reference model.
    #[cfg(feature = "reference")]
    const REFERENCE: fn(&Self, &GlobalTransform) -> Light = Light::spot;

    /// A cookie spans its cone.
    fn cookie_mapping(&self) -> PhongCookieProjection {
        PhongCookieProjection::Cone {
            half_angle: self.outer_angle,
        }
    }

    /// Its transform sets the position and the direction.
    const PLACED: Placed = Placed {
        position: true,
        direction: true,
    };

    /// The record without its placement, shadow slot or reach: intensities, decay and the
    /// cone's terms.
    fn constants(&self) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        let (outer_versine, cone_scale) =
            spot_cone_terms(self.inner_angle, self.outer_angle, self.cone_edge);
        GpuLight {
            reach: f32::MAX,
            outer_versine,
            color,
            cone_scale,
            specular,
            cone_exponent: self.exponent,
            decay: self.decay.to_array(),
            ..GpuLight::default()
        }
    }
}

/// The spot light as a kind: its record, reach, validation and shadow (one perspective map
/// over its cone).
impl PhongLightKind for PhongSpotLight {
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
        validate_angles(checker, self);
        checker.scalar("exponent", &mut self.exponent, limits::EXPONENT);
        checker.shadows(&mut self.shadows);
    }

    fn shadow(&self, transform: &GlobalTransform) -> Option<PhongShadowRequest> {
        Some(PhongShadowRequest {
            projection: PhongShadowProjection::Cone {
                position: transform.translation(),
                direction: light_direction(transform),
                half_angle: self.outer_angle,
            },
            settings: self.shadows,
            reach: self.range.unwrap_or(f32::INFINITY),
        })
    }
}

/// Brings the cone's angles into `[0, π]` and the inner one to at most the outer one (a hard
/// edge), each replacement reported by `checker`.
fn validate_angles(checker: &mut Checker, light: &mut PhongSpotLight) {
    checker.scalar("inner_angle", &mut light.inner_angle, limits::CONE_ANGLE);
    checker.scalar("outer_angle", &mut light.outer_angle, limits::CONE_ANGLE);
    let outer = light.outer_angle;
    checker.at_most(
        "inner_angle",
        &mut light.inner_angle,
        ("outer_angle", outer),
        "a hard edge",
    );
}
