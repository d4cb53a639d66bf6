//! Spot lights: a point light limited to a cone.

use super::{Decay, PhongShadows};
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

/// How a spot light fades from its inner cone to its outer one, as a function of
/// `t = (cos θ − cos outer) / (cos inner − cos outer)` clamped to `[0, 1]` (SPEC.md, "The
/// equation", the spot cone).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Default, Debug, PartialEq, Clone)]
pub enum ConeEdge {
    /// `t` itself.
    #[default]
    Linear,
    /// `t² (3 − 2t)`: GLSL's `smoothstep(cos outer, cos inner, cos θ)`, three.js's spot edge
    /// (its `angle` is the outer angle, `angle · (1 − penumbra)` the inner one).
    Smooth,
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
