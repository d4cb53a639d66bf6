//! The disk light as a kind of light ([`PhongLightKind`]): its record, its validation and its
//! reference light; what it shares with the rectangle is `gpu_area_light::area_light_kind`.

use super::PhongDiskLight;
use crate::light_kind::PhongLightKind;
use crate::light_kind::gpu_area_light::{GpuAreaLight, UnplacedShape, area_light_kind};
use crate::limits;
use crate::validation::Checker;

impl PhongDiskLight {
    /// The disk light in the reference model.
    #[cfg(feature = "reference")]
    const REFERENCE: fn(
        &Self,
        &bevy::transform::components::GlobalTransform,
    ) -> crate::reference::AreaLight = crate::reference::AreaLight::disk;

    /// The record at the identity transform: the radius along X and Y, the colors per unit
    /// area, range, decay and flags ([`GpuAreaLight::DISK`]).
    fn unplaced_record(&self) -> GpuAreaLight {
        let radius = limits::AREA_SIZE.apply(self.radius);
        GpuAreaLight::unplaced(
            UnplacedShape {
                half_extents: [radius, radius],
                area: std::f64::consts::PI * f64::from(radius).powi(2),
                flags: GpuAreaLight::DISK,
            },
            (self.color, self.specular),
            self.decay,
            (self.two_sided, self.highlight),
        )
    }
}

/// The disk light as a kind: its record (placed by its transform's translation and rotation;
/// scale ignored), reach (sharing ε with the point and spot lights) and bounds.
impl PhongLightKind for PhongDiskLight {
    // Written by `area_light_kind!` (gpu_area_light.rs), as for every area kind: `type Gpu =
    // GpuAreaLight`, `SHARES_EPSILON = true`, `to_gpu` (`unplaced_record` above, placed by
    // `place`: the transform's translation and rotation), `reach` and `set_reach`
    // (`GpuAreaLight::reach` of its `range`, into the record's `reach`), `bounding_sphere`
    // (around its shape),
    // `casts_shadows`, `shadow` and `set_shadow` (`GpuAreaLight::shadow_request`) and
    // `reference_light` (`Self::REFERENCE`).
    area_light_kind!();

    fn validate(&mut self, checker: &mut Checker) {
        checker.color("color", &mut self.color);
        checker.optional_color("specular", &mut self.specular);
        checker.scalar("radius", &mut self.radius, limits::AREA_SIZE);
        checker.decay(&mut self.decay);
        checker.range(&mut self.range);
        checker.shadows(&mut self.shadows);
    }
}
