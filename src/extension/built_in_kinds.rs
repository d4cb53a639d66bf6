//! The built-in kinds of light through [`PhongLightKind`], the trait every kind implements:
//! their records, validation and shadows, in one place for each kind. The built-in kinds
//! share the scene's light buffer (gathered by `render::gather_lights`, their constants
//! cached), where an extension's kind gets a buffer of its own ([`super::PhongLightKindPlugin`]).

use super::PhongLightKind;
use crate::lights::{PhongDirectionalLight, PhongPointLight, PhongSpotLight, light_direction};
use crate::limits;
use crate::render::{BuiltInLight, GpuLight};
use crate::shadows::{PhongShadowProjection, PhongShadowRequest};
use crate::validation::Checker;
use bevy::transform::components::GlobalTransform;
use core::any::TypeId;

/// Whether `L` is one of the built-in kinds, which `PhongPlugin` gathers itself.
pub(crate) fn is_built_in<L: PhongLightKind>() -> bool {
    [
        TypeId::of::<PhongDirectionalLight>(),
        TypeId::of::<PhongPointLight>(),
        TypeId::of::<PhongSpotLight>(),
    ]
    .contains(&TypeId::of::<L>())
}

/// What every built-in kind does alike: its record is `BuiltInLight`'s constants placed by
/// the transform, it casts shadows where its `shadows` are on, and its record holds the
/// shadow slot in `GpuLight::shadow`.
macro_rules! built_in_record {
    () => {
        type Gpu = GpuLight;

        fn to_gpu(&self, transform: &GlobalTransform) -> GpuLight {
            let mut record = self.constants();
            Self::place(&mut record, transform);
            record
        }

        fn casts_shadows(&self) -> bool {
            self.shadows.enabled
        }

        fn set_shadow(record: &mut GpuLight, shadow: u32) {
            record.shadow = shadow;
        }
    };
}

/// The directional light as a kind: its record, its validation and its shadow (cascades per
/// camera along its rays).
impl PhongLightKind for PhongDirectionalLight {
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

/// The point light as a kind: its record, its validation and its shadow (a cube map).
impl PhongLightKind for PhongPointLight {
    built_in_record!();

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

/// The spot light as a kind: its record, its validation and its shadow (one perspective map
/// over its cone).
impl PhongLightKind for PhongSpotLight {
    built_in_record!();

    fn validate(&mut self, checker: &mut Checker) {
        checker.color("color", &mut self.color);
        checker.optional_color("specular", &mut self.specular);
        checker.decay(&mut self.decay);
        checker.range(&mut self.range);
        checker.spot_angles(self);
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
