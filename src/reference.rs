//! The lighting model of SPEC.md in `f64`, for one surface point: the specification in
//! code.
//!
//! The shader computes the same equation in `f32`; the tests render a scene, read back each
//! pixel's color together with the world position and normal it was lit with (see
//! `SurfaceInputsMaterial`), and compare the color with
//! [`shade`] evaluated on those inputs. A textured material is first given the texels of
//! the fragment ([`Material::mapped`], [`mapped_normal`]).
//!
//! Every function follows the shader's rules for degenerate input, so that the two can be
//! compared anywhere:
//! - a vector is normalized by its largest component first ([`normalize_or_zero`]); one
//!   that is not finite, or whose largest component is below `f32`'s smallest normal number
//!   (about 1.2e-38), has no direction: such a normal, view or light vector gives no diffuse
//!   or specular light;
//! - a point or spot light at the surface point (closer than 1e-15, [`MIN_LENGTH_SQUARED`])
//!   lights nothing;
//! - a spot light whose outer angle is not positive has an empty cone and lights nothing;
//! - `power(0, 0) = 1`;
//! - an attenuation denominator at or below 1 (a `Decay` of all zeros included) gives 1;
//! - a [`PhongMaterial`]'s values, and a spot light's angles, are first brought into their
//!   ranges (`crate::limits`) as its uniform and light record do.

use crate::{
    culling::influence_radius,
    lights::{
        ConeEdge, PhongAmbientLight, PhongDirectionalLight, PhongPointLight, PhongSpotLight,
        light_direction,
    },
    limits,
    material::{DiffuseMode, PhongMaterial, SpecularMode, SpecularModel},
};
use bevy::{
    color::{Color, ColorToComponents},
    transform::components::GlobalTransform,
};
use core::fmt;
use glam::DVec3;
use std::sync::Arc;

mod camera_effects;
mod cookies;
mod environment;
mod hemisphere;
mod normals;
mod per_vertex;
pub(crate) mod stylized;
mod surface_inputs;
mod texture_maps;
pub use camera_effects::{directional_scattering, fogged, reinhard};
pub use cookies::{Cookie, CookieProjection, cube_face_uv};
pub use environment::{cube_direction, environment_direction, environment_lod, with_environment};
pub use hemisphere::Hemisphere;
pub use normals::{bumped_normal, face_normal, mapped_normal};
pub use per_vertex::VertexLight;
pub use stylized::{Rim, ToonRamp, diffuse_factor, highlight_factor, rim_factor};
pub use surface_inputs::transformed_uv;
pub use texture_maps::Texels;

#[cfg(test)]
mod baked_light_tests;

/// A point or spot light whose squared distance from the surface point is at or below this
/// (closer than 1e-15) lights nothing, here and in the shader.
pub const MIN_LENGTH_SQUARED: f64 = 1e-30;

/// `v / |v|`, computed as `u / |u|` with `u = v / max(|v.x|, |v.y|, |v.z|)` (as the shader
/// does, so that no `f32` square overflows or underflows); zero where `v` is not finite or
/// its largest component is below `f32::MIN_POSITIVE` (about 1.2e-38: GPUs may flush smaller
/// numbers to zero).
pub fn normalize_or_zero(v: DVec3) -> DVec3 {
    crate::direction::normalize_or_zero_f64(v)
}

/// A surface point and where it is seen from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// `P`, world space.
    pub position: DVec3,
    /// The surface normal; any length (it is normalized here, like the interpolated mesh
    /// normal in the shader).
    pub normal: DVec3,
    /// The camera position; `V = normalize(camera - P)`.
    pub camera: DVec3,
}

/// The material terms of the equation.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// `k_d`, linear RGB.
    pub diffuse: DVec3,
    /// `k_a`.
    pub ambient_factor: f64,
    /// `k_s`, linear RGB.
    pub specular: DVec3,
    /// Multiplier on `k_s`.
    pub specular_strength: f64,
    /// `α`.
    pub shininess: f64,
    /// Phong or Blinn-Phong highlight.
    pub specular_model: SpecularModel,
    /// Added unlit color, linear RGB.
    pub emissive: DVec3,
    /// How each light's `N·L` is shaped (its numbers in their ranges).
    pub diffuse_mode: DiffuseMode,
    /// The toon ramp that replaces a toon mode's bands, if the material has one bound.
    pub toon_ramp: Option<ToonRamp>,
    /// How each light's highlight is drawn (its numbers in their ranges).
    pub specular_mode: SpecularMode,
    /// The rim light.
    pub rim: Rim,
}

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

/// The color of `surface` made of `material` under `lights` (SPEC.md's equation):
/// `emissive + ambient ⊙ k_a ⊙ k_d + Σ light_contribution`.
pub fn shade(surface: &SurfacePoint, material: &Material, lights: &Lights) -> DVec3 {
    shade_baked(surface, material, lights, &BakedLight::NONE)
}

/// What a material's baked maps give a fragment (SPEC.md, "Baked light").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BakedLight {
    /// The light map's light: its texel times its intensity, linear RGB.
    pub light_map: DVec3,
    /// The AO map's factor on the indirect light, `1 + intensity · (r − 1)`.
    pub occlusion: f64,
}

impl BakedLight {
    /// No light map and no AO map.
    pub const NONE: Self = Self {
        light_map: DVec3::ZERO,
        occlusion: 1.0,
    };

    /// The baked light of a fragment whose maps gave `texels`, with the material's
    /// `light_map_intensity` and `ao_map_intensity`.
    pub fn from_texels(texels: &Texels, light_map_intensity: f64, ao_map_intensity: f64) -> Self {
        Self {
            light_map: texels
                .light_map
                .map_or(DVec3::ZERO, |texel| texel * light_map_intensity),
            occlusion: texels
                .ao_map
                .map_or(1.0, |red| 1.0 + ao_map_intensity * (red - 1.0)),
        }
    }
}

/// [`shade`] with the light of a material's baked maps: the indirect light
/// `(ambient ⊙ k_a + light map) ⊙ k_d` scaled by the AO map's factor.
pub fn shade_baked(
    surface: &SurfacePoint,
    material: &Material,
    lights: &Lights,
    baked: &BakedLight,
) -> DVec3 {
    let indirect = lights.indirect(surface.normal) * material.ambient_factor + baked.light_map;
    let ambient = indirect * material.diffuse * baked.occlusion;
    lights
        .lights
        .iter()
        .map(|light| light_contribution(surface, material, light))
        .chain(other_terms(surface, material, lights))
        .fold(
            material.emissive + ambient + material.rim.glow(surface),
            |sum, term| sum + term,
        )
}

/// The terms of the lights of kinds from outside the crate.
fn other_terms<'a>(
    surface: &'a SurfacePoint,
    material: &'a Material,
    lights: &'a Lights,
) -> impl Iterator<Item = DVec3> + 'a {
    lights
        .others
        .0
        .iter()
        .map(|light| light.term(surface, material))
}

/// How much of one light reaches a surface point (SPEC.md, "Shadows").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shadowing {
    /// `V ∈ [0, 1]`: 1 where nothing is in the way, 0 where the light is blocked.
    pub visibility: f64,
    /// `f_d`: the fraction of the diffuse term left in full shadow.
    pub diffuse_in_shadow: f64,
    /// `f_s`: the fraction of the highlight left in full shadow.
    pub specular_in_shadow: f64,
}

impl Shadowing {
    /// Nothing in the way.
    pub const LIT: Self = Self {
        visibility: 1.0,
        diffuse_in_shadow: 0.0,
        specular_in_shadow: 0.0,
    };

    /// The factors on the diffuse term and the highlight: `f + (1 − f)·V` each.
    pub fn factors(&self) -> (f64, f64) {
        let factor = |fraction: f64| fraction + (1.0 - fraction) * self.visibility;
        (
            factor(self.diffuse_in_shadow),
            factor(self.specular_in_shadow),
        )
    }
}

/// [`shade`] with each light's share scaled by its [`Shadowing`] (`shadowing[i]` for
/// `lights.lights[i]`; lights past the end of `shadowing`, and `lights.others`, are lit).
pub fn shade_shadowed(
    surface: &SurfacePoint,
    material: &Material,
    lights: &Lights,
    shadowing: &[Shadowing],
) -> DVec3 {
    let ambient = lights.indirect(surface.normal) * material.ambient_factor * material.diffuse;
    lights
        .lights
        .iter()
        .enumerate()
        .map(|(index, light)| {
            let (diffuse, specular) = shadowing.get(index).unwrap_or(&Shadowing::LIT).factors();
            light_contribution(surface, material, &light.scaled(diffuse, specular))
        })
        .chain(other_terms(surface, material, lights))
        .fold(
            material.emissive + ambient + material.rim.glow(surface),
            |sum, term| sum + term,
        )
}

/// One light's `A · S · [diffuse + specular]` at `surface`.
pub fn light_contribution(surface: &SurfacePoint, material: &Material, light: &Light) -> DVec3 {
    match *light {
        Light::Directional {
            direction,
            color,
            specular,
        } => phong_light(
            surface,
            material,
            -normalize_or_zero(direction),
            color,
            specular,
        ),
        Light::Point {
            position,
            color,
            specular,
            decay,
            range,
        } => {
            let Some((to_light, attenuation)) = toward(surface, position, decay, range) else {
                return DVec3::ZERO;
            };
            attenuation * phong_light(surface, material, to_light, color, specular)
        }
        Light::Spot {
            position,
            direction,
            color,
            specular,
            decay,
            range,
            inner_angle,
            outer_angle,
            exponent,
            edge,
        } => {
            let Some((to_light, attenuation)) = toward(surface, position, decay, range) else {
                return DVec3::ZERO;
            };
            // Also true for a NaN angle.
            if outer_angle.is_nan() || outer_angle <= 0.0 {
                return DVec3::ZERO;
            }
            let cos_theta = (-to_light).dot(normalize_or_zero(direction));
            let cone = spot_cone(
                cos_theta,
                inner_angle.cos(),
                outer_angle.cos(),
                exponent,
                edge,
            );
            attenuation * cone * phong_light(surface, material, to_light, color, specular)
        }
    }
}

/// The unit vector from `surface` toward a light at `position` and the light's attenuation
/// there; `None` where the light is at the point (closer than 1e-15) or out of range.
fn toward(
    surface: &SurfacePoint,
    position: DVec3,
    decay: [f64; 3],
    range: Option<f64>,
) -> Option<(DVec3, f64)> {
    let offset = position - surface.position;
    let distance_squared = offset.length_squared();
    if distance_squared.is_nan() || distance_squared <= MIN_LENGTH_SQUARED {
        return None;
    }
    let distance = distance_squared.sqrt();
    let attenuation = attenuation(distance, decay, range);
    (attenuation > 0.0).then(|| (offset / distance, attenuation))
}

/// `color ⊙ k_d · f_d(N·L) + specular ⊙ k_s · strength · f_s(H(N, L, V))` for a unit
/// `to_light` (`L`), `f_d` and `f_s` the material's modes ([`diffuse_factor`],
/// [`highlight_factor`]: `max(N·L, 0)` and `H` by default); zero where `N·L ≤ 0` but for a
/// wrapped diffuse term, and zero without a normal.
pub fn phong_light(
    surface: &SurfacePoint,
    material: &Material,
    to_light: DVec3,
    color: DVec3,
    specular: DVec3,
) -> DVec3 {
    let normal = normalize_or_zero(surface.normal);
    let n_dot_l = normal.dot(to_light);
    // Nothing on the far side (but for a wrapped diffuse term or a toon ramp), nor without a
    // normal.
    let ramp = match material.diffuse_mode {
        DiffuseMode::Toon { .. } => material.toon_ramp.as_ref(),
        _ => None,
    };
    let wrapped = matches!(material.diffuse_mode, DiffuseMode::Wrap(_)) || ramp.is_some();
    if n_dot_l.is_nan() || normal == DVec3::ZERO || (!wrapped && n_dot_l <= 0.0) {
        return DVec3::ZERO;
    }
    let view = normalize_or_zero(surface.camera - surface.position);
    let highlight = if n_dot_l > 0.0 {
        let h = highlight(
            material.specular_model,
            normal,
            to_light,
            view,
            material.shininess,
        );
        highlight_factor(material.specular_mode, h)
    } else {
        0.0
    };
    let rim = if material.rim.lit_side {
        color * material.rim.color * rim_factor(normal, view, material.rim.power) * n_dot_l.max(0.0)
    } else {
        DVec3::ZERO
    };
    let diffuse = ramp.map_or_else(
        || diffuse_factor(material.diffuse_mode, n_dot_l),
        |ramp| ramp.factor(n_dot_l),
    );
    color * material.diffuse * diffuse
        + rim
        + specular * specular_weight(material, view, to_light) * highlight
}

/// What weighs a light's highlight: `k_s · strength`, or for the normalized model Schlick's
/// `F = f₀ + (1 − f₀) · w` with `f₀ = k_s · strength` ([`fresnel_weight`]; zero for a zero
/// strength, which has no specular term).
pub fn specular_weight(material: &Material, view: DVec3, to_light: DVec3) -> DVec3 {
    let f0 = material.specular * material.specular_strength;
    if material.specular_model != SpecularModel::NormalizedBlinnPhong
        || material.specular_strength <= 0.0
    {
        return f0;
    }
    let w = fresnel_weight(view, to_light);
    f0 + (DVec3::ONE - f0) * w
}

/// three.js's Schlick weight `w = 2^((−5.55473·c − 6.98316)·c)` for `c = max(V·H, 0)`,
/// `H = normalize(L + V)` (SPEC.md, "Normalized Blinn-Phong").
pub fn fresnel_weight(view: DVec3, to_light: DVec3) -> f64 {
    let c = view.dot(normalize_or_zero(to_light + view)).clamp(0.0, 1.0);
    ((-5.55473 * c - 6.98316) * c).exp2()
}

/// `H(N, L, V)` for unit `N`, `L` and `V` with `N·L > 0`:
/// Phong `max(R·V, 0)^α` with `R = 2(N·L)N - L` (SPEC.md), Blinn-Phong `max(N·H, 0)^α` with
/// `H = normalize(L + V)`, normalized Blinn-Phong that times `(α + 2)/(8π) · N·L`.
pub fn highlight(
    model: SpecularModel,
    normal: DVec3,
    to_light: DVec3,
    view: DVec3,
    shininess: f64,
) -> f64 {
    let half_vector = || normal.dot(normalize_or_zero(to_light + view));
    let cosine = match model {
        SpecularModel::Phong => reflect(-to_light, normal).dot(view),
        SpecularModel::BlinnPhong | SpecularModel::NormalizedBlinnPhong => half_vector(),
    };
    let lobe = power(cosine.max(0.0), shininess);
    match model {
        SpecularModel::NormalizedBlinnPhong => {
            lobe * (shininess + 2.0) / (8.0 * std::f64::consts::PI) * normal.dot(to_light)
        }
        _ => lobe,
    }
}

/// GLSL's `reflect(incident, normal) = incident - 2(N·I)N`; with `incident = -L` it is
/// `R = 2(N·L)N - L`.
pub fn reflect(incident: DVec3, normal: DVec3) -> DVec3 {
    incident - 2.0 * normal.dot(incident) * normal
}

/// `base^exponent` for `base ≥ 0`, with `0^0 = 1` and `0^exponent = 0` for `exponent > 0`.
pub fn power(base: f64, exponent: f64) -> f64 {
    if exponent == 0.0 {
        1.0
    } else if base <= 0.0 {
        0.0
    } else {
        base.powf(exponent)
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
pub fn spot_cone(
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
pub fn linear_rgb(color: Color) -> DVec3 {
    let linear = color.to_linear();
    DVec3::new(linear.red.into(), linear.green.into(), linear.blue.into())
}

fn position(transform: &GlobalTransform) -> DVec3 {
    transform.translation().as_dvec3()
}

/// The material's values brought into their ranges, by the same walk over its numbers as
/// validation and its uniform (`PhongMaterial::in_range`).
impl From<&PhongMaterial> for Material {
    fn from(material: &PhongMaterial) -> Self {
        let material = material.in_range();
        let channels = |color: Color| color.to_linear().to_vec3().as_dvec3();
        Self {
            diffuse: channels(material.base_color),
            ambient_factor: material.ambient_factor.into(),
            specular: channels(material.specular_color),
            specular_strength: material.specular_strength.into(),
            shininess: material.shininess.into(),
            specular_model: material.specular_model,
            emissive: material.emissive.to_vec3().as_dvec3(),
            diffuse_mode: material.diffuse_mode,
            toon_ramp: None,
            specular_mode: material.specular_mode,
            rim: Rim {
                color: material.rim_color.to_vec3().as_dvec3() * f64::from(material.rim_strength),
                power: material.rim_power.into(),
                lit_side: material.rim_lit_side,
            },
        }
    }
}

impl From<&PhongAmbientLight> for DVec3 {
    fn from(ambient: &PhongAmbientLight) -> Self {
        linear_rgb(ambient.color)
    }
}

fn decay_of(decay: crate::Decay) -> [f64; 3] {
    decay.to_array().map(f64::from)
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

    /// The reference form of a directional light entity.
    pub fn directional(light: &PhongDirectionalLight, transform: &GlobalTransform) -> Self {
        Light::Directional {
            direction: light_direction(transform).as_dvec3(),
            color: linear_rgb(light.color),
            specular: linear_rgb(light.specular.unwrap_or(light.color)),
        }
    }

    /// The reference form of a point light entity.
    pub fn point(light: &PhongPointLight, transform: &GlobalTransform) -> Self {
        Light::Point {
            position: position(transform),
            color: linear_rgb(light.color),
            specular: linear_rgb(light.specular.unwrap_or(light.color)),
            decay: decay_of(light.decay),
            range: light.range.map(f64::from),
        }
    }

    /// The reference form of a spot light entity, its angles brought into `[0, π]` as its
    /// light record's are (`crate::limits::SPOT_ANGLE`).
    pub fn spot(light: &PhongSpotLight, transform: &GlobalTransform) -> Self {
        Light::Spot {
            position: position(transform),
            direction: light_direction(transform).as_dvec3(),
            color: linear_rgb(light.color),
            specular: linear_rgb(light.specular.unwrap_or(light.color)),
            decay: decay_of(light.decay),
            range: light.range.map(f64::from),
            inner_angle: limits::SPOT_ANGLE.apply(light.inner_angle).into(),
            outer_angle: limits::SPOT_ANGLE.apply(light.outer_angle).into(),
            exponent: light.exponent.into(),
            edge: light.cone_edge,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const EPSILON: f64 = 1e-12;

    fn close(actual: f64, expected: f64) -> bool {
        (actual - expected).abs() <= EPSILON * expected.abs().max(1.0)
    }

    fn matte(diffuse: DVec3) -> Material {
        Material {
            toon_ramp: None,
            diffuse,
            ambient_factor: 1.0,
            specular: DVec3::ONE,
            specular_strength: 0.0,
            shininess: 1.0,
            specular_model: SpecularModel::Phong,
            emissive: DVec3::ZERO,
            diffuse_mode: crate::DiffuseMode::Lambert,
            specular_mode: crate::SpecularMode::Smooth,
            rim: crate::reference::Rim::NONE,
        }
    }

    #[test]
    fn visibility_scales_the_diffuse_term_and_the_highlight_by_their_shadow_fractions() {
        let surface = SurfacePoint {
            position: DVec3::ZERO,
            normal: DVec3::Y,
            camera: DVec3::new(-1.0, 1.0, 0.0),
        };
        let material = Material {
            specular_strength: 1.0,
            shininess: 8.0,
            emissive: DVec3::splat(0.01),
            ..matte(DVec3::splat(0.5))
        };
        let lights = Lights {
            hemisphere: None,
            ambient: DVec3::splat(0.1),
            lights: vec![Light::Directional {
                direction: DVec3::new(-1.0, -1.0, 0.0),
                color: DVec3::ONE,
                specular: DVec3::ONE,
            }],
            others: Default::default(),
        };
        let diffuse_only = Material {
            specular_strength: 0.0,
            ..material.clone()
        };
        let base = material.emissive + lights.ambient * 0.5;
        let diffuse = shade(&surface, &diffuse_only, &lights) - base;
        let specular = shade(&surface, &material, &lights) - base - diffuse;
        let shaded = |visibility, diffuse_in_shadow, specular_in_shadow| {
            let shadowing = Shadowing {
                visibility,
                diffuse_in_shadow,
                specular_in_shadow,
            };
            shade_shadowed(&surface, &material, &lights, &[shadowing])
        };
        assert!((shaded(1.0, 0.0, 0.0) - shade(&surface, &material, &lights)).length() < EPSILON);
        assert!(
            (shaded(0.0, 0.0, 0.0) - base).length() < EPSILON,
            "blocked: ambient only"
        );
        let seed_003 = base + 0.1 * diffuse + specular;
        assert!((shaded(0.0, 0.1, 1.0) - seed_003).length() < EPSILON);
        let half = base + 0.5 * (diffuse + specular);
        assert!((shaded(0.5, 0.0, 0.0) - half).length() < EPSILON);
    }

    #[test]
    fn reflection_is_two_n_dot_l_n_minus_l_as_seed_002_derives() {
        // N = +Y, L at 45° in the XY plane: R mirrors L's x component.
        let normal = DVec3::Y;
        let to_light = DVec3::new(1.0, 1.0, 0.0).normalize();
        let reflected = reflect(-to_light, normal);
        let by_hand = DVec3::new(-1.0, 1.0, 0.0) / 2f64.sqrt();
        assert!((reflected - by_hand).length() < EPSILON);
        assert!((reflected - (2.0 * normal.dot(to_light) * normal - to_light)).length() < EPSILON);
    }

    #[test]
    fn phong_highlight_is_one_when_looking_down_the_reflection() {
        let to_light = DVec3::new(1.0, 1.0, 0.0).normalize();
        let view = DVec3::new(-1.0, 1.0, 0.0).normalize();
        let h = highlight(SpecularModel::Phong, DVec3::Y, to_light, view, 50.0);
        assert!(close(h, 1.0));
        // And Blinn-Phong agrees there: H = N.
        let h = highlight(SpecularModel::BlinnPhong, DVec3::Y, to_light, view, 50.0);
        assert!(close(h, 1.0));
    }

    #[test]
    fn seed_000_demo_highlight_is_two_times_cos_to_the_fiftieth() {
        // specular = 2.0 * pow(eyeCos, 50.0), eyeCos = cos(10°) between R and V.
        let to_light = DVec3::Y;
        let angle = 10f64.to_radians();
        let view = DVec3::new(angle.sin(), angle.cos(), 0.0);
        let surface = SurfacePoint {
            position: DVec3::ZERO,
            normal: DVec3::Y,
            camera: view * 5.0,
        };
        let material = Material {
            diffuse: DVec3::ZERO,
            specular_strength: 2.0,
            shininess: 50.0,
            ..matte(DVec3::ZERO)
        };
        let color = phong_light(&surface, &material, to_light, DVec3::ZERO, DVec3::ONE);
        let by_hand = 2.0 * 0.984_807_753_012_208_f64.powf(50.0); // = 0.9323…
        assert!(close(color.x, by_hand), "{color} vs {by_hand}");
    }

    #[test]
    fn normalized_blinn_phong_is_three_js_brdf_worked_by_hand() {
        // L and V 60° either side of N: H = N, N·H = 1, N·L = V·H = c = 1/2. Schlick's
        // weight w = 2^((−5.55473·c − 6.98316)·c) = 2^(−4.8802625) = 0.0339543;
        // F = f₀ + (1 − f₀)·w with f₀ = k_s = 0.2: 0.2271634; the term
        // F · (α + 2)/(8π) · (N·H)^α · N·L = 0.2271634 · 8/(8π) · 1 · 0.5 = 0.0361542 (α = 6).
        let angle = 60f64.to_radians();
        let to_light = DVec3::new(angle.sin(), angle.cos(), 0.0);
        let view = DVec3::new(-angle.sin(), angle.cos(), 0.0);
        let surface = SurfacePoint {
            position: DVec3::ZERO,
            normal: DVec3::Y,
            camera: view * 4.0,
        };
        let material = Material {
            specular: DVec3::splat(0.2),
            specular_strength: 1.0,
            shininess: 6.0,
            specular_model: SpecularModel::NormalizedBlinnPhong,
            ..matte(DVec3::ZERO)
        };
        let color = phong_light(&surface, &material, to_light, DVec3::ZERO, DVec3::ONE);
        let by_hand = 0.036_154_182_566_8;
        assert!(close(color.x, by_hand), "{color} vs {by_hand}");
        // A black specular color keeps the grazing part alone: w · 1/π · 0.5 = 0.0054040.
        let black = Material {
            specular: DVec3::ZERO,
            ..material
        };
        let color = phong_light(&surface, &black, to_light, DVec3::ZERO, DVec3::ONE);
        let by_hand = 0.033_954_285_871_0 / std::f64::consts::PI * 0.5;
        assert!(close(color.x, by_hand), "{color} vs {by_hand}");
    }

    #[test]
    fn seed_004_attenuation_constants_give_one_over_five_point_one_at_ten_units() {
        // 1 / (1.0 + 0.09·10 + 0.032·100) = 1 / 5.1
        assert!(close(
            attenuation(10.0, [1.0, 0.09, 0.032], None),
            1.0 / 5.1
        ));
        assert!(close(attenuation(0.0, [1.0, 0.09, 0.032], None), 1.0));
    }

    #[test]
    fn seed_000_caps_attenuation_at_one_near_the_light() {
        // decay x·d² + y·d + z with (x, y, z) = (1, 0, 0): 1/d² would be 4 at d = 0.5.
        assert!(close(attenuation(0.5, [0.0, 0.0, 1.0], None), 1.0));
        assert!(close(attenuation(2.0, [0.0, 0.0, 1.0], None), 0.25));
        // A zero decay is no fall-off rather than a division by zero.
        assert!(close(attenuation(3.0, [0.0, 0.0, 0.0], None), 1.0));
    }

    #[test]
    fn attenuation_is_zero_past_the_range_as_seed_001_cuts_it() {
        assert!(close(attenuation(4.99, [1.0, 0.0, 0.0], Some(5.0)), 1.0));
        assert_eq!(attenuation(5.01, [1.0, 0.0, 0.0], Some(5.0)), 0.0);
    }

    #[test]
    fn seed_004_soft_cone_is_full_inside_12_5_degrees_and_dark_past_17_5() {
        let (inner, outer) = (12.5f64.to_radians().cos(), 17.5f64.to_radians().cos());
        assert!(close(
            spot_cone(
                10f64.to_radians().cos(),
                inner,
                outer,
                0.0,
                ConeEdge::Linear
            ),
            1.0
        ));
        assert_eq!(
            spot_cone(
                18f64.to_radians().cos(),
                inner,
                outer,
                0.0,
                ConeEdge::Linear
            ),
            0.0
        );
        // At 15°: (cos 15° - cos 17.5°) / (cos 12.5° - cos 17.5°), worked by hand
        // (0.965925826 - 0.953716951) / (0.976296007 - 0.953716951) = 0.540717…
        let by_hand = (0.965_925_826_289_068 - 0.953_716_950_748_227)
            / (0.976_296_007_119_933_4 - 0.953_716_950_748_227);
        assert!(close(
            spot_cone(
                15f64.to_radians().cos(),
                inner,
                outer,
                0.0,
                ConeEdge::Linear
            ),
            by_hand
        ));
    }

    /// three.js's `smoothstep(cos outer, cos inner, cos θ)`: at 15° between 12.5° and 17.5°,
    /// `t = 0.540717…` (above) gives `t² (3 − 2t) = 0.560940…`, worked by hand.
    #[test]
    fn a_smooth_cone_edge_is_the_smoothstep_of_the_linear_one() {
        let (inner, outer) = (12.5f64.to_radians().cos(), 17.5f64.to_radians().cos());
        let smooth = spot_cone(
            15f64.to_radians().cos(),
            inner,
            outer,
            0.0,
            ConeEdge::Smooth,
        );
        assert!((smooth - 0.560_940_2).abs() < 1e-6, "{smooth}");
        assert_eq!(
            spot_cone(
                10f64.to_radians().cos(),
                inner,
                outer,
                0.0,
                ConeEdge::Smooth
            ),
            1.0
        );
        assert_eq!(
            spot_cone(
                18f64.to_radians().cos(),
                inner,
                outer,
                0.0,
                ConeEdge::Smooth
            ),
            0.0
        );
    }

    #[test]
    fn seed_000_hard_cone_is_a_step_at_the_angle() {
        let edge = 20f64.to_radians().cos();
        assert_eq!(
            spot_cone(19f64.to_radians().cos(), edge, edge, 0.0, ConeEdge::Linear),
            1.0
        );
        assert_eq!(
            spot_cone(21f64.to_radians().cos(), edge, edge, 0.0, ConeEdge::Linear),
            0.0
        );
    }

    #[test]
    fn seed_001_spot_exponent_darkens_by_cos_theta_to_the_exponent() {
        let cos_theta = 5f64.to_radians().cos();
        let cone = spot_cone(
            cos_theta,
            1.0_f64.cos(),
            1.2_f64.cos(),
            8.0,
            ConeEdge::Linear,
        );
        assert!(close(cone, cos_theta.powi(8)));
    }

    #[test]
    fn unlit_side_gets_neither_diffuse_nor_highlight() {
        let surface = SurfacePoint {
            position: DVec3::ZERO,
            normal: DVec3::Y,
            camera: DVec3::new(0.0, -1.0, 1.0),
        };
        let material = Material {
            specular_strength: 1.0,
            shininess: 0.0,
            ..matte(DVec3::ONE)
        };
        let color = phong_light(&surface, &material, -DVec3::Y, DVec3::ONE, DVec3::ONE);
        assert_eq!(color, DVec3::ZERO);
    }

    #[test]
    fn shade_adds_emissive_ambient_and_lights() {
        let surface = SurfacePoint {
            position: DVec3::ZERO,
            normal: DVec3::Y * 3.0,
            camera: DVec3::new(0.0, 4.0, 0.0),
        };
        let material = Material {
            emissive: DVec3::new(0.1, 0.0, 0.0),
            ambient_factor: 0.5,
            ..matte(DVec3::new(0.5, 0.25, 1.0))
        };
        let lights = Lights {
            hemisphere: None,
            ambient: DVec3::splat(0.2),
            lights: vec![Light::Directional {
                direction: DVec3::new(0.0, -1.0, -1.0),
                color: DVec3::ONE,
                specular: DVec3::ONE,
            }],
            others: Default::default(),
        };
        let n_dot_l = 1.0 / 2f64.sqrt();
        let by_hand = DVec3::new(0.1, 0.0, 0.0)
            + DVec3::splat(0.2 * 0.5) * material.diffuse
            + material.diffuse * n_dot_l;
        assert!((shade(&surface, &material, &lights) - by_hand).length() < EPSILON);
    }

    #[test]
    fn degenerate_inputs_give_finite_colors() {
        let material = Material {
            specular_strength: 1.0,
            shininess: 0.0,
            ..matte(DVec3::ONE)
        };
        let light_at_origin = Light::Point {
            position: DVec3::ZERO,
            color: DVec3::ONE,
            specular: DVec3::ONE,
            decay: [0.0; 3],
            range: None,
        };
        let lights = Lights {
            hemisphere: None,
            ambient: DVec3::ONE,
            lights: vec![light_at_origin],
            others: Default::default(),
        };
        for normal in [DVec3::ZERO, DVec3::NAN, DVec3::Y] {
            let surface = SurfacePoint {
                position: DVec3::ZERO,
                normal,
                camera: DVec3::ZERO,
            };
            assert!(shade(&surface, &material, &lights).is_finite());
        }
    }
}

#[cfg(test)]
mod properties {
    //! Properties the reference model holds for all valid input (non-negative colors,
    //! decays and material scalars).

    use super::*;
    use glam::DQuat;
    use proptest::prelude::*;

    fn unit_vector() -> impl Strategy<Value = DVec3> {
        (-1.0..1.0f64, 0.0..std::f64::consts::TAU).prop_map(|(z, angle)| {
            let r = (1.0 - z * z).sqrt();
            DVec3::new(r * angle.cos(), r * angle.sin(), z)
        })
    }

    fn point() -> impl Strategy<Value = DVec3> {
        (-20.0..20.0f64, -20.0..20.0f64, -20.0..20.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    fn color() -> impl Strategy<Value = DVec3> {
        (0.0..2.0f64, 0.0..2.0f64, 0.0..2.0f64).prop_map(|(r, g, b)| DVec3::new(r, g, b))
    }

    fn decay() -> impl Strategy<Value = [f64; 3]> {
        (0.0..2.0f64, 0.0..1.0f64, 0.0..1.0f64).prop_map(|(c, l, q)| [c, l, q])
    }

    fn model() -> impl Strategy<Value = SpecularModel> {
        prop_oneof![
            Just(SpecularModel::Phong),
            Just(SpecularModel::BlinnPhong),
            Just(SpecularModel::NormalizedBlinnPhong)
        ]
    }

    fn material() -> impl Strategy<Value = Material> {
        (
            color(),
            color(),
            0.0..3.0f64,
            0.0..1000.0f64,
            model(),
            color(),
        )
            .prop_map(
                |(diffuse, specular, specular_strength, shininess, specular_model, emissive)| {
                    Material {
                        toon_ramp: None,
                        diffuse,
                        ambient_factor: 1.0,
                        specular,
                        specular_strength,
                        shininess,
                        specular_model,
                        emissive,
                        diffuse_mode: crate::DiffuseMode::Lambert,
                        specular_mode: crate::SpecularMode::Smooth,
                        rim: crate::reference::Rim::NONE,
                    }
                },
            )
    }

    fn light() -> impl Strategy<Value = Light> {
        prop_oneof![
            (unit_vector(), color(), color()).prop_map(|(direction, color, specular)| {
                Light::Directional {
                    direction,
                    color,
                    specular,
                }
            }),
            (
                point(),
                color(),
                color(),
                decay(),
                proptest::option::of(0.1..30.0f64)
            )
                .prop_map(|(position, color, specular, decay, range)| Light::Point {
                    position,
                    color,
                    specular,
                    decay,
                    range,
                }),
            (
                point(),
                unit_vector(),
                color(),
                decay(),
                0.0..1.2f64,
                0.0..0.5f64,
                0.0..8.0f64
            )
                .prop_map(
                    |(position, direction, color, decay, inner, width, exponent)| {
                        Light::Spot {
                            position,
                            direction,
                            color,
                            specular: color,
                            decay,
                            range: None,
                            inner_angle: inner,
                            outer_angle: inner + width,
                            exponent,
                            edge: ConeEdge::Linear,
                        }
                    }
                ),
        ]
    }

    fn rotate(mut light: Light, rotation: DQuat) -> Light {
        match &mut light {
            Light::Directional { direction, .. } => *direction = rotation * *direction,
            Light::Point { position, .. } => *position = rotation * *position,
            Light::Spot {
                position,
                direction,
                ..
            } => {
                *position = rotation * *position;
                *direction = rotation * *direction;
            }
        }
        light
    }

    proptest! {
        #[test]
        fn output_is_never_negative(
            position in point(), normal in unit_vector(), camera in point(),
            material in material(), light in light(), ambient in color(),
        ) {
            let surface = SurfacePoint { position, normal, camera };
            let lights = Lights { ambient, hemisphere: None, lights: vec![light], others: Default::default() };
            let color = shade(&surface, &material, &lights);
            prop_assert!(color.min_element() >= 0.0, "{color}");
        }

        #[test]
        fn attenuation_never_increases_with_distance(
            decay in decay(), near in 0.0..100.0f64, further in 0.0..100.0f64,
            range in proptest::option::of(0.0..100.0f64),
        ) {
            let far = near + further;
            prop_assert!(attenuation(far, decay, range) <= attenuation(near, decay, range));
        }

        #[test]
        fn rotating_the_whole_scene_does_not_change_the_result(
            position in point(), normal in unit_vector(), camera in point(),
            material in material(), light in light(),
            axis in unit_vector(), angle in 0.0..std::f64::consts::TAU,
        ) {
            let rotation = DQuat::from_axis_angle(axis, angle);
            let surface = SurfacePoint { position, normal, camera };
            let rotated = SurfacePoint {
                position: rotation * position,
                normal: rotation * normal,
                camera: rotation * camera,
            };
            let before = light_contribution(&surface, &material, &light);
            let after = light_contribution(&rotated, &material, &rotate(light, rotation));
            // Rotation rounds each coordinate (~1e-15 relative); the highlight multiplies
            // that by at most α = 1000, the cone edge by 1 / (cos inner - cos outer).
            let tolerance = 1e-7 * before.max_element().max(1.0);
            prop_assert!((before - after).abs().max_element() <= tolerance, "{before} vs {after}");
        }

        #[test]
        fn phong_equals_blinn_phong_where_they_coincide(
            normal in unit_vector(), tilt in unit_vector(), distance in 0.5..20.0f64,
            material in material(), color in color(), zero_shininess in any::<bool>(),
        ) {
            // Looking down the mirror direction, R = V and H = N: both highlights peak at 1;
            // with α = 0 both are 1 everywhere on the lit side.
            let to_light = (normal + tilt * 0.9).normalize_or_zero();
            prop_assume!(normal.dot(to_light) > 1e-3);
            let view = reflect(-to_light, normal);
            let surface = SurfacePoint { position: DVec3::ZERO, normal, camera: view * distance };
            let material = Material {
                shininess: if zero_shininess { 0.0 } else { material.shininess },
                ..material
            };
            let light = Light::Directional { direction: -to_light, color, specular: color };
            let phong = light_contribution(&surface, &Material { specular_model: SpecularModel::Phong, ..material.clone() }, &light);
            let blinn = light_contribution(&surface, &Material { specular_model: SpecularModel::BlinnPhong, ..material }, &light);
            prop_assert!((phong - blinn).abs().max_element() <= 1e-9 * phong.max_element().max(1.0));
        }
    }
}
