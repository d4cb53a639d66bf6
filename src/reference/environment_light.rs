//! The camera's environment map light in the reference model (SPEC.md, "Environment
//! light"): Bevy's `EnvironmentMapLight` lighting a Phong surface as it lights a
//! `StandardMaterial`. The cubes' texels are the caller's: [`environment_light_direction`]
//! and [`environment_light_level`] say where the specular cube is read, the normal (turned
//! by [`cube_direction`](super::cube_direction)) where the diffuse cube is.

use super::{Material, SurfacePoint, normalize_or_zero};
use glam::DVec3;

/// The direction a lobe of perceptual roughness `r` reads the specular cube along, as Bevy
/// reads it (Frostbite's dominant direction): `mix(N, R, s · (√s + r²))` with the reflected
/// view ray `R` and `s = 1 − r²`; not normalized (a cube lookup needs none).
pub fn environment_light_direction(
    normal: DVec3,
    reflected: DVec3,
    perceptual_roughness: f64,
) -> DVec3 {
    let roughness = perceptual_roughness * perceptual_roughness;
    let smoothness = (1.0 - roughness).clamp(0.0, 1.0);
    normal.lerp(reflected, smoothness * (smoothness.sqrt() + roughness))
}

/// The specular cube's mip level for perceptual roughness `r`: `r · (levels − 1)`, with
/// `levels` the cube's mip levels (Bevy's split-sum lookup).
pub fn environment_light_level(perceptual_roughness: f64, levels: u32) -> f64 {
    perceptual_roughness * f64::from(levels.saturating_sub(1))
}

impl Material {
    /// What the environment light sends toward the viewer off `surface`, given the diffuse
    /// cube's texel along the normal (`irradiance`) and the specular cube's along
    /// [`environment_light_direction`] at [`environment_light_level`] (`radiance`), each
    /// times the light's intensity and the camera's exposure: `irradiance ⊙ k_d ⊙ max(1 − S,
    /// 0) + radiance ⊙ S`, with `S` the [ambient specular
    /// reflectance](Material::ambient_specular_reflectance). The shader adds it to the
    /// ambient term, before the ambient occlusion.
    pub fn environment_light(
        &self,
        surface: &SurfacePoint,
        irradiance: DVec3,
        radiance: DVec3,
    ) -> DVec3 {
        if normalize_or_zero(surface.normal) == DVec3::ZERO {
            return DVec3::ZERO;
        }
        let reflectance = self.ambient_specular_reflectance(surface);
        let diffuse = irradiance * self.diffuse * (DVec3::ONE - reflectance).max(DVec3::ZERO);
        diffuse + radiance * reflectance
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::AmbientSpecular;

    #[test]
    fn a_smooth_lobe_reads_along_the_reflection_and_a_rough_one_along_the_normal() {
        let (normal, reflected) = (DVec3::Y, DVec3::new(1.0, 1.0, 0.0).normalize());
        assert_eq!(
            environment_light_direction(normal, reflected, 0.0),
            reflected
        );
        assert_eq!(environment_light_direction(normal, reflected, 1.0), normal);
        // r = 0.5: r² = 0.25, s = 0.75, weight 0.75 · (√0.75 + 0.25), worked by hand.
        let weight = 0.75 * (0.75f64.sqrt() + 0.25);
        let half = environment_light_direction(normal, reflected, 0.5);
        assert!((half - normal.lerp(reflected, weight)).length() < 1e-15);
        assert_eq!(environment_light_level(0.6, 6), 3.0);
        assert_eq!(environment_light_level(1.0, 1), 0.0);
    }

    #[test]
    fn the_diffuse_cube_lights_what_the_specular_color_does_not_reflect() {
        let surface = SurfacePoint {
            position: DVec3::ZERO,
            normal: DVec3::Z,
            camera: DVec3::Z * 3.0,
        };
        let mut material = Material {
            specular: DVec3::splat(0.04),
            ..crate::reference::tests::matte(DVec3::new(0.5, 0.25, 1.0))
        };
        let (irradiance, radiance) = (DVec3::new(2.0, 1.0, 0.5), DVec3::new(0.0, 4.0, 8.0));
        // Without the ambient specular, the diffuse color takes all of the diffuse cube.
        let plain = material.environment_light(&surface, irradiance, radiance);
        assert_eq!(plain, irradiance * material.diffuse);
        material.ambient_specular = Some(AmbientSpecular {
            perceptual_roughness: 0.5,
        });
        let s = material.ambient_specular_reflectance(&surface);
        assert!(s.min_element() > 0.0);
        let lit = material.environment_light(&surface, irradiance, radiance);
        let expected = irradiance * material.diffuse * (1.0 - s) + radiance * s;
        assert!((lit - expected).length() < 1e-15, "{lit} {expected}");
        let degenerate = SurfacePoint {
            normal: DVec3::ZERO,
            ..surface
        };
        assert_eq!(
            material.environment_light(&degenerate, irradiance, radiance),
            DVec3::ZERO
        );
    }
}
