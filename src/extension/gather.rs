//! The gather of an extension kind: every frame in which one of its lights, their shadow
//! slots or the culling changed, it writes every lit light into the kind's buffer (those lit
//! everywhere, then the clustered ones) and hands the clustered ones' spheres to the
//! clusters.

use super::{GpuLightCount, PhongLightKind, PhongLightKindBuffer};
use crate::culling::PhongLightCulling;
use crate::lights::{LightChanges, LightQuery, lit_lights};
use crate::render::{
    DATA_TEXTURE_MAX_TEXELS, DataTextureWrite, ExtensionClusterSlots, PhongCookies,
    PhongLightBuffer, SharedEpsilonLights, is_finite_sphere, sphere_bits, words_of,
};
use crate::shadows::ShadowSlots;
use crate::storage_buffer::LightBufferResized;
use bevy::{
    asset::Assets,
    ecs::{
        change_detection::DetectChanges,
        message::MessageWriter,
        system::{Res, ResMut, SystemParam},
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

/// What an extension kind's gather reads besides its lights: this frame's shadow and cookie
/// slots, the culling, and the built-in gather (its per-light ε and its cookies' indices).
#[derive(SystemParam)]
pub(super) struct KindGatherInputs<'w> {
    slots: Res<'w, ShadowSlots>,
    cookies: Res<'w, PhongCookies>,
    culling: Res<'w, PhongLightCulling>,
    built_in: Res<'w, PhongLightBuffer>,
}

/// Where an extension kind's gather writes: its buffer and data texture (a message when
/// either grows) and its cluster slot.
#[derive(SystemParam)]
pub(super) struct KindGatherWrites<'w, L: PhongLightKind> {
    state: ResMut<'w, PhongLightKindBuffer<L>>,
    cluster_slots: ResMut<'w, ExtensionClusterSlots>,
    buffers: ResMut<'w, Assets<ShaderBuffer>>,
    images: ResMut<'w, Assets<Image>>,
    resized: MessageWriter<'w, LightBufferResized>,
}

/// Writes every visible `L` into its buffer when any of them, their shadow or cookie slots,
/// the culling or the per-light ε changed (and on the first run): each light's record with
/// its shadow slot, its cookie's index (see [`PhongLightBuffer::cookie_index`]) and its
/// [`PhongLightKind::reach`] for the per-light ε (left out where that is 0); the lights
/// without a bounding sphere first, then those with one, whose spheres go to
/// [`ExtensionClusterSlots`].
pub(super) fn gather_light_kind<L: PhongLightKind>(
    lights: LightQuery<L>,
    mut changes: LightChanges<L>,
    inputs: KindGatherInputs,
    mut writes: KindGatherWrites<L>,
) {
    // A kind that does not share ε is given none: its lights reach as far as they light.
    let epsilon = if L::SHARES_EPSILON {
        inputs.built_in.per_light_epsilon()
    } else {
        0.0
    };
    let gathered_with = Some((
        epsilon.to_bits(),
        *inputs.culling,
        inputs.built_in.cookie_index(1),
    ));
    let changed = changes.any()
        || inputs.slots.is_changed()
        || inputs.cookies.is_changed()
        || writes.state.gathered_with != gathered_with;
    if !changed && writes.state.buffer.capacity() > 0 {
        return;
    }
    let state = &mut *writes.state;
    state.gathered_with = gathered_with;
    state.push_lit(&lights, &inputs, epsilon, &mut writes.cluster_slots);
    let header = state.header;
    let buffer_resized = state
        .buffer
        .write(&mut writes.buffers, &header, &state.records);
    let texture_resized = write_texture::<L>(state, &mut writes.images, header);
    if buffer_resized || texture_resized {
        writes.resized.write(LightBufferResized);
    }
}

impl<L: PhongLightKind> PhongLightKindBuffer<L> {
    /// Makes the records and the header of the lit `lights` that reach somewhere for
    /// `epsilon`: those without a bounding sphere first, then the clustered ones, whose
    /// spheres go to the kind's cluster slot.
    fn push_lit(
        &mut self,
        lights: &LightQuery<L>,
        inputs: &KindGatherInputs,
        epsilon: f32,
        cluster_slots: &mut ExtensionClusterSlots,
    ) {
        self.records.clear();
        self.clustered.clear();
        let slot = cluster_slots.slot_mut(self.cluster_slot);
        slot.spheres.clear();
        for (entity, light, transform) in lit_lights(lights) {
            let mut record = light.to_gpu(transform);
            L::set_shadow(&mut record, inputs.slots.get(entity));
            let cookie = inputs.cookies.slot_of(entity);
            L::set_cookie(&mut record, inputs.built_in.cookie_index(cookie));
            let reach = light.reach(&record, epsilon);
            if reach == 0.0 {
                continue;
            }
            // A NaN reach is no reach limit.
            let reach = if reach.is_nan() { f32::INFINITY } else { reach };
            L::set_reach(&mut record, reach);
            let sphere = (inputs.culling.clusters && reach.is_finite())
                .then(|| L::bounding_sphere(&record, reach))
                .flatten()
                .map(|sphere| (Vec3::from(sphere.center), sphere.radius()))
                .filter(|&(center, radius)| is_finite_sphere(center, radius));
            match sphere {
                Some((center, radius)) => {
                    self.clustered.push(record);
                    slot.spheres.push(sphere_bits(center, radius));
                }
                None => self.records.push(record),
            }
        }
        let clustered_first = self.records.len() as u32;
        self.records.append(&mut self.clustered);
        slot.first = clustered_first;
        self.header = GpuLightCount {
            count: self.records.len() as u32,
            clustered_first,
            cluster_slot: self.cluster_slot,
            padding: 0,
        };
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
