//! [`phong_material_from_gltf`]: a glTF material (metallic/roughness) as a [`PhongMaterial`].

use crate::material::{
    ANISOTROPY, CLEARCOAT, MetallicRoughness, PhongMaterial, TRANSMISSION, Unmapped, VOLUME,
    bevy_dielectric_f0, metallic_roughness::emissive_color, warn_unmapped,
};
use bevy::gltf::GltfMaterial;

/// The [`PhongMaterial`] that stands for a glTF material, as `PhongGltfPlugin` builds it for
/// each material of a file (`Material{n}/phong`).
///
/// | glTF ([`GltfMaterial`]) | `PhongMaterial` |
/// |---|---|
/// | `base_color` (baseColorFactor), `base_color_texture`, `base_color_channel` | `base_color` = `base_color · (1 − metallic)` in linear RGB (alpha kept), `base_color_texture`, `base_color_channel` |
/// | `emissive` (emissiveFactor · `KHR_materials_emissive_strength`, as Bevy's loader gives it), `emissive_texture`, `emissive_channel` | `emissive`, `emissive_texture`, `emissive_channel` |
/// | `normal_map_texture` (+Y up, OpenGL's convention), `normal_map_channel` | `normal_map_texture`, `normal_map_channel`, `flip_normal_map_y: false` (`PhongGltfPlugin` then reads the file's `scale` as `normal_map_scale`) |
/// | `alpha_mode` OPAQUE / MASK(alphaCutoff) / BLEND | `alpha_mode` unchanged |
/// | `double_sided` (doubleSided) | `double_sided`: back faces drawn, their normal flipped |
/// | `uv_transform` (`KHR_texture_transform`, as Bevy's loader reads it) | `uv_transform`, which moves the maps on the first UV set |
/// | each texture's `texCoord` (the `*_channel` fields) | the map's `*_channel`; `PhongGltfPlugin` reads `KHR_texture_transform`'s `texCoord` from the file, which overrides it and which Bevy's loader drops |
/// | `unlit` (`KHR_materials_unlit`) | `unlit`, with `base_color` as it is (not darkened by `metallic`) |
/// | `occlusion_texture`, `occlusion_channel` (occlusionTexture and its texCoord) | `ao_map_texture`, `ao_map_channel`, `ao_map_intensity: 1` (`PhongGltfPlugin` then reads the file's `strength`, which `GltfMaterial` drops) |
/// | `metallic` m, `perceptual_roughness` r, `reflectance` ρ and `specular_tint` t (`KHR_materials_specular`, as Bevy's loader reads it) | `specular_model: NormalizedBlinnPhong`, `specular_color = k · (1 + k · (1/E − 1))` with `k = mix(F₀, base_color, m)`, Bevy's `F₀ = 0.16 · (ρ·t)²` (0.04 without the extension) and `E` a GGX lobe's single-scattering albedo at `r` (Bevy's compensation for multiple scattering), `shininess` n `= clamp(0.669/r⁴ + 1.42/r² − 1.59, 1, 10⁴)`, `specular_strength = π` |
/// | `metallic_roughness_texture` (metallicRoughnessTexture), `metallic_roughness_channel` | the same, with `metallic` and `perceptual_roughness` as its factors: the rules above applied per texel by the shader, `base_color` and `specular_color = F₀` kept as they are (`PhongGltfPlugin` reads the texture's `KHR_texture_transform` `texCoord`) |
/// | (Bevy's weights on the ambient light) | `ambient_factor = 0.4524` (Bevy's weight on the diffuse color), `ambient_specular: true` and `perceptual_roughness = r`: the ambient light reflected by `specular_color` as Bevy weighs it (SPEC.md, "Ambient specular") |
/// | (Bevy's `EnvironmentMapLight` on the camera) | `environment_light: true`: its diffuse cube lights the diffuse color, its specular cube is reflected by the same weights (SPEC.md, "Environment light") |
///
/// The exponent gives the Blinn-Phong lobe `cos^n(θ_h)` nearest Bevy's GGX lobe of roughness
/// `r` as a display shows them (SPEC.md, "Metallic-roughness map"); `r = 0` gives the
/// maximum, `10⁴`. The
/// normalized Blinn-Phong model is three.js's BRDF `F · (n + 2)/(8π) · cos^n(θ_h)` times
/// `N·L`, with Schlick's Fresnel; the crate's diffuse term `k_d · max(N·L, 0)` is the
/// Lambert BRDF `k_d/π` times π, so the strength π draws the BRDF in the same units. A glTF
/// highlight then reflects about `F₀` of the light whatever its roughness, as in PBR: a
/// rough one spreads it wide and dim, a smooth one gathers it into a bright point
/// (docs/switching.md measures it against Bevy's).
///
/// Invalid numbers are replaced, never propagated: a NaN `metallic` becomes 0 and a NaN
/// roughness 0.5 (`METALLIC`, `ROUGHNESS`; both are clamped to `[0, 1]`), and the
/// colors are brought into `limits` as the material's own validation does (NaN channels
/// become 0, alpha 1). The result never holds a NaN.
///
/// What has no counterpart is left out (see `unmapped_gltf_parts`): transmission,
/// volume, clearcoat and anisotropy. When `label` is `Some`, one warning naming it lists
/// them, each with what the surface becomes without it.
///
/// ```
/// use bevy::{color::Color, gltf::GltfMaterial};
/// use bevy_phong::gltf::phong_material_from_gltf;
///
/// let gold = GltfMaterial {
///     base_color: Color::linear_rgb(1.0, 0.8, 0.3),
///     metallic: 1.0,
///     perceptual_roughness: 0.5,
///     ..Default::default()
/// };
/// let phong = phong_material_from_gltf(&gold, None);
/// assert_eq!(phong.base_color, Color::linear_rgb(0.0, 0.0, 0.0)); // a metal has no diffuse
/// // Its color as specular, brightened where Bevy adds the light a rough lobe scatters
/// // more than once: never darker than the color.
/// let specular = phong.specular_color.to_linear();
/// assert!(specular.red >= 1.0 && specular.green >= 0.8 && specular.blue >= 0.3);
/// assert!((phong.shininess - 14.794).abs() < 1e-4); // 0.669·16 + 1.42·4 − 1.59
/// ```
pub fn phong_material_from_gltf(material: &GltfMaterial, label: Option<&str>) -> PhongMaterial {
    if let Some(label) = label {
        warn_unmapped(
            &format!("glTF material {label}"),
            &unmapped_gltf_parts(material),
        );
    }
    let numbers = MetallicRoughness {
        base_color: material.base_color,
        metallic: material.metallic,
        perceptual_roughness: material.perceptual_roughness,
        dielectric_f0: bevy_dielectric_f0(material.reflectance, material.specular_tint),
        unlit: material.unlit,
        map: material
            .metallic_roughness_texture
            .clone()
            .map(|texture| (texture, material.metallic_roughness_channel.clone())),
    };
    PhongMaterial {
        emissive: emissive_color(material.emissive),
        alpha_mode: material.alpha_mode,
        base_color_texture: material.base_color_texture.clone(),
        base_color_channel: material.base_color_channel.clone(),
        emissive_texture: material.emissive_texture.clone(),
        emissive_channel: material.emissive_channel.clone(),
        normal_map_texture: material.normal_map_texture.clone(),
        normal_map_channel: material.normal_map_channel.clone(),
        flip_normal_map_y: false,
        double_sided: material.double_sided,
        uv_transform: material.uv_transform,
        ao_map_texture: material.occlusion_texture.clone(),
        ao_map_channel: material.occlusion_channel.clone(),
        ..numbers.phong_material()
    }
}

/// The parts of a glTF material that [`phong_material_from_gltf`] does not map, by their
/// glTF names, with what the surface becomes without each (empty when it maps everything
/// the material has).
fn unmapped_gltf_parts(material: &GltfMaterial) -> Vec<Unmapped> {
    [
        (
            material.specular_transmission > 0.0,
            "KHR_materials_transmission",
            TRANSMISSION,
        ),
        (material.thickness > 0.0, "KHR_materials_volume", VOLUME),
        (
            material.clearcoat > 0.0,
            "KHR_materials_clearcoat",
            CLEARCOAT,
        ),
        (
            material.anisotropy_strength > 0.0,
            "KHR_materials_anisotropy",
            ANISOTROPY,
        ),
    ]
    .into_iter()
    .filter_map(|(set, name, becomes)| set.then_some(Unmapped { name, becomes }))
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The glTF names of the parts [`phong_material_from_gltf`] does not map.
    fn unmapped_gltf_features(material: &GltfMaterial) -> Vec<&'static str> {
        unmapped_gltf_parts(material)
            .iter()
            .map(|part| part.name)
            .collect()
    }
    use crate::material::metallic_roughness::tests::{assert_close, compensated, linear};
    use crate::{SpecularModel, limits, material::metallic_roughness::shininess_from_roughness};
    use bevy::{
        asset::Handle,
        color::{Color, ColorToComponents, LinearRgba},
        image::Image,
        mesh::UvChannel,
        prelude::AlphaMode,
    };

    #[test]
    fn a_dielectric_keeps_its_color_and_gets_four_percent_specular() {
        let material = GltfMaterial {
            base_color: Color::linear_rgba(0.8, 0.4, 0.2, 1.0),
            metallic: 0.0,
            perceptual_roughness: 1.0,
            ..Default::default()
        };
        let phong = phong_material_from_gltf(&material, None);
        assert_close(linear(phong.base_color), [0.8, 0.4, 0.2, 1.0], "base color");
        assert_close(
            linear(phong.specular_color),
            compensated([0.04, 0.04, 0.04, 1.0], 1.0),
            "F0",
        );
        assert_eq!(phong.specular_model, SpecularModel::NormalizedBlinnPhong);
        // r = 1: 2/1 − 2 = 0, clamped up to 1; the BRDF drawn times π.
        assert_eq!(phong.shininess, 1.0);
        assert_eq!(phong.specular_strength, core::f32::consts::PI);
        // Bevy's ambient weights: F_AB(1, ·).x on the diffuse color, and the specular color's
        // own at the roughness.
        assert_eq!(phong.ambient_factor, 0.4524);
        assert!(phong.ambient_specular);
        assert!(phong.environment_light);
        assert_eq!(phong.perceptual_roughness, 1.0);
    }

    #[test]
    fn a_metal_has_no_diffuse_and_its_color_as_specular() {
        let material = GltfMaterial {
            base_color: Color::linear_rgba(1.0, 0.8, 0.3, 0.5),
            metallic: 1.0,
            perceptual_roughness: 0.5,
            ..Default::default()
        };
        let phong = phong_material_from_gltf(&material, None);
        assert_close(linear(phong.base_color), [0.0, 0.0, 0.0, 0.5], "base color");
        assert_close(
            linear(phong.specular_color),
            compensated([1.0, 0.8, 0.3, 1.0], 0.5),
            "F0",
        );
        // 0.669 · 16 + 1.42 · 4 − 1.59.
        assert!(
            (phong.shininess - 14.794).abs() < 1e-4,
            "{}",
            phong.shininess
        );
    }

    #[test]
    fn half_metallic_mixes_diffuse_and_specular() {
        let material = GltfMaterial {
            base_color: Color::linear_rgb(0.5, 1.0, 0.0),
            metallic: 0.5,
            perceptual_roughness: 0.25,
            ..Default::default()
        };
        let phong = phong_material_from_gltf(&material, None);
        assert_close(
            linear(phong.base_color),
            [0.25, 0.5, 0.0, 1.0],
            "base color",
        );
        assert_close(
            linear(phong.specular_color),
            compensated([0.27, 0.52, 0.02, 1.0], 0.25),
            "mix(0.04, c, 0.5)",
        );
        // 0.669 / 0.25⁴ + 1.42 / 0.25² − 1.59 = 171.264 + 22.72 − 1.59 = 192.394.
        assert!(
            (phong.shininess - 192.394).abs() < 1e-3,
            "{}",
            phong.shininess
        );
    }

    #[test]
    fn roughness_zero_gives_the_largest_exponent_and_never_nan() {
        assert_eq!(shininess_from_roughness(0.0), 1e4);
        assert_eq!(shininess_from_roughness(-0.0), 1e4);
        assert_eq!(shininess_from_roughness(f32::MIN_POSITIVE), 1e4);
        assert_eq!(shininess_from_roughness(-1.0), 1e4, "clamped to 0");
        assert_eq!(shininess_from_roughness(f32::NEG_INFINITY), 1e4);
        assert_eq!(shininess_from_roughness(1.0), 1.0);
        assert_eq!(shininess_from_roughness(f32::INFINITY), 1.0, "clamped to 1");
        // 0.669 · 16 + 1.42 · 4 − 1.59 = 14.794.
        let half = shininess_from_roughness(f32::NAN);
        assert!((half - 14.794).abs() < 1e-4, "NaN taken as 0.5: {half}");
        // Just above the cap's threshold (r ≈ 0.09) the fit takes over.
        let r = 0.2_f32;
        let fitted = 0.669 / r.powi(4) + 1.42 / r.powi(2) - 1.59;
        assert!((shininess_from_roughness(r) - fitted).abs() < 1e-2);
        // Monotonic: smoother is sharper, over the whole range.
        let mut previous = f32::INFINITY;
        for i in 0..=1000 {
            let n = shininess_from_roughness(i as f32 / 1000.0);
            assert!(
                n.is_finite() && (1.0..=1e4).contains(&n),
                "r = {i}/1000: {n}"
            );
            assert!(n <= previous, "r = {i}/1000: {n} > {previous}");
            previous = n;
        }
    }

    #[test]
    fn nan_inputs_give_a_material_without_nan() {
        let material = GltfMaterial {
            base_color: Color::linear_rgba(f32::NAN, 0.5, f32::INFINITY, f32::NAN),
            emissive: LinearRgba::new(f32::NAN, 2.0, -1.0, 1.0),
            metallic: f32::NAN,
            perceptual_roughness: f32::NAN,
            ..Default::default()
        };
        let phong = phong_material_from_gltf(&material, None);
        let values = [
            linear(phong.base_color),
            linear(phong.specular_color),
            phong.emissive.to_f32_array(),
        ];
        assert!(values.iter().flatten().all(|v| v.is_finite()), "{values:?}");
        // NaN metallic → 0: the (sanitized) base color stays diffuse, F0 is 0.04.
        assert_close(
            linear(phong.base_color),
            [0.0, 0.5, limits::MAX_INTENSITY, 1.0],
            "base color",
        );
        assert_close(
            linear(phong.specular_color),
            compensated([0.04, 0.04, 0.04, 1.0], 0.5),
            "F0",
        );
        assert_eq!(phong.emissive, LinearRgba::new(0.0, 2.0, 0.0, 1.0));
        // NaN roughness taken as 0.5.
        assert!(
            (phong.shininess - 14.794).abs() < 1e-4,
            "{}",
            phong.shininess
        );
    }

    #[test]
    fn out_of_range_metallic_is_clamped() {
        let base_color = Color::linear_rgb(0.2, 0.4, 0.6);
        let over = phong_material_from_gltf(
            &GltfMaterial {
                base_color,
                metallic: 3.0,
                ..Default::default()
            },
            None,
        );
        assert_close(linear(over.base_color), [0.0, 0.0, 0.0, 1.0], "m = 1");
        let r = GltfMaterial::default().perceptual_roughness;
        assert_close(
            linear(over.specular_color),
            compensated([0.2, 0.4, 0.6, 1.0], r),
            "m = 1",
        );
        let under = phong_material_from_gltf(
            &GltfMaterial {
                base_color,
                metallic: -2.0,
                ..Default::default()
            },
            None,
        );
        assert_close(linear(under.base_color), [0.2, 0.4, 0.6, 1.0], "m = 0");
    }

    #[test]
    fn textures_emissive_and_alpha_modes_carry_over() {
        let texture = |index: u32| -> Option<Handle<Image>> {
            Some(Handle::Uuid(
                bevy::asset::uuid::Uuid::from_u128(index as u128),
                Default::default(),
            ))
        };
        for alpha_mode in [AlphaMode::Opaque, AlphaMode::Mask(0.5), AlphaMode::Blend] {
            let material = GltfMaterial {
                base_color_texture: texture(1),
                emissive: LinearRgba::rgb(2.0, 1.0, 0.5),
                emissive_texture: texture(2),
                normal_map_texture: texture(3),
                alpha_mode,
                ..Default::default()
            };
            let phong = phong_material_from_gltf(&material, Some("Material0"));
            assert_eq!(phong.base_color_texture, texture(1));
            assert_eq!(phong.emissive_texture, texture(2));
            assert_eq!(phong.normal_map_texture, texture(3));
            assert_eq!(phong.specular_texture, None);
            assert!(!phong.flip_normal_map_y, "glTF normal maps are +Y up");
            assert!(!phong.double_sided);
            assert_eq!(phong.emissive, LinearRgba::rgb(2.0, 1.0, 0.5));
            assert_eq!(phong.alpha_mode, alpha_mode);
            assert!(unmapped_gltf_features(&material).is_empty());
        }
    }

    #[test]
    fn double_sidedness_carries_over() {
        for double_sided in [false, true] {
            let material = GltfMaterial {
                double_sided,
                ..Default::default()
            };
            assert_eq!(
                phong_material_from_gltf(&material, None).double_sided,
                double_sided
            );
        }
    }

    #[test]
    fn the_texture_transform_is_carried() {
        let uv_transform = bevy::math::Affine2::from_scale_angle_translation(
            bevy::math::Vec2::new(2.0, 0.5),
            -0.3,
            bevy::math::Vec2::new(0.25, 0.5),
        );
        let material = GltfMaterial {
            uv_transform,
            ..Default::default()
        };
        assert_eq!(
            phong_material_from_gltf(&material, None).uv_transform,
            uv_transform
        );
        assert!(unmapped_gltf_features(&material).is_empty());
    }

    #[test]
    fn an_unlit_material_is_unlit_with_its_base_color_as_it_is() {
        let material = GltfMaterial {
            base_color: Color::linear_rgba(0.8, 0.4, 0.2, 0.5),
            metallic: 1.0,
            unlit: true,
            ..Default::default()
        };
        let phong = phong_material_from_gltf(&material, None);
        assert!(phong.unlit);
        assert_close(linear(phong.base_color), [0.8, 0.4, 0.2, 0.5], "base color");
        assert!(unmapped_gltf_features(&material).is_empty());
    }

    #[test]
    fn each_map_keeps_the_uv_set_its_texture_reads() {
        let map = Handle::<Image>::default();
        let material = GltfMaterial {
            base_color_texture: Some(map.clone()),
            base_color_channel: UvChannel::Uv1,
            emissive_texture: Some(map.clone()),
            emissive_channel: UvChannel::Uv1,
            normal_map_texture: Some(map),
            normal_map_channel: UvChannel::Uv1,
            ..Default::default()
        };
        let phong = phong_material_from_gltf(&material, None);
        assert_eq!(phong.base_color_channel, UvChannel::Uv1);
        assert_eq!(phong.emissive_channel, UvChannel::Uv1);
        assert_eq!(phong.normal_map_channel, UvChannel::Uv1);
        assert!(unmapped_gltf_features(&material).is_empty());
    }

    #[test]
    fn the_occlusion_texture_is_the_ao_map_on_its_uv_set() {
        let occlusion = Handle::<Image>::default();
        let material = GltfMaterial {
            occlusion_texture: Some(occlusion.clone()),
            occlusion_channel: UvChannel::Uv1,
            ..Default::default()
        };
        let phong = phong_material_from_gltf(&material, None);
        assert_eq!(phong.ao_map_texture, Some(occlusion));
        assert_eq!(phong.ao_map_channel, UvChannel::Uv1);
        assert_eq!(phong.ao_map_intensity, 1.0);
        assert!(unmapped_gltf_features(&material).is_empty());
    }

    #[test]
    fn parts_without_a_counterpart_are_listed() {
        let material = GltfMaterial {
            metallic_roughness_texture: Some(Handle::default()),
            clearcoat: 0.5,
            specular_transmission: 0.5,
            ..Default::default()
        };
        assert_eq!(
            unmapped_gltf_features(&material),
            ["KHR_materials_transmission", "KHR_materials_clearcoat"]
        );
        assert!(unmapped_gltf_features(&GltfMaterial::default()).is_empty());
    }

    /// The usual export: factors 1, the values in the texture. The material keeps what the
    /// shader needs to apply the rules per texel.
    #[test]
    fn the_metallic_roughness_texture_is_drawn_with_its_factors() {
        let map = Handle::<Image>::Uuid(bevy::asset::uuid::Uuid::from_u128(9), Default::default());
        let material = GltfMaterial {
            base_color: Color::linear_rgba(0.8, 0.4, 0.2, 0.5),
            metallic: 1.0,
            perceptual_roughness: 0.5,
            metallic_roughness_texture: Some(map.clone()),
            metallic_roughness_channel: UvChannel::Uv1,
            ..Default::default()
        };
        let phong = phong_material_from_gltf(&material, None);
        assert_eq!(phong.metallic_roughness_texture, Some(map));
        assert_eq!(phong.metallic_roughness_channel, UvChannel::Uv1);
        assert_eq!((phong.metallic, phong.perceptual_roughness), (1.0, 0.5));
        // Not darkened by the factor: the texel's metallic does that.
        assert_close(linear(phong.base_color), [0.8, 0.4, 0.2, 0.5], "base color");
        assert_close(linear(phong.specular_color), [0.04, 0.04, 0.04, 1.0], "F0");
        assert_eq!(phong.specular_strength, core::f32::consts::PI);
        // The factor's, for the vertices.
        assert!(
            (phong.shininess - 14.794).abs() < 1e-4,
            "{}",
            phong.shininess
        );
        assert!(
            crate::MaterialFeatures::of(&phong)
                .contains(crate::MaterialFeatures::METALLIC_ROUGHNESS_MAP_UV_B)
        );
        // Unlit: the base color as it is, no map drawn.
        let unlit = phong_material_from_gltf(
            &GltfMaterial {
                unlit: true,
                ..material.clone()
            },
            None,
        );
        assert_eq!(unlit.metallic_roughness_texture, None);
        assert_close(linear(unlit.base_color), [0.8, 0.4, 0.2, 0.5], "unlit");
        // NaN factors: metallic 0, roughness 0.5, as without a map.
        let nan = phong_material_from_gltf(
            &GltfMaterial {
                metallic: f32::NAN,
                perceptual_roughness: f32::NAN,
                ..material
            },
            None,
        );
        assert_eq!((nan.metallic, nan.perceptual_roughness), (0.0, 0.5));
    }

    /// `KHR_materials_specular` as Bevy's loader reads it (`reflectance` = specularFactor /
    /// 2, `specular_tint` = specularColorFactor): Bevy's `F₀ = 0.16 · (ρ·t)²`.
    #[test]
    fn khr_materials_specular_gives_bevys_dielectric_f0() {
        let material = GltfMaterial {
            reflectance: 0.25,
            specular_tint: Color::linear_rgb(1.0, 0.5, 2.0),
            ..Default::default()
        };
        let phong = phong_material_from_gltf(&material, None);
        // 0.16 · (0.25, 0.125, 0.5)² = (0.01, 0.0025, 0.04).
        assert_close(
            linear(phong.specular_color),
            compensated(
                [0.01, 0.0025, 0.04, 1.0],
                GltfMaterial::default().perceptual_roughness,
            ),
            "F0",
        );
    }
}
