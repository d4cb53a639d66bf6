// The material's colors and normal at a fragment, with its texture maps applied. Each map
// is sampled only in the shader variant whose def names it (see `PhongMaterialKey`).
#define_import_path bevy_phong::texture_maps

#import bevy_pbr::forward_io::VertexOutput
#import bevy_phong::bindings::{
    material,
    base_color_texture, base_color_sampler,
    specular_texture, specular_sampler,
    emissive_texture, emissive_sampler,
    normal_map_texture, normal_map_sampler,
}
#import bevy_phong::types::FLIP_NORMAL_MAP_Y

// What the lighting equation takes from the material at one fragment.
struct MappedMaterial {
    // k_d ⊙ base color map, with the output alpha.
    base_color: vec4<f32>,
    // k_s · strength ⊙ specular map.
    specular: vec3<f32>,
    // emissive ⊙ emissive map.
    emissive: vec3<f32>,
    // The surface normal, any length (normalized by `phong_surface`).
    normal: vec3<f32>,
}

// `n.x·T + n.y·B + n.z·N` with `n = 2·texel − 1` (green negated when the material says so)
// and `B = T.w · N × T`: MikkTSpace's tangent frame, from the interpolated, unnormalized
// normal and tangent.
fn mapped_normal(normal: vec3<f32>, tangent: vec4<f32>, texel: vec3<f32>, flip_y: bool) -> vec3<f32> {
    var n = texel * 2.0 - 1.0;
    n.y = select(n.y, -n.y, flip_y);
    let bitangent = tangent.w * cross(normal, tangent.xyz);
    return n.x * tangent.xyz + n.y * bitangent + n.z * normal;
}

fn mapped_material(in: VertexOutput) -> MappedMaterial {
    var mapped = MappedMaterial(material.base_color, material.specular, material.emissive, in.world_normal);
#ifdef PHONG_BASE_COLOR_TEXTURE
    mapped.base_color *= textureSample(base_color_texture, base_color_sampler, in.uv);
#endif
#ifdef PHONG_SPECULAR_TEXTURE
    mapped.specular *= textureSample(specular_texture, specular_sampler, in.uv).rgb;
#endif
#ifdef PHONG_EMISSIVE_TEXTURE
    mapped.emissive *= textureSample(emissive_texture, emissive_sampler, in.uv).rgb;
#endif
#ifdef PHONG_NORMAL_MAP
    let texel = textureSample(normal_map_texture, normal_map_sampler, in.uv).rgb;
    let flip_y = (material.flags & FLIP_NORMAL_MAP_Y) != 0u;
    mapped.normal = mapped_normal(in.world_normal, in.world_tangent, texel, flip_y);
#endif
    return mapped;
}
