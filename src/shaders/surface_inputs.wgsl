// The fragment stage of `SurfaceInputsMaterial`: writes the inputs of the lighting equation
// that a mesh gives each pixel, so that the reference model can be evaluated on them.
#import bevy_pbr::forward_io::VertexOutput

struct SurfaceInputsUniform {
    // 0: world position P; 1: interpolated world normal (not normalized).
    output: u32,
    // Written to alpha.
    tag: u32,
}

@group(#{MATERIAL_BIND_GROUP}) @binding(0) var<uniform> inputs: SurfaceInputsUniform;

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {
    if inputs.output == 1u {
        return vec4<f32>(in.world_normal, f32(inputs.tag));
    }
    return vec4<f32>(in.world_position.xyz, f32(inputs.tag));
}
