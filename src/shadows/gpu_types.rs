//! The GPU layout of the shadow views, as the shader reads them (`PhongShadowView` in
//! `bevy_phong::shaders::types`).

use bytemuck::{Pod, Zeroable};

/// One shadow map as the shader reads it (`PhongShadowView` in WGSL): 144 bytes.
///
/// A light's views are consecutive; a light record's `shadow` field holds the index of its
/// first view plus one (`0` for a light without shadows), and that first view holds the
/// count and the settings the light's views share. A directional light has one set of
/// cascades per camera, set after set, each fitted to its camera's view and marked with that
/// view's key; every set's first view holds the counts. Depth is reversed (near 1, far 0).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuShadowView {
    /// World space to the map's clip space (column-major).
    pub clip_from_world: [[f32; 4]; 4],
    /// Directional cascades: `dot(view_plane.xyz, P) + view_plane.w` is the view depth of
    /// `P` from the camera the cascades were fitted to. Zero otherwise.
    pub view_plane: [f32; 4],
    /// [`Self::ORTHOGRAPHIC`] or [`Self::PERSPECTIVE`].
    pub projection: u32,
    /// Layer of the shadow map array that holds this view.
    pub layer: u32,
    /// In the first view of a light's set: how many views the set has (cascades, or 6 cube
    /// faces).
    pub view_count: u32,
    /// The map's resolution over the array's: the part of the layer the view covers.
    pub uv_scale: f32,
    /// World size of one texel: orthographic, everywhere; perspective, at distance 1.
    pub texel_size: f32,
    /// Orthographic: world units between depth 1 and depth 0. Perspective: unused.
    pub depth_range: f32,
    /// Perspective: the near distance (depth = near / distance). Orthographic: unused.
    pub near: f32,
    /// World units the comparison point moves toward the light.
    pub depth_bias: f32,
    /// Texels the comparison point moves along the surface normal.
    pub normal_bias: f32,
    /// The light's size for soft shadows: perspective, a radius in world units;
    /// orthographic, the tangent of the angular radius. `0`: hard edges.
    pub light_size: f32,
    /// Directional cascades: the view depth where this cascade ends.
    pub cascade_far: f32,
    /// Directional cascades: the view depth where this cascade starts blending into the next.
    pub cascade_blend_start: f32,
    /// Fraction of the diffuse term left in full shadow.
    pub diffuse_in_shadow: f32,
    /// Fraction of the highlight left in full shadow.
    pub specular_in_shadow: f32,
    /// Directional cascades: the key of the camera's view they were fitted to (the view key
    /// of `render::view_key`, by which the shader finds the set of the view it draws). Zero
    /// otherwise.
    pub camera_key: u32,
    /// In the first view of a light's set: how many sets the light has, one per camera for
    /// directional cascades (each of `view_count` views), 1 otherwise.
    pub camera_count: u32,
}

/// The fixed part at the start of the shadow view buffer (`PhongShadowViews` in WGSL,
/// before its `views` array): 16 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuShadowViewsHeader {
    /// Number of views.
    pub count: u32,
    /// Unused; the array starts at a 16-byte boundary.
    pub padding: [u32; 3],
}

impl GpuShadowView {
    /// [`projection`](Self::projection) of parallel rays (directional lights, beams): depth
    /// is linear over [`depth_range`](Self::depth_range).
    pub const ORTHOGRAPHIC: u32 = 0;
    /// [`projection`](Self::projection) of rays from a point (spot lights, cube faces):
    /// depth is `near / distance` along the view axis.
    pub const PERSPECTIVE: u32 = 1;
}

const _: () = assert!(size_of::<GpuShadowView>() == 144);
const _: () = assert!(size_of::<GpuShadowViewsHeader>() == 16);
