//! Bevy's `DistanceFog` on a camera applies to `PhongMaterial` as to `StandardMaterial`:
//! every falloff, with the inscattering of the Phong directional lights (two of them).

use bevy::prelude::*;
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::Harness;

use crate::frames::{SIZE, TOLERANCE, spawn_objects};

/// The fogs compared: each falloff Bevy has, the atmospheric one with directional
/// inscattering from a light shining toward the camera.
fn fogs() -> [(&'static str, DistanceFog); 4] {
    let fog = |falloff, directional_light_color| DistanceFog {
        color: Color::linear_rgba(0.35, 0.4, 0.5, 0.9),
        directional_light_color,
        directional_light_exponent: 8.0,
        falloff,
    };
    [
        (
            "linear",
            fog(
                FogFalloff::Linear {
                    start: 4.0,
                    end: 12.0,
                },
                Color::NONE,
            ),
        ),
        (
            "exponential",
            fog(FogFalloff::Exponential { density: 0.15 }, Color::NONE),
        ),
        (
            "exponential_squared",
            fog(
                FogFalloff::ExponentialSquared { density: 0.12 },
                Color::NONE,
            ),
        ),
        (
            "atmospheric_with_inscattering",
            fog(
                FogFalloff::Atmospheric {
                    extinction: Vec3::new(0.10, 0.12, 0.15),
                    inscattering: Vec3::new(0.08, 0.10, 0.14),
                },
                Color::linear_rgba(1.0, 0.9, 0.7, 0.8),
            ),
        ),
    ]
}

/// Each pixel's color is the reference model's, seen through the fog at the pixel's own
/// distance from the camera (Bevy's fog formulas on the view distance, `reference::fogged`),
/// except on the sphere, whose material turns fog off (`fog_enabled: false`): there it is
/// the reference model's color as it is. The box is unlit: its base color is fogged as a lit
/// color is (SPEC.md, "Unlit"). Tolerance: the frames' (`TOLERANCE`); the fog adds
/// an `exp` and a blend in `f32`, a few roundings of 6e-8 each.
#[test]
fn distance_fog_matches_the_fog_formula_on_each_pixels_view_distance() {
    let mut harness = Harness::new(SIZE, SIZE);
    let materials = spawn_objects(&mut harness);
    let mut assets = harness.world_mut().resource_mut::<Assets<PhongMaterial>>();
    assets.get_mut(&materials[1]).unwrap().fog_enabled = false;
    assets.get_mut(&materials[2]).unwrap().unlit = true;
    harness.world_mut().spawn((
        PhongDirectionalLight {
            color: Color::linear_rgb(0.7, 0.6, 0.5),
            ..default()
        },
        Transform::default().looking_to(Vec3::new(0.3, -0.3, 1.0), Vec3::Y),
    ));
    // A second directional light toward the camera: the inscattering sums every one.
    harness.world_mut().spawn((
        PhongDirectionalLight {
            color: Color::linear_rgb(0.2, 0.3, 0.6),
            ..default()
        },
        Transform::default().looking_to(Vec3::new(-0.5, -0.2, 1.0), Vec3::Y),
    ));
    harness.world_mut().spawn((
        PhongPointLight {
            color: Color::linear_rgb(0.9, 0.9, 1.0),
            ..default()
        },
        Transform::from_xyz(1.0, 3.0, 2.0),
    ));
    harness.settle();
    let inputs = harness.capture_inputs();
    let lights = harness.reference_lights();
    let camera = harness.camera_position();
    for (case, fog) in fogs() {
        harness.camera_mut().insert(fog.clone());
        harness.settle();
        let rendered = harness.render_next_frame();
        let comparison = harness.compare_with(&rendered, &inputs, |material, surface| {
            let model = reference::Material::from(material);
            let lit = if material.unlit {
                model.unlit_color()
            } else {
                reference::shade(surface, &model, &lights)
            };
            if !material.fog_enabled {
                return Some(lit);
            }
            Some(reference::fogged(
                lit,
                surface.position - camera,
                &fog,
                &lights,
            ))
        });
        comparison.assert_within(&format!("fog_{case}"), TOLERANCE);
    }
}
