//! Whole frames: scenes with `PhongMaterial` rendered on the render device, every pixel read
//! back as `f32` together with the world position and normal it was lit with, and checked
//! against `bevy_phong::reference` evaluated on those same inputs.
//!
//! Tolerance: the shader computes in `f32` what the reference computes in `f64` on identical
//! inputs, so the only differences are `f32` rounding. A handful of roundings (a few units of
//! 6e-8 relative each) in `N·L` and the attenuation give ~1e-6; the highlight amplifies the
//! direction error of its unit vectors by at most `sqrt(α / e)` (the contract tests bound it
//! by `5e-7·sqrt(α) + 1e-6`, here ≤ 1e-5 for α ≤ 200), times the specular intensities
//! (≤ 4 here). The budget is [`TOLERANCE`] relative to `max(1, |expected|)`, per channel: a
//! tenth of an 8-bit step, invisible on screen, ten times above that bound, yet far below
//! what a wrong term (a missing attenuation, a wrong reflection) produces. The largest
//! errors measured on lavapipe are near 3e-6.

use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::{FloatImage, Harness, SurfaceInputs};

/// See the module docs: a tenth of an 8-bit step (1/255).
pub use bevy_phong_headless::TOLERANCE;
/// Render size: small enough for a software rasterizer, large enough for smooth gradients.
pub const SIZE: u32 = 128;

/// Scene objects: a floor, a sphere, a cube and a torus, each with its own material.
pub fn spawn_objects(harness: &mut Harness) -> Vec<Handle<PhongMaterial>> {
    let world = harness.world_mut();
    let specs: [(Mesh, Transform, PhongMaterial); 4] = [
        (
            Plane3d::default().mesh().size(12.0, 12.0).into(),
            Transform::from_xyz(0.0, -1.0, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.8, 0.8, 0.8),
                shininess: 8.0,
                specular_strength: 0.5,
                ..default()
            },
        ),
        (
            Sphere::new(1.0).mesh().uv(48, 32),
            Transform::from_xyz(0.0, 0.0, 0.0),
            PhongMaterial {
                base_color: Color::srgb(1.0, 0.0, 1.0),
                specular_strength: 2.0,
                shininess: 50.0,
                ..default()
            },
        ),
        (
            Cuboid::new(1.2, 1.2, 1.2).into(),
            Transform::from_xyz(-2.3, -0.4, 0.5).with_rotation(Quat::from_rotation_y(0.6)),
            PhongMaterial {
                base_color: Color::srgb(0.0, 0.0, 1.0),
                specular_strength: 2.0,
                shininess: 50.0,
                ..default()
            },
        ),
        (
            Torus::new(0.35, 0.75).into(),
            Transform::from_xyz(2.3, -0.2, 0.5).with_rotation(Quat::from_rotation_x(1.0)),
            PhongMaterial {
                base_color: Color::srgb(0.0, 0.5, 0.0),
                specular_color: Color::srgb(1.0, 0.9, 0.6),
                shininess: 160.0,
                ..default()
            },
        ),
    ];
    specs
        .into_iter()
        .map(|(mesh, transform, material)| {
            let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
            let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
            world.spawn((Mesh3d(mesh), MeshMaterial3d(material.clone()), transform));
            material
        })
        .collect()
}

/// A harness with the scene objects, its pipelines compiled and the per-pixel inputs read.
fn scene() -> (Harness, SurfaceInputs, Vec<Handle<PhongMaterial>>) {
    let mut harness = Harness::new(SIZE, SIZE);
    let materials = spawn_objects(&mut harness);
    harness.settle();
    let inputs = harness.capture_inputs();
    (harness, inputs, materials)
}

fn check(harness: &mut Harness, inputs: &SurfaceInputs, case: &str) -> FloatImage {
    let rendered = harness.render_next_frame();
    harness
        .compare(&rendered, inputs)
        .assert_within(case, TOLERANCE);
    rendered
}

fn red_point_light() -> (PhongPointLight, Transform) {
    (
        PhongPointLight {
            color: Color::linear_rgb(1.0, 0.2, 0.2),
            decay: Decay::DISTANCE_50,
            ..default()
        },
        Transform::from_xyz(-3.0, 3.0, 0.0),
    )
}

fn blue_point_light() -> (PhongPointLight, Transform) {
    (
        PhongPointLight {
            color: Color::linear_rgb(0.2, 0.2, 1.0),
            decay: Decay::quadratic(0.02),
            range: Some(9.0),
            ..default()
        },
        Transform::from_xyz(3.0, 3.0, 0.0),
    )
}

fn directional_light() -> (PhongDirectionalLight, Transform) {
    (
        PhongDirectionalLight {
            color: Color::linear_rgb(0.6, 0.6, 0.5),
            specular: Some(Color::WHITE),
            ..default()
        },
        Transform::default().looking_to(Vec3::new(-1.0, -0.6, -0.4), Vec3::Y),
    )
}

fn spot_light() -> (PhongSpotLight, Transform) {
    (
        PhongSpotLight {
            color: Color::linear_rgb(1.0, 1.0, 0.8),
            decay: Decay::DISTANCE_50,
            inner_angle: 12.5_f32.to_radians(),
            outer_angle: 17.5_f32.to_radians(),
            exponent: 2.0,
            ..default()
        },
        Transform::from_xyz(0.5, 5.0, 3.0).looking_at(Vec3::new(0.0, -0.5, 0.0), Vec3::Y),
    )
}

#[test]
fn each_light_kind_alone_matches_the_reference() {
    let (mut harness, inputs, _) = scene();
    harness.world_mut().insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.05, 0.05, 0.05),
    });
    check(&mut harness, &inputs, "ambient_only");

    let light = harness.world_mut().spawn(directional_light()).id();
    check(&mut harness, &inputs, "directional_alone");
    harness.world_mut().despawn(light);

    let light = harness.world_mut().spawn(red_point_light()).id();
    check(&mut harness, &inputs, "point_alone");
    harness.world_mut().despawn(light);

    let light = harness.world_mut().spawn(blue_point_light()).id();
    check(&mut harness, &inputs, "point_with_range_alone");
    harness.world_mut().despawn(light);

    harness.world_mut().spawn(spot_light());
    check(&mut harness, &inputs, "spot_alone");
}

#[test]
fn all_lights_together_match_the_reference_in_both_specular_models() {
    let (mut harness, inputs, materials) = scene();
    let world = harness.world_mut();
    world.spawn(directional_light());
    world.spawn(red_point_light());
    world.spawn(blue_point_light());
    world.spawn(spot_light());
    check(&mut harness, &inputs, "all_lights_phong");

    for handle in &materials {
        edit_material(&mut harness, handle, |material| {
            material.specular_model = SpecularModel::BlinnPhong;
            material.shininess *= 4.0;
        });
    }
    check(&mut harness, &inputs, "all_lights_blinn_phong");
}

#[test]
fn light_changes_show_in_the_next_frame() {
    let (mut harness, inputs, _) = scene();
    let world = harness.world_mut();
    world.spawn(directional_light());
    let point = world.spawn(red_point_light()).id();
    let spot = world.spawn(spot_light()).id();
    let before = check(&mut harness, &inputs, "before_changes");

    harness
        .world_mut()
        .entity_mut(point)
        .get_mut::<Transform>()
        .unwrap()
        .translation = Vec3::new(1.0, 2.0, 2.5);
    let moved = check(&mut harness, &inputs, "point_moved");
    assert_ne!(
        before.pixels, moved.pixels,
        "moving a light changes the image"
    );

    harness
        .world_mut()
        .entity_mut(point)
        .get_mut::<PhongPointLight>()
        .unwrap()
        .color = Color::linear_rgb(0.0, 1.0, 0.3);
    check(&mut harness, &inputs, "point_recolored");

    *harness
        .world_mut()
        .entity_mut(spot)
        .get_mut::<Visibility>()
        .unwrap() = Visibility::Hidden;
    check(&mut harness, &inputs, "spot_hidden");

    harness.world_mut().despawn(point);
    check(&mut harness, &inputs, "point_despawned");

    harness
        .world_mut()
        .resource_mut::<PhongAmbientLight>()
        .color = Color::linear_rgb(0.3, 0.1, 0.0);
    check(&mut harness, &inputs, "ambient_changed");
}

#[test]
fn material_changes_show_in_the_next_frame() {
    let (mut harness, inputs, materials) = scene();
    let world = harness.world_mut();
    world.spawn(directional_light());
    world.spawn(red_point_light());
    check(&mut harness, &inputs, "material_before");

    edit_material(&mut harness, &materials[1], |sphere| {
        sphere.base_color = Color::srgb(0.2, 0.9, 0.1);
        sphere.specular_color = Color::srgb(1.0, 0.0, 0.0);
        sphere.shininess = 5.0;
        sphere.ambient_factor = 3.0;
        sphere.emissive = LinearRgba::rgb(0.0, 0.0, 0.25);
    });
    check(&mut harness, &inputs, "material_changed");

    // The floor now needs the variant without specular; once it has compiled (see
    // `a_new_shader_variant_leaves_a_gap_once_and_cached_ones_none`), it is drawn as before.
    edit_material(&mut harness, &materials[0], |floor| {
        floor.specular_strength = 0.0
    });
    harness.settle();
    check(&mut harness, &inputs, "material_without_specular");
}

#[test]
fn a_new_shader_variant_leaves_a_gap_once_and_cached_ones_none() {
    let (mut harness, inputs, materials) = scene();
    harness.world_mut().spawn(red_point_light());
    harness.settle();
    let all_drawn = harness.render_next_frame().covered_pixels();

    // First switch to the variant without specular: Bevy skips the floor until it compiled.
    let start = std::time::Instant::now();
    edit_material(&mut harness, &materials[0], |floor| {
        floor.specular_strength = 0.0
    });
    let mut gap_frames = 0;
    while harness.render_next_frame().covered_pixels() < all_drawn {
        gap_frames += 1;
        assert!(gap_frames < 600, "the variant never compiled");
    }
    println!(
        "first use of the variant without specular: floor missing for {gap_frames} frames, \
         {:.0} ms",
        start.elapsed().as_secs_f64() * 1000.0
    );

    // Both pipelines are now cached: switching back and forth shows in the very next frame.
    for (case, strength) in [("specular_back_on", 0.5), ("specular_off_again", 0.0)] {
        edit_material(&mut harness, &materials[0], |floor| {
            floor.specular_strength = strength
        });
        let rendered = harness.render_next_frame();
        assert_eq!(rendered.covered_pixels(), all_drawn, "{case}: no gap");
        harness
            .compare(&rendered, &inputs)
            .assert_within(case, TOLERANCE);
    }
}

fn edit_material(
    harness: &mut Harness,
    handle: &Handle<PhongMaterial>,
    edit: impl FnOnce(&mut PhongMaterial),
) {
    let mut assets = harness.world_mut().resource_mut::<Assets<PhongMaterial>>();
    edit(&mut assets.get_mut(handle).expect("material exists"));
}

#[test]
fn zero_lights_leave_only_ambient_and_emissive() {
    let (mut harness, inputs, materials) = scene();
    harness.world_mut().insert_resource(PhongAmbientLight::NONE);
    let dark = check(&mut harness, &inputs, "zero_lights_no_ambient");
    assert!(
        dark.pixels
            .iter()
            .all(|p| p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0),
        "with no light and no emissive, every pixel is black"
    );
    edit_material(&mut harness, &materials[2], |cube| {
        cube.emissive = LinearRgba::rgb(0.5, 0.25, 0.0);
    });
    harness.world_mut().insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.2, 0.3, 0.4),
    });
    check(&mut harness, &inputs, "zero_lights_ambient_and_emissive");
}

#[test]
fn light_count_grows_to_5000_and_back_to_1() {
    let (mut harness, inputs, _) = scene();
    harness.world_mut().insert_resource(PhongAmbientLight::NONE);
    let first = harness.world_mut().spawn(red_point_light()).id();
    check(&mut harness, &inputs, "one_light");

    // 4,999 dim lights on a deterministic spiral above the scene, each reaching a few units.
    let extra: Vec<Entity> = (1..5000)
        .map(|i| {
            let t = i as f32;
            let angle = t * 2.399_963; // the golden angle spreads them evenly
            let radius = 6.0 * (t / 5000.0).sqrt();
            let position = Vec3::new(
                radius * angle.cos(),
                0.5 + (t % 7.0) * 0.5,
                radius * angle.sin(),
            );
            let hue = (t * 0.618_034).fract() * 360.0;
            harness
                .world_mut()
                .spawn((
                    PhongPointLight {
                        color: Color::hsl(hue, 1.0, 0.5)
                            .to_linear()
                            .with_luminance(0.01)
                            .into(),
                        decay: Decay::new(1.0, 0.5, 0.5),
                        range: Some(6.0),
                        ..default()
                    },
                    Transform::from_translation(position),
                ))
                .id()
        })
        .collect();
    check(&mut harness, &inputs, "five_thousand_lights");

    for entity in extra {
        harness.world_mut().despawn(entity);
    }
    check(&mut harness, &inputs, "back_to_one_light");
    harness.world_mut().despawn(first);
    check(&mut harness, &inputs, "back_to_zero_lights");
}

/// A spot whose inner angle is at or past its outer one has a hard edge at the outer cone
/// (three.js's `penumbra: 0` converts to it): full light inside, none outside, as the
/// reference model says. The shader takes its own branch for it (`cone_scale` 0). Both
/// sides of the edge cover many pixels of the floor, the sphere and the torus; a pixel
/// within f32 rounding of the edge (`1 − cos θ` within 1e-7 of the outer cone's) could go
/// either way, and none lies there in this frame.
#[test]
fn a_hard_edged_spot_lights_its_cone_and_nothing_past_it() {
    let (mut harness, inputs, _) = scene();
    let camera = harness.camera_position();
    let at = Vec3::new(0.5, 5.0, 3.0);
    let transform = Transform::from_translation(at).looking_at(Vec3::new(0.0, -0.5, 0.0), Vec3::Y);
    let outer = 15_f32.to_radians();
    let axis = transform.forward().as_vec3().as_dvec3();
    for (case, inner) in [
        ("hard spot, inner = outer", outer),
        ("hard spot, inner > outer", 0.4),
    ] {
        let spot = harness
            .world_mut()
            .spawn((
                PhongSpotLight {
                    color: Color::linear_rgb(1.0, 0.9, 0.7),
                    decay: Decay::DISTANCE_50,
                    inner_angle: inner,
                    outer_angle: outer,
                    ..default()
                },
                transform,
            ))
            .id();
        check(&mut harness, &inputs, case);
        harness.world_mut().despawn(spot);
    }
    // Where the frame's surface points lie against the cone: many on each side, none within
    // rounding of its edge.
    let outer_versine = 1.0 - f64::from(outer).cos();
    let (mut inside, mut outside, mut on_edge) = (0, 0, 0);
    for index in 0..inputs.positions.pixels.len() {
        let Some((_, surface)) = inputs.surface_at(index, camera) else {
            continue;
        };
        let from_light = (surface.position - at.as_dvec3()).normalize();
        let versine = 1.0 - from_light.dot(axis);
        match versine - outer_versine {
            d if d.abs() < 1e-7 => on_edge += 1,
            d if d < 0.0 => inside += 1,
            _ => outside += 1,
        }
    }
    assert!(
        inside > 500 && outside > 500 && on_edge == 0,
        "{inside} pixels inside the cone, {outside} outside, {on_edge} on its edge"
    );
}

/// A view that mirrors the scene (a camera scaled by −1 across, as a planar reflection's is)
/// turns every triangle's winding, and `Camera::invert_culling` tells the materials to cull
/// the other face (Bevy's `INVERT_CULLING`): each mesh still shows its outside, lit as the
/// reference model says. Where the Phong pipeline culled the usual face, the frame would
/// show the meshes' insides (their far sides, facing away from the camera): nearly every
/// shown pixel must face the camera (interpolated normals at a silhouette may lean a little
/// past it; a culled outside turns nearly all of them away).
#[test]
fn a_mirrored_view_shows_every_mesh_from_outside() {
    let mut harness = Harness::new(SIZE, SIZE);
    spawn_objects(&mut harness);
    let mut camera = harness.camera_mut();
    camera
        .get_mut::<Camera>()
        .expect("the harness camera")
        .invert_culling = true;
    camera
        .get_mut::<Transform>()
        .expect("the harness camera's transform")
        .scale = Vec3::new(-1.0, 1.0, 1.0);
    harness.world_mut().spawn(directional_light());
    harness.world_mut().spawn(red_point_light());
    harness.settle();
    let inputs = harness.capture_inputs();
    let camera = harness.camera_position();
    let (mut facing, mut judged) = (0, 0);
    for index in 0..inputs.positions.pixels.len() {
        if let Some((_, surface)) = inputs.surface_at(index, camera) {
            judged += 1;
            facing += usize::from(surface.normal.dot(camera - surface.position) > 0.0);
        }
    }
    assert!(judged > 5000, "{judged} pixels show a mesh");
    assert!(
        facing * 100 >= judged * 98,
        "{facing} of {judged} shown surfaces face the camera"
    );
    check(&mut harness, &inputs, "mirrored view");
}
