// Draws a shadow caster into a shadow map: depth only, from the mesh's positions placed by
// the draw's `clip_from_local` matrix (an instance attribute, one column per location).
//
// A skinned or morphed caster (POSED) is first posed as Bevy's mesh vertex stage poses it
// (`bevy_pbr::morph`, `bevy_pbr::skinning`), from the joint matrices and morph weights
// Bevy prepared for it this frame (src/shadows/posed.rs): p' = p + Σ_t w_t · Δ_t, then for a
// skinned one P = Σ_k ω_k · J_k · p' with `clip_from_local` being the map's clip-from-world
// (the joint matrices J_k place it in the world).
//
// A displaced caster (DISPLACED: its material has a displacement map) moves each vertex, after
// the morph targets, along its (morphed) normal by red · scale + bias of the map at its moved
// UVs, as the material's own vertex stages do (`bevy_phong::displacement`): the map in group
// DISPLACEMENT_GROUP, the scale, bias and UV transform in the draw's instance data.

struct Caster {
    @builtin(vertex_index) vertex_index: u32,
    @location(0) position: vec3<f32>,
    @location(1) clip_from_local_0: vec4<f32>,
    @location(2) clip_from_local_1: vec4<f32>,
    @location(3) clip_from_local_2: vec4<f32>,
    @location(4) clip_from_local_3: vec4<f32>,
#ifdef POSED
    // (first joint, morph descriptor, first vertex of the mesh in its buffer, 0).
    @location(5) deform: vec4<u32>,
#endif
#ifdef SKINNED
    @location(6) joint_indices: vec4<u32>,
    @location(7) joint_weights: vec4<f32>,
#endif
#ifdef DISPLACED
    @location(8) normal: vec3<f32>,
    @location(9) uv: vec2<f32>,
    // The UV transform's matrix by columns (xy, zw), then its translation, scale and bias.
    @location(10) uv_matrix: vec4<f32>,
    @location(11) shift_scale_bias: vec4<f32>,
#endif
}

#ifdef DISPLACED
@group(#{DISPLACEMENT_GROUP}) @binding(0) var displacement_map: texture_2d<f32>;
@group(#{DISPLACEMENT_GROUP}) @binding(1) var displacement_sampler: sampler;

// The local offset of the caster's vertex with local normal `normal`.
fn displacement_offset(caster: Caster, normal: vec3<f32>) -> vec3<f32> {
    let length_squared = dot(normal, normal);
    if length_squared == 0.0 {
        return vec3<f32>(0.0);
    }
    let uv = mat2x2<f32>(caster.uv_matrix.xy, caster.uv_matrix.zw) * caster.uv
        + caster.shift_scale_bias.xy;
    let height = textureSampleLevel(displacement_map, displacement_sampler, uv, 0.0).r;
    let distance = height * caster.shift_scale_bias.z + caster.shift_scale_bias.w;
    return normal * inverseSqrt(length_squared) * distance;
}
#endif

#ifdef POSED
#ifdef DEFORMATION_IN_UNIFORMS
// The draw's window of 256 joint matrices (Bevy's `MAX_JOINTS`), bound at its offset.
struct JointWindow {
    matrices: array<mat4x4<f32>, 256u>,
}
@group(0) @binding(0) var<uniform> joints: JointWindow;

fn joint(first: u32, index: u32) -> mat4x4<f32> {
    return joints.matrices[min(index, 255u)];
}
#else
@group(0) @binding(0) var<storage> joints: array<mat4x4<f32>>;

fn joint(first: u32, index: u32) -> mat4x4<f32> {
    return joints[first + index];
}
#endif
#endif

#ifdef MORPHED
#ifdef DEFORMATION_IN_UNIFORMS
// The draw's window of 256 weights (Bevy's `MAX_MORPH_WEIGHTS`), bound at its offset, and
// its mesh's targets: texel (9 · vertex + component) of row-major layers, one per morph_target
// (position first), as Bevy writes them.
struct WeightWindow {
    weights: array<vec4<f32>, 64u>,
}
@group(1) @binding(0) var<uniform> weights: WeightWindow;
@group(1) @binding(1) var targets: texture_3d<f32>;

fn target_count(descriptor: u32) -> u32 {
    return min(u32(textureDimensions(targets).z), 256u);
}

fn weight(descriptor: u32, morph_target: u32) -> f32 {
    return weights.weights[morph_target / 4u][morph_target % 4u];
}

// The target's change of `kind` (0 position, 1 normal) at `vertex`.
fn target_delta(descriptor: u32, vertex: u32, morph_target: u32, kind: u32) -> vec3<f32> {
    let width = u32(textureDimensions(targets).x);
    var moved = vec3<f32>(0.0);
    for (var component = 0u; component < 3u; component += 1u) {
        let texel = 9u * vertex + 3u * kind + component;
        moved[component] = textureLoad(targets, vec3<u32>(texel % width, texel / width, morph_target), 0).r;
    }
    return moved;
}
#else
// Bevy's `MorphAttributes` (position, normal, tangent) and `GpuMorphDescriptor`.
struct MorphTarget {
    position: vec3<f32>,
    normal: vec3<f32>,
    tangent: vec3<f32>,
}
struct MorphDescriptor {
    current_weights_offset: u32,
    prev_weights_offset: u32,
    targets_offset: u32,
    vertex_count: u32,
    weight_count: u32,
}
@group(1) @binding(0) var<storage> weights: array<f32>;
@group(1) @binding(1) var<storage> targets: array<MorphTarget>;
@group(1) @binding(2) var<storage> descriptors: array<MorphDescriptor>;

fn target_count(descriptor: u32) -> u32 {
    return descriptors[descriptor].weight_count;
}

fn weight(descriptor: u32, morph_target: u32) -> f32 {
    return weights[descriptors[descriptor].current_weights_offset + morph_target];
}

// The target's change of `kind` (0 position, 1 normal) at `vertex`.
fn target_delta(descriptor: u32, vertex: u32, morph_target: u32, kind: u32) -> vec3<f32> {
    let d = descriptors[descriptor];
    let morph = targets[d.targets_offset + morph_target * d.vertex_count + vertex];
    return select(morph.position, morph.normal, kind == 1u);
}
#endif

// v + Σ_t w_t · Δ_t for the mesh's `vertex`, `v` its `kind` (0 position, 1 normal).
fn morphed(value: vec3<f32>, descriptor: u32, vertex: u32, kind: u32) -> vec3<f32> {
    var moved = value;
    let count = target_count(descriptor);
    for (var morph_target = 0u; morph_target < count; morph_target += 1u) {
        let w = weight(descriptor, morph_target);
        if w != 0.0 {
            moved += w * target_delta(descriptor, vertex, morph_target, kind);
        }
    }
    return moved;
}
#endif

@vertex
fn vertex(caster: Caster) -> @builtin(position) vec4<f32> {
    let clip_from_local = mat4x4<f32>(
        caster.clip_from_local_0,
        caster.clip_from_local_1,
        caster.clip_from_local_2,
        caster.clip_from_local_3,
    );
    var position = vec4<f32>(caster.position, 1.0);
#ifdef MORPHED
    let vertex = caster.vertex_index - caster.deform.z;
    position = vec4<f32>(morphed(caster.position, caster.deform.y, vertex, 0u), 1.0);
#endif
#ifdef DISPLACED
    var normal = caster.normal;
#ifdef MORPHED
    normal = morphed(caster.normal, caster.deform.y, vertex, 1u);
#endif
    position = vec4<f32>(position.xyz + displacement_offset(caster, normal), 1.0);
#endif
#ifdef SKINNED
    let first = caster.deform.x;
    let w = caster.joint_weights;
    let k = caster.joint_indices;
    let world_from_local = w.x * joint(first, k.x) + w.y * joint(first, k.y)
        + w.z * joint(first, k.z) + w.w * joint(first, k.w);
    position = world_from_local * position;
#endif
    return clip_from_local * position;
}
