// Lights a surface point with every light in the light buffer.
#define_import_path bevy_phong::shading

#import bevy_phong::bindings::material
#import bevy_phong::lighting::{LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT, incidence, light_of_kind, phong_surface, unshadowed_light}
#import bevy_phong::scene::{ambient_color, cluster_view_count, cluster_word, clustered_point_count, clustered_spot_count, directional_count, light_at, point_count, spot_count}
#import bevy_phong::shadows::shadow_factors
#import bevy_pbr::mesh_bindings::mesh
#import bevy_pbr::mesh_view_bindings::view
#import bevy_pbr::mesh_types::MESH_FLAGS_SHADOW_RECEIVER_BIT
#import bevy_phong::types::{CLUSTER_VIEW_WORDS, CLUSTER_WORDS, PhongSurface}
#import bevy_phong::view_key::view_key

// The surface point `position` with the interpolated mesh normal, seen from `camera`,
// made of the bound material.
fn material_surface(position: vec3<f32>, normal: vec3<f32>, camera: vec3<f32>) -> PhongSurface {
    return phong_surface(
        position,
        normal,
        camera,
        material.base_color.rgb,
        material.specular,
        material.shininess,
        material.flags & 3u,
    );
}

// Whether the mesh drawn as `instance_index` receives shadows (it has no
// `NotShadowReceiver`); a fragment shader sets `PhongSurface.receives_shadows` from it.
fn receives_shadows(instance_index: u32) -> bool {
    return (mesh[instance_index].flags & MESH_FLAGS_SHADOW_RECEIVER_BIT) != 0u;
}

// ambient ⊙ k_a ⊙ k_d, times the surface's ambient occlusion
fn ambient_light(surface: PhongSurface) -> vec3<f32> {
    return ambient_color() * material.ambient_factor * surface.diffuse * surface.ambient_occlusion;
}

// Σ over every light that reaches the surface point: the directional lights, the point and
// spot lights of unlimited reach, and those of the point's cluster. One loop lights every
// kind (see `incidence`); while some light casts shadows (PHONG_SHADOWS), each light's
// terms are scaled by its shadow factors.
fn direct_lights(surface: PhongSurface) -> vec3<f32> {
    let point_start = directional_count();
    let spot_start = point_start + point_count();
    let end = spot_start + spot_count();
    var color = vec3<f32>(0.0);
    for (var index = 0u; index < end; index += 1u) {
        let light = light_at(index);
        let kind = select(select(LIGHT_DIRECTIONAL, LIGHT_POINT, index >= point_start), LIGHT_SPOT, index >= spot_start);
        let arriving = incidence(surface, light, kind);
#ifdef PHONG_SHADOWS
        let factors = shadow_factors(light.shadow, surface, arriving.to_light, light.position);
#else
        let factors = vec2<f32>(1.0);
#endif
        color += light_of_kind(surface, light, kind, arriving, factors);
    }
    return color + clustered_lights(surface, end);
}

// What `view_record` returns for a view without clusters.
const NO_VIEW_RECORD: u32 = 0xffffffffu;

// The first word of the cluster data's record of the view being drawn, or
// `NO_VIEW_RECORD` for a view without clusters.
fn view_record() -> u32 {
    let end = CLUSTER_VIEW_WORDS * cluster_view_count();
    if end == 0u {
        return NO_VIEW_RECORD;
    }
    let key = view_key();
    for (var record = 0u; record < end; record += CLUSTER_VIEW_WORDS) {
        if cluster_word(record) == key {
            return record;
        }
    }
    return NO_VIEW_RECORD;
}

// The first word of the record of the cluster that holds the world position `position` in
// the view whose record starts at word `record` (src/render/clusters.rs): its tile from the
// unjittered normalized device coordinates, its slice from the depth in front of the camera.
fn cluster_record(record: u32, position: vec3<f32>) -> u32 {
    let first = cluster_word(record + 1u);
    let tiles = vec2<u32>(cluster_word(record + 2u), cluster_word(record + 3u));
    let slices = cluster_word(record + 4u);
    let logarithmic = cluster_word(record + 5u) != 0u;
    let depth_scale = bitcast<f32>(cluster_word(record + 6u));
    let depth_bias = bitcast<f32>(cluster_word(record + 7u));
    let world = vec4<f32>(position, 1.0);
    let clip = view.unjittered_clip_from_world * world;
    let ndc = clip.xy / clip.w;
    let tile = min(vec2<u32>(max((ndc * 0.5 + 0.5) * vec2<f32>(tiles), vec2<f32>(0.0))), tiles - 1u);
    let depth = -(view.view_from_world * world).z;
    let f = select(depth, log2(max(depth, 1e-30)), logarithmic);
    let slice = min(u32(max(f * depth_scale + depth_bias, 0.0)), slices - 1u);
    return first + CLUSTER_WORDS * (tile.x + tiles.x * (tile.y + tiles.y * slice));
}

// Σ over the point and spot lights of finite reach that may reach the surface point: those
// listed in its cluster of the view being drawn, or every one where the view has no
// clusters (a camera that appeared after the lights were listed, a key collision). The
// clustered lights start at index `start` of the light buffer.
fn clustered_lights(surface: PhongSurface, start: u32) -> vec3<f32> {
    let record = view_record();
    var color = vec3<f32>(0.0);
    if record == NO_VIEW_RECORD {
        let spot_start = start + clustered_point_count();
        let end = spot_start + clustered_spot_count();
        for (var index = start; index < end; index += 1u) {
            let kind = select(LIGHT_POINT, LIGHT_SPOT, index >= spot_start);
            color += unshadowed_light(surface, light_at(index), kind);
        }
        return color;
    }
    let cluster = cluster_record(record, surface.position);
    let first = cluster_word(cluster);
    let spot_slot = first + cluster_word(cluster + 1u);
    let end = spot_slot + cluster_word(cluster + 2u);
    for (var slot = first; slot < end; slot += 1u) {
        let kind = select(LIGHT_POINT, LIGHT_SPOT, slot >= spot_slot);
        color += unshadowed_light(surface, light_at(cluster_word(slot)), kind);
    }
    return color;
}

// SPEC.md's whole equation: emissive + ambient + Σ lights, with the given emissive color.
fn lit_color(surface: PhongSurface, emissive: vec3<f32>) -> vec3<f32> {
    return emissive + ambient_light(surface) + direct_lights(surface);
}

// SPEC.md's whole equation for the bound material without its texture maps.
fn phong_shade(surface: PhongSurface) -> vec3<f32> {
    return lit_color(surface, material.emissive);
}
