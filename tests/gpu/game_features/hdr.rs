//! HDR cameras, tonemapping (in the shader and as Bevy's post-process) and bloom.

use bevy::{
    camera::Hdr,
    core_pipeline::tonemapping::{DebandDither, Tonemapping},
    post_process::bloom::Bloom,
    prelude::*,
    render::view::{ColorGrading, ColorGradingGlobal},
};
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{Comparison, Expected, Harness};
use glam::DVec3;

use super::{HDR_TOLERANCE, bright_scene, brightest, tone_curves::tone_mapped};
use crate::frames::{SIZE, TOLERANCE};

/// An HDR camera stores the Phong colors above 1 as they are: the frame matches the
/// reference model within the half-float rounding.
#[test]
fn an_hdr_camera_keeps_phong_colors_above_one() {
    let mut harness = Harness::new(SIZE, SIZE);
    bright_scene(&mut harness);
    harness.settle();
    let inputs = harness.capture_inputs();
    harness.camera_mut().insert(Hdr);
    harness.settle();
    let rendered = harness.render_next_frame();
    let peak = brightest(&rendered);
    assert!(peak > 1.5, "the brightest channel is {peak}, not above 1.5");
    harness
        .compare(&rendered, &inputs)
        .assert_within("hdr", HDR_TOLERANCE);
}

/// Bevy's Reinhard, luminance Reinhard, ACES fitted and Khronos PBR Neutral curves map every
/// Phong color `c` as their formulas do (`tone_curves.rs`), after the camera's exposure and
/// before its saturation (`ColorGrading`'s global part), in the material's shader on a camera
/// without HDR (as `StandardMaterial` does it); Reinhard's also in Bevy's tonemapping pass on
/// an HDR camera. (The others are not compared there: the half floats' rounding grows through a
/// curve whose channels share the luminance beyond `HDR_TOLERANCE`, and Bevy's luminance
/// Reinhard divides the black background's zero luminance by itself.) The scene's
/// highlights exceed 1.5, where each curve is far from the identity: an untonemapped frame
/// fails the comparison there.
#[test]
fn tonemapping_applies_bevys_curve_to_the_phong_colors() {
    let mut harness = Harness::new(SIZE, SIZE);
    bright_scene(&mut harness);
    harness.settle();
    let inputs = harness.capture_inputs();
    let lights = harness.reference_lights();
    let neutral = ColorGradingGlobal::default();
    let graded = ColorGradingGlobal {
        exposure: -0.5,
        post_saturation: 0.6,
        ..default()
    };
    for (method, grading, hdr) in [
        (Tonemapping::Reinhard, &neutral, false),
        (Tonemapping::Reinhard, &neutral, true),
        (Tonemapping::ReinhardLuminance, &neutral, false),
        (Tonemapping::AcesFitted, &neutral, false),
        (Tonemapping::KhronosPbrNeutral, &graded, false),
    ] {
        let (place, tolerance) = if hdr {
            ("in the HDR pass", HDR_TOLERANCE)
        } else {
            ("in the shader", TOLERANCE)
        };
        let case = format!("{method:?} {place}, exposure {}", grading.exposure);
        let mut camera = harness.camera_mut();
        camera.insert((
            method,
            ColorGrading {
                global: grading.clone(),
                ..default()
            },
        ));
        if hdr {
            camera.insert(Hdr);
        } else {
            camera.remove::<Hdr>();
        }
        harness.settle();
        let rendered = harness.render_next_frame();
        harness
            .compare_with(&rendered, &inputs, |material, surface| {
                let lit = reference::shade(surface, &reference::Material::from(material), &lights);
                tone_mapped(lit, method, grading)
            })
            .assert_within(&case, tolerance);
    }
}

/// Bloom spreads a bright Phong surface's light past its silhouette, fading with distance,
/// where without bloom the background stays clear, and keeps the frame's light (an
/// energy-conserving composite).
#[test]
fn bloom_spreads_bright_phong_light_past_its_silhouette() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(Sphere::new(0.8).mesh().uv(48, 32));
    let material = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(PhongMaterial {
            base_color: Color::BLACK,
            specular_strength: 0.0,
            emissive: LinearRgba::rgb(8.0, 6.0, 3.0),
            ..default()
        });
    world.spawn((Mesh3d(mesh), MeshMaterial3d(material)));
    harness.camera_mut().insert(Hdr);
    harness.settle();
    let plain = harness.render_next_frame();
    let covered: Vec<bool> = plain.pixels.iter().map(|pixel| pixel[3] > 0.0).collect();
    let distances = silhouette_distances(&covered, plain.width);
    let background_light = |image: &bevy_phong_headless::FloatImage, rings: (f32, f32)| {
        ring_mean(image, &distances, rings)
    };
    assert_eq!(
        background_light(&plain, (0.0, f32::MAX)),
        0.0,
        "light outside the sphere without bloom"
    );

    harness.camera_mut().insert(Bloom::NATURAL);
    harness.settle();
    let bloomed = harness.render_next_frame();
    let near = background_light(&bloomed, (1.0, 4.0));
    let far = background_light(&bloomed, (12.0, 16.0));
    let total = |image: &bevy_phong_headless::FloatImage| -> f64 {
        image
            .pixels
            .iter()
            .map(|pixel| f64::from(pixel[0] + pixel[1] + pixel[2]))
            .sum()
    };
    let (before, after) = (total(&plain), total(&bloomed));
    let kept = after / before;
    println!(
        "bloom: mean background light 1–4 px from the sphere {near:.4}, 12–16 px {far:.4}; \
         the frame's light {before:.1} without, {after:.1} with ({kept:.4})"
    );
    // `Bloom::NATURAL` composites energy-conservingly: the frame is mixed with its blur at
    // the bloom's intensity (0.15), and the blur carries the frame's light, less what the
    // first downsample's Karis average takes from the brightest pixels (about 5 % of this
    // sphere's 8.0 emissive). So the frame keeps between 90 % and all of its light, where
    // an additive composite, or a blur of a frame without the Phong light, would not.
    assert!(
        (0.9..=1.0 + 1e-3).contains(&kept),
        "bloom kept {kept} of the frame's light"
    );
    // 15 % of a blur whose first mips spread the silhouette's 8.0 over a few pixels: about a
    // tenth next to it (0.108 measured); half that says the glow is there at all.
    assert!(near > 0.05, "no glow next to the sphere ({near})");
    assert!(
        far < near / 2.0,
        "the glow does not fade ({near} near, {far} far)"
    );
}

/// For each pixel not covered by the mesh, its distance in pixels from the silhouette (the
/// nearest covered pixel); `None` for covered pixels.
fn silhouette_distances(covered: &[bool], width: u32) -> Vec<Option<f32>> {
    let width = width as i32;
    let position = |index: usize| (index as i32 % width, index as i32 / width);
    let covered_at: Vec<(i32, i32)> = (0..covered.len())
        .filter(|&index| covered[index])
        .map(position)
        .collect();
    (0..covered.len())
        .map(|index| {
            let (x, y) = position(index);
            (!covered[index]).then(|| {
                covered_at
                    .iter()
                    .map(|&(cx, cy)| (((cx - x).pow(2) + (cy - y).pow(2)) as f32).sqrt())
                    .fold(f32::MAX, f32::min)
            })
        })
        .collect()
}

/// The mean color (averaged over channels) of the pixels not covered by the mesh whose
/// distance from its silhouette ([`silhouette_distances`]) is within `rings`.
fn ring_mean(
    image: &bevy_phong_headless::FloatImage,
    distances: &[Option<f32>],
    rings: (f32, f32),
) -> f32 {
    let (mut sum, mut count) = (0.0, 0);
    for (pixel, distance) in image.pixels.iter().zip(distances) {
        if distance.is_some_and(|distance| distance >= rings.0 && distance <= rings.1) {
            sum += (pixel[0] + pixel[1] + pixel[2]) / 3.0;
            count += 1;
        }
    }
    if count == 0 { 0.0 } else { sum / count as f32 }
}

/// Bevy's `screen_space_dither` (bevy_core_pipeline 0.20.1, `tonemapping.wesl`) at the
/// pixel whose center is `frag`, in `f64`: `(fract(dot((171, 231), frag) / m) − ½) / 255`
/// for `m` = 103, 71, 97. `None` where a fraction lies within 10⁻⁴ of a whole number, where
/// the shader's `f32` may round across it (a jump of a whole 1/255): the dot product is a
/// whole number at pixel centers, so that is where it is a multiple of `m`, about one pixel
/// in thirty.
fn screen_space_dither(frag: [f64; 2]) -> Option<DVec3> {
    let d = 171.0 * frag[0] + 231.0 * frag[1];
    let fraction = [103.0, 71.0, 97.0].map(|m: f64| (d / m).fract());
    if fraction.iter().any(|f| *f < 1e-4 || *f > 1.0 - 1e-4) {
        return None;
    }
    Some(DVec3::from_array(fraction.map(|f| (f - 0.5) / 255.0)))
}

/// `DebandDither` on a camera that tone maps in the shader: each Phong pixel is the
/// undithered one moved by Bevy's dither in a 2.2 gamma, `((c^(1/2.2) + dither)^2.2)` per
/// channel, as `StandardMaterial` dithers. The dither is about 1/255 in gamma, so a frame
/// left undithered differs by up to about 4e-3, ten times the tolerance.
#[test]
fn deband_dither_moves_each_pixel_by_bevys_dither_pattern() {
    let mut harness = Harness::new(SIZE, SIZE);
    bright_scene(&mut harness);
    harness.camera_mut().insert(Tonemapping::Reinhard);
    harness.settle();
    let plain = harness.render_next_frame();
    harness.camera_mut().insert(DebandDither::Enabled);
    harness.settle();
    let dithered = harness.render_next_frame();
    let width = plain.width;
    let comparison = Comparison::of(&dithered, |index| {
        let undithered = plain.pixels[index];
        if undithered[3] == 0.0 {
            return Expected::Clear;
        }
        let frag = [
            f64::from(index as u32 % width) + 0.5,
            f64::from(index as u32 / width) + 0.5,
        ];
        let Some(dither) = screen_space_dither(frag) else {
            return Expected::Unjudged;
        };
        let powsafe = |value: f64, power: f64| value.signum() * value.abs().powf(power);
        let expected = DVec3::from_array([0, 1, 2].map(|channel| {
            let value = f64::from(undithered[channel]);
            powsafe(powsafe(value, 1.0 / 2.2) + dither[channel], 2.2)
        }));
        Expected::Lit(expected)
    });
    comparison.assert_within("deband_dither", TOLERANCE);
}
