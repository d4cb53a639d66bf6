//! The edge of a light's cone (the spot light's).

use bevy::{prelude::ReflectDefault, reflect::Reflect};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

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
