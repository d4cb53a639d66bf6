//! A rectangle light cut into convex pieces over which the integrand of its term is smooth,
//! and the quadrature over such a piece; a disk integrated along rays split where they cross
//! the same lines; for [`super::area`].
//!
//! The integrand is not smooth everywhere on the light: the diffuse term has a kink where
//! the light crosses the surface's horizon (`N·ω = 0`, a jump for a highlight gated by it),
//! and the Phong lobe one where it crosses the mirror direction's plane (`R_V·ω = 0`). Each of
//! those is a plane through the surface point, which meets the light's plane in a line: the
//! rectangle is cut along both lines, and each convex piece is integrated on its own, where
//! the adaptive rule converges at its full order instead of halving intervals down to the
//! kink. A disk is integrated in polar coordinates, each ray's radial integral split where
//! it crosses a line and the angles split where a line meets the circle. Nothing of the
//! integrals' closed forms enters.

use super::quadrature::{Value, integrate, integrate_2d};
use std::f64::consts::TAU;

/// A point of the light's plane, in its own coordinates (along its local X and Y).
pub(super) type PlanePoint = (f64, f64);

/// The line `a·x + b·y + c = 0` of the light's plane, as `(a, b, c)`.
pub(super) type Line = (f64, f64, f64);

/// The convex `polygon` cut along each of `lines`: the pieces on either side of every line,
/// those without area left out.
pub(super) fn cut(polygon: Vec<PlanePoint>, lines: &[Line]) -> Vec<Vec<PlanePoint>> {
    let mut pieces = vec![polygon];
    for &line in lines {
        pieces = pieces
            .iter()
            .flat_map(|piece| [side(piece, line, 1.0), side(piece, line, -1.0)])
            .filter(|piece| piece.len() >= 3)
            .collect();
    }
    pieces
}

/// The part of the convex `polygon` where `sign · (a·x + b·y + c) ≥ 0` (Sutherland–Hodgman).
fn side(polygon: &[PlanePoint], (a, b, c): Line, sign: f64) -> Vec<PlanePoint> {
    let value = |(x, y): PlanePoint| sign * (a * x + b * y + c);
    let mut kept = Vec::with_capacity(polygon.len() + 1);
    for (index, &current) in polygon.iter().enumerate() {
        let next = polygon[(index + 1) % polygon.len()];
        let (here, there) = (value(current), value(next));
        if here >= 0.0 {
            kept.push(current);
        }
        if (here >= 0.0) != (there >= 0.0) {
            let t = here / (here - there);
            kept.push((
                current.0 + t * (next.0 - current.0),
                current.1 + t * (next.1 - current.1),
            ));
        }
    }
    kept
}

/// `∫ f dA` over the convex `polygon` to within `tolerance`: the triangles of its fan, each
/// mapped from the unit square (`(s, t)` ↦ `a + s·((1 − t)·b + t·c − a)`, Jacobian
/// `s · 2·area`).
pub(super) fn integrate_polygon<V: Value>(
    f: &mut dyn FnMut(f64, f64) -> V,
    polygon: &[PlanePoint],
    tolerance: f64,
) -> V {
    let triangles = polygon.len().saturating_sub(2);
    let mut sum = V::ZERO;
    for index in 1..polygon.len().saturating_sub(1) {
        let (a, b, c) = (polygon[0], polygon[index], polygon[index + 1]);
        let twice_area = ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)).abs();
        if twice_area == 0.0 {
            continue;
        }
        sum = sum
            + integrate_2d(
                &mut |s, t| {
                    let edge = (b.0 + t * (c.0 - b.0), b.1 + t * (c.1 - b.1));
                    let point = (a.0 + s * (edge.0 - a.0), a.1 + s * (edge.1 - a.1));
                    f(point.0, point.1) * (s * twice_area)
                },
                (0.0, 1.0),
                &|_| (0.0, 1.0),
                tolerance / triangles as f64,
            );
    }
    sum
}

/// `∫ f dA` over the disk of `radius` around the plane's origin, whose integrand has kinks
/// along `lines`, to within about `tolerance`: over the angle, split where a line meets the
/// circle, the radial integral (times `r`) split where the ray crosses a line.
pub(super) fn integrate_disk<V: Value>(
    f: &mut dyn FnMut(f64, f64) -> V,
    radius: f64,
    lines: &[Line],
    tolerance: f64,
) -> V {
    // The angles where a line meets the circle: `R·ρ·cos(θ − φ) = −c`.
    let mut angles = vec![0.0, TAU];
    for &(a, b, c) in lines {
        let length = a.hypot(b);
        if length > 0.0 && c.abs() < radius * length {
            let (toward, spread) = (b.atan2(a), (-c / (radius * length)).acos());
            angles.extend(
                [toward - spread, toward + spread]
                    .into_iter()
                    .map(|angle| angle.rem_euclid(TAU)),
            );
        }
    }
    angles.sort_by(f64::total_cmp);
    angles.dedup();
    let inner_tolerance = 0.1 * tolerance / TAU;
    let mut ray = |angle: f64| -> V {
        let (sin, cos) = angle.sin_cos();
        // Where the ray crosses each line: `r (a cos θ + b sin θ) + c = 0`.
        let mut stops = vec![0.0, radius];
        stops.extend(lines.iter().filter_map(|&(a, b, c)| {
            let r = -c / (a * cos + b * sin);
            (r > 0.0 && r < radius).then_some(r)
        }));
        stops.sort_by(f64::total_cmp);
        stops.windows(2).fold(V::ZERO, |sum, span| {
            sum + integrate(
                &mut |r| f(r * cos, r * sin) * r,
                span[0],
                span[1],
                inner_tolerance / (stops.len() - 1) as f64,
            )
        })
    };
    angles.windows(2).fold(V::ZERO, |sum, span| {
        sum + integrate(
            &mut ray,
            span[0],
            span[1],
            0.9 * tolerance / (angles.len() - 1) as f64,
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_cut_along_two_lines_keeps_its_area_and_integrates_a_kinked_function() {
        let square = vec![(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        // x = 0.3 and y = x: up to four pieces.
        let pieces = cut(square, &[(1.0, 0.0, -0.3), (1.0, -1.0, 0.0)]);
        assert_eq!(pieces.len(), 4);
        let area: f64 = pieces
            .iter()
            .map(|piece| integrate_polygon(&mut |_, _| 1.0, piece, 1e-12))
            .sum();
        assert!((area - 4.0).abs() < 1e-12, "{area}");
        // ∫ max(x − 0.3, 0) over the square: 2 · 0.7² / 2.
        let kinked: f64 = pieces
            .iter()
            .map(|piece| integrate_polygon(&mut |x, _| (x - 0.3).max(0.0), piece, 1e-12))
            .sum();
        assert!((kinked - 0.49).abs() < 1e-12, "{kinked}");
    }

    #[test]
    fn a_disk_cut_along_a_line_integrates_a_kinked_function() {
        let line = (1.0, 0.0, -0.3);
        let area = integrate_disk(&mut |_, _| 1.0, 1.0, &[line], 1e-12);
        assert!((area - std::f64::consts::PI).abs() < 1e-11, "{area}");
        // ∫ max(x − 0.3, 0) over the unit disk: ∫_0.3^1 2√(1 − x²)(x − 0.3) dx
        // = (2/3)(1 − 0.09)^{3/2} − 0.3·(acos 0.3 − 0.3·√0.91).
        let chord = (1.0_f64 - 0.09).sqrt();
        let expected = 2.0 / 3.0 * chord.powi(3) - 0.3 * (0.3_f64.acos() - 0.3 * chord);
        let kinked = integrate_disk(&mut |x, _| (x - 0.3).max(0.0), 1.0, &[line], 1e-12);
        assert!((kinked - expected).abs() < 1e-11, "{kinked} for {expected}");
    }
}
