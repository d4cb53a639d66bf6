//! A growable GPU storage buffer made of a fixed header and an array of records, kept in a
//! [`ShaderBuffer`] asset that materials bind: the built-in lights and their clusters
//! ([`crate::render`]), the shadow views ([`crate::shadows`]) and each extension's lights
//! ([`crate::extension`]) are written through one. It knows nothing of what the records
//! mean, so that all of them can use it.

use bevy::{
    app::App,
    asset::{AssetApp, Assets, Handle},
    ecs::message::Message,
    platform::collections::AlignedVec,
    render::{
        renderer::RenderDevice,
        storage::{ShaderBuffer, ShaderBufferData},
    },
};
use bytemuck::Pod;

/// Storage buffers a shader stage needs for the scene data to stay in buffers: the plugin's
/// three beside Bevy's own (its clustered lights and meshes take up to five). Every native
/// backend with full WebGPU limits has 8; WebGL2 has none. The shaders follow through the
/// flag `PHONG_STORAGE_BUFFERS`, set from the bind group layout this number chose.
pub(crate) const STORAGE_BUFFERS_NEEDED: u32 = 8;

/// Whether `device` has too few storage buffers per shader stage for the scene data, which
/// then travels in the data texture.
pub(crate) fn needs_scene_texture(device: &RenderDevice) -> bool {
    device.limits().max_storage_buffers_per_shader_stage < STORAGE_BUFFERS_NEEDED
}

/// Registers the [`ShaderBuffer`] asset type where the renderer has not (as under
/// `MinimalPlugins`), so that light buffers can be gathered without one.
pub(crate) fn init_shader_buffers(app: &mut App) {
    if !app.world().contains_resource::<Assets<ShaderBuffer>>() {
        app.init_asset::<ShaderBuffer>();
    }
}

/// Sent when a light buffer's byte size changed (or the cookie atlas was made again), so that
/// the render world made a new GPU resource for it: every material bind group that holds
/// the old one must be rebuilt.
///
/// Crate-internal: the crate's own systems send and read it. It is `pub` only because the
/// gather systems that `bevy_phong::testing` shows name it in their parameters; no public
/// path leads to it.
#[derive(Message, Clone, Debug)]
pub struct LightBufferResized;

/// Smallest number of records a buffer holds room for. A runtime-sized WGSL array needs at
/// least one element to bind; a few more spare the first resizes.
pub(crate) const MIN_CAPACITY: usize = 16;

/// A [`ShaderBuffer`] asset laid out as `header, records[capacity]`.
///
/// The capacity grows to the next power of two when the records outgrow it and shrinks when
/// fewer than a quarter of it is used, so a scene whose light count wobbles does not
/// reallocate every frame. Writing reuses the asset's byte vector: no allocation once the
/// capacity is reached.
#[derive(Debug)]
pub(crate) struct LightBuffer {
    handle: Handle<ShaderBuffer>,
    capacity: usize,
    /// Bytes of records last written; past them the asset holds zeros.
    written: usize,
}

impl LightBuffer {
    /// A buffer that writes into the asset behind `handle` (created on first write).
    pub fn new(handle: Handle<ShaderBuffer>) -> Self {
        Self {
            handle,
            capacity: 0,
            written: 0,
        }
    }

    /// The asset the buffer writes into, for a material's `#[storage]` binding.
    pub fn handle(&self) -> &Handle<ShaderBuffer> {
        &self.handle
    }

    /// Number of records the buffer holds room for.
    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// Capacity for `len` records: unchanged while `len` fits and uses more than a quarter
    /// of it, else the next power of two (at least [`MIN_CAPACITY`]).
    fn capacity_for(&self, len: usize) -> usize {
        let fits = len <= self.capacity && len * 4 >= self.capacity;
        if fits && self.capacity >= MIN_CAPACITY {
            self.capacity
        } else {
            len.next_power_of_two().max(MIN_CAPACITY)
        }
    }

    /// Writes `header` then `records` (zero-filled up to the capacity) into the asset,
    /// unless it holds exactly these bytes already (then it is left alone, and not uploaded).
    ///
    /// Returns `true` when the byte size changed (or the asset was created), which gives the
    /// buffer a new GPU buffer: the caller must then send [`LightBufferResized`].
    pub fn write<H: Pod, R: Pod>(
        &mut self,
        buffers: &mut Assets<ShaderBuffer>,
        header: &H,
        records: &[R],
    ) -> bool {
        debug_assert_eq!(size_of::<H>() % align_of::<R>().max(16), 0);
        let capacity = self.capacity_for(records.len());
        let resized = capacity != self.capacity;
        self.capacity = capacity;
        let size = size_of::<H>() + capacity * size_of::<R>();

        let records_bytes: &[u8] = bytemuck::cast_slice(records);
        // Past `written` bytes of records the asset is zero: only the part that may differ
        // is compared.
        let unchanged = self.written <= records_bytes.len()
            && buffers
                .get(&self.handle)
                .is_some_and(|asset| holds(asset, bytemuck::bytes_of(header), records_bytes, size));
        if unchanged {
            return resized;
        }
        self.written = records_bytes.len();
        match buffers.get_or_insert_with(&self.handle, ShaderBuffer::default) {
            Ok(mut asset) => fill(&mut asset, header, records, size),
            // Only a stale `Handle::Index` can fail; the buffer keeps its last contents.
            Err(error) => bevy::log::error!("cannot write light buffer {:?}: {error}", self.handle),
        }
        resized
    }
}

/// The bytes a [`ShaderBuffer`] asset holds, up to its buffer size; `None` before its first
/// write.
pub(crate) fn buffer_bytes(asset: &ShaderBuffer) -> Option<&[u8]> {
    match &asset.data {
        ShaderBufferData::Initialized { data, buffer_size } => {
            Some(&data[..data.len().min(*buffer_size as usize)])
        }
        ShaderBufferData::Uninitialized(_) => None,
    }
}

/// Whether `asset` is `size` bytes long and starts with `header, records` (the caller knows
/// that the rest is zero).
fn holds(asset: &ShaderBuffer, header: &[u8], records: &[u8], size: usize) -> bool {
    match &asset.data {
        ShaderBufferData::Initialized { data, buffer_size } => {
            *buffer_size == size as u64
                && data.len() == size
                && data.starts_with(header)
                && data[header.len()..].starts_with(records)
        }
        ShaderBufferData::Uninitialized(_) => false,
    }
}

/// Replaces the bytes of `asset` with `header, records`, zero-padded to `size`.
fn fill<H: Pod, R: Pod>(asset: &mut ShaderBuffer, header: &H, records: &[R], size: usize) {
    let mut data = match core::mem::take(&mut asset.data) {
        ShaderBufferData::Initialized { data, .. } => data,
        ShaderBufferData::Uninitialized(_) => AlignedVec::new(align_of::<R>().max(align_of::<H>())),
    };
    data.clear();
    data.extend_from_slice(bytemuck::bytes_of(header));
    data.extend_from_slice(bytemuck::cast_slice(records));
    data.resize(size, 0);
    asset.data = ShaderBufferData::Initialized {
        data,
        buffer_size: size as u64,
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    fn buffer_with_capacity(capacity: usize) -> LightBuffer {
        LightBuffer {
            handle: Handle::default(),
            capacity,
            written: 0,
        }
    }

    #[test]
    fn capacity_starts_at_the_minimum() {
        assert_eq!(buffer_with_capacity(0).capacity_for(0), MIN_CAPACITY);
        assert_eq!(buffer_with_capacity(0).capacity_for(3), MIN_CAPACITY);
    }

    #[test]
    fn capacity_grows_to_the_next_power_of_two() {
        assert_eq!(buffer_with_capacity(16).capacity_for(17), 32);
        assert_eq!(buffer_with_capacity(16).capacity_for(5000), 8192);
    }

    #[test]
    fn capacity_holds_while_a_quarter_is_used_and_then_shrinks() {
        assert_eq!(buffer_with_capacity(8192).capacity_for(2048), 8192);
        assert_eq!(buffer_with_capacity(8192).capacity_for(2047), 2048);
        assert_eq!(buffer_with_capacity(8192).capacity_for(1), MIN_CAPACITY);
        assert_eq!(buffer_with_capacity(16).capacity_for(0), MIN_CAPACITY);
    }
}
