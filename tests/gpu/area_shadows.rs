//! Shadows from area lights (`PhongRectLight::shadows`, `PhongDiskLight::shadows`): cast from
//! the light's center into a cube of maps, soft as a light of the area's size
//! (percentage-closer soft shadows), against the light's exact visibility: the reference
//! model's quadrature over the light's area with each element weighed by whether the segment
//! from the surface point to it meets the blocker
//! (`reference::visible_area_light_contribution`).
//!
//! The scene: a floor under a sphere that blocks part of an overhead light, the light a disk
//! and then a panel. The blocker is the analytic sphere in the reference and a fine UV sphere
//! (64 × 48) in the frame. Measured as a share of the frame's largest value: the soft shadow
//! errs by at most [`BOUND`], and the same light without shadows errs by more than twice as
//! much (the shadow is there).

use crate::area_lights::largest_channel;
use bevy::prelude::*;
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{FloatImage, Harness, SurfaceInputs};
use glam::DVec3;

/// Small: the reference integrates each pixel's light over the area, past the blocker.
const SIZE: u32 = 24;

/// The documented error of an area light's soft shadow, as a share of the frame's largest
/// value (docs/design/area-lights.md, "Shadows").
const BOUND: f64 = 0.2;

/// The quadrature's tolerance, relative to each pixel's term: the visibility's edges are
/// jumps, which the adaptive rule halves down to.
const QUADRATURE: f64 = 1e-4;

const BLOCKER_CENTER: Vec3 = Vec3::new(0.1, -0.3, 0.2);
const BLOCKER_RADIUS: f32 = 0.45;

/// Whether the segment from `from` to `to` misses the blocker: it enters the analytic sphere
/// nowhere between its ends (a point on the sphere, drawn slightly inside it by the mesh's
/// faces, is not blocked by the sphere's own surface as the segment leaves it).
fn clear(from: DVec3, to: DVec3) -> f64 {
    let center = BLOCKER_CENTER.as_dvec3();
    let radius = f64::from(BLOCKER_RADIUS);
    let span = to - from;
    let start = from - center;
    let (a, b, c) = (
        span.length_squared(),
        2.0 * start.dot(span),
        start.length_squared() - radius * radius,
    );
    let discriminant = b * b - 4.0 * a * c;
    if discriminant <= 0.0 {
        return 1.0;
    }
    let entry = (-b - discriminant.sqrt()) / (2.0 * a);
    if entry > 1e-6 && entry < 1.0 {
        0.0
    } else {
        1.0
    }
}

/// The floor and the blocker (white, diffuse only), `light` at `transform` with `shadows`,
/// settled, with each pixel's inputs.
fn scene<L: Component>(light: L, transform: Transform) -> (Harness, SurfaceInputs) {
    let mut harness = Harness::new(SIZE, SIZE);
    harness.look_from(Vec3::new(0.5, 3.0, 4.0));
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight::NONE);
    let material = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(PhongMaterial {
            base_color: Color::WHITE,
            specular_strength: 0.0,
            ..default()
        });
    for (mesh, transform) in [
        (
            Plane3d::default().mesh().size(6.0, 6.0).into(),
            Transform::from_xyz(0.0, -1.0, 0.0),
        ),
        (
            Sphere::new(BLOCKER_RADIUS).mesh().uv(64, 48),
            Transform::from_translation(BLOCKER_CENTER),
        ),
    ] {
        let mesh: Mesh = mesh;
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        world.spawn((Mesh3d(mesh), MeshMaterial3d(material.clone()), transform));
    }
    world.spawn((light, transform));
    harness.settle();
    let inputs = harness.capture_inputs();
    harness.settle();
    (harness, inputs)
}

/// The largest error of `frame` against the light's exact visibility, as a share of the
/// frame's largest value, printed under `case`.
fn shadow_error(
    harness: &mut Harness,
    inputs: &SurfaceInputs,
    frame: &FloatImage,
    light: &reference::AreaLight,
    case: &str,
) -> f64 {
    let comparison = harness.compare_with(frame, inputs, |material, surface| {
        let material = reference::Material::from(material);
        Some(reference::visible_area_light_contribution(
            surface,
            &material,
            light,
            &|point| clear(surface.position, point),
            QUADRATURE,
        ))
    });
    let largest = largest_channel(frame);
    let share = comparison.max_error / largest;
    println!(
        "{case}: {} pixels, largest error {:.3e} ({share:.3} of the largest value {largest:.3})",
        comparison.lit_pixels, comparison.max_error
    );
    share
}

/// Renders `light` at `transform` with soft shadows, without shadows, and (as a point light
/// would cast it) with a hard shadow, and holds each to what it must be.
fn check_shadows<L: Component + Clone>(
    name: &str,
    light: L,
    transform: Transform,
    reference: reference::AreaLight,
    set_shadows: fn(&mut L, PhongShadows),
) {
    let mut soft = light.clone();
    set_shadows(&mut soft, PhongShadows::ON);
    // One harness at a time: each holds the device.
    let soft_error = {
        let (mut harness, inputs) = scene(soft, transform);
        let frame = harness.render_next_frame();
        shadow_error(&mut harness, &inputs, &frame, &reference, name)
    };
    assert!(
        soft_error <= BOUND,
        "{name}: the soft shadow errs by {soft_error:.3} of the largest value, past {BOUND}"
    );

    let unshadowed = {
        let (mut harness, inputs) = scene(light, transform);
        let frame = harness.render_next_frame();
        shadow_error(&mut harness, &inputs, &frame, &reference, "  unshadowed")
    };
    assert!(
        unshadowed > 2.0 * soft_error,
        "{name}: the shadow is there ({unshadowed:.3} unshadowed, {soft_error:.3} shadowed)"
    );
}

#[test]
fn an_area_lights_soft_shadow_follows_its_exact_visibility_within_its_bound() {
    let overhead =
        Transform::from_xyz(-0.2, 1.6, 0.0).looking_to(Vec3::new(0.2, -1.0, 0.1), Vec3::Z);
    let disk = PhongDiskLight {
        color: Color::linear_rgb(2.0, 2.0, 2.0),
        radius: 0.6,
        ..default()
    };
    let reference = reference::AreaLight::disk(&disk, &GlobalTransform::from(overhead));
    check_shadows("disk", disk, overhead, reference, |light, shadows| {
        light.shadows = shadows;
    });

    let panel = PhongRectLight {
        color: Color::linear_rgb(2.0, 2.0, 2.0),
        width: 1.4,
        height: 0.6,
        ..default()
    };
    let reference = reference::AreaLight::rect(&panel, &GlobalTransform::from(overhead));
    check_shadows("panel", panel, overhead, reference, |light, shadows| {
        light.shadows = shadows;
    });
}
