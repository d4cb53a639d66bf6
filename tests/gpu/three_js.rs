//! three.js as the judge: a scene written as three.js describes it (`tests/three_js/scene.json`:
//! Phong and toon materials, an ambient, a hemisphere (its sky toward a tilted position), a
//! directional, a point and a spot light, a sphere, a
//! box and a floor) is converted with `bevy_phong::from_three` and rendered by the crate, and
//! rendered by three.js r187 itself in headless Chromium (`scripts/three/render.cjs`, WebGL2 on
//! SwiftShader, into a float target); the two pictures are compared pixel by pixel. The
//! converted scene is also compared with the reference model, which holds the conversion's
//! formulas (normalized Blinn-Phong with its Fresnel term, the smooth spot edge) to SPEC.md.

use bevy::{camera::Projection, math::DVec3, prelude::*};
use bevy_phong::{
    from_three::{
        ThreeGeometry, ThreeLight, ThreeLightOf, ThreeMaterial, aimed_transform, object_transform,
        perspective_projection,
    },
    prelude::*,
    reference,
};
use bevy_phong_headless::{
    Comparison, Expected, FloatImage, Harness, SurfaceInputs, pixel_model::loaded_images,
};
use serde::Deserialize;
use std::{collections::HashMap, path::PathBuf, process::Command};

use crate::{frames::TOLERANCE, stylized::toward_lights};

/// The scenes, as `scripts/three/scene.mjs` reads them: the first with every light kind,
/// both materials and a toon ramp; the second with what makes a picture hard to compare
/// pixel for pixel: a shininess-200 highlight a few pixels wide, a sphere of 10 × 6 faces, a
/// hard-edged spot (`penumbra: 0`), point lights of decay 0 and 1.
const SCENES: [&str; 2] = [
    "tests/three_js/scene.json",
    "tests/three_js/highlights.json",
];

/// How far the crate's pixel may lie outside the range three.js's picture takes around the
/// same pixel, relative to `max(1, |three.js's|)`.
///
/// The two rasterizers evaluate the same formulas on the same triangles, but each puts its
/// samples, interpolates and rounds its own way (three.js runs on SwiftShader, whose `pow`
/// is `exp2 ∘ log2`): where the picture changes fast, a highlight a pixel or two wide, a
/// coarse sphere's facets, a hard spot edge, the same pixel holds a value from a little
/// further along the slope. So each pixel is judged against the range three.js gives within
/// half a pixel of it (its own value and the halfway values toward its eight neighbours),
/// widened by this tolerance, which covers the rest: on flat faces the two agree to about
/// 5e-6, on the spheres to about 3e-3 at most. An error in a conversion or in a formula it
/// relies on moves pixels well past it where the picture is smooth, which is most of it:
/// without the Fresnel term the largest difference is 5.3e-2 (the floor's glare from the
/// light behind it), with a linear spot edge 5.2e-2, with Blinn-Phong for three.js's
/// highlight 3.5e-2.
const THREE_JS_TOLERANCE: f64 = 1e-2;

/// How near (in `u`, the ramp's coordinate) a texel's edge a toon pixel's `N·L` may be and
/// still be judged: the two rasterizers' normals differ by up to about 1e-5, and a pixel
/// whose `u` lies that near an edge reads one band in one picture and the next in the other.
const TOON_EDGE_MARGIN: f64 = 1e-3;

#[derive(Deserialize)]
struct Scene {
    width: u32,
    height: u32,
    camera: Camera,
    lights: Vec<PlacedLight>,
    materials: HashMap<String, ThreeMaterial>,
    meshes: Vec<Object>,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Camera {
    fov: f32,
    near: f32,
    far: f32,
    position: Vec3,
    look_at: Vec3,
}

#[derive(Deserialize)]
struct PlacedLight {
    #[serde(flatten)]
    light: ThreeLight,
    /// three.js places a light at `(0, 1, 0)`.
    #[serde(default = "above")]
    position: Vec3,
    #[serde(default)]
    target: Vec3,
}

fn above() -> Vec3 {
    Vec3::Y
}

#[derive(Deserialize)]
struct Object {
    geometry: ThreeGeometry,
    material: String,
    position: Vec3,
    #[serde(default)]
    rotation: Vec3,
}

fn repository() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The name of a scene's file without its folder and extension.
fn stem(file: &str) -> String {
    let path = std::path::Path::new(file);
    let stem = path.file_stem().expect("a file name");
    stem.to_string_lossy().into_owned()
}

fn scene(file: &str) -> Scene {
    let path = repository().join(file);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|error| panic!("{path:?}: {error}"));
    serde_json::from_str(&text).unwrap_or_else(|error| panic!("{path:?}: {error}"))
}

/// Spawns `scene` converted into the harness: its camera, lights and meshes. Returns the
/// handles of its toon materials.
fn spawn(harness: &mut Harness, scene: &Scene) -> Vec<Handle<PhongMaterial>> {
    let camera = &scene.camera;
    let aspect = scene.width as f32 / scene.height as f32;
    harness.camera_mut().insert((
        aimed_transform(camera.position, camera.look_at),
        Projection::Perspective(perspective_projection(
            camera.fov,
            aspect,
            camera.near,
            camera.far,
        )),
    ));
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight::NONE);
    for placed in &scene.lights {
        let aimed = aimed_transform(placed.position, placed.target);
        match placed.light.to_phong().expect("a light that converts") {
            ThreeLightOf::Ambient(light) => world.insert_resource(light),
            // three.js lights the sky side toward the light's position (docs/from-three.md).
            ThreeLightOf::Hemisphere(light) => world.insert_resource(PhongHemisphereLight {
                up: placed.position.normalize(),
                ..light
            }),
            ThreeLightOf::Directional(light) => {
                world.spawn((light, aimed));
            }
            ThreeLightOf::Point(light) => {
                world.spawn((light, Transform::from_translation(placed.position)));
            }
            ThreeLightOf::Spot(light) => {
                world.spawn((light, aimed));
            }
        }
    }
    let mut toon = Vec::new();
    let mut materials = HashMap::new();
    for (name, material) in &scene.materials {
        let converted = material.to_phong(&mut world.resource_mut::<Assets<Image>>());
        let handle = world.resource_mut::<Assets<PhongMaterial>>().add(converted);
        if matches!(material, ThreeMaterial::MeshToonMaterial(_)) {
            toon.push(handle.clone());
        }
        materials.insert(name.as_str(), handle);
    }
    for object in &scene.meshes {
        let mesh = world
            .resource_mut::<Assets<Mesh>>()
            .add(object.geometry.to_mesh());
        world.spawn((
            Mesh3d(mesh),
            MeshMaterial3d(materials[object.material.as_str()].clone()),
            object_transform(object.position, object.rotation),
        ));
    }
    toon
}

/// Renders `scene` converted, and captures its inputs.
fn render(
    scene: &Scene,
) -> (
    Harness,
    FloatImage,
    SurfaceInputs,
    Vec<Handle<PhongMaterial>>,
) {
    let mut harness = Harness::new(scene.width, scene.height);
    let toon = spawn(&mut harness, scene);
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    (harness, rendered, inputs, toon)
}

/// The converted scene follows SPEC.md: every pixel against the reference model.
#[test]
fn the_converted_three_js_scene_follows_the_reference_model() {
    for file in SCENES {
        let (mut harness, rendered, inputs, _) = render(&scene(file));
        let comparison = harness.compare(&rendered, &inputs);
        let case = format!("three.js scene {}, reference model", stem(file));
        comparison.assert_within(&case, TOLERANCE);
        comparison.assert_mostly_judged(&case);
    }
}

/// three.js's picture of the scene: `scripts/three/render.cjs` run on it, its floats read
/// back (rows top first).
fn three_js_render(file: &str, scene: &Scene) -> Vec<[f32; 4]> {
    let root = repository();
    let modules = root.join("target/browser/node_modules");
    let output = root
        .join("target/render-tests/three_js")
        .join(stem(file))
        .with_extension("f32");
    std::fs::create_dir_all(output.parent().unwrap()).expect("create target/render-tests");
    assert!(
        modules.join("three/package.json").is_file()
            && modules.join("playwright-core/package.json").is_file(),
        "three.js and playwright-core are not installed in {modules:?}: run \
         scripts/ensure-browser.sh (scripts/test.sh runs it)"
    );
    let status = Command::new("node")
        .arg(root.join("scripts/three/render.cjs"))
        .arg(root.join(file))
        .arg(&output)
        .arg(&modules)
        .status()
        .expect("run node (scripts/ensure-browser.sh installs it)");
    assert!(status.success(), "three.js did not render {file}: {status}");
    let bytes = std::fs::read(&output).expect("three.js's picture");
    let pixels: Vec<[f32; 4]> = bytes
        .chunks_exact(16)
        .map(bytemuck::pod_read_unaligned)
        .collect();
    assert_eq!(pixels.len(), (scene.width * scene.height) as usize);
    pixels
}

/// Whether the 3×3 pixels around `index` all lie on one smooth surface: one material, and
/// normals within 25° of each other. A pixel on a silhouette or on a box's edge goes to
/// whichever triangle each rasterizer's rounding picks.
fn inside_one_surface(inputs: &SurfaceInputs, index: usize) -> bool {
    let (width, height) = (
        inputs.positions.width as i64,
        inputs.positions.height as i64,
    );
    let (x, y) = (index as i64 % width, index as i64 / width);
    let tag = inputs.positions.pixels[index][3];
    let normal = |index: usize| {
        let [x, y, z, _] = inputs.normals.pixels[index];
        Vec3::new(x, y, z).normalize_or_zero()
    };
    (-1..=1).all(|dy| {
        (-1..=1).all(|dx| {
            let (nx, ny) = (x + dx, y + dy);
            let neighbour = (ny * width + nx) as usize;
            (0..width).contains(&nx)
                && (0..height).contains(&ny)
                && inputs.positions.pixels[neighbour][3] == tag
                && normal(neighbour).dot(normal(index)) > 0.9
        })
    })
}

/// The range, per channel, that `picture` (three.js's) takes within half a pixel of pixel
/// `index`: its own value and the halfway values toward each of its eight neighbours (the
/// pixel lies inside one surface, so they are that surface's too).
fn sub_pixel_range(picture: &[[f32; 4]], width: usize, index: usize) -> (DVec3, DVec3) {
    let rgb = |index: usize| {
        let [r, g, b, _] = picture[index].map(f64::from);
        DVec3::new(r, g, b)
    };
    let (x, y) = ((index % width) as i64, (index / width) as i64);
    let own = rgb(index);
    let (mut low, mut high) = (own, own);
    for (dx, dy) in (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (dx, dy))) {
        let neighbour = ((y + dy) * width as i64 + x + dx) as usize;
        let halfway = (own + rgb(neighbour)) / 2.0;
        low = low.min(halfway);
        high = high.max(halfway);
    }
    (low, high)
}

/// Whether a toon pixel's `N·L` toward some light lies within [`TOON_EDGE_MARGIN`] of a
/// texel's edge of `ramp`.
fn near_a_toon_step(
    ramp: &reference::ToonRamp,
    inputs: &SurfaceInputs,
    index: usize,
    lights: &reference::Lights,
) -> bool {
    let [x, y, z, _] = inputs.positions.pixels[index].map(f64::from);
    let [nx, ny, nz, _] = inputs.normals.pixels[index].map(f64::from);
    let normal = DVec3::new(nx, ny, nz).normalize();
    toward_lights(lights, DVec3::new(x, y, z))
        .into_iter()
        .any(|to_light| ramp.near_an_edge(normal.dot(to_light), TOON_EDGE_MARGIN))
}

/// three.js itself draws each scene as the crate draws its conversion: every pixel inside a
/// surface within [`THREE_JS_TOLERANCE`] of the range three.js's picture takes within half a
/// pixel of it (but a toon pixel at a band's edge), the background clear in both. Under
/// WebGL2's limits the crate binds no toon ramp (it draws bands instead, SPEC.md), so the
/// toon material's pixels are judged natively only.
#[test]
fn three_js_draws_the_scene_as_the_crate_draws_its_conversion() {
    for file in SCENES {
        judge_against_three_js(file);
    }
}

fn judge_against_three_js(file: &str) {
    let scene = scene(file);
    let three = three_js_render(file, &scene);
    let (mut harness, rendered, inputs, toon) = render(&scene);
    let lights = harness.reference_lights();
    let images = loaded_images(&mut harness);
    let materials = harness.world_mut().resource::<Assets<PhongMaterial>>();
    let ramps: HashMap<u32, reference::ToonRamp> = inputs
        .materials
        .iter()
        .filter(|(_, handle)| toon.contains(handle))
        .map(|(tag, handle)| {
            let ramp = materials
                .get(handle)
                .and_then(|m| m.toon_ramp_texture.as_ref());
            let image = &images[&ramp.expect("a toon ramp").id()];
            (
                *tag,
                reference::ToonRamp::from_image(image).expect("a readable ramp"),
            )
        })
        .collect();
    let width = scene.width as usize;
    // Toon pixels left out because the device binds no ramp.
    let without_ramp = std::cell::Cell::new(0);
    // The pixels judged: three.js's own value at each, and the crate's nearest point of
    // the range three.js takes around it (the crate's value where it lies inside).
    let judged = |index: usize, against_range: bool| {
        let tag = inputs.positions.pixels[index][3] as u32;
        let toon_ramp = ramps.get(&tag);
        if toon_ramp.is_some() && !inputs.every_map_bound {
            return (Expected::Unjudged, true);
        }
        if tag == 0 && three[index][3] == 0.0 {
            return (Expected::Clear, false);
        }
        if !inside_one_surface(&inputs, index)
            || toon_ramp.is_some_and(|ramp| near_a_toon_step(ramp, &inputs, index, &lights))
        {
            return (Expected::Unjudged, false);
        }
        let [r, g, b, _] = three[index].map(f64::from);
        if !against_range {
            return (Expected::Lit(DVec3::new(r, g, b)), false);
        }
        let (low, high) = sub_pixel_range(&three, width, index);
        let [cr, cg, cb, _] = rendered.pixels[index].map(f64::from);
        (
            Expected::Lit(DVec3::new(cr, cg, cb).clamp(low, high)),
            false,
        )
    };
    let pixel_for_pixel = Comparison::of(&rendered, |index| judged(index, false).0);
    let comparison = Comparison::of(&rendered, |index| {
        let (expected, no_ramp) = judged(index, true);
        without_ramp.set(without_ramp.get() + usize::from(no_ramp));
        expected
    });
    println!(
        "{file}: three.js r187 against the crate: {} pixels judged, {} unjudged; outside the \
         range three.js takes within half a pixel by at most {:.3e} at {:?}; pixel for pixel \
         {:.3e} at most, 99th percentile {:.3e}",
        comparison.lit_pixels,
        comparison.skipped_pixels,
        comparison.max_error,
        comparison.worst_pixel,
        pixel_for_pixel.max_error,
        pixel_for_pixel.error_quantile(0.99),
    );
    // The case names the images' folder (target/render-tests/CASE).
    comparison.assert_within(
        &format!("three.js against the crate, {}", stem(file)),
        THREE_JS_TOLERANCE,
    );
    // Edges and toon steps: fewer than a fifth of the pixels judged.
    let left_out = comparison.skipped_pixels - without_ramp.get();
    assert!(
        left_out < comparison.lit_pixels / 5,
        "{file}: too few pixels judged: {} judged, {left_out} on edges and toon steps",
        comparison.lit_pixels
    );
}
