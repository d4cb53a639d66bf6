//! `--compare`: the example's scene, seen from its camera, rendered into a float image and
//! compared pixel by pixel with the reference model (`bevy_phong::reference`), as the render
//! tests compare theirs (`Harness::compare_with_reference`): every lit pixel within
//! [`TOLERANCE`], and most pixels of each object judged.
//!
//! What the comparison does not model is left out of the frame, so that it judges the rest,
//! each left to the render test that checks it against its own formula:
//!
//! - no mesh casts a shadow (the shadow tests check shadows against exact rays);
//! - no material reflects an environment map, and Bevy's `Lightmap` components are removed
//!   (the environment and surface-input tests);
//! - every 2D image is sampled nearest from its first level, whose texels the reference
//!   model reads (a filtered sample blends texels with the device's own weights);
//! - the example's camera is replaced by one that draws the lighting model's colors as they
//!   are: no tone mapping, fog, bloom or MSAA (the camera-feature tests).
//!
//! Pixels the reference model cannot judge (a texel's edge, an edge of what shows through a
//! masked or blended mesh) are counted as unjudged.

use super::StillLoading;
use bevy::{
    app::{AppExit, PluginGroupBuilder},
    camera::RenderTarget,
    image::{ImageSampler, ImageSamplerDescriptor},
    light::NotShadowCaster,
    pbr::Lightmap,
    prelude::*,
    render::render_resource::TextureDimension,
    time::TimeUpdateStrategy,
};
use bevy_phong::PhongSceneMaterial;
use bevy_phong_headless::{
    Harness, HarnessCamera, TOLERANCE, frame_driven_plugins, read_back_frame,
};
use std::{path::Path, path::PathBuf, time::Duration};

/// Size of the compared frame: a third of the PNG's, so that the reference model's f64
/// pass over every pixel stays short.
const COMPARED_SIZE: UVec2 = UVec2::new(320, 180);
/// Frames to wait for an example's scene to load before giving up.
const MAX_LOADING_FRAMES: u32 = 2_000;

/// Bevy's plugins without a window, each frame rendered within `App::update`, and time held
/// at 0 (as the headless PNG holds it).
pub fn add_plugins(
    app: &mut App,
    configure: impl FnOnce(PluginGroupBuilder) -> PluginGroupBuilder,
) {
    app.add_plugins(configure(frame_driven_plugins(
        AssetPlugin::default().file_path,
    )))
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::ZERO));
}

/// Renders `app`'s scene and compares it with the reference model: success where every
/// judged pixel is within [`TOLERANCE`] and most pixels of each object are judged. With a
/// `picture` path, the example's own view is written there first, as a headless run writes
/// it.
pub fn run<M: PhongSceneMaterial>(app: App, picture: Option<PathBuf>) -> AppExit {
    match compare::<M>(app, picture) {
        Ok(summary) => {
            println!("--compare: {summary}");
            AppExit::Success
        }
        Err(failure) => {
            eprintln!("--compare failed: {failure}");
            AppExit::error()
        }
    }
}

fn compare<M: PhongSceneMaterial>(app: App, picture: Option<PathBuf>) -> Result<String, String> {
    let mut harness = Harness::adopting(app, COMPARED_SIZE.x, COMPARED_SIZE.y);
    // The first frame runs the example's startup: its camera and scene exist after it.
    harness.app.update();
    let mut frames = 1;
    while harness.world_mut().contains_resource::<StillLoading>() {
        if frames == MAX_LOADING_FRAMES {
            return Err(format!(
                "the scene was still loading after {MAX_LOADING_FRAMES} frames"
            ));
        }
        harness.app.update();
        frames += 1;
    }
    let world = harness.world_mut();
    let cameras: Vec<Entity> = world
        .query_filtered::<Entity, (With<Camera3d>, Without<HarnessCamera>)>()
        .iter(world)
        .collect();
    let [camera] = cameras[..] else {
        return Err(format!(
            "the example has {} 3D cameras; the comparison sees from one",
            cameras.len()
        ));
    };
    if let Some(path) = picture {
        write_picture(&mut harness, camera, &path)?;
    }
    harness.adopt_camera(camera);
    let world = harness.world_mut();
    let meshes: Vec<Entity> = world
        .query_filtered::<Entity, With<Mesh3d>>()
        .iter(world)
        .collect();
    for mesh in meshes {
        world
            .entity_mut(mesh)
            .insert(NotShadowCaster)
            .remove::<Lightmap>();
    }
    sample_nearest_from_the_first_level(&mut world.resource_mut::<Assets<Image>>());
    // Each material binds its maps' samplers when it is prepared: prepared again, it binds
    // the nearest ones.
    let mut materials = world.resource_mut::<Assets<M>>();
    let ids: Vec<AssetId<M>> = materials.ids().collect();
    for id in ids {
        let phong = materials
            .get_mut(id)
            .and_then(|material| material.into_inner().phong_material_mut());
        if let Some(phong) = phong {
            phong.environment_map = None;
            phong.camera_environment = false;
        }
    }

    harness.settle();
    let rendered = harness.render_next_frame();
    let comparison = harness.compare_with_reference_of::<M>(&rendered);
    let summary = format!(
        "{} pixels judged on {} objects, {} not; largest difference from the reference model \
         {:.2e} (tolerance {TOLERANCE:.0e}) at {:?}",
        comparison.lit_pixels,
        comparison.objects.len(),
        comparison.skipped_pixels,
        comparison.max_error,
        comparison.worst_pixel
    );
    let mut failures = comparison.judging_failures();
    if !comparison.within(TOLERANCE) {
        failures.push(format!(
            "a judged pixel beyond the tolerance, no pixel judged, or {} pixels drawn where \
             no mesh is",
            comparison.stray_pixels
        ));
    }
    if failures.is_empty() {
        Ok(summary)
    } else {
        let images = comparison.write_pngs("compare");
        Err(format!(
            "{summary}: {}; images in {}",
            failures.join("; "),
            images.display()
        ))
    }
}

/// Makes every 2D image of 4-byte texels kept in memory (the maps, not the render targets)
/// sampled with nearest filtering from its first mip level only.
fn sample_nearest_from_the_first_level(images: &mut Assets<Image>) {
    let ids: Vec<AssetId<Image>> = images.ids().collect();
    for id in ids {
        let Some(image) = images.get(id) else {
            continue;
        };
        let descriptor = &image.texture_descriptor;
        let first_level = (image.width() * image.height()) as usize * 4;
        let eligible = descriptor.dimension == TextureDimension::D2
            && descriptor.size.depth_or_array_layers == 1
            && descriptor.format.block_copy_size(None) == Some(4)
            && image
                .data
                .as_ref()
                .is_some_and(|data| data.len() >= first_level);
        if !eligible {
            continue;
        }
        let Some(mut image) = images.get_mut(id) else {
            continue;
        };
        if let Some(data) = image.data.as_mut() {
            data.truncate(first_level);
        }
        image.texture_descriptor.mip_level_count = 1;
        image.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor::nearest());
    }
}

/// Renders the example's own `camera`, with its effects, into an sRGB image of the headless
/// picture's size once the pipelines have settled, and writes it to `path` as a PNG: the
/// picture `--headless` writes, from the same run as the comparison.
fn write_picture(harness: &mut Harness, camera: Entity, path: &Path) -> Result<(), String> {
    let world = harness.world_mut();
    let target = world
        .resource_mut::<Assets<Image>>()
        .add(super::picture_target());
    world
        .entity_mut(camera)
        .insert(RenderTarget::Image(target.clone().into()));
    // Settled: every pipeline ready for three frames in a row, time held at 0 and no
    // effect that accumulates over frames, so a later frame is the same picture.
    harness.settle();
    let (width, height) = (
        super::PICTURE_SIZE.x as usize,
        super::PICTURE_SIZE.y as usize,
    );
    let pixels = read_back_frame(&mut harness.app, &target, 4 * width, height, App::update);
    super::save_picture(path, &pixels)
}
