// A material's toon ramp (`PhongMaterial::toon_ramp_texture`, three.js's `gradientMap`):
// each light's diffuse factor read from an image rather than computed in bands (SPEC.md,
// "Stylized shading"). Imported by `bevy_phong::lighting` only in the PHONG_TOON_RAMP
// variant, so that the lighting functions need no material binding otherwise.
#define_import_path bevy_phong::toon_ramp

#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
#import bevy_phong::bindings::toon_ramp_texture
#endif

// The ramp's red channel at `u = (1 + N·L) / 2` along its middle row, nearest (column
// `min(⌊u·width⌋, width − 1)`), clamped to [0, 1]; -1 where the device binds no ramp
// (WebGL2: `render::binds_every_map`), which draws the bands instead.
fn toon_ramp(n_dot_l: f32) -> f32 {
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
    let size = textureDimensions(toon_ramp_texture);
    let u = saturate((1.0 + n_dot_l) * 0.5);
    let column = min(u32(u * f32(size.x)), size.x - 1u);
    return saturate(textureLoad(toon_ramp_texture, vec2<u32>(column, size.y / 2u), 0).r);
#else
    return -1.0;
#endif
}
