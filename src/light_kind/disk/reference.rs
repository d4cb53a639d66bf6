//! The disk light in the reference model: its [`AreaLight`] (SPEC.md, "Area lights").

use super::PhongDiskLight;
use crate::limits;
use crate::reference::{AreaLight, AreaShape};
use bevy::transform::components::GlobalTransform;

impl AreaLight {
    /// The reference form of a disk light entity, placed by its transform's translation and
    /// rotation (scale ignored, as its record's), its radius brought into range as its
    /// record's is (`crate::limits::AREA_SIZE`). The quadrature integrates the disk itself,
    /// not the shader's polygon.
    pub fn disk(light: &PhongDiskLight, transform: &GlobalTransform) -> Self {
        let shape = AreaShape::Disk {
            radius: limits::AREA_SIZE.apply(light.radius).into(),
        };
        AreaLight::placed(
            transform,
            shape,
            light.two_sided,
            (light.color, light.specular),
            light.decay,
            light.range,
        )
    }
}
