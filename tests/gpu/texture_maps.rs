//! Texture maps: meshes with base color, specular, emissive and normal maps rendered on the
//! render device and compared with the reference model given each pixel's texels
//! (`reference::Material::mapped`, `reference::mapped_normal`).
//!
//! The maps are small `Rgba32Float` images sampled with nearest filtering, so the texel a
//! pixel received is known exactly from its UV (read back by `SurfaceInputsMaterial`);
//! pixels within 1/100 texel of a texel's edge, where the GPU's rounding of `uv · size` may
//! pick the neighbour, are left out. Tolerance: as the frame tests ([`TOLERANCE`]): the
//! texel products add one `f32` rounding each, and the mapped normal a few more before
//! it is normalized.

use crate::frames::{SIZE, TOLERANCE};
use bevy::{
    asset::RenderAssetUsages,
    image::{Image, ImageSampler},
    mesh::UvChannel,
    prelude::*,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{Harness, SurfaceInputs};
use glam::{DVec2, DVec3, DVec4};
use std::collections::HashMap;

/// Texels per side of every map this file makes.
pub(crate) const TEXELS: u32 = 4;

/// A `TEXELS`² map with nearest filtering whose texel `(x, y)` is `texel(x, y)` (each
/// channel in `[0, 1]`), stored as `Rgba8Unorm`: the 8-bit format games ship, which every
/// device filters (WebGL2 cannot filter 32-bit floats). The reference reads the stored
/// bytes, so the rounding to 1/255 is in both.
pub(crate) fn float_map(texel: impl Fn(u32, u32) -> [f32; 4]) -> Image {
    let data: Vec<u8> = (0..TEXELS * TEXELS)
        .flat_map(|index| texel(index % TEXELS, index / TEXELS))
        .map(|channel| (channel.clamp(0.0, 1.0) * 255.0).round() as u8)
        .collect();
    let mut image = Image::new(
        Extent3d {
            width: TEXELS,
            height: TEXELS,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8Unorm,
        RenderAssetUsages::default(),
    );
    image.sampler = ImageSampler::nearest();
    image
}

/// A value in `[low, high]` that varies from texel to texel and channel to channel.
fn scatter(x: u32, y: u32, channel: u32, low: f32, high: f32) -> f32 {
    let hash = (x * 7 + y * 13 + channel * 5 + 3) % 11;
    low + (high - low) * hash as f32 / 10.0
}

/// A map whose channels vary from texel to texel within `[low, high]`.
pub(crate) fn color_map(low: f32, high: f32) -> Image {
    float_map(|x, y| [0, 1, 2, 3].map(|channel| scatter(x, y, channel, low, high)))
}

/// Tangent-space normals tilted up to ~50° from the surface normal, encoded as `(n + 1) / 2`.
pub(crate) fn normal_map() -> Image {
    float_map(|x, y| {
        let n = Vec3::new(
            scatter(x, y, 0, -0.6, 0.6),
            scatter(x, y, 1, -0.6, 0.6),
            1.0,
        )
        .normalize();
        let encoded = (n + 1.0) / 2.0;
        [encoded.x, encoded.y, encoded.z, 1.0]
    })
}

/// How the reference decodes an 8-bit sRGB texel. A sampler may return any linear value
/// whose exact sRGB encoding is within half an 8-bit step of the texel (Direct3D 10's rule;
/// lavapipe's cubic approximation stays within 0.35 of a step), so a pixel lit with an
/// sRGB map is judged against the colors its lowest and highest decodings give.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SrgbDecoding {
    /// The exact transfer function.
    Exact,
    /// Half a step below the texel, then exact.
    Lowest,
    /// Half a step above the texel, then exact.
    Highest,
}

/// The texel of `image` that nearest filtering gives at `uv` (clamped to the edge), or
/// `None` within 1/100 texel of a texel's edge. Channels in `[0, 1]`; the color channels
/// of an sRGB image decoded to linear as `decoding` says.
pub(crate) fn texel_at(image: &Image, uv: [f64; 2], decoding: SrgbDecoding) -> Option<DVec4> {
    let size = [image.width() as usize, image.height() as usize];
    let mut texel = [0usize; 2];
    for axis in 0..2 {
        let scaled = uv[axis] * size[axis] as f64;
        let fraction = scaled - scaled.floor();
        if (0.01..=0.99).contains(&fraction) || scaled <= 0.0 || scaled >= size[axis] as f64 {
            texel[axis] = (scaled.floor().max(0.0) as usize).min(size[axis] - 1);
        } else {
            return None;
        }
    }
    let data = image.data.as_ref().expect("test maps keep their data");
    assert_eq!(
        data.len(),
        size[0] * size[1] * 4,
        "an image of 4 bytes per texel"
    );
    let start = (texel[1] * size[0] + texel[0]) * 4;
    let srgb = image.texture_descriptor.format.is_srgb();
    let offset = match decoding {
        SrgbDecoding::Exact => 0.0,
        SrgbDecoding::Lowest => -0.5,
        SrgbDecoding::Highest => 0.5,
    };
    let channels: Vec<f64> = data[start..start + 4]
        .iter()
        .enumerate()
        .map(|(channel, &byte)| {
            if srgb && channel < 3 {
                srgb_to_linear(((f64::from(byte) + offset) / 255.0).clamp(0.0, 1.0))
            } else {
                f64::from(byte) / 255.0
            }
        })
        .collect();
    Some(DVec4::from_slice(&channels))
}

/// The sRGB transfer function's inverse (IEC 61966-2-1).
fn srgb_to_linear(value: f64) -> f64 {
    if value <= 0.04045 {
        value / 12.92
    } else {
        ((value + 0.055) / 1.055).powf(2.4)
    }
}

/// The UVs `material`'s maps are sampled at in pixel `pixel`: the captured first UV set
/// moved by the material's UV transform, in `f64` (`reference::transformed_uv`).
pub(crate) fn sampled_uv<M: Material>(
    material: &PhongMaterial,
    inputs: &SurfaceInputs<M>,
    pixel: usize,
) -> [f64; 2] {
    let uv_and_sign = inputs.uvs.as_ref().unwrap().pixels[pixel];
    let uv = DVec2::new(uv_and_sign[0].into(), uv_and_sign[1].into());
    let transform = bevy_phong::limits::uv_transform(material.uv_transform);
    reference::transformed_uv(transform, uv).to_array()
}

/// The UVs a map of `material` on `channel` is sampled at in pixel `pixel`: the first set
/// as [`sampled_uv`] gives it, the second as captured.
fn map_uv<M: Material>(
    material: &PhongMaterial,
    channel: &UvChannel,
    inputs: &SurfaceInputs<M>,
    pixel: usize,
) -> [f64; 2] {
    match channel {
        UvChannel::Uv0 => sampled_uv(material, inputs, pixel),
        UvChannel::Uv1 => {
            let uv = inputs.second_uvs.as_ref().unwrap().pixels[pixel];
            [uv[0].into(), uv[1].into()]
        }
    }
}

/// The interpolated vertex color of pixel `pixel` (white where the mesh has none).
pub(crate) fn vertex_color<M: Material>(inputs: &SurfaceInputs<M>, pixel: usize) -> DVec4 {
    let color = inputs.colors.as_ref().unwrap().pixels[pixel];
    DVec4::from_array(color.map(f64::from))
}

/// Every image the harness's app holds, by id: the texels the reference reads.
pub(crate) fn loaded_images(harness: &mut Harness) -> HashMap<AssetId<Image>, Image> {
    harness
        .world_mut()
        .resource::<Assets<Image>>()
        .iter()
        .map(|(id, image)| (id, image.clone()))
        .collect()
}

/// The normal a pixel of `material` is lit with, given its captured inputs: the normal
/// map's and then the bump map's where the material has them and the mesh has tangents
/// (the bump map only where the device binds it), around `surface.normal` (the frame normal:
/// the interpolated normal, or the face normal with flat shading); `None` on a texel edge.
pub(crate) fn lit_normal<M: Material>(
    material: &PhongMaterial,
    surface: &reference::SurfacePoint,
    pixel: usize,
    inputs: &SurfaceInputs<M>,
    images: &HashMap<AssetId<Image>, Image>,
) -> Option<DVec3> {
    let uv_and_sign = inputs.uvs.as_ref().unwrap().pixels[pixel];
    let tangent = inputs.tangents.as_ref().unwrap().pixels[pixel];
    let tangent = DVec4::new(
        tangent[0].into(),
        tangent[1].into(),
        tangent[2].into(),
        uv_and_sign[2].into(),
    );
    // The tangent maps apply only where the mesh has tangents (`w` is ±1 there, 0 without).
    if tangent.w == 0.0 {
        return Some(surface.normal);
    }
    let uv = sampled_uv(material, inputs, pixel);
    // Normal and bump maps are linear: nothing to decode.
    let texel = |handle: &Handle<Image>, uv: [f64; 2]| {
        texel_at(&images[&handle.id()], uv, SrgbDecoding::Exact)
    };
    let mut normal = surface.normal;
    if let Some(handle) = &material.normal_map_texture {
        let texel = texel(handle, uv)?.truncate();
        normal = reference::mapped_normal(normal, tangent, texel, material.flip_normal_map_y);
    }
    if let Some(handle) = material
        .bump_map_texture
        .as_ref()
        .filter(|_| inputs.every_map_bound)
    {
        let image = &images[&handle.id()];
        let step = [
            1.0 / f64::from(image.width()),
            1.0 / f64::from(image.height()),
        ];
        let height = texel(handle, uv)?.x;
        let along_u = texel(handle, [uv[0] + step[0], uv[1]])?.x;
        let along_v = texel(handle, [uv[0], uv[1] + step[1]])?.x;
        let slope = DVec2::new(along_u - height, along_v - height);
        let scale = f64::from(bevy_phong::limits::SIGNED_SCALE.apply(material.bump_scale));
        normal = reference::bumped_normal(normal, surface.normal, tangent, slope, scale);
    }
    Some(normal)
}

/// The texels each of `material`'s maps gives in pixel `pixel` (at the UVs of
/// [`sampled_uv`], or the second set for a light or AO map on it), sRGB maps decoded as
/// `decoding` says; `None` on a texel edge.
pub(crate) fn texels_at<M: Material>(
    material: &PhongMaterial,
    inputs: &SurfaceInputs<M>,
    pixel: usize,
    images: &HashMap<AssetId<Image>, Image>,
    decoding: SrgbDecoding,
) -> Option<reference::Texels> {
    let uv = sampled_uv(material, inputs, pixel);
    let sample_at = |map: &Option<Handle<Image>>, uv: [f64; 2]| -> Result<Option<DVec4>, ()> {
        match map {
            None => Ok(None),
            Some(handle) => texel_at(&images[&handle.id()], uv, decoding)
                .map(Some)
                .ok_or(()),
        }
    };
    let sample = |map: &Option<Handle<Image>>| sample_at(map, uv);
    let light_map_uv = map_uv(material, &material.light_map_channel, inputs, pixel);
    let ao_map_uv = map_uv(material, &material.ao_map_channel, inputs, pixel);
    Some(reference::Texels {
        base_color: sample(&material.base_color_texture).ok()?,
        specular: sample(&material.specular_texture)
            .ok()?
            .map(DVec4::truncate),
        emissive: sample(&material.emissive_texture)
            .ok()?
            .map(DVec4::truncate),
        normal: sample(&material.normal_map_texture)
            .ok()?
            .map(DVec4::truncate),
        light_map: sample_at(&material.light_map_texture, light_map_uv)
            .ok()?
            .map(DVec4::truncate),
        ao_map: sample_at(&material.ao_map_texture, ao_map_uv)
            .ok()?
            .map(|texel| texel.x),
        // Left out where the device does not bind every map (WebGL2).
        alpha_map: sample(&material.alpha_map_texture)
            .ok()?
            .map(|texel| texel.y)
            .filter(|_| inputs.every_map_bound),
    })
}

/// The output alpha of a fragment of `material` whose maps gave `texels` and whose vertex
/// color has alpha `vertex_alpha`.
pub(crate) fn output_alpha(
    material: &PhongMaterial,
    texels: &reference::Texels,
    vertex_alpha: f64,
) -> f64 {
    texels.base_color.map_or(1.0, |t| t.w)
        * f64::from(material.base_color.alpha())
        * vertex_alpha
        * texels.alpha_map.unwrap_or(1.0)
}

/// Whether `material`'s alpha mask discards a fragment whose maps gave `texels` and whose
/// vertex color has alpha `vertex_alpha`; `None` within 10⁻⁶ of the cutoff, too close to
/// say.
pub(crate) fn masked_out(
    material: &PhongMaterial,
    texels: &reference::Texels,
    vertex_alpha: f64,
) -> Option<bool> {
    let AlphaMode::Mask(cutoff) = material.alpha_mode else {
        return Some(false);
    };
    let alpha = output_alpha(material, texels, vertex_alpha);
    if (alpha - f64::from(cutoff)).abs() < 1e-6 {
        return None;
    }
    Some(alpha < f64::from(cutoff))
}

/// `material` as the reference model lights pixel `pixel`: its vertex color and its maps'
/// `texels` applied, with the toon ramp the device binds.
pub(crate) fn mapped_material<M: Material>(
    material: &PhongMaterial,
    pixel: usize,
    inputs: &SurfaceInputs<M>,
    texels: &reference::Texels,
    images: &HashMap<AssetId<Image>, Image>,
) -> reference::Material {
    let mut mapped = reference::Material::from(material)
        .with_vertex_color(vertex_color(inputs, pixel))
        .mapped(texels);
    mapped.toon_ramp = toon_ramp(material, inputs, images);
    mapped
}

/// The reference color of a pixel of `material` that is drawn (not masked out), given its
/// captured inputs and its maps' `texels` (`emissive + k_d` where it is unlit); `None` on a
/// texel edge of the normal map.
pub(crate) fn lit_color<M: Material>(
    material: &PhongMaterial,
    surface: &reference::SurfacePoint,
    pixel: usize,
    inputs: &SurfaceInputs<M>,
    texels: &reference::Texels,
    images: &HashMap<AssetId<Image>, Image>,
    lights: &reference::Lights,
) -> Option<DVec3> {
    let mapped = mapped_material(material, pixel, inputs, texels, images);
    if material.unlit {
        return Some(mapped.unlit_color());
    }
    let normal = lit_normal(material, surface, pixel, inputs, images)?;
    let surface = reference::SurfacePoint { normal, ..*surface };
    let baked = reference::BakedLight::from_texels(
        texels,
        f64::from(material.light_map_intensity),
        f64::from(material.ao_map_intensity),
    );
    Some(reference::shade_baked(&surface, &mapped, lights, &baked))
}

/// The toon ramp `material` is drawn with: its `toon_ramp_texture` where the device binds it.
pub(crate) fn toon_ramp<M: Material>(
    material: &PhongMaterial,
    inputs: &SurfaceInputs<M>,
    images: &HashMap<AssetId<Image>, Image>,
) -> Option<reference::ToonRamp> {
    let image = images.get(&material.toon_ramp_texture.as_ref()?.id())?;
    inputs
        .every_map_bound
        .then(|| reference::ToonRamp::from_image(image).expect("a readable toon ramp"))
}

/// The reference color of a pixel of `material`, given its captured inputs; `None` on a
/// texel edge. Where the mask discards, the clear color (nothing is behind these meshes).
pub(crate) fn expected_color(
    material: &PhongMaterial,
    surface: &reference::SurfacePoint,
    pixel: usize,
    inputs: &SurfaceInputs,
    images: &HashMap<AssetId<Image>, Image>,
    lights: &reference::Lights,
) -> Option<DVec3> {
    // The maps here are linear (`Rgba8Unorm`): nothing to decode.
    let texels = texels_at(material, inputs, pixel, images, SrgbDecoding::Exact)?;
    if masked_out(material, &texels, vertex_color(inputs, pixel).w)? {
        return Some(DVec3::ZERO);
    }
    lit_color(material, surface, pixel, inputs, &texels, images, lights)
}

/// The lights of the map tests: ambient, a directional light and a point light.
pub(crate) fn spawn_map_lights(world: &mut World) {
    world.insert_resource(PhongAmbientLight {
        color: Color::srgb(0.2, 0.2, 0.25),
    });
    world.spawn((
        PhongDirectionalLight {
            color: Color::srgb(0.7, 0.7, 0.6),
            ..default()
        },
        Transform::from_xyz(1.0, 2.0, 1.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    world.spawn((
        PhongPointLight {
            color: Color::srgb(0.9, 0.5, 0.3),
            decay: Decay::new(1.0, 0.09, 0.032),
            ..default()
        },
        Transform::from_xyz(-1.5, 1.5, 2.5),
    ));
}

/// What a pixel should show, given its material, surface point, index, captured inputs,
/// the app's images and the lights: `None` where it cannot be judged.
pub(crate) type ExpectedColor<'a> = dyn Fn(
        &PhongMaterial,
        &reference::SurfacePoint,
        usize,
        &SurfaceInputs,
        &HashMap<AssetId<Image>, Image>,
        &reference::Lights,
    ) -> Option<DVec3>
    + 'a;

/// Spawns `objects`, renders a frame, captures its inputs with the maps' and compares every
/// pixel with `expected`; at most a fifth of the lit pixels may go unjudged.
pub(crate) fn assert_pixels_follow(
    mut harness: Harness,
    objects: impl IntoIterator<Item = (Mesh, Transform, PhongMaterial)>,
    name: &str,
    expected: &ExpectedColor,
) {
    let world = harness.world_mut();
    for (mesh, transform, material) in objects {
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
        world.spawn((Mesh3d(mesh), MeshMaterial3d(material), transform));
    }
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    let lights = harness.reference_lights();
    let images = loaded_images(&mut harness);
    let comparison = harness.compare_pixels(&rendered, &inputs, |material, surface, pixel| {
        expected(material, surface, pixel, &inputs, &images, &lights)
    });
    comparison.assert_within(name, TOLERANCE);
    assert!(
        comparison.skipped_pixels < comparison.lit_pixels / 5,
        "{name}: too few pixels judged: {} lit, {} on texel edges or the mask's cutoff",
        comparison.lit_pixels,
        comparison.skipped_pixels
    );
}

/// [`assert_pixels_follow`] the reference model ([`expected_color`]).
pub(crate) fn assert_follows_the_reference(
    harness: Harness,
    objects: impl IntoIterator<Item = (Mesh, Transform, PhongMaterial)>,
    name: &str,
) {
    assert_pixels_follow(harness, objects, name, &expected_color);
}

#[test]
fn texture_maps_follow_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);

    let mut images = world.resource_mut::<Assets<Image>>();
    let base_color = images.add(color_map(0.2, 1.0));
    let specular = images.add(color_map(0.0, 1.0));
    let emissive = images.add(color_map(0.0, 0.3));
    let normals = images.add(normal_map());
    let cutout = images.add(float_map(|x, y| {
        [0.9, 0.6, 0.3, scatter(x, y, 3, 0.0, 1.0)]
    }));

    let every_map = PhongMaterial {
        base_color_texture: Some(base_color.clone()),
        specular_texture: Some(specular),
        emissive_texture: Some(emissive),
        normal_map_texture: Some(normals.clone()),
        flip_normal_map_y: true,
        specular_strength: 2.0,
        shininess: 40.0,
        emissive: LinearRgba::WHITE,
        ..default()
    };
    let base_color_and_normals = PhongMaterial {
        base_color_texture: Some(base_color),
        normal_map_texture: Some(normals),
        shininess: 20.0,
        ..default()
    };
    let masked = PhongMaterial {
        base_color_texture: Some(cutout),
        alpha_mode: AlphaMode::Mask(0.5),
        emissive: LinearRgba::rgb(0.1, 0.1, 0.1),
        ..default()
    };
    let objects = [
        // Tangents: the normal map applies.
        (
            Sphere::new(1.2)
                .mesh()
                .uv(48, 32)
                .with_generated_tangents()
                .unwrap(),
            Transform::from_xyz(0.0, 0.0, 0.0),
            every_map,
        ),
        // No tangents: the normal map is left out (with a warning), the base color map not.
        (
            Cuboid::new(1.2, 1.2, 1.2).into(),
            Transform::from_xyz(-2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(0.6)),
            base_color_and_normals,
        ),
        // Alpha mask: texels below 0.5 are holes.
        (
            Cuboid::new(1.2, 1.2, 1.2).into(),
            Transform::from_xyz(2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(-0.6)),
            masked,
        ),
    ];
    assert_follows_the_reference(harness, objects, "texture maps");
}
