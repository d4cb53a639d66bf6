//! The GPU layout of the light buffer, as the shader reads it (`bevy_phong::shaders::types`).
//!
//! The Rust structs here are `#[repr(C)]` plain data, written into the buffer byte for byte;
//! a test compares their sizes and field offsets with the layout naga reflects from
//! `shaders/types.wesl`.

use crate::light_kind::GpuLight;
use bytemuck::{Pod, Zeroable};

/// A light's cookie as the shader reads it (`bevy_phong::shaders::cookies`): 80 bytes, the size of a
/// [`GpuLight`], stored after the lights in the light buffer (its index there in the high
/// half of its light's [`GpuLight::shadow`]). See [`PhongLightCookie`](crate::PhongLightCookie).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuCookie {
    /// The rows of the light's `local_from_world` affine transform.
    pub light_from_world: [[f32; 4]; 3],
    /// The cookie atlas's layer that holds the image.
    pub layer: u32,
    /// How the image is laid over the light ([`Self::CONE`], [`Self::PLANE`], or
    /// [`Self::CUBE`] plus the cube map layout's index).
    pub projection: u32,
    /// `tan` of a cone's half-angle (below 90°).
    pub tan_outer: f32,
    /// [`Self::RED_ONLY`], [`Self::TILED`] and [`Self::DARK_OUTSIDE`].
    pub flags: u32,
    /// Unused: the record is as long as a light's.
    pub padding: [u32; 4],
}

impl GpuCookie {
    /// A cone (`PhongCookieProjection::Cone`).
    pub const CONE: u32 = 0;
    /// A plane (`PhongCookieProjection::Plane`).
    pub const PLANE: u32 = 1;
    /// A cube map, plus the index of its `CubemapLayout` (0 to 3).
    pub const CUBE: u32 = 2;
    /// The red channel tints all three.
    pub const RED_ONLY: u32 = 1;
    /// The image repeats over a directional light's plane.
    pub const TILED: u32 = 2;
    /// An untiled directional light is dark outside its image.
    pub const DARK_OUTSIDE: u32 = 4;
}

/// The fixed part at the start of the light buffer (`PhongLights` in WGSL, before its
/// `lights` array): 64 bytes.
///
/// The array that follows holds `directional_count` directional lights, then `local_count`
/// local lights of unlimited reach (every fragment loops over these), then
/// `clustered_local_count` local lights of finite reach, which fragments find through their
/// view's clusters ([`GpuClustersHeader`]), with their shadows and cookies; then the area
/// lights the same way, `area_count` then `clustered_area_count`
/// ([`GpuAreaLight`](crate::light_kind::GpuAreaLight) records in a light's place). A local light
/// shines from a position and fades with distance: a point light is a local light whose cone
/// is the whole sphere, a spot light one with its cone (see
/// [`GpuLight`](crate::light_kind::GpuLight)); one loop lights both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLightsHeader {
    /// The ambient light plus the mean of the hemisphere light's sky and ground colors, linear
    /// RGB: the light a surface receives from them without its `N·up` share.
    pub ambient: [f32; 3],
    /// Number of directional lights at the start of the array.
    pub directional_count: u32,
    /// Number of local lights of unlimited reach after the directional ones.
    pub local_count: u32,
    /// Number of local lights of finite reach after those (clustered).
    pub clustered_local_count: u32,
    /// Number of area lights ([`GpuAreaLight`](crate::light_kind::GpuAreaLight)) of
    /// unlimited reach after the local lights.
    pub area_count: u32,
    /// Number of area lights of finite reach at the end of the array (clustered).
    pub clustered_area_count: u32,
    /// The hemisphere light's unit `up` direction (zero without one).
    pub hemisphere_up: [f32; 3],
    /// The share of each view's Bevy ambient light (Bevy's `lights.ambient_color`, the
    /// camera's `AmbientLight` or else `GlobalAmbientLight`) added to `ambient` in that view:
    /// the Bevy-light mirror's exposure factor, `0` without the mirror.
    pub bevy_ambient_scale: f32,
    /// Half the hemisphere light's sky color minus its ground color, linear RGB: what
    /// `N·up` scales (zero without one).
    pub hemisphere_half_difference: [f32; 3],
    /// Unused.
    pub padding_difference: u32,
}

/// The fixed part at the start of the light cluster buffer (`PhongLightClusters` in WGSL,
/// before its `data` array): 16 bytes. The array holds [`VIEW_WORDS`](Self::VIEW_WORDS)
/// words per view, then `cluster_words` per cluster of each view, then the entries;
/// `render::clusters` describes them.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuClustersHeader {
    /// Number of views whose clusters the data holds; 0 when no light is clustered (or no
    /// camera renders).
    pub view_count: u32,
    /// `u32` words per cluster record: one per slot of lights, one more for the end of the
    /// last, padded to a multiple of 4 (4 for the built-in lights alone).
    pub cluster_words: u32,
    /// Unused; the array that follows starts at a 16-byte boundary.
    pub padding: [u32; 2],
}

impl GpuClustersHeader {
    /// `u32` words per view record: `[key, first, tiles_x, tiles_y, slices, logarithmic,
    /// depth_scale, depth_bias]`.
    pub const VIEW_WORDS: u32 = 8;

    /// No views, no clusters.
    pub const EMPTY: Self = Self {
        view_count: 0,
        cluster_words: 4,
        padding: [0; 2],
    };
}

impl Default for GpuClustersHeader {
    fn default() -> Self {
        Self::EMPTY
    }
}

const _: () = assert!(size_of::<GpuLight>() == 80);
const _: () = assert!(size_of::<GpuCookie>() == size_of::<GpuLight>());
const _: () = assert!(size_of::<GpuLightsHeader>() == 64);
const _: () = assert!(size_of::<GpuClustersHeader>() == 16);
