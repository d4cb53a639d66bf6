//! What a new user does first, rendered: the minimal example's scene as it spawns it, and a
//! scene built only with Bevy's own types (`StandardMaterial`, `PointLight`, `SpotLight`,
//! `DirectionalLight`) switched to Phong by `PhongStandardMaterialPlugin` and
//! `PhongBevyLightsPlugin`. Each is compared pixel by pixel with the reference model, within
//! the render tests' [`TOLERANCE`] (f32 rounding; see `frames`).
//!
//! The conversions themselves are checked against values worked by hand in the crate's unit
//! tests (`material::from_standard`, `interop`); here the switched scene must be drawn, lit
//! by every mirrored light, exactly as the materials and lights it was switched to say.

use crate::frames::{SIZE, TOLERANCE};
use bevy::{ecs::system::RunSystemOnce, prelude::*};
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;

#[path = "../../examples/minimal.rs"]
#[allow(dead_code, reason = "the test runs the example's setup, not its main")]
mod minimal;

#[test]
fn the_minimal_example_draws_what_the_reference_model_says() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    world
        .run_system_once(minimal::setup)
        .expect("the example's setup runs");
    // One frame propagates the camera's transform, which the harness adopts.
    harness.app.update();
    let world = harness.world_mut();
    let camera = world
        .query_filtered::<Entity, (With<Camera3d>, Without<bevy_phong_headless::HarnessCamera>)>()
        .single(world)
        .expect("the example spawns one camera");
    harness.adopt_camera(camera);
    harness.settle();
    let rendered = harness.render_next_frame();
    harness
        .compare_with_reference(&rendered)
        .assert_within("the minimal example", TOLERANCE);
}

/// Bevy's materials on a floor and three spheres: a default dielectric, a tinted rough
/// plastic, a smooth metal; lit by Bevy's point, spot and directional lights.
fn spawn_bevy_scene(world: &mut World) -> Vec<Entity> {
    let materials = [
        StandardMaterial {
            base_color: Color::srgb(0.7, 0.7, 0.7),
            perceptual_roughness: 0.9,
            ..default()
        },
        StandardMaterial::default(),
        StandardMaterial {
            base_color: Color::srgb(0.2, 0.5, 0.9),
            perceptual_roughness: 0.35,
            reflectance: 0.7,
            specular_tint: Color::srgb(1.0, 0.6, 0.6),
            ..default()
        },
        StandardMaterial {
            base_color: Color::srgb(1.0, 0.8, 0.3),
            metallic: 1.0,
            perceptual_roughness: 0.45,
            ..default()
        },
    ];
    let meshes: [(Mesh, Transform); 4] = [
        (
            Plane3d::default().mesh().size(12.0, 12.0).into(),
            Transform::from_xyz(0.0, -1.0, 0.0),
        ),
        (
            Sphere::new(0.8).mesh().uv(48, 32),
            Transform::from_xyz(-1.8, -0.2, 0.0),
        ),
        (
            Sphere::new(0.8).mesh().uv(48, 32),
            Transform::from_xyz(0.0, -0.2, 0.0),
        ),
        (
            Sphere::new(0.8).mesh().uv(48, 32),
            Transform::from_xyz(1.8, -0.2, 0.0),
        ),
    ];
    let spawned = meshes
        .into_iter()
        .zip(materials)
        .map(|((mesh, transform), material)| {
            let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
            let material = world
                .resource_mut::<Assets<StandardMaterial>>()
                .add(material);
            world
                .spawn((Mesh3d(mesh), MeshMaterial3d(material), transform))
                .id()
        })
        .collect();
    world.spawn((
        PointLight {
            intensity: 400_000.0,
            range: 20.0,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(-2.0, 2.5, 2.0),
    ));
    world.spawn((
        SpotLight {
            intensity: 600_000.0,
            color: Color::srgb(0.6, 0.8, 1.0),
            range: 20.0,
            inner_angle: 0.3,
            outer_angle: 0.6,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(2.5, 3.0, 1.5).looking_at(Vec3::new(1.8, -0.2, 0.0), Vec3::Y),
    ));
    world.spawn((
        DirectionalLight {
            illuminance: 3_000.0,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    spawned
}

#[test]
fn a_scene_of_bevys_own_types_switched_to_phong_follows_the_reference_model() {
    let mut harness = Harness::with_plugins(SIZE, SIZE, |app| {
        app.add_plugins((PhongStandardMaterialPlugin, PhongBevyLightsPlugin));
    });
    harness.world_mut().insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.03, 0.03, 0.03),
    });
    let meshes = spawn_bevy_scene(harness.world_mut());
    harness.look_from(Vec3::new(0.0, 2.5, 6.0));
    harness.settle();

    // Each mesh is drawn with the Phong material `From` makes of its StandardMaterial.
    let world = harness.world_mut();
    for &mesh in &meshes {
        let entity = world.entity(mesh);
        assert!(!entity.contains::<MeshMaterial3d<StandardMaterial>>());
        let phong = entity
            .get::<MeshMaterial3d<PhongMaterial>>()
            .expect("switched to a PhongMaterial");
        assert!(world.resource::<Assets<PhongMaterial>>().contains(&phong.0));
    }
    // The metal sphere's: no diffuse, its color as specular, roughness 0.45.
    let metal = world
        .entity(meshes[3])
        .get::<MeshMaterial3d<PhongMaterial>>()
        .unwrap();
    let metal = world
        .resource::<Assets<PhongMaterial>>()
        .get(&metal.0)
        .unwrap();
    assert_eq!(metal.base_color.to_linear().red, 0.0);
    // The exponent fitted to Bevy's lobe at 0.45 (SPEC.md, "Metallic-roughness map").
    let fitted = bevy_phong::reference::shininess_from_roughness(0.45) as f32;
    assert!(
        (metal.shininess - fitted).abs() < 1e-3,
        "{}",
        metal.shininess
    );
    // Every Bevy light lights them.
    let lights = harness.reference_lights();
    assert_eq!(lights.lights.len(), 3, "the point, spot and sun mirrored");

    let rendered = harness.render_next_frame();
    harness
        .compare_with_reference(&rendered)
        .assert_within("Bevy's types switched to Phong", TOLERANCE);
}

/// Under the mirror each view is lit by its own camera's Bevy ambient light: the camera's
/// `AmbientLight` where it has one, else `GlobalAmbientLight` (Bevy's per-view uniform, read
/// by the shader). The two are far apart (an orange light 25 times as bright as a faint
/// blue one), so that a view lit by the other one fails the comparison by far more than the
/// render tests' tolerance.
#[test]
fn each_camera_is_lit_by_its_own_bevy_ambient_light() {
    let mut harness = Harness::with_plugins(SIZE, SIZE, |app| {
        app.add_plugins((PhongStandardMaterialPlugin, PhongBevyLightsPlugin));
    });
    harness.world_mut().insert_resource(GlobalAmbientLight {
        color: Color::srgb(0.3, 0.5, 1.0),
        brightness: 60.0,
        ..default()
    });
    spawn_bevy_scene(harness.world_mut());
    harness.camera_mut().insert(AmbientLight {
        color: Color::srgb(1.0, 0.6, 0.2),
        brightness: 1_500.0,
        ..default()
    });
    harness.look_from(Vec3::new(0.0, 2.5, 6.0));
    harness.settle();
    // Without any Phong ambient light of its own, the scene's is the camera's, converted.
    assert_eq!(
        *harness.world_mut().resource::<PhongAmbientLight>(),
        PhongAmbientLight::NONE
    );
    let rendered = harness.render_next_frame();
    harness
        .compare_with_reference(&rendered)
        .assert_within("the camera's own AmbientLight", TOLERANCE);

    harness.camera_mut().remove::<AmbientLight>();
    harness.settle();
    let rendered = harness.render_next_frame();
    harness
        .compare_with_reference(&rendered)
        .assert_within("GlobalAmbientLight, the camera having none", TOLERANCE);
}
