//! The rectangle light as a kind of light ([`PhongLightKind`]): its record, its validation and
//! its reference light; what it shares with the disk is `gpu_area_light::area_light_kind`.

use super::PhongRectLight;
use crate::light_kind::PhongLightKind;
use crate::light_kind::gpu_area_light::{GpuAreaLight, UnplacedShape, area_light_kind};
use crate::limits;
use crate::validation::Checker;

impl PhongRectLight {
    /// The rectangle light in the reference model.
    #[cfg(feature = "reference")]
    const REFERENCE: fn(
        &Self,
        &bevy::transform::components::GlobalTransform,
    ) -> crate::reference::AreaLight = crate::reference::AreaLight::rect;

    /// The record at the identity transform: the half extents along X and Y, the colors per
    /// unit area, range, decay and flags.
    fn unplaced_record(&self) -> GpuAreaLight {
        let (width, height) = (
            limits::AREA_SIZE.apply(self.width),
            limits::AREA_SIZE.apply(self.height),
        );
        GpuAreaLight::unplaced(
            UnplacedShape {
                half_extents: [0.5 * width, 0.5 * height],
                area: f64::from(width) * f64::from(height),
                flags: 0,
            },
            (self.color, self.specular),
            self.decay,
            (self.two_sided, self.highlight),
        )
    }
}

/// The rectangle light as a kind: its record (placed by its transform's translation and
/// rotation; scale ignored), reach (sharing ε with the point and spot lights) and bounds.
impl PhongLightKind for PhongRectLight {
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
        checker.scalar("width", &mut self.width, limits::AREA_SIZE);
        checker.scalar("height", &mut self.height, limits::AREA_SIZE);
        checker.decay(&mut self.decay);
        checker.range(&mut self.range);
        checker.shadows(&mut self.shadows);
    }
}
