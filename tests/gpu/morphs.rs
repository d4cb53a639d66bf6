//! Two morphed meshes side by side, one mesh asset with different weights: each must be
//! drawn, prepassed and cast its shadow with its own weights.
//!
//! Bevy 0.20's morph functions take a morph descriptor index where Bevy 0.19's took the
//! instance index; both are `u32`, so a call left unported compiles and reads another mesh's
//! weights. The crate has its own copies of Bevy's vertex stages (a displaced material's main
//! pass and prepass, `phong_vertex.wesl`, `phong_prepass_vertex.wesl`) and its own shadow
//! caster (`shadow_caster.wesl`, posed by `src/shadows/posed.rs`): all three are on this
//! test's path. The mesh is a cube (24 vertices: WebGL2's limits keep a morphed mesh's
//! targets in a texture of at most 28 vertices) whose one morph target lifts every vertex by
//! `LIFT`, so each posed cube is a cube again, `weight · LIFT` above where it was: its surface
//! and its shadow have a closed form that no shader computes.
//!
//! - Main pass: every pixel tagged with a cube's material lies on that cube as its weight
//!   places it, and every pixel's color is the reference model's, with shadows judged against
//!   rays to the posed cubes (`shadows::judge`).
//! - Prepass: the same frame drawn with Bevy's depth and normal prepasses; the main pass
//!   keeps only the fragments at the prepass's depth, so a cube the prepass placed elsewhere
//!   leaves holes and stray occlusions that the judge sees.
//! - Shadow maps: the floor receives both cubes' shadows from a directional light.
//!
//! And a morph target that turns normals, lit on each vertex stage against its closed form.

use crate::{
    frames::TOLERANCE,
    shadow_band::MapCover,
    shadows::{CaseLight, EVERYONE, Scene, Shape, Toward, judge},
    texture_maps::float_map,
};
use bevy::{
    core_pipeline::prepass::{DepthPrepass, NormalPrepass},
    mesh::morph::{MeshMorphWeights, MorphAttributes},
    prelude::*,
};
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;
use glam::DVec3;

/// Render size.
const SIZE: u32 = 128;
/// The morph target's offset of every vertex (world units; the cubes are not rotated or
/// scaled).
const LIFT: Vec3 = Vec3::new(0.0, 1.0, 0.0);
/// Half the cubes' edge before displacement.
const HALF: f32 = 0.4;
/// The materials' displacement: a constant map (`red · scale + bias`) with scale and bias 0,
/// which moves no vertex but puts the meshes on the crate's own vertex stages and its
/// displaced caster. (A displacement of a cube, whose vertices carry their face's normal,
/// would open cracks along its edges.)
const DISPLACEMENT: f32 = 0.0;
/// The two cubes: where each stands unposed and its weight. The weights differ by 0.6, so
/// a cube posed with the other's weight is 0.6 from where it belongs.
const CUBES: [(Vec3, f32); 2] = [
    (Vec3::new(-1.0, 0.6, 0.0), 0.15),
    (Vec3::new(1.0, 0.6, 0.3), 0.75),
];
/// How far a pixel of a cube may lie from the posed cube's faces: the read-back positions'
/// rounding (a few 1e-7 at these coordinates) and the posed vertices' (measured on lavapipe:
/// 1.4e-4 for the cube of weight 0.15, 2.7e-7 for the other), with room. Another mesh's
/// weight would move a cube by 0.6.
const ON_FACE: f64 = 1e-3;

/// The morphed cube: one target, `LIFT` on every vertex (normals and tangents unchanged).
fn lifted_cube() -> Mesh {
    let mesh = Mesh::from(Cuboid::from_length(2.0 * HALF));
    let vertices = mesh.count_vertices();
    mesh.with_morph_targets(vec![
        MorphAttributes::new(LIFT, Vec3::ZERO, Vec3::ZERO);
        vertices
    ])
}

/// The distance from `point` to the surface of the axis-aligned box at `center` with
/// half-extents `half` (negative inside).
fn box_distance(point: DVec3, center: DVec3, half: DVec3) -> f64 {
    let q = (point - center).abs() - half;
    q.max(DVec3::ZERO).length() + q.max_element().min(0.0)
}

#[test]
fn two_morphed_meshes_are_drawn_prepassed_and_cast_shadows_with_their_own_weights() {
    for prepass in [false, true] {
        let case = if prepass {
            "morphed, with depth and normal prepasses"
        } else {
            "morphed"
        };
        let mut harness = Harness::new(SIZE, SIZE);
        harness.look_from(Vec3::new(0.0, 3.0, 5.5));
        if prepass {
            harness.camera_mut().insert((DepthPrepass, NormalPrepass));
        }
        let world = harness.world_mut();
        world.insert_resource(PhongAmbientLight {
            color: Color::srgb(0.2, 0.2, 0.25),
        });
        let shadows = PhongShadows {
            enabled: true,
            ..default()
        };
        let direction = Vec3::new(0.3, -1.0, -0.4).normalize();
        world.spawn((
            PhongDirectionalLight {
                color: Color::linear_rgb(0.9, 0.9, 0.9),
                shadows,
                ..default()
            },
            Transform::default().looking_to(direction, Vec3::Z),
        ));
        let lights = [CaseLight {
            toward: Toward::Direction(direction.as_dvec3()),
            settings: shadows,
            cover: MapCover::Cascades(PhongCascades::default()),
            of_other_kind: false,
        }];
        let flat = world
            .resource_mut::<Assets<Image>>()
            .add(float_map(|_, _| [0.5, 0.0, 0.0, 1.0]));
        let mesh = world.resource_mut::<Assets<Mesh>>().add(lifted_cube());
        let floor_mesh = world
            .resource_mut::<Assets<Mesh>>()
            .add(Plane3d::default().mesh().size(8.0, 8.0));
        let floor_material = world
            .resource_mut::<Assets<PhongMaterial>>()
            .add(PhongMaterial {
                base_color: Color::srgb(0.7, 0.7, 0.7),
                shininess: 8.0,
                ..default()
            });
        let floor = world
            .spawn((Mesh3d(floor_mesh), MeshMaterial3d(floor_material.clone())))
            .id();
        let mut shapes = vec![(floor, Shape::Floor { half: 4.0 }, floor_material)];
        for (index, (position, weight)) in CUBES.into_iter().enumerate() {
            let material = world
                .resource_mut::<Assets<PhongMaterial>>()
                .add(PhongMaterial {
                    base_color: [Color::srgb(0.9, 0.3, 0.2), Color::srgb(0.2, 0.4, 0.9)][index],
                    shininess: 30.0,
                    displacement_map: Some(flat.clone()),
                    displacement_scale: 0.0,
                    displacement_bias: DISPLACEMENT,
                    ..default()
                });
            let entity = world
                .spawn((
                    Mesh3d(mesh.clone()),
                    MeshMaterial3d(material.clone()),
                    MeshMorphWeights::Value {
                        weights: vec![weight],
                    },
                    Transform::from_translation(position),
                ))
                .id();
            let center = (position + weight * LIFT).as_dvec3();
            let half = DVec3::splat(f64::from(HALF + DISPLACEMENT));
            shapes.push((
                entity,
                Shape::Box {
                    center,
                    half,
                    yaw: 0.0,
                },
                material,
            ));
        }
        let scene = Scene { shapes };
        harness.settle();
        let inputs = harness.capture_inputs();

        // Each cube's pixels lie on it as its own weight places it.
        let camera = harness.camera_position();
        for (_, shape, material) in &scene.shapes[1..] {
            let Shape::Box { center, half, .. } = *shape else {
                unreachable!("the cubes follow the floor")
            };
            let mut on_it = 0;
            let mut largest = 0.0_f64;
            for index in 0..inputs.positions.pixels.len() {
                let Some((drawn, surface)) = inputs.surface_at(index, camera) else {
                    continue;
                };
                if drawn != material {
                    continue;
                }
                let off = box_distance(surface.position, center, half);
                largest = largest.max(off.abs());
                assert!(
                    off.abs() <= ON_FACE,
                    "{case}: a pixel of the cube centred at {center} lies {off:.4} from it \
                     (posed with another mesh's weight?)"
                );
                on_it += 1;
            }
            assert!(
                on_it >= 200,
                "{case}: {on_it} pixels of the cube at {center}"
            );
            println!(
                "{case}: {on_it} pixels of the cube at {center}, largest distance {largest:.3e}"
            );
        }
        judge(&mut harness, &scene, &lights, &EVERYONE, &inputs).assert_holds(case);
    }
}

/// How far the morph target turns each vertex normal: `n + w·Δn` with
/// `Δn = (sin 60°, cos 60° − 1, 0)` turns the floor's `+Y` toward `+X` (60° at weight 1).
const NORMAL_TURN: f32 = std::f32::consts::FRAC_PI_3;
/// The weight each quad is posed at.
const NORMAL_WEIGHT: f32 = 0.7;

/// A flat quad at `y = 0` whose one morph target moves no vertex but turns every normal by
/// [`NORMAL_TURN`] (a glTF face's blend shape carries such normal deltas).
fn quad_with_turning_normals() -> Mesh {
    let mesh: Mesh = Plane3d::default().mesh().size(1.6, 1.6).into();
    let vertices = mesh.count_vertices();
    let delta = Vec3::new(NORMAL_TURN.sin(), NORMAL_TURN.cos() - 1.0, 0.0);
    mesh.with_morph_targets(vec![
        MorphAttributes::new(Vec3::ZERO, delta, Vec3::ZERO);
        vertices
    ])
}

/// A morphed face is lit by its moved normals, on each vertex stage a Phong mesh can take:
/// Bevy's (a plain material), the crate's (a displaced one) and the crate's per-vertex one.
/// The expectation is the closed form of SPEC.md's equation without a highlight, on the
/// posed normal `normalize(n + w·Δn)` worked here: `k_d ⊙ (ambient + c · max(N·L, 0))`, one
/// color per quad. Captured positions are only checked to lie on the quads' plane (the
/// target moves no vertex); no captured normal is read.
#[test]
fn morph_targets_turn_the_normals_each_vertex_stage_lights_with() {
    let mut harness = Harness::new(SIZE, SIZE);
    harness.look_from(Vec3::new(0.0, 4.0, 2.5));
    let world = harness.world_mut();
    let ambient = Vec3::splat(0.1);
    world.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(ambient.x, ambient.y, ambient.z),
    });
    let light_color = Vec3::new(0.9, 0.8, 0.7);
    // Toward the light: up and toward +X, so that the turned normal faces it more.
    let to_light = Vec3::new(0.8, 1.0, 0.3).normalize();
    world.spawn((
        PhongDirectionalLight {
            color: Color::linear_rgb(light_color.x, light_color.y, light_color.z),
            ..default()
        },
        Transform::default().looking_to(-to_light, Vec3::Z),
    ));
    let flat = world
        .resource_mut::<Assets<Image>>()
        .add(float_map(|_, _| [0.5, 0.0, 0.0, 1.0]));
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(quad_with_turning_normals());
    let base = Vec3::new(0.8, 0.6, 0.4);
    let plain = PhongMaterial {
        base_color: Color::linear_rgb(base.x, base.y, base.z),
        specular_strength: 0.0,
        ..default()
    };
    let stages = [
        ("Bevy's vertex stage", plain.clone()),
        (
            "the crate's displaced vertex stage",
            PhongMaterial {
                displacement_map: Some(flat),
                displacement_scale: 0.0,
                displacement_bias: 0.0,
                ..plain.clone()
            },
        ),
        (
            "the crate's per-vertex stage",
            PhongMaterial {
                vertex_lighting: true,
                ..plain
            },
        ),
    ];
    let mut materials = Vec::new();
    for (index, (stage, material)) in stages.into_iter().enumerate() {
        let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
        world.spawn((
            Mesh3d(mesh.clone()),
            MeshMaterial3d(material.clone()),
            MeshMorphWeights::Value {
                weights: vec![NORMAL_WEIGHT],
            },
            Transform::from_xyz(-1.8 + 1.8 * index as f32, 0.0, 0.0),
        ));
        materials.push((stage, material));
    }
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs();
    let camera = harness.camera_position();

    // The posed normal and the color it gives, worked from the target's delta.
    let posed = (Vec3::Y
        + NORMAL_WEIGHT * Vec3::new(NORMAL_TURN.sin(), NORMAL_TURN.cos() - 1.0, 0.0))
    .normalize()
    .as_dvec3();
    let n_dot_l = posed.dot(to_light.as_dvec3()).max(0.0);
    let expected = base.as_dvec3() * (ambient.as_dvec3() + light_color.as_dvec3() * n_dot_l);
    let unturned =
        base.as_dvec3() * (ambient.as_dvec3() + light_color.as_dvec3() * f64::from(to_light.y));
    assert!(
        (expected - unturned).abs().max_element() > 0.05,
        "the turn shows: {expected} against {unturned} unturned"
    );
    for (stage, material) in &materials {
        let (mut pixels, mut largest) = (0, 0.0_f64);
        for index in 0..inputs.positions.pixels.len() {
            let Some((drawn, surface)) = inputs.surface_at(index, camera) else {
                continue;
            };
            if drawn != material {
                continue;
            }
            assert!(
                surface.position.y.abs() < 1e-5,
                "{stage}: a pixel off the plane"
            );
            let color = rendered.pixels[index];
            let error = (0..3)
                .map(|c| (f64::from(color[c]) - expected[c]).abs())
                .fold(0.0, f64::max);
            largest = largest.max(error);
            pixels += 1;
        }
        println!("{stage}: {pixels} pixels, largest error {largest:.2e}");
        assert!(pixels > 300, "{stage}: {pixels} pixels of its quad");
        assert!(
            largest <= TOLERANCE,
            "{stage}: a morphed face lit {largest:.3e} away from its posed normal's color \
             {expected} (the normal left unturned gives {unturned})"
        );
    }
}
