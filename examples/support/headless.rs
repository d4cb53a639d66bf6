//! Headless runs: no window, every 3D camera rendered into an image, saved as a PNG once
//! the pipelines are ready, then exit.

use super::{
    PICTURE_SIZE, RunMode, StillLoading,
    ready::{PipelinesReady, PipelinesReadyPlugin, ReadyFrames},
};
use bevy::{
    app::{AppExit, PluginGroupBuilder, ScheduleRunnerPlugin},
    camera::RenderTarget,
    prelude::*,
    render::gpu_readback::{Readback, ReadbackComplete},
    time::TimeUpdateStrategy,
};
use bevy_phong_headless::{headless_plugins, without_row_padding};
use std::time::Duration;

/// Bevy's plugins without a window, a loop that renders until the PNG is written, and the
/// capture.
pub fn add_plugins(
    app: &mut App,
    configure: impl FnOnce(PluginGroupBuilder) -> PluginGroupBuilder,
) {
    app.add_plugins((
        configure(headless_plugins()),
        ScheduleRunnerPlugin::run_loop(Duration::ZERO),
        HeadlessCapturePlugin,
    ))
    // Animations hold still at t = 0, so the picture is the same on every run.
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::ZERO));
}

/// Renders every 3D camera into an image and saves it once the pipelines are ready.
struct HeadlessCapturePlugin;

#[derive(Resource)]
struct CaptureTarget {
    image: Handle<Image>,
    frames_ready: ReadyFrames,
    requested: bool,
}

impl Plugin for HeadlessCapturePlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins(PipelinesReadyPlugin)
            .add_systems(PostStartup, render_cameras_to_image)
            .add_systems(Update, (request_capture, exit_when_drained))
            .add_observer(save_capture);
    }
}

fn render_cameras_to_image(
    mut commands: Commands,
    mut images: ResMut<Assets<Image>>,
    cameras: Query<Entity, With<Camera3d>>,
) {
    let image = images.add(super::picture_target());
    for camera in &cameras {
        commands
            .entity(camera)
            .insert(RenderTarget::Image(image.clone().into()));
    }
    commands.insert_resource(CaptureTarget {
        image,
        frames_ready: ReadyFrames::default(),
        requested: false,
    });
}

fn request_capture(
    mut commands: Commands,
    ready: Res<PipelinesReady>,
    target: Option<ResMut<CaptureTarget>>,
    loading: Option<Res<StillLoading>>,
) {
    let Some(mut target) = target else { return };
    if target.requested || loading.is_some() {
        return;
    }
    if target.frames_ready.settled(&ready) {
        target.requested = true;
        commands.spawn(Readback::texture(target.image.clone()));
    }
}

/// Frames to run after the picture is saved, before exiting: readbacks the render world
/// had already started for the next frames then arrive while the app still listens, instead
/// of failing against a closed channel.
const DRAIN_FRAMES: u32 = 3;

/// The exit code, and the frames left before the app exits with it.
#[derive(Resource)]
struct PendingExit {
    exit: AppExit,
    frames_left: u32,
}

fn exit_when_drained(pending: Option<ResMut<PendingExit>>, mut exit: MessageWriter<AppExit>) {
    let Some(mut pending) = pending else { return };
    if pending.frames_left == 0 {
        exit.write(pending.exit.clone());
    } else {
        pending.frames_left -= 1;
    }
}

fn save_capture(
    readback: On<ReadbackComplete>,
    mode: Res<RunMode>,
    mut saved: Local<bool>,
    mut commands: Commands,
) {
    let RunMode::Headless(path) = &*mode else {
        return;
    };
    // One frame is all it takes: later readbacks (already under way) are dropped.
    commands.entity(readback.entity).try_despawn();
    if *saved {
        return;
    }
    *saved = true;
    let (width, height) = (PICTURE_SIZE.x as usize, PICTURE_SIZE.y as usize);
    let pixels = without_row_padding(&readback.data, 4 * width, height);
    let exit = match super::save_picture(path, &pixels) {
        Ok(()) => AppExit::Success,
        Err(error) => {
            eprintln!("{error}");
            AppExit::error()
        }
    };
    commands.insert_resource(PendingExit {
        exit,
        frames_left: DRAIN_FRAMES,
    });
}
