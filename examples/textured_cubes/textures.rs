//! The crate's texture maps, drawn in code: a square of horizontal planks inside a steel
//! frame. All three maps share the layout, so the highlights and grooves line up with the
//! colors.

use bevy::{
    asset::RenderAssetUsages,
    image::Image,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};

/// Texels per side.
const SIZE: u32 = 256;
/// Width of the steel frame, texels.
const FRAME: f32 = 22.0;
/// Planks inside the frame.
const PLANKS: f32 = 4.0;
/// Half-width of the groove between planks and of the frame's bevel, texels.
const GROOVE: f32 = 2.5;

/// What a texel shows.
enum Part {
    /// The steel frame; `bevel` in `[-1, 1]` across its inner edge (0 elsewhere), pointing
    /// toward the frame's outside along `(x, y)`.
    Steel { bevel: (f32, f32) },
    /// Plank `index` at texel `(x, y)`; `groove` in `[-1, 1]` across a groove.
    Wood { index: u32, x: f32, groove: f32 },
}

fn part(x: u32, y: u32) -> Part {
    let (x, y) = (x as f32 + 0.5, y as f32 + 0.5);
    let inner = SIZE as f32 - FRAME;
    // Distance inside the frame's inner edge, per axis (negative in the frame).
    let (from_left, from_right) = (x - FRAME, inner - x);
    let (from_top, from_bottom) = (y - FRAME, inner - y);
    let nearest = from_left.min(from_right).min(from_top).min(from_bottom);
    if nearest < 0.0 {
        let bevel = |distance: f32| (1.0 - (-distance / GROOVE)).clamp(0.0, 1.0);
        let across = (
            bevel(from_right) - bevel(from_left),
            bevel(from_bottom) - bevel(from_top),
        );
        return Part::Steel { bevel: across };
    }
    let plank_height = (inner - FRAME) / PLANKS;
    let along = from_top / plank_height;
    let index = along.floor() as u32;
    let to_seam = (along - along.round()) * plank_height;
    let groove = if to_seam.abs() < GROOVE && along.round() > 0.0 && along.round() < PLANKS {
        to_seam / GROOVE
    } else {
        0.0
    };
    Part::Wood { index, x, groove }
}

fn image(format: TextureFormat, texel: impl Fn(u32, u32) -> [f32; 4]) -> Image {
    let data = (0..SIZE * SIZE)
        .flat_map(|index| texel(index % SIZE, index / SIZE))
        .map(|value| (value.clamp(0.0, 1.0) * 255.0).round() as u8)
        .collect();
    Image::new(
        Extent3d {
            width: SIZE,
            height: SIZE,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        format,
        // Kept in the main world too, where `--compare` reads the texels.
        RenderAssetUsages::default(),
    )
}

/// sRGB colors: warm planks of slightly different tones with grain, gray steel.
pub fn crate_base_color() -> Image {
    image(TextureFormat::Rgba8UnormSrgb, |x, y| match part(x, y) {
        Part::Steel { .. } => [0.55, 0.56, 0.6, 1.0],
        Part::Wood { index, x, groove } => {
            let tone = 0.85 + 0.05 * (index % 3) as f32;
            let grain = 0.9 + 0.1 * (x * 0.21 + (index as f32) * 1.7).sin() * (x * 0.043).cos();
            let shade =
                tone * grain * (1.0 - 0.6 * (1.0 - groove.abs()) * (groove != 0.0) as u8 as f32);
            [0.62 * shade, 0.42 * shade, 0.22 * shade, 1.0]
        }
    })
}

/// Linear specular reflectance: the steel shines, the wood barely, the grooves not at all.
pub fn crate_specular() -> Image {
    image(TextureFormat::Rgba8Unorm, |x, y| {
        let value = match part(x, y) {
            Part::Steel { .. } => 0.9,
            Part::Wood { groove, .. } if groove != 0.0 => 0.0,
            Part::Wood { .. } => 0.08,
        };
        [value, value, value, 1.0]
    })
}

/// Tangent-space normals, encoded `(n + 1) / 2`: flat, tilted across the grooves and the
/// frame's bevel.
pub fn crate_normal_map() -> Image {
    image(TextureFormat::Rgba8Unorm, |x, y| {
        let (tilt_x, tilt_y) = match part(x, y) {
            Part::Steel { bevel } => (0.8 * bevel.0, -0.8 * bevel.1),
            Part::Wood { groove, .. } => (0.0, -0.9 * groove),
        };
        let length = (tilt_x * tilt_x + tilt_y * tilt_y + 1.0).sqrt();
        let n = [tilt_x / length, tilt_y / length, 1.0 / length];
        [
            (n[0] + 1.0) / 2.0,
            (n[1] + 1.0) / 2.0,
            (n[2] + 1.0) / 2.0,
            1.0,
        ]
    })
}
