//! The baked room's light map and AO map: one atlas each over the room's quads
//! ([`room::Quad::region`]), computed here as a light baker would, in closed form.
//!
//! - AO (linear, red): each quad darkened near the surfaces it meets at a right angle,
//!   `1 − 0.55 · e^(−3d)` per neighbouring surface at distance `d`;
//! - light (sRGB): a window's glow, a warm point at [`WINDOW`] falling off as
//!   `6 · max(N·L, 0) / (1 + 0.8 d²)`, shadowed by the pedestal (a ray test against its
//!   box), plus a cool sky term of about 0.06.

use crate::encoding;
use crate::room::{self, ATLAS, Quad};

/// Where the baked window light stands, and its color.
pub const WINDOW: [f64; 3] = [2.4, 1.8, 0.6];
const WINDOW_COLOR: [f64; 3] = [1.0, 0.82, 0.6];
const SKY: [f64; 3] = [0.05, 0.055, 0.07];

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Whether the segment from `from` to `to` passes through the pedestal's box (slab test).
fn blocked(from: [f64; 3], to: [f64; 3]) -> bool {
    let direction = sub(to, from);
    let (mut near, mut far) = (1e-4, 1.0 - 1e-4);
    for axis in 0..3 {
        let low = room::PEDESTAL[axis] - room::PEDESTAL_HALF;
        let high = room::PEDESTAL[axis] + room::PEDESTAL_HALF;
        if direction[axis].abs() < 1e-12 {
            if from[axis] < low || from[axis] > high {
                return false;
            }
            continue;
        }
        let a = (low - from[axis]) / direction[axis];
        let b = (high - from[axis]) / direction[axis];
        near = f64::max(near, a.min(b));
        far = f64::min(far, a.max(b));
        if near > far {
            return false;
        }
    }
    true
}

/// The ambient occlusion at `point` on a surface facing `normal`: the floor meets the walls
/// and the pedestal, the walls meet the floor and each other, the pedestal meets the floor.
fn occlusion(point: [f64; 3], normal: [f64; 3]) -> f64 {
    let [x, y, z] = point;
    let near = |distance: f64| 1.0 - 0.55 * (-3.0 * distance.max(0.0)).exp();
    let pedestal = |a: f64, b: f64| {
        let dx = (a - room::PEDESTAL[0]).abs() - room::PEDESTAL_HALF;
        let dz = (b - room::PEDESTAL[2]).abs() - room::PEDESTAL_HALF;
        (dx.max(0.0).powi(2) + dz.max(0.0).powi(2)).sqrt()
    };
    let floor = normal[1] > 0.5 && y < 1e-6;
    if floor {
        near(x + room::HALF) * near(z + room::HALF) * near(pedestal(x, z))
    } else if normal[1] > 0.5 {
        // The pedestal's top: open.
        1.0
    } else {
        let mut ao = near(y);
        if normal[2] > 0.5 && z < -room::HALF + 1e-6 {
            ao *= near(x + room::HALF);
        }
        if normal[0] > 0.5 && x < -room::HALF + 1e-6 {
            ao *= near(z + room::HALF);
        }
        ao
    }
}

/// The baked light arriving at `point` on a surface facing `normal` (linear RGB).
fn light(point: [f64; 3], normal: [f64; 3]) -> [f64; 3] {
    let to_window = sub(WINDOW, point);
    let distance = dot(to_window, to_window).sqrt();
    let cosine = dot(normal, to_window) / distance;
    let direct = if cosine <= 0.0 || blocked(point, WINDOW) {
        0.0
    } else {
        6.0 * cosine / (1.0 + 0.8 * distance * distance)
    };
    [0, 1, 2].map(|i| WINDOW_COLOR[i] * direct + SKY[i])
}

/// Every quad of the atlas: the room's and the pedestal's.
fn quads() -> Vec<Quad> {
    room::room_quads()
        .into_iter()
        .chain(room::pedestal_quads())
        .collect()
}

/// One atlas: `texel(point, normal)` at each texel of each quad's region (zeros elsewhere).
fn atlas(channels: usize, texel: impl Fn([f64; 3], [f64; 3]) -> Vec<u8>) -> Vec<u8> {
    let quads = quads();
    let mut pixels = Vec::with_capacity((ATLAS * ATLAS) as usize * channels);
    for row in 0..ATLAS {
        for column in 0..ATLAS {
            match quads.iter().find(|quad| quad.holds_texel(column, row)) {
                Some(quad) => {
                    let (s, t) = quad.texel_point(column, row);
                    pixels.extend(texel(quad.point(s, t), quad.normal()));
                }
                None => pixels.extend(vec![0; channels]),
            }
        }
    }
    pixels
}

/// The sRGB transfer function, to 8 bits.
fn srgb_byte(linear: f64) -> u8 {
    let linear = linear.clamp(0.0, 1.0);
    let encoded = if linear <= 0.003_130_8 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    };
    (encoded * 255.0).round() as u8
}

/// The light map (RGB, sRGB).
pub fn light_map() -> Vec<u8> {
    let pixels = atlas(3, |point, normal| {
        light(point, normal).map(srgb_byte).to_vec()
    });
    encoding::png(ATLAS, ATLAS, 3, &pixels)
}

/// The AO map (its red channel; linear).
pub fn ao_map() -> Vec<u8> {
    let pixels = atlas(3, |point, normal| {
        let ao = (occlusion(point, normal) * 255.0).round() as u8;
        vec![ao, ao, ao]
    });
    encoding::png(ATLAS, ATLAS, 3, &pixels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pedestal_shadows_the_floor_behind_it_from_the_window() {
        // Behind the pedestal seen from the window: blocked; beside the window: lit.
        let behind = [-0.5, 0.0, -1.5];
        assert!(blocked(behind, WINDOW));
        assert!(!blocked([2.0, 0.0, 2.0], WINDOW));
        assert_eq!(light(behind, [0.0, 1.0, 0.0]), SKY);
    }

    #[test]
    fn corners_are_darker_than_the_open_floor() {
        let up = [0.0, 1.0, 0.0];
        let corner = occlusion([-2.95, 0.0, -2.95], up);
        let open = occlusion([2.5, 0.0, 2.5], up);
        assert!(corner < 0.3 && open > 0.95, "{corner} {open}");
    }
}
