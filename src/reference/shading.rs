//! The color of a surface point: the sum over its lights, each light's term, and the
//! highlight models (SPEC.md, "The equation" and "Shadows").

use super::{
    Light, Lights, MIN_LENGTH_SQUARED, Material, SurfacePoint, Texels, attenuation, cone_factor,
    diffuse_factor, highlight_factor, normalize_or_zero, rim_factor,
};
use crate::material::{DiffuseMode, SpecularModel};
use glam::DVec3;

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
/// `(ambient ⊙ k_a + light map) ⊙ k_d` (and the ambient specular) scaled by the AO map's
/// factor.
pub fn shade_baked(
    surface: &SurfacePoint,
    material: &Material,
    lights: &Lights,
    baked: &BakedLight,
) -> DVec3 {
    let ambient = ambient_term(surface, material, lights, baked);
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

/// The indirect term: `((ambient + hemisphere(N)) ⊙ k_a + light map) ⊙ k_d` plus
/// `(ambient + hemisphere(N)) ⊙` the ambient specular reflectance, scaled by the AO map's
/// factor.
fn ambient_term(
    surface: &SurfacePoint,
    material: &Material,
    lights: &Lights,
    baked: &BakedLight,
) -> DVec3 {
    let indirect = lights.indirect(surface.normal);
    let diffuse = (indirect * material.ambient_factor + baked.light_map) * material.diffuse;
    let specular = indirect * material.ambient_specular_reflectance(surface);
    (diffuse + specular) * baked.occlusion
}

/// [`shade`] with each light's share scaled by its [`Shadowing`] (`shadowing[i]` for
/// `lights.lights[i]`; lights past the end of `shadowing`, and `lights.others`, are lit).
pub fn shade_shadowed(
    surface: &SurfacePoint,
    material: &Material,
    lights: &Lights,
    shadowing: &[Shadowing],
) -> DVec3 {
    let ambient = ambient_term(surface, material, lights, &BakedLight::NONE);
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
            let cone = cone_factor(
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
