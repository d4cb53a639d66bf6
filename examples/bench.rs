//! Frame time of `PhongMaterial` beside Bevy's `StandardMaterial` (lit by the equivalent
//! Bevy lights) and a constant-color material (the floor: rasterization and Bevy's overhead
//! without lighting), rendered headless on the render device, measured side by side in one
//! run.
//!
//! ```sh
//! cargo run --example bench             # the full table: 512² and 1024², 3 to 4,096 lights
//! cargo run --example bench -- --quick  # a small smoke run (what CI runs)
//! ```
//!
//! Each frame is timed from the start of `App::update` until the device has finished the
//! frame's work; the table gives the median over the measured frames, after the pipelines
//! compiled and a few warm-up frames. It also writes `target/bench/frame_times.csv`.

#[path = "support/headless.rs"]
mod headless;

use bevy::{
    camera::RenderTarget,
    core_pipeline::tonemapping::Tonemapping,
    prelude::*,
    render::{
        RenderApp,
        render_resource::{AsBindGroup, PipelineCache, PollType, TextureFormat, TextureUsages},
        renderer::RenderDevice,
        view::Msaa,
    },
    shader::ShaderRef,
};
use bevy_phong::prelude::*;
use std::{
    fmt::Write as _,
    time::{Duration, Instant},
};

/// What the scene's meshes are made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shading {
    Phong,
    Standard,
    Constant,
}

/// The scenes: the showcase (3 lights), or a field of objects under `n` point lights.
#[derive(Clone, Copy, Debug)]
enum Scene {
    Showcase,
    Field(usize),
}

impl Scene {
    fn name(self) -> String {
        match self {
            Scene::Showcase => "showcase (3 lights)".into(),
            Scene::Field(lights) => format!("field, {lights} point lights"),
        }
    }
}

/// A material whose fragment shader returns a constant color.
#[derive(Asset, AsBindGroup, TypePath, Clone)]
struct ConstantColor {
    #[uniform(0)]
    color: LinearRgba,
}

impl Material for ConstantColor {
    fn fragment_shader() -> ShaderRef {
        "shaders/constant_color.wgsl".into()
    }
}

struct Options {
    sizes: Vec<u32>,
    scenes: Vec<Scene>,
    warmup_frames: usize,
    frames: usize,
}

impl Options {
    fn from_args() -> Self {
        if std::env::args().any(|arg| arg == "--quick") {
            return Self {
                sizes: vec![128],
                scenes: vec![Scene::Showcase, Scene::Field(16)],
                warmup_frames: 1,
                frames: 2,
            };
        }
        Self {
            sizes: vec![512, 1024],
            scenes: vec![
                Scene::Showcase,
                Scene::Field(16),
                Scene::Field(256),
                Scene::Field(4096),
            ],
            warmup_frames: 3,
            frames: 9,
        }
    }
}

fn main() {
    let options = Options::from_args();
    let mut table = String::from(
        "| scene | size | Phong ms | Standard ms | constant ms | Phong/Standard | Phong/constant |\n|---|---|---|---|---|---|---|\n",
    );
    let mut csv = String::from("scene,size,shading,median_ms\n");
    for &size in &options.sizes {
        for &scene in &options.scenes {
            let times = [Shading::Phong, Shading::Standard, Shading::Constant].map(|shading| {
                let median = measure(scene, size, shading, &options);
                let _ = writeln!(csv, "{},{size},{shading:?},{:.3}", scene.name(), ms(median));
                eprintln!("{} {size}² {shading:?}: {:.1} ms", scene.name(), ms(median));
                ms(median)
            });
            let _ = writeln!(
                table,
                "| {} | {size}² | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} |",
                scene.name(),
                times[0],
                times[1],
                times[2],
                times[0] / times[1],
                times[0] / times[2],
            );
        }
    }
    println!("{table}");
    let _ = std::fs::create_dir_all("target/bench");
    match std::fs::write("target/bench/frame_times.csv", csv) {
        Ok(()) => println!("wrote target/bench/frame_times.csv"),
        Err(error) => eprintln!("cannot write target/bench/frame_times.csv: {error}"),
    }
}

fn ms(duration: Duration) -> f64 {
    duration.as_secs_f64() * 1000.0
}

/// The median frame time of `scene` at `size`² drawn with `shading`.
fn measure(scene: Scene, size: u32, shading: Shading, options: &Options) -> Duration {
    let mut app = headless::headless_app(|app| {
        app.add_plugins(MaterialPlugin::<ConstantColor>::default());
    });
    spawn_scene(app.world_mut(), scene, size, shading);

    // Until every pipeline has compiled, then a few more frames.
    for _ in 0..600 {
        frame(&mut app);
        let cache = app.sub_app(RenderApp).world().resource::<PipelineCache>();
        if cache.waiting_pipelines().next().is_none() {
            break;
        }
    }
    for _ in 0..options.warmup_frames {
        frame(&mut app);
    }
    let mut times: Vec<Duration> = (0..options.frames).map(|_| frame(&mut app)).collect();
    times.sort();
    times[times.len() / 2]
}

/// Runs one frame and waits for the device to finish it; returns how long that took.
fn frame(app: &mut App) -> Duration {
    let start = Instant::now();
    app.update();
    app.sub_app(RenderApp)
        .world()
        .resource::<RenderDevice>()
        .poll(PollType::wait_indefinitely())
        .expect("the device finishes the frame");
    start.elapsed()
}

/// A small deterministic generator for light positions and colors.
fn scatter(i: usize) -> (f32, f32, f32) {
    let golden = 0.618_034_f32;
    let t = i as f32;
    (
        (t * golden).fract(),
        (t * golden * golden).fract(),
        (t * 0.754_877_7).fract(),
    )
}

fn spawn_scene(world: &mut World, scene: Scene, size: u32, shading: Shading) {
    let mut target = Image::new_target_texture(size, size, TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let target = world.resource_mut::<Assets<Image>>().add(target);
    let camera_position = match scene {
        Scene::Showcase => Vec3::new(0.0, 1.0, 8.5),
        Scene::Field(_) => Vec3::new(0.0, 14.0, 16.0),
    };
    world.spawn((
        Camera3d::default(),
        RenderTarget::Image(target.into()),
        Msaa::Off,
        Tonemapping::None,
        Transform::from_translation(camera_position).looking_at(Vec3::ZERO, Vec3::Y),
    ));

    let mut objects: Vec<(Mesh, Vec3, Color)> = Vec::new();
    match scene {
        Scene::Showcase => {
            objects.push((
                Cuboid::new(1.6, 1.6, 1.6).into(),
                Vec3::new(-4.5, 0.0, 0.0),
                Color::srgb(0.0, 0.0, 1.0),
            ));
            objects.push((
                Sphere::new(1.0).mesh().uv(64, 48),
                Vec3::new(-1.5, 0.0, 0.0),
                Color::srgb(1.0, 0.0, 1.0),
            ));
            objects.push((
                Cylinder::new(0.9, 1.8).into(),
                Vec3::new(1.5, 0.0, 0.0),
                Color::srgb(0.0, 0.5, 0.0),
            ));
            objects.push((
                Torus::new(0.45, 1.0).into(),
                Vec3::new(4.5, 0.0, 0.0),
                Color::srgb(1.0, 0.0, 0.0),
            ));
        }
        Scene::Field(_) => {
            objects.push((
                Plane3d::default().mesh().size(40.0, 40.0).into(),
                Vec3::new(0.0, -0.8, 0.0),
                Color::srgb(0.7, 0.7, 0.7),
            ));
            for x in -5..5 {
                for z in -5..5 {
                    let position = Vec3::new(x as f32 * 2.4 + 1.2, 0.0, z as f32 * 2.4 + 1.2);
                    let hue = ((x + 5) * 10 + z + 5) as f32 * 3.6;
                    objects.push((
                        Sphere::new(0.8).mesh().uv(24, 16),
                        position,
                        Color::hsl(hue, 0.7, 0.5),
                    ));
                }
            }
        }
    }
    for (mesh, position, color) in objects {
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        let transform = Transform::from_translation(position);
        match shading {
            Shading::Phong => {
                let material = world
                    .resource_mut::<Assets<PhongMaterial>>()
                    .add(PhongMaterial {
                        base_color: color,
                        specular_strength: 2.0,
                        shininess: 50.0,
                        ..default()
                    });
                world.spawn((Mesh3d(mesh), MeshMaterial3d(material), transform));
            }
            Shading::Standard => {
                let material = world
                    .resource_mut::<Assets<StandardMaterial>>()
                    .add(StandardMaterial::from(color));
                world.spawn((Mesh3d(mesh), MeshMaterial3d(material), transform));
            }
            Shading::Constant => {
                let material = world
                    .resource_mut::<Assets<ConstantColor>>()
                    .add(ConstantColor {
                        color: color.into(),
                    });
                world.spawn((Mesh3d(mesh), MeshMaterial3d(material), transform));
            }
        }
    }

    let lights: Vec<(Vec3, Color, Option<f32>)> = match scene {
        Scene::Showcase => vec![
            (
                Vec3::new(-3.0, 3.0, 0.0),
                Color::linear_rgb(1.0, 0.0, 0.0),
                None,
            ),
            (
                Vec3::new(3.0, 3.0, 0.0),
                Color::linear_rgb(0.0, 0.0, 1.0),
                None,
            ),
        ],
        Scene::Field(count) => (0..count)
            .map(|i| {
                let (u, v, w) = scatter(i);
                let position = Vec3::new(u * 24.0 - 12.0, 0.5 + 2.5 * w, v * 24.0 - 12.0);
                (position, Color::hsl(w * 360.0, 1.0, 0.5), Some(4.0))
            })
            .collect(),
    };
    let directional = matches!(scene, Scene::Showcase);
    match shading {
        Shading::Phong => {
            if directional {
                world.spawn((
                    PhongDirectionalLight::default(),
                    Transform::default().looking_to(Vec3::NEG_X, Vec3::Y),
                ));
            }
            for (position, color, range) in lights {
                world.spawn((
                    PhongPointLight {
                        color,
                        decay: Decay::quadratic(0.2),
                        range,
                        ..default()
                    },
                    Transform::from_translation(position),
                ));
            }
        }
        Shading::Standard => {
            if directional {
                world.spawn((
                    DirectionalLight::default(),
                    Transform::default().looking_to(Vec3::NEG_X, Vec3::Y),
                ));
            }
            for (position, color, range) in lights {
                world.spawn((
                    PointLight {
                        color,
                        range: range.unwrap_or(20.0),
                        ..default()
                    },
                    Transform::from_translation(position),
                ));
            }
        }
        Shading::Constant => {}
    }
}
