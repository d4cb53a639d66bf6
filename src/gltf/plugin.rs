//! [`PhongGltfPlugin`]: glTF files drawn with [`PhongMaterial`](crate::PhongMaterial).

use super::handler::PhongGltfExtensionHandler;
use crate::{PhongPlugin, interop::PhongBevyLightsPlugin};
use bevy::{
    app::{App, Plugin},
    gltf::extensions::GltfExtensionHandlers,
    log::warn,
    pbr::PbrPlugin,
};

/// Draws the meshes of glTF files with [`PhongMaterial`](crate::PhongMaterial) and lights
/// them with the files' `KHR_lights_punctual` lights. Opt-in; needs the `gltf` feature (on by
/// default).
///
/// While Bevy's glTF loader loads a file, the plugin's glTF extension handler
///
/// - adds a [`PhongMaterial`](crate::PhongMaterial) sub-asset per glTF material, labeled
///   `Material{n}/phong` (and `DefaultMaterial/phong` for primitives without one), made by
///   [`phong_material_from_gltf`](super::phong_material_from_gltf): see there for the
///   mapping of metallic/roughness and what is left out;
/// - inserts `MeshMaterial3d<PhongMaterial>` with that material on every primitive entity
///   of the file's scenes.
///
/// So the Phong materials exist before a scene is spawned, each is addressable
/// (`"scene.gltf#Material0/phong"`), and reloading the file rebuilds them the same way.
///
/// The plugin also adds [`PhongBevyLightsPlugin`] unless the app has it: Bevy spawns a
/// file's lights as its own `DirectionalLight`, `PointLight` and `SpotLight`, which that
/// plugin mirrors into Phong lights (the intensity conversion is
/// [`BevyLightExposure`](crate::BevyLightExposure)'s). Add `PhongBevyLightsPlugin` before
/// this plugin, or not at all.
///
/// # Bevy's `StandardMaterial` too
///
/// Bevy's PBR plugin registers a handler of the same kind that gives every primitive a
/// `MeshMaterial3d<StandardMaterial>` as well: each primitive is then drawn twice, once by
/// each material. The plugin warns once when it finds that handler on. Turn it off with
/// `PbrPlugin { gltf_enable_standard_materials: false, .. }`, as in the example below.
///
/// # Example
///
/// ```no_run
/// use bevy::{pbr::PbrPlugin, prelude::*};
/// use bevy_phong::prelude::*;
///
/// fn main() {
///     App::new()
///         .add_plugins((
///             DefaultPlugins.set(PbrPlugin {
///                 gltf_enable_standard_materials: false,
///                 ..default()
///             }),
///             PhongPlugin,
///             PhongGltfPlugin,
///         ))
///         .add_systems(Startup, setup)
///         .run();
/// }
///
/// fn setup(mut commands: Commands, asset_server: Res<AssetServer>) {
///     commands.spawn(WorldAssetRoot(
///         asset_server.load(GltfAssetLabel::Scene(0).from_asset("gltf/phong_test.gltf")),
///     ));
///     commands.spawn((Camera3d::default(), Transform::from_xyz(0.0, 4.0, 12.0)));
/// }
/// ```
///
/// Add it after [`PhongPlugin`] and Bevy's `DefaultPlugins` (it needs their glTF and
/// PBR plugins).
#[derive(Clone, Copy, Debug, Default)]
pub struct PhongGltfPlugin;

impl Plugin for PhongGltfPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<PhongBevyLightsPlugin>() {
            app.add_plugins(PhongBevyLightsPlugin);
        }
        // Bevy's glTF plugin creates the same resource; its loader shares the list, so a
        // handler pushed here is called whether that plugin is built before or after.
        app.init_resource::<GltfExtensionHandlers>();
        let handlers = app.world().resource::<GltfExtensionHandlers>().0.clone();
        #[cfg(target_family = "wasm")]
        let mut handlers = bevy::tasks::block_on(handlers.write());
        #[cfg(not(target_family = "wasm"))]
        let mut handlers = handlers.write_blocking();
        handlers.push(Box::new(PhongGltfExtensionHandler));
    }

    fn finish(&self, app: &mut App) {
        if !app.is_plugin_added::<PhongPlugin>() {
            warn!("PhongGltfPlugin without PhongPlugin: glTF meshes get no PhongMaterial drawn");
        }
        if standard_materials_enabled(app) {
            warn!("{DRAWN_TWICE}");
        }
    }
}

/// The warning given when Bevy's `StandardMaterial` handler is on beside this plugin's.
pub(crate) const DRAWN_TWICE: &str = "PhongGltfPlugin: Bevy's glTF StandardMaterials are \
    also on, so every glTF primitive gets both a StandardMaterial and a PhongMaterial and is \
    drawn twice. Turn Bevy's off with \
    `DefaultPlugins.set(PbrPlugin { gltf_enable_standard_materials: false, ..default() })`";

/// Whether Bevy's PBR plugin registers its glTF `StandardMaterial` handler in `app`.
pub(crate) fn standard_materials_enabled(app: &App) -> bool {
    app.get_added_plugins::<PbrPlugin>()
        .iter()
        .any(|pbr| pbr.gltf_enable_standard_materials)
}
