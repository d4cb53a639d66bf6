//! `PhongMaterial::from(&StandardMaterial)`: Bevy's physically based material as a Blinn-Phong
//! one, by the rules glTF materials follow ([`MetallicRoughness`]).

use super::{MetallicRoughness, PhongMaterial, metallic_roughness::emissive_color};
use bevy::{
    color::{Color, ColorToComponents, LinearRgba},
    log::warn,
    math::Vec3,
    pbr::StandardMaterial,
};

/// The Phong material that draws like `material` as nearly as Blinn-Phong can.
///
/// | `StandardMaterial` | `PhongMaterial` |
/// |---|---|
/// | `base_color`, `base_color_texture`, `base_color_channel` | `base_color = base_color · (1 − metallic)` in linear RGB (alpha kept), the same texture and UV set |
/// | `metallic` m, `perceptual_roughness` r, `reflectance` ρ, `specular_tint` t | `specular_model: NormalizedBlinnPhong`, `specular_color = k · (1 + k · (1/E − 1))` with `k = mix(0.16 · (ρ·t)², base_color, m)` (Bevy's `F₀`; 0.04 at the default ρ = 0.5) and `E` a GGX lobe's single-scattering albedo at `r` (Bevy's compensation for multiple scattering), `shininess` n `= clamp(0.669/r⁴ + 1.42/r² − 1.59, 1, 10⁴)` (SPEC.md, "Metallic-roughness map"), `specular_strength = π` |
/// | `emissive`, `emissive_texture`, `emissive_channel` | the same |
/// | `normal_map_texture`, `normal_map_channel`, `flip_normal_map_y` | the same |
/// | `occlusion_texture`, `occlusion_channel` | `ao_map_texture`, `ao_map_channel` (intensity 1) |
/// | `alpha_mode`, `double_sided`, `cull_mode`, `unlit`, `fog_enabled`, `depth_bias`, `uv_transform` | the same |
/// | `metallic_roughness_texture`, `metallic_roughness_channel` | the same, with `metallic` and `perceptual_roughness` as its factors: the rules above applied per texel by the shader, `base_color` and `specular_color = F₀` kept as they are |
/// | (Bevy's weights on the ambient light) | `ambient_factor = 0.4524` (Bevy's weight on the diffuse color), `ambient_specular: true` and `perceptual_roughness = r`: the ambient light reflected by `specular_color` as Bevy weighs it (SPEC.md, "Ambient specular") |
/// | (Bevy's `EnvironmentMapLight` on the camera) | `environment_light: true`: its diffuse cube lights the diffuse color, its specular cube is reflected by the same weights (SPEC.md, "Environment light") |
///
/// What has no counterpart is left out, with one warning that lists it and says what the
/// surface becomes without it: parallax (`depth_map`), transmission, thickness, clearcoat,
/// anisotropy and an emissive exposure weight. Bevy's `Lightmap` component keeps working on
/// the mesh; its exposure is the camera's (see `BevyLightExposure`). Invalid numbers are
/// brought into range as `PhongMaterial`'s validation does: the result never holds a NaN.
///
/// ```
/// use bevy::prelude::*;
/// use bevy_phong::prelude::*;
///
/// let plastic = StandardMaterial {
///     base_color: Color::linear_rgb(0.8, 0.1, 0.1),
///     perceptual_roughness: 0.5,
///     ..default()
/// };
/// let phong = PhongMaterial::from(&plastic);
/// assert!((phong.shininess - 14.794).abs() < 1e-4); // 0.669·16 + 1.42·4 − 1.59
/// assert_eq!(phong.specular_model, SpecularModel::NormalizedBlinnPhong);
/// assert_eq!(phong.specular_strength, std::f32::consts::PI); // the BRDF drawn times π
/// ```
impl From<&StandardMaterial> for PhongMaterial {
    fn from(material: &StandardMaterial) -> Self {
        warn_unmapped("a StandardMaterial", &unmapped_standard_features(material));
        converted_standard_material(material)
    }
}

/// [`PhongMaterial::from`] a `StandardMaterial`, without a warning.
pub(crate) fn converted_standard_material(material: &StandardMaterial) -> PhongMaterial {
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
        flip_normal_map_y: material.flip_normal_map_y,
        double_sided: material.double_sided,
        cull_mode: material.cull_mode,
        fog_enabled: material.fog_enabled,
        depth_bias: material.depth_bias,
        uv_transform: material.uv_transform,
        ao_map_texture: material.occlusion_texture.clone(),
        ao_map_channel: material.occlusion_channel.clone(),
        ..numbers.phong_material()
    }
}

/// Bevy's reflectance of a dielectric at normal incidence, per channel, linear RGB:
/// `0.16 · (reflectance · specular_tint)²` (`StandardMaterial`'s `reflectance` and
/// `specular_tint`; glTF's `KHR_materials_specular` as Bevy's loader reads it into them).
pub(crate) fn bevy_dielectric_f0(reflectance: f32, specular_tint: Color) -> Vec3 {
    let tinted = LinearRgba::from(specular_tint).to_vec3() * reflectance;
    0.16 * tinted * tinted
}

/// A part of a PBR material that has no Phong counterpart, named as its source names it,
/// with what the surface becomes without it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Unmapped {
    /// The field (or glTF extension).
    pub(crate) name: &'static str,
    /// What the Phong surface draws in its place.
    pub(crate) becomes: &'static str,
}

/// One warning for `label` listing `unmapped` (none where it is empty).
pub(crate) fn warn_unmapped(label: &str, unmapped: &[Unmapped]) {
    if unmapped.is_empty() {
        return;
    }
    let parts: Vec<String> = unmapped
        .iter()
        .map(|part| format!("{} ({})", part.name, part.becomes))
        .collect();
    warn!(
        "{label}: PhongMaterial has no counterpart of {}",
        parts.join("; ")
    );
}

/// The parts of `material` that [`PhongMaterial::from`] leaves out because they are set and
/// Phong has no counterpart (empty when it maps everything set).
pub(crate) fn unmapped_standard_features(material: &StandardMaterial) -> Vec<Unmapped> {
    [
        (
            material.depth_map.is_some(),
            "depth_map",
            "drawn flat, without parallax",
        ),
        (
            material.specular_transmission > 0.0,
            "specular_transmission",
            TRANSMISSION,
        ),
        (
            material.diffuse_transmission > 0.0,
            "diffuse_transmission",
            "drawn opaque: no light passes through",
        ),
        (material.thickness > 0.0, "thickness", VOLUME),
        (material.clearcoat > 0.0, "clearcoat", CLEARCOAT),
        (
            material.anisotropy_strength > 0.0,
            "anisotropy_strength",
            ANISOTROPY,
        ),
        (
            material.emissive_exposure_weight != 0.0,
            "emissive_exposure_weight",
            "emissive drawn as bright at every exposure",
        ),
    ]
    .into_iter()
    .filter_map(|(set, name, becomes)| set.then_some(Unmapped { name, becomes }))
    .collect()
}

/// What a transmissive surface becomes.
pub(crate) const TRANSMISSION: &str = "drawn opaque, reflecting only: nothing seen through it";
/// What a surface with a volume becomes.
pub(crate) const VOLUME: &str = "drawn without absorption inside it";
/// What a clear-coated surface becomes.
pub(crate) const CLEARCOAT: &str = "drawn without its coat's second highlight";
/// What an anisotropic surface becomes.
pub(crate) const ANISOTROPY: &str = "its highlight drawn round, not stretched";

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::metallic_roughness::tests::{assert_close, compensated, linear};
    use bevy::{
        asset::Handle,
        color::{Color, LinearRgba},
        image::Image,
        math::Affine2,
        mesh::UvChannel,
        prelude::AlphaMode,
        render::render_resource::Face,
    };

    #[test]
    fn the_default_standard_material_is_a_white_dielectric_of_four_percent_specular() {
        // Bevy's defaults: white, metallic 0, perceptual roughness 0.5, reflectance 0.5.
        let phong = PhongMaterial::from(&StandardMaterial::default());
        assert_close(linear(phong.base_color), [1.0, 1.0, 1.0, 1.0], "base");
        // 0.16 · 0.5² = 0.04, worked by hand, then compensated at r = 0.5.
        assert_close(
            linear(phong.specular_color),
            compensated([0.04, 0.04, 0.04, 1.0], 0.5),
            "F₀",
        );
        // 0.669 · 16 + 1.42 · 4 − 1.59.
        assert!(
            (phong.shininess - 14.794).abs() < 1e-4,
            "{}",
            phong.shininess
        );
        assert_eq!(
            phong.specular_strength,
            core::f32::consts::PI,
            "the BRDF times π"
        );
        assert_eq!(
            phong.specular_model,
            crate::SpecularModel::NormalizedBlinnPhong
        );
    }

    #[test]
    fn reflectance_and_specular_tint_give_bevys_dielectric_f0() {
        // ρ = 0.8, t = (1, 0.5, 0.25): 0.16 · (0.8, 0.4, 0.2)² = (0.1024, 0.0256, 0.0064).
        let material = StandardMaterial {
            reflectance: 0.8,
            specular_tint: Color::linear_rgb(1.0, 0.5, 0.25),
            ..Default::default()
        };
        let phong = PhongMaterial::from(&material);
        assert_close(
            linear(phong.specular_color),
            compensated([0.1024, 0.0256, 0.0064, 1.0], 0.5),
            "F₀",
        );
    }

    #[test]
    fn a_metal_has_no_diffuse_and_its_color_as_specular() {
        let material = StandardMaterial {
            base_color: Color::linear_rgb(1.0, 0.8, 0.3),
            metallic: 1.0,
            perceptual_roughness: 0.25,
            ..Default::default()
        };
        let phong = PhongMaterial::from(&material);
        assert_close(linear(phong.base_color), [0.0, 0.0, 0.0, 1.0], "base");
        assert_close(
            linear(phong.specular_color),
            compensated([1.0, 0.8, 0.3, 1.0], 0.25),
            "specular",
        );
        // 0.669 / 0.25⁴ + 1.42 / 0.25² − 1.59.
        assert!(
            (phong.shininess - 192.394).abs() < 1e-3,
            "{}",
            phong.shininess
        );
    }

    #[test]
    fn maps_modes_and_flags_carry_over() {
        let texture = |index: u32| {
            Handle::<Image>::Uuid(
                bevy::asset::uuid::Uuid::from_u128(u128::from(index)),
                Default::default(),
            )
        };
        let transform = Affine2::from_scale_angle_translation(
            bevy::math::Vec2::new(2.0, 3.0),
            0.5,
            bevy::math::Vec2::new(0.1, 0.2),
        );
        let material = StandardMaterial {
            base_color_texture: Some(texture(1)),
            base_color_channel: UvChannel::Uv1,
            emissive: LinearRgba::rgb(0.5, 0.25, 0.0),
            emissive_texture: Some(texture(2)),
            normal_map_texture: Some(texture(3)),
            normal_map_channel: UvChannel::Uv1,
            flip_normal_map_y: true,
            occlusion_texture: Some(texture(4)),
            occlusion_channel: UvChannel::Uv1,
            alpha_mode: AlphaMode::Mask(0.3),
            double_sided: true,
            cull_mode: None,
            unlit: true,
            fog_enabled: false,
            depth_bias: 2.0,
            uv_transform: transform,
            ..Default::default()
        };
        let phong = PhongMaterial::from(&material);
        assert_eq!(phong.base_color_texture, Some(texture(1)));
        assert_eq!(phong.base_color_channel, UvChannel::Uv1);
        assert_eq!(phong.emissive, LinearRgba::rgb(0.5, 0.25, 0.0));
        assert_eq!(phong.emissive_texture, Some(texture(2)));
        assert_eq!(phong.normal_map_texture, Some(texture(3)));
        assert_eq!(phong.normal_map_channel, UvChannel::Uv1);
        assert!(phong.flip_normal_map_y);
        assert_eq!(phong.ao_map_texture, Some(texture(4)));
        assert_eq!(phong.ao_map_channel, UvChannel::Uv1);
        assert_eq!(phong.alpha_mode, AlphaMode::Mask(0.3));
        assert!(phong.double_sided);
        assert_eq!(phong.cull_mode, None);
        assert!(phong.unlit);
        assert!(!phong.fog_enabled);
        assert_eq!(phong.depth_bias, 2.0);
        assert_eq!(phong.uv_transform, transform);
        // An unlit material keeps its base color whole (not darkened by metallic).
        assert_close(linear(phong.base_color), [1.0, 1.0, 1.0, 1.0], "unlit base");
        let culled = PhongMaterial::from(&StandardMaterial {
            cull_mode: Some(Face::Front),
            ..Default::default()
        });
        assert_eq!(culled.cull_mode, Some(Face::Front));
    }

    #[test]
    fn nan_numbers_give_a_material_without_nan() {
        let material = StandardMaterial {
            base_color: Color::linear_rgba(f32::NAN, 0.5, 0.5, 1.0),
            metallic: f32::NAN,
            perceptual_roughness: f32::NAN,
            reflectance: f32::NAN,
            emissive: LinearRgba::rgb(f32::NAN, 1.0, 1.0),
            ..Default::default()
        };
        let phong = PhongMaterial::from(&material);
        for value in linear(phong.base_color)
            .into_iter()
            .chain(linear(phong.specular_color))
            .chain(phong.emissive.to_f32_array())
            .chain([phong.shininess, phong.specular_strength])
        {
            assert!(!value.is_nan(), "{phong:?}");
        }
        // NaN roughness taken as 0.5.
        assert!(
            (phong.shininess - 14.794).abs() < 1e-4,
            "{}",
            phong.shininess
        );
    }

    #[test]
    fn the_metallic_roughness_texture_carries_over_with_its_factors() {
        let map = Handle::<Image>::Uuid(bevy::asset::uuid::Uuid::from_u128(5), Default::default());
        let material = StandardMaterial {
            base_color: Color::linear_rgb(1.0, 0.8, 0.3),
            metallic: 1.0,
            perceptual_roughness: 1.0,
            metallic_roughness_texture: Some(map.clone()),
            ..Default::default()
        };
        let phong = PhongMaterial::from(&material);
        assert_eq!(phong.metallic_roughness_texture, Some(map));
        assert_eq!(phong.metallic_roughness_channel, UvChannel::Uv0);
        assert_eq!((phong.metallic, phong.perceptual_roughness), (1.0, 1.0));
        assert_close(linear(phong.base_color), [1.0, 0.8, 0.3, 1.0], "base");
        // F₀ as it is: the shader mixes and compensates it per texel.
        assert_close(linear(phong.specular_color), [0.04, 0.04, 0.04, 1.0], "F₀");
        assert_eq!(phong.specular_strength, core::f32::consts::PI);
        assert!(unmapped_standard_features(&material).is_empty());
    }

    #[test]
    fn fields_without_a_counterpart_are_listed() {
        assert!(unmapped_standard_features(&StandardMaterial::default()).is_empty());
        let material = StandardMaterial {
            clearcoat: 1.0,
            specular_transmission: 0.5,
            depth_map: Some(Handle::default()),
            ..Default::default()
        };
        let names: Vec<_> = unmapped_standard_features(&material)
            .iter()
            .map(|part| part.name)
            .collect();
        assert_eq!(names, ["depth_map", "specular_transmission", "clearcoat"]);
    }
}
