//! What a light asks of the shadow system: the shape of the volume its rays fill, and its
//! [`PhongShadows`] settings. Built-in lights and extension kinds ask the same way.

use crate::lights::{PhongCascades, PhongShadows};
use bevy::{
    ecs::{entity::Entity, resource::Resource},
    math::{Vec2, Vec3},
};

/// The rays a shadow-casting light sends, which decide how its shadow maps project.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PhongShadowProjection {
    /// Parallel rays along the unit `direction` everywhere, as the sun's: cascaded
    /// orthographic maps fitted to each camera's view.
    Directional {
        /// Unit vector the rays travel along.
        direction: Vec3,
        /// How the maps split each camera's view.
        cascades: PhongCascades,
    },
    /// A beam of parallel rays along the unit `direction`, through the rectangle centred on
    /// `origin` with half-extents `half_size` (x along the unit `right`, y along
    /// `direction × right`), reaching `length` world units: one orthographic map.
    Beam {
        /// Centre of the rectangle the beam starts from, world space.
        origin: Vec3,
        /// Unit vector the rays travel along.
        direction: Vec3,
        /// Unit vector across the beam, perpendicular to `direction`.
        right: Vec3,
        /// Half-extents of the rectangle along `right` and `direction × right`, world units.
        half_size: Vec2,
        /// How far the beam reaches, world units.
        length: f32,
    },
    /// Rays from `position` within `half_angle` (radians) of the unit `direction`: one
    /// perspective map, or a cube of six past 60°.
    Cone {
        /// Where the rays start, world space.
        position: Vec3,
        /// Unit vector of the cone's axis.
        direction: Vec3,
        /// Half-angle of the cone, radians.
        half_angle: f32,
    },
    /// Rays from `position` in every direction: a cube of six perspective maps.
    Omni {
        /// Where the rays start, world space.
        position: Vec3,
    },
}

/// The shadow a light casts this frame: the shape of its rays, its settings, and how far
/// its light reaches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhongShadowRequest {
    /// Its rays.
    pub projection: PhongShadowProjection,
    /// Its settings; nothing is cast while `enabled` is false.
    pub settings: PhongShadows,
    /// How far its light reaches, world units (`f32::INFINITY` unlimited): a light whose
    /// reach misses the camera's view gets no map.
    pub reach: f32,
}

/// One light's request, for this frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShadowRequest {
    /// The light.
    pub entity: Entity,
    /// Its rays.
    pub projection: PhongShadowProjection,
    /// Its settings (enabled).
    pub settings: PhongShadows,
    /// How far its light reaches.
    pub reach: f32,
}

/// The requests of the current frame, filled by each light kind's system and consumed by the
/// shadow gather.
#[derive(Resource, Default, Debug)]
pub(crate) struct ShadowRequests(pub Vec<ShadowRequest>);

impl ShadowRequests {
    /// Adds `entity`'s request if its shadows are on.
    pub fn push(&mut self, entity: Entity, request: PhongShadowRequest) {
        if request.settings.enabled {
            self.0.push(ShadowRequest {
                entity,
                projection: request.projection,
                settings: request.settings,
                reach: request.reach,
            });
        }
    }
}
