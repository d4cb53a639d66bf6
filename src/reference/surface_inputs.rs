//! A mesh's vertex colors, a material's UV transform and unlit materials in the reference
//! model (SPEC.md, "Vertex colors and UV transform" and "Unlit").

use super::Material;
use glam::{Affine2, DVec2, DVec3, DVec4};

impl Material {
    /// This material on a fragment whose interpolated vertex color is `color`: `k_d` times
    /// its RGB (its alpha multiplies only the output alpha).
    pub fn with_vertex_color(&self, color: DVec4) -> Material {
        Material {
            diffuse: self.diffuse * color.truncate(),
            ..self.clone()
        }
    }

    /// The color of this material drawn unlit (`PhongMaterial::unlit`): `k_d` alone.
    pub fn unlit_color(&self) -> DVec3 {
        self.diffuse
    }
}

/// The UVs a material's maps are sampled at: `transform · uv`, in `f64` (the material's
/// `uv_transform` as drawn, `limits::uv_transform`).
pub fn transformed_uv(transform: Affine2, uv: DVec2) -> DVec2 {
    transform.matrix2.as_dmat2() * uv + transform.translation.as_dvec2()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::SpecularModel;
    use glam::Vec2;

    #[test]
    fn a_vertex_color_multiplies_only_the_diffuse_color() {
        let material = Material {
            toon_ramp: None,
            diffuse: DVec3::new(0.5, 0.6, 0.8),
            ambient_factor: 1.0,
            specular: DVec3::ONE,
            specular_strength: 2.0,
            shininess: 32.0,
            specular_model: SpecularModel::Phong,
            emissive: DVec3::splat(0.1),
            diffuse_mode: crate::DiffuseMode::Lambert,
            specular_mode: crate::SpecularMode::Smooth,
            rim: crate::reference::Rim::NONE,
            metallic_roughness: None,
            ambient_specular: None,
        };
        let colored = material.with_vertex_color(DVec4::new(0.5, 1.0, 0.25, 0.3));
        assert_eq!(colored.diffuse, DVec3::new(0.25, 0.6, 0.2));
        let unlit = colored.unlit_color() - DVec3::new(0.25, 0.6, 0.2);
        assert!(unlit.abs().max_element() < 1e-15, "k_d alone: {unlit}");
        assert_eq!(
            Material {
                diffuse: material.diffuse,
                ..colored
            },
            material
        );
    }

    #[test]
    fn uvs_are_scaled_and_rotated_then_moved() {
        let transform = Affine2::from_scale_angle_translation(
            Vec2::new(2.0, 0.5),
            core::f32::consts::FRAC_PI_2,
            Vec2::new(0.25, -1.0),
        );
        let uv = transformed_uv(transform, DVec2::new(1.0, 0.0));
        // (1, 0) scaled to (2, 0), turned a quarter to (0, 2), moved by (0.25, -1).
        assert!((uv - DVec2::new(0.25, 1.0)).length() < 1e-6, "{uv}");
    }
}
