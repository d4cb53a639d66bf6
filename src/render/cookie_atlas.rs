//! The light cookie atlas: every cookie image as a layer of one 2D array texture,
//! [`COOKIE_RESOLUTION`] texels square, holding 8-bit sRGB values (the shader decodes them).

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

/// The atlas's format: the same bytes, which the shader decodes from sRGB itself, texel by
/// texel before it filters (exactly, where some devices' sRGB decoding is approximate).
const ATLAS_FORMAT: TextureFormat = TextureFormat::Rgba8Unorm;

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
    let data: Vec<u8> = layers
        .iter()
        .flat_map(|layer| layer.iter().flatten().copied())
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
        assert!(atlas.data.unwrap().iter().all(|&byte| byte == 255));
    }
}
