// SPEC.md's lighting equation, one function per term. Every light kind, the built-in ones
// and those added by extensions, is lit by `phong_light`, after its own attenuation.
#define_import_path bevy_phong::lighting

#import bevy_phong::types::{PhongLight, PhongSurface, SPECULAR_MODEL_BLINN_PHONG}

// `v / |v|`, or zero when `v` is zero, NaN or too small to normalize.
fn normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let length_squared = dot(v, v);
    // `!(x > 0)` is also true for NaN.
    if !(length_squared > 1e-30) {
        return vec3<f32>(0.0);
    }
    return v * inverseSqrt(length_squared);
}

// `base^exponent` for `base ≥ 0` with `0^0 = 1` (WGSL leaves `pow(0, 0)` undefined) and
// `0^exponent = 0` for `exponent > 0`.
fn power(base: f32, exponent: f32) -> f32 {
    if exponent == 0.0 {
        return 1.0;
    }
    if base <= 0.0 {
        return 0.0;
    }
    return pow(base, exponent);
}

// A(d) = min(1, 1 / (c + l·d + q·d²)), and 0 past `range`. A denominator at or below 1
// (including a zero `decay`) gives 1.
fn distance_attenuation(distance: f32, decay: vec3<f32>, range: f32) -> f32 {
    if distance > range {
        return 0.0;
    }
    let denominator = decay.x + distance * (decay.y + distance * decay.z);
    if denominator <= 1.0 {
        return 1.0;
    }
    return 1.0 / denominator;
}

// S_cone for `cos_theta = dot(-L, spot_direction)`: the soft edge between the inner and
// outer cone (`cone_scale = 1 / (cos_inner - cos_outer)`, or 0 for a hard edge at
// `cos_outer`), times `cos(θ)^exponent`.
fn spot_cone(cos_theta: f32, cos_outer: f32, cone_scale: f32, exponent: f32) -> f32 {
    var edge: f32;
    if cone_scale > 0.0 {
        edge = saturate((cos_theta - cos_outer) * cone_scale);
    } else {
        edge = select(0.0, 1.0, cos_theta >= cos_outer);
    }
    if edge == 0.0 {
        return 0.0;
    }
    return edge * power(max(cos_theta, 0.0), exponent);
}

// H(N, L, V): the highlight factor of one light, for `n_dot_l = N·L > 0`.
// Phong: max(R·V, 0)^α with R = 2(N·L)N - L. Blinn-Phong: max(N·H, 0)^α with
// H = normalize(L + V).
fn highlight(surface: PhongSurface, to_light: vec3<f32>, n_dot_l: f32) -> f32 {
    var cosine: f32;
    if surface.specular_model == SPECULAR_MODEL_BLINN_PHONG {
        let half_vector = normalize_or_zero(to_light + surface.view);
        cosine = dot(surface.normal, half_vector);
    } else {
        let reflected = 2.0 * n_dot_l * surface.normal - to_light;
        cosine = dot(reflected, surface.view);
    }
    return power(max(cosine, 0.0), surface.shininess);
}

// color ⊙ k_d · max(N·L, 0) + specular ⊙ k_s · H(N, L, V), for a unit `to_light` (L).
// Zero on the side of the surface facing away from the light.
fn phong_light(
    surface: PhongSurface,
    to_light: vec3<f32>,
    color: vec3<f32>,
    specular: vec3<f32>,
) -> vec3<f32> {
    let n_dot_l = dot(surface.normal, to_light);
    if !(n_dot_l > 0.0) {
        return vec3<f32>(0.0);
    }
    let diffuse = color * surface.diffuse * n_dot_l;
    return diffuse + specular * surface.specular * highlight(surface, to_light, n_dot_l);
}

// A directional light: L = -direction, no attenuation.
fn directional_light(surface: PhongSurface, light: PhongLight) -> vec3<f32> {
    return phong_light(surface, -light.direction, light.color, light.specular);
}

// The unit vector from the surface toward a light at `position` (L), and the light's
// attenuation there; the attenuation is 0 out of range, and for a light exactly at P, which
// has no direction.
struct LightRay {
    to_light: vec3<f32>,
    attenuation: f32,
}

fn ray_toward(surface: PhongSurface, position: vec3<f32>, decay: vec3<f32>, range: f32) -> LightRay {
    let offset = position - surface.position;
    let distance = length(offset);
    let attenuation = distance_attenuation(distance, decay, range);
    if !(attenuation > 0.0 && distance > 0.0) {
        return LightRay(vec3<f32>(0.0), 0.0);
    }
    return LightRay(offset / distance, attenuation);
}

// A point light: L toward its position, attenuated by distance.
fn point_light(surface: PhongSurface, light: PhongLight) -> vec3<f32> {
    let ray = ray_toward(surface, light.position, light.decay, light.range);
    if ray.attenuation == 0.0 {
        return vec3<f32>(0.0);
    }
    return ray.attenuation * phong_light(surface, ray.to_light, light.color, light.specular);
}

// A spot light: a point light times its cone factor.
fn spot_light(surface: PhongSurface, light: PhongLight) -> vec3<f32> {
    let ray = ray_toward(surface, light.position, light.decay, light.range);
    if ray.attenuation == 0.0 {
        return vec3<f32>(0.0);
    }
    let cos_theta = dot(-ray.to_light, light.direction);
    let cone = spot_cone(cos_theta, light.cos_outer, light.cone_scale, light.spot_exponent);
    if cone == 0.0 {
        return vec3<f32>(0.0);
    }
    return (ray.attenuation * cone) * phong_light(surface, ray.to_light, light.color, light.specular);
}
