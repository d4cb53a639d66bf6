//! Writes `assets/gltf/baked_room.gltf`: a room whose light is baked, for the `baked_room`
//! example. One JSON file with its buffer and images as `data:` URIs, made by this crate.
//!
//! - `Floor` (6 × 6 m at y = 0), `BackWall` (z = −3) and `LeftWall` (x = −3), 3 m high, and
//!   `Pedestal` (a 1 m cube at (0.8, 0.5, −0.5)): vertex colors (`COLOR_0`), a tiling first
//!   UV set and a second (`TEXCOORD_1`) laid out in one 128² atlas;
//! - materials `Floor` (a checkerboard through `KHR_texture_transform`, roughness 0.25),
//!   `Wall`, `Pedestal`, each with the atlas's AO map as its occlusion texture on
//!   `TEXCOORD_1`;
//! - texture 2, `Lightmap`: the atlas's baked light (sRGB), used by no material: the example
//!   gives it to the meshes as Bevy's `Lightmap` component, as a light baker's output is used;
//! - `Ball`: a sphere on the pedestal with vertex colors, not baked (lit by the lights);
//! - `Lamp`: a `KHR_lights_punctual` point light where the baked window light is.

use crate::builder::Buffers;
use crate::room::{self, Surface};
use crate::{encoding, images, room_bake};
use serde_json::{Value, json};

/// Where the asset lives, relative to the bevy_phong crate's root.
pub const ASSET_PATH: &str = "assets/gltf/baked_room.gltf";

/// The index of the light map among the file's textures.
pub const LIGHTMAP_TEXTURE: usize = 2;

/// The ball's radius (m).
pub const BALL_RADIUS: f64 = 0.4;
/// The ball's center, on the pedestal (m).
pub const BALL: [f64; 3] = [0.8, 1.0 + BALL_RADIUS, -0.5];

/// Warm plaster, a little darker toward the floor.
fn wall_color(point: [f64; 3]) -> [f64; 3] {
    let shade = 0.85 + 0.05 * point[1];
    [shade, shade * 0.96, shade * 0.9]
}

/// The floor's tint: a faint warm patch around the room's middle.
fn floor_color(point: [f64; 3]) -> [f64; 3] {
    let distance = (point[0] * point[0] + point[2] * point[2]).sqrt();
    let warm = (-0.15 * distance * distance).exp();
    [0.8 + 0.2 * warm, 0.78 + 0.12 * warm, 0.75]
}

/// The pedestal's colors: teal at the foot to pale at the top.
fn pedestal_color(point: [f64; 3]) -> [f64; 3] {
    let t = point[1].clamp(0.0, 1.0);
    [0.25 + 0.6 * t, 0.55 + 0.35 * t, 0.6 + 0.3 * t]
}

/// The ball's colors: a red-to-gold gradient over its height.
fn ball_color(normal: [f64; 3]) -> [f64; 3] {
    let t = 0.5 + 0.5 * normal[1];
    [0.9, 0.2 + 0.6 * t, 0.1 + 0.2 * t]
}

/// The asset's text.
pub fn baked_room_gltf() -> String {
    let mut buffers = Buffers::default();
    let [floor, back_wall, left_wall] = room::room_quads();
    let mut surfaces: Vec<(&str, Surface, usize)> = Vec::new();
    for (name, quad, material, color) in [
        ("Floor", floor, 0, floor_color as fn([f64; 3]) -> [f64; 3]),
        ("BackWall", back_wall, 1, wall_color),
        ("LeftWall", left_wall, 1, wall_color),
    ] {
        let mut surface = Surface::default();
        surface.add_quad(&quad, 12, color);
        surfaces.push((name, surface, material));
    }
    let mut pedestal = Surface::default();
    for quad in room::pedestal_quads() {
        pedestal.add_quad(&quad, 2, pedestal_color);
    }
    surfaces.push(("Pedestal", pedestal, 2));
    surfaces.push(("Ball", room::ball(BALL_RADIUS, ball_color), 3));
    let meshes: Vec<Value> = surfaces
        .iter()
        .map(|(name, surface, material)| mesh(&mut buffers, name, surface, *material))
        .collect();

    let uri = encoding::data_uri("application/octet-stream", &buffers.bytes);
    let image = |name: &str, png: Vec<u8>| json!({"name": name, "uri": encoding::data_uri("image/png", &png)});
    let occlusion = json!({"index": 1, "texCoord": 1});
    let document = json!({
        "asset": {"version": "2.0", "generator": "phong_gltf_asset (bevy_phong)"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_texture_transform"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "Lamp", "type": "point", "color": [1.0, 0.85, 0.65], "intensity": 3000.0, "range": 12.0},
        ]}},
        "scene": 0,
        "scenes": [{"name": "Room", "nodes": [0, 1, 2, 3, 4, 5]}],
        "nodes": [
            {"name": "Floor", "mesh": 0},
            {"name": "BackWall", "mesh": 1},
            {"name": "LeftWall", "mesh": 2},
            {"name": "Pedestal", "mesh": 3},
            {"name": "Ball", "mesh": 4, "translation": BALL},
            {"name": "Lamp", "translation": room_bake::WINDOW,
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        "meshes": meshes,
        "materials": [
            {"name": "Floor",
             "pbrMetallicRoughness": {
                 "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":
                     {"offset": [0.25, 0.0], "scale": [2.0, 2.0]}}},
                 "metallicFactor": 0.0, "roughnessFactor": 0.25},
             "occlusionTexture": occlusion},
            {"name": "Wall",
             "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.9},
             "occlusionTexture": occlusion},
            {"name": "Pedestal",
             "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6},
             "occlusionTexture": occlusion},
            {"name": "Ball",
             "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.3}},
        ],
        "textures": [
            {"name": "Checker", "source": 0, "sampler": 0},
            {"name": "Occlusion", "source": 1, "sampler": 1},
            {"name": "Lightmap", "source": 2, "sampler": 1},
        ],
        "samplers": [
            {"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497},
            {"magFilter": 9729, "minFilter": 9729, "wrapS": 33071, "wrapT": 33071},
        ],
        "images": [
            image("Checker", images::checker()),
            image("Occlusion", room_bake::ao_map()),
            image("Lightmap", room_bake::light_map()),
        ],
        "accessors": buffers.accessors,
        "bufferViews": buffers.views,
        "buffers": [{"byteLength": buffers.bytes.len(), "uri": uri}],
    });
    let mut text = serde_json::to_string_pretty(&document).expect("a JSON value serializes");
    text.push('\n');
    text
}

/// A mesh of one primitive with `surface`'s attributes and material `material`.
fn mesh(buffers: &mut Buffers, name: &str, surface: &Surface, material: usize) -> Value {
    let mut attributes = json!({
        "POSITION": buffers.attribute(&surface.positions),
        "NORMAL": buffers.attribute(&surface.normals),
        "TEXCOORD_0": buffers.attribute(&surface.uv0),
        "COLOR_0": buffers.attribute(&surface.colors),
    });
    if !surface.uv1.is_empty() {
        attributes["TEXCOORD_1"] = json!(buffers.attribute(&surface.uv1));
    }
    json!({"name": name, "primitives": [{
        "attributes": attributes,
        "indices": buffers.indices(&surface.indices),
        "material": material,
    }]})
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    #[test]
    fn the_committed_room_is_what_the_generator_writes() {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(ASSET_PATH);
        let committed = std::fs::read_to_string(path).unwrap_or_default();
        assert!(
            committed == baked_room_gltf(),
            "{ASSET_PATH} differs from what the generator writes: run `{}` and commit the result",
            crate::REGENERATE
        );
    }

    #[test]
    fn the_room_has_what_the_example_shows() {
        let text = baked_room_gltf();
        let gltf = gltf::Gltf::from_slice(text.as_bytes())
            .unwrap_or_else(|error| panic!("invalid glTF: {error}"));
        let names: Vec<_> = gltf.nodes().filter_map(|n| n.name()).collect();
        assert_eq!(
            names,
            ["Floor", "BackWall", "LeftWall", "Pedestal", "Ball", "Lamp"]
        );
        for mesh in gltf.meshes() {
            let primitive = mesh.primitives().next().unwrap();
            let has = |semantic| primitive.get(&semantic).is_some();
            assert!(
                has(gltf::Semantic::Colors(0)),
                "{:?} has COLOR_0",
                mesh.name()
            );
            let baked = mesh.name() != Some("Ball");
            assert_eq!(
                has(gltf::Semantic::TexCoords(1)),
                baked,
                "{:?}",
                mesh.name()
            );
        }
        let floor = gltf.materials().next().unwrap();
        let base_color = floor.pbr_metallic_roughness().base_color_texture().unwrap();
        assert!(base_color.texture_transform().is_some());
        assert_eq!(floor.occlusion_texture().unwrap().tex_coord(), 1);
        let lightmap = gltf.textures().nth(LIGHTMAP_TEXTURE).unwrap();
        assert_eq!(lightmap.name(), Some("Lightmap"));
    }
}
