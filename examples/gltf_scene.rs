//! A glTF file drawn with `PhongMaterial`: the repository's test asset
//! (`assets/gltf/phong_test.gltf`), an arm skinned to two joints that bends, a blob whose
//! morph target lifts it, a masked fence and a textured, normal-mapped ground. The file's
//! sun and lamp light it as Phong lights (`PhongGltfPlugin` mirrors them), with shadows on,
//! seen through an HDR camera with distance fog and bloom.
//!
//! The bent arm and the lifted blob cast the shadow of their pose; the fence casts the
//! shadow of its whole quad (alpha-mask holes are not cut in Phong shadow maps).
//!
//! ```sh
//! cargo run --example gltf_scene                       # a window, where a display exists
//! cargo run --example gltf_scene -- --headless out.png # a PNG, and exit
//! ```
//!
//! Keys: Space pauses the animations, S turns the shadows on and off.

mod support;

use bevy::{
    camera::{Hdr, ShadowLodOrigin},
    core_pipeline::tonemapping::Tonemapping,
    gltf::{Gltf, GltfAssetLabel},
    pbr::PbrPlugin,
    post_process::bloom::Bloom,
    prelude::*,
    world_serialization::{WorldAssetRoot, WorldInstanceReady},
};
use bevy_phong::prelude::*;

/// The glTF file, in the crate's asset folder.
const GLTF_PATH: &str = "gltf/phong_test.gltf";

/// Where the animations start (s): the elbow half bent, the blob half lifted, which is
/// also the picture a headless run saves (time stands still there).
const START_SECONDS: f32 = 0.5;

/// The fog's color, and the sky's.
const FOG_COLOR: Color = Color::srgb(0.42, 0.5, 0.62);

/// The glTF file being loaded, until its scene is spawned and its animations started.
#[derive(Resource)]
struct Loading(Handle<Gltf>);

fn main() -> AppExit {
    let mut app = support::example_app_with("gltf_scene", |plugins| {
        // The file's materials become Phong materials only: without this, Bevy also gives
        // each primitive a StandardMaterial and draws it twice.
        plugins.set(PbrPlugin {
            gltf_enable_standard_materials: false,
            ..default()
        })
    });
    support::show_key_help(&mut app, "Space pause, S shadows")
        .add_plugins((PhongPlugin, PhongGltfPlugin))
        .insert_resource(support::StillLoading)
        .add_systems(Startup, setup)
        .add_systems(Update, (cast_shadows, keys))
        .add_observer(start_animations);
    support::run(app)
}

fn setup(mut commands: Commands, server: Res<AssetServer>) {
    commands.insert_resource(Loading(server.load(GLTF_PATH)));
    commands.spawn(WorldAssetRoot(
        server.load(GltfAssetLabel::Scene(0).from_asset(GLTF_PATH)),
    ));
    commands.insert_resource(ClearColor(FOG_COLOR));
    commands.spawn((
        Camera3d::default(),
        // Bevy's point-light shadows are culled from here (Bevy asks for one when a
        // camera renders to an image).
        ShadowLodOrigin,
        Hdr,
        Tonemapping::TonyMcMapface,
        Bloom::NATURAL,
        DistanceFog {
            color: FOG_COLOR,
            directional_light_color: Color::srgba(1.0, 0.9, 0.7, 0.5),
            directional_light_exponent: 20.0,
            falloff: FogFalloff::from_visibility_color(40.0, FOG_COLOR),
        },
        Transform::from_xyz(4.0, 4.5, 7.0).looking_at(Vec3::new(0.0, 0.5, -0.5), Vec3::Y),
    ));
}

/// The file's lights cast shadows: set on Bevy's lights, which their Phong mirrors follow.
fn cast_shadows(
    mut directional: Query<&mut DirectionalLight, Added<DirectionalLight>>,
    mut point: Query<&mut PointLight, Added<PointLight>>,
) {
    for mut light in &mut directional {
        light.shadow_maps_enabled = true;
    }
    for mut light in &mut point {
        light.shadow_maps_enabled = true;
    }
}

/// Once the scene is spawned: every animation player plays all of the file's clips,
/// repeating, from [`START_SECONDS`].
fn start_animations(
    _: On<WorldInstanceReady>,
    mut commands: Commands,
    loading: Option<Res<Loading>>,
    gltfs: Res<Assets<Gltf>>,
    mut graphs: ResMut<Assets<AnimationGraph>>,
    mut players: Query<(Entity, &mut AnimationPlayer)>,
) {
    let Some(gltf) = loading.and_then(|loading| gltfs.get(&loading.0)) else {
        error!("{GLTF_PATH}: the scene spawned before its file was loaded");
        return;
    };
    let (graph, nodes) = AnimationGraph::from_clips(gltf.animations.clone());
    let graph = graphs.add(graph);
    for (entity, mut player) in &mut players {
        for node in &nodes {
            player.play(*node).repeat().set_seek_time(START_SECONDS);
        }
        commands
            .entity(entity)
            .insert(AnimationGraphHandle(graph.clone()));
    }
    commands.remove_resource::<Loading>();
    commands.remove_resource::<support::StillLoading>();
}

fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut players: Query<&mut AnimationPlayer>,
    mut directional: Query<&mut DirectionalLight>,
    mut point: Query<&mut PointLight>,
) {
    if keys.just_pressed(KeyCode::Space) {
        for mut player in &mut players {
            if player.all_paused() {
                player.resume_all();
            } else {
                player.pause_all();
            }
        }
    }
    if keys.just_pressed(KeyCode::KeyS) {
        for mut light in &mut directional {
            light.shadow_maps_enabled = !light.shadow_maps_enabled;
        }
        for mut light in &mut point {
            light.shadow_maps_enabled = !light.shadow_maps_enabled;
        }
    }
}
