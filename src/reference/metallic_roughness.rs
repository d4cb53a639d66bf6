//! A metallic-roughness map in the reference model (SPEC.md, "Metallic-roughness map"): the
//! metallic/roughness surface of one texel, as Blinn-Phong or Phong terms.

use super::{AmbientSpecular, Material};

/// The factors on a metallic-roughness map's channels (`PhongMaterial::metallic`,
/// `PhongMaterial::perceptual_roughness`, in their ranges).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetallicRoughness {
    /// Multiplies the map's blue channel.
    pub metallic: f64,
    /// Multiplies the map's green channel.
    pub perceptual_roughness: f64,
}

/// The largest highlight exponent a roughness gives.
pub const MAX_SHININESS: f64 = 1e4;

/// The Blinn-Phong exponent of perceptual roughness `r` (in `[0, 1]`):
/// `clamp(2 / r⁴ − 2, 1, 10⁴)`, the width of a GGX lobe of `α = r²`; `10⁴` wherever
/// `2 / r⁴ − 2` reaches it (`r = 0` included).
pub fn shininess_from_roughness(r: f64) -> f64 {
    let alpha_squared = r.powi(4);
    if alpha_squared <= 2.0 / (MAX_SHININESS + 2.0) {
        MAX_SHININESS
    } else {
        (2.0 / alpha_squared - 2.0).clamp(1.0, MAX_SHININESS)
    }
}

impl Material {
    /// This material (its maps and vertex color applied) at a texel of its metallic-roughness
    /// map whose blue and green channels are `metallic` and `roughness`: with
    /// `m = metallic · factor` and `r = roughness · factor` clamped to `[0, 1]`,
    /// `k_d · (1 − m)`, `k_s = mix(k_s, k_d, m)`, `α` from `r`
    /// ([`shininess_from_roughness`]) and the strength times `(α + 8) / 8`; `r` is also the
    /// ambient specular's roughness.
    pub fn at_metallic_roughness_texel(
        &self,
        factors: MetallicRoughness,
        metallic: f64,
        roughness: f64,
    ) -> Material {
        let m = (metallic * factors.metallic).clamp(0.0, 1.0);
        let r = (roughness * factors.perceptual_roughness).clamp(0.0, 1.0);
        let shininess = shininess_from_roughness(r);
        Material {
            diffuse: self.diffuse * (1.0 - m),
            specular: self.specular + (self.diffuse - self.specular) * m,
            specular_strength: self.specular_strength * (shininess + 8.0) / 8.0,
            shininess,
            ambient_specular: self.ambient_specular.map(|_| AmbientSpecular {
                perceptual_roughness: r,
            }),
            ..self.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn plastic() -> Material {
        Material {
            diffuse: DVec3::new(0.8, 0.4, 0.2),
            specular: DVec3::splat(0.04),
            specular_strength: 1.0,
            metallic_roughness: Some(FACTORS_ONE),
            ..crate::reference::tests::matte(DVec3::ZERO)
        }
    }

    const FACTORS_ONE: MetallicRoughness = MetallicRoughness {
        metallic: 1.0,
        perceptual_roughness: 1.0,
    };

    #[test]
    fn a_metal_texel_reflects_its_base_color_and_has_no_diffuse() {
        let metal = plastic().at_metallic_roughness_texel(FACTORS_ONE, 1.0, 0.5);
        assert_eq!(metal.diffuse, DVec3::ZERO);
        assert_eq!(metal.specular, DVec3::new(0.8, 0.4, 0.2));
        // 2 / 0.5⁴ − 2 = 30, worked by hand; (30 + 8) / 8.
        assert_eq!(metal.shininess, 30.0);
        assert_eq!(metal.specular_strength, 4.75);
    }

    #[test]
    fn a_dielectric_texel_keeps_its_color_and_the_factors_scale_the_channels() {
        let half = MetallicRoughness {
            metallic: 0.5,
            perceptual_roughness: 0.5,
        };
        // m = 0.5 · 0.5 = 0.25, r = 0.5 · 1 = 0.5.
        let texel = plastic().at_metallic_roughness_texel(half, 0.5, 1.0);
        let expected_diffuse = DVec3::new(0.6, 0.3, 0.15);
        assert!((texel.diffuse - expected_diffuse).abs().max_element() < 1e-15);
        // mix(0.04, 0.8, 0.25) = 0.23 in red.
        assert!(
            (texel.specular.x - 0.23).abs() < 1e-15,
            "{}",
            texel.specular
        );
        assert_eq!(texel.shininess, 30.0);
        let dielectric = plastic().at_metallic_roughness_texel(FACTORS_ONE, 0.0, 1.0);
        assert_eq!(dielectric.diffuse, plastic().diffuse);
        assert_eq!(dielectric.specular, plastic().specular);
        assert_eq!(dielectric.shininess, 1.0, "r = 1 gives 0, clamped to 1");
    }

    #[test]
    fn the_exponent_is_capped_and_never_divides_by_zero() {
        assert_eq!(shininess_from_roughness(0.0), MAX_SHININESS);
        assert_eq!(shininess_from_roughness(0.1), MAX_SHININESS);
        assert!((shininess_from_roughness(0.2) - (2.0 / 0.2f64.powi(4) - 2.0)).abs() < 1e-9);
        assert_eq!(shininess_from_roughness(1.0), 1.0);
        // Out-of-range products are clamped before: a texel of 2 is a full metal.
        let clamped = plastic().at_metallic_roughness_texel(FACTORS_ONE, 2.0, -1.0);
        assert_eq!(clamped.diffuse, DVec3::ZERO);
        assert_eq!(clamped.shininess, MAX_SHININESS);
    }
}
