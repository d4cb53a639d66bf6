//! How the converted highlight's exponent is fitted to Bevy's GGX lobe (docs/switching.md,
//! "The highlight's fit"): by least squares over the hemisphere, between Bevy's specular
//! term (`D_GGX · V_SmithGGXCorrelated · N·L`, bevy_pbr 0.20.1's `specular`) and the
//! conversion's (normalized Blinn-Phong at strength π: `(α + 2)/(8π) · (N·H)^α · N·L`, the
//! same light). Fresnel is left out of both (the same Schlick term multiplies each).
//!
//! The lobes are compared as a display shows them: each raised to the power `1/2.2`, the
//! encoding a display undoes. The distance of a lobe `p` from Bevy's `g` is
//! `√(∫(g^γ − p^γ)² dω / ∫g^{2γ} dω)` over the directions `ω` of the light, summed over
//! views 0°, 30° and 60° from the normal. A power law scales both lobes alike for any
//! brightness of the light (`(k·g)^γ − (k·p)^γ = k^γ · (g^γ − p^γ)`), so the fit holds for
//! every light. In linear light (`γ = 1`) the fit weighs the lobe's peak and hardly sees
//! GGX's long tails, which a display shows brightly around a smooth metal's highlight; the
//! table prints that distance too, and Walter's width (`2/r⁴ − 2`, the lobe of the same
//! width), which is nearest in linear light.

use super::{EXPONENT_FIT, shininess_from_roughness};
use core::f64::consts::{FRAC_PI_2, PI};
use glam::DVec3;

/// The power that encodes linear light for a display (sRGB's, near its mid-tones).
const DISPLAY_POWER: f64 = 1.0 / 2.2;

/// Bevy's specular term times `N·L` for the GGX roughness `a = r²`.
fn bevy_lobe(a: f64, n_dot_h: f64, n_dot_v: f64, n_dot_l: f64) -> f64 {
    let k = a / ((1.0 - n_dot_h * n_dot_h) + (n_dot_h * a).powi(2));
    let distribution = k * k / PI;
    let a2 = a * a;
    let lambda_v = n_dot_l * ((n_dot_v - a2 * n_dot_v) * n_dot_v + a2).sqrt();
    let lambda_l = n_dot_v * ((n_dot_l - a2 * n_dot_l) * n_dot_l + a2).sqrt();
    distribution * 0.5 / (lambda_v + lambda_l) * n_dot_l
}

/// The converted highlight times `N·L`, per unit of Bevy's light, for the exponent `alpha`.
fn converted_lobe(alpha: f64, n_dot_h: f64, n_dot_l: f64) -> f64 {
    (alpha + 2.0) / (8.0 * PI) * n_dot_h.powf(alpha) * n_dot_l
}

/// `(N·H, N·V, N·L, dω)` over a grid of light directions (64 × 128 over the hemisphere),
/// for each view.
fn samples() -> Vec<[f64; 4]> {
    const ROWS: usize = 64;
    let mut samples = Vec::with_capacity(3 * ROWS * 2 * ROWS);
    for view_angle in [0.0f64, 30.0, 60.0] {
        let view = DVec3::new(
            view_angle.to_radians().sin(),
            0.0,
            view_angle.to_radians().cos(),
        );
        for row in 0..ROWS {
            let theta = (row as f64 + 0.5) / ROWS as f64 * FRAC_PI_2;
            let solid_angle = theta.sin() * (FRAC_PI_2 / ROWS as f64) * (PI / ROWS as f64);
            for column in 0..2 * ROWS {
                let phi = (column as f64 + 0.5) / ROWS as f64 * PI;
                let light = DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                );
                let half = (view + light).normalize();
                samples.push([half.z, view.z, light.z, solid_angle]);
            }
        }
    }
    samples
}

/// Bevy's lobe of GGX roughness `a` at each of `samples`, with their directions and solid
/// angles: what each candidate lobe is measured against, computed once, for one encoding.
struct Target {
    /// The power each lobe is raised to before they are compared.
    power: f64,
    /// `(N·H, N·L, dω, Bevy's lobe to the power)` per sample.
    samples: Vec<[f64; 4]>,
    /// `∫g^{2·power} dω`.
    norm: f64,
}

impl Target {
    fn new(samples: &[[f64; 4]], a: f64, power: f64) -> Self {
        let samples: Vec<[f64; 4]> = samples
            .iter()
            .map(|&[n_dot_h, n_dot_v, n_dot_l, solid_angle]| {
                let bevy = bevy_lobe(a, n_dot_h, n_dot_v, n_dot_l).powf(power);
                [n_dot_h, n_dot_l, solid_angle, bevy]
            })
            .collect();
        let norm = samples
            .iter()
            .map(|&[_, _, dw, bevy]| bevy * bevy * dw)
            .sum();
        Self {
            power,
            samples,
            norm,
        }
    }

    /// The distance of the converted lobe of exponent `alpha` (at strength π).
    fn distance(&self, alpha: f64) -> f64 {
        let error: f64 = self
            .samples
            .iter()
            .map(|&[n_dot_h, n_dot_l, dw, bevy]| {
                (bevy - converted_lobe(alpha, n_dot_h, n_dot_l).powf(self.power)).powi(2) * dw
            })
            .sum();
        (error / self.norm).sqrt()
    }

    /// The exponent in `[alpha / 16, 4 · alpha]` nearest Bevy's lobe (golden-section search
    /// on its logarithm).
    fn best_exponent(&self, alpha: f64) -> f64 {
        let (mut low, mut high) = ((alpha / 16.0).max(0.3).ln(), (4.0 * alpha).ln());
        let ratio = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..30 {
            let (a, b) = (high - ratio * (high - low), low + ratio * (high - low));
            if self.distance(a.exp()) < self.distance(b.exp()) {
                high = b;
            } else {
                low = a;
            }
        }
        ((low + high) / 2.0).exp()
    }
}

/// The coefficients `(a, b, c)` of `a·x² + b·x + c`, `x = 1/r²`, that fit `exponents`
/// (`(r, α)` pairs) with the least squared relative error: the normal equations of
/// `Σ((a·x² + b·x + c)/α − 1)²`, solved by Cramer's rule.
fn fitted_coefficients(exponents: &[(f64, f64)]) -> [f64; 3] {
    let rows: Vec<[f64; 3]> = exponents
        .iter()
        .map(|&(r, alpha)| {
            let x = 1.0 / (r * r);
            [x * x / alpha, x / alpha, 1.0 / alpha]
        })
        .collect();
    let mut normal = [[0.0; 3]; 3];
    let mut right = [0.0; 3];
    for row in &rows {
        for i in 0..3 {
            right[i] += row[i];
            for j in 0..3 {
                normal[i][j] += row[i] * row[j];
            }
        }
    }
    let determinant = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let whole = determinant(normal);
    core::array::from_fn(|column| {
        let mut replaced = normal;
        for (row, value) in replaced.iter_mut().zip(right) {
            row[column] = value;
        }
        determinant(replaced) / whole
    })
}

/// Each row: roughness; the conversion's exponent and its distance as a display shows the
/// lobes; the best exponent there and its distance; Walter's exponent, its distance there
/// and in linear light beside the conversion's.
#[test]
fn the_converted_exponent_is_the_one_nearest_bevys_lobe_as_a_display_shows_it() {
    let samples = samples();
    println!(
        "| r | α | distance | best α | distance | Walter's α | distance | \
         in linear light (Walter's, α's) |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let mut best = Vec::new();
    for step in 3..=20 {
        let r = f64::from(step) * 0.05;
        let display = Target::new(&samples, r * r, DISPLAY_POWER);
        let linear = Target::new(&samples, r * r, 1.0);
        let alpha = shininess_from_roughness(r);
        let walter = (2.0 / r.powi(4) - 2.0).clamp(1.0, 1e4);
        let fitted = display.best_exponent(alpha);
        let (converted, fitted_distance) = (display.distance(alpha), display.distance(fitted));
        println!(
            "| {r:.2} | {alpha:.1} | {converted:.3} | {fitted:.1} | {fitted_distance:.3} | \
             {walter:.1} | {:.3} | {:.3}, {:.3} |",
            display.distance(walter),
            linear.distance(walter),
            linear.distance(alpha),
        );
        best.push((r, fitted));
        // Up to r = 0.9 the fitted form is within 0.002 of the best exponent (whose
        // distance is 0.18–0.42: no power of the cosine takes GGX's shape). At r = 1 the
        // best exponent, 0.45, is below the conversion's smallest, 1 (0.013 further).
        let margin = if r < 0.95 { 0.002 } else { 0.015 };
        assert!(
            converted - fitted_distance < margin,
            "r = {r}: {converted} against {fitted_distance}"
        );
        assert!(
            converted <= display.distance(walter) + margin,
            "r = {r}: the fit is further than Walter's width"
        );
    }
    // The constants are the fit of these exponents, rounded to three digits.
    let refitted = fitted_coefficients(&best);
    println!("fitted a/r⁴ + b/r² + c: {refitted:?}, the conversion's: {EXPONENT_FIT:?}");
    for (refitted, constant) in refitted.iter().zip(EXPONENT_FIT) {
        assert!(
            (refitted - constant).abs() < 0.01 * constant.abs(),
            "{refitted} against {constant}"
        );
    }
}
