//! Adversarial whole frames, read back as floats: whatever the scene, no pixel is NaN or
//! infinite.

use crate::frames::{SIZE, TOLERANCE};
use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::{FloatImage, Harness};

/// Asserts that `image` has covered pixels and that every pixel is finite.
fn assert_finite(case: &str, image: &FloatImage) {
    let bad = image.non_finite_pixels();
    let covered = image.covered_pixels();
    println!("{case}: {covered} covered pixels, {bad} NaN or infinite");
    assert!(covered > 0, "{case}: nothing was drawn");
    assert_eq!(bad, 0, "{case}: NaN or infinite pixels");
}

fn spawn_mesh(harness: &mut Harness, mesh: Mesh, transform: Transform, material: PhongMaterial) {
    let world = harness.world_mut();
    let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
    let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
    world.spawn((Mesh3d(mesh), MeshMaterial3d(material), transform));
}

fn shiny(shininess: f32) -> PhongMaterial {
    PhongMaterial {
        shininess,
        specular_strength: 2.0,
        ..default()
    }
}

/// A unit sphere at the origin on a 10×10 floor, with the given shininesses.
fn spawn_sphere_on_floor(harness: &mut Harness, sphere_shininess: f32, floor_shininess: f32) {
    spawn_mesh(
        harness,
        Sphere::new(1.0).mesh().uv(32, 16),
        Transform::default(),
        shiny(sphere_shininess),
    );
    spawn_mesh(
        harness,
        Plane3d::default().mesh().size(10.0, 10.0).into(),
        Transform::from_xyz(0.0, -1.0, 0.0),
        shiny(floor_shininess),
    );
}

#[test]
fn lights_inside_and_on_objects_give_finite_pixels() {
    let mut harness = Harness::new(SIZE, SIZE);
    spawn_sphere_on_floor(&mut harness, 0.0, 10_000.0);
    let world = harness.world_mut();
    // Inside the sphere, at its center, with no fall-off and with a zero decay.
    world.spawn((
        PhongPointLight {
            decay: Decay::new(0.0, 0.0, 0.0),
            ..default()
        },
        Transform::default(),
    ));
    // On the floor, and a spot on the floor aimed into it.
    world.spawn((
        PhongPointLight::default(),
        Transform::from_xyz(2.0, -1.0, 1.0),
    ));
    world.spawn((
        PhongSpotLight {
            inner_angle: 0.0,
            outer_angle: 0.0,
            ..default()
        },
        Transform::from_xyz(-2.0, -1.0, 1.0).looking_to(Vec3::NEG_Y, Vec3::Z),
    ));
    harness.settle();
    assert_finite("lights_inside_and_on_objects", &harness.render_next_frame());
}

#[test]
fn a_million_unit_wide_scene_gives_finite_pixels() {
    let mut harness = Harness::new(SIZE, SIZE);
    let far = Vec3::new(4e5, 0.0, -5e5);
    spawn_mesh(
        &mut harness,
        Plane3d::default().mesh().size(2e6, 2e6).into(),
        Transform::from_xyz(0.0, -1.0, 0.0),
        shiny(50.0),
    );
    spawn_mesh(
        &mut harness,
        Sphere::new(1.0).mesh().uv(32, 16),
        Transform::default(),
        shiny(50.0),
    );
    spawn_mesh(
        &mut harness,
        Cuboid::new(2e4, 2e4, 2e4).into(),
        Transform::from_translation(far),
        shiny(5.0),
    );
    let world = harness.world_mut();
    world.spawn((
        PhongPointLight {
            decay: Decay::DISTANCE_50,
            ..default()
        },
        Transform::from_xyz(0.0, 3.0, 2.0),
    ));
    world.spawn((
        PhongPointLight {
            color: Color::linear_rgb(1e10, 1e10, 1e10),
            decay: Decay::quadratic(1.0),
            ..default()
        },
        Transform::from_translation(far + Vec3::new(0.0, 3e4, 3e4)),
    ));
    world.spawn((
        PhongDirectionalLight::default(),
        Transform::default().looking_to(Vec3::new(-1.0, -1.0, -0.5), Vec3::Y),
    ));
    harness.settle();
    assert_finite("million_unit_scene", &harness.render_next_frame());
}

#[test]
fn ten_thousand_overlapping_lights_give_finite_pixels() {
    let mut harness = Harness::new(SIZE, SIZE);
    spawn_sphere_on_floor(&mut harness, 160.0, 8.0);
    let world = harness.world_mut();
    for i in 0..10_000 {
        let position = Vec3::new(0.0, 2.0, 1.5);
        if i % 2 == 0 {
            world.spawn((
                PhongPointLight::default(),
                Transform::from_translation(position),
            ));
        } else {
            world.spawn((
                PhongSpotLight {
                    outer_angle: 0.8,
                    ..default()
                },
                Transform::from_translation(position).looking_at(Vec3::ZERO, Vec3::Y),
            ));
        }
    }
    harness.settle();
    assert_finite(
        "ten_thousand_overlapping_lights",
        &harness.render_next_frame(),
    );
}

#[test]
fn an_invalid_light_is_sanitised_and_the_others_still_render() {
    let mut harness = Harness::new(SIZE, SIZE);
    spawn_sphere_on_floor(&mut harness, 50.0, 8.0);
    harness.settle();
    let inputs = harness.capture_inputs();
    let world = harness.world_mut();
    world.spawn((
        PhongPointLight {
            color: Color::linear_rgb(0.2, 0.8, 0.3),
            ..default()
        },
        Transform::from_xyz(-2.0, 3.0, 2.0),
    ));
    world.spawn((
        PhongPointLight {
            color: Color::linear_rgb(f32::NAN, 1.0, f32::INFINITY),
            range: Some(-2.0),
            decay: Decay::new(-1.0, 0.0, 0.1),
            ..default()
        },
        Transform::from_xyz(2.0, 3.0, 2.0),
    ));
    world.spawn((
        PhongPointLight::default(),
        Transform::from_xyz(f32::NAN, 1.0, 1.0),
    ));
    let rendered = harness.render_next_frame();
    assert_finite("invalid_light", &rendered);
    // The reference takes the lights as they are now: sanitised, the NaN-placed one skipped
    // by both.
    let comparison = harness.compare(&rendered, &inputs);
    comparison.assert_within("invalid_light_sanitised", TOLERANCE);
}
