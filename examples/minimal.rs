//! The smallest Phong scene: a sphere, a point light, a sun and a camera, as a game writes
//! it. `cargo run --example minimal` opens a window; the render tests draw the same `setup`
//! headless and compare it with the reference model (`tests/gpu/adoption.rs`).

use bevy::prelude::*;
use bevy_phong::prelude::*;

fn main() {
    App::new()
        // PhongPlugin after DefaultPlugins: it needs Bevy's assets and renderer.
        .add_plugins((DefaultPlugins, PhongPlugin))
        .add_systems(Startup, setup)
        .run();
}

/// Spawns the scene: lights are entities with a `Transform`, the ambient light a resource.
pub fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<PhongMaterial>>,
) {
    commands.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.05, 0.05, 0.05),
    });
    commands.spawn((
        PhongPointLight {
            color: Color::srgb(1.0, 0.0, 0.0),
            decay: Decay::quadratic(0.02),
            ..default()
        },
        Transform::from_xyz(-3.0, 3.0, 0.0),
    ));
    commands.spawn((
        PhongDirectionalLight {
            color: Color::linear_rgb(0.6, 0.6, 0.6),
            ..default()
        },
        Transform::from_xyz(2.0, 3.0, 4.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Sphere::new(1.0))),
        MeshMaterial3d(materials.add(PhongMaterial {
            base_color: Color::srgb(1.0, 0.0, 1.0),
            specular_strength: 2.0,
            shininess: 50.0,
            ..default()
        })),
    ));
    commands.spawn((Camera3d::default(), Transform::from_xyz(0.0, 0.0, 6.0)));
}
