//! Displacement maps: spheres whose vertices the map moves along their normals, rendered on
//! the render device. The captured world positions lie on the displaced sphere (the radius
//! plus `red · scale + bias`), and each pixel is lit as the reference model says on those
//! positions; the prepass tests (`game_features::prepasses`) check that the prepasses move
//! the vertices alike.
//!
//! The map has two heights, a half each, read nearest; each sphere's UV transform squeezes its
//! UVs into one half, so every vertex moves by one known distance. A UV sphere's flat triangles lie
//! inside its vertices' sphere by at most `1 − cos(θ)` of its radius (θ the angle from a
//! grid cell's middle to its corners, under 0.14 rad here): the radius is judged within
//! [`SAG`] below and `f32` rounding (10⁻⁵) above.

use crate::frames::{SIZE, TOLERANCE};
use crate::texture_maps::{expected_color, float_map, loaded_images, spawn_map_lights};
use bevy::{
    math::Affine2,
    mesh::{UvChannel, VertexAttributeValues},
    prelude::*,
};
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;

/// The largest share of a vertex's radius a triangle's interior lies inside it (sectors 33,
/// stacks 16: cells of 0.19 × 0.2 rad, 1 − cos(0.14) < 0.01).
const SAG: f64 = 0.01;

/// The map's two texels' red values, as stored (8 bits).
const HEIGHTS: [u8; 2] = [51, 204];

/// A map whose left half (texel columns 0–1) holds `HEIGHTS[0]` in red and right half
/// `HEIGHTS[1]`, nearest-sampled.
fn two_height_map() -> Image {
    float_map(|x, _| {
        let red = f32::from(HEIGHTS[(x / 2) as usize]) / 255.0;
        [red, 0.0, 0.0, 1.0]
    })
}

/// UVs squeezed into the map's half `texel` (0 left, 1 right).
fn into_texel(texel: usize) -> Affine2 {
    Affine2::from_scale_angle_translation(
        Vec2::splat(0.3),
        0.0,
        Vec2::new(0.1 + 0.5 * texel as f32, 0.2),
    )
}

#[test]
fn displaced_vertices_move_along_their_normals_by_the_map() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let map = world.resource_mut::<Assets<Image>>().add(two_height_map());
    // (center, radius, texel, scale, bias); the third is not displaced; the last reads the
    // map at its second UV set, which holds its first squeezed into `texel` (its UV
    // transform, which squeezes the first set into the other texel, moving nothing there).
    let spheres = [
        (Vec3::new(-1.6, 0.3, 0.0), 0.9, 0, 0.5, 0.1),
        (Vec3::new(1.4, 0.3, 0.0), 1.1, 1, -0.4, 0.05),
        (Vec3::new(0.0, -1.6, 0.5), 0.6, 0, 0.0, 0.0),
        (Vec3::new(0.0, 1.9, -0.5), 0.6, 1, 0.4, 0.0),
    ];
    let second_set = 3;
    for (index, &(center, radius, texel, scale, bias)) in spheres.iter().enumerate() {
        let mut mesh = Sphere::new(radius).mesh().uv(33, 16);
        let material = if index == second_set {
            let Some(VertexAttributeValues::Float32x2(uvs)) = mesh.attribute(Mesh::ATTRIBUTE_UV_0)
            else {
                panic!("a UV sphere has UVs");
            };
            let squeezed: Vec<[f32; 2]> = uvs
                .iter()
                .map(|&uv| into_texel(texel).transform_point2(Vec2::from(uv)).into())
                .collect();
            mesh.insert_attribute(Mesh::ATTRIBUTE_UV_1, squeezed);
            PhongMaterial {
                base_color: Color::srgb(0.3, 0.7, 0.5),
                displacement_map: Some(map.clone()),
                displacement_map_channel: UvChannel::Uv1,
                displacement_scale: scale,
                displacement_bias: bias,
                uv_transform: into_texel(1 - texel),
                ..default()
            }
        } else {
            PhongMaterial {
                base_color: Color::srgb(0.8, 0.6 - 0.2 * index as f32, 0.4),
                displacement_map: (index < 2).then(|| map.clone()),
                displacement_scale: scale,
                displacement_bias: bias,
                uv_transform: into_texel(texel),
                shininess: 24.0,
                ..default()
            }
        };
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
        world.spawn((
            Mesh3d(mesh),
            MeshMaterial3d(material),
            Transform::from_translation(center),
        ));
    }
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    let lights = harness.reference_lights();
    let images = loaded_images(&mut harness);
    let comparison = harness.compare_pixels(&rendered, &inputs, |material, surface, pixel| {
        expected_color(material, surface, pixel, &inputs, &images, &lights)
    });
    comparison.assert_within("displacement", TOLERANCE);

    // Each pixel's position is on its sphere, the radius moved by the map.
    let camera = harness.camera_position();
    let world = harness.world_mut();
    let materials = world.resource::<Assets<PhongMaterial>>();
    let mut judged = [0usize; 4];
    for pixel in 0..inputs.positions.pixels.len() {
        let Some((handle, surface)) = inputs.surface_at(pixel, camera) else {
            continue;
        };
        let material = materials.get(handle).expect("a spawned material");
        let (index, &(center, radius, texel, scale, bias)) = spheres
            .iter()
            .enumerate()
            .min_by(|a, b| {
                let distance = |c: Vec3| (surface.position - c.as_dvec3()).length();
                distance(a.1.0).total_cmp(&distance(b.1.0))
            })
            .expect("four spheres");
        let moved = match material.displacement_map {
            Some(_) => f64::from(HEIGHTS[texel]) / 255.0 * f64::from(scale) + f64::from(bias),
            None => 0.0,
        };
        let expected = f64::from(radius) + moved;
        let actual = (surface.position - center.as_dvec3()).length();
        assert!(
            actual <= expected * (1.0 + 1e-5) && actual >= expected * (1.0 - SAG),
            "sphere {index}, pixel {pixel}: radius {actual}, expected {expected} (less its \
             triangles' sag)"
        );
        judged[index] += 1;
    }
    assert!(
        judged.iter().all(|&count| count > 200),
        "every sphere covers pixels: {judged:?}"
    );
}
