//! What a camera's own components do to the lit color, in `f64`: Bevy's distance fog with
//! the Phong directional lights' inscattering, and Bevy's Reinhard tonemapping curve.

use super::{Light, Lights, normalize_or_zero, power};
use bevy::{
    color::{ColorToComponents, LinearRgba},
    pbr::{DistanceFog, FogFalloff},
};
use glam::DVec3;

/// `color` at the point `from_camera` away from the camera (the vector from the camera to
/// it), seen through `fog`: Bevy's fog formulas (`bevy_pbr::fog`) on its length, with the
/// inscattering of [`directional_scattering`] along its direction.
pub fn fogged(color: DVec3, from_camera: DVec3, fog: &DistanceFog, lights: &Lights) -> DVec3 {
    let distance = from_camera.length();
    let fog_color = LinearRgba::from(fog.color).to_vec4().as_dvec4();
    let sun = LinearRgba::from(fog.directional_light_color)
        .to_vec4()
        .as_dvec4();
    let mut scattered = fog_color.truncate();
    if sun.w > 0.0 {
        let scattering =
            directional_scattering(from_camera, lights, fog.directional_light_exponent.into());
        scattered += scattering * sun.truncate() * sun.w;
    }
    let blend = |amount: f64| color.lerp(scattered, amount * fog_color.w);
    match fog.falloff {
        FogFalloff::Linear { start, end } => {
            let (start, end) = (f64::from(start), f64::from(end));
            blend(1.0 - ((end - distance) / (end - start)).clamp(0.0, 1.0))
        }
        FogFalloff::Exponential { density } => blend(1.0 - (-distance * f64::from(density)).exp()),
        FogFalloff::ExponentialSquared { density } => {
            blend(1.0 - (-(distance * f64::from(density)).powi(2)).exp())
        }
        FogFalloff::Atmospheric {
            extinction,
            inscattering,
        } => {
            let factor =
                |coefficients: glam::Vec3| DVec3::ONE - (-distance * coefficients.as_dvec3()).exp();
            color * (DVec3::ONE - factor(extinction) * fog_color.w)
                + scattered * factor(inscattering) * fog_color.w
        }
    }
}

/// Σ over the directional lights of `color · max(direction · L, 0)^exponent`, with `L` the
/// unit vector toward the light: the light a fog scatters toward a camera looking along
/// `direction`.
pub fn directional_scattering(direction: DVec3, lights: &Lights, exponent: f64) -> DVec3 {
    let direction = normalize_or_zero(direction);
    lights
        .lights
        .iter()
        .filter_map(|light| match light {
            Light::Directional {
                direction: travel,
                color,
                ..
            } => Some(
                *color
                    * power(
                        direction.dot(-normalize_or_zero(*travel)).max(0.0),
                        exponent,
                    ),
            ),
            _ => None,
        })
        .sum()
}

/// Bevy's `Tonemapping::Reinhard`: `c / (1 + c)` per channel (negative channels are
/// first raised to 0, as Bevy's `tone_mapping` does).
pub fn reinhard(color: DVec3) -> DVec3 {
    let color = color.max(DVec3::ZERO);
    color / (DVec3::ONE + color)
}
