// The bindings of `PhongMaterial` in the material bind group: the material's own (0, 3–10,
// 14–23, 27; 24–26 in the vertex stage: bevy_phong::displacement)
// and the plugin's scene data (1, 2, 11–13, 28; `PhongSceneBindings`).
#define_import_path bevy_phong::bindings

#import bevy_phong::types::{PhongLightClusters, PhongLights, PhongMaterialUniform, PhongShadowViews}

@group(#{MATERIAL_BIND_GROUP}) @binding(0) var<uniform> material: PhongMaterialUniform;
#if AVAILABLE_STORAGE_BUFFER_BINDINGS < 8
// Where a stage has fewer than 8 storage buffers (WebGL2 has none; Bevy's pipeline cache
// gives every shader the device's count): the lights, the clusters and the shadow views in one
// texture (src/render/scene_texture.rs), read through `bevy_phong::scene`. The 8 is
// `PhongSceneBindings::STORAGE_BUFFERS_NEEDED`.
@group(#{MATERIAL_BIND_GROUP}) @binding(1) var scene_data: texture_2d<u32>;
#else
@group(#{MATERIAL_BIND_GROUP}) @binding(1) var<storage, read> lights: PhongLights;
@group(#{MATERIAL_BIND_GROUP}) @binding(2) var<storage, read> light_clusters: PhongLightClusters;
@group(#{MATERIAL_BIND_GROUP}) @binding(11) var<storage, read> shadow_views: PhongShadowViews;
// The light cookies' images, a layer each (src/render/cookie_atlas.rs), read texel by texel
// by `bevy_phong::cookies`.
@group(#{MATERIAL_BIND_GROUP}) @binding(28) var cookie_atlas: texture_2d_array<f32>;
#endif
@group(#{MATERIAL_BIND_GROUP}) @binding(3) var base_color_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(4) var base_color_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(5) var specular_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(6) var specular_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(7) var emissive_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(8) var emissive_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(9) var normal_map_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(10) var normal_map_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(14) var light_map_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(15) var light_map_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(16) var ao_map_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(17) var ao_map_sampler: sampler;
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
// Left out where the scene data is in a texture (WebGL2: 16 textures a stage, shared with
// Bevy's view): `render::binds_every_map`.
@group(#{MATERIAL_BIND_GROUP}) @binding(18) var alpha_map_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(19) var alpha_map_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(20) var environment_map: texture_cube<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(21) var environment_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(22) var bump_map_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(23) var bump_map_sampler: sampler;
// Read texel by texel (nearest, as three.js's `gradientMap`): no sampler.
@group(#{MATERIAL_BIND_GROUP}) @binding(27) var toon_ramp_texture: texture_2d<f32>;
#endif
@group(#{MATERIAL_BIND_GROUP}) @binding(12) var shadow_maps: texture_depth_2d_array;
@group(#{MATERIAL_BIND_GROUP}) @binding(13) var shadow_sampler: sampler_comparison;
