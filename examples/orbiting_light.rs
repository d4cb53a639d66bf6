//! Seed 003's scene: a sphere, a box and a torus on a plane, lit by one light that circles
//! 20 units above them, with Blinn-Phong highlights of shininess 160.
//!
//! The seed's values carry over directly: `k_d = 0.6` times each object's color, `k_s = 0.8`
//! (white), shininess 160, and its uncolored ambient `k_a · 0.6 = 0.12` as emissive (this
//! crate's ambient term is tinted by `k_d`, the seed's is not). The seed ray-marches a box
//! with rounded edges; here the box is a plain cuboid. The seed's shadows are the light's
//! shadow maps that dim the diffuse term only, [`PhongShadows::DIFFUSE_DIMMED`]: a shadowed point keeps 10 %
//! of the diffuse term and the whole highlight. The seed's diffuse term reads `materialColor / r * r`, which cancels to no
//! fall-off, so the light has none either. The seed's coordinates are left-handed (x to the
//! right while looking along +z); x is mirrored here so that the picture is the seed's.
//!
//! ```sh
//! cargo run --example orbiting_light                       # a window, where a display exists
//! cargo run --example orbiting_light -- --headless out.png # a PNG, and exit
//! ```
//!
//! Keys: B cycles the highlight model (Blinn-Phong, normalized, Phong), S the shadows on and off, Space pauses the light.

mod support;

use bevy::prelude::*;
use bevy_phong::prelude::*;
use std::f32::consts::FRAC_PI_2;

/// The light circles at this height, this far from the axis (seed 003's
/// `vec3(4.0 * sin(t), 20.0, 4.0 * cos(t))`, x mirrored).
const LIGHT_HEIGHT: f32 = 20.0;
const LIGHT_CIRCLE_RADIUS: f32 = 4.0;

#[derive(Component)]
struct Orbiting;

#[derive(Resource, Default)]
struct Paused(bool);

fn main() -> AppExit {
    let mut app = support::example_app("orbiting_light");
    support::show_key_help(&mut app, "B highlight model, S shadows, Space pause")
        .add_plugins(PhongPlugin)
        .insert_resource(PhongAmbientLight::NONE)
        .init_resource::<Paused>()
        .add_systems(Startup, setup)
        .add_systems(Update, (orbit, keys));
    support::run(app)
}

/// Seed 003's material for an object of `color`.
fn seed_material(color: Vec3) -> PhongMaterial {
    let diffuse = 0.6 * color;
    PhongMaterial {
        base_color: Color::linear_rgb(diffuse.x, diffuse.y, diffuse.z),
        specular_color: Color::WHITE,
        specular_strength: 0.8,
        shininess: 160.0,
        specular_model: SpecularModel::BlinnPhong,
        emissive: LinearRgba::rgb(0.12, 0.12, 0.12),
        ..default()
    }
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<PhongMaterial>>,
) {
    let objects: [(Mesh, Vec3, Vec3); 4] = [
        (
            Plane3d::default().mesh().size(60.0, 60.0).into(),
            Vec3::new(0.0, 0.0, 5.0),
            Vec3::new(0.2, 0.0, 0.0),
        ),
        (
            Sphere::new(0.8).mesh().uv(64, 48),
            Vec3::new(0.0, 1.0, 5.0),
            Vec3::new(0.2, 0.0, 1.0),
        ),
        (
            Cuboid::new(1.6, 0.6, 1.2).into(),
            Vec3::new(-2.0, 1.0, 5.0),
            Vec3::new(0.7, 0.2, 0.0),
        ),
        (
            // Seed 003's torus: ring radius 0.6, tube radius 0.2, lying flat.
            Torus::new(0.4, 0.8)
                .mesh()
                .minor_resolution(32)
                .major_resolution(64)
                .into(),
            Vec3::new(2.0, 1.0, 5.0),
            Vec3::new(0.8, 0.9, 0.0),
        ),
    ];
    for (mesh, position, color) in objects {
        commands.spawn((
            Mesh3d(meshes.add(mesh)),
            MeshMaterial3d(materials.add(seed_material(color))),
            Transform::from_translation(position),
        ));
    }

    commands.spawn((
        PhongPointLight {
            shadows: PhongShadows {
                resolution: 2048,
                ..PhongShadows::DIFFUSE_DIMMED
            },
            ..default()
        },
        Transform::from_translation(light_position(0.0)),
        Orbiting,
    ));

    // The seed's eye at (0, 2, 0) looking along +Z, with a 90° vertical field of view.
    commands.spawn((
        support::example_camera(Transform::from_xyz(0.0, 2.0, 0.0).looking_to(Vec3::Z, Vec3::Y)),
        Projection::Perspective(PerspectiveProjection {
            fov: FRAC_PI_2,
            ..default()
        }),
    ));
}

fn light_position(seconds: f32) -> Vec3 {
    Vec3::new(
        -LIGHT_CIRCLE_RADIUS * seconds.sin(),
        LIGHT_HEIGHT,
        LIGHT_CIRCLE_RADIUS * seconds.cos(),
    )
}

fn orbit(
    time: Res<Time>,
    paused: Res<Paused>,
    mut seconds: Local<f32>,
    mut light: Query<&mut Transform, With<Orbiting>>,
) {
    if !paused.0 {
        *seconds += time.delta_secs();
    }
    for mut transform in &mut light {
        transform.translation = light_position(*seconds);
    }
}

fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut paused: ResMut<Paused>,
    mut materials: ResMut<Assets<PhongMaterial>>,
    mut lights: Query<&mut PhongPointLight, With<Orbiting>>,
) {
    if keys.just_pressed(KeyCode::KeyB) {
        support::switch_specular_model(&mut materials);
    }
    if keys.just_pressed(KeyCode::KeyS) {
        for mut light in &mut lights {
            light.shadows.enabled = !light.shadows.enabled;
        }
    }
    if keys.just_pressed(KeyCode::Space) {
        paused.0 = !paused.0;
    }
}
