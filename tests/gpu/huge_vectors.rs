//! Directions of any scale and colors past the documented bound, rendered and compared pixel
//! by pixel with the reference model (at the frame tests' tolerance, see `frames`).
//!
//! A direction of `(3e38, 3e38, 3e38)` (whose squared length overflows `f32`) or
//! `(1e-30, -1e-30, 0)` (whose squared length underflows to zero) must light the scene as
//! the unit vector it points along; the expected image is computed by the `f64` reference
//! from the raw vector, where nothing overflows. A color of `f32::MAX` is clamped to
//! `limits::MAX_INTENSITY` (1e6) and must give finite pixels equal to the reference's with
//! the clamped value.

use crate::frames::{SIZE, TOLERANCE};
use bevy::prelude::*;
use bevy_phong::{
    prelude::*,
    reference::{self, Light},
    testing::limits::MAX_INTENSITY,
};
use bevy_phong_headless::{FloatImage, Harness, SurfaceInputs};
use glam::DVec3;

/// Objects shared by the scene files: a floor, a sphere, a cube and a torus.
const OBJECTS: &str = r#"
    (mesh: Plane(size: (12.0, 12.0)), transform: (translation: (0.0, -1.0, 0.0)),
        material: Inline((base_color: Linear(0.8, 0.8, 0.8), shininess: 8.0, specular_strength: 0.5))),
    (mesh: Sphere(radius: 1.0),
        material: Inline((base_color: Linear(1.0, 0.2, 1.0), shininess: 50.0, specular_strength: 2.0))),
    (mesh: Cuboid(size: (1.2, 1.2, 1.2)), transform: (translation: (-2.3, -0.4, 0.5), rotation: (0.0, 34.0, 0.0)),
        material: Inline((base_color: Linear(0.1, 0.1, 1.0), shininess: 50.0, specular_strength: 2.0))),
    (mesh: Torus(minor_radius: 0.35, major_radius: 0.75), transform: (translation: (2.3, -0.2, 0.5), rotation: (57.0, 0.0, 0.0)),
        material: Inline((base_color: Linear(0.1, 0.5, 0.1), shininess: 160.0))),
"#;

/// Writes `files` (name, text) into `scenes/` of a fresh asset folder; returns its path.
fn asset_folder(case: &str, files: &[(&str, String)]) -> std::path::PathBuf {
    let root = std::env::temp_dir().join(format!("bevy_phong_{case}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(root.join("scenes")).unwrap();
    for (name, text) in files {
        std::fs::write(root.join("scenes").join(name), text).unwrap();
    }
    root
}

fn assert_finite(case: &str, image: &FloatImage) {
    assert_eq!(
        image.non_finite_pixels(),
        0,
        "{case}: NaN or infinite pixels"
    );
}

/// The four directions of the scene file, as the file writes them and as `f64` holds them
/// exactly: a huge and a tiny directional light, a huge and a tiny spot axis.
const HUGE_DIRECTIONAL: [f64; 3] = [3e38, 3e38, 3e38];
const TINY_DIRECTIONAL: [f64; 3] = [1e-30, -1e-30, 0.0];
const HUGE_SPOT: [f64; 3] = [-5e36, -5.5e37, -3e37];
const TINY_SPOT: [f64; 3] = [1.5e-31, -4e-31, -2e-31];

fn ron(v: [f64; 3]) -> String {
    format!("({:e}, {:e}, {:e})", v[0], v[1], v[2])
}

/// The lights of the directions file, as the reference takes them: every direction the raw
/// vector, normalized by the reference itself.
fn reference_direction_lights(ambient: DVec3) -> reference::Lights {
    let spot =
        |position: DVec3, direction: [f64; 3], color: DVec3, inner: f64, outer: f64| Light::Spot {
            position,
            direction: DVec3::from_array(direction),
            color,
            specular: color,
            decay: [1.0, 0.0, 0.02],
            range: None,
            inner_angle: inner.to_radians(),
            outer_angle: outer.to_radians(),
            exponent: 2.0,
            edge: ConeEdge::Linear,
        };
    reference::Lights {
        ambient,
        hemisphere: None,
        lights: vec![
            Light::Directional {
                direction: DVec3::from_array(HUGE_DIRECTIONAL),
                color: DVec3::new(0.5, 0.4, 0.3),
                specular: DVec3::new(0.5, 0.4, 0.3),
            },
            Light::Directional {
                direction: DVec3::from_array(TINY_DIRECTIONAL),
                color: DVec3::new(0.3, 0.4, 0.5),
                specular: DVec3::new(0.3, 0.4, 0.5),
            },
            spot(
                DVec3::new(0.5, 5.0, 3.0),
                HUGE_SPOT,
                DVec3::new(1.0, 1.0, 0.8),
                12.5,
                17.5,
            ),
            spot(
                DVec3::new(-1.5, 4.0, 2.0),
                TINY_SPOT,
                DVec3::new(0.6, 0.8, 1.0),
                20.0,
                30.0,
            ),
        ],
        others: Default::default(),
    }
}

fn directions_file() -> String {
    format!(
        "(lights: [
            Directional(color: Linear(0.5, 0.4, 0.3), direction: {}),
            Directional(color: Linear(0.3, 0.4, 0.5), direction: {}),
            Spot(color: Linear(1.0, 1.0, 0.8), position: (0.5, 5.0, 3.0), direction: {},
                decay: (constant: 1.0, linear: 0.0, quadratic: 0.02),
                inner_angle_degrees: 12.5, outer_angle_degrees: 17.5, exponent: 2.0),
            Spot(color: Linear(0.6, 0.8, 1.0), position: (-1.5, 4.0, 2.0), direction: {},
                decay: (constant: 1.0, linear: 0.0, quadratic: 0.02),
                inner_angle_degrees: 20.0, outer_angle_degrees: 30.0, exponent: 2.0),
        ], objects: [{OBJECTS}])",
        ron(HUGE_DIRECTIONAL),
        ron(TINY_DIRECTIONAL),
        ron(HUGE_SPOT),
        ron(TINY_SPOT),
    )
}

/// How many covered pixels `lights` lights beyond the ambient term (N·L > 0 and, for a spot,
/// inside its cone): the comparison must see lit pixels, not the ambient alone.
fn directly_lit(
    harness: &mut Harness,
    rendered: &FloatImage,
    inputs: &SurfaceInputs,
    lights: &reference::Lights,
) -> usize {
    let lit = std::cell::Cell::new(0);
    let unlit = reference::Lights {
        ambient: lights.ambient,
        hemisphere: None,
        lights: Vec::new(),
        others: Default::default(),
    };
    harness.compare_with(rendered, inputs, |material, surface| {
        let material = reference::Material::from(material);
        let with = reference::shade(surface, &material, lights);
        let without = reference::shade(surface, &material, &unlit);
        if (with - without).max_element() > 1e-3 {
            lit.set(lit.get() + 1);
        }
        Some(with)
    });
    lit.get()
}

#[test]
fn huge_and_tiny_light_directions_light_the_scene_as_their_unit_vectors() {
    let root = asset_folder(
        "directions",
        &[("directions.phong_scene.ron", directions_file())],
    );
    let mut harness = Harness::with_assets(SIZE, SIZE, root.to_string_lossy().into_owned(), |_| {});
    harness
        .load_scene("scenes/directions.phong_scene.ron")
        .unwrap_or_else(|error| panic!("{error}"));
    harness.settle();
    let rendered = harness.render_next_frame();
    assert_finite("file directions", &rendered);
    let ambient: DVec3 = harness.world_mut().resource::<PhongAmbientLight>().into();
    let lights = reference_direction_lights(ambient);
    let inputs = harness.capture_inputs();
    harness
        .compare_with(&rendered, &inputs, |material, surface| {
            Some(reference::shade(
                surface,
                &reference::Material::from(material),
                &lights,
            ))
        })
        .assert_within("file_huge_and_tiny_directions", TOLERANCE);
    let lit = directly_lit(&mut harness, &rendered, &inputs, &lights);
    println!("file directions: {lit} pixels directly lit");
    assert!(
        lit > 100,
        "the lights must light the scene, not only the ambient"
    );

    // The same directions from components: transforms whose -Z axis is the huge or tiny
    // vector (a rotation and a scale of 3e38 or 1e-30); the reference takes the axis in f64.
    let world = harness.world_mut();
    let lights: Vec<Entity> = world
        .query_filtered::<Entity, Or<(With<PhongDirectionalLight>, With<PhongSpotLight>)>>()
        .iter(world)
        .collect();
    for light in lights {
        world.despawn(light);
    }
    let aimed = |direction: DVec3, scale: f32, position: Vec3| Transform {
        translation: position,
        rotation: Quat::from_rotation_arc(Vec3::NEG_Z, direction.normalize().as_vec3()),
        scale: Vec3::splat(scale),
    };
    let axis = |transform: &Transform| {
        transform.rotation.as_dquat() * (DVec3::NEG_Z * f64::from(transform.scale.x))
    };
    let directional = aimed(DVec3::new(-1.0, -1.0, -0.5), 3e38, Vec3::ZERO);
    let spot = aimed(
        DVec3::new(-0.5, -5.5, -3.0),
        1e-30,
        Vec3::new(0.5, 5.0, 3.0),
    );
    let color = Color::linear_rgb(0.7, 0.6, 0.5);
    world.spawn((PhongDirectionalLight { color, ..default() }, directional));
    world.spawn((
        PhongSpotLight {
            color,
            decay: Decay::new(1.0, 0.0, 0.02),
            range: None,
            inner_angle: 12.5_f32.to_radians(),
            outer_angle: 17.5_f32.to_radians(),
            exponent: 2.0,
            ..default()
        },
        spot,
    ));
    let rendered = harness.render_next_frame();
    assert_finite("component directions", &rendered);
    let linear = DVec3::new(0.7, 0.6, 0.5);
    let lights = reference::Lights {
        ambient,
        hemisphere: None,
        lights: vec![
            Light::Directional {
                direction: axis(&directional),
                color: linear,
                specular: linear,
            },
            Light::Spot {
                position: DVec3::new(0.5, 5.0, 3.0),
                direction: axis(&spot),
                color: linear,
                specular: linear,
                decay: [1.0, 0.0, 0.02],
                range: None,
                inner_angle: f64::from(12.5_f32.to_radians()),
                outer_angle: f64::from(17.5_f32.to_radians()),
                exponent: 2.0,
                edge: ConeEdge::Linear,
            },
        ],
        others: Default::default(),
    };
    harness
        .compare_with(&rendered, &inputs, |material, surface| {
            Some(reference::shade(
                surface,
                &reference::Material::from(material),
                &lights,
            ))
        })
        .assert_within("component_huge_and_tiny_directions", TOLERANCE);
    let lit = directly_lit(&mut harness, &rendered, &inputs, &lights);
    println!("component directions: {lit} pixels directly lit");
    assert!(
        lit > 100,
        "the lights must light the scene, not only the ambient"
    );
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn colors_past_the_bound_are_clamped_to_it_and_render_finite() {
    // Every channel of the light and of the material is at or past 1e6: f32::MAX, 1e30 and
    // 2e6 all become 1e6. Unclamped, one light on this material overflowed to infinity.
    let file = "(ambient: Some(Linear(3.4028235e38, 1e30, 2e6)), lights: [
            Point(color: Linear(3.4028235e38, 1e30, 2e6), position: (1.0, 3.0, 3.0),
                decay: (constant: 1.0, linear: 0.0, quadratic: 0.02)),
        ], objects: [
            (mesh: Sphere(radius: 1.0), material: Inline((
                base_color: Linear(3.4028235e38, 1e30, 2e6),
                specular_color: Linear(3.4028235e38, 1e30, 2e6),
                specular_strength: 3.4028235e38, ambient_factor: 1e30, shininess: 50.0))),
            (mesh: Cuboid(size: (1.2, 1.2, 1.2)), transform: (translation: (-2.3, -0.4, 0.5)),
                material: Inline((base_color: Linear(3.4028235e38, 1e30, 2e6),
                    emissive: Linear(3.4028235e38, 1e30, 2e6)))),
        ])"
    .to_owned();
    let root = asset_folder("huge_colors", &[("huge.phong_scene.ron", file)]);
    let mut harness = Harness::with_assets(SIZE, SIZE, root.to_string_lossy().into_owned(), |_| {});
    harness
        .load_scene("scenes/huge.phong_scene.ron")
        .unwrap_or_else(|error| panic!("{error}"));
    harness.settle();
    let rendered = harness.render_next_frame();
    assert_finite("huge colors", &rendered);
    let inputs = harness.capture_inputs();

    // The reference, given the clamped values by hand (not the loaded assets).
    let bound = f64::from(MAX_INTENSITY);
    let clamped = DVec3::splat(bound);
    let lights = reference::Lights {
        ambient: clamped,
        hemisphere: None,
        lights: vec![Light::Point {
            position: DVec3::new(1.0, 3.0, 3.0),
            color: clamped,
            specular: clamped,
            decay: [1.0, 0.0, 0.02],
            range: None,
        }],
        others: Default::default(),
    };
    let defaults = reference::Material::from(&PhongMaterial::default());
    let sphere = reference::Material {
        diffuse: clamped,
        specular: clamped,
        specular_strength: bound,
        ambient_factor: bound,
        shininess: 50.0,
        ..defaults.clone()
    };
    let cube = reference::Material {
        diffuse: clamped,
        emissive: clamped,
        ..defaults
    };
    let comparison = harness.compare_with(&rendered, &inputs, |material, surface| {
        // The sphere is the material with a shininess of 50; the cube keeps the default.
        let expected = if material.shininess == 50.0 {
            &sphere
        } else {
            &cube
        };
        Some(reference::shade(surface, expected, &lights))
    });
    comparison.assert_within("colors_clamped_to_the_bound", TOLERANCE);
    let brightest = rendered
        .pixels
        .iter()
        .flat_map(|p| p[..3].iter().copied())
        .fold(0.0, f32::max);
    println!("huge colors: brightest channel {brightest:e}");
    // The clamped values reach the screen: ambient · k_a · k_d alone is 1e6 · 1e6 · 1e6.
    assert!(brightest >= 1e17, "{brightest:e}");
    let _ = std::fs::remove_dir_all(&root);
}
