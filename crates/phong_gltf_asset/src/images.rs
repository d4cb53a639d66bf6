//! The asset's textures, as PNG files.

use crate::encoding;
use core::f64::consts::TAU;

/// Texture side, texels.
pub const SIZE: u32 = 16;

fn texels(channels: usize, texel: impl Fn(u32, u32) -> Vec<u8>) -> Vec<u8> {
    let mut pixels = Vec::with_capacity((SIZE * SIZE) as usize * channels);
    for row in 0..SIZE {
        for column in 0..SIZE {
            let value = texel(column, row);
            assert_eq!(value.len(), channels);
            pixels.extend(value);
        }
    }
    pixels
}

/// The ground's base color: a 4 × 4 checkerboard of warm light and dark squares (sRGB).
pub fn checker() -> Vec<u8> {
    let pixels = texels(3, |column, row| {
        if (column / 4 + row / 4) % 2 == 0 {
            vec![224, 208, 176]
        } else {
            vec![96, 80, 64]
        }
    });
    encoding::png(SIZE, SIZE, 3, &pixels)
}

/// The ground's normal map (linear, +Y up: green points to the image's top): the normals
/// of the height field `h = 0.5 · sin(2π·2·x) · sin(2π·2·y)` over the unit square.
pub fn bumps() -> Vec<u8> {
    let amplitude = 0.5;
    let frequency = 2.0;
    let pixels = texels(3, |column, row| {
        // x right, y up, at the texel's center.
        let x = (f64::from(column) + 0.5) / f64::from(SIZE);
        let y = 1.0 - (f64::from(row) + 0.5) / f64::from(SIZE);
        let k = TAU * frequency;
        let dh_dx = amplitude * k * (k * x).cos() * (k * y).sin();
        let dh_dy = amplitude * k * (k * x).sin() * (k * y).cos();
        let length = (dh_dx * dh_dx + dh_dy * dh_dy + 1.0).sqrt();
        [-dh_dx, -dh_dy, 1.0]
            .map(|n| ((n / length * 0.5 + 0.5) * 255.0).round() as u8)
            .to_vec()
    });
    encoding::png(SIZE, SIZE, 3, &pixels)
}

/// The fence's base color: vertical white bars two texels wide (alpha 1) with gaps two
/// texels wide (alpha 0), for an alpha mask to cut.
pub fn bars() -> Vec<u8> {
    let pixels = texels(4, |column, _| {
        if (column / 2) % 2 == 0 {
            vec![255, 255, 255, 255]
        } else {
            vec![255, 255, 255, 0]
        }
    });
    encoding::png(SIZE, SIZE, 4, &pixels)
}
