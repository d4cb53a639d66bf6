//! Environment maps: a cube map reflected or refracted into Phong surfaces, joined to the
//! lit color by each combine mode, compared per pixel with the reference model
//! (`reference::environment_direction`, `environment_lod`, `with_environment`).
//!
//! The cube has 8 texels a side and two mip levels, nearest-sampled, so the texel each
//! pixel reads is known from the direction (Vulkan's cube face rules) and the level from
//! the material's shininess; pixels within 1/100 texel of a texel's or a face's edge are
//! left out. Tolerance: the frame tests' (`TOLERANCE`); the lookup adds a blend in `f32`.
//! Under WebGL2's limits the environment map is left out (`render::binds_every_map`): there
//! the test checks that the surfaces are drawn as without it.

use crate::frames::SIZE;
use crate::texture_maps::{
    SrgbDecoding, assert_pixels_follow, float_map, lit_color, lit_normal, texels_at,
};
use bevy::{
    asset::RenderAssetUsages,
    image::{Image, ImageSampler},
    prelude::*,
    render::render_resource::{
        Extent3d, TextureDescriptor, TextureDimension, TextureFormat, TextureUsages,
        TextureViewDescriptor, TextureViewDimension,
    },
};
use bevy_phong::{EnvironmentCombine, prelude::*, reference};
use bevy_phong_headless::{Harness, SurfaceInputs};
use glam::{DVec3, DVec4};
use std::collections::HashMap;

/// Texels a side of the cube's first level.
const CUBE_SIZE: u32 = 8;

/// The texel of face `face` at `(x, y)` of level `level`, RGBA in `[0, 1]`.
fn cube_texel(face: u32, level: u32, x: u32, y: u32) -> [f32; 4] {
    let hash = (x * 5 + y * 3 + face * 7 + level * 11) % 9;
    let level = hash as f32 / 8.0;
    [
        0.2 + 0.8 * level,
        0.9 - 0.6 * level,
        (face as f32 + 1.0) / 7.0,
        1.0,
    ]
}

/// A cube map of `CUBE_SIZE` texels a side with two levels, stored layer by layer (each
/// face's levels together, as Bevy's images order them), nearest-sampled.
fn cube_map() -> Image {
    let mut data = Vec::new();
    for face in 0..6 {
        for level in 0..2 {
            let size = CUBE_SIZE >> level;
            for y in 0..size {
                for x in 0..size {
                    let texel = cube_texel(face, level, x, y);
                    data.extend(texel.map(|channel| (channel * 255.0).round() as u8));
                }
            }
        }
    }
    Image {
        data: Some(data),
        texture_descriptor: TextureDescriptor {
            label: None,
            size: Extent3d {
                width: CUBE_SIZE,
                height: CUBE_SIZE,
                depth_or_array_layers: 6,
            },
            mip_level_count: 2,
            sample_count: 1,
            dimension: TextureDimension::D2,
            format: TextureFormat::Rgba8Unorm,
            usage: TextureUsages::TEXTURE_BINDING | TextureUsages::COPY_DST,
            view_formats: &[],
        },
        sampler: ImageSampler::nearest(),
        texture_view_descriptor: Some(TextureViewDescriptor {
            dimension: Some(TextureViewDimension::Cube),
            ..default()
        }),
        asset_usage: RenderAssetUsages::default(),
        ..Image::default()
    }
}

/// The texel of level `level` that a nearest lookup along `direction` reads (Vulkan's
/// cube map face selection and coordinates), as the stored bytes give it; `None` within
/// 1/100 texel of a texel's edge or 1/1000 of a face's.
fn cube_texel_at(direction: DVec3, level: u32) -> Option<DVec4> {
    let [x, y, z] = direction.to_array();
    let (ax, ay, az) = (x.abs(), y.abs(), z.abs());
    // (face, sc, tc, ma) for +X, -X, +Y, -Y, +Z, -Z.
    let (face, sc, tc, ma) = if ax >= ay && ax >= az {
        if x > 0.0 {
            (0, -z, -y, ax)
        } else {
            (1, z, -y, ax)
        }
    } else if ay >= az {
        if y > 0.0 {
            (2, x, z, ay)
        } else {
            (3, x, -z, ay)
        }
    } else if z > 0.0 {
        (4, x, -y, az)
    } else {
        (5, -x, -y, az)
    };
    let size = f64::from(CUBE_SIZE >> level);
    let mut texel = [0u32; 2];
    for (axis, coordinate) in [sc, tc].into_iter().enumerate() {
        let s = coordinate / ma;
        if s.abs() > 0.999 {
            return None;
        }
        let scaled = (s + 1.0) / 2.0 * size;
        let fraction = scaled - scaled.floor();
        if !(0.01..=0.99).contains(&fraction) {
            return None;
        }
        texel[axis] = scaled.floor() as u32;
    }
    let stored = cube_texel(face, level, texel[0], texel[1])
        .map(|channel| f64::from((channel * 255.0).round() as u8) / 255.0);
    Some(DVec4::from_array(stored))
}

#[test]
fn environment_maps_follow_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::srgb(0.2, 0.2, 0.25),
    });
    world.spawn((
        PhongPointLight {
            color: Color::srgb(0.9, 0.8, 0.7),
            ..default()
        },
        Transform::from_xyz(-1.0, 2.5, 3.0),
    ));
    let mut images = world.resource_mut::<Assets<Image>>();
    let cube = images.add(cube_map());
    let specular_map = images.add(float_map(|x, y| {
        [0.2 + 0.25 * ((x + y) % 4) as f32, 0.5, 0.5, 1.0]
    }));
    // A lobe one level-1 texel wide (see `reference::environment_lod`).
    let level_one = (CUBE_SIZE as f32 / core::f32::consts::PI).powi(2) - 1.0;
    let objects = [
        (
            Sphere::new(1.0).mesh().uv(48, 32),
            Transform::from_xyz(-2.3, 0.0, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.9, 0.8, 0.7),
                environment_map: Some(cube.clone()),
                reflectivity: 0.8,
                shininess: 1e4,
                ..default()
            },
        ),
        (
            Cuboid::new(1.3, 1.3, 1.3).into(),
            Transform::from_xyz(0.0, 0.0, 0.0).with_rotation(Quat::from_euler(
                EulerRot::YXZ,
                0.6,
                0.5,
                0.0,
            )),
            PhongMaterial {
                base_color: Color::srgb(0.4, 0.5, 0.9),
                specular_texture: Some(specular_map),
                environment_map: Some(cube.clone()),
                environment_combine: EnvironmentCombine::Mix,
                reflectivity: 0.7,
                shininess: level_one,
                ..default()
            },
        ),
        (
            Sphere::new(1.0).mesh().uv(48, 32),
            Transform::from_xyz(2.3, 0.0, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.3, 0.3, 0.3),
                environment_map: Some(cube),
                environment_combine: EnvironmentCombine::Add,
                reflectivity: 0.5,
                refraction_ratio: Some(0.66),
                shininess: 1e4,
                ..default()
            },
        ),
    ];
    let expected = |material: &PhongMaterial,
                    surface: &reference::SurfacePoint,
                    pixel: usize,
                    inputs: &SurfaceInputs,
                    images: &HashMap<AssetId<Image>, Image>,
                    lights: &reference::Lights| {
        let texels = texels_at(material, inputs, pixel, images, SrgbDecoding::Exact)?;
        let lit = lit_color(material, surface, pixel, inputs, &texels, images, lights)?;
        // Where the device does not bind every map (WebGL2), the environment is left out.
        if !inputs.every_map_bound {
            return Some(lit);
        }
        let normal = lit_normal(material, surface, pixel, inputs, images)?;
        let lit_surface = reference::SurfacePoint { normal, ..*surface };
        let ratio = material.refraction_ratio.map(f64::from);
        let direction = reference::environment_direction(&lit_surface, ratio);
        let lod = reference::environment_lod(f64::from(material.shininess), CUBE_SIZE.into());
        // Nearest between levels: the nearer level, of the two there are.
        let level = (lod + 0.5).floor().min(1.0) as u32;
        assert!(
            (lod - lod.round()).abs() < 1e-3,
            "a level, not between two: {lod}"
        );
        let environment = cube_texel_at(direction, level)?.truncate();
        let mask = texels.specular.map_or(1.0, |texel| texel.x);
        let strength = mask * f64::from(material.reflectivity);
        Some(reference::with_environment(
            lit,
            environment,
            strength,
            material.environment_combine,
        ))
    };
    assert_pixels_follow(harness, objects, "environment maps", &expected);
}
