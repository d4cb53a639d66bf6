//! Two thousand colored point lights, each with a range, circling over a field of spheres:
//! per-camera light clusters let each fragment loop over the few dozen lights that reach it.
//!
//! ```sh
//! cargo run --example many_lights                       # a window, where a display exists
//! cargo run --example many_lights -- --headless out.png # a PNG, and exit
//! ```
//!
//! Keys: G turns the light clusters on and off (the frame time printed each second shows the
//! difference), B cycles the highlight model (Phong, Blinn-Phong, normalized), Space pauses
//! the lights.

mod support;

use bevy::{diagnostic::FrameTimeDiagnosticsPlugin, prelude::*};
use bevy_phong::prelude::*;

/// Number of point lights.
const LIGHTS: usize = 2000;
/// Half the width of the field, world units.
const HALF_WIDTH: f32 = 20.0;

/// A light's circle: center, radius, angular speed (radians per second) and phase.
#[derive(Component)]
struct Orbit {
    center: Vec3,
    radius: f32,
    speed: f32,
    phase: f32,
}

#[derive(Resource, Default)]
struct Paused(bool);

fn main() -> AppExit {
    let mut app = support::example_app("many_lights");
    support::show_key_help(
        &mut app,
        "G light clusters on/off, B highlight model, Space pause",
    )
    .add_plugins((PhongPlugin, FrameTimeDiagnosticsPlugin::default()))
    .insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.02, 0.02, 0.02),
    })
    .init_resource::<Paused>()
    .add_systems(Startup, setup)
    .add_systems(Update, (move_lights, keys, report_frame_time));
    support::run(app)
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<PhongMaterial>>,
) {
    commands.spawn((
        Mesh3d(
            meshes.add(
                Plane3d::default()
                    .mesh()
                    .size(2.0 * HALF_WIDTH, 2.0 * HALF_WIDTH),
            ),
        ),
        MeshMaterial3d(materials.add(PhongMaterial {
            base_color: Color::srgb(0.6, 0.6, 0.6),
            shininess: 16.0,
            specular_strength: 0.5,
            ..default()
        })),
        Transform::from_xyz(0.0, -0.6, 0.0),
    ));
    let sphere = meshes.add(Sphere::new(0.6).mesh().uv(32, 20));
    let sphere_material = materials.add(PhongMaterial {
        base_color: Color::srgb(0.9, 0.9, 0.9),
        shininess: 60.0,
        ..default()
    });
    for x in -10..10 {
        for z in -10..10 {
            commands.spawn((
                Mesh3d(sphere.clone()),
                MeshMaterial3d(sphere_material.clone()),
                Transform::from_xyz(x as f32 * 2.0 + 1.0, 0.0, z as f32 * 2.0 + 1.0),
            ));
        }
    }

    for i in 0..LIGHTS {
        let t = i as f32;
        // The R2 sequence spreads the lights evenly over the field.
        let (u, v, w) = (
            (0.5 + t * 0.754_877_7).fract(),
            (0.5 + t * 0.569_840_3).fract(),
            (t * 0.618_034).fract(),
        );
        let center = Vec3::new(
            (u * 2.0 - 1.0) * HALF_WIDTH,
            -0.3 + 0.6 * w,
            (v * 2.0 - 1.0) * HALF_WIDTH,
        );
        let orbit = Orbit {
            center,
            radius: 0.3 + 1.0 * w,
            speed: 0.3 + 0.7 * u,
            phase: t,
        };
        commands.spawn((
            PhongPointLight {
                color: Color::hsl(w * 360.0, 1.0, 0.5),
                decay: Decay::quadratic(4.0),
                range: Some(1.5),
                ..default()
            },
            Transform::from_translation(orbit.position(0.0)),
            orbit,
        ));
    }

    commands.spawn(support::example_camera(
        Transform::from_xyz(0.0, 16.0, 22.0).looking_at(Vec3::new(0.0, 0.0, 2.0), Vec3::Y),
    ));
}

impl Orbit {
    fn position(&self, seconds: f32) -> Vec3 {
        let angle = self.phase + self.speed * seconds;
        self.center + self.radius * Vec3::new(angle.cos(), 0.0, angle.sin())
    }
}

fn move_lights(time: Res<Time>, paused: Res<Paused>, mut lights: Query<(&Orbit, &mut Transform)>) {
    if paused.0 {
        return;
    }
    let seconds = time.elapsed_secs();
    for (orbit, mut transform) in &mut lights {
        transform.translation = orbit.position(seconds);
    }
}

fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut culling: ResMut<PhongLightCulling>,
    mut paused: ResMut<Paused>,
    mut materials: ResMut<Assets<PhongMaterial>>,
) {
    if keys.just_pressed(KeyCode::KeyG) {
        culling.clusters = !culling.clusters;
        println!(
            "light clusters {}",
            if culling.clusters { "on" } else { "off" }
        );
    }
    if keys.just_pressed(KeyCode::KeyB) {
        support::switch_specular_model(&mut materials);
    }
    if keys.just_pressed(KeyCode::Space) {
        paused.0 = !paused.0;
    }
}

/// Prints the average frame time once a second (windowed runs).
fn report_frame_time(
    time: Res<Time<Real>>,
    diagnostics: Res<bevy::diagnostic::DiagnosticsStore>,
    mut last: Local<f32>,
) {
    let now = time.elapsed_secs();
    if now - *last < 1.0 {
        return;
    }
    *last = now;
    if let Some(average) = diagnostics
        .get(&FrameTimeDiagnosticsPlugin::FRAME_TIME)
        .and_then(|frame_time| frame_time.average())
    {
        println!("frame time {average:.1} ms");
    }
}
