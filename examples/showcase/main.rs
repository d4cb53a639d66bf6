//! Seed 000's scene: a blue cube, a magenta sphere, a green cylinder and a red torus, with
//! specular strength 2 and shininess 50, lit by a directional light along -X, a red point
//! light at (-3, 3, 0) and a blue one at (3, 3, 0). The sphere shows all three highlights.
//! As in the seed, whose highlight is an uncolored `2.0 * pow(eyeCos, 50.0)`, every light's
//! specular intensity is white.
//!
//! Below the shapes, a floor receives the shadows of the two point lights (the directional
//! light shines along the floor, so its shadows fall on the shapes themselves, and would
//! hide the sphere's third highlight behind the cylinder: it casts none here).
//!
//! ```sh
//! cargo run --example showcase                       # a window, where a display exists
//! cargo run --example showcase -- --headless out.png # a PNG, and exit
//! cargo run --example showcase -- --check out.png    # are the sphere's three highlights there?
//! scripts/browser.sh --serve                         # in a browser (WebGL2)
//! ```
//!
//! Keys: S switches the shadows on and off.

#[path = "../support/mod.rs"]
mod support;

#[cfg(not(target_arch = "wasm32"))]
mod check;

use bevy::prelude::*;
use bevy_phong::prelude::*;

/// The floor's height, below the lowest shape.
const FLOOR_HEIGHT: f32 = -1.6;
/// The sphere's center, world units.
const SPHERE_CENTER: Vec3 = Vec3::new(-1.5, 0.0, 0.0);
/// The sphere's radius, world units.
const SPHERE_RADIUS: f32 = 1.0;
/// The sphere's color (seed 000's magenta).
const SPHERE_COLOR: &str = "#ff00ff";

/// The camera: 8.5 units in front of the shapes and 1 above, looking at the origin, with
/// Bevy's default perspective (45° vertical field of view).
fn camera_transform() -> Transform {
    Transform::from_xyz(0.0, 1.0, 8.5).looking_at(Vec3::ZERO, Vec3::Y)
}

/// A light of the scene.
enum SceneLight {
    Directional(PhongDirectionalLight),
    Point(PhongPointLight),
}

/// The three lights, each with the name the highlight check gives it.
fn lights() -> [(&'static str, SceneLight, Transform); 3] {
    [
        (
            "the directional light (along -X)",
            SceneLight::Directional(PhongDirectionalLight::default()),
            Transform::default().looking_to(Vec3::NEG_X, Vec3::Y),
        ),
        (
            "the red point light (at (-3, 3, 0))",
            SceneLight::Point(PhongPointLight {
                color: Color::linear_rgb(1.0, 0.0, 0.0),
                specular: Some(Color::WHITE),
                shadows: point_light_shadows(),
                ..default()
            }),
            Transform::from_xyz(-3.0, 3.0, 0.0),
        ),
        (
            "the blue point light (at (3, 3, 0))",
            SceneLight::Point(PhongPointLight {
                color: Color::linear_rgb(0.0, 0.0, 1.0),
                specular: Some(Color::WHITE),
                shadows: point_light_shadows(),
                ..default()
            }),
            Transform::from_xyz(3.0, 3.0, 0.0),
        ),
    ]
}

/// Seed 000's material: `hex` as the base color, specular strength 2, shininess 50.
fn seed_material(hex: &str) -> PhongMaterial {
    PhongMaterial {
        base_color: Srgba::hex(hex).expect("valid hex color").into(),
        specular_strength: 2.0,
        shininess: 50.0,
        ..default()
    }
}

fn main() -> AppExit {
    #[cfg(not(target_arch = "wasm32"))]
    let mode = {
        let (mode, check) = support::command_line::<check::CheckOption>("showcase");
        if let Some(path) = check.path() {
            std::process::exit(check::run(&path));
        }
        mode
    };
    #[cfg(target_arch = "wasm32")]
    let mode = support::RunMode::from_args("showcase");
    let mut app = support::example_app_in(mode, "showcase", |plugins| plugins);
    support::show_key_help(&mut app, "S shadows on / off")
        .add_plugins(PhongPlugin)
        // Seed 000's default ambient light.
        .insert_resource(PhongAmbientLight {
            color: Color::linear_rgb(0.5, 0.5, 0.5),
        })
        .add_systems(Startup, setup)
        .add_systems(Update, toggle_shadows);
    support::run(app)
}

/// Shadows of the two point lights, at a resolution that keeps their edges crisp on the floor.
fn point_light_shadows() -> PhongShadows {
    PhongShadows {
        resolution: 1024,
        ..PhongShadows::ON
    }
}

fn toggle_shadows(keys: Res<ButtonInput<KeyCode>>, mut lights: Query<&mut PhongPointLight>) {
    if keys.just_pressed(KeyCode::KeyS) {
        for mut light in &mut lights {
            light.shadows.enabled = !light.shadows.enabled;
        }
    }
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<PhongMaterial>>,
) {
    let objects: [(Mesh, &str, Vec3); 4] = [
        (
            Cuboid::new(1.6, 1.6, 1.6).into(),
            "#0000ff",
            Vec3::new(-4.5, 0.0, 0.0),
        ),
        (
            Sphere::new(SPHERE_RADIUS).mesh().uv(64, 48),
            SPHERE_COLOR,
            SPHERE_CENTER,
        ),
        (
            Cylinder::new(0.9, 1.8).into(),
            "#008000",
            Vec3::new(1.5, 0.0, 0.0),
        ),
        (
            Torus::new(0.45, 1.0).into(),
            "#ff0000",
            Vec3::new(4.5, 0.0, 0.0),
        ),
    ];
    for (mesh, color, position) in objects {
        commands.spawn((
            Mesh3d(meshes.add(mesh)),
            MeshMaterial3d(materials.add(seed_material(color))),
            Transform::from_translation(position).with_rotation(Quat::from_euler(
                EulerRot::XYZ,
                0.5,
                0.6,
                0.0,
            )),
        ));
    }

    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(30.0, 30.0))),
        MeshMaterial3d(materials.add(PhongMaterial {
            base_color: Color::srgb(0.6, 0.6, 0.6),
            specular_strength: 0.0,
            ..default()
        })),
        Transform::from_xyz(0.0, FLOOR_HEIGHT, 0.0),
    ));

    for (_, light, transform) in lights() {
        match light {
            SceneLight::Directional(light) => commands.spawn((light, transform)),
            SceneLight::Point(light) => commands.spawn((light, transform)),
        };
    }

    commands.spawn(support::example_camera(camera_transform()));
}
