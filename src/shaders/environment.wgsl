// The environment a surface reflects (three.js's `envMap`): the view ray reflected about the
// normal, or refracted through the surface, looks up a cube map at a mip level as blurred as
// the highlight's lobe, and the lit color takes it by the material's combine mode (SPEC.md,
// "Environment map"). The cube is the material's own (`PhongMaterial::environment_map`;
// not under WebGL2: `render::binds_every_map`) or, with PHONG_ENV_CAMERA, the specular map
// of the camera's Bevy `EnvironmentMapLight` (Bevy's ENVIRONMENT_MAP), rotated and scaled as
// `StandardMaterial` reads it.
#define_import_path bevy_phong::environment

#import bevy_phong::bindings::material
#import bevy_phong::types::PhongSurface
#ifdef PHONG_ENV_CAMERA
#ifdef ENVIRONMENT_MAP
#import bevy_pbr::mesh_view_bindings::{light_probes, environment_map_sampler, view}
#ifdef MULTIPLE_LIGHT_PROBES_IN_ARRAY
#import bevy_pbr::mesh_view_bindings::specular_environment_maps
#else
#import bevy_pbr::mesh_view_bindings::specular_environment_map
#endif
#endif
#else
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
#import bevy_phong::bindings::{environment_map, environment_sampler}
#endif
#endif

const HALF_PI: f32 = 1.5707963;

// The mip level a cube of `size` texels a side is read at for the highlight exponent
// `shininess`: where a texel spans about the lobe of cos^α, 1/sqrt(α + 1) radians (a face
// spans π/2: a texel of level m, (π/2)·2^m / size). Past the last level the sampler
// clamps.
fn environment_lod(shininess: f32, size: f32) -> f32 {
    return max(log2(size / (HALF_PI * sqrt(shininess + 1.0))), 0.0);
}

// The direction the environment is looked up along: the ray from the camera reflected
// about N or, with PHONG_ENV_REFRACTION, refracted with the material's ratio of indices.
fn environment_direction(surface: PhongSurface) -> vec3<f32> {
    let incident = -surface.view;
#ifdef PHONG_ENV_REFRACTION
    return refract(incident, surface.normal, material.refraction_ratio);
#else
    return reflect(incident, surface.normal);
#endif
}

// What the environment shows along a direction, if the surface has one to reflect.
struct EnvironmentSample {
    color: vec3<f32>,
    found: bool,
}

// The environment's color along `direction` for the highlight exponent `shininess`.
fn environment_sample(direction: vec3<f32>, shininess: f32) -> EnvironmentSample {
#ifdef PHONG_ENV_CAMERA
#ifdef ENVIRONMENT_MAP
    if light_probes.view_cubemap_index < 0 {
        return EnvironmentSample(vec3<f32>(0.0), false);
    }
    // As Bevy: the world direction turned by the inverse of the light's rotation (the
    // uniform holds it), in the cube's left-handed frame.
    var turned = rotated(light_probes.view_rotation, direction);
    turned.z = -turned.z;
#ifdef MULTIPLE_LIGHT_PROBES_IN_ARRAY
    let index = u32(light_probes.view_cubemap_index);
    let size = f32(textureDimensions(specular_environment_maps[index]).x);
    let lod = environment_lod(shininess, size);
    let texel = textureSampleLevel(specular_environment_maps[index], environment_map_sampler, turned, lod);
#else
    let size = f32(textureDimensions(specular_environment_map).x);
    let lod = environment_lod(shininess, size);
    let texel = textureSampleLevel(specular_environment_map, environment_map_sampler, turned, lod);
#endif
    return EnvironmentSample(texel.rgb * light_probes.intensity_for_view * view.exposure, true);
#else
    // The camera has no `EnvironmentMapLight`: nothing to reflect.
    return EnvironmentSample(vec3<f32>(0.0), false);
#endif
#else
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
    let size = f32(textureDimensions(environment_map).x);
    let lod = environment_lod(shininess, size);
    let texel = textureSampleLevel(environment_map, environment_sampler, direction, lod);
    return EnvironmentSample(texel.rgb, true);
#else
    // Left out where not every map is bound (WebGL2).
    return EnvironmentSample(vec3<f32>(0.0), false);
#endif
#endif
}

// `v` rotated by the unit quaternion `q` (xyz, w).
fn rotated(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    let t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

// `lit` with the environment, weighted by `mask` (the specular map's red, 1 without one)
// times the material's reflectivity: multiplied in (the default), mixed in
// (PHONG_ENV_MIX) or added (PHONG_ENV_ADD), as three.js's `combine`. Unchanged where
// there is no environment to reflect.
fn with_environment(lit: vec3<f32>, surface: PhongSurface, mask: f32) -> vec3<f32> {
    let environment = environment_sample(environment_direction(surface), surface.shininess);
    if !environment.found {
        return lit;
    }
    let strength = mask * material.reflectivity;
#ifdef PHONG_ENV_ADD
    return lit + environment.color * strength;
#else
#ifdef PHONG_ENV_MIX
    return mix(lit, environment.color, strength);
#else
    return mix(lit, lit * environment.color, strength);
#endif
#endif
}
