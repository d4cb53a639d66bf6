//! Props as glTF exporters write them: metallic and roughness factors 1 and the values in a
//! metallic-roughness map (blue metallic stripes, green roughness rising up the map), with a
//! base color map, a normal map, an occlusion map and an emissive map, beside the floor.

use super::{Bound, Object, assert_switched_within, bevy_lights};
use bevy::{
    asset::RenderAssetUsages,
    image::ImageSampler,
    prelude::*,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};

/// A map of `SIZE`² texels whose texel `(x, y)` is `texel(x, y)` (channels in `[0, 1]`),
/// 8-bit, sRGB or linear, repeated with linear filtering.
fn map(srgb: bool, texel: impl Fn(f32, f32) -> [f32; 4]) -> Image {
    const SIZE: u32 = 64;
    let data = (0..SIZE * SIZE)
        .flat_map(|index| {
            let (x, y) = (index % SIZE, index / SIZE);
            texel(x as f32 / SIZE as f32, y as f32 / SIZE as f32)
        })
        .map(|channel| (channel.clamp(0.0, 1.0) * 255.0).round() as u8)
        .collect();
    let format = if srgb {
        TextureFormat::Rgba8UnormSrgb
    } else {
        TextureFormat::Rgba8Unorm
    };
    let mut image = Image::new(
        Extent3d {
            width: SIZE,
            height: SIZE,
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

/// A square wave of `periods` periods across `[0, 1)`: 0 or 1.
fn stripes(t: f32, periods: f32) -> f32 {
    ((t * periods).floor() % 2.0).abs()
}

/// The floor and three props.
fn objects(world: &mut World) -> Vec<Object> {
    let mut images = world.resource_mut::<Assets<Image>>();
    let checker = images.add(map(true, |u, v| {
        let c =
            stripes(u, 8.0) * (1.0 - stripes(v, 8.0)) + stripes(v, 8.0) * (1.0 - stripes(u, 8.0));
        [0.85 - 0.5 * c, 0.6, 0.25 + 0.5 * c, 1.0]
    }));
    // Blue: metal and dielectric in stripes; green: roughness from 0.25 to 0.95.
    let metallic_roughness = images.add(map(false, |u, v| {
        [0.0, 0.25 + 0.7 * v, stripes(u, 4.0), 1.0]
    }));
    let normals = images.add(map(false, |u, v| {
        let (dx, dy) = (
            0.3 * (u * 6.0 * core::f32::consts::TAU).cos(),
            0.3 * (v * 4.0 * core::f32::consts::TAU).cos(),
        );
        let n = Vec3::new(-dx, -dy, 1.0).normalize();
        [0.5 + 0.5 * n.x, 0.5 + 0.5 * n.y, 0.5 + 0.5 * n.z, 1.0]
    }));
    let occlusion = images.add(map(false, |u, v| {
        [
            0.4 + 0.6 * (1.0 - stripes(u, 2.0) * stripes(v, 2.0)),
            0.0,
            0.0,
            1.0,
        ]
    }));
    let emissive = images.add(map(true, |u, v| {
        let c = stripes(u, 4.0) * stripes(v, 4.0);
        [c, 0.45 * c, 0.0, 1.0]
    }));
    let exported = |base_color_texture| StandardMaterial {
        base_color_texture,
        metallic: 1.0,
        perceptual_roughness: 1.0,
        metallic_roughness_texture: Some(metallic_roughness.clone()),
        ..default()
    };
    let sphere = || {
        Sphere::new(0.7)
            .mesh()
            .uv(48, 32)
            .with_generated_tangents()
            .expect("a UV sphere has UVs and normals")
    };
    vec![
        Object {
            name: "floor",
            mesh: Plane3d::default().mesh().size(12.0, 12.0).into(),
            transform: Transform::from_xyz(0.0, -1.0, 0.0),
            material: StandardMaterial {
                base_color: Color::srgb(0.6, 0.6, 0.6),
                perceptual_roughness: 0.9,
                ..default()
            },
        },
        Object {
            name: "checkered prop",
            mesh: sphere(),
            transform: Transform::from_xyz(-1.6, 0.0, 0.0),
            material: exported(Some(checker.clone())),
        },
        Object {
            name: "normal-mapped prop",
            mesh: sphere(),
            transform: Transform::from_xyz(0.0, 0.0, 0.0),
            material: StandardMaterial {
                base_color: Color::srgb(0.7, 0.75, 0.8),
                normal_map_texture: Some(normals),
                occlusion_texture: Some(occlusion),
                ..exported(None)
            },
        },
        Object {
            name: "emissive prop",
            mesh: Cuboid::new(1.0, 1.0, 1.0)
                .mesh()
                .build()
                .with_generated_tangents()
                .expect("a cuboid has UVs and normals"),
            transform: Transform::from_xyz(1.6, 0.0, 0.0).with_rotation(Quat::from_rotation_y(0.6)),
            material: StandardMaterial {
                emissive: LinearRgba::rgb(0.6, 0.6, 0.6),
                emissive_texture: Some(emissive),
                ..exported(Some(checker))
            },
        },
    ]
}

/// The measured figures (in the comments) plus 0.005 and 2 percentage points.
const BOUNDS: [Bound; 5] = [
    ("floor", 0.0214, 0.02),               // 0.0164, 0.0 %
    ("checkered prop", 0.0205, 0.067),     // 0.0155, 4.7 %
    ("normal-mapped prop", 0.0247, 0.041), // 0.0197, 2.1 %
    ("emissive prop", 0.0211, 0.082),      // 0.0161, 6.2 %
    ("scene", 0.0217, 0.037),              // 0.0167, 1.7 %
];

#[test]
fn switched_props_with_their_maps_stay_near_bevys_own_picture_of_them() {
    assert_switched_within(objects, bevy_lights, "switching_textured", &BOUNDS);
}
