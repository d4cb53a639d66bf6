//! How near the converted highlight is to Bevy's GGX lobe (docs/switching.md, "The
//! highlight's fit"): the least-squares distance over the hemisphere between Bevy's
//! specular term (`D_GGX · V_SmithGGXCorrelated · N·L`, bevy_pbr 0.20.1's `specular`) and
//! the conversion's (normalized Blinn-Phong at strength π: `(α + 2)/(8π) · (N·H)^α · N·L`,
//! the same light), with the exponent [`shininess_from_roughness`] gives and with the
//! exponent, and the exponent and a strength, that fit best. Fresnel is left out of both
//! (the same Schlick term multiplies each).
//!
//! The distance of a lobe `p` from Bevy's `g` is `√(∫(g − p)² dω / ∫g² dω)` over the
//! directions `ω` of the light, summed over views 0°, 30° and 60° from the normal.

use super::shininess_from_roughness;
use core::f64::consts::{FRAC_PI_2, PI};
use glam::DVec3;

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
/// angles: what each candidate lobe is measured against, computed once.
struct Target {
    /// `(N·H, N·L, dω, Bevy's lobe)` per sample.
    samples: Vec<[f64; 4]>,
    /// `∫g² dω`.
    norm: f64,
}

impl Target {
    fn new(samples: &[[f64; 4]], a: f64) -> Self {
        let samples: Vec<[f64; 4]> = samples
            .iter()
            .map(|&[n_dot_h, n_dot_v, n_dot_l, solid_angle]| {
                let bevy = bevy_lobe(a, n_dot_h, n_dot_v, n_dot_l);
                [n_dot_h, n_dot_l, solid_angle, bevy]
            })
            .collect();
        let norm = samples
            .iter()
            .map(|&[_, _, dw, bevy]| bevy * bevy * dw)
            .sum();
        Self { samples, norm }
    }

    /// The distance of the converted lobe of exponent `alpha` and strength `scale` (1: π).
    fn distance(&self, alpha: f64, scale: f64) -> f64 {
        let error: f64 = self
            .samples
            .iter()
            .map(|&[n_dot_h, n_dot_l, dw, bevy]| {
                (bevy - scale * converted_lobe(alpha, n_dot_h, n_dot_l)).powi(2) * dw
            })
            .sum();
        (error / self.norm).sqrt()
    }

    /// The strength (1: π) that fits best for the exponent `alpha`.
    fn best_scale(&self, alpha: f64) -> f64 {
        let (mut both, mut converted) = (0.0, 0.0);
        for &[n_dot_h, n_dot_l, dw, bevy] in &self.samples {
            let lobe = converted_lobe(alpha, n_dot_h, n_dot_l);
            both += bevy * lobe * dw;
            converted += lobe * lobe * dw;
        }
        both / converted
    }
}

/// The exponent in `[alpha / 8, 4 · alpha]` that minimizes `cost` (golden-section search on
/// its logarithm).
fn best_exponent(alpha: f64, cost: impl Fn(f64) -> f64) -> f64 {
    let (mut low, mut high) = ((alpha / 8.0).max(0.5).ln(), (4.0 * alpha).ln());
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..30 {
        let (a, b) = (high - ratio * (high - low), low + ratio * (high - low));
        if cost(a.exp()) < cost(b.exp()) {
            high = b;
        } else {
            low = a;
        }
    }
    ((low + high) / 2.0).exp()
}

/// Each row: roughness, the conversion's distance, the best exponent (ratio to the
/// conversion's) and its distance, the best exponent and strength and their distance.
#[test]
fn the_converted_exponent_fits_bevys_lobe_as_well_as_any_exponent_at_its_strength() {
    let samples = samples();
    println!("| r | α | distance | best α (×) | distance | best α, strength (×π) | distance |");
    println!("|---|---|---|---|---|---|---|");
    for r in [0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9] {
        let target = Target::new(&samples, r * r);
        let alpha = shininess_from_roughness(r);
        let converted = target.distance(alpha, 1.0);
        let fitted = best_exponent(alpha, |x| target.distance(x, 1.0));
        let fitted_distance = target.distance(fitted, 1.0);
        let scaled = best_exponent(alpha, |x| target.distance(x, target.best_scale(x)));
        let scale = target.best_scale(scaled);
        let scaled_distance = target.distance(scaled, scale);
        println!(
            "| {r} | {alpha:.1} | {converted:.3} | {fitted:.1} (×{:.2}) | {fitted_distance:.3} | \
             {scaled:.1}, {scale:.2} | {scaled_distance:.3} |",
            fitted / alpha
        );
        // The lobes' shapes differ (GGX's falls as (1 + x)⁻², a power of the cosine as
        // e^−x): no exponent comes within 0.3 of Bevy's lobe; the conversion's is within
        // 0.025 of the best one at the same strength.
        assert!(
            converted - fitted_distance < 0.025,
            "r = {r}: {converted} against {fitted_distance}"
        );
        assert!((0.3..0.52).contains(&converted), "r = {r}: {converted}");
    }
}
