//! The scene data in one data texture, for devices without enough storage buffers (WebGL2).
//!
//! The lights, their clusters and the shadow views are written as usual into their
//! [`ShaderBuffer`] assets; on such a device [`pack_scene_texture`] then copies their bytes,
//! unchanged, into one data texture (see [`super::data_texture`]) that materials bind
//! instead of the three buffers. The shaders read it through the same accessors
//! (`bevy_phong::shaders::scene`), choosing the path from the flag `PHONG_STORAGE_BUFFERS`,
//! which each pipeline sets from the layout bound here. See `docs/design/webgl2.md`.
//!
//! Layout, in texels: texel 0 holds the first texel of each region
//! `[lights, clusters, shadow views, 0]`; then the three buffers' bytes, each region starting on
//! a texel of its own. The lights always start at texel 1 (`LIGHTS_START` in WGSL).
//!
//! # Capacity
//!
//! The texture holds [`DATA_TEXTURE_MAX_TEXELS`] texels (64 MiB): a light takes 5, its
//! place in the clusters a word per cluster it may reach, a shadow view 9. That is about
//! 800,000 lights not clustered. Past it, lights are left out in this order, with one
//! warning each time the count left out changes:
//! 1. the clusters and every clustered light (finite reach, no shadow);
//! 2. then lights of unlimited reach, each kind from its end: local (point and spot)
//!    lights, then area lights, then directional lights.
//!
//! The lights that remain are lit exactly as they would be with room for all.

use super::light_sections::LightSection;
use super::{
    GpuClustersHeader, GpuLight, GpuLightsHeader, PHONG_LIGHT_BUFFER, PHONG_LIGHT_CLUSTER_BUFFER,
    data_texture::{DATA_TEXTURE_MAX_TEXELS, DataTexture, DataTextureWrite, words_of},
};
use crate::shadows::PHONG_SHADOW_VIEW_BUFFER;
use crate::storage_buffer::LightBufferResized;
use bevy::{
    asset::{Assets, Handle, uuid_handle},
    ecs::{
        message::MessageWriter,
        system::{Local, Res, ResMut},
    },
    image::Image,
    log::{info, warn},
    render::{renderer::RenderDevice, storage::ShaderBuffer},
};

/// The texture that holds the scene data where storage buffers are missing.
pub(crate) const PHONG_SCENE_TEXTURE: Handle<Image> =
    uuid_handle!("3f6c2a71-8e0b-4d52-a9e4-1c7b5d3e8f90");

pub(crate) use crate::storage_buffer::{STORAGE_BUFFERS_NEEDED, needs_scene_texture};

/// Render startup: says once when the device reads the scene data from the texture.
pub(crate) fn announce_scene_data_path(device: Res<RenderDevice>) {
    if needs_scene_texture(&device) {
        info!(
            "bevy_phong: the device has {} storage buffers per shader stage (fewer than \
             {STORAGE_BUFFERS_NEEDED}): the lights, light clusters and shadow views are read from \
             a data texture",
            device.limits().max_storage_buffers_per_shader_stage
        );
    }
}

/// The scene texture and how many lights the last packing left out.
pub(crate) struct SceneTexture {
    texture: DataTexture,
    left_out: usize,
}

impl Default for SceneTexture {
    fn default() -> Self {
        Self {
            texture: DataTexture::new(PHONG_SCENE_TEXTURE),
            left_out: 0,
        }
    }
}

/// Copies the three scene buffers into [`PHONG_SCENE_TEXTURE`] where the device reads it
/// (the main world holds the render device too), when their bytes changed.
///
/// Runs in [`PhongSystems::GatherLights`](crate::PhongSystems::GatherLights), after the
/// buffers are written.
pub(crate) fn pack_scene_texture(
    device: Option<Res<RenderDevice>>,
    buffers: Res<Assets<ShaderBuffer>>,
    mut images: ResMut<Assets<Image>>,
    mut scene: Local<SceneTexture>,
    mut resized: MessageWriter<LightBufferResized>,
) {
    if !device.is_some_and(|device| needs_scene_texture(&device)) {
        return;
    }
    let [lights, clusters, views] = [
        &PHONG_LIGHT_BUFFER,
        &PHONG_LIGHT_CLUSTER_BUFFER,
        &PHONG_SHADOW_VIEW_BUFFER,
    ]
    .map(|handle| {
        buffers
            .get(handle)
            .and_then(crate::storage_buffer::buffer_bytes)
            .unwrap_or(&[])
    });
    let packed = pack(lights, clusters, views, DATA_TEXTURE_MAX_TEXELS);
    if packed.left_out != scene.left_out {
        if packed.left_out > 0 {
            warn!(
                "bevy_phong: the scene data texture holds {DATA_TEXTURE_MAX_TEXELS} texels: \
                 {} lights are left out (the clustered ones first, then local and directional \
                 lights from the last)",
                packed.left_out
            );
        }
        scene.left_out = packed.left_out;
    }
    if scene.texture.write(&mut images, &packed.words) == DataTextureWrite::Resized {
        // A new size is a new GPU texture: bind groups holding the old one are rebuilt.
        resized.write(LightBufferResized);
    }
}

/// The texture's words, and how many lights did not fit.
#[derive(Debug)]
struct Packed {
    words: Vec<u32>,
    left_out: usize,
}

const HEADER_BYTES: usize = size_of::<GpuLightsHeader>();
const RECORD_BYTES: usize = size_of::<GpuLight>();

/// The directory texel, then the light buffer (its header and used records), the clusters and
/// the shadow views, each from a texel of its own, within `max_texels` texels (see the
/// module documentation for what is left out past it).
fn pack(lights: &[u8], clusters: &[u8], views: &[u8], max_texels: usize) -> Packed {
    let full = lights
        .get(..HEADER_BYTES)
        .map(bytemuck::pod_read_unaligned::<GpuLightsHeader>)
        .unwrap_or_default();
    let body = lights.get(HEADER_BYTES..).unwrap_or(&[]);
    let stored = body.len() / RECORD_BYTES;
    // The records kept of each section (in `sections`' order): the first `kept` of each,
    // read from where the section starts in the whole buffer.
    let records = |header: &GpuLightsHeader| -> Vec<&[u8]> {
        let mut start = 0;
        full.counts()
            .into_iter()
            .zip(header.counts())
            .map(|(whole, kept)| {
                let first = (start as usize).min(stored);
                let end = (start as usize + kept as usize).min(stored);
                start += whole;
                &body[first * RECORD_BYTES..end * RECORD_BYTES]
            })
            .collect()
    };
    let texels = |bytes: usize| bytes.div_ceil(16);
    let total = |header: &GpuLightsHeader, clusters: &[u8]| {
        let record_bytes: usize = records(header).iter().map(|part| part.len()).sum();
        1 + texels(HEADER_BYTES + record_bytes) + texels(clusters.len()) + texels(views.len())
    };
    let mut header = full;
    let no_clusters = bytemuck::bytes_of(&GpuClustersHeader::EMPTY);
    let mut clusters = clusters;
    if total(&header, clusters) > max_texels {
        for section in LightSection::ALL.into_iter().filter(|s| s.is_clustered()) {
            *header.count_mut(section) = 0;
        }
        clusters = no_clusters;
    }
    while total(&header, clusters) > max_texels && header.light_count() > 0 {
        // The local lights go first, then the area lights, the directional ones last.
        let leave_out = [
            LightSection::Local,
            LightSection::Area,
            LightSection::Directional,
        ];
        if let Some(section) = leave_out.into_iter().find(|&s| header.count(s) > 0) {
            *header.count_mut(section) -= 1;
        }
    }
    let mut words = vec![0u32; 4];
    let mut light_parts = vec![bytemuck::bytes_of(&header)];
    light_parts.extend(records(&header));
    let regions: [&[&[u8]]; 3] = [&light_parts, &[clusters], &[views]];
    for (region, parts) in regions.into_iter().enumerate() {
        words[region] = (words.len() / 4) as u32;
        for part in parts {
            words.extend(words_of(part));
        }
        words.resize(words.len().next_multiple_of(4), 0);
    }
    Packed {
        words,
        left_out: full.light_count() - header.light_count(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light_buffer(directional: u32, local: u32, clustered_local: u32) -> Vec<u8> {
        let header = GpuLightsHeader {
            directional_count: directional,
            local_count: local,
            clustered_local_count: clustered_local,
            ..bytemuck::Zeroable::zeroed()
        };
        let count = header.light_count();
        let mut bytes = bytemuck::bytes_of(&header).to_vec();
        for index in 0..count {
            let record = GpuLight {
                reach: index as f32,
                ..bytemuck::Zeroable::zeroed()
            };
            bytes.extend_from_slice(bytemuck::bytes_of(&record));
        }
        // Spare capacity, zero-filled, as the light buffer keeps it.
        bytes.resize(bytes.len() + 3 * RECORD_BYTES, 0);
        bytes
    }

    #[test]
    fn each_region_starts_on_its_own_texel_after_the_directory() {
        let lights = light_buffer(1, 0, 0);
        let clusters = [2u8; 36];
        let views = [3u8; 16];
        let packed = pack(&lights, &clusters, &views, usize::MAX);
        // Directory, 4 texels of header and 5 of one light (spare capacity left out), 3 of
        // clusters (36 bytes rounded up), 1 of views.
        assert_eq!(&packed.words[..4], &[1, 10, 13, 0]);
        assert_eq!(packed.words.len(), 4 * 14);
        assert_eq!(packed.words[4 + 3], 1, "directional count");
        assert_eq!(packed.words[10 * 4], u32::from_le_bytes([2; 4]));
        assert_eq!(
            packed.words[10 * 4 + 9],
            0,
            "the clusters' last texel is zero-padded"
        );
        assert_eq!(packed.words[13 * 4], u32::from_le_bytes([3; 4]));
        assert_eq!(packed.left_out, 0);
    }

    #[test]
    fn past_capacity_the_clusters_go_first_then_local_and_directional_lights() {
        let lights = light_buffer(2, 7, 5);
        let clusters = [1u8; 16 * 10];
        let views = [0u8; 16];
        let header_of = |packed: &Packed| -> GpuLightsHeader {
            let start = packed.words[0] as usize * 4;
            bytemuck::pod_read_unaligned(bytemuck::cast_slice(&packed.words[start..start + 16]))
        };
        // Everything: 1 + 4 + 5 · 14 + 10 + 1 = 86 texels.
        assert_eq!(pack(&lights, &clusters, &views, 86).left_out, 0);
        // One texel short: the clusters and their 5 lights go; the clusters' region is an
        // empty header.
        let packed = pack(&lights, &clusters, &views, 85);
        assert_eq!(packed.left_out, 5);
        let header = header_of(&packed);
        assert_eq!((header.clustered_local_count, header.local_count), (0, 7));
        let clusters_start = packed.words[1] as usize * 4;
        assert_eq!(
            &packed.words[clusters_start..clusters_start + 4],
            &[0, GpuClustersHeader::EMPTY.cluster_words, 0, 0],
            "no views"
        );
        // Room for 28 texels, 1 + 4 + 5 · 4 + 1 + 1 = 27 used (an empty clusters header is one
        // texel): 5 of the 7 local lights go, from the last.
        let packed = pack(&lights, &clusters, &views, 28);
        assert_eq!(packed.left_out, 10);
        let header = header_of(&packed);
        assert_eq!((header.directional_count, header.local_count), (2, 2));
        // The records kept are the first ones, unchanged (`range` is word 3 of 20).
        let first = packed.words[0] as usize * 4 + 16;
        assert_eq!(f32::from_bits(packed.words[first + 3]), 0.0);
        assert_eq!(f32::from_bits(packed.words[first + 3 * 20 + 3]), 3.0);
        // No room at all: every light is left out, never a panic.
        assert_eq!(pack(&lights, &clusters, &views, 0).left_out, 14);
    }
}
