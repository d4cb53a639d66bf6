//! [`PhongStandardMaterialPlugin`]: every mesh a game draws with Bevy's `StandardMaterial`
//! drawn with a [`PhongMaterial`] instead.

use crate::{
    material::{
        PhongMaterial, Unmapped, converted_standard_material, unmapped_standard_features,
        warn_unmapped,
    },
    schedule::PhongSystems,
};
use bevy::{
    app::{App, Plugin, PostUpdate},
    asset::{AssetEvent, AssetId, Assets, Handle},
    ecs::{
        entity::Entity,
        message::MessageReader,
        resource::Resource,
        schedule::IntoScheduleConfigs,
        system::{Commands, Query, Res, ResMut},
    },
    pbr::{MeshMaterial3d, StandardMaterial},
    platform::collections::HashMap,
};

/// Switches every `MeshMaterial3d<StandardMaterial>` to a `MeshMaterial3d<PhongMaterial>` made
/// by [`PhongMaterial::from`] (the mapping and what it leaves out are documented there), in
/// the frame the mesh is spawned, before it is drawn.
///
/// - Meshes that share a `StandardMaterial` share its Phong material: each is converted once.
/// - A `StandardMaterial` still loading (a glTF file's, say) is converted when it arrives.
/// - A `StandardMaterial` changed later (through a handle the game kept) changes its Phong
///   material one frame later (when Bevy has sent the change's asset event).
/// - A warning names each material that has fields without a Phong counterpart.
///
/// Add it after [`PhongPlugin`](crate::PhongPlugin). Bevy's lights light Phong materials once
/// [`PhongBevyLightsPlugin`](crate::PhongBevyLightsPlugin) mirrors them: an existing scene
/// switches with
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_phong::prelude::*;
///
/// App::new().add_plugins((
///     DefaultPlugins,
///     PhongPlugin,
///     PhongStandardMaterialPlugin,
///     PhongBevyLightsPlugin,
/// ));
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct PhongStandardMaterialPlugin;

impl Plugin for PhongStandardMaterialPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<SwitchedMaterials>().add_systems(
            PostUpdate,
            (follow_standard_materials, switch_standard_materials)
                .chain()
                .before(PhongSystems::Validate),
        );
    }
}

/// The Phong material made for each `StandardMaterial`, kept until the `StandardMaterial` is
/// removed, and what its last warning listed.
#[derive(Resource, Default)]
struct SwitchedMaterials {
    phong_of: HashMap<AssetId<StandardMaterial>, Handle<PhongMaterial>>,
    warned: HashMap<AssetId<StandardMaterial>, Vec<Unmapped>>,
}

impl SwitchedMaterials {
    /// `source` as a Phong material; warns about what it leaves out the first time, and
    /// again only where a change of the material changes that list (Bevy sends a material
    /// loaded with its textures as changed: it is converted twice, warned once).
    fn convert(
        &mut self,
        id: AssetId<StandardMaterial>,
        source: &StandardMaterial,
    ) -> PhongMaterial {
        let unmapped = unmapped_standard_features(source);
        if self.warned.get(&id) != Some(&unmapped) {
            warn_unmapped(&label(id), &unmapped);
            self.warned.insert(id, unmapped);
        }
        converted_standard_material(source)
    }
}

/// The label the conversion's warning names a material by.
fn label(id: AssetId<StandardMaterial>) -> String {
    format!("StandardMaterial {id}")
}

/// Converts a changed `StandardMaterial` again into the Phong material made for it, and
/// forgets a removed one.
fn follow_standard_materials(
    mut events: MessageReader<AssetEvent<StandardMaterial>>,
    standard: Res<Assets<StandardMaterial>>,
    mut phong: ResMut<Assets<PhongMaterial>>,
    mut switched: ResMut<SwitchedMaterials>,
) {
    for event in events.read() {
        match *event {
            AssetEvent::Modified { id } => {
                let (Some(handle), Some(source)) = (switched.phong_of.get(&id), standard.get(id))
                else {
                    continue;
                };
                let handle = handle.clone();
                if let Some(mut material) = phong.get_mut(&handle) {
                    *material = switched.convert(id, source);
                }
            }
            AssetEvent::Removed { id } => {
                switched.phong_of.remove(&id);
                switched.warned.remove(&id);
            }
            _ => {}
        }
    }
}

/// Gives each mesh drawn with a loaded `StandardMaterial` that material's Phong material in
/// its place.
fn switch_standard_materials(
    mut commands: Commands,
    meshes: Query<(Entity, &MeshMaterial3d<StandardMaterial>)>,
    standard: Res<Assets<StandardMaterial>>,
    mut phong: ResMut<Assets<PhongMaterial>>,
    mut switched: ResMut<SwitchedMaterials>,
) {
    for (entity, material) in &meshes {
        let id = material.id();
        let handle = match switched.phong_of.get(&id) {
            Some(handle) => handle.clone(),
            None => {
                // Not loaded yet: the mesh keeps its material until it is.
                let Some(source) = standard.get(id) else {
                    continue;
                };
                let handle = phong.add(switched.convert(id, source));
                switched.phong_of.insert(id, handle.clone());
                handle
            }
        };
        commands
            .entity(entity)
            .remove::<MeshMaterial3d<StandardMaterial>>()
            .insert(MeshMaterial3d(handle));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_app::test_app;
    use bevy::{color::Color, prelude::*};

    fn switching_app() -> App {
        test_app(|app| {
            app.init_asset::<StandardMaterial>()
                .add_plugins(PhongStandardMaterialPlugin);
        })
    }

    fn phong_handle(app: &App, entity: Entity) -> Handle<PhongMaterial> {
        let entity = app.world().entity(entity);
        assert!(
            !entity.contains::<MeshMaterial3d<StandardMaterial>>(),
            "the StandardMaterial is gone from the mesh"
        );
        entity
            .get::<MeshMaterial3d<PhongMaterial>>()
            .expect("the mesh is drawn with a PhongMaterial")
            .0
            .clone()
    }

    #[test]
    fn meshes_sharing_a_standard_material_share_one_phong_material() {
        let mut app = switching_app();
        let world = app.world_mut();
        let mut standard = world.resource_mut::<Assets<StandardMaterial>>();
        let red = standard.add(StandardMaterial::from(Color::linear_rgb(1.0, 0.0, 0.0)));
        let blue = standard.add(StandardMaterial::from(Color::linear_rgb(0.0, 0.0, 1.0)));
        let spawned: Vec<Entity> = [&red, &red, &blue]
            .map(|material| world.spawn(MeshMaterial3d(material.clone())).id())
            .into();
        app.update();
        let [a, b, c] = [0, 1, 2].map(|i| phong_handle(&app, spawned[i]));
        assert_eq!(a, b, "one Phong material for the two red meshes");
        assert_ne!(a, c);
        let materials = app.world().resource::<Assets<PhongMaterial>>();
        assert_eq!(materials.len(), 2, "each StandardMaterial converted once");
        assert_eq!(
            materials.get(&c).unwrap().base_color,
            Color::linear_rgb(0.0, 0.0, 1.0)
        );
    }

    #[test]
    fn a_changed_standard_material_changes_its_phong_material() {
        let mut app = switching_app();
        let world = app.world_mut();
        let source = world
            .resource_mut::<Assets<StandardMaterial>>()
            .add(StandardMaterial::default());
        let mesh = world.spawn(MeshMaterial3d(source.clone())).id();
        app.update();
        let phong = phong_handle(&app, mesh);
        app.world_mut()
            .resource_mut::<Assets<StandardMaterial>>()
            .get_mut(&source)
            .unwrap()
            .perceptual_roughness = 0.25;
        // Bevy sends the change's asset event at the end of this frame: the Phong material
        // follows in the next.
        app.update();
        app.update();
        let materials = app.world().resource::<Assets<PhongMaterial>>();
        // 0.669 / 0.25⁴ + 1.42 / 0.25² − 1.59.
        let shininess = materials.get(&phong).unwrap().shininess;
        assert!((shininess - 192.394).abs() < 1e-3, "{shininess}");
    }

    #[test]
    fn a_standard_material_not_yet_loaded_is_switched_when_it_arrives() {
        let mut app = switching_app();
        let uuid = bevy::asset::uuid::Uuid::from_u128(7);
        let handle = Handle::<StandardMaterial>::Uuid(uuid, Default::default());
        let mesh = app.world_mut().spawn(MeshMaterial3d(handle.clone())).id();
        app.update();
        assert!(
            app.world()
                .entity(mesh)
                .contains::<MeshMaterial3d<StandardMaterial>>(),
            "kept while the material is missing"
        );
        app.world_mut()
            .resource_mut::<Assets<StandardMaterial>>()
            .insert(&handle, StandardMaterial::default())
            .unwrap();
        app.update();
        phong_handle(&app, mesh);
    }
}
