//! The searchlight example's extension (`examples/searchlight/`), rendered and compared with
//! its f64 reference on each pixel's own inputs: every shape, hard and soft edges, a beam
//! that misses everything, and a beam with objects behind it.

use crate::shading_normals::tangent_sphere;
use crate::{
    frames::TOLERANCE,
    light::{
        BeamShape, Searchlight, SearchlightExtension, SearchlightPlugin, SearchlitMaterial,
        reference::ReferenceSearchlight,
    },
    texture_maps::{
        SrgbDecoding, color_map, lit_color, loaded_images, normal_map, spawn_map_lights, texels_at,
    },
};
use bevy::prelude::*;
use bevy_phong::{extension::PhongLightKindBuffer, prelude::*, reference};
use bevy_phong_headless::{FloatImage, Harness, SurfaceInputs};

/// Pixels whose f64 distance from a hard beam boundary is below this many world units are
/// not judged: the f32 shader computes that distance from coordinates of a few units with
/// an error near 1e-6, so within 1e-4 of the boundary either side may be right.
const HARD_EDGE_BAND: f64 = 1e-4;

/// At most this share of the lit pixels may sit in that band (it is a thin line).
const MAX_SKIPPED_SHARE: f64 = 0.02;

/// A `size`² harness with the searchlights' plugin, under an ambient light of 0.05, and the
/// extension that binds their buffer to a material.
pub(crate) fn searchlit_harness(size: u32) -> (Harness, SearchlightExtension) {
    let mut harness = Harness::with_plugins(size, size, |app| {
        app.add_plugins(SearchlightPlugin);
    });
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.05, 0.05, 0.05),
    });
    let extension =
        SearchlightExtension::new(world.resource::<PhongLightKindBuffer<Searchlight>>());
    (harness, extension)
}

pub(crate) fn searchlit_scene() -> (Harness, SurfaceInputs<SearchlitMaterial>) {
    let (mut harness, extension) = searchlit_harness(128);
    let world = harness.world_mut();
    let objects: [(Mesh, Transform, Color, f32); 3] = [
        (
            Plane3d::default().mesh().size(12.0, 12.0).into(),
            Transform::from_xyz(0.0, -1.0, 0.0),
            Color::srgb(0.8, 0.8, 0.8),
            10.0,
        ),
        (
            Sphere::new(1.0).mesh().uv(48, 32),
            Transform::default(),
            Color::srgb(1.0, 0.3, 0.6),
            60.0,
        ),
        (
            Cuboid::new(1.2, 1.2, 1.2).into(),
            Transform::from_xyz(2.2, -0.4, 0.3).with_rotation(Quat::from_rotation_y(0.5)),
            Color::srgb(0.2, 0.4, 1.0),
            40.0,
        ),
    ];
    for (mesh, transform, base_color, shininess) in objects {
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        let material = world
            .resource_mut::<Assets<SearchlitMaterial>>()
            .add(SearchlitMaterial {
                base: PhongMaterial {
                    base_color,
                    shininess,
                    ..default()
                },
                extension: extension.clone(),
            });
        world.spawn((Mesh3d(mesh), MeshMaterial3d(material), transform));
    }
    harness.settle();
    let inputs = harness.capture_inputs_of::<SearchlitMaterial>();
    (harness, inputs)
}

/// The searchlights of the scene, for the reference.
fn reference_searchlights(harness: &mut Harness) -> Vec<ReferenceSearchlight> {
    let world = harness.world_mut();
    world
        .query::<(&Searchlight, &GlobalTransform)>()
        .iter(world)
        .map(|(light, transform)| ReferenceSearchlight::new(light, transform))
        .collect()
}

/// Renders the next frame and compares it with Phong lighting plus every searchlight term,
/// leaving out pixels on a hard beam boundary.
pub(crate) fn check_searchlit(
    harness: &mut Harness,
    inputs: &SurfaceInputs<SearchlitMaterial>,
    case: &str,
) -> FloatImage {
    let rendered = harness.render_next_frame();
    // The searchlights are in the model's lights (`PhongLightKind::reference_light`).
    let lights = harness.reference_lights();
    let searchlights = reference_searchlights(harness);
    let comparison = harness.compare_with(&rendered, inputs, |material, surface| {
        let on_hard_boundary = searchlights.iter().any(|light| {
            let (along, boundary) = light.beam_coordinates(surface.position);
            light.edge == 0.0 && along > 0.0 && boundary.abs() < HARD_EDGE_BAND
        });
        if on_hard_boundary {
            return None;
        }
        let material = reference::Material::from(&material.base);
        Some(reference::shade(surface, &material, &lights))
    });
    comparison.assert_within(case, TOLERANCE);
    let skipped_share = comparison.skipped_pixels as f64 / comparison.lit_pixels as f64;
    assert!(
        skipped_share <= MAX_SKIPPED_SHARE,
        "{case}: {} pixels on a hard boundary is more than a thin line",
        comparison.skipped_pixels
    );
    rendered
}

#[test]
fn searchlight_matches_its_reference_for_every_shape_hard_and_soft() {
    let (mut harness, inputs) = searchlit_scene();
    let light = harness
        .world_mut()
        .spawn((
            Searchlight {
                color: Color::linear_rgb(1.5, 1.3, 1.0),
                radius: 1.6,
                decay: Decay::linear(0.05),
                ..default()
            },
            Transform::from_xyz(0.6, 6.0, 2.5)
                .looking_at(Vec3::new(0.4, -1.0, 0.2), Vec3::new(0.3, 0.0, 1.0)),
        ))
        .id();
    for shape in BeamShape::ALL {
        for edge in [0.0, 0.4] {
            let mut searchlight = harness.world_mut().get_mut::<Searchlight>(light).unwrap();
            searchlight.shape = shape;
            searchlight.edge = edge;
            check_searchlit(
                &mut harness,
                &inputs,
                &format!("searchlight_{shape:?}_edge_{edge}"),
            );
        }
    }
}

#[test]
fn searchlight_that_misses_everything_adds_nothing() {
    let (mut harness, inputs) = searchlit_scene();
    harness.world_mut().spawn((
        PhongPointLight {
            color: Color::linear_rgb(0.6, 0.6, 0.6),
            decay: Decay::DISTANCE_50,
            ..default()
        },
        Transform::from_xyz(-2.0, 3.0, 2.0),
    ));
    // Aimed at the floor well outside the view and the objects.
    harness.world_mut().spawn((
        Searchlight {
            color: Color::linear_rgb(5.0, 5.0, 5.0),
            radius: 1.0,
            edge: 0.5,
            ..default()
        },
        Transform::from_xyz(30.0, 5.0, 0.0).looking_at(Vec3::new(30.0, -1.0, 0.0), Vec3::Z),
    ));
    assert_no_beam_light(&mut harness, &inputs, "searchlight_missing_everything");
}

#[test]
fn searchlight_does_not_light_what_is_behind_it() {
    let (mut harness, inputs) = searchlit_scene();
    // Above the sphere, shining straight up: the sphere, the cube and the floor all lie in the
    // beam's prism, but behind the light.
    harness.world_mut().spawn((
        Searchlight {
            color: Color::linear_rgb(5.0, 5.0, 5.0),
            radius: 4.0,
            ..default()
        },
        Transform::from_xyz(0.0, 1.5, 0.0).looking_to(Vec3::Y, Vec3::Z),
    ));
    assert_no_beam_light(&mut harness, &inputs, "searchlight_behind");
}

/// Renders the next frame and checks it against Phong lighting alone: no pixel may show
/// the searchlight.
fn assert_no_beam_light(
    harness: &mut Harness,
    inputs: &SurfaceInputs<SearchlitMaterial>,
    case: &str,
) {
    let rendered = harness.render_next_frame();
    // Phong lighting alone: the model without the searchlights.
    let lights = reference::Lights {
        others: Default::default(),
        ..harness.reference_lights()
    };
    harness
        .compare_with(
            &rendered,
            inputs,
            |material: &SearchlitMaterial, surface| {
                Some(reference::shade(surface, &(&material.base).into(), &lights))
            },
        )
        .assert_within(case, TOLERANCE);
}

/// The extension's surfaces are `PhongMaterial`'s as its maps and the mesh's vertex colors
/// give them (the crate's shader API, `bevy_phong::shaders::fragment`): a sphere with base
/// color, specular, emissive and normal maps, and a cube with vertex colors and a base color
/// map, under the map tests' lights and a soft searchlight, each pixel against the reference
/// model with those maps plus the searchlight's term on the mapped surface. Pixels on a
/// texel's edge are not judged (either texel may be sampled); at most a fifth of them.
#[test]
fn searchlit_surfaces_show_their_maps_and_vertex_colors() {
    let mut harness = Harness::with_plugins(128, 128, |app| {
        app.add_plugins(SearchlightPlugin);
    });
    let world = harness.world_mut();
    spawn_map_lights(world);
    let extension =
        SearchlightExtension::new(world.resource::<PhongLightKindBuffer<Searchlight>>());
    let mut images = world.resource_mut::<Assets<Image>>();
    let base_color = images.add(color_map(0.2, 1.0));
    let specular = images.add(color_map(0.0, 1.0));
    let emissive = images.add(color_map(0.0, 0.3));
    let normals = images.add(normal_map());
    let every_map = PhongMaterial {
        base_color_texture: Some(base_color.clone()),
        specular_texture: Some(specular),
        emissive_texture: Some(emissive),
        normal_map_texture: Some(normals),
        specular_strength: 2.0,
        shininess: 40.0,
        emissive: LinearRgba::WHITE,
        ..default()
    };
    let colored = PhongMaterial {
        base_color_texture: Some(base_color),
        shininess: 20.0,
        ..default()
    };
    let mut cube = Mesh::from(Cuboid::new(1.2, 1.2, 1.2));
    let colors: Vec<[f32; 4]> = cube
        .attribute(Mesh::ATTRIBUTE_POSITION)
        .and_then(|positions| positions.as_float3())
        .expect("a cuboid has positions")
        .iter()
        .map(|&[x, y, z]| [0.5 + 0.4 * x, 0.5 + 0.4 * y, 0.5 - 0.4 * z, 1.0])
        .collect();
    cube.insert_attribute(Mesh::ATTRIBUTE_COLOR, colors);
    let objects = [
        (tangent_sphere(1.2), Transform::default(), every_map),
        (
            cube,
            Transform::from_xyz(2.2, -0.3, 0.5).with_rotation(Quat::from_rotation_y(-0.6)),
            colored,
        ),
    ];
    for (mesh, transform, base) in objects {
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        let material = world
            .resource_mut::<Assets<SearchlitMaterial>>()
            .add(SearchlitMaterial {
                base,
                extension: extension.clone(),
            });
        world.spawn((Mesh3d(mesh), MeshMaterial3d(material), transform));
    }
    world.spawn((
        Searchlight {
            color: Color::linear_rgb(1.2, 1.1, 0.9),
            radius: 2.0,
            edge: 0.6,
            ..default()
        },
        Transform::from_xyz(1.0, 6.0, 2.0).looking_at(Vec3::new(1.0, 0.0, 0.0), Vec3::Z),
    ));
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps_of::<SearchlitMaterial>();
    // The searchlight is in the model's lights, lit on the mapped surface.
    let lights = harness.reference_lights();
    let images = loaded_images(&mut harness);
    let comparison = harness.compare_pixels(&rendered, &inputs, |material, surface, pixel| {
        let base = &material.base;
        // The maps here are linear (`Rgba8Unorm`): nothing to decode.
        let texels = texels_at(base, &inputs, pixel, &images, SrgbDecoding::Exact)?;
        lit_color(base, surface, pixel, &inputs, &texels, &images, &lights)
    });
    comparison.assert_within("searchlit maps", TOLERANCE);
    comparison.assert_mostly_judged("searchlit maps");
}
