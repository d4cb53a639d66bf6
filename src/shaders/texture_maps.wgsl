// The material's colors and normal at a fragment, with its vertex colors and texture maps
// applied. Each map is sampled only in the shader variant whose def names it (see
// `PhongMaterialKey`), at the UVs `map_uv` gives; vertex colors only on meshes that have
// them (Bevy's `VERTEX_COLORS`).
#define_import_path bevy_phong::texture_maps

#import bevy_pbr::forward_io::VertexOutput
#import bevy_phong::bindings::{
    material,
    base_color_texture, base_color_sampler,
    specular_texture, specular_sampler,
    emissive_texture, emissive_sampler,
}
#import bevy_phong::normals::facing_normal
#import bevy_phong::uv::map_uv
#ifdef PHONG_NORMAL_MAP
#import bevy_phong::normals::with_normal_map
#endif

// What the lighting equation takes from the material at one fragment.
struct MappedMaterial {
    // k_d ⊙ vertex color ⊙ base color map, with the output alpha.
    base_color: vec4<f32>,
    // k_s · strength ⊙ specular map.
    specular: vec3<f32>,
    // emissive ⊙ emissive map.
    emissive: vec3<f32>,
    // The surface normal, any length (normalized by `phong_surface`).
    normal: vec3<f32>,
}

// `is_front`: the fragment's `@builtin(front_facing)`.
fn mapped_material(in: VertexOutput, is_front: bool) -> MappedMaterial {
    let normal = facing_normal(in.world_normal, is_front);
    var mapped = MappedMaterial(material.base_color, material.specular, material.emissive, normal);
#ifdef VERTEX_COLORS
    mapped.base_color *= in.color;
#endif
#ifdef VERTEX_UVS_A
    let uv = map_uv(in.uv);
#endif
#ifdef PHONG_BASE_COLOR_TEXTURE
    mapped.base_color *= textureSample(base_color_texture, base_color_sampler, uv);
#endif
#ifdef PHONG_SPECULAR_TEXTURE
    mapped.specular *= textureSample(specular_texture, specular_sampler, uv).rgb;
#endif
#ifdef PHONG_EMISSIVE_TEXTURE
    mapped.emissive *= textureSample(emissive_texture, emissive_sampler, uv).rgb;
#endif
#ifdef PHONG_NORMAL_MAP
    mapped.normal = with_normal_map(normal, in.world_tangent, uv);
#endif
    return mapped;
}
