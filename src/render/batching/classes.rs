//! The render world's part: each material's class (the materials that can share one bind
//! group), the class's shared material, and the meshes pointed at it.

use super::records::{MaterialRecord, MaterialRecordBuffer, RecordBufferReplaced};
use super::slots::MaterialSlots;
use crate::material::{PhongMaterial, PhongMaterialKey, map_images};
use crate::render::scene_keys::set_scene_key;
use crate::scene_variants::{SceneKey, SceneVariants};
use bevy::asset::uuid::Uuid;
use bevy::{
    asset::{AssetEvent, AssetId, Assets, Handle},
    camera::visibility::ViewVisibility,
    ecs::{
        entity::Entity,
        message::MessageReader,
        query::{Changed, Or},
        resource::Resource,
        system::{Query, Res, ResMut, StaticSystemParam, SystemParam},
    },
    image::Image,
    pbr::{MeshMaterial3d, PreparedMaterial, RenderMaterialInstances},
    platform::collections::{HashMap, HashSet},
    prelude::AlphaMode,
    render::{
        Extract,
        erased_render_asset::{ErasedRenderAsset, ErasedRenderAssets, PrepareAssetError},
        sync_world::MainEntity,
    },
};

/// What materials of one class have alike: everything but the numbers of their records.
/// Their shader variant (key), their alpha mode (it chooses the render phase) and their
/// maps (the bind group's textures).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct ClassKey {
    key: PhongMaterialKey,
    /// The alpha mode's variant and its cutoff's bits (for `Mask`).
    alpha_mode: (u8, u32),
    maps: Vec<Option<AssetId<Image>>>,
}

impl From<&PhongMaterial> for ClassKey {
    fn from(material: &PhongMaterial) -> Self {
        let alpha_mode = match material.alpha_mode {
            AlphaMode::Opaque => (0, 0),
            AlphaMode::Mask(cutoff) => (1, cutoff.to_bits()),
            AlphaMode::Blend => (2, 0),
            AlphaMode::Premultiplied => (3, 0),
            AlphaMode::AlphaToCoverage => (4, 0),
            AlphaMode::Add => (5, 0),
            AlphaMode::Multiply => (6, 0),
        };
        Self {
            key: material.into(),
            alpha_mode,
            maps: map_images(material)
                .into_iter()
                .map(|image| image.map(Handle::id))
                .collect(),
        }
    }
}

/// A class: its shared material (one of its members', prepared under an id of its own with
/// [`SceneKey::from_records`] in its key) and how many materials it has.
struct Class {
    id: AssetId<PhongMaterial>,
    material: PhongMaterial,
    members: usize,
    /// Whether its bind group is to be (made) again this frame.
    to_prepare: bool,
}

/// The classes, each material's, and what the render world has yet to do for them.
#[derive(Resource, Default)]
pub(crate) struct MaterialClasses {
    /// Each material's slot, as the main world gave them.
    slots: HashMap<AssetId<PhongMaterial>, u32>,
    classes: HashMap<ClassKey, Class>,
    class_of: HashMap<AssetId<PhongMaterial>, ClassKey>,
    /// Shared materials whose class has no member left, to unload.
    to_unload: Vec<AssetId<PhongMaterial>>,
    /// Classes made so far: each gets the next id.
    made: u64,
    /// Bind groups of shared materials made since the app started.
    prepared: usize,
}

impl MaterialClasses {
    /// Marks every class's bind group to be made again (the record buffer was replaced).
    fn prepare_all_again(&mut self) {
        for class in self.classes.values_mut() {
            class.to_prepare = true;
        }
    }

    /// The shared material that draws `material`, if it has a class.
    fn shared_material_of(
        &self,
        material: AssetId<PhongMaterial>,
    ) -> Option<AssetId<PhongMaterial>> {
        let key = self.class_of.get(&material)?;
        Some(self.classes.get(key)?.id)
    }

    /// Files `id` (a material now as `material`) in its class, making the class where it is
    /// new; its class's bind group is made again. Returns whether its class changed.
    fn file(&mut self, id: AssetId<PhongMaterial>, material: &PhongMaterial) -> bool {
        let key = ClassKey::from(material);
        let moved = self.class_of.get(&id) != Some(&key);
        if moved {
            self.leave(id);
            let made = &mut self.made;
            let class = self.classes.entry(key.clone()).or_insert_with(|| {
                *made += 1;
                Class {
                    id: AssetId::Uuid {
                        uuid: Uuid::from_u64_pair(SHARED_MATERIAL_IDS, *made),
                    },
                    material: material.clone(),
                    members: 0,
                    to_prepare: true,
                }
            });
            class.members += 1;
            self.class_of.insert(id, key.clone());
        }
        // Also where only numbers changed: a material is modified when the scene's buffers
        // it binds were replaced, and its class binds them too.
        if let Some(class) = self.classes.get_mut(&key) {
            class.to_prepare = true;
        }
        moved
    }

    /// Takes `id` out of its class; a class left empty is unloaded.
    fn leave(&mut self, id: AssetId<PhongMaterial>) {
        let Some(key) = self.class_of.remove(&id) else {
            return;
        };
        if let Some(class) = self.classes.get_mut(&key) {
            class.members -= 1;
            if class.members == 0 {
                self.to_unload.push(class.id);
                self.classes.remove(&key);
            }
        }
    }

    /// How many classes there are, and how many bind groups of shared materials were made
    /// since the app started.
    #[cfg(feature = "testing")]
    pub fn counts(&self) -> (usize, usize) {
        (self.classes.len(), self.prepared)
    }
}

/// The high 64 bits of every shared material's id (the low ones count the classes made).
const SHARED_MATERIAL_IDS: u64 = 0x6265_7679_5f70_686f;

/// Whether `id` is a class's shared material.
#[cfg(feature = "testing")]
pub(crate) fn is_shared_material(id: bevy::asset::UntypedAssetId) -> bool {
    matches!(id, bevy::asset::UntypedAssetId::Uuid { uuid, .. } if uuid.as_u64_pair().0 == SHARED_MATERIAL_IDS)
}

/// Extraction: the slots given and taken back, the records and classes of the materials
/// added or changed this frame (removed ones leave theirs), and each mesh whose material
/// instance Bevy extracted, or whose material moved to another class, pointed at its
/// material's shared one.
///
/// Runs after Bevy extracts the material instances; iterates over every mesh only in frames
/// where some material moved to a class (added, or changed in its key or maps).
pub(crate) fn extract_material_classes(
    mut classes: ResMut<MaterialClasses>,
    mut records: ResMut<MaterialRecordBuffer>,
    mut instances: ResMut<RenderMaterialInstances>,
    slots: Extract<Res<MaterialSlots>>,
    materials: Extract<Res<Assets<PhongMaterial>>>,
    mut events: Extract<MessageReader<AssetEvent<PhongMaterial>>>,
    meshes: PhongMeshes,
) {
    for &(id, slot) in slots.changes() {
        match slot {
            Some(slot) => classes.slots.insert(id, slot),
            None => classes.slots.remove(&id),
        };
    }
    let mut moved = HashSet::new();
    for event in events.read() {
        match *event {
            AssetEvent::Added { id } | AssetEvent::Modified { id } => {
                let (Some(material), Some(&slot)) = (materials.get(id), classes.slots.get(&id))
                else {
                    continue;
                };
                records.queue(slot, MaterialRecord::from(material));
                if classes.file(id, material) {
                    moved.insert(id);
                }
            }
            AssetEvent::Removed { id } => classes.leave(id),
            AssetEvent::Unused { .. } | AssetEvent::LoadedWithDependencies { .. } => {}
        }
    }
    let mut point = |entity: Entity, material: AssetId<PhongMaterial>| {
        if let (Some(instance), Some(shared)) = (
            instances.instances.get_mut(&MainEntity::from(entity)),
            classes.shared_material_of(material),
        ) {
            instance.asset_id = shared.untyped();
        }
    };
    for (entity, visibility, material) in &meshes.extracted_again {
        if visibility.get() {
            point(entity, material.id());
        }
    }
    if !moved.is_empty() {
        for (entity, material) in &meshes.all {
            if moved.contains(&material.id()) {
                point(entity, material.id());
            }
        }
    }
}

/// The main world's meshes drawn with a `PhongMaterial`: those whose material instance Bevy
/// extracts again this frame, and all of them.
#[derive(SystemParam)]
pub(crate) struct PhongMeshes<'w, 's> {
    extracted_again:
        Extract<'w, 's, Query<'static, 'static, ExtractedMesh, MaterialInstanceExtracted>>,
    all: Extract<'w, 's, Query<'static, 'static, (Entity, &'static MeshMaterial3d<PhongMaterial>)>>,
}

/// A mesh drawn with a `PhongMaterial`: what Bevy's extraction of material instances reads.
type ExtractedMesh = (
    Entity,
    &'static ViewVisibility,
    &'static MeshMaterial3d<PhongMaterial>,
);

/// When Bevy extracts a mesh's material instance again.
type MaterialInstanceExtracted = Or<(
    Changed<ViewVisibility>,
    Changed<MeshMaterial3d<PhongMaterial>>,
)>;

/// The parameters with which Bevy prepares a `PhongMaterial`.
type PrepareParam = <MeshMaterial3d<PhongMaterial> as ErasedRenderAsset>::Param;

/// Unloads the shared materials of classes left empty and prepares (again) those marked,
/// and every class where the record buffer was replaced, through Bevy's own preparation of
/// a material: a class that cannot be prepared yet (the scene's buffers not uploaded) is
/// tried again next frame.
///
/// Runs after Bevy prepares the materials of the frame and the records are written.
pub(crate) fn prepare_material_classes(
    mut classes: ResMut<MaterialClasses>,
    mut replaced: ResMut<RecordBufferReplaced>,
    mut prepared: ResMut<ErasedRenderAssets<PreparedMaterial>>,
    mut param: StaticSystemParam<PrepareParam>,
    variants: Res<SceneVariants>,
) {
    let scene = SceneKey {
        variants: *variants,
        from_records: true,
    };
    let classes = &mut *classes;
    if replaced.take() {
        classes.prepare_all_again();
    }
    for id in classes.to_unload.drain(..) {
        prepared.remove(id);
        <MeshMaterial3d<PhongMaterial> as ErasedRenderAsset>::unload_asset(id, &mut param);
    }
    for class in classes
        .classes
        .values_mut()
        .filter(|class| class.to_prepare)
    {
        match <MeshMaterial3d<PhongMaterial> as ErasedRenderAsset>::prepare_asset(
            class.material.clone(),
            class.id,
            &mut param,
        ) {
            Ok(mut material) => {
                set_scene_key::<PhongMaterial>(&mut material, &scene);
                prepared.insert(class.id, material);
                class.to_prepare = false;
                classes.prepared += 1;
            }
            Err(PrepareAssetError::RetryNextUpdate(_)) => {}
            Err(error) => {
                bevy::log::error!("bevy_phong: a shared material was not prepared: {error}");
                class.to_prepare = false;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::batching::tests::material_id as id;
    use bevy::color::Color;

    #[test]
    fn materials_that_differ_in_numbers_share_a_class_and_others_do_not() {
        let mut classes = MaterialClasses::default();
        let red = PhongMaterial {
            base_color: Color::linear_rgb(1.0, 0.0, 0.0),
            shininess: 10.0,
            ..Default::default()
        };
        let blue = PhongMaterial {
            base_color: Color::linear_rgb(0.0, 0.0, 1.0),
            shininess: 70.0,
            specular_model: crate::SpecularModel::BlinnPhong,
            ..Default::default()
        };
        let textured = PhongMaterial {
            base_color_texture: Some(Handle::default()),
            ..red.clone()
        };
        let masked = PhongMaterial {
            alpha_mode: AlphaMode::Mask(0.5),
            ..red.clone()
        };
        let other_texture = PhongMaterial {
            base_color_texture: Some(Handle::Uuid(Uuid::from_u128(7), Default::default())),
            ..red.clone()
        };
        assert!(
            classes.file(id(1), &red),
            "a new material moves into a class"
        );
        assert!(classes.file(id(2), &blue));
        assert_eq!(classes.classes.len(), 1, "numbers only: one class");
        assert_eq!(
            classes.shared_material_of(id(1)),
            classes.shared_material_of(id(2))
        );
        assert!(classes.file(id(3), &textured));
        assert!(classes.file(id(4), &masked));
        assert!(classes.file(id(5), &other_texture));
        assert_eq!(
            classes.classes.len(),
            4,
            "a map, another image in it and an alpha mode: a class each"
        );
        assert!(
            !classes.file(id(2), &red),
            "changed numbers: the same class, no mesh to re-point"
        );
        assert!(
            classes.file(id(2), &masked),
            "another alpha mode: another class"
        );
        assert_eq!(classes.classes.len(), 4);
    }

    #[test]
    fn a_class_left_without_materials_is_unloaded() {
        let mut classes = MaterialClasses::default();
        let material = PhongMaterial::default();
        classes.file(id(1), &material);
        classes.file(id(2), &material);
        let shared = classes.shared_material_of(id(1)).unwrap();
        classes.leave(id(1));
        assert!(classes.to_unload.is_empty(), "one material left");
        classes.leave(id(2));
        assert_eq!(classes.to_unload, vec![shared]);
        assert!(classes.classes.is_empty());
        assert_eq!(classes.shared_material_of(id(2)), None);
    }
}
