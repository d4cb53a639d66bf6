//! The shadow requests of the built-in lights.

use super::request::{PhongShadowProjection, PhongShadowRequest, ShadowRequests};
use crate::lights::{
    LightQuery, PhongDirectionalLight, PhongPointLight, PhongShadows, PhongSpotLight,
    light_direction, lit_light,
};
use bevy::{
    ecs::{
        component::Component,
        entity::Entity,
        lifecycle::RemovedComponents,
        query::Changed,
        resource::Resource,
        system::{Query, Res, ResMut},
    },
    transform::components::GlobalTransform,
};
use core::marker::PhantomData;

/// A light component that may cast shadows.
pub(crate) trait ShadowSource: Component {
    /// The light's shadow settings.
    fn shadows(&self) -> &PhongShadows;

    /// The shadow of this light placed by `transform`.
    fn shadow_request(&self, transform: &GlobalTransform) -> PhongShadowRequest;
}

impl ShadowSource for PhongDirectionalLight {
    fn shadows(&self) -> &PhongShadows {
        &self.shadows
    }

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
    fn shadows(&self) -> &PhongShadows {
        &self.shadows
    }

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
    fn shadows(&self) -> &PhongShadows {
        &self.shadows
    }

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

/// The lights of kind `L` whose shadows are on, in the order of their entities: kept up to
/// date from the lights' changes ([`track_shadow_casters`]), so that a frame's requests
/// cost the shadow-casting lights, not every light of the world.
#[derive(Resource, Debug)]
pub(crate) struct ShadowCasters<L> {
    entities: Vec<Entity>,
    kind: PhantomData<fn() -> L>,
}

impl<L> Default for ShadowCasters<L> {
    fn default() -> Self {
        Self {
            entities: Vec::new(),
            kind: PhantomData,
        }
    }
}

impl<L> ShadowCasters<L> {
    /// Adds `entity` if `casts`, removes it otherwise.
    fn set(&mut self, entity: Entity, casts: bool) {
        match (self.entities.binary_search(&entity), casts) {
            (Err(place), true) => self.entities.insert(place, entity),
            (Ok(place), false) => {
                self.entities.remove(place);
            }
            _ => {}
        }
    }
}

/// Brings [`ShadowCasters`] up to date with the lights of kind `L` added, changed or
/// removed since its last run.
pub(crate) fn track_shadow_casters<L: ShadowSource>(
    changed: Query<(Entity, &L), Changed<L>>,
    mut removed: RemovedComponents<L>,
    mut casters: ResMut<ShadowCasters<L>>,
) {
    // Removals first: a component removed and inserted again since the last run is there.
    for entity in removed.read() {
        casters.set(entity, false);
    }
    for (entity, light) in &changed {
        casters.set(entity, light.shadows().enabled);
    }
}

/// Adds the request of every visible light of kind `L` whose shadows are on.
pub(crate) fn request_shadows<L: ShadowSource>(
    casters: Res<ShadowCasters<L>>,
    lights: LightQuery<L>,
    mut requests: ResMut<ShadowRequests>,
) {
    for &entity in &casters.entities {
        if let Some((light, transform)) = lit_light(&lights, entity) {
            requests.push(entity, light.shadow_request(transform));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_app::test_app;
    use bevy::prelude::Transform;

    fn casters(app: &bevy::app::App) -> Vec<Entity> {
        app.world()
            .resource::<ShadowCasters<PhongPointLight>>()
            .entities
            .clone()
    }

    #[test]
    fn shadow_casters_follow_their_lights_settings_and_lifetimes() {
        let mut app = test_app(|_| {});
        let light = |enabled| PhongPointLight {
            shadows: PhongShadows {
                enabled,
                ..PhongShadows::ON
            },
            ..Default::default()
        };
        let world = app.world_mut();
        let on = world.spawn((light(true), Transform::default())).id();
        let off = world.spawn((light(false), Transform::default())).id();
        app.update();
        assert_eq!(casters(&app), [on], "only the light with shadows on");

        let world = app.world_mut();
        world
            .get_mut::<PhongPointLight>(on)
            .unwrap()
            .shadows
            .enabled = false;
        world
            .get_mut::<PhongPointLight>(off)
            .unwrap()
            .shadows
            .enabled = true;
        app.update();
        assert_eq!(casters(&app), [off], "switched over");

        app.world_mut().entity_mut(off).remove::<PhongPointLight>();
        app.update();
        assert!(casters(&app).is_empty(), "its component removed");

        app.world_mut().entity_mut(off).insert(light(true));
        app.world_mut().despawn(on);
        app.update();
        assert_eq!(casters(&app), [off], "inserted again");
        app.world_mut().despawn(off);
        app.update();
        assert!(casters(&app).is_empty(), "despawned");
    }
}
