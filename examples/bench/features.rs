//! The showcase with a group of material features turned on, for `PhongMaterial` and for
//! `StandardMaterial` with the nearest settings Bevy has (`--materials`):
//!
//! - surface inputs: vertex colors, a UV transform, a base color map and a perturbed normal
//!   (Phong's bump map; Standard's normal map), on meshes with tangents;
//! - baked light: a light map on the second UV set (Phong's `light_map_texture`; Bevy's
//!   `Lightmap` component) and an AO map (Standard's `occlusion_texture`);
//! - environment: the camera's `EnvironmentMapLight` reflected (Phong's `camera_environment`
//!   with `reflectivity` 0.5; Standard at roughness 0.2, metallic 0.5);
//! - converted PBR: a material as glTF exporters write one, a base color map and a
//!   metallic-roughness map with factors 1 (Standard's own; Phong's `PhongMaterial::from` it:
//!   the map read per texel and the ambient specular);
//! - converted PBR under an environment map: the same, with the camera's
//!   `EnvironmentMapLight` (Phong's `environment_light`, which the conversion sets);
//!
//! and each stylized mode alone, for `PhongMaterial` only (`--stylized`): wrapped diffuse,
//! toon bands, a toon ramp, a toon highlight, a rim everywhere and on the lit side, a
//! hemisphere light, and a cookie on every light.

use crate::scene::Shading;
use bevy::{
    asset::RenderAssetUsages,
    image::{Image, ImageSampler},
    math::Affine2,
    mesh::VertexAttributeValues,
    pbr::Lightmap,
    prelude::*,
    render::render_resource::{
        Extent3d, TextureDescriptor, TextureDimension, TextureFormat, TextureUsages,
        TextureViewDescriptor, TextureViewDimension,
    },
};
use bevy_phong::{DiffuseMode, SpecularMode, prelude::*};

/// A group of material features, or one stylized mode (`--stylized`: Phong only, Bevy's
/// material has none of them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Features {
    SurfaceInputs,
    BakedLight,
    Environment,
    /// A base color map and a metallic-roughness map with factors 1, Phong's converted from
    /// Standard's.
    Converted,
    /// [`Features::Converted`] with the camera's `EnvironmentMapLight`.
    ConvertedEnvironment,
    /// `DiffuseMode::Wrap(0.5)`.
    Wrap,
    /// `DiffuseMode::Toon { bands: 3, smoothing: 0.1 }`.
    ToonBands,
    /// `DiffuseMode::Toon` through a four-texel `toon_ramp_texture`.
    ToonRamp,
    /// `SpecularMode::Toon { smoothing: 0.1 }`.
    ToonHighlight,
    /// A rim everywhere.
    Rim,
    /// A rim on the lit side.
    RimLitSide,
    /// A `PhongHemisphereLight`.
    Hemisphere,
    /// A `PhongLightCookie` on every light (a cube map on the point lights, a tiled image on
    /// the directional one).
    Cookies,
}

impl Features {
    pub fn name(self) -> &'static str {
        match self {
            Features::SurfaceInputs => "surface inputs",
            Features::BakedLight => "baked light",
            Features::Environment => "environment",
            Features::Converted => "converted PBR",
            Features::ConvertedEnvironment => "converted PBR, environment map",
            Features::Wrap => "wrap diffuse",
            Features::ToonBands => "toon bands",
            Features::ToonRamp => "toon ramp",
            Features::ToonHighlight => "toon highlight",
            Features::Rim => "rim",
            Features::RimLitSide => "rim on the lit side",
            Features::Hemisphere => "hemisphere light",
            Features::Cookies => "light cookies",
        }
    }

    /// Whether the group changes the meshes (vertex colors, a second UV set, tangents).
    fn changes_meshes(self) -> bool {
        matches!(self, Features::SurfaceInputs | Features::BakedLight)
    }
}

/// A `size`² RGBA8 image whose texel `(x, y)` is `texel(x, y)` (channels in `[0, 1]`),
/// repeated, with linear filtering.
fn image(size: u32, srgb: bool, texel: impl Fn(u32, u32) -> [f32; 4]) -> Image {
    let data = (0..size * size)
        .flat_map(|index| texel(index % size, index / size))
        .map(|channel| (channel.clamp(0.0, 1.0) * 255.0).round() as u8)
        .collect();
    let format = if srgb {
        TextureFormat::Rgba8UnormSrgb
    } else {
        TextureFormat::Rgba8Unorm
    };
    let mut image = Image::new(
        Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        format,
        RenderAssetUsages::default(),
    );
    image.sampler = ImageSampler::linear();
    image
}

/// A wave in `[0, 1]` across a map of `size` texels.
fn wave(x: u32, size: u32, periods: f32) -> f32 {
    0.5 + 0.5 * (x as f32 / size as f32 * periods * core::f32::consts::TAU).sin()
}

/// A cube of 64 texels a side with its mip chain: a sky-like gradient per face.
fn cube_map() -> Image {
    const SIZE: u32 = 64;
    let levels = SIZE.ilog2() + 1;
    let mut data = Vec::new();
    for face in 0..6u32 {
        for level in 0..levels {
            let size = SIZE >> level;
            for y in 0..size {
                let t = (y as f32 + 0.5) / size as f32;
                let texel = [0.3 + 0.1 * face as f32, 0.5 + 0.4 * t, 0.9 - 0.3 * t, 1.0];
                for _ in 0..size {
                    data.extend(texel.map(|channel| (channel * 255.0) as u8));
                }
            }
        }
    }
    Image {
        data: Some(data),
        texture_descriptor: TextureDescriptor {
            label: None,
            size: Extent3d {
                width: SIZE,
                height: SIZE,
                depth_or_array_layers: 6,
            },
            mip_level_count: levels,
            sample_count: 1,
            dimension: TextureDimension::D2,
            format: TextureFormat::Rgba8UnormSrgb,
            usage: TextureUsages::TEXTURE_BINDING | TextureUsages::COPY_DST,
            view_formats: &[],
        },
        sampler: ImageSampler::linear(),
        texture_view_descriptor: Some(TextureViewDescriptor {
            dimension: Some(TextureViewDimension::Cube),
            ..default()
        }),
        asset_usage: RenderAssetUsages::default(),
        ..default()
    }
}

/// `mesh` with a color at each vertex, a second UV set (a copy of the first) and tangents.
fn featured_mesh(mut mesh: Mesh) -> Mesh {
    let positions: Vec<[f32; 3]> = mesh
        .attribute(Mesh::ATTRIBUTE_POSITION)
        .and_then(|positions| positions.as_float3())
        .expect("the showcase's meshes have positions")
        .to_vec();
    let colors: Vec<[f32; 4]> = positions
        .iter()
        .map(|[x, y, z]| {
            [
                0.6 + 0.4 * x.sin(),
                0.6 + 0.4 * y.cos(),
                0.6 + 0.4 * z.sin(),
                1.0,
            ]
        })
        .collect();
    mesh.insert_attribute(Mesh::ATTRIBUTE_COLOR, colors);
    if let Some(VertexAttributeValues::Float32x2(uvs)) = mesh.attribute(Mesh::ATTRIBUTE_UV_0) {
        let uvs = uvs.clone();
        mesh.insert_attribute(Mesh::ATTRIBUTE_UV_1, uvs);
    }
    mesh.with_generated_tangents()
        .expect("the showcase's meshes have UVs and normals")
}

/// Turns `features` on for every mesh the scene spawned with `shading`.
pub fn apply(world: &mut World, features: Features, shading: Shading) {
    let mut images = world.resource_mut::<Assets<Image>>();
    let base_color = images.add(image(256, true, |x, y| {
        let checker = ((x / 32 + y / 32) % 2) as f32;
        [0.6 + 0.4 * checker, 0.8, 0.7 + 0.3 * checker, 1.0]
    }));
    let heights = images.add(image(256, false, |x, y| {
        [wave(x, 256, 8.0) * wave(y, 256, 6.0), 0.0, 0.0, 1.0]
    }));
    // The normals of those heights, as a normal map holds them.
    let normals = images.add(image(256, false, |x, y| {
        let slope_x = (wave(x + 1, 256, 8.0) - wave(x, 256, 8.0)) * wave(y, 256, 6.0);
        let slope_y = (wave(y + 1, 256, 6.0) - wave(y, 256, 6.0)) * wave(x, 256, 8.0);
        let normal = Vec3::new(-slope_x, -slope_y, 1.0).normalize();
        [
            0.5 + 0.5 * normal.x,
            0.5 + 0.5 * normal.y,
            0.5 + 0.5 * normal.z,
            1.0,
        ]
    }));
    let light_map = images.add(image(128, true, |x, y| {
        let glow = wave(x, 128, 1.0) * wave(y, 128, 1.0);
        [0.3 * glow, 0.25 * glow, 0.2 * glow, 1.0]
    }));
    let ao_map = images.add(image(128, false, |x, y| {
        [
            0.4 + 0.6 * wave(x, 128, 2.0).max(wave(y, 128, 2.0)),
            0.0,
            0.0,
            1.0,
        ]
    }));
    let cube = images.add(cube_map());
    // Metallic in blue (stripes of metal and dielectric), roughness in green.
    let metallic_roughness = images.add(image(256, false, |x, y| {
        [
            0.0,
            0.25 + 0.7 * wave(y, 256, 3.0),
            (wave(x, 256, 4.0) > 0.5) as u32 as f32,
            1.0,
        ]
    }));
    let ramp = images.add(image(4, false, |x, _| {
        [[0.15, 0.3, 0.75, 1.0][x as usize], 0.0, 0.0, 1.0]
    }));
    let cookie = images.add(image(256, true, |x, y| {
        [wave(x, 256, 4.0), wave(y, 256, 3.0), 0.8, 1.0]
    }));

    if features == Features::Hemisphere {
        world.insert_resource(PhongHemisphereLight::default());
    }
    if features == Features::Cookies {
        let lights: Vec<Entity> = world
            .query_filtered::<Entity, Or<(
                With<PhongPointLight>,
                With<PhongSpotLight>,
                With<PhongDirectionalLight>,
            )>>()
            .iter(world)
            .collect();
        for light in lights {
            world.entity_mut(light).insert(PhongLightCookie {
                image: cookie.clone(),
                tiled: true,
                ..default()
            });
        }
    }
    let uv_transform = Affine2::from_scale_angle_translation(Vec2::splat(2.0), 0.3, Vec2::ZERO);

    if matches!(
        features,
        Features::Environment | Features::ConvertedEnvironment
    ) {
        let cameras: Vec<Entity> = world
            .query_filtered::<Entity, With<Camera3d>>()
            .iter(world)
            .collect();
        for camera in cameras {
            world.entity_mut(camera).insert(EnvironmentMapLight {
                diffuse_map: cube.clone(),
                specular_map: cube.clone(),
                intensity: 1000.0,
                ..default()
            });
        }
    }
    let meshes: Vec<(Entity, Handle<Mesh>)> = world
        .query::<(Entity, &Mesh3d)>()
        .iter(world)
        .map(|(entity, mesh)| (entity, mesh.0.clone()))
        .collect();
    for (entity, mesh) in meshes {
        if features.changes_meshes() {
            let mut assets = world.resource_mut::<Assets<Mesh>>();
            let featured = featured_mesh(assets.get(&mesh).expect("a spawned mesh").clone());
            let featured = assets.add(featured);
            world.entity_mut(entity).insert(Mesh3d(featured));
        }
        if features == Features::BakedLight && shading == Shading::Standard {
            world.entity_mut(entity).insert(Lightmap {
                image: light_map.clone(),
                ..default()
            });
        }
        if let Some(handle) = world.get::<MeshMaterial3d<PhongMaterial>>(entity) {
            let handle = handle.0.clone();
            let mut materials = world.resource_mut::<Assets<PhongMaterial>>();
            let mut material = materials.get_mut(&handle).expect("a spawned material");
            match features {
                Features::SurfaceInputs => {
                    material.base_color_texture = Some(base_color.clone());
                    material.uv_transform = uv_transform;
                    material.bump_map_texture = Some(heights.clone());
                    // The heights rise about 0.05 a texel at most: tilts like the normal map's.
                    material.bump_scale = 8.0;
                }
                Features::BakedLight => {
                    material.light_map_texture = Some(light_map.clone());
                    material.ao_map_texture = Some(ao_map.clone());
                }
                Features::Environment => {
                    material.camera_environment = true;
                    material.reflectivity = 0.5;
                }
                Features::Converted | Features::ConvertedEnvironment => {
                    *material = PhongMaterial::from(&StandardMaterial {
                        base_color: material.base_color,
                        base_color_texture: Some(base_color.clone()),
                        metallic: 1.0,
                        perceptual_roughness: 1.0,
                        metallic_roughness_texture: Some(metallic_roughness.clone()),
                        ..default()
                    });
                }
                Features::Wrap => material.diffuse_mode = DiffuseMode::Wrap(0.5),
                Features::ToonBands => {
                    material.diffuse_mode = DiffuseMode::Toon {
                        bands: 3,
                        smoothing: 0.1,
                    };
                }
                Features::ToonRamp => {
                    material.diffuse_mode = DiffuseMode::Toon {
                        bands: 3,
                        smoothing: 0.1,
                    };
                    material.toon_ramp_texture = Some(ramp.clone());
                }
                Features::Hemisphere | Features::Cookies => {}
                Features::ToonHighlight => {
                    material.specular_mode = SpecularMode::Toon { smoothing: 0.1 };
                }
                Features::Rim | Features::RimLitSide => {
                    material.rim_color = LinearRgba::rgb(0.3, 0.5, 0.9);
                    material.rim_lit_side = features == Features::RimLitSide;
                }
            }
        }
        if let Some(handle) = world.get::<MeshMaterial3d<StandardMaterial>>(entity) {
            let handle = handle.0.clone();
            let mut materials = world.resource_mut::<Assets<StandardMaterial>>();
            let mut material = materials.get_mut(&handle).expect("a spawned material");
            match features {
                Features::SurfaceInputs => {
                    material.base_color_texture = Some(base_color.clone());
                    material.uv_transform = uv_transform;
                    material.normal_map_texture = Some(normals.clone());
                }
                Features::BakedLight => material.occlusion_texture = Some(ao_map.clone()),
                Features::Environment => {
                    material.perceptual_roughness = 0.2;
                    material.metallic = 0.5;
                }
                Features::Converted | Features::ConvertedEnvironment => {
                    material.base_color_texture = Some(base_color.clone());
                    material.metallic = 1.0;
                    material.perceptual_roughness = 1.0;
                    material.metallic_roughness_texture = Some(metallic_roughness.clone());
                }
                _ => {}
            }
        }
    }
}
