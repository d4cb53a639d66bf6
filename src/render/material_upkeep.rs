//! Keeping material bind groups on the current light buffer after it is reallocated.

use crate::material::PhongSceneMaterial;
use crate::scene_variants::SceneVariants;
use crate::storage_buffer::LightBufferResized;
use bevy::{
    asset::{AssetId, Assets},
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

/// Keeps the scene's shader variant of every material of type `M` made of a
/// [`PhongMaterial`](crate::PhongMaterial) equal to the app's [`SceneVariants`]: a material
/// that differs (one just added or replaced, or every one where the scene's variant changed
/// this frame) is modified; frames where neither the variant nor `M`'s assets changed cost
/// nothing. The render world prepares each modified one again, with the new key, in the
/// same frame. The variant travels with the material's extraction: each app has its own,
/// and the render world reads the one of the frame it draws.
///
/// Runs in [`PhongSystems::RefreshMaterials`](crate::PhongSystems::RefreshMaterials).
pub(crate) fn carry_scene_variants<M: PhongSceneMaterial>(
    variants: Res<SceneVariants>,
    mut materials: ResMut<Assets<M>>,
) {
    // Only a new variant, or a material added or changed since the last run, can differ.
    if !variants.is_changed() && !materials.is_changed() {
        return;
    }
    let stale: Vec<AssetId<M>> = materials
        .iter()
        .filter(|(_, material)| {
            material
                .phong_material()
                .is_some_and(|phong| phong.scene_variants != *variants)
        })
        .map(|(id, _)| id)
        .collect();
    for id in stale {
        if let Some(mut material) = materials.get_mut(id)
            && let Some(phong) = material.phong_material_mut()
        {
            phong.scene_variants = *variants;
        }
    }
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
