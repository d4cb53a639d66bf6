//! The line light as a kind of light: its record, reach, bounds and validation.

use super::LineLight;
use crate::light_kind::{PhongLightKind, linear_rgb};
use crate::validation::Checker;
use bevy::{math::Vec3, shape::BoundingSphere, transform::components::GlobalTransform};
use bytemuck::{Pod, Zeroable};

/// The record of a line light: its two ends, its range and its color (48 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuLine {
    pub start: [f32; 3],
    pub range: f32,
    pub end: [f32; 3],
    pub padding: f32,
    pub color: [f32; 3],
    pub padding2: f32,
}

impl PhongLightKind for LineLight {
    type Gpu = GpuLine;

    fn to_gpu(&self, transform: &GlobalTransform) -> GpuLine {
        let half = transform.right() * (0.5 * self.length);
        let center = transform.translation();
        GpuLine {
            start: (center - half).to_array(),
            range: self.range,
            end: (center + half).to_array(),
            padding: 0.0,
            color: linear_rgb(self.color),
            padding2: 0.0,
        }
    }

    fn reach(&self, _record: &GpuLine, _epsilon: f32) -> f32 {
        self.range
    }

    fn bounding_sphere(record: &GpuLine, reach: f32) -> Option<BoundingSphere> {
        let (start, end) = (Vec3::from(record.start), Vec3::from(record.end));
        Some(BoundingSphere::new(
            (start + end) / 2.0,
            start.distance(end) / 2.0 + reach,
        ))
    }

    fn validate(&mut self, checker: &mut Checker) {
        checker.color("color", &mut self.color);
        checker.number("length", &mut self.length, 0.0..=1e6, 0.0);
        checker.number("range", &mut self.range, f32::MIN_POSITIVE..=1e6, 1.0);
    }

    #[cfg(feature = "reference")]
    fn reference_light(
        &self,
        transform: &GlobalTransform,
    ) -> Option<std::sync::Arc<dyn crate::reference::ReferenceLight>> {
        Some(std::sync::Arc::new(self.to_gpu(transform)))
    }
}
