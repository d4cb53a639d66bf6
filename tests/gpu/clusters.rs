//! Per-view light clusters: every pixel lit as the reference model says wherever lights
//! sit against the view's frustum (just outside it and reaching in, across the near plane,
//! around the camera, far away), with two cameras seeing different parts of the scene, and
//! while the light count rises and falls; and the shader finds its own view's clusters
//! (`view_key`) rather than the fallback that loops over every light.
//!
//! Tolerance: [`TOLERANCE`] (see `frames`). Clusters only choose which lights a fragment
//! loops over; the arithmetic is the frame tests', so any light a cluster missed would show
//! as an error of its whole contribution, far above the tolerance.

use crate::frames::{SIZE, TOLERANCE, spawn_objects};
use crate::probes::harness_with_probe;
use bevy::{
    asset::uuid_handle,
    camera::{RenderTarget, primitives::Frustum},
    pbr::{ExtendedMaterial, MaterialExtension},
    prelude::*,
    render::render_resource::{AsBindGroup, TextureFormat},
    shader::ShaderRef,
};
use bevy_phong::{
    prelude::*,
    testing::{PhongLightBuffer, PhongLightClusters, view_key},
};
use bevy_phong_headless::{CAMERA_POSITION, Harness, HarnessCamera, SurfaceInputs};

/// A point light of `range` at `position`, fading so that it lights the objects visibly.
fn light(position: Vec3, range: f32, hue: f32) -> (PhongPointLight, Transform) {
    (
        PhongPointLight {
            color: Color::hsl(hue, 1.0, 0.5),
            decay: Decay::new(1.0, 0.1, 0.05),
            range: Some(range),
            ..default()
        },
        Transform::from_translation(position),
    )
}

/// Forty lights of short range (1 to 3) scattered among the objects.
fn spawn_lights_among_the_objects(world: &mut World) {
    for i in 0..40 {
        let t = i as f32;
        let position = Vec3::new(
            (t * 0.618).fract() * 10.0 - 5.0,
            -0.5 + (t * 0.382).fract() * 2.0,
            (t * 0.754).fract() * 10.0 - 5.0,
        );
        world.spawn(light(position, 1.0 + (t * 0.13).fract() * 2.0, t * 9.0));
    }
}

fn objects() -> (Harness, SurfaceInputs) {
    let mut harness = Harness::new(SIZE, SIZE);
    harness.world_mut().insert_resource(PhongAmbientLight::NONE);
    spawn_objects(&mut harness);
    harness.settle();
    let inputs = harness.capture_inputs();
    (harness, inputs)
}

/// How many local (point and spot) lights the gather put in the clustered part of the light
/// buffer.
pub fn clustered_light_count(harness: &mut Harness) -> u32 {
    let header = *harness.world_mut().resource::<PhongLightBuffer>().header();
    header.clustered_local_count
}

fn assert_exact(harness: &mut Harness, inputs: &SurfaceInputs, case: &str) {
    let rendered = harness.render_next_frame();
    harness
        .compare(&rendered, inputs)
        .assert_within(case, TOLERANCE);
}

#[test]
fn lights_around_the_frustum_light_every_pixel_as_the_model_says() {
    let (mut harness, inputs) = objects();
    // The harness camera looks at the origin from CAMERA_POSITION with Bevy's default
    // perspective (vertical field of view 45°, near 0.1, square target).
    let forward = (-CAMERA_POSITION).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let half_width = (std::f32::consts::FRAC_PI_8).tan() * CAMERA_POSITION.length();
    let world = harness.world_mut();
    // Outside the frustum's right edge by 1.5, reaching 2.5 into it.
    world.spawn(light(right * (half_width + 1.5), 4.0, 0.0));
    // Above its top edge, reaching the back of the sphere.
    world.spawn(light(up * (half_width + 0.8), 3.0, 60.0));
    // Across the near plane, and around the camera: every cluster lists it.
    world.spawn(light(CAMERA_POSITION + forward * 0.1, 9.0, 120.0));
    world.spawn(light(CAMERA_POSITION - forward * 2.0, 10.0, 180.0));
    // Far-flung: off to the side (listed nowhere), and far behind the scene reaching back.
    for far in [1e4, 1e30] {
        world.spawn(light(Vec3::X * far, 4.0, 240.0));
        world.spawn(light(Vec3::new(0.0, 1.0, -far), far + 2.0, 300.0));
    }
    // Near ones among the objects.
    spawn_lights_among_the_objects(world);
    assert_exact(&mut harness, &inputs, "lights_around_the_frustum");
    assert_eq!(clustered_light_count(&mut harness), 48);
    let clusters = harness.world_mut().resource::<PhongLightClusters>();
    assert_eq!(clusters.view_count(), 1);
}

/// A second camera, rendering into an image of its own, at `position` looking at `target`.
pub(crate) fn spawn_second_camera(harness: &mut Harness, position: Vec3, target: Vec3) -> Entity {
    let image = Image::new_target_texture(SIZE, SIZE, TextureFormat::Rgba32Float, None);
    let world = harness.world_mut();
    let image = world.resource_mut::<Assets<Image>>().add(image);
    world
        .spawn((
            Camera3d::default(),
            RenderTarget::Image(image.into()),
            Transform::from_translation(position).looking_at(target, Vec3::Y),
        ))
        .id()
}

#[test]
fn two_cameras_each_light_their_own_view_exactly() {
    let (mut harness, inputs) = objects();
    // Lights over the left and the right half of the floor, and lights far off to the right
    // that only the second camera sees.
    let world = harness.world_mut();
    for i in 0..30 {
        let t = i as f32;
        let x = (t * 0.618).fract() * 12.0 - 6.0;
        let z = (t * 0.754).fract() * 10.0 - 5.0;
        world.spawn(light(Vec3::new(x, 0.2, z), 2.5, t * 11.0));
        world.spawn(light(Vec3::new(x + 40.0, 0.2, z), 2.5, t * 11.0));
    }
    let second = spawn_second_camera(
        &mut harness,
        Vec3::new(40.0, 3.0, 8.0),
        Vec3::new(40.0, 0.0, 0.0),
    );
    assert_exact(&mut harness, &inputs, "first_camera_beside_a_second");
    assert_eq!(
        harness
            .world_mut()
            .resource::<PhongLightClusters>()
            .view_count(),
        2
    );
    // The same views the other way round: the harness camera where the second one was.
    let pose = |position: Vec3, target: Vec3| {
        Transform::from_translation(position).looking_at(target, Vec3::Y)
    };
    let world = harness.world_mut();
    *world.get_mut::<Transform>(second).unwrap() = pose(CAMERA_POSITION, Vec3::ZERO);
    let mut camera = world.query_filtered::<&mut Transform, With<HarnessCamera>>();
    *camera.single_mut(world).unwrap() = pose(Vec3::new(40.0, 3.0, 8.0), Vec3::new(40.0, 0.0, 0.0));
    // The objects seen from there: move them along with the camera.
    let mut objects = world.query_filtered::<&mut Transform, With<MeshMaterial3d<PhongMaterial>>>();
    for mut transform in objects.iter_mut(world) {
        transform.translation.x += 40.0;
    }
    harness.settle();
    let moved_inputs = harness.capture_inputs();
    assert_exact(
        &mut harness,
        &moved_inputs,
        "second_view_from_the_harness_camera",
    );
}

#[test]
fn lights_rising_to_3000_and_falling_to_none_leave_no_stale_cluster() {
    let (mut harness, inputs) = objects();
    let mut spawned: Vec<Entity> = Vec::new();
    for (step, count) in [0usize, 200, 3_000, 1_200, 40, 0].into_iter().enumerate() {
        let world = harness.world_mut();
        while spawned.len() > count {
            world.despawn(spawned.pop().unwrap());
        }
        while spawned.len() < count {
            let t = spawned.len() as f32;
            let position = Vec3::new(
                (t * 0.618_034).fract() * 14.0 - 7.0,
                -0.8 + (t * 0.381_966).fract() * 2.5,
                (t * 0.754_878).fract() * 14.0 - 7.0,
            );
            let (mut point, transform) = light(position, 0.5 + (t * 0.13).fract(), t);
            point.color = point.color.with_luminance(0.05);
            spawned.push(world.spawn((point, transform)).id());
        }
        assert_exact(
            &mut harness,
            &inputs,
            &format!("step_{step}_{count}_lights"),
        );
        assert_eq!(clustered_light_count(&mut harness) as usize, count);
    }
}

/// The extension whose fragment shader says which view record the shader found.
#[derive(Asset, AsBindGroup, Reflect, Clone, Debug, Default)]
struct ViewProbe {}

const VIEW_PROBE_SHADER: Handle<Shader> = uuid_handle!("5b0f3c1e-8a7d-4e2b-9c61-0d4f7a2e3b58");

impl MaterialExtension for ViewProbe {
    fn fragment_shader() -> ShaderRef {
        VIEW_PROBE_SHADER.into()
    }
}

type ProbedMaterial = ExtendedMaterial<PhongMaterial, ViewProbe>;

#[test]
fn the_shader_finds_its_own_views_clusters() {
    let mut harness = harness_with_probe::<ProbedMaterial>(
        &VIEW_PROBE_SHADER,
        include_str!("view_probe.wesl"),
        "tests/gpu/view_probe.wesl",
    );
    let world = harness.world_mut();
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::default().mesh().size(8.0, 8.0));
    let material = world
        .resource_mut::<Assets<ProbedMaterial>>()
        .add(ProbedMaterial {
            base: PhongMaterial::default(),
            extension: ViewProbe {},
        });
    world.spawn((Mesh3d(mesh), MeshMaterial3d(material)));
    world.spawn(light(Vec3::Y, 2.0, 0.0));
    spawn_second_camera(&mut harness, Vec3::new(5.0, 5.0, 5.0), Vec3::ZERO);
    harness.settle();
    let rendered = harness.render_next_frame();

    let world = harness.world_mut();
    let frustum = *world
        .query_filtered::<&Frustum, With<HarnessCamera>>()
        .single(world)
        .unwrap();
    let clusters = world.resource::<PhongLightClusters>();
    assert_eq!(clusters.view_count(), 2);
    let record = (0..clusters.view_count() as usize)
        .map(|view| view * 8)
        .find(|&record| clusters.data()[record] == view_key(&frustum))
        .expect("the harness camera's view has clusters");
    let covered: Vec<&[f32; 4]> = rendered
        .pixels
        .iter()
        .filter(|pixel| pixel[3] == 1.0)
        .collect();
    assert!(covered.len() > 1_000, "the plane covers the view");
    for pixel in covered {
        assert_eq!(
            (pixel[0], pixel[1]),
            (1.0, record as f32),
            "the shader found view record {} (red 1 when it found one), not {record}",
            pixel[1]
        );
    }
}

/// An orthographic camera, as isometric and strategy games use: its clusters are sliced
/// evenly in depth (`DepthSlices::linear`) and its tiles cut a box, not a pyramid. Forty
/// lights of short range among the objects, each listed only in the clusters it reaches,
/// light every pixel as the reference model says; a light a cluster missed would miss by its
/// whole contribution.
#[test]
fn an_orthographic_view_lights_every_pixel_as_the_model_says() {
    let mut harness = Harness::new(SIZE, SIZE);
    harness.world_mut().insert_resource(PhongAmbientLight::NONE);
    spawn_objects(&mut harness);
    harness
        .camera_mut()
        .insert(Projection::Orthographic(OrthographicProjection {
            scaling_mode: bevy::camera::ScalingMode::FixedVertical {
                viewport_height: 9.0,
            },
            near: 0.0,
            far: 40.0,
            ..OrthographicProjection::default_3d()
        }));
    harness.settle();
    let inputs = harness.capture_inputs();
    let world = harness.world_mut();
    spawn_lights_among_the_objects(world);
    assert_exact(&mut harness, &inputs, "orthographic view");
    assert_eq!(clustered_light_count(&mut harness), 40);
}
