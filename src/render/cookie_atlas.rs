//! The light cookie atlas: every cookie image as a layer of one 2D array texture,
//! [`COOKIE_RESOLUTION`] texels square, holding each image's 8-bit sRGB values decoded to
//! linear `f32` here, once (the shader reads and filters them).

#[cfg(test)]
use crate::lights::cookie_layer_texels;
use crate::limits::COOKIE_RESOLUTION;
use bevy::{
    asset::{Handle, RenderAssetUsages, uuid_handle},
    image::{Image, ImageSampler},
    render::render_resource::{
        Extent3d, TextureDimension, TextureFormat, TextureViewDescriptor, TextureViewDimension,
    },
};

/// The atlas image, bound by every Phong material (`cookie_atlas` in `bevy_phong::shaders::bindings`)
/// where the device binds every map.
pub(crate) const PHONG_COOKIE_ATLAS: Handle<Image> =
    uuid_handle!("9b4e6d2a-7c1f-4e85-b3a0-5d8f2c6e1a47");

/// The atlas's format: linear color, each 8-bit sRGB value decoded by the formula in `f64`
/// and rounded once ([`srgb_to_linear`]). Decoding here rather than in the shader spares a
/// fragment twelve `pow`s per cookie (four texels, three channels): a cookied lamp cost
/// 2.6× a plain one with them (see docs/performance.md); a device's own sRGB decoding
/// would be approximate.
const ATLAS_FORMAT: TextureFormat = TextureFormat::Rgba32Float;

/// An 8-bit sRGB value as linear color (IEC 61966-2-1), computed in `f64`.
fn srgb_to_linear(value: u8) -> f32 {
    let srgb = f64::from(value) / 255.0;
    let linear = if srgb <= 0.04045 {
        srgb / 12.92
    } else {
        ((srgb + 0.055) / 1.055).powf(2.4)
    };
    linear as f32
}

/// The atlas image of `layers` (each [`cookie_layer_texels`]), one white layer when there
/// are none, viewed as a 2D array.
pub(crate) fn atlas_image(layers: &[Vec<[u8; 4]>]) -> Image {
    let side = COOKIE_RESOLUTION;
    let white = vec![[255u8; 4]; (side * side) as usize];
    let layers: Vec<&Vec<[u8; 4]>> = if layers.is_empty() {
        vec![&white]
    } else {
        layers.iter().collect()
    };
    let decode: [f32; 256] = core::array::from_fn(|value| srgb_to_linear(value as u8));
    let data: Vec<u8> = layers
        .iter()
        .flat_map(|layer| layer.iter().flatten())
        .flat_map(|&value| decode[usize::from(value)].to_le_bytes())
        .collect();
    let mut image = Image::new(
        Extent3d {
            width: side,
            height: side,
            depth_or_array_layers: layers.len() as u32,
        },
        TextureDimension::D2,
        data,
        ATLAS_FORMAT,
        RenderAssetUsages::RENDER_WORLD,
    );
    // Read texel by texel (the shader filters): no sampler is bound.
    image.sampler = ImageSampler::nearest();
    image.texture_view_descriptor = Some(TextureViewDescriptor {
        dimension: Some(TextureViewDimension::D2Array),
        ..Default::default()
    });
    image
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: u32, height: u32, format: TextureFormat, texel: [u8; 4]) -> Image {
        Image::new_fill(
            Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            &texel,
            format,
            RenderAssetUsages::MAIN_WORLD,
        )
    }

    #[test]
    fn a_layer_sized_srgb_image_is_copied_and_others_are_converted() {
        let side = COOKIE_RESOLUTION;
        let srgb = TextureFormat::Rgba8UnormSrgb;
        let copied = cookie_layer_texels(&image(side, side, srgb, [10, 20, 30, 255])).unwrap();
        assert!(copied.iter().all(|texel| *texel == [10, 20, 30, 255]));
        // A linear 0.5 is sRGB 188 (0.5^(1/2.4)·1.055 − 0.055 = 0.7354).
        let linear = image(3, 5, TextureFormat::Rgba8Unorm, [0, 128, 255, 255]);
        let converted = cookie_layer_texels(&linear).unwrap();
        assert_eq!(converted.len(), (side * side) as usize);
        assert!(converted.iter().all(|texel| *texel == [0, 188, 255, 255]));
        let compressed = Image {
            texture_descriptor: bevy::render::render_resource::TextureDescriptor {
                format: TextureFormat::Bc1RgbaUnorm,
                ..linear.texture_descriptor.clone()
            },
            ..linear
        };
        assert_eq!(cookie_layer_texels(&compressed), None);
    }

    #[test]
    fn the_atlas_has_a_white_layer_when_no_light_has_a_cookie() {
        let atlas = atlas_image(&[]);
        assert_eq!(atlas.texture_descriptor.size.depth_or_array_layers, 1);
        let data = atlas.data.unwrap();
        let texels: &[[f32; 4]] = bytemuck::cast_slice(&data);
        assert!(
            texels.iter().all(|&texel| texel == [1.0; 4]),
            "linear white"
        );
    }

    #[test]
    fn the_atlas_holds_each_srgb_value_decoded_to_linear() {
        // sRGB 188 is linear ((188/255 + 0.055)/1.055)^2.4 = 0.5029; 10 is 10/255/12.92.
        let side = COOKIE_RESOLUTION as usize;
        let atlas = atlas_image(&[vec![[188, 10, 0, 255]; side * side]]);
        let data = atlas.data.unwrap();
        let texel: [f32; 4] = bytemuck::cast_slice(&data)[0];
        let expected = [
            ((188.0 / 255.0 + 0.055) / 1.055f64).powf(2.4),
            10.0 / 255.0 / 12.92,
            0.0,
            1.0,
        ];
        for (value, expected) in texel.into_iter().zip(expected) {
            // One rounding to f32: within half an ulp.
            assert!(
                (f64::from(value) - expected).abs() <= expected * 6e-8,
                "{value} {expected}"
            );
        }
    }
}
