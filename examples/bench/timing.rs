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
};
use bevy_phong::PhongLightCulling;
use bevy_phong_headless::{headless_app, run_until_settled};
use std::time::{Duration, Instant};

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
    let mut app = headless_app(|app| {
        app.add_plugins(MaterialPlugin::<ConstantColor>::default())
            .insert_resource(culling);
    });
    spawn_camera(app.world_mut(), scene, size);
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
    times[times.len() / 2]
}

/// A camera that renders `scene` into a `size`² sRGB image.
fn spawn_camera(world: &mut World, scene: Scene, size: u32) {
    let mut target = Image::new_target_texture(size, size, TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let target = world.resource_mut::<Assets<Image>>().add(target);
    world.spawn((
        Camera3d::default(),
        RenderTarget::Image(target.into()),
        Msaa::Off,
        Tonemapping::None,
        Transform::from_translation(scene.camera_position()).looking_at(Vec3::ZERO, Vec3::Y),
    ));
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
