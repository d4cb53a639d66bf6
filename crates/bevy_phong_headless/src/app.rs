//! A headless app with Bevy's renderer and `PhongPlugin`, for tests and benchmarks that drive
//! frames themselves.

use bevy::{
    app::{PluginGroupBuilder, PluginsState},
    log::LogPlugin,
    prelude::*,
    render::{RenderApp, pipelined_rendering::PipelinedRenderingPlugin},
    window::ExitCondition,
    winit::WinitPlugin,
};
use bevy_phong::PhongPlugin;

/// Bevy's default plugins without a window: no primary window, no winit event loop, and an
/// app that does not exit when it has no window.
pub fn headless_plugins() -> PluginGroupBuilder {
    DefaultPlugins
        .set(WindowPlugin {
            primary_window: None,
            exit_condition: ExitCondition::DontExit,
            ..default()
        })
        .disable::<WinitPlugin>()
}

/// An app with Bevy's default plugins (no window, no log, no pipelined rendering) and
/// [`PhongPlugin`], plus what `add_plugins` adds, built and ready to `update`. Rendering
/// happens inside `update`, so the render world can be read between updates.
///
/// # Panics
///
/// Without a render device (no Vulkan driver), with a message that says what to install.
pub fn headless_app(add_plugins: impl FnOnce(&mut App)) -> App {
    headless_app_with_assets(AssetPlugin::default().file_path, add_plugins)
}

/// [`headless_app`] whose assets load from `asset_root` (relative to the crate being run, or
/// absolute).
pub fn headless_app_with_assets(asset_root: String, add_plugins: impl FnOnce(&mut App)) -> App {
    let mut app = App::new();
    app.add_plugins(frame_driven_plugins(asset_root))
        .add_plugins(PhongPlugin);
    add_plugins(&mut app);
    finish_frame_driven_app(&mut app);
    app
}

/// [`headless_plugins`] as a frame-driven app has them: assets from `asset_root`, no log
/// and no pipelined rendering (each `update` renders its frame). An app built from them
/// and finished with [`finish_frame_driven_app`] is what [`headless_app`] builds, less
/// `PhongPlugin`.
pub fn frame_driven_plugins(asset_root: String) -> PluginGroupBuilder {
    headless_plugins()
        .set(AssetPlugin {
            file_path: asset_root,
            ..default()
        })
        .disable::<LogPlugin>()
        .disable::<PipelinedRenderingPlugin>()
}

/// Builds the plugins of `app` (made from [`frame_driven_plugins`]) so that it is ready to
/// `update`.
///
/// # Panics
///
/// Without a render device (no Vulkan driver), with a message that says what to install.
pub fn finish_frame_driven_app(app: &mut App) {
    while app.plugins_state() == PluginsState::Adding {
        bevy::tasks::tick_global_task_pools_on_main_thread();
    }
    app.finish();
    app.cleanup();
    assert!(
        app.get_sub_app(RenderApp).is_some(),
        "no render app: is a Vulkan driver installed? On Debian: \
         apt-get install mesa-vulkan-drivers, then WGPU_ADAPTER_NAME=llvmpipe"
    );
}
