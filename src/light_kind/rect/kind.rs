//! The rectangle light as a kind of light ([`PhongLightKind`]): its record, reach, bounds
//! and validation.

use super::PhongRectLight;
use crate::light_kind::PhongLightKind;
use crate::light_kind::built_in::{intensities, stored_range};
use crate::light_kind::gpu_area_light::GpuAreaLight;
use crate::lights::AreaHighlight;
use crate::limits;
use crate::validation::Checker;
use bevy::{math::Vec3, shape::BoundingSphere, transform::components::GlobalTransform};

impl PhongRectLight {
    /// The record at the identity transform: the half extents along X and Y, the colors per
    /// unit area (computed in `f64`; zero for a panel without area), range, decay and flags.
    fn constants(&self) -> GpuAreaLight {
        let (width, height) = (
            limits::AREA_SIZE.apply(self.width),
            limits::AREA_SIZE.apply(self.height),
        );
        let (color, specular) = intensities(self.color, self.specular);
        let area = f64::from(width) * f64::from(height);
        let per_area = |channels: [f32; 3]| {
            channels.map(|channel| {
                if area > 0.0 {
                    (f64::from(channel) / area).min(f64::from(f32::MAX)) as f32
                } else {
                    0.0
                }
            })
        };
        let mut flags = 0;
        if self.two_sided {
            flags |= GpuAreaLight::TWO_SIDED;
        }
        if self.highlight == AreaHighlight::RepresentativePoint {
            flags |= GpuAreaLight::REPRESENTATIVE_POINT;
        }
        GpuAreaLight {
            center: [0.0; 3],
            range: stored_range(self.range),
            half_width: [0.5 * width, 0.0, 0.0],
            half_height: [0.0, 0.5 * height, 0.0],
            color: per_area(color),
            specular: per_area(specular),
            decay: self.decay.to_array(),
            flags,
        }
    }
}

/// The rectangle light as a kind: its record (placed by its transform's translation and
/// rotation; scale ignored), reach (sharing ε with the point and spot lights) and bounds.
impl PhongLightKind for PhongRectLight {
    type Gpu = GpuAreaLight;
    const SHARES_EPSILON: bool = true;

    fn to_gpu(&self, transform: &GlobalTransform) -> GpuAreaLight {
        let mut record = self.constants();
        Self::place(&mut record, transform);
        record
    }

    /// Moves a record made at the identity transform (its half extents along X and Y).
    fn place(record: &mut GpuAreaLight, transform: &GlobalTransform) -> bool {
        let (_, rotation, translation) = transform.to_scale_rotation_translation();
        record.center = translation.to_array();
        record.half_width = (rotation * Vec3::from(record.half_width)).to_array();
        record.half_height = (rotation * Vec3::from(record.half_height)).to_array();
        true
    }

    fn reach(record: &GpuAreaLight, epsilon: f32) -> f32 {
        record.reach(epsilon)
    }

    fn set_reach(record: &mut GpuAreaLight, reach: f32) {
        record.range = reach.min(f32::MAX);
    }

    fn bounding_sphere(record: &GpuAreaLight, reach: f32) -> Option<BoundingSphere> {
        record.bounding_sphere(reach)
    }

    fn validate(&mut self, checker: &mut Checker) {
        checker.color("color", &mut self.color);
        checker.optional_color("specular", &mut self.specular);
        checker.scalar("width", &mut self.width, limits::AREA_SIZE);
        checker.scalar("height", &mut self.height, limits::AREA_SIZE);
        checker.decay(&mut self.decay);
        checker.range(&mut self.range);
    }

    fn casts_shadows(&self) -> bool {
        false
    }

    #[cfg(feature = "reference")]
    fn reference_light(
        &self,
        transform: &GlobalTransform,
    ) -> Option<std::sync::Arc<dyn crate::reference::ReferenceLight>> {
        Some(std::sync::Arc::new(crate::reference::AreaLight::rect(
            self, transform,
        )))
    }
}
