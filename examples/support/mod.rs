//! What every example shares: a window where a display exists, else (or with
//! `--headless PATH`) a render to a PNG file and exit.

use bevy::{
    app::{AppExit, ScheduleRunnerPlugin},
    camera::RenderTarget,
    core_pipeline::tonemapping::Tonemapping,
    prelude::*,
    render::{
        Render, RenderApp, RenderSystems,
        gpu_readback::{Readback, ReadbackComplete},
        render_resource::{PipelineCache, TextureFormat, TextureUsages},
    },
    time::TimeUpdateStrategy,
};
use bevy_phong_headless::headless_plugins;
use std::{
    path::PathBuf,
    sync::{
        Arc,
        atomic::{AtomicBool, Ordering},
    },
    time::Duration,
};

/// Size of the PNG written in headless mode.
const HEADLESS_SIZE: UVec2 = UVec2::new(960, 540);
/// Frames drawn after every pipeline is ready, before the one that is saved.
const SETTLE_FRAMES: u32 = 3;

/// How an example runs.
#[derive(Clone, Debug, Resource)]
pub enum RunMode {
    /// In a window.
    Windowed,
    /// Render one frame into a PNG at this path, then exit.
    Headless(PathBuf),
}

impl RunMode {
    /// `--headless PATH` renders to PATH; without a display (no `DISPLAY` or
    /// `WAYLAND_DISPLAY`) it renders to `target/NAME.png`; otherwise it opens a window.
    pub fn from_args(name: &str) -> Self {
        let args: Vec<String> = std::env::args().skip(1).collect();
        if let Some(index) = args.iter().position(|arg| arg == "--headless") {
            let path = args
                .get(index + 1)
                .map(PathBuf::from)
                .unwrap_or_else(|| default_png(name));
            return RunMode::Headless(path);
        }
        let has_display = ["DISPLAY", "WAYLAND_DISPLAY"]
            .iter()
            .any(|var| std::env::var_os(var).is_some_and(|v| !v.is_empty()));
        if has_display {
            RunMode::Windowed
        } else {
            let path = default_png(name);
            println!("no display found: rendering to {}", path.display());
            RunMode::Headless(path)
        }
    }
}

fn default_png(name: &str) -> PathBuf {
    PathBuf::from("target").join(format!("{name}.png"))
}

/// An app with Bevy's default plugins set up for `mode`: a titled window, or no window and
/// a loop that renders until the PNG is written.
pub fn example_app(name: &str) -> App {
    let mode = RunMode::from_args(name);
    let mut app = App::new();
    match &mode {
        RunMode::Windowed => {
            app.add_plugins(DefaultPlugins.set(WindowPlugin {
                primary_window: Some(Window {
                    title: format!("bevy_phong: {name}"),
                    ..default()
                }),
                ..default()
            }));
        }
        RunMode::Headless(_) => {
            app.add_plugins((
                headless_plugins(),
                ScheduleRunnerPlugin::run_loop(Duration::ZERO),
                HeadlessCapturePlugin,
            ))
            // Animations hold still at t = 0, so the picture is the same on every run.
            .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::ZERO));
        }
    }
    app.insert_resource(mode);
    app
}

/// Renders every 3D camera into an image and saves it once the pipelines are ready.
struct HeadlessCapturePlugin;

/// Set by the render world when no pipeline is waiting to compile.
#[derive(Resource, Clone, Default)]
struct PipelinesReady(Arc<AtomicBool>);

#[derive(Resource)]
struct CaptureTarget {
    image: Handle<Image>,
    frames_ready: u32,
    requested: bool,
}

impl Plugin for HeadlessCapturePlugin {
    fn build(&self, app: &mut App) {
        let ready = PipelinesReady::default();
        app.insert_resource(ready.clone())
            .add_systems(PostStartup, render_cameras_to_image)
            .add_systems(Update, (request_capture, exit_when_drained))
            .add_observer(save_capture);
        if let Some(render_app) = app.get_sub_app_mut(RenderApp) {
            render_app
                .insert_resource(ready)
                .add_systems(Render, report_pipelines.after(RenderSystems::Render));
        }
    }
}

fn report_pipelines(cache: Res<PipelineCache>, ready: Res<PipelinesReady>) {
    ready.0.store(
        cache.waiting_pipelines().next().is_none(),
        Ordering::Relaxed,
    );
}

fn render_cameras_to_image(
    mut commands: Commands,
    mut images: ResMut<Assets<Image>>,
    cameras: Query<Entity, With<Camera3d>>,
) {
    let mut image = Image::new_target_texture(
        HEADLESS_SIZE.x,
        HEADLESS_SIZE.y,
        TextureFormat::Rgba8UnormSrgb,
        None,
    );
    image.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let image = images.add(image);
    for camera in &cameras {
        commands
            .entity(camera)
            .insert(RenderTarget::Image(image.clone().into()));
    }
    commands.insert_resource(CaptureTarget {
        image,
        frames_ready: 0,
        requested: false,
    });
}

fn request_capture(
    mut commands: Commands,
    ready: Res<PipelinesReady>,
    target: Option<ResMut<CaptureTarget>>,
) {
    let Some(mut target) = target else { return };
    if target.requested {
        return;
    }
    if ready.0.load(Ordering::Relaxed) {
        target.frames_ready += 1;
    } else {
        target.frames_ready = 0;
    }
    if target.frames_ready > SETTLE_FRAMES {
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
    let (width, height) = (HEADLESS_SIZE.x as usize, HEADLESS_SIZE.y as usize);
    let row_bytes = readback.data.len() / height;
    let pixels: Vec<u8> = (0..height)
        .flat_map(|row| readback.data[row * row_bytes..row * row_bytes + width * 4].to_vec())
        .collect();
    if let Some(parent) = path.parent() {
        let _ = std::fs::create_dir_all(parent);
    }
    match image::save_buffer(
        path,
        &pixels,
        width as u32,
        height as u32,
        image::ExtendedColorType::Rgba8,
    ) {
        Ok(()) => {
            println!("wrote {}", path.display());
            commands.insert_resource(PendingExit {
                exit: AppExit::Success,
                frames_left: DRAIN_FRAMES,
            });
        }
        Err(error) => {
            eprintln!("cannot write {}: {error}", path.display());
            commands.insert_resource(PendingExit {
                exit: AppExit::error(),
                frames_left: DRAIN_FRAMES,
            });
        }
    }
}

/// The camera settings every example uses, so the window and the PNG look the same: the
/// lighting model's colors as they are (no tone mapping).
pub fn example_camera(transform: Transform) -> impl Bundle {
    (Camera3d::default(), Tonemapping::None, transform)
}

/// Switches every `PhongMaterial` between Phong and Blinn-Phong highlights (key B).
#[allow(dead_code, reason = "only the examples that take keys use it")]
pub fn switch_specular_model(materials: &mut Assets<bevy_phong::PhongMaterial>) {
    use bevy_phong::SpecularModel;
    for (_, material) in materials.iter_mut() {
        material.specular_model = match material.specular_model {
            SpecularModel::Phong => SpecularModel::BlinnPhong,
            SpecularModel::BlinnPhong => SpecularModel::Phong,
        };
    }
    println!("specular model switched");
}

/// Shows `keys` as a line of help in the window's top-left corner (windowed runs only; the
/// PNG of a headless run shows the scene alone) and prints it.
#[allow(dead_code, reason = "only the examples that take keys use it")]
pub fn show_key_help<'a>(app: &'a mut App, keys: &'static str) -> &'a mut App {
    println!("keys: {keys}");
    if matches!(app.world().resource::<RunMode>(), RunMode::Windowed) {
        app.add_systems(Startup, move |mut commands: Commands| {
            commands.spawn((
                Text::new(keys),
                TextFont::from_font_size(16.0),
                Node {
                    position_type: PositionType::Absolute,
                    top: px(8.0),
                    left: px(8.0),
                    ..default()
                },
            ));
        });
    }
    app
}

/// Toggles the visibility of every entity with `L` (a light kind): hidden lights give no
/// light.
#[allow(dead_code, reason = "only the examples that take keys use it")]
pub fn toggle_visibility<L: Component>(lights: &mut Query<&mut Visibility, With<L>>) {
    for mut visibility in lights.iter_mut() {
        *visibility = match *visibility {
            Visibility::Hidden => Visibility::Inherited,
            _ => Visibility::Hidden,
        };
    }
}
