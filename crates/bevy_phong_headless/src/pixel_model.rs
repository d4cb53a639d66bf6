//! The reference model's color of one captured pixel: what [`bevy_phong::reference`] says a
//! pixel of a [`PhongMaterial`] shows, given the inputs the harness read back for it
//! ([`SurfaceInputs`]: its position, normal, UVs, tangent and vertex color) and the texels
//! its maps hold there. Every material feature is applied as the material's shader applies
//! it: the maps (base color, specular, emissive, normal, bump, alpha, light, AO), the alpha
//! mask, vertex colors, the UV transform, flat shading (the normal of the mesh's triangle
//! under the pixel, [`face_normal_at`]), unlit materials, the diffuse and specular modes, the toon ramp and the rim.
//!
//! A pixel is left unjudged (`None`) where its color cannot be known exactly: within 1/100
//! texel of a texel's edge, within 10⁻⁶ of the alpha mask's cutoff, and on a map that is not
//! sampled with nearest filtering from one level ([`is_judged`]). Environment maps are not
//! modelled here (their test reads the cube map's texels itself): their pixels are unjudged.

use bevy::{
    asset::{AssetId, Assets, Handle},
    image::{Image, ImageFilterMode, ImageSampler},
    math::{DVec2, DVec3, DVec4, Vec3},
    mesh::{Mesh, UvChannel},
    pbr::Material,
    prelude::GlobalTransform,
    prelude::{Alpha, AlphaMode},
};
use bevy_phong::{PhongMaterial, reference};
use std::collections::HashMap;

use crate::{Harness, SurfaceInputs};

/// Whether the reference can know the texel `image` gives at a UV: one mip level, 4 bytes a
/// texel, kept in memory, and sampled with nearest filtering (the images the render tests
/// make). A filtered image blends texels with the device's own weights.
pub fn is_judged(image: &Image) -> bool {
    let nearest = match &image.sampler {
        ImageSampler::Descriptor(descriptor) => {
            descriptor.mag_filter == ImageFilterMode::Nearest
                && descriptor.min_filter == ImageFilterMode::Nearest
        }
        ImageSampler::Default => false,
    };
    let texels = (image.width() * image.height()) as usize;
    nearest
        && image.texture_descriptor.mip_level_count == 1
        && image
            .data
            .as_ref()
            .is_some_and(|data| data.len() == texels * 4)
}

/// How the reference decodes an 8-bit sRGB texel. A sampler may return any linear value
/// whose exact sRGB encoding is within half an 8-bit step of the texel (Direct3D 10's rule;
/// lavapipe's cubic approximation stays within 0.35 of a step), so a pixel lit with an
/// sRGB map is judged against the colors its lowest and highest decodings give.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SrgbDecoding {
    /// The exact transfer function.
    Exact,
    /// Half a step below the texel, then exact.
    Lowest,
    /// Half a step above the texel, then exact.
    Highest,
}

/// The texel of `image` that nearest filtering gives at `uv` (clamped to the edge), or
/// `None` within 1/100 texel of a texel's edge. Channels in `[0, 1]`; the color channels
/// of an sRGB image decoded to linear as `decoding` says. `None` too for an image whose
/// texel the reference cannot know ([`is_judged`]).
pub fn texel_at(image: &Image, uv: [f64; 2], decoding: SrgbDecoding) -> Option<DVec4> {
    if !is_judged(image) {
        return None;
    }
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
    let data = image.data.as_ref()?;
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
pub fn sampled_uv<M: Material>(
    material: &PhongMaterial,
    inputs: &SurfaceInputs<M>,
    pixel: usize,
) -> Option<[f64; 2]> {
    let uv_and_sign = inputs.uvs.as_ref()?.pixels[pixel];
    let uv = DVec2::new(uv_and_sign[0].into(), uv_and_sign[1].into());
    let transform = bevy_phong::testing::limits::uv_transform(material.uv_transform);
    Some(reference::transformed_uv(transform, uv).to_array())
}

/// The UVs a map of `material` on `channel` is sampled at in pixel `pixel`: the first set
/// as [`sampled_uv`] gives it, the second as captured.
fn map_uv<M: Material>(
    material: &PhongMaterial,
    channel: &UvChannel,
    inputs: &SurfaceInputs<M>,
    pixel: usize,
) -> Option<[f64; 2]> {
    match channel {
        UvChannel::Uv0 => sampled_uv(material, inputs, pixel),
        UvChannel::Uv1 => {
            let uv = inputs.second_uvs.as_ref()?.pixels[pixel];
            Some([uv[0].into(), uv[1].into()])
        }
    }
}

/// The interpolated vertex color of pixel `pixel` (white where the mesh has none).
pub fn vertex_color<M: Material>(inputs: &SurfaceInputs<M>, pixel: usize) -> DVec4 {
    inputs.colors.as_ref().map_or(DVec4::ONE, |colors| {
        DVec4::from_array(colors.pixels[pixel].map(f64::from))
    })
}

/// Every image the harness's app holds, by id: the texels the reference reads.
pub fn loaded_images(harness: &mut Harness) -> HashMap<AssetId<Image>, Image> {
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
pub fn lit_normal<M: Material>(
    material: &PhongMaterial,
    surface: &reference::SurfacePoint,
    pixel: usize,
    inputs: &SurfaceInputs<M>,
    images: &HashMap<AssetId<Image>, Image>,
) -> Option<DVec3> {
    if material.normal_map_texture.is_none() && material.bump_map_texture.is_none() {
        return Some(surface.normal);
    }
    let uv_and_sign = inputs.uvs.as_ref()?.pixels[pixel];
    let tangent = inputs.tangents.as_ref()?.pixels[pixel];
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
    // Normal and bump maps are linear: nothing to decode.
    let texel = |handle: &Handle<Image>, uv: [f64; 2]| {
        texel_at(images.get(&handle.id())?, uv, SrgbDecoding::Exact)
    };
    let mut normal = surface.normal;
    if let Some(handle) = &material.normal_map_texture {
        let uv = map_uv(material, &material.normal_map_channel, inputs, pixel)?;
        let texel = texel(handle, uv)?.truncate();
        let scale = bevy_phong::testing::limits::NORMAL_MAP_SCALE;
        let scale = DVec2::new(
            scale.apply(material.normal_map_scale.x).into(),
            scale.apply(material.normal_map_scale.y).into(),
        );
        normal =
            reference::mapped_normal(normal, tangent, texel, material.flip_normal_map_y, scale);
    }
    if let Some(handle) = material
        .bump_map_texture
        .as_ref()
        .filter(|_| inputs.every_map_bound)
    {
        let image = images.get(&handle.id())?;
        let uv = map_uv(material, &material.bump_map_channel, inputs, pixel)?;
        let step = [
            1.0 / f64::from(image.width()),
            1.0 / f64::from(image.height()),
        ];
        let height = texel(handle, uv)?.x;
        let along_u = texel(handle, [uv[0] + step[0], uv[1]])?.x;
        let along_v = texel(handle, [uv[0], uv[1] + step[1]])?.x;
        let slope = DVec2::new(along_u - height, along_v - height);
        let scale = f64::from(bevy_phong::testing::limits::SIGNED_SCALE.apply(material.bump_scale));
        normal = reference::bumped_normal(normal, surface.normal, tangent, slope, scale);
    }
    Some(normal)
}

/// The texels each of `material`'s maps gives in pixel `pixel` (each at its UV set: the
/// first as [`sampled_uv`] gives it, the second as captured), sRGB maps decoded as
/// `decoding` says; `None` on a texel edge.
pub fn texels_at<M: Material>(
    material: &PhongMaterial,
    inputs: &SurfaceInputs<M>,
    pixel: usize,
    images: &HashMap<AssetId<Image>, Image>,
    decoding: SrgbDecoding,
) -> Option<reference::Texels> {
    // A map the reference cannot read (not loaded, filtered, no UVs captured) is an
    // unjudged pixel, as a texel edge is.
    let sample_at =
        |map: &Option<Handle<Image>>, channel: &UvChannel| -> Result<Option<DVec4>, ()> {
            match map {
                None => Ok(None),
                Some(handle) => {
                    let uv = map_uv(material, channel, inputs, pixel).ok_or(())?;
                    let image = images.get(&handle.id()).ok_or(())?;
                    texel_at(image, uv, decoding).map(Some).ok_or(())
                }
            }
        };
    Some(reference::Texels {
        base_color: sample_at(&material.base_color_texture, &material.base_color_channel).ok()?,
        specular: sample_at(&material.specular_texture, &material.specular_channel)
            .ok()?
            .map(DVec4::truncate),
        emissive: sample_at(&material.emissive_texture, &material.emissive_channel)
            .ok()?
            .map(DVec4::truncate),
        normal: sample_at(&material.normal_map_texture, &material.normal_map_channel)
            .ok()?
            .map(DVec4::truncate),
        light_map: sample_at(&material.light_map_texture, &material.light_map_channel)
            .ok()?
            .map(DVec4::truncate),
        ao_map: sample_at(&material.ao_map_texture, &material.ao_map_channel)
            .ok()?
            .map(|texel| texel.x),
        // Left out where the device does not bind every map (WebGL2).
        alpha_map: sample_at(&material.alpha_map_texture, &material.alpha_map_channel)
            .ok()?
            .map(|texel| texel.y)
            .filter(|_| inputs.every_map_bound),
        // Blue metallic, green roughness.
        metallic_roughness: sample_at(
            &material.metallic_roughness_texture,
            &material.metallic_roughness_channel,
        )
        .ok()?
        .map(|texel| DVec2::new(texel.z, texel.y)),
    })
}

/// The output alpha of a fragment of `material` whose maps gave `texels` and whose vertex
/// color has alpha `vertex_alpha`.
pub fn output_alpha(
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
pub fn masked_out(
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
pub fn mapped_material<M: Material>(
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
/// captured inputs and its maps' `texels` (`k_d` alone where it is unlit); `None` on a
/// texel edge of the normal map.
pub fn lit_color<M: Material>(
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
pub fn toon_ramp<M: Material>(
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
/// texel edge, and for a material with an environment map (not modelled here). Where the
/// mask discards, the clear color (nothing is behind these meshes).
pub fn expected_color(
    material: &PhongMaterial,
    surface: &reference::SurfacePoint,
    pixel: usize,
    inputs: &SurfaceInputs,
    images: &HashMap<AssetId<Image>, Image>,
    lights: &reference::Lights,
) -> Option<DVec3> {
    // sRGB maps decoded exactly: a sampler may land within half an 8-bit step of that (see
    // `SrgbDecoding`), so the render tests' maps are linear.
    expected_color_decoded(
        material,
        surface,
        pixel,
        inputs,
        images,
        lights,
        SrgbDecoding::Exact,
    )
}

/// [`expected_color`] with the sRGB maps' texels decoded as `decoding` says, on the inputs
/// of any material made of a [`PhongMaterial`].
pub fn expected_color_decoded<M: Material>(
    material: &PhongMaterial,
    surface: &reference::SurfacePoint,
    pixel: usize,
    inputs: &SurfaceInputs<M>,
    images: &HashMap<AssetId<Image>, Image>,
    lights: &reference::Lights,
    decoding: SrgbDecoding,
) -> Option<DVec3> {
    if material.environment_map.is_some() || material.camera_environment {
        return None;
    }
    let texels = texels_at(material, inputs, pixel, images, decoding)?;
    if masked_out(material, &texels, vertex_color(inputs, pixel).w)? {
        return Some(DVec3::ZERO);
    }
    lit_color(material, surface, pixel, inputs, &texels, images, lights)
}

/// Whether `material` reads a map stored as sRGB: its pixels are judged between the colors
/// the lowest and the highest decodings give ([`SrgbDecoding`]).
pub fn reads_srgb_map(material: &PhongMaterial, images: &HashMap<AssetId<Image>, Image>) -> bool {
    [
        &material.base_color_texture,
        &material.specular_texture,
        &material.emissive_texture,
        &material.normal_map_texture,
        &material.light_map_texture,
        &material.ao_map_texture,
        &material.alpha_map_texture,
        &material.metallic_roughness_texture,
    ]
    .into_iter()
    .flatten()
    .any(|handle| {
        images
            .get(&handle.id())
            .is_some_and(|image| image.texture_descriptor.format.is_srgb())
    })
}

/// How much of what is behind pixel `pixel` of `material` shows through it: `Some(0.0)`
/// where nothing does, `Some(1.0)` where the alpha mask discards, `1 − alpha` where it
/// blends ([`AlphaMode::Blend`]); `None` where that cannot be told (a texel edge, the
/// mask's cutoff).
pub fn see_through<M: Material>(
    material: &PhongMaterial,
    pixel: usize,
    inputs: &SurfaceInputs<M>,
    images: &HashMap<AssetId<Image>, Image>,
) -> Option<f64> {
    let texels = texels_at(material, inputs, pixel, images, SrgbDecoding::Exact)?;
    let vertex_alpha = vertex_color(inputs, pixel).w;
    match material.alpha_mode {
        AlphaMode::Mask(_) => masked_out(material, &texels, vertex_alpha)
            .map(|discarded| if discarded { 1.0 } else { 0.0 }),
        AlphaMode::Blend => Some(1.0 - output_alpha(material, &texels, vertex_alpha)),
        _ => Some(0.0),
    }
}

/// Whether `direction`'s two largest components are within 10⁻⁵ of each other (relative):
/// on a cube edge, where a device's `f32` may pick the other face of a cube map.
pub fn near_a_cube_edge(direction: DVec3) -> bool {
    let mut a = direction.abs().to_array();
    a.sort_by(f64::total_cmp);
    a[2] - a[1] <= 1e-5 * a[2]
}

/// The world-space triangles of `mesh` placed by `transform` (none without positions).
pub fn world_triangles(mesh: &Mesh, transform: &GlobalTransform) -> Vec<[DVec3; 3]> {
    world_corners(mesh, transform)
        .into_iter()
        .map(|corners| corners.map(|(position, _)| position))
        .collect()
}

/// The world-space triangles of `mesh` placed by `transform`, each corner's position and
/// normal (as the vertex stage turns it: by the inverse transpose of the transform, any
/// length; zero where the mesh has no normals). None without positions.
pub fn world_corners(mesh: &Mesh, transform: &GlobalTransform) -> Vec<[(DVec3, DVec3); 3]> {
    let Some(positions) = mesh
        .attribute(Mesh::ATTRIBUTE_POSITION)
        .and_then(|positions| positions.as_float3())
    else {
        return Vec::new();
    };
    let normals = mesh
        .attribute(Mesh::ATTRIBUTE_NORMAL)
        .and_then(|normals| normals.as_float3());
    let affine = transform.affine();
    let normal_matrix = affine.matrix3.as_dmat3().inverse().transpose();
    let corner = |index: usize| {
        let position = transform
            .transform_point(Vec3::from(positions[index]))
            .as_dvec3();
        let normal = normals.map_or(DVec3::ZERO, |normals| {
            normal_matrix * Vec3::from(normals[index]).as_dvec3()
        });
        (position, normal)
    };
    let indices: Vec<usize> = match mesh.indices() {
        Some(indices) => indices.iter().collect(),
        None => (0..positions.len()).collect(),
    };
    indices
        .chunks_exact(3)
        .map(|triangle| {
            [
                corner(triangle[0]),
                corner(triangle[1]),
                corner(triangle[2]),
            ]
        })
        .collect()
}

/// Each triangle among `triangles` that holds `position` to 10⁻⁴ (world units, off its
/// plane and outside its edges), with `position`'s barycentric weights in it (summing to
/// one): the weights by which the device interpolates its vertices' outputs there.
pub fn triangles_holding(triangles: &[[DVec3; 3]], position: DVec3) -> Vec<(usize, [f64; 3])> {
    const NEAR: f64 = 1e-4;
    let mut holding = Vec::new();
    for (index, [a, b, c]) in triangles.iter().enumerate() {
        let normal = (*b - *a).cross(*c - *a);
        let area_squared = normal.length_squared();
        // A degenerate triangle (or a NaN corner) holds nothing.
        if area_squared.is_nan() || area_squared <= 0.0 {
            continue;
        }
        let unit = normal / area_squared.sqrt();
        if unit.dot(position - *a).abs() > NEAR {
            continue;
        }
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|(from, to)| unit.cross(**to - **from).normalize().dot(position - **from) > -NEAR);
        if !inside {
            continue;
        }
        let weight =
            |from: DVec3, to: DVec3| (to - from).cross(position - from).dot(normal) / area_squared;
        let (weight_a, weight_b) = (weight(*b, *c), weight(*c, *a));
        holding.push((index, [weight_a, weight_b, 1.0 - weight_a - weight_b]));
    }
    holding
}

/// The geometric normal (any length) of the one triangle among `triangles` that holds
/// `position`, to 10⁻⁴; `None` where none or two with different planes do (an edge).
pub fn face_normal_at(triangles: &[[DVec3; 3]], position: DVec3) -> Option<DVec3> {
    let mut found: Option<DVec3> = None;
    for (index, _) in triangles_holding(triangles, position) {
        let [a, b, c] = triangles[index];
        let normal = (b - a).cross(c - a);
        match found {
            Some(other) if other.normalize().dot(normal.normalize()) < 1.0 - 1e-9 => return None,
            _ => found = Some(normal),
        }
    }
    found
}

/// The triangles of the meshes lit per vertex (`PhongMaterial::vertex_lighting`), each
/// corner with the lights' sums there (`reference::VertexLight`), to interpolate at a pixel.
#[derive(Default)]
pub struct VertexLitTriangles {
    corners: Vec<[DVec3; 3]>,
    /// The sums at each corner; `None` where the model cannot say at some corner (a point
    /// light's cookie read on a cube edge).
    sums: Vec<Option<[reference::VertexLight; 3]>>,
}

impl VertexLitTriangles {
    /// Adds the triangles of `mesh` placed by `transform`, made of `material`, seen from
    /// `camera`, each corner lit by the built-in lights of `lights_at(its position)`.
    pub fn add(
        &mut self,
        mesh: &Mesh,
        transform: &GlobalTransform,
        material: &reference::Material,
        camera: DVec3,
        lights_at: impl Fn(DVec3) -> Option<reference::Lights>,
    ) {
        for triangle in world_corners(mesh, transform) {
            let sum = |(position, normal): (DVec3, DVec3)| {
                let vertex = reference::SurfacePoint {
                    position,
                    normal,
                    camera,
                };
                let lights = lights_at(position)?;
                Some(reference::VertexLight::at(
                    &vertex,
                    material,
                    &lights.lights,
                ))
            };
            let [a, b, c] = triangle.map(sum);
            self.corners.push(triangle.map(|(position, _)| position));
            self.sums.push(a.zip(b).zip(c).map(|((a, b), c)| [a, b, c]));
        }
    }

    /// The sums interpolated at world position `position`; `None` where no triangle holds it,
    /// or where two that do (an edge between faces whose vertices differ) disagree by more
    /// than 10⁻⁶.
    pub fn light_at(&self, position: DVec3) -> Option<reference::VertexLight> {
        let mut found: Option<reference::VertexLight> = None;
        for (index, weights) in triangles_holding(&self.corners, position) {
            let light = reference::VertexLight::interpolated(self.sums[index].as_ref()?, weights);
            if let Some(other) = found {
                let apart = [
                    light.diffuse - other.diffuse,
                    light.specular - other.specular,
                    light.rim - other.rim,
                ]
                .iter()
                .map(|difference| difference.abs().max_element())
                .fold(0.0, f64::max);
                if apart > 1e-6 {
                    return None;
                }
            }
            found = Some(light);
        }
        found
    }
}
