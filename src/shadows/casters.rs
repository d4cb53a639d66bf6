//! The meshes that cast shadows this frame: each visible caster's triangles (as stored, or
//! posed on the GPU for skinned and morphed meshes), its place, its bounds (grown by how far
//! its displacement map moves a vertex) and its material's displacement and mask.

use super::{
    deformed::Poses,
    displaced::CasterDisplacement,
    instance::{CasterSource, ShadowInstance},
    masked::CasterMask,
    views::Bounds,
};
use crate::material::PhongMaterial;
use bevy::{
    asset::Assets,
    camera::{primitives::Aabb, visibility::InheritedVisibility},
    ecs::{
        entity::{Entity, EntityHashSet},
        query::{Has, Without},
        system::{Query, Res, SystemParam},
    },
    light::NotShadowCaster,
    log::warn,
    math::{Mat4, Vec3},
    mesh::{Mesh3d, morph::MeshMorphWeights, skinning::SkinnedMesh},
    pbr::MeshMaterial3d,
    transform::components::GlobalTransform,
};

/// A visible mesh that casts shadows.
pub(crate) struct Caster {
    pub source: CasterSource,
    world_from_local: Mat4,
    /// A sphere around it in world space.
    pub bounds: Bounds,
    displacement: Option<CasterDisplacement>,
    mask: Option<CasterMask>,
}

impl Caster {
    /// The caster as a map whose view is `clip_from_world` draws it.
    pub fn instance(&self, clip_from_world: Mat4) -> ShadowInstance {
        ShadowInstance {
            source: self.source.clone(),
            clip_from_local: clip_from_world * self.world_from_local,
            displacement: self.displacement.clone(),
            mask: self.mask.clone(),
        }
    }
}

/// What the gather reads of each mesh that may cast, and whether it is skinned or morphed.
type CasterData = (
    Entity,
    &'static Mesh3d,
    &'static GlobalTransform,
    Option<&'static Aabb>,
    &'static InheritedVisibility,
    Has<SkinnedMesh>,
    Has<MeshMorphWeights>,
    Option<&'static MeshMaterial3d<PhongMaterial>>,
);

/// The meshes that may cast shadows (all but `NotShadowCaster` ones), their materials, and
/// the poses of the skinned and morphed ones.
#[derive(SystemParam)]
pub(crate) struct CasterSet<'w, 's> {
    meshes: Query<'w, 's, CasterData, Without<NotShadowCaster>>,
    materials: Res<'w, Assets<PhongMaterial>>,
    poses: Poses<'w, 's>,
}

impl CasterSet<'_, '_> {
    /// Appends every visible caster to `casters`. A mesh without bounds
    /// (`NoFrustumCulling`) is placed in no map; a skinned or morphed mesh whose assets are
    /// loading casts once they are loaded, and one that cannot be posed is reported once
    /// (`unposed` holds those reported, until they are posed again).
    pub fn collect(&self, casters: &mut Vec<Caster>, unposed: &mut EntityHashSet) {
        for (entity, mesh, transform, aabb, visibility, skinned, morphed, material) in &self.meshes
        {
            if !visibility.get() {
                continue;
            }
            let material = material.and_then(|material| self.materials.get(&material.0));
            let displacement = material.and_then(CasterDisplacement::of);
            let mask = material.and_then(CasterMask::of);
            // Bounds grown by the farthest the displacement moves a vertex.
            let reach = displacement.as_ref().map_or(0.0, |displacement| {
                displacement.reach() * largest_scale(transform)
            });
            let placed = if skinned || morphed {
                match self
                    .poses
                    .pose(entity, mesh.id(), transform.to_matrix(), aabb)
                {
                    Ok(pose) => {
                        unposed.remove(&entity);
                        let world_from_local = if pose.skinned {
                            Mat4::IDENTITY
                        } else {
                            transform.to_matrix()
                        };
                        let source = CasterSource::Posed {
                            entity,
                            mesh: mesh.id(),
                            skinned: pose.skinned,
                        };
                        Some((source, world_from_local, pose.bounds))
                    }
                    // Still loading: it casts once its assets are loaded.
                    Err(error) if error.is_loading() => None,
                    Err(error) => {
                        if unposed.insert(entity) {
                            warn!(
                                "skinned or morphed mesh {entity} casts no Phong shadow: {error}"
                            );
                        }
                        None
                    }
                }
            } else {
                aabb.map(|aabb| {
                    let source = CasterSource::Mesh(mesh.id());
                    (source, transform.to_matrix(), bounds(transform, aabb))
                })
            };
            if let Some((source, world_from_local, bounds)) = placed {
                casters.push(Caster {
                    source,
                    world_from_local,
                    bounds: Bounds {
                        radius: bounds.radius + reach,
                        ..bounds
                    },
                    displacement,
                    mask,
                });
            }
        }
    }
}

/// The largest factor by which `transform` stretches a length.
fn largest_scale(transform: &GlobalTransform) -> f32 {
    let matrix = transform.affine().matrix3;
    matrix
        .x_axis
        .length()
        .max(matrix.y_axis.length())
        .max(matrix.z_axis.length())
}

/// A sphere around a mesh's bounding box, in world space.
fn bounds(transform: &GlobalTransform, aabb: &Aabb) -> Bounds {
    Bounds {
        center: transform.transform_point(Vec3::from(aabb.center)),
        radius: Vec3::from(aabb.half_extents).length() * largest_scale(transform),
    }
}
