// SPEC.md's lighting equation, one function per term. Every light kind, the built-in ones
// and those added by extensions, is lit by `phong_light`, after its own attenuation.
#define_import_path bevy_phong::lighting

#import bevy_phong::types::{PhongLight, PhongSurface, SPECULAR_MODEL_BLINN_PHONG}
#ifdef PHONG_TOON_RAMP
#import bevy_phong::toon_ramp::toon_ramp
#endif

// A vector whose largest component is below this has no direction: f32's smallest normal
// number (GPUs may flush smaller ones to zero). The rule of src/direction.rs and SPEC.md.
const MIN_COMPONENT: f32 = 1.17549435e-38;

// A point or spot light closer than this to the surface point lights nothing (1e-15 units,
// far below any scene's scale).
const MIN_LIGHT_DISTANCE: f32 = 1e-15;

// A finite, non-zero `v` divided by its largest component (which becomes ±1), with the
// squared length of the result, in [1, 3]: no square of `v` overflows or underflows on the
// way. The length is NaN or outside [1, 3] for a zero, NaN or infinite `v`.
struct Scaled {
    vector: vec3<f32>,
    largest: f32,
    length_squared: f32,
}

fn scaled(v: vec3<f32>) -> Scaled {
    let largest = max(abs(v.x), max(abs(v.y), abs(v.z)));
    let vector = v / largest;
    return Scaled(vector, largest, dot(vector, vector));
}

// Whether a `Scaled` came from a finite vector with a direction: its largest component at
// least MIN_COMPONENT (`!(…)` also rejects NaN) and its squared length in [1, 3].
fn has_direction(s: Scaled) -> bool {
    return s.largest >= MIN_COMPONENT && s.length_squared >= 0.5 && s.length_squared <= 4.0;
}

// `v / |v|`, computed by way of `scaled` so that `(3e38, 3e38, 3e38)` and
// `(1e-30, -1e-30, 0)` keep their directions; zero when `v` is NaN, infinite, or its largest
// component is below MIN_COMPONENT.
fn normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let s = scaled(v);
    if !has_direction(s) {
        return vec3<f32>(0.0);
    }
    return s.vector * inverseSqrt(s.length_squared);
}

// `ln(1 - d)` for `0 ≤ d < 1`, with full relative precision for small `d`: there `1 - d`
// rounds, and `log` near 1 carries an absolute rather than a relative error on some
// devices (lavapipe's among them), which `α` would amplify. Below 1/8 a series is used
// (truncation error below `d^8/8`, under 1e-7 relative).
fn ln_one_minus(d: f32) -> f32 {
    if d < 0.125 {
        let series = 1.0 + d * (1.0 / 2.0 + d * (1.0 / 3.0 + d * (1.0 / 4.0 + d * (1.0 / 5.0
            + d * (1.0 / 6.0 + d * (1.0 / 7.0))))));
        return -d * series;
    }
    return log(1.0 - d);
}

// Below `e^LN_NEGLIGIBLE` (1.8e-35) a factor is flushed to zero: its contribution is far
// below any output's resolution, and the f32 subnormals it would produce are slow to compute
// with on CPU rasterizers.
const LN_NEGLIGIBLE: f32 = -80.0;

// `(1 - d)^exponent` for `0 ≤ d`, with `0^0 = 1`: the highlight as a function of
// `d = 1 - cos`, the form that stays accurate near the peak, where `cos` itself rounds to 1.
// The exponent (a material's shininess, from a uniform) selects rather than branches: a
// branch on a uniform value makes some drivers (lavapipe) recompile the shader for every
// material bound.
fn power_of_one_minus(d: f32, exponent: f32) -> f32 {
    // ln(1 - d) ≤ -d, so past α·d > 80 the value is flushed anyway: skip the log and exp
    // (most of a surface, away from its highlights).
    if exponent * d > -LN_NEGLIGIBLE {
        return 0.0;
    }
    let ln_power = exponent * ln_one_minus(min(d, 1.0));
    let value = select(exp(ln_power), 0.0, !(d < 1.0) || ln_power < LN_NEGLIGIBLE);
    return select(value, 1.0, exponent == 0.0);
}

// The surface point `position` with the (interpolated, any length) `normal`, seen from
// `camera`, made of a material with diffuse `k_d`, specular `k_s · strength`, shininess and
// specular model.
fn phong_surface(
    position: vec3<f32>,
    normal: vec3<f32>,
    camera: vec3<f32>,
    diffuse: vec3<f32>,
    specular: vec3<f32>,
    shininess: f32,
    specular_model: u32,
) -> PhongSurface {
    return PhongSurface(
        position,
        normalize_or_zero(normal),
        normalize_or_zero(camera - position),
        diffuse,
        specular,
        shininess,
        specular_model,
        true,
        vec3<f32>(1.0),
        vec3<f32>(0.0),
        vec4<f32>(0.0, 1.0, 0.0, 0.0),
        vec4<f32>(0.0),
    );
}

// The rim factor (1 − max(N·V, 0))^power, 0 where N or V has no direction.
fn rim_factor(surface: PhongSurface) -> f32 {
    if all(surface.normal == vec3<f32>(0.0)) || all(surface.view == vec3<f32>(0.0)) {
        return 0.0;
    }
    return power_of_one_minus(max(dot(surface.normal, surface.view), 0.0), surface.rim.w);
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

// S_cone for the ray `from_light = -L` and the spot's unit `direction`: the soft edge
// between the inner and outer cone (`cone_scale = 1 / (cos_inner - cos_outer)`, or 0 for a
// hard edge at the outer cone), times `cos(θ)^exponent`. Computed from
// `1 - cos θ = |from_light - direction|² / 2`, whose precision does not run out for narrow
// cones, where `cos θ` rounds near 1 and `cone_scale` magnifies every rounding.
fn spot_cone(from_light: vec3<f32>, direction: vec3<f32>, outer_versine: f32, cone_scale: f32, exponent: f32) -> f32 {
    let difference = from_light - direction;
    let versine = 0.5 * dot(difference, difference);
    var edge: f32;
    if cone_scale > 0.0 {
        edge = saturate((outer_versine - versine) * cone_scale);
    } else {
        edge = select(0.0, 1.0, versine <= outer_versine);
    }
    if edge == 0.0 {
        return 0.0;
    }
    return edge * power_of_one_minus(versine, exponent);
}

// H(N, L, V): the highlight factor of one light, for `n_dot_l = N·L > 0`.
// Phong: max(R·V, 0)^α with R = 2(N·L)N - L. Blinn-Phong: max(N·H, 0)^α with
// H = normalize(L + V). Both are computed from `1 - cos = |A - B|² / 2` for the two unit
// vectors A, B whose cosine it is: near the peak, where the highlight matters and `α`
// amplifies every error, this keeps the relative precision `cos` rounded to 1 would lose.
fn highlight(surface: PhongSurface, to_light: vec3<f32>, n_dot_l: f32) -> f32 {
    // Both vectors are computed and one is selected: the model comes from a uniform, and a
    // branch on it would make some drivers (lavapipe) recompile the shader per material.
    let blinn_phong = surface.specular_model == SPECULAR_MODEL_BLINN_PHONG;
    let half_vector = normalize_or_zero(to_light + surface.view);
    let reflected = 2.0 * n_dot_l * surface.normal - to_light;
    let toward = select(surface.view, surface.normal, blinn_phong);
    let away = select(reflected, half_vector, blinn_phong);
    // A zero view (camera at P) or half vector (L = -V) has no direction: cos = 0.
    let degenerate = all(away == vec3<f32>(0.0)) || all(toward == vec3<f32>(0.0));
    let difference = away - toward;
    let d = select(0.5 * dot(difference, difference), 1.0, degenerate);
    return power_of_one_minus(d, surface.shininess);
}

// `t` in [0, 1] eased from 0 at `1 − width` to 1 at 1 (a smoothstep; 0 throughout for a
// zero width): how a toon step rises into the next.
fn step_rise(t: f32, width: f32) -> f32 {
    if !(width > 0.0) {
        return 0.0;
    }
    let x = saturate((t - (1.0 - width)) / width);
    return x * x * (3.0 - 2.0 * x);
}

// The diffuse factor of `n_dot_l` (N·L) in the material's mode: max(N·L, 0) (Lambert),
// max((N·L + w) / (1 + w), 0) (PHONG_DIFFUSE_WRAP), or (⌊x·n⌋ + rise(fract(x·n))) / n with
// x = max(N·L, 0) (PHONG_DIFFUSE_TOON), the numbers from `style` (PhongSurface.style); with
// PHONG_TOON_RAMP, the material's ramp at N·L (`bevy_phong::toon_ramp`) where it is bound.
fn diffuse_factor(n_dot_l: f32, style: vec4<f32>) -> f32 {
#ifdef PHONG_DIFFUSE_WRAP
    return max((n_dot_l + style.x) / (1.0 + style.x), 0.0);
#else
#ifdef PHONG_DIFFUSE_TOON
#ifdef PHONG_TOON_RAMP
    let ramp = toon_ramp(n_dot_l);
    if ramp >= 0.0 {
        return ramp;
    }
#endif
    let steps = max(n_dot_l, 0.0) * style.y;
    return (floor(steps) + step_rise(fract(steps), style.z)) / style.y;
#else
    return max(n_dot_l, 0.0);
#endif
#endif
}

// The highlight `h` drawn in the material's mode: as it is, or (PHONG_SPECULAR_TOON) a
// flat spot where h > 1/2, its edge rising over `width`.
fn highlight_factor(h: f32, width: f32) -> f32 {
#ifdef PHONG_SPECULAR_TOON
    if !(width > 0.0) {
        return select(0.0, 1.0, h >= 0.5);
    }
    return smoothstep(0.5 - 0.5 * width, 0.5 + 0.5 * width, h);
#else
    return h;
#endif
}

// color ⊙ k_d · f_d(N·L) + specular ⊙ k_s · f_s(H(N, L, V)), for a unit `to_light` (L), with
// f_d and f_s the material's diffuse and specular modes (`diffuse_factor`,
// `highlight_factor`; Lambert's max(N·L, 0) and H itself by default). The highlight is zero
// where N·L ≤ 0; so is the diffuse term but for a wrapped one or a toon ramp
// (PHONG_LIT_PAST_TERMINATOR); both are zero for a surface without a normal.
fn phong_light(
    surface: PhongSurface,
    to_light: vec3<f32>,
    color: vec3<f32>,
    specular: vec3<f32>,
) -> vec3<f32> {
    let n_dot_l = dot(surface.normal, to_light);
#ifdef PHONG_LIT_PAST_TERMINATOR
    // Lit past the terminator: only a surface without a normal (or a NaN) is left dark.
    if all(surface.normal == vec3<f32>(0.0)) || !(n_dot_l > -1.5) {
        return vec3<f32>(0.0);
    }
#else
    if !(n_dot_l > 0.0) {
        return vec3<f32>(0.0);
    }
#endif
    var diffuse = color * surface.diffuse * diffuse_factor(n_dot_l, surface.style);
#ifdef PHONG_RIM_LIT
    // The rim on the lit side: this light's color, weighted by max(N·L, 0).
    diffuse += color * surface.rim.rgb * (rim_factor(surface) * max(n_dot_l, 0.0));
#endif
#ifdef PHONG_NO_SPECULAR
    // The material's k_s · strength is zero: the variant without the highlight.
    return diffuse;
#else
    let h = highlight_factor(highlight(surface, to_light, n_dot_l), surface.style.w);
    return diffuse + specular * surface.specular * select(0.0, h, n_dot_l > 0.0);
#endif
}

// A directional light: L = -direction, no attenuation.
fn directional_light(surface: PhongSurface, light: PhongLight) -> vec3<f32> {
    return unshadowed_light(surface, light, LIGHT_DIRECTIONAL);
}

// The unit vector from the surface toward a light at `position` (L), and the light's
// attenuation there; the attenuation is 0 out of range, and for a light exactly at P, which
// (closer than 1e-15) has no direction.
struct LightRay {
    to_light: vec3<f32>,
    attenuation: f32,
}

fn ray_toward(surface: PhongSurface, position: vec3<f32>, decay: vec3<f32>, range: f32) -> LightRay {
    let offset = scaled(position - surface.position);
    if !has_direction(offset) {
        return LightRay(vec3<f32>(0.0), 0.0);
    }
    let scaled_length = sqrt(offset.length_squared);
    let distance = offset.largest * scaled_length;
    if !(distance > MIN_LIGHT_DISTANCE) {
        return LightRay(vec3<f32>(0.0), 0.0);
    }
    let attenuation = distance_attenuation(distance, decay, range);
    if !(attenuation > 0.0) {
        return LightRay(vec3<f32>(0.0), 0.0);
    }
    return LightRay(offset.vector / scaled_length, attenuation);
}

// A point light: L toward its position, attenuated by distance.
fn point_light(surface: PhongSurface, light: PhongLight) -> vec3<f32> {
    return unshadowed_light(surface, light, LIGHT_POINT);
}

// A spot light: a point light times its cone factor.
fn spot_light(surface: PhongSurface, light: PhongLight) -> vec3<f32> {
    return unshadowed_light(surface, light, LIGHT_SPOT);
}

// The built-in kinds of light, by where a record sits in the light buffer.
const LIGHT_DIRECTIONAL: u32 = 0u;
const LIGHT_POINT: u32 = 1u;
const LIGHT_SPOT: u32 = 2u;

// How a light of any built-in kind arrives at the surface point: L, and the factor on its
// `phong_light` term (1 for a directional light; the distance attenuation, times the cone
// factor for a spot light, for the others).
struct Incidence {
    to_light: vec3<f32>,
    attenuation: f32,
}

// How the light of `kind` arrives at the surface point, with the kind selected rather than
// branched on: one loop then lights every kind, and a SIMD rasterizer on the CPU
// (lavapipe), which runs every branch and every loop at least once under a mask, does one
// light's work per light instead of a loop's body per kind. `directional_light`,
// `point_light` and `spot_light` are this, unshadowed.
fn incidence(surface: PhongSurface, light: PhongLight, kind: u32) -> Incidence {
    let ray = ray_toward(surface, light.position, light.decay, light.range);
    let cone = spot_cone(-ray.to_light, light.direction, light.outer_versine, light.cone_scale, light.spot_exponent);
    let at_point = kind != LIGHT_DIRECTIONAL;
    return Incidence(
        select(-light.direction, ray.to_light, at_point),
        select(1.0, ray.attenuation * select(1.0, cone, kind == LIGHT_SPOT), at_point),
    );
}

// The term of a light of `kind` arriving as `incidence`, with the light's color and
// specular color scaled by `factors` (its shadow factors; (1, 1) unshadowed).
fn light_of_kind(surface: PhongSurface, light: PhongLight, kind: u32, incidence: Incidence, factors: vec2<f32>) -> vec3<f32> {
    let lit = phong_light(surface, incidence.to_light, light.color * factors.x, light.specular * factors.y);
    return select(lit, incidence.attenuation * lit, kind != LIGHT_DIRECTIONAL);
}

// The light of `kind` without shadows: `light_of_kind` with factors (1, 1).
fn unshadowed_light(surface: PhongSurface, light: PhongLight, kind: u32) -> vec3<f32> {
    return light_of_kind(surface, light, kind, incidence(surface, light, kind), vec2<f32>(1.0));
}
