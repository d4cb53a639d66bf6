//! Spawning a loaded scene under a [`PhongSceneRoot`], and again whenever its file changes.

use super::{PhongScene, SceneLight};
use crate::lights::PhongAmbientLight;
use bevy::{
    asset::{AssetEvent, AssetId, Assets, Handle},
    camera::{Camera3d, PerspectiveProjection, Projection},
    ecs::prelude::*,
    log::info,
    mesh::Mesh3d,
    pbr::MeshMaterial3d,
    reflect::Reflect,
    transform::components::Transform,
};

/// Spawns the scene of a `*.phong_scene.ron` file as children of this entity once it has
/// loaded, and spawns it again each time the file is reloaded (hot reload, with Bevy's
/// `file_watcher` feature). A file that fails to load leaves the last good scene in place;
/// the asset server logs the error with its line and column.
///
/// ```no_run
/// # use bevy::prelude::*;
/// # use bevy_phong::prelude::*;
/// fn setup(mut commands: Commands, assets: Res<AssetServer>) {
///     commands.spawn(PhongSceneRoot(assets.load("scenes/showcase.phong_scene.ron")));
/// }
/// ```
///
/// The scene's camera (if it has one) is spawned with [`PhongSceneCamera`]; its ambient
/// light replaces the [`PhongAmbientLight`] resource, and its hemisphere light (if it has
/// one) is inserted as the [`PhongHemisphereLight`](crate::PhongHemisphereLight) resource.
#[derive(Component, Clone, Debug, Default, Reflect)]
#[require(Transform, bevy::camera::visibility::Visibility)]
pub struct PhongSceneRoot(pub Handle<PhongScene>);

/// Marks the camera a [`PhongSceneRoot`] spawned from its file.
#[derive(Component, Clone, Copy, Debug, Default, Reflect)]
pub struct PhongSceneCamera;

/// Marks a [`PhongSceneRoot`] whose scene has been spawned, with the version it spawned.
#[derive(Component)]
pub(crate) struct SpawnedScene(AssetId<PhongScene>);

/// Spawns scenes as soon as their file has loaded (materials and textures it names may
/// follow), and respawns those whose file changed (`AssetEvent::Modified`, which a hot
/// reload sends; a failed reload sends none).
pub(crate) fn spawn_phong_scenes(
    mut commands: Commands,
    mut events: MessageReader<AssetEvent<PhongScene>>,
    scenes: Res<Assets<PhongScene>>,
    roots: Query<(
        Entity,
        &PhongSceneRoot,
        Option<&SpawnedScene>,
        Option<&Children>,
    )>,
    mut ambient: ResMut<PhongAmbientLight>,
) {
    let changed: Vec<AssetId<PhongScene>> = events
        .read()
        .filter_map(|event| match event {
            AssetEvent::Modified { id } => Some(*id),
            _ => None,
        })
        .collect();
    for (root, PhongSceneRoot(handle), spawned, children) in &roots {
        let id = handle.id();
        let up_to_date = spawned.is_some_and(|spawned| spawned.0 == id) && !changed.contains(&id);
        let Some(scene) = scenes.get(id) else {
            continue;
        };
        if up_to_date {
            continue;
        }
        if spawned.is_some() {
            info!("respawning the changed scene {handle:?}");
            for child in children.into_iter().flatten() {
                commands.entity(*child).despawn();
            }
        }
        spawn_scene(&mut commands, root, scene, &mut ambient);
        commands.entity(root).insert(SpawnedScene(id));
    }
}

fn spawn_scene(
    commands: &mut Commands,
    root: Entity,
    scene: &PhongScene,
    ambient: &mut PhongAmbientLight,
) {
    if let Some(scene_ambient) = &scene.ambient {
        *ambient = scene_ambient.clone();
    }
    if let Some(hemisphere) = &scene.hemisphere {
        commands.insert_resource(hemisphere.clone());
    }
    commands.entity(root).with_children(|parent| {
        if let Some((transform, fov)) = scene.camera {
            parent.spawn((
                Camera3d::default(),
                Projection::Perspective(PerspectiveProjection {
                    fov,
                    ..Default::default()
                }),
                transform,
                PhongSceneCamera,
            ));
        }
        for (light, transform, cookie) in &scene.lights {
            let mut light = match light {
                SceneLight::Directional(light) => parent.spawn((light.clone(), *transform)),
                SceneLight::Point(light) => parent.spawn((light.clone(), *transform)),
                SceneLight::Spot(light) => parent.spawn((light.clone(), *transform)),
                SceneLight::Rect(light) => parent.spawn((light.clone(), *transform)),
                SceneLight::Disk(light) => parent.spawn((light.clone(), *transform)),
            };
            if let Some(cookie) = cookie {
                light.insert(cookie.clone());
            }
        }
        for (mesh, material, transform) in &scene.objects {
            parent.spawn((
                Mesh3d(mesh.clone()),
                MeshMaterial3d(material.clone()),
                *transform,
            ));
        }
    });
}
