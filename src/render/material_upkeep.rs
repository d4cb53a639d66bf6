//! Keeping material bind groups on the current light buffer after it is reallocated.

use crate::material::PhongSceneMaterial;
use crate::scene_variants::SceneVariants;
use crate::storage_buffer::LightBufferResized;
use bevy::{
    asset::Assets,
    ecs::message::MessageReader,
    pbr::{Material, MeshMaterial3d},
    render::{
        erased_render_asset::prepare_erased_assets, render_asset::prepare_assets,
        storage::GpuShaderBuffer,
    },
};

/// Marks every material of type `M` as modified when a light buffer was resized this frame,
/// so that the render world rebuilds their bind groups around the new GPU buffer.
///
/// Runs in [`PhongSystems::RefreshMaterials`](crate::PhongSystems::RefreshMaterials).
pub(crate) fn refresh_material_bind_groups<M: Material>(
    mut resized: MessageReader<LightBufferResized>,
    mut materials: ResMut<Assets<M>>,
) {
    if resized.read().count() == 0 {
        return;
    }
    // `iter_mut` reports every asset it yields as modified.
    for _ in materials.iter_mut() {}
}

/// Marks every material of type `M` as modified when the app's [`SceneVariants`] changed
/// this frame, so that the render world prepares each again in the same frame, with the new
/// variant in its key (`render::scene_keys`); other frames cost nothing. The asset itself
/// is not changed: the variant lives in the render world.
///
/// Runs in [`PhongSystems::RefreshMaterials`](crate::PhongSystems::RefreshMaterials).
pub(crate) fn prepare_again_on_new_variants<M: PhongSceneMaterial>(
    variants: Res<SceneVariants>,
    mut materials: ResMut<Assets<M>>,
) {
    // The first frame's variants are those every material is first prepared with.
    if !variants.is_changed() || variants.is_added() {
        return;
    }
    // `iter_mut` reports every asset it yields as modified.
    for _ in materials.iter_mut() {}
}

/// Does nothing; it exists for its place in the render schedule: after the light buffers
/// are uploaded (`prepare_assets::<GpuShaderBuffer>`) and the shadow map array is sized,
/// and before the bind groups of `M` are
/// built (`prepare_erased_assets::<MeshMaterial3d<M>>`), which Bevy otherwise leaves
/// unordered. Without it a material rebuilt in the frame its buffer was reallocated could
/// bind the old GPU buffer.
pub(crate) fn order_after_light_buffers<M: Material>() {}

/// Adds [`order_after_light_buffers::<M>`] to the render app's schedule.
pub(crate) fn schedule_light_buffers_before<M: Material>(render_app: &mut bevy::app::SubApp)
where
    M::Data: PartialEq + Eq + core::hash::Hash + Clone,
{
    render_app.add_systems(
        bevy::render::Render,
        order_after_light_buffers::<M>
            .after(prepare_assets::<GpuShaderBuffer>)
            .after(prepare_assets::<bevy::render::texture::GpuImage>)
            .after(crate::shadows::prepare_shadow_atlas)
            .before(prepare_erased_assets::<MeshMaterial3d<M>>),
    );
}

use bevy::ecs::{
    change_detection::DetectChanges,
    schedule::IntoScheduleConfigs,
    system::{Res, ResMut},
};
