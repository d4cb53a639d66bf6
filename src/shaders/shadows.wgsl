// Shadows (SPEC.md, "Shadows"): the visibility V ∈ [0, 1] of a light at a surface point,
// read from the light's shadow maps, and the factors it puts on the light's two terms.
#define_import_path bevy_phong::shadows

#import bevy_phong::bindings::{shadow_maps, shadow_sampler}
#import bevy_phong::scene::{shadow_view_at, shadow_view_count}
#import bevy_phong::types::{PhongLight, PhongShadowView, PhongSurface, SHADOW_PROJECTION_PERSPECTIVE}
#import bevy_phong::view_key::view_key

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
    // Perspective: the texel grows with the point's distance along the view axis, the clip
    // w (the matrix's last row times the point).
    let m = view.clip_from_world;
    let w = dot(vec4<f32>(m[0].w, m[1].w, m[2].w, m[3].w), vec4<f32>(surface.position, 1.0));
    let perspective = view.projection == SHADOW_PROJECTION_PERSPECTIVE;
    let texel = view.texel_size * select(1.0, max(w, 0.0), perspective);
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

#ifdef PHONG_SOFT_SHADOWS
// The comparison averaged over a `grid`×`grid` square of taps spanning `radius` texels at
// each side of `uv` (`grid` 1: one tap at `uv`; 0: no tap, and 0).
//
// What runs follows what is needed through loop trip counts, never through a branch around
// a fixed amount of work: a GPU skips a branch that no pixel of a group takes, but a SIMD
// rasterizer on the CPU (lavapipe) runs both sides of every branch under a mask and saves
// work only where a loop ends early.
fn filtered(view: PhongShadowView, uv: vec2<f32>, depth: f32, radius: f32, grid: i32) -> f32 {
    let step = radius / (2.0 * f32(textureDimensions(shadow_maps).x));
    let center = 0.5 * f32(grid - 1);
    let taps = grid * grid;
    var sum = 0.0;
    for (var tap = 0; tap < taps; tap += 1) {
        let offset = (vec2<f32>(f32(tap / grid), f32(tap % grid)) - center) * step;
        sum += compare(view, uv + offset, depth);
    }
    return sum / f32(max(taps, 1));
}

// Percentage-closer soft shadows, the filter's half-width in texels: the blockers' mean
// depth over the widest penumbra the light can cast at the point, then half the penumbra
// those blockers cast (`light_size · (d_receiver − d_blocker) / d_blocker` for a light at a
// point, `tan(angular radius) · (d_receiver − d_blocker)` for parallel light), in
// [1, MAX_FILTER_RADIUS]; 0 where no blocker is found (the point is lit) and for a light
// without size (it searches nothing).
fn penumbra_radius(view: PhongShadowView, point: MapPoint) -> f32 {
    let size = f32(textureDimensions(shadow_maps).x);
    let last = vec2<i32>(vec2<f32>(view.uv_scale * size - 1.0));
    let perspective = view.projection == SHADOW_PROJECTION_PERSPECTIVE;
    let widest = select(
        view.light_size * (1.0 - point.depth) * view.depth_range,
        view.light_size * (1.0 / point.depth - 1.0),
        perspective,
    );
    let search = clamp(0.5 * widest / point.texel, 1.0, MAX_FILTER_RADIUS);
    // A 4×4 grid of texels for a light with a size.
    let taps = select(0, 16, view.light_size > 0.0);
    var blocker_sum = 0.0;
    var blockers = 0.0;
    for (var tap = 0; tap < taps; tap += 1) {
        let offset = (vec2<f32>(f32(tap / 4), f32(tap % 4)) - 1.5) * (search / 1.5);
        let texel = clamp(vec2<i32>(point.uv * size + offset), vec2<i32>(0), last);
        let depth = textureLoad(shadow_maps, texel, view.layer, 0);
        let blocks = depth > point.depth;
        blocker_sum += select(0.0, depth, blocks);
        blockers += select(0.0, 1.0, blocks);
    }
    let blocker = blocker_sum / max(blockers, 1.0);
    let penumbra = select(
        view.light_size * (blocker - point.depth) * view.depth_range,
        // Distances along the view axis are near / depth.
        view.light_size * (blocker / point.depth - 1.0),
        perspective,
    );
    return select(clamp(0.5 * penumbra / point.texel, 1.0, MAX_FILTER_RADIUS), 0.0, blockers == 0.0);
}
#endif

// V from one map, 1 outside it: one bilinear comparison for a light without size; for one
// with a size (compiled in only while some light has one: PHONG_SOFT_SHADOWS), PCSS's
// filter around the point lifted off the surface by the filter's width (around the point
// itself where that leaves the map), and 1 where no blocker was found.
fn view_visibility(view: PhongShadowView, surface: PhongSurface, to_light: vec3<f32>) -> f32 {
    let point = map_point(view, surface, to_light, 0.0);
#ifdef PHONG_SOFT_SHADOWS
    let soft = view.light_size > 0.0;
    let radius = penumbra_radius(view, point);
    let widened = map_point(view, surface, to_light, radius);
    let uv = select(point.uv, widened.uv, widened.inside);
    let depth = select(point.depth, widened.depth, widened.inside);
    let grid = select(1, select(0, 4, radius > 0.0), soft);
    let visibility = select(filtered(view, uv, depth, radius, grid), 1.0, soft && radius == 0.0);
#else
    let visibility = compare(view, point.uv, point.depth);
#endif
    return select(visibility, 1.0, !point.inside);
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

// Where the light whose record's shadow slot is `shadow` (its first view plus one; 0: no
// shadow) keeps the views that the surface point reads: the first one's index (0 where it
// has none: a valid index, read and discarded), and whether it has views in the buffer that
// the point reads.
struct ShadowSlot {
    first: u32,
    read: bool,
}

fn shadow_slot(shadow: u32, surface: PhongSurface) -> ShadowSlot {
    let listed = shadow != 0u && shadow <= shadow_view_count();
    let light_first = select(0u, shadow - 1u, listed);
    let head = shadow_view_at(light_first);
    // At most MAX_SHADOW_VIEWS sets, however the record reads when nothing is listed.
    let sets = select(1u, clamp(head.camera_count, 1u, 256u), listed);
    let views = head.view_count * sets;
    let read = listed && surface.receives_shadows && light_first + views <= shadow_view_count();
    return ShadowSlot(camera_views(light_first, head.view_count, sets), read);
}

// The first view of the set fitted to the view being drawn, of a light whose `sets` sets of
// `set_size` views start at `first` (a directional light's cascades, one set per camera,
// each view marked with its camera's view key): the set whose key is the view's, else the
// first (a view that appeared after the gather). A light with one set is `first` itself,
// read without a loop trip.
fn camera_views(first: u32, set_size: u32, sets: u32) -> u32 {
    let key = view_key();
    var chosen = first;
    for (var index = 1u; index < sets; index += 1u) {
        let candidate = first + index * set_size;
        chosen = select(chosen, candidate, shadow_view_at(candidate).camera_key == key);
    }
    return chosen;
}

// V at the surface point of the light whose views start at `first`, `head` being the first,
// with `to_light` the unit vector toward the light and `light_position` its position (used
// by lights at a point).
//
// The view is chosen by arithmetic and read once (see `filtered` on branches): a
// directional light's cascade is the first whose slice holds the point's view depth (past
// the last, V = 1), blended into the next over its overlap; a cube's face is the major
// axis of the offset from the light; a single view is itself.
fn visibility_from(first: u32, head: PhongShadowView, surface: PhongSurface, to_light: vec3<f32>, light_position: vec3<f32>) -> f32 {
    let view_count = max(head.view_count, 1u);
    let cascaded = any(head.view_plane != vec4<f32>(0.0));
    let depth = dot(head.view_plane.xyz, surface.position) + head.view_plane.w;
    let cascades = select(0u, view_count, cascaded);
    var index = 0u;
    for (; index < cascades; index += 1u) {
        if depth < shadow_view_at(first + index).cascade_far {
            break;
        }
    }
    let beyond_cascades = cascaded && index == cascades;
    let face = select(0u, cube_face(surface.position, light_position), view_count == 6u);
    index = min(select(face, index, cascaded), view_count - 1u);
    let blend_start = shadow_view_at(first + index).cascade_blend_start;
    let blend_end = shadow_view_at(first + index).cascade_far;
    let blends = cascaded && depth > blend_start;
    let t = select(0.0, (depth - blend_start) / (blend_end - blend_start), blends);
    // This view, and where it blends the next (past the last, 1).
    var visibility = 0.0;
    let samples = select(1u, 2u, blends);
    for (var sample = 0u; sample < samples; sample += 1u) {
        let next = index + sample;
        let sampled = view_visibility(shadow_view_at(first + min(next, view_count - 1u)), surface, to_light);
        visibility += select(1.0 - t, t, sample == 1u) * select(1.0, sampled, next < view_count);
    }
    return select(visibility, 1.0, beyond_cascades);
}

// V of the light whose record's shadow slot is `shadow` at the surface point, with
// `to_light` the unit vector toward the light and `light_position` its position (used by
// lights at a point); 1 for a light without shadows.
fn light_visibility(shadow: u32, surface: PhongSurface, to_light: vec3<f32>, light_position: vec3<f32>) -> f32 {
    let slot = shadow_slot(shadow, surface);
    let head = shadow_view_at(slot.first);
    return select(1.0, visibility_from(slot.first, head, surface, to_light, light_position), slot.read);
}

// The factors on a light's diffuse term and highlight at the surface point:
// (f_d + (1 − f_d)·V, f_s + (1 − f_s)·V), with f_d and f_s the fractions its settings leave
// in full shadow. (1, 1) for a light without shadows.
fn shadow_factors(shadow: u32, surface: PhongSurface, to_light: vec3<f32>, light_position: vec3<f32>) -> vec2<f32> {
    let slot = shadow_slot(shadow, surface);
    let head = shadow_view_at(slot.first);
    let visibility = visibility_from(slot.first, head, surface, to_light, light_position);
    let factors = mix(vec2<f32>(head.diffuse_in_shadow, head.specular_in_shadow), vec2<f32>(1.0), visibility);
    return select(vec2<f32>(1.0), factors, slot.read);
}
