//! A caster masked by its alpha map, read through the material's UV transform, with a base
//! color alpha below one: the crate's caster cuts the holes the main pass cuts.

use crate::shadows::{EVERYONE, Shape, harness, judge, on, spot};
use bevy::{
    asset::RenderAssetUsages,
    image::ImageSampler,
    math::Affine2,
    prelude::*,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};
use bevy_phong::prelude::*;
use glam::DVec3;

/// A square whose alpha map holds, in its right half, a checkerboard of opaque cells
/// (green 1) and holes (green 0.6), and the inverted board in its left half, read through a
/// UV transform that takes the right half over the square; the base color's alpha is 0.8,
/// so that a hole's alpha is 0.48, below the mask's 1/2, and an opaque cell's 0.8. A caster
/// that ignored the transform would cast a board of six columns; one that ignored the base
/// alpha, every cell; one that ignored the alpha map, the whole square. Under WebGL2's
/// limits the alpha map is not bound (`render::binds_every_map`): there the square is
/// opaque (0.8) and casts whole, in the main pass and the caster alike. Judged against rays
/// cast in `f64` from a spot light, as the other masked casters are.
#[test]
fn a_caster_masked_by_its_alpha_map_through_a_uv_transform_casts_its_holes() {
    const CELLS: u32 = 3;
    let (mut harness, mut scene) = harness();
    let board = |cells| Shape::Checkerboard {
        center: DVec3::new(0.6, 1.8, -0.2),
        half: 0.9,
        cells,
    };
    let shape = board(if harness.binds_every_map() { CELLS } else { 1 });
    let texels: Vec<u8> = (0..2 * CELLS * CELLS)
        .flat_map(|index| {
            let (column, row) = (index % (2 * CELLS), index / (2 * CELLS));
            let in_right_half = column >= CELLS;
            let even = (column % CELLS + row).is_multiple_of(2);
            let green = if even == in_right_half { 255 } else { 153 };
            [0, green, 0, 255]
        })
        .collect();
    let mut image = Image::new(
        Extent3d {
            width: 2 * CELLS,
            height: CELLS,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        texels,
        TextureFormat::Rgba8Unorm,
        RenderAssetUsages::default(),
    );
    image.sampler = ImageSampler::nearest();
    let world = harness.world_mut();
    let alpha_map = world.resource_mut::<Assets<Image>>().add(image);
    let material = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(PhongMaterial {
            base_color: Color::srgba(0.8, 0.7, 0.25, 0.8),
            alpha_map_texture: Some(alpha_map),
            uv_transform: Affine2::from_scale_angle_translation(
                Vec2::new(0.5, 1.0),
                0.0,
                Vec2::new(0.5, 0.0),
            ),
            alpha_mode: AlphaMode::Mask(0.5),
            double_sided: true,
            ..default()
        });
    let Shape::Checkerboard { center, half, .. } = shape else {
        unreachable!()
    };
    let size = 2.0 * half as f32;
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::default().mesh().size(size, size));
    let entity = world
        .spawn((
            Mesh3d(mesh),
            MeshMaterial3d(material.clone()),
            Transform::from_translation(center.as_vec3()),
        ))
        .id();
    scene.shapes.push((entity, shape, material));
    let shadows = PhongShadows {
        resolution: 2048,
        ..on()
    };
    let lights = vec![spot(
        &mut harness,
        Vec3::new(1.2, 4.5, 0.8),
        Vec3::new(0.4, 0.0, -0.4),
        shadows,
    )];
    harness.settle();
    let inputs = harness.capture_inputs();
    judge(&mut harness, &scene, &lights, &EVERYONE, &inputs)
        .assert_holds("alpha map through a UV transform, translucent base");
}
