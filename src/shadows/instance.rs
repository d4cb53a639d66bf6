//! A caster as one shadow map draws it: where its triangles come from, the map's clip
//! space from theirs, and its material's displacement and mask. The casters of a frame
//! ([`super::casters`]) make them, the gather ([`super::gather`]) lists them per map, and the
//! render world ([`super::render`]) draws them.

use super::{displaced::CasterDisplacement, masked::CasterMask};
use bevy::{asset::AssetId, ecs::entity::Entity, math::Mat4, mesh::Mesh};

/// Where a caster's triangles come from.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum CasterSource {
    /// A mesh as stored (in its local space).
    Mesh(AssetId<Mesh>),
    /// A skinned or morphed mesh, posed on the GPU as Bevy poses it to draw it: by the
    /// joint matrices and morph weights Bevy prepared for `entity` this frame
    /// (`shadows::posed`).
    Posed {
        entity: Entity,
        mesh: AssetId<Mesh>,
        /// Whether its joints place it (in world space); otherwise it is in its local space.
        skinned: bool,
    },
}

/// A caster drawn into one map.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ShadowInstance {
    /// Its triangles.
    pub source: CasterSource,
    /// The triangles' space (the mesh's local space, or world space for skinned ones) to
    /// the map's clip space.
    pub clip_from_local: Mat4,
    /// How its material's displacement map moves its vertices, if it has one.
    pub displacement: Option<CasterDisplacement>,
    /// Where its material's alpha mask cuts holes, if it is masked.
    pub mask: Option<CasterMask>,
}
