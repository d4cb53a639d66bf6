//! Bevy's tonemapping (`bevy_core_pipeline` 0.20.1, `tonemapping.wesl`, `tone_mapping`),
//! written again in `f64` from its formulas for four of the curves that read no lookup table,
//! with
//! the global color grading a camera applies in both places Bevy tonemaps (the material's
//! shader and the post-process): the exposure before the curve, the saturation after it.
//! The grading Bevy does per section, or with a hue or white balance, is compiled into its
//! post-process only; these tests leave it at its default.

use bevy::{core_pipeline::tonemapping::Tonemapping, render::view::ColorGradingGlobal};
use bevy_phong::reference;
use glam::{DMat3, DVec3};

/// Rec. 709's luminance weights, as `tonemapping_luminance` takes them.
const LUMINANCE: DVec3 = DVec3::new(0.2126, 0.7152, 0.0722);

/// Bevy's `tone_mapping` of a lit `color` under `method` and the camera's `grading`:
/// Reinhard (the reference model's `reinhard`), luminance Reinhard, ACES fitted and Khronos
/// PBR Neutral. `None` for the others: the methods with a lookup table (AgX, TonyMcMapface,
/// Blender Filmic), the display transform and `Linear`, which this module does not write
/// again, and `Tonemapping::None`, under which Bevy grades nothing either.
pub fn tone_mapped(
    color: DVec3,
    method: Tonemapping,
    grading: &ColorGradingGlobal,
) -> Option<DVec3> {
    let exposed = color.max(DVec3::ZERO) * 2f64.powf(f64::from(grading.exposure));
    let curved = match method {
        Tonemapping::Reinhard => reference::reinhard(exposed),
        Tonemapping::ReinhardLuminance => {
            let luminance = exposed.dot(LUMINANCE);
            exposed * (1.0 / (1.0 + luminance))
        }
        Tonemapping::AcesFitted => aces_fitted(exposed),
        Tonemapping::KhronosPbrNeutral => pbr_neutral(exposed),
        _ => return None,
    };
    // `saturation`: a mix from the luminance (0) to the color (1).
    let luminance = DVec3::splat(curved.dot(LUMINANCE));
    Some(luminance.lerp(curved, f64::from(grading.post_saturation)))
}

/// Stephen Hill's fit of ACES's reference rendering and output transforms: into the
/// transforms' space, a rational curve per channel, back, clamped to `[0, 1]`.
fn aces_fitted(color: DVec3) -> DVec3 {
    // Rows: sRGB → XYZ → D65→D60 → AP1 → RRT_SAT, and back from ODT_SAT.
    let rgb_to_rrt = DMat3::from_cols_array(&[
        0.59719, 0.35458, 0.04823, //
        0.07600, 0.90834, 0.01566, //
        0.02840, 0.13383, 0.83777,
    ])
    .transpose();
    let odt_to_rgb = DMat3::from_cols_array(&[
        1.60475, -0.53108, -0.07367, //
        -0.10208, 1.10813, -0.00605, //
        -0.00327, -0.07276, 1.07602,
    ])
    .transpose();
    let v = rgb_to_rrt * color;
    let a = v * (v + DVec3::splat(0.0245786)) - DVec3::splat(0.000090537);
    let b = v * (0.983729 * v + DVec3::splat(0.4329510)) + DVec3::splat(0.238081);
    (odt_to_rgb * (a / b)).clamp(DVec3::ZERO, DVec3::ONE)
}

/// Khronos's PBR Neutral: a toe below 0.08, uncompressed up to 0.76, then the largest
/// channel compressed toward 1 and the color desaturated toward it.
fn pbr_neutral(color: DVec3) -> DVec3 {
    const START_COMPRESSION: f64 = 0.8 - 0.04;
    const DESATURATION: f64 = 0.15;
    let x = color.min_element();
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    let color = color - DVec3::splat(offset);
    let peak = color.max_element();
    if peak < START_COMPRESSION {
        return color;
    }
    let d = 1.0 - START_COMPRESSION;
    let new_peak = 1.0 - d * d / (peak + d - START_COMPRESSION);
    let compressed = color * (new_peak / peak);
    let g = 1.0 - 1.0 / (DESATURATION * (peak - new_peak) + 1.0);
    compressed.lerp(DVec3::splat(new_peak), g)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values worked by hand: Reinhard's 1 → ½; the luminance curve scales gray 1 by ½ and
    /// keeps hue; ACES's fit maps gray 1 to `(1.0245786 − 0.000090537) / (0.983729 +
    /// 0.4329510 + 0.238081)` = 0.6191154 (the matrices' rows sum to 1 within 1e-5, so gray
    /// stays gray within that), clamps black's −0.00038 to 0 and large values to 1; PBR
    /// Neutral leaves a mid gray 0.5 at 0.46 (its toe takes 0.04).
    #[test]
    fn each_curve_gives_values_worked_by_hand() {
        let neutral = ColorGradingGlobal::default();
        let gray = |value: f64| DVec3::splat(value);
        let curve = |method, color| tone_mapped(color, method, &neutral).unwrap();
        assert!(
            (curve(Tonemapping::Reinhard, gray(1.0)) - gray(0.5))
                .abs()
                .max_element()
                < 1e-12
        );
        let red = DVec3::new(2.0, 0.0, 0.0);
        let expected = red / (1.0 + 2.0 * 0.2126);
        assert!(
            (curve(Tonemapping::ReinhardLuminance, red) - expected)
                .abs()
                .max_element()
                < 1e-12
        );
        let one = curve(Tonemapping::AcesFitted, gray(1.0));
        assert!((one - gray(0.6191154)).abs().max_element() < 1e-5, "{one}");
        assert_eq!(curve(Tonemapping::AcesFitted, gray(0.0)), gray(0.0));
        assert_eq!(curve(Tonemapping::AcesFitted, gray(1e6)), gray(1.0));
        assert!(
            (curve(Tonemapping::KhronosPbrNeutral, gray(0.5)) - gray(0.46))
                .abs()
                .max_element()
                < 1e-12
        );
        // An exposure of 1 doubles the color before the curve (red 4: Reinhard's 0.8); a
        // saturation of 0 leaves its luminance as gray.
        let graded = ColorGradingGlobal {
            exposure: 1.0,
            post_saturation: 0.0,
            ..ColorGradingGlobal::default()
        };
        let grayed = tone_mapped(red, Tonemapping::Reinhard, &graded).unwrap();
        assert!((grayed - gray(0.8 * 0.2126)).abs().max_element() < 1e-12);
        assert_eq!(tone_mapped(red, Tonemapping::None, &graded), None);
    }
}
