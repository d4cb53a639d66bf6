//! The rectangle light in the reference model: its [`AreaLight`] (SPEC.md, "Area lights").

use super::PhongRectLight;
use crate::limits;
use crate::reference::{AreaLight, AreaShape, rgb};
use bevy::transform::components::GlobalTransform;

impl AreaLight {
    /// The reference form of a rectangle light entity, placed by its transform's
    /// translation and rotation (scale ignored, as its record's), its size brought into
    /// range as its record's is (`crate::limits::AREA_SIZE`).
    pub fn rect(light: &PhongRectLight, transform: &GlobalTransform) -> Self {
        let (_, rotation, translation) = transform.to_scale_rotation_translation();
        let rotation = rotation.as_dquat();
        AreaLight {
            position: translation.as_dvec3(),
            right: rotation * glam::DVec3::X,
            up: rotation * glam::DVec3::Y,
            shape: AreaShape::Rect {
                width: limits::AREA_SIZE.apply(light.width).into(),
                height: limits::AREA_SIZE.apply(light.height).into(),
            },
            two_sided: light.two_sided,
            color: rgb(light.color),
            specular: rgb(light.specular.unwrap_or(light.color)),
            decay: light.decay.to_array().map(f64::from),
            range: light.range.map(f64::from),
        }
    }
}
