// The material's colors and normal at a fragment, with its vertex colors and texture maps
// applied. Each map is sampled only in the shader variant whose def names it (see
// `PhongMaterialKey`), at the UVs `map_uv` gives; vertex colors only on meshes that have
// them (Bevy's `VERTEX_COLORS`).
#define_import_path bevy_phong::texture_maps

#import bevy_pbr::forward_io::VertexOutput
#import bevy_phong::bindings::{
    material,
    base_color_texture, base_color_sampler,
    specular_texture, specular_sampler,
    emissive_texture, emissive_sampler,
    light_map_texture, light_map_sampler,
    ao_map_texture, ao_map_sampler,
}
#ifdef PHONG_ALPHA_MAP
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
#import bevy_phong::bindings::{alpha_map_texture, alpha_map_sampler}
#endif
#endif
#import bevy_phong::normals::lit_normal
#import bevy_phong::uv::map_uv
#ifdef LIGHTMAP
#import bevy_pbr::lightmap::lightmap
#endif

// What the lighting equation takes from the material at one fragment.
struct MappedMaterial {
    // k_d ⊙ vertex color ⊙ base color map, with the output alpha (times the alpha map's
    // green channel).
    base_color: vec4<f32>,
    // k_s · strength ⊙ specular map.
    specular: vec3<f32>,
    // emissive ⊙ emissive map.
    emissive: vec3<f32>,
    // The surface normal, any length (normalized by `phong_surface`): `lit_normal`'s.
    normal: vec3<f32>,
    // The light map's light and Bevy's `Lightmap`'s, times the light map intensity (zero
    // without either).
    baked_light: vec3<f32>,
    // The AO map's factor on the indirect light, 1 + intensity · (texel.r − 1) (1 without one).
    occlusion: f32,
    // The specular map's red channel, which weights the environment map (1 without one).
    environment_mask: f32,
}

// `is_front`: the fragment's `@builtin(front_facing)`.
fn mapped_material(in: VertexOutput, is_front: bool) -> MappedMaterial {
    var uv = vec2<f32>(0.0);
#ifdef VERTEX_UVS_A
    uv = map_uv(in.uv);
#endif
    var tangent = vec4<f32>(0.0);
#ifdef VERTEX_TANGENTS
    tangent = in.world_tangent;
#endif
    let normal = lit_normal(in.world_normal, in.world_position.xyz, tangent, uv, is_front);
    var mapped = MappedMaterial(
        material.base_color, material.specular, material.emissive, normal, vec3<f32>(0.0), 1.0, 1.0,
    );
#ifdef VERTEX_COLORS
    mapped.base_color *= in.color;
#endif
#ifdef PHONG_BASE_COLOR_TEXTURE
    mapped.base_color *= textureSample(base_color_texture, base_color_sampler, uv);
#endif
#ifdef PHONG_SPECULAR_TEXTURE
    let specular_texel = textureSample(specular_texture, specular_sampler, uv).rgb;
    mapped.specular *= specular_texel;
    mapped.environment_mask = specular_texel.r;
#endif
#ifdef PHONG_EMISSIVE_TEXTURE
    mapped.emissive *= textureSample(emissive_texture, emissive_sampler, uv).rgb;
#endif
#ifdef PHONG_ALPHA_MAP
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
    mapped.base_color.a *= textureSample(alpha_map_texture, alpha_map_sampler, uv).g;
#endif
#endif
#ifdef PHONG_LIGHT_MAP
#ifdef PHONG_LIGHT_MAP_UV_B
    let light_map_uv = in.uv_b;
#else
    let light_map_uv = uv;
#endif
    let light_map = textureSample(light_map_texture, light_map_sampler, light_map_uv).rgb;
    mapped.baked_light = light_map * material.light_map_intensity;
#endif
#ifdef LIGHTMAP
    // Bevy's `Lightmap` component on the mesh: its texture at the second UV set mapped into
    // its UV rectangle, as `StandardMaterial` reads it, times the light map intensity.
    mapped.baked_light += lightmap(in.uv_b, material.light_map_intensity, in.instance_index);
#endif
#ifdef PHONG_AO_MAP
#ifdef PHONG_AO_MAP_UV_B
    let ao_map_uv = in.uv_b;
#else
    let ao_map_uv = uv;
#endif
    let ao = textureSample(ao_map_texture, ao_map_sampler, ao_map_uv).r;
    mapped.occlusion = 1.0 + material.ao_map_intensity * (ao - 1.0);
#endif
    return mapped;
}
