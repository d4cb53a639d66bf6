// The benchmark's floor: a fragment shader that returns a constant color, so a frame costs
// only rasterization and Bevy's per-frame overhead.
#import bevy_pbr::forward_io::VertexOutput

@group(#{MATERIAL_BIND_GROUP}) @binding(0) var<uniform> color: vec4<f32>;

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {
    return color;
}
