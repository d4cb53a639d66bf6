// The benchmark's shader ablation (examples/bench/ablation.rs): `PhongMaterial`'s fragment
// shader (src/shaders/phong_material.wgsl) cut after one stage of its work, composed from
// the crate's own WGSL functions. The benchmark puts this source in place of that shader's
// in its own app only. The stage is chosen by these defs, which only the benchmark sets:
//
// - NO_LIGHTS: the fragment returns a color made of the surface set-up alone (normal, view
//   vector, the material's colors and maps).
// - NO_TERMS: the light loops read the fields of every record they reach that the diffuse
//   term uses (position, direction, color) and sum them, computing nothing else; with
//   ALL_FIELDS, every field the shader reads without shadows.
// - NO_ATTENUATION: every light arrives at full strength along L (no distance attenuation,
//   range or cone).
// - NO_HIGHLIGHT: each light's term is its diffuse part.
// - NO_AMBIENT: the color is the lights' sum alone (no ambient, no emissive).
// - CONSTANT_LIGHTS: the full shader's work with the showcase's three light records written
//   into it: every light's arithmetic, no record read, no clusters.
//
// Without defs it computes what `phong_material.wgsl` computes for a scene without shadows
// (the ablation's scene, the showcase, casts none): the same loops over the same functions.
#import bevy_pbr::forward_io::VertexOutput
#import bevy_phong::bindings::material
#import bevy_phong::camera_effects::camera_effects
#import bevy_phong::lighting::{Incidence, LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT, incidence, light_of_kind, normalize_or_zero, phong_light}
#import bevy_phong::scene::{directional_count, light_at, point_count, spot_count}
#import bevy_phong::shading::{ambient_light, clustered_light, clustered_list, fragment_surface}
#import bevy_phong::texture_maps::mapped_material
#import bevy_phong::types::{PhongLight, PhongSurface}

@fragment
fn fragment(@builtin(front_facing) is_front: bool, in: VertexOutput) -> @location(0) vec4<f32> {
    let mapped = mapped_material(in, is_front);
#ifdef PHONG_ALPHA_MASK
    if mapped.base_color.a < material.alpha_cutoff {
        discard;
    }
#endif
    let surface = fragment_surface(in, mapped);
    let lit = vec4<f32>(stage_color(surface, mapped.emissive), mapped.base_color.a);
    return camera_effects(lit, in.world_position.xyz, in.position.xy);
}

// SPEC.md's whole equation (the crate's `lit_color`) as far as the stage goes.
fn stage_color(surface: PhongSurface, emissive: vec3<f32>) -> vec3<f32> {
#ifdef NO_LIGHTS
    // No light: the normal, the view vector and the colors all used (a headlight).
    let colors = (surface.diffuse + 0.25 * surface.specular) * surface.ambient_occlusion;
    return abs(dot(surface.normal, surface.view)) * colors + emissive;
#else ifdef NO_AMBIENT
    return direct_lights(surface);
#else
    return emissive + ambient_light(surface) + direct_lights(surface);
#endif
}

// The crate's `direct_lights`: the lights of unlimited reach, then those of the point's
// cluster, each lit by `light_term`.
fn direct_lights(surface: PhongSurface) -> vec3<f32> {
#ifdef CONSTANT_LIGHTS
    return showcase_lights(surface);
#else
    let point_start = directional_count();
    let spot_start = point_start + point_count();
    let end = spot_start + spot_count();
    var color = vec3<f32>(0.0);
    for (var index = 0u; index < end; index += 1u) {
        let kind = select(select(LIGHT_DIRECTIONAL, LIGHT_POINT, index >= point_start), LIGHT_SPOT, index >= spot_start);
        color += light_term(surface, light_at(index), kind);
    }
    return color + clustered_lights(surface, end);
#endif
}

// The crate's `clustered_lights`, each light lit by `light_term`.
fn clustered_lights(surface: PhongSurface, start: u32) -> vec3<f32> {
    let list = clustered_list(start, surface.position);
    var color = vec3<f32>(0.0);
    for (var entry = list.first; entry < list.end; entry += 1u) {
        color += light_term(surface, clustered_light(list, entry), select(LIGHT_POINT, LIGHT_SPOT, entry >= list.spot));
    }
    return color;
}

// One light's term as far as the stage goes: the crate's `light_of_kind` with shadow
// factors (1, 1) when no cut applies.
fn light_term(surface: PhongSurface, light: PhongLight, kind: u32) -> vec3<f32> {
#ifdef NO_TERMS
    return record_sum(light);
#else
    let arriving = arrival(surface, light, kind);
    let lit = response(surface, arriving.to_light, light.color, light.specular);
    return select(lit, arriving.attenuation * lit, kind != LIGHT_DIRECTIONAL);
#endif
}

// The crate's `incidence`, or with NO_ATTENUATION L alone at full strength.
fn arrival(surface: PhongSurface, light: PhongLight, kind: u32) -> Incidence {
#ifdef NO_ATTENUATION
    let toward_position = normalize_or_zero(light.position - surface.position);
    return Incidence(select(-light.direction, toward_position, kind != LIGHT_DIRECTIONAL), 1.0);
#else
    return incidence(surface, light, kind);
#endif
}

// The crate's `phong_light`, or with NO_HIGHLIGHT its diffuse part alone.
fn response(surface: PhongSurface, to_light: vec3<f32>, color: vec3<f32>, specular: vec3<f32>) -> vec3<f32> {
#ifdef NO_HIGHLIGHT
    let n_dot_l = dot(surface.normal, to_light);
    if !(n_dot_l > 0.0) {
        return vec3<f32>(0.0);
    }
    return color * surface.diffuse * n_dot_l;
#else
    return phong_light(surface, to_light, color, specular);
#endif
}

// The sum of the fields of a light record that the diffuse term reads (position,
// direction, color) or, with ALL_FIELDS, of every field the shader reads without shadows,
// so that the loops read them and compute nothing else.
fn record_sum(light: PhongLight) -> vec3<f32> {
    let diffuse_fields = light.position + light.direction + light.color;
#ifdef ALL_FIELDS
    let scalars = light.range + light.outer_versine + light.cone_scale + light.spot_exponent;
    return diffuse_fields + light.specular + light.decay + vec3<f32>(scalars);
#else
    return diffuse_fields;
#endif
}

#ifdef CONSTANT_LIGHTS
// The records the gather makes of the showcase's three lights (examples/bench/scene.rs; the
// point lights' range unlimited, which their reach, over 100 units, is in that scene).
var<private> SHOWCASE_LIGHTS: array<PhongLight, 3> = array<PhongLight, 3>(
    PhongLight(vec3(0.0), 0.0, vec3(-1.0, 0.0, 0.0), 0.0, vec3(1.0), 0.0, vec3(1.0), 0.0, vec3(0.0), 0u),
    PhongLight(vec3(-3.0, 3.0, 0.0), 3.4028235e38, vec3(0.0), 0.0, vec3(1.0, 0.0, 0.0), 0.0, vec3(1.0, 0.0, 0.0), 0.0, vec3(1.0, 0.0, 0.2), 0u),
    PhongLight(vec3(3.0, 3.0, 0.0), 3.4028235e38, vec3(0.0), 0.0, vec3(0.0, 0.0, 1.0), 0.0, vec3(0.0, 0.0, 1.0), 0.0, vec3(1.0, 0.0, 0.2), 0u),
);

// The first loop of `direct_lights` over `SHOWCASE_LIGHTS`: every light's arithmetic, and
// no light record read from the scene data (the loop's count still is, so that the
// compiler cannot fold the lights into the code).
fn showcase_lights(surface: PhongSurface) -> vec3<f32> {
    let end = directional_count() + 2u;
    var color = vec3<f32>(0.0);
    for (var index = 0u; index < end; index += 1u) {
        let light = SHOWCASE_LIGHTS[min(index, 2u)];
        let kind = select(LIGHT_DIRECTIONAL, LIGHT_POINT, index >= 1u);
        let arriving = incidence(surface, light, kind);
        color += light_of_kind(surface, light, kind, arriving, vec2<f32>(1.0));
    }
    return color;
}
#endif
