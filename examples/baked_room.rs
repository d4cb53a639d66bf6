//! A room whose light is baked, drawn with `PhongMaterial`: `assets/gltf/baked_room.gltf`
//! (written by `crates/phong_gltf_asset`, no third-party asset) brings vertex colors, a
//! second UV set with a light map and an AO map laid out on it, and a floor whose
//! checkerboard is tiled by `KHR_texture_transform`. `PhongGltfPlugin` turns the file's
//! materials into Phong ones (the occlusion texture on `TEXCOORD_1` becomes the AO map, the
//! texture transform `uv_transform`); this example gives the room's meshes the file's light
//! map as Bevy's `Lightmap` component, and makes the floor reflect the camera's
//! `EnvironmentMapLight` (`camera_environment`). The ball on the pedestal is not baked: the
//! file's lamp lights it, and Phong shadows fall from it.
//!
//! ```sh
//! cargo run --example baked_room                       # a window, where a display exists
//! cargo run --example baked_room -- --headless out.png # a PNG, and exit
//! ```
//!
//! Keys: L turns the baked light off and on.

mod support;

use bevy::{
    asset::RenderAssetUsages,
    camera::Exposure,
    gltf::GltfAssetLabel,
    image::ImageSampler,
    pbr::{Lightmap, PbrPlugin},
    prelude::*,
    render::render_resource::{
        Extent3d, TextureDescriptor, TextureDimension, TextureFormat, TextureUsages,
        TextureViewDescriptor, TextureViewDimension,
    },
    world_serialization::{WorldAssetRoot, WorldInstanceReady},
};
use bevy_phong::{EnvironmentCombine, prelude::*};

/// The room, in the crate's asset folder.
const GLTF_PATH: &str = "gltf/baked_room.gltf";

/// The index of the baked light map among the file's textures (`phong_gltf_asset`'s
/// `baked_room::LIGHTMAP_TEXTURE`).
const LIGHTMAP_TEXTURE: usize = 2;

/// The nodes whose meshes the light map covers.
const BAKED: [&str; 4] = ["Floor", "BackWall", "LeftWall", "Pedestal"];

/// The light map, to give back to the meshes when L turns it on again.
#[derive(Resource)]
struct BakedLight(Handle<Image>);

fn main() -> AppExit {
    let mut app = support::example_app_with("baked_room", |plugins| {
        // The file's materials become Phong materials only.
        plugins.set(PbrPlugin {
            gltf_enable_standard_materials: false,
            ..default()
        })
    });
    support::show_key_help(&mut app, "L baked light")
        .add_plugins((PhongPlugin, PhongGltfPlugin))
        .insert_resource(support::StillLoading)
        .insert_resource(PhongAmbientLight {
            color: Color::srgb(0.05, 0.05, 0.06),
        })
        .add_systems(Startup, setup)
        .add_systems(Update, (cast_shadows, keys))
        .add_observer(bake_in);
    support::run(app)
}

fn setup(mut commands: Commands, server: Res<AssetServer>, mut images: ResMut<Assets<Image>>) {
    commands.insert_resource(BakedLight(
        server.load(GltfAssetLabel::Texture(LIGHTMAP_TEXTURE).from_asset(GLTF_PATH)),
    ));
    commands.spawn(WorldAssetRoot(
        server.load(GltfAssetLabel::Scene(0).from_asset(GLTF_PATH)),
    ));
    let sky = images.add(sky_cube());
    commands.spawn((
        support::example_camera(
            Transform::from_xyz(4.6, 3.6, 3.2).looking_at(Vec3::new(-0.9, 0.4, -1.2), Vec3::Y),
        ),
        // What the floor reflects; its intensity undoes the camera's exposure, so that the
        // sky's texels are reflected as they are.
        EnvironmentMapLight {
            diffuse_map: sky.clone(),
            specular_map: sky,
            intensity: 1.0 / Exposure::default().exposure(),
            ..default()
        },
    ));
}

/// The file's lamp casts Phong shadows (set on Bevy's light, which its mirror follows).
fn cast_shadows(mut point: Query<&mut PointLight, Added<PointLight>>) {
    for mut light in &mut point {
        light.shadow_maps_enabled = true;
    }
}

/// Once the room is spawned: the baked meshes get the light map, and the floor reflects the
/// camera's environment.
fn bake_in(
    _: On<WorldInstanceReady>,
    mut commands: Commands,
    baked_light: Res<BakedLight>,
    names: Query<&Name>,
    primitives: Query<(Entity, &ChildOf, &MeshMaterial3d<PhongMaterial>)>,
    mut materials: ResMut<Assets<PhongMaterial>>,
) {
    for (entity, parent, material) in &primitives {
        let Ok(name) = names.get(parent.parent()) else {
            continue;
        };
        if BAKED.contains(&name.as_str()) {
            commands.entity(entity).insert(Lightmap {
                image: baked_light.0.clone(),
                ..default()
            });
        }
        if name.as_str() == "Floor"
            && let Some(mut floor) = materials.get_mut(&material.0)
        {
            floor.camera_environment = true;
            floor.environment_combine = EnvironmentCombine::Mix;
            floor.reflectivity = 0.2;
        }
    }
    commands.remove_resource::<support::StillLoading>();
}

/// L: the baked meshes lose their light map, or get it back.
fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut commands: Commands,
    baked_light: Res<BakedLight>,
    lightmapped: Query<Entity, With<Lightmap>>,
    names: Query<&Name>,
    primitives: Query<(Entity, &ChildOf), With<MeshMaterial3d<PhongMaterial>>>,
) {
    if !keys.just_pressed(KeyCode::KeyL) {
        return;
    }
    if !lightmapped.is_empty() {
        for entity in &lightmapped {
            commands.entity(entity).remove::<Lightmap>();
        }
        return;
    }
    for (entity, parent) in &primitives {
        if names
            .get(parent.parent())
            .is_ok_and(|name| BAKED.contains(&name.as_str()))
        {
            commands.entity(entity).insert(Lightmap {
                image: baked_light.0.clone(),
                ..default()
            });
        }
    }
}

/// The sky the floor reflects: blue above, a pale horizon, brown ground below, and a warm
/// glow toward the window; a 64² cube with its mip chain (each level the same sky at its
/// own texel centers: smooth enough to need no filtering).
fn sky_cube() -> Image {
    const SIZE: u32 = 64;
    let levels = SIZE.ilog2() + 1;
    let sky = |direction: Vec3| -> Vec3 {
        let direction = direction.normalize();
        let up = direction.y;
        let above = Vec3::new(0.85, 0.85, 0.8).lerp(Vec3::new(0.3, 0.5, 0.9), up.max(0.0).sqrt());
        let below =
            Vec3::new(0.6, 0.55, 0.5).lerp(Vec3::new(0.25, 0.2, 0.15), (-up).max(0.0).sqrt());
        let base = if up >= 0.0 { above } else { below };
        let glow = direction
            .dot(Vec3::new(0.5, 0.45, 0.74).normalize())
            .max(0.0)
            .powf(24.0);
        base + Vec3::new(1.0, 0.8, 0.5) * glow
    };
    // Vulkan's cube faces (+X, −X, +Y, −Y, +Z, −Z): the direction of face coordinates (s, t).
    let face_direction = |face: u32, s: f32, t: f32| match face {
        0 => Vec3::new(1.0, -t, -s),
        1 => Vec3::new(-1.0, -t, s),
        2 => Vec3::new(s, 1.0, t),
        3 => Vec3::new(s, -1.0, -t),
        4 => Vec3::new(s, -t, 1.0),
        _ => Vec3::new(-s, -t, -1.0),
    };
    let mut data = Vec::new();
    for face in 0..6 {
        for level in 0..levels {
            let size = SIZE >> level;
            let coordinate = |index: u32| (index as f32 + 0.5) / size as f32 * 2.0 - 1.0;
            for row in 0..size {
                for column in 0..size {
                    let color = sky(face_direction(face, coordinate(column), coordinate(row)));
                    let texel = color.extend(1.0).to_array();
                    data.extend(texel.map(|channel| (channel.clamp(0.0, 1.0) * 255.0) as u8));
                }
            }
        }
    }
    Image {
        data: Some(data),
        texture_descriptor: TextureDescriptor {
            label: Some("sky"),
            size: Extent3d {
                width: SIZE,
                height: SIZE,
                depth_or_array_layers: 6,
            },
            mip_level_count: levels,
            sample_count: 1,
            dimension: TextureDimension::D2,
            format: TextureFormat::Rgba8Unorm,
            usage: TextureUsages::TEXTURE_BINDING | TextureUsages::COPY_DST,
            view_formats: &[],
        },
        sampler: ImageSampler::linear(),
        texture_view_descriptor: Some(TextureViewDescriptor {
            dimension: Some(TextureViewDimension::Cube),
            ..default()
        }),
        asset_usage: RenderAssetUsages::default(),
        ..default()
    }
}
