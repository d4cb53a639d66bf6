//! Writes bevy_phong's glTF assets: the test asset, `assets/gltf/phong_test.gltf`, and the
//! `baked_room` example's room ([`baked_room`]). Each is one JSON file with its buffer and
//! images as base64 `data:` URIs, made entirely by this crate (no third-party asset).
//! Regenerate them with `cargo run -p phong_gltf_asset`; a test fails when a committed file
//! differs from what its function writes.
//!
//! Its scene's nodes:
//!
//! - `Ground`: a 10 × 10 m square at y = 0 with UVs and tangents, material `GroundOpaque`
//!   (OPAQUE, a checkerboard base color map, a normal map, metallic 0, roughness 0.8);
//! - `Arm`: a tube skinned to two joints, `Shoulder` (at x = −2.5 on the ground) and its
//!   child `Elbow` (1 m above), its weights blending within 0.25 m of the elbow; material
//!   `ArmDoubleSided` (doubleSided, metallic 0.25, roughness 0.45). Animation `Bend` turns
//!   the elbow about +Z from 0 to 60° over 1 s (LINEAR);
//! - `Blob`: a sphere of radius 0.75 at (2.5, 1, 0) with one morph target lifting its upper
//!   half (mesh weight 0), material `BlobBlend` (BLEND, alpha 0.6, emissive 0.1, 0.05, 0
//!   at `KHR_materials_emissive_strength` 2, metallic 0, roughness 0.2). Animation `Morph`
//!   takes its weight from 0 to 1 over 1 s (LINEAR);
//! - `Fence`: a 3 × 1.5 m quad at z = −2.5 facing +Z, material `FenceMask` (MASK, cutoff
//!   0.5, a base color map of opaque and transparent bars, metallic 1, roughness 0.6);
//! - `Lamp`: a `KHR_lights_punctual` point light at (0, 4, 3), 50,000 cd, range 20 m;
//! - `Sun`: a directional light of 3,000 lux pointing down at 60° toward −Z.

pub mod baked_room;
mod builder;
mod encoding;
mod images;
mod room;
mod room_bake;
mod shapes;

use builder::{Buffers, quantize, quantize_json};
use serde_json::{Value, json};
use shapes::Shape;

/// Where the asset lives, relative to the bevy_phong crate's root.
pub const ASSET_PATH: &str = "assets/gltf/phong_test.gltf";

/// The command that rewrites the asset.
pub const REGENERATE: &str = "cargo run -p phong_gltf_asset";

/// Where the shoulder joint stands, in the bind pose (m).
pub const SHOULDER: [f64; 3] = [-2.5, 0.0, 0.0];

/// The elbow's angle at the end of `Bend` (degrees).
pub const BEND_DEGREES: f64 = 60.0;

/// Half the angle the sun is turned down by (60°), in radians.
const SUN_HALF_ANGLE: f64 = core::f64::consts::PI / 6.0;

/// The asset's text.
pub fn phong_test_gltf() -> String {
    let mut buffers = Buffers::default();
    let meshes = vec![
        mesh(&mut buffers, "Ground", &shapes::ground(), 0),
        mesh(&mut buffers, "Arm", &shapes::arm(SHOULDER), 1),
        mesh(&mut buffers, "Blob", &shapes::blob(0.75), 2),
        mesh(&mut buffers, "Fence", &shapes::fence(3.0, 1.5), 3),
    ];

    // Column-major inverses of the joints' bind-pose transforms (pure translations).
    let elbow = [SHOULDER[0], SHOULDER[1] + shapes::ELBOW, SHOULDER[2]];
    let inverse_bind = |t: [f64; 3]| -> [f32; 16] {
        let mut m = [0.0; 16];
        m[0] = 1.0;
        m[5] = 1.0;
        m[10] = 1.0;
        m[15] = 1.0;
        m[12..15].copy_from_slice(&t.map(|x| quantize(-x)));
        m
    };
    let inverse_binds = buffers.data(&[inverse_bind(SHOULDER), inverse_bind(elbow)]);

    let half_angle = BEND_DEGREES.to_radians() / 2.0;
    let bend_times = buffers.data(&[[0.0], [1.0]]);
    let bend_rotations = buffers.data(&[
        [0.0, 0.0, 0.0, 1.0],
        [
            0.0,
            0.0,
            quantize(half_angle.sin()),
            quantize(half_angle.cos()),
        ],
    ]);
    let morph_times = buffers.data(&[[0.0], [1.0]]);
    let morph_weights = buffers.data(&[[0.0], [1.0]]);

    let uri = encoding::data_uri("application/octet-stream", &buffers.bytes);
    let image = |name: &str, png: Vec<u8>| json!({"name": name, "uri": encoding::data_uri("image/png", &png)});

    let document = json!({
        "asset": {"version": "2.0", "generator": "phong_gltf_asset (bevy_phong)"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "Lamp", "type": "point", "color": [1.0, 0.9, 0.8], "intensity": 50000.0, "range": 20.0},
            {"name": "Sun", "type": "directional", "color": [1.0, 1.0, 0.95], "intensity": 3000.0},
        ]}},
        "scene": 0,
        "scenes": [{"name": "Scene", "nodes": [0, 1, 2, 4, 5, 6, 7]}],
        "nodes": [
            {"name": "Ground", "mesh": 0},
            {"name": "Arm", "mesh": 1, "skin": 0},
            {"name": "Shoulder", "translation": SHOULDER, "children": [3]},
            {"name": "Elbow", "translation": [0.0, shapes::ELBOW, 0.0]},
            {"name": "Blob", "mesh": 2, "translation": [2.5, 1.0, 0.0]},
            {"name": "Fence", "mesh": 3, "translation": [0.0, 0.0, -2.5]},
            {"name": "Lamp", "translation": [0.0, 4.0, 3.0],
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
            // −Z (a light's direction) turned 60° down about +X.
            {"name": "Sun", "rotation": [quantize_json(-SUN_HALF_ANGLE.sin()), 0.0, 0.0, quantize_json(SUN_HALF_ANGLE.cos())],
             "extensions": {"KHR_lights_punctual": {"light": 1}}},
        ],
        "meshes": meshes,
        "skins": [{"name": "ArmSkin", "joints": [2, 3], "skeleton": 2, "inverseBindMatrices": inverse_binds}],
        "animations": [
            {"name": "Bend",
             "samplers": [{"input": bend_times, "output": bend_rotations, "interpolation": "LINEAR"}],
             "channels": [{"sampler": 0, "target": {"node": 3, "path": "rotation"}}]},
            {"name": "Morph",
             "samplers": [{"input": morph_times, "output": morph_weights, "interpolation": "LINEAR"}],
             "channels": [{"sampler": 0, "target": {"node": 4, "path": "weights"}}]},
        ],
        "materials": [
            {"name": "GroundOpaque", "alphaMode": "OPAQUE",
             "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 0.8},
             "normalTexture": {"index": 1}},
            {"name": "ArmDoubleSided", "doubleSided": true,
             "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.3, 0.2, 1.0], "metallicFactor": 0.25, "roughnessFactor": 0.45}},
            {"name": "BlobBlend", "alphaMode": "BLEND",
             "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.9, 0.6], "metallicFactor": 0.0, "roughnessFactor": 0.2},
             "emissiveFactor": [0.1, 0.05, 0.0],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2.0}}},
            {"name": "FenceMask", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": false,
             "pbrMetallicRoughness": {"baseColorTexture": {"index": 2}, "baseColorFactor": [0.9, 0.85, 0.7, 1.0],
                                      "metallicFactor": 1.0, "roughnessFactor": 0.6}},
        ],
        "textures": [
            {"name": "Checker", "source": 0, "sampler": 0},
            {"name": "Bumps", "source": 1, "sampler": 0},
            {"name": "Bars", "source": 2, "sampler": 1},
        ],
        "samplers": [
            {"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497},
            {"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33071},
        ],
        "images": [image("Checker", images::checker()), image("Bumps", images::bumps()), image("Bars", images::bars())],
        "accessors": buffers.accessors,
        "bufferViews": buffers.views,
        "buffers": [{"byteLength": buffers.bytes.len(), "uri": uri}],
    });
    let mut text = serde_json::to_string_pretty(&document).expect("a JSON value serializes");
    text.push('\n');
    text
}

/// A mesh of one primitive with `shape`'s attributes and material `material`.
fn mesh(buffers: &mut Buffers, name: &str, shape: &Shape, material: usize) -> Value {
    let mut attributes = json!({
        "POSITION": buffers.attribute(&shape.positions),
        "NORMAL": buffers.attribute(&shape.normals),
        "TEXCOORD_0": buffers.attribute(&shape.uvs),
    });
    if !shape.tangents.is_empty() {
        attributes["TANGENT"] = json!(buffers.attribute(&shape.tangents));
    }
    if !shape.joints.is_empty() {
        attributes["JOINTS_0"] = json!(buffers.joints(&shape.joints));
        attributes["WEIGHTS_0"] = json!(buffers.attribute(&shape.weights));
    }
    let mut primitive = json!({
        "attributes": attributes,
        "indices": buffers.indices(&shape.indices),
        "material": material,
    });
    let mut mesh = json!({"name": name});
    if !shape.morph_positions.is_empty() {
        primitive["targets"] = json!([{"POSITION": buffers.attribute(&shape.morph_positions)}]);
        mesh["weights"] = json!([0.0]);
    }
    mesh["primitives"] = json!([primitive]);
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn committed_path() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(ASSET_PATH)
    }

    #[test]
    fn the_committed_asset_is_what_the_generator_writes() {
        let committed = std::fs::read_to_string(committed_path()).unwrap_or_default();
        assert!(
            committed == phong_test_gltf(),
            "{ASSET_PATH} differs from what the generator writes: run `{REGENERATE}` and \
             commit the result"
        );
    }

    #[test]
    fn the_asset_parses_and_validates_as_gltf() {
        let text = phong_test_gltf();
        let gltf = gltf::Gltf::from_slice(text.as_bytes())
            .unwrap_or_else(|error| panic!("invalid glTF: {error}"));
        let names: Vec<_> = gltf.nodes().filter_map(|n| n.name()).collect();
        assert_eq!(
            names,
            [
                "Ground", "Arm", "Shoulder", "Elbow", "Blob", "Fence", "Lamp", "Sun"
            ]
        );
        let animations: Vec<_> = gltf.animations().filter_map(|a| a.name()).collect();
        assert_eq!(animations, ["Bend", "Morph"]);
        assert_eq!(gltf.lights().map(|l| l.count()), Some(2));
        let blob = gltf.meshes().find(|m| m.name() == Some("Blob")).unwrap();
        assert_eq!(blob.primitives().next().unwrap().morph_targets().len(), 1);
        let skin = gltf.skins().next().unwrap();
        assert_eq!(skin.joints().count(), 2);
        let modes: Vec<_> = gltf.materials().map(|m| m.alpha_mode()).collect();
        use gltf::material::AlphaMode::*;
        assert_eq!(modes, [Opaque, Opaque, Blend, Mask]);
    }
}
