//! The directional light in the reference model: its [`Light`] (SPEC.md, "Light types").

use super::PhongDirectionalLight;
use crate::lights::light_direction;
use crate::reference::{Light, rgb};
use bevy::transform::components::GlobalTransform;

impl Light {
    /// The reference form of a directional light entity.
    pub fn directional(light: &PhongDirectionalLight, transform: &GlobalTransform) -> Self {
        Light::Directional {
            direction: light_direction(transform).as_dvec3(),
            color: rgb(light.color),
            specular: rgb(light.specular.unwrap_or(light.color)),
        }
    }
}
