// The UVs the material's maps are sampled at: the mesh's first UV set moved by the
// material's UV transform (`PhongMaterial::uv_transform`) in the variants that have one
// (`PHONG_UV_TRANSFORM`), as it is elsewhere. Shared by the main pass and the prepass.
#define_import_path bevy_phong::uv

#import bevy_phong::bindings::material

fn map_uv(uv: vec2<f32>) -> vec2<f32> {
#ifdef PHONG_UV_TRANSFORM
    return (material.uv_transform * vec3<f32>(uv, 1.0)).xy;
#else
    return uv;
#endif
}
