//! The light header's indirect terms, from the ambient and hemisphere lights. The lights'
//! records come from their kinds ([`crate::light_kind`]).

use crate::direction::normalize_or_zero;
use crate::light_kind::linear_rgb;
use crate::lights::{PhongAmbientLight, PhongHemisphereLight};
use bevy::{
    color::Color,
    math::{DVec3, Vec3},
};

/// The light header's indirect terms, `[ambient, hemisphere_up, hemisphere_half_difference]`:
/// the ambient color plus the mean of the hemisphere light's sky and ground colors, the
/// hemisphere's unit up direction (`+Y` for one without a direction), and half its sky
/// minus its ground color, each computed in `f64` and rounded once. Without a hemisphere
/// light, the ambient color and two zero vectors.
pub fn indirect_light(
    ambient: &PhongAmbientLight,
    hemisphere: Option<&PhongHemisphereLight>,
) -> [[f32; 3]; 3] {
    let rgb = |color: Color| DVec3::from(linear_rgb(color).map(f64::from));
    let flat = rgb(ambient.color);
    let Some(hemisphere) = hemisphere else {
        return [flat.as_vec3().to_array(), [0.0; 3], [0.0; 3]];
    };
    let (sky, ground) = (rgb(hemisphere.sky_color), rgb(hemisphere.ground_color));
    let up = match normalize_or_zero(hemisphere.up) {
        Vec3::ZERO => Vec3::Y,
        up => up,
    };
    [
        (flat + (sky + ground) / 2.0).as_vec3().to_array(),
        up.to_array(),
        ((sky - ground) / 2.0).as_vec3().to_array(),
    ]
}
