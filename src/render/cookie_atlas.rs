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

    /// A black texel beside a white one (linear 8-bit) resampled to a layer: along `x` the
    /// layer's texel centers `(x + ½)/side` fall at `u · 2 − ½` in the image, so the linear
    /// value is that position clamped to `[0, 1]` (black up to the first texel's center,
    /// white from the second's), the same in every row; stored as 8-bit sRGB. Worked by
    /// hand: `x` 127 and 128 are linear 0.496 and 0.504, sRGB 187 and 188.
    #[test]
    fn an_image_is_resampled_bilinearly_between_its_texel_centers() {
        let side = COOKIE_RESOLUTION;
        let mut black_white = image(2, 1, TextureFormat::Rgba8Unorm, [0, 0, 0, 255]);
        black_white
            .set_color_at(1, 0, bevy::color::Color::WHITE)
            .expect("a writable texel");
        let layer = cookie_layer_texels(&black_white).expect("a readable image");
        let srgb = |linear: f64| {
            let encoded = if linear <= 0.003_130_8 {
                12.92 * linear
            } else {
                1.055 * linear.powf(1.0 / 2.4) - 0.055
            };
            encoded * 255.0
        };
        for y in [0, side / 2, side - 1] {
            for x in 0..side {
                let position = (f64::from(x) + 0.5) / f64::from(side) * 2.0 - 0.5;
                let expected = srgb(position.clamp(0.0, 1.0));
                let texel = layer[(y * side + x) as usize];
                // Half a byte of rounding, and a little for the f32 interpolation.
                assert!(
                    (f64::from(texel[0]) - expected).abs() <= 0.51,
                    "texel ({x}, {y}): {texel:?}, expected red {expected:.2}"
                );
                assert_eq!(texel[0], texel[1], "gray");
                assert_eq!(texel[3], 255, "opaque");
            }
            let row = |x: u32| layer[(y * side + x) as usize][0];
            assert_eq!(
                (row(0), row(63), row(127), row(128), row(192), row(255)),
                (0, 0, 187, 188, 255, 255)
            );
        }
    }

    #[test]
    fn the_atlas_has_a_white_layer_when_no_light_has_a_cookie() {
        let atlas = atlas_image(&[]);
        assert_eq!(atlas.texture_descriptor.size.depth_or_array_layers, 1);
        assert!(atlas.data.unwrap().iter().all(|&byte| byte == 255));
    }
}
