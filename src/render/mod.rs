//! From light entities to the GPU: the buffer layout, the gather system, and how materials
//! bind the result.
//!
//! ```text
//!  main world (PostUpdate)                      render world (Render)
//!  ─────────────────────────                    ─────────────────────────────────────
//!  light components ──validate──▶ gather_lights: records (rewritten only in frames
//!        │                          │             where a light changed)
//!  cameras (frusta) ─────────────▶ assign_lights_to_clusters: every view's clusters
//!        │                          │   (rebuilt only when a view or a clustered light
//!        │                          ▼    changed)
//!        │                  ShaderBuffer assets ──extract──▶ GpuShaderBuffer (storage)
//!        │                                                        │
//!  PhongMaterial (surface data only) ──extract──▶ prepare: bind group = the material's
//!                                                 uniform and maps + PhongSceneBindings
//!                                                        │
//!  fragment: view_key(view.frustum) ─▶ its view's record ─▶ its cluster ─▶ its lights
//! ```
//!
//! The lights live in two buffers the plugin owns, the light records and the light
//! clusters (see [`crate::culling`]). The gather system writes the records in the main world
//! only in frames where a light changed; the cluster system lists the lights of finite
//! reach in the clusters of every active 3D camera's view, in frames where a view or one of
//! those lights changed. Bevy uploads both to the render world (into the same GPU buffer
//! while its size holds). A [`PhongMaterial`](crate::PhongMaterial) holds no handle to
//! them: when Bevy prepares its bind group, [`PhongSceneBindings`] adds the plugin's
//! buffers from the render world beside the material's own uniform and texture maps.
//!
//! Bevy binds its own lights and clusters per view, in the view bind group, which a
//! material cannot extend; and WebGL2 allows no fifth bind group for a per-view one of the
//! crate's. So every view's clusters sit side by side in one buffer of the material bind
//! group, and a fragment finds its own view's by a key it computes from Bevy's view
//! uniform (see `view_key`).
//!
//! When the light count outgrows a buffer it is reallocated, which gives it a new GPU
//! buffer. Material bind groups hold the old one, so every material type registered with
//! [`add_phong_material`](crate::PhongMaterialAppExt::add_phong_material) is marked
//! modified in that same frame, and the render world uploads the new buffer before it
//! rebuilds those bind groups. Buffers grow to the next power of two and shrink below a
//! quarter, so this happens rarely.
//!
//! Where the device has too few storage buffers (WebGL2), the same bytes travel in one
//! data texture instead (`scene_texture`, read in WGSL through `bevy_phong::shaders::scene`), chosen
//! once at render startup from the device's limits; see `docs/design/webgl2.md`.

// The main world's part: from light entities and cameras to the buffers' bytes.
mod cluster_views;
mod clusters;
mod cookie_atlas;
mod cookies;
mod data_texture;
mod gather;
mod light_records;
mod light_sections;
mod scene_texture;
// Both: the byte layouts the two sides share; keeping materials on the current buffers
// (marked in the main world, ordered in the render world).
mod gpu_types;
mod material_upkeep;
mod scene_keys;
// The render world's part: binding the uploaded buffers to each material.
mod material_bindings;
// Both: materials that differ only in their numbers drawn as one batch.
mod batching;

// That every validated input reaches the light buffer and the material uniform in range.
#[cfg(test)]
mod validated_inputs_tests;
// The rectangle light through the built-in machinery.
#[cfg(test)]
mod area_light_tests;

#[cfg(any(test, feature = "testing"))]
pub use crate::light_kind::GpuAreaLight;
pub use crate::light_kind::GpuLight;
pub(crate) use batching::add_material_batching;
pub(crate) use cluster_views::ExtensionClusterSlots;
pub use cluster_views::{PhongLightClusters, assign_lights_to_clusters};
pub(crate) use clusters::{is_finite_sphere, sphere_bits};
pub(crate) use cookie_atlas::PHONG_COOKIE_ATLAS;
pub use cookies::PhongCookies;
pub(crate) use cookies::gather_cookies;
pub(crate) use cookies::{CookieRequests, request_cookies};
pub use data_texture::DATA_TEXTURE_MAX_TEXELS;
pub(crate) use data_texture::{DataTexture, DataTextureWrite, words_of};
pub use gather::{PhongLightBuffer, SharedEpsilonLights, gather_lights};
pub use gpu_types::{GpuClustersHeader, GpuLightsHeader};
pub use material_bindings::PhongSceneBindings;
pub(crate) use material_upkeep::{
    prepare_again_on_new_variants, refresh_material_bind_groups, schedule_light_buffers_before,
};
pub(crate) use scene_keys::key_materials_in_scene;
pub(crate) use scene_texture::{
    PHONG_SCENE_TEXTURE, STORAGE_BUFFERS_NEEDED, announce_scene_data_path, needs_scene_texture,
    pack_scene_texture,
};
/// For [`crate::testing`]: what the crate's own tests and benchmarks read.
#[cfg(feature = "testing")]
pub use {
    batching::{MaterialBatching, material_batching},
    data_texture::DATA_TEXTURE_WIDTH,
    gpu_types::GpuCookie,
    material_bindings::{binds_every_map, material_map_bindings},
};

use bevy::{
    asset::{Handle, uuid_handle},
    render::storage::ShaderBuffer,
};

/// The storage buffer that holds the built-in lights, bound by every
/// [`PhongMaterial`](crate::PhongMaterial) through [`PhongSceneBindings`].
pub(crate) const PHONG_LIGHT_BUFFER: Handle<ShaderBuffer> =
    uuid_handle!("6a0d3e0c-5b35-4c57-9c38-2f1b7d8a4e21");

/// The storage buffer that holds every view's light clusters of the built-in lights (see
/// [`crate::culling`]), bound by every [`PhongMaterial`](crate::PhongMaterial) through
/// [`PhongSceneBindings`].
pub(crate) const PHONG_LIGHT_CLUSTER_BUFFER: Handle<ShaderBuffer> =
    uuid_handle!("0c8f2f8e-59a4-4d0e-8d3b-6f0f4b8a9c12");
