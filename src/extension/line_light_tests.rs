//! A new kind needs its folder and one registration line: the line light, registered by the
//! plugin every kind from outside `PhongPlugin` takes, is validated, gathered, clustered
//! and in the reference model.

use crate::extension::{PhongLightKindPlugin, reference_lights};
use crate::light_kind::line::LineLight;
use crate::reference::{Material, SurfacePoint};
use crate::render::PhongLightClusters;
use crate::test_app::{invalid_inputs, test_app};
use crate::{Owner, extension::PhongLightKindBuffer};
use bevy::{
    color::Color,
    prelude::{Camera3d, Transform, Vec3},
};
use glam::DVec3;

#[test]
fn a_line_light_in_its_own_folder_is_validated_gathered_clustered_and_modelled() {
    let mut app = test_app(|app| {
        // The registration line.
        app.add_plugins(PhongLightKindPlugin::<LineLight>::default());
    });
    let world = app.world_mut();
    world.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 2.0, 10.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    let line = |length: f32, x: f32| {
        (
            LineLight {
                color: Color::WHITE,
                length,
                range: 2.0,
            },
            Transform::from_xyz(x, 0.0, 0.0),
        )
    };
    let broken = world.spawn(line(f32::NAN, 0.0)).id();
    world.spawn(line(4.0, 1000.0));
    app.update();

    // Validated: the NaN length replaced, with a message naming the entity and field.
    let invalid = invalid_inputs(&mut app);
    assert_eq!(
        invalid
            .iter()
            .map(|input| (&input.owner, input.component, input.field))
            .collect::<Vec<_>>(),
        [(&Owner::Entity(broken), "LineLight", "length")]
    );
    assert_eq!(app.world().get::<LineLight>(broken).unwrap().length, 0.0);

    // Gathered into its buffer, both lights clustered (a finite sphere each).
    let lines = app.world().resource::<PhongLightKindBuffer<LineLight>>();
    let header = *lines.header();
    assert_eq!((header.count, header.clustered_first), (2, 0));
    let far = lines
        .records()
        .iter()
        .position(|record| record.start == [998.0, 0.0, 0.0] && record.end == [1002.0, 0.0, 0.0])
        .expect("the far line's ends, 4 units apart along X") as u32;

    // Listed in the clusters it reaches: the one in view in some, the far one in none.
    let clusters = app.world().resource::<PhongLightClusters>();
    let slot = header.cluster_slot as usize;
    let listed = clusters.first_view_entries(slot..slot + 1).concat();
    assert!(listed.contains(&(1 - far)), "the line in view is listed");
    assert!(!listed.contains(&far), "the far line in no cluster");

    // In the reference model: the line in view lights a point below it, the far one none.
    let lights = reference_lights(app.world_mut());
    assert_eq!(lights.len(), 2);
    let surface = SurfacePoint {
        position: DVec3::new(0.0, -1.0, 0.0),
        normal: DVec3::Y,
        camera: DVec3::new(0.0, 5.0, 5.0),
    };
    let material = Material::from(&crate::PhongMaterial::default());
    let terms: Vec<f64> = lights
        .iter()
        .map(|light| light.term(&surface, &material).max_element())
        .collect();
    assert!(terms.iter().any(|&term| term > 0.0), "{terms:?}");
    assert!(terms.contains(&0.0), "{terms:?}");
}
