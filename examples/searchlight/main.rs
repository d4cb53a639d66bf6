//! Searchlights, a light kind added from outside the crate with `bevy_phong`'s extension API:
//! four beams of parallel light, one of each cross-section (circle, triangle, diamond,
//! square), sweep over a floor and a few objects that an ambient and a point light also
//! light. See `light.rs` for the light and `assets/shaders/searchlight.wesl` for its shader.
//!
//! Keys: `1`–`4` select a searchlight, `S` changes its shape, `E` its edge softness,
//! `Space` pauses the sweep.
//!
//! ```sh
//! cargo run --example searchlight                         # a window, where a display exists
//! cargo run --example searchlight -- --headless out.png   # a PNG, and exit
//! ```

#[path = "../support/mod.rs"]
mod support;

mod light;

use bevy::prelude::*;
use bevy_phong::{extension::PhongLightKindBuffer, prelude::*};
use light::{BeamShape, Searchlight, SearchlightExtension, SearchlightPlugin, SearchlitMaterial};

/// Edge widths `E` cycles through, world units.
const EDGE_WIDTHS: [f32; 3] = [0.0, 0.25, 0.8];

fn main() -> AppExit {
    let mut app = support::example_app("searchlight");
    support::show_key_help(
        &mut app,
        "1-4 select a searchlight, S shape, E edge softness, Space pause",
    )
    .add_plugins((PhongPlugin, SearchlightPlugin))
    .insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.06, 0.06, 0.08),
    })
    .init_resource::<Controls>()
    .add_systems(Startup, setup)
    .add_systems(Update, (handle_keys, sweep).chain());
    support::run_comparing::<SearchlitMaterial>(app)
}

/// Which searchlight the keys change, and whether the beams move.
#[derive(Resource, Default)]
struct Controls {
    selected: usize,
    paused: bool,
    elapsed: f32,
}

/// Where a searchlight sweeps: a circle on the floor around `center`.
#[derive(Component)]
struct Sweep {
    index: usize,
    center: Vec3,
    radius: f32,
    phase: f32,
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<SearchlitMaterial>>,
    searchlights: Res<PhongLightKindBuffer<Searchlight>>,
) {
    let mut material = |base_color: Color, shininess: f32| {
        materials.add(SearchlitMaterial {
            base: PhongMaterial {
                base_color,
                shininess,
                specular_strength: 0.6,
                ..default()
            },
            extension: SearchlightExtension::new(&searchlights),
        })
    };
    let floor = material(Color::srgb(0.75, 0.75, 0.72), 16.0);
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(16.0, 12.0))),
        MeshMaterial3d(floor),
    ));
    let objects: [(Mesh, Color, Vec3); 3] = [
        (
            Sphere::new(0.8).mesh().uv(48, 32),
            Color::srgb(0.9, 0.2, 0.6),
            Vec3::new(-2.0, 0.8, 0.0),
        ),
        (
            Cuboid::new(1.2, 1.2, 1.2).into(),
            Color::srgb(0.2, 0.4, 0.9),
            Vec3::new(0.6, 0.6, -1.0),
        ),
        (
            Cylinder::new(0.5, 1.6).into(),
            Color::srgb(0.3, 0.8, 0.3),
            Vec3::new(2.6, 0.8, 0.6),
        ),
    ];
    for (mesh, color, position) in objects {
        commands.spawn((
            Mesh3d(meshes.add(mesh)),
            MeshMaterial3d(material(color, 60.0)),
            Transform::from_translation(position),
        ));
    }

    commands.spawn((
        PhongPointLight {
            color: Color::linear_rgb(0.5, 0.45, 0.4),
            decay: Decay::DISTANCE_50,
            ..default()
        },
        Transform::from_xyz(0.0, 4.0, 4.0),
    ));

    let colors = [
        Color::linear_rgb(1.0, 0.85, 0.6),
        Color::linear_rgb(0.6, 0.9, 1.0),
        Color::linear_rgb(1.0, 0.6, 0.9),
        Color::linear_rgb(0.8, 1.0, 0.6),
    ];
    for (index, (shape, color)) in BeamShape::ALL.into_iter().zip(colors).enumerate() {
        let center = Vec3::new(
            -4.2 + 2.8 * index as f32,
            0.0,
            if index % 2 == 0 { 1.8 } else { -1.6 },
        );
        commands.spawn((
            Searchlight {
                color,
                radius: 1.1,
                shape,
                edge: EDGE_WIDTHS[index % 2],
                // The beam's parallel rays cast one orthographic shadow map.
                shadows: PhongShadows::ON,
                ..default()
            },
            Sweep {
                index,
                center,
                radius: 1.2,
                phase: index as f32 * 1.7,
            },
            Transform::default(),
        ));
    }

    commands.spawn(support::example_camera(
        Transform::from_xyz(0.0, 7.0, 9.0).looking_at(Vec3::new(0.0, 0.0, 0.3), Vec3::Y),
    ));
}

/// Moves each searchlight on its circle, 8 units above the floor, aimed at a point that
/// circles the floor, and turns its cross-section slowly.
fn sweep(
    time: Res<Time>,
    mut controls: ResMut<Controls>,
    mut lights: Query<(&Sweep, &mut Transform)>,
) {
    if !controls.paused {
        controls.elapsed += time.delta_secs();
    }
    let t = controls.elapsed * 0.6;
    for (sweep, mut transform) in &mut lights {
        let angle = t + sweep.phase;
        let target = sweep.center + sweep.radius * Vec3::new(angle.cos(), 0.0, angle.sin());
        let position = target + Vec3::new(0.8, 8.0, 1.5);
        let up = Quat::from_rotation_y(0.3 * t + sweep.phase) * Vec3::Z;
        *transform = Transform::from_translation(position).looking_at(target, up);
    }
}

fn handle_keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut controls: ResMut<Controls>,
    mut lights: Query<(&Sweep, &mut Searchlight)>,
) {
    let digits = [
        KeyCode::Digit1,
        KeyCode::Digit2,
        KeyCode::Digit3,
        KeyCode::Digit4,
    ];
    if let Some(index) = digits.iter().position(|key| keys.just_pressed(*key)) {
        controls.selected = index;
    }
    if keys.just_pressed(KeyCode::Space) {
        controls.paused = !controls.paused;
    }
    let Some((_, mut light)) = lights
        .iter_mut()
        .find(|(sweep, _)| sweep.index == controls.selected)
    else {
        return;
    };
    if keys.just_pressed(KeyCode::KeyS) {
        let next = BeamShape::ALL
            .iter()
            .position(|s| *s == light.shape)
            .map_or(0, |i| i + 1);
        light.shape = BeamShape::ALL[next % BeamShape::ALL.len()];
        println!("searchlight {}: {:?}", controls.selected + 1, light.shape);
    }
    if keys.just_pressed(KeyCode::KeyE) {
        let next = EDGE_WIDTHS
            .iter()
            .position(|e| *e == light.edge)
            .map_or(0, |i| i + 1);
        light.edge = EDGE_WIDTHS[next % EDGE_WIDTHS.len()];
        println!("searchlight {}: edge {}", controls.selected + 1, light.edge);
    }
}
