//! `AlphaMode::Blend`: a translucent Phong surface over what is behind it.

use bevy::{math::DVec3, prelude::*};
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{Comparison, Expected, Harness};

use super::bright_scene;
use crate::frames::{SIZE, TOLERANCE};

/// The translucent square's alpha.
const ALPHA: f32 = 0.6;

/// Each pixel of a translucent Phong square is `α · lit + (1 − α) · behind`, with `lit` the
/// reference model on the square's own inputs and `behind` the reference on the inputs of
/// the opaque scene behind it (or the clear color, black). Bevy's alpha blending, in `f32`:
/// within the frames' tolerance.
#[test]
fn a_blended_phong_surface_is_mixed_over_what_is_behind_it_by_its_alpha() {
    let mut harness = Harness::new(SIZE, SIZE);
    let behind = bright_scene(&mut harness);
    let world = harness.world_mut();
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::new(Vec3::Z, Vec2::new(2.5, 1.2)));
    let translucent = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(PhongMaterial {
            base_color: Color::srgba(0.2, 0.7, 0.9, ALPHA),
            shininess: 20.0,
            alpha_mode: AlphaMode::Blend,
            ..default()
        });
    let square = world
        .spawn((
            Mesh3d(mesh),
            MeshMaterial3d(translucent),
            Transform::from_xyz(-0.8, 0.3, 2.0).with_rotation(Quat::from_rotation_y(0.3)),
        ))
        .id();
    harness.settle();

    // The inputs of the scene behind, then of the square alone.
    harness
        .world_mut()
        .entity_mut(square)
        .insert(Visibility::Hidden);
    let behind_inputs = harness.capture_inputs();
    harness
        .world_mut()
        .entity_mut(square)
        .insert(Visibility::Visible);
    let hidden: Vec<Entity> = {
        let world = harness.world_mut();
        world
            .query::<(Entity, &MeshMaterial3d<PhongMaterial>)>()
            .iter(world)
            .filter(|(_, material)| behind.contains(&material.0))
            .map(|(entity, _)| entity)
            .collect()
    };
    for &entity in &hidden {
        harness
            .world_mut()
            .entity_mut(entity)
            .insert(Visibility::Hidden);
    }
    let square_inputs = harness.capture_inputs();
    for &entity in &hidden {
        harness
            .world_mut()
            .entity_mut(entity)
            .insert(Visibility::Visible);
    }
    harness.settle();
    let rendered = harness.render_next_frame();

    let lights = harness.reference_lights();
    let camera = harness.camera_position();
    let materials = harness.world_mut().resource::<Assets<PhongMaterial>>();
    let shade = |inputs: &bevy_phong_headless::SurfaceInputs, index| {
        inputs.surface_at(index, camera).map(|(material, surface)| {
            let material = reference::Material::from(materials.get(material).unwrap());
            reference::shade(&surface, &material, &lights)
        })
    };
    let alpha = f64::from(ALPHA);
    let comparison = Comparison::of(&rendered, |index| {
        match (shade(&square_inputs, index), shade(&behind_inputs, index)) {
            (Some(front), back) => {
                Expected::Lit(alpha * front + (1.0 - alpha) * back.unwrap_or(DVec3::ZERO))
            }
            (None, Some(back)) => Expected::Lit(back),
            (None, None) => Expected::Clear,
        }
    });
    comparison.assert_within("blend", TOLERANCE);
}
