// The data the Phong shaders read: the light buffer, the material uniform and the surface
// point being shaded. The Rust side of each buffer layout is in `src/render/gpu_types.rs`
// and `src/material.rs`; a test checks that both agree.
#define_import_path bevy_phong::types

// One light of any kind (80 bytes). Fields a kind does not use are zero.
struct PhongLight {
    // World-space position (point, spot).
    position: vec3<f32>,
    // Cut-off distance; f32 max when unlimited (point, spot).
    range: f32,
    // Unit vector along which the light travels (directional, spot).
    direction: vec3<f32>,
    // 1 - cos(outer_angle) (spot); -1 for an empty cone.
    outer_versine: f32,
    // Diffuse intensity, linear RGB.
    color: vec3<f32>,
    // 1 / (cos(inner) - cos(outer)), or 0 for a hard cone edge (spot).
    cone_scale: f32,
    // Specular intensity, linear RGB.
    specular: vec3<f32>,
    // Exponent of the cos(θ)^exponent rim darkening (spot).
    spot_exponent: f32,
    // (constant, linear, quadratic) distance fall-off (point, spot).
    decay: vec3<f32>,
    // Low 16 bits: index of the light's first shadow view plus one (0: no shadow). High 16
    // bits: index of its cookie's record (after the lights) plus one (0: none;
    // `bevy_phong::cookies`).
    shadow: u32,
}

// The `PhongLight` whose 80 bytes are the words `a` to `e`, in order.
fn light_from_words(a: vec4<u32>, b: vec4<u32>, c: vec4<u32>, d: vec4<u32>, e: vec4<u32>) -> PhongLight {
    return PhongLight(
        bitcast<vec3<f32>>(a.xyz),
        bitcast<f32>(a.w),
        bitcast<vec3<f32>>(b.xyz),
        bitcast<f32>(b.w),
        bitcast<vec3<f32>>(c.xyz),
        bitcast<f32>(c.w),
        bitcast<vec3<f32>>(d.xyz),
        bitcast<f32>(d.w),
        bitcast<vec3<f32>>(e.xyz),
        e.w,
    );
}

// The light buffer (`GpuLightsHeader` in src/render/gpu_types.rs): the ambient and hemisphere
// lights, then `directional_count` directional lights, `point_count` point lights and `spot_count` spot lights of unlimited reach (every fragment
// loops over them), then `clustered_point_count` point lights and `clustered_spot_count`
// spot lights of finite reach (fragments find these through their view's clusters), in that
// order. No shadow-casting light is clustered.
struct PhongLights {
    // The ambient light plus the mean of the hemisphere light's sky and ground colors.
    ambient: vec3<f32>,
    directional_count: u32,
    point_count: u32,
    spot_count: u32,
    clustered_point_count: u32,
    clustered_spot_count: u32,
    // The hemisphere light's unit up direction, and half its sky minus its ground color
    // (both zero without one): it adds `hemisphere_half_difference · N·up`.
    hemisphere_up: vec3<f32>,
    hemisphere_half_difference: vec3<f32>,
    // Each light's `PhongLight` as five 16-byte words (`light_from_words`).
    lights: array<array<vec4<u32>, 5>>,
}

// Every view's light clusters (src/render/clusters.rs): `data` holds one record per view
// (`VIEW_WORDS`: `[key, first, tiles_x, tiles_y, slices, logarithmic, depth_scale,
// depth_bias]`), then each view's cluster records from its `first` word (x fastest, then y,
// then slice): `[first, point_count, spot_count, 0]`, where `data[first..]` are the indices
// (into `PhongLights.lights`) of the cluster's point lights, then of its spot lights.
// `u32` words per view record (`GpuClustersHeader::VIEW_WORDS`).
const CLUSTER_VIEW_WORDS: u32 = 8u;
// `u32` words per cluster record (`GpuClustersHeader::CLUSTER_WORDS`).
const CLUSTER_WORDS: u32 = 4u;

struct PhongLightClusters {
    // Views whose clusters `data` holds; 0 when no light is clustered.
    view_count: u32,
    padding: array<u32, 3>,
    data: array<u32>,
}

// One shadow map (`GpuShadowView` in src/shadows/gpu_types.rs). A light's views are
// consecutive; its first holds the count and the settings they share. A directional light
// has one set of cascades per camera, set after set. Depth is reversed.
struct PhongShadowView {
    // World space to the map's clip space.
    clip_from_world: mat4x4<f32>,
    // Directional cascades: dot(xyz, P) + w is P's view depth from the fitted camera.
    view_plane: vec4<f32>,
    // SHADOW_PROJECTION_ORTHOGRAPHIC or SHADOW_PROJECTION_PERSPECTIVE.
    projection: u32,
    // Layer of `shadow_maps`.
    layer: u32,
    // In the first view of a light's set: how many views the set has.
    view_count: u32,
    // The map's resolution over the layer's.
    uv_scale: f32,
    // World size of a texel: orthographic, everywhere; perspective, at distance 1.
    texel_size: f32,
    // Orthographic: world units from depth 1 to depth 0.
    depth_range: f32,
    // Perspective: the near distance (depth = near / distance along the view axis).
    near: f32,
    // World units the comparison point moves toward the light.
    depth_bias: f32,
    // Texels the comparison point moves along the normal.
    normal_bias: f32,
    // Soft shadows: perspective, the light's radius; orthographic, tan(angular radius).
    light_size: f32,
    // Directional cascades: the view depth where this cascade ends, and where it starts
    // blending into the next.
    cascade_far: f32,
    cascade_blend_start: f32,
    // Fractions of the diffuse term and of the highlight left in full shadow.
    diffuse_in_shadow: f32,
    specular_in_shadow: f32,
    // Directional cascades: the view key of the camera they were fitted to; 0 otherwise.
    camera_key: u32,
    // In the first view of a light's set: how many sets it has (one per camera for
    // directional cascades, each of `view_count` views; 1 otherwise).
    camera_count: u32,
}

// The shadow view buffer: `count` views.
struct PhongShadowViews {
    count: u32,
    padding: array<u32, 3>,
    views: array<PhongShadowView>,
}

const SHADOW_PROJECTION_ORTHOGRAPHIC: u32 = 0u;
const SHADOW_PROJECTION_PERSPECTIVE: u32 = 1u;

// `PhongMaterial` as the shader reads it.
struct PhongMaterialUniform {
    // k_d, linear RGB, and the alpha of the output.
    base_color: vec4<f32>,
    // k_s · specular_strength, linear RGB.
    specular: vec3<f32>,
    // The highlight exponent α (≥ 0).
    shininess: f32,
    // Added unlit color, linear RGB.
    emissive: vec3<f32>,
    // k_a.
    ambient_factor: f32,
    // SPECULAR_MODEL_* in bits 0..1; FLIP_NORMAL_MAP_Y; DOUBLE_SIDED.
    flags: u32,
    // With PHONG_ALPHA_MASK, fragments whose alpha is below this are discarded.
    alpha_cutoff: f32,
    // With PHONG_UV_TRANSFORM, the maps are sampled at (uv_transform · (uv, 1)).xy.
    uv_transform: mat3x3<f32>,
    // With PHONG_LIGHT_MAP, the light map's texel times this is added to the ambient light.
    light_map_intensity: f32,
    // With PHONG_AO_MAP, the indirect light is scaled by 1 + this · (ao texel.r − 1).
    ao_map_intensity: f32,
    // With PHONG_ENVIRONMENT_MAP, the environment's weight (times the specular map's red).
    reflectivity: f32,
    // With PHONG_ENV_REFRACTION, the ratio of refractive indices.
    refraction_ratio: f32,
    // With PHONG_BUMP_MAP, how far a height step of 1 between neighbouring texels tilts the
    // normal (1: 45°).
    bump_scale: f32,
    // The stylized modes' numbers (`PhongSurface.style`).
    style: vec4<f32>,
    // With PHONG_RIM or PHONG_RIM_LIT: the rim's color times strength, and its power.
    rim: vec4<f32>,
}

// A surface point, ready to be lit.
struct PhongSurface {
    // P, world space.
    position: vec3<f32>,
    // N: unit normal, or zero where the mesh's normal is degenerate (then only ambient and
    // emissive light remain).
    normal: vec3<f32>,
    // V: unit vector toward the camera, or zero when the camera is at P.
    view: vec3<f32>,
    // k_d, linear RGB.
    diffuse: vec3<f32>,
    // k_s · specular_strength, linear RGB.
    specular: vec3<f32>,
    // α.
    shininess: f32,
    // SPECULAR_MODEL_PHONG or SPECULAR_MODEL_BLINN_PHONG.
    specular_model: u32,
    // Whether shadows darken it (false for meshes with `NotShadowReceiver`).
    receives_shadows: bool,
    // Scales the ambient term per channel: 1, or the view's screen-space ambient occlusion
    // (`bevy_phong::camera_effects::ambient_occlusion`) times the material's AO map.
    ambient_occlusion: vec3<f32>,
    // Light baked into the material's light map, linear RGB, added to the ambient light
    // before k_d (zero without one).
    baked_light: vec3<f32>,
    // The stylized modes' numbers: (diffuse wrap, toon bands, toon band smoothing, toon
    // highlight smoothing); read with PHONG_DIFFUSE_WRAP, PHONG_DIFFUSE_TOON and
    // PHONG_SPECULAR_TOON only. (0, 1, 0, 0) by default.
    style: vec4<f32>,
    // The rim light: color times strength (linear RGB) and power; read with PHONG_RIM and
    // PHONG_RIM_LIT only. Zero by default.
    rim: vec4<f32>,
}

const SPECULAR_MODEL_PHONG: u32 = 0u;
const SPECULAR_MODEL_BLINN_PHONG: u32 = 1u;
// Flag bit of PhongMaterialUniform.flags: negate the normal map's green channel.
const FLIP_NORMAL_MAP_Y: u32 = 4u;
// Flag bit of PhongMaterialUniform.flags: negate the normal on back faces.
const DOUBLE_SIDED: u32 = 8u;
