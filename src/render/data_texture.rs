//! Bytes in a texture, for devices without storage buffers (WebGL2).
//!
//! A data texture is an `Rgba32Uint` texture [`DATA_TEXTURE_WIDTH`] texels wide: texel `i`
//! (counting row after row) holds bytes `16 i .. 16 i + 16` of what it stores, as four
//! little-endian `u32`s. Shaders read texel `i` with `bevy_phong::shaders::data_texture::data_texel`
//! and rebuild their structs with `bitcast`. The bytes are those of the storage buffers,
//! unchanged, so both paths read the same values.

use bevy::{
    asset::{Assets, Handle, RenderAssetUsages},
    image::Image,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};

/// Texels per row: WebGL2's smallest guaranteed texture size (`DATA_TEXTURE_WIDTH` in
/// `data_texture.wesl`).
pub const DATA_TEXTURE_WIDTH: u32 = 2048;

/// Most rows, the same bound: `2048 × 2048` texels of 16 bytes, 64 MiB.
pub(crate) const DATA_TEXTURE_MAX_ROWS: u32 = 2048;

/// Most texels a data texture holds.
pub const DATA_TEXTURE_MAX_TEXELS: usize =
    DATA_TEXTURE_WIDTH as usize * DATA_TEXTURE_MAX_ROWS as usize;

/// `bytes` as little-endian `u32`s, the last one zero-padded.
pub(crate) fn words_of(bytes: &[u8]) -> impl Iterator<Item = u32> + '_ {
    bytes.chunks(4).map(|chunk| {
        let mut word = [0u8; 4];
        word[..chunk.len()].copy_from_slice(chunk);
        u32::from_le_bytes(word)
    })
}

/// Rows of [`DATA_TEXTURE_WIDTH`] texels for `words`, as a power of two (so that data whose
/// size wobbles does not reallocate the texture every frame), at least 1.
pub(crate) fn rows_for(words: usize) -> u32 {
    let texels = words.div_ceil(4) as u32;
    texels
        .div_ceil(DATA_TEXTURE_WIDTH)
        .max(1)
        .next_power_of_two()
}

/// What [`DataTexture::write`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum DataTextureWrite {
    /// The texture already held these words: nothing was written (or uploaded).
    Unchanged,
    /// The words were written into a texture of the same size.
    Written,
    /// The texture was created or changed its size: the GPU holds a new texture, and bind
    /// groups holding the old one must be rebuilt.
    Resized,
}

/// An [`Image`] asset that holds words as a data texture, rewritten only when they change.
#[derive(Debug)]
pub(crate) struct DataTexture {
    handle: Handle<Image>,
    words: Vec<u32>,
    rows: u32,
}

impl DataTexture {
    /// A data texture that writes into the asset behind `handle` (created on first write).
    pub(crate) fn new(handle: Handle<Image>) -> Self {
        Self {
            handle,
            words: Vec::new(),
            rows: 0,
        }
    }

    /// The image asset to bind.
    pub(crate) fn handle(&self) -> &Handle<Image> {
        &self.handle
    }

    /// Writes `words` (at most [`DATA_TEXTURE_MAX_TEXELS`] texels; callers trim to fit)
    /// into the asset, zero-filled to whole rows.
    pub(crate) fn write(&mut self, images: &mut Assets<Image>, words: &[u32]) -> DataTextureWrite {
        let rows = rows_for(words.len()).min(DATA_TEXTURE_MAX_ROWS);
        if rows == self.rows && self.words == words && images.contains(&self.handle) {
            return DataTextureWrite::Unchanged;
        }
        let texels = (DATA_TEXTURE_WIDTH * rows) as usize;
        let mut bytes = Vec::with_capacity(texels * 16);
        bytes.extend(
            words
                .iter()
                .take(texels * 4)
                .flat_map(|word| word.to_le_bytes()),
        );
        bytes.resize(texels * 16, 0);
        let image = Image::new(
            Extent3d {
                width: DATA_TEXTURE_WIDTH,
                height: rows,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            bytes,
            TextureFormat::Rgba32Uint,
            RenderAssetUsages::RENDER_WORLD,
        );
        // A handle made by `reserve_handle` or `uuid_handle!` always accepts an asset.
        let _ = images.insert(&self.handle, image);
        self.words.clear();
        self.words.extend_from_slice(words);
        let resized = rows != self.rows;
        self.rows = rows;
        if resized {
            DataTextureWrite::Resized
        } else {
            DataTextureWrite::Written
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bevy::asset::AssetApp;

    #[test]
    fn words_are_little_endian_and_zero_padded() {
        let words: Vec<u32> = words_of(&[1, 0, 0, 0, 2, 3]).collect();
        assert_eq!(words, [1, 0x0302]);
    }

    #[test]
    fn rows_grow_by_powers_of_two() {
        assert_eq!(rows_for(0), 1);
        assert_eq!(rows_for(4 * 2048), 1);
        assert_eq!(rows_for(4 * 2048 + 4), 2);
        assert_eq!(rows_for(4 * 2048 * 3), 4);
    }

    #[test]
    fn a_write_reports_whether_the_texture_changed_size() {
        let mut app = bevy::app::App::new();
        app.add_plugins(bevy::asset::AssetPlugin::default())
            .init_asset::<Image>();
        let handle = app
            .world_mut()
            .resource_mut::<Assets<Image>>()
            .reserve_handle();
        let mut texture = DataTexture::new(handle.clone());
        let mut images = app.world_mut().resource_mut::<Assets<Image>>();
        assert_eq!(
            texture.write(&mut images, &[1, 2]),
            DataTextureWrite::Resized
        );
        assert_eq!(
            texture.write(&mut images, &[1, 2]),
            DataTextureWrite::Unchanged
        );
        assert_eq!(
            texture.write(&mut images, &[1, 3]),
            DataTextureWrite::Written
        );
        let image = images.get(&handle).unwrap();
        assert_eq!(image.height(), 1);
        assert_eq!(
            &image.data.as_ref().unwrap()[..8],
            &[1, 0, 0, 0, 3, 0, 0, 0]
        );
        let two_rows = vec![7; 4 * 2048 + 1];
        assert_eq!(
            texture.write(&mut images, &two_rows),
            DataTextureWrite::Resized
        );
        assert_eq!(images.get(&handle).unwrap().height(), 2);
    }
}
