// The fragment stage of `SearchlitMaterial` (examples/searchlight): Phong lighting from the
// crate's lights, plus every searchlight in the extension's data texture, each lit with the
// crate's own `phong_light`.
#import bevy_pbr::{forward_io::VertexOutput, mesh_view_bindings::view}
#import bevy_phong::camera_effects::{ambient_occlusion, camera_effects}
#import bevy_phong::{
    bindings::material,
    data_texture::data_texel,
    lighting::{distance_attenuation, phong_light},
    shading::{material_surface, phong_shade, receives_shadows},
    shadows::shadow_factors,
    types::PhongSurface,
}

struct Searchlight {
    position: vec3<f32>,
    radius: f32,
    // Unit vector the beam travels along.
    direction: vec3<f32>,
    // Width of the soft boundary; 0 for a hard one.
    edge: f32,
    // Unit vector of the cross-section's +Y, perpendicular to `direction`.
    up: vec3<f32>,
    // 0 circle, 1 triangle, 2 diamond, 3 square.
    shape: u32,
    color: vec3<f32>,
    // Shadow slot: the first shadow view plus one, 0 without shadows.
    shadow: u32,
    specular: vec3<f32>,
    padding1: f32,
    decay: vec3<f32>,
    padding2: f32,
}

// `PhongLightKindBuffer::texture`: texel 0 holds the count, then each searchlight takes 6
// texels (96 bytes).
@group(#{MATERIAL_BIND_GROUP}) @binding(100) var searchlights: texture_2d<u32>;

fn searchlight_count() -> u32 {
    return data_texel(searchlights, 0u).x;
}

fn searchlight_at(index: u32) -> Searchlight {
    let first = 1u + 6u * index;
    let a = data_texel(searchlights, first);
    let b = data_texel(searchlights, first + 1u);
    let c = data_texel(searchlights, first + 2u);
    let d = data_texel(searchlights, first + 3u);
    let e = data_texel(searchlights, first + 4u);
    let f = data_texel(searchlights, first + 5u);
    return Searchlight(
        bitcast<vec3<f32>>(a.xyz),
        bitcast<f32>(a.w),
        bitcast<vec3<f32>>(b.xyz),
        bitcast<f32>(b.w),
        bitcast<vec3<f32>>(c.xyz),
        c.w,
        bitcast<vec3<f32>>(d.xyz),
        d.w,
        bitcast<vec3<f32>>(e.xyz),
        bitcast<f32>(e.w),
        bitcast<vec3<f32>>(f.xyz),
        bitcast<f32>(f.w),
    );
}

const HALF_SQRT_3: f32 = 0.8660254037844386;
const FRAC_1_SQRT_2: f32 = 0.7071067811865476;

// Signed distance of the cross-section point `p` from the shape's boundary (negative
// inside); polygons use the largest signed distance to their edge lines.
fn beam_distance(shape: u32, p: vec2<f32>, radius: f32) -> f32 {
    switch shape {
        case 1u: {
            let edges = max(-p.y, max(HALF_SQRT_3 * p.x + 0.5 * p.y, -HALF_SQRT_3 * p.x + 0.5 * p.y));
            return edges - 0.5 * radius;
        }
        case 2u: {
            return (abs(p.x) + abs(p.y) - radius) * FRAC_1_SQRT_2;
        }
        case 3u: {
            return max(abs(p.x), abs(p.y)) - radius * FRAC_1_SQRT_2;
        }
        default: {
            return length(p) - radius;
        }
    }
}

// 1 inside, 0 past `edge` outside, a smoothstep between; a step when `edge` is 0.
fn beam_coverage(distance: f32, edge: f32) -> f32 {
    if edge <= 0.0 {
        return select(0.0, 1.0, distance <= 0.0);
    }
    let t = saturate(distance / edge);
    return 1.0 - t * t * (3.0 - 2.0 * t);
}

fn searchlight(surface: PhongSurface, light: Searchlight) -> vec3<f32> {
    let offset = surface.position - light.position;
    let along = dot(offset, light.direction);
    if along <= 0.0 {
        return vec3<f32>(0.0);
    }
    let right = cross(light.direction, light.up);
    let section = vec2<f32>(dot(offset, right), dot(offset, light.up));
    let coverage = beam_coverage(beam_distance(light.shape, section, light.radius), light.edge);
    if coverage == 0.0 {
        return vec3<f32>(0.0);
    }
    let attenuation = distance_attenuation(along, light.decay, 3.4028235e38);
    var shadow = vec2<f32>(1.0);
#ifdef PHONG_SHADOWS
    // Compiled only when the scene casts shadows (see `PhongMaterialKey::shadows`).
    shadow = shadow_factors(light.shadow, surface, -light.direction, light.position);
#endif
    return (coverage * attenuation)
        * phong_light(surface, -light.direction, shadow.x * light.color, shadow.y * light.specular);
}

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {
    var surface = material_surface(in.world_position.xyz, in.world_normal, view.world_position);
    surface.receives_shadows = receives_shadows(in.instance_index);
    surface.ambient_occlusion = ambient_occlusion(in.position.xy, surface.diffuse);
    var color = phong_shade(surface);
    let count = searchlight_count();
    for (var index = 0u; index < count; index += 1u) {
        color += searchlight(surface, searchlight_at(index));
    }
    // Fog, tonemapping and debanding as the camera asks, like `PhongMaterial`.
    return camera_effects(vec4<f32>(color, material.base_color.a), in.world_position.xyz, in.position.xy);
}
