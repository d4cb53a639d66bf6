//! Screen-space ambient occlusion darkens the ambient term of `PhongMaterial`, as it does
//! `StandardMaterial`'s, and nothing else.

use bevy::{pbr::ScreenSpaceAmbientOcclusion, prelude::*, render::renderer::RenderDevice};
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;

use super::assert_same_frame;
use crate::frames::{SIZE, TOLERANCE, spawn_objects};
use crate::texture_maps::float_map;

/// Bevy's SSAO needs 5 storage textures per shader stage (its compute passes); without
/// them (WebGL2) it is not loaded and the frame is drawn unoccluded.
const SSAO_STORAGE_TEXTURES: u32 = 5;

/// Bevy's multi-bounce correction (`ssao_multibounce`, bevy_pbr 0.20.1's `ssao/utils.wesl`,
/// Jimenez et al.'s fit) for one channel of albedo `albedo`, in `f64`: the share of the
/// ambient light a point of visibility `v` receives once light bounced off its
/// surroundings is counted.
fn multibounce(v: f64, albedo: f64) -> f64 {
    let a = 2.0404 * albedo - 0.3324;
    let b = -4.7951 * albedo + 0.6417;
    let c = 2.7552 * albedo + 0.6903;
    v.max(((v * a + b) * v + c) * v)
}

/// The visibility `v` in `[0, 1]` with `multibounce(v, albedo) = factor` (the correction
/// grows with `v` there), by bisection to 10⁻¹².
fn visibility_of(factor: f64, albedo: f64) -> f64 {
    let (mut low, mut high) = (0.0, 1.0);
    while high - low > 1e-12 {
        let middle = 0.5 * (low + high);
        if multibounce(middle, albedo) < factor {
            low = middle;
        } else {
            high = middle;
        }
    }
    0.5 * (low + high)
}

/// Each channel of a pixel's ambient factor, recovered from the frames, may differ from the
/// one the formula predicts by this much: the ratio of two `f32` pixels (a relative 6e-8
/// each, on values down to 0.005) and the cubic's rounding in the shader (a few 10⁻⁷), the
/// visibility recovered from the red channel carrying them over by the ratio of the
/// channels' slopes (under 4 on this floor).
const FACTOR_TOLERANCE: f64 = 1e-5;

/// With `ScreenSpaceAmbientOcclusion` on the camera:
/// - lit by the directional light alone, the frame is the one without SSAO (occlusion
///   never touches direct light);
/// - lit by the ambient light alone, each pixel is the unoccluded one (the floor's AO map
///   included) times a factor in `[0, 1]` per channel, Bevy's visibility `v` with its
///   multi-bounce correction:
///   `min(1, multibounce(v, k_d))` for each channel of the surface's diffuse color. On the
///   floor, whose channels differ (linear 0.79, 0.21, 0.02), `v` is recovered from the red
///   channel and the green and blue factors must be the formula's at that `v` (a factor
///   taken as `v` alone in every channel fails). In the crease where the sphere meets the
///   floor half the hemisphere above the floor is blocked, so the darkest factor is well
///   below 1 (measured 0.31); below 0.9 says SSAO reached the crease at all.
///
/// Where the device cannot run Bevy's SSAO, both frames equal those without it.
#[test]
fn ssao_darkens_the_ambient_term_only() {
    let mut harness = Harness::new(SIZE, SIZE);
    let materials = spawn_objects(&mut harness);
    // The floor: channels far apart, where the multi-bounce correction differs most.
    let floor = materials[0].clone();
    let floor_color = Color::srgb(0.9, 0.5, 0.15);
    // An AO map on it, four levels from 0.4 to 0.85: SSAO multiplies it (SPEC.md, "Baked
    // light"), so that the ratio of the frames is still SSAO's factor alone. (The map itself
    // is checked in `surface_inputs`; here its combination with SSAO: a `min`, as
    // `StandardMaterial` takes it, fails.)
    let ao_map = harness
        .world_mut()
        .resource_mut::<Assets<Image>>()
        .add(float_map(|x, y| {
            [0.4 + 0.15 * ((x + 3 * y) % 4) as f32, 0.0, 0.0, 1.0]
        }));
    if let Some(mut material) = harness
        .world_mut()
        .resource_mut::<Assets<PhongMaterial>>()
        .get_mut(&floor)
    {
        material.base_color = floor_color;
        material.ao_map_texture = Some(ao_map);
    }
    let albedo = floor_color.to_linear().to_f32_array().map(f64::from);
    let ambient = PhongAmbientLight {
        color: Color::linear_rgb(0.5, 0.5, 0.5),
    };
    let sun = harness
        .world_mut()
        .spawn((
            PhongDirectionalLight {
                color: Color::linear_rgb(0.8, 0.8, 0.7),
                ..default()
            },
            Transform::default().looking_to(Vec3::new(-1.0, -0.6, -0.4), Vec3::Y),
        ))
        .id();
    harness.world_mut().insert_resource(PhongAmbientLight::NONE);
    harness.settle();
    let direct = harness.render_next_frame();
    harness.world_mut().insert_resource(ambient.clone());
    harness
        .world_mut()
        .entity_mut(sun)
        .insert(Visibility::Hidden);
    harness.settle();
    let ambient_only = harness.render_next_frame();
    let inputs = harness.capture_inputs();
    let floor_tag = inputs
        .materials
        .iter()
        .find(|(_, handle)| **handle == floor)
        .map(|(tag, _)| *tag)
        .expect("the floor is drawn");

    harness
        .camera_mut()
        .insert(ScreenSpaceAmbientOcclusion::default());
    harness.settle();
    let occluded_ambient = harness.render_next_frame();
    harness.world_mut().insert_resource(PhongAmbientLight::NONE);
    harness
        .world_mut()
        .entity_mut(sun)
        .insert(Visibility::Visible);
    harness.settle();
    let occluded_direct = harness.render_next_frame();

    assert_same_frame("ssao_direct_light", &occluded_direct, &direct, TOLERANCE);
    let storage_textures = harness
        .app
        .sub_app(bevy::render::RenderApp)
        .world()
        .resource::<RenderDevice>()
        .limits()
        .max_storage_textures_per_shader_stage;
    if storage_textures < SSAO_STORAGE_TEXTURES {
        println!("ssao: {storage_textures} storage textures per stage: Bevy leaves SSAO out");
        assert_same_frame(
            "ssao_unsupported",
            &occluded_ambient,
            &ambient_only,
            TOLERANCE,
        );
        return;
    }
    let mut darkest = 1.0f32;
    for (index, (occluded, open)) in occluded_ambient
        .pixels
        .iter()
        .zip(&ambient_only.pixels)
        .enumerate()
    {
        for channel in 0..3 {
            if open[channel] <= 1e-3 {
                continue;
            }
            let factor = occluded[channel] / open[channel];
            assert!(
                (-1e-6..=1.0 + 1e-5).contains(&factor),
                "pixel {index}, channel {channel}: occluded {} over unoccluded {} is {factor}",
                occluded[channel],
                open[channel]
            );
            darkest = darkest.min(factor);
        }
    }
    // On the floor, the green and blue factors are the formula's at the red one's visibility.
    let (mut judged, mut largest) = (0, 0.0f64);
    for (index, (occluded, open)) in occluded_ambient
        .pixels
        .iter()
        .zip(&ambient_only.pixels)
        .enumerate()
    {
        let on_floor = inputs.positions.pixels[index][3] as u32 == floor_tag;
        let factor = |channel: usize| f64::from(occluded[channel]) / f64::from(open[channel]);
        // Where the red factor is 1 the correction is clamped: `v` cannot be recovered.
        if !on_floor || open[2] <= 0.005 || factor(0) >= 1.0 - 1e-4 {
            continue;
        }
        let v = visibility_of(factor(0), albedo[0]);
        for (channel, &channel_albedo) in albedo.iter().enumerate().take(3).skip(1) {
            let expected = multibounce(v, channel_albedo).min(1.0);
            let error = (factor(channel) - expected).abs();
            largest = largest.max(error);
            assert!(
                error <= FACTOR_TOLERANCE,
                "pixel {index}, channel {channel}: factor {}, the formula's {expected} at the \
                 red channel's visibility {v}",
                factor(channel)
            );
        }
        judged += 1;
    }
    println!(
        "ssao: the darkest ambient factor is {darkest:.3}; on {judged} occluded floor pixels the \
         green and blue factors are the formula's within {largest:.2e}"
    );
    // The floor around the sphere's and the cube's feet is occluded over thousands of
    // pixels (3,802 measured; the AO map darkens some below the blue channel's floor of
    // 0.005); at least 100 says the check saw the creases at all.
    assert!(judged >= 100, "only {judged} occluded floor pixels judged");
    assert!(
        darkest < 0.9,
        "SSAO darkened no pixel below 0.9 ({darkest})"
    );
}
