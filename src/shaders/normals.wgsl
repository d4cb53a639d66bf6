// The surface normal a fragment is lit with, before normalization: the interpolated normal
// turned toward the viewer on double-sided materials, the face's normal in place of it with
// flat shading, then the normal map and the bump map. Shared by the material's main pass
// (`bevy_phong::texture_maps`) and its prepass.
#define_import_path bevy_phong::normals

#import bevy_phong::bindings::material
#import bevy_phong::types::{DOUBLE_SIDED, FLIP_NORMAL_MAP_Y}
#ifdef PHONG_NORMAL_MAP
#import bevy_phong::bindings::{normal_map_texture, normal_map_sampler}
#endif
#ifdef PHONG_BUMP_MAP
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
#import bevy_phong::bindings::{bump_map_texture, bump_map_sampler}
#endif
#endif

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

// The unit normal of the plane of the fragment's triangle, from the screen derivatives of the
// world position, on the side of `side` (the facing interpolated normal).
fn face_normal(world_position: vec3<f32>, side: vec3<f32>) -> vec3<f32> {
    let face = normalize(cross(dpdx(world_position), dpdy(world_position)));
    return select(face, -face, dot(face, side) < 0.0);
}

// The normal a fragment is lit with, any length: `interpolated` (the mesh's world normal)
// turned toward the viewer, then what the material's variant applies. `tangent` and `uv` (the
// maps' UVs) are read only by the normal and bump maps, whose variants exist only on meshes
// with both. Texture sampling and derivatives: call in uniform control flow.
fn lit_normal(
    interpolated: vec3<f32>,
    world_position: vec3<f32>,
    tangent: vec4<f32>,
    uv: vec2<f32>,
    is_front: bool,
) -> vec3<f32> {
    var frame_normal = facing_normal(interpolated, is_front);
#ifdef PHONG_FLAT_SHADING
    frame_normal = face_normal(world_position, frame_normal);
#endif
    var normal = frame_normal;
#ifdef PHONG_NORMAL_MAP
    let texel = textureSample(normal_map_texture, normal_map_sampler, uv).rgb;
    normal = mapped_normal(frame_normal, tangent, texel, (material.flags & FLIP_NORMAL_MAP_Y) != 0u);
#endif
#ifdef PHONG_BUMP_MAP
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
    normal = bumped_normal(normal, frame_normal, tangent, height_slope(uv), material.bump_scale);
#endif
#endif
    return normal;
}

// `normal − scale · (slope.x·T + slope.y·B)`, with `B = T.w · frame_normal × T`: the tangent
// frame of the normal map, tilted against the height's rise.
fn bumped_normal(
    normal: vec3<f32>,
    frame_normal: vec3<f32>,
    tangent: vec4<f32>,
    slope: vec2<f32>,
    scale: f32,
) -> vec3<f32> {
    let bitangent = tangent.w * cross(frame_normal, tangent.xyz);
    return normal - scale * (slope.x * tangent.xyz + slope.y * bitangent);
}

#ifdef PHONG_BUMP_MAP
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
// How the bump map's height (red) changes one texel of its largest mip along u and along v
// from `uv`: forward differences of three samples.
fn height_slope(uv: vec2<f32>) -> vec2<f32> {
    let texel = 1.0 / vec2<f32>(textureDimensions(bump_map_texture));
    let height = textureSample(bump_map_texture, bump_map_sampler, uv).r;
    let along_u = textureSample(bump_map_texture, bump_map_sampler, uv + vec2<f32>(texel.x, 0.0)).r;
    let along_v = textureSample(bump_map_texture, bump_map_sampler, uv + vec2<f32>(0.0, texel.y)).r;
    return vec2<f32>(along_u - height, along_v - height);
}
#endif
#endif
