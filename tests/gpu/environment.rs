//! Environment maps: a cube map reflected or refracted into Phong surfaces, joined to the
//! lit color by each combine mode, compared per pixel with the reference model
//! (`reference::environment_direction`, `environment_lod`, `with_environment`).
//!
//! The cube has 8 texels a side and three mip levels, nearest-sampled, so the texel each
//! pixel reads is known from the direction (Vulkan's cube face rules) and the level from
//! the material's shininess (the nearest level to the formula's: the objects read levels
//! 0, 1 and 2, the last two at 0.05 of a level from the boundary between levels 1 and 2,
//! one on each side, so that a level formula off by more than 0.05 of a level, either way,
//! reads another level's texels); pixels within 1/100 texel of a
//! texel's or a face's edge are left out. Tolerance: the frame tests' (`TOLERANCE`); the lookup adds a blend in `f32`.
//! Under WebGL2's limits the environment map is left out (`render::binds_every_map`): there
//! the test checks that the surfaces are drawn as without it.
//!
//! The camera's Bevy `EnvironmentMapLight` is read through Bevy's own sampler, which filters
//! linearly: its cube has one color per face and level, so that a lookup at a whole level
//! returns that color wherever its footprint stays on the face; pixels within half a texel
//! (and 1 %) of a face's edge are left out (Vulkan filters across the edges of a cube's
//! faces).

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
use bevy_phong_headless::{Harness, HarnessCamera, SurfaceInputs};
use glam::{DVec3, DVec4};
use std::collections::HashMap;

/// Texels a side of the cube's first level.
const CUBE_SIZE: u32 = 8;

/// The mip levels of the test cubes.
const CUBE_LEVELS: u32 = 3;

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

/// A cube map of `cube_size` texels a side with `levels` mip levels whose texel `(x, y)` of
/// face `face` at level `level` is `texel(face, level, x, y)`, stored layer by layer (each
/// face's levels together, as Bevy's images order them), nearest-sampled.
pub(crate) fn cube_map(
    cube_size: u32,
    levels: u32,
    texel: impl Fn(u32, u32, u32, u32) -> [f32; 4],
) -> Image {
    let mut data = Vec::new();
    for face in 0..6 {
        for level in 0..levels {
            let size = cube_size >> level;
            for y in 0..size {
                for x in 0..size {
                    let texel = texel(face, level, x, y);
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
                width: cube_size,
                height: cube_size,
                depth_or_array_layers: 6,
            },
            mip_level_count: levels,
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

/// The face a lookup along `direction` reads and its coordinates `(s, t)` on it, each in
/// `[-1, 1]` (Vulkan's cube map face selection).
pub(crate) fn cube_face(direction: DVec3) -> (u32, [f64; 2]) {
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
    (face, [sc / ma, tc / ma])
}

/// The texel of level `level` that a nearest lookup along `direction` reads, as the stored
/// bytes give it; `None` within 1/100 texel of a texel's edge or 1/1000 of a face's.
fn cube_texel_at(direction: DVec3, level: u32) -> Option<DVec4> {
    let (face, coordinates) = cube_face(direction);
    let size = f64::from(CUBE_SIZE >> level);
    let mut texel = [0u32; 2];
    for (axis, s) in coordinates.into_iter().enumerate() {
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

/// The lights of the environment tests: ambient and a point light.
pub(crate) fn spawn_lights(world: &mut World) {
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
}

/// Three reflective objects, each given its environment by `environment`: a mirror-like
/// sphere (Multiply, level 0), a dull cube masked by a specular map (Mix, level 1 of a cube
/// `cube_size` texels a side, its formula giving 1.45) and a duller refracting sphere (Add,
/// level 2, its formula giving 1.55).
fn reflective_objects(
    world: &mut World,
    cube_size: u32,
    environment: impl Fn(PhongMaterial) -> PhongMaterial,
) -> [(Mesh, Transform, PhongMaterial); 3] {
    let specular_map = world.resource_mut::<Assets<Image>>().add(float_map(|x, y| {
        [0.2 + 0.25 * ((x + y) % 4) as f32, 0.5, 0.5, 1.0]
    }));
    // A lobe one texel of level `m` wide: `environment_lod` (`log2(size / (π/2 · √(n + 1)))`)
    // is `m` at `n = (2 · size / (π · 2^m))² − 1`, for any real `m`.
    let at_level =
        |m: f32| (2.0 * cube_size as f32 / (core::f32::consts::PI * 2f32.powf(m))).powi(2) - 1.0;
    [
        (
            Sphere::new(1.0).mesh().uv(48, 32),
            Transform::from_xyz(-2.3, 0.0, 0.0),
            environment(PhongMaterial {
                base_color: Color::srgb(0.9, 0.8, 0.7),
                reflectivity: 0.8,
                shininess: 1e4,
                ..default()
            }),
        ),
        (
            Cuboid::new(1.3, 1.3, 1.3).into(),
            Transform::from_xyz(0.0, 0.0, 0.0).with_rotation(Quat::from_euler(
                EulerRot::YXZ,
                0.6,
                0.5,
                0.0,
            )),
            environment(PhongMaterial {
                base_color: Color::srgb(0.4, 0.5, 0.9),
                specular_texture: Some(specular_map),
                environment_combine: EnvironmentCombine::Mix,
                reflectivity: 0.7,
                shininess: at_level(1.45),
                ..default()
            }),
        ),
        (
            Sphere::new(1.0).mesh().uv(48, 32),
            Transform::from_xyz(2.3, 0.0, 0.0),
            environment(PhongMaterial {
                base_color: Color::srgb(0.3, 0.3, 0.3),
                environment_combine: EnvironmentCombine::Add,
                reflectivity: 0.5,
                refraction_ratio: Some(0.66),
                shininess: at_level(1.55),
                ..default()
            }),
        ),
    ]
}

/// The color `color(face)` as stored (8-bit) of the face a linear lookup along `direction`
/// (in the cube's frame) reads, on a cube of one color per face and `size` texels a side;
/// `None` within half a texel (2 / size in the face's coordinates, halved) and 1 % of a
/// face's edge, where linear filtering reaches the next face.
pub(crate) fn face_texel(
    direction: DVec3,
    size: u32,
    color: impl Fn(u32) -> [f32; 4],
) -> Option<DVec3> {
    let (face, coordinates) = cube_face(direction);
    let margin = 1.0 - 1.01 / f64::from(size);
    if coordinates.iter().any(|s| s.abs() > margin) {
        return None;
    }
    let stored = color(face).map(|channel| f64::from((channel * 255.0).round() as u8) / 255.0);
    Some(DVec4::from_array(stored).truncate())
}

/// The environment a test's surfaces reflect: whether it is drawn at all, its cube's size
/// (texels a side) and its color along a world direction at a level (`None` where it cannot
/// be judged).
struct Environment<'a> {
    drawn: bool,
    cube_size: u32,
    color_at: &'a dyn Fn(DVec3, u32) -> Option<DVec3>,
}

/// The reference color of a pixel of a reflective material in `environment`, or the lit
/// color alone where it is not drawn (the environment left out).
fn reflected_color(
    material: &PhongMaterial,
    surface: &reference::SurfacePoint,
    pixel: usize,
    inputs: &SurfaceInputs,
    images: &HashMap<AssetId<Image>, Image>,
    lights: &reference::Lights,
    environment: &Environment,
) -> Option<DVec3> {
    let texels = texels_at(material, inputs, pixel, images, SrgbDecoding::Exact)?;
    let lit = lit_color(material, surface, pixel, inputs, &texels, images, lights)?;
    if !environment.drawn {
        return Some(lit);
    }
    let normal = lit_normal(material, surface, pixel, inputs, images)?;
    let lit_surface = reference::SurfacePoint { normal, ..*surface };
    let ratio = material.refraction_ratio.map(f64::from);
    let direction = reference::environment_direction(&lit_surface, ratio);
    let lod =
        reference::environment_lod(f64::from(material.shininess), environment.cube_size.into());
    // The nearer level, of those there are.
    let level = (lod + 0.5).floor().min(f64::from(CUBE_LEVELS - 1)) as u32;
    assert!(
        (lod.fract() - 0.5).abs() > 0.04,
        "a level clear of the boundary between two: {lod}"
    );
    let environment = (environment.color_at)(direction, level)?;
    let mask = texels.specular.map_or(1.0, |texel| texel.x);
    let strength = mask * f64::from(material.reflectivity);
    Some(reference::with_environment(
        lit,
        environment,
        strength,
        material.environment_combine,
    ))
}

#[test]
fn environment_maps_follow_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_lights(world);
    let cube =
        world
            .resource_mut::<Assets<Image>>()
            .add(cube_map(CUBE_SIZE, CUBE_LEVELS, cube_texel));
    let objects = reflective_objects(world, CUBE_SIZE, |material| PhongMaterial {
        environment_map: Some(cube.clone()),
        ..material
    });
    let expected = |material: &PhongMaterial,
                    surface: &reference::SurfacePoint,
                    pixel: usize,
                    inputs: &SurfaceInputs,
                    images: &HashMap<AssetId<Image>, Image>,
                    lights: &reference::Lights| {
        // Where the device does not bind every map (WebGL2), the environment is left out.
        let drawn = inputs.every_map_bound;
        // The material's cube in Bevy's cube frame, as the camera's below (no rotation).
        let environment_at = |direction, level| {
            let in_cube = reference::cube_direction(direction, glam::DQuat::IDENTITY);
            Some(cube_texel_at(in_cube, level)?.truncate())
        };
        reflected_color(
            material,
            surface,
            pixel,
            inputs,
            images,
            lights,
            &Environment {
                drawn,
                cube_size: CUBE_SIZE,
                color_at: &environment_at,
            },
        )
    };
    assert_pixels_follow(harness, objects, "environment maps", &expected);
}

/// Texels a side of the first level of the camera's cube: many, so that few pixels read
/// near a face's edge.
const CAMERA_CUBE_SIZE: u32 = 32;

/// One color per face and level of the camera's cube.
fn face_color(face: u32, level: u32) -> [f32; 4] {
    [
        (face as f32 + 1.0) / 7.0,
        0.9 - 0.3 * level as f32,
        1.0 - (face as f32) / 8.0,
        1.0,
    ]
}

#[test]
fn the_cameras_environment_map_light_is_reflected_as_the_materials_own_map() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_lights(world);
    let cube = world.resource_mut::<Assets<Image>>().add(cube_map(
        CAMERA_CUBE_SIZE,
        CUBE_LEVELS,
        |face, level, _, _| face_color(face, level),
    ));
    let exposure = f64::from(bevy::camera::Exposure::default().exposure());
    let intensity = 1.2 / exposure as f32;
    let rotation = Quat::from_rotation_y(0.7) * Quat::from_rotation_x(0.3);
    let camera = world
        .query_filtered::<Entity, With<HarnessCamera>>()
        .single(world)
        .expect("the harness's camera");
    world.entity_mut(camera).insert(EnvironmentMapLight {
        diffuse_map: cube.clone(),
        specular_map: cube,
        intensity,
        rotation,
        affects_lightmapped_mesh_diffuse: true,
    });
    let mut objects = reflective_objects(world, CAMERA_CUBE_SIZE, |material| PhongMaterial {
        camera_environment: true,
        ..material
    })
    .to_vec();
    // A material that does not ask for it is lit as before.
    objects.push((
        Sphere::new(0.7).mesh().uv(32, 16),
        Transform::from_xyz(0.0, -1.8, 0.5),
        PhongMaterial::from(Color::srgb(0.8, 0.8, 0.8)),
    ));
    let rotation = rotation.as_dquat();
    let expected = |material: &PhongMaterial,
                    surface: &reference::SurfacePoint,
                    pixel: usize,
                    inputs: &SurfaceInputs,
                    images: &HashMap<AssetId<Image>, Image>,
                    lights: &reference::Lights| {
        let environment_at = |direction, level: u32| {
            let turned = reference::cube_direction(direction, rotation);
            let texel = face_texel(turned, CAMERA_CUBE_SIZE >> level, |face| {
                face_color(face, level)
            })?;
            Some(texel * f64::from(intensity) * exposure)
        };
        reflected_color(
            material,
            surface,
            pixel,
            inputs,
            images,
            lights,
            &Environment {
                drawn: material.camera_environment,
                cube_size: CAMERA_CUBE_SIZE,
                color_at: &environment_at,
            },
        )
    };
    assert_pixels_follow(harness, objects, "camera environment", &expected);
}
