//! What a game turns on around its materials: double-sided surfaces, culled faces and depth
//! bias, Bevy's fog, HDR, bloom, tonemapping, MSAA, blending, prepasses, SSAO and the
//! deferred renderer, Bevy's wireframes, each rendered with `PhongMaterial` and checked against what the
//! feature's own formula gives.

mod blend;
mod double_sided;
mod faces;
mod fog;
mod hdr;
mod motion_vectors;
mod msaa;
mod prepasses;
mod ssao;
mod tone_curves;
mod wireframe;

use bevy::math::DVec3;
use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::{Comparison, Expected, FloatImage, Harness};

use crate::frames::{TOLERANCE, spawn_objects};

/// Where an HDR camera stores the frame (`Rgba16Float`) a value is rounded to 11
/// significant bits, a relative error of at most 2⁻¹¹; twice when a post-process pass
/// (tonemapping) reads and writes it again. On top of the frames' [`TOLERANCE`].
pub const HDR_TOLERANCE: f64 = TOLERANCE + 2.0 / 2048.0;

/// The frames' objects under an ambient light and a directional light bright enough that
/// highlights exceed 1.
pub fn bright_scene(harness: &mut Harness) -> Vec<Handle<PhongMaterial>> {
    let materials = spawn_objects(harness);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.08, 0.08, 0.08),
    });
    world.spawn((
        PhongDirectionalLight {
            color: Color::linear_rgb(1.6, 1.5, 1.3),
            specular: Some(Color::linear_rgb(3.0, 3.0, 3.0)),
            ..default()
        },
        Transform::default().looking_to(Vec3::new(-1.0, -0.6, -0.4), Vec3::Y),
    ));
    materials
}

/// The largest channel value in `image`'s color.
pub fn brightest(image: &FloatImage) -> f32 {
    image
        .pixels
        .iter()
        .flat_map(|pixel| &pixel[..3])
        .fold(0.0, |a, &b| a.max(b))
}

/// Asserts that `rendered` equals `baseline` within `tolerance`, pixel by pixel (clear
/// where `baseline` is).
pub fn assert_same_frame(case: &str, rendered: &FloatImage, baseline: &FloatImage, tolerance: f64) {
    Comparison::of(rendered, |index| {
        let [r, g, b, a] = baseline.pixels[index];
        if a == 0.0 {
            Expected::Clear
        } else {
            Expected::Lit(DVec3::new(r.into(), g.into(), b.into()))
        }
    })
    .assert_within(case, tolerance);
}
