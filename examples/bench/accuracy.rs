//! The error of a Phong render against the f64 reference model, measured with the render
//! tests' harness: every pixel read back as `f32` with the world position and normal it was
//! lit with, compared with `bevy_phong::reference` on those inputs and *all* the scene's
//! lights (no culling in the model).

use crate::harness::Harness;
use crate::scene::{Scene, Shading, spawn_scene};
use bevy_phong::{PhongLightCulling, SpecularModel};

/// Width and height of the renders the error is measured on.
pub const ERROR_SIZE: u32 = 128;

/// The largest per-channel error, relative to `max(1, |expected|)`, over the lit pixels of
/// `scene` drawn with `specular_model` (or none) and `culling`.
pub fn max_error(
    scene: Scene,
    specular_model: Option<SpecularModel>,
    culling: PhongLightCulling,
) -> f64 {
    let mut harness = Harness::new(ERROR_SIZE, ERROR_SIZE);
    harness.world_mut().insert_resource(culling);
    harness.look_from(scene.camera_position());
    spawn_scene(harness.world_mut(), scene, Shading::Phong(specular_model));
    harness.settle();
    let inputs = harness.capture_inputs();
    let rendered = harness.render_next_frame();
    harness.compare(&rendered, &inputs).max_error
}
