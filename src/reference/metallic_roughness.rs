//! A metallic-roughness map in the reference model (SPEC.md, "Metallic-roughness map"): the
//! metallic/roughness surface of one texel, as Blinn-Phong or Phong terms.

use super::{AmbientSpecular, Material, environment_brdf};
use glam::DVec3;

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

/// `(a, b, c)` of the highlight exponent `a/r⁴ + b/r² + c` of perceptual roughness `r`: the
/// normalized Blinn-Phong lobe nearest Bevy's GGX lobe of roughness `r` as a display shows
/// them, by least squares over the hemisphere (SPEC.md, "Metallic-roughness map"; the unit
/// test `reference::ggx_fit` fits them).
pub const EXPONENT_FIT: [f64; 3] = [0.669, 1.42, -1.59];

/// The Blinn-Phong exponent of perceptual roughness `r` (in `[0, 1]`):
/// `clamp(a/r⁴ + b/r² + c, 1, 10⁴)` with [`EXPONENT_FIT`]; `r²` is taken as at least `10⁻⁴`
/// (the exponent is `10⁴` well above that, from `r ≈ 0.09`), so `r = 0` never divides.
pub fn shininess_from_roughness(r: f64) -> f64 {
    let [a, b, c] = EXPONENT_FIT;
    let x = 1.0 / (r * r).max(1e-4);
    ((a * x + b) * x + c).clamp(1.0, MAX_SHININESS)
}

/// The mean `N·V` over the visible half of a sphere, weighted by its projected area
/// (`∫cos² dω / ∫cos dω` over the hemisphere).
pub const MEAN_N_DOT_V: f64 = 2.0 / 3.0;

/// `k · (1 + k · (1/E − 1))` per channel, `E = A + B` of [`environment_brdf`]`(r,`
/// [`MEAN_N_DOT_V`]`)`: Bevy's compensation of a specular reflectance `k` for the light a
/// GGX lobe of perceptual roughness `r` scatters more than once (bevy_pbr's
/// `specular_multiscatter`), at the mean `N·V`.
pub fn with_multiple_scattering(reflectance: DVec3, r: f64) -> DVec3 {
    let weights = environment_brdf(r, MEAN_N_DOT_V);
    let albedo = weights.x + weights.y;
    reflectance * (DVec3::ONE + reflectance * (1.0 / albedo - 1.0))
}

impl Material {
    /// This material (its maps and vertex color applied) at a texel of its metallic-roughness
    /// map whose blue and green channels are `metallic` and `roughness`: with
    /// `m = metallic · factor` and `r = roughness · factor` clamped to `[0, 1]`,
    /// `k_d · (1 − m)`, `k_s = mix(k_s, k_d, m)` compensated for multiple scattering
    /// ([`with_multiple_scattering`]) and `α` from `r` ([`shininess_from_roughness`]); `r` is
    /// also the ambient specular's roughness. The strength stays the material's.
    pub fn at_metallic_roughness_texel(
        &self,
        factors: MetallicRoughness,
        metallic: f64,
        roughness: f64,
    ) -> Material {
        let m = (metallic * factors.metallic).clamp(0.0, 1.0);
        let r = (roughness * factors.perceptual_roughness).clamp(0.0, 1.0);
        let shininess = shininess_from_roughness(r);
        let reflectance = self.specular + (self.diffuse - self.specular) * m;
        Material {
            diffuse: self.diffuse * (1.0 - m),
            specular: with_multiple_scattering(reflectance, r),
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
        assert_eq!(
            metal.specular,
            with_multiple_scattering(DVec3::new(0.8, 0.4, 0.2), 0.5)
        );
        // 2 / 0.5⁴ − 2 = 30, worked by hand; the strength stays the material's.
        assert!(
            (metal.shininess - 14.794).abs() < 1e-9,
            "0.669·16 + 1.42·4 − 1.59"
        );
        assert_eq!(metal.specular_strength, 1.0);
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
        // mix(0.04, 0.8, 0.25) = 0.23 in red, compensated at r = 0.5.
        let red = with_multiple_scattering(DVec3::splat(0.23), 0.5).x;
        assert!((texel.specular.x - red).abs() < 1e-15, "{}", texel.specular);
        assert!(
            (texel.shininess - 14.794).abs() < 1e-9,
            "0.669·16 + 1.42·4 − 1.59"
        );
        let dielectric = plastic().at_metallic_roughness_texel(FACTORS_ONE, 0.0, 1.0);
        assert_eq!(dielectric.diffuse, plastic().diffuse);
        assert_eq!(
            dielectric.specular,
            with_multiple_scattering(plastic().specular, 1.0)
        );
        assert_eq!(dielectric.shininess, 1.0, "r = 1 gives 0, clamped to 1");
    }

    #[test]
    fn multiple_scattering_adds_what_a_rough_lobe_loses_and_nothing_to_a_smooth_one() {
        // E = A + B of F_AB(1, 2/3): A = 0.4524, B = 5e-5 (worked in ambient_specular's
        // tests), so a white metal at r = 1 reflects 1/E.
        let white = with_multiple_scattering(DVec3::ONE, 1.0);
        assert!((white.x - 1.0 / (0.4524 + 5e-5)).abs() < 1e-9, "{white}");
        // A black specular color stays black; a smooth lobe loses nothing: at r = 0,
        // a004 = 2^(−9.28·2/3) + 0.0425, A = 1.04 − 1.04·a004, B = 1.04·a004 − 0.04, E = 1.
        assert_eq!(with_multiple_scattering(DVec3::ZERO, 0.5), DVec3::ZERO);
        let smooth = with_multiple_scattering(DVec3::splat(0.9), 0.0).x;
        assert!((smooth - 0.9).abs() < 1e-12, "{smooth}");
    }

    #[test]
    fn the_exponent_is_capped_and_never_divides_by_zero() {
        assert_eq!(shininess_from_roughness(0.0), MAX_SHININESS);
        assert_eq!(shininess_from_roughness(0.05), MAX_SHININESS);
        let fitted = 0.669 / 0.2f64.powi(4) + 1.42 / 0.2f64.powi(2) - 1.59;
        assert!((shininess_from_roughness(0.2) - fitted).abs() < 1e-9);
        assert_eq!(shininess_from_roughness(1.0), 1.0);
        // Out-of-range products are clamped before: a texel of 2 is a full metal.
        let clamped = plastic().at_metallic_roughness_texel(FACTORS_ONE, 2.0, -1.0);
        assert_eq!(clamped.diffuse, DVec3::ZERO);
        assert_eq!(clamped.shininess, MAX_SHININESS);
    }

    /// The conversion's fit (`material::metallic_roughness`, f32) is this model's, to f32's
    /// precision.
    #[test]
    fn the_conversions_exponent_is_this_models() {
        use crate::material::metallic_roughness as conversion;
        assert_eq!(
            conversion::EXPONENT_FIT.map(f64::from),
            EXPONENT_FIT.map(|c| f64::from(c as f32))
        );
        for step in 0..=100 {
            let r = step as f32 / 100.0;
            let expected = shininess_from_roughness(f64::from(r));
            let actual = f64::from(conversion::shininess_from_roughness(r));
            assert!(
                (actual / expected - 1.0).abs() < 1e-5,
                "r = {r}: {actual}, {expected}"
            );
        }
    }
}
