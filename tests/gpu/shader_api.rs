//! The public shader functions that the crate's own shaders do not call
//! (`shadows::light_visibility`, `shading::phong_shade`), drawn by an extension beside the
//! functions the material is drawn with (`tests/gpu/shader_api_probe.wesl`): a plane under a
//! sphere, lit by one directional light that casts shadows.

use crate::probes::harness_with_probe;
use bevy::{
    asset::uuid_handle,
    pbr::{ExtendedMaterial, MaterialExtension},
    prelude::*,
    render::render_resource::AsBindGroup,
    shader::ShaderRef,
};
use bevy_phong::prelude::*;

/// The extension whose fragment shader draws the probe.
#[derive(Asset, AsBindGroup, Reflect, Clone, Debug, Default)]
struct ApiProbe {}

const API_PROBE_SHADER: Handle<Shader> = uuid_handle!("8d2e6f41-3b9a-4c07-a1e5-6f0c2d9b7e13");

impl MaterialExtension for ApiProbe {
    fn fragment_shader() -> ShaderRef {
        API_PROBE_SHADER.into()
    }
}

type ProbedMaterial = ExtendedMaterial<PhongMaterial, ApiProbe>;

/// `light_visibility` is the visibility `shadow_factors` scales the light by: equal in every
/// pixel (the same `f32` work, to rounding: 1e-6), in shade and in light alike, with at
/// least a hundred pixels of each. `phong_shade` of a material without maps is the lit
/// color the material is drawn with, to 1e-5 (relative to the color's size, at most a few:
/// the two sum the same terms, in orders that may round differently).
#[test]
fn light_visibility_and_phong_shade_agree_with_the_drawn_path() {
    let mut harness = harness_with_probe::<ProbedMaterial>(
        &API_PROBE_SHADER,
        include_str!("shader_api_probe.wesl"),
        "tests/gpu/shader_api_probe.wesl",
    );
    let world = harness.world_mut();
    let material = world
        .resource_mut::<Assets<ProbedMaterial>>()
        .add(ProbedMaterial {
            base: PhongMaterial {
                base_color: Color::srgb(0.8, 0.6, 0.4),
                ..default()
            },
            extension: ApiProbe {},
        });
    let plane = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::default().mesh().size(8.0, 8.0));
    let sphere = world.resource_mut::<Assets<Mesh>>().add(Sphere::new(0.8));
    world.spawn((Mesh3d(plane), MeshMaterial3d(material.clone())));
    world.spawn((
        Mesh3d(sphere),
        MeshMaterial3d(material),
        Transform::from_xyz(0.0, 1.5, 0.0),
    ));
    world.spawn((
        PhongDirectionalLight {
            shadows: PhongShadows::ON,
            ..default()
        },
        Transform::default().looking_to(Vec3::new(0.3, -1.0, 0.2), Vec3::Y),
    ));
    harness.settle();
    let rendered = harness.render_next_frame();

    let covered: Vec<&[f32; 4]> = rendered
        .pixels
        .iter()
        .filter(|pixel| pixel[3] == 1.0)
        .collect();
    assert!(covered.len() > 1_000, "the plane covers the view");
    for pixel in &covered {
        assert!(
            (pixel[0] - pixel[1]).abs() <= 1e-6,
            "light_visibility {} where shadow_factors gives {}",
            pixel[0],
            pixel[1]
        );
        assert!(
            pixel[2] <= 1e-5,
            "phong_shade differs from the drawn lit color by {}",
            pixel[2]
        );
    }
    let shaded = covered.iter().filter(|pixel| pixel[0] < 0.01).count();
    let lit = covered.iter().filter(|pixel| pixel[0] > 0.99).count();
    assert!(
        shaded >= 100 && lit >= 100,
        "{shaded} pixels in shade, {lit} in light"
    );
}
