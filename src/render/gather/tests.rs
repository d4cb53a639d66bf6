//! The gather against records made afresh, frame after frame, and its order of the lights.

use super::*;
use crate::test_app::{built_in_buffer_bytes, test_app, uploads_in_next_frame};
use crate::{PhongDirectionalLight, PhongPointLight, PhongSpotLight};
use bevy::prelude::{App, Entity, Transform, Vec3, Visibility, World};
use bevy::{camera::visibility::InheritedVisibility, transform::components::GlobalTransform};

#[test]
fn lights_are_uploaded_only_in_frames_where_they_change() {
    let mut app = test_app(|_| {});
    let light = app
        .world_mut()
        .spawn((
            PhongPointLight::default(),
            Transform::from_xyz(1.0, 2.0, 3.0),
        ))
        .id();
    assert_eq!(
        uploads_in_next_frame(&mut app),
        1,
        "a new light is uploaded"
    );
    let state = app.world().resource::<PhongLightBuffer>();
    assert_eq!(state.header().local_count, 1);
    assert_eq!(state.records()[0].position, [1.0, 2.0, 3.0]);

    assert_eq!(
        uploads_in_next_frame(&mut app),
        0,
        "nothing changed: no upload"
    );
    assert_eq!(
        uploads_in_next_frame(&mut app),
        0,
        "nothing changed: no upload"
    );

    app.world_mut()
        .get_mut::<Transform>(light)
        .unwrap()
        .translation = Vec3::X;
    assert_eq!(
        uploads_in_next_frame(&mut app),
        1,
        "a moved light is uploaded"
    );
    let state = app.world().resource::<PhongLightBuffer>();
    assert_eq!(state.records()[0].position, [1.0, 0.0, 0.0]);

    *app.world_mut().get_mut::<Visibility>(light).unwrap() = Visibility::Hidden;
    assert_eq!(
        uploads_in_next_frame(&mut app),
        1,
        "a hidden light is removed"
    );
    assert_eq!(
        app.world()
            .resource::<PhongLightBuffer>()
            .header()
            .light_count(),
        0
    );

    *app.world_mut().get_mut::<Visibility>(light).unwrap() = Visibility::Inherited;
    assert_eq!(uploads_in_next_frame(&mut app), 1, "a shown light is back");
    app.world_mut().despawn(light);
    assert_eq!(
        uploads_in_next_frame(&mut app),
        1,
        "a despawned light is removed"
    );
    assert_eq!(
        app.world()
            .resource::<PhongLightBuffer>()
            .header()
            .light_count(),
        0
    );

    app.world_mut().resource_mut::<PhongAmbientLight>().color = bevy::color::Color::BLACK;
    assert_eq!(
        uploads_in_next_frame(&mut app),
        1,
        "a changed ambient light is uploaded"
    );
    assert_eq!(
        app.world().resource::<PhongLightBuffer>().header().ambient,
        [0.0; 3]
    );
    assert!(!built_in_buffer_bytes(&app).is_empty());
}

#[test]
fn a_hemisphere_light_adds_its_mean_to_the_ambient_and_its_half_difference_along_up() {
    let mut app = test_app(|_| {});
    app.world_mut().resource_mut::<PhongAmbientLight>().color =
        bevy::color::Color::linear_rgb(0.1, 0.1, 0.1);
    uploads_in_next_frame(&mut app);
    app.world_mut().insert_resource(PhongHemisphereLight {
        sky_color: bevy::color::Color::linear_rgb(0.5, 0.25, 1.0),
        ground_color: bevy::color::Color::linear_rgb(0.25, 0.5, 0.0),
        up: Vec3::new(0.0, 0.0, -4.0),
    });
    assert_eq!(uploads_in_next_frame(&mut app), 1, "inserted: uploaded");
    let header = *app.world().resource::<PhongLightBuffer>().header();
    // Exact in binary: 0.1 + 0.375 and the others are each rounded once.
    assert_eq!(header.ambient, [0.475, 0.475, 0.6].map(|x: f64| x as f32));
    assert_eq!(header.hemisphere_up, [0.0, 0.0, -1.0]);
    assert_eq!(header.hemisphere_half_difference, [0.125, -0.125, 0.5]);
    assert_eq!(uploads_in_next_frame(&mut app), 0, "unchanged: no upload");

    app.world_mut().remove_resource::<PhongHemisphereLight>();
    assert_eq!(uploads_in_next_frame(&mut app), 1, "removed: uploaded");
    let header = *app.world().resource::<PhongLightBuffer>().header();
    assert_eq!(header.ambient, [0.1; 3]);
    assert_eq!(header.hemisphere_up, [0.0; 3]);
    assert_eq!(header.hemisphere_half_difference, [0.0; 3]);
}

/// The records a gather must write for the lights in `app`, made afresh (no cache):
/// sorted by their bits, as the gather's own are by [`sorted_records`].
fn fresh_records(app: &mut App) -> Vec<[u32; 20]> {
    let world = app.world_mut();
    let epsilon = world.resource::<PhongLightCulling>().epsilon;
    let mut records: Vec<Fresh> = Vec::new();
    push_fresh::<PhongPointLight>(world, &mut records);
    push_fresh::<PhongSpotLight>(world, &mut records);
    let per_light_epsilon = epsilon / records.len().max(1) as f32;
    let records: Vec<GpuLight> = records
        .into_iter()
        .filter_map(|(mut record, reach)| {
            let reach = reach(&record, per_light_epsilon);
            // Point and spot lights alike store their reach as the point light does.
            PhongPointLight::set_reach(&mut record, reach);
            (reach > 0.0).then_some(record)
        })
        .collect();
    let mut bits: Vec<[u32; 20]> = records.iter().map(|r| bytemuck::cast(*r)).collect();
    bits.sort();
    bits
}

/// A light's record as `to_gpu` makes it, and its reach for a per-light ε.
type Fresh = (GpuLight, Box<dyn Fn(&GpuLight, f32) -> f32>);

/// Appends the whole record of every visible light of kind `L`, made afresh, with its reach.
fn push_fresh<L: PhongLightKind<Gpu = GpuLight> + Clone>(
    world: &mut World,
    records: &mut Vec<Fresh>,
) {
    let mut lights = world.query::<(&L, &GlobalTransform, &InheritedVisibility)>();
    for (light, transform, visibility) in lights.iter(world) {
        if visibility.get() {
            let record = light.to_gpu(transform);
            let light = light.clone();
            let reach = move |record: &GpuLight, epsilon| light.reach(record, epsilon);
            records.push((record, Box::new(reach)));
        }
    }
}

/// The records the gather wrote, sorted by their bits.
fn sorted_records(app: &App) -> Vec<[u32; 20]> {
    let state = app.world().resource::<PhongLightBuffer>();
    let mut bits: Vec<[u32; 20]> = state.records().iter().map(|r| bytemuck::cast(*r)).collect();
    bits.sort();
    bits
}

#[test]
fn kept_constants_never_outlive_a_change() {
    let mut app = test_app(|app| {
        app.insert_resource(PhongLightCulling {
            epsilon: 1e-2,
            clusters: true,
        });
    });
    let decay = crate::Decay::DISTANCE_50;
    let mut lights: Vec<Entity> = (0..6)
        .map(|i| {
            let position = Transform::from_xyz(i as f32, 1.0, 0.0);
            let world = app.world_mut();
            if i % 3 == 0 {
                world.spawn((
                    PhongSpotLight {
                        decay,
                        ..Default::default()
                    },
                    position,
                ))
            } else {
                world.spawn((
                    PhongPointLight {
                        decay,
                        ..Default::default()
                    },
                    position,
                ))
            }
            .id()
        })
        .collect();
    app.update();
    assert_eq!(
        sorted_records(&app),
        fresh_records(&mut app),
        "first gather"
    );

    type Step = fn(&mut World, &mut Vec<Entity>);
    let steps: [(&str, Step); 9] = [
        ("a point light recolored", |world, lights| {
            world.get_mut::<PhongPointLight>(lights[1]).unwrap().color =
                bevy::color::Color::srgb(0.2, 0.4, 0.9);
        }),
        ("a spot light's cone narrowed", |world, lights| {
            world
                .get_mut::<PhongSpotLight>(lights[0])
                .unwrap()
                .outer_angle = 0.2;
        }),
        ("a light moved", |world, lights| {
            world.get_mut::<Transform>(lights[2]).unwrap().translation.y = 4.0;
        }),
        ("a spot light turned", |world, lights| {
            world.get_mut::<Transform>(lights[3]).unwrap().rotate_x(0.5);
        }),
        ("a light despawned from the middle", |world, lights| {
            world.despawn(lights.remove(1));
        }),
        ("a light hidden", |world, lights| {
            *world.get_mut::<Visibility>(lights[1]).unwrap() = Visibility::Hidden;
        }),
        ("a light spawned: ε per light shrinks", |world, lights| {
            let light = PhongPointLight {
                decay: crate::Decay::DISTANCE_50,
                color: bevy::color::Color::srgb(3.0, 3.0, 3.0),
                ..Default::default()
            };
            lights.push(
                world
                    .spawn((light, Transform::from_xyz(0.0, 0.0, 2.0)))
                    .id(),
            );
        }),
        ("the hidden light shown", |world, lights| {
            *world.get_mut::<Visibility>(lights[1]).unwrap() = Visibility::Inherited;
        }),
        ("ε changed", |world, _| {
            world.resource_mut::<PhongLightCulling>().epsilon = 1e-3;
        }),
    ];
    for (name, step) in steps {
        step(app.world_mut(), &mut lights);
        app.update();
        assert_eq!(
            sorted_records(&app),
            fresh_records(&mut app),
            "after {name}"
        );
    }
}

#[test]
fn cookied_and_shadow_casting_lights_are_listed_only_in_the_clusters_they_reach() {
    use crate::render::PhongLightClusters;
    use crate::{PhongShadows, test_app::white_cookie};
    use bevy::{asset::AssetApp, image::Image, prelude::Camera3d};
    let mut app = test_app(|app| {
        app.init_asset::<Image>();
    });
    let cookie = white_cookie(&mut app);
    let world = app.world_mut();
    world.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 2.0, 10.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    let spot = |x: f32| {
        (
            PhongSpotLight {
                range: Some(2.0),
                ..Default::default()
            },
            cookie.clone(),
            Transform::from_xyz(x, 1.0, 0.0).looking_at(Vec3::new(x, 0.0, 0.0), Vec3::Z),
        )
    };
    world.spawn(spot(-3.0));
    world.spawn(spot(1000.0));
    world.spawn((
        PhongPointLight {
            range: Some(2.0),
            shadows: PhongShadows::ON,
            ..Default::default()
        },
        Transform::from_xyz(3.0, 1.0, 0.0),
    ));
    app.update();

    let state = app.world().resource::<PhongLightBuffer>();
    let header = *state.header();
    assert_eq!(
        [header.local_count, header.clustered_local_count],
        [0, 3],
        "no light is looped over by every fragment: all three are clustered"
    );
    let index_at = |x: f32| {
        state
            .records()
            .iter()
            .position(|record| record.position[0] == x)
            .unwrap() as u32
    };
    let (shadowed, near, far) = (index_at(3.0), index_at(-3.0), index_at(1000.0));
    let records = state.records();
    assert_eq!(
        records[shadowed as usize].shadow, 1,
        "its first view, plus one"
    );
    assert_ne!(records[near as usize].shadow >> GpuLight::COOKIE_SHIFT, 0);

    let clusters = app.world().resource::<PhongLightClusters>();
    assert_eq!(clusters.view_count(), 1);
    // Each cluster's local lights (slot 0).
    let entries = clusters.first_view_entries(0..1);
    let cluster_count = entries.len();
    let clusters_listing = |light: u32| {
        entries
            .iter()
            .filter(|entries| entries.contains(&light))
            .count()
    };
    let (near_clusters, shadowed_clusters) = (clusters_listing(near), clusters_listing(shadowed));
    assert!(
        0 < near_clusters && near_clusters < cluster_count / 4,
        "the cookied lamp in view is listed in the few clusters it reaches: {near_clusters} of \
         {cluster_count}"
    );
    assert!(
        0 < shadowed_clusters && shadowed_clusters < cluster_count / 4,
        "the shadow-casting light too: {shadowed_clusters} of {cluster_count}"
    );
    assert_eq!(clusters_listing(far), 0, "the far cookied lamp in none");
}

#[test]
fn mixed_lights_are_ordered_unlimited_then_clustered_each_kind_in_its_order() {
    // Points 1 and 3 then spots 4 and 5 after one directional light (0); `shadow` marks
    // the unlimited ones.
    let light = |id: f32, shadow: u32| GpuLight {
        position: [id, 0.0, 0.0],
        shadow,
        ..Default::default()
    };
    let mut records = vec![light(0.0, 0), light(1.0, 0), light(3.0, 1), light(4.0, 1)];
    records.push(light(5.0, 0));
    let clustered = |light: &GpuLight| light.shadow == 0;
    let pushed = |kept: usize, clustered: usize| Pushed {
        lit: kept,
        kept,
        clustered,
    };
    let mut scratch = Vec::new();
    let counts = order_by_reach(
        &mut records[1..],
        &[pushed(2, 1), pushed(2, 1)],
        &mut scratch,
        clustered,
    );
    assert_eq!(counts, [2, 2]);
    let order: Vec<f32> = records.iter().map(|light| light.position[0]).collect();
    assert_eq!(order, [0.0, 3.0, 4.0, 1.0, 5.0]);

    // All of one sort: left where they are.
    let counts = order_by_reach(
        &mut records[1..],
        &[pushed(2, 2), pushed(2, 2)],
        &mut scratch,
        |_| true,
    );
    assert_eq!(counts, [0, 4]);
    let again: Vec<f32> = records.iter().map(|light| light.position[0]).collect();
    assert_eq!(again, order);
}

#[test]
fn lights_are_ordered_directional_then_local_each_kind_in_its_order() {
    let mut app = test_app(|_| {});
    let world = app.world_mut();
    world.spawn(PhongSpotLight::default());
    world.spawn(PhongPointLight::default());
    world.spawn(PhongDirectionalLight::default());
    world.spawn(PhongPointLight::default());
    app.update();
    let state = app.world().resource::<PhongLightBuffer>();
    let header = state.header();
    assert_eq!((header.directional_count, header.local_count), (1, 3));
    // A directional light has no range; point and spot lights keep "unlimited". The point
    // lights come first, their cone the whole sphere; then the spot light with its cone.
    let records = state.records();
    assert_eq!(records[0].reach, 0.0);
    assert_eq!(records[1].reach, f32::MAX);
    for point in &records[1..3] {
        assert_eq!(
            (point.direction, point.outer_versine, point.cone_scale),
            ([0.0; 3], GpuLight::WHOLE_SPHERE, 0.0)
        );
    }
    assert!(records[3].cone_scale > 0.0);
    // Without a specular color of their own, lights highlight in their color.
    for record in records {
        assert_eq!(record.specular, record.color);
    }
}

/// A light's cookie changed on its own (its component, not the light's): the light buffer,
/// which holds the cookie records after the lights, is written again in the next frame.
#[test]
fn a_cookie_changed_alone_writes_the_light_buffer_again() {
    use crate::test_app::white_cookie;
    use bevy::{asset::AssetApp, image::Image};
    let mut app = test_app(|app| {
        app.init_asset::<Image>();
    });
    let cookie = white_cookie(&mut app);
    let light = app
        .world_mut()
        .spawn((PhongSpotLight::default(), cookie))
        .id();
    app.update();
    assert_eq!(uploads_in_next_frame(&mut app), 0, "nothing changed");
    app.world_mut()
        .get_mut::<crate::PhongLightCookie>(light)
        .unwrap()
        .red_only = true;
    assert_eq!(
        uploads_in_next_frame(&mut app),
        1,
        "the cookie's record changed: uploaded"
    );
}
