// The prepass's vertex stage of a displaced material (PHONG_DISPLACEMENT_MAP; the depth,
// normal, motion-vector and deferred prepasses, and Bevy's shadow maps): Bevy's prepass
// vertex shader (`bevy_pbr/prepass/prepass.wgsl`) with the vertex moved along its normal by
// the displacement map after the morph targets (`bevy_phong::displacement`), as the main
// pass moves it. Its input always has the mesh's normal (location 3), which
// `PhongMaterial::specialize` adds where Bevy's prepass leaves it out.
#import bevy_pbr::{
    mesh_bindings::mesh,
    mesh_functions,
    prepass_io::VertexOutput,
    skinning,
    morph,
    morph::{morph_position, morph_normal, morph_tangent},
    view_transformations::position_world_to_clip,
}
#import bevy_phong::displacement::displacement_offset

// Bevy's prepass `Vertex`, with the normal whichever prepass runs.
struct DisplacedVertex {
    @builtin(instance_index) instance_index: u32,
    @location(0) position: vec3<f32>,
    @location(1) uv: vec2<f32>,
#ifdef VERTEX_UVS_B
    @location(2) uv_b: vec2<f32>,
#endif
    @location(3) normal: vec3<f32>,
#ifdef NORMAL_PREPASS_OR_DEFERRED_PREPASS
#ifdef VERTEX_TANGENTS
    @location(4) tangent: vec4<f32>,
#endif
#endif
#ifdef SKINNED
    @location(5) joint_indices: vec4<u32>,
    @location(6) joint_weights: vec4<f32>,
#endif
#ifdef VERTEX_COLORS
    @location(7) color: vec4<f32>,
#endif
#ifdef MORPH_TARGETS
    @builtin(vertex_index) index: u32,
#endif
}

#ifdef MORPH_TARGETS
// The vertex posed by the morph weights of this frame (`previous`: of the last frame, the
// position only, for motion vectors).
fn morph_vertex(vertex_in: DisplacedVertex, instance_index: u32, previous: bool) -> DisplacedVertex {
    var vertex = vertex_in;
    let first_vertex = mesh[instance_index].first_vertex_index;
    let vertex_index = vertex.index - first_vertex;
    let weight_count = morph::layer_count(instance_index);
    for (var i: u32 = 0u; i < weight_count; i ++) {
        var weight = morph::weight_at(i, instance_index);
#ifdef HAS_PREVIOUS_MORPH
        if previous {
            weight = morph::prev_weight_at(i, instance_index);
        }
#endif
        if weight == 0.0 {
            continue;
        }
        vertex.position += weight * morph_position(vertex_index, i, instance_index);
        if !previous {
            vertex.normal += weight * morph_normal(vertex_index, i, instance_index);
#ifdef NORMAL_PREPASS_OR_DEFERRED_PREPASS
#ifdef VERTEX_TANGENTS
            vertex.tangent += vec4(weight * morph_tangent(vertex_index, i, instance_index), 0.0);
#endif
#endif
        }
    }
    return vertex;
}
#endif

@vertex
fn vertex(vertex_no_morph: DisplacedVertex) -> VertexOutput {
    var out: VertexOutput;
#ifdef MORPH_TARGETS
    var vertex = morph_vertex(vertex_no_morph, vertex_no_morph.instance_index, false);
#else
    var vertex = vertex_no_morph;
#endif
    // The displacement, the same offset for this frame's position and the last's (the map
    // does not move).
    let offset = displacement_offset(vertex.normal, vertex.uv);
    vertex.position += offset;

    let mesh_world_from_local = mesh_functions::get_world_from_local(vertex_no_morph.instance_index);
#ifdef SKINNED
    var world_from_local = skinning::skin_model(
        vertex.joint_indices,
        vertex.joint_weights,
        vertex_no_morph.instance_index
    );
#else
    var world_from_local = mesh_world_from_local;
#endif

    out.world_position = mesh_functions::mesh_position_local_to_world(world_from_local, vec4<f32>(vertex.position, 1.0));
    out.position = position_world_to_clip(out.world_position.xyz);
#ifdef UNCLIPPED_DEPTH_ORTHO_EMULATION
    out.unclipped_depth = out.position.z;
    out.position.z = min(out.position.z, 1.0);
#endif
    out.uv = vertex.uv;
#ifdef VERTEX_UVS_B
    out.uv_b = vertex.uv_b;
#endif

#ifdef NORMAL_PREPASS_OR_DEFERRED_PREPASS
#ifdef SKINNED
    out.world_normal = skinning::skin_normals(world_from_local, vertex.normal);
#else
    out.world_normal = mesh_functions::mesh_normal_local_to_world(
        vertex.normal,
        vertex_no_morph.instance_index
    );
#endif
#ifdef VERTEX_TANGENTS
    out.world_tangent = mesh_functions::mesh_tangent_local_to_world(
        world_from_local,
        vertex.tangent,
        vertex_no_morph.instance_index
    );
#endif
#endif

#ifdef VERTEX_COLORS
    out.color = vertex.color;
#endif

#ifdef MOTION_VECTOR_PREPASS
#ifdef MORPH_TARGETS
#ifdef HAS_PREVIOUS_MORPH
    var prev_vertex = morph_vertex(vertex_no_morph, vertex_no_morph.instance_index, true);
#else
    var prev_vertex = vertex_no_morph;
#endif
#else
    var prev_vertex = vertex_no_morph;
#endif
    prev_vertex.position += offset;
#ifdef SKINNED
#ifdef HAS_PREVIOUS_SKIN
    let prev_model = skinning::skin_prev_model(
        prev_vertex.joint_indices,
        prev_vertex.joint_weights,
        vertex_no_morph.instance_index
    );
#else
    let prev_model = mesh_functions::get_previous_world_from_local(vertex_no_morph.instance_index);
#endif
#else
    let prev_model = mesh_functions::get_previous_world_from_local(vertex_no_morph.instance_index);
#endif
    out.previous_world_position = mesh_functions::mesh_position_local_to_world(
        prev_model,
        vec4<f32>(prev_vertex.position, 1.0)
    );
#endif

#ifdef VERTEX_OUTPUT_INSTANCE_INDEX
    out.instance_index = vertex_no_morph.instance_index;
#endif
#ifdef VISIBILITY_RANGE_DITHER
    out.visibility_range_dither = mesh_functions::get_visibility_range_dither_level(
        vertex_no_morph.instance_index, mesh_world_from_local[3]);
#endif
    return out;
}
