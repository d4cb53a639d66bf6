//! The rectangle light in the reference model: its [`AreaLight`] (SPEC.md, "Area lights").

use super::PhongRectLight;
use crate::limits;
use crate::reference::{AreaLight, AreaShape};
use bevy::transform::components::GlobalTransform;

impl AreaLight {
    /// The reference form of a rectangle light entity, placed by its transform's
    /// translation and rotation (scale ignored, as its record's), its size brought into
    /// range as its record's is (`crate::limits::AREA_SIZE`).
    pub fn rect(light: &PhongRectLight, transform: &GlobalTransform) -> Self {
        let shape = AreaShape::Rect {
            width: limits::AREA_SIZE.apply(light.width).into(),
            height: limits::AREA_SIZE.apply(light.height).into(),
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
