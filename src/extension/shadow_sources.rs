//! The shadow requests of every kind of light: the lights that cast shadows, tracked as they
//! change, each asked for its request every frame.

use super::PhongLightKind;
use crate::lights::{LightQuery, lit_light};
use crate::shadows::ShadowRequests;
use bevy::ecs::{
    entity::Entity,
    lifecycle::RemovedComponents,
    query::Changed,
    resource::Resource,
    system::{Query, Res, ResMut},
};
use core::marker::PhantomData;

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
pub(crate) fn track_shadow_casters<L: PhongLightKind>(
    changed: Query<(Entity, &L), Changed<L>>,
    mut removed: RemovedComponents<L>,
    mut casters: ResMut<ShadowCasters<L>>,
) {
    // Removals first: a component removed and inserted again since the last run is there.
    for entity in removed.read() {
        casters.set(entity, false);
    }
    for (entity, light) in &changed {
        casters.set(entity, light.casts_shadows());
    }
}

/// Adds the request of every visible light of kind `L` whose shadows are on.
pub(crate) fn request_shadows<L: PhongLightKind>(
    casters: Res<ShadowCasters<L>>,
    lights: LightQuery<L>,
    mut requests: ResMut<ShadowRequests>,
) {
    for &entity in &casters.entities {
        if let Some((light, transform)) = lit_light(&lights, entity)
            && let Some(request) = light.shadow(transform)
        {
            requests.push(entity, request);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_app::test_app;
    use crate::{PhongPointLight, PhongShadows};
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
