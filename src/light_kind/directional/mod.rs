//! The directional light: parallel rays from infinitely far away.
//!
//! Everything particular to the kind is in this folder: the component (this file); the kind
//! (`kind.rs`, [`PhongLightKind`](crate::extension::PhongLightKind)): its record and validation, its shadow (cascades per camera along its rays) and its cookie projection (on its local XY plane); and its light
//! in the reference model (`reference.rs`, feature `reference`). Its scene-file form is one
//! case of `scene::LightDescription`, beside every kind's (one file format), and the
//! conversions from Bevy's and three.js's lights are in `interop` and `from_three`.
//! Registered by one line of `PhongPlugin` (`add_light_kind`).

mod kind;
#[cfg(feature = "reference")]
mod reference;

use crate::lights::{PhongCascades, PhongShadows};
use bevy::{
    camera::visibility::Visibility,
    color::Color,
    ecs::component::Component,
    prelude::{ReflectComponent, ReflectDefault},
    reflect::Reflect,
    transform::components::Transform,
};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// A light whose rays are all parallel, like the sun: no position, no fall-off.
///
/// The rays travel along the entity's local -Z axis (Bevy's forward, so
/// `Transform::looking_to(direction, Vec3::Y)` aims it); translation and scale are ignored.
/// A hidden entity ([`Visibility::Hidden`]) gives no light.
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Component, Default, Debug, Clone)]
#[require(Transform, Visibility)]
#[cfg_attr(feature = "scene", serde(default))]
pub struct PhongDirectionalLight {
    /// Diffuse intensity, converted to linear RGB; each channel `0` to `1e6`
    /// (`MAX_INTENSITY`), so it may exceed 1. Default white.
    pub color: Color,
    /// Specular intensity, in the same range; `None` (the default) uses
    /// [`color`](Self::color).
    pub specular: Option<Color>,
    /// Shadow settings. Default off.
    pub shadows: PhongShadows,
    /// How the shadow is split along the camera's view. Default four cascades to 100 units.
    pub cascades: PhongCascades,
}

impl Default for PhongDirectionalLight {
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            specular: None,
            shadows: PhongShadows::default(),
            cascades: PhongCascades::default(),
        }
    }
}
