//! MSAA: a Phong mesh's silhouette is resolved from its samples, its inside shaded as
//! without MSAA.

use bevy::{camera::Hdr, prelude::*};
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{Comparison, Expected, Harness, SurfaceInputs};

use super::{HDR_TOLERANCE, bright_scene};
use crate::frames::SIZE;

/// Samples per pixel.
const SAMPLES: f32 = 4.0;

/// With `Msaa::Sample4` (on an HDR camera: `Rgba16Float` is the format every device
/// multisamples), pixels whose 3×3 neighborhood lies on one mesh match the reference model
/// (the fragment is shaded once, at the pixel center), those whose neighborhood is all
/// background stay clear, and pixels on a silhouette against
/// the clear background have the covered fraction of the 4 samples in alpha.
#[test]
fn msaa_resolves_silhouettes_and_leaves_insides_exact() {
    let mut harness = Harness::new(SIZE, SIZE);
    bright_scene(&mut harness);
    harness.settle();
    let inputs = harness.capture_inputs();
    harness.camera_mut().insert((Hdr, Msaa::Sample4));
    harness.settle();
    let rendered = harness.render_next_frame();

    let inside = inside_pixels(&inputs);
    let lights = harness.reference_lights();
    let camera = harness.camera_position();
    let materials = harness.world_mut().resource::<Assets<PhongMaterial>>();
    Comparison::of(&rendered, |index| {
        match (inside[index], inputs.surface_at(index, camera)) {
            (false, _) => Expected::Unjudged,
            (true, None) => Expected::Clear,
            (true, Some((material, surface))) => {
                let material = reference::Material::from(materials.get(material).unwrap());
                Expected::Lit(reference::shade(&surface, &material, &lights))
            }
        }
    })
    .assert_within("msaa_inside", HDR_TOLERANCE);

    let partial: Vec<f32> = rendered
        .pixels
        .iter()
        .map(|pixel| pixel[3])
        .filter(|&alpha| alpha > 0.0 && alpha < 1.0)
        .collect();
    println!("msaa: {} silhouette pixels partly covered", partial.len());
    assert!(
        partial.len() > 50,
        "only {} partly covered pixels",
        partial.len()
    );
    for alpha in partial {
        let samples = alpha * SAMPLES;
        assert!(
            (samples - samples.round()).abs() < 1e-3,
            "alpha {alpha} is not a whole number of the {SAMPLES} samples"
        );
    }
}

/// Whether each pixel and its eight neighbors show the same material with normals within
/// 2.6° of each other. Elsewhere a pixel's samples can fall on two triangles, each shaded
/// at the pixel center with its own (extrapolated) inputs: across a silhouette, a crease (a
/// cube's edges), or a fast-turning normal under a sharp highlight (measured: 1.6e-3 off
/// on the sphere's).
fn inside_pixels(inputs: &SurfaceInputs) -> Vec<bool> {
    let (width, height) = (
        inputs.positions.width as i32,
        inputs.positions.height as i32,
    );
    let at = |x: i32, y: i32| (y * width + x) as usize;
    let tag = |x: i32, y: i32| inputs.positions.pixels[at(x, y)][3];
    let normal = |x: i32, y: i32| {
        let [nx, ny, nz, _] = inputs.normals.pixels[at(x, y)];
        Vec3::new(nx, ny, nz).normalize_or_zero()
    };
    let alike = |x: i32, y: i32, dx: i32, dy: i32| {
        tag(x + dx, y + dy) == tag(x, y) && normal(x + dx, y + dy).dot(normal(x, y)) > 0.999
    };
    (0..width * height)
        .map(|index| {
            let (x, y) = (index % width, index / width);
            x > 0
                && y > 0
                && x < width - 1
                && y < height - 1
                && (-1..=1).all(|dy| (-1..=1).all(|dx| alike(x, y, dx, dy)))
        })
        .collect()
}
