//! The range of every float a light, the ambient light or a [`PhongMaterial`] holds, and the
//! one rule that brings a value into it: NaN becomes the range's fallback, anything else is
//! clamped (so `-∞` becomes the minimum and `+∞` the maximum).
//!
//! [`crate::validation`] applies these ranges to components and materials (with a warning),
//! the material's uniform and the light records apply them again on their own (silently, so
//! that no frame draws with an invalid value), and [`crate::reference`] applies them exactly
//! as the uniform does.
//!
//! # Why `1e6`
//!
//! Every intensity and material factor is at most [`MAX_INTENSITY`] = `1e6`: light color and
//! specular channels, the ambient light, `base_color`, `specular_color`, `emissive`,
//! `specular_strength` and `ambient_factor`. Attenuation, cone and highlight factors and
//! `N·L` are at most 1, so one light adds at most
//! `color · k_d + specular · k_s · strength ≤ 1e6·1e6 + 1e6·1e6·1e6 ≈ 1e18` to a channel, and
//! `emissive + ambient · k_a · k_d ≤ 1e6 + 1e18`. A frame holds fewer than `2³²` lights (the
//! light counts are `u32`), so the whole sum stays below `2³² · 1e18 + 1e18 ≈ 4.3e27`,
//! eleven orders of magnitude under `f32::MAX` (3.4e38): no finite input can overflow to
//! infinity, however many lights there are. `1e6` is far above any physically meaningful
//! value in these units (1 is a full channel).
//!
//! [`PhongMaterial`]: crate::PhongMaterial

use bevy::{color::LinearRgba, math::Affine2};
use core::fmt;

/// The largest light intensity channel and material color channel or factor (see the
/// module documentation for the arithmetic behind it).
pub const MAX_INTENSITY: f32 = 1e6;

/// The largest highlight (`shininess`) or spot rim (`exponent`) exponent. Beyond it
/// `cos^α` is indistinguishable from a single point; the value keeps `α · ln(cos)` finite.
pub const MAX_EXPONENT: f32 = 1e6;

/// The largest `Decay` coefficient. A light with `quadratic = 1e6` has faded to 1% at 1 cm
/// (in metres): larger coefficients would change nothing visible.
pub const MAX_DECAY: f32 = 1e6;

/// A closed range `[min, max]` for one kind of value and what replaces NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// The smallest value allowed; `-∞` and smaller values become it.
    pub min: f32,
    /// The largest value allowed; `+∞` and larger values become it.
    pub max: f32,
    /// What replaces NaN.
    pub nan: f32,
}

/// Light color and specular channels, the ambient light, material color channels (alpha
/// excepted), `specular_strength`, `ambient_factor`: `[0, 1e6]`, NaN → 0.
pub const INTENSITY: Limits = Limits::new(0.0, MAX_INTENSITY, 0.0);

/// A color's alpha: `[0, 1]`, NaN → 1 (opaque).
pub const ALPHA: Limits = Limits::new(0.0, 1.0, 1.0);

/// `AlphaMode::Mask`'s cutoff: `[0, 1]`, NaN → 0.5 (Bevy's usual cutoff).
pub const ALPHA_CUTOFF: Limits = Limits::new(0.0, 1.0, 0.5);

/// `shininess` and the spot `exponent`: `[0, 1e6]`, NaN → 0.
pub const EXPONENT: Limits = Limits::new(0.0, MAX_EXPONENT, 0.0);

/// Each `Decay` coefficient: `[0, 1e6]`, NaN → 0.
pub const DECAY: Limits = Limits::new(0.0, MAX_DECAY, 0.0);

/// A cone's half-angle (a spot light's `inner_angle` and `outer_angle`, a cookie's cone),
/// radians: `[0, π]` (0° to 180°), NaN → 0 (an outer angle of 0 is an empty cone).
pub const CONE_ANGLE: Limits = Limits::new(0.0, core::f32::consts::PI, 0.0);

/// An area light's `width`, `height` and `radius`, world units: `[0, 1e6]`, NaN → 0 (no
/// area: no light).
pub const AREA_SIZE: Limits = Limits::new(0.0, 1e6, 0.0);

/// `PhongShadows::depth_bias` (world units) and `normal_bias` (texels): `[0, 1e6]`, NaN → 0.
pub const SHADOW_BIAS: Limits = Limits::new(0.0, 1e6, 0.0);

/// `PhongShadows::softness` (world units, or degrees for a directional light):
/// `[0, 1e6]`, NaN → 0 (hard edges). A directional light's is used up to 45°.
pub const SHADOW_SOFTNESS: Limits = Limits::new(0.0, 1e6, 0.0);

/// `PhongShadows::near_distance`, world units: `[1e-6, 1e6]`, NaN → 0.1.
pub const SHADOW_NEAR: Limits = Limits::new(1e-6, 1e6, 0.1);

/// `PhongShadows::diffuse_in_shadow` and `specular_in_shadow`: `[0, 1]`, NaN → 0.
pub const SHADOW_FRACTION: Limits = Limits::new(0.0, 1.0, 0.0);

/// `PhongCascades::first_far_bound` and `max_distance`, world units: `[1e-3, 1e7]`, NaN →
/// 100 (a far bound a camera sees).
pub const CASCADE_DISTANCE: Limits = Limits::new(1e-3, 1e7, 100.0);

/// `PhongCascades::overlap`: `[0, 0.95]`, NaN → 0.2.
pub const CASCADE_OVERLAP: Limits = Limits::new(0.0, 0.95, 0.2);

impl Limits {
    /// The range `[min, max]`, NaN replaced by `nan`.
    pub const fn new(min: f32, max: f32, nan: f32) -> Self {
        Self { min, max, nan }
    }

    /// `value` brought into the range: NaN → [`nan`](Self::nan), else clamped to
    /// `[min, max]`.
    pub fn apply(self, value: f32) -> f32 {
        if value.is_nan() {
            self.nan
        } else {
            value.clamp(self.min, self.max)
        }
    }
}

impl fmt::Display for Limits {
    /// `0 to 1000000`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} to {}", self.min, self.max)
    }
}

/// A fraction such as a material's reflectivity: `[0, 1]`, NaN → 0.
pub const FRACTION: Limits = Limits::new(0.0, 1.0, 0.0);

/// A ratio of refractive indices: `[0, 1e6]`, NaN → 1 (no bending).
pub const REFRACTION_RATIO: Limits = Limits::new(0.0, 1e6, 1.0);

/// The most toon bands a [`DiffuseMode::Toon`](crate::DiffuseMode::Toon) has (at least 1).
pub const TOON_BANDS: u32 = 256;

/// The side, in texels, of each layer of the light cookie atlas: every
/// [`PhongLightCookie`](crate::PhongLightCookie)'s image is resampled to it.
pub const COOKIE_RESOLUTION: u32 = 256;

/// The widest cone, in radians, that a cookie's image is laid across (89.5°): a cone past
/// 90° has no plane to lay it on, so a wider one takes its image at this angle.
pub const WIDEST_COOKIE_CONE: f32 = 89.5 * core::f32::consts::PI / 180.0;

/// The most distinct cookie images a scene uses at once (layers of the atlas); lights whose
/// image comes later are drawn without their cookie, with a warning.
pub const MAX_COOKIE_IMAGES: usize = 64;

/// A signed scale such as a material's bump scale: `[-1e6, 1e6]`, NaN → 0.
pub const SIGNED_SCALE: Limits = Limits::new(-MAX_INTENSITY, MAX_INTENSITY, 0.0);

/// A factor on a normal map's `n.x` or `n.y` (`PhongMaterial::normal_map_scale`): `[-1e6,
/// 1e6]`, NaN → 1 (the map as it is).
pub const NORMAL_MAP_SCALE: Limits = Limits::new(-MAX_INTENSITY, MAX_INTENSITY, 1.0);

/// A material's depth bias, in the depth buffer's steps: wgpu takes an `i32`. NaN → 0.
pub const DEPTH_BIAS: Limits = Limits::new(-2_147_483_500.0, 2_147_483_500.0, 0.0);

/// A linear color with its red, green and blue in [`INTENSITY`]'s range and its alpha in
/// [`ALPHA`]'s.
pub fn linear_color(color: LinearRgba) -> LinearRgba {
    LinearRgba::new(
        INTENSITY.apply(color.red),
        INTENSITY.apply(color.green),
        INTENSITY.apply(color.blue),
        ALPHA.apply(color.alpha),
    )
}

/// A material's UV transform as it is drawn: itself where every number of it is finite,
/// the identity otherwise.
pub fn uv_transform(transform: Affine2) -> Affine2 {
    if transform.is_finite() {
        transform
    } else {
        Affine2::IDENTITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_takes_the_fallback_and_everything_else_is_clamped() {
        assert_eq!(INTENSITY.apply(f32::NAN), 0.0);
        assert_eq!(INTENSITY.apply(f32::NEG_INFINITY), 0.0);
        assert_eq!(INTENSITY.apply(-3.0), 0.0);
        assert_eq!(INTENSITY.apply(0.25), 0.25);
        assert_eq!(INTENSITY.apply(f32::MAX), MAX_INTENSITY);
        assert_eq!(INTENSITY.apply(f32::INFINITY), MAX_INTENSITY);
        assert_eq!(ALPHA.apply(f32::NAN), 1.0);
        assert_eq!(
            CONE_ANGLE.apply(1e9_f32.to_radians()),
            core::f32::consts::PI
        );
    }

    #[test]
    fn a_frame_of_the_largest_values_cannot_overflow() {
        // The worst channel the module documentation bounds: every light at the maximum,
        // on a material at the maximum, as many lights as a u32 counts. Computed in f64,
        // compared with f32::MAX; exact arithmetic, no tolerance needed.
        let bound = f64::from(MAX_INTENSITY);
        let per_light = bound * bound + bound * bound * bound;
        let frame = f64::from(u32::MAX) * per_light + bound + bound * bound * bound;
        assert!(frame < f64::from(f32::MAX) / 1e10, "{frame:e}");
    }
}
