//! The built-in kinds of light through [`PhongLightKind`], the trait every kind implements:
//! their records (placement-free constants, then the placement), reach, validation and
//! shadows, in one place for each kind. The built-in kinds share the scene's light buffer
//! (gathered by `render::gather_lights` through these methods, their constants cached),
//! where an extension's kind gets a buffer of its own
//! ([`PhongLightKindPlugin`](crate::extension::PhongLightKindPlugin)).

use super::{GpuLight, PhongLightKind};
use crate::lights::influence_radius;
use crate::lights::{
    ConeEdge, PhongCookieProjection, PhongDirectionalLight, PhongPointLight, PhongSpotLight,
    light_direction,
};
use crate::limits;
#[cfg(feature = "reference")]
use crate::reference::{Light, ReferenceLight};
use crate::shadows::{PhongShadowProjection, PhongShadowRequest};
use crate::validation::Checker;
use bevy::{
    color::Color, math::Vec3, shape::BoundingSphere, transform::components::GlobalTransform,
};
use core::any::TypeId;
#[cfg(feature = "reference")]
use std::sync::Arc;

/// Whether `L` is one of the built-in kinds, which `PhongPlugin` gathers itself.
pub(crate) fn is_built_in<L: PhongLightKind>() -> bool {
    [
        TypeId::of::<PhongDirectionalLight>(),
        TypeId::of::<PhongPointLight>(),
        TypeId::of::<PhongSpotLight>(),
    ]
    .contains(&TypeId::of::<L>())
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
        type Gpu = GpuLight;

        fn to_gpu(&self, transform: &GlobalTransform) -> GpuLight {
            let mut record = self.constants();
            Self::place(&mut record, transform);
            record
        }

        fn place(record: &mut GpuLight, transform: &GlobalTransform) -> bool {
            self::place(record, transform, Self::PLACED);
            true
        }

        fn casts_shadows(&self) -> bool {
            self.shadows.enabled
        }

        #[cfg(feature = "reference")]
        fn reference_light(&self, transform: &GlobalTransform) -> Option<Arc<dyn ReferenceLight>> {
            Some(Arc::new(Self::REFERENCE(self, transform)))
        }

        fn set_shadow(record: &mut GpuLight, shadow: u32) {
            record.shadow = (record.shadow & !GpuLight::SHADOW_BITS) | shadow;
        }

        fn cookie_projection(&self) -> Option<PhongCookieProjection> {
            Some(self.cookie_mapping())
        }

        fn set_cookie(record: &mut GpuLight, cookie: u32) {
            record.shadow =
                (record.shadow & GpuLight::SHADOW_BITS) | cookie << GpuLight::COOKIE_SHIFT;
        }
    };
}

/// What every kind that fades with distance (point, spot) does alike: it shares ε, reaches
/// as far as its range and its influence radius allow, and is clustered where that is a
/// finite sphere, shadow and cookie or not (the clusters' loop applies both).
macro_rules! fading_reach {
    () => {
        const SHARES_EPSILON: bool = true;

        fn reach(record: &GpuLight, epsilon: f32) -> f32 {
            fading_reach(record, epsilon)
        }

        fn set_reach(record: &mut GpuLight, reach: f32) {
            record.range = reach.min(f32::MAX);
        }

        fn bounding_sphere(record: &GpuLight, reach: f32) -> Option<BoundingSphere> {
            (reach < f32::MAX).then(|| BoundingSphere::new(Vec3::from(record.position), reach))
        }
    };
}

/// Which parts of its record a kind's transform sets.
#[derive(Clone, Copy)]
struct Placed {
    position: bool,
    direction: bool,
}

/// Sets the parts of `record` that `placed` names from `transform`: the position its
/// translation, the direction its `-Z` axis ([`light_direction`]).
fn place(record: &mut GpuLight, transform: &GlobalTransform, placed: Placed) {
    if placed.position {
        record.position = transform.translation().to_array();
    }
    if placed.direction {
        record.direction = light_direction(transform).to_array();
    }
}

/// How far a point or spot light of `record` reaches for the per-light `epsilon`: its
/// range, shortened to its influence radius (see [`crate::culling`]) from its largest color
/// or specular channel; `f32::INFINITY` for one without a range that ε does not limit, and
/// `0` where it reaches nowhere.
fn fading_reach(record: &GpuLight, epsilon: f32) -> f32 {
    let intensity = record
        .color
        .into_iter()
        .chain(record.specular)
        .fold(0.0, f32::max);
    let reach = record
        .range
        .min(influence_radius(record.decay, intensity, epsilon));
    if reach >= f32::MAX {
        f32::INFINITY
    } else {
        reach
    }
}

/// `range`, with `None` stored as `f32::MAX` (never reached).
fn stored_range(range: Option<f32>) -> f32 {
    range.unwrap_or(f32::MAX)
}

/// The diffuse and specular intensities of a light whose specular color may default.
fn intensities(color: Color, specular: Option<Color>) -> ([f32; 3], [f32; 3]) {
    (linear_rgb(color), linear_rgb(specular.unwrap_or(color)))
}

/// `(1 - cos(outer), cone_scale)` of a spot cone, computed in `f64` and rounded once:
/// `cone_scale = 1 / (cos(inner) - cos(outer))`, negated for a smooth edge
/// ([`ConeEdge::Smooth`]), or `0` (a hard edge at the outer angle) where the inner cone is
/// not narrower. A cone whose outer angle is not positive is empty:
/// its `1 - cos(outer)` is stored as `-1`, which no `1 - cos θ` reaches. Angles are first
/// brought into `[0, π]` ([`crate::limits::SPOT_ANGLE`]).
fn spot_cone_terms(inner_angle: f32, outer_angle: f32, edge: ConeEdge) -> (f32, f32) {
    let inner_angle = limits::SPOT_ANGLE.apply(inner_angle);
    let outer_angle = limits::SPOT_ANGLE.apply(outer_angle);
    if outer_angle <= 0.0 {
        return (-1.0, 0.0);
    }
    let (inner, outer) = (f64::from(inner_angle), f64::from(outer_angle));
    // 1 - cos x = 2 sin²(x/2) and cos i - cos o = 2 sin((o+i)/2) sin((o-i)/2): no
    // cancellation for small or close angles.
    let outer_versine = 2.0 * (outer / 2.0).sin().powi(2);
    let width = 2.0 * ((outer + inner) / 2.0).sin() * ((outer - inner) / 2.0).sin();
    // Beyond f32's range (or for no width at all) the edge is hard.
    let cone_scale = (1.0 / width) as f32;
    let cone_scale = if width > 0.0 && cone_scale.is_finite() {
        match edge {
            ConeEdge::Linear => cone_scale,
            ConeEdge::Smooth => -cone_scale,
        }
    } else {
        0.0
    };
    (outer_versine as f32, cone_scale)
}

impl PhongDirectionalLight {
    /// Its light in the reference model.
    #[cfg(feature = "reference")]
    const REFERENCE: fn(&Self, &GlobalTransform) -> Light = Light::directional;

    /// A cookie lies on its local XY plane.
    fn cookie_mapping(&self) -> PhongCookieProjection {
        PhongCookieProjection::Directional
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

impl PhongPointLight {
    /// Its light in the reference model.
    #[cfg(feature = "reference")]
    const REFERENCE: fn(&Self, &GlobalTransform) -> Light = Light::point;

    /// A cookie is a cube map around it.
    fn cookie_mapping(&self) -> PhongCookieProjection {
        PhongCookieProjection::Point
    }

    /// Its transform sets the position only.
    const PLACED: Placed = Placed {
        position: true,
        direction: false,
    };

    /// The record without its position or shadow slot: intensities, range and decay.
    fn constants(&self) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        GpuLight {
            range: stored_range(self.range),
            color,
            specular,
            decay: self.decay.to_array(),
            ..GpuLight::default()
        }
    }
}

impl PhongSpotLight {
    /// Its light in the reference model.
    #[cfg(feature = "reference")]
    const REFERENCE: fn(&Self, &GlobalTransform) -> Light = Light::spot;

    /// A cookie spans its cone.
    fn cookie_mapping(&self) -> PhongCookieProjection {
        PhongCookieProjection::Spot {
            outer_angle: self.outer_angle,
        }
    }

    /// Its transform sets the position and the direction.
    const PLACED: Placed = Placed {
        position: true,
        direction: true,
    };

    /// The record without its placement or shadow slot: intensities, range, decay and the
    /// cone's terms.
    fn constants(&self) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        let (outer_versine, cone_scale) =
            spot_cone_terms(self.inner_angle, self.outer_angle, self.cone_edge);
        GpuLight {
            range: stored_range(self.range),
            outer_versine,
            color,
            cone_scale,
            specular,
            spot_exponent: self.exponent,
            decay: self.decay.to_array(),
            ..GpuLight::default()
        }
    }
}

/// The directional light as a kind: its record, its validation and its shadow (cascades per
/// camera along its rays). It reaches everywhere and is never clustered.
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

/// The point light as a kind: its record, reach, validation and shadow (a cube map).
impl PhongLightKind for PhongPointLight {
    built_in_record!();
    fading_reach!();

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

/// The spot light as a kind: its record, reach, validation and shadow (one perspective map
/// over its cone).
impl PhongLightKind for PhongSpotLight {
    built_in_record!();
    fading_reach!();

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
