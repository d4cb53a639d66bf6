//! The self-check of `render_scene` ([`Harness::compare_with_reference`]), one scene per
//! material feature and per kind of light: each scene is rendered and compared with the
//! reference model through the same call that `render_scene` makes, which must know every
//! feature (a feature it left out would show as a difference, as an unlit material once
//! did). Tolerance: the frame tests' ([`TOLERANCE`]); at most a fifth of the lit pixels may
//! go unjudged (texel edges, the alpha mask's cutoff, a point cookie's cube edges).
//!
//! Shadows and environment maps are left out: the self-check does not model them (see
//! `bevy_phong_headless::pixel_model`); their own tests cast rays and read cube maps.

use crate::frames::{SIZE, TOLERANCE};
use crate::shading_normals::{height_map, tangent_sphere};
use crate::surface_inputs::{with_second_uvs, with_vertex_colors};
use crate::texture_maps::{TEXELS, color_map, float_map, normal_map, spawn_map_lights};
use bevy::{math::Affine2, prelude::*};
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;
use std::collections::HashSet;

/// Lit pixels each scene must show at least: a sphere of radius 1.3 covers about 1,900.
const LIT_PIXELS: usize = 1_000;

/// What a scene adds to the map tests' lights (ambient, directional, point): its objects and
/// any other light.
type Scene = Box<dyn FnOnce(&mut World)>;

/// A sphere of `material` at the origin, with UVs, tangents, a second UV set and vertex
/// colors as `mesh` gives them.
fn sphere(material: PhongMaterial, mesh: impl FnOnce(Mesh) -> Mesh + 'static) -> Scene {
    Box::new(move |world: &mut World| {
        let mesh = world
            .resource_mut::<Assets<Mesh>>()
            .add(mesh(tangent_sphere(1.3)));
        let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
        world.spawn((
            Mesh3d(mesh),
            MeshMaterial3d(material),
            Transform::from_rotation(Quat::from_rotation_y(0.7)),
        ));
    })
}

/// A sphere of `material` made with the app's images: `material(images)`.
fn mapped(
    material: impl FnOnce(&mut Assets<Image>) -> PhongMaterial + 'static,
    mesh: impl FnOnce(Mesh) -> Mesh + 'static,
) -> Scene {
    Box::new(move |world: &mut World| {
        let material = material(&mut world.resource_mut::<Assets<Image>>());
        sphere(material, mesh)(world);
    })
}

/// A sphere of `material` under one more light, `light`.
fn lit_by(light: impl Bundle, material: PhongMaterial) -> Scene {
    Box::new(move |world: &mut World| {
        world.spawn(light);
        sphere(material, |mesh| mesh)(world);
    })
}

fn plain() -> PhongMaterial {
    PhongMaterial {
        base_color: Color::srgb(0.7, 0.6, 0.5),
        shininess: 24.0,
        ..default()
    }
}

/// A spot light above and in front of the sphere.
fn spot() -> (PhongSpotLight, Transform) {
    (
        PhongSpotLight {
            color: Color::srgb(0.9, 0.9, 0.7),
            inner_angle: 12f32.to_radians(),
            outer_angle: 24f32.to_radians(),
            ..default()
        },
        Transform::from_xyz(0.5, 3.0, 3.0).looking_at(Vec3::ZERO, Vec3::Y),
    )
}

/// The scenes, by the feature each shows.
fn scenes() -> Vec<(&'static str, Scene)> {
    let same = |mesh: Mesh| mesh;
    vec![
        (
            "base color map",
            mapped(
                |images| PhongMaterial {
                    base_color_texture: Some(images.add(color_map(0.2, 1.0))),
                    ..plain()
                },
                same,
            ),
        ),
        (
            "specular map",
            mapped(
                |images| PhongMaterial {
                    specular_texture: Some(images.add(color_map(0.0, 1.0))),
                    ..plain()
                },
                same,
            ),
        ),
        (
            "emissive map",
            mapped(
                |images| PhongMaterial {
                    emissive: LinearRgba::rgb(0.5, 0.4, 0.3),
                    emissive_texture: Some(images.add(color_map(0.0, 1.0))),
                    ..plain()
                },
                same,
            ),
        ),
        (
            "normal map",
            mapped(
                |images| PhongMaterial {
                    normal_map_texture: Some(images.add(normal_map())),
                    ..plain()
                },
                same,
            ),
        ),
        (
            "bump map",
            mapped(
                |images| PhongMaterial {
                    bump_map_texture: Some(images.add(height_map())),
                    bump_scale: 0.5,
                    ..plain()
                },
                same,
            ),
        ),
        (
            "alpha map",
            mapped(
                |images| PhongMaterial {
                    alpha_map_texture: Some(images.add(color_map(0.0, 1.0))),
                    alpha_mode: AlphaMode::Mask(0.5),
                    ..plain()
                },
                same,
            ),
        ),
        (
            "alpha mask",
            mapped(
                |images| PhongMaterial {
                    base_color_texture: Some(images.add(color_map(0.0, 1.0))),
                    alpha_mode: AlphaMode::Mask(0.4),
                    ..plain()
                },
                same,
            ),
        ),
        (
            "light map on the second UVs",
            mapped(
                |images| PhongMaterial {
                    light_map_texture: Some(images.add(color_map(0.0, 1.0))),
                    light_map_intensity: 0.8,
                    ..plain()
                },
                with_second_uvs,
            ),
        ),
        (
            "AO map",
            mapped(
                |images| PhongMaterial {
                    ao_map_texture: Some(images.add(color_map(0.0, 1.0))),
                    ao_map_intensity: 0.9,
                    ..plain()
                },
                same,
            ),
        ),
        ("vertex colors", sphere(plain(), with_vertex_colors)),
        (
            "UV transform",
            mapped(
                |images| PhongMaterial {
                    base_color_texture: Some(images.add(color_map(0.2, 1.0))),
                    uv_transform: Affine2::from_scale_angle_translation(
                        Vec2::splat(2.0),
                        0.4,
                        Vec2::new(0.1, 0.3),
                    ),
                    ..plain()
                },
                same,
            ),
        ),
        (
            "flat shading",
            sphere(
                PhongMaterial {
                    flat_shading: true,
                    ..plain()
                },
                // Faces larger than a pixel's neighbourhood, where the shader's face normal
                // (from the position's screen derivatives) is the triangle's.
                |_| Sphere::new(1.3).mesh().ico(1).expect("one subdivision"),
            ),
        ),
        (
            "unlit",
            sphere(
                PhongMaterial {
                    unlit: true,
                    emissive: LinearRgba::rgb(0.2, 0.1, 0.0),
                    ..plain()
                },
                with_vertex_colors,
            ),
        ),
        (
            "Blinn-Phong highlight",
            sphere(
                PhongMaterial {
                    specular_model: SpecularModel::BlinnPhong,
                    ..plain()
                },
                same,
            ),
        ),
        (
            "wrapped diffuse",
            sphere(
                PhongMaterial {
                    diffuse_mode: DiffuseMode::Wrap(0.4),
                    ..plain()
                },
                same,
            ),
        ),
        (
            "toon bands and highlight",
            sphere(
                PhongMaterial {
                    diffuse_mode: DiffuseMode::Toon {
                        bands: 3,
                        smoothing: 0.1,
                    },
                    specular_mode: SpecularMode::Toon { smoothing: 0.2 },
                    ..plain()
                },
                same,
            ),
        ),
        (
            "toon ramp",
            mapped(
                |images| PhongMaterial {
                    diffuse_mode: DiffuseMode::Toon {
                        bands: 3,
                        smoothing: 0.0,
                    },
                    toon_ramp_texture: Some(images.add(float_map(|x, _| {
                        [0.1 + 0.8 * x as f32 / (TEXELS - 1) as f32, 0.0, 0.0, 1.0]
                    }))),
                    ..plain()
                },
                same,
            ),
        ),
        (
            "rim",
            sphere(
                PhongMaterial {
                    rim_color: LinearRgba::rgb(0.3, 0.6, 1.0),
                    rim_strength: 1.5,
                    rim_power: 3.0,
                    ..plain()
                },
                same,
            ),
        ),
        (
            "displacement map",
            mapped(
                |images| PhongMaterial {
                    displacement_map: Some(images.add(float_map(|_, _| [0.5, 0.0, 0.0, 1.0]))),
                    displacement_scale: 0.4,
                    displacement_bias: -0.1,
                    ..plain()
                },
                same,
            ),
        ),
        ("spot light", lit_by(spot(), plain())),
        (
            "hemisphere light",
            Box::new(|world: &mut World| {
                world.insert_resource(PhongHemisphereLight {
                    sky_color: Color::srgb(0.3, 0.3, 0.5),
                    ground_color: Color::srgb(0.3, 0.2, 0.0),
                    ..default()
                });
                sphere(plain(), |mesh| mesh)(world);
            }),
        ),
        (
            "spot light's cookie",
            Box::new(|world: &mut World| {
                let image = world
                    .resource_mut::<Assets<Image>>()
                    .add(color_map(0.0, 1.0));
                world.spawn((spot(), PhongLightCookie { image, ..default() }));
                sphere(plain(), |mesh| mesh)(world);
            }),
        ),
    ]
}

/// The scenes share one app, as `render_scene` would render one scene after another: each
/// scene's entities and hemisphere light are taken out before the next is spawned, so that
/// each comparison sees its own scene (the pipelines the scenes share compile once).
#[test]
fn the_self_check_knows_every_material_feature_and_light() {
    let mut harness = Harness::new(SIZE, SIZE);
    spawn_map_lights(harness.world_mut());
    let before: HashSet<Entity> = entities(harness.world_mut());
    for (name, scene) in scenes() {
        scene(harness.world_mut());
        harness.settle();
        let rendered = harness.render_next_frame();
        let comparison = harness.compare_with_reference(&rendered);
        comparison.assert_within(name, TOLERANCE);
        assert!(
            comparison.lit_pixels >= LIT_PIXELS,
            "{name}: {} lit pixels",
            comparison.lit_pixels
        );
        comparison.assert_mostly_judged(name);
        let world = harness.world_mut();
        for entity in entities(world).difference(&before) {
            world.despawn(*entity);
        }
        world.remove_resource::<PhongHemisphereLight>();
    }
}

/// The meshes and spot lights of `world`: what a scene spawns.
fn entities(world: &mut World) -> HashSet<Entity> {
    world
        .query_filtered::<Entity, Or<(With<Mesh3d>, With<PhongSpotLight>)>>()
        .iter(world)
        .collect()
}

/// A comparison that judged most of the frame but next to nothing of one object fails: a
/// small object wholly on texel edges (2 pixels judged, 10 not) beside a large one (100
/// judged) passes the frame's fifth but not the object's half.
#[test]
fn an_object_left_mostly_unjudged_fails_the_comparison() {
    let image = bevy_phong_headless::FloatImage {
        width: 1,
        height: 1,
        pixels: vec![[0.0; 4]],
    };
    let mut comparison =
        bevy_phong_headless::Comparison::of(&image, |_| bevy_phong_headless::Expected::Clear);
    comparison.lit_pixels = 102;
    comparison.skipped_pixels = 10;
    comparison.objects.insert(1, (100, 0));
    comparison.assert_mostly_judged("the large object alone");
    comparison.objects.insert(2, (2, 10));
    let failed = std::panic::catch_unwind(|| comparison.assert_mostly_judged("both objects"));
    assert!(
        failed.is_err(),
        "the small object's pixels went unjudged unnoticed"
    );
}
