//! The baked room's geometry: flat quads laid out in one light map atlas (the second UV
//! set), and a ball that is not baked. glTF's frame (+Y up, metres), floats quantized.

use crate::builder::quantize;
use crate::shapes::grid_indices;
use core::f64::consts::{PI, TAU};

/// Texels a side of the light map and AO atlas.
pub const ATLAS: u32 = 128;

/// A flat rectangle `origin + s·u + t·v` (`s`, `t` in `[0, 1]`), facing `u × v`, with its
/// texels in the atlas at `region` (x, y, width, height, in texels).
#[derive(Clone, Copy, Debug)]
pub struct Quad {
    pub origin: [f64; 3],
    pub u: [f64; 3],
    pub v: [f64; 3],
    pub region: [u32; 4],
}

impl Quad {
    /// The point at `(s, t)`.
    pub fn point(&self, s: f64, t: f64) -> [f64; 3] {
        [0, 1, 2].map(|i| self.origin[i] + s * self.u[i] + t * self.v[i])
    }

    /// The unit normal, `u × v` normalized.
    pub fn normal(&self) -> [f64; 3] {
        let [a, b] = [self.u, self.v];
        let n = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let length = n.iter().map(|x| x * x).sum::<f64>().sqrt();
        n.map(|x| x / length)
    }

    /// The atlas UV of `(s, t)`: the region inset by one texel, so that bilinear filtering
    /// stays inside it.
    pub fn atlas_uv(&self, s: f64, t: f64) -> [f64; 2] {
        let [x, y, width, height] = self.region.map(f64::from);
        let size = f64::from(ATLAS);
        [
            (x + 1.0 + s * (width - 2.0)) / size,
            (y + 1.0 + t * (height - 2.0)) / size,
        ]
    }

    /// The `(s, t)` of the atlas texel `(column, row)` of this quad's region, clamped to the
    /// quad (the border texels repeat its edge).
    pub fn texel_point(&self, column: u32, row: u32) -> (f64, f64) {
        let [x, y, width, height] = self.region.map(f64::from);
        let s = (f64::from(column) + 0.5 - x - 1.0) / (width - 2.0);
        let t = (f64::from(row) + 0.5 - y - 1.0) / (height - 2.0);
        (s.clamp(0.0, 1.0), t.clamp(0.0, 1.0))
    }

    /// Whether the atlas texel `(column, row)` is in this quad's region.
    pub fn holds_texel(&self, column: u32, row: u32) -> bool {
        let [x, y, width, height] = self.region;
        (x..x + width).contains(&column) && (y..y + height).contains(&row)
    }
}

/// The room's size: the floor spans `[-HALF, HALF]` in x and z, the walls `HEIGHT` up.
pub const HALF: f64 = 3.0;
pub const HEIGHT: f64 = 3.0;
/// The pedestal: a cube of side `2 · PEDESTAL_HALF` standing on the floor at this center.
pub const PEDESTAL: [f64; 3] = [0.8, 0.5, -0.5];
pub const PEDESTAL_HALF: f64 = 0.5;

/// The floor, the back wall (z = −HALF) and the left wall (x = −HALF).
pub fn room_quads() -> [Quad; 3] {
    let size = 2.0 * HALF;
    [
        Quad {
            origin: [-HALF, 0.0, HALF],
            u: [size, 0.0, 0.0],
            v: [0.0, 0.0, -size],
            region: [0, 0, 64, 64],
        },
        Quad {
            origin: [-HALF, 0.0, -HALF],
            u: [size, 0.0, 0.0],
            v: [0.0, HEIGHT, 0.0],
            region: [64, 0, 64, 64],
        },
        Quad {
            origin: [-HALF, 0.0, HALF],
            u: [0.0, 0.0, -size],
            v: [0.0, HEIGHT, 0.0],
            region: [0, 64, 64, 64],
        },
    ]
}

/// The pedestal's five visible faces (top, +Z, −Z, +X, −X), each in a 21 × 32 cell of the
/// atlas's last quarter.
pub fn pedestal_quads() -> [Quad; 5] {
    let [cx, cy, cz] = PEDESTAL;
    let h = PEDESTAL_HALF;
    let side = 2.0 * h;
    let cell = |index: u32| [64 + 21 * (index % 3), 64 + 32 * (index / 3), 21, 32];
    [
        (
            [cx - h, cy + h, cz + h],
            [side, 0.0, 0.0],
            [0.0, 0.0, -side],
        ),
        ([cx - h, cy - h, cz + h], [side, 0.0, 0.0], [0.0, side, 0.0]),
        (
            [cx + h, cy - h, cz - h],
            [-side, 0.0, 0.0],
            [0.0, side, 0.0],
        ),
        (
            [cx + h, cy - h, cz + h],
            [0.0, 0.0, -side],
            [0.0, side, 0.0],
        ),
        ([cx - h, cy - h, cz - h], [0.0, 0.0, side], [0.0, side, 0.0]),
    ]
    .into_iter()
    .enumerate()
    .map(|(index, (origin, u, v))| Quad {
        origin,
        u,
        v,
        region: cell(index as u32),
    })
    .collect::<Vec<_>>()
    .try_into()
    .expect("five faces")
}

/// A triangle list with both UV sets and vertex colors.
#[derive(Default)]
pub struct Surface {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub uv0: Vec<[f32; 2]>,
    pub uv1: Vec<[f32; 2]>,
    pub colors: Vec<[f32; 4]>,
    pub indices: Vec<u16>,
}

impl Surface {
    /// Appends `quad` as a grid of `cells × cells` squares, its first UV set in metres / 2
    /// along `u` and `v` (for a tiling texture), its second the atlas's, each vertex colored
    /// `color(point)`.
    pub fn add_quad(&mut self, quad: &Quad, cells: usize, color: impl Fn([f64; 3]) -> [f64; 3]) {
        let first = self.positions.len() as u16;
        let length = |e: [f64; 3]| e.iter().map(|x| x * x).sum::<f64>().sqrt();
        let normal = quad.normal().map(quantize);
        for row in 0..=cells {
            for column in 0..=cells {
                let (s, t) = (column as f64 / cells as f64, row as f64 / cells as f64);
                let point = quad.point(s, t);
                self.positions.push(point.map(quantize));
                self.normals.push(normal);
                self.uv0
                    .push([s * length(quad.u) / 2.0, t * length(quad.v) / 2.0].map(quantize));
                self.uv1.push(quad.atlas_uv(s, t).map(quantize));
                let [r, g, b] = color(point);
                self.colors.push([r, g, b, 1.0].map(quantize));
            }
        }
        self.indices.extend(
            grid_indices(cells, cells)
                .into_iter()
                .map(|index| first + index),
        );
    }
}

/// A sphere of `radius` with UVs, its vertex colors `color(normal)`; no second UV set (not
/// baked).
pub fn ball(radius: f64, color: impl Fn([f64; 3]) -> [f64; 3]) -> Surface {
    const SIDES: usize = 24;
    const RINGS: usize = 16;
    let mut surface = Surface::default();
    for ring in 0..=RINGS {
        let polar = PI * ring as f64 / RINGS as f64;
        let (sin_polar, cos_polar) = polar.sin_cos();
        for side in 0..=SIDES {
            let angle = TAU * side as f64 / SIDES as f64;
            let (sin, cos) = angle.sin_cos();
            let normal = [sin_polar * cos, cos_polar, -sin_polar * sin];
            surface.positions.push(normal.map(|n| quantize(n * radius)));
            surface.normals.push(normal.map(quantize));
            surface
                .uv0
                .push([side as f64 / SIDES as f64, ring as f64 / RINGS as f64].map(quantize));
            let [r, g, b] = color(normal);
            surface.colors.push([r, g, b, 1.0].map(quantize));
        }
    }
    // Around × down = inward: flip each triangle.
    surface.indices = grid_indices(SIDES, RINGS)
        .chunks(3)
        .flat_map(|t| [t[0], t[2], t[1]])
        .collect();
    surface
}
