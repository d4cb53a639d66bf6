// The surface normal a fragment is lit with, before normalization: the interpolated
// normal turned toward the viewer on double-sided materials, then the normal map. Shared by
// the material's main pass (`bevy_phong::texture_maps`) and its prepass.
#define_import_path bevy_phong::normals

#import bevy_phong::bindings::{material, normal_map_texture, normal_map_sampler}
#import bevy_phong::types::{DOUBLE_SIDED, FLIP_NORMAL_MAP_Y}

// `n.x·T + n.y·B + n.z·N` with `n = 2·texel − 1` (green negated when the material says so)
// and `B = T.w · N × T`: MikkTSpace's tangent frame, from the interpolated, unnormalized
// normal and tangent.
fn mapped_normal(normal: vec3<f32>, tangent: vec4<f32>, texel: vec3<f32>, flip_y: bool) -> vec3<f32> {
    var n = texel * 2.0 - 1.0;
    n.y = select(n.y, -n.y, flip_y);
    let bitangent = tangent.w * cross(normal, tangent.xyz);
    return n.x * tangent.xyz + n.y * bitangent + n.z * normal;
}

// The interpolated normal, negated on the back faces of a double-sided material (the only
// back faces drawn): the side the viewer sees is the side that is lit.
fn facing_normal(normal: vec3<f32>, is_front: bool) -> vec3<f32> {
    return select(normal, -normal, !is_front && (material.flags & DOUBLE_SIDED) != 0u);
}

#ifdef PHONG_NORMAL_MAP
// `normal` with the material's normal map, sampled at `uv`, applied in the frame of
// `tangent`.
fn with_normal_map(normal: vec3<f32>, tangent: vec4<f32>, uv: vec2<f32>) -> vec3<f32> {
    let texel = textureSample(normal_map_texture, normal_map_sampler, uv).rgb;
    return mapped_normal(normal, tangent, texel, (material.flags & FLIP_NORMAL_MAP_Y) != 0u);
}
#endif
