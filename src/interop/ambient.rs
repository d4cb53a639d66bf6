//! Bevy's ambient lights under the mirror: each camera's view is lit by its own Bevy ambient
//! light, the camera's `AmbientLight` or else `GlobalAmbientLight`, converted by the mirror's
//! exposure (`color · e · L`, as Bevy writes it into each view's light uniform and weighs it
//! by the camera's exposure). The shader reads it from Bevy's view uniform
//! ([`BevyAmbientPerView`]); [`PhongAmbientLight`] starts at none under the mirror, and a
//! game's own adds to it.

use super::BevyLightExposure;
use crate::lights::BevyAmbientPerView;
use crate::validation::{Checker, InvalidInput, Owner};
use bevy::{
    ecs::{
        change_detection::{DetectChanges, DetectChangesMut},
        entity::Entity,
        message::MessageWriter,
        query::Changed,
        system::{Query, Res, ResMut},
    },
    light::{AmbientLight, GlobalAmbientLight},
};

/// The brightest Bevy ambient light read, in cd/m² (Bevy's default is 80): a brighter one
/// is clamped to it, so that converted it stays a finite color.
pub(crate) const MAX_BEVY_AMBIENT_BRIGHTNESS: f32 = 1e9;

/// Keeps [`BevyAmbientPerView`]'s scale equal to the exposure's factor: an exposure that
/// gives no finite factor `≥ 0` gives no Bevy ambient light, with a warning.
pub(crate) fn mirror_ambient_scale(
    exposure: Res<BevyLightExposure>,
    mut per_view: ResMut<BevyAmbientPerView>,
    mut messages: MessageWriter<InvalidInput>,
) {
    if !exposure.is_changed() {
        return;
    }
    let mut scale = exposure.factor();
    let mut checker = Checker::new(Owner::Resource, "BevyLightExposure");
    checker.number("ev100 (its factor)", &mut scale, 0.0..=f32::MAX, 0.0);
    checker.report(&mut messages);
    per_view.set_if_neq(BevyAmbientPerView { scale });
}

/// Replaces invalid fields of Bevy's ambient lights, the resource and each camera's, when
/// they changed: a color as a Phong light's (finite, non-negative), a brightness within
/// `[0, MAX_BEVY_AMBIENT_BRIGHTNESS]` (NaN: 0). Bevy's own materials then read the same
/// values.
pub(crate) fn validate_bevy_ambient_lights(
    global: Option<ResMut<GlobalAmbientLight>>,
    mut cameras: Query<(Entity, &mut AmbientLight), Changed<AmbientLight>>,
    mut messages: MessageWriter<InvalidInput>,
) {
    if let Some(mut global) = global.filter(|global| global.is_changed()) {
        let global = global.bypass_change_detection();
        let mut checker = Checker::new(Owner::Resource, "GlobalAmbientLight");
        checker.color("color", &mut global.color);
        checker.number(
            "brightness",
            &mut global.brightness,
            0.0..=MAX_BEVY_AMBIENT_BRIGHTNESS,
            0.0,
        );
        checker.report(&mut messages);
    }
    for (entity, mut light) in &mut cameras {
        let light = light.bypass_change_detection();
        let mut checker = Checker::new(Owner::Entity(entity), "AmbientLight");
        checker.color("color", &mut light.color);
        checker.number(
            "brightness",
            &mut light.brightness,
            0.0..=MAX_BEVY_AMBIENT_BRIGHTNESS,
            0.0,
        );
        checker.report(&mut messages);
    }
}

#[cfg(test)]
mod tests {
    use crate::test_app::{invalid_inputs, test_app};
    use crate::{BevyLightExposure, PhongBevyLightsPlugin, validation::Owner};
    use bevy::{
        color::Color,
        light::{AmbientLight, GlobalAmbientLight},
    };

    #[test]
    fn invalid_bevy_ambient_lights_are_replaced_and_named() {
        let mut app = test_app(|app| {
            app.add_plugins(PhongBevyLightsPlugin)
                .insert_resource(GlobalAmbientLight {
                    brightness: f32::NAN,
                    ..GlobalAmbientLight::default()
                });
        });
        let camera = app
            .world_mut()
            .spawn(AmbientLight {
                color: Color::linear_rgb(f32::INFINITY, 0.5, 0.5),
                brightness: -3.0,
                ..AmbientLight::default()
            })
            .id();
        app.update();
        let found: Vec<_> = invalid_inputs(&mut app)
            .into_iter()
            .map(|invalid| (invalid.owner, invalid.component, invalid.field))
            .collect();
        assert!(found.contains(&(Owner::Resource, "GlobalAmbientLight", "brightness")));
        assert!(found.contains(&(Owner::Entity(camera), "AmbientLight", "color")));
        assert!(found.contains(&(Owner::Entity(camera), "AmbientLight", "brightness")));
        let world = app.world();
        assert_eq!(world.resource::<GlobalAmbientLight>().brightness, 0.0);
        assert_eq!(world.get::<AmbientLight>(camera).unwrap().brightness, 0.0);
    }

    #[test]
    fn an_exposure_without_a_finite_factor_gives_no_bevy_ambient_light() {
        let mut app = test_app(|app| {
            app.add_plugins(PhongBevyLightsPlugin)
                .insert_resource(BevyLightExposure { ev100: f32::NAN });
        });
        app.update();
        let header = *app
            .world()
            .resource::<crate::render::PhongLightBuffer>()
            .header();
        assert_eq!(header.bevy_ambient_scale, 0.0);
        assert!(
            invalid_inputs(&mut app)
                .iter()
                .any(|invalid| invalid.component == "BevyLightExposure")
        );
    }
}
