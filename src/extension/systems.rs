//! The systems every kind of light gets, built in or added by an extension: its validation
//! and its shadow requests.

use super::PhongLightKind;
use super::shadow_sources::{ShadowCasters, request_shadows, track_shadow_casters};
use crate::lights::is_finite_transform;
use crate::render::{CookieRequests, gather_cookies, request_cookies};
use crate::schedule::PhongSystems;
use crate::validation::{Checker, InvalidInput, Owner};
use bevy::{
    app::{App, PostUpdate},
    asset::Assets,
    ecs::{
        change_detection::{DetectChanges, DetectChangesMut},
        entity::Entity,
        message::MessageWriter,
        query::{Changed, Or},
        schedule::{IntoScheduleConfigs, common_conditions::resource_exists},
        system::Query,
        world::Ref,
    },
    image::Image,
    transform::components::GlobalTransform,
};

/// Adds the systems of light kind `L`: each changed light validated
/// ([`PhongLightKind::validate`]) in [`PhongSystems::Validate`], the shadows of the
/// lights that cast them ([`PhongLightKind::casts_shadows`], [`PhongLightKind::shadow`])
/// requested in [`PhongSystems::RequestShadows`], and the cookies of those that take one
/// ([`PhongLightKind::cookie_projection`]) asked for before the cookie gather.
pub(crate) fn add_light_kind<L: PhongLightKind>(app: &mut App) {
    app.init_resource::<ShadowCasters<L>>()
        .init_resource::<CookieRequests>()
        .add_systems(
            PostUpdate,
            (
                validate_lights::<L>.in_set(PhongSystems::Validate),
                (track_shadow_casters::<L>, request_shadows::<L>)
                    .chain()
                    .in_set(PhongSystems::RequestShadows),
                request_cookies::<L>
                    .run_if(resource_exists::<Assets<Image>>)
                    .before(gather_cookies)
                    .in_set(PhongSystems::GatherLights),
            ),
        );
}

/// Lights whose component or transform changed.
type ChangedLight<L> = Or<(Changed<L>, Changed<GlobalTransform>)>;

/// Replaces the invalid fields of every light of kind `L` that changed, without marking it
/// changed again, and warns once per replacement; warns once when a light's transform
/// becomes non-finite (the gather system skips it while it is).
pub(crate) fn validate_lights<L: PhongLightKind>(
    mut lights: Query<(Entity, &mut L, Ref<GlobalTransform>), ChangedLight<L>>,
    mut messages: MessageWriter<InvalidInput>,
) {
    // The type's name without its path, as warnings name it: `PhongPointLight`.
    let name = core::any::type_name::<L>()
        .rsplit("::")
        .next()
        .unwrap_or_default();
    for (entity, mut light, transform) in &mut lights {
        let mut checker = Checker::new(Owner::Entity(entity), name);
        if transform.is_changed() && !is_finite_transform(&transform) {
            checker.replace(
                "GlobalTransform",
                format!("{:?}", transform.translation()),
                "nothing: the light is skipped until its transform is finite".into(),
            );
        }
        light.bypass_change_detection().validate(&mut checker);
        checker.report(&mut messages);
    }
}
