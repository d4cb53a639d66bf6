//! Every kind's lights in the reference model: each kind's plugin registers how to find its
//! lights' [`PhongLightKind::reference_light`], and [`reference_lights`] collects them all.

use super::PhongLightKind;
use crate::lights::gives_light;
use crate::reference::ReferenceLight;
use bevy::{
    camera::visibility::InheritedVisibility,
    ecs::{resource::Resource, world::World},
    transform::components::GlobalTransform,
};
use std::sync::Arc;

/// Appends the reference lights of one kind's lights in `world` to the list.
type CollectLights = fn(&mut World, &mut Vec<Arc<dyn ReferenceLight>>);

/// How to find the reference lights of each kind added with a plugin.
#[derive(Resource, Default)]
pub(crate) struct ReferenceLightKinds {
    kinds: Vec<CollectLights>,
}

impl ReferenceLightKinds {
    /// Adds kind `L`.
    pub fn add<L: PhongLightKind>(&mut self) {
        self.kinds.push(collect::<L>);
    }
}

/// Adds kind `L` to those [`reference_lights`] collects: every kind added with
/// [`PhongLightKindPlugin`](super::PhongLightKindPlugin), and the built-in area lights, which
/// the model's [`Light`](crate::reference::Light) does not hold.
pub(crate) fn add_reference_kind<L: PhongLightKind>(world: &mut World) {
    world
        .get_resource_or_init::<ReferenceLightKinds>()
        .add::<L>();
}

/// The reference lights of the lights of kind `L` that give light ([`gives_light`]), as the
/// gather takes them.
fn collect<L: PhongLightKind>(world: &mut World, lights: &mut Vec<Arc<dyn ReferenceLight>>) {
    let mut query = world.query::<(&L, &GlobalTransform, &InheritedVisibility)>();
    lights.extend(
        query
            .iter(world)
            .filter(|(_, transform, visibility)| gives_light(visibility, transform))
            .filter_map(|(light, transform, _)| light.reference_light(transform)),
    );
}

/// The reference-model lights ([`PhongLightKind::reference_light`]) of every light of the
/// kinds added with [`PhongLightKindPlugin`](super::PhongLightKindPlugin), and of the area
/// lights ([`PhongRectLight`](crate::PhongRectLight)), that give light, for
/// [`reference::Lights::others`](crate::reference::Lights::others).
pub fn reference_lights(world: &mut World) -> Vec<Arc<dyn ReferenceLight>> {
    let kinds = world
        .get_resource::<ReferenceLightKinds>()
        .map(|kinds| kinds.kinds.clone())
        .unwrap_or_default();
    let mut lights = Vec::new();
    for collect in kinds {
        collect(world, &mut lights);
    }
    lights
}
