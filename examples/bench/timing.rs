//! Frame time on the render device: the median of repeated frames after warm-up.

use crate::scene::{ConstantColor, Scene, Shading, spawn_scene};
use bevy::{
    camera::RenderTarget,
    core_pipeline::tonemapping::Tonemapping,
    prelude::*,
    render::{
        RenderApp,
        gpu_readback::{Readback, ReadbackComplete},
        render_resource::{PollType, TextureFormat, TextureUsages},
        renderer::RenderDevice,
        view::Msaa,
    },
    shader::ShaderDefVal,
};
use bevy_phong::PhongLightCulling;
use bevy_phong_headless::{assert_no_failed_pipelines, headless_app, run_until_settled};
use std::{
    sync::{Arc, Mutex},
    time::{Duration, Instant},
};

/// The asset path of `PhongMaterial`'s fragment shader (`src/shaders/phong_material.wgsl`).
const PHONG_MATERIAL_SHADER: &str = "embedded://bevy_phong/shaders/phong_material.wgsl";

/// Frames to wait for a shader to load, and for a readback to arrive, before giving up.
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

/// [`median_frame_time`] with `phong_defs` added to the shader defs of `PhongMaterial`'s
/// fragment shader (the benchmark's shader ablation: `examples/bench/ablation.rs`), and
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
    phong_defs: &[&str],
) -> (Duration, Vec<u8>) {
    let mut measured = measured_app(scene, size, shading, culling, frames, phong_defs);
    assert_no_failed_pipelines(&measured.app, &format!("shader defs {phong_defs:?}"));
    let picture = read_back(&mut measured.app, measured.target, size);
    (measured.median, picture)
}

/// An app after its frames were measured.
struct Measured {
    app: App,
    /// The image the camera renders into.
    target: Handle<Image>,
    /// The median frame time.
    median: Duration,
    /// The Phong fragment shader whose defs were changed, held so that it stays loaded
    /// with them (an asset no handle holds is unloaded, and loads afresh when next asked
    /// for).
    _changed_shader: Option<Handle<Shader>>,
}

/// Measures `scene` as [`median_frame_time`] does, with `phong_defs` added to the shader
/// defs of `PhongMaterial`'s fragment shader before any mesh is spawned.
fn measured_app(
    scene: Scene,
    size: u32,
    shading: Shading,
    culling: PhongLightCulling,
    frames: Frames,
    phong_defs: &[&str],
) -> Measured {
    let mut app = headless_app(|app| {
        app.add_plugins(MaterialPlugin::<ConstantColor>::default())
            .insert_resource(culling);
    });
    let changed_shader = (!phong_defs.is_empty())
        .then(|| add_shader_defs(&mut app, PHONG_MATERIAL_SHADER, phong_defs));
    let target = spawn_camera(app.world_mut(), scene, size);
    spawn_scene(app.world_mut(), scene, shading);

    // Until every pipeline has compiled, then the warm-up frames.
    run_until_settled(&mut app, 600, |app| {
        frame(app);
    });
    for _ in 0..frames.warmup {
        frame(&mut app);
    }
    let start = Instant::now();
    let mut times = Vec::new();
    while times.len() < Frames::MIN_MEASURED
        || (times.len() < frames.measured && start.elapsed() < frames.budget)
    {
        times.push(frame(&mut app));
    }
    times.sort();
    Measured {
        app,
        target,
        median: times[times.len() / 2],
        _changed_shader: changed_shader,
    }
}

/// Waits until the shader asset at `path` has loaded, then adds `defs` to its own
/// `Shader::shader_defs`. Bevy composes every pipeline of that shader with the asset's defs
/// added to the pipeline's (`bevy_shader` 0.19.1, `ShaderCache::get`), and naga_oil applies
/// them to every module it imports: the defs reach `#ifdef`s in any of the crate's modules.
/// Returns the shader's handle, to be held while the app runs: an asset no handle holds is
/// unloaded, and the material would then load the file afresh, without the defs.
///
/// # Panics
///
/// When the shader has not loaded within [`MAX_WAIT_FRAMES`] frames.
fn add_shader_defs(app: &mut App, path: &'static str, defs: &[&str]) -> Handle<Shader> {
    let handle: Handle<Shader> = app.world().resource::<AssetServer>().load(path);
    let mut frames = 0;
    while !app.world().resource::<AssetServer>().is_loaded(&handle) {
        assert!(frames < MAX_WAIT_FRAMES, "{path} did not load");
        app.update();
        std::thread::sleep(Duration::from_millis(1));
        frames += 1;
    }
    let mut shaders = app.world_mut().resource_mut::<Assets<Shader>>();
    let mut shader = shaders.get_mut(&handle).expect("the shader has loaded");
    shader
        .shader_defs
        .extend(defs.iter().map(|&def| ShaderDefVal::from(def)));
    handle
}

/// Draws one more frame and reads the camera's `size`² target back: RGBA with 8-bit
/// channels, row by row, without the readback's row padding.
///
/// # Panics
///
/// When the readback has not arrived within [`MAX_WAIT_FRAMES`] frames.
fn read_back(app: &mut App, target: Handle<Image>, size: u32) -> Vec<u8> {
    let received: Arc<Mutex<Option<Vec<u8>>>> = Arc::default();
    let sink = received.clone();
    let entity = app
        .world_mut()
        .spawn(Readback::texture(target))
        .observe(move |readback: On<ReadbackComplete>| {
            *sink.lock().unwrap() = Some(readback.data.clone());
        })
        .id();
    for _ in 0..MAX_WAIT_FRAMES {
        frame(app);
        if let Some(bytes) = received.lock().unwrap().take() {
            app.world_mut().despawn(entity);
            let row_bytes = bytes.len() / size as usize;
            return bytes
                .chunks_exact(row_bytes)
                .flat_map(|row| &row[..4 * size as usize])
                .copied()
                .collect();
        }
    }
    panic!("the readback did not arrive within {MAX_WAIT_FRAMES} frames");
}

/// A camera that renders `scene` into a `size`² sRGB image; returns the image.
fn spawn_camera(world: &mut World, scene: Scene, size: u32) -> Handle<Image> {
    let mut target = Image::new_target_texture(size, size, TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let target = world.resource_mut::<Assets<Image>>().add(target);
    world.spawn((
        Camera3d::default(),
        RenderTarget::Image(target.clone().into()),
        Msaa::Off,
        Tonemapping::None,
        Transform::from_translation(scene.camera_position()).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    target
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
