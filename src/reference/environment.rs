//! A material's environment map in the reference model (SPEC.md, "Environment map").

use super::SurfacePoint;
use crate::material::EnvironmentCombine;
use core::f64::consts::FRAC_PI_2;
use glam::{DQuat, DVec3};

/// The mip level a cube of `size` texels a side is read at for the highlight exponent
/// `shininess`: `max(log2(size / ((π/2) · sqrt(α + 1))), 0)`, where a texel spans about
/// the lobe of `cos^α`.
pub fn environment_lod(shininess: f64, size: f64) -> f64 {
    (size / (FRAC_PI_2 * (shininess + 1.0).sqrt()))
        .log2()
        .max(0.0)
}

/// The direction the environment is looked up along at `surface` (its normal taken
/// normalized): the ray from the camera reflected about the normal or, with
/// `refraction_ratio`, refracted (zero past the critical angle, as WGSL's `refract`).
pub fn environment_direction(surface: &SurfacePoint, refraction_ratio: Option<f64>) -> DVec3 {
    let normal = surface.normal.normalize_or_zero();
    let incident = (surface.position - surface.camera).normalize_or_zero();
    let cosine = normal.dot(incident);
    match refraction_ratio {
        None => incident - 2.0 * cosine * normal,
        Some(eta) => {
            let k = 1.0 - eta * eta * (1.0 - cosine * cosine);
            if k < 0.0 {
                DVec3::ZERO
            } else {
                eta * incident - (eta * cosine + k.sqrt()) * normal
            }
        }
    }
}

/// The direction a cube is read along for the world direction `direction`, in Bevy's cube
/// frame: turned by the inverse of the cube's `rotation`, then `z` negated (Bevy's cubes are
/// left-handed), as Bevy's `Skybox` and `EnvironmentMapLight` read theirs. A material's own
/// `environment_map` (no rotation) and the camera's `EnvironmentMapLight` (its `rotation`)
/// are both read so.
pub fn cube_direction(direction: DVec3, rotation: DQuat) -> DVec3 {
    let turned = rotation.inverse() * direction;
    DVec3::new(turned.x, turned.y, -turned.z)
}

/// `lit` with the `environment` color joined by `combine` with weight `strength` (the
/// reflectivity times the specular map's red).
pub fn with_environment(
    lit: DVec3,
    environment: DVec3,
    strength: f64,
    combine: EnvironmentCombine,
) -> DVec3 {
    match combine {
        EnvironmentCombine::Multiply => lit.lerp(lit * environment, strength),
        EnvironmentCombine::Mix => lit.lerp(environment, strength),
        EnvironmentCombine::Add => lit + environment * strength,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cube_is_read_turned_against_its_rotation_in_a_left_handed_frame() {
        let quarter_turn = DQuat::from_rotation_y(FRAC_PI_2);
        // The light turned a quarter about +Y: what was seen along +X is now along -Z.
        let direction = cube_direction(-DVec3::Z, quarter_turn);
        assert!((direction - DVec3::X).length() < 1e-12, "{direction}");
        assert_eq!(cube_direction(DVec3::Z, DQuat::IDENTITY), -DVec3::Z);
    }

    #[test]
    fn a_lobe_as_wide_as_a_texel_of_level_one_reads_level_one() {
        // 8 texels a side: level 1's texel spans (π/2) · 2 / 8 = π/8; the lobe 1/sqrt(α+1).
        let shininess = (8.0 / (2.0 * FRAC_PI_2)).powi(2) - 1.0;
        assert!((environment_lod(shininess, 8.0) - 1.0).abs() < 1e-12);
        assert_eq!(environment_lod(1e6, 8.0), 0.0, "a mirror reads level 0");
    }

    #[test]
    fn the_view_ray_is_reflected_or_refracted() {
        let surface = SurfacePoint {
            position: DVec3::ZERO,
            normal: DVec3::Y * 3.0,
            camera: DVec3::new(-1.0, 1.0, 0.0),
        };
        let reflected = environment_direction(&surface, None);
        assert!((reflected - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-12);
        // Straight on, a ray goes straight through whatever the ratio.
        let head_on = SurfacePoint {
            camera: DVec3::Y,
            ..surface
        };
        let refracted = environment_direction(&head_on, Some(0.66));
        assert!((refracted - DVec3::NEG_Y).length() < 1e-12);
    }

    #[test]
    fn the_combine_modes_weight_the_environment() {
        let (lit, environment) = (DVec3::new(0.5, 1.0, 0.25), DVec3::new(0.5, 0.0, 2.0));
        let multiply = with_environment(lit, environment, 0.5, EnvironmentCombine::Multiply);
        assert_eq!(multiply, DVec3::new(0.375, 0.5, 0.375));
        let mix = with_environment(lit, environment, 0.5, EnvironmentCombine::Mix);
        assert_eq!(mix, DVec3::new(0.5, 0.5, 1.125));
        let add = with_environment(lit, environment, 0.5, EnvironmentCombine::Add);
        assert_eq!(add, DVec3::new(0.75, 1.0, 1.25));
    }
}
