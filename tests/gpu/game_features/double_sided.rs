//! `PhongMaterial::double_sided`: back faces drawn, lit with the normal turned toward the
//! viewer.

use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;

use crate::frames::{SIZE, TOLERANCE};

/// A 4×4 square through the origin facing away from the harness camera (which looks from
/// +z), lit from the camera's side.
fn back_facing_square(
    harness: &mut Harness,
    double_sided: bool,
) -> (Entity, Handle<PhongMaterial>) {
    let world = harness.world_mut();
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::new(Vec3::NEG_Z, Vec2::splat(2.0)));
    let material = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(PhongMaterial {
            base_color: Color::srgb(0.9, 0.6, 0.2),
            shininess: 40.0,
            double_sided,
            ..default()
        });
    world.spawn((
        PhongPointLight {
            color: Color::linear_rgb(1.0, 1.0, 1.0),
            ..default()
        },
        Transform::from_xyz(0.5, 1.0, 3.0),
    ));
    let square = world
        .spawn((Mesh3d(mesh), MeshMaterial3d(material.clone())))
        .id();
    (square, material)
}

#[test]
fn a_single_sided_back_face_is_not_drawn() {
    let mut harness = Harness::new(SIZE, SIZE);
    back_facing_square(&mut harness, false);
    harness.settle();
    let rendered = harness.render_next_frame();
    let drawn = rendered
        .pixels
        .iter()
        .filter(|pixel| **pixel != [0.0; 4])
        .count();
    assert_eq!(drawn, 0, "pixels drawn by a culled back face");
}

/// The back face is lit as the front face of the same square turned around would be: the
/// per-pixel inputs are captured from that square (same positions, normal negated), then
/// the double-sided back face is rendered and compared with the reference on them.
#[test]
fn a_double_sided_back_face_is_lit_with_its_normal_toward_the_viewer() {
    let mut harness = Harness::new(SIZE, SIZE);
    let (square, _) = back_facing_square(&mut harness, true);
    let world = harness.world_mut();
    let back = world.get::<Mesh3d>(square).unwrap().clone();
    let turned = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::new(Vec3::Z, Vec2::splat(2.0)));
    world.entity_mut(square).insert(Mesh3d(turned));
    harness.settle();
    let inputs = harness.capture_inputs();
    harness.world_mut().entity_mut(square).insert(back);
    harness.settle();
    let rendered = harness.render_next_frame();
    let comparison = harness.compare(&rendered, &inputs);
    assert!(
        comparison.lit_pixels > (SIZE * SIZE / 8) as usize,
        "the square covers {} pixels",
        comparison.lit_pixels
    );
    comparison.assert_within("double_sided_back_face", TOLERANCE);
}
