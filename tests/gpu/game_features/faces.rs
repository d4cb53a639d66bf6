//! Which faces a `PhongMaterial` draws and in what depth order: `cull_mode` (front faces
//! culled, so the inside of a closed mesh shows, lit with the mesh's own normals) and
//! `depth_bias` (of two surfaces in one place, the biased one is drawn).

use bevy::{prelude::*, render::render_resource::Face};
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;

use crate::frames::{SIZE, TOLERANCE};

/// A point light in front and above, a directional light from behind the meshes (so that
/// the far inner faces of a cube, whose normals point away from the camera, are lit too).
fn spawn_lights(world: &mut World) {
    world.insert_resource(PhongAmbientLight {
        color: Color::srgb(0.1, 0.1, 0.12),
    });
    world.spawn((
        PhongPointLight {
            color: Color::srgb(0.9, 0.8, 0.6),
            ..default()
        },
        Transform::from_xyz(1.0, 2.5, 3.0),
    ));
    world.spawn((
        PhongDirectionalLight {
            color: Color::srgb(0.4, 0.5, 0.7),
            ..default()
        },
        Transform::default().looking_to(Vec3::new(0.2, -0.4, 1.0), Vec3::Y),
    ));
}

/// With front faces culled, a cube shows its three far faces from inside, each lit with
/// its outward normal (facing away from the viewer), as the reference model says on the
/// inputs captured with the same culling. A cube culling no face shows its outside.
#[test]
fn front_faces_culled_show_the_inside_lit_with_the_meshs_normals() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_lights(world);
    let cube = world
        .resource_mut::<Assets<Mesh>>()
        .add(Cuboid::new(1.6, 1.6, 1.6));
    for (x, cull_mode) in [(-1.2, Some(Face::Front)), (1.2, None)] {
        let material = world
            .resource_mut::<Assets<PhongMaterial>>()
            .add(PhongMaterial {
                base_color: Color::srgb(0.8, 0.5, 0.3),
                shininess: 20.0,
                cull_mode,
                ..default()
            });
        world.spawn((
            Mesh3d(cube.clone()),
            MeshMaterial3d(material),
            Transform::from_xyz(x, 0.0, 0.0).with_rotation(Quat::from_euler(
                EulerRot::YXZ,
                0.5,
                0.4,
                0.0,
            )),
        ));
    }
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs();
    let camera = harness.camera_position();
    let comparison = harness.compare(&rendered, &inputs);
    comparison.assert_within("cull_mode", TOLERANCE);
    // The front-culled cube shows faces turned away from the camera.
    let size = SIZE as usize;
    let inside = (0..size * size)
        .filter_map(|pixel| inputs.surface_at(pixel, camera))
        .filter(|(_, surface)| surface.normal.dot(surface.camera - surface.position) < 0.0)
        .count();
    assert!(
        inside > size * size / 40,
        "{inside} pixels show a face turned away from the camera"
    );
}

/// Two spheres in one place, the one with a depth bias a hundred-thousandth smaller (so a
/// few hundred-thousandths of a unit behind the other, far less than the bias moves it):
/// the biased one is drawn at every pixel, lit as the reference model says on its own
/// inputs (captured with the other hidden).
#[test]
fn a_depth_bias_draws_the_biased_one_of_two_surfaces_in_one_place() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_lights(world);
    let sphere = world
        .resource_mut::<Assets<Mesh>>()
        .add(Sphere::new(1.3).mesh().uv(48, 32));
    let biased = PhongMaterial {
        base_color: Color::srgb(0.2, 0.4, 0.9),
        depth_bias: 1000.0,
        ..default()
    };
    let plain = PhongMaterial::from(Color::srgb(0.9, 0.3, 0.2));
    let mut spawn = |material: PhongMaterial, scale: f32| {
        let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
        world
            .spawn((
                Mesh3d(sphere.clone()),
                MeshMaterial3d(material),
                Transform::from_scale(Vec3::splat(scale)),
            ))
            .id()
    };
    spawn(biased, 1.0 - 1e-5);
    let in_front = spawn(plain, 1.0);
    harness
        .world_mut()
        .entity_mut(in_front)
        .insert(Visibility::Hidden);
    harness.settle();
    let inputs = harness.capture_inputs();
    harness
        .world_mut()
        .entity_mut(in_front)
        .insert(Visibility::Inherited);
    harness.settle();
    let rendered = harness.render_next_frame();
    let comparison = harness.compare(&rendered, &inputs);
    assert!(
        comparison.lit_pixels > (SIZE * SIZE / 8) as usize,
        "the sphere covers {} pixels",
        comparison.lit_pixels
    );
    comparison.assert_within("depth_bias", TOLERANCE);
}
