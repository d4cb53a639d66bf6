//! A rectangle light cut into convex pieces over which the integrand of its term is smooth,
//! and the quadrature over such a piece, for [`super::area`].
//!
//! The integrand is not smooth everywhere on the light: the diffuse term has a kink where
//! the light crosses the surface's horizon (`N·ω = 0`, a jump for a highlight gated by it),
//! and the Phong lobe one where it crosses the mirror direction's plane (`R_V·ω = 0`). Each of
//! those is a plane through the surface point, which meets the light's plane in a line: the
//! rectangle is cut along both lines, and each convex piece is integrated on its own, where
//! the adaptive rule converges at its full order instead of halving intervals down to the
//! kink. Nothing of the integrals' closed forms enters.

use super::quadrature::{Value, integrate_2d};

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
}
