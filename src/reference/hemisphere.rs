//! The hemisphere light in the reference model (SPEC.md, "Hemisphere light").

use super::{normalize_or_zero, rgb};
use crate::lights::PhongHemisphereLight;
use glam::DVec3;

/// A sky color above and a ground color below, blended by the normal's `up` component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hemisphere {
    /// The light from above, linear RGB.
    pub sky: DVec3,
    /// The light from below, linear RGB.
    pub ground: DVec3,
    /// The direction of the sky (any length; normalized here, `+Y` without a direction).
    pub up: DVec3,
}

impl Hemisphere {
    /// The light a surface with `normal` (any length) receives:
    /// `ground + (sky − ground) · (1 + N·up) / 2`; the mean of the two for a normal without a
    /// direction.
    pub fn irradiance(&self, normal: DVec3) -> DVec3 {
        let up = match normalize_or_zero(self.up) {
            DVec3::ZERO => DVec3::Y,
            up => up,
        };
        let weight = (1.0 + normalize_or_zero(normal).dot(up)) / 2.0;
        self.ground + (self.sky - self.ground) * weight
    }
}

impl From<&PhongHemisphereLight> for Hemisphere {
    fn from(light: &PhongHemisphereLight) -> Self {
        Self {
            sky: rgb(light.sky_color),
            ground: rgb(light.ground_color),
            up: light.up.as_dvec3(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sky_lights_what_faces_up_and_the_ground_what_faces_down() {
        let hemisphere = Hemisphere {
            sky: DVec3::new(0.4, 0.6, 1.0),
            ground: DVec3::new(0.2, 0.1, 0.0),
            up: DVec3::new(0.0, 0.0, 2.0),
        };
        assert_eq!(hemisphere.irradiance(DVec3::Z), hemisphere.sky);
        assert_eq!(hemisphere.irradiance(-DVec3::Z * 3.0), hemisphere.ground);
        let mean = (hemisphere.sky + hemisphere.ground) / 2.0;
        assert!((hemisphere.irradiance(DVec3::X) - mean).abs().max_element() < 1e-15);
        assert_eq!(hemisphere.irradiance(DVec3::ZERO), mean);
    }
}
