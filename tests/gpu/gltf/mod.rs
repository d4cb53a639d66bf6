//! glTF: the repository's test asset, `assets/gltf/phong_test.gltf` (written by
//! `crates/phong_gltf_asset`), loaded through the asset server with `PhongGltfPlugin`.
//!
//! - `load`: each primitive's `PhongMaterial`, skin, morph weights, animation players and
//!   lights, as the file says;
//! - `posed`: the scene posed at a fixed animation time: each primitive, skinned and
//!   morphed ones included, covers the pixels `StandardMaterial` covers, and every pixel is
//!   lit as the reference model says on the deformed inputs;
//! - `shadows`: the skinned and morphed meshes cast the shadow of their pose;
//! - `baked_room`: the baked room's vertex colors, second UV set, occlusion texture and
//!   texture transform, loaded from its file.

mod baked_room;
mod load;
mod posed;
mod shadows;

use bevy::{
    animation::{AnimationPlayer, graph::AnimationGraphHandle},
    asset::RecursiveDependencyLoadState,
    gltf::{Gltf, GltfAssetLabel, GltfLoaderSettings, extensions::GltfExtensionHandlers},
    prelude::*,
    world_serialization::{WorldAsset, WorldAssetRoot, WorldInstanceReady},
};
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;
use std::sync::{
    Arc,
    atomic::{AtomicBool, Ordering},
};

/// The asset, in the crate's asset folder.
pub const PHONG_TEST_GLTF: &str = "gltf/phong_test.gltf";

/// Frames to wait for the file to load and its scene to spawn (loading takes a handful).
const MAX_LOAD_FRAMES: u32 = 500;

/// A harness whose glTF loads give primitives only a `PhongMaterial`.
///
/// The harness builds Bevy's default plugins, whose `PbrPlugin` registers its glTF
/// `StandardMaterial` handler; the handlers registered so far (that one only) are taken out
/// before `PhongGltfPlugin` adds its own, which is what
/// `PbrPlugin { gltf_enable_standard_materials: false, .. }` does in an app.
pub fn phong_only_gltf_harness(width: u32, height: u32) -> Harness {
    Harness::with_plugins(width, height, |app| {
        app.world()
            .resource::<GltfExtensionHandlers>()
            .0
            .write_blocking()
            .clear();
        app.add_plugins(PhongGltfPlugin);
    })
}

/// Spawns scene 0 of `path` and updates until it and every asset it names have loaded and
/// the scene's instance is ready. Returns the file's `Gltf`.
pub fn spawn_gltf_scene(harness: &mut Harness, path: &str) -> Handle<Gltf> {
    spawn_gltf_scene_with(harness, path, |_| {})
}

/// [`spawn_gltf_scene`], the file loaded with `settings` applied to the loader's.
pub fn spawn_gltf_scene_with(
    harness: &mut Harness,
    path: &str,
    settings: impl Fn(&mut GltfLoaderSettings) + Clone + Send + Sync + 'static,
) -> Handle<Gltf> {
    let world = harness.world_mut();
    let server = world.resource::<AssetServer>().clone();
    let gltf: Handle<Gltf> = server
        .load_builder()
        .with_settings(settings.clone())
        .load(path.to_owned());
    let scene: Handle<WorldAsset> = server
        .load_builder()
        .with_settings(settings)
        .load(GltfAssetLabel::Scene(0).from_asset(path.to_owned()));
    let ready = Arc::new(AtomicBool::new(false));
    let flag = ready.clone();
    world
        .spawn(WorldAssetRoot(scene))
        .observe(move |_: On<WorldInstanceReady>| flag.store(true, Ordering::Relaxed));
    for _ in 0..MAX_LOAD_FRAMES {
        harness.app.update();
        if let Some(RecursiveDependencyLoadState::Failed(error)) =
            server.get_recursive_dependency_load_state(&gltf)
        {
            panic!("{path} failed to load: {error}");
        }
        if ready.load(Ordering::Relaxed) && server.is_loaded_with_dependencies(&gltf) {
            // One more frame: the Bevy lights' Phong mirrors are made in `PostUpdate`.
            harness.app.update();
            return gltf;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    panic!("{path} did not load and spawn within {MAX_LOAD_FRAMES} frames");
}

/// Poses the spawned scene at `seconds` into every animation of `gltf`, paused there: each
/// animation player gets a graph of all the file's clips, each played and held at that
/// time (a clip whose targets are not under a player changes nothing there). Runs two
/// updates: Bevy prepares a new graph for evaluation in the update after the one it was
/// added in, and applies the animations in the next.
pub fn pose_at(harness: &mut Harness, gltf: &Handle<Gltf>, seconds: f32) {
    let world = harness.world_mut();
    let clips: Vec<Handle<AnimationClip>> = world
        .resource::<Assets<Gltf>>()
        .get(gltf)
        .unwrap()
        .animations
        .clone();
    let (graph, nodes) = AnimationGraph::from_clips(clips);
    let graph = world.resource_mut::<Assets<AnimationGraph>>().add(graph);
    let mut players = world.query::<(Entity, &mut AnimationPlayer)>();
    let entities: Vec<Entity> = players.iter(world).map(|(entity, _)| entity).collect();
    for entity in entities {
        let mut player = world.get_mut::<AnimationPlayer>(entity).unwrap();
        for node in &nodes {
            player.play(*node).set_seek_time(seconds).pause();
        }
        world
            .entity_mut(entity)
            .insert(AnimationGraphHandle(graph.clone()));
    }
    harness.app.update();
    harness.app.update();
}
