//! How far a point or spot light reaches before its light fades below a bound: the
//! *influence radius* that culling cuts each light at (see [`crate::PhongLightCulling`]).

/// The distance (world units) past which a light of largest channel `intensity` with
/// distance fall-off `1 / (constant + linear·d + quadratic·d²)` stays below `epsilon`:
/// `f32::INFINITY` when it never does (no fall-off, or `epsilon ≤ 0`), `0` when it never
/// reaches `epsilon` at all. Computed in `f64`, rounded up. For example
/// `1 / (1 + 0.09·d + 0.032·d²)` falls to 1/256 at about 88 units.
pub fn influence_radius(decay: [f32; 3], intensity: f32, epsilon: f32) -> f32 {
    if epsilon.is_nan() || epsilon <= 0.0 {
        return f32::INFINITY;
    }
    if intensity.is_nan() || intensity < epsilon {
        // A ≤ 1, so the light is below ε everywhere (also for a NaN intensity).
        return 0.0;
    }
    let [constant, linear, quadratic] = decay.map(f64::from);
    // I · A(d) < ε  ⇔  constant + linear·d + quadratic·d² > I / ε  (A's min(1, …) aside,
    // which only matters where I / ε ≤ 1, handled above).
    let threshold = f64::from(intensity) / f64::from(epsilon) - constant;
    let radius = if threshold <= 0.0 {
        0.0
    } else if quadratic > 0.0 {
        // The positive root of quadratic·d² + linear·d - threshold, in the form without
        // cancellation.
        2.0 * threshold / (linear + (linear * linear + 4.0 * quadratic * threshold).sqrt())
    } else if linear > 0.0 {
        threshold / linear
    } else {
        f64::INFINITY
    };
    let rounded = radius as f32;
    if f64::from(rounded) < radius {
        rounded.next_up()
    } else {
        rounded
    }
}
