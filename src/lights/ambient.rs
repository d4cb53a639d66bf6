//! The ambient light: one per scene, a resource.

use bevy::prelude::{ReflectDefault, ReflectResource};
use bevy::{color::Color, ecs::resource::Resource, reflect::Reflect};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// Light that reaches every surface from every direction, without a position, a direction or
/// a highlight. It adds `color ⊙ ambient_factor ⊙ base_color` to every [`PhongMaterial`]
/// (see SPEC.md's equation).
///
/// There is one per scene: change it with `ResMut<PhongAmbientLight>`.
///
/// [`PhongMaterial`]: crate::PhongMaterial
#[derive(Resource, Clone, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Resource, Default, Debug, Clone)]
#[cfg_attr(feature = "scene", serde(default))]
pub struct PhongAmbientLight {
    /// Intensity as a color, converted to linear RGB; each channel `0` to `1e6`
    /// (`MAX_INTENSITY`), so it may exceed 1.
    /// Default: linear gray `0.1`.
    pub color: Color,
}

impl PhongAmbientLight {
    /// No ambient light at all.
    pub const NONE: Self = Self {
        color: Color::BLACK,
    };
}

impl Default for PhongAmbientLight {
    fn default() -> Self {
        Self {
            color: Color::linear_rgb(0.1, 0.1, 0.1),
        }
    }
}
