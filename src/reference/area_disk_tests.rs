//! The disk light's polygon (`area_disk_polygon`, the shader's `disk_polygon`) against the
//! quadrature over the disk itself (`area`), at every distance from its rim: where a disk
//! touches a floor, crosses its plane, or hangs just above it.

use super::area::{AreaLight, AreaShape, area_light_contribution};
use super::area_closed_forms::{self as closed, Specular};
use super::area_disk_polygon::DISK_SIDES;
use super::area_tests::{diffuse_only, material};
use super::{Material, SurfacePoint};
use crate::SpecularModel;
use bevy::math::DVec3;
use std::f64::consts::PI;

/// The radius of the disks of [`rim_scenes`].
const RADIUS: f64 = 0.5;

/// A one-sided disk of radius 0.5 facing down and toward +X (60° from the floor's plane),
/// its lowest rim point `lowest` above the floor `y = 0` (negative: below it, the disk
/// crossing the floor's plane).
fn tilted_disk(lowest: f64) -> AreaLight {
    // up × right = facing = (sin 60°, −cos 60°, 0).
    let up = DVec3::new(0.5, 0.75_f64.sqrt(), 0.0);
    AreaLight {
        position: DVec3::new(0.0, lowest + RADIUS * up.y, 0.0),
        right: DVec3::Z,
        up,
        shape: AreaShape::Disk { radius: RADIUS },
        two_sided: false,
        color: DVec3::new(2.0, 1.5, 1.0),
        specular: DVec3::new(1.0, 1.5, 2.0),
        decay: [1.0, 0.0, 0.0],
        range: None,
    }
}

/// The distance from `point` to the light's rim, in radii.
fn to_rim(light: &AreaLight, point: DVec3) -> f64 {
    let offset = point - light.position;
    let from_axis = offset.dot(light.right).hypot(offset.dot(light.up));
    (from_axis - RADIUS).hypot(offset.dot(light.facing())) / RADIUS
}

/// The three placements of the disk over a floor (touching it, crossing its plane 0.1 below
/// it, and 5 mm above it) with floor points in front of the disk at distances from its rim
/// spread over 1e-3 to 2 radii (closer, the quadrature takes
/// seconds a point): around the rim points nearest the floor, each with a camera
/// whose mirror ray runs to the disk.
pub(super) fn rim_scenes() -> Vec<(&'static str, AreaLight, Vec<SurfacePoint>)> {
    [("touching", 0.0), ("crossing", -0.1), ("above", 0.005)]
        .into_iter()
        .map(|(name, lowest)| {
            let light = tilted_disk(lowest);
            // The rim's points on the floor (where the disk crosses it), or its lowest.
            let anchors: Vec<DVec3> = if lowest < 0.0 {
                let half = (-lowest / (RADIUS * light.up.y)).acos();
                [-half, half]
                    .map(|t| light.point(RADIUS * t.sin(), -RADIUS * t.cos()))
                    .to_vec()
            } else {
                vec![light.point(0.0, -RADIUS)]
            };
            let mut points = Vec::new();
            for (index, anchor) in anchors.iter().enumerate() {
                for step in 0..36 {
                    let distance = RADIUS * 2.0 * 10f64.powf(-3.3 * f64::from(step % 12) / 11.0);
                    let turn = 0.45 * PI * (f64::from(step / 12) - 1.0) + index as f64;
                    let position = DVec3::new(
                        anchor.x + distance * turn.cos(),
                        0.0,
                        anchor.z + distance * turn.sin(),
                    );
                    if light.facing().dot(position - light.position) <= 0.0
                        || to_rim(&light, position) < 5e-4
                    {
                        continue;
                    }
                    // A camera whose mirror ray (about +Y) runs to a point inside the disk,
                    // or just inside or outside its rim, where the polygon's edges part from
                    // the circle.
                    let rim = 0.3 * f64::from(step);
                    let target = match step % 3 {
                        0 => light.point(0.3 * RADIUS * turn.sin(), 0.2 * RADIUS),
                        side => {
                            let reach = RADIUS * if side == 1 { 0.97 } else { 1.03 };
                            light.point(reach * rim.cos(), reach * rim.sin().abs())
                        }
                    };
                    let toward = target - position;
                    points.push(SurfacePoint {
                        position,
                        normal: DVec3::Y,
                        camera: position + DVec3::new(-toward.x, toward.y, -toward.z),
                    });
                }
            }
            // The floor in front of the disk as the render tests (tests/gpu/disk_rims.rs) see
            // it, from a camera in front of it.
            for i in 0..12 {
                for k in 0..12 {
                    let position =
                        DVec3::new(-0.2 + 0.18 * f64::from(i), 0.0, -1.1 + 0.2 * f64::from(k));
                    if light.facing().dot(position - light.position) > 0.0
                        && to_rim(&light, position) >= 5e-4
                    {
                        points.push(SurfacePoint {
                            position,
                            normal: DVec3::Y,
                            camera: DVec3::new(2.2, 1.3, 1.1),
                        });
                    }
                }
            }
            (name, light, points)
        })
        .collect()
}

/// The irradiance vector `∫ ω dω` of the whole disk at `point` (a polygon of 4,096 sides
/// graded toward it): its length is the most diffuse light the disk gives there.
fn irradiance_vector(light: &AreaLight, point: DVec3) -> DVec3 {
    let corners = closed::on_sphere(&closed::corners(light, point, 4096));
    let mut sum = DVec3::ZERO;
    for (index, start) in corners.iter().enumerate() {
        let end = corners[(index + 1) % corners.len()];
        let plane = start.cross(end);
        if plane.length() > 0.0 {
            sum += plane.length().atan2(start.dot(end)) * plane.normalize();
        }
    }
    0.5 * sum
}

/// The errors of the disk's polygon of `sides` sides at each point of the scenes, against
/// the quadrature over the disk: `(distance to the rim in radii, diffuse error as a share of
/// the most diffuse light the disk gives there, highlight error as a share of the whole
/// lobe)`, the highlight the integer Phong lobe of `shininess`.
fn rim_errors(sides: usize, shininess: f64) -> Vec<(f64, f64, f64)> {
    let highlight_only = Material {
        diffuse: DVec3::ZERO,
        ..material(SpecularModel::Phong, shininess)
    };
    let mut errors = Vec::new();
    for (_, light, points) in rim_scenes() {
        for surface in &points {
            let most = irradiance_vector(&light, surface.position).length()
                * (light.color / light.shape.area()).max_element();
            let reference = area_light_contribution(surface, &diffuse_only(), &light);
            let polygon =
                closed::contribution(surface, &diffuse_only(), &light, Specular::Exact, sides);
            let whole = closed::whole_lobe(shininess)
                * (light.specular / light.shape.area() * highlight_only.specular).max_element();
            let reference_highlight = area_light_contribution(surface, &highlight_only, &light);
            let polygon_highlight =
                closed::contribution(surface, &highlight_only, &light, Specular::Exact, sides);
            errors.push((
                to_rim(&light, surface.position),
                (polygon - reference).abs().max_element() / most,
                (polygon_highlight - reference_highlight)
                    .abs()
                    .max_element()
                    / whole,
            ));
        }
    }
    errors
}

/// The shader's disk polygons at every distance from the rim where a disk touches, crosses
/// or hangs just above a floor, against the quadrature over the disk: the diffuse light (32
/// corners toward the nearest rim point) within 5e-4 of the most the disk gives at the
/// point; the highlight (16 corners toward its lobe) within 1e-3 of the whole lobe at
/// shininess 12, 3e-3 at 50 and 1e-2 at 200 (its error grows as the lobe narrows): the
/// bounds SPEC.md states. The regular 16-gon these polygons replaced fails both by far near
/// the rim.
#[test]
fn a_disk_is_a_disk_up_to_its_rim() {
    let mut report = String::new();
    let (mut diffuse_worst, mut highlight_worst) = (0.0_f64, 0.0_f64);
    for (shininess, highlight_bound) in [(12.0, 1e-3), (50.0, 3e-3), (200.0, 1e-2)] {
        let errors = rim_errors(DISK_SIDES, shininess);
        let bands = [(0.0, 1e-2), (1e-2, 1e-1), (1e-1, 1.0), (1.0, 10.0)];
        for (low, high) in bands {
            let (diffuse, highlight) = errors
                .iter()
                .filter(|(rim, ..)| *rim >= low && *rim < high)
                .fold((0.0_f64, 0.0_f64), |(d, h), &(_, de, he)| {
                    (d.max(de), h.max(he))
                });
            report += &format!(
                "\n  α {shininess}, {low:.0e} to {high:.0e} radii from the rim: diffuse {diffuse:.1e}, highlight {highlight:.1e}"
            );
            diffuse_worst = diffuse_worst.max(diffuse);
            highlight_worst = highlight_worst.max(highlight / highlight_bound);
        }
    }
    println!("the disk's polygons, largest errors:{report}");
    // Measured: diffuse 1.8e-4 (between a hundredth and a tenth of a radius from the rim);
    // the highlight 5.7e-4, 2.5e-3 and 8.4e-3 at α = 12, 50 and 200 (with 32 corners toward
    // the nearest rim point: 9.0e-5, 4.9e-4 and 1.8e-3, at 4.8 times the cost on lavapipe).
    // The regular 16-gon errs by 0.66 (diffuse) and 0.38.
    assert!(diffuse_worst < 5e-4, "{report}");
    assert!(highlight_worst < 1.0, "{report}");
}
