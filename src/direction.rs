//! Unit vectors from vectors of any scale. A vector is divided by its largest component
//! before it is normalized, so that neither `(3e38, 3e38, 3e38)` (whose squared length
//! overflows `f32`) nor `(1e-30, -1e-30, 0)` (whose squared length underflows to zero) loses
//! its direction on the way. The shader's `normalize_or_zero` and the reference model's
//! follow the same rule (SPEC.md, "Numerical rules").

#[cfg(any(feature = "scene", feature = "reference", test))]
use bevy::math::DVec3;
use bevy::math::Vec3;

/// A vector whose largest component (in absolute value) is below this has no direction:
/// `f32`'s smallest normal number, about 1.2e-38. GPUs may flush smaller (subnormal) numbers
/// to zero, so below it the shader could not tell the vector from zero.
pub(crate) const MIN_COMPONENT: f32 = f32::MIN_POSITIVE;

/// `v / |v|`, computed as `u / |u|` with `u = v / max(|v.x|, |v.y|, |v.z|)`; zero where `v`
/// is not finite or its largest component is below [`MIN_COMPONENT`].
pub(crate) fn normalize_or_zero(v: Vec3) -> Vec3 {
    let largest = v.abs().max_element();
    if !v.is_finite() || largest < MIN_COMPONENT {
        return Vec3::ZERO;
    }
    let scaled = v / largest;
    scaled / scaled.length()
}

/// [`normalize_or_zero`] in `f64`, with the same threshold (for scene files' cameras and the
/// reference model).
#[cfg(any(feature = "scene", feature = "reference", test))]
pub(crate) fn normalize_or_zero_f64(v: DVec3) -> DVec3 {
    let largest = v.abs().max_element();
    if !v.is_finite() || largest < f64::from(MIN_COMPONENT) {
        return DVec3::ZERO;
    }
    let scaled = v / largest;
    scaled / scaled.length()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unit vectors from normalizing agree to a few `f32` ulps (division by the largest
    /// component and the square root each round once).
    const TOLERANCE: f32 = 4.0 * f32::EPSILON;

    fn assert_close(actual: Vec3, expected: Vec3) {
        assert!(
            (actual - expected).abs().max_element() <= TOLERANCE,
            "{actual} vs {expected}"
        );
    }

    #[test]
    fn huge_and_tiny_vectors_keep_their_direction() {
        let diagonal = Vec3::ONE / 3f32.sqrt();
        assert_close(normalize_or_zero(Vec3::splat(3e38)), diagonal);
        assert_close(normalize_or_zero(Vec3::splat(-f32::MAX)), -diagonal);
        let tiny = normalize_or_zero(Vec3::new(1e-30, -1e-30, 0.0));
        assert_close(tiny, Vec3::new(1.0, -1.0, 0.0) / 2f32.sqrt());
        assert_close(normalize_or_zero(Vec3::new(0.0, 2e-38, 0.0)), Vec3::Y);
    }

    #[test]
    fn zero_subnormal_and_non_finite_vectors_have_no_direction() {
        for v in [
            Vec3::ZERO,
            Vec3::splat(1e-40),
            Vec3::new(f32::NAN, 1.0, 0.0),
            Vec3::new(f32::INFINITY, 1.0, 0.0),
        ] {
            assert_eq!(normalize_or_zero(v), Vec3::ZERO, "{v}");
            assert_eq!(normalize_or_zero_f64(v.as_dvec3()), DVec3::ZERO, "{v}");
        }
    }

    #[test]
    fn f32_and_f64_agree() {
        for v in [
            Vec3::splat(3e38),
            Vec3::new(1e-30, -1e-30, 0.0),
            Vec3::new(3.0, 4.0, 0.0),
        ] {
            let single = normalize_or_zero(v);
            let double = normalize_or_zero_f64(v.as_dvec3()).as_vec3();
            assert_close(single, double);
        }
    }
}
