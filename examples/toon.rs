//! A scene in the style of a cel-shaded game, drawn with `PhongMaterial`'s stylized modes:
//! a toon ramp (`toon_ramp_texture`, three.js's `gradientMap`) in place of Lambert's
//! shading, toon highlights, a rim light on the lit side, a hemisphere light (a sky above and
//! warm ground below) beside a dim ambient light, a spot light whose cookie throws the shadow
//! of a window frame, and the sun's and the spot's shadows.
//!
//! Under WebGL2's limits the ramp and the cookie are left out (16 textures a shader stage,
//! with a warning): the materials fall back to their three toon bands and the spot shines
//! without its window.
//!
//! ```sh
//! cargo run --example toon                       # a window, where a display exists
//! cargo run --example toon -- --headless out.png # a PNG, and exit
//! ```
//!
//! Keys: T toon / Lambert shading, H hemisphere light, C the spot's cookie, R rim light.

mod support;

use bevy::{
    asset::RenderAssetUsages,
    prelude::*,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};
use bevy_phong::{DiffuseMode, SpecularMode, prelude::*};

/// The toon ramp: four tones from the far side (`N·L = −1`, left) to the light (`N·L = 1`,
/// right), linear. The two darkest fall where `N·L < 0`: the shadow side keeps a tone.
const RAMP: [u8; 4] = [40, 70, 185, 255];

/// The three bands the materials fall back to where the ramp is not bound (WebGL2).
const FALLBACK: DiffuseMode = DiffuseMode::Toon {
    bands: 3,
    smoothing: 0.05,
};

/// The sky and ground of the hemisphere light.
const HEMISPHERE: PhongHemisphereLight = PhongHemisphereLight {
    sky_color: Color::LinearRgba(LinearRgba::rgb(0.22, 0.26, 0.38)),
    ground_color: Color::LinearRgba(LinearRgba::rgb(0.12, 0.08, 0.04)),
    up: Vec3::Y,
};

/// The spot light's window cookie, to give back when C turns it on again.
#[derive(Resource)]
struct WindowCookie(PhongLightCookie);

/// Marks the spot light.
#[derive(Component)]
struct Lamp;

fn main() -> AppExit {
    let mut app = support::example_app("toon");
    support::show_key_help(
        &mut app,
        "T toon / Lambert, H hemisphere light, C cookie, R rim",
    )
    .add_plugins(PhongPlugin)
    .insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.03, 0.03, 0.04),
    })
    .insert_resource(HEMISPHERE)
    .add_systems(Startup, setup)
    .add_systems(Update, keys);
    support::run(app)
}

/// A `width`×1 image of linear red values (the ramp).
fn ramp_image(red: &[u8]) -> Image {
    Image::new(
        Extent3d {
            width: red.len() as u32,
            height: 1,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        red.iter().flat_map(|&r| [r, r, r, 255]).collect(),
        TextureFormat::Rgba8Unorm,
        RenderAssetUsages::default(),
    )
}

/// A window frame's cookie: four warm panes in a dark frame with a dark border (so that the
/// light ends inside its cone), 256² sRGB.
fn window_image() -> Image {
    let side = 256u32;
    let data = (0..side * side)
        .flat_map(|index| {
            let (x, y) = (index % side, index / side);
            let inside = |c: u32| (40..216).contains(&c);
            let bar = |c: u32| (122..134).contains(&c);
            let pane = inside(x) && inside(y) && !bar(x) && !bar(y);
            if pane {
                [255, 236, 200, 255]
            } else {
                [12, 10, 8, 255]
            }
        })
        .collect();
    Image::new(
        Extent3d {
            width: side,
            height: side,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::default(),
    )
}

/// A cel-shaded material of `color`: the ramp, a toon highlight of `shininess` (none for
/// 0), and a rim of `rim` on the lit side.
fn toon(color: Color, ramp: &Handle<Image>, shininess: f32, rim: LinearRgba) -> PhongMaterial {
    PhongMaterial {
        base_color: color,
        diffuse_mode: FALLBACK,
        toon_ramp_texture: Some(ramp.clone()),
        specular_mode: if shininess > 0.0 {
            SpecularMode::Toon { smoothing: 0.1 }
        } else {
            SpecularMode::Off
        },
        shininess,
        specular_strength: 0.6,
        rim_color: rim,
        rim_strength: 0.8,
        rim_power: 3.0,
        rim_lit_side: true,
        ..default()
    }
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<PhongMaterial>>,
    mut images: ResMut<Assets<Image>>,
) {
    let ramp = images.add(ramp_image(&RAMP));
    let no_rim = LinearRgba::BLACK;
    let warm_rim = LinearRgba::rgb(1.0, 0.9, 0.7);
    let objects: [(Mesh, Transform, PhongMaterial); 6] = [
        (
            Plane3d::default().mesh().size(30.0, 30.0).into(),
            Transform::default(),
            toon(Color::srgb(0.45, 0.7, 0.35), &ramp, 0.0, no_rim),
        ),
        // The hero: a capsule with a head.
        (
            Capsule3d::new(0.45, 1.0)
                .mesh()
                .rings(8)
                .latitudes(24)
                .into(),
            Transform::from_xyz(0.0, 0.95, 0.0),
            toon(Color::srgb(0.95, 0.45, 0.3), &ramp, 40.0, warm_rim),
        ),
        (
            Sphere::new(0.38).mesh().uv(48, 32),
            Transform::from_xyz(0.0, 2.25, 0.0),
            toon(Color::srgb(1.0, 0.85, 0.7), &ramp, 60.0, warm_rim),
        ),
        (
            Torus::new(0.25, 0.6).mesh().minor_resolution(24).into(),
            Transform::from_xyz(-2.2, 0.6, 0.8).with_rotation(Quat::from_rotation_x(1.1)),
            toon(Color::srgb(0.35, 0.55, 0.95), &ramp, 80.0, warm_rim),
        ),
        (
            Cuboid::new(1.2, 1.2, 1.2).into(),
            Transform::from_xyz(2.3, 0.6, -0.6).with_rotation(Quat::from_rotation_y(0.5)),
            toon(Color::srgb(0.95, 0.8, 0.3), &ramp, 0.0, warm_rim),
        ),
        (
            Sphere::new(0.7).mesh().ico(5).unwrap(),
            Transform::from_xyz(1.2, 0.7, 1.9),
            toon(Color::srgb(0.8, 0.4, 0.85), &ramp, 120.0, warm_rim),
        ),
    ];
    for (mesh, transform, material) in objects {
        commands.spawn((
            Mesh3d(meshes.add(mesh)),
            MeshMaterial3d(materials.add(material)),
            transform,
        ));
    }

    // The sun, low and warm, with shadows.
    commands.spawn((
        PhongDirectionalLight {
            color: Color::linear_rgb(0.85, 0.78, 0.65),
            shadows: PhongShadows {
                enabled: true,
                ..default()
            },
            ..default()
        },
        Transform::from_xyz(-4.0, 6.0, 3.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    // A lamp through a window: the cookie lays the frame on the ground.
    let cookie = PhongLightCookie {
        image: images.add(window_image()),
        ..default()
    };
    commands.insert_resource(WindowCookie(cookie.clone()));
    commands.spawn((
        PhongSpotLight {
            color: Color::linear_rgb(1.6, 1.3, 0.9),
            decay: Decay::new(1.0, 0.05, 0.02),
            inner_angle: 28f32.to_radians(),
            outer_angle: 34f32.to_radians(),
            shadows: PhongShadows {
                enabled: true,
                ..default()
            },
            ..default()
        },
        Transform::from_xyz(3.5, 5.5, 3.0).looking_at(Vec3::new(0.6, 0.0, 0.6), Vec3::Y),
        cookie,
        Lamp,
    ));

    commands.spawn(support::example_camera(
        Transform::from_xyz(-1.5, 4.2, 8.5).looking_at(Vec3::new(0.2, 0.9, 0.0), Vec3::Y),
    ));
}

fn keys(
    mut commands: Commands,
    keys: Res<ButtonInput<KeyCode>>,
    mut materials: ResMut<Assets<PhongMaterial>>,
    hemisphere: Option<Res<PhongHemisphereLight>>,
    cookie: Res<WindowCookie>,
    lamps: Query<(Entity, Has<PhongLightCookie>), With<Lamp>>,
) {
    if keys.just_pressed(KeyCode::KeyT) {
        for (_, material) in materials.iter_mut() {
            material.diffuse_mode = match material.diffuse_mode {
                DiffuseMode::Lambert => FALLBACK,
                _ => DiffuseMode::Lambert,
            };
        }
    }
    if keys.just_pressed(KeyCode::KeyR) {
        for (_, material) in materials.iter_mut() {
            material.rim_strength = if material.rim_strength > 0.0 {
                0.0
            } else {
                0.8
            };
        }
    }
    if keys.just_pressed(KeyCode::KeyH) {
        match hemisphere {
            Some(_) => commands.remove_resource::<PhongHemisphereLight>(),
            None => commands.insert_resource(HEMISPHERE),
        }
    }
    if keys.just_pressed(KeyCode::KeyC) {
        for (lamp, has_cookie) in &lamps {
            if has_cookie {
                commands.entity(lamp).remove::<PhongLightCookie>();
            } else {
                commands.entity(lamp).insert(cookie.0.clone());
            }
        }
    }
}
