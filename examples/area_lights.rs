//! A living room lit by its window and its television: two `PhongRectLight`s, the kind of
//! light games light interiors with. The window (warm daylight, on the left wall) and the
//! screen (cool, on the back wall) each emit from their whole area: close to them the light
//! stays finite and wraps around what faces them, a floor point sees only the part of a
//! panel above its horizon, and the glossy table and ball show each panel's shape in their
//! highlights. Each light's visible face is an unlit quad just behind it (a light itself is
//! not drawn).
//!
//! ```sh
//! cargo run --example area_lights                       # a window, where a display exists
//! cargo run --example area_lights -- --headless out.png # a PNG, and exit
//! ```
//!
//! Keys: H the highlight (integrated over each panel at a bounded cost or exactly, its
//! fitted lobe, or at a representative point), W the window, T the television.

mod support;

use bevy::prelude::*;
use bevy_phong::prelude::*;

/// The room's half size along X and Z, and its walls' height, world units (metres).
const HALF_ROOM: f32 = 3.0;
const WALL_HEIGHT: f32 = 3.0;

/// Marks the window's light and its quad.
#[derive(Component)]
struct Window;

/// Marks the television's light and its quad.
#[derive(Component)]
struct Television;

fn main() -> AppExit {
    let mut app = support::example_app("area_lights");
    support::show_key_help(&mut app, "H highlight, W window, T television")
        .add_plugins(PhongPlugin)
        .insert_resource(PhongAmbientLight {
            color: Color::linear_rgb(0.04, 0.04, 0.05),
        })
        .add_systems(Startup, setup)
        .add_systems(Update, keys);
    support::run(app)
}

/// A matte material of `color` with a faint highlight.
fn matte(color: Color) -> PhongMaterial {
    PhongMaterial {
        base_color: color,
        specular_strength: 0.05,
        shininess: 8.0,
        ..default()
    }
}

/// A glossy material of `color` with a sharp white highlight.
fn glossy(color: Color, shininess: f32) -> PhongMaterial {
    PhongMaterial {
        base_color: color,
        specular_strength: 0.6,
        shininess,
        ..default()
    }
}

/// The visible face of a light: an unlit quad of `color`, `size` across, facing `normal`.
fn light_face(normal: Vec3, size: Vec2, color: Color) -> (Mesh, PhongMaterial) {
    (
        Plane3d::new(normal, size / 2.0).into(),
        PhongMaterial {
            base_color: color,
            unlit: true,
            ..default()
        },
    )
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<PhongMaterial>>,
) {
    let wall = Color::srgb(0.78, 0.74, 0.68);
    let furniture: [(Mesh, PhongMaterial, Vec3); 9] = [
        // The floor, wood with a soft sheen.
        (
            Plane3d::new(Vec3::Y, Vec2::splat(HALF_ROOM)).into(),
            glossy(Color::srgb(0.45, 0.3, 0.18), 20.0),
            Vec3::ZERO,
        ),
        // The back wall and the left wall.
        (
            Plane3d::new(Vec3::Z, Vec2::new(HALF_ROOM, WALL_HEIGHT / 2.0)).into(),
            matte(wall),
            Vec3::new(0.0, WALL_HEIGHT / 2.0, -HALF_ROOM),
        ),
        (
            Plane3d::new(Vec3::X, Vec2::new(WALL_HEIGHT / 2.0, HALF_ROOM)).into(),
            matte(wall),
            Vec3::new(-HALF_ROOM, WALL_HEIGHT / 2.0, 0.0),
        ),
        // The cabinet under the television.
        (
            Cuboid::new(1.8, 0.5, 0.4).into(),
            glossy(Color::srgb(0.12, 0.12, 0.13), 40.0),
            Vec3::new(0.0, 0.25, -2.75),
        ),
        // The sofa: its seat and its back.
        (
            Cuboid::new(2.0, 0.45, 0.9).into(),
            matte(Color::srgb(0.3, 0.38, 0.5)),
            Vec3::new(0.0, 0.225, 1.7),
        ),
        (
            Cuboid::new(2.0, 0.55, 0.2).into(),
            matte(Color::srgb(0.3, 0.38, 0.5)),
            Vec3::new(0.0, 0.725, 2.05),
        ),
        // The coffee table, lacquered, and a ball on it.
        (
            Cuboid::new(1.1, 0.06, 0.6).into(),
            glossy(Color::srgb(0.55, 0.12, 0.08), 60.0),
            Vec3::new(0.0, 0.4, 0.4),
        ),
        (
            Sphere::new(0.18).mesh().uv(48, 32),
            glossy(Color::srgb(0.85, 0.8, 0.7), 120.0),
            Vec3::new(0.25, 0.61, 0.4),
        ),
        // A plant pot in the corner.
        (
            Cylinder::new(0.25, 0.6).into(),
            matte(Color::srgb(0.6, 0.35, 0.25)),
            Vec3::new(-2.4, 0.3, -2.4),
        ),
    ];
    for (mesh, material, position) in furniture {
        commands.spawn((
            Mesh3d(meshes.add(mesh)),
            MeshMaterial3d(materials.add(material)),
            Transform::from_translation(position),
        ));
    }

    // The window: daylight through a 1.6 × 1.2 pane in the left wall, facing into the room.
    let window_size = Vec2::new(1.6, 1.2);
    let window_center = Vec3::new(-HALF_ROOM + 0.01, 1.7, -0.6);
    commands.spawn((
        PhongRectLight {
            color: Color::linear_rgb(16.0, 15.0, 13.0),
            width: window_size.x,
            height: window_size.y,
            ..default()
        },
        Transform::from_translation(window_center).looking_to(Vec3::X, Vec3::Y),
        Window,
    ));
    let (mesh, material) = light_face(Vec3::X, window_size.yx(), Color::srgb(1.0, 0.97, 0.9));
    commands.spawn((
        Mesh3d(meshes.add(mesh)),
        MeshMaterial3d(materials.add(material)),
        Transform::from_translation(window_center - Vec3::X * 0.005),
        Window,
    ));

    // The television: a cool 1.4 × 0.8 screen on the back wall, facing the sofa.
    let screen_size = Vec2::new(1.4, 0.8);
    let screen_center = Vec3::new(0.0, 1.25, -HALF_ROOM + 0.02);
    commands.spawn((
        PhongRectLight {
            color: Color::linear_rgb(2.0, 2.6, 4.8),
            width: screen_size.x,
            height: screen_size.y,
            ..default()
        },
        Transform::from_translation(screen_center).looking_to(Vec3::Z, Vec3::Y),
        Television,
    ));
    let (mesh, material) = light_face(Vec3::Z, screen_size, Color::srgb(0.55, 0.68, 0.95));
    commands.spawn((
        Mesh3d(meshes.add(mesh)),
        MeshMaterial3d(materials.add(material)),
        Transform::from_translation(screen_center - Vec3::Z * 0.005),
        Television,
    ));

    commands.spawn(support::example_camera(
        Transform::from_xyz(2.8, 2.5, 1.6).looking_at(Vec3::new(-1.0, 0.5, -1.2), Vec3::Y),
    ));
}

/// The window's and the television's lights and quads, each with whether it is the window's.
type RoomLights<'w, 's> =
    Query<'w, 's, (&'static mut Visibility, Has<Window>), Or<(With<Window>, With<Television>)>>;

/// H switches every panel's highlight from bounded to exact to fitted to a representative
/// point and back; W and T turn the window and the television (each light and its quad) off
/// and on.
fn keys(
    input: Res<ButtonInput<KeyCode>>,
    mut panels: Query<&mut PhongRectLight>,
    mut parts: RoomLights,
) {
    if input.just_pressed(KeyCode::KeyH) {
        for mut panel in &mut panels {
            panel.highlight = match panel.highlight {
                AreaHighlight::Bounded => AreaHighlight::Exact,
                AreaHighlight::Exact => AreaHighlight::Fitted,
                AreaHighlight::Fitted => AreaHighlight::RepresentativePoint,
                AreaHighlight::RepresentativePoint => AreaHighlight::Bounded,
            };
            println!("highlight: {:?}", panel.highlight);
        }
    }
    for (key, window) in [(KeyCode::KeyW, true), (KeyCode::KeyT, false)] {
        if !input.just_pressed(key) {
            continue;
        }
        for (mut visibility, is_window) in &mut parts {
            if is_window == window {
                *visibility = match *visibility {
                    Visibility::Hidden => Visibility::Inherited,
                    _ => Visibility::Hidden,
                };
            }
        }
    }
}
