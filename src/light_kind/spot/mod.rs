//! The spot light: a point light limited to a cone.
//!
//! Everything particular to the kind is in this folder: the component (this file); the kind
//! (`kind.rs`, [`PhongLightKind`](crate::extension::PhongLightKind)): its record (with the cone's terms, `cone.rs`), reach and validation, its shadow (one perspective map over its cone) and its cookie projection (across its cone); and its light
//! in the reference model (`reference.rs`, feature `reference`). Its scene-file form is one
//! case of `scene::LightDescription`, beside every kind's (one file format), and the
//! conversions from Bevy's and three.js's lights are in `interop` and `from_three`.
//! Registered by one line of `PhongPlugin` (`add_light_kind`).

mod cone;
mod kind;
#[cfg(feature = "reference")]
mod reference;

use crate::lights::{ConeEdge, Decay, PhongShadows};
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

/// A light that shines from the entity's position into a cone around its local -Z axis.
///
/// With `θ` the angle between the cone's axis and the ray to a surface point, the light is
/// full inside `inner_angle`, fades (linearly in `cos θ`, or along a smoothstep:
/// [`ConeEdge`]) to zero at `outer_angle` and is zero beyond; `inner_angle == outer_angle`
/// gives a hard edge. On top of that,
/// `cos(θ)^exponent` darkens the cone towards its rim. Distance fall-off is as for
/// [`PhongPointLight`](crate::PhongPointLight). Scale is ignored; a hidden entity gives no
/// light.
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Component, Default, Debug, Clone)]
#[require(Transform, Visibility)]
#[cfg_attr(feature = "scene", serde(default))]
pub struct PhongSpotLight {
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
    /// Half-angle of the fully lit core, in radians, `0 ≤ inner ≤ outer`.
    /// Default 12.5°.
    pub inner_angle: f32,
    /// Half-angle where the light reaches zero, in radians, `inner ≤ outer ≤ π` (180°; past
    /// 90° the cone lights behind the light too); a cone with `outer_angle = 0` is empty and
    /// gives no light. Default 17.5°.
    pub outer_angle: f32,
    /// Exponent of the `cos(θ)^exponent` rim darkening, `0` to `1e6`
    /// (`MAX_EXPONENT`). Default `0` (none).
    pub exponent: f32,
    /// How the light fades between `inner_angle` and `outer_angle`. Default
    /// [`ConeEdge::Linear`].
    pub cone_edge: ConeEdge,
}

impl Default for PhongSpotLight {
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            specular: None,
            decay: Decay::NONE,
            range: None,
            shadows: PhongShadows::default(),
            inner_angle: 12.5_f32.to_radians(),
            outer_angle: 17.5_f32.to_radians(),
            exponent: 0.0,
            cone_edge: ConeEdge::Linear,
        }
    }
}
