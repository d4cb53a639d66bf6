//! The test asset's skinned arm and morphed blob cast the shadow of their pose: the sun's
//! shadow on the ground against rays cast in `f64` through their triangles posed by the
//! reference below, judged as the other shadow tests are (`crate::shadows`: outside a band
//! around the exact shadow's edge, every pixel within the budget).

use super::{PHONG_TEST_GLTF, phong_only_gltf_harness, pose_at, spawn_gltf_scene};
use crate::{
    shadow_band::MapCover,
    shadows::{CaseLight, EVERYONE, Roles, Scene, Shape, Toward, exact_visibility, judge},
};
use bevy::{
    gltf::GltfMaterialName,
    light::NotShadowReceiver,
    math::{DMat4, DVec3},
    mesh::{
        Indices, VertexAttributeValues,
        morph::{MeshMorphWeights, MorphWeights},
        skinning::{SkinnedMesh, SkinnedMeshInverseBindposes},
    },
    prelude::*,
};
use bevy_phong::prelude::*;

/// Render size.
const SIZE: u32 = 128;
/// The pose: the end of the animations, the elbow bent fully and the blob fully lifted, its
/// silhouette toward the sun risen 0.3 (at half the animation, 0.15, a blob cast unmorphed
/// moved its shadow's edge by less than the band and passed).
const POSE_SECONDS: f32 = 1.0;
/// The camera looks down on the ground from the side the sun shines from, so that the
/// shadows, which fall toward −Z, are in view.
const CAMERA: Vec3 = Vec3::new(0.0, 7.0, 5.0);

/// `entity`'s mesh posed in `f64`, world space: morph targets first
/// (`p + Σ w_t Δ_t`), then the skin (`Σ ω_k · G_k · B_k · p`, glTF's skinning) or, without
/// one, the entity's transform.
fn posed_triangles(world: &mut World, entity: Entity) -> Vec<[DVec3; 3]> {
    let mesh = world.get::<Mesh3d>(entity).unwrap().id();
    let mesh = world.resource::<Assets<Mesh>>().get(mesh).unwrap();
    let Some(VertexAttributeValues::Float32x3(stored)) = mesh.attribute(Mesh::ATTRIBUTE_POSITION)
    else {
        panic!("positions");
    };
    let mut positions: Vec<DVec3> = stored
        .iter()
        .map(|p| Vec3::from_array(*p).as_dvec3())
        .collect();
    if let Some(morph) = world.get::<MeshMorphWeights>(entity) {
        let weights = match morph {
            MeshMorphWeights::Reference(node) => {
                world.get::<MorphWeights>(*node).unwrap().weights()
            }
            MeshMorphWeights::Value { weights } => weights,
        };
        let targets = mesh.get_morph_targets().unwrap();
        for (target, weight) in weights.iter().enumerate() {
            let displacements = &targets[target * positions.len()..(target + 1) * positions.len()];
            for (position, displacement) in positions.iter_mut().zip(displacements) {
                *position += f64::from(*weight) * displacement.position.as_dvec3();
            }
        }
    }
    if let Some(skin) = world.get::<SkinnedMesh>(entity) {
        let bind_poses = world
            .resource::<Assets<SkinnedMeshInverseBindposes>>()
            .get(&skin.inverse_bindposes)
            .unwrap();
        let joints: Vec<DMat4> = skin
            .joints
            .iter()
            .zip(bind_poses.iter())
            .map(|(joint, inverse_bind)| {
                let global = world.get::<GlobalTransform>(*joint).unwrap().to_matrix();
                global.as_dmat4() * inverse_bind.as_dmat4()
            })
            .collect();
        let Some(VertexAttributeValues::Uint16x4(indices)) =
            mesh.attribute(Mesh::ATTRIBUTE_JOINT_INDEX)
        else {
            panic!("joint indices");
        };
        let Some(VertexAttributeValues::Float32x4(weights)) =
            mesh.attribute(Mesh::ATTRIBUTE_JOINT_WEIGHT)
        else {
            panic!("joint weights");
        };
        for ((position, indices), weights) in positions.iter_mut().zip(indices).zip(weights) {
            *position = indices
                .iter()
                .zip(weights)
                .map(|(joint, weight)| {
                    f64::from(*weight) * joints[usize::from(*joint)].transform_point3(*position)
                })
                .sum();
        }
    } else {
        let world_from_local = world
            .get::<GlobalTransform>(entity)
            .unwrap()
            .to_matrix()
            .as_dmat4();
        for position in &mut positions {
            *position = world_from_local.transform_point3(*position);
        }
    }
    let order: Vec<usize> = match mesh.indices().unwrap() {
        Indices::U16(indices) => indices.iter().map(|i| usize::from(*i)).collect(),
        Indices::U32(indices) => indices.iter().map(|i| *i as usize).collect(),
    };
    order
        .chunks_exact(3)
        .map(|t| [positions[t[0]], positions[t[1]], positions[t[2]]])
        .collect()
}

#[test]
fn skinned_and_morphed_meshes_cast_the_shadow_of_their_pose() {
    let mut harness = phong_only_gltf_harness(SIZE, SIZE);
    harness.look_from(CAMERA);
    let gltf = spawn_gltf_scene(&mut harness, PHONG_TEST_GLTF);
    pose_at(&mut harness, &gltf, POSE_SECONDS);

    // One light to judge: the sun, its shadows on (its Phong mirror follows); the lamp
    // hidden. The fence is hidden too: the posed triangles below have no model of its alpha
    // mask's holes (`crate::shadows` judges masked casters on their own).
    let world = harness.world_mut();
    let mut suns = world.query::<&mut DirectionalLight>();
    for mut sun in suns.iter_mut(world) {
        sun.shadow_maps_enabled = true;
    }
    let lamps: Vec<Entity> = world
        .query_filtered::<Entity, With<PointLight>>()
        .iter(world)
        .collect();
    for lamp in lamps {
        world.entity_mut(lamp).insert(Visibility::Hidden);
    }
    // Plain opaque materials on the ground and the blob: this test is about where shadows
    // fall (the reference here has no texture maps, nor blending). The arm and the blob
    // receive no shadow (a bent arm shadows itself, which the convex shapes of the other
    // shadow tests do not); the ground receives them.
    let mut primitives = world.query_filtered::<(Entity, &GltfMaterialName), With<Mesh3d>>();
    let primitives: Vec<(Entity, String)> = primitives
        .iter(world)
        .map(|(entity, name)| (entity, name.0.clone()))
        .collect();
    let mut shapes = Vec::new();
    let mut ground = None;
    for (entity, name) in &primitives {
        let plain = PhongMaterial {
            base_color: Color::srgb(0.7, 0.7, 0.7),
            shininess: 16.0,
            ..default()
        };
        match name.as_str() {
            "FenceMask" => {
                world.entity_mut(*entity).insert(Visibility::Hidden);
                continue;
            }
            "GroundOpaque" => ground = Some(*entity),
            _ => {
                world.entity_mut(*entity).insert(NotShadowReceiver);
            }
        }
        let material = if name == "ArmDoubleSided" {
            world
                .get::<MeshMaterial3d<PhongMaterial>>(*entity)
                .unwrap()
                .0
                .clone()
        } else {
            let handle = world.resource_mut::<Assets<PhongMaterial>>().add(plain);
            world
                .entity_mut(*entity)
                .insert(MeshMaterial3d(handle.clone()));
            handle
        };
        let shape = if name == "GroundOpaque" {
            Shape::Floor { half: 5.0 }
        } else {
            Shape::Triangles(posed_triangles(world, *entity))
        };
        shapes.push((*entity, shape, material));
    }
    let ground = ground.expect("the ground");
    harness.settle();

    let world = harness.world_mut();
    let (sun, transform) = world
        .query::<(&PhongDirectionalLight, &GlobalTransform)>()
        .single(world)
        .expect("the sun's Phong mirror");
    assert!(sun.shadows.enabled, "the mirror casts shadows");
    let lights = [CaseLight {
        toward: Toward::Direction(transform.forward().as_dvec3()),
        settings: sun.shadows,
        cover: MapCover::Cascades(sun.cascades),
        of_other_kind: false,
    }];
    let scene = Scene { shapes };

    // The posed casters' shadows are in view: ground pixels the exact rays find blocked by
    // the arm and by the blob.
    let inputs = harness.capture_inputs();
    let ground_tag = inputs
        .materials
        .iter()
        .find(|(_, handle)| **handle == scene.shapes.iter().find(|s| s.0 == ground).unwrap().2)
        .map(|(tag, _)| *tag)
        .unwrap();
    for (entity, shape, _) in &scene.shapes {
        if *entity == ground {
            continue;
        }
        let shadowed = inputs
            .positions
            .pixels
            .iter()
            .filter(|p| p[3] as u32 == ground_tag)
            .filter(|p| {
                let position = DVec3::new(p[0].into(), p[1].into(), p[2].into());
                exact_visibility(position, lights[0].toward, std::slice::from_ref(shape)) == 0.0
            })
            .count();
        println!("{entity}: shadows {shadowed} ground pixels");
        assert!(
            shadowed >= 20,
            "{entity}'s shadow is in view: {shadowed} pixels"
        );
    }
    let roles = Roles {
        receiving: &|entity| entity == ground,
        ..EVERYONE
    };
    judge(&mut harness, &scene, &lights, &roles, &inputs).assert_holds("posed casters");
}
