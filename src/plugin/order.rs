//! Where [`PhongPlugin`](crate::PhongPlugin) must sit among Bevy's plugins, and what it says
//! when it does not.
//!
//! `PhongPlugin` registers an asset (the material), shaders and render-world systems, so
//! Bevy's `AssetPlugin` and `RenderPlugin` (both in `DefaultPlugins`) must be built first:
//! `.add_plugins((DefaultPlugins, PhongPlugin))`.
//!
//! - Added before `AssetPlugin`: nothing it registers could work, so it stops at once
//!   ([`ADD_AFTER_DEFAULT_PLUGINS`]).
//! - Added after `AssetPlugin` but before `RenderPlugin`: it would gather lights but never
//!   draw, so it stops when the app finishes building ([`RENDERER_ADDED_LATER`]).
//! - In an app without a renderer (`MinimalPlugins` and `AssetPlugin`, as ECS-only tests and
//!   servers use): it gathers lights and validates input, and warns once that nothing is
//!   drawn ([`NO_RENDERER`]).

use crate::material::PhongMaterial;
use bevy::{app::App, asset::AssetPlugin, pbr::MaterialPlugin, render::RenderApp};

/// The panic message of a `PhongPlugin` added before Bevy's `AssetPlugin`.
pub(crate) const ADD_AFTER_DEFAULT_PLUGINS: &str = "bevy_phong: add PhongPlugin after \
    DefaultPlugins, as in `.add_plugins((DefaultPlugins, PhongPlugin))`: it was added before \
    Bevy's AssetPlugin, which it needs to register PhongMaterial and its shaders";

/// The panic message of a `PhongPlugin` added before Bevy's `RenderPlugin`.
pub(crate) const RENDERER_ADDED_LATER: &str = "bevy_phong: add PhongPlugin after \
    DefaultPlugins, as in `.add_plugins((DefaultPlugins, PhongPlugin))`: Bevy's RenderPlugin \
    was added after it, so PhongMaterial would never be drawn";

/// The warning of an app that has no renderer when it finishes building.
pub(crate) const NO_RENDERER: &str = "bevy_phong: the app has no renderer (Bevy's \
    RenderPlugin, part of DefaultPlugins): PhongPlugin gathers and validates lights, but \
    nothing is drawn";

/// Called first in `PhongPlugin::build`: stops with [`ADD_AFTER_DEFAULT_PLUGINS`] where Bevy's
/// `AssetPlugin` is not there yet.
pub(crate) fn check_build(app: &App) {
    if !app.is_plugin_added::<AssetPlugin>() {
        panic!("{ADD_AFTER_DEFAULT_PLUGINS}");
    }
}

/// What `PhongPlugin::finish` finds: `Err` with [`RENDERER_ADDED_LATER`] where the app has a
/// renderer but `PhongPlugin` added no material plugin (its build found no renderer yet),
/// `Ok(Some(NO_RENDERER))` where there is none, `Ok(None)` where all is in order.
pub(crate) fn check_finish(app: &App) -> Result<Option<&'static str>, &'static str> {
    let drawn = app.is_plugin_added::<MaterialPlugin<PhongMaterial>>();
    match (app.get_sub_app(RenderApp).is_some(), drawn) {
        (true, false) => Err(RENDERER_ADDED_LATER),
        (false, _) => Ok(Some(NO_RENDERER)),
        (true, true) => Ok(None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PhongPlugin;
    use bevy::{prelude::*, render::RenderApp};
    use std::panic::{AssertUnwindSafe, catch_unwind};

    /// The text of a panic payload (`panic!` with a format string gives a `String`).
    fn panic_text(payload: Box<dyn core::any::Any + Send>) -> String {
        payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default()
    }

    #[test]
    fn the_plugin_before_default_plugins_stops_at_once_naming_the_fix() {
        // Exactly the order a new user writes by mistake: `PhongPlugin` is built first and
        // stops before `DefaultPlugins` (which needs a window system) is built at all.
        let result = catch_unwind(AssertUnwindSafe(|| {
            App::new().add_plugins((PhongPlugin, DefaultPlugins));
        }));
        let message = panic_text(result.expect_err("PhongPlugin before DefaultPlugins stops"));
        assert!(
            message.contains("add PhongPlugin after DefaultPlugins"),
            "the message names the fix: {message}"
        );
        assert!(message.contains("AssetPlugin"), "and the cause: {message}");
    }

    #[test]
    fn a_renderer_added_after_the_plugin_stops_when_the_app_finishes() {
        let mut app = App::new();
        app.add_plugins((MinimalPlugins, AssetPlugin::default()));
        check_build(&app);
        assert_eq!(check_finish(&app), Ok(Some(NO_RENDERER)));
        // A render sub-app inserted after the plugin was built, as a RenderPlugin added
        // later would.
        app.insert_sub_app(RenderApp, bevy::app::SubApp::new());
        assert_eq!(check_finish(&app), Err(RENDERER_ADDED_LATER));
    }

    #[test]
    fn an_app_without_a_renderer_runs_and_is_warned_once() {
        // `test_app` is `MinimalPlugins`, `AssetPlugin`, transforms and `PhongPlugin`: built,
        // finished and one frame run without a panic.
        let app = crate::test_app::test_app(|_| {});
        assert_eq!(check_finish(&app), Ok(Some(NO_RENDERER)));
        assert!(NO_RENDERER.contains("RenderPlugin"));
    }
}
