//! In a browser: the app draws on the page's `<canvas id="bevy">` and, once it has drawn,
//! marks the page's `<body>` with `data-drawn`, which `scripts/browser.sh` waits for before
//! it takes its screenshot.

use super::{
    PICTURE_SIZE, StillLoading,
    ready::{PipelinesReady, PipelinesReadyPlugin, ReadyFrames},
};
use bevy::{app::PluginGroupBuilder, prelude::*, window::WindowResolution};

/// The attribute set on `<body>` once the app has drawn its scene.
const DRAWN_ATTRIBUTE: &str = "data-drawn";

/// Bevy's plugins with the primary window on the page's canvas, sized like the headless
/// PNG (one canvas pixel per picture pixel), and the signal that the scene is drawn.
pub fn add_plugins(
    app: &mut App,
    name: &str,
    configure: impl FnOnce(PluginGroupBuilder) -> PluginGroupBuilder,
) {
    app.add_plugins(configure(
        DefaultPlugins.set(WindowPlugin {
            primary_window: Some(Window {
                title: format!("bevy_phong: {name}"),
                canvas: Some("#bevy".into()),
                resolution: WindowResolution::new(PICTURE_SIZE.x, PICTURE_SIZE.y)
                    .with_scale_factor_override(1.0),
                ..default()
            }),
            ..default()
        }),
    ))
    .add_plugins(PipelinesReadyPlugin)
    .add_systems(Last, mark_drawn);
}

/// Sets [`DRAWN_ATTRIBUTE`] once frames have been drawn with every pipeline ready.
fn mark_drawn(
    ready: Res<PipelinesReady>,
    loading: Option<Res<StillLoading>>,
    mut frames: Local<ReadyFrames>,
    mut done: Local<bool>,
) {
    if *done || loading.is_some() || !frames.settled(&ready) {
        return;
    }
    *done = true;
    let body = web_sys::window()
        .and_then(|window| window.document())
        .and_then(|document| document.body());
    match body.map(|body| body.set_attribute(DRAWN_ATTRIBUTE, "")) {
        Some(Ok(())) => info!("the scene is drawn"),
        _ => warn!("cannot mark the page's <body> with {DRAWN_ATTRIBUTE}"),
    }
}
