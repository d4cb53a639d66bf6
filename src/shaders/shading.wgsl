// Lights a surface point with every light in the light buffer.
#define_import_path bevy_phong::shading

#import bevy_phong::bindings::material
#import bevy_phong::lighting::{LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT, incidence, light_of_kind, phong_surface, rim_factor, unshadowed_light}
#import bevy_phong::scene::{ambient_color, hemisphere_half_difference, hemisphere_up, cluster_view_count, cluster_word, clustered_point_count, clustered_spot_count, directional_count, light_at, point_count, spot_count}
#import bevy_phong::shadows::shadow_factors
#ifdef PHONG_LIGHT_COOKIES
#import bevy_phong::cookies::light_cookie
#endif
#import bevy_pbr::mesh_bindings::mesh
#import bevy_pbr::mesh_view_bindings::view
#import bevy_pbr::mesh_types::MESH_FLAGS_SHADOW_RECEIVER_BIT
#import bevy_phong::types::{CLUSTER_VIEW_WORDS, CLUSTER_WORDS, PhongLight, PhongSurface}
#import bevy_phong::texture_maps::MappedMaterial
#import bevy_phong::camera_effects::ambient_occlusion
#import bevy_pbr::forward_io::VertexOutput
#import bevy_phong::view_key::view_key

// The surface point `position` with the interpolated mesh normal, seen from `camera`,
// made of the bound material.
fn material_surface(position: vec3<f32>, normal: vec3<f32>, camera: vec3<f32>) -> PhongSurface {
    var surface = phong_surface(
        position,
        normal,
        camera,
        material.base_color.rgb,
        material.specular,
        material.shininess,
        material.flags & 3u,
    );
    surface.style = material.style;
    surface.rim = material.rim;
    return surface;
}

// Whether the mesh drawn as `instance_index` receives shadows (it has no
// `NotShadowReceiver`); a fragment shader sets `PhongSurface.receives_shadows` from it.
fn receives_shadows(instance_index: u32) -> bool {
    return (mesh[instance_index].flags & MESH_FLAGS_SHADOW_RECEIVER_BIT) != 0u;
}

// (ambient + hemisphere(N)) ⊙ k_a ⊙ k_d, times the surface's ambient occlusion
fn ambient_light(surface: PhongSurface) -> vec3<f32> {
    var ambient = ambient_color();
#ifdef PHONG_HEMISPHERE
    // The hemisphere light's `ground + (sky − ground)·(1 + N·up)/2`, its mean in `ambient`.
    ambient += hemisphere_half_difference() * dot(surface.normal, hemisphere_up());
#endif
    let indirect = ambient * material.ambient_factor + surface.baked_light;
    return indirect * surface.diffuse * surface.ambient_occlusion;
}

// Σ over every light that reaches the surface point: the directional lights, the point and
// spot lights of unlimited reach, and those of the point's cluster. One loop lights every
// kind (see `incidence`); while some light casts shadows (PHONG_SHADOWS), each light's
// terms are scaled by its shadow factors, and while some light has a cookie
// (PHONG_LIGHT_COOKIES), its colors by the cookie's tint.
fn direct_lights(surface: PhongSurface) -> vec3<f32> {
    let point_start = directional_count();
    let spot_start = point_start + point_count();
    let end = spot_start + spot_count();
    var color = vec3<f32>(0.0);
    for (var index = 0u; index < end; index += 1u) {
        var light = light_at(index);
#ifdef PHONG_LIGHT_COOKIES
        // The index of the cookie's record plus one in the high half of `shadow`
        // (`GpuLight::shadow`).
        let cookie = light.shadow >> 16u;
        if cookie != 0u {
            let tint = light_cookie(cookie - 1u, surface.position);
            light.color *= tint;
            light.specular *= tint;
        }
#endif
        let kind = select(select(LIGHT_DIRECTIONAL, LIGHT_POINT, index >= point_start), LIGHT_SPOT, index >= spot_start);
        let arriving = incidence(surface, light, kind);
#ifdef PHONG_SHADOWS
        let factors = shadow_factors(light.shadow & 0xffffu, surface, arriving.to_light, light.position);
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

// The lights of finite reach that may reach a point, as a list of entries: those listed in
// its cluster of the view being drawn, or, where the view has no clusters (a camera that
// appeared after the lights were listed, a key collision), every one. Entries
// [first, spot) are point lights, [spot, end) spot lights; `clustered_light` gives an
// entry's light.
struct ClusteredList {
    first: u32,
    spot: u32,
    end: u32,
    // Whether the entries are slots of a cluster's list (else light indices).
    listed: bool,
}

// The clustered lights that may reach `position`; the clustered lights start at index
// `start` of the light buffer.
fn clustered_list(start: u32, position: vec3<f32>) -> ClusteredList {
    let record = view_record();
    if record == NO_VIEW_RECORD {
        let spot = start + clustered_point_count();
        return ClusteredList(start, spot, spot + clustered_spot_count(), false);
    }
    let cluster = cluster_record(record, position);
    let first = cluster_word(cluster);
    let spot = first + cluster_word(cluster + 1u);
    return ClusteredList(first, spot, spot + cluster_word(cluster + 2u), true);
}

// The light of entry `entry` of `list`.
fn clustered_light(list: ClusteredList, entry: u32) -> PhongLight {
    return light_at(select(entry, cluster_word(entry), list.listed));
}

// Σ over the point and spot lights of finite reach that may reach the surface point
// (`clustered_list`); the clustered lights start at index `start` of the light buffer.
fn clustered_lights(surface: PhongSurface, start: u32) -> vec3<f32> {
    let list = clustered_list(start, surface.position);
    var color = vec3<f32>(0.0);
    for (var entry = list.first; entry < list.end; entry += 1u) {
        let kind = select(LIGHT_POINT, LIGHT_SPOT, entry >= list.spot);
        color += unshadowed_light(surface, clustered_light(list, entry), kind);
    }
    return color;
}

// The surface point a `PhongMaterial` fragment lights: the material as its maps give it at
// the fragment (`mapped`), seen from the view's camera, with the mesh's shadow receiving and
// the view's ambient occlusion.
fn fragment_surface(in: VertexOutput, mapped: MappedMaterial) -> PhongSurface {
    var surface = phong_surface(
        in.world_position.xyz,
        mapped.normal,
        view.world_position,
        mapped.base_color.rgb,
        mapped.specular,
        material.shininess,
        material.flags & 3u,
    );
    surface.receives_shadows = receives_shadows(in.instance_index);
    surface.ambient_occlusion = ambient_occlusion(in.position.xy, mapped.base_color.rgb) * mapped.occlusion;
    surface.baked_light = mapped.baked_light;
    surface.style = material.style;
    surface.rim = material.rim;
    return surface;
}

// SPEC.md's whole equation: emissive + ambient + Σ lights, with the given emissive color.
fn lit_color(surface: PhongSurface, emissive: vec3<f32>) -> vec3<f32> {
    var color = emissive + ambient_light(surface) + direct_lights(surface);
#ifdef PHONG_RIM
    // The rim everywhere, added as the emissive color is.
    color += surface.rim.rgb * rim_factor(surface);
#endif
    return color;
}

// SPEC.md's whole equation for the bound material without its texture maps.
fn phong_shade(surface: PhongSurface) -> vec3<f32> {
    return lit_color(surface, material.emissive);
}
