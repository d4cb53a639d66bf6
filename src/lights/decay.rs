//! Distance attenuation of point and spot lights.

use bevy::{prelude::ReflectDefault, reflect::Reflect};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// How a point or spot light fades with distance `d` (world units) from the light:
///
/// ```text
/// A(d) = min(1, 1 / (constant + linear·d + quadratic·d²))
/// ```
///
/// The `min(1, …)` keeps a light that sits on a surface finite. All three coefficients are
/// multipliers of `1`, `d` and `d²`, each `0` to `1e6`
/// (`MAX_DECAY`); at least one should be positive (a `Decay` of
/// all zeros means "no fall-off": `A = 1`).
///
/// The default, [`Decay::NONE`], does not fade.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Default, Debug, PartialEq, Clone)]
#[cfg_attr(feature = "scene", serde(default))]
pub struct Decay {
    /// Constant term `c`. Default `1`.
    pub constant: f32,
    /// Linear term `l`, per world unit. Default `0`.
    pub linear: f32,
    /// Quadratic term `q`, per world unit squared. Default `0`.
    pub quadratic: f32,
}

impl Decay {
    /// No fall-off: `A(d) = 1` at every distance.
    pub const NONE: Self = Self::new(1.0, 0.0, 0.0);

    /// The common OpenGL choice for a light meant to reach about
    /// 50 units: `1 / (1 + 0.09·d + 0.032·d²)`, which is 0.44 at 5 units, 0.12 at 14 and
    /// 0.01 at 50.
    pub const DISTANCE_50: Self = Self::new(1.0, 0.09, 0.032);

    /// Builds a decay from its three coefficients.
    pub const fn new(constant: f32, linear: f32, quadratic: f32) -> Self {
        Self {
            constant,
            linear,
            quadratic,
        }
    }

    /// `1 / (1 + linear·d)`.
    pub const fn linear(linear: f32) -> Self {
        Self::new(1.0, linear, 0.0)
    }

    /// `1 / (1 + quadratic·d²)`: inverse-square fall-off that stays finite near the light.
    pub const fn quadratic(quadratic: f32) -> Self {
        Self::new(1.0, 0.0, quadratic)
    }

    /// The coefficients as `[constant, linear, quadratic]`.
    pub const fn to_array(self) -> [f32; 3] {
        [self.constant, self.linear, self.quadratic]
    }
}

impl Default for Decay {
    fn default() -> Self {
        Self::NONE
    }
}
