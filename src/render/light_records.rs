//! From light components and their transforms to [`GpuLight`] records.

use super::gpu_types::GpuLight;
use crate::culling::influence_radius;
use crate::direction::normalize_or_zero;
use crate::lights::{
    PhongAmbientLight, PhongDirectionalLight, PhongHemisphereLight, PhongPointLight,
    PhongSpotLight, light_direction,
};
use bevy::{
    color::Color,
    ecs::component::Component,
    math::{DVec3, Vec3},
    transform::components::GlobalTransform,
};

/// A color's linear RGB components (alpha dropped).
pub fn linear_rgb(color: Color) -> [f32; 3] {
    let linear = color.to_linear();
    [linear.red, linear.green, linear.blue]
}

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

/// `range`, with `None` stored as `f32::MAX` (never reached).
fn stored_range(range: Option<f32>) -> f32 {
    range.unwrap_or(f32::MAX)
}

/// Shortens a point or spot light's `range` to its influence radius for `epsilon` (see
/// [`crate::culling`]), from its largest color or specular channel; returns `false` when the
/// light reaches nowhere, so that it can be left out.
pub fn limit_reach(light: &mut GpuLight, epsilon: f32) -> bool {
    let intensity = light
        .color
        .into_iter()
        .chain(light.specular)
        .fold(0.0, f32::max);
    light.range = light
        .range
        .min(influence_radius(light.decay, intensity, epsilon));
    light.range > 0.0
}

/// The diffuse and specular intensities of a light whose specular color may default.
fn intensities(color: Color, specular: Option<Color>) -> ([f32; 3], [f32; 3]) {
    (linear_rgb(color), linear_rgb(specular.unwrap_or(color)))
}

/// `(1 - cos(outer), cone_scale)` of a spot cone, computed in `f64` and rounded once:
/// `cone_scale = 1 / (cos(inner) - cos(outer))`, or `0` (a hard edge at the outer angle)
/// where the inner cone is not narrower. A cone whose outer angle is not positive is empty:
/// its `1 - cos(outer)` is stored as `-1`, which no `1 - cos θ` reaches. Angles are first
/// brought into `[0, π]` ([`crate::limits::SPOT_ANGLE`]).
pub fn spot_cone_terms(inner_angle: f32, outer_angle: f32) -> (f32, f32) {
    let inner_angle = crate::limits::SPOT_ANGLE.apply(inner_angle);
    let outer_angle = crate::limits::SPOT_ANGLE.apply(outer_angle);
    if outer_angle <= 0.0 {
        return (-1.0, 0.0);
    }
    let (inner, outer) = (f64::from(inner_angle), f64::from(outer_angle));
    // 1 - cos x = 2 sin²(x/2) and cos i - cos o = 2 sin((o+i)/2) sin((o-i)/2): no
    // cancellation for small or close angles.
    let outer_versine = 2.0 * (outer / 2.0).sin().powi(2);
    let width = 2.0 * ((outer + inner) / 2.0).sin() * ((outer - inner) / 2.0).sin();
    // Beyond f32's range (or for no width at all) the edge is hard.
    let cone_scale = (1.0 / width) as f32;
    let cone_scale = if width > 0.0 && cone_scale.is_finite() {
        cone_scale
    } else {
        0.0
    };
    (outer_versine as f32, cone_scale)
}

/// A built-in light kind, its record in two parts: the constants, which depend on the
/// component alone (colors, decay, range, cone), and the placement, which its transform sets
/// (position, direction). A gather reuses the constants of a light whose component is equal
/// to the one they were made from (see `record_cache`).
pub(crate) trait BuiltInLight: Component + Clone + PartialEq {
    /// The record without its placement (position and direction zero) or shadow slot.
    fn constants(&self) -> GpuLight;

    /// Sets the position and direction of `record` from `transform`.
    fn place(record: &mut GpuLight, transform: &GlobalTransform);
}

impl BuiltInLight for PhongDirectionalLight {
    fn constants(&self) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        GpuLight {
            color,
            specular,
            ..GpuLight::default()
        }
    }

    fn place(record: &mut GpuLight, transform: &GlobalTransform) {
        record.direction = light_direction(transform).to_array();
    }
}

impl BuiltInLight for PhongPointLight {
    fn constants(&self) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        GpuLight {
            range: stored_range(self.range),
            color,
            specular,
            decay: self.decay.to_array(),
            ..GpuLight::default()
        }
    }

    fn place(record: &mut GpuLight, transform: &GlobalTransform) {
        record.position = transform.translation().to_array();
    }
}

impl BuiltInLight for PhongSpotLight {
    fn constants(&self) -> GpuLight {
        let (color, specular) = intensities(self.color, self.specular);
        let (outer_versine, cone_scale) = spot_cone_terms(self.inner_angle, self.outer_angle);
        GpuLight {
            range: stored_range(self.range),
            outer_versine,
            color,
            cone_scale,
            specular,
            spot_exponent: self.exponent,
            decay: self.decay.to_array(),
            ..GpuLight::default()
        }
    }

    fn place(record: &mut GpuLight, transform: &GlobalTransform) {
        record.position = transform.translation().to_array();
        record.direction = light_direction(transform).to_array();
    }
}
