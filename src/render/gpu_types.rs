//! The GPU layout of the light buffer, as the shader reads it (`bevy_phong::types`).
//!
//! The Rust structs here are `#[repr(C)]` plain data, written into the buffer byte for byte;
//! a test compares their sizes and field offsets with the layout naga reflects from
//! `shaders/types.wgsl`.

use bytemuck::{Pod, Zeroable};

/// One light as the shader reads it (`PhongLight` in WGSL): 80 bytes.
///
/// Every kind uses the same record; the fields a kind does not use are zero. Colors are
/// linear RGB, positions world-space; the spot cone is stored as `1 - cos`, which keeps its
/// precision for narrow cones where the cosine rounds to 1.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    /// World-space position (point, spot).
    pub position: [f32; 3],
    /// Distance past which the light is cut off; `f32::MAX` when unlimited (point, spot).
    pub range: f32,
    /// Unit vector along which the light travels (directional, spot).
    pub direction: [f32; 3],
    /// `1 - cos(outer_angle)` (spot), computed in `f64`; `-1` for an empty cone.
    pub outer_versine: f32,
    /// Diffuse intensity, linear RGB.
    pub color: [f32; 3],
    /// `1 / (cos(inner) - cos(outer))`, computed in `f64`, or `0` for a hard edge (spot).
    pub cone_scale: f32,
    /// Specular intensity, linear RGB.
    pub specular: [f32; 3],
    /// Exponent of the `cos(θ)^exponent` rim darkening (spot).
    pub spot_exponent: f32,
    /// `[constant, linear, quadratic]` distance fall-off (point, spot).
    pub decay: [f32; 3],
    /// The index of the light's first shadow view plus one, or `0` for a light that casts no
    /// shadow this frame.
    pub shadow: u32,
}

/// The fixed part at the start of the light buffer (`PhongLights` in WGSL, before its
/// `lights` array): 32 bytes.
///
/// The array that follows holds `directional_count` directional lights, then `point_count`
/// point lights and `spot_count` spot lights of unlimited reach (every fragment loops over
/// these), then `grid_point_count` point lights and `grid_spot_count` spot lights of finite
/// reach, which fragments find through the light grid ([`GpuLightGridHeader`]).
/// Shadow-casting point and spot lights are never in the grid (the grid's loop applies no
/// shadows).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLightsHeader {
    /// The ambient light, linear RGB.
    pub ambient: [f32; 3],
    /// Number of directional lights at the start of the array.
    pub directional_count: u32,
    /// Number of point lights of unlimited reach after the directional ones.
    pub point_count: u32,
    /// Number of spot lights of unlimited reach after those point lights.
    pub spot_count: u32,
    /// Number of point lights of finite reach after those spot lights (in the grid).
    pub grid_point_count: u32,
    /// Number of spot lights of finite reach at the end of the array (in the grid).
    pub grid_spot_count: u32,
}

impl GpuLightsHeader {
    /// Total number of lights in the array.
    pub fn light_count(&self) -> usize {
        (self.directional_count
            + self.point_count
            + self.spot_count
            + self.grid_point_count
            + self.grid_spot_count) as usize
    }
}

/// The fixed part at the start of the light grid buffer (`PhongLightGrid` in WGSL, before
/// its `data` array): 32 bytes. [`CELL_WORDS`](Self::CELL_WORDS) describes the array.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuLightGridHeader {
    /// World-space corner of cell `(0, 0, 0)`, the grid's minimum.
    pub origin: [f32; 3],
    /// Edge length of the cubic cells, world units.
    pub cell_size: f32,
    /// Number of cells along x, y and z; zeros when no light is in the grid.
    pub dimensions: [u32; 3],
    /// Unused; the array that follows starts at a 16-byte boundary.
    pub padding: u32,
}

impl GpuLightGridHeader {
    /// `u32` words per cell record in the array after the header: `[first, point_count,
    /// spot_count, 0]`, one record per cell (x fastest, then y, then z), then the light
    /// indices the records point into.
    pub const CELL_WORDS: u32 = 4;

    /// A grid of no cells.
    pub const EMPTY: Self = Self {
        origin: [0.0; 3],
        cell_size: 1.0,
        dimensions: [0; 3],
        padding: 0,
    };
}

impl Default for GpuLightGridHeader {
    fn default() -> Self {
        Self::EMPTY
    }
}

const _: () = assert!(size_of::<GpuLight>() == 80);
const _: () = assert!(size_of::<GpuLightsHeader>() == 32);
const _: () = assert!(size_of::<GpuLightGridHeader>() == 32);
