//! The gather of an extension kind: every frame in which one of its lights, their shadow
//! slots or the culling changed, it writes every lit light into the kind's buffer (those lit
//! everywhere, then the clustered ones) and hands the clustered ones' spheres to the
//! clusters.

use super::{GpuLightCount, PhongLightKind, PhongLightKindBuffer};
use crate::culling::PhongLightCulling;
use crate::lights::{LightQuery, lit_lights};
use crate::render::{
    DATA_TEXTURE_MAX_TEXELS, DataTextureWrite, ExtensionClusterSlots, LightChanges, PhongCookies,
    PhongLightBuffer, SharedEpsilonLights, is_finite_sphere, sphere_bits, words_of,
};
use crate::shadows::ShadowSlots;
use crate::storage_buffer::LightBufferResized;
use bevy::{
    asset::Assets,
    ecs::{
        change_detection::DetectChanges,
        message::MessageWriter,
        system::{Res, ResMut},
    },
    image::Image,
    log::warn_once,
    math::Vec3,
    render::storage::ShaderBuffer,
};

/// Keeps the number of lit `L` in [`SharedEpsilonLights`] (for a kind that shares ε), for
/// the built-in gather to divide ε by; touches it only when the number changes.
pub(super) fn count_sharing_lights<L: PhongLightKind>(
    lights: LightQuery<L>,
    mut changes: LightChanges<L>,
    state: Res<PhongLightKindBuffer<L>>,
    mut sharing: ResMut<SharedEpsilonLights>,
) {
    let Some(kind) = state.epsilon_share else {
        return;
    };
    if !changes.any() && !sharing.is_added() {
        return;
    }
    let count = lit_lights(&lights).count() as u32;
    if sharing.count(kind) != count {
        sharing.set_count(kind, count);
    }
}

/// Writes every visible `L` into its buffer when any of them, their shadow or cookie slots,
/// the culling or the per-light ε changed (and on the first run): each light's record with
/// its shadow slot, its cookie's index (see [`PhongLightBuffer::cookie_index`]) and its [`PhongLightKind::reach`] for the per-light ε (left out where that
/// is 0); the lights without a bounding sphere first, then those with one, whose spheres go
/// to [`ExtensionClusterSlots`].
#[allow(clippy::too_many_arguments)]
pub(super) fn gather_light_kind<L: PhongLightKind>(
    lights: LightQuery<L>,
    slots: Res<ShadowSlots>,
    cookies: Res<PhongCookies>,
    culling: Res<PhongLightCulling>,
    built_in: Res<PhongLightBuffer>,
    mut changes: LightChanges<L>,
    mut state: ResMut<PhongLightKindBuffer<L>>,
    mut cluster_slots: ResMut<ExtensionClusterSlots>,
    mut buffers: ResMut<Assets<ShaderBuffer>>,
    mut images: ResMut<Assets<Image>>,
    mut resized: MessageWriter<LightBufferResized>,
) {
    // A kind that does not share ε is given none: its lights reach as far as they light.
    let epsilon = if L::SHARES_EPSILON {
        built_in.per_light_epsilon()
    } else {
        0.0
    };
    let gathered_with = Some((epsilon.to_bits(), *culling, built_in.cookie_index(1)));
    let changed = changes.any()
        || slots.is_changed()
        || cookies.is_changed()
        || state.gathered_with != gathered_with;
    if !changed && state.buffer.capacity() > 0 {
        return;
    }
    let state = &mut *state;
    state.gathered_with = gathered_with;
    state.records.clear();
    state.clustered.clear();
    let slot = cluster_slots.slot_mut(state.cluster_slot);
    slot.spheres.clear();
    for (entity, light, transform) in lit_lights(&lights) {
        let mut record = light.to_gpu(transform);
        L::set_shadow(&mut record, slots.get(entity));
        L::set_cookie(&mut record, built_in.cookie_index(cookies.slot_of(entity)));
        let reach = L::reach(&record, epsilon);
        if reach == 0.0 {
            continue;
        }
        // A NaN reach is no reach limit.
        let reach = if reach.is_nan() { f32::INFINITY } else { reach };
        L::set_reach(&mut record, reach);
        let sphere = (culling.clusters && reach.is_finite())
            .then(|| L::bounding_sphere(&record, reach))
            .flatten()
            .map(|sphere| (Vec3::from(sphere.center), sphere.radius()))
            .filter(|&(center, radius)| is_finite_sphere(center, radius));
        match sphere {
            Some((center, radius)) => {
                state.clustered.push(record);
                slot.spheres.push(sphere_bits(center, radius));
            }
            None => state.records.push(record),
        }
    }
    let clustered_first = state.records.len() as u32;
    state.records.append(&mut state.clustered);
    slot.first = clustered_first;
    state.header = GpuLightCount {
        count: state.records.len() as u32,
        clustered_first,
        cluster_slot: state.cluster_slot,
        padding: 0,
    };
    let header = state.header;
    let buffer_resized = state.buffer.write(&mut buffers, &header, &state.records);
    let texture_resized = write_texture::<L>(state, &mut images, header);
    if buffer_resized || texture_resized {
        resized.write(LightBufferResized);
    }
}

/// Writes the header and records into the kind's data texture, leaving out the last records
/// past its capacity (with a warning): the header's `count` then says how many it holds, and
/// a shader skips the cluster entries at or past it. Returns whether the texture changed
/// size.
fn write_texture<L: PhongLightKind>(
    state: &mut PhongLightKindBuffer<L>,
    images: &mut Assets<Image>,
    mut header: GpuLightCount,
) -> bool {
    let record_texels = size_of::<L::Gpu>() / 16;
    let room = (DATA_TEXTURE_MAX_TEXELS - 1) / record_texels;
    if state.records.len() > room {
        warn_once!(
            "bevy_phong: {} {} lights do not fit their data texture ({room} do): the last ones are left out",
            state.records.len(),
            core::any::type_name::<L>()
        );
        header.count = room as u32;
        header.clustered_first = header.clustered_first.min(header.count);
    }
    let kept = &state.records[..state.records.len().min(room)];
    state.words.clear();
    state.words.extend(words_of(bytemuck::bytes_of(&header)));
    state.words.extend(words_of(bytemuck::cast_slice(kept)));
    state.texture.write(images, &state.words) == DataTextureWrite::Resized
}
