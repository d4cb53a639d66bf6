//! The surface point and the material's terms of the equation (SPEC.md, "Material").

use super::{AmbientSpecular, MetallicRoughness, Rim, ToonRamp};
use crate::material::{DiffuseMode, PhongMaterial, SpecularMode, SpecularModel};
use bevy::color::{Color, ColorToComponents};
use glam::DVec3;

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
    /// The factors of the metallic-roughness map, where the material draws one (its texels
    /// then make the surface: [`Material::mapped`]).
    pub metallic_roughness: Option<MetallicRoughness>,
    /// The ambient light reflected by `k_s` (`PhongMaterial::ambient_specular`), where the
    /// material draws it: [`Material::ambient_specular_reflectance`].
    pub ambient_specular: Option<AmbientSpecular>,
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
            metallic_roughness: (material.metallic_roughness_texture.is_some() && !material.unlit)
                .then(|| MetallicRoughness {
                    metallic: material.metallic.into(),
                    perceptual_roughness: material.perceptual_roughness.into(),
                }),
            ambient_specular: (material.ambient_specular
                && !material.unlit
                && material.specular_strength > 0.0)
                .then(|| AmbientSpecular {
                    perceptual_roughness: material.perceptual_roughness.into(),
                }),
        }
    }
}
