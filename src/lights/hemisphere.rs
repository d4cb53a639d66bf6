//! The hemisphere light: a sky color above and a ground color below, one per scene, a
//! resource.

use bevy::prelude::{ReflectDefault, ReflectResource};
use bevy::{color::Color, ecs::resource::Resource, math::Vec3, reflect::Reflect};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// Ambient light that depends on which way a surface faces, as three.js's `HemisphereLight`:
/// a surface whose normal points along `up` receives `sky_color`, one facing the other way
/// `ground_color`, and one in between their blend by `w = (1 + N·up) / 2`,
/// `ground_color + (sky_color − ground_color) · w`. Like [`PhongAmbientLight`], to which it
/// adds, it lights every [`PhongMaterial`] without a direction of its own, times the
/// material's `ambient_factor` and diffuse color (see SPEC.md, "Hemisphere light").
///
/// There is none by default: insert the resource to light a scene with it, remove it to stop.
/// Only while it is present is its term compiled into the materials (shader def
/// `PHONG_HEMISPHERE`): a scene without one pays nothing for it.
///
/// [`PhongAmbientLight`]: crate::PhongAmbientLight
/// [`PhongMaterial`]: crate::PhongMaterial
#[derive(Resource, Clone, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Resource, Default, Debug, Clone)]
#[cfg_attr(feature = "scene", serde(default))]
pub struct PhongHemisphereLight {
    /// The light from above (along `up`), linear RGB intensity as a color; each channel `0`
    /// to `1e6` (`MAX_INTENSITY`). Default: a pale sky blue,
    /// linear `(0.3, 0.35, 0.4)`.
    pub sky_color: Color,
    /// The light from below, as `sky_color`. Default: a dim brown, linear
    /// `(0.1, 0.08, 0.05)`.
    pub ground_color: Color,
    /// The world-space direction of the sky, any length. Default `+Y`; a vector without a
    /// direction (zero, NaN or infinite) is replaced by `+Y` with a warning.
    pub up: Vec3,
}

impl Default for PhongHemisphereLight {
    fn default() -> Self {
        Self {
            sky_color: Color::linear_rgb(0.3, 0.35, 0.4),
            ground_color: Color::linear_rgb(0.1, 0.08, 0.05),
            up: Vec3::Y,
        }
    }
}
