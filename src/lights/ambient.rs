//! The ambient light: one per scene, a resource.

use bevy::prelude::{ReflectDefault, ReflectResource};
use bevy::{color::Color, ecs::resource::Resource, reflect::Reflect};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// Light that reaches every surface from every direction, without a position, a direction or
/// a highlight. It adds `color ⊙ ambient_factor ⊙ base_color` to every [`PhongMaterial`]
/// (see SPEC.md's equation).
///
/// There is one per scene: change it with `ResMut<PhongAmbientLight>`. Under
/// [`PhongBevyLightsPlugin`](crate::PhongBevyLightsPlugin), which sets it to none when it
/// is added, each camera's Bevy ambient light adds to it in that camera's view.
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

/// Each camera's own Bevy ambient light, added to [`PhongAmbientLight`] in that camera's view
/// ([`PhongBevyLightsPlugin`](crate::PhongBevyLightsPlugin) inserts it): the camera's Bevy
/// `AmbientLight`, else the `GlobalAmbientLight` resource, `color × brightness` as Bevy
/// writes it into each view's light uniform, times `scale`. Without this resource no Bevy
/// ambient light is read.
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub(crate) struct BevyAmbientPerView {
    /// The factor from Bevy's ambient light to Phong's: the mirror's exposure factor
    /// (`BevyLightExposure::factor`), finite and `≥ 0`.
    pub scale: f32,
}
