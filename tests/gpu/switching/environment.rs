//! Spheres lit by an environment map, as most Bevy scenes are lit: the camera's
//! `EnvironmentMapLight` (a sky over a darker ground) and a sun, no ambient light. A floor;
//! a rough and a smooth dielectric and a tinted plastic (top row); a rough and a smooth gold
//! sphere and a smooth chrome one (bottom row).

use super::{Bound, Object, assert_switched_within};
use crate::environment::cube_map;
use bevy::{image::ImageSampler, prelude::*};
use bevy_phong_headless::HarnessCamera;

/// The sky's and the ground's radiance (before the light's intensity), linear RGB.
const SKY: Vec3 = Vec3::new(0.45, 0.6, 0.9);
const GROUND: Vec3 = Vec3::new(0.35, 0.25, 0.15);

/// Texels a side of the specular cube's first level, and its mip levels (64 down to 1).
const SPECULAR_SIZE: u32 = 64;
const SPECULAR_LEVELS: u32 = 7;

/// The direction through the center of texel `(x, y)` of face `face` of a cube `size` texels
/// a side, in the cube's frame (Vulkan's face layout; `crate::environment::cube_face`
/// inverted).
fn texel_direction(face: u32, size: u32, x: u32, y: u32) -> Vec3 {
    let s = 2.0 * (x as f32 + 0.5) / size as f32 - 1.0;
    let t = 2.0 * (y as f32 + 0.5) / size as f32 - 1.0;
    match face {
        0 => Vec3::new(1.0, -t, -s),
        1 => Vec3::new(-1.0, -t, s),
        2 => Vec3::new(s, 1.0, t),
        3 => Vec3::new(s, -1.0, -t),
        4 => Vec3::new(s, -t, 1.0),
        _ => Vec3::new(-s, -t, -1.0),
    }
    .normalize()
}

/// The camera's environment map light: the sky above the horizon, the ground below. The
/// specular cube's level `l` blurs the horizon over `±(0.03 + 0.6 · l / 6)` in `y` (a
/// rougher lobe reads a blurrier level); the diffuse cube holds the exact cosine-weighted
/// mean of the sharp sky about each direction `N`, `GROUND + (SKY − GROUND) · (1 + N.y) / 2`
/// (Bevy's diffuse cube is that mean, its `π` taken out).
fn sky_light(world: &mut World) {
    let rgba = |color: Vec3| [color.x, color.y, color.z, 1.0];
    let mut images = world.resource_mut::<Assets<Image>>();
    let specular = images.add(cube_map(
        SPECULAR_SIZE,
        SPECULAR_LEVELS,
        |face, level, x, y| {
            let y_up = texel_direction(face, SPECULAR_SIZE >> level, x, y).y;
            let blur = 0.03 + 0.6 * level as f32 / (SPECULAR_LEVELS - 1) as f32;
            rgba(GROUND.lerp(SKY, (y_up / blur * 0.5 + 0.5).clamp(0.0, 1.0)))
        },
    ));
    let mut diffuse = cube_map(16, 1, |face, _, x, y| {
        let n_up = texel_direction(face, 16, x, y).y;
        rgba(GROUND.lerp(SKY, (1.0 + n_up) / 2.0))
    });
    // Bevy reads both cubes through the diffuse cube's sampler.
    diffuse.sampler = ImageSampler::linear();
    let diffuse = images.add(diffuse);
    let camera = world
        .query_filtered::<Entity, With<HarnessCamera>>()
        .single(world)
        .expect("the harness's camera");
    world.entity_mut(camera).insert(EnvironmentMapLight {
        diffuse_map: diffuse,
        specular_map: specular,
        intensity: 1_200.0,
        ..default()
    });
    world.insert_resource(GlobalAmbientLight {
        brightness: 0.0,
        ..default()
    });
    world.spawn((
        DirectionalLight {
            illuminance: 2_000.0,
            color: Color::srgb(1.0, 0.95, 0.85),
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(-1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
}

/// The floor and six spheres.
fn objects(_: &mut World) -> Vec<Object> {
    let sphere = |name, x: f32, y: f32, material| Object {
        name,
        mesh: Sphere::new(0.55).mesh().uv(48, 32),
        transform: Transform::from_xyz(x, y, 0.0),
        material,
    };
    let gold = Color::srgb(1.0, 0.77, 0.34);
    let metal = |base_color, perceptual_roughness| StandardMaterial {
        base_color,
        metallic: 1.0,
        perceptual_roughness,
        ..default()
    };
    vec![
        Object {
            name: "floor",
            mesh: Plane3d::default().mesh().size(12.0, 12.0).into(),
            transform: Transform::from_xyz(0.0, -1.0, 0.0),
            material: StandardMaterial {
                base_color: Color::srgb(0.5, 0.5, 0.45),
                perceptual_roughness: 0.9,
                ..default()
            },
        },
        sphere(
            "rough dielectric",
            -1.3,
            0.75,
            StandardMaterial {
                base_color: Color::srgb(0.8, 0.15, 0.1),
                perceptual_roughness: 0.9,
                ..default()
            },
        ),
        sphere(
            "smooth dielectric",
            0.0,
            0.75,
            StandardMaterial {
                base_color: Color::srgb(0.1, 0.35, 0.8),
                perceptual_roughness: 0.2,
                ..default()
            },
        ),
        sphere(
            "tinted plastic",
            1.3,
            0.75,
            StandardMaterial {
                base_color: Color::srgb(0.2, 0.6, 0.3),
                perceptual_roughness: 0.5,
                reflectance: 0.7,
                specular_tint: Color::srgb(1.0, 0.6, 0.6),
                ..default()
            },
        ),
        sphere("rough gold", -1.3, -0.45, metal(gold, 0.7)),
        sphere("smooth gold", 0.0, -0.45, metal(gold, 0.3)),
        sphere(
            "chrome",
            1.3,
            -0.45,
            metal(Color::srgb(0.9, 0.9, 0.92), 0.15),
        ),
    ]
}

/// The measured figures (in the comments) plus 0.005 and 2 percentage points.
const BOUNDS: [Bound; 8] = [
    ("floor", 0.0152, 0.02),              // 0.0102, 0.0 %
    ("rough dielectric", 0.0112, 0.02),   // 0.0062, 0.0 %
    ("smooth dielectric", 0.0075, 0.023), // 0.0025, 0.3 %
    ("tinted plastic", 0.0083, 0.028),    // 0.0033, 0.8 %
    ("rough gold", 0.0298, 0.079),        // 0.0248, 5.9 %
    ("smooth gold", 0.0171, 0.031),       // 0.0121, 1.1 %
    ("chrome", 0.0153, 0.033),            // 0.0103, 1.3 %
    ("scene", 0.0149, 0.027),             // 0.0099, 0.7 %
];

#[test]
fn switched_spheres_under_an_environment_map_stay_near_bevys_own_picture_of_them() {
    assert_switched_within(objects, sky_light, "switching_environment", &BOUNDS);
}
