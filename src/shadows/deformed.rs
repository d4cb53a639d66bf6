//! Skinned and morphed shadow casters in the main world: what the shadow gather needs of
//! them before the render world poses them on the GPU (`shadows::posed`), as Bevy's vertex
//! stage poses them to draw them: whether they are skinned, and a sphere that holds them in
//! this frame's pose, which places them in the maps that can see them. No vertex is posed
//! or copied on the CPU: the cost is `O(joints)` per skinned caster, plus
//! `O(vertices × targets)` per morphed one (the reach of its weighted targets).
//!
//! A vertex `p` of the stored mesh is first moved by the morph targets,
//! `p' = p + Σ_t w_t · Δ_t` (`w_t` the entity's morph weights, `Δ_t` target `t`'s position
//! displacement), then, for a skinned mesh, placed in the world by its joints,
//! `P = Σ_k ω_k · (G_k · B_k) · p'` (`ω_k` the vertex's joint weights, `G_k` joint `k`'s
//! global transform, `B_k` its inverse bind matrix: glTF's skinning, and Bevy's), or else by
//! the entity's own transform, `P = world_from_local · p'`.

use super::views::Bounds;
use bevy::{
    asset::{AssetId, Assets},
    camera::primitives::{Aabb, MeshAabb},
    ecs::{entity::Entity, system::Query, system::Res, system::SystemParam},
    math::{Mat4, Vec3, Vec3A},
    mesh::{
        Mesh, MeshAccessError,
        morph::{MeshMorphWeights, MorphWeights},
        skinning::{
            SkinnedMesh, SkinnedMeshInverseBindposes, entity_aabb_from_skinned_mesh_bounds,
        },
    },
    shape::Aabb3d,
    transform::components::GlobalTransform,
};
use thiserror::Error;

/// Why a skinned or morphed mesh cannot be placed in the shadow maps (it then casts no
/// shadow).
#[derive(Debug, Error, PartialEq)]
pub(crate) enum DeformError {
    #[error(
        "its mesh keeps no vertex data in the main world (its `RenderAssetUsages` lacks \
         `MAIN_WORLD`), which bounding its pose needs"
    )]
    NoMainWorldData,
    #[error("its mesh lacks {0}")]
    Missing(&'static str),
    #[error("its mesh asset is not loaded yet")]
    MeshNotLoaded,
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

/// A skinned or morphed caster as the gather places it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pose {
    /// Whether its joints place it (its skin's joint matrices are world-from-local, so the
    /// map draws it with `clip_from_world`); otherwise its transform does.
    pub skinned: bool,
    /// A sphere holding every vertex in this frame's pose, world space.
    pub bounds: Bounds,
}

/// What placing a skinned or morphed caster reads. The asset collections are optional so
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
    /// How `entity`, drawn with `mesh`, is placed this frame. `aabb` is its local box where
    /// it has one (Bevy keeps it with the mesh's); without one the mesh's box is computed.
    pub fn pose(
        &self,
        entity: Entity,
        mesh: AssetId<Mesh>,
        world_from_local: Mat4,
        aabb: Option<&Aabb>,
    ) -> Result<Pose, DeformError> {
        let mesh = self
            .meshes
            .as_ref()
            .and_then(|meshes| meshes.get(mesh))
            .ok_or(DeformError::MeshNotLoaded)?;
        let local = || match aabb {
            Some(aabb) => Ok(*aabb),
            None => mesh.get_aabb().ok_or(DeformError::Missing("positions")),
        };
        let morph_reach = match self.morphs.get(entity) {
            Ok(morph) => morph_reach(mesh, self.morph_weights(morph))?,
            Err(_) => 0.0,
        };
        // Bevy skins a mesh only where its vertices have joints; otherwise it draws the mesh
        // with the entity's transform, skin or not.
        let has_joints = mesh.try_contains_attribute(Mesh::ATTRIBUTE_JOINT_INDEX)?
            && mesh.try_contains_attribute(Mesh::ATTRIBUTE_JOINT_WEIGHT)?;
        let Some(skin) = self.skins.get(entity).ok().filter(|_| has_joints) else {
            return Ok(Pose {
                skinned: false,
                bounds: placed_bounds(&[world_from_local], &local()?, morph_reach),
            });
        };
        let bind_poses = self
            .bind_poses
            .as_ref()
            .and_then(|poses| poses.get(&skin.inverse_bindposes))
            .filter(|poses| poses.len() >= skin.joints.len())
            .ok_or(DeformError::BindPosesNotReady)?;
        let joint_matrices = self.joint_matrices(skin, bind_poses)?;
        // Bevy's own bound from the mesh's per-joint boxes where it has them (glTF meshes
        // do), else every joint's placement of the whole mesh's box; both widened by the
        // morph targets' reach, as far as a joint stretches it.
        let bounds = match entity_aabb_from_skinned_mesh_bounds(
            &self.joints,
            mesh,
            skin,
            bind_poses,
            None,
        ) {
            Ok(aabb) if morph_reach == 0.0 => sphere_around(&aabb),
            _ => placed_bounds(&joint_matrices, &local()?, morph_reach),
        };
        Ok(Pose {
            skinned: true,
            bounds,
        })
    }

    /// The weights of a morphed entity (none where its source has no `MorphWeights`).
    fn morph_weights<'a>(&'a self, morph: &'a MeshMorphWeights) -> &'a [f32] {
        match morph {
            MeshMorphWeights::Reference(source) => self
                .weights
                .get(*source)
                .map(MorphWeights::weights)
                .unwrap_or(&[]),
            MeshMorphWeights::Value { weights } => weights.as_slice(),
        }
    }

    /// `G_k · B_k` for each joint `k` of `skin`.
    fn joint_matrices(
        &self,
        skin: &SkinnedMesh,
        bind_poses: &SkinnedMeshInverseBindposes,
    ) -> Result<Vec<Mat4>, DeformError> {
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

/// How far `Σ_t w_t · Δ_t` can move a vertex: `Σ_t |w_t| · max_v |Δ_t(v)|` (targets stored
/// target by target, each holding every vertex, as Bevy stores them).
fn morph_reach(mesh: &Mesh, weights: &[f32]) -> Result<f32, DeformError> {
    if !mesh.try_has_morph_targets()? {
        return Ok(0.0);
    }
    let targets = mesh.try_morph_targets()?;
    let count = mesh.try_attribute(Mesh::ATTRIBUTE_POSITION)?.len().max(1);
    Ok(targets
        .chunks(count)
        .zip(weights)
        .filter(|(_, weight)| **weight != 0.0)
        .map(|(target, weight)| {
            let longest = target
                .iter()
                .map(|displacement| displacement.position.length())
                .fold(0.0, f32::max);
            weight.abs() * longest
        })
        .sum())
}

/// A sphere holding `local` (a local-space box) placed by each of `placements`, widened by
/// `reach` local units in every direction (scaled by the placement that stretches most).
fn placed_bounds(placements: &[Mat4], local: &Aabb, reach: f32) -> Bounds {
    let half = Vec3::from(local.half_extents) + Vec3::splat(reach);
    let mut world = Aabb3d {
        min: Vec3A::INFINITY,
        max: Vec3A::NEG_INFINITY,
    };
    for placement in placements {
        let center = Vec3A::from(placement.transform_point3(Vec3::from(local.center)));
        // The box's half extents along the world axes: |M| · half.
        let extent = Vec3A::new(
            placement.row(0).truncate().abs().dot(half),
            placement.row(1).truncate().abs().dot(half),
            placement.row(2).truncate().abs().dot(half),
        );
        world.min = world.min.min(center - extent);
        world.max = world.max.max(center + extent);
    }
    sphere_around(&world)
}

/// The sphere around a box.
fn sphere_around(aabb: &Aabb3d) -> Bounds {
    Bounds {
        center: Vec3::from((aabb.min + aabb.max) / 2.0),
        radius: Vec3::from(aabb.max - aabb.min).length() / 2.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bevy::{
        asset::RenderAssetUsages,
        mesh::{PrimitiveTopology, morph::MorphAttributes},
    };

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
    fn morph_targets_reach_as_far_as_their_weighted_longest_displacement() {
        let displacement = |y: f32| MorphAttributes {
            position: Vec3::new(0.0, y, 0.0),
            ..Default::default()
        };
        // Two targets: the first lifts vertices by up to 1, the second by up to 10.
        let mesh = triangle()
            .with_morph_targets([0.5, 1.0, 0.0, 10.0, 2.0, 0.0].map(displacement).to_vec());
        assert_eq!(morph_reach(&mesh, &[0.5, -0.25]).unwrap(), 0.5 + 2.5);
        assert_eq!(morph_reach(&triangle(), &[1.0]).unwrap(), 0.0);
    }

    #[test]
    fn a_placed_box_is_held_by_the_sphere_of_every_placement() {
        let local = Aabb::from_min_max(Vec3::ZERO, Vec3::ONE);
        let placements = [
            Mat4::from_translation(Vec3::new(0.0, 0.0, 4.0)),
            Mat4::from_scale_rotation_translation(
                Vec3::splat(2.0),
                bevy::math::Quat::from_rotation_y(0.7),
                Vec3::new(0.0, 0.0, 8.0),
            ),
        ];
        let bounds = placed_bounds(&placements, &local, 0.25);
        for placement in &placements {
            for corner in 0..8 {
                let point = Vec3::new(
                    if corner & 1 == 0 { -0.25 } else { 1.25 },
                    if corner & 2 == 0 { -0.25 } else { 1.25 },
                    if corner & 4 == 0 { -0.25 } else { 1.25 },
                );
                let placed = placement.transform_point3(point);
                assert!(
                    placed.distance(bounds.center) <= bounds.radius * (1.0 + 1e-6),
                    "{placed} outside {bounds:?}"
                );
            }
        }
    }

    #[test]
    fn a_mesh_kept_in_the_render_world_only_is_reported() {
        let mut mesh = triangle();
        mesh.asset_usage = RenderAssetUsages::RENDER_WORLD;
        let _ = mesh.take_gpu_data();
        assert_eq!(
            morph_reach(&mesh, &[1.0]).unwrap_err(),
            DeformError::NoMainWorldData
        );
    }
}
