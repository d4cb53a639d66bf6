//! Screen-space ambient occlusion darkens the ambient term of `PhongMaterial`, as it does
//! `StandardMaterial`'s, and nothing else.

use bevy::{pbr::ScreenSpaceAmbientOcclusion, prelude::*, render::renderer::RenderDevice};
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;

use super::assert_same_frame;
use crate::frames::{SIZE, TOLERANCE, spawn_objects};

/// Bevy's SSAO needs 5 storage textures per shader stage (its compute passes); without
/// them (WebGL2) it is not loaded and the frame is drawn unoccluded.
const SSAO_STORAGE_TEXTURES: u32 = 5;

/// With `ScreenSpaceAmbientOcclusion` on the camera:
/// - lit by the directional light alone, the frame is the one without SSAO (occlusion
///   never touches direct light);
/// - lit by the ambient light alone, each pixel is the unoccluded one times a factor in
///   `[0, 1]` per channel (Bevy's visibility with its multi-bounce correction), below 0.9
///   in the creases where the sphere meets the floor.
///
/// Where the device cannot run Bevy's SSAO, both frames equal those without it.
#[test]
fn ssao_darkens_the_ambient_term_only() {
    let mut harness = Harness::new(SIZE, SIZE);
    spawn_objects(&mut harness);
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
    println!("ssao: the darkest ambient factor is {darkest:.3}");
    assert!(
        darkest < 0.9,
        "SSAO darkened no pixel below 0.9 ({darkest})"
    );
}
