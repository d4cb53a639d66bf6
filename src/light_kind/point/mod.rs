//! The point light: light from one position in every direction.
//!
//! Everything particular to the kind is in this folder: the component (this file); the kind
//! (`kind.rs`, [`PhongLightKind`](crate::extension::PhongLightKind)): its record, reach and validation, its shadow (a cube map) and its cookie projection (a cube map around it); and its light
//! in the reference model (`reference.rs`, feature `reference`). Its scene-file form is one
//! case of `scene::LightDescription`, beside every kind's (one file format), and the
//! conversions from Bevy's and three.js's lights are in `interop` and `from_three`.
//! Registered by one line of `PhongPlugin` (`add_light_kind`).

mod kind;
#[cfg(feature = "reference")]
mod reference;

use crate::lights::{Decay, PhongShadows};
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

/// A light that shines from the entity's position in every direction, fading with distance
/// by its [`Decay`] and cut off at `range`.
///
/// Rotation and scale of the entity are ignored. A hidden entity gives no light.
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Component, Default, Debug, Clone)]
#[require(Transform, Visibility)]
#[cfg_attr(feature = "scene", serde(default))]
pub struct PhongPointLight {
    /// Diffuse intensity, converted to linear RGB; each channel `0` to `1e6`
    /// (`MAX_INTENSITY`), so it may exceed 1. Default white.
    pub color: Color,
    /// Specular intensity, in the same range; `None` (the default) uses
    /// [`color`](Self::color).
    pub specular: Option<Color>,
    /// Fall-off with distance. Default [`Decay::NONE`].
    pub decay: Decay,
    /// Distance (world units, `> 0`; `∞` is unlimited) past which the light contributes
    /// nothing; `None` (the default) means unlimited.
    pub range: Option<f32>,
    /// Shadow settings. Default off.
    pub shadows: PhongShadows,
}

impl Default for PhongPointLight {
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            specular: None,
            decay: Decay::NONE,
            range: None,
            shadows: PhongShadows::default(),
        }
    }
}
