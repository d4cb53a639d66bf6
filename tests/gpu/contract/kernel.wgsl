// The shader contract kernel: runs the material's own lighting functions
// (`bevy_phong::lighting`, imported as the material imports them) on a batch of cases, in
// the fragment stage the material runs in: one pixel of the results target per case.
#import bevy_phong::data_texture::{data_light, data_texel}
#import bevy_phong::lighting::{directional_light, highlight, phong_surface, point_light, spot_light}
#import bevy_phong::types::SPECULAR_MODEL_BLINN_PHONG
#import bevy_phong::types::{PhongLight, PhongSurface}

struct ContractCase {
    position: vec3<f32>,
    // 0 directional, 1 point, 2 spot.
    kind: u32,
    normal: vec3<f32>,
    shininess: f32,
    camera: vec3<f32>,
    specular_model: u32,
    diffuse: vec3<f32>,
    padding0: f32,
    specular: vec3<f32>,
    padding1: f32,
    light: PhongLight,
}

// The cases as a data texture (`bevy_phong::data_texture`): texel 0 holds their count,
// then each case takes 10 texels. Every device binds it, WebGL2 included.
@group(0) @binding(0) var cases: texture_2d<u32>;

// Pixels per row of the results target; pixel (x, y) holds case `y * RESULTS_WIDTH + x`.
const RESULTS_WIDTH: u32 = 1024u;

fn case_count() -> u32 {
    return data_texel(cases, 0u).x;
}

fn case_at(index: u32) -> ContractCase {
    let first = 1u + 10u * index;
    var t: array<vec4<u32>, 5>;
    for (var i = 0u; i < 5u; i += 1u) {
        t[i] = data_texel(cases, first + i);
    }
    let light = data_light(cases, first + 5u);
    return ContractCase(
        bitcast<vec3<f32>>(t[0].xyz),
        t[0].w,
        bitcast<vec3<f32>>(t[1].xyz),
        bitcast<f32>(t[1].w),
        bitcast<vec3<f32>>(t[2].xyz),
        t[2].w,
        bitcast<vec3<f32>>(t[3].xyz),
        bitcast<f32>(t[3].w),
        bitcast<vec3<f32>>(t[4].xyz),
        bitcast<f32>(t[4].w),
        light,
    );
}

// The case a fragment of the results target stands for (past the last case, the
// fragments of the last row repeat it; their results are not read).
fn case_index(position: vec4<f32>) -> u32 {
    return u32(position.y) * RESULTS_WIDTH + u32(position.x);
}

// A triangle that covers the whole target.
@vertex
fn cover(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((vertex << 1u) & 2u), f32(vertex & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

fn case_surface(input: ContractCase) -> PhongSurface {
    return phong_surface(
        input.position,
        input.normal,
        input.camera,
        input.diffuse,
        input.specular,
        input.shininess,
        input.specular_model,
    );
}

// The highlight factor H of a directional light, as the crate computes it.
@fragment
fn crate_highlight(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let input = case_at(min(case_index(position), case_count() - 1u));
    let surface = case_surface(input);
    let to_light = -input.light.direction;
    let n_dot_l = dot(surface.normal, to_light);
    return vec4<f32>(highlight(surface, to_light, max(n_dot_l, 0.0)), 0.0, 0.0, 0.0);
}

// `pow(base, α)` with `0^0 = 1`, for the straightforward formula below.
fn naive_power(base: f32, exponent: f32) -> f32 {
    if exponent == 0.0 {
        return 1.0;
    }
    if base <= 0.0 {
        return 0.0;
    }
    return pow(base, exponent);
}

// The same factor by the straightforward formula, `pow(max(cos, 0), α)`: kept here only to
// measure what the crate's formula gains near the peak.
@fragment
fn naive_highlight(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let input = case_at(min(case_index(position), case_count() - 1u));
    let surface = case_surface(input);
    let to_light = -input.light.direction;
    var cosine: f32;
    if surface.specular_model == SPECULAR_MODEL_BLINN_PHONG {
        cosine = dot(surface.normal, normalize(to_light + surface.view));
    } else {
        cosine = dot(2.0 * dot(surface.normal, to_light) * surface.normal - to_light, surface.view);
    }
    return vec4<f32>(naive_power(max(cosine, 0.0), surface.shininess), 0.0, 0.0, 0.0);
}

@fragment
fn main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let input = case_at(min(case_index(position), case_count() - 1u));
    let surface = case_surface(input);
    var color: vec3<f32>;
    switch input.kind {
        case 0u: {
            color = directional_light(surface, input.light);
        }
        case 1u: {
            color = point_light(surface, input.light);
        }
        default: {
            color = spot_light(surface, input.light);
        }
    }
    return vec4<f32>(color, 0.0);
}
