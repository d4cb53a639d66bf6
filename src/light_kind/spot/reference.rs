//! The spot light in the reference model: its [`Light`] (SPEC.md, "Light types").

use super::PhongSpotLight;
use crate::lights::light_direction;
use crate::limits;
use crate::reference::{Light, rgb};
use bevy::transform::components::GlobalTransform;

impl Light {
    /// The reference form of a spot light entity, its angles brought into `[0, π]` as its
    /// light record's are (`crate::limits::CONE_ANGLE`).
    pub fn spot(light: &PhongSpotLight, transform: &GlobalTransform) -> Self {
        Light::Spot {
            position: transform.translation().as_dvec3(),
            direction: light_direction(transform).as_dvec3(),
            color: rgb(light.color),
            specular: rgb(light.specular.unwrap_or(light.color)),
            decay: light.decay.to_array().map(f64::from),
            range: light.range.map(f64::from),
            inner_angle: limits::CONE_ANGLE.apply(light.inner_angle).into(),
            outer_angle: limits::CONE_ANGLE.apply(light.outer_angle).into(),
            exponent: light.exponent.into(),
            edge: light.cone_edge,
        }
    }
}
