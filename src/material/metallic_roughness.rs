//! A metallic/roughness surface (glTF's, Bevy's `StandardMaterial`'s) as a Blinn-Phong one:
//! the rules that [`phong_material_from_gltf`](crate::gltf::phong_material_from_gltf) and
//! `PhongMaterial::from(&StandardMaterial)` share.
//!
//! - `base_color = base · (1 − metallic)` in linear RGB (alpha kept); an unlit surface keeps
//!   its base color as it is;
//! - `specular_color = mix(F₀, base, metallic)`, `F₀` the dielectric reflectance at normal
//!   incidence (0.04 for glTF; `0.16 · (reflectance · specular_tint)²` for
//!   `StandardMaterial`, Bevy's `calculate_F0_dielectric`);
//! - `specular_color` times Bevy's compensation for multiple scattering,
//!   `k · (1 + k · (1/E − 1))` per channel ([`with_multiple_scattering`]);
//! - three.js's normalized Blinn-Phong highlight ([`SpecularModel::NormalizedBlinnPhong`]:
//!   `F · (n + 2)/(8π) · cos^n(θ_h) · N·L`, Schlick's Fresnel on `f₀ = k_s · strength`) of
//!   exponent `n = clamp(a/r⁴ + b/r² + c, 1, 10⁴)` for perceptual roughness `r`
//!   ([`shininess_from_roughness`]), the lobe nearest Bevy's GGX lobe of roughness `r` as a
//!   display shows them (SPEC.md, "Metallic-roughness map"), with strength π:
//!   the crate's diffuse term `k_d · max(N·L, 0)` is the Lambert BRDF `k_d/π` times π, so a
//!   BRDF is drawn times π;
//! - the ambient light as `StandardMaterial` weighs it: `ambient_factor` [`BEVY_DIFFUSE_AMBIENT`]
//!   on the diffuse color, and the specular color's reflection of it
//!   (`ambient_specular`, at the perceptual roughness);
//! - the camera's `EnvironmentMapLight` as `StandardMaterial` weighs it
//!   (`environment_light`).

use super::{PhongMaterial, SpecularModel};
use crate::limits::{self, Limits};
use bevy::{
    asset::Handle,
    color::{Color, LinearRgba},
    image::Image,
    math::Vec3,
    mesh::UvChannel,
};

/// `metallic`: `[0, 1]`, NaN → 0 (a dielectric, the default of both sources).
pub(crate) const METALLIC: Limits = Limits::new(0.0, 1.0, 0.0);

/// Perceptual roughness: `[0, 1]`, NaN → 0.5 (the default of both sources).
pub(crate) const ROUGHNESS: Limits = Limits::new(0.0, 1.0, 0.5);

/// The smallest and largest highlight exponent the conversion gives: the fit
/// ([`shininess_from_roughness`]) would give 0.5 at `r = 1`, a highlight flatter than the
/// diffuse light; from `r ≈ 0.09` down it exceeds `10⁴`, where the highlight is already a
/// point at any screen resolution.
pub(crate) const SHININESS_RANGE: (f32, f32) = (1.0, 1e4);

/// The specular reflectance of a dielectric at normal incidence (glTF's `F₀`, and Bevy's at
/// its default reflectance 0.5).
pub(crate) const DIELECTRIC_F0: f32 = 0.04;

/// Bevy's weight on a `StandardMaterial`'s diffuse color under its ambient light:
/// bevy_pbr's `ambient_light` takes `EnvBRDFApprox(diffuse, F_AB(1, N·V))`, whose scale
/// `F_AB(1, ·).x = 0.468 − 1.04 · 0.015 = 0.4524` does not depend on `N·V` (its bias, 5e-5,
/// is left out).
pub(crate) const BEVY_DIFFUSE_AMBIENT: f32 = 0.4524;

/// The mean `N·V` over the visible half of a sphere, weighted by its projected area
/// (`∫cos² / ∫cos` over the hemisphere): where [`single_scattering_albedo`] is evaluated.
const MEAN_N_DOT_V: f32 = 2.0 / 3.0;

/// `E = A + B` of Bevy's `F_AB(r, N·V)` (Karis's fit of the split-sum integral, as Bevy
/// draws it by default) at [`MEAN_N_DOT_V`]: the share of the light a GGX lobe of perceptual
/// roughness `r` reflects in one scattering when `F₀ = 1`.
pub(crate) fn single_scattering_albedo(r: f32) -> f32 {
    let c = [
        1.0 - r,
        0.0425 - 0.0275 * r,
        1.04 - 0.572 * r,
        0.022 * r - 0.04,
    ];
    let a004 = (c[0] * c[0]).min((-9.28 * MEAN_N_DOT_V).exp2()) * c[0] + c[1];
    (c[2] - 1.04 * a004).max(5e-5) + (1.04 * a004 + c[3]).max(5e-5)
}

/// `k · (1 + k · (1/E − 1))` with `E` the [`single_scattering_albedo`] of roughness `r`: Bevy's
/// compensation of a specular reflectance `k` for the light a rough lobe scatters more than
/// once (bevy_pbr's `specular_multiscatter`, Filament's), at [`MEAN_N_DOT_V`].
pub(crate) fn with_multiple_scattering(reflectance: f32, r: f32) -> f32 {
    reflectance * (1.0 + reflectance * (1.0 / single_scattering_albedo(r) - 1.0))
}

/// A metallic/roughness surface's numbers.
#[derive(Clone, Debug)]
pub(crate) struct MetallicRoughness {
    /// The base color, any color space (alpha is the output alpha).
    pub(crate) base_color: Color,
    /// `[0, 1]` ([`METALLIC`]).
    pub(crate) metallic: f32,
    /// `[0, 1]` ([`ROUGHNESS`]).
    pub(crate) perceptual_roughness: f32,
    /// The dielectric `F₀` per channel, linear RGB (`[0, 1]`, NaN → [`DIELECTRIC_F0`]).
    pub(crate) dielectric_f0: Vec3,
    /// Shown as its base color, unlit (`KHR_materials_unlit`, `StandardMaterial::unlit`).
    pub(crate) unlit: bool,
    /// The metallic-roughness map (blue metallic, green roughness, times the factors above)
    /// and its UV set, if any.
    pub(crate) map: Option<(Handle<Image>, UvChannel)>,
}

impl MetallicRoughness {
    /// The [`PhongMaterial`] of these numbers: its colors, exponent, strength and the
    /// normalized Blinn-Phong model, the other fields at their defaults. Never holds a NaN:
    /// the numbers are brought into their ranges first. With a map (on a lit surface), the
    /// shader applies the same rules per texel
    /// ([`PhongMaterial::metallic_roughness_texture`]): the material keeps the base color and
    /// the dielectric `F₀` as they are, and the factors.
    pub(crate) fn phong_material(&self) -> PhongMaterial {
        match &self.map {
            Some((texture, channel)) if !self.unlit => PhongMaterial {
                metallic_roughness_texture: Some(texture.clone()),
                metallic_roughness_channel: channel.clone(),
                metallic: METALLIC.apply(self.metallic),
                perceptual_roughness: ROUGHNESS.apply(self.perceptual_roughness),
                // The dielectric's F₀ as it is: the texel's rules mix it and compensate it.
                specular_color: Color::LinearRgba(self.dielectric_f0_in_range()),
                ..Self {
                    metallic: 0.0,
                    ..self.clone()
                }
                .without_map()
            },
            _ => self.without_map(),
        }
    }

    /// The material of these numbers without a map.
    fn without_map(&self) -> PhongMaterial {
        let metallic = METALLIC.apply(self.metallic);
        let shininess = shininess_from_roughness(self.perceptual_roughness);
        let base = limits::linear_color(self.base_color.to_linear());
        let f0 = self.dielectric_f0_in_range();
        let f0 = [f0.red, f0.green, f0.blue];
        let r = ROUGHNESS.apply(self.perceptual_roughness);
        // An unlit material shows its base color as it is (KHR_materials_unlit).
        let diffuse = if self.unlit { 1.0 } else { 1.0 - metallic };
        // mix(F₀, c, m), written so that m = 0 and m = 1 give F₀ and c exactly, with Bevy's
        // compensation for multiple scattering.
        let specular =
            |f0: f32, channel: f32| with_multiple_scattering(f0 * diffuse + channel * metallic, r);
        PhongMaterial {
            base_color: Color::LinearRgba(LinearRgba::new(
                base.red * diffuse,
                base.green * diffuse,
                base.blue * diffuse,
                base.alpha,
            )),
            ambient_factor: BEVY_DIFFUSE_AMBIENT,
            ambient_specular: !self.unlit,
            environment_light: !self.unlit,
            perceptual_roughness: r,
            specular_color: Color::linear_rgb(
                specular(f0[0], base.red),
                specular(f0[1], base.green),
                specular(f0[2], base.blue),
            ),
            specular_strength: core::f32::consts::PI,
            shininess,
            specular_model: SpecularModel::NormalizedBlinnPhong,
            unlit: self.unlit,
            ..PhongMaterial::default()
        }
    }
}

impl MetallicRoughness {
    /// The dielectric `F₀` per channel in `[0, 1]` (NaN → [`DIELECTRIC_F0`]), alpha 1.
    fn dielectric_f0_in_range(&self) -> LinearRgba {
        let [red, green, blue] = self.dielectric_f0.to_array().map(|channel| {
            if channel.is_nan() {
                DIELECTRIC_F0
            } else {
                channel.clamp(0.0, 1.0)
            }
        });
        LinearRgba::rgb(red, green, blue)
    }
}

/// `(a, b, c)` of the highlight exponent `a/r⁴ + b/r² + c` of perceptual roughness `r`: the
/// normalized Blinn-Phong lobe nearest Bevy's GGX lobe of roughness `r` as a display shows
/// them (SPEC.md, "Metallic-roughness map"; fitted by the unit test `reference::ggx_fit`).
pub(crate) const EXPONENT_FIT: [f32; 3] = [0.669, 1.42, -1.59];

/// The Blinn-Phong exponent of roughness `r`: `clamp(a/r⁴ + b/r² + c, 1, 10⁴)` with
/// [`EXPONENT_FIT`], `r²` taken as at least `10⁻⁴` (the exponent is `10⁴` from `r ≈ 0.09`
/// down); NaN is taken as 0.5, values outside `[0, 1]` are clamped first ([`ROUGHNESS`]).
pub(crate) fn shininess_from_roughness(roughness: f32) -> f32 {
    let r = ROUGHNESS.apply(roughness);
    let (min, max) = SHININESS_RANGE;
    let [a, b, c] = EXPONENT_FIT;
    let x = 1.0 / (r * r).max(1e-4);
    ((a * x + b) * x + c).clamp(min, max)
}

/// `emissive` in [`limits::INTENSITY`]'s range, alpha 1 (the shader reads its RGB only).
pub(crate) fn emissive_color(emissive: LinearRgba) -> LinearRgba {
    let emissive = limits::linear_color(emissive);
    LinearRgba::rgb(emissive.red, emissive.green, emissive.blue)
}

/// What the tests of both conversions compare colors with.
#[cfg(test)]
pub(crate) mod tests {
    use bevy::color::{Color, ColorToComponents};

    /// `color` in linear RGBA.
    pub(crate) fn linear(color: Color) -> [f32; 4] {
        color.to_linear().to_f32_array()
    }

    /// `color` (linear RGBA) with each RGB channel compensated for multiple scattering at
    /// roughness `r`, as the conversions' specular color is.
    pub(crate) fn compensated(color: [f32; 4], r: f32) -> [f32; 4] {
        let [red, green, blue, alpha] = color;
        let [red, green, blue] = [red, green, blue].map(|k| super::with_multiple_scattering(k, r));
        [red, green, blue, alpha]
    }

    /// Exact up to f32 rounding of a product or a `mix` (a few ulps of values ≤ 1).
    const ROUNDING: f32 = 1e-6;

    /// Fails naming `what` where a channel is off by more than [`ROUNDING`].
    pub(crate) fn assert_close(actual: [f32; 4], expected: [f32; 4], what: &str) {
        for (a, e) in actual.iter().zip(expected) {
            assert!(
                (a - e).abs() <= ROUNDING,
                "{what}: {actual:?}, expected {expected:?}"
            );
        }
    }
}
