// The fragment stage of `SurfaceInputsMaterial`: writes the inputs of the lighting equation
// that a mesh gives each pixel, so that the reference model can be evaluated on them.
#import bevy_pbr::forward_io::VertexOutput

struct SurfaceInputsUniform {
    // 0: world position P; 1: interpolated world normal (not normalized); 2: UV and the
    // tangent's handedness; 3: interpolated world tangent (not normalized); 4: vertex color
    // (its own alpha, no tag); 5: the second UV set.
    output: u32,
    // Written to alpha.
    tag: u32,
    // 1 where back faces are lit with their normal negated (double-sided).
    double_sided: u32,
}

@group(#{MATERIAL_BIND_GROUP}) @binding(0) var<uniform> inputs: SurfaceInputsUniform;

@fragment
fn fragment(in: VertexOutput, @builtin(front_facing) is_front: bool) -> @location(0) vec4<f32> {
    let tag = f32(inputs.tag);
    var uv_and_sign = vec3<f32>(0.0);
    var tangent = vec3<f32>(0.0);
#ifdef VERTEX_UVS_A
    uv_and_sign = vec3<f32>(in.uv, 0.0);
#endif
#ifdef VERTEX_TANGENTS
    uv_and_sign.z = in.world_tangent.w;
    tangent = in.world_tangent.xyz;
#endif
    var uv_b = vec2<f32>(0.0);
#ifdef VERTEX_UVS_B
    uv_b = in.uv_b;
#endif
    var color = vec4<f32>(1.0);
#ifdef VERTEX_COLORS
    color = in.color;
#endif
    switch inputs.output {
        // A double-sided material lights a back face with its normal negated.
        case 1u: {
            let flip = !is_front && inputs.double_sided != 0u;
            return vec4<f32>(select(in.world_normal, -in.world_normal, flip), tag);
        }
        case 2u: { return vec4<f32>(uv_and_sign, tag); }
        case 3u: { return vec4<f32>(tangent, tag); }
        case 4u: { return color; }
        case 5u: { return vec4<f32>(uv_b, 0.0, tag); }
        default: { return vec4<f32>(in.world_position.xyz, tag); }
    }
}
