//! Writing a read-back float image as OpenEXR (linear, unclipped) or PNG (sRGB, 8 bits).

use bevy_phong_headless::{FloatImage, save_srgb_png};
use std::path::Path;

/// Writes all four channels as 32-bit floats.
pub fn write_exr(path: &Path, image: &FloatImage) -> Result<(), String> {
    let data: Vec<f32> = image.pixels.iter().flatten().copied().collect();
    image::Rgba32FImage::from_raw(image.width, image.height, data)
        .expect("the pixel count matches the size")
        .save(path)
        .map_err(|error| format!("{}: {error}", path.display()))
}

/// Writes the color sRGB-encoded and clipped to `[0, 1]`, 8 bits per channel.
pub fn write_png(path: &Path, image: &FloatImage) -> Result<(), String> {
    let rgb: Vec<[f32; 3]> = image.pixels.iter().map(|&[r, g, b, _]| [r, g, b]).collect();
    save_srgb_png(path, image.width, image.height, &rgb);
    Ok(())
}
