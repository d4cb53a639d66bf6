//! Colors as scene and material files write them.

use crate::quoting::quoted;
use bevy::color::{Color, LinearRgba};
use serde::{Deserialize, Serialize};

/// A color in a scene or material file: `Srgb(r, g, b)` (what color pickers show),
/// `Srgba(r, g, b, a)`, `Linear(r, g, b)` (the shader's units; components may exceed 1) or
/// `Hex("#ffcc00")`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum SceneColor {
    /// sRGB-encoded red, green, blue in `[0, 1]`.
    Srgb(f32, f32, f32),
    /// sRGB-encoded red, green, blue and a linear alpha.
    Srgba(f32, f32, f32, f32),
    /// Linear red, green, blue.
    Linear(f32, f32, f32),
    /// `#rrggbb`, `#rrggbbaa`, `#rgb` or `#rgba` (sRGB).
    Hex(String),
}

impl SceneColor {
    /// The color, or a message saying what is wrong with it.
    pub fn to_color(&self) -> Result<Color, String> {
        Ok(match *self {
            SceneColor::Srgb(r, g, b) => Color::srgb(r, g, b),
            SceneColor::Srgba(r, g, b, a) => Color::srgba(r, g, b, a),
            SceneColor::Linear(r, g, b) => Color::LinearRgba(LinearRgba::rgb(r, g, b)),
            SceneColor::Hex(ref hex) => bevy::color::Srgba::hex(hex)
                .map(Color::from)
                .map_err(|error| format!("{} is not a hex color: {error}", quoted(hex)))?,
        })
    }

    /// White.
    pub fn white() -> Self {
        SceneColor::Linear(1.0, 1.0, 1.0)
    }

    /// Black.
    pub fn black() -> Self {
        SceneColor::Linear(0.0, 0.0, 0.0)
    }
}
