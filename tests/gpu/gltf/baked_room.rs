//! The repository's baked room (`assets/gltf/baked_room.gltf`, written by
//! `crates/phong_gltf_asset`) loaded from its file: vertex colors (`COLOR_0`), a second UV
//! set (`TEXCOORD_1`) carrying the occlusion texture, and a floor checkerboard tiled by
//! `KHR_texture_transform`, each as the file says it and drawn as the reference model says.
//! The file's images are loaded nearest-sampled (the loader's `override_sampler`), so that
//! the reference knows the texel each pixel reads. They are sRGB, which a sampler may decode
//! within half an 8-bit step of the exact transfer function: each pixel is judged between
//! the reference's colors at its texels half a step below and half a step above
//! (`SrgbDecoding`), within the frame tests' tolerance.

use super::{phong_only_gltf_harness, spawn_gltf_scene_with};
use crate::frames::TOLERANCE;
use bevy::{
    image::ImageSamplerDescriptor,
    math::{Affine2, Vec2},
    mesh::UvChannel,
    prelude::*,
};
use bevy_phong::prelude::*;
use bevy_phong_headless::{
    Comparison, Expected,
    pixel_model::{SrgbDecoding, lit_color, loaded_images, texels_at},
};

/// The room, in the crate's asset folder.
const BAKED_ROOM_GLTF: &str = "gltf/baked_room.gltf";

/// Render size.
const SIZE: u32 = 160;

#[test]
fn a_loaded_room_keeps_its_vertex_colors_second_uv_set_occlusion_and_texture_transform() {
    let mut harness = phong_only_gltf_harness(SIZE, SIZE);
    harness.look_from(Vec3::new(4.6, 3.6, 3.2));
    spawn_gltf_scene_with(&mut harness, BAKED_ROOM_GLTF, |settings| {
        settings.override_sampler = true;
        settings.default_sampler = Some(ImageSamplerDescriptor::nearest());
    });
    harness.world_mut().insert_resource(PhongAmbientLight {
        color: Color::srgb(0.4, 0.4, 0.45),
    });

    // As the file says: the floor's occlusion on TEXCOORD_1, its checkerboard tiled twice
    // and moved a quarter (KHR_texture_transform), every baked mesh with vertex colors.
    let world = harness.world_mut();
    let mut primitives = world.query::<(&ChildOf, &Mesh3d, &MeshMaterial3d<PhongMaterial>)>();
    let names: Vec<(String, Handle<Mesh>, Handle<PhongMaterial>)> = primitives
        .iter(world)
        .map(|(parent, mesh, material)| {
            let name = world
                .get::<Name>(parent.parent())
                .map_or_else(String::new, |name| name.as_str().to_owned());
            (name, mesh.0.clone(), material.0.clone())
        })
        .collect();
    let floor = names
        .iter()
        .find(|(name, ..)| name == "Floor")
        .expect("the room's floor");
    let material = world
        .resource::<Assets<PhongMaterial>>()
        .get(&floor.2)
        .expect("the floor's material");
    assert_eq!(material.ao_map_channel, UvChannel::Uv1);
    assert!(
        material.ao_map_texture.is_some(),
        "the floor's occlusion texture"
    );
    assert_eq!(
        material.uv_transform,
        Affine2::from_scale_angle_translation(Vec2::splat(2.0), 0.0, Vec2::new(0.25, 0.0)),
        "the floor's texture transform"
    );
    let meshes = world.resource::<Assets<Mesh>>();
    for (name, mesh, _) in &names {
        let mesh = meshes.get(mesh).expect("a loaded mesh");
        assert!(
            mesh.attribute(Mesh::ATTRIBUTE_COLOR).is_some(),
            "{name}: its vertex colors"
        );
    }

    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    let scene = harness.reference_scene();
    let images = loaded_images(&mut harness);
    let camera = harness.camera_position();
    let materials = harness.world_mut().resource::<Assets<PhongMaterial>>();
    let comparison = Comparison::of(&rendered, |pixel| {
        let Some((handle, surface)) = inputs.surface_at(pixel, camera) else {
            return Expected::Clear;
        };
        let material = materials.get(handle).expect("a loaded material");
        let color = |decoding| {
            let lights = scene.lights_at(surface.position, inputs.every_map_bound)?;
            let texels = texels_at(material, &inputs, pixel, &images, decoding)?;
            lit_color(
                material, &surface, pixel, &inputs, &texels, &images, &lights,
            )
        };
        match (color(SrgbDecoding::Lowest), color(SrgbDecoding::Highest)) {
            (Some(low), Some(high)) => Expected::Between(low, high),
            _ => Expected::Unjudged,
        }
    });
    comparison.assert_within("loaded baked room", TOLERANCE);
    comparison.assert_mostly_judged("loaded baked room");
}
