//! The polygons the shader draws a disk light as, seen from a surface point
//! (`shaders/disk_polygon.wesl`), in `f64`: test-only, measured against the quadrature over
//! the disk itself in `area_disk_tests` and `area_tests`.
//!
//! A regular polygon errs where the surface point is close to the disk's rim: its edges cut
//! inside the circle by the sagitta `r (1 − cos(π/n))` and its corners stand outside it,
//! each a fixed distance, which seen from a point that near is a large angle (a 16-gon gives
//! 0.78 for the disk's 1.25 five millimetres from a half-metre disk's rim). The polygon is
//! drawn per surface point instead, its corners on the rim graded by their distance from
//! the rim point nearest the surface point: at the angle `t* + s(u)` around the disk, for
//! `u = (2j + 1)/n − 1`, with `s(u) = π · sinh(βu) / sinh β` and `β = asinh(k / δ)`
//! (`δ` the distance to the rim in radii, `k` the grading, [`DISK_GRADING`]). The step
//! `ds/du = β √(s² + s₀²)` (`s₀ = π / sinh β ≈ π δ / k`) grows in proportion to the angle
//! from the nearest rim point, and near it is proportional to `δ`: each edge subtends about
//! the same angle seen from the point, however near the rim it is. Far from the disk
//! (`δ ≫ k`) `β → 0` and the polygon is regular. The diffuse light is integrated over a
//! polygon of [`DISK_SIDES`] corners crowded toward the rim point nearest the surface point;
//! the highlight over one of [`DISK_HIGHLIGHT_SIDES`] crowded toward where its lobe meets
//! the rim, where that is nearer ([`Grading::lobe`]). Each corner stands at `r √(g(θ₋) g(θ₊))`,
//! `g(θ) = √(θ / sin θ)` of its two edges' angles, the circumradius that gives each edge's
//! triangle its sector's area (for a regular polygon, the polygon of the disk's area).

use std::f64::consts::PI;

/// The corners of the polygon the diffuse light is integrated over (`disk_polygon.wesl`'s
/// `DISK_SIDES`).
pub const DISK_SIDES: usize = 32;

/// The corners of the polygon the highlight is integrated over (`DISK_HIGHLIGHT_SIDES`).
pub const DISK_HIGHLIGHT_SIDES: usize = 16;

/// The grading `k` of the disk's polygons (`DISK_GRADING`): how many radii from the rim
/// they start to crowd their corners.
pub const DISK_GRADING: f64 = 1.0;

/// The least distance to the rim, in radii, the grading follows (`DISK_NEAREST_RIM`): closer
/// points are graded as at this distance.
pub const DISK_NEAREST_RIM: f64 = 1e-6;

/// Where a polygon crowds its corners: toward the rim point at the angle `toward` (radians
/// from the disk's X toward its Y), `to_rim` radii from it.
#[derive(Clone, Copy, Debug)]
pub struct Grading {
    /// Radians around the disk from its X toward its Y.
    pub toward: f64,
    /// Radii; `β = asinh(k / to_rim)`.
    pub to_rim: f64,
}

impl Grading {
    /// Toward the rim point nearest `(x, y, z)` in the disk's frame (its center the origin,
    /// its plane `z = 0`), in radii.
    pub fn nearest(x: f64, y: f64, z: f64) -> Self {
        Self {
            toward: y.atan2(x),
            to_rim: (x.hypot(y) - 1.0).hypot(z),
        }
    }

    /// For the highlight's lobe around `mirror` of `exponent` from the surface point `(x, y,
    /// z)` (both in the disk's frame, in radii): toward the rim point nearest where the
    /// mirror ray meets the disk's plane, as far as the larger of that point's distance to
    /// the rim and the lobe's width there (`2 distance / √exponent`); or [`Self::nearest`]
    /// where that is nearer, or the ray runs away from the plane.
    pub fn lobe(x: f64, y: f64, z: f64, mirror: (f64, f64, f64), exponent: f64) -> Self {
        let surface = Self::nearest(x, y, z);
        let distance = -z / mirror.2;
        if !(distance > 0.0 && distance < 1e30) {
            return surface;
        }
        let (hx, hy) = (x + distance * mirror.0, y + distance * mirror.1);
        let width = 2.0 * distance / exponent.max(1.0).sqrt();
        let lobe = Self {
            toward: hy.atan2(hx),
            to_rim: (hx.hypot(hy) - 1.0).abs().max(width),
        };
        if lobe.to_rim.max(DISK_NEAREST_RIM) < surface.to_rim.max(DISK_NEAREST_RIM) {
            lobe
        } else {
            surface
        }
    }
}

/// The corners of a disk of radius `radius`'s polygon of `sides` corners graded by
/// `grading`, as `(x, y)` in its plane, winding from +X toward +Y (see the module docs).
pub fn disk_polygon(radius: f64, grading: Grading, sides: usize) -> Vec<(f64, f64)> {
    let beta = (DISK_GRADING / grading.to_rim.max(DISK_NEAREST_RIM)).asinh();
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
            let (sin, cos) = (grading.toward + here).sin_cos();
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
