//! The shader contract: the WGSL lighting functions the material uses, compiled into a
//! fragment shader kernel and run on the render device on a corpus of cases, compared with
//! the f64 reference model on identical inputs.
//!
//! `PHONG_CONTRACT_CASES=4000000 cargo test --test gpu contract -- --nocapture` runs the
//! benchmark size (millions of random cases) and prints the same table.

mod area;
mod corpus;
mod kernel;

use bevy::prelude::*;
use bevy_phong::{PhongDirectionalLight, PhongMaterial, SpecularModel, reference};
use corpus::{AnyLight, Case, Random, Regime, corpus};
use glam::DVec3;
use kernel::ContractKernel;
use std::collections::BTreeMap;

/// Random cases in the default (CI) run; the degenerate cases come on top.
const DEFAULT_RANDOM_CASES: usize = 20_000;
const SEED: u64 = 0x5EED_F1A7;

/// Largest error over the channels of one result, relative to `max(1, |expected|)`;
/// infinite for a NaN or infinite result.
fn relative_error(actual: [f32; 3], expected: DVec3) -> f64 {
    (0..3)
        .map(|c| {
            let actual = f64::from(actual[c]);
            if !actual.is_finite() {
                return f64::INFINITY;
            }
            (actual - expected[c]).abs() / expected[c].abs().max(1.0)
        })
        .fold(0.0, f64::max)
}

/// The error of `case`: against the reference, or for a grazing case against whichever
/// side of the terminator is nearer.
fn case_error(case: &Case, actual: [f32; 3]) -> f64 {
    let error = relative_error(actual, case.expected());
    match case.other_side_of_terminator() {
        Some(other) => error.min(relative_error(actual, other)),
        None => error,
    }
}

#[derive(Default)]
struct RegimeStats {
    cases: usize,
    non_finite: usize,
    max_error: f64,
    worst: Option<(f64, &'static str, usize)>,
}

#[test]
fn lighting_functions_match_the_reference_on_the_whole_corpus() {
    let random_cases = std::env::var("PHONG_CONTRACT_CASES")
        .ok()
        .and_then(|count| count.parse().ok())
        .unwrap_or(DEFAULT_RANDOM_CASES);
    let cases = corpus(SEED, random_cases);
    let gpu: Vec<_> = cases.iter().map(|case| case.gpu).collect();
    let mut kernel = ContractKernel::new("main");
    let started = std::time::Instant::now();
    let results = kernel.run(&gpu);
    let gpu_time = started.elapsed();

    let mut stats: BTreeMap<Regime, RegimeStats> = BTreeMap::new();
    let mut stresses: BTreeMap<&'static str, f64> = BTreeMap::new();
    for (index, (case, actual)) in cases.iter().zip(&results).enumerate() {
        let error = case_error(case, *actual);
        let entry = stats.entry(case.regime).or_default();
        entry.cases += 1;
        if actual.iter().any(|c| !c.is_finite()) {
            entry.non_finite += 1;
        }
        if error > entry.max_error || entry.worst.is_none() {
            entry.max_error = error;
            entry.worst = Some((error, case.stresses, index));
        }
        if case.regime == Regime::Degenerate {
            let worst = stresses.entry(case.stresses).or_default();
            *worst = worst.max(error);
        }
    }

    println!(
        "\n{} cases on the render device in {:.2?}\n\n| regime | cases | NaN/inf | largest error | budget |\n|---|---|---|---|---|",
        cases.len(),
        gpu_time
    );
    for (regime, stat) in &stats {
        println!(
            "| {regime:?} | {} | {} | {:.2e} | {:.0e} |",
            stat.cases,
            stat.non_finite,
            stat.max_error,
            budget(*regime)
        );
    }
    println!("\n| degenerate case | largest error |\n|---|---|");
    for (stress, error) in &stresses {
        println!("| {stress} | {error:.2e} |");
    }

    for (regime, stat) in &stats {
        assert_eq!(stat.non_finite, 0, "{regime:?}: NaN or infinite results");
        let (error, stresses, index) = stat.worst.expect("cases in every regime");
        assert!(
            error <= budget(*regime),
            "{regime:?}: error {error:.3e} over budget {:.0e} at case {index} ({stresses}): {:?}",
            budget(*regime),
            cases[index]
        );
    }
}

/// The error budget of each regime, relative to `max(1, |expected|)`.
///
/// The largest error is the highlight's ([`highlight_budget`]) times the specular
/// intensities (light ≤ 2, `k_s · strength` ≤ 2 in the random cases, 1 in the degenerate
/// ones); the diffuse term and the attenuation add a few `f32` roundings (~1e-6). Each
/// budget is that bound at the regime's largest shininess, with a factor 2 of margin:
/// - typical and far (α ≤ 512): 4 · 1.2e-5 · 2 ≈ 1e-4; far from the origin the offsets
///   `light - P` and `camera - P` are exact (Sterbenz), so only the coarser inputs differ,
///   and both sides see the same inputs;
/// - grazing (α ≤ 512): as typical, judged on the nearer side of the terminator, where `f32`
///   cannot resolve the sign of `N·L`;
/// - degenerate (α ≤ 10,000, unit intensities): 5.1e-5 · 2 ≈ 1e-4.
fn budget(regime: Regime) -> f64 {
    match regime {
        Regime::Typical | Regime::Far | Regime::Grazing | Regime::Degenerate => 1e-4,
    }
}

/// Absolute error budget of the highlight factor `H ≤ 1` for shininess `α`.
///
/// `H = (1 - d)^α` with `d = |A - B|² / 2` for the two unit vectors of its cosine. `f32`
/// leaves each of them a direction error near 6 ulps (3.6e-7 rad), which moves `d` by
/// `θ · 3.6e-7` at angle `θ` from the peak; `H` moves by `α · θ · e^(-αθ²/2)` times that,
/// at most `sqrt(α / e) · 3.6e-7`, and twice that for two vectors: `4.4e-7 · sqrt(α)`. The
/// device's `exp` and `log` add about 1e-6. So: `5e-7 · sqrt(α) + 1e-6`.
fn highlight_budget(shininess: f64) -> f64 {
    5e-7 * shininess.sqrt() + 1e-6
}

/// Near the peak of the highlight, where it matters most and `α` amplifies every rounding,
/// the crate's `1 - cos = |A - B|² / 2` form keeps the accuracy that `pow(cos, α)` loses
/// once `cos` rounds to 1 (measured here against the f64 highlight, both formulas on the
/// same device).
#[test]
fn highlight_near_the_peak_is_accurate_where_the_naive_pow_is_not() {
    let mut random = Random::new(SEED);
    println!("\n| shininess | naive pow(cos, α) error | crate error | budget |\n|---|---|---|---|");
    let mut crate_kernel = ContractKernel::new("crate_highlight");
    let mut naive_kernel = ContractKernel::new("naive_highlight");
    for shininess in [50.0_f32, 500.0, 5_000.0, 10_000.0] {
        let cases: Vec<Case> = (0..4000)
            .map(|i| {
                let position = random.vector(10.0);
                let normal = random.direction();
                let to_light = (normal + random.direction() * 0.7).normalize();
                let mirror = 2.0 * normal.dot(to_light) * normal - to_light;
                // Within a few highlight widths of the peak (width ~ 1/sqrt(α)).
                let tilt = random.direction() * random.range(0.0, 3.0) / shininess.sqrt();
                let view = (mirror + tilt).normalize();
                let material = PhongMaterial {
                    shininess,
                    specular_model: if i % 2 == 0 {
                        SpecularModel::Phong
                    } else {
                        SpecularModel::BlinnPhong
                    },
                    ..default()
                };
                let light = AnyLight::Directional(
                    PhongDirectionalLight::default(),
                    Transform::default().looking_to(-to_light, to_light.any_orthonormal_vector()),
                );
                let camera = position + view * random.range(1.0, 20.0);
                Case::new(
                    Regime::Typical,
                    "highlight peak",
                    (position, normal, camera),
                    &material,
                    &light,
                )
            })
            .collect();
        let gpu: Vec<_> = cases.iter().map(|case| case.gpu).collect();
        let expected: Vec<f64> = cases
            .iter()
            .map(|case| {
                let reference::Light::Directional { direction, .. } = case.light else {
                    unreachable!("directional cases")
                };
                let normal = reference::normalize_or_zero(case.surface.normal);
                let view =
                    reference::normalize_or_zero(case.surface.camera - case.surface.position);
                reference::highlight(
                    case.material.specular_model,
                    normal,
                    -reference::normalize_or_zero(direction),
                    view,
                    case.material.shininess,
                )
            })
            .collect();
        let worst = |results: Vec<[f32; 3]>| {
            results
                .iter()
                .zip(&expected)
                .map(|(actual, expected)| (f64::from(actual[0]) - expected).abs())
                .fold(0.0, f64::max)
        };
        let naive = worst(naive_kernel.run(&gpu));
        let accurate = worst(crate_kernel.run(&gpu));
        let budget = highlight_budget(shininess.into());
        println!("| {shininess} | {naive:.2e} | {accurate:.2e} | {budget:.1e} |");
        assert!(
            accurate <= budget,
            "α = {shininess}: highlight error {accurate:.2e} over {budget:.1e}"
        );
    }
}
