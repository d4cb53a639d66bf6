//! Scene and material files: a scene (camera, ambient light, lights, and objects made of
//! Bevy's mesh primitives with [`PhongMaterial`](crate::PhongMaterial)s) written in RON,
//! loaded by Bevy's asset server and hot-reloaded when the file changes.
//!
//! - `*.phong_scene.ron`: a [`PhongSceneDescription`], loaded as a [`PhongScene`] and
//!   spawned by a [`PhongSceneRoot`];
//! - `*.phong.ron`: a [`PhongMaterialDescription`], loaded as a `PhongMaterial`.
//!
//! [`PhongPlugin`](crate::PhongPlugin) registers both loaders. A file that does not parse
//! gives a [`SceneFileError`] with its line, column and what was expected there; a value
//! that cannot be used (a negative radius, a zero light direction) names its field
//! (`objects[2].mesh`). Either way nothing panics and a hot-reloaded scene keeps its last
//! good version. Paths to material files and textures are relative to the file that names
//! them and must stay inside its asset folder: a path with `..` above the folder's root, an
//! absolute path or another asset source (`name://`) is refused with an error naming its
//! field. Text quoted in an error is cut to 80 characters, its full length named. Light and
//! material values outside their ranges (a negative color, say) are replaced at run time,
//! with a warning, as for any light (`crate::validation`).
//!
//! Hot reload needs Bevy's `file_watcher` feature (it is off in this crate's own
//! dependencies; enable it in the game's).

mod color;
mod description;
pub(crate) mod error;
mod loader;
mod material_file;
mod relative_path;
mod spawn;

pub use color::SceneColor;
pub use description::{
    CameraDescription, CookieDescription, CubemapLayoutDescription, HemisphereDescription,
    LightDescription, MaterialSource, MeshDescription, ObjectDescription, PhongSceneDescription,
    TransformDescription,
};
pub use error::SceneFileError;
pub(crate) use error::{read_ron, scene_color};
pub use loader::{PhongScene, PhongSceneLoader, SceneLight};
pub use material_file::{
    AlphaModeDescription, CullModeDescription, PhongMaterialDescription, PhongMaterialLoader,
    UvChannelDescription, UvTransformDescription,
};
pub(crate) use relative_path::relative_path;
pub(crate) use spawn::spawn_phong_scenes;
pub use spawn::{PhongSceneCamera, PhongSceneRoot};

/// Adds scene and material files to `app` (after [`PhongMaterial`](crate::PhongMaterial)'s
/// asset type): their loaders, [`PhongScene`] and the system that spawns each
/// [`PhongSceneRoot`].
pub(crate) fn add_scene_files(app: &mut bevy::app::App) {
    use bevy::asset::AssetApp;
    app.register_type::<PhongSceneRoot>()
        .register_type::<PhongSceneCamera>()
        .init_asset::<PhongScene>()
        .register_asset_loader(PhongSceneLoader)
        .register_asset_loader(PhongMaterialLoader)
        .add_systems(bevy::app::PreUpdate, spawn_phong_scenes);
}

#[cfg(test)]
mod hostile_file_tests;
#[cfg(test)]
mod tests;
