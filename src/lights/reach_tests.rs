//! The influence radius against the fall-off it inverts: its boundaries, the exact root it
//! rounds up, and the light past it under SPEC.md's fall-off, written out here.

use super::reach::influence_radius;

/// The boundaries of `influence_radius`: a light exactly at ε reaches ε out to where its
/// fall-off begins (1 unit for `1/d²`), one below ε reaches nowhere, and so does a NaN
/// intensity.
#[test]
fn a_light_at_epsilon_reaches_to_its_fall_off_and_one_below_or_nan_nowhere() {
    let epsilon = 1.0 / 256.0;
    let inverse_square = [0.0, 0.0, 1.0];
    assert_eq!(influence_radius(inverse_square, epsilon, epsilon), 1.0);
    assert_eq!(
        influence_radius(inverse_square, 0.5 * epsilon, epsilon),
        0.0
    );
    assert_eq!(influence_radius(inverse_square, f32::NAN, epsilon), 0.0);
}

/// The radius is rounded up to the next `f32`: at or past the exact radius (the root of
/// `constant + linear·d + quadratic·d² = I / ε`, worked in `f64` in its textbook form),
/// and the `f32` just below it falls short of the exact one.
#[test]
fn the_radius_is_the_exact_one_rounded_up_to_an_f32() {
    let epsilon = 1.0 / 1024.0;
    for step in 1..200 {
        let intensity = 0.01 * step as f32;
        let decay = [1.0, 0.3, 0.07];
        // The coefficients as the function takes them: `f32`s.
        let [constant, linear, quadratic] = decay.map(f64::from);
        let threshold = f64::from(intensity) / f64::from(epsilon) - constant;
        let exact =
            (-linear + (linear * linear + 4.0 * quadratic * threshold).sqrt()) / (2.0 * quadratic);
        let radius = influence_radius(decay, intensity, epsilon);
        assert!(
            f64::from(radius) >= exact && f64::from(radius.next_down()) < exact,
            "intensity {intensity}: radius {:.17}, the f32 below it {:.17}, exact {exact:.17}",
            f64::from(radius),
            f64::from(radius.next_down())
        );
    }
}

#[test]
fn the_common_opengl_decay_falls_to_one_256th_at_about_88_units() {
    let radius = influence_radius([1.0, 0.09, 0.032], 1.0, 1.0 / 256.0);
    assert!((radius - 88.0).abs() < 0.5, "{radius}");
}

/// `I · min(1, 1 / (c + l·d + q·d²))` (SPEC.md's fall-off, without a range), in `f64`.
fn intensity_at(decay: [f32; 3], intensity: f32, distance: f32) -> f64 {
    let [constant, linear, quadratic] = decay.map(f64::from);
    let d = f64::from(distance);
    f64::from(intensity) * (1.0 / (constant + linear * d + quadratic * d * d)).min(1.0)
}

#[test]
fn past_the_radius_a_light_stays_below_epsilon() {
    let epsilon = 1.0 / 4096.0;
    for (decay, intensity) in [
        ([1.0, 0.09, 0.032], 1.0),
        ([1.0, 0.0, 0.2], 3.0),
        ([1.0, 0.5, 0.0], 0.5),
        ([0.0, 0.0, 1.0], 100.0),
    ] {
        let radius = influence_radius(decay, intensity, epsilon);
        assert!(radius.is_finite() && radius > 0.0);
        for factor in [1.0, 1.0001, 2.0, 100.0] {
            let beyond = intensity_at(decay, intensity, radius * factor);
            assert!(
                beyond <= f64::from(epsilon) * (1.0 + 1e-6),
                "{decay:?} at {factor}× the radius: {beyond}"
            );
        }
        let inside = intensity_at(decay, intensity, radius * 0.999);
        assert!(
            inside > f64::from(epsilon),
            "{decay:?} just inside: {inside}"
        );
    }
}

#[test]
fn lights_without_fall_off_or_epsilon_reach_everywhere() {
    assert_eq!(influence_radius([1.0, 0.0, 0.0], 1.0, 1e-3), f32::INFINITY);
    assert_eq!(influence_radius([1.0, 0.0, 0.2], 1.0, 0.0), f32::INFINITY);
    assert_eq!(
        influence_radius([1.0, 0.0, 0.2], 1.0, f32::NAN),
        f32::INFINITY
    );
}

#[test]
fn lights_dimmer_than_epsilon_reach_nowhere() {
    assert_eq!(influence_radius([1.0, 0.0, 0.2], 1e-4, 1e-3), 0.0);
    assert_eq!(influence_radius([1.0, 0.0, 0.2], 0.0, 1e-3), 0.0);
    assert_eq!(influence_radius([4.0, 0.0, 0.2], 2e-3, 1e-3), 0.0);
}
