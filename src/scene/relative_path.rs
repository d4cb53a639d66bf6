//! Paths that scene and material files name (material files, textures): relative to the
//! file that names them, and never outside its asset source.
//!
//! A path is refused, with an error naming its field, when it
//! - is longer than 1,024 characters (no file system takes it, and Bevy's error would
//!   repeat it);
//! - is empty, names a folder (ends in `/`, `.` or `..`) or names the file itself (a scene
//!   is no material, a material no image);
//! - names another asset source (`name://…`);
//! - is absolute (starts with `/` or `\`), since a file's paths are written relative to it;
//! - climbs above the asset folder's root with `..` segments.
//!
//! Bevy's asset server would otherwise either refuse such a path by panicking inside the
//! loader or, with `UnapprovedPathMode::Allow`, read a file outside the asset folder.

use super::SceneFileError;
use crate::quoting::quoted;
use bevy::asset::{AssetPath, LoadContext};

/// `path`, relative to the file being loaded, as an asset path inside the same asset source;
/// a path that is malformed or leads outside is an [`Invalid`](SceneFileError::Invalid)
/// error at `field`.
pub(crate) fn relative_path(
    load_context: &LoadContext,
    path: &str,
    field: impl Into<String>,
) -> Result<AssetPath<'static>, SceneFileError> {
    let field = field.into();
    let refuse = |why: &str| {
        SceneFileError::invalid(
            load_context,
            field.clone(),
            format!("{} {why}", quoted(path)),
        )
    };
    if path.chars().nth(MAX_PATH_CHARS).is_some() {
        return Err(refuse(&format!(
            "is too long: at most {MAX_PATH_CHARS} characters"
        )));
    }
    if path.is_empty() {
        return Err(refuse("is empty: name a file, relative to this one"));
    }
    if path.contains("://") {
        return Err(refuse(
            "names another asset source: only files in this file's asset source are loaded",
        ));
    }
    if path.starts_with(['/', '\\']) {
        return Err(refuse("is absolute: write it relative to this file"));
    }
    let without_label = path.rsplit_once('#').map_or(path, |(path, _)| path);
    if without_label.is_empty() {
        return Err(refuse(ITSELF));
    }
    if names_a_folder(without_label) {
        return Err(refuse("names a folder, not a file"));
    }
    let resolved = load_context
        .path()
        .resolve_embed_str(path)
        .map_err(|error| refuse(&format!("is not an asset path: {error}")))?;
    if resolved.is_unapproved() {
        return Err(refuse(
            "climbs out of the asset folder: `..` may not go above its root",
        ));
    }
    if resolved.source() != load_context.path().source() {
        return Err(refuse(
            "names another asset source: only files in this file's asset source are loaded",
        ));
    }
    if resolved.path() == load_context.path().path() {
        return Err(refuse(ITSELF));
    }
    Ok(resolved)
}

/// The longest path a file may name, in characters.
const MAX_PATH_CHARS: usize = 1024;

/// Why a path that names the file being loaded is refused.
const ITSELF: &str = "names this file itself: name another file";

/// Whether `path` (without a label) ends in a folder rather than a file name.
fn names_a_folder(path: &str) -> bool {
    let last = path.rsplit(['/', '\\']).next().unwrap_or_default();
    matches!(last, "" | "." | "..")
}

#[cfg(test)]
mod tests {
    use super::names_a_folder;

    #[test]
    fn folders_are_told_from_files() {
        for folder in ["textures/", ".", "..", "a/..", "./", "x\\.."] {
            assert!(names_a_folder(folder), "{folder}");
        }
        for file in ["a.png", "../a.png", "./a.png", "..a"] {
            assert!(!names_a_folder(file), "{file}");
        }
    }
}
