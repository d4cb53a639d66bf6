//! The glTF test asset posed halfway through its animations ([`POSE_SECONDS`]): the arm's
//! elbow bent 30° by its skin, the blob's upper half lifted by half its morph target.
//!
//! - Coverage: each primitive drawn alone with its `PhongMaterial` covers exactly the pixels
//!   it covers with the `StandardMaterial` Bevy's own glTF handler makes of it. Both run
//!   Bevy's mesh vertex stage, so skinning and morphing place the same fragments.
//! - Lighting: every pixel of the posed scene against the reference model on the inputs
//!   the vertex stage produced (deformed positions and normals, UVs, tangents), read back by
//!   `SurfaceInputsMaterial`, which runs the same vertex stage.

use super::{
    PHONG_TEST_GLTF, phong_only_gltf_harness, pose_at, spawn_gltf_scene, spawn_gltf_scene_with,
};
use crate::{
    frames::TOLERANCE,
    texture_maps::{
        SrgbDecoding, lit_color, loaded_images, masked_out, output_alpha, texels_at, vertex_color,
    },
};
use bevy::{
    gltf::GltfMaterialName, image::ImageSamplerDescriptor, math::DVec3, mesh::morph::MorphWeights,
    prelude::*,
};
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{Comparison, Expected, FloatImage, Harness, SurfaceInputs};
use std::{cell::RefCell, collections::HashMap};

/// The animation time the scene is held at (s): both clips run from 0 to 1 s, LINEAR.
const POSE_SECONDS: f32 = 0.5;
/// Render size: the arm, 0.5 m wide about 9 m away, gets about ten pixels across.
const WIDTH: u32 = 256;
const HEIGHT: u32 = 192;
/// Where the camera looks from (at the origin): the ground, the arm, the blob and the
/// fence in view, with the fence in front of the ground.
const CAMERA: Vec3 = Vec3::new(0.0, 3.0, 8.0);
/// Fewest pixels each primitive must be judged on, so that a primitive out of view (or
/// hidden behind another) cannot pass by being absent.
const MIN_PIXELS: usize = 100;

/// Every glTF primitive in the world: its entity and glTF material name.
fn primitives(harness: &mut Harness) -> Vec<(Entity, String)> {
    let world = harness.world_mut();
    let mut query = world.query_filtered::<(Entity, &GltfMaterialName), With<Mesh3d>>();
    let mut primitives: Vec<_> = query
        .iter(world)
        .map(|(entity, name)| (entity, name.0.clone()))
        .collect();
    primitives.sort_by(|a, b| a.1.cmp(&b.1));
    primitives
}

/// Asserts the pose took effect: the elbow turned by half of `Bend`'s 60°, the blob's
/// weight half of `Morph`'s 1.
fn assert_posed(harness: &mut Harness) {
    let world = harness.world_mut();
    let mut named = world.query::<(&Name, &Transform, Option<&MorphWeights>)>();
    let mut elbow = None;
    let mut blob = None;
    for (name, transform, weights) in named.iter(world) {
        match name.as_str() {
            "Elbow" => elbow = Some(transform.rotation),
            "Blob" => blob = weights.map(|w| w.weights().to_vec()),
            _ => {}
        }
    }
    let angle = elbow.expect("an Elbow node").to_axis_angle().1.to_degrees();
    // f32 rounding of the quaternion's slerp and angle extraction.
    assert!((angle - 30.0).abs() < 1e-3, "elbow at {angle}°");
    assert_eq!(blob.expect("the Blob's weights"), [0.5]);
}

/// Gives `entity` `material`, settles and renders a frame.
///
/// A mesh shown again after being hidden is extracted anew in the frame it reappears, and
/// Bevy 0.19 then looks up its morph descriptor before preparing it for that frame: the
/// mesh keeps no morph descriptor, and draws unmorphed, until it changes again (seen here:
/// the blob drew unmorphed, whatever its material, until its material was set once more).
/// So the material is set again once the mesh has been visible for a frame.
fn draw_with<M: Material>(
    harness: &mut Harness,
    entity: Entity,
    material: MeshMaterial3d<M>,
) -> FloatImage {
    harness
        .world_mut()
        .entity_mut(entity)
        .insert(material.clone());
    harness.settle();
    harness.world_mut().entity_mut(entity).insert(material);
    harness.settle();
    harness.render_next_frame()
}

/// Which pixels a frame covers (alpha above 0).
fn coverage(frame: &FloatImage) -> Vec<bool> {
    frame.pixels.iter().map(|pixel| pixel[3] > 0.0).collect()
}

#[test]
fn each_posed_primitive_covers_the_pixels_standard_material_covers() {
    // Both glTF handlers: Bevy's gives each primitive its StandardMaterial, the crate's its
    // PhongMaterial. Each primitive is drawn alone, with one material at a time.
    let mut harness = Harness::with_plugins(WIDTH, HEIGHT, |app| {
        app.add_plugins(PhongGltfPlugin);
    });
    harness.look_from(CAMERA);
    let gltf = spawn_gltf_scene(&mut harness, PHONG_TEST_GLTF);
    pose_at(&mut harness, &gltf, POSE_SECONDS);
    assert_posed(&mut harness);
    let primitives = primitives(&mut harness);
    let world = harness.world_mut();
    let materials: Vec<_> = primitives
        .iter()
        .map(|(entity, name)| {
            let mut primitive = world.entity_mut(*entity);
            let phong = primitive
                .take::<MeshMaterial3d<PhongMaterial>>()
                .unwrap_or_else(|| panic!("{name}: no PhongMaterial"));
            let standard = primitive
                .take::<MeshMaterial3d<StandardMaterial>>()
                .unwrap_or_else(|| panic!("{name}: no StandardMaterial"));
            (phong, standard)
        })
        .collect();

    let show_alone = |harness: &mut Harness, shown: Entity| {
        let world = harness.world_mut();
        for (entity, _) in &primitives {
            let visibility = if *entity == shown {
                Visibility::Inherited
            } else {
                Visibility::Hidden
            };
            world.entity_mut(*entity).insert(visibility);
        }
    };
    for ((entity, name), (phong, standard)) in primitives.iter().zip(&materials) {
        show_alone(&mut harness, *entity);
        let with_phong = coverage(&draw_with(&mut harness, *entity, phong.clone()));
        harness
            .world_mut()
            .entity_mut(*entity)
            .remove::<MeshMaterial3d<PhongMaterial>>();
        let with_standard = coverage(&draw_with(&mut harness, *entity, standard.clone()));
        harness
            .world_mut()
            .entity_mut(*entity)
            .remove::<MeshMaterial3d<StandardMaterial>>();

        let covered = with_phong.iter().filter(|c| **c).count();
        let differing = with_phong
            .iter()
            .zip(&with_standard)
            .filter(|(a, b)| a != b)
            .count();
        println!("{name}: {covered} pixels covered, {differing} differ from StandardMaterial's");
        assert!(covered >= MIN_PIXELS, "{name}: {covered} pixels in view");
        assert_eq!(
            differing, 0,
            "{name}: coverage differs in {differing} pixels"
        );
    }
}

/// What a pixel shows, by the reference model: the lit color of the surface the inputs
/// found there; where an alpha mask discards it, or a blended surface lets it through, what
/// `behind` (the inputs without the masked and blended primitives) shows. `None` where it
/// cannot be judged (a texel edge).
struct Scene<'a> {
    camera: DVec3,
    materials: &'a HashMap<AssetId<PhongMaterial>, PhongMaterial>,
    images: &'a HashMap<AssetId<Image>, Image>,
    lights: &'a reference::Lights,
}

impl Scene<'_> {
    /// The color at `pixel`, sRGB maps decoded as `decoding` says (the color grows with
    /// every texel, so the lowest and highest decodings bound it).
    fn color(
        &self,
        inputs: &SurfaceInputs,
        behind: Option<&SurfaceInputs>,
        pixel: usize,
        decoding: SrgbDecoding,
    ) -> Option<DVec3> {
        let Some((handle, surface)) = inputs.surface_at(pixel, self.camera) else {
            return Some(DVec3::ZERO);
        };
        let material = &self.materials[&handle.id()];
        let texels = texels_at(material, inputs, pixel, self.images, decoding)?;
        let vertex_alpha = vertex_color(inputs, pixel).w;
        let through = |weight: f64| -> Option<DVec3> {
            let behind = behind.expect("masked and blended primitives are not behind others");
            Some(weight * self.color(behind, None, pixel, decoding)?)
        };
        if masked_out(material, &texels, vertex_alpha)? {
            return through(1.0);
        }
        let lit = lit_color(
            material,
            &surface,
            pixel,
            inputs,
            &texels,
            self.images,
            self.lights,
        )?;
        match material.alpha_mode {
            AlphaMode::Blend => {
                let alpha = output_alpha(material, &texels, vertex_alpha);
                Some(alpha * lit + through(1.0 - alpha)?)
            }
            _ => Some(lit),
        }
    }
}

/// Tolerance: the frame tests' ([`TOLERANCE`]), beyond the range the sRGB base color map's
/// decoding allows ([`SrgbDecoding`]). The glTF is loaded with nearest filtering
/// for every image (`GltfLoaderSettings::override_sampler`), so that the texel each pixel received is
/// known exactly, as in the texture-map test; filtering is the sampler's, not the
/// crate's. The blended blob adds one `f32` blend.
#[test]
fn a_posed_gltf_scene_is_lit_as_the_reference_model_says_on_its_deformed_inputs() {
    let mut harness = phong_only_gltf_harness(WIDTH, HEIGHT);
    harness.look_from(CAMERA);
    let gltf = spawn_gltf_scene_with(&mut harness, PHONG_TEST_GLTF, |settings| {
        settings.override_sampler = true;
        settings.default_sampler = Some(ImageSamplerDescriptor::nearest());
    });
    pose_at(&mut harness, &gltf, POSE_SECONDS);
    assert_posed(&mut harness);
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    // What the masked fence and the blended blob let through: the scene without them.
    let primitives = primitives(&mut harness);
    let see_through = |name: &str| name == "FenceMask" || name == "BlobBlend";
    let set_visibility = |harness: &mut Harness, visibility: Visibility| {
        for (entity, name) in &primitives {
            if see_through(name) {
                harness.world_mut().entity_mut(*entity).insert(visibility);
            }
        }
    };
    set_visibility(&mut harness, Visibility::Hidden);
    let behind = harness.capture_inputs_with_maps();
    set_visibility(&mut harness, Visibility::Inherited);

    let camera = harness.camera_position();
    let lights = harness.reference_lights();
    let images = loaded_images(&mut harness);
    let materials: HashMap<_, _> = harness
        .world_mut()
        .resource::<Assets<PhongMaterial>>()
        .iter()
        .map(|(id, material)| (id, material.clone()))
        .collect();
    let scene = Scene {
        camera,
        materials: &materials,
        images: &images,
        lights: &lights,
    };
    let judged: RefCell<HashMap<AssetId<PhongMaterial>, usize>> = RefCell::default();
    let comparison = Comparison::of(&rendered, |pixel| {
        let Some((material, _)) = inputs.surface_at(pixel, camera) else {
            return Expected::Clear;
        };
        let color = |decoding| scene.color(&inputs, Some(&behind), pixel, decoding);
        match (color(SrgbDecoding::Lowest), color(SrgbDecoding::Highest)) {
            (Some(low), Some(high)) => {
                *judged.borrow_mut().entry(material.id()).or_default() += 1;
                Expected::Between(low, high)
            }
            _ => Expected::Unjudged,
        }
    });
    comparison.assert_within("posed glTF scene", TOLERANCE);

    // Every primitive, the skinned arm and the morphed blob included, was judged.
    let world = harness.world_mut();
    let mut names = world.query::<(&GltfMaterialName, &MeshMaterial3d<PhongMaterial>)>();
    for (name, material) in names.iter(world) {
        let judged = judged.borrow().get(&material.id()).copied().unwrap_or(0);
        println!("{}: {judged} pixels judged", name.0);
        assert!(judged >= MIN_PIXELS, "{}: {judged} pixels judged", name.0);
    }
    assert!(
        comparison.skipped_pixels < comparison.lit_pixels / 10,
        "too few pixels judged: {} lit, {} on texel edges",
        comparison.lit_pixels,
        comparison.skipped_pixels
    );
}
