//! glTF: `assets/gltf/phong_test.gltf` (written by `crates/phong_gltf_asset`) loaded through
//! the asset server with `PhongGltfPlugin`, its scene spawned and drawn. Each primitive
//! carries the `PhongMaterial` that `phong_material_from_gltf` makes of its glTF material,
//! and nothing else; the skinned arm has its `SkinnedMesh`, the blob its morph weights,
//! the animations their players, and the file's two lights became Phong lights.

use super::{PHONG_TEST_GLTF, phong_only_gltf_harness, spawn_gltf_scene};
use bevy::{
    animation::AnimationPlayer,
    gltf::{Gltf, GltfMaterial, GltfMaterialName},
    mesh::{
        morph::{MeshMorphWeights, MorphWeights},
        skinning::SkinnedMesh,
    },
    prelude::*,
};
use bevy_phong::{
    BevyLightExposure,
    gltf::{phong_material_from_gltf, phong_material_label},
    prelude::*,
    reference,
};
use glam::DVec3;

/// Exact: the loaded material and the one computed here come from the same `GltfMaterial`
/// through the same function, handles included (compared through their `Debug` text, as
/// `PhongMaterial` has no `PartialEq`).
fn assert_same_material(actual: &PhongMaterial, expected: &PhongMaterial, label: &str) {
    assert_eq!(format!("{actual:?}"), format!("{expected:?}"), "{label}");
}

/// `a` and `b` within `f32` rounding of the mapping's few operations (relative to
/// `max(1, |b|)`: the exponents reach 10³).
fn assert_close(a: f32, b: f32, what: &str) {
    assert!(
        (a - b).abs() <= 1e-5 * b.abs().max(1.0),
        "{what}: {a}, expected {b}"
    );
}

#[test]
fn a_gltf_scene_spawns_with_phong_materials_skins_morphs_and_lights() {
    let mut harness = phong_only_gltf_harness(64, 64);
    let gltf_handle = spawn_gltf_scene(&mut harness, PHONG_TEST_GLTF);
    let world = harness.world_mut();
    let mut primitives = world.query_filtered::<(
        &Name,
        &GltfMaterialName,
        &MeshMaterial3d<PhongMaterial>,
        Has<MeshMaterial3d<StandardMaterial>>,
    ), With<Mesh3d>>();
    let mut skinned = world.query::<(&Name, &SkinnedMesh)>();
    let mut morphed = world.query::<(&MeshMorphWeights, &GltfMaterialName)>();
    let mut players = world.query_filtered::<&Name, With<AnimationPlayer>>();
    let mut points = world.query::<(&PointLight, &PhongPointLight)>();
    let mut directionals = world.query::<(&DirectionalLight, &PhongDirectionalLight)>();
    let world: &World = world;
    let server = world.resource::<AssetServer>();
    let gltf = world.resource::<Assets<Gltf>>().get(&gltf_handle).unwrap();
    let gltf_materials = world.resource::<Assets<GltfMaterial>>();
    let phong_materials = world.resource::<Assets<PhongMaterial>>();

    // Every primitive: the Phong material of its glTF material, under `Material{n}/phong`,
    // and no StandardMaterial.
    let mut seen = Vec::new();
    for (name, material_name, phong, has_standard) in primitives.iter(world) {
        assert!(!has_standard, "{name}: also has a StandardMaterial");
        let gltf_material = &gltf.named_materials[material_name.0.as_str()];
        let index = gltf
            .materials
            .iter()
            .position(|m| m == gltf_material)
            .unwrap();
        let label = format!("Material{index}");
        assert_eq!(
            server.get_path(phong.id()).unwrap().label(),
            Some(phong_material_label(&label).as_str()),
            "{name}"
        );
        let actual = phong_materials.get(phong).unwrap();
        let expected = phong_material_from_gltf(gltf_materials.get(gltf_material).unwrap(), None);
        assert_same_material(actual, &expected, &label);
        seen.push((material_name.0.clone(), actual.clone()));
    }
    seen.sort_by(|a, b| a.0.cmp(&b.0));
    let names: Vec<_> = seen.iter().map(|(name, _)| name.as_str()).collect();
    assert_eq!(
        names,
        ["ArmDoubleSided", "BlobBlend", "FenceMask", "GroundOpaque"],
        "one primitive per mesh"
    );

    // The file's factors, converted by the design's table.
    let linear = |color: Color| color.to_linear().to_f32_array();
    let [arm, blob, fence, ground] = [0, 1, 2, 3].map(|i| &seen[i].1);
    // Arm: base (0.8, 0.3, 0.2), metallic 0.25, roughness 0.45.
    let [r, g, b, _] = linear(arm.base_color);
    assert_close(r, 0.8 * 0.75, "arm base red");
    assert_close(g, 0.3 * 0.75, "arm base green");
    assert_close(b, 0.2 * 0.75, "arm base blue");
    // F₀ compensated for multiple scattering at the roughness (SPEC.md, "Metallic-roughness
    // map").
    let compensated = |k: f32, r: f32| {
        reference::with_multiple_scattering(DVec3::splat(k.into()), r.into()).x as f32
    };
    let [r, _, _, _] = linear(arm.specular_color);
    assert_close(r, compensated(0.04 * 0.75 + 0.8 * 0.25, 0.45), "arm F0 red");
    // The exponent fitted to Bevy's lobe at the roughness (SPEC.md, "Metallic-roughness map").
    let shininess = |r: f32| reference::shininess_from_roughness(r.into()) as f32;
    assert_close(arm.shininess, shininess(0.45), "arm shininess");
    assert_eq!(arm.specular_model, SpecularModel::NormalizedBlinnPhong);
    assert!(arm.double_sided, "the arm's material is doubleSided");
    assert!(!fence.double_sided && !blob.double_sided && !ground.double_sided);
    // Blob: BLEND, alpha 0.6, emissive (0.1, 0.05, 0) × strength 2, roughness 0.2.
    assert_eq!(blob.alpha_mode, AlphaMode::Blend);
    assert_close(linear(blob.base_color)[3], 0.6, "blob alpha");
    assert_close(blob.emissive.red, 0.2, "blob emissive red");
    assert_close(blob.emissive.green, 0.1, "blob emissive green");
    assert_close(blob.shininess, shininess(0.2), "blob shininess");
    // Fence: MASK 0.5, a metal (no diffuse, its color as F0), roughness 0.6.
    assert_eq!(fence.alpha_mode, AlphaMode::Mask(0.5));
    assert_eq!(linear(fence.base_color)[..3], [0.0; 3]);
    assert_close(
        linear(fence.specular_color)[1],
        compensated(0.85, 0.6),
        "fence F0 green",
    );
    assert!(fence.base_color_texture.is_some());
    // Ground: OPAQUE, base color and normal maps, no flip (glTF's normal maps are +Y up).
    assert_eq!(ground.alpha_mode, AlphaMode::Opaque);
    assert!(ground.base_color_texture.is_some() && ground.normal_map_texture.is_some());
    assert!(!ground.flip_normal_map_y);

    // The arm is skinned to Shoulder and Elbow; the blob's primitive follows its node's
    // morph weights (mesh weight 0).
    let skins: Vec<_> = skinned
        .iter(world)
        .map(|(n, s)| (n.clone(), s.clone()))
        .collect();
    assert_eq!(skins.len(), 1, "one skinned primitive");
    let joint_names: Vec<_> = skins[0]
        .1
        .joints
        .iter()
        .map(|&joint| world.get::<Name>(joint).unwrap().as_str().to_owned())
        .collect();
    assert_eq!(joint_names, ["Shoulder", "Elbow"]);
    let morphed: Vec<_> = morphed
        .iter(world)
        .map(|(w, m)| (w.clone(), m.0.clone()))
        .collect();
    assert_eq!(morphed.len(), 1, "one morphed primitive");
    assert_eq!(morphed[0].1, "BlobBlend");
    let MeshMorphWeights::Reference(blob_node) = morphed[0].0 else {
        panic!(
            "the blob's primitive holds its own weights: {:?}",
            morphed[0].0
        );
    };
    assert_eq!(
        world.get::<MorphWeights>(blob_node).unwrap().weights(),
        [0.0]
    );
    assert_eq!(world.get::<Name>(blob_node).unwrap().as_str(), "Blob");

    // The animations are the file's; each animated root node got a player.
    let mut animation_names: Vec<_> = gltf
        .named_animations
        .keys()
        .map(|k| k.to_string())
        .collect();
    animation_names.sort();
    assert_eq!(animation_names, ["Bend", "Morph"]);
    let mut players: Vec<_> = players.iter(world).map(|n| n.as_str().to_owned()).collect();
    players.sort();
    assert_eq!(players, ["Blob", "Shoulder"]);

    // Lights: each of Bevy's lights from the file has its Phong mirror.
    let exposure = BevyLightExposure::default();
    let points: Vec<_> = points.iter(world).collect();
    assert_eq!(points.len(), 1, "the file's point light, mirrored");
    assert_eq!(*points[0].1, exposure.point(points[0].0));
    let directionals: Vec<_> = directionals.iter(world).collect();
    assert_eq!(
        directionals.len(),
        1,
        "the file's directional light, mirrored"
    );
    assert_eq!(*directionals[0].1, exposure.directional(directionals[0].0));
    // 50,000 cd times 4π sr, Bevy's conversion to lumens (relative f32 rounding).
    let candela = points[0].0.intensity / (4.0 * core::f32::consts::PI);
    assert!(
        (candela / 50_000.0 - 1.0).abs() < 1e-6,
        "point light: {candela} cd"
    );
    assert_eq!(directionals[0].0.illuminance, 3000.0);

    // And the scene draws: every primitive's pipeline compiles, no render error.
    harness.settle();
    let frame = harness.render_next_frame();
    assert_eq!(frame.non_finite_pixels(), 0);
    assert!(frame.covered_pixels() > 0, "the scene is in view");
}
