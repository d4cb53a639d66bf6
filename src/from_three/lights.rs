//! three.js's lights as the crate's: their colors times their intensities (three.js's
//! `color · intensity`, not divided by π: the converted materials hold the `1/π`), and
//! three.js's fall-off and spot edge.

use super::{ThreeError, linear_color, scaled};
use crate::light_kind::{PhongDirectionalLight, PhongPointLight, PhongSpotLight};
use crate::lights::{ConeEdge, Decay, PhongAmbientLight, PhongHemisphereLight};
use bevy::{color::Color, math::Vec3, transform::components::Transform};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// A three.js light, as its JSON's `type` names it, with the fields that convert and
/// three.js's defaults (color `0xffffff`, intensity 1, distance 0, decay 2, angle π/3,
/// penumbra 0). Where it is and where it points are the object's (see [`aimed_transform`]).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "scene", serde(tag = "type"))]
pub enum ThreeLight {
    /// `AmbientLight(color, intensity)`.
    AmbientLight {
        /// `0xRRGGBB` sRGB.
        #[cfg_attr(feature = "scene", serde(default = "white"))]
        color: u32,
        /// Factor on the color.
        #[cfg_attr(feature = "scene", serde(default = "one"))]
        intensity: f32,
    },
    /// `HemisphereLight(skyColor, groundColor, intensity)`.
    #[cfg_attr(feature = "scene", serde(rename_all = "camelCase"))]
    HemisphereLight {
        /// `0xRRGGBB` sRGB; `color` in three.js's JSON (its `Light.color`).
        #[cfg_attr(feature = "scene", serde(default = "white", rename = "color"))]
        sky_color: u32,
        /// `0xRRGGBB` sRGB.
        #[cfg_attr(feature = "scene", serde(default = "white"))]
        ground_color: u32,
        /// Factor on both colors.
        #[cfg_attr(feature = "scene", serde(default = "one"))]
        intensity: f32,
    },
    /// `DirectionalLight(color, intensity)`.
    DirectionalLight {
        /// `0xRRGGBB` sRGB.
        #[cfg_attr(feature = "scene", serde(default = "white"))]
        color: u32,
        /// Factor on the color.
        #[cfg_attr(feature = "scene", serde(default = "one"))]
        intensity: f32,
    },
    /// `PointLight(color, intensity, distance, decay)`.
    PointLight {
        /// `0xRRGGBB` sRGB.
        #[cfg_attr(feature = "scene", serde(default = "white"))]
        color: u32,
        /// Factor on the color.
        #[cfg_attr(feature = "scene", serde(default = "one"))]
        intensity: f32,
        /// Where three.js's window fades the light out; 0: nowhere (only 0 converts).
        #[cfg_attr(feature = "scene", serde(default))]
        distance: f32,
        /// The fall-off's exponent (0, 1 and 2 convert).
        #[cfg_attr(feature = "scene", serde(default = "two"))]
        decay: f32,
    },
    /// `SpotLight(color, intensity, distance, angle, penumbra, decay)`.
    SpotLight {
        /// `0xRRGGBB` sRGB.
        #[cfg_attr(feature = "scene", serde(default = "white"))]
        color: u32,
        /// Factor on the color.
        #[cfg_attr(feature = "scene", serde(default = "one"))]
        intensity: f32,
        /// As a point light's.
        #[cfg_attr(feature = "scene", serde(default))]
        distance: f32,
        /// As a point light's.
        #[cfg_attr(feature = "scene", serde(default = "two"))]
        decay: f32,
        /// The cone's half-angle, radians.
        #[cfg_attr(feature = "scene", serde(default = "third_of_pi"))]
        angle: f32,
        /// The share of the cone, from its rim, over which the light fades.
        #[cfg_attr(feature = "scene", serde(default))]
        penumbra: f32,
    },
}

#[cfg(feature = "scene")]
fn white() -> u32 {
    0xffffff
}

#[cfg(feature = "scene")]
fn one() -> f32 {
    1.0
}

#[cfg(feature = "scene")]
fn two() -> f32 {
    2.0
}

#[cfg(feature = "scene")]
fn third_of_pi() -> f32 {
    core::f32::consts::FRAC_PI_3
}

/// A converted light: a resource for the ambient and hemisphere lights, a component for the
/// others.
#[derive(Clone, Debug, PartialEq)]
pub enum ThreeLightOf {
    /// Insert as the resource.
    Ambient(PhongAmbientLight),
    /// Insert as the resource; set its `up` to the three.js light's position (its direction
    /// from the origin; `+Y` here).
    Hemisphere(PhongHemisphereLight),
    /// Spawn with [`aimed_transform`].
    Directional(PhongDirectionalLight),
    /// Spawn at the light's position.
    Point(PhongPointLight),
    /// Spawn with [`aimed_transform`].
    Spot(PhongSpotLight),
}

impl ThreeLight {
    /// The crate's light that lights as this one: `color · intensity`, and for point and
    /// spot lights three.js's `1 / max(d^decay, 0.01)` as a [`Decay`] of
    /// `1 / (100·d^decay)` (capped at 1) with the color times 100, exact for `decay` 0, 1
    /// and 2; a spot's inner angle `angle · (1 − penumbra)` with a [`ConeEdge::Smooth`]
    /// edge, three.js's `smoothstep`.
    ///
    /// # Errors
    ///
    /// [`ThreeError::Unsupported`] for a `distance` other than 0 (three.js's window
    /// `(1 − (d/distance)⁴)²` has no counterpart) and a `decay` other than 0, 1 or 2.
    pub fn to_phong(&self) -> Result<ThreeLightOf, ThreeError> {
        Ok(match *self {
            ThreeLight::AmbientLight { color, intensity } => {
                ThreeLightOf::Ambient(PhongAmbientLight {
                    color: times(color, intensity),
                })
            }
            ThreeLight::HemisphereLight {
                sky_color,
                ground_color,
                intensity,
            } => ThreeLightOf::Hemisphere(PhongHemisphereLight {
                sky_color: times(sky_color, intensity),
                ground_color: times(ground_color, intensity),
                up: Vec3::Y,
            }),
            ThreeLight::DirectionalLight { color, intensity } => {
                ThreeLightOf::Directional(PhongDirectionalLight {
                    color: times(color, intensity),
                    ..PhongDirectionalLight::default()
                })
            }
            ThreeLight::PointLight {
                color,
                intensity,
                distance,
                decay,
            } => {
                let (decay, factor) = fall_off("PointLight", distance, decay)?;
                ThreeLightOf::Point(PhongPointLight {
                    color: times(color, intensity * factor),
                    decay,
                    range: None,
                    ..PhongPointLight::default()
                })
            }
            ThreeLight::SpotLight {
                color,
                intensity,
                distance,
                decay,
                angle,
                penumbra,
            } => {
                let (decay, factor) = fall_off("SpotLight", distance, decay)?;
                ThreeLightOf::Spot(PhongSpotLight {
                    color: times(color, intensity * factor),
                    decay,
                    range: None,
                    outer_angle: angle,
                    inner_angle: angle * (1.0 - penumbra.clamp(0.0, 1.0)),
                    exponent: 0.0,
                    cone_edge: ConeEdge::Smooth,
                    ..PhongSpotLight::default()
                })
            }
        })
    }
}

/// `0xRRGGBB` times `intensity`, linear.
fn times(hex: u32, intensity: f32) -> Color {
    scaled(linear_color(hex), intensity.into()).into()
}

/// three.js's `1 / max(d^decay, 0.01)` (with `distance` 0) as a decay and a factor on the
/// color: `min(1, 1 / (100·d^decay)) · 100`.
fn fall_off(object: &'static str, distance: f32, decay: f32) -> Result<(Decay, f32), ThreeError> {
    if distance != 0.0 {
        return Err(ThreeError::Unsupported {
            object,
            field: "distance",
            value: distance,
            reason: "three.js fades the light out toward `distance` by (1 − (d/distance)⁴)², \
                     which no Phong light does; 0 (the default) converts",
        });
    }
    let decay = match decay {
        0.0 => return Ok((Decay::NONE, 1.0)),
        1.0 => Decay::new(0.0, 100.0, 0.0),
        2.0 => Decay::new(0.0, 0.0, 100.0),
        other => {
            return Err(ThreeError::Unsupported {
                object,
                field: "decay",
                value: other,
                reason: "a Phong light's fall-off is a polynomial of the distance: \
                         0, 1 and 2 (the default) convert",
            });
        }
    };
    Ok((decay, 100.0))
}

/// The transform of a three.js directional or spot light at `position` shining toward
/// `target` (its `target.position`), or of a camera at `position` after
/// `lookAt(target)`: its -Z axis toward the target, +Y up where it can be (looking straight
/// down or up, +Z or -Z up, as three.js's `lookAt` turns then).
pub fn aimed_transform(position: Vec3, target: Vec3) -> Transform {
    let forward = target - position;
    let up = if forward.cross(Vec3::Y).length_squared() > 0.0 {
        Vec3::Y
    } else {
        Vec3::Z * forward.y.signum()
    };
    Transform::from_translation(position).looking_at(target, up)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// three.js's `1 / max(d², 0.01)` and the converted `min(1, 1 / (100 d²)) · 100` agree
    /// on both sides of `d = 0.1`, where three.js's cap starts.
    #[test]
    fn an_inverse_square_point_light_falls_off_as_three_js() {
        let light = ThreeLight::PointLight {
            color: 0xffffff,
            intensity: 3.0,
            distance: 0.0,
            decay: 2.0,
        };
        let ThreeLightOf::Point(point) = light.to_phong().unwrap() else {
            panic!("a point light");
        };
        let color = f64::from(point.color.to_linear().red);
        for d in [0.01_f64, 0.1, 0.5, 1.0, 7.0] {
            let converted = color
                * crate::reference::attenuation(d, point.decay.to_array().map(f64::from), None);
            let three = 3.0 / (d * d).max(0.01);
            assert!(
                (converted - three).abs() < 1e-6 * three,
                "d {d}: {converted} against {three}"
            );
        }
    }

    #[test]
    fn what_three_js_fades_by_distance_or_by_another_power_is_an_error() {
        let light = |distance, decay| ThreeLight::PointLight {
            color: 0xffffff,
            intensity: 1.0,
            distance,
            decay,
        };
        let field = |error| match error {
            Err(ThreeError::Unsupported { field, .. }) => field,
            Ok(_) => "none",
        };
        assert_eq!(field(light(5.0, 2.0).to_phong()), "distance");
        assert_eq!(field(light(0.0, 1.5).to_phong()), "decay");
        assert!(light(0.0, 1.0).to_phong().is_ok());
    }

    #[test]
    fn a_spot_light_fades_over_its_penumbra_along_a_smoothstep() {
        let light = ThreeLight::SpotLight {
            color: 0xffffff,
            intensity: 1.0,
            distance: 0.0,
            decay: 2.0,
            angle: 0.5,
            penumbra: 0.4,
        };
        let ThreeLightOf::Spot(spot) = light.to_phong().unwrap() else {
            panic!("a spot light");
        };
        assert_eq!(spot.outer_angle, 0.5);
        assert!(
            (spot.inner_angle - 0.3).abs() < 1e-7,
            "{}",
            spot.inner_angle
        );
        assert_eq!(spot.cone_edge, ConeEdge::Smooth);
    }
}
