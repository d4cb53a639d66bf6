//! Skinned and morphed shadow casters: their triangles in the pose of this frame, computed on
//! the CPU as Bevy's vertex stage computes them on the GPU, so that a shadow map draws what
//! the camera sees.
//!
//! A vertex `p` of the stored mesh is first moved by the morph targets,
//! `p' = p + Σ_t w_t · Δ_t` (`w_t` the entity's morph weights, `Δ_t` target `t`'s position
//! displacement), then, for a skinned mesh, placed in the world by its joints,
//! `P = Σ_k ω_k · (G_k · B_k) · p'` (`ω_k` the vertex's joint weights, `G_k` joint `k`'s
//! global transform, `B_k` its inverse bind matrix: glTF's skinning, and Bevy's), or else by
//! the entity's own transform, `P = world_from_local · p'`.

use bevy::{
    asset::{AssetId, Assets},
    ecs::{entity::Entity, system::Query, system::Res, system::SystemParam},
    math::{Mat4, Vec3},
    mesh::{
        Indices, Mesh, MeshAccessError, PrimitiveTopology, VertexAttributeValues,
        morph::{MeshMorphWeights, MorphWeights},
        skinning::{SkinnedMesh, SkinnedMeshInverseBindposes},
    },
    transform::components::GlobalTransform,
};
use thiserror::Error;

/// Why a skinned or morphed mesh cannot be posed on the CPU (it then casts no shadow).
#[derive(Debug, Error, PartialEq)]
pub(crate) enum DeformError {
    #[error(
        "its mesh keeps no vertex data in the main world (its `RenderAssetUsages` lacks \
         `MAIN_WORLD`)"
    )]
    NoMainWorldData,
    #[error("its mesh is not a triangle list or strip")]
    NotTriangles,
    #[error("its mesh lacks {0}")]
    Missing(&'static str),
    #[error("its mesh asset is not loaded yet")]
    MeshNotLoaded,
    #[error("its joint indices or weights are not one per vertex")]
    JointDataLength,
    #[error("its skin names joint {0}, which has no transform")]
    MissingJoint(usize),
    #[error("its skin's inverse bind matrices are not loaded, or fewer than its joints")]
    BindPosesNotReady,
}

impl DeformError {
    /// Whether the error is a state that loading ends (an asset not loaded yet), as opposed
    /// to one that lasts until the mesh or skin changes.
    pub(crate) fn is_loading(&self) -> bool {
        matches!(self, Self::MeshNotLoaded | Self::BindPosesNotReady)
    }
}

impl From<MeshAccessError> for DeformError {
    fn from(error: MeshAccessError) -> Self {
        match error {
            MeshAccessError::ExtractedToRenderWorld => DeformError::NoMainWorldData,
            MeshAccessError::NotFound => DeformError::Missing("data it needs"),
        }
    }
}

/// What posing a skinned or morphed caster reads. The asset collections are optional so
/// that an app without a mesh or skin asset type (a test app, say) still gathers shadows.
#[derive(SystemParam)]
pub(crate) struct Poses<'w, 's> {
    meshes: Option<Res<'w, Assets<Mesh>>>,
    bind_poses: Option<Res<'w, Assets<SkinnedMeshInverseBindposes>>>,
    joints: Query<'w, 's, &'static GlobalTransform>,
    skins: Query<'w, 's, &'static SkinnedMesh>,
    morphs: Query<'w, 's, &'static MeshMorphWeights>,
    weights: Query<'w, 's, &'static MorphWeights>,
}

impl Poses<'_, '_> {
    /// The triangles of `entity`'s `mesh` in this frame's pose, world space, three vertices
    /// each, appended to `vertices`.
    pub fn append_triangles(
        &self,
        entity: Entity,
        mesh: AssetId<Mesh>,
        world_from_local: Mat4,
        vertices: &mut Vec<Vec3>,
    ) -> Result<(), DeformError> {
        let mesh = self
            .meshes
            .as_ref()
            .and_then(|meshes| meshes.get(mesh))
            .ok_or(DeformError::MeshNotLoaded)?;
        let mut positions = local_positions(mesh)?;
        if let Ok(morph) = self.morphs.get(entity) {
            let weights = match morph {
                MeshMorphWeights::Reference(source) => self
                    .weights
                    .get(*source)
                    .map(MorphWeights::weights)
                    .unwrap_or(&[]),
                MeshMorphWeights::Value { weights } => weights.as_slice(),
            };
            apply_morph_targets(mesh, weights, &mut positions)?;
        }
        // Bevy skins a mesh only where its vertices have joints; otherwise it draws the mesh
        // with the entity's transform, skin or not.
        let has_joints = mesh.try_contains_attribute(Mesh::ATTRIBUTE_JOINT_INDEX)?
            && mesh.try_contains_attribute(Mesh::ATTRIBUTE_JOINT_WEIGHT)?;
        match self.skins.get(entity).ok().filter(|_| has_joints) {
            Some(skin) => {
                let joint_matrices = self.joint_matrices(skin)?;
                skin_positions(mesh, &joint_matrices, &mut positions)?;
            }
            None => {
                for position in &mut positions {
                    *position = world_from_local.transform_point3(*position);
                }
            }
        }
        append_triangle_list(mesh, &positions, vertices)
    }

    /// `G_k · B_k` for each joint `k` of `skin`.
    fn joint_matrices(&self, skin: &SkinnedMesh) -> Result<Vec<Mat4>, DeformError> {
        let bind_poses = self
            .bind_poses
            .as_ref()
            .and_then(|poses| poses.get(&skin.inverse_bindposes))
            .filter(|poses| poses.len() >= skin.joints.len())
            .ok_or(DeformError::BindPosesNotReady)?;
        skin.joints
            .iter()
            .zip(bind_poses.iter())
            .enumerate()
            .map(|(index, (joint, inverse_bind))| {
                let global = self
                    .joints
                    .get(*joint)
                    .map_err(|_| DeformError::MissingJoint(index))?;
                Ok(global.to_matrix() * *inverse_bind)
            })
            .collect()
    }
}

/// The stored positions of `mesh`.
fn local_positions(mesh: &Mesh) -> Result<Vec<Vec3>, DeformError> {
    match mesh.try_attribute(Mesh::ATTRIBUTE_POSITION)? {
        VertexAttributeValues::Float32x3(positions) => {
            Ok(positions.iter().map(|p| Vec3::from_array(*p)).collect())
        }
        _ => Err(DeformError::Missing("Float32x3 positions")),
    }
}

/// Adds `Σ_t w_t · Δ_t` to each position (targets stored target by target, each holding
/// every vertex, as Bevy stores them).
fn apply_morph_targets(
    mesh: &Mesh,
    weights: &[f32],
    positions: &mut [Vec3],
) -> Result<(), DeformError> {
    let Some(targets) = mesh.get_morph_targets() else {
        return Ok(());
    };
    let count = positions.len();
    for (target, weight) in weights.iter().enumerate() {
        if *weight == 0.0 {
            continue;
        }
        let Some(displacements) = targets.get(target * count..(target + 1) * count) else {
            break;
        };
        for (position, displacement) in positions.iter_mut().zip(displacements) {
            *position += *weight * displacement.position;
        }
    }
    Ok(())
}

/// Places each position in the world by its joints: `Σ_k ω_k · joint_matrices[j_k] · p`.
fn skin_positions(
    mesh: &Mesh,
    joint_matrices: &[Mat4],
    positions: &mut [Vec3],
) -> Result<(), DeformError> {
    let indices: Vec<[u16; 4]> = match mesh.try_attribute(Mesh::ATTRIBUTE_JOINT_INDEX)? {
        VertexAttributeValues::Uint16x4(indices) => indices.clone(),
        VertexAttributeValues::Uint8x4(indices) => {
            indices.iter().map(|i| i.map(u16::from)).collect()
        }
        _ => return Err(DeformError::Missing("joint indices")),
    };
    let VertexAttributeValues::Float32x4(weights) =
        mesh.try_attribute(Mesh::ATTRIBUTE_JOINT_WEIGHT)?
    else {
        return Err(DeformError::Missing("Float32x4 joint weights"));
    };
    if indices.len() != positions.len() || weights.len() != positions.len() {
        return Err(DeformError::JointDataLength);
    }
    for ((position, joints), weights) in positions.iter_mut().zip(&indices).zip(weights) {
        let mut skinned = Vec3::ZERO;
        // A joint of weight 0 is padding: its index need not name a joint.
        for (joint, weight) in joints.iter().zip(weights).filter(|(_, w)| **w != 0.0) {
            let matrix = joint_matrices
                .get(usize::from(*joint))
                .ok_or(DeformError::MissingJoint(usize::from(*joint)))?;
            skinned += *weight * matrix.transform_point3(*position);
        }
        *position = skinned;
    }
    Ok(())
}

/// Appends `mesh`'s triangles, with `positions` for its vertices, three vertices each.
fn append_triangle_list(
    mesh: &Mesh,
    positions: &[Vec3],
    vertices: &mut Vec<Vec3>,
) -> Result<(), DeformError> {
    let order: Vec<usize> = match mesh.try_indices_option()? {
        Some(Indices::U16(indices)) => indices.iter().map(|i| usize::from(*i)).collect(),
        Some(Indices::U32(indices)) => indices.iter().map(|i| *i as usize).collect(),
        None => (0..positions.len()).collect(),
    };
    let vertex = |index: usize| positions.get(index).copied();
    let start = vertices.len();
    let appended = match mesh.primitive_topology() {
        PrimitiveTopology::TriangleList => {
            order
                .chunks_exact(3)
                .try_for_each(|triangle| -> Option<()> {
                    for index in triangle {
                        vertices.push(vertex(*index)?);
                    }
                    Some(())
                })
        }
        PrimitiveTopology::TriangleStrip => order.windows(3).try_for_each(|window| -> Option<()> {
            for index in window {
                vertices.push(vertex(*index)?);
            }
            Some(())
        }),
        _ => return Err(DeformError::NotTriangles),
    };
    if appended.is_none() {
        vertices.truncate(start);
        return Err(DeformError::Missing("vertices its indices name"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use bevy::{asset::RenderAssetUsages, mesh::morph::MorphAttributes};

    fn triangle() -> Mesh {
        Mesh::new(
            PrimitiveTopology::TriangleList,
            RenderAssetUsages::default(),
        )
        .with_inserted_attribute(
            Mesh::ATTRIBUTE_POSITION,
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        )
    }

    #[test]
    fn morph_targets_add_their_weighted_displacements() {
        let displacement = |y: f32| MorphAttributes {
            position: Vec3::new(0.0, y, 0.0),
            ..Default::default()
        };
        // Two targets: the first lifts every vertex by 1, the second by 10.
        let mesh = triangle()
            .with_morph_targets([1.0, 1.0, 1.0, 10.0, 10.0, 10.0].map(displacement).to_vec());
        let mut positions = local_positions(&mesh).unwrap();
        apply_morph_targets(&mesh, &[0.5, 0.25], &mut positions).unwrap();
        assert_eq!(positions[1], Vec3::new(1.0, 3.0, 0.0));
    }

    #[test]
    fn joints_blend_by_weight() {
        let mesh = triangle()
            .with_inserted_attribute(
                Mesh::ATTRIBUTE_JOINT_INDEX,
                VertexAttributeValues::Uint16x4(vec![[0, 1, 0, 0]; 3]),
            )
            .with_inserted_attribute(
                Mesh::ATTRIBUTE_JOINT_WEIGHT,
                vec![[0.25f32, 0.75, 0.0, 0.0]; 3],
            );
        let joints = [
            Mat4::from_translation(Vec3::new(0.0, 0.0, 4.0)),
            Mat4::from_translation(Vec3::new(0.0, 0.0, 8.0)),
        ];
        let mut positions = local_positions(&mesh).unwrap();
        skin_positions(&mesh, &joints, &mut positions).unwrap();
        // 0.25 · (p + 4z) + 0.75 · (p + 8z) = p + 7z.
        assert_eq!(positions[1], Vec3::new(1.0, 0.0, 7.0));
    }

    #[test]
    fn padding_joints_of_weight_zero_need_not_exist_and_joint_data_must_cover_every_vertex() {
        let skinned = |weights: Vec<[f32; 4]>| {
            triangle()
                .with_inserted_attribute(
                    Mesh::ATTRIBUTE_JOINT_INDEX,
                    VertexAttributeValues::Uint16x4(vec![[0, 9, 9, 9]; 3]),
                )
                .with_inserted_attribute(Mesh::ATTRIBUTE_JOINT_WEIGHT, weights)
        };
        let joints = [Mat4::from_translation(Vec3::Z)];
        let mesh = skinned(vec![[1.0, 0.0, 0.0, 0.0]; 3]);
        let mut positions = local_positions(&mesh).unwrap();
        skin_positions(&mesh, &joints, &mut positions).unwrap();
        assert_eq!(positions[1], Vec3::new(1.0, 0.0, 1.0));

        let short = skinned(vec![[1.0, 0.0, 0.0, 0.0]; 2]);
        let mut positions = local_positions(&short).unwrap();
        assert_eq!(
            skin_positions(&short, &joints, &mut positions),
            Err(DeformError::JointDataLength)
        );
        let named = skinned(vec![[0.5, 0.5, 0.0, 0.0]; 3]);
        assert_eq!(
            skin_positions(&named, &joints, &mut positions),
            Err(DeformError::MissingJoint(9))
        );
    }

    #[test]
    fn strips_become_lists_and_bad_indices_are_an_error() {
        let mut vertices = Vec::new();
        let strip = Mesh::new(
            PrimitiveTopology::TriangleStrip,
            RenderAssetUsages::default(),
        )
        .with_inserted_attribute(
            Mesh::ATTRIBUTE_POSITION,
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        )
        .with_inserted_indices(Indices::U16(vec![0, 1, 2, 0]));
        let positions = local_positions(&strip).unwrap();
        append_triangle_list(&strip, &positions, &mut vertices).unwrap();
        assert_eq!(vertices.len(), 6, "two triangles");

        let broken = triangle().with_inserted_indices(Indices::U16(vec![0, 1, 7]));
        assert!(append_triangle_list(&broken, &positions, &mut vertices).is_err());
        assert_eq!(vertices.len(), 6, "nothing appended");
    }

    #[test]
    fn a_mesh_kept_in_the_render_world_only_is_reported() {
        let mut mesh = triangle();
        mesh.asset_usage = RenderAssetUsages::RENDER_WORLD;
        let _ = mesh.take_gpu_data();
        assert_eq!(
            local_positions(&mesh).unwrap_err(),
            DeformError::NoMainWorldData
        );
    }
}
