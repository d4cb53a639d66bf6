// The material's environment map (`PhongMaterial::environment_map`, three.js's `envMap`):
// the view ray reflected about the normal, or refracted through the surface, looks up a
// cube map, at a mip level as blurred as the highlight's lobe, and the lit color takes it
// by the material's combine mode (SPEC.md, "Environment map").
#define_import_path bevy_phong::environment
//
// Only where every map is bound (not under WebGL2: `render::binds_every_map`).

#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
#import bevy_phong::bindings::{material, environment_map, environment_sampler}
#import bevy_phong::types::PhongSurface

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

// `lit` with the environment, weighted by `mask` (the specular map's red, 1 without one)
// times the material's reflectivity: multiplied in (the default), mixed in
// (PHONG_ENV_MIX) or added (PHONG_ENV_ADD), as three.js's `combine`.
fn with_environment(lit: vec3<f32>, surface: PhongSurface, mask: f32) -> vec3<f32> {
    let size = f32(textureDimensions(environment_map).x);
    let lod = environment_lod(surface.shininess, size);
    let direction = environment_direction(surface);
    let environment = textureSampleLevel(environment_map, environment_sampler, direction, lod).rgb;
    let strength = mask * material.reflectivity;
#ifdef PHONG_ENV_ADD
    return lit + environment * strength;
#else
#ifdef PHONG_ENV_MIX
    return mix(lit, environment, strength);
#else
    return mix(lit, lit * environment, strength);
#endif
#endif
}
#endif
