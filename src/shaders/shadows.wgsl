// Shadows (SPEC.md, "Shadows"): the visibility V ∈ [0, 1] of a light at a surface point,
// read from the light's shadow maps, and the factors it puts on the light's two terms.
#define_import_path bevy_phong::shadows

#import bevy_phong::bindings::{shadow_maps, shadow_sampler, shadow_views}
#import bevy_phong::types::{PhongLight, PhongShadowView, PhongSurface, SHADOW_PROJECTION_PERSPECTIVE}

// Widest filter, in texels at each side of the point: the margin the cube faces keep
// (`MAX_FILTER_RADIUS_TEXELS` in src/shadows/views.rs).
const MAX_FILTER_RADIUS: f32 = 16.0;

// Where a surface point lands in one shadow map.
struct MapPoint {
    // Position in the layer, in [0, uv_scale]².
    uv: vec2<f32>,
    // Reversed depth of the (biased) point.
    depth: f32,
    // World size of one texel at the point.
    texel: f32,
    // Whether the map covers the point; outside it nothing is in the way.
    inside: bool,
}

// The surface point moved by the light's biases (`normal_bias + widening` texels along the
// normal, `depth_bias` world units toward the light), projected into the map. A filter
// `widening` texels wide reads the surface that far to each side: lifting the point as far
// off the surface keeps a slanted or curved receiver from shadowing itself there.
fn map_point(view: PhongShadowView, surface: PhongSurface, to_light: vec3<f32>, widening: f32) -> MapPoint {
    var texel = view.texel_size;
    if view.projection == SHADOW_PROJECTION_PERSPECTIVE {
        texel *= max((view.clip_from_world * vec4<f32>(surface.position, 1.0)).w, 0.0);
    }
    let biased = surface.position + surface.normal * ((view.normal_bias + widening) * texel)
        + to_light * view.depth_bias;
    let clip = view.clip_from_world * vec4<f32>(biased, 1.0);
    let ndc = clip.xyz / clip.w;
    // `!(…)` rejects NaN too.
    let inside = clip.w > 0.0 && all(abs(ndc.xy) <= vec2<f32>(1.0)) && ndc.z >= 0.0 && ndc.z <= 1.0;
    let uv = (ndc.xy * vec2<f32>(0.5, -0.5) + 0.5) * view.uv_scale;
    return MapPoint(uv, ndc.z, texel, inside);
}

// 1 where the point is at least as near the light as the map's depth at `uv`, 0 where it is
// farther, filtered bilinearly over the four texels around `uv`. Reads stay inside the
// map's part of the layer.
fn compare(view: PhongShadowView, uv: vec2<f32>, depth: f32) -> f32 {
    let half_texel = 0.5 / f32(textureDimensions(shadow_maps).x);
    let clamped = clamp(uv, vec2<f32>(half_texel), vec2<f32>(view.uv_scale - half_texel));
    return textureSampleCompareLevel(shadow_maps, shadow_sampler, clamped, view.layer, depth);
}

// The comparison averaged over a 4×4 grid spanning `radius` texels at each side.
fn filtered(view: PhongShadowView, point: MapPoint, radius: f32) -> f32 {
    let step = radius / (2.0 * f32(textureDimensions(shadow_maps).x));
    var sum = 0.0;
    for (var i = 0; i < 4; i += 1) {
        for (var j = 0; j < 4; j += 1) {
            let offset = (vec2<f32>(f32(i), f32(j)) - 1.5) * step;
            sum += compare(view, point.uv + offset, point.depth);
        }
    }
    return sum / 16.0;
}

// Percentage-closer soft shadows, the filter's half-width in texels: the blockers' mean
// depth over the widest penumbra the light can cast at the point, then half the penumbra
// those blockers cast (`light_size · (d_receiver − d_blocker) / d_blocker` for a light at a
// point, `tan(angular radius) · (d_receiver − d_blocker)` for parallel light), in
// [1, MAX_FILTER_RADIUS]; 0 where no blocker is found (the point is lit).
fn penumbra_radius(view: PhongShadowView, point: MapPoint) -> f32 {
    let size = f32(textureDimensions(shadow_maps).x);
    let last = vec2<i32>(vec2<f32>(view.uv_scale * size - 1.0));
    var widest: f32;
    if view.projection == SHADOW_PROJECTION_PERSPECTIVE {
        widest = view.light_size * (1.0 / point.depth - 1.0);
    } else {
        widest = view.light_size * (1.0 - point.depth) * view.depth_range;
    }
    let search = clamp(0.5 * widest / point.texel, 1.0, MAX_FILTER_RADIUS);
    var blocker_sum = 0.0;
    var blockers = 0.0;
    for (var i = 0; i < 4; i += 1) {
        for (var j = 0; j < 4; j += 1) {
            let offset = (vec2<f32>(f32(i), f32(j)) - 1.5) * (search / 1.5);
            let texel = clamp(vec2<i32>(point.uv * size + offset), vec2<i32>(0), last);
            let depth = textureLoad(shadow_maps, texel, view.layer, 0);
            if depth > point.depth {
                blocker_sum += depth;
                blockers += 1.0;
            }
        }
    }
    if blockers == 0.0 {
        return 0.0;
    }
    let blocker = blocker_sum / blockers;
    var penumbra: f32;
    if view.projection == SHADOW_PROJECTION_PERSPECTIVE {
        // Distances along the view axis are near / depth.
        penumbra = view.light_size * (blocker / point.depth - 1.0);
    } else {
        penumbra = view.light_size * (blocker - point.depth) * view.depth_range;
    }
    return clamp(0.5 * penumbra / point.texel, 1.0, MAX_FILTER_RADIUS);
}

// V from one map.
fn view_visibility(view: PhongShadowView, surface: PhongSurface, to_light: vec3<f32>) -> f32 {
    let point = map_point(view, surface, to_light, 0.0);
    if !point.inside {
        return 1.0;
    }
    if view.light_size <= 0.0 {
        return compare(view, point.uv, point.depth);
    }
    let radius = penumbra_radius(view, point);
    if radius == 0.0 {
        return 1.0;
    }
    let widened = map_point(view, surface, to_light, radius);
    if !widened.inside {
        return filtered(view, point, radius);
    }
    return filtered(view, widened, radius);
}

// V from a directional light's cascades: the first whose slice holds the point's view
// depth, blended into the next over its overlap; past the last, 1.
fn cascade_visibility(first: u32, count: u32, surface: PhongSurface, to_light: vec3<f32>) -> f32 {
    let plane = shadow_views.views[first].view_plane;
    let depth = dot(plane.xyz, surface.position) + plane.w;
    for (var index = 0u; index < count; index += 1u) {
        let cascade = shadow_views.views[first + index];
        if depth < cascade.cascade_far {
            let visibility = view_visibility(cascade, surface, to_light);
            if depth <= cascade.cascade_blend_start {
                return visibility;
            }
            var next = 1.0;
            if index + 1u < count {
                next = view_visibility(shadow_views.views[first + index + 1u], surface, to_light);
            }
            let t = (depth - cascade.cascade_blend_start)
                / (cascade.cascade_far - cascade.cascade_blend_start);
            return mix(visibility, next, t);
        }
    }
    return 1.0;
}

// The face of a cube of maps around `center` that holds `position`: the major axis of the
// offset, in the order +X, −X, +Y, −Y, +Z, −Z.
fn cube_face(position: vec3<f32>, center: vec3<f32>) -> u32 {
    let offset = position - center;
    let size = abs(offset);
    if size.x >= size.y && size.x >= size.z {
        return select(1u, 0u, offset.x > 0.0);
    }
    if size.y >= size.z {
        return select(3u, 2u, offset.y > 0.0);
    }
    return select(5u, 4u, offset.z > 0.0);
}

// V of the light whose record's shadow slot is `shadow` (its first view plus one; 0: no
// shadow, V = 1) at the surface point, with `to_light` the unit vector toward the light and
// `light_position` its position (used by lights at a point).
fn light_visibility(shadow: u32, surface: PhongSurface, to_light: vec3<f32>, light_position: vec3<f32>) -> f32 {
    if shadow == 0u || !surface.receives_shadows || shadow > shadow_views.count {
        return 1.0;
    }
    let first = shadow - 1u;
    let head = shadow_views.views[first];
    if first + head.view_count > shadow_views.count {
        return 1.0;
    }
    if any(head.view_plane != vec4<f32>(0.0)) {
        return cascade_visibility(first, head.view_count, surface, to_light);
    }
    if head.view_count == 6u {
        let face = cube_face(surface.position, light_position);
        return view_visibility(shadow_views.views[first + face], surface, to_light);
    }
    return view_visibility(head, surface, to_light);
}

// The factors on a light's diffuse term and highlight at the surface point:
// (f_d + (1 − f_d)·V, f_s + (1 − f_s)·V), with f_d and f_s the fractions its settings leave
// in full shadow. (1, 1) for a light without shadows.
fn shadow_factors(shadow: u32, surface: PhongSurface, to_light: vec3<f32>, light_position: vec3<f32>) -> vec2<f32> {
    let visibility = light_visibility(shadow, surface, to_light, light_position);
    if visibility == 1.0 {
        return vec2<f32>(1.0);
    }
    let head = shadow_views.views[shadow - 1u];
    return mix(vec2<f32>(head.diffuse_in_shadow, head.specular_in_shadow), vec2<f32>(1.0), visibility);
}

// `light` with its diffuse and specular intensities scaled by its shadow factors.
fn shadowed(light: PhongLight, surface: PhongSurface, to_light: vec3<f32>) -> PhongLight {
    if light.shadow == 0u {
        return light;
    }
    let factors = shadow_factors(light.shadow, surface, to_light, light.position);
    var lit = light;
    lit.color *= factors.x;
    lit.specular *= factors.y;
    return lit;
}
