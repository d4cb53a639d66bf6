//! Adaptive Gauss–Kronrod quadrature in `f64`: the reference model's integrals over a
//! light's area (`area`), independent of any closed form.
//!
//! Each interval is integrated with the 7-point Gauss and 15-point Kronrod rules; where the
//! two differ by more than the interval's share of the tolerance, it is halved and each half
//! integrated again. An integrand with a kink (a light's edge crossing the horizon) is
//! resolved by halving around the kink; one with a narrow peak (a high exponent's highlight)
//! by halving around the peak.

use bevy::math::DVec3;

/// The 15-point Kronrod nodes in `[0, 1]` (their negatives are the others) and weights; the
/// odd-indexed nodes are the 7-point Gauss rule's, [`GAUSS_WEIGHTS`].
const KRONROD_NODES: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
const KRONROD_WEIGHTS: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_8,
];
/// The 7-point Gauss weights of the nodes `KRONROD_NODES[1]`, `[3]`, `[5]` and `[7]` (0).
const GAUSS_WEIGHTS: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// Halvings at most from the whole interval down: an interval narrower than 2⁻⁴⁰ of it is
/// accepted as it is (a discontinuity is then resolved to that width).
const MAX_DEPTH: u32 = 40;

/// Where the rules' difference is down to rounding: relative to the interval's integral, a
/// few hundred times `f64`'s epsilon. An interval whose rules agree to that is accepted
/// whatever its share of the tolerance: halving it again would only halve the rounding's
/// noise, never reach a tolerance below it (a peak whose values are `1/h²` against an
/// absolute tolerance of `1e-10` would otherwise be halved to [`MAX_DEPTH`] everywhere).
/// The integrands here do not change sign, so the interval's integral bounds the rounding
/// of its terms; the error this leaves is at most `ROUNDING` of the whole integral.
const ROUNDING: f64 = 1e-13;

/// What the quadrature integrates: a number, or a color (each channel to the tolerance).
pub trait Value: Copy + std::ops::Add<Output = Self> + std::ops::Mul<f64, Output = Self> {
    const ZERO: Self;
    /// The largest absolute channel of `self − other`.
    fn distance(self, other: Self) -> f64;
}

impl Value for f64 {
    const ZERO: Self = 0.0;
    fn distance(self, other: Self) -> f64 {
        (self - other).abs()
    }
}

impl Value for DVec3 {
    const ZERO: Self = DVec3::ZERO;
    fn distance(self, other: Self) -> f64 {
        (self - other).abs().max_element()
    }
}

/// `∫_a^b f(x) dx` to within `tolerance` (absolute, in each channel), by adaptive
/// Gauss–Kronrod.
pub fn integrate<V: Value>(f: &mut dyn FnMut(f64) -> V, a: f64, b: f64, tolerance: f64) -> V {
    if a == b {
        return V::ZERO;
    }
    adaptive(f, a, b, tolerance, 0)
}

/// `∫_a^b ∫_c(x)^d(x) f(x, y) dy dx` to within about `tolerance`: the inner integral to a
/// tenth of it at each `x`, the outer to the rest.
pub fn integrate_2d<V: Value>(
    f: &mut dyn FnMut(f64, f64) -> V,
    (a, b): (f64, f64),
    inner: &dyn Fn(f64) -> (f64, f64),
    tolerance: f64,
) -> V {
    let inner_tolerance = 0.1 * tolerance / (b - a).abs().max(f64::MIN_POSITIVE);
    integrate(
        &mut |x| {
            let (c, d) = inner(x);
            integrate(&mut |y| f(x, y), c, d, inner_tolerance)
        },
        a,
        b,
        0.9 * tolerance,
    )
}

fn adaptive<V: Value>(
    f: &mut dyn FnMut(f64) -> V,
    a: f64,
    b: f64,
    tolerance: f64,
    depth: u32,
) -> V {
    let (kronrod, gauss) = rules(f, a, b);
    let difference = kronrod.distance(gauss);
    let rounding = ROUNDING * kronrod.distance(V::ZERO);
    if difference <= tolerance || difference <= rounding || depth == MAX_DEPTH {
        return kronrod;
    }
    let middle = 0.5 * (a + b);
    adaptive(f, a, middle, 0.5 * tolerance, depth + 1)
        + adaptive(f, middle, b, 0.5 * tolerance, depth + 1)
}

/// The Kronrod and Gauss estimates of `∫_a^b f`.
fn rules<V: Value>(f: &mut dyn FnMut(f64) -> V, a: f64, b: f64) -> (V, V) {
    let center = 0.5 * (a + b);
    let half = 0.5 * (b - a);
    let mut kronrod = V::ZERO;
    let mut gauss = V::ZERO;
    for (index, (&node, &weight)) in KRONROD_NODES.iter().zip(&KRONROD_WEIGHTS).enumerate() {
        let sum = if node == 0.0 {
            f(center)
        } else {
            f(center - half * node) + f(center + half * node)
        };
        kronrod = kronrod + sum * weight;
        if index % 2 == 1 {
            gauss = gauss + sum * GAUSS_WEIGHTS[index / 2];
        }
    }
    (kronrod * half, gauss * half)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Worked integrals: a polynomial the rules hold exactly, a narrow peak, a kink and a
    /// jump, each to 1e-12 of its closed form.
    #[test]
    fn integrals_of_known_functions_match_their_closed_forms() {
        /// A name, the integrand, the bounds and the integral.
        type Case = (&'static str, fn(f64) -> f64, f64, f64, f64);
        let cases: [Case; 4] = [
            ("x⁵", |x| x.powi(5), 0.0, 2.0, 64.0 / 6.0),
            // ∫ cos^200 over [−π/2, π/2] = π · C(200, 100) / 2^200.
            (
                "cos²⁰⁰",
                |x| x.cos().powi(200),
                -std::f64::consts::FRAC_PI_2,
                std::f64::consts::FRAC_PI_2,
                0.177_023_967_696_438_63,
            ),
            ("|x − 0.3|", |x| (x - 0.3).abs(), 0.0, 1.0, 0.045 + 0.245),
            (
                "step at 1/3",
                |x| f64::from(x > 1.0 / 3.0),
                0.0,
                1.0,
                2.0 / 3.0,
            ),
        ];
        for (name, f, a, b, exact) in cases {
            let value: f64 = integrate(&mut { f }, a, b, 1e-13);
            assert!((value - exact).abs() < 1e-12, "{name}: {value} for {exact}");
        }
    }

    /// The area of the unit disk, `∫_{-1}^{1} ∫_{-√(1−x²)}^{√(1−x²)} 1 dy dx = π`, whose
    /// inner bounds have unbounded slope at ±1.
    #[test]
    fn a_double_integral_over_a_disk_gives_its_area() {
        let area: f64 = integrate_2d(
            &mut |_, _| 1.0,
            (-1.0, 1.0),
            &|x: f64| {
                let h = (1.0 - x * x).max(0.0).sqrt();
                (-h, h)
            },
            1e-11,
        );
        assert!((area - std::f64::consts::PI).abs() < 1e-10, "{area}");
    }
}
