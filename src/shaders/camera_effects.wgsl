// What the camera's own components do to a lit fragment, as they do to Bevy's
// `StandardMaterial`: screen-space ambient occlusion on the ambient term, distance fog,
// tonemapping and debanding in the shader (cameras without HDR). Each part is compiled only
// where Bevy's mesh pipeline sets its shader def for the view.
#define_import_path bevy_phong::camera_effects

#import bevy_pbr::mesh_view_bindings::view
#ifdef SCREEN_SPACE_AMBIENT_OCCLUSION
#import bevy_pbr::mesh_view_bindings::screen_space_ambient_occlusion_texture
#import bevy_pbr::ssao_utils::ssao_multibounce
#endif
#ifdef DISTANCE_FOG
#import bevy_pbr::mesh_view_bindings::fog
#import bevy_pbr::mesh_view_types::{FOG_MODE_LINEAR, FOG_MODE_EXPONENTIAL, FOG_MODE_EXPONENTIAL_SQUARED, FOG_MODE_ATMOSPHERIC}
#import bevy_pbr::fog::{linear_fog, exponential_fog, exponential_squared_fog, atmospheric_fog}
#import bevy_phong::scene::{directional_count, light_at}
#endif
#ifdef TONEMAP_IN_SHADER
#import bevy_core_pipeline::tonemapping::{tone_mapping, screen_space_dither}
#import bevy_render::maths::powsafe
#endif

// The ambient term's factor at the pixel `frag_coord` of a surface of diffuse color
// `diffuse`: with `ScreenSpaceAmbientOcclusion` on the camera, Bevy's occlusion with its
// multi-bounce correction (`ssao_multibounce`, per channel), as `StandardMaterial` takes
// it; otherwise 1.
fn ambient_occlusion(frag_coord: vec2<f32>, diffuse: vec3<f32>) -> vec3<f32> {
#ifdef SCREEN_SPACE_AMBIENT_OCCLUSION
    let visibility = textureLoad(screen_space_ambient_occlusion_texture, vec2<i32>(frag_coord), 0i).r;
    return min(vec3<f32>(1.0), ssao_multibounce(visibility, diffuse));
#else
    return vec3<f32>(1.0);
#endif
}

#ifdef DISTANCE_FOG
// The light of the Phong directional lights scattered toward the viewer along `direction`
// (unit, from the camera): Σ color · max(direction · L, 0)^directional_light_exponent, with
// L toward each light. Bevy's fog takes the same sum over Bevy's directional lights, whose
// colors Phong surfaces never see; here the lights are the ones that light the surface.
// Unshadowed.
fn directional_scattering(direction: vec3<f32>) -> vec3<f32> {
    var scattering = vec3<f32>(0.0);
    for (var index = 0u; index < directional_count(); index += 1u) {
        let light = light_at(index);
        scattering += pow(max(dot(direction, -light.direction), 0.0), fog.directional_light_exponent) * light.color;
    }
    return scattering;
}

// `color` at `position` seen through the camera's `DistanceFog`, by Bevy's own fog
// functions (`bevy_pbr::fog`) on the distance from the camera.
fn fogged(color: vec4<f32>, position: vec3<f32>) -> vec4<f32> {
    let from_camera = position - view.world_position;
    let distance = length(from_camera);
    var scattering = vec3<f32>(0.0);
    if fog.directional_light_color.a > 0.0 && distance > 0.0 {
        scattering = directional_scattering(from_camera / distance);
    }
    if fog.mode == FOG_MODE_LINEAR {
        return linear_fog(fog, color, distance, scattering);
    } else if fog.mode == FOG_MODE_EXPONENTIAL {
        return exponential_fog(fog, color, distance, scattering);
    } else if fog.mode == FOG_MODE_EXPONENTIAL_SQUARED {
        return exponential_squared_fog(fog, color, distance, scattering);
    } else if fog.mode == FOG_MODE_ATMOSPHERIC {
        return atmospheric_fog(fog, color, distance, scattering);
    }
    return color;
}
#endif

// The lit `color` of the fragment at `position` (world) and `frag_coord` (pixel), as the
// camera shows it: fogged (unless the material turns fog off, `PHONG_NO_FOG`), then tonemapped and debanded where the camera does that in the
// shader. Bevy's `main_pass_post_lighting_processing`, in the same order.
fn camera_effects(color: vec4<f32>, position: vec3<f32>, frag_coord: vec2<f32>) -> vec4<f32> {
    var output = color;
#ifdef DISTANCE_FOG
#ifndef PHONG_NO_FOG
    output = fogged(output, position);
#endif
#endif
#ifdef TONEMAP_IN_SHADER
    output = tone_mapping(output, view.color_grading);
#ifdef DEBAND_DITHER
    // Dithered in sRGB's gamma, then back to linear: the target's encoding is applied after.
    let gamma = powsafe(output.rgb, 1.0 / 2.2) + screen_space_dither(frag_coord);
    output = vec4<f32>(powsafe(gamma, 2.2), output.a);
#endif
#endif
    return output;
}
