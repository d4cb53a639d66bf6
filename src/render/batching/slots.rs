//! The main world's part: a slot in the record array for each [`PhongMaterial`], and each
//! mesh drawn with one tagged with its slot.

use super::records_supported;
use crate::material::PhongMaterial;
use bevy::{
    asset::{AssetEvent, AssetId},
    ecs::{
        change_detection::DetectChanges,
        entity::Entity,
        message::MessageReader,
        query::Changed,
        resource::Resource,
        system::{Commands, Query, Res, ResMut},
        world::Ref,
    },
    log::warn,
    mesh::MeshTag,
    pbr::MeshMaterial3d,
    platform::collections::HashMap,
    render::renderer::RenderDevice,
};

/// Each material's slot (its record's index in the array), kept while the material
/// exists; a removed material's slot is given to the next new one.
#[derive(Resource, Default, Debug)]
pub(crate) struct MaterialSlots {
    slots: HashMap<AssetId<PhongMaterial>, u32>,
    free: Vec<u32>,
    /// One past the highest slot ever given.
    next: u32,
    /// The slots given (`Some`) and taken back (`None`) this frame, for the render world.
    changes: Vec<(AssetId<PhongMaterial>, Option<u32>)>,
}

impl MaterialSlots {
    /// The slot of `id`, given now if it has none.
    pub fn slot_of(&mut self, id: AssetId<PhongMaterial>) -> u32 {
        if let Some(&slot) = self.slots.get(&id) {
            return slot;
        }
        let slot = self.free.pop().unwrap_or_else(|| {
            self.next += 1;
            self.next - 1
        });
        self.slots.insert(id, slot);
        self.changes.push((id, Some(slot)));
        slot
    }

    /// Takes back the slot of `id`, if it has one.
    fn release(&mut self, id: AssetId<PhongMaterial>) {
        if let Some(slot) = self.slots.remove(&id) {
            self.free.push(slot);
            self.changes.push((id, None));
        }
    }

    /// Materials that hold a slot now.
    #[cfg(feature = "testing")]
    pub fn live(&self) -> usize {
        self.slots.len()
    }

    /// One past the highest slot ever given.
    #[cfg(feature = "testing")]
    pub fn given(&self) -> usize {
        self.next as usize
    }

    /// The slots given and taken back since the main world's last frame began.
    pub fn changes(&self) -> &[(AssetId<PhongMaterial>, Option<u32>)] {
        &self.changes
    }
}

/// Whether the render device draws materials from their records (see
/// [`records_supported`]); the main world holds the render device too.
pub(crate) fn records_on(device: Option<Res<RenderDevice>>) -> bool {
    device.is_some_and(|device| records_supported(&device))
}

/// A mesh drawn with a `PhongMaterial`, and its tag.
type MeshToTag = (
    Entity,
    Ref<'static, MeshMaterial3d<PhongMaterial>>,
    Option<&'static MeshTag>,
);

/// Gives every new material a slot and takes back removed ones' (from this frame's asset
/// events), and tags each mesh whose material changed with its material's slot.
///
/// Runs in `PostUpdate`, after Bevy's asset events; costs nothing in frames where no
/// material and no mesh's material changed.
pub(crate) fn tag_phong_meshes(
    mut commands: Commands,
    mut slots: ResMut<MaterialSlots>,
    mut events: MessageReader<AssetEvent<PhongMaterial>>,
    meshes: Query<MeshToTag, Changed<MeshMaterial3d<PhongMaterial>>>,
) {
    slots.changes.clear();
    for event in events.read() {
        match *event {
            AssetEvent::Added { id } | AssetEvent::Modified { id } => {
                slots.slot_of(id);
            }
            AssetEvent::Removed { id } => slots.release(id),
            AssetEvent::Unused { .. } | AssetEvent::LoadedWithDependencies { .. } => {}
        }
    }
    for (entity, material, tag) in &meshes {
        let slot = slots.slot_of(material.id());
        let Some(old) = tag.map(|tag| tag.value) else {
            commands.entity(entity).insert(MeshTag::new(slot));
            continue;
        };
        if old != slot {
            if material.is_added() {
                warn!(
                    "entity {entity}: its MeshTag({old}) is replaced by its PhongMaterial's \
                     record slot ({slot}): bevy_phong tags the meshes drawn with a \
                     PhongMaterial (tag them through a material of your own instead)"
                );
            }
            commands.entity(entity).insert(MeshTag::new(slot));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::batching::tests::material_id as id;

    #[test]
    fn a_material_keeps_its_slot_and_a_removed_ones_slot_is_given_again() {
        let mut slots = MaterialSlots::default();
        assert_eq!(slots.slot_of(id(1)), 0);
        assert_eq!(slots.slot_of(id(2)), 1);
        assert_eq!(slots.slot_of(id(1)), 0, "asked again: the same slot");
        slots.release(id(1));
        assert_eq!(slots.slot_of(id(3)), 0, "the freed slot, not a new one");
        assert_eq!(slots.slot_of(id(4)), 2);
        assert_eq!(
            slots.changes(),
            &[
                (id(1), Some(0)),
                (id(2), Some(1)),
                (id(1), None),
                (id(3), Some(0)),
                (id(4), Some(2)),
            ]
        );
    }
}
