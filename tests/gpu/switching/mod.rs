//! Switching a Bevy scene to Phong, measured against Bevy's own picture of it: a scene of
//! `StandardMaterial` under Bevy's `GlobalAmbientLight`, `PointLight`, `SpotLight` and
//! `DirectionalLight`, rendered once as Bevy draws it and once switched by
//! `PhongStandardMaterialPlugin` and `PhongBevyLightsPlugin`, in two apps side by side with
//! the same camera. Each object's pixels (found from the switched frame's material tags) are
//! compared in sRGB (each channel clamped to `[0, 1]` and encoded, as a display shows the
//! frames): the mean absolute difference over its channels, the 95th percentile and the
//! share of pixels with a channel off by more than 0.1. The scenes: `spheres`, dielectrics
//! and metals from rough to smooth; `textured`, props as glTF exporters write them, both
//! under Bevy's three light kinds and its ambient light ([`bevy_lights`]); `environment`,
//! spheres lit by the camera's `EnvironmentMapLight` and a sun.
//!
//! What cannot match is the model: Bevy's GGX lobe has long tails, a geometry term and
//! Burley's diffuse beside it, the converted normalized Blinn-Phong lobe and Lambert's
//! diffuse have none of them (docs/switching.md). Each scene's bounds are the figures
//! measured on lavapipe (docs/switching.md's tables, printed by the tests) with a margin of
//! 0.005 on the means and 2 percentage points on the shares: they hold what the switch
//! achieves, so that a regression fails.

mod environment;
mod spheres;
mod textured;

use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::{FloatImage, Harness, save_srgb_png};

/// Pixels per side of each frame: large enough for docs/switching.md's pictures.
const SIZE: u32 = 256;

/// Where both cameras look from, at the origin.
const CAMERA: Vec3 = Vec3::new(0.0, 1.2, 5.0);

/// One object of a scene: its name, mesh, place and material.
struct Object {
    name: &'static str,
    mesh: Mesh,
    transform: Transform,
    material: StandardMaterial,
}

/// A scene's objects, made in the world they are spawned into (their textures are its
/// images).
type Objects = fn(&mut World) -> Vec<Object>;

/// How a scene is lit: what it spawns besides its objects (lights, the camera's
/// environment map light), in the world they light.
type Lighting = fn(&mut World);

/// A bound on one object (or on the whole scene, named "scene"): its name, the largest mean
/// difference and the largest share of pixels off by more than 0.1.
type Bound = (&'static str, f32, f32);

/// Spawns `objects` (each with its own material) lit by `lighting`; returns the objects'
/// entities in order.
fn spawn_scene(world: &mut World, objects: Objects, lighting: Lighting) -> Vec<Entity> {
    lighting(world);
    objects(world)
        .into_iter()
        .map(|object| {
            let mesh = world.resource_mut::<Assets<Mesh>>().add(object.mesh);
            let material = world
                .resource_mut::<Assets<StandardMaterial>>()
                .add(object.material);
            world
                .spawn((Mesh3d(mesh), MeshMaterial3d(material), object.transform))
                .id()
        })
        .collect()
}

/// Bevy's ambient light and its three light kinds: a point light, a bluish spot light and a
/// directional light, none casting shadows.
fn bevy_lights(world: &mut World) {
    world.insert_resource(GlobalAmbientLight {
        color: Color::WHITE,
        brightness: 300.0,
        ..default()
    });
    world.spawn((
        PointLight {
            intensity: 300_000.0,
            range: 20.0,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(-2.5, 2.5, 2.5),
    ));
    world.spawn((
        SpotLight {
            intensity: 500_000.0,
            color: Color::srgb(0.6, 0.8, 1.0),
            range: 20.0,
            inner_angle: 0.3,
            outer_angle: 0.6,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(2.5, 3.0, 2.0).looking_at(Vec3::new(1.3, -0.45, 0.0), Vec3::Y),
    ));
    world.spawn((
        DirectionalLight {
            illuminance: 2_500.0,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
}

/// Renders `objects` lit by `lighting` as Bevy draws them and switched, writes both frames
/// to `target/render-tests/{picture}.png` and asserts each object within its bound.
fn assert_switched_within(objects: Objects, lighting: Lighting, picture: &str, bounds: &[Bound]) {
    let (mut bevy, mut phong) = Harness::side_by_side(
        SIZE,
        SIZE,
        |_| {},
        |app| {
            app.add_plugins((PhongStandardMaterialPlugin, PhongBevyLightsPlugin));
        },
    );
    spawn_scene(bevy.world_mut(), objects, lighting);
    let entities = spawn_scene(phong.world_mut(), objects, lighting);
    for harness in [&mut bevy, &mut phong] {
        harness.look_from(CAMERA);
        harness.settle();
    }
    let bevy_frame = bevy.render_next_frame();
    let phong_frame = phong.render_next_frame();
    save_frames(&bevy_frame, &phong_frame, picture);

    // Which object covers each pixel: the switched frame's material tags.
    let world = phong.world_mut();
    let handles: Vec<Handle<PhongMaterial>> = entities
        .iter()
        .map(|&entity| {
            world
                .entity(entity)
                .get::<MeshMaterial3d<PhongMaterial>>()
                .expect("switched to a PhongMaterial")
                .0
                .clone()
        })
        .collect();
    let names: Vec<&str> = objects(world).iter().map(|object| object.name).collect();
    let inputs = phong.capture_inputs();
    let mut pixels_of: Vec<Vec<usize>> = vec![Vec::new(); handles.len()];
    for (index, position) in inputs.positions.pixels.iter().enumerate() {
        let Some(handle) = inputs.materials.get(&(position[3] as u32)) else {
            continue;
        };
        if let Some(object) = handles.iter().position(|h| h == handle) {
            pixels_of[object].push(index);
        }
    }
    let every_pixel: Vec<usize> = pixels_of.iter().flatten().copied().collect();

    let mut failures = Vec::new();
    println!("{picture}:\n| object | pixels | mean | 95th percentile | off by > 0.1 |");
    println!("|---|---|---|---|---|");
    for (name, pixels) in names.iter().copied().chain(["scene"]).zip(
        pixels_of
            .iter()
            .map(Vec::as_slice)
            .chain([every_pixel.as_slice()]),
    ) {
        let measured = difference(&bevy_frame, &phong_frame, pixels);
        println!(
            "| {name} | {} | {:.4} | {:.3} | {:.1} % |",
            measured.pixels,
            measured.mean,
            measured.p95,
            100.0 * measured.off
        );
        let &(_, mean, off) = bounds
            .iter()
            .find(|(bound, ..)| *bound == name)
            .expect("a bound per object");
        assert!(
            measured.pixels > 100,
            "{name} covers {} pixels",
            measured.pixels
        );
        if measured.mean > mean || measured.off > off {
            failures.push(format!("{name}: {measured:?} past ({mean}, {off})"));
        }
    }
    assert!(failures.is_empty(), "past their bounds: {failures:#?}");
}

/// `linear` as a display shows it: clamped to `[0, 1]`, sRGB-encoded.
fn srgb(linear: f32) -> f32 {
    let c = linear.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// How far one object's pixels are from Bevy's picture of them.
#[derive(Debug)]
struct Difference {
    pixels: usize,
    /// The mean absolute sRGB difference over the pixels' channels.
    mean: f32,
    /// The 95th percentile of each pixel's largest channel difference.
    p95: f32,
    /// The share of pixels with a channel off by more than 0.1.
    off: f32,
}

fn difference(bevy: &FloatImage, phong: &FloatImage, pixels: &[usize]) -> Difference {
    let mut largest: Vec<f32> = Vec::with_capacity(pixels.len());
    let mut sum = 0.0;
    for &index in pixels {
        let channels =
            (0..3).map(|c| (srgb(bevy.pixels[index][c]) - srgb(phong.pixels[index][c])).abs());
        let channels: Vec<f32> = channels.collect();
        sum += channels.iter().sum::<f32>();
        largest.push(channels.iter().copied().fold(0.0, f32::max));
    }
    largest.sort_by(f32::total_cmp);
    let count = pixels.len().max(1);
    Difference {
        pixels: pixels.len(),
        mean: sum / (3 * count) as f32,
        p95: largest.get(count * 95 / 100).copied().unwrap_or(0.0),
        off: largest.iter().filter(|&&d| d > 0.1).count() as f32 / count as f32,
    }
}

/// Writes both frames, Bevy's on the left, to `target/render-tests/{picture}.png`
/// (docs/switching.md shows them).
fn save_frames(bevy: &FloatImage, phong: &FloatImage, picture: &str) {
    let directory = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/render-tests");
    std::fs::create_dir_all(&directory).expect("create target/render-tests");
    let (width, height) = (bevy.width as usize, bevy.height as usize);
    let pixels: Vec<[f32; 3]> = (0..height)
        .flat_map(|row| {
            let side = |frame: &FloatImage| {
                frame.pixels[row * width..(row + 1) * width]
                    .iter()
                    .map(|p| [p[0], p[1], p[2]])
                    .collect::<Vec<_>>()
            };
            let mut both = side(bevy);
            both.extend(side(phong));
            both
        })
        .collect();
    save_srgb_png(
        &directory.join(format!("{picture}.png")),
        2 * bevy.width,
        bevy.height,
        &pixels,
    );
}
