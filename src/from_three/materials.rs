//! three.js's `MeshPhongMaterial` and `MeshToonMaterial` as [`PhongMaterial`]s.

use super::{linear_color, scaled};
use crate::material::{DiffuseMode, PhongMaterial, SpecularMode, SpecularModel};
use bevy::{
    asset::{Assets, RenderAssetUsages},
    color::Color,
    image::Image,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// three.js's `MeshPhongMaterial`, the fields that convert (maps aside), with its defaults.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "scene", serde(default, rename_all = "camelCase"))]
pub struct ThreePhongMaterial {
    /// Diffuse color, `0xRRGGBB` sRGB. Default `0xffffff`.
    pub color: u32,
    /// Specular color, `0xRRGGBB` sRGB. Default `0x111111`.
    pub specular: u32,
    /// Shininess; three.js draws at least `1e-4`. Default `30`.
    pub shininess: f32,
    /// Emissive color, `0xRRGGBB` sRGB. Default `0x000000`.
    pub emissive: u32,
    /// Factor on the emissive color. Default `1`.
    pub emissive_intensity: f32,
    /// Lit with the faces' normals. Default `false`.
    pub flat_shading: bool,
}

impl Default for ThreePhongMaterial {
    fn default() -> Self {
        Self {
            color: 0xffffff,
            specular: 0x111111,
            shininess: 30.0,
            emissive: 0x000000,
            emissive_intensity: 1.0,
            flat_shading: false,
        }
    }
}

impl ThreePhongMaterial {
    /// The material that draws as this one: the diffuse color divided by π (three.js's
    /// `BRDF_Lambert`), three.js's normalized Blinn-Phong highlight with its Fresnel term
    /// ([`SpecularModel::NormalizedBlinnPhong`]), the emissive color times its intensity.
    pub fn to_phong(&self) -> PhongMaterial {
        PhongMaterial {
            base_color: diffuse_color(self.color),
            specular_color: linear_color(self.specular).into(),
            specular_strength: 1.0,
            shininess: self.shininess.max(1e-4),
            specular_model: SpecularModel::NormalizedBlinnPhong,
            emissive: scaled(linear_color(self.emissive), self.emissive_intensity.into()),
            flat_shading: self.flat_shading,
            ..PhongMaterial::default()
        }
    }
}

/// three.js's `MeshToonMaterial`, the fields that convert, with its defaults.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "scene", serde(default, rename_all = "camelCase"))]
pub struct ThreeToonMaterial {
    /// Diffuse color, `0xRRGGBB` sRGB. Default `0xffffff`.
    pub color: u32,
    /// Emissive color, `0xRRGGBB` sRGB. Default `0x000000`.
    pub emissive: u32,
    /// Factor on the emissive color. Default `1`.
    pub emissive_intensity: f32,
    /// The `gradientMap`'s texels (its red channel, 8-bit, one row, sampled nearest), or
    /// `None` for three.js's two tones.
    pub gradient_map: Option<Vec<u8>>,
}

impl Default for ThreeToonMaterial {
    fn default() -> Self {
        Self {
            color: 0xffffff,
            emissive: 0x000000,
            emissive_intensity: 1.0,
            gradient_map: None,
        }
    }
}

/// Texels of the ramp that stands for three.js's toon shading without a `gradientMap`.
const TWO_TONES_WIDTH: usize = 10;

impl ThreeToonMaterial {
    /// The material that draws as this one: a toon ramp of the `gradientMap` (an `R8Unorm`
    /// image, its texels read nearest at `u = (1 + N·L)/2` as three.js reads them), or without
    /// one a ramp of 10 texels, 0.7 for `u < 0.7` and 1 above, three.js's two tones (which it
    /// smooths over the pixel at the edge: there alone the two differ); the diffuse color
    /// divided by π; no highlight.
    pub fn to_phong(&self, images: &mut Assets<Image>) -> PhongMaterial {
        let ramp = match &self.gradient_map {
            Some(texels) if !texels.is_empty() => {
                ramp_image(TextureFormat::R8Unorm, texels.len(), texels.clone())
            }
            _ => ramp_image(
                TextureFormat::R32Float,
                TWO_TONES_WIDTH,
                (0..TWO_TONES_WIDTH)
                    .flat_map(|texel| if texel < 7 { 0.7_f32 } else { 1.0 }.to_le_bytes())
                    .collect(),
            ),
        };
        PhongMaterial {
            base_color: diffuse_color(self.color),
            specular_color: Color::BLACK,
            specular_mode: SpecularMode::Off,
            diffuse_mode: DiffuseMode::Toon {
                bands: 1,
                smoothing: 0.0,
            },
            toon_ramp_texture: Some(images.add(ramp)),
            emissive: scaled(linear_color(self.emissive), self.emissive_intensity.into()),
            ..PhongMaterial::default()
        }
    }
}

/// A `width`×1 ramp of `format` holding `bytes`.
fn ramp_image(format: TextureFormat, width: usize, bytes: Vec<u8>) -> Image {
    Image::new(
        Extent3d {
            width: width as u32,
            height: 1,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        bytes,
        format,
        RenderAssetUsages::default(),
    )
}

/// A three.js material of either kind, as its JSON's `type` names it.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "scene", serde(tag = "type"))]
pub enum ThreeMaterial {
    /// `MeshPhongMaterial`.
    MeshPhongMaterial(ThreePhongMaterial),
    /// `MeshToonMaterial`.
    MeshToonMaterial(ThreeToonMaterial),
}

impl ThreeMaterial {
    /// The material that draws as this one (its kind's `to_phong`).
    pub fn to_phong(&self, images: &mut Assets<Image>) -> PhongMaterial {
        match self {
            ThreeMaterial::MeshPhongMaterial(material) => material.to_phong(),
            ThreeMaterial::MeshToonMaterial(material) => material.to_phong(images),
        }
    }
}

/// three.js's diffuse color `0xRRGGBB` with its `1/π` (`BRDF_Lambert`) folded in.
fn diffuse_color(hex: u32) -> Color {
    scaled(linear_color(hex), 1.0 / PI).into()
}

#[cfg(test)]
mod tests {
    use super::*;
    use bevy::color::LinearRgba;

    #[test]
    fn a_phong_material_keeps_three_js_defaults_and_folds_in_one_over_pi() {
        let material = ThreePhongMaterial::default().to_phong();
        let base = material.base_color.to_linear();
        assert!((f64::from(base.red) - 1.0 / PI).abs() < 1e-7);
        assert!((material.specular_color.to_linear().red - 0.005_605_39).abs() < 1e-8);
        assert_eq!(material.shininess, 30.0);
        assert_eq!(material.specular_model, SpecularModel::NormalizedBlinnPhong);
        let glow = ThreePhongMaterial {
            emissive: 0xffffff,
            emissive_intensity: 2.5,
            ..ThreePhongMaterial::default()
        };
        assert_eq!(glow.to_phong().emissive, LinearRgba::rgb(2.5, 2.5, 2.5));
    }

    /// Without a `gradientMap`, 0.7 below `u = 0.7` and 1 from there, as three.js's
    /// `getGradientIrradiance`; with one, its texels.
    #[test]
    fn a_toon_material_ramps_as_three_js() {
        let mut images = Assets::<Image>::default();
        let two_tones = ThreeToonMaterial::default().to_phong(&mut images);
        let ramp = images.get(&two_tones.toon_ramp_texture.unwrap()).unwrap();
        let ramp = crate::reference::ToonRamp::from_image(ramp).unwrap();
        for (n_dot_l, factor) in [(-1.0, 0.7), (0.35, 0.7), (0.41, 1.0), (1.0, 1.0)] {
            let got = ramp.factor(n_dot_l);
            assert!((got - factor).abs() < 1e-7, "N·L {n_dot_l}: {got}");
        }
        let mapped = ThreeToonMaterial {
            gradient_map: Some(vec![0, 255]),
            ..ThreeToonMaterial::default()
        }
        .to_phong(&mut images);
        let ramp = images.get(&mapped.toon_ramp_texture.unwrap()).unwrap();
        let ramp = crate::reference::ToonRamp::from_image(ramp).unwrap();
        assert_eq!((ramp.factor(-0.1), ramp.factor(0.1)), (0.0, 1.0));
    }
}
