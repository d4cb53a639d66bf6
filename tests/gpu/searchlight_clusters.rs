//! Searchlights in the light clusters: beams of finite reach lit exactly where their
//! clusters list them, and a beam far from the view looped over by no fragment.

use crate::{
    light::Searchlight,
    searchlight::{check_searchlit, searchlit_scene},
};
use bevy::{
    asset::uuid_handle,
    pbr::{ExtendedMaterial, MaterialExtension},
    prelude::*,
    render::render_resource::AsBindGroup,
    shader::ShaderRef,
};
use bevy_phong::{extension::PhongLightKindBuffer, prelude::*};
use bevy_phong_headless::Harness;

/// A beam of `range` from `position` toward `target`.
fn beam(range: f32, position: Vec3, target: Vec3) -> (Searchlight, Transform) {
    (
        Searchlight {
            color: Color::linear_rgb(1.2, 1.0, 0.8),
            radius: 1.2,
            edge: 0.3,
            decay: Decay::linear(0.05),
            range: Some(range),
            ..default()
        },
        Transform::from_translation(position).looking_at(target, Vec3::Z),
    )
}

/// Beams far from the view: over a town 1,000 units away, reaching 40 units each.
fn spawn_far_beams(world: &mut World, count: usize) {
    for i in 0..count {
        let x = 1000.0 + 5.0 * i as f32;
        world.spawn(beam(40.0, Vec3::new(x, 10.0, 0.0), Vec3::new(x, -1.0, 0.0)));
    }
}

#[test]
fn searchlights_of_finite_reach_are_lit_exactly_through_their_clusters() {
    let (mut harness, inputs) = searchlit_scene();
    let world = harness.world_mut();
    // One beam reaches the floor (7 units down, 10 long), one stops 2 units above it (cut
    // off at its range, mid-air), one points into the view from just outside it.
    world.spawn(beam(
        10.0,
        Vec3::new(-1.0, 6.0, 0.5),
        Vec3::new(-1.0, -1.0, 0.5),
    ));
    world.spawn(beam(
        5.0,
        Vec3::new(2.0, 6.0, 0.3),
        Vec3::new(2.0, -1.0, 0.3),
    ));
    world.spawn(beam(
        30.0,
        Vec3::new(-14.0, 4.0, 0.0),
        Vec3::new(0.0, -1.0, 0.0),
    ));
    spawn_far_beams(world, 40);
    check_searchlit(&mut harness, &inputs, "searchlights_of_finite_reach");
    let header = *harness
        .world_mut()
        .resource::<PhongLightKindBuffer<Searchlight>>()
        .header();
    assert_eq!(
        (header.count, header.clustered_first),
        (43, 0),
        "every beam has a range: all are clustered"
    );
}

/// The probe: `SearchlitMaterial`'s binding, drawn by `searchlight_probe.wesl`.
#[derive(Asset, AsBindGroup, Reflect, Clone, Debug)]
struct SearchlightProbe {
    #[texture(100, sample_type = "u_int")]
    searchlights: Handle<Image>,
}

const SEARCHLIGHT_PROBE_SHADER: Handle<Shader> =
    uuid_handle!("a4d1c2f0-3b5e-4c7a-9e21-6f8b0d3c5a17");

impl MaterialExtension for SearchlightProbe {
    fn fragment_shader() -> ShaderRef {
        SEARCHLIGHT_PROBE_SHADER.into()
    }
}

type ProbedMaterial = ExtendedMaterial<PhongMaterial, SearchlightProbe>;

/// Per covered pixel, how many searchlight records its fragment loops over, and whether it
/// found its view's clusters.
fn records_looped_over(harness: &mut Harness) -> Vec<(u32, bool)> {
    let rendered = harness.render_next_frame();
    let covered: Vec<(u32, bool)> = rendered
        .pixels
        .iter()
        .filter(|pixel| pixel[3] == 1.0)
        .map(|pixel| (pixel[0] as u32, pixel[1] == 1.0))
        .collect();
    assert!(covered.len() > 1_000, "the floor covers the view");
    covered
}

#[test]
fn a_searchlight_far_from_the_view_costs_no_fragment() {
    let mut harness = Harness::with_plugins(96, 96, |app| {
        app.add_plugins(crate::light::SearchlightPlugin)
            .add_phong_material::<ProbedMaterial>();
        let shader = Shader::from_wesl(
            include_str!("searchlight_probe.wesl"),
            "tests/gpu/searchlight_probe.wesl",
        );
        app.world_mut()
            .resource_mut::<Assets<Shader>>()
            .insert(SEARCHLIGHT_PROBE_SHADER.id(), shader)
            .expect("the probe shader's handle is free");
    });
    let world = harness.world_mut();
    let searchlights = world
        .resource::<PhongLightKindBuffer<Searchlight>>()
        .texture()
        .clone();
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::default().mesh().size(40.0, 40.0));
    let material = world
        .resource_mut::<Assets<ProbedMaterial>>()
        .add(ProbedMaterial {
            base: PhongMaterial::default(),
            extension: SearchlightProbe { searchlights },
        });
    world.spawn((Mesh3d(mesh), MeshMaterial3d(material)));
    spawn_far_beams(world, 200);
    harness.settle();
    let looped = records_looped_over(&mut harness);
    assert!(
        looped.iter().all(|&(count, _)| count == 0),
        "200 beams far from the view: some fragment loops over {} records",
        looped.iter().map(|&(count, _)| count).max().unwrap()
    );
    assert!(
        looped.iter().all(|&(_, found)| found),
        "every fragment found its view's clusters"
    );

    // A beam in the view: the fragments near it loop over it, and only it.
    harness.world_mut().spawn(beam(
        10.0,
        Vec3::new(0.0, 5.0, 0.0),
        Vec3::new(0.0, -1.0, 0.0),
    ));
    let looped = records_looped_over(&mut harness);
    assert!(looped.iter().all(|&(count, _)| count <= 1));
    let near = looped.iter().filter(|&&(count, _)| count == 1).count();
    assert!(
        near > 0 && near < looped.len(),
        "the near beam is looped over near it only ({near} of {} pixels)",
        looped.len()
    );
}
