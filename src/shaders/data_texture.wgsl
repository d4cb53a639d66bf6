// Data textures: bytes in an `Rgba32Uint` texture, for devices without storage buffers
// (WebGL2). Texel `i`, counting row after row, holds bytes `16 i .. 16 i + 16` as four
// `u32`s (src/render/data_texture.rs); rebuild structs from them with `bitcast`.
#define_import_path bevy_phong::data_texture

#import bevy_phong::types::{PhongLight, light_from_words}

// Texels per row of every data texture (`DATA_TEXTURE_WIDTH` in Rust).
const DATA_TEXTURE_WIDTH: u32 = 2048u;

// Texel `index` of `data`, counting row after row.
fn data_texel(data: texture_2d<u32>, index: u32) -> vec4<u32> {
    return textureLoad(data, vec2<u32>(index % DATA_TEXTURE_WIDTH, index / DATA_TEXTURE_WIDTH), 0);
}

// The `PhongLight` (80 bytes, 5 texels) whose first texel is `first`.
fn data_light(data: texture_2d<u32>, first: u32) -> PhongLight {
    return light_from_words(
        data_texel(data, first),
        data_texel(data, first + 1u),
        data_texel(data, first + 2u),
        data_texel(data, first + 3u),
        data_texel(data, first + 4u),
    );
}
