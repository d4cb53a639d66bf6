//! The crate's internals that its own tests, benchmarks and harness
//! (`bevy_phong_headless`) read: GPU layouts, gather systems, the limits table, the
//! surface-inputs capture. Compiled only with the `testing` feature, which games do not
//! need; nothing here is a stable API.

pub use crate::displacement::DisplacementUniform;
pub use crate::lights::cookie_layer_texels;
pub use crate::lights::is_finite_transform;
pub use crate::material::PhongMaterialUniform;
pub use crate::reference::stylized::near_a_step;
pub use crate::render::{
    DATA_TEXTURE_MAX_TEXELS, DATA_TEXTURE_WIDTH, GpuAreaLight, GpuClustersHeader, GpuCookie,
    GpuLight, GpuLightsHeader, MaterialBatching, PhongCookies, PhongLightBuffer,
    PhongLightClusters, assign_lights_to_clusters, binds_every_map, gather_lights,
    material_batching, material_map_bindings,
};
pub use crate::shadows::{
    GpuShadowView, GpuShadowViewsHeader, MAX_SHADOW_VIEWS, PhongShadowViews, ShadowSlots,
};
pub use crate::surface_inputs::{
    SurfaceInput, SurfaceInputUniform, SurfaceInputsKey, SurfaceInputsMaterial, SurfaceInputsPlugin,
};
pub use crate::view_key::view_key;

/// The ranges and bounds every input is clamped to (the crate's `limits` module).
pub mod limits {
    pub use crate::limits::*;
}
