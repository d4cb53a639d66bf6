//! The baked maps' terms (SPEC.md, "Baked light").

use super::*;
use crate::material::SpecularModel;
use glam::DVec3;

#[test]
fn the_light_map_adds_to_the_ambient_light_and_the_ao_map_scales_both() {
    let material = Material {
        toon_ramp: None,
        diffuse: DVec3::new(0.5, 0.25, 1.0),
        ambient_factor: 2.0,
        specular: DVec3::ONE,
        specular_strength: 1.0,
        shininess: 32.0,
        specular_model: SpecularModel::Phong,
        emissive: DVec3::splat(0.125),
        diffuse_mode: crate::DiffuseMode::Lambert,
        specular_mode: crate::SpecularMode::Smooth,
        rim: crate::reference::Rim::NONE,
        metallic_roughness: None,
        ambient_specular: None,
    };
    let lights = Lights {
        hemisphere: None,
        ambient: DVec3::splat(0.25),
        lights: Vec::new(),
        others: Default::default(),
    };
    let surface = SurfacePoint {
        position: DVec3::ZERO,
        normal: DVec3::Y,
        camera: DVec3::new(0.0, 1.0, 1.0),
    };
    let texels = Texels {
        light_map: Some(DVec3::new(0.5, 1.0, 0.0)),
        ao_map: Some(0.5),
        ..Texels::default()
    };
    // Intensity 2: (0.5, 1, 0) · 2; AO at half intensity: 1 + 0.5 · (0.5 − 1) = 0.75.
    let baked = BakedLight::from_texels(&texels, 2.0, 0.5);
    assert_eq!(baked.light_map, DVec3::new(1.0, 2.0, 0.0));
    assert_eq!(baked.occlusion, 0.75);
    // emissive + (ambient · k_a + light map) ⊙ k_d · occlusion.
    let indirect = DVec3::new(0.5 + 1.0, 0.5 + 2.0, 0.5) * material.diffuse * 0.75;
    assert_eq!(
        shade_baked(&surface, &material, &lights, &baked),
        material.emissive + indirect
    );
    assert_eq!(
        shade_baked(&surface, &material, &lights, &BakedLight::NONE),
        shade(&surface, &material, &lights)
    );
}
