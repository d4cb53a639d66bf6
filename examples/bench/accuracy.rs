//! The error of a Phong render against the f64 reference model, measured with the render
//! tests' harness: every pixel read back as `f32` with the world position and normal it was
//! lit with, compared with `bevy_phong::reference` on those inputs and *all* the scene's
//! lights (no culling in the model), per pixel (a material lit per vertex is measured against
//! the exact per-pixel picture).

use crate::scene::{Scene, Shading, spawn_scene};
use bevy::prelude::*;
use bevy_phong::{
    PhongLightCulling, PhongRectLight,
    reference::{self, AreaLight, Light},
};
use bevy_phong_headless::Harness;

/// Width and height of the renders the error is measured on.
pub const ERROR_SIZE: u32 = 128;

/// Pixels this close (world units) to a light's `range` (a rect light's, from its nearest
/// point) are not judged: there the light is cut off, and whether `f32` puts the pixel inside
/// or outside is a matter of rounding.
const RANGE_BOUNDARY: f64 = 1e-5;

/// How far a render is from the per-pixel model: each lit pixel's largest per-channel error,
/// relative to `max(1, |expected|)`.
#[derive(Clone, Copy, Debug)]
pub struct Accuracy {
    /// The largest over the lit pixels.
    pub max: f64,
    /// The error 95 % of the lit pixels stay within.
    pub p95: f64,
}

/// The [`Accuracy`] of `scene` drawn with `shading` (`PhongMaterial`, lit per pixel or per
/// vertex) and `culling`, against the per-pixel model; pixels on a range boundary are left
/// out.
pub fn measure(scene: Scene, shading: Shading, culling: PhongLightCulling) -> Accuracy {
    measure_at(scene, shading, culling, ERROR_SIZE)
}

/// [`measure`] on a `size`² picture.
pub fn measure_at(
    scene: Scene,
    shading: Shading,
    culling: PhongLightCulling,
    size: u32,
) -> Accuracy {
    let mut harness = Harness::new(size, size);
    harness.world_mut().insert_resource(culling);
    harness.look_from(scene.camera_position());
    spawn_scene(harness.world_mut(), scene, shading);
    harness.settle();
    let inputs = harness.capture_inputs();
    let rendered = harness.render_next_frame();
    let lights = harness.reference_lights();
    let world = harness.world_mut();
    let panels: Vec<(AreaLight, f64)> = world
        .query::<(&PhongRectLight, &GlobalTransform)>()
        .iter(world)
        .filter_map(|(panel, transform)| {
            Some((AreaLight::rect(panel, transform), f64::from(panel.range?)))
        })
        .collect();
    let comparison = harness.compare_with(&rendered, &inputs, |material, surface| {
        let on_panel_boundary = panels.iter().any(|(panel, range)| {
            (panel.distance(surface.position) - range).abs() < RANGE_BOUNDARY
        });
        let on_boundary = on_panel_boundary
            || lights.lights.iter().any(|light| match light {
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
    Accuracy {
        max: comparison.max_error,
        p95: comparison.error_quantile(0.95),
    }
}
