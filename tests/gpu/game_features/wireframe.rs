//! Bevy's `Wireframe` over `PhongMaterial` meshes: `WireframePlugin` draws the edges of any
//! mesh after the main pass, whatever its material, where the device has line rasterization
//! and immediates (`POLYGON_MODE_LINE`, `IMMEDIATES`; not under WebGL2).

use bevy::{
    pbr::wireframe::{Wireframe, WireframeColor, WireframePlugin},
    prelude::*,
    render::settings::WgpuFeatures,
};
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{Comparison, Expected, Harness};
use std::cell::Cell;

use crate::frames::{SIZE, TOLERANCE};

/// The wires' color: pure green, which no lit pixel of these spheres shows.
const WIRE: [f32; 4] = [0.0, 1.0, 0.0, 1.0];

/// A sphere with `Wireframe` beside one without: on a device with line rasterization, the
/// wired sphere shows green edges (at least 100 pixels of them) and is elsewhere the Phong
/// frame the reference model gives, as is the other sphere, which shows no wire. Without
/// line rasterization (WebGL2's limits) no wire is drawn and the frame is the Phong frame.
#[test]
fn bevys_wireframe_draws_over_phong_meshes() {
    let mut harness = Harness::with_plugins(SIZE, SIZE, |app| {
        app.add_plugins(WireframePlugin::default());
    });
    let draws_lines = harness
        .device_features()
        .contains(WgpuFeatures::POLYGON_MODE_LINE | WgpuFeatures::IMMEDIATES);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::srgb(0.15, 0.15, 0.2),
    });
    world.spawn((
        PhongPointLight {
            color: Color::srgb(0.9, 0.7, 0.5),
            ..default()
        },
        Transform::from_xyz(0.0, 2.0, 3.0),
    ));
    let sphere = world
        .resource_mut::<Assets<Mesh>>()
        .add(Sphere::new(1.0).mesh().uv(12, 8));
    let mut materials = world.resource_mut::<Assets<PhongMaterial>>();
    let wired_material = materials.add(PhongMaterial::from(Color::srgb(0.8, 0.3, 0.3)));
    let plain_material = materials.add(PhongMaterial::from(Color::srgb(0.3, 0.3, 0.8)));
    let wired = world
        .spawn((
            Mesh3d(sphere.clone()),
            MeshMaterial3d(wired_material),
            Transform::from_xyz(-1.3, 0.0, 0.0),
            WireframeColor {
                color: Color::linear_rgb(WIRE[0], WIRE[1], WIRE[2]),
            },
        ))
        .id();
    world.spawn((
        Mesh3d(sphere),
        MeshMaterial3d(plain_material.clone()),
        Transform::from_xyz(1.3, 0.0, 0.0),
    ));
    harness.settle();
    // The wire is added once the camera draws into its image: Bevy 0.20.1 specializes an
    // entity's wireframe pipeline once, for the view's target format of that frame, and
    // the harness's float image is the target only from the frame it is prepared (before,
    // the view reports Bevy's default format, and the pipeline would never be made again).
    harness.world_mut().entity_mut(wired).insert(Wireframe);
    harness.settle();
    let rendered = harness.render_next_frame();
    // The inputs without the wires, which would draw over them too.
    harness.world_mut().entity_mut(wired).remove::<Wireframe>();
    let inputs = harness.capture_inputs();
    let lights = harness.reference_lights();
    let camera = harness.camera_position();
    let world = harness.world_mut();
    let materials = world.resource::<Assets<PhongMaterial>>();
    let (wire_pixels, wires_on_the_plain_sphere) = (Cell::new(0), Cell::new(0));
    let comparison = Comparison::of(&rendered, |index| {
        let surface = inputs.surface_at(index, camera);
        if rendered.pixels[index] == WIRE {
            wire_pixels.set(wire_pixels.get() + 1);
            if surface.is_some_and(|(material, _)| *material == plain_material) {
                wires_on_the_plain_sphere.set(wires_on_the_plain_sphere.get() + 1);
            }
            return Expected::Unjudged;
        }
        match surface {
            Some((material, surface)) => {
                let material =
                    reference::Material::from(materials.get(material).expect("a spawned material"));
                Expected::Lit(reference::shade(&surface, &material, &lights))
            }
            None => Expected::Clear,
        }
    });
    comparison.assert_within("wireframe", TOLERANCE);
    assert_eq!(
        wires_on_the_plain_sphere.get(),
        0,
        "the sphere without Wireframe shows none"
    );
    if draws_lines {
        assert!(
            wire_pixels.get() >= 100,
            "the wired sphere shows its edges: {} wire pixels",
            wire_pixels.get()
        );
    } else {
        assert_eq!(wire_pixels.get(), 0, "no lines without POLYGON_MODE_LINE");
    }
}
