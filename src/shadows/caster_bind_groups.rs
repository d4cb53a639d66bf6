//! What the bind groups of the casters' maps share: each frame's groups made anew, one per
//! distinct set of maps, and the entries that bind one map.

use bevy::{
    platform::collections::HashMap,
    render::{
        render_resource::{BindGroup, BindGroupEntry, BindingResource},
        texture::GpuImage,
    },
};
use core::hash::Hash;

/// Replaces `groups` with a bind group for each distinct key of `keys`, made by `make`;
/// a key whose images are not on the GPU yet (`make` gives `None`) gets none, and its
/// casters are not drawn this frame. Groups are made anew every frame: an image may be
/// replaced.
pub(crate) fn remake_bind_groups<K: Copy + Eq + Hash>(
    groups: &mut HashMap<K, BindGroup>,
    keys: impl Iterator<Item = K>,
    mut make: impl FnMut(K) -> Option<BindGroup>,
) {
    groups.clear();
    for key in keys {
        if groups.contains_key(&key) {
            continue;
        }
        if let Some(group) = make(key) {
            groups.insert(key, group);
        }
    }
}

/// The entries that bind `image`'s texture at `binding` and its sampler at `binding + 1`.
pub(crate) fn image_entries(binding: u32, image: &GpuImage) -> [BindGroupEntry<'_>; 2] {
    [
        BindGroupEntry {
            binding,
            resource: BindingResource::TextureView(&image.texture_view),
        },
        BindGroupEntry {
            binding: binding + 1,
            resource: BindingResource::Sampler(&image.sampler),
        },
    ]
}
