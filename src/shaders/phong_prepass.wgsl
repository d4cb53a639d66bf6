// The prepass fragment stage of `PhongMaterial` (depth, normal and motion-vector prepasses,
// and Bevy's shadow maps, which draw with the prepass pipeline). Bevy runs it only where it
// has something to do: a target to write, or fragments to discard (`AlphaMode::Mask`).
// - Alpha mask: the fragments the main pass discards (by the base color's, the vertex
//   color's, the base color map's and the alpha map's alpha) are discarded here too, so the
//   depth prepass leaves the holes open and Bevy's shadow maps let light through them.
// - Normal prepass: the normal the main pass lights the fragment with (`lit_normal`: double-
//   sided faces turned toward the viewer, flat shading, the normal and bump maps), normalized (zero where degenerate), encoded as `n/2 + 1/2`
//   like Bevy's.
// - Motion vectors and unclipped depth: as Bevy's own prepass shader.
#import bevy_pbr::prepass_io::VertexOutput
#ifdef PREPASS_FRAGMENT
#import bevy_pbr::prepass_io::FragmentOutput
#endif
#import bevy_phong::bindings::material
#import bevy_phong::uv::map_uv
#ifdef PHONG_ALPHA_MASK
#ifdef PHONG_BASE_COLOR_TEXTURE
#import bevy_phong::bindings::{base_color_texture, base_color_sampler}
#endif
#ifdef PHONG_ALPHA_MAP
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
#import bevy_phong::bindings::{alpha_map_texture, alpha_map_sampler}
#endif
#endif
#endif
#ifdef NORMAL_PREPASS
#import bevy_phong::lighting::normalize_or_zero
#import bevy_phong::normals::lit_normal
#endif
#ifdef MOTION_VECTOR_PREPASS
#import bevy_pbr::{prepass_bindings::previous_view_uniforms, mesh_view_bindings::view}
#endif

// Discards the fragment where the main pass does (`AlphaMode::Mask`).
fn discard_masked(in: VertexOutput) {
#ifdef PHONG_ALPHA_MASK
    var alpha = material.base_color.a;
#ifdef VERTEX_COLORS
    alpha *= in.color.a;
#endif
#ifdef PHONG_BASE_COLOR_TEXTURE
    alpha *= textureSample(base_color_texture, base_color_sampler, map_uv(in.uv)).a;
#endif
#ifdef PHONG_ALPHA_MAP
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
    alpha *= textureSample(alpha_map_texture, alpha_map_sampler, map_uv(in.uv)).g;
#endif
#endif
    if alpha < material.alpha_cutoff {
        discard;
    }
#endif
}

#ifdef PREPASS_FRAGMENT
@fragment
fn fragment(@builtin(front_facing) is_front: bool, in: VertexOutput) -> FragmentOutput {
    var out: FragmentOutput;
#ifdef NORMAL_PREPASS
    var uv = vec2<f32>(0.0);
#ifdef VERTEX_UVS_A
    uv = map_uv(in.uv);
#endif
    var tangent = vec4<f32>(0.0);
#ifdef VERTEX_TANGENTS
    tangent = in.world_tangent;
#endif
    let normal = lit_normal(in.world_normal, in.world_position.xyz, tangent, uv, is_front);
    // Sampled before any discard: texture sampling needs uniform control flow.
    out.normal = vec4<f32>(normalize_or_zero(normal) * 0.5 + vec3<f32>(0.5), 1.0);
#endif
    discard_masked(in);
#ifdef UNCLIPPED_DEPTH_ORTHO_EMULATION
    out.frag_depth = in.unclipped_depth;
#endif
#ifdef MOTION_VECTOR_PREPASS
    let clip = view.unjittered_clip_from_world * in.world_position;
    let previous_clip = previous_view_uniforms.clip_from_world * in.previous_world_position;
    out.motion_vector = (clip.xy / clip.w - previous_clip.xy / previous_clip.w) * vec2<f32>(0.5, -0.5);
#endif
    return out;
}
#else
// A depth-only prepass with nothing to write: Bevy runs this stage only to discard.
@fragment
fn fragment(in: VertexOutput) {
    discard_masked(in);
}
#endif
