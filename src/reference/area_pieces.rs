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

/// `∫ f dA` over the convex `polygon` (counter-clockwise) to within `tolerance`: the
/// triangles of its fan from its point nearest `near`, each mapped from the unit square
/// (`(s, t)` ↦ `a + s·((1 − t)·b + t·c − a)`, Jacobian `s · 2·area`).
///
/// `near` is where the integrand peaks: the surface point's foot on the light's plane, where
/// `1 / r²` peaks when the point is close to the light. At the fan's apex the peak falls
/// along one coordinate of every triangle, which the adaptive rule resolves in a few halvings
/// of that coordinate, not of both.
pub(super) fn integrate_polygon<V: Value>(
    f: &mut dyn FnMut(f64, f64) -> V,
    polygon: &[PlanePoint],
    near: PlanePoint,
    tolerance: f64,
) -> V {
    let a = nearest_on_polygon(polygon, near);
    let mut triangles = Vec::with_capacity(polygon.len());
    for (index, &b) in polygon.iter().enumerate() {
        let c = polygon[(index + 1) % polygon.len()];
        let twice_area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
        // The apex on an edge or a vertex: that edge's triangle has no area.
        if twice_area > 0.0 {
            triangles.push((b, c, twice_area));
        }
    }
    let share = tolerance / triangles.len().max(1) as f64;
    triangles
        .into_iter()
        .fold(V::ZERO, |sum, (b, c, twice_area)| {
            sum + integrate_2d(
                &mut |s, t| {
                    let edge = (b.0 + t * (c.0 - b.0), b.1 + t * (c.1 - b.1));
                    let point = (a.0 + s * (edge.0 - a.0), a.1 + s * (edge.1 - a.1));
                    f(point.0, point.1) * (s * twice_area)
                },
                (0.0, 1.0),
                &|_| (0.0, 1.0),
                share,
            )
        })
}

/// The point of the convex `polygon` (counter-clockwise) nearest `point`: `point` itself
/// where it is inside, else the nearest point of an edge.
fn nearest_on_polygon(polygon: &[PlanePoint], point: PlanePoint) -> PlanePoint {
    let edges = || {
        polygon
            .iter()
            .enumerate()
            .map(|(index, &b)| (b, polygon[(index + 1) % polygon.len()]))
    };
    let left_of = |(b, c): (PlanePoint, PlanePoint)| {
        (c.0 - b.0) * (point.1 - b.1) - (c.1 - b.1) * (point.0 - b.0) >= 0.0
    };
    if edges().all(left_of) {
        return point;
    }
    let on_edge = |(b, c): (PlanePoint, PlanePoint)| {
        let (dx, dy) = (c.0 - b.0, c.1 - b.1);
        let length_squared = dx * dx + dy * dy;
        let t = if length_squared > 0.0 {
            (((point.0 - b.0) * dx + (point.1 - b.1) * dy) / length_squared).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (b.0 + t * dx, b.1 + t * dy)
    };
    let distance_squared = |q: PlanePoint| (q.0 - point.0).powi(2) + (q.1 - point.1).powi(2);
    edges()
        .map(on_edge)
        .min_by(|&p, &q| distance_squared(p).total_cmp(&distance_squared(q)))
        .unwrap_or(point)
}

/// `∫ f dA` over the disk of `radius` around the plane's origin, whose integrand has kinks
/// along `lines`, to within about `tolerance`: in polar coordinates around the disk's point
/// nearest `near` (the apex, where the integrand peaks, as for [`integrate_polygon`]), over
/// the angle, the radial integral (times `r`) from the apex to the circle, split where the
/// ray crosses a line. The angles are split where the rays' structure changes: toward each
/// point where a line meets the circle, along each such line, and, for an apex on the rim,
/// along the rim's tangent.
pub(super) fn integrate_disk<V: Value>(
    f: &mut dyn FnMut(f64, f64) -> V,
    radius: f64,
    near: PlanePoint,
    lines: &[Line],
    tolerance: f64,
) -> V {
    let distance = near.0.hypot(near.1);
    let apex = if distance > radius {
        (near.0 * radius / distance, near.1 * radius / distance)
    } else {
        near
    };
    // What the square root of a ray's reach takes: `R² − |apex|²`, 0 on the rim.
    let inside = (radius * radius - apex.0 * apex.0 - apex.1 * apex.1).max(0.0);
    let direction = |x: f64, y: f64| y.atan2(x).rem_euclid(TAU);
    let mut angles = vec![0.0, TAU];
    for &(a, b, c) in lines {
        let length = a.hypot(b);
        if length > 0.0 && c.abs() < radius * length {
            // The line `n·p = d` (n unit) meets the circle at `d·n ± h·t`.
            let (nx, ny, d) = (a / length, b / length, -c / length);
            let h = (radius * radius - d * d).sqrt();
            for sign in [-1.0, 1.0] {
                let (x, y) = (d * nx - sign * h * ny, d * ny + sign * h * nx);
                angles.push(direction(x - apex.0, y - apex.1));
                angles.push(direction(sign * -ny, sign * nx));
            }
        }
    }
    if inside == 0.0 {
        angles.extend([direction(-apex.1, apex.0), direction(apex.1, -apex.0)]);
    }
    angles.sort_by(f64::total_cmp);
    angles.dedup();
    let inner_tolerance = 0.1 * tolerance / TAU;
    let mut ray = |angle: f64| -> V {
        let (sin, cos) = angle.sin_cos();
        // Where the ray leaves the circle: `|apex + r·u| = R`.
        let along = apex.0 * cos + apex.1 * sin;
        let reach = -along + (along * along + inside).sqrt();
        if reach <= 0.0 {
            return V::ZERO;
        }
        // Where the ray crosses each line: `a (x₀ + r cos θ) + b (y₀ + r sin θ) + c = 0`.
        let mut stops = vec![0.0, reach];
        stops.extend(lines.iter().filter_map(|&(a, b, c)| {
            let r = -(a * apex.0 + b * apex.1 + c) / (a * cos + b * sin);
            (r > 0.0 && r < reach).then_some(r)
        }));
        stops.sort_by(f64::total_cmp);
        stops.windows(2).fold(V::ZERO, |sum, span| {
            sum + integrate(
                &mut |r| f(apex.0 + r * cos, apex.1 + r * sin) * r,
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

    /// Points of the plane the quadratures are centered on: inside, on an edge or the rim,
    /// at a corner, and outside.
    const NEAR: [PlanePoint; 5] = [(0.0, 0.0), (0.2, -0.6), (1.0, 0.0), (1.0, 1.0), (2.5, -3.0)];

    #[test]
    fn a_square_cut_along_two_lines_keeps_its_area_and_integrates_a_kinked_function() {
        let square = vec![(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        // x = 0.3 and y = x: up to four pieces.
        let pieces = cut(square, &[(1.0, 0.0, -0.3), (1.0, -1.0, 0.0)]);
        assert_eq!(pieces.len(), 4);
        for near in NEAR {
            let area: f64 = pieces
                .iter()
                .map(|piece| integrate_polygon(&mut |_, _| 1.0, piece, near, 1e-12))
                .sum();
            assert!((area - 4.0).abs() < 1e-12, "{area} around {near:?}");
            // ∫ max(x − 0.3, 0) over the square: 2 · 0.7² / 2.
            let kinked: f64 = pieces
                .iter()
                .map(|piece| integrate_polygon(&mut |x, _| (x - 0.3).max(0.0), piece, near, 1e-12))
                .sum();
            assert!((kinked - 0.49).abs() < 1e-12, "{kinked} around {near:?}");
        }
    }

    #[test]
    fn a_disk_cut_along_a_line_integrates_a_kinked_function() {
        let line = (1.0, 0.0, -0.3);
        // ∫ max(x − 0.3, 0) over the unit disk: ∫_0.3^1 2√(1 − x²)(x − 0.3) dx
        // = (2/3)(1 − 0.09)^{3/2} − 0.3·(acos 0.3 − 0.3·√0.91).
        let chord = (1.0_f64 - 0.09).sqrt();
        let expected = 2.0 / 3.0 * chord.powi(3) - 0.3 * (0.3_f64.acos() - 0.3 * chord);
        for near in NEAR {
            let area = integrate_disk(&mut |_, _| 1.0, 1.0, near, &[line], 1e-12);
            assert!(
                (area - std::f64::consts::PI).abs() < 1e-11,
                "{area} around {near:?}"
            );
            let kinked = integrate_disk(&mut |x, _| (x - 0.3).max(0.0), 1.0, near, &[line], 1e-12);
            assert!(
                (kinked - expected).abs() < 1e-11,
                "{kinked} for {expected} around {near:?}"
            );
        }
    }

    /// The solid angle the element `dA` at `(x, y)` fills, seen from `height` above `foot`.
    fn solid_angle_element(foot: PlanePoint, height: f64) -> impl Fn(f64, f64) -> f64 {
        move |x, y| {
            let r2 = (x - foot.0).powi(2) + (y - foot.1).powi(2) + height * height;
            height / (r2 * r2.sqrt())
        }
    }

    /// A surface point a hair (`h` = 1e-4) above a light, as where a light's rim crosses a
    /// floor: the integrand `h / r³` peaks within `h` of the foot. With the fan's apex or the
    /// polar center at the foot, the quadrature resolves the peak along one coordinate
    /// (measured at 1e-9: 470,000 evaluations for the square, 537,000 for the disk). Centered
    /// elsewhere it halves both coordinates down to the peak: 210 million for the square
    /// fanned from its corner, 1.2 million for the disk around its center.
    #[test]
    fn a_peak_at_the_foot_is_integrated_along_one_coordinate() {
        let height = 1e-4;
        // A rectangle seen from above one of its corners fills `atan(a·b / (h·√(a² + b² +
        // h²)))`; the square is four of them around the foot.
        let corner =
            |a: f64, b: f64| (a * b / (height * (a * a + b * b + height * height).sqrt())).atan();
        let foot = (0.9, 0.3);
        let expected = corner(0.1, 0.7) + corner(0.1, 1.3) + corner(1.9, 0.7) + corner(1.9, 1.3);
        let square = vec![(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        let element = solid_angle_element(foot, height);
        let mut evaluations = 0_u64;
        let angle = integrate_polygon(
            &mut |x, y| {
                evaluations += 1;
                element(x, y)
            },
            &square,
            foot,
            1e-9,
        );
        assert!((angle - expected).abs() < 1e-9, "{angle} for {expected}");
        assert!(evaluations < 1_000_000, "{evaluations} evaluations");

        // The disk seen from above its rim, against the same integral around its center.
        let rim = (0.6, 0.8);
        let element = solid_angle_element(rim, height);
        let mut evaluations = 0_u64;
        let angle = integrate_disk(
            &mut |x, y| {
                evaluations += 1;
                element(x, y)
            },
            1.0,
            rim,
            &[],
            1e-9,
        );
        assert!(evaluations < 1_000_000, "{evaluations} evaluations");
        let from_center = integrate_disk(&mut |x, y| element(x, y), 1.0, (0.0, 0.0), &[], 1e-9);
        assert!(
            (angle - from_center).abs() < 1e-9,
            "{angle} against {from_center}"
        );
    }
}
