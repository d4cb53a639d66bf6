//! The normal a surface is lit with beside the normal map: bump maps (`reference::bumped_normal`)
//! and flat shading (`reference::face_normal`), rendered on the render device and compared
//! per pixel with the reference model given each pixel's captured inputs.
//!
//! The maps and the texel-edge rule are `texture_maps`'s; a bump map's three samples (at the
//! UV, one texel along u, one along v) share the UV's fraction of a texel, so one edge test
//! covers them. The face normal the reference lights with is the geometric normal of the
//! mesh's triangle that holds the pixel's captured position, found among the mesh's
//! triangles in world space; a pixel within 10⁻⁴ of two triangles (on an edge) is left out.
//! Tolerance: the frame tests' ([`TOLERANCE`]); the device's face normal is the cross product
//! of two screen derivatives of the position, whose `f32` rounding (about 10⁻⁷ of a
//! coordinate over a pixel's 10⁻² footprint) tilts it by about 10⁻⁵.

use crate::frames::SIZE;
use crate::texture_maps::{
    assert_follows_the_reference, assert_pixels_follow, expected_color, float_map, normal_map,
    spawn_map_lights,
};
use bevy::{math::Affine2, prelude::*};
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{
    Harness,
    pixel_model::{face_normal_at, world_triangles},
};
use glam::DVec3;

/// A height map whose red channel varies from texel to texel over `[0, 1]`.
pub(crate) fn height_map() -> Image {
    float_map(|x, y| {
        let height = ((x * 5 + y * 3 + 1) % 7) as f32 / 6.0;
        [height, 0.0, 0.0, 1.0]
    })
}

/// A UV sphere with tangents, as the normal and bump maps need.
pub(crate) fn tangent_sphere(radius: f32) -> Mesh {
    Sphere::new(radius)
        .mesh()
        .uv(48, 32)
        .with_generated_tangents()
        .expect("a UV sphere has UVs and normals")
}

#[test]
fn bump_maps_follow_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let mut images = world.resource_mut::<Assets<Image>>();
    let heights = images.add(height_map());
    let normals = images.add(normal_map());
    let bumped = PhongMaterial {
        base_color: Color::srgb(0.8, 0.7, 0.5),
        bump_map_texture: Some(heights.clone()),
        bump_scale: 1.5,
        shininess: 24.0,
        ..default()
    };
    // Dents (a negative scale) over a normal map, at moved UVs.
    let dented_over_normals = PhongMaterial {
        base_color: Color::srgb(0.4, 0.7, 0.9),
        normal_map_texture: Some(normals),
        bump_map_texture: Some(heights.clone()),
        bump_scale: -0.8,
        uv_transform: Affine2::from_scale_angle_translation(
            Vec2::new(1.5, 0.75),
            0.4,
            Vec2::new(0.1, 0.2),
        ),
        ..default()
    };
    // No tangents: the bump map is left out (with a warning).
    let untangented = PhongMaterial {
        base_color: Color::srgb(0.9, 0.4, 0.4),
        bump_map_texture: Some(heights),
        ..default()
    };
    let objects = [
        (
            tangent_sphere(1.0),
            Transform::from_xyz(-1.2, 0.3, 0.0),
            bumped,
        ),
        (
            tangent_sphere(1.0),
            Transform::from_xyz(1.2, 0.3, 0.0).with_rotation(Quat::from_rotation_y(0.8)),
            dented_over_normals,
        ),
        (
            Cuboid::new(1.0, 1.0, 1.0).into(),
            Transform::from_xyz(0.0, -1.6, 0.5).with_rotation(Quat::from_rotation_y(0.5)),
            untangented,
        ),
    ];
    assert_follows_the_reference(harness, objects, "bump maps");
}

#[test]
fn flat_shading_lights_each_triangle_with_its_face_normal() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let normals = world.resource_mut::<Assets<Image>>().add(normal_map());
    let low_poly = || {
        Sphere::new(1.0)
            .mesh()
            .ico(1)
            .expect("one subdivision")
            .with_generated_tangents()
            .expect("an icosphere has UVs and normals")
    };
    let objects = [
        (
            low_poly(),
            // A scale that is not uniform: the faces' planes are the world's.
            Transform::from_xyz(-1.2, 0.2, 0.0)
                .with_rotation(Quat::from_euler(EulerRot::XYZ, 0.3, 0.5, 0.0))
                .with_scale(Vec3::new(1.0, 1.3, 0.8)),
            PhongMaterial {
                base_color: Color::srgb(0.9, 0.6, 0.3),
                flat_shading: true,
                shininess: 16.0,
                ..default()
            },
        ),
        (
            low_poly(),
            Transform::from_xyz(1.2, 0.2, 0.0).with_rotation(Quat::from_rotation_y(-0.4)),
            PhongMaterial {
                base_color: Color::srgb(0.3, 0.7, 0.9),
                flat_shading: true,
                normal_map_texture: Some(normals),
                ..default()
            },
        ),
        // Smooth beside them: its interpolated normal, as before.
        (
            Sphere::new(0.8).mesh().ico(1).expect("one subdivision"),
            Transform::from_xyz(0.0, -1.5, 0.5),
            PhongMaterial::from(Color::srgb(0.7, 0.9, 0.5)),
        ),
    ];
    let triangles: Vec<[DVec3; 3]> = objects
        .iter()
        .filter(|(_, _, material)| material.flat_shading)
        .flat_map(|(mesh, transform, _)| world_triangles(mesh, &GlobalTransform::from(*transform)))
        .collect();
    assert_pixels_follow(
        harness,
        objects,
        "flat shading",
        &|material, surface, pixel, inputs, images, lights| {
            let surface = if material.flat_shading {
                let face = face_normal_at(&triangles, surface.position)?;
                reference::SurfacePoint {
                    normal: reference::face_normal(face, surface.normal),
                    ..*surface
                }
            } else {
                *surface
            };
            expected_color(material, &surface, pixel, inputs, images, lights)
        },
    );
}
