//! Frame time on the render device: the median of repeated frames after warm-up.

use crate::scene::{ConstantColor, Scene, Shading, spawn_scene};
use bevy::{
    camera::RenderTarget,
    core_pipeline::tonemapping::Tonemapping,
    prelude::*,
    render::{
        RenderApp,
        render_resource::{PollType, TextureFormat, TextureUsages},
        renderer::RenderDevice,
        view::Msaa,
    },
    shader::ShaderDefVal,
};
use bevy_phong::PhongLightCulling;
use bevy_phong_headless::{
    assert_no_failed_pipelines, headless_app, read_back_frame, run_until_settled,
};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Whether every camera orbits the scene's middle by [`ORBIT_STEP`] before each frame
/// (`--orbit`), so that every view changes every frame, as a game's camera does.
static ORBIT: AtomicBool = AtomicBool::new(false);

/// How far the cameras orbit between two frames, radians (half a degree).
const ORBIT_STEP: f32 = 0.5 * core::f32::consts::PI / 180.0;

/// Makes every measured app's cameras orbit (see [`ORBIT`]).
pub fn orbit_cameras() {
    ORBIT.store(true, Ordering::Relaxed);
}

/// The asset path of `PhongMaterial`'s fragment shader (`src/shaders/phong_material.wesl`).
const PHONG_MATERIAL_SHADER: &str = "embedded://bevy_phong/shaders/phong_material.wesl";

/// Frames to wait for a shader to load before giving up.
const MAX_WAIT_FRAMES: u32 = 600;

/// How many frames to measure.
#[derive(Clone, Copy, Debug)]
pub struct Frames {
    /// Frames drawn and not measured once the pipelines have compiled.
    pub warmup: usize,
    /// Frames measured (at least [`Frames::MIN_MEASURED`] whatever the time budget).
    pub measured: usize,
    /// Measuring stops once this much time went by, after at least three frames: the
    /// slowest rows (seconds per frame) would otherwise take many minutes.
    pub budget: Duration,
}

impl Frames {
    const MIN_MEASURED: usize = 3;
}

/// The median frame time of `scene` at `size`² drawn with `shading`, the Phong lights culled
/// by `culling`.
pub fn median_frame_time(
    scene: Scene,
    size: u32,
    shading: Shading,
    culling: PhongLightCulling,
    frames: Frames,
) -> Duration {
    measured_app(scene, size, shading, culling, frames, &[]).median
}

/// [`median_frame_time`] with `PhongMaterial`'s fragment shader replaced by the ablation's,
/// cut by `ablation_defs`, where they are not empty (the benchmark's shader ablation:
/// `examples/bench/ablation.rs`), and
/// the picture of a frame drawn after the measured ones: `size`² pixels, row by row, each
/// RGBA with 8-bit sRGB channels.
///
/// # Panics
///
/// When a pipeline failed to compile (Bevy would draw nothing with it, and the time would
/// be that of drawing nothing).
pub fn median_frame_time_and_picture(
    scene: Scene,
    size: u32,
    shading: Shading,
    culling: PhongLightCulling,
    frames: Frames,
    ablation_defs: &[&str],
) -> (Duration, Vec<u8>) {
    let mut measured = measured_app(scene, size, shading, culling, frames, ablation_defs);
    assert_no_failed_pipelines(&measured.app, &format!("shader defs {ablation_defs:?}"));
    let picture = read_back_frame(
        &mut measured.app,
        &measured.target,
        4 * size as usize,
        size as usize,
        |app| {
            frame(app);
        },
    );
    (measured.median, picture)
}

/// An app after its frames were measured.
struct Measured {
    app: App,
    /// The image the camera renders into.
    target: Handle<Image>,
    /// The median frame time.
    median: Duration,
    /// The median frame's split.
    median_split: FrameSplit,
    /// The Phong fragment shader replaced by the ablation's, held so that it stays loaded
    /// as it is (an asset no handle holds is unloaded, and loads afresh when next asked
    /// for).
    _changed_shader: Option<Handle<Shader>>,
}

/// Measures `scene` as [`median_frame_time`] does, with `PhongMaterial`'s fragment shader
/// replaced by the ablation's, cut by `ablation_defs`, before any mesh is spawned (unless
/// `ablation_defs` is empty).
fn measured_app(
    scene: Scene,
    size: u32,
    shading: Shading,
    culling: PhongLightCulling,
    frames: Frames,
    ablation_defs: &[&str],
) -> Measured {
    let mut app = headless_app(|app| {
        app.add_plugins(MaterialPlugin::<ConstantColor>::default())
            .insert_resource(culling);
    });
    let changed_shader = (!ablation_defs.is_empty())
        .then(|| replace_with_ablation_shader(&mut app, PHONG_MATERIAL_SHADER, ablation_defs));
    let target = spawn_camera(app.world_mut(), scene, size);
    spawn_scene(app.world_mut(), scene, shading);

    // Until every pipeline has compiled, then the warm-up frames.
    run_until_settled(&mut app, Duration::from_secs(300), |app| {
        frame(app);
    });
    for _ in 0..frames.warmup {
        frame(&mut app);
    }
    let start = Instant::now();
    let mut splits = Vec::new();
    while splits.len() < Frames::MIN_MEASURED
        || (splits.len() < frames.measured && start.elapsed() < frames.budget)
    {
        splits.push(frame_split(&mut app));
    }
    splits.sort_by(|a, b| a.frame_ms().total_cmp(&b.frame_ms()));
    let median_split = splits[splits.len() / 2];
    Measured {
        app,
        target,
        median: Duration::from_secs_f64(median_split.frame_ms() / 1e3),
        median_split,
        _changed_shader: changed_shader,
    }
}

/// The benchmark's cut fragment shader (`examples/bench/ablation.wesl`), composed from the
/// crate's shader functions.
const ABLATION_SHADER: &str = include_str!("ablation.wesl");

/// Waits until the shader asset at `path` has loaded, then puts the ablation's shader
/// ([`ABLATION_SHADER`]) with `defs` in its place. Bevy composes every pipeline of that
/// asset anew when it changes, so the material draws with the cut shader; the crate's
/// shaders are not touched. Returns the shader's handle, to be held while the app runs: an
/// asset no handle holds is unloaded, and the material would then load the file afresh.
///
/// # Panics
///
/// When the shader has not loaded within [`MAX_WAIT_FRAMES`] frames.
fn replace_with_ablation_shader(
    app: &mut App,
    path: &'static str,
    defs: &[&str],
) -> Handle<Shader> {
    let handle: Handle<Shader> = app.world().resource::<AssetServer>().load(path);
    let mut frames = 0;
    while !app.world().resource::<AssetServer>().is_loaded(&handle) {
        assert!(frames < MAX_WAIT_FRAMES, "{path} did not load");
        app.update();
        std::thread::sleep(Duration::from_millis(1));
        frames += 1;
    }
    let defs = defs
        .iter()
        .map(|&def| ShaderDefVal::Bool(def.to_owned().into(), true))
        .collect();
    let mut shaders = app.world_mut().resource_mut::<Assets<Shader>>();
    let mut shader = shaders.get_mut(&handle).expect("the shader has loaded");
    let mut ablation = Shader::from_wesl(ABLATION_SHADER, "examples/bench/ablation.wesl");
    ablation.shader_defs = defs;
    *shader = ablation;
    handle
}

/// The cameras that render `scene` into a `size`² sRGB image (one, or two side by side for
/// split screen); returns the image.
fn spawn_camera(world: &mut World, scene: Scene, size: u32) -> Handle<Image> {
    let mut target = Image::new_target_texture(size, size, TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let target = world.resource_mut::<Assets<Image>>().add(target);
    for (order, (position, viewport)) in scene.cameras(size).into_iter().enumerate() {
        world.spawn((
            Camera3d::default(),
            Camera {
                viewport,
                order: order as isize,
                ..default()
            },
            RenderTarget::Image(target.clone().into()),
            Msaa::Off,
            Tonemapping::Linear,
            Transform::from_translation(position).looking_at(Vec3::ZERO, Vec3::Y),
        ));
    }
    target
}

/// Where one frame's time went, ms.
#[derive(Clone, Copy, Debug, Default)]
pub struct FrameSplit {
    /// The main world's schedule.
    pub main_ms: f64,
    /// The render world: extraction and its schedule (which submits the frame).
    pub render_ms: f64,
    /// The wait until the device finished the frame.
    pub device_ms: f64,
}

impl FrameSplit {
    /// The whole frame, ms.
    pub fn frame_ms(self) -> f64 {
        self.main_ms + self.render_ms + self.device_ms
    }
}

/// Runs one frame as `App::update` does, timing the main world, the render world and the
/// wait until the device finished the frame.
fn frame_split(app: &mut App) -> FrameSplit {
    let ms = |from: Instant| from.elapsed().as_secs_f64() * 1e3;
    if ORBIT.load(Ordering::Relaxed) {
        let world = app.world_mut();
        let mut cameras = world.query_filtered::<&mut Transform, With<Camera3d>>();
        for mut transform in cameras.iter_mut(world) {
            transform.rotate_around(Vec3::ZERO, Quat::from_rotation_y(ORBIT_STEP));
        }
    }
    let sub_apps = app.sub_apps_mut();
    let start = Instant::now();
    sub_apps.main.run_default_schedule();
    let main_ms = ms(start);
    let start = Instant::now();
    for sub_app in sub_apps.sub_apps.values_mut() {
        sub_app.extract(sub_apps.main.world_mut());
        sub_app.update();
    }
    sub_apps.main.world_mut().clear_trackers();
    let render_ms = ms(start);
    let start = Instant::now();
    app.sub_app(RenderApp)
        .world()
        .resource::<RenderDevice>()
        .poll(PollType::wait_indefinitely())
        .expect("the device finishes the frame");
    FrameSplit {
        main_ms,
        render_ms,
        device_ms: ms(start),
    }
}

/// Runs one frame and waits for the device to finish it; returns how long that took.
fn frame(app: &mut App) -> Duration {
    Duration::from_secs_f64(frame_split(app).frame_ms() / 1e3)
}

/// The split of the median frame (by its whole time) of `scene` at `size`² drawn with
/// `shading`, the Phong lights culled by `culling`.
pub fn median_frame_split(
    scene: Scene,
    size: u32,
    shading: Shading,
    culling: PhongLightCulling,
    frames: Frames,
) -> FrameSplit {
    measured_app(scene, size, shading, culling, frames, &[]).median_split
}
