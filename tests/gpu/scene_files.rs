//! Scene files: `assets/scenes/shapes.phong_scene.ron` (four shapes and a floor, a material
//! file, directional, point and spot lights) loaded through the asset server, rendered from
//! its own camera and compared with the reference model, pixel by pixel, at the frame
//! tests' tolerance (same equation, same inputs; see `frames`).

use crate::frames::{SIZE, TOLERANCE};
use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;

#[test]
fn a_scene_file_renders_as_the_reference_model_says() {
    let mut harness = Harness::new(SIZE, SIZE);
    harness
        .load_scene("scenes/shapes.phong_scene.ron")
        .unwrap_or_else(|error| panic!("{error}"));
    let lights = harness.reference_lights();
    assert_eq!(lights.lights.len(), 4, "the file's four lights");
    let world = harness.world_mut();
    let objects = world
        .query::<&MeshMaterial3d<PhongMaterial>>()
        .iter(world)
        .count();
    assert_eq!(objects, 5, "the file's five objects");

    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs();
    harness
        .compare(&rendered, &inputs)
        .assert_within("scene file", TOLERANCE);
}
