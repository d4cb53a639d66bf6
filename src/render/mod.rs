//! From light entities to the GPU: the buffer layout, the gather system and the upkeep that
//! keeps material bind groups pointing at the current buffer.
//!
//! The lights live in a [`ShaderBuffer`] asset ([`PHONG_LIGHT_BUFFER`]) that every
//! [`PhongMaterial`](crate::PhongMaterial) binds, beside the light grid
//! ([`PHONG_LIGHT_GRID_BUFFER`], see [`crate::culling`]). The main world owns its bytes: the gather
//! system rewrites them in place only in frames where a light changed, and Bevy uploads the
//! asset to the GPU when it is modified (into the same GPU buffer while its size holds).
//! This keeps the crate on Bevy's public asset path (no render-graph node, no render-world
//! buffer of its own) and lets extensions bind the same buffer from their own materials.
//!
//! When the light count outgrows the buffer it is reallocated, which gives it a new GPU
//! buffer. Material bind groups hold the old one, so [`refresh_material_bind_groups`] marks
//! every material of the affected types as modified in that same frame, and
//! [`order_after_light_buffers`] makes the render world prepare the new buffer before it
//! rebuilds those bind groups.

mod gather;
mod gpu_types;
mod light_buffer;
mod light_grid;
mod light_records;
mod material_upkeep;

pub use gather::{
    LightChanged, LightChanges, LightQuery, PhongLightBuffer, gather_lights, push_visible,
};
pub use gpu_types::{GpuLight, GpuLightGridHeader, GpuLightsHeader};
pub(crate) use light_buffer::init_shader_buffers;
pub use light_buffer::{LightBuffer, LightBufferResized, MIN_CAPACITY};
pub use light_grid::{CELL_WORDS, LightGrid, MAX_CELLS, MAX_CELLS_PER_AXIS, has_finite_reach};
pub use light_records::{light_direction, limit_reach, linear_rgb, spot_cone_terms};
pub(crate) use material_upkeep::schedule_light_buffers_before;
pub use material_upkeep::{order_after_light_buffers, refresh_material_bind_groups};

use bevy::{
    asset::{Handle, uuid_handle},
    render::storage::ShaderBuffer,
};

/// The storage buffer that holds the built-in lights, bound by every
/// [`PhongMaterial`](crate::PhongMaterial) (its `lights` field).
pub const PHONG_LIGHT_BUFFER: Handle<ShaderBuffer> =
    uuid_handle!("6a0d3e0c-5b35-4c57-9c38-2f1b7d8a4e21");

/// The storage buffer that holds the light grid of the built-in lights (see
/// [`crate::culling`]), bound by every [`PhongMaterial`](crate::PhongMaterial) (its
/// `light_grid` field).
pub const PHONG_LIGHT_GRID_BUFFER: Handle<ShaderBuffer> =
    uuid_handle!("0c8f2f8e-59a4-4d0e-8d3b-6f0f4b8a9c12");
