//! A flat cost per material: `PhongMaterial`s that differ only in their numbers draw as one
//! batch, with one bind group (docs/design/material-batching.md).
//!
//! Bevy gives every material of a type that is not bindless a bind group of its own, and
//! a batch set per bind group: each batch set writes its buffers every frame, so a scene's
//! frame grew faster than its number of materials. Here the numbers leave the bind group:
//!
//! ```text
//!  main world (PostUpdate)                  render world
//!  ────────────────────────                 ──────────────────────────────────────────
//!  PhongMaterial assets ──▶ a slot each ──extract──▶ its record (uniform + displacement)
//!        │                  (MaterialSlots)          written to one storage buffer
//!        │                                           (MaterialRecordBuffer, binding 29)
//!  meshes ──▶ MeshTag(slot of their material)
//!                                           its class: key, alpha mode and maps alike
//!                                           ──▶ one shared material, prepared by Bevy's
//!                                               own code, that reads the numbers from the
//!                                               records at the instance's tag
//!                                           meshes' material instances ──▶ their class's
//! ```
//!
//! So every material of a class binds the same group and lands in the same batch set; a
//! change to one material rewrites its record and prepares its class's one bind group
//! again, whatever the number of materials. The materials themselves are still prepared by
//! Bevy (each bind group built when it changes, never drawn while its class draws it).
//!
//! Only where the device has a storage buffer to spare for the records
//! ([`records_supported`]): elsewhere (WebGL2, and WebGPU's 8 a stage) every material draws
//! with its own bind group, as before, and nothing here runs. A mesh whose material has no
//! class yet (not loaded) draws with its own material until it has one.
//!
//! The crate owns [`MeshTag`](bevy::mesh::MeshTag) on meshes drawn with a
//! [`PhongMaterial`]: a tag of the game's own there is replaced, with a warning naming the
//! entity.

mod classes;
mod records;
mod slots;

pub(crate) use records::{MaterialRecordBuffer, records_supported};

use crate::material::PhongMaterial;
use bevy::{
    app::{App, PostUpdate},
    asset::AssetEventSystems,
    ecs::schedule::IntoScheduleConfigs,
    pbr::{MaterialExtractionSystems, MeshMaterial3d},
    render::{
        ExtractSchedule, Render, RenderApp, RenderStartup, RenderSystems,
        erased_render_asset::prepare_erased_assets,
    },
};

/// What material batching did in an app's main and render worlds (for the crate's tests).
#[cfg(feature = "testing")]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MaterialBatching {
    /// Whether the device draws materials from their records (else every material draws
    /// with its own bind group, and the rest is zero).
    pub on: bool,
    /// Classes of materials (each drawn with one bind group).
    pub classes: usize,
    /// Bind groups of classes made since the app started.
    pub class_bind_groups_made: usize,
    /// Meshes drawn with their class's bind group.
    pub meshes_drawn_by_class: usize,
    /// Materials that hold a slot in the record array now.
    pub slots: usize,
    /// Slots given since the app started: one past the highest (a freed slot is given
    /// again before a new one).
    pub slots_given: usize,
    /// Records the record buffer holds room for.
    pub record_capacity: usize,
    /// The room it starts with.
    pub initial_record_capacity: usize,
}

/// [`MaterialBatching`] of `app` (zero where the device draws every material alone).
#[cfg(feature = "testing")]
pub fn material_batching(app: &App) -> MaterialBatching {
    let world = app.sub_app(RenderApp).world();
    let (Some(classes), true) = (
        world.get_resource::<classes::MaterialClasses>(),
        world.contains_resource::<MaterialRecordBuffer>(),
    ) else {
        return MaterialBatching::default();
    };
    let (count, made) = classes.counts();
    let slots = app.world().resource::<slots::MaterialSlots>();
    let meshes = world
        .resource::<bevy::pbr::RenderMaterialInstances>()
        .instances
        .values()
        .filter(|instance| classes::is_shared_material(instance.asset_id))
        .count();
    MaterialBatching {
        on: true,
        classes: count,
        class_bind_groups_made: made,
        meshes_drawn_by_class: meshes,
        slots: slots.live(),
        slots_given: slots.given(),
        record_capacity: world.resource::<MaterialRecordBuffer>().capacity(),
        initial_record_capacity: crate::storage_buffer::MIN_CAPACITY,
    }
}

/// Adds the systems of both worlds (where the app has a renderer).
pub(crate) fn add_material_batching(app: &mut App) {
    app.init_resource::<slots::MaterialSlots>().add_systems(
        PostUpdate,
        slots::tag_phong_meshes
            .run_if(slots::records_on)
            .after(AssetEventSystems),
    );
    let Some(render_app) = app.get_sub_app_mut(RenderApp) else {
        return;
    };
    render_app
        .init_resource::<classes::MaterialClasses>()
        .add_systems(RenderStartup, records::create_record_buffer)
        .add_systems(
            ExtractSchedule,
            classes::extract_material_classes
                .run_if(records::buffer_exists)
                .after(MaterialExtractionSystems),
        )
        .add_systems(
            Render,
            (records::write_records, classes::prepare_material_classes)
                .chain()
                .run_if(records::buffer_exists)
                .in_set(RenderSystems::PrepareAssets)
                .after(prepare_erased_assets::<MeshMaterial3d<PhongMaterial>>),
        );
}

#[cfg(test)]
mod tests {
    use crate::material::PhongMaterial;
    use bevy::asset::{AssetId, uuid::Uuid};

    /// A material's id for the tests of slots and classes (no asset behind it).
    pub fn material_id(index: u128) -> AssetId<PhongMaterial> {
        AssetId::Uuid {
            uuid: Uuid::from_u128(index),
        }
    }
}
