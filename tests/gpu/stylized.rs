//! Stylized shading: the diffuse modes (wrap, toon bands, a toon ramp), the specular modes
//! (toon spot, off), the rim light (everywhere, on the lit side) and the hemisphere light,
//! rendered on the render device and compared per pixel with the reference model
//! (`reference::diffuse_factor`, `reference::ToonRamp`, `reference::highlight_factor`,
//! `reference::rim_factor`, `reference::Hemisphere`) on each pixel's inputs.
//!
//! A hard toon step is a discontinuity: where a light's `N·L` (for bands and ramps) or
//! highlight (for a spot) is within 10⁻⁴ of a step, the device's `f32` may fall on either
//! side, and the pixel is not judged (`reference::near_a_step`, `ToonRamp::near_an_edge`).
//! Tolerance: the frame tests' ([`TOLERANCE`]).

use crate::frames::SIZE;
use crate::texture_maps::{
    TEXELS, assert_pixels_follow, expected_color, float_map, spawn_map_lights, toon_ramp,
};
use bevy::prelude::*;
use bevy_phong::{DiffuseMode, SpecularMode, prelude::*, reference};
use glam::DVec3;

/// The directions toward every light of `lights` from `position`.
pub(crate) fn toward_lights(lights: &reference::Lights, position: DVec3) -> Vec<DVec3> {
    lights
        .lights
        .iter()
        .map(|light| match *light {
            reference::Light::Directional { direction, .. } => -direction.normalize(),
            reference::Light::Point { position: at, .. }
            | reference::Light::Spot { position: at, .. } => (at - position).normalize(),
        })
        .collect()
}

#[test]
fn stylized_modes_follow_the_reference_model() {
    let mut harness = bevy_phong_headless::Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    world.insert_resource(PhongHemisphereLight {
        sky_color: Color::linear_rgb(0.25, 0.3, 0.45),
        ground_color: Color::linear_rgb(0.15, 0.08, 0.02),
        up: Vec3::new(0.2, 1.0, -0.1),
    });
    // Four levels, from the far side (N·L < −1/2) to the light (N·L ≥ 1/2), in the middle
    // row (`TEXELS / 2`), which the ramp is read at; the other rows hold other levels, so
    // that a ramp read at another row is seen.
    let levels = [0.1, 0.35, 0.7, 1.0];
    let ramp = world.resource_mut::<Assets<Image>>().add(float_map(|x, y| {
        let level = levels[x as usize];
        let red = if y == TEXELS / 2 {
            level
        } else {
            1.0 - 0.5 * level
        };
        [red, 0.0, 0.0, 1.0]
    }));
    let sphere = || Sphere::new(0.7).mesh().uv(48, 32);
    let objects = [
        (
            Vec3::new(-2.2, 1.7, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.9, 0.6, 0.5),
                diffuse_mode: DiffuseMode::Wrap(0.5),
                specular_model: SpecularModel::BlinnPhong,
                shininess: 60.0,
                ..default()
            },
        ),
        (
            Vec3::new(0.0, 1.7, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.4, 0.7, 0.9),
                diffuse_mode: DiffuseMode::Toon {
                    bands: 4,
                    smoothing: 0.0,
                },
                specular_mode: SpecularMode::Toon { smoothing: 0.0 },
                shininess: 30.0,
                ..default()
            },
        ),
        (
            Vec3::new(2.2, 1.7, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.6, 0.9, 0.4),
                diffuse_mode: DiffuseMode::Toon {
                    bands: 3,
                    smoothing: 0.3,
                },
                specular_mode: SpecularMode::Toon { smoothing: 0.2 },
                shininess: 20.0,
                ..default()
            },
        ),
        (
            Vec3::new(-2.2, 0.0, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.8, 0.8, 0.8),
                specular_mode: SpecularMode::Off,
                ..default()
            },
        ),
        // A rim everywhere, and one on the lit side only.
        (
            Vec3::new(0.0, 0.0, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.5, 0.4, 0.7),
                rim_color: LinearRgba::rgb(0.3, 0.6, 1.0),
                rim_strength: 1.5,
                rim_power: 3.0,
                ..default()
            },
        ),
        (
            Vec3::new(2.2, 0.0, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.7, 0.5, 0.3),
                diffuse_mode: DiffuseMode::Wrap(0.3),
                rim_color: LinearRgba::rgb(1.0, 0.9, 0.6),
                rim_power: 1.5,
                rim_lit_side: true,
                ..default()
            },
        ),
        // A toon ramp (under WebGL2, where it is not bound, the bands), with a smooth and a
        // toon highlight.
        (
            Vec3::new(-1.1, -1.7, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.9, 0.5, 0.6),
                diffuse_mode: DiffuseMode::Toon {
                    bands: 2,
                    smoothing: 0.0,
                },
                toon_ramp_texture: Some(ramp.clone()),
                ..default()
            },
        ),
        (
            Vec3::new(1.1, -1.7, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.5, 0.8, 0.9),
                diffuse_mode: DiffuseMode::Toon {
                    bands: 3,
                    smoothing: 0.2,
                },
                specular_mode: SpecularMode::Toon { smoothing: 0.1 },
                toon_ramp_texture: Some(ramp),
                ..default()
            },
        ),
    ]
    .map(|(at, material)| (sphere(), Transform::from_translation(at), material));
    assert_pixels_follow(
        harness,
        objects,
        "stylized modes",
        &|material, surface, pixel, inputs, images, lights| {
            let reference_material = reference::Material::from(material);
            let ramp = toon_ramp(material, inputs, images);
            let normal = reference::normalize_or_zero(surface.normal);
            let view = reference::normalize_or_zero(surface.camera - surface.position);
            for to_light in toward_lights(lights, surface.position) {
                let n_dot_l = normal.dot(to_light);
                let h = reference::highlight(
                    reference_material.specular_model,
                    normal,
                    to_light,
                    view,
                    reference_material.shininess,
                );
                if ramp
                    .as_ref()
                    .is_some_and(|ramp| ramp.near_an_edge(n_dot_l, 1e-4))
                    || bevy_phong::testing::near_a_step(
                        reference_material.diffuse_mode,
                        reference_material.specular_mode,
                        n_dot_l,
                        h,
                        1e-4,
                    )
                {
                    return None;
                }
            }
            expected_color(material, surface, pixel, inputs, images, lights)
        },
    );
}
