// Data textures: bytes in an `Rgba32Uint` texture, for devices without storage buffers
// (WebGL2). Texel `i`, counting row after row, holds bytes `16 i .. 16 i + 16` as four
// `u32`s (src/render/data_texture.rs); rebuild structs from them with `bitcast`.
#define_import_path bevy_phong::data_texture

#import bevy_phong::types::PhongLight

// Texels per row of every data texture (`DATA_TEXTURE_WIDTH` in Rust).
const DATA_TEXTURE_WIDTH: u32 = 2048u;

// Texel `index` of `data`, counting row after row.
fn data_texel(data: texture_2d<u32>, index: u32) -> vec4<u32> {
    return textureLoad(data, vec2<u32>(index % DATA_TEXTURE_WIDTH, index / DATA_TEXTURE_WIDTH), 0);
}

// The `PhongLight` (80 bytes, 5 texels) whose first texel is `first`.
fn data_light(data: texture_2d<u32>, first: u32) -> PhongLight {
    let a = data_texel(data, first);
    let b = data_texel(data, first + 1u);
    let c = data_texel(data, first + 2u);
    let d = data_texel(data, first + 3u);
    let e = data_texel(data, first + 4u);
    return PhongLight(
        bitcast<vec3<f32>>(a.xyz),
        bitcast<f32>(a.w),
        bitcast<vec3<f32>>(b.xyz),
        bitcast<f32>(b.w),
        bitcast<vec3<f32>>(c.xyz),
        bitcast<f32>(c.w),
        bitcast<vec3<f32>>(d.xyz),
        bitcast<f32>(d.w),
        bitcast<vec3<f32>>(e.xyz),
        e.w,
    );
}
