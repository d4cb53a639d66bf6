//! What goes wrong with a scene or material file.

use super::SceneColor;
use crate::quoting::shorten_quoted_spans;
use bevy::{
    asset::{LoadContext, io::Reader},
    color::Color,
};
use serde::de::DeserializeOwned;
use thiserror::Error;

/// Why a scene or material file did not load. The app keeps what it had (a hot-reloaded
/// scene stays as it last loaded) and Bevy's asset server logs this message.
#[derive(Debug, Error)]
pub enum SceneFileError {
    /// The file could not be read.
    #[error("{path}: could not read the file: {source}")]
    Read {
        /// The asset path.
        path: String,
        /// What the reader said.
        source: std::io::Error,
    },
    /// The file is not valid RON for its type: the position of the problem and what was
    /// expected there. Values quoted from the file are cut to 80 characters.
    #[error("{path}:{line}:{column}: {message}")]
    Syntax {
        /// The asset path.
        path: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What was found and what was expected.
        message: String,
    },
    /// A value parsed but cannot be used (a negative radius, an unknown color).
    #[error("{path}: {field}: {message}")]
    Invalid {
        /// The asset path.
        path: String,
        /// Where the value sits, as `objects[2].mesh.radius`.
        field: String,
        /// What is wrong and what is allowed; a value it quotes is cut to 80 characters.
        message: String,
    },
}

impl SceneFileError {
    /// An [`Invalid`](Self::Invalid) error for the file being loaded.
    pub(crate) fn invalid(
        load_context: &LoadContext,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        SceneFileError::Invalid {
            path: load_context.path().to_string(),
            field: field.into(),
            message: message.into(),
        }
    }
}

/// `color` as a Bevy color; one that cannot be used is an [`Invalid`](SceneFileError::Invalid)
/// error at `field` of the file being loaded.
pub(crate) fn scene_color(
    load_context: &LoadContext,
    color: &SceneColor,
    field: impl Into<String>,
) -> Result<Color, SceneFileError> {
    color
        .to_color()
        .map_err(|message| SceneFileError::invalid(load_context, field, message))
}

/// Parses `text` as RON into `T`; a syntax or type error says where (`path:line:column`).
/// Text the message quotes from the file is cut to 80 characters, its length named.
pub fn parse_ron<T: DeserializeOwned>(path: &str, text: &[u8]) -> Result<T, SceneFileError> {
    ron::de::from_bytes(text).map_err(|error| SceneFileError::Syntax {
        path: path.to_owned(),
        line: error.span.start.line,
        column: error.span.start.col,
        message: shorten_quoted_spans(&error.code.to_string()),
    })
}

/// Reads the file being loaded and parses it as RON into `T`.
pub(crate) async fn read_ron<T: DeserializeOwned>(
    reader: &mut dyn Reader,
    load_context: &LoadContext<'_>,
) -> Result<T, SceneFileError> {
    let path = load_context.path().to_string();
    let mut bytes = Vec::new();
    reader
        .read_to_end(&mut bytes)
        .await
        .map_err(|source| SceneFileError::Read {
            path: path.clone(),
            source,
        })?;
    parse_ron(&path, &bytes)
}
