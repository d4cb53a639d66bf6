//! The camera's environment map light (`PhongMaterial::environment_light`, SPEC.md
//! "Environment light"): materials converted from `StandardMaterial` (a metal and a
//! dielectric at three roughnesses) and a plain material, lit by the camera's Bevy
//! `EnvironmentMapLight`, each pixel against the reference model
//! (`reference::Material::environment_light`, `environment_light_direction`,
//! `environment_light_level`).
//!
//! Both cubes have one color per face (and, for the specular cube, per level), read through
//! Bevy's sampler, which the test makes trilinear: a lookup returns its face's color
//! wherever its footprint stays on the face, so the level a roughness reads is seen in the
//! color. The roughnesses 1/6, 2/6 and 3/6 read whole levels 1, 2 and 3 of the seven
//! (`r · 6`); a level formula off by a fifth of a level blends two levels' colors, 0.13
//! apart in green. Pixels within half a texel (and 1 %) of a face's edge are left out
//! (Vulkan filters across the edges of a cube's faces). Tolerance: the frame tests'
//! ([`crate::frames::TOLERANCE`]): the term adds two texel reads and a few `f32` products.

use crate::environment::{cube_map, face_texel, spawn_lights};
use crate::frames::SIZE;
use crate::texture_maps::{SrgbDecoding, assert_pixels_follow, lit_color, lit_normal, texels_at};
use bevy::{image::ImageSampler, prelude::*};
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{Harness, SurfaceInputs, pixel_model::mapped_material};
use glam::{DQuat, DVec3};
use std::collections::HashMap;

/// Texels a side of the specular cube's first level, and its mip levels (64 down to 1).
const SPECULAR_SIZE: u32 = 64;
const SPECULAR_LEVELS: u32 = 7;

/// Texels a side of the diffuse cube (one level).
const DIFFUSE_SIZE: u32 = 32;

/// The specular cube's color on face `face` at level `level`: the levels 0.13 apart in
/// green.
fn specular_color(face: u32, level: u32) -> [f32; 4] {
    [
        0.15 + 0.12 * face as f32,
        0.95 - 0.13 * level as f32,
        0.3 + 0.1 * ((face + level) % 4) as f32,
        1.0,
    ]
}

/// The diffuse cube's color on face `face`.
fn diffuse_color(face: u32) -> [f32; 4] {
    [0.8 - 0.1 * face as f32, 0.3 + 0.1 * face as f32, 0.5, 1.0]
}

#[test]
fn the_cameras_environment_map_light_lights_surfaces_as_the_reference_model_says() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_lights(world);
    let mut images = world.resource_mut::<Assets<Image>>();
    let specular = images.add(cube_map(
        SPECULAR_SIZE,
        SPECULAR_LEVELS,
        |face, level, _, _| specular_color(face, level),
    ));
    // Bevy reads both cubes through the diffuse cube's sampler.
    let mut diffuse = cube_map(DIFFUSE_SIZE, 1, |face, _, _, _| diffuse_color(face));
    diffuse.sampler = ImageSampler::linear();
    let diffuse = images.add(diffuse);
    let exposure = f64::from(bevy::camera::Exposure::default().exposure());
    let intensity = 0.9 / exposure as f32;
    let rotation = Quat::from_rotation_y(-0.5) * Quat::from_rotation_x(0.2);
    harness.camera_mut().insert(EnvironmentMapLight {
        diffuse_map: diffuse,
        specular_map: specular,
        intensity,
        rotation,
        affects_lightmapped_mesh_diffuse: true,
    });

    let gold = Color::linear_rgb(1.0, 0.78, 0.34);
    let red = Color::linear_rgb(0.7, 0.1, 0.1);
    let mut objects = Vec::new();
    for (column, perceptual_roughness) in [1.0 / 6.0, 2.0 / 6.0, 3.0 / 6.0].into_iter().enumerate()
    {
        for (row, (base_color, metallic)) in [(gold, 1.0), (red, 0.0)].into_iter().enumerate() {
            let material = PhongMaterial::from(&StandardMaterial {
                base_color,
                metallic,
                perceptual_roughness,
                ..default()
            });
            assert!(material.environment_light && material.ambient_specular);
            objects.push((
                Sphere::new(0.6).mesh().uv(48, 32),
                Transform::from_xyz(1.4 * column as f32 - 1.4, 0.7 - 1.4 * row as f32, 0.0),
                material,
            ));
        }
    }
    // Without the ambient specular: the diffuse cube lights the whole diffuse color, and
    // nothing is reflected.
    objects.push((
        Sphere::new(0.5).mesh().uv(48, 32),
        Transform::from_xyz(-1.4, -1.9, 0.3),
        PhongMaterial {
            environment_light: true,
            perceptual_roughness: 0.5,
            ..PhongMaterial::from(Color::srgb(0.6, 0.7, 0.8))
        },
    ));
    // Without the flag, a material is lit as before.
    objects.push((
        Sphere::new(0.5).mesh().uv(48, 32),
        Transform::from_xyz(0.0, -1.9, 0.3),
        PhongMaterial::from(Color::srgb(0.8, 0.8, 0.8)),
    ));

    let rotation = rotation.as_dquat();
    let weight = f64::from(intensity) * exposure;
    let expected = |material: &PhongMaterial,
                    surface: &reference::SurfacePoint,
                    pixel: usize,
                    inputs: &SurfaceInputs,
                    images: &HashMap<AssetId<Image>, Image>,
                    lights: &reference::Lights| {
        let texels = texels_at(material, inputs, pixel, images, SrgbDecoding::Exact)?;
        let lit = lit_color(material, surface, pixel, inputs, &texels, images, lights)?;
        if !material.environment_light {
            return Some(lit);
        }
        let normal = lit_normal(material, surface, pixel, inputs, images)?;
        let surface = reference::SurfacePoint { normal, ..*surface };
        let mapped = mapped_material(material, pixel, inputs, &texels, images);
        let (irradiance, radiance) = environment_at(material, &surface, rotation)?;
        let environment = mapped.environment_light(&surface, irradiance, radiance);
        Some(lit + environment * weight)
    };
    assert_pixels_follow(harness, objects, "environment light", &expected);
}

/// The diffuse cube's texel along the normal and the specular cube's along the lobe's
/// direction at its level, for `material` at `surface` (its normal the lit one), each cube
/// turned by `rotation`; `None` near a face's edge.
fn environment_at(
    material: &PhongMaterial,
    surface: &reference::SurfacePoint,
    rotation: DQuat,
) -> Option<(DVec3, DVec3)> {
    let normal = surface.normal.normalize();
    let view = (surface.camera - surface.position).normalize();
    let reflected = reference::reflect(-view, normal);
    let roughness = f64::from(material.perceptual_roughness);
    let level = reference::environment_light_level(roughness, SPECULAR_LEVELS);
    assert!(
        (level - level.round()).abs() < 1e-6,
        "a whole level: {level}"
    );
    let level = level.round() as u32;
    let along_lobe = reference::environment_light_direction(normal, reflected, roughness);
    let irradiance = face_texel(
        reference::cube_direction(normal, rotation),
        DIFFUSE_SIZE,
        diffuse_color,
    )?;
    let radiance = face_texel(
        reference::cube_direction(along_lobe, rotation),
        SPECULAR_SIZE >> level,
        |face| specular_color(face, level),
    )?;
    Some((irradiance, radiance))
}
