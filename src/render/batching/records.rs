//! The array of every material's numbers: one record per slot, in one storage buffer of the
//! render world that every class's bind group holds (binding 29,
//! `bevy_phong::shaders::bindings::material_records`).

use crate::displacement::DisplacementUniform;
use crate::material::{PhongMaterial, PhongMaterialUniform};
use crate::storage_buffer::{MIN_CAPACITY, STORAGE_BUFFERS_NEEDED};
use bevy::{
    ecs::{
        resource::Resource,
        system::{Commands, Res, ResMut},
    },
    render::{
        render_resource::{Buffer, BufferDescriptor, BufferUsages, ShaderType, encase},
        renderer::{RenderDevice, RenderQueue},
    },
};

/// Storage buffers per shader stage a device needs to draw materials from their records:
/// the scene data's, and one more.
const STORAGE_BUFFERS_WITH_RECORDS: u32 = STORAGE_BUFFERS_NEEDED + 1;

/// Whether `device` draws `PhongMaterial`s from their records: it has a storage buffer per
/// shader stage beyond what the scene data needs (native GPUs have many; WebGL2 has none,
/// WebGPU 8).
pub(crate) fn records_supported(device: &RenderDevice) -> bool {
    device.limits().max_storage_buffers_per_shader_stage >= STORAGE_BUFFERS_WITH_RECORDS
}

/// One material's numbers as the shaders read them (`PhongMaterialRecord` in
/// `bevy_phong::shaders::types`).
#[derive(Clone, Copy, Debug, PartialEq, ShaderType)]
pub(crate) struct MaterialRecord {
    pub material: PhongMaterialUniform,
    pub displacement: DisplacementUniform,
}

impl From<&PhongMaterial> for MaterialRecord {
    fn from(material: &PhongMaterial) -> Self {
        Self {
            material: material.into(),
            displacement: material.into(),
        }
    }
}

/// Bytes between two records of the array (the record's size, a multiple of 16).
fn record_stride() -> usize {
    MaterialRecord::min_size().get().next_multiple_of(16) as usize
}

/// `record` as the shader reads it: [`record_stride`] bytes.
fn record_bytes(record: &MaterialRecord) -> Vec<u8> {
    let mut bytes = encase::StorageBuffer::new(Vec::with_capacity(record_stride()));
    // Writing into a growable vector does not fail.
    let _ = bytes.write(record);
    let mut bytes = bytes.into_inner();
    bytes.resize(record_stride(), 0);
    bytes
}

/// The records on the GPU, a copy of their bytes to fill a larger buffer from, and the
/// records extracted this frame, still to write.
#[derive(Resource)]
pub(crate) struct MaterialRecordBuffer {
    buffer: Buffer,
    bytes: Vec<u8>,
    /// Records to write this frame, by slot.
    pending: Vec<(u32, MaterialRecord)>,
}

/// Whether [`MaterialRecordBuffer`]'s buffer was replaced (every bind group that holds it is
/// to be made again) since [`Self::take`] last said so. A resource of its own: the systems
/// that make bind groups read the buffer itself.
#[derive(Resource, Default)]
pub(crate) struct RecordBufferReplaced(bool);

impl RecordBufferReplaced {
    /// Whether the buffer was replaced since the last call.
    pub fn take(&mut self) -> bool {
        core::mem::take(&mut self.0)
    }
}

impl MaterialRecordBuffer {
    /// The buffer that bind groups take (replaced when the records outgrow it).
    pub fn buffer(&self) -> &Buffer {
        &self.buffer
    }

    /// Queues `record` to be written into slot `slot` this frame.
    pub fn queue(&mut self, slot: u32, record: MaterialRecord) {
        self.pending.push((slot, record));
    }

    pub(crate) fn capacity(&self) -> usize {
        self.bytes.len() / record_stride()
    }
}

fn new_buffer(device: &RenderDevice, records: usize) -> Buffer {
    device.create_buffer(&BufferDescriptor {
        label: Some("bevy_phong material records"),
        size: (records * record_stride()) as u64,
        usage: BufferUsages::STORAGE | BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Render startup: the buffer, with room for a few records, where the device draws
/// materials from them.
pub(crate) fn create_record_buffer(mut commands: Commands, device: Res<RenderDevice>) {
    if records_supported(&device) {
        commands.insert_resource(MaterialRecordBuffer {
            buffer: new_buffer(&device, MIN_CAPACITY),
            bytes: vec![0; MIN_CAPACITY * record_stride()],
            pending: Vec::new(),
        });
        commands.init_resource::<RecordBufferReplaced>();
    }
}

/// Run condition: the device draws materials from their records.
pub(crate) fn buffer_exists(buffer: Option<Res<MaterialRecordBuffer>>) -> bool {
    buffer.is_some()
}

/// Writes the records extracted this frame: one upload of the range they span, or, where
/// a slot is past the buffer's end, a buffer twice as large (or more) holding every record,
/// which every class's bind group is then made again around ([`RecordBufferReplaced`]).
pub(crate) fn write_records(
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    mut records: ResMut<MaterialRecordBuffer>,
    mut replaced: ResMut<RecordBufferReplaced>,
) {
    let written = core::mem::take(&mut records.pending);
    let Some(last) = written.iter().map(|(slot, _)| *slot as usize).max() else {
        return;
    };
    let stride = record_stride();
    let grew = last >= records.capacity();
    if grew {
        let capacity = (last + 1).next_power_of_two();
        records.bytes.resize(capacity * stride, 0);
        records.buffer = new_buffer(&device, capacity);
        replaced.0 = true;
    }
    let first = written
        .iter()
        .map(|(slot, _)| *slot as usize)
        .min()
        .unwrap_or(last);
    for (slot, record) in &written {
        let start = *slot as usize * stride;
        records.bytes[start..start + stride].copy_from_slice(&record_bytes(record));
    }
    let (start, end) = if grew {
        (0, records.bytes.len())
    } else {
        (first * stride, (last + 1) * stride)
    };
    queue.write_buffer(&records.buffer, start as u64, &records.bytes[start..end]);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_is_the_uniform_then_the_displacement_with_wgsl_offsets() {
        // WGSL's layout of PhongMaterialRecord: PhongMaterialUniform is 192 bytes (its last
        // member, a vec2 at 176, rounded up to the struct's 16-byte alignment), and
        // PhongDisplacement (a mat3x3 of 48 bytes and two f32) 64.
        assert_eq!(record_stride(), 256);
        let material = PhongMaterial {
            shininess: 7.0,
            displacement_scale: 3.0,
            ..Default::default()
        };
        let bytes = record_bytes(&MaterialRecord::from(&material));
        let f32_at =
            |offset: usize| f32::from_le_bytes(bytes[offset..offset + 4].try_into().unwrap());
        // shininess: the w of the second vec4; the displacement's scale after its mat3x3.
        assert_eq!(f32_at(28), 7.0);
        assert_eq!(f32_at(192 + 48), 3.0);
    }
}
