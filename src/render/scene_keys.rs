//! The render world's part of each Phong material's key: the app's scene variants of the
//! frame ([`SceneVariants`], extracted from the main world), set in the key of every
//! material of a type made of a [`PhongMaterial`](crate::PhongMaterial) as Bevy prepares
//! it, so that the asset a game writes holds only the material. A material is prepared
//! where it was added or modified, and every one again where the variants changed
//! ([`prepare_again_on_new_variants`](super::material_upkeep::prepare_again_on_new_variants));
//! Bevy specializes its pipelines after that, with the key set here.

use crate::{
    material::PhongSceneMaterial,
    scene_variants::{SceneKey, SceneVariants},
};
use bevy::{
    asset::AssetId,
    ecs::{
        resource::Resource,
        schedule::IntoScheduleConfigs,
        system::{Res, ResMut},
    },
    material::{MaterialProperties, key::ErasedMaterialKey},
    pbr::{MeshMaterial3d, PreparedMaterial},
    platform::collections::HashSet,
    render::{
        Render, RenderSystems,
        erased_render_asset::{ErasedRenderAssets, ExtractedAssets, prepare_erased_assets},
    },
};
use core::hash::Hash;
use std::sync::Arc;

/// The materials of type `M` extracted since their key was last set: prepared this frame,
/// or waiting for a later one (Bevy prepares a material again next frame where what it binds
/// is not uploaded yet).
#[derive(Resource)]
pub(crate) struct MaterialsToKey<M: PhongSceneMaterial> {
    ids: HashSet<AssetId<M>>,
}

impl<M: PhongSceneMaterial> Default for MaterialsToKey<M> {
    fn default() -> Self {
        Self {
            ids: HashSet::default(),
        }
    }
}

/// Notes the materials of type `M` that Bevy is about to prepare (added or modified this
/// frame), and forgets those removed.
///
/// Runs before Bevy prepares the materials of type `M`.
pub(crate) fn note_materials_to_key<M: PhongSceneMaterial>(
    extracted: Res<ExtractedAssets<MeshMaterial3d<M>>>,
    mut to_key: ResMut<MaterialsToKey<M>>,
) where
    M::Data: PartialEq + Eq + Hash + Clone,
{
    for id in &extracted.removed {
        to_key.ids.remove(id);
    }
    to_key
        .ids
        .extend(extracted.extracted.iter().map(|(id, _)| *id));
}

/// Sets the scene's variants of the frame in the key of each material of type `M` that
/// Bevy prepared (this frame, or now where an earlier frame's preparation waited).
///
/// Runs after Bevy prepares the materials of type `M`, before it specializes pipelines.
pub(crate) fn key_prepared_materials<M: PhongSceneMaterial>(
    mut to_key: ResMut<MaterialsToKey<M>>,
    variants: Res<SceneVariants>,
    mut prepared: ResMut<ErasedRenderAssets<PreparedMaterial>>,
) where
    M::Data: PartialEq + Eq + Hash + Clone,
{
    let scene = SceneKey {
        variants: *variants,
        from_records: false,
    };
    to_key.ids.retain(|&id| match prepared.get_mut(id) {
        Some(material) => {
            set_scene_key::<M>(material, &scene);
            false
        }
        None => true,
    });
}

/// Sets `scene` in the key of `material`, a prepared material of type `M`.
pub(crate) fn set_scene_key<M: PhongSceneMaterial>(
    material: &mut PreparedMaterial,
    scene: &SceneKey,
) where
    M::Data: PartialEq + Eq + Hash + Clone,
{
    let key: M::Data = material.properties.material_key.to_key();
    let key = M::with_phong_material_key(key, &|phong| phong.in_scene(scene));
    material.properties = Arc::new(with_material_key(
        &material.properties,
        ErasedMaterialKey::new(key),
    ));
}

/// `properties` with its material key replaced by `material_key` (Bevy's properties are
/// shared behind an `Arc`, and not `Clone`).
fn with_material_key(
    properties: &MaterialProperties,
    material_key: ErasedMaterialKey,
) -> MaterialProperties {
    MaterialProperties {
        render_method: properties.render_method,
        alpha_mode: properties.alpha_mode,
        mesh_pipeline_key_bits: properties.mesh_pipeline_key_bits,
        depth_bias: properties.depth_bias,
        reads_view_transmission_texture: properties.reads_view_transmission_texture,
        render_phase_type: properties.render_phase_type,
        material_layout: properties.material_layout.clone(),
        draw_functions: properties.draw_functions.clone(),
        shaders: properties.shaders.clone(),
        bindless: properties.bindless,
        base_specialize: properties.base_specialize,
        prepass_specialize: properties.prepass_specialize,
        user_specialize: properties.user_specialize,
        material_key,
        shadows_enabled: properties.shadows_enabled,
        prepass_enabled: properties.prepass_enabled,
        oit_enabled: properties.oit_enabled,
    }
}

/// Adds the two systems above for `M` to the render app's schedule.
pub(crate) fn key_materials_in_scene<M: PhongSceneMaterial>(render_app: &mut bevy::app::SubApp)
where
    M::Data: PartialEq + Eq + Hash + Clone,
{
    render_app.init_resource::<MaterialsToKey<M>>().add_systems(
        Render,
        (
            note_materials_to_key::<M>.before(prepare_erased_assets::<MeshMaterial3d<M>>),
            key_prepared_materials::<M>.after(prepare_erased_assets::<MeshMaterial3d<M>>),
        )
            .in_set(RenderSystems::PrepareAssets),
    );
}
