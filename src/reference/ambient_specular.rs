//! The ambient light's specular reflectance in the reference model (SPEC.md, "Ambient
//! specular"): the share of a light from every direction that a specular color reflects
//! toward the viewer, weighed as `StandardMaterial` weighs its ambient light.

use super::{Material, SurfacePoint, normalize_or_zero};
use glam::{DVec2, DVec3, DVec4};

/// A material's ambient specular term (`PhongMaterial::ambient_specular`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AmbientSpecular {
    /// The perceptual roughness that weighs it, in `[0, 1]` (the material's, or its
    /// metallic-roughness map's texel's).
    pub perceptual_roughness: f64,
}

/// bevy_pbr's `F_AB(perceptual_roughness, n_dot_v)` as Bevy draws it by default (without
/// its `dfg_lut` feature): Karis's polynomial fit of the split-sum integral of a GGX lobe,
/// the scale `A` on `F₀` and the bias `B`, each at least `5·10⁻⁵`.
pub fn environment_brdf(perceptual_roughness: f64, n_dot_v: f64) -> DVec2 {
    let c0 = DVec4::new(-1.0, -0.0275, -0.572, 0.022);
    let c1 = DVec4::new(1.0, 0.0425, 1.04, -0.04);
    let r = perceptual_roughness * c0 + c1;
    let a004 = (r.x * r.x).min((-9.28 * n_dot_v).exp2()) * r.x + r.y;
    (DVec2::new(-1.04, 1.04) * a004 + DVec2::new(r.z, r.w)).max(DVec2::splat(5e-5))
}

impl Material {
    /// The ambient light's specular reflectance at `surface`:
    /// `(k_s · A + B) · clamp(16.5 · (k_s.r + k_s.g + k_s.b), 0, 1)` with `(A, B)`
    /// [`environment_brdf`] at the term's roughness and `max(N·V, 10⁻⁴)`, the last factor
    /// Bevy's specular occlusion; zero for a material without the term.
    pub fn ambient_specular_reflectance(&self, surface: &SurfacePoint) -> DVec3 {
        let Some(term) = self.ambient_specular else {
            return DVec3::ZERO;
        };
        let normal = normalize_or_zero(surface.normal);
        let view = normalize_or_zero(surface.camera - surface.position);
        let weights = environment_brdf(term.perceptual_roughness, normal.dot(view).max(1e-4));
        let occlusion = (16.5 * self.specular.element_sum()).clamp(0.0, 1.0);
        (self.specular * weights.x + DVec3::splat(weights.y)) * occlusion
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weights_are_bevys_polynomial_worked_by_hand() {
        // Roughness 1: r = (0, 0.015, 0.468, −0.018), a004 = 0.015 at any N·V, so
        // A = 0.468 − 0.0156 = 0.4524 and B = max(0.0156 − 0.018, 5e-5) = 5e-5.
        for n_dot_v in [1e-4, 0.5, 1.0] {
            let weights = environment_brdf(1.0, n_dot_v);
            assert!((weights - DVec2::new(0.4524, 5e-5)).abs().max_element() < 1e-12);
        }
        // Roughness 0 at N·V = 1: r = (1, 0.0425, 1.04, −0.04),
        // a004 = 2^−9.28 + 0.0425, A = 1.04 − 1.04·a004, B = 1.04·a004 − 0.04.
        let a004 = (-9.28f64).exp2() + 0.0425;
        let weights = environment_brdf(0.0, 1.0);
        assert!((weights.x - (1.04 - 1.04 * a004)).abs() < 1e-12);
        assert!((weights.y - (1.04 * a004 - 0.04)).abs() < 1e-12);
    }

    #[test]
    fn a_surface_without_a_specular_color_or_the_term_reflects_no_ambient_light() {
        let surface = SurfacePoint {
            position: DVec3::ZERO,
            normal: DVec3::Z,
            camera: DVec3::new(0.0, 1.0, 2.0),
        };
        let metal = Material {
            specular: DVec3::new(1.0, 0.78, 0.34),
            ambient_specular: Some(AmbientSpecular {
                perceptual_roughness: 0.5,
            }),
            ..crate::reference::tests::matte(DVec3::ZERO)
        };
        let reflectance = metal.ambient_specular_reflectance(&surface);
        let weights = environment_brdf(0.5, 2.0 / 5f64.sqrt());
        assert!((reflectance - (metal.specular * weights.x + weights.y)).length() < 1e-12);
        let black = Material {
            specular: DVec3::ZERO,
            ..metal.clone()
        };
        assert_eq!(black.ambient_specular_reflectance(&surface), DVec3::ZERO);
        let without = Material {
            ambient_specular: None,
            ..metal
        };
        assert_eq!(without.ambient_specular_reflectance(&surface), DVec3::ZERO);
    }
}
