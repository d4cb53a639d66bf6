// The fragment stage of `PhongMaterial`. The vertex stage is Bevy's mesh vertex shader.
#import bevy_pbr::forward_io::VertexOutput
#import bevy_phong::bindings::material
#import bevy_phong::shading::{fragment_surface, lit_color}
#import bevy_phong::texture_maps::mapped_material
#import bevy_phong::camera_effects::camera_effects
#ifdef PHONG_ENVIRONMENT_MAP
#import bevy_phong::environment::with_environment
#endif

@fragment
fn fragment(@builtin(front_facing) is_front: bool, in: VertexOutput) -> @location(0) vec4<f32> {
    let mapped = mapped_material(in, is_front);
#ifdef PHONG_ALPHA_MASK
    if mapped.base_color.a < material.alpha_cutoff {
        discard;
    }
#endif
#ifdef PHONG_UNLIT
    // `PhongMaterial::unlit`: no light, ambient or shadow.
    let color = mapped.emissive + mapped.base_color.rgb;
#else
    let surface = fragment_surface(in, mapped);
    var color = lit_color(surface, mapped.emissive);
#ifdef PHONG_ENVIRONMENT_MAP
    color = with_environment(color, surface, mapped.environment_mask);
#endif
#endif
    let lit = vec4<f32>(color, mapped.base_color.a);
    return camera_effects(lit, in.world_position.xyz, in.position.xy);
}
