//! The lights of the model: each built-in kind, the kinds of extensions, the ambient and
//! hemisphere lights, distance fall-off and the spot cone (SPEC.md, "Light types" and "The
//! equation"). Each built-in kind's constructor from its entity (`Light::spot` and the
//! others) is in the kind's folder (`light_kind/spot/reference.rs`).

use super::{Hemisphere, Material, SurfacePoint, light_contribution, power};
use crate::lights::{ConeEdge, PhongAmbientLight, influence_radius};
use bevy::color::Color;
use core::fmt;
use glam::DVec3;
use std::sync::Arc;

/// One light, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// Parallel rays along `direction` (any length; normalized here).
    Directional {
        /// Direction the light travels.
        direction: DVec3,
        /// Diffuse intensity.
        color: DVec3,
        /// Specular intensity.
        specular: DVec3,
    },
    /// Light from `position` in every direction.
    Point {
        /// Position.
        position: DVec3,
        /// Diffuse intensity.
        color: DVec3,
        /// Specular intensity.
        specular: DVec3,
        /// `[constant, linear, quadratic]`.
        decay: [f64; 3],
        /// Cut-off distance.
        range: Option<f64>,
    },
    /// Light from `position` into a cone around `direction`.
    Spot {
        /// Position.
        position: DVec3,
        /// Axis of the cone, the direction the light travels (any length).
        direction: DVec3,
        /// Diffuse intensity.
        color: DVec3,
        /// Specular intensity.
        specular: DVec3,
        /// `[constant, linear, quadratic]`.
        decay: [f64; 3],
        /// Cut-off distance.
        range: Option<f64>,
        /// Half-angle of the full-intensity core, radians.
        inner_angle: f64,
        /// Half-angle where the light reaches zero, radians.
        outer_angle: f64,
        /// Exponent of the `cos(θ)^exponent` rim darkening.
        exponent: f64,
        /// How the light fades between the cones.
        edge: ConeEdge,
    },
}

/// A light of a kind added from outside the crate, in the reference model: its term at a
/// surface point, what its shader adds to SPEC.md's sum (unshadowed).
/// [`PhongLightKind::reference_light`](crate::extension::PhongLightKind::reference_light)
/// gives one for each light of such a kind.
pub trait ReferenceLight: Send + Sync + 'static {
    /// The light's term at `surface`, made of `material`, linear RGB.
    fn term(&self, surface: &SurfacePoint, material: &Material) -> DVec3;
}

/// A built-in light's term is [`light_contribution`]'s: the crate's kinds give theirs
/// through [`PhongLightKind::reference_light`](crate::extension::PhongLightKind::reference_light)
/// as extension kinds do.
impl ReferenceLight for Light {
    fn term(&self, surface: &SurfacePoint, material: &Material) -> DVec3 {
        light_contribution(surface, material, self)
    }
}

/// The lights of kinds added from outside the crate, beside the built-in ones.
#[derive(Clone, Default)]
pub struct OtherLights(pub Vec<Arc<dyn ReferenceLight>>);

impl fmt::Debug for OtherLights {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "OtherLights({} lights)", self.0.len())
    }
}

/// The same lights: the same objects, in the same order.
impl PartialEq for OtherLights {
    fn eq(&self, other: &Self) -> bool {
        self.0.len() == other.0.len() && self.0.iter().zip(&other.0).all(|(a, b)| Arc::ptr_eq(a, b))
    }
}

/// Everything that lights a point: the ambient and hemisphere lights and the other lights.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Lights {
    /// The ambient light, linear RGB.
    pub ambient: DVec3,
    /// The hemisphere light, if the scene has one.
    pub hemisphere: Option<Hemisphere>,
    /// Directional, point and spot lights.
    pub lights: Vec<Light>,
    /// Lights of the kinds an extension adds (each term added as it is, unshadowed).
    pub others: OtherLights,
}

impl Lights {
    /// These lights as [`PhongLightCulling`](crate::PhongLightCulling) with `epsilon`
    /// leaves them: each of the `n` point and spot lights' range shortened to its
    /// `influence_radius` for `epsilon / n`, and the
    /// lights that reach nowhere left out. With `epsilon = 0`, the lights unchanged.
    pub fn culled(&self, epsilon: f32) -> Lights {
        let count = self
            .lights
            .iter()
            .filter(|light| !matches!(light, Light::Directional { .. }))
            .count();
        let epsilon = epsilon / count.max(1) as f32;
        let limit = |range: &mut Option<f64>, decay: [f64; 3], color: DVec3, specular: DVec3| {
            let intensity = color.max_element().max(specular.max_element()) as f32;
            let radius = influence_radius(decay.map(|c| c as f32), intensity, epsilon);
            if radius.is_finite() {
                *range = Some(range.map_or(f64::from(radius), |r| r.min(f64::from(radius))));
            }
            *range != Some(0.0)
        };
        let lights = self
            .lights
            .iter()
            .copied()
            .filter_map(|mut light| {
                let reaches = match &mut light {
                    Light::Directional { .. } => true,
                    Light::Point {
                        range,
                        decay,
                        color,
                        specular,
                        ..
                    }
                    | Light::Spot {
                        range,
                        decay,
                        color,
                        specular,
                        ..
                    } => limit(range, *decay, *color, *specular),
                };
                reaches.then_some(light)
            })
            .collect();
        Lights {
            ambient: self.ambient,
            hemisphere: self.hemisphere,
            lights,
            others: self.others.clone(),
        }
    }

    /// The light that reaches a surface with `normal` from every direction: the ambient
    /// light plus the hemisphere light's [`Hemisphere::irradiance`].
    pub fn indirect(&self, normal: DVec3) -> DVec3 {
        self.ambient
            + self
                .hemisphere
                .map_or(DVec3::ZERO, |hemisphere| hemisphere.irradiance(normal))
    }
}

/// `A(d) = min(1, 1 / (c + l·d + q·d²))`, and 0 past `range` (SPEC.md's fall-off).
pub fn attenuation(
    distance: f64,
    [constant, linear, quadratic]: [f64; 3],
    range: Option<f64>,
) -> f64 {
    if range.is_some_and(|range| distance > range) {
        return 0.0;
    }
    let denominator = constant + linear * distance + quadratic * distance * distance;
    if denominator <= 1.0 {
        1.0
    } else {
        1.0 / denominator
    }
}

/// `S_cone = edge · max(cosθ, 0)^exponent`, where `edge` is
/// `t = clamp((cosθ - cos_outer) / (cos_inner - cos_outer), 0, 1)` (a soft edge; `t² (3 − 2t)`
/// for [`ConeEdge::Smooth`]) or, when the inner cone is not narrower than the outer one,
/// `step(cos_outer, cosθ)` (a hard edge).
pub fn cone_factor(
    cos_theta: f64,
    cos_inner: f64,
    cos_outer: f64,
    exponent: f64,
    shape: ConeEdge,
) -> f64 {
    let edge = if cos_inner > cos_outer {
        let t = ((cos_theta - cos_outer) / (cos_inner - cos_outer)).clamp(0.0, 1.0);
        match shape {
            ConeEdge::Linear => t,
            ConeEdge::Smooth => t * t * (3.0 - 2.0 * t),
        }
    } else if cos_theta >= cos_outer {
        1.0
    } else {
        0.0
    };
    if edge == 0.0 {
        return 0.0;
    }
    edge * power(cos_theta.max(0.0), exponent)
}

/// A color's linear RGB components in `f64`.
pub fn rgb(color: Color) -> DVec3 {
    let linear = color.to_linear();
    DVec3::new(linear.red.into(), linear.green.into(), linear.blue.into())
}

impl From<&PhongAmbientLight> for DVec3 {
    fn from(ambient: &PhongAmbientLight) -> Self {
        rgb(ambient.color)
    }
}

impl Light {
    /// This light with its diffuse intensity times `diffuse` and its specular intensity times
    /// `specular` (each term of the equation is linear in its intensity).
    pub fn scaled(mut self, diffuse: f64, specular: f64) -> Self {
        match &mut self {
            Light::Directional {
                color,
                specular: specular_color,
                ..
            }
            | Light::Point {
                color,
                specular: specular_color,
                ..
            }
            | Light::Spot {
                color,
                specular: specular_color,
                ..
            } => {
                *color *= diffuse;
                *specular_color *= specular;
            }
        }
        self
    }

    /// This light with its diffuse and specular intensities times `tint`, channel by channel
    /// (a cookie's, [`Cookie::tint`]).
    pub fn tinted(mut self, tint: DVec3) -> Self {
        match &mut self {
            Light::Directional {
                color, specular, ..
            }
            | Light::Point {
                color, specular, ..
            }
            | Light::Spot {
                color, specular, ..
            } => {
                *color *= tint;
                *specular *= tint;
            }
        }
        self
    }
}
