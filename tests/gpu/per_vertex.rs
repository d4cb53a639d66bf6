//! Lighting per vertex (`PhongMaterial::vertex_lighting`, SPEC.md, "Per-vertex lighting"),
//! a cookie read at the vertices among its lights, rendered on the render device and
//! compared per pixel with the reference model's
//! per-vertex counterpart (`reference::VertexLight`, through `Harness::compare`): the lights'
//! sums at each triangle's corners in `f64`, interpolated with the pixel's barycentric
//! weights in its triangle, recovered from its captured world position (the device
//! interpolates every output with the same perspective-correct weights, which are the
//! triangle's barycentric weights in world space), then weighed with the material and its
//! maps at the pixel. Pixels within 10⁻⁴ of an edge between faces whose vertices differ are
//! not judged. Tolerance: the frame tests' ([`TOLERANCE`]).
//!
//! The meshes are coarse (a 20-face icosahedron subdivided once, a floor of 32 triangles), so
//! that lighting per vertex differs from lighting per pixel over much of the picture; the test
//! asserts that too, so that a device lighting these pixels per pixel fails it.

use crate::cookies::{cookie_image, wave};
use crate::frames::{SIZE, TOLERANCE};
use crate::texture_maps::{assert_scene_follows, color_map, expected_color};
use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::{Harness, pixel_model::loaded_images};
use std::cell::Cell;

/// Lit pixels whose per-vertex color must differ from the per-pixel model's by more than
/// [`SHOWS`]: a fifth of them.
const SHOWING_SHARE: usize = 5;
/// Ten of the tolerances: a difference the comparison cannot mistake for rounding.
const SHOWS: f64 = 10.0 * TOLERANCE;

fn low_poly_sphere(radius: f32) -> Mesh {
    Sphere::new(radius).mesh().ico(1).expect("one subdivision")
}

/// A floor 6 units square of 32 triangles.
fn coarse_floor() -> Mesh {
    Plane3d::default()
        .mesh()
        .size(6.0, 6.0)
        .subdivisions(3)
        .into()
}

#[test]
fn lights_summed_at_the_vertices_follow_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::srgb(0.1, 0.1, 0.12),
    });
    world.spawn((
        PhongDirectionalLight {
            color: Color::srgb(0.5, 0.5, 0.45),
            ..default()
        },
        Transform::from_xyz(1.0, 2.0, 1.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    // A point light of finite reach among the objects: its pool spans a few triangles.
    world.spawn((
        PhongPointLight {
            color: Color::srgb(0.9, 0.6, 0.3),
            decay: Decay::new(1.0, 0.2, 0.3),
            range: Some(4.0),
            ..default()
        },
        Transform::from_xyz(0.3, 0.4, 1.6),
    ));
    // A spot light whose cone's edge crosses the floor's triangles, with a cookie: its
    // texels are read at the vertices (under WebGL2's limits it is not bound: untinted).
    let cookie = PhongLightCookie {
        image: world
            .resource_mut::<Assets<Image>>()
            .add(cookie_image(|x, y| [wave(x, 16.0), wave(y, 24.0), 200])),
        ..default()
    };
    world.spawn((
        PhongSpotLight {
            color: Color::srgb(0.4, 0.7, 0.9),
            outer_angle: 0.45,
            inner_angle: 0.3,
            ..default()
        },
        cookie,
        Transform::from_xyz(-1.0, 3.0, 1.0).looking_at(Vec3::new(-0.8, -1.0, 0.5), Vec3::Y),
    ));
    let base_color = world
        .resource_mut::<Assets<Image>>()
        .add(color_map(0.3, 1.0));
    let objects = [
        // Phong, its base color from a map at the pixel.
        (
            low_poly_sphere(0.9),
            Transform::from_xyz(-1.2, 0.1, 0.0),
            PhongMaterial {
                base_color_texture: Some(base_color),
                shininess: 20.0,
                vertex_lighting: true,
                ..default()
            },
        ),
        // Blinn-Phong, wrapped diffuse light and a rim on the lit side.
        (
            low_poly_sphere(0.9),
            Transform::from_xyz(1.2, 0.1, 0.0).with_rotation(Quat::from_rotation_y(0.5)),
            PhongMaterial {
                base_color: Color::srgb(0.5, 0.8, 0.6),
                specular_model: SpecularModel::BlinnPhong,
                shininess: 40.0,
                diffuse_mode: DiffuseMode::Wrap(0.3),
                rim_color: LinearRgba::rgb(0.9, 0.3, 0.6),
                rim_lit_side: true,
                vertex_lighting: true,
                ..default()
            },
        ),
        // A coarse floor under all three lights.
        (
            coarse_floor(),
            Transform::from_xyz(0.0, -1.0, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.8, 0.8, 0.7),
                shininess: 8.0,
                vertex_lighting: true,
                ..default()
            },
        ),
        // Lit per pixel beside them, as before.
        (
            low_poly_sphere(0.5),
            Transform::from_xyz(0.0, 1.3, -0.5),
            PhongMaterial::from(Color::srgb(0.9, 0.9, 0.4)),
        ),
    ];
    let (rendered, inputs) =
        assert_scene_follows(&mut harness, objects, "lights summed at the vertices");

    // The same pixels against the per-pixel model: per-vertex lighting shows.
    let lights = harness.reference_lights();
    let images = loaded_images(&mut harness);
    let (vertex_lit, showing) = (Cell::new(0), Cell::new(0));
    harness.compare_pixels(&rendered, &inputs, |material, surface, pixel| {
        if material.vertex_lighting {
            let per_pixel = expected_color(material, surface, pixel, &inputs, &images, &lights)?;
            let color = rendered.pixels[pixel];
            let apart = (0..3)
                .map(|c| (f64::from(color[c]) - per_pixel[c]).abs())
                .fold(0.0, f64::max);
            vertex_lit.set(vertex_lit.get() + 1);
            showing.set(showing.get() + usize::from(apart > SHOWS));
        }
        None
    });
    println!(
        "{} of {} pixels lit per vertex differ from the per-pixel model by more than {SHOWS:.0e}",
        showing.get(),
        vertex_lit.get()
    );
    assert!(
        showing.get() * SHOWING_SHARE > vertex_lit.get(),
        "per-vertex lighting barely shows: {} of {} pixels differ from the per-pixel model \
         by more than {SHOWS:.0e}",
        showing.get(),
        vertex_lit.get()
    );
}

/// A vertex outside the view is in none of its light clusters: it is lit by every light of
/// finite reach, so a light that reaches only off-screen vertices still brightens the visible
/// part of their triangles, as the model's interpolation says.
#[test]
fn a_vertex_outside_the_view_is_lit_by_the_lights_that_reach_it() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    // Outside the frustum (its sphere reaches no pixel), within reach of the floor's far
    // right corner (15, -1, -15), about 1.6 units away.
    world.spawn((
        PhongPointLight {
            color: Color::srgb(0.9, 0.8, 0.6),
            decay: Decay::new(1.0, 0.0, 0.0),
            range: Some(3.0),
            ..default()
        },
        Transform::from_xyz(16.5, -0.5, -15.0),
    ));
    let floor = (
        Plane3d::default().mesh().size(30.0, 30.0).into(),
        Transform::from_xyz(0.0, -1.0, 0.0),
        PhongMaterial {
            base_color: Color::srgb(0.8, 0.8, 0.7),
            vertex_lighting: true,
            ..default()
        },
    );
    let name = "a light reaching only off-screen vertices";
    let (rendered, _) = assert_scene_follows(&mut harness, [floor], name);
    let brightest = rendered
        .pixels
        .iter()
        .map(|pixel| pixel[0])
        .fold(0.0, f32::max);
    assert!(
        f64::from(brightest) > SHOWS,
        "the off-screen corner's light shows nowhere: brightest red {brightest}"
    );
}

/// Three.js's normalized Blinn-Phong lit per vertex: the share `w` of the highlight that
/// Fresnel's term weighs by 1 instead of `f₀` is summed apart at the vertices (`grazing`,
/// SPEC.md, "Per-vertex lighting"). Under a black specular color `f₀` is 0, so that share
/// is all the highlight there is; the light comes from behind the objects toward the camera,
/// where `V·H` is small and `w` large (about a sixth on the floor), so that the share decides
/// every lit pixel: a device that dropped it would draw them black.
#[test]
fn the_fresnel_share_summed_at_the_vertices_follows_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::BLACK,
    });
    world.spawn((
        PhongDirectionalLight {
            color: Color::linear_rgb(2.0, 1.8, 1.5),
            ..default()
        },
        Transform::from_xyz(0.0, 1.0, -6.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    let grazing_only = PhongMaterial {
        base_color: Color::BLACK,
        specular_color: Color::BLACK,
        specular_model: SpecularModel::NormalizedBlinnPhong,
        shininess: 8.0,
        vertex_lighting: true,
        ..default()
    };
    let objects = [
        (
            low_poly_sphere(0.9),
            Transform::from_xyz(0.0, 0.1, 0.0),
            grazing_only.clone(),
        ),
        (
            coarse_floor(),
            Transform::from_xyz(0.0, -1.0, 0.0),
            grazing_only,
        ),
    ];
    let (rendered, inputs) = assert_scene_follows(
        &mut harness,
        objects,
        "the Fresnel share summed at the vertices",
    );
    let covered = inputs
        .positions
        .pixels
        .iter()
        .filter(|position| inputs.materials.contains_key(&(position[3] as u32)))
        .count();
    let showing = rendered
        .pixels
        .iter()
        .filter(|color| f64::from(color[0]) > SHOWS)
        .count();
    println!("{showing} of {covered} covered pixels show the Fresnel share above {SHOWS:.0e}");
    assert!(
        showing * 2 > covered,
        "the Fresnel share barely shows: {showing} of {covered} covered pixels above {SHOWS:.0e}"
    );
}

/// Vertex colors (`COLOR_0`, multiplying `k_d` and alpha) on a mesh lit per vertex, and
/// `NotShadowReceiver` there: the vertex stage sums the lights, the fragment weighs them with
/// the color interpolated at the pixel, and a mesh that receives no shadow takes none at its
/// vertices, though the sun casts shadows and a sphere stands between it and the floor.
#[test]
fn vertex_colors_and_meshes_receiving_no_shadow_are_lit_per_vertex_as_the_model_says() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::srgb(0.1, 0.1, 0.1),
    });
    world.spawn((
        PhongDirectionalLight {
            color: Color::srgb(0.7, 0.7, 0.6),
            shadows: PhongShadows {
                enabled: true,
                ..default()
            },
            ..default()
        },
        Transform::from_xyz(0.5, 3.0, 1.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    world.spawn((
        PhongPointLight {
            color: Color::srgb(0.6, 0.5, 0.9),
            decay: Decay::new(1.0, 0.2, 0.3),
            range: Some(5.0),
            ..default()
        },
        Transform::from_xyz(-1.0, 0.5, 1.5),
    ));
    // Each vertex of the floor its own color, from its position: red across, blue in depth.
    let mut floor = coarse_floor();
    let colors: Vec<[f32; 4]> = match floor.attribute(Mesh::ATTRIBUTE_POSITION) {
        Some(bevy::mesh::VertexAttributeValues::Float32x3(positions)) => positions
            .iter()
            .map(|[x, _, z]| [0.5 + x / 6.0, 0.8, 0.5 + z / 6.0, 1.0])
            .collect(),
        _ => panic!("the floor has positions"),
    };
    floor.insert_attribute(Mesh::ATTRIBUTE_COLOR, colors);
    let mut sphere = low_poly_sphere(0.7);
    let count = sphere.count_vertices();
    sphere.insert_attribute(
        Mesh::ATTRIBUTE_COLOR,
        (0..count)
            .map(|i| [0.4 + 0.6 * ((i % 7) as f32 / 6.0), 0.6, 0.9, 1.0])
            .collect::<Vec<[f32; 4]>>(),
    );
    let objects = [
        (
            floor,
            Transform::from_xyz(0.0, -1.0, 0.0),
            PhongMaterial {
                shininess: 8.0,
                vertex_lighting: true,
                ..default()
            },
        ),
        (
            sphere,
            Transform::from_xyz(0.2, 0.0, 0.2),
            PhongMaterial {
                shininess: 30.0,
                vertex_lighting: true,
                ..default()
            },
        ),
    ];
    for (mesh, transform, material) in objects {
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
        world.spawn((
            Mesh3d(mesh),
            MeshMaterial3d(material),
            transform,
            bevy::light::NotShadowReceiver,
        ));
    }
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    let comparison = harness.compare(&rendered, &inputs);
    let name = "vertex colors, no shadow received, lit per vertex";
    comparison.assert_within(name, TOLERANCE);
    comparison.assert_mostly_judged(name);
}
