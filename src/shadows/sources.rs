//! The shadow requests of the built-in lights.

use super::request::{PhongShadowProjection, PhongShadowRequest, ShadowRequests};
use crate::lights::{
    LightQuery, PhongDirectionalLight, PhongPointLight, PhongSpotLight, light_direction, lit_lights,
};
use bevy::{
    ecs::{component::Component, system::ResMut},
    transform::components::GlobalTransform,
};

/// A light component that may cast shadows.
pub(crate) trait ShadowSource: Component {
    /// The shadow of this light placed by `transform`.
    fn shadow_request(&self, transform: &GlobalTransform) -> PhongShadowRequest;
}

impl ShadowSource for PhongDirectionalLight {
    fn shadow_request(&self, transform: &GlobalTransform) -> PhongShadowRequest {
        PhongShadowRequest {
            projection: PhongShadowProjection::Directional {
                direction: light_direction(transform),
                cascades: self.cascades,
            },
            settings: self.shadows,
            reach: f32::INFINITY,
        }
    }
}

impl ShadowSource for PhongPointLight {
    fn shadow_request(&self, transform: &GlobalTransform) -> PhongShadowRequest {
        PhongShadowRequest {
            projection: PhongShadowProjection::Omni {
                position: transform.translation(),
            },
            settings: self.shadows,
            reach: self.range.unwrap_or(f32::INFINITY),
        }
    }
}

impl ShadowSource for PhongSpotLight {
    fn shadow_request(&self, transform: &GlobalTransform) -> PhongShadowRequest {
        PhongShadowRequest {
            projection: PhongShadowProjection::Cone {
                position: transform.translation(),
                direction: light_direction(transform),
                half_angle: self.outer_angle,
            },
            settings: self.shadows,
            reach: self.range.unwrap_or(f32::INFINITY),
        }
    }
}

/// Adds the request of every visible light of kind `L` whose shadows are on.
pub(crate) fn request_shadows<L: ShadowSource>(
    lights: LightQuery<L>,
    mut requests: ResMut<ShadowRequests>,
) {
    for (entity, light, transform) in lit_lights(&lights) {
        requests.push(entity, light.shadow_request(transform));
    }
}
