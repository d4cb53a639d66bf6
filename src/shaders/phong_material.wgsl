// The fragment stage of `PhongMaterial`. The vertex stage is Bevy's mesh vertex shader.
#import bevy_pbr::forward_io::VertexOutput
#import bevy_pbr::mesh_view_bindings::view
#import bevy_phong::bindings::material
#import bevy_phong::lighting::phong_surface
#import bevy_phong::shading::{lit_color, receives_shadows}
#import bevy_phong::texture_maps::mapped_material
#import bevy_phong::camera_effects::{ambient_occlusion, camera_effects}

@fragment
fn fragment(@builtin(front_facing) is_front: bool, in: VertexOutput) -> @location(0) vec4<f32> {
    let mapped = mapped_material(in, is_front);
#ifdef PHONG_ALPHA_MASK
    if mapped.base_color.a < material.alpha_cutoff {
        discard;
    }
#endif
    var surface = phong_surface(
        in.world_position.xyz,
        mapped.normal,
        view.world_position,
        mapped.base_color.rgb,
        mapped.specular,
        material.shininess,
        material.flags & 3u,
    );
    surface.receives_shadows = receives_shadows(in.instance_index);
    surface.ambient_occlusion = ambient_occlusion(in.position.xy, mapped.base_color.rgb);
    let lit = vec4<f32>(lit_color(surface, mapped.emissive), mapped.base_color.a);
    return camera_effects(lit, in.world_position.xyz, in.position.xy);
}
