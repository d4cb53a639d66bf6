//! The polygon the shader draws a disk light as, seen from a surface point
//! (`area_integrals.wesl`'s `disk_polygon`), in `f64`: test-only, measured against the
//! quadrature over the disk itself in `area_tests`.
//!
//! A regular polygon errs where the surface point is close to the disk's rim: its edges cut
//! inside the circle by the sagitta `r (1 − cos(π/n))` and its corners stand outside it,
//! each a fixed distance, which seen from a point that near is a large angle (a 16-gon gives
//! 0.78 for the disk's 1.25 five millimetres from a half-metre disk's rim). The polygon is
//! drawn per surface point instead, its corners on the rim graded by their distance from
//! the rim point nearest the surface point: at the angle `t* + s(u)` around the disk, for
//! `u = (2j + 1)/n − 1`, with `s(u) = π · sinh(βu) / sinh β` and `β = asinh(g / δ)`
//! (`δ` the distance to the rim in radii, `g` the grading, [`DISK_GRADING`]). The step
//! `ds/du = β √(s² + s₀²)` (`s₀ = π / sinh β ≈ π δ / g`) grows in proportion to the angle
//! from the nearest rim point, and near it is proportional to `δ`: each edge subtends about
//! the same angle seen from the point, however near the rim it is. Far from the disk
//! (`δ ≫ g`) `β → 0` and the polygon is regular. Each corner stands at `r √(g(θ₋) g(θ₊))`,
//! `g(θ) = √(θ / sin θ)` of its two edges' angles, the circumradius that gives each edge's
//! triangle its sector's area (for a regular polygon, the polygon of the disk's area).

use std::f64::consts::PI;

/// The sides of the polygon a disk is drawn as (`area_integrals.wesl`'s `DISK_SIDES`).
pub const DISK_SIDES: usize = 32;

/// The grading `g` of the disk's polygon (`area_integrals.wesl`'s `DISK_GRADING`): how many
/// radii from the rim the polygon starts to crowd its corners toward the nearest rim point.
pub const DISK_GRADING: f64 = 1.0;

/// The least distance to the rim, in radii, the grading follows (`DISK_NEAREST_RIM`): closer
/// points are graded as at this distance.
pub const DISK_NEAREST_RIM: f64 = 1e-6;

/// The polygon's corners for a disk of radius `radius` with a surface point at `(x, y, z)`
/// in the disk's frame (its center the origin, its plane `z = 0`), as `(x, y)` in that
/// plane, winding from +X toward +Y: `sides` corners graded toward the rim point nearest the
/// surface point (see the module docs).
pub fn disk_polygon(radius: f64, (x, y, z): (f64, f64, f64), sides: usize) -> Vec<(f64, f64)> {
    let from_axis = x.hypot(y);
    let nearest = y.atan2(x);
    let to_rim = (from_axis - radius).hypot(z) / radius;
    let beta = (DISK_GRADING / to_rim.max(DISK_NEAREST_RIM)).asinh();
    let angle = |j: isize| -> f64 {
        let u = (2 * j + 1) as f64 / sides as f64 - 1.0;
        if beta < 1e-4 {
            PI * u
        } else {
            PI * (beta * u).sinh() / beta.sinh()
        }
    };
    let scale = |theta: f64| (theta / theta.sin()).sqrt();
    (0..sides as isize)
        .map(|j| {
            // Corner j − n is corner j a turn back, and j + n a turn on.
            let (before, here, after) = (
                wrapped(j - 1, sides, &angle),
                angle(j),
                wrapped(j + 1, sides, &angle),
            );
            let corner = radius * (scale(here - before) * scale(after - here)).sqrt();
            let (sin, cos) = (nearest + here).sin_cos();
            (corner * cos, corner * sin)
        })
        .collect()
}

/// The angle of corner `j` (one past either end, wrapped a turn).
fn wrapped(j: isize, sides: usize, angle: &impl Fn(isize) -> f64) -> f64 {
    let sides = sides as isize;
    if j < 0 {
        angle(j + sides) - 2.0 * PI
    } else if j >= sides {
        angle(j - sides) + 2.0 * PI
    } else {
        angle(j)
    }
}
