//! A disk light where its rim meets a floor: touching it, crossing its plane, and hanging 5 mm
//! above it, against the reference model's quadrature over the disk itself (not over the
//! shader's polygon), every pixel, on both device limits.
//!
//! The shader draws the disk as polygons graded toward each surface point's nearest rim
//! point (the diffuse light) and toward its highlight's lobe (`disk_polygon.wesl`).
//! Tolerances, as shares of the frame's largest value: the diffuse light 1e-3 (the polygon's
//! bound is 5e-4 of the most the disk gives at the point, `reference::area_disk_tests`, plus
//! `f32`'s rounding of corners a few millimetres away), the Phong highlight of shininess 50
//! 3e-3 (its bound, of the whole lobe, which the frame's largest highlight nearly is here).
//! Measured on both limits: 2.0e-5 and 3.7e-5 of the frame's largest value at most. The
//! regular 16-gon the disk was drawn as before fails each frame near the rim (5.4e-2 to
//! 6.7e-2 in the diffuse light).

use crate::area_lights::largest_channel;
use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;

/// Small: the reference integrates each pixel's light over the disk.
const SIZE: u32 = 32;

/// The disk's radius, as the f64 scenes' (`reference::area_disk_tests`).
const RADIUS: f32 = 0.5;

/// A floor at `y = 0` under a one-sided disk of radius 0.5 that faces down and toward +X (60°
/// from the floor's plane), its lowest rim point `lowest` above the floor (negative: below,
/// the disk crossing the floor's plane) at the origin's X, seen from in front of it.
fn rim_scene(lowest: f32) -> (Harness, Handle<PhongMaterial>) {
    let mut harness = Harness::new(SIZE, SIZE);
    harness.look_from(Vec3::new(2.2, 1.3, 1.1));
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight::NONE);
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::default().mesh().size(8.0, 8.0));
    let material = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(PhongMaterial {
            base_color: Color::srgb(0.8, 0.7, 0.6),
            specular_strength: 0.0,
            ..default()
        });
    world.spawn((Mesh3d(mesh), MeshMaterial3d(material.clone())));
    // up × right = facing = (sin 60°, −cos 60°, 0); the disk's up is (cos 60°, sin 60°, 0).
    let facing = Vec3::new(0.75_f32.sqrt(), -0.5, 0.0);
    let up = Vec3::new(0.5, 0.75_f32.sqrt(), 0.0);
    let center = Vec3::new(0.0, lowest, 0.0) + RADIUS * up;
    world.spawn((
        PhongDiskLight {
            color: Color::linear_rgb(0.5, 0.4, 0.3),
            specular: Some(Color::linear_rgb(0.3, 0.4, 0.5)),
            radius: RADIUS,
            ..default()
        },
        Transform::from_translation(center).looking_to(facing, up),
    ));
    harness.settle();
    (harness, material)
}

/// Renders the disk's diffuse light and then its Phong highlight of shininess 50 (exact over
/// the polygon) and holds each to its share of the frame's largest value.
fn check_rim(lowest: f32, case: &str) {
    let (mut harness, material) = rim_scene(lowest);
    let inputs = harness.capture_inputs();
    for (part, share) in [("diffuse", 1e-3), ("highlight", 3e-3)] {
        if part == "highlight" {
            {
                let mut assets = harness.world_mut().resource_mut::<Assets<PhongMaterial>>();
                let mut floor = assets.get_mut(&material).expect("the floor's material");
                floor.base_color = Color::BLACK;
                floor.specular_color = Color::WHITE;
                floor.specular_strength = 1.0;
                floor.specular_model = SpecularModel::Phong;
                floor.shininess = 50.0;
            }
            harness.settle();
        }
        let probe = harness.render_next_frame();
        let tolerance = share * largest_channel(&probe);
        let rendered = harness.render_next_frame();
        harness
            .compare(&rendered, &inputs)
            .assert_within(&format!("disk_rim_{case}_{part}"), tolerance);
    }
}

#[test]
fn a_disk_touching_a_floor_matches_the_disk_at_every_pixel() {
    check_rim(0.0, "touching");
}

#[test]
fn a_disk_crossing_a_floor_matches_the_disk_at_every_pixel() {
    check_rim(-0.1, "crossing");
}

#[test]
fn a_disk_just_above_a_floor_matches_the_disk_at_every_pixel() {
    check_rim(0.005, "above");
}
