// A material's displacement map (three.js's `displacementMap`): the vertex moved along its
// normal by the map's red channel times a scale, plus a bias, in the mesh's local space
// (SPEC.md, "Displacement"). Read in the vertex stage of the main pass, the prepasses and
// the crate's shadow casters alike. The bindings (24–26) are the same in every material that
// displaces: `PhongMaterial`, `SurfaceInputsMaterial`.
#define_import_path bevy_phong::displacement

// `PhongMaterial`'s displacement, as the vertex stage reads it.
struct PhongDisplacement {
    // The material's UV transform, applied to the first UV set before the map is read.
    uv_transform: mat3x3<f32>,
    // The distance a texel of 1 moves a vertex, in the mesh's local units.
    scale: f32,
    // Added to every vertex's distance, local units.
    bias: f32,
}

@group(#{MATERIAL_BIND_GROUP}) @binding(24) var displacement_map: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(25) var displacement_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(26) var<uniform> displacement: PhongDisplacement;

// How far along its normal the vertex at `uv` (the mesh's first UV set) moves:
// red · scale + bias, the map read at its largest mip (a vertex has no derivatives).
fn displacement_distance(uv: vec2<f32>) -> f32 {
    let moved_uv = (displacement.uv_transform * vec3<f32>(uv, 1.0)).xy;
    let height = textureSampleLevel(displacement_map, displacement_sampler, moved_uv, 0.0).r;
    return height * displacement.scale + displacement.bias;
}

// The local offset of the vertex with local normal `normal` (any length) at `uv`.
fn displacement_offset(normal: vec3<f32>, uv: vec2<f32>) -> vec3<f32> {
    let length_squared = dot(normal, normal);
    if length_squared == 0.0 {
        return vec3<f32>(0.0);
    }
    return normal * inverseSqrt(length_squared) * displacement_distance(uv);
}
