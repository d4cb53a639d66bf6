//! The rectangle and disk lights through the built-in machinery: validated, written after the local
//! lights with its record's fields and flags, clustered in slot 1 by the box its range
//! grows around it, the scene's area-light variant set while one is in the buffer, and in
//! the reference model.

use super::{GpuAreaLight, PhongLightBuffer, PhongLightClusters};
use crate::light_kind::PhongLightKind;
use crate::reference::{Material, SurfacePoint};
use crate::scene_variants::SceneVariants;
use crate::test_app::{invalid_inputs, test_app};
use crate::{
    AreaHighlight, Owner, PhongDiskLight, PhongLightCulling, PhongPointLight, PhongRectLight,
};
use bevy::prelude::{Camera3d, Transform, Vec3, Visibility};
use glam::DVec3;

/// The area section of the buffer, as records.
fn area_records(buffer: &PhongLightBuffer) -> Vec<GpuAreaLight> {
    let header = buffer.header();
    let first =
        (header.directional_count + header.local_count + header.clustered_local_count) as usize;
    let count = (header.area_count + header.clustered_area_count) as usize;
    buffer.records()[first..first + count]
        .iter()
        .map(|record| bytemuck::cast(*record))
        .collect()
}

#[test]
fn a_rect_light_is_validated_gathered_after_the_local_lights_clustered_and_modelled() {
    let mut app = test_app(|_| {});
    let world = app.world_mut();
    world.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 2.0, 10.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    world.spawn((
        PhongPointLight::default(),
        Transform::from_xyz(0.0, 3.0, 0.0),
    ));
    // A 2 × 0.5 panel facing down (its −Z along world −Y), its height along world Z.
    let panel = |x: f32, range: Option<f32>| {
        (
            PhongRectLight {
                width: 2.0,
                height: 0.5,
                range,
                two_sided: true,
                highlight: AreaHighlight::RepresentativePoint,
                ..Default::default()
            },
            Transform::from_xyz(x, 2.0, 0.0).looking_to(Vec3::NEG_Y, Vec3::Z),
        )
    };
    world.spawn(panel(0.0, None));
    world.spawn(panel(0.0, Some(3.0)));
    world.spawn(panel(1000.0, Some(3.0)));
    let broken = world
        .spawn((
            PhongRectLight {
                width: f32::NAN,
                ..Default::default()
            },
            Transform::default(),
        ))
        .id();
    app.update();

    // Validated: the NaN width replaced by 0, named; a panel without area is left out.
    let invalid = invalid_inputs(&mut app);
    assert_eq!(
        invalid
            .iter()
            .map(|input| (&input.owner, input.component, input.field))
            .collect::<Vec<_>>(),
        [(&Owner::Entity(broken), "PhongRectLight", "width")]
    );
    assert_eq!(
        app.world().get::<PhongRectLight>(broken).unwrap().width,
        0.0
    );

    // After the point light. ε (the default culling) gives even the panel without a range a
    // finite reach: its light falls with the inverse square.
    let header = *app.world().resource::<PhongLightBuffer>().header();
    assert_eq!(
        (
            header.local_count,
            header.area_count,
            header.clustered_area_count
        ),
        (1, 0, 3)
    );
    // Culled only past ranges: one unlimited panel, then the two of finite reach.
    app.world_mut().insert_resource(PhongLightCulling::EXACT);
    app.update();
    let buffer = app.world().resource::<PhongLightBuffer>();
    let header = *buffer.header();
    assert_eq!(
        (
            header.local_count,
            header.area_count,
            header.clustered_area_count
        ),
        (1, 1, 2)
    );
    let records = area_records(buffer);
    let first = records[0];
    assert_eq!(first.center, [0.0, 2.0, 0.0]);
    assert_eq!(first.reach, f32::MAX, "unlimited");
    let close = |a: [f32; 3], b: [f32; 3]| (Vec3::from(a) - Vec3::from(b)).length() < 1e-6;
    // Its local X is forward × up = −Y × Z = −X.
    assert!(close(first.half_width, [-1.0, 0.0, 0.0]), "{first:?}");
    assert!(
        close(first.half_height, [0.0, 0.0, 0.25]),
        "local Y along world Z: {first:?}"
    );
    let facing = Vec3::from(first.half_height).cross(Vec3::from(first.half_width));
    assert!(
        facing.normalize().abs_diff_eq(Vec3::NEG_Y, 1e-6),
        "faces down"
    );
    // White over an area of 1: color per unit area 1.
    assert_eq!(first.color, [1.0; 3]);
    assert_eq!(
        first.flags,
        GpuAreaLight::TWO_SIDED | GpuAreaLight::REPRESENTATIVE_POINT
    );
    let variants = app.world().resource::<SceneVariants>();
    assert!(
        variants.area_lights && !variants.disk_lights && !variants.fitted_highlights,
        "rectangles alone, none fitted: the polygons hold 6 corners, no fitted branch"
    );

    // The near panel of finite reach is listed in slot 1 of some clusters, the far one in
    // none; slot 0 holds no area light.
    let area_first = header.directional_count + header.local_count + header.clustered_local_count;
    let index_at = |x: f32| {
        area_first
            + 1
            + records[1..]
                .iter()
                .position(|record| record.center[0] == x)
                .expect("the panel is in the buffer") as u32
    };
    let clusters = app.world().resource::<PhongLightClusters>();
    let listed = clusters.first_view_entries(1..2).concat();
    assert!(listed.contains(&index_at(0.0)), "the near panel is listed");
    assert!(
        !listed.contains(&index_at(1000.0)),
        "the far one in no cluster"
    );
    assert!(
        clusters
            .first_view_entries(0..1)
            .concat()
            .iter()
            .all(|&index| index < area_first),
        "slot 0 lists local lights only"
    );

    // In the reference model: a point under the panels is lit.
    let world = app.world_mut();
    let mut panels = world.query::<(&PhongRectLight, &bevy::prelude::GlobalTransform)>();
    let lights: Vec<_> = panels
        .iter(world)
        .filter_map(|(panel, transform)| panel.reference_light(transform))
        .collect();
    assert_eq!(lights.len(), 4, "every panel has its reference light");
    let material = Material::from(&crate::PhongMaterial::default());
    let below = SurfacePoint {
        position: DVec3::new(0.0, 0.0, 0.0),
        normal: DVec3::Y,
        camera: DVec3::new(0.0, 5.0, 5.0),
    };
    assert!(
        lights
            .iter()
            .any(|light| light.term(&below, &material).max_element() > 0.0)
    );

    // The last panel hidden: the variant goes with it.
    let world = app.world_mut();
    let mut panels = world.query::<(bevy::prelude::Entity, &PhongRectLight)>();
    let all: Vec<_> = panels.iter(world).map(|(entity, _)| entity).collect();
    for entity in all {
        *world.get_mut::<Visibility>(entity).unwrap() = Visibility::Hidden;
    }
    app.update();
    assert!(!app.world().resource::<SceneVariants>().area_lights);
}

#[test]
fn a_disk_light_is_validated_and_gathered_with_its_shape_flag_area_and_bounds() {
    let mut app = test_app(|app| {
        app.insert_resource(PhongLightCulling::EXACT);
    });
    let world = app.world_mut();
    world.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 2.0, 10.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    world.spawn((
        PhongDiskLight {
            radius: 2.0,
            color: bevy::color::Color::linear_rgb(4.0 * core::f32::consts::PI, 0.0, 0.0),
            range: Some(3.0),
            highlight: AreaHighlight::Fitted,
            ..Default::default()
        },
        Transform::from_xyz(0.0, 2.0, 0.0).looking_to(Vec3::NEG_Y, Vec3::Z),
    ));
    let broken = world
        .spawn((
            PhongDiskLight {
                radius: -1.0,
                ..Default::default()
            },
            Transform::default(),
        ))
        .id();
    app.update();

    // A negative radius is replaced by 0, named; a disk without area is left out.
    let invalid = invalid_inputs(&mut app);
    assert_eq!(
        invalid
            .iter()
            .map(|input| (&input.owner, input.component, input.field))
            .collect::<Vec<_>>(),
        [(&Owner::Entity(broken), "PhongDiskLight", "radius")]
    );
    let buffer = app.world().resource::<PhongLightBuffer>();
    let header = *buffer.header();
    assert_eq!((header.area_count, header.clustered_area_count), (0, 1));
    let disk = area_records(buffer)[0];
    assert_eq!(disk.flags, GpuAreaLight::DISK | GpuAreaLight::FITTED);
    // Its radius along both half extents; 4π over π·2²: 1 per unit area.
    let length = |v: [f32; 3]| Vec3::from(v).length();
    assert!((length(disk.half_width) - 2.0).abs() < 1e-6, "{disk:?}");
    assert!((length(disk.half_height) - 2.0).abs() < 1e-6, "{disk:?}");
    assert!((disk.area() - 4.0 * core::f32::consts::PI).abs() < 1e-5);
    assert!((disk.color[0] - 1.0).abs() < 1e-6, "{disk:?}");
    // Clustered by its range grown by its radius, not by a square's half diagonal.
    let sphere = PhongDiskLight::bounding_sphere(&disk, 3.0).expect("a finite reach");
    assert!((sphere.radius() - 5.0).abs() < 1e-5, "{sphere:?}");
    // The disk's 18-corner polygons and the fitted lobe's branch are compiled in.
    let variants = app.world().resource::<SceneVariants>();
    assert!(variants.area_lights && variants.disk_lights && variants.fitted_highlights);
}
