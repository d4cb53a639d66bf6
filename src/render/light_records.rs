//! From light components and their transforms to [`GpuLight`] records.

use super::gpu_types::GpuLight;
use crate::lights::{Decay, PhongDirectionalLight, PhongPointLight, PhongSpotLight};
use bevy::{color::Color, math::Vec3, transform::components::GlobalTransform};

/// A color's linear RGB components (alpha dropped).
pub fn linear_rgb(color: Color) -> [f32; 3] {
    let linear = color.to_linear();
    [linear.red, linear.green, linear.blue]
}

/// The unit vector a light travels along: the entity's world -Z, or zero for a transform
/// that has collapsed it (zero scale).
pub fn light_direction(transform: &GlobalTransform) -> Vec3 {
    (transform.affine().matrix3 * Vec3::NEG_Z).normalize_or_zero()
}

/// `range`, with `None` stored as `f32::MAX` (never reached).
fn stored_range(range: Option<f32>) -> f32 {
    range.unwrap_or(f32::MAX)
}

/// The diffuse and specular intensities of a light whose specular color may default.
fn intensities(color: Color, specular: Option<Color>) -> ([f32; 3], [f32; 3]) {
    (linear_rgb(color), linear_rgb(specular.unwrap_or(color)))
}

/// `(cos(outer), cone_scale)` of a spot cone: `cone_scale = 1 / (cos(inner) - cos(outer))`,
/// or `0` (a hard edge at the outer angle) where the inner cone is not narrower. A cone whose
/// outer angle is not positive is empty: its `cos(outer)` is stored as infinity, which no
/// `cos θ` reaches.
pub fn spot_cone_terms(inner_angle: f32, outer_angle: f32) -> (f32, f32) {
    let cos_outer = if outer_angle > 0.0 {
        outer_angle.cos()
    } else {
        f32::INFINITY
    };
    let cos_inner = inner_angle.cos();
    let scale = 1.0 / (cos_inner - cos_outer);
    let cone_scale = if cos_inner > cos_outer && scale.is_finite() {
        scale
    } else {
        0.0
    };
    (cos_outer, cone_scale)
}

impl PhongDirectionalLight {
    /// This light's GPU record.
    pub fn to_gpu(&self, transform: &GlobalTransform) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        GpuLight {
            direction: light_direction(transform).to_array(),
            color,
            specular,
            ..GpuLight::default()
        }
    }
}

impl PhongPointLight {
    /// This light's GPU record.
    pub fn to_gpu(&self, transform: &GlobalTransform) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        GpuLight {
            position: transform.translation().to_array(),
            range: stored_range(self.range),
            color,
            specular,
            decay: Decay::to_array(self.decay),
            ..GpuLight::default()
        }
    }
}

impl PhongSpotLight {
    /// This light's GPU record.
    pub fn to_gpu(&self, transform: &GlobalTransform) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        let (cos_outer, cone_scale) = spot_cone_terms(self.inner_angle, self.outer_angle);
        GpuLight {
            position: transform.translation().to_array(),
            range: stored_range(self.range),
            direction: light_direction(transform).to_array(),
            cos_outer,
            color,
            cone_scale,
            specular,
            spot_exponent: self.exponent,
            decay: self.decay.to_array(),
            padding: 0.0,
        }
    }
}
