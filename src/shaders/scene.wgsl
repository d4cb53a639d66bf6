// The scene data every Phong material reads (lights, light clusters, shadow views), through
// accessors: the rest of the shaders never name the bindings that hold it, so that where
// storage buffers are missing (WebGL2) the same data can be read from elsewhere without
// touching them. See docs/design/webgl2.md.
#define_import_path bevy_phong::scene

#import bevy_phong::types::{PhongLight, PhongShadowView, light_from_words}
#if AVAILABLE_STORAGE_BUFFER_BINDINGS < 8
#import bevy_phong::bindings::scene_data
#import bevy_phong::data_texture::{data_light, data_texel}
#else
#import bevy_phong::bindings::{light_clusters, lights, shadow_views}
#endif

#if AVAILABLE_STORAGE_BUFFER_BINDINGS < 8
// Texel `index` of the scene data texture (src/render/scene_texture.rs).
fn texel(index: u32) -> vec4<u32> {
    return data_texel(scene_data, index);
}

// The first texel of region `region` (1 clusters, 2 shadow views), from texel 0.
fn region_start(region: u32) -> u32 {
    return texel(0u)[region];
}

// The lights' region always follows the directory texel.
const LIGHTS_START: u32 = 1u;

// The light buffer's header is texels 0–3 of its region (`GpuLightsHeader`), its records 5
// texels each from texel 4.
fn ambient_color() -> vec3<f32> {
    return bitcast<vec3<f32>>(texel(LIGHTS_START).xyz);
}

fn hemisphere_up() -> vec3<f32> {
    return bitcast<vec3<f32>>(texel(LIGHTS_START + 2u).xyz);
}

fn hemisphere_half_difference() -> vec3<f32> {
    return bitcast<vec3<f32>>(texel(LIGHTS_START + 3u).xyz);
}

fn directional_count() -> u32 {
    return texel(LIGHTS_START).w;
}

fn point_count() -> u32 {
    return texel(LIGHTS_START + 1u).x;
}

fn spot_count() -> u32 {
    return texel(LIGHTS_START + 1u).y;
}

fn clustered_point_count() -> u32 {
    return texel(LIGHTS_START + 1u).z;
}

fn clustered_spot_count() -> u32 {
    return texel(LIGHTS_START + 1u).w;
}

fn light_at(index: u32) -> PhongLight {
    return data_light(scene_data, LIGHTS_START + 4u + 5u * index);
}

// The clusters' header is texel 0 of its region (`GpuClustersHeader`), its words four to
// a texel from texel 1.
fn cluster_view_count() -> u32 {
    return texel(region_start(1u)).x;
}

fn cluster_word(index: u32) -> u32 {
    return texel(region_start(1u) + 1u + index / 4u)[index % 4u];
}

// The shadow views' header is texel 0 of its region, each view 9 texels from texel 1.
fn shadow_view_count() -> u32 {
    return texel(region_start(2u)).x;
}

fn shadow_view_at(index: u32) -> PhongShadowView {
    let first = region_start(2u) + 1u + 9u * index;
    let plane = texel(first + 4u);
    let a = texel(first + 5u);
    let b = texel(first + 6u);
    let c = texel(first + 7u);
    let d = texel(first + 8u);
    return PhongShadowView(
        mat4x4<f32>(
            bitcast<vec4<f32>>(texel(first)),
            bitcast<vec4<f32>>(texel(first + 1u)),
            bitcast<vec4<f32>>(texel(first + 2u)),
            bitcast<vec4<f32>>(texel(first + 3u)),
        ),
        bitcast<vec4<f32>>(plane),
        a.x,
        a.y,
        a.z,
        bitcast<f32>(a.w),
        bitcast<f32>(b.x),
        bitcast<f32>(b.y),
        bitcast<f32>(b.z),
        bitcast<f32>(b.w),
        bitcast<f32>(c.x),
        bitcast<f32>(c.y),
        bitcast<f32>(c.z),
        bitcast<f32>(c.w),
        bitcast<f32>(d.x),
        bitcast<f32>(d.y),
        d.z,
        d.w,
    );
}
#else
// The ambient light plus the mean of the hemisphere light's sky and ground colors, linear
// RGB.
fn ambient_color() -> vec3<f32> {
    return lights.ambient;
}

// The hemisphere light's unit up direction (zero without one).
fn hemisphere_up() -> vec3<f32> {
    return lights.hemisphere_up;
}

// Half the hemisphere light's sky color minus its ground color (zero without one).
fn hemisphere_half_difference() -> vec3<f32> {
    return lights.hemisphere_half_difference;
}

// How many directional, point and spot lights of unlimited reach the light buffer holds, in
// that order from index 0 (the clustered lights follow them).
fn directional_count() -> u32 {
    return lights.directional_count;
}

fn point_count() -> u32 {
    return lights.point_count;
}

fn spot_count() -> u32 {
    return lights.spot_count;
}

// How many point and spot lights of finite reach follow those, in that order (clustered).
fn clustered_point_count() -> u32 {
    return lights.clustered_point_count;
}

fn clustered_spot_count() -> u32 {
    return lights.clustered_spot_count;
}

// The light at `index` in the light buffer, read as its five 16-byte words: lavapipe reads
// a storage buffer one pixel and one load at a time, and a record read field by field takes
// ten loads (docs/design/performance.md, "Reading the records").
fn light_at(index: u32) -> PhongLight {
    return light_from_words(
        lights.lights[index][0],
        lights.lights[index][1],
        lights.lights[index][2],
        lights.lights[index][3],
        lights.lights[index][4],
    );
}

// Word `word` (0 to 4) of record `index` of the light buffer: past the lights, the cookies'
// records (`GpuCookie`).
fn record_word(index: u32, word: u32) -> vec4<u32> {
    return lights.lights[index][word];
}

// How many views have clusters; 0 when no light is clustered.
fn cluster_view_count() -> u32 {
    return light_clusters.view_count;
}

// Word `index` of the clusters' data (`PhongLightClusters.data`).
fn cluster_word(index: u32) -> u32 {
    return light_clusters.data[index];
}

// How many shadow views the frame has.
fn shadow_view_count() -> u32 {
    return shadow_views.count;
}

// Shadow view `index`.
fn shadow_view_at(index: u32) -> PhongShadowView {
    return shadow_views.views[index];
}
#endif
