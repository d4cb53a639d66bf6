// Lights a surface point with every light in the light buffer.
#define_import_path bevy_phong::shading

#import bevy_phong::bindings::{light_grid, lights, material}
#import bevy_phong::lighting::{directional_light, normalize_or_zero, phong_surface, point_light, spot_light}
#import bevy_phong::shadows::shadowed
#import bevy_pbr::mesh_bindings::mesh
#import bevy_pbr::mesh_types::MESH_FLAGS_SHADOW_RECEIVER_BIT
#import bevy_phong::types::{PhongLight, PhongSurface}

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

// ambient ⊙ k_a ⊙ k_d
fn ambient_light(surface: PhongSurface) -> vec3<f32> {
    return lights.ambient * material.ambient_factor * surface.diffuse;
}

// A point or spot light with its shadow applied (see `bevy_phong::shadows::shadowed`).
fn shadowed_at_point(light: PhongLight, surface: PhongSurface) -> PhongLight {
    return shadowed(light, surface, normalize_or_zero(light.position - surface.position));
}

// Σ over every light that reaches the surface point: the directional lights, the point and
// spot lights of unlimited reach, and those of the point's grid cell.
fn direct_lights(surface: PhongSurface) -> vec3<f32> {
    var color = vec3<f32>(0.0);
    var index = 0u;
    let directional_end = lights.directional_count;
    // Each kind's shadow-casting lights come first; the others run the plain loop. The
    // shadow code is compiled only in the variant for scenes with shadows (PHONG_SHADOWS).
#ifdef PHONG_SHADOWS
    let shadowed_directional_end = lights.shadowed_directional_count;
    for (; index < shadowed_directional_end; index += 1u) {
        let light = lights.lights[index];
        color += directional_light(surface, shadowed(light, surface, -light.direction));
    }
#endif
    for (; index < directional_end; index += 1u) {
        color += directional_light(surface, lights.lights[index]);
    }
#ifdef PHONG_SHADOWS
    let shadowed_point_end = directional_end + lights.shadowed_point_count;
    for (; index < shadowed_point_end; index += 1u) {
        color += point_light(surface, shadowed_at_point(lights.lights[index], surface));
    }
#endif
    let point_end = directional_end + lights.point_count;
    for (; index < point_end; index += 1u) {
        color += point_light(surface, lights.lights[index]);
    }
#ifdef PHONG_SHADOWS
    let shadowed_spot_end = point_end + lights.shadowed_spot_count;
    for (; index < shadowed_spot_end; index += 1u) {
        color += spot_light(surface, shadowed_at_point(lights.lights[index], surface));
    }
#endif
    let spot_end = point_end + lights.spot_count;
    for (; index < spot_end; index += 1u) {
        color += spot_light(surface, lights.lights[index]);
    }
    return color + grid_lights(surface);
}

// Σ over the point and spot lights listed in the grid cell that holds the surface point.
fn grid_lights(surface: PhongSurface) -> vec3<f32> {
    let dimensions = light_grid.dimensions;
    let cell = (surface.position - light_grid.origin) / light_grid.cell_size;
    // Outside the grid no light of finite reach arrives; `!(…)` also rejects NaN.
    if !(all(cell >= vec3<f32>(0.0)) && all(cell < vec3<f32>(dimensions))) {
        return vec3<f32>(0.0);
    }
    let cell_index = vec3<u32>(cell);
    let record = 4u * (cell_index.x + dimensions.x * (cell_index.y + dimensions.y * cell_index.z));
    var slot = light_grid.data[record];
    let point_end = slot + light_grid.data[record + 1u];
    let spot_end = point_end + light_grid.data[record + 2u];
    var color = vec3<f32>(0.0);
    for (; slot < point_end; slot += 1u) {
        color += point_light(surface, lights.lights[light_grid.data[slot]]);
    }
    for (; slot < spot_end; slot += 1u) {
        color += spot_light(surface, lights.lights[light_grid.data[slot]]);
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
