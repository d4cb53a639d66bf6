//! The closed forms of the area lights (docs/design/area-lights.md), in `f64`, checked against the quadrature of
//! the reference model ([`super::area`]) in `area_tests`.
//!
//! A light seen from the surface point `P` is a spherical polygon: its corners `y − P`,
//! clipped to the half-spaces the integrand lives in (the surface's horizon `N·ω ≥ 0`, and a
//! lobe's own hemisphere `w·ω ≥ 0`), then normalized. Over such a polygon `A`:
//!
//! - the irradiance moment `∫_A N·ω dω` is Lambert's formula `½ Σ Θ_i (N·n_i)` (`Θ_i` the
//!   arc of edge `i`, `n_i` its plane's unit normal toward the inside);
//! - the lobe moment `τⁿ(w) = ∫_A (w·ω)ⁿ dω` for an integer `n` follows Arvo's recurrence
//!   (Arvo 1995, "Applications of irradiance tensors"):
//!   `τⁿ = ((n − 1)·τⁿ⁻² + Σ_i (w·n_i)·Eᵢⁿ⁻¹) / (n + 1)` from `τ⁰` (the solid angle) and
//!   `τ¹` (Lambert's), with the edge integrals `Eᵢᵏ = ∫₀^Θᵢ (a cos t + b sin t)ᵏ dt`
//!   (`a = w·vᵢ`, `b = w·vᵢ'`, `vᵢ'` the unit vector of the edge's plane perpendicular to
//!   `vᵢ` toward `vᵢ₊₁`) by their own recurrence
//!   `Eᵏ = ((k − 1)(a² + b²)·Eᵏ⁻² − [qᵏ⁻¹q']₀^Θ) / k`, `q = a cos t + b sin t`. The cost is
//!   `n/2` steps per edge.
//!
//! The recurrence of `τⁿ` comes from the divergence theorem on the sphere applied to the
//! field `(w·ω)ᵏ (w − (w·ω) ω)`, whose surface divergence is
//! `k (w·ω)ᵏ⁻¹ − (k + 2)(w·ω)ᵏ⁺¹`.

use super::area::{AreaLight, AreaShape};
use super::area_disk_polygon::{DISK_HIGHLIGHT_SIDES, DISK_SIDES, Grading, disk_polygon};
use super::{Material, SurfacePoint, attenuation, normalize_or_zero, power, reflect};
use crate::SpecularModel;
use bevy::math::DVec3;
use std::f64::consts::PI;

/// The part of the planar polygon `corners` (relative to the surface point) where
/// `normal · q ≥ 0`, by Sutherland–Hodgman: empty where nothing is on that side.
pub fn clipped(corners: &[DVec3], normal: DVec3) -> Vec<DVec3> {
    let mut kept = Vec::with_capacity(corners.len() + 1);
    for (index, &current) in corners.iter().enumerate() {
        let next = corners[(index + 1) % corners.len()];
        let (here, there) = (normal.dot(current), normal.dot(next));
        if here >= 0.0 {
            kept.push(current);
        }
        if (here >= 0.0) != (there >= 0.0) {
            let t = here / (here - there);
            kept.push(current + t * (next - current));
        }
    }
    kept
}

/// The spherical polygon of `corners`: each normalized.
pub fn on_sphere(corners: &[DVec3]) -> Vec<DVec3> {
    corners.iter().map(|corner| corner.normalize()).collect()
}

/// One edge of a spherical polygon: its arc and the unit vectors spanning its plane.
struct Edge {
    /// `vᵢ`.
    start: DVec3,
    /// `vᵢ'`: in the edge's plane, perpendicular to `vᵢ`, toward `vᵢ₊₁`.
    toward: DVec3,
    /// `Θᵢ`, radians.
    arc: f64,
    /// `nᵢ`: the plane's unit normal, toward the polygon's inside.
    inward: DVec3,
}

/// The edges of the spherical polygon `vertices` (at least three), their normals turned
/// toward its inside by the sign of its `signed_solid_angle`.
fn edges(vertices: &[DVec3], signed_solid_angle: f64) -> Vec<Edge> {
    let count = vertices.len();
    let mut edges: Vec<Edge> = (0..count)
        .filter_map(|index| {
            let (start, end) = (vertices[index], vertices[(index + 1) % count]);
            let normal = start.cross(end);
            let length = normal.length();
            if length <= 1e-300 {
                return None;
            }
            let arc = length.atan2(start.dot(end));
            let toward = (end - start.dot(end) * start).normalize();
            Some(Edge {
                start,
                toward,
                arc,
                inward: normal / length,
            })
        })
        .collect();
    // The normals point inside where the polygon winds counterclockwise seen from its
    // center; the solid angle's sign says which way it winds.
    if signed_solid_angle < 0.0 {
        for edge in &mut edges {
            edge.inward = -edge.inward;
        }
    }
    edges
}

/// The solid angle of the spherical polygon `vertices`, signed by its winding: the sum of its
/// fan's triangles by Van Oosterom and Strackee's formula.
fn signed_solid_angle(vertices: &[DVec3]) -> f64 {
    let first = vertices[0];
    vertices[1..]
        .windows(2)
        .map(|pair| {
            let (b, c) = (pair[0], pair[1]);
            let numerator = first.dot(b.cross(c));
            let denominator = 1.0 + first.dot(b) + b.dot(c) + c.dot(first);
            2.0 * numerator.atan2(denominator)
        })
        .sum()
}

/// `∫_A N·ω dω` over the spherical polygon `vertices` (already within `N`'s hemisphere):
/// Lambert's formula.
pub fn irradiance(vertices: &[DVec3], normal: DVec3) -> f64 {
    lobe_moment(vertices, normal, 1)
}

/// `τⁿ(w) = ∫_A (w·ω)ⁿ dω` over the spherical polygon `vertices`, by Arvo's recurrence.
pub fn lobe_moment(vertices: &[DVec3], axis: DVec3, n: u32) -> f64 {
    if vertices.len() < 3 {
        return 0.0;
    }
    let solid_angle = signed_solid_angle(vertices);
    let edges = edges(vertices, solid_angle);
    let weights: Vec<f64> = edges.iter().map(|edge| axis.dot(edge.inward)).collect();
    // τ at the parity of n, and each edge's integral at the other parity, raised together.
    let (mut tau, mut degree) = if n.is_multiple_of(2) {
        (solid_angle.abs(), 0)
    } else {
        let lambert: f64 = edges
            .iter()
            .zip(&weights)
            .map(|(edge, weight)| weight * edge.arc)
            .sum();
        (0.5 * lambert, 1)
    };
    let mut edge_integrals: Vec<EdgeIntegral> = edges
        .iter()
        .map(|edge| EdgeIntegral::new(edge, axis, 1 - degree))
        .collect();
    while degree < n {
        degree += 2;
        // Eᵢ at degree − 1.
        for integral in &mut edge_integrals {
            integral.raise_to(degree - 1);
        }
        let boundary: f64 = edge_integrals
            .iter()
            .zip(&weights)
            .map(|(integral, weight)| weight * integral.value)
            .sum();
        tau = (f64::from(degree - 1) * tau + boundary) / f64::from(degree + 1);
    }
    tau
}

/// `Eᵏ = ∫₀^Θ (a cos t + b sin t)ᵏ dt` of one edge, raised two degrees at a time.
struct EdgeIntegral {
    a: f64,
    b: f64,
    arc: f64,
    degree: u32,
    value: f64,
}

impl EdgeIntegral {
    /// The integral at degree 0 or 1.
    fn new(edge: &Edge, axis: DVec3, degree: u32) -> Self {
        let (a, b, arc) = (axis.dot(edge.start), axis.dot(edge.toward), edge.arc);
        let value = if degree == 0 {
            arc
        } else {
            a * arc.sin() + b * (1.0 - arc.cos())
        };
        Self {
            a,
            b,
            arc,
            degree,
            value,
        }
    }

    /// Raises the integral to `degree` (of the same parity) by
    /// `Eᵏ = ((k − 1)(a² + b²)·Eᵏ⁻² − [qᵏ⁻¹q']₀^Θ) / k`.
    fn raise_to(&mut self, degree: u32) {
        let (a, b) = (self.a, self.b);
        let (sin, cos) = self.arc.sin_cos();
        let (q_end, q_slope_end) = (a * cos + b * sin, -a * sin + b * cos);
        while self.degree < degree {
            let k = self.degree + 2;
            let ends = q_end.powi(k as i32 - 1) * q_slope_end - a.powi(k as i32 - 1) * b;
            self.value = (f64::from(k - 1) * (a * a + b * b) * self.value - ends) / f64::from(k);
            self.degree = k;
        }
    }
}

/// `∫_A max(w·ω, 0)^α dω` for a non-integer `α ≥ 0` over the spherical polygon `vertices`
/// (already within `w`'s hemisphere): the moments at the integers around `α`, interpolated
/// geometrically (`τ^⌊α⌋ · (τ^⌈α⌉ / τ^⌊α⌋)^f`), which is exact for a light small beside the
/// lobe (`τ^α = Ω · cos^α`).
pub fn lobe(vertices: &[DVec3], axis: DVec3, exponent: f64) -> f64 {
    let below = exponent.floor();
    let fraction = exponent - below;
    let low = lobe_moment(vertices, axis, below as u32);
    if fraction == 0.0 || low <= 0.0 {
        return low;
    }
    let high = lobe_moment(vertices, axis, below as u32 + 1);
    low * (high / low).powf(fraction)
}

/// The solid angle of a whole lobe, `∫ max(w·ω, 0)^α dω = 2π / (α + 1)` over the sphere.
pub fn whole_lobe(exponent: f64) -> f64 {
    2.0 * PI / (exponent + 1.0)
}

/// The exponent of the Phong lobe around the mirror direction that stands for a
/// Blinn-Phong lobe of `exponent` seen at `n_dot_v`: `α / (4 N·V)`. Near its peak the
/// Blinn-Phong lobe is a Phong lobe of `α/4` across the plane of incidence's normal and of
/// `α / (4 (N·V)²)` along it (the half vector turns half as fast as the light in the plane,
/// `1/(2 N·V)` times as fast across it); `α / (4 N·V)` is their geometric mean, the lobe of
/// the same solid angle. `N·V` is taken at least 1e-3.
pub fn blinn_as_phong(exponent: f64, n_dot_v: f64) -> f64 {
    0.25 * exponent / n_dot_v.max(1e-3)
}

/// How a light's highlight is integrated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Specular {
    /// The lobe's moment over the clipped polygon ([`lobe`]).
    Exact,
    /// The lobe toward the light's point nearest the mirror ray, times the light's solid
    /// angle and the whole lobe's ([`whole_lobe`]) joined harmonically.
    RepresentativePoint,
    /// The lobe's fitted linearly transformed cosine integrated over the lit polygon
    /// ([`fitted_lobe`]).
    Fitted,
    /// The lobe's moment up to [`BOUNDED_EXACT_UP_TO`], the stretched lower lobes beyond it
    /// ([`bounded_lobe`]).
    Bounded,
}

/// The largest exponent [`bounded_lobe`] integrates exactly (as [`lobe`]).
pub const BOUNDED_EXACT_UP_TO: f64 = 64.0;

/// The exponents of the two lobes [`bounded_lobe`] stretches to a larger exponent's width.
pub const BOUNDED_LOBES: [u32; 2] = [32, 16];

/// `∫ max(w·ω, 0)^α dω` over the planar polygon `corners` (relative to the surface point) at
/// a cost that does not grow with `α`: [`lobe`] up to [`BOUNDED_EXACT_UP_TO`]; beyond it,
/// `2·S(32) − S(16)`, where `S(m)` is the lobe of the integer exponent `m` over the polygon
/// stretched across `w` by `√(α/m)` ([`stretched_lobe`]), which narrows it to the width of
/// the lobe of `α` near its peak. `S(m)` errs by about `c/m` of the whole lobe (the lobe of
/// `m` is not yet the Gaussian the lobe of `α` is); the two taken together cancel that term
/// (Richardson's extrapolation). Never below 0.
pub fn bounded_lobe(corners: &[DVec3], axis: DVec3, exponent: f64) -> f64 {
    if exponent <= BOUNDED_EXACT_UP_TO {
        return lobe(&on_sphere(&clipped(corners, axis)), axis, exponent);
    }
    let [high, low] = BOUNDED_LOBES;
    (2.0 * stretched_lobe(corners, axis, exponent, high)
        - stretched_lobe(corners, axis, exponent, low))
    .max(0.0)
}

/// The lobe of `exponent` over the planar polygon `corners` (relative to the surface point)
/// as the lobe of the integer `m` over the polygon stretched across `w` by `k = √(α/m)`
/// (each corner's components across `w` times `k`, along `w` kept), times
/// `(m + 1)/(α + 1)`, the ratio of the whole lobes: in the plane tangent to the sphere at
/// `w`, the lobe of `α` near its peak is the Gaussian `exp(−α r²/2)`, and the stretch maps
/// the lobe of `m` onto it.
pub fn stretched_lobe(corners: &[DVec3], axis: DVec3, exponent: f64, m: u32) -> f64 {
    let stretch = (exponent / f64::from(m)).sqrt();
    let stretched = across(corners, axis, stretch);
    let above = on_sphere(&clipped(&stretched, DVec3::Z));
    whole_lobe(exponent) / whole_lobe(f64::from(m)) * lobe_moment(&above, DVec3::Z, m)
}

/// The planar polygon `corners` in the frame of `axis` (its +Z), stretched across it by
/// `stretch`.
fn across(corners: &[DVec3], axis: DVec3, stretch: f64) -> Vec<DVec3> {
    let (across, other) = axis.any_orthonormal_pair();
    corners
        .iter()
        .map(|corner| {
            DVec3::new(
                stretch * corner.dot(across),
                stretch * corner.dot(other),
                corner.dot(axis),
            )
        })
        .collect()
}

/// `∫ max(w·ω, 0)^α dω` over the planar polygon `corners` (relative to the surface point)
/// with the lobe replaced by the linearly transformed cosine fitted to it: the clamped
/// cosine around `w` squeezed across it by `s = 1/√(0.585 α + 0.415)` (the least-squares fit
/// of the normalized lobe `cos^α θ / W` over the hemisphere, `W` the [`whole_lobe`]; `s = 1`,
/// exact, at `α = 1`). Its integral over the polygon is the clamped cosine's, `1/π` of
/// Lambert's formula, over the polygon stretched across `w` by `1/s`, times `W`.
pub fn fitted_lobe(corners: &[DVec3], axis: DVec3, exponent: f64) -> f64 {
    if corners.len() < 3 {
        return 0.0;
    }
    let stretch = (0.585 * exponent + 0.415).sqrt();
    let stretched = across(corners, axis, stretch);
    let above = on_sphere(&clipped(&stretched, DVec3::Z));
    whole_lobe(exponent) / PI * irradiance(&above, DVec3::Z)
}

/// The corners of `light` relative to `point`, winding counterclockwise seen from its facing
/// side: a disk as the polygon of `sides` corners the shader's diffuse light takes, graded
/// toward the rim point nearest `point` (`area_disk_polygon`).
pub fn corners(light: &AreaLight, point: DVec3, sides: usize) -> Vec<DVec3> {
    disk_or_rect(light, point, sides, &Grading::nearest)
}

/// The corners of `light` the highlight's lobe around `mirror` of `exponent` is integrated
/// over, as [`corners`]: a disk as the shader's polygon of `sides` corners graded toward
/// where the lobe meets its rim ([`Grading::lobe`]).
pub fn highlight_corners(
    light: &AreaLight,
    point: DVec3,
    sides: usize,
    (mirror, exponent): (DVec3, f64),
) -> Vec<DVec3> {
    let in_frame = |v: DVec3| (v.dot(light.right), v.dot(light.up), v.dot(light.facing()));
    let mirror = in_frame(mirror);
    disk_or_rect(light, point, sides, &|x, y, z| {
        Grading::lobe(x, y, z, mirror, exponent)
    })
}

/// The rectangle's corners, or the disk's polygon of `sides` corners graded by
/// `grading(x, y, z)` of the point in the disk's frame, in radii.
fn disk_or_rect(
    light: &AreaLight,
    point: DVec3,
    sides: usize,
    grading: &dyn Fn(f64, f64, f64) -> Grading,
) -> Vec<DVec3> {
    let relative = |x: f64, y: f64| light.point(x, y) - point;
    match light.shape {
        AreaShape::Rect { width, height } => {
            let (x, y) = (0.5 * width, 0.5 * height);
            vec![
                relative(-x, -y),
                relative(x, -y),
                relative(x, y),
                relative(-x, y),
            ]
        }
        AreaShape::Disk { radius } => {
            let offset = (point - light.position) / radius;
            let seen = grading(
                offset.dot(light.right),
                offset.dot(light.up),
                offset.dot(light.facing()),
            );
            disk_polygon(radius, seen, sides)
                .into_iter()
                .map(|(x, y)| relative(x, y))
                .collect()
        }
    }
}

/// The light's term at `surface` by the closed forms: Lambert's diffuse and the Phong lobe
/// around the mirror direction `R_V = 2(N·V)N − V` (a Blinn-Phong lobe of exponent `α` as the
/// Phong lobe of `α/4`), for a material of Lambert diffuse and a smooth highlight. A disk's
/// diffuse light is taken over its polygon of `sides` corners ([`corners`]), its highlight
/// over one of `sides · 16/32` ([`highlight_corners`]), as the shader's 32 and 16.
pub fn contribution(
    surface: &SurfacePoint,
    material: &Material,
    light: &AreaLight,
    specular: Specular,
    sides: usize,
) -> DVec3 {
    let fall_off = attenuation(light.distance(surface.position), light.decay, light.range);
    let area = light.shape.area();
    let normal = normalize_or_zero(surface.normal);
    let front = light.facing().dot(surface.position - light.position);
    if fall_off <= 0.0 || area <= 0.0 || normal == DVec3::ZERO {
        return DVec3::ZERO;
    }
    if front == 0.0 || (!light.two_sided && front < 0.0) {
        return DVec3::ZERO;
    }
    let diffuse = irradiance(
        &on_sphere(&clipped(&corners(light, surface.position, sides), normal)),
        normal,
    );
    let view = normalize_or_zero(surface.camera - surface.position);
    let mirror = reflect(-view, normal);
    let exponent = match material.specular_model {
        SpecularModel::Phong => material.shininess,
        _ => blinn_as_phong(material.shininess, normal.dot(view)),
    };
    // The highlight's polygon of a disk has the shader's share of the diffuse one's corners.
    let highlight_sides = (sides * DISK_HIGHLIGHT_SIDES / DISK_SIDES).max(3);
    let lit = clipped(
        &highlight_corners(light, surface.position, highlight_sides, (mirror, exponent)),
        normal,
    );
    let highlight = match specular {
        Specular::Exact => lobe(&on_sphere(&clipped(&lit, mirror)), mirror, exponent),
        Specular::RepresentativePoint => {
            representative_highlight(light, surface.position, &lit, mirror, exponent)
        }
        Specular::Fitted => fitted_lobe(&lit, mirror, exponent),
        Specular::Bounded => bounded_lobe(&lit, mirror, exponent),
    };
    let weight = material.specular * material.specular_strength;
    fall_off
        * (light.color / area * material.diffuse * diffuse
            + light.specular / area * weight * highlight)
}

/// The representative point's highlight: `max(w·ω_r, 0)^α` toward the point `ω_r` of the
/// lit part `lit` (the light's polygon above the horizon, relative to the surface point)
/// nearest where the mirror ray `w` meets the light's plane (or, for a ray that runs away
/// from the plane, where it heads), times `Ω·W / (Ω + W)`, `Ω` the lit part's solid angle
/// and `W = 2π/(α + 1)` the whole lobe's: `Ω` for a light small beside the lobe, `W` for
/// one that holds it.
fn representative_highlight(
    light: &AreaLight,
    point: DVec3,
    lit: &[DVec3],
    mirror: DVec3,
    exponent: f64,
) -> f64 {
    if lit.len() < 3 {
        return 0.0;
    }
    let facing = light.facing();
    // Relative to the surface point, as `lit`.
    let plane = light.position - point;
    let height = facing.dot(plane);
    let along = facing.dot(mirror);
    let aim = if along * height > 0.0 {
        mirror * (height / along)
    } else {
        // Far along the ray, brought onto the plane.
        let far = mirror * 1e6 * (plane.length() + 1.0);
        far - facing * facing.dot(far - plane)
    };
    let toward = nearest_on_polygon(lit, aim, facing).normalize();
    let solid_angle = signed_solid_angle(&on_sphere(lit)).abs();
    let whole = whole_lobe(exponent);
    power(mirror.dot(toward).max(0.0), exponent) * solid_angle * whole / (solid_angle + whole)
}

/// The point of the convex planar polygon `corners` (in the plane of normal `normal`)
/// nearest `target` of that plane: `target` itself where it is inside.
fn nearest_on_polygon(corners: &[DVec3], target: DVec3, normal: DVec3) -> DVec3 {
    let count = corners.len();
    let edge = |index: usize| (corners[index], corners[(index + 1) % count]);
    let side = |index: usize| {
        let (start, end) = edge(index);
        normal.dot((end - start).cross(target - start))
    };
    let sides: Vec<f64> = (0..count).map(side).collect();
    if sides.iter().all(|&s| s >= 0.0) || sides.iter().all(|&s| s <= 0.0) {
        return target;
    }
    (0..count)
        .map(|index| {
            let (start, end) = edge(index);
            let span = end - start;
            let t =
                ((target - start).dot(span) / span.length_squared().max(1e-300)).clamp(0.0, 1.0);
            start + t * span
        })
        .min_by(|a, b| {
            (*a - target)
                .length_squared()
                .total_cmp(&(*b - target).length_squared())
        })
        .unwrap_or(target)
}
