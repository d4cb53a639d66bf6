//! MSAA: a Phong mesh's silhouette is resolved from its samples, its inside shaded as
//! without MSAA.

use bevy::{camera::Hdr, prelude::*};
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{
    Comparison, Expected, Harness, HarnessCamera, SurfaceInputs, pixel_model::world_triangles,
};
use glam::DVec2;

use super::{HDR_TOLERANCE, bright_scene};
use crate::frames::SIZE;

/// Samples per pixel.
const SAMPLES: f32 = 4.0;

/// Vulkan's standard locations of 4 samples in a pixel, `(x, y)` from its top-left corner
/// (`VkPhysicalDeviceLimits::standardSampleLocations`, which lavapipe and the GPUs wgpu
/// runs on report).
const SAMPLE_LOCATIONS: [[f64; 2]; 4] = [
    [0.375, 0.125],
    [0.875, 0.375],
    [0.125, 0.625],
    [0.625, 0.875],
];

/// A sample this near a triangle's edge, in pixels, may fall either side of it: the
/// rasterizer snaps vertices to its subpixel grid, 1/256 of a pixel on lavapipe and the
/// desktop GPUs (`subPixelPrecisionBits` 8), and the projection differs from this `f32`
/// one by about 10⁻⁵ of a pixel.
const EDGE_MARGIN: f64 = 1.0 / 256.0 + 1e-3;

/// Each pixel's samples as the front faces of every mesh in view cover them, projected by
/// the harness's camera: `Some(count)` of the 4 covered where every sample lies farther
/// than [`EDGE_MARGIN`] from the edges that decide it, `None` elsewhere.
fn covered_samples(harness: &mut Harness) -> Vec<Option<u32>> {
    let world = harness.world_mut();
    let (camera, camera_transform) = world
        .query_filtered::<(&Camera, &GlobalTransform), With<HarnessCamera>>()
        .single(world)
        .map(|(camera, transform)| (camera.clone(), *transform))
        .expect("the harness's camera");
    let size = camera.logical_viewport_size().expect("a viewport");
    let (width, height) = (size.x as usize, size.y as usize);
    let placed: Vec<(Handle<Mesh>, GlobalTransform)> = world
        .query::<(&Mesh3d, &GlobalTransform)>()
        .iter(world)
        .map(|(mesh, transform)| (mesh.0.clone(), *transform))
        .collect();
    let meshes = world.resource::<Assets<Mesh>>();
    let mut triangles: Vec<[DVec2; 3]> = Vec::new();
    for (mesh, transform) in &placed {
        let mesh = meshes.get(mesh).expect("a loaded mesh");
        for triangle in world_triangles(mesh, transform) {
            let corners = triangle.map(|corner| {
                camera
                    .world_to_viewport(&camera_transform, corner.as_vec3())
                    .expect("every corner in front of the camera")
                    .as_dvec2()
            });
            triangles.push(corners);
        }
    }
    // Per sample: covered well inside some triangle, or possibly covered (within the margin).
    let mut surely = vec![[false; 4]; width * height];
    let mut possibly = vec![[false; 4]; width * height];
    for [a, b, c] in triangles {
        // Front faces wind counter-clockwise in clip space, so clockwise in the viewport
        // (y down): a back face is culled, and covers nothing.
        let area = (b - a).perp_dot(c - a);
        if area > -1e-12 {
            continue;
        }
        // Signed distances to the edges, positive inside whatever the winding.
        let distances = |p: DVec2| {
            [(a, b), (b, c), (c, a)].map(|(from, to)| {
                (to - from).perp_dot(p - from) * area.signum() / (to - from).length()
            })
        };
        let low = a.min(b).min(c) - EDGE_MARGIN;
        let high = a.max(b).max(c) + EDGE_MARGIN;
        for y in low.y.floor().max(0.0) as usize..(high.y.ceil().max(0.0) as usize).min(height) {
            for x in low.x.floor().max(0.0) as usize..(high.x.ceil().max(0.0) as usize).min(width) {
                for (sample, [sx, sy]) in SAMPLE_LOCATIONS.into_iter().enumerate() {
                    let d = distances(DVec2::new(x as f64 + sx, y as f64 + sy));
                    let nearest = d.into_iter().fold(f64::INFINITY, f64::min);
                    surely[y * width + x][sample] |= nearest > EDGE_MARGIN;
                    possibly[y * width + x][sample] |= nearest > -EDGE_MARGIN;
                }
            }
        }
    }
    surely
        .iter()
        .zip(&possibly)
        .map(|(surely, possibly)| {
            (surely == possibly).then(|| surely.iter().filter(|&&covered| covered).count() as u32)
        })
        .collect()
}

/// With `Msaa::Sample4` (on an HDR camera: `Rgba16Float` is the format every device
/// multisamples), pixels whose 3×3 neighborhood lies on one mesh match the reference model
/// (the fragment is shaded once, at the pixel center), those whose neighborhood is all
/// background stay clear, and every pixel's alpha is the share of its 4 samples the meshes'
/// triangles cover, each sample at Vulkan's standard location (pixels with a sample within
/// [`EDGE_MARGIN`] of a deciding edge left out).
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

    // Coverage: alpha is exact in `Rgba16Float` (a quarter is a power of two).
    let coverage = covered_samples(&mut harness);
    let (mut judged, mut partial) = (0, 0);
    for (index, (pixel, covered)) in rendered.pixels.iter().zip(&coverage).enumerate() {
        let Some(covered) = *covered else {
            continue;
        };
        let expected = covered as f32 / SAMPLES;
        assert!(
            (pixel[3] - expected).abs() < 1e-3,
            "pixel ({}, {}): alpha {}, but {covered} of its {SAMPLES} samples are covered",
            index as u32 % rendered.width,
            index as u32 / rendered.width,
            pixel[3]
        );
        judged += 1;
        partial += usize::from(covered > 0 && covered < 4);
    }
    println!(
        "msaa: coverage judged on {judged} pixels, {partial} of them partly covered; {} left out \
         near an edge",
        coverage.len() - judged
    );
    // The silhouettes against the background (the sphere's, the cube's, the floor's far
    // edge) cross about 140 pixels, most with no sample within the margin (115 judged): at
    // least 50 says the check saw silhouettes at all.
    assert!(partial >= 50, "only {partial} partly covered pixels judged");
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
