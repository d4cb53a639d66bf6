//! The crowd: 100 skinned meshes of 5,041 vertices each (a sheet of 70 × 70 quads, bent in
//! its middle by a second joint), every one bending every frame, casting into a directional
//! light's four cascades, seen by one camera.
//!
//! - `crowd/frame_shadows_on` and `crowd/frame_shadows_off`: one main-world frame
//!   (`App::update`, no renderer) of the crowd with the light's shadows on and off, two apps
//!   updated in turn. Their difference is what the shadow casters cost the main world: the
//!   light's request, placing the 100 casters in the maps, laying out the maps.
//! - `crowd/cpu_posing`: posing the 100 meshes' triangles on the CPU, as the shadow gather
//!   did before the maps posed them on the GPU (the same arithmetic, kept here to measure
//!   against: `Σ_k ω_k · J_k · p` per vertex, then the triangle list).

use bevy::{
    camera::{primitives::MeshAabb, visibility::InheritedVisibility},
    mesh::{
        Indices, VertexAttributeValues,
        skinning::{SkinnedMesh, SkinnedMeshInverseBindposes},
    },
    prelude::*,
};
use bevy_phong::prelude::*;
use criterion::Criterion;
use std::time::{Duration, Instant};

/// Crowd members.
const MEMBERS: usize = 100;
/// Quads along each side of a member's sheet: (70 + 1)² = 5,041 vertices.
const QUADS: u32 = 70;

/// A sheet two units wide in the xz plane whose vertices follow joint 0 left of x = −0.5,
/// joint 1 right of x = 0.5, and a blend of both between.
fn member_mesh() -> Mesh {
    let mut mesh = Plane3d::default()
        .mesh()
        .size(2.0, 2.0)
        .subdivisions(QUADS - 1)
        .build();
    let Some(VertexAttributeValues::Float32x3(positions)) =
        mesh.attribute(Mesh::ATTRIBUTE_POSITION)
    else {
        unreachable!("a plane has positions");
    };
    let weights: Vec<[f32; 4]> = positions
        .iter()
        .map(|p| {
            let bent = (p[0] + 0.5).clamp(0.0, 1.0);
            [1.0 - bent, bent, 0.0, 0.0]
        })
        .collect();
    let count = weights.len();
    mesh.insert_attribute(
        Mesh::ATTRIBUTE_JOINT_INDEX,
        VertexAttributeValues::Uint16x4(vec![[0, 1, 0, 0]; count]),
    );
    mesh.insert_attribute(Mesh::ATTRIBUTE_JOINT_WEIGHT, weights);
    mesh.with_generated_skinned_mesh_bounds()
        .expect("the sheet's joint data is complete")
}

/// The crowd in a main-world app with the plugin, the light casting shadows or not, and
/// the joints that bend.
fn crowd_app(shadows: bool) -> (App, Vec<Entity>) {
    let mut app = super::main_world_app();
    app.init_asset::<Mesh>()
        .init_asset::<SkinnedMeshInverseBindposes>();
    app.update();
    let world = app.world_mut();
    let mesh = member_mesh();
    let aabb = mesh.get_aabb().expect("the sheet has positions");
    let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
    let bind_poses = world
        .resource_mut::<Assets<SkinnedMeshInverseBindposes>>()
        .add(SkinnedMeshInverseBindposes::from(vec![Mat4::IDENTITY; 2]));
    let mut bends = Vec::with_capacity(MEMBERS);
    for member in 0..MEMBERS {
        let at = Vec3::new((member % 10) as f32 * 3.0, 1.0, (member / 10) as f32 * 3.0);
        let root = world
            .spawn((
                Mesh3d(mesh.clone()),
                aabb,
                Transform::from_translation(at),
                InheritedVisibility::VISIBLE,
            ))
            .id();
        let bend = world.spawn((Transform::default(), ChildOf(root))).id();
        world.entity_mut(root).insert(SkinnedMesh {
            inverse_bindposes: bind_poses.clone(),
            joints: vec![root, bend],
        });
        bends.push(bend);
    }
    world.spawn((
        PhongDirectionalLight {
            shadows: PhongShadows {
                enabled: shadows,
                ..PhongShadows::ON
            },
            ..default()
        },
        Transform::default().looking_to(Vec3::new(-0.4, -1.0, -0.3), Vec3::Y),
        InheritedVisibility::VISIBLE,
    ));
    let transform =
        Transform::from_xyz(13.5, 20.0, 40.0).looking_at(Vec3::new(13.5, 0.0, 13.5), Vec3::Y);
    let projection = Projection::default();
    let frustum = projection.compute_frustum(&GlobalTransform::from(transform));
    world.spawn((Camera3d::default(), projection, frustum, transform));
    app.update();
    (app, bends)
}

/// Bends every member's second joint, back and forth with `odd`.
fn bend(app: &mut App, bends: &[Entity], odd: bool) {
    let angle = if odd { 0.6 } else { 0.2 };
    for &joint in bends {
        if let Some(mut transform) = app.world_mut().get_mut::<Transform>(joint) {
            transform.rotation = Quat::from_rotation_z(angle);
        }
    }
}

/// The triangles of `mesh` posed by `joints` (`G_k · B_k`), world space, appended to
/// `triangles`: the CPU posing of a skinned caster.
fn pose_on_cpu(mesh: &Mesh, joints: &[Mat4], triangles: &mut Vec<Vec3>) {
    let (
        Some(VertexAttributeValues::Float32x3(positions)),
        Some(VertexAttributeValues::Uint16x4(indices)),
        Some(VertexAttributeValues::Float32x4(weights)),
        Some(Indices::U32(order)),
    ) = (
        mesh.attribute(Mesh::ATTRIBUTE_POSITION),
        mesh.attribute(Mesh::ATTRIBUTE_JOINT_INDEX),
        mesh.attribute(Mesh::ATTRIBUTE_JOINT_WEIGHT),
        mesh.indices(),
    )
    else {
        unreachable!("the sheet's attributes");
    };
    let posed: Vec<Vec3> = positions
        .iter()
        .zip(indices)
        .zip(weights)
        .map(|((position, joint), weight)| {
            let p = Vec3::from_array(*position);
            joint
                .iter()
                .zip(weight)
                .filter(|(_, w)| **w != 0.0)
                .map(|(k, w)| *w * joints[usize::from(*k)].transform_point3(p))
                .sum()
        })
        .collect();
    triangles.extend(order.iter().map(|&index| posed[index as usize]));
}

pub fn crowd(c: &mut Criterion) {
    let mut group = c.benchmark_group("crowd");
    let (mut on, on_bends) = crowd_app(true);
    let (mut off, off_bends) = crowd_app(false);
    let frame = |app: &mut App, bends: &[Entity], iterations: u64| {
        let mut total = Duration::ZERO;
        for iteration in 0..iterations {
            bend(app, bends, iteration % 2 == 1);
            let start = Instant::now();
            app.update();
            total += start.elapsed();
        }
        total
    };
    group.bench_function("frame_shadows_on", |b| {
        b.iter_custom(|iterations| frame(&mut on, &on_bends, iterations))
    });
    group.bench_function("frame_shadows_off", |b| {
        b.iter_custom(|iterations| frame(&mut off, &off_bends, iterations))
    });

    let world = on.world_mut();
    let members: Vec<(Handle<Mesh>, Vec<Entity>)> = world
        .query::<(&Mesh3d, &SkinnedMesh)>()
        .iter(world)
        .map(|(mesh, skin)| (mesh.0.clone(), skin.joints.clone()))
        .collect();
    group.bench_function("cpu_posing", |b| {
        let mut triangles = Vec::new();
        b.iter(|| {
            triangles.clear();
            let meshes = world.resource::<Assets<Mesh>>();
            for (mesh, joints) in &members {
                let joints: Vec<Mat4> = joints
                    .iter()
                    .map(|&joint| world.get::<GlobalTransform>(joint).unwrap().to_matrix())
                    .collect();
                pose_on_cpu(meshes.get(mesh).unwrap(), &joints, &mut triangles);
            }
            triangles.len()
        })
    });
    group.finish();
}
