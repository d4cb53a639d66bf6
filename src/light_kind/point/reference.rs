//! The point light in the reference model: its [`Light`] (SPEC.md, "Light types").

use super::PhongPointLight;
use crate::reference::{Light, rgb};
use bevy::transform::components::GlobalTransform;

impl Light {
    /// The reference form of a point light entity.
    pub fn point(light: &PhongPointLight, transform: &GlobalTransform) -> Self {
        Light::Point {
            position: transform.translation().as_dvec3(),
            color: rgb(light.color),
            specular: rgb(light.specular.unwrap_or(light.color)),
            decay: light.decay.to_array().map(f64::from),
            range: light.range.map(f64::from),
        }
    }
}
