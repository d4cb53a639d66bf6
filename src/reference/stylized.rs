//! The stylized diffuse and specular modes in the reference model (SPEC.md, "Stylized
//! shading"): how each light's `N·L` and highlight are shaped.

use super::{SurfacePoint, normalize_or_zero, power};
use crate::material::{DiffuseMode, SpecularMode};
use bevy::image::Image;
use glam::DVec3;

/// A material's rim light: `color` (the rim color times its strength, linear RGB) times
/// [`rim_factor`], added everywhere, or with `lit_side` to each light's term.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rim {
    /// Color times strength.
    pub color: DVec3,
    /// The exponent on `1 − N·V`.
    pub power: f64,
    /// Whether it is added per light, weighted by the light's `max(N·L, 0)`.
    pub lit_side: bool,
}

impl Rim {
    /// No rim.
    pub const NONE: Self = Self {
        color: DVec3::ZERO,
        power: 2.0,
        lit_side: false,
    };

    /// The rim added everywhere at `surface` (zero with `lit_side`).
    pub fn glow(&self, surface: &SurfacePoint) -> DVec3 {
        if self.lit_side {
            return DVec3::ZERO;
        }
        let normal = normalize_or_zero(surface.normal);
        let view = normalize_or_zero(surface.camera - surface.position);
        self.color * rim_factor(normal, view, self.power)
    }
}

/// `(1 − max(N·V, 0))^power` for unit `normal` and `view`, 0 where either has no direction.
pub fn rim_factor(normal: DVec3, view: DVec3, power_of: f64) -> f64 {
    if normal == DVec3::ZERO || view == DVec3::ZERO {
        return 0.0;
    }
    power(1.0 - normal.dot(view).max(0.0), power_of)
}

/// `t` eased from 0 at `1 − width` to 1 at 1 (a smoothstep), 0 throughout for `width = 0`:
/// how a toon step rises into the next.
fn step_rise(t: f64, width: f64) -> f64 {
    if width <= 0.0 {
        return 0.0;
    }
    let x = ((t - (1.0 - width)) / width).clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// The diffuse factor of `n_dot_l` (`N·L`) in `mode`: `max(N·L, 0)` (Lambert),
/// `max((N·L + w) / (1 + w), 0)` (wrap), or `(⌊x·n⌋ + rise(fract(x·n))) / n` with
/// `x = max(N·L, 0)` (toon bands).
pub fn diffuse_factor(mode: DiffuseMode, n_dot_l: f64) -> f64 {
    match mode {
        DiffuseMode::Lambert => n_dot_l.max(0.0),
        DiffuseMode::Wrap(wrap) => {
            let wrap = f64::from(wrap);
            ((n_dot_l + wrap) / (1.0 + wrap)).max(0.0)
        }
        DiffuseMode::Toon { bands, smoothing } => {
            let bands = f64::from(bands);
            let steps = n_dot_l.max(0.0) * bands;
            (steps.floor() + step_rise(steps.fract(), smoothing.into())) / bands
        }
    }
}

/// A toon ramp (`PhongMaterial::toon_ramp_texture`): the red channel of its image's middle
/// row, linear, from left to right.
#[derive(Clone, Debug, PartialEq)]
pub struct ToonRamp {
    /// The texels' red values.
    pub red: Vec<f64>,
}

impl ToonRamp {
    /// The ramp of `image`, its texels decoded as a GPU samples them (sRGB formats to
    /// linear); `None` for an empty image or a format whose texels cannot be read here.
    pub fn from_image(image: &Image) -> Option<Self> {
        let (width, height) = (image.width(), image.height());
        let red = (0..width)
            .map(|x| {
                Some(f64::from(
                    image.get_color_at(x, height / 2).ok()?.to_linear().red,
                ))
            })
            .collect::<Option<Vec<f64>>>()?;
        (!red.is_empty()).then_some(Self { red })
    }

    /// The diffuse factor at `n_dot_l`: the texel at `u = (1 + N·L) / 2`, column
    /// `min(⌊u·width⌋, width − 1)`, clamped to `[0, 1]`.
    pub fn factor(&self, n_dot_l: f64) -> f64 {
        let u = ((1.0 + n_dot_l) / 2.0).clamp(0.0, 1.0);
        let column = ((u * self.red.len() as f64) as usize).min(self.red.len() - 1);
        self.red[column].clamp(0.0, 1.0)
    }

    /// Whether `n_dot_l` lies within `margin` (in units of `u`'s texels) of a texel's edge,
    /// where a shader's `f32` may read the neighbour.
    pub fn near_an_edge(&self, n_dot_l: f64, margin: f64) -> bool {
        let position = (1.0 + n_dot_l) / 2.0 * self.red.len() as f64;
        let fraction = position.fract();
        fraction < margin || fraction > 1.0 - margin
    }
}

/// The highlight `h` drawn in `mode`: itself (smooth), a spot where `h > 1/2` whose edge
/// rises over `smoothing` (toon; a step at `h ≥ 1/2` for 0), or 0 (off).
pub fn highlight_factor(mode: SpecularMode, h: f64) -> f64 {
    match mode {
        SpecularMode::Smooth => h,
        SpecularMode::Off => 0.0,
        SpecularMode::Toon { smoothing } => {
            let width = f64::from(smoothing);
            if width <= 0.0 {
                return if h >= 0.5 { 1.0 } else { 0.0 };
            }
            let x = ((h - (0.5 - 0.5 * width)) / width).clamp(0.0, 1.0);
            x * x * (3.0 - 2.0 * x)
        }
    }
}

/// Where a shader's `f32` may land on the other side of a discontinuity of the modes: a toon
/// step at `N·L` (hard bands) or a hard toon spot at `h`, within `margin` of it. Pixels there
/// are not judged.
#[cfg(any(test, feature = "testing"))]
pub fn near_a_step(
    diffuse: DiffuseMode,
    specular: SpecularMode,
    n_dot_l: f64,
    h: f64,
    margin: f64,
) -> bool {
    let band_edge = match diffuse {
        DiffuseMode::Toon { bands, smoothing } if smoothing <= 0.0 => {
            let steps = n_dot_l.max(0.0) * f64::from(bands);
            let fraction = steps.fract();
            n_dot_l > 0.0 && (fraction < margin || fraction > 1.0 - margin)
        }
        _ => false,
    };
    let highlight_edge = matches!(specular, SpecularMode::Toon { smoothing } if smoothing <= 0.0)
        && (h - 0.5).abs() < margin;
    band_edge || highlight_edge
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lambert_is_the_clamped_cosine_and_wrap_reaches_past_the_terminator() {
        assert_eq!(diffuse_factor(DiffuseMode::Lambert, 0.25), 0.25);
        assert_eq!(diffuse_factor(DiffuseMode::Lambert, -0.25), 0.0);
        // w = 0.5: N·L = -0.5 is the new terminator, N·L = 1 still 1.
        let wrap = DiffuseMode::Wrap(0.5);
        assert_eq!(diffuse_factor(wrap, -0.5), 0.0);
        assert_eq!(diffuse_factor(wrap, 1.0), 1.0);
        assert!((diffuse_factor(wrap, 0.0) - 1.0 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn toon_bands_are_flat_steps_that_rise_over_their_smoothing() {
        let hard = DiffuseMode::Toon {
            bands: 4,
            smoothing: 0.0,
        };
        assert_eq!(diffuse_factor(hard, 0.3), 0.25);
        assert_eq!(diffuse_factor(hard, 0.49), 0.25);
        assert_eq!(diffuse_factor(hard, 1.0), 1.0);
        assert_eq!(diffuse_factor(hard, -0.2), 0.0);
        let soft = DiffuseMode::Toon {
            bands: 4,
            smoothing: 0.5,
        };
        // Flat over the first half of a step, then halfway up at 3/4 of it.
        assert_eq!(diffuse_factor(soft, 0.3), 0.25);
        assert!((diffuse_factor(soft, 0.25 + 0.25 * 0.75) - 0.375).abs() < 1e-12);
    }

    #[test]
    fn a_toon_highlight_is_a_spot_where_the_highlight_passes_one_half() {
        let hard = SpecularMode::Toon { smoothing: 0.0 };
        assert_eq!(highlight_factor(hard, 0.49), 0.0);
        assert_eq!(highlight_factor(hard, 0.5), 1.0);
        let soft = SpecularMode::Toon { smoothing: 0.2 };
        assert_eq!(highlight_factor(soft, 0.39), 0.0);
        assert_eq!(highlight_factor(soft, 0.5), 0.5);
        assert_eq!(highlight_factor(soft, 0.61), 1.0);
        assert_eq!(highlight_factor(SpecularMode::Off, 1.0), 0.0);
        assert_eq!(highlight_factor(SpecularMode::Smooth, 0.3), 0.3);
    }
}
