//! Linear float images read back from the GPU, and writing them as PNG.

use bevy::color::Color;
use std::path::{Path, PathBuf};

/// An RGBA32F image read back from the GPU: linear values, rows top to bottom.
#[derive(Clone)]
pub struct FloatImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` pixels, row by row.
    pub pixels: Vec<[f32; 4]>,
}

impl FloatImage {
    /// The image in `bytes`: `width * height` RGBA32F pixels, row by row, without padding
    /// (as [`read_back_frame`](crate::read_back_frame) returns them).
    pub(crate) fn from_rows(width: u32, height: u32, bytes: &[u8]) -> Self {
        Self {
            width,
            height,
            pixels: bytes
                .chunks_exact(16)
                .map(bytemuck::pod_read_unaligned)
                .collect(),
        }
    }

    /// Pixels with a NaN or infinite channel.
    pub fn non_finite_pixels(&self) -> usize {
        self.pixels
            .iter()
            .filter(|pixel| pixel.iter().any(|channel| !channel.is_finite()))
            .count()
    }

    /// Pixels a mesh covers: the harness clears the background to alpha 0, materials draw
    /// alpha 1.
    pub fn covered_pixels(&self) -> usize {
        self.pixels.iter().filter(|pixel| pixel[3] > 0.0).count()
    }
}

/// Writes linear RGB pixels as an 8-bit sRGB PNG (values outside 0–1 clipped).
///
/// # Panics
///
/// When the file cannot be written.
pub fn save_srgb_png(path: &Path, width: u32, height: u32, pixels: &[[f32; 3]]) {
    let bytes: Vec<u8> = pixels
        .iter()
        .flat_map(|rgb| {
            let srgb = Color::linear_rgb(rgb[0], rgb[1], rgb[2]).to_srgba();
            [srgb.red, srgb.green, srgb.blue].map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
        })
        .collect();
    image::save_buffer(path, &bytes, width, height, image::ExtendedColorType::Rgb8)
        .expect("write PNG");
}

/// `target/render-tests` of the build that made the running binary: the nearest folder above
/// it that Cargo marked as a target folder (with a `CACHEDIR.TAG`), else `target` in the
/// working folder.
pub(crate) fn render_tests_directory() -> PathBuf {
    let target = std::env::current_exe()
        .ok()
        .and_then(|exe| {
            exe.ancestors()
                .find(|folder| folder.join("CACHEDIR.TAG").is_file())
                .map(Path::to_path_buf)
        })
        .unwrap_or_else(|| PathBuf::from("target"));
    target.join("render-tests")
}
