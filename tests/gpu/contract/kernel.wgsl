// The shader contract kernel: runs the material's own lighting functions
// (`bevy_phong::lighting`, imported as the material imports them) on a batch of cases.
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

@group(0) @binding(0) var<storage, read> cases: array<ContractCase>;
@group(0) @binding(1) var<storage, read_write> results: array<vec4<f32>>;

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
@compute @workgroup_size(64)
fn crate_highlight(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    if index >= arrayLength(&cases) {
        return;
    }
    let surface = case_surface(cases[index]);
    let to_light = -cases[index].light.direction;
    let n_dot_l = dot(surface.normal, to_light);
    results[index] = vec4<f32>(highlight(surface, to_light, max(n_dot_l, 0.0)), 0.0, 0.0, 0.0);
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
@compute @workgroup_size(64)
fn naive_highlight(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    if index >= arrayLength(&cases) {
        return;
    }
    let surface = case_surface(cases[index]);
    let to_light = -cases[index].light.direction;
    var cosine: f32;
    if surface.specular_model == SPECULAR_MODEL_BLINN_PHONG {
        cosine = dot(surface.normal, normalize(to_light + surface.view));
    } else {
        cosine = dot(2.0 * dot(surface.normal, to_light) * surface.normal - to_light, surface.view);
    }
    results[index] = vec4<f32>(naive_power(max(cosine, 0.0), surface.shininess), 0.0, 0.0, 0.0);
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    if index >= arrayLength(&cases) {
        return;
    }
    let input = cases[index];
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
    results[index] = vec4<f32>(color, 0.0);
}
