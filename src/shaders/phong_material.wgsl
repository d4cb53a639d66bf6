// The fragment stage of `PhongMaterial`. The vertex stage is Bevy's mesh vertex shader.
#import bevy_pbr::forward_io::VertexOutput
#import bevy_pbr::mesh_view_bindings::view
#import bevy_phong::bindings::material
#import bevy_phong::shading::{material_surface, phong_shade}

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {
    let surface = material_surface(in.world_position.xyz, in.world_normal, view.world_position);
    return vec4<f32>(phong_shade(surface), material.base_color.a);
}
