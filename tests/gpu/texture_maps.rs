//! Texture maps: meshes with base color, specular, emissive and normal maps rendered on the
//! render device and compared with the reference model given each pixel's texels
//! (`reference::Material::mapped`, `reference::mapped_normal`).
//!
//! The maps are small `Rgba32Float` images sampled with nearest filtering, so the texel a
//! pixel received is known exactly from its UV (read back by `SurfaceInputsMaterial`);
//! pixels within 1/100 texel of a texel's edge, where the GPU's rounding of `uv · size` may
//! pick the neighbour, are left out. Tolerance: as the frame tests ([`TOLERANCE`]): the
//! texel products add one `f32` rounding each, and the mapped normal a few more before
//! it is normalized.

use crate::frames::{SIZE, TOLERANCE};
use crate::shading_normals::tangent_sphere;
use crate::surface_inputs::with_second_uvs;
use bevy::{
    asset::RenderAssetUsages,
    image::{Image, ImageSampler},
    mesh::UvChannel,
    prelude::*,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};
use bevy_phong::{prelude::*, reference};
pub(crate) use bevy_phong_headless::pixel_model::{
    SrgbDecoding, expected_color, lit_color, lit_normal, loaded_images, masked_out, output_alpha,
    texel_at, texels_at, toon_ramp, vertex_color,
};
use bevy_phong_headless::{FloatImage, Harness, SurfaceInputs};
use glam::DVec3;
use std::collections::HashMap;

/// Texels per side of every map this file makes.
pub(crate) const TEXELS: u32 = 4;

/// A `TEXELS`² map with nearest filtering whose texel `(x, y)` is `texel(x, y)` (each
/// channel in `[0, 1]`), stored as `Rgba8Unorm`: the 8-bit format games ship, which every
/// device filters (WebGL2 cannot filter 32-bit floats). The reference reads the stored
/// bytes, so the rounding to 1/255 is in both.
pub(crate) fn float_map(texel: impl Fn(u32, u32) -> [f32; 4]) -> Image {
    let data: Vec<u8> = (0..TEXELS * TEXELS)
        .flat_map(|index| texel(index % TEXELS, index / TEXELS))
        .map(|channel| (channel.clamp(0.0, 1.0) * 255.0).round() as u8)
        .collect();
    let mut image = Image::new(
        Extent3d {
            width: TEXELS,
            height: TEXELS,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8Unorm,
        RenderAssetUsages::default(),
    );
    image.sampler = ImageSampler::nearest();
    image
}

/// A value in `[low, high]` that varies from texel to texel and channel to channel.
fn scatter(x: u32, y: u32, channel: u32, low: f32, high: f32) -> f32 {
    let hash = (x * 7 + y * 13 + channel * 5 + 3) % 11;
    low + (high - low) * hash as f32 / 10.0
}

/// A map whose channels vary from texel to texel within `[low, high]`.
pub(crate) fn color_map(low: f32, high: f32) -> Image {
    float_map(|x, y| [0, 1, 2, 3].map(|channel| scatter(x, y, channel, low, high)))
}

/// Tangent-space normals tilted up to ~50° from the surface normal, encoded as `(n + 1) / 2`.
pub(crate) fn normal_map() -> Image {
    float_map(|x, y| {
        let n = Vec3::new(
            scatter(x, y, 0, -0.6, 0.6),
            scatter(x, y, 1, -0.6, 0.6),
            1.0,
        )
        .normalize();
        let encoded = (n + 1.0) / 2.0;
        [encoded.x, encoded.y, encoded.z, 1.0]
    })
}

/// The lights of the map tests: ambient, a directional light and a point light.
pub(crate) fn spawn_map_lights(world: &mut World) {
    world.insert_resource(PhongAmbientLight {
        color: Color::srgb(0.2, 0.2, 0.25),
    });
    world.spawn((
        PhongDirectionalLight {
            color: Color::srgb(0.7, 0.7, 0.6),
            ..default()
        },
        Transform::from_xyz(1.0, 2.0, 1.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    world.spawn((
        PhongPointLight {
            color: Color::srgb(0.9, 0.5, 0.3),
            decay: Decay::new(1.0, 0.09, 0.032),
            ..default()
        },
        Transform::from_xyz(-1.5, 1.5, 2.5),
    ));
}

/// What a pixel should show, given its material, surface point, index, captured inputs,
/// the app's images and the lights: `None` where it cannot be judged.
pub(crate) type ExpectedColor<'a> = dyn Fn(
        &PhongMaterial,
        &reference::SurfacePoint,
        usize,
        &SurfaceInputs,
        &HashMap<AssetId<Image>, Image>,
        &reference::Lights,
    ) -> Option<DVec3>
    + 'a;

/// Spawns each of `objects`: a mesh at a place, drawn with a material.
pub(crate) fn spawn_objects(
    world: &mut World,
    objects: impl IntoIterator<Item = (Mesh, Transform, PhongMaterial)>,
) {
    for (mesh, transform, material) in objects {
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
        world.spawn((Mesh3d(mesh), MeshMaterial3d(material), transform));
    }
}

/// Spawns `objects`, renders a frame and compares every pixel with the reference model on the
/// harness's scene as spawned (`Harness::compare`: its lights with their cookies, lighting per
/// vertex); at most a fifth of the lit pixels may go unjudged. Returns the frame and its
/// captured inputs.
pub(crate) fn assert_scene_follows(
    harness: &mut Harness,
    objects: impl IntoIterator<Item = (Mesh, Transform, PhongMaterial)>,
    name: &str,
) -> (FloatImage, SurfaceInputs) {
    spawn_objects(harness.world_mut(), objects);
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    let comparison = harness.compare(&rendered, &inputs);
    comparison.assert_within(name, TOLERANCE);
    comparison.assert_mostly_judged(name);
    (rendered, inputs)
}

/// Spawns `objects`, renders a frame, captures its inputs with the maps' and compares every
/// pixel with `expected`; at most a fifth of the lit pixels may go unjudged.
pub(crate) fn assert_pixels_follow(
    mut harness: Harness,
    objects: impl IntoIterator<Item = (Mesh, Transform, PhongMaterial)>,
    name: &str,
    expected: &ExpectedColor,
) {
    spawn_objects(harness.world_mut(), objects);
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    let lights = harness.reference_lights();
    let images = loaded_images(&mut harness);
    let comparison = harness.compare_pixels(&rendered, &inputs, |material, surface, pixel| {
        expected(material, surface, pixel, &inputs, &images, &lights)
    });
    comparison.assert_within(name, TOLERANCE);
    comparison.assert_mostly_judged(name);
}

/// [`assert_pixels_follow`] the reference model ([`expected_color`]).
pub(crate) fn assert_follows_the_reference(
    harness: Harness,
    objects: impl IntoIterator<Item = (Mesh, Transform, PhongMaterial)>,
    name: &str,
) {
    assert_pixels_follow(harness, objects, name, &expected_color);
}

/// The maps the texture map tests draw with.
struct TestMaps {
    base_color: Handle<Image>,
    specular: Handle<Image>,
    emissive: Handle<Image>,
    normals: Handle<Image>,
    /// A base color map whose alpha varies from 0 to 1 (for an alpha mask).
    cutout: Handle<Image>,
}

impl TestMaps {
    /// The maps, added to the app's images.
    fn add(world: &mut World) -> Self {
        let mut images = world.resource_mut::<Assets<Image>>();
        Self {
            base_color: images.add(color_map(0.2, 1.0)),
            specular: images.add(color_map(0.0, 1.0)),
            emissive: images.add(color_map(0.0, 0.3)),
            normals: images.add(normal_map()),
            cutout: images.add(float_map(|x, y| {
                [0.9, 0.6, 0.3, scatter(x, y, 3, 0.0, 1.0)]
            })),
        }
    }
}

#[test]
fn texture_maps_follow_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let maps = TestMaps::add(world);

    let every_map = PhongMaterial {
        base_color_texture: Some(maps.base_color.clone()),
        specular_texture: Some(maps.specular.clone()),
        emissive_texture: Some(maps.emissive.clone()),
        normal_map_texture: Some(maps.normals.clone()),
        flip_normal_map_y: true,
        // Deeper across, shallower and turned back along (three.js's `normalScale`).
        normal_map_scale: Vec2::new(1.8, -0.6),
        specular_strength: 2.0,
        shininess: 40.0,
        emissive: LinearRgba::WHITE,
        ..default()
    };
    let base_color_and_normals = PhongMaterial {
        base_color_texture: Some(maps.base_color.clone()),
        normal_map_texture: Some(maps.normals.clone()),
        shininess: 20.0,
        ..default()
    };
    let masked = PhongMaterial {
        base_color_texture: Some(maps.cutout.clone()),
        alpha_mode: AlphaMode::Mask(0.5),
        emissive: LinearRgba::rgb(0.1, 0.1, 0.1),
        ..default()
    };
    let objects = [
        // Tangents: the normal map applies.
        (
            tangent_sphere(1.2),
            Transform::from_xyz(0.0, 0.0, 0.0),
            every_map,
        ),
        // No tangents: the normal map is left out (with a warning), the base color map not.
        (
            Cuboid::new(1.2, 1.2, 1.2).into(),
            Transform::from_xyz(-2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(0.6)),
            base_color_and_normals,
        ),
        // Alpha mask: texels below 0.5 are holes.
        (
            Cuboid::new(1.2, 1.2, 1.2).into(),
            Transform::from_xyz(2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(-0.6)),
            masked,
        ),
    ];
    assert_follows_the_reference(harness, objects, "texture maps");
}

/// Every map read at the mesh's second UV set (`*_channel: UvChannel::Uv1`), as it is,
/// beside maps on the first set moved by the UV transform: the second set is the first
/// turned a quarter and shrunk (`with_second_uvs`), so a map read at the wrong set shows
/// other texels. The bump and alpha maps only where the device binds them.
#[test]
fn maps_on_the_second_uv_set_follow_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let maps = TestMaps::add(world);
    let mut images = world.resource_mut::<Assets<Image>>();
    let heights = images.add(color_map(0.0, 0.4));
    let holes = images.add(float_map(|x, y| {
        [0.0, scatter(x, y, 1, 0.0, 1.0), 0.0, 1.0]
    }));
    // Moves the maps on the first set only.
    let uv_transform =
        bevy::math::Affine2::from_scale_angle_translation(Vec2::new(1.4, 0.8), 0.3, Vec2::ZERO);
    let every_map_on_the_second_set = PhongMaterial {
        base_color_texture: Some(maps.base_color.clone()),
        base_color_channel: UvChannel::Uv1,
        specular_texture: Some(maps.specular.clone()),
        specular_channel: UvChannel::Uv1,
        emissive_texture: Some(maps.emissive.clone()),
        emissive_channel: UvChannel::Uv1,
        normal_map_texture: Some(maps.normals.clone()),
        normal_map_channel: UvChannel::Uv1,
        bump_map_texture: Some(heights.clone()),
        bump_map_channel: UvChannel::Uv1,
        bump_scale: 0.8,
        specular_strength: 2.0,
        shininess: 40.0,
        emissive: LinearRgba::WHITE,
        uv_transform,
        ..default()
    };
    let sets_mixed = PhongMaterial {
        base_color_texture: Some(maps.base_color.clone()),
        specular_texture: Some(maps.specular.clone()),
        specular_channel: UvChannel::Uv1,
        emissive_texture: Some(maps.emissive.clone()),
        emissive: LinearRgba::WHITE,
        normal_map_texture: Some(maps.normals.clone()),
        bump_map_texture: Some(heights),
        bump_map_channel: UvChannel::Uv1,
        shininess: 20.0,
        uv_transform,
        ..default()
    };
    let masked_on_the_second_set = PhongMaterial {
        base_color_texture: Some(maps.cutout.clone()),
        base_color_channel: UvChannel::Uv1,
        alpha_map_texture: Some(holes),
        alpha_map_channel: UvChannel::Uv1,
        alpha_mode: AlphaMode::Mask(0.3),
        emissive: LinearRgba::rgb(0.1, 0.1, 0.1),
        uv_transform,
        ..default()
    };
    let objects = [
        (
            with_second_uvs(tangent_sphere(1.2)),
            Transform::from_xyz(0.0, 0.0, 0.0),
            every_map_on_the_second_set,
        ),
        (
            with_second_uvs(
                Mesh::from(Cuboid::new(1.2, 1.2, 1.2))
                    .with_generated_tangents()
                    .expect("a cuboid has UVs and normals"),
            ),
            Transform::from_xyz(-2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(0.6)),
            sets_mixed,
        ),
        (
            with_second_uvs(Cuboid::new(1.2, 1.2, 1.2).into()),
            Transform::from_xyz(2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(-0.6)),
            masked_on_the_second_set,
        ),
    ];
    assert_follows_the_reference(harness, objects, "maps on the second UV set");
}

/// A metallic-roughness map (glTF's `metallicRoughnessTexture`): each texel's blue metallic
/// and green roughness, times the material's factors, make the surface by the reference
/// model's rules (`reference::Material::at_metallic_roughness_texel`). A material converted
/// from a `StandardMaterial` as most tools export one (factors 1, the values in the texture,
/// a base color map), beside one with its own factors, a specular map and the Phong model on
/// the second UV set. Roughness texels in `[0.3, 1]` keep the exponent at most 245: the
/// frame tests' tolerance is for `f32`'s `pow` at such exponents.
#[test]
fn metallic_roughness_maps_follow_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let maps = TestMaps::add(world);
    let metallic_roughness = world.resource_mut::<Assets<Image>>().add(float_map(|x, y| {
        [
            0.0,
            scatter(x, y, 1, 0.3, 1.0),
            scatter(x, y, 2, 0.0, 1.0),
            1.0,
        ]
    }));
    let exported = PhongMaterial::from(&StandardMaterial {
        base_color: Color::linear_rgb(1.0, 0.8, 0.5),
        base_color_texture: Some(maps.base_color.clone()),
        metallic: 1.0,
        perceptual_roughness: 1.0,
        metallic_roughness_texture: Some(metallic_roughness.clone()),
        ..default()
    });
    let own_factors = PhongMaterial {
        base_color: Color::linear_rgb(0.9, 0.6, 0.3),
        specular_color: Color::linear_rgb(0.1, 0.2, 0.3),
        specular_texture: Some(maps.specular.clone()),
        specular_strength: 0.8,
        metallic_roughness_texture: Some(metallic_roughness),
        metallic_roughness_channel: UvChannel::Uv1,
        metallic: 0.7,
        perceptual_roughness: 0.9,
        ..default()
    };
    let objects = [
        (
            tangent_sphere(1.2),
            Transform::from_xyz(0.0, 0.0, 0.0),
            exported,
        ),
        (
            with_second_uvs(Cuboid::new(1.2, 1.2, 1.2).into()),
            Transform::from_xyz(-2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(0.6)),
            own_factors,
        ),
    ];
    assert_follows_the_reference(harness, objects, "metallic-roughness maps");
}
