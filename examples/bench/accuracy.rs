//! The error of a Phong render against the f64 reference model, measured with the render
//! tests' harness: every pixel read back as `f32` with the world position and normal it was
//! lit with, compared with `bevy_phong::reference` on those inputs and *all* the scene's
//! lights (no culling in the model).

use crate::scene::{Scene, Shading, spawn_scene};
use bevy_phong::{
    PhongLightCulling, SpecularModel,
    reference::{self, Light},
};
use bevy_phong_headless::Harness;

/// Width and height of the renders the error is measured on.
pub const ERROR_SIZE: u32 = 128;

/// Pixels this close (world units) to a light's `range` are not judged: there the light is
/// cut off, and whether `f32` puts the pixel inside or outside is a matter of rounding.
const RANGE_BOUNDARY: f64 = 1e-5;

/// The largest per-channel error, relative to `max(1, |expected|)`, over the lit pixels of
/// `scene` drawn with `specular_model` (or none) and `culling`, and the number of pixels
/// left out on a range boundary.
pub fn max_error(
    scene: Scene,
    specular_model: Option<SpecularModel>,
    culling: PhongLightCulling,
) -> (f64, usize) {
    let mut harness = Harness::new(ERROR_SIZE, ERROR_SIZE);
    harness.world_mut().insert_resource(culling);
    harness.look_from(scene.camera_position());
    spawn_scene(harness.world_mut(), scene, Shading::Phong(specular_model));
    harness.settle();
    let inputs = harness.capture_inputs();
    let rendered = harness.render_next_frame();
    let lights = harness.reference_lights();
    let comparison = harness.compare_with(&rendered, &inputs, |material, surface| {
        let on_boundary = lights.lights.iter().any(|light| match light {
            Light::Point {
                position,
                range: Some(range),
                ..
            }
            | Light::Spot {
                position,
                range: Some(range),
                ..
            } => (position.distance(surface.position) - range).abs() < RANGE_BOUNDARY,
            _ => false,
        });
        (!on_boundary)
            .then(|| reference::shade(surface, &reference::Material::from(material), &lights))
    });
    if let Some((x, y, actual, expected)) = comparison.worst_pixel {
        eprintln!(
            "  largest error {:.2e} at pixel ({x}, {y}): rendered {actual:?}, model {expected:?}; \
             {} of {} pixels on a range boundary",
            comparison.max_error, comparison.skipped_pixels, comparison.lit_pixels
        );
    }
    (comparison.max_error, comparison.skipped_pixels)
}
