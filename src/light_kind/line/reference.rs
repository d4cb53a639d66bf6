//! The line light in the reference model: the light of the segment's nearest point to the
//! surface, a point light there cut off at the range (a stub's model, not an area light's).

use super::kind::GpuLine;
use crate::reference::{
    Material, ReferenceLight, SurfacePoint, attenuation, normalize_or_zero, phong_light,
};
use glam::DVec3;

impl ReferenceLight for GpuLine {
    fn term(&self, surface: &SurfacePoint, material: &Material) -> DVec3 {
        let (start, end) = (
            DVec3::from(self.start.map(f64::from)),
            DVec3::from(self.end.map(f64::from)),
        );
        let along = end - start;
        let t = if along.length_squared() > 0.0 {
            ((surface.position - start).dot(along) / along.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let offset = start + t * along - surface.position;
        let fall_off = attenuation(offset.length(), [1.0, 0.0, 0.0], Some(self.range.into()));
        let color = DVec3::from(self.color.map(f64::from));
        fall_off * phong_light(surface, material, normalize_or_zero(offset), color, color)
    }
}
