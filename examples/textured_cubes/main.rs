//! Seed 004's scene: ten textured crates lit by a directional light, a point light with
//! seed 004's fall-off (1.0, 0.09, 0.032), and a spot light from the eye with a soft edge
//! from 12.5° to 17.5°. Each crate has a base color map (planks in a steel frame), a
//! specular map (the steel shines, the wood hardly) and a normal map (grooves between the
//! planks, a bevel on the frame), made by `textures.rs`.
//!
//! `cargo run --example textured_cubes` (`-- --headless PATH` renders a PNG).
//! Keys: D directional, P point, S spot light on/off; N normal maps on/off; B Phong /
//! Blinn-Phong.

#[path = "../support/mod.rs"]
mod support;
mod textures;

use bevy::prelude::*;
use bevy_phong::prelude::*;

/// The crates' places (the course's ten cubes), each turned by `20° · i` about (1, 0.3, 0.5).
const CRATES: [Vec3; 10] = [
    Vec3::new(0.0, 0.0, 0.0),
    Vec3::new(2.0, 5.0, -15.0),
    Vec3::new(-1.5, -2.2, -2.5),
    Vec3::new(-3.8, -2.0, -12.3),
    Vec3::new(2.4, -0.4, -3.5),
    Vec3::new(-1.7, 3.0, -7.5),
    Vec3::new(1.3, -2.0, -2.5),
    Vec3::new(1.5, 2.0, -2.5),
    Vec3::new(1.5, 0.2, -1.5),
    Vec3::new(-1.3, 1.0, -1.5),
];

/// Where the eye, and the spot light it carries, are.
const EYE: Vec3 = Vec3::new(0.0, 0.0, 3.0);

/// The normal map, kept while it is switched off (key N).
#[derive(Resource)]
struct NormalMap(Handle<Image>);

fn main() -> AppExit {
    let mut app = support::example_app("textured_cubes");
    support::show_key_help(
        &mut app,
        "D directional, P point, S spot light on/off; N normal maps; B highlight model",
    )
    .add_plugins(PhongPlugin)
    .insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.2, 0.2, 0.2),
    })
    .add_systems(Startup, setup)
    .add_systems(Update, keys);
    support::run(app)
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<PhongMaterial>>,
    mut images: ResMut<Assets<Image>>,
) {
    let normal_map = images.add(textures::crate_normal_map());
    let material = materials.add(PhongMaterial {
        base_color_texture: Some(images.add(textures::crate_base_color())),
        specular_texture: Some(images.add(textures::crate_specular())),
        normal_map_texture: Some(normal_map.clone()),
        shininess: 32.0,
        ..default()
    });
    commands.insert_resource(NormalMap(normal_map));
    let cube = meshes.add(
        Mesh::from(Cuboid::new(1.0, 1.0, 1.0))
            .with_generated_tangents()
            .expect("a cuboid has UVs, normals and indices"),
    );
    let axis = Vec3::new(1.0, 0.3, 0.5).normalize();
    for (index, position) in CRATES.into_iter().enumerate() {
        commands.spawn((
            Mesh3d(cube.clone()),
            MeshMaterial3d(material.clone()),
            Transform::from_translation(position).with_rotation(Quat::from_axis_angle(
                axis,
                (20.0 * index as f32).to_radians(),
            )),
        ));
    }

    // The course's lights: each with diffuse 0.5 (directional 0.4), specular 1.
    commands.spawn((
        PhongDirectionalLight {
            color: Color::linear_rgb(0.4, 0.4, 0.4),
            specular: Some(Color::linear_rgb(0.5, 0.5, 0.5)),
            ..default()
        },
        Transform::default().looking_to(Vec3::new(-0.2, -1.0, -0.3), Vec3::Z),
    ));
    commands.spawn((
        PhongPointLight {
            color: Color::linear_rgb(0.8, 0.6, 0.4),
            specular: Some(Color::WHITE),
            decay: Decay::new(1.0, 0.09, 0.032),
            range: None,
            ..default()
        },
        Transform::from_xyz(0.7, 0.2, 2.0),
    ));
    commands.spawn((
        PhongSpotLight {
            color: Color::linear_rgb(0.5, 0.5, 0.5),
            specular: Some(Color::WHITE),
            decay: Decay::new(1.0, 0.09, 0.032),
            inner_angle: 12.5_f32.to_radians(),
            outer_angle: 17.5_f32.to_radians(),
            ..default()
        },
        Transform::from_translation(EYE).looking_to(Vec3::NEG_Z, Vec3::Y),
    ));
    commands.spawn(support::example_camera(
        Transform::from_translation(EYE).looking_to(Vec3::NEG_Z, Vec3::Y),
    ));
}

#[allow(clippy::type_complexity, reason = "one query per light kind")]
fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut materials: ResMut<Assets<PhongMaterial>>,
    normal_map: Res<NormalMap>,
    mut lights: ParamSet<(
        Query<&mut Visibility, With<PhongDirectionalLight>>,
        Query<&mut Visibility, With<PhongPointLight>>,
        Query<&mut Visibility, With<PhongSpotLight>>,
    )>,
) {
    if keys.just_pressed(KeyCode::KeyD) {
        support::toggle_visibility(&mut lights.p0());
    }
    if keys.just_pressed(KeyCode::KeyP) {
        support::toggle_visibility(&mut lights.p1());
    }
    if keys.just_pressed(KeyCode::KeyS) {
        support::toggle_visibility(&mut lights.p2());
    }
    if keys.just_pressed(KeyCode::KeyN) {
        for (_, material) in materials.iter_mut() {
            material.normal_map_texture = match material.normal_map_texture {
                Some(_) => None,
                None => Some(normal_map.0.clone()),
            };
        }
    }
    if keys.just_pressed(KeyCode::KeyB) {
        support::switch_specular_model(&mut materials);
    }
}
