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
//! good version. Light and material values outside their ranges (a negative color, say) are
//! replaced at run time, with a warning, as for any light ([`crate::validation`]).
//!
//! Hot reload needs Bevy's `file_watcher` feature (it is off in this crate's own
//! dependencies; enable it in the game's).

mod color;
mod description;
mod error;
mod loader;
mod material_file;
mod spawn;

pub use color::SceneColor;
pub use description::{
    CameraDescription, LightDescription, MaterialSource, MeshDescription, ObjectDescription,
    PhongSceneDescription, TransformDescription,
};
pub use error::{SceneFileError, parse_ron};
pub(crate) use error::{read_ron, relative_path, scene_color};
pub use loader::{PhongScene, PhongSceneLoader, SceneLight};
pub use material_file::{AlphaModeDescription, PhongMaterialDescription, PhongMaterialLoader};
pub(crate) use spawn::spawn_phong_scenes;
pub use spawn::{PhongSceneCamera, PhongSceneRoot};

#[cfg(test)]
mod tests;
