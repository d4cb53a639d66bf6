// The scene data every Phong material reads (lights, light grid, shadow views), through
// accessors: the rest of the shaders never name the bindings that hold it, so that where
// storage buffers are missing (WebGL2) the same data can be read from elsewhere without
// touching them. See docs/design/webgl2.md.
#define_import_path bevy_phong::scene

#import bevy_phong::bindings::{light_grid, lights, shadow_views}
#import bevy_phong::types::{PhongLight, PhongShadowView}

// The ambient light, linear RGB.
fn ambient_color() -> vec3<f32> {
    return lights.ambient;
}

// How many directional, point and spot lights of unlimited reach the light buffer holds, in
// that order from index 0 (the grid's lights follow them).
fn directional_count() -> u32 {
    return lights.directional_count;
}

fn point_count() -> u32 {
    return lights.point_count;
}

fn spot_count() -> u32 {
    return lights.spot_count;
}

// The light at `index` in the light buffer.
fn light_at(index: u32) -> PhongLight {
    return lights.lights[index];
}

// The light grid's corner of cell (0, 0, 0), world space.
fn grid_origin() -> vec3<f32> {
    return light_grid.origin;
}

// The edge length of the grid's cells, world units.
fn grid_cell_size() -> f32 {
    return light_grid.cell_size;
}

// Cells along x, y, z; zeros when no light is in the grid.
fn grid_dimensions() -> vec3<u32> {
    return light_grid.dimensions;
}

// Word `index` of the grid's data (`PhongLightGrid.data`).
fn grid_word(index: u32) -> u32 {
    return light_grid.data[index];
}

// How many shadow views the frame has.
fn shadow_view_count() -> u32 {
    return shadow_views.count;
}

// Shadow view `index`.
fn shadow_view_at(index: u32) -> PhongShadowView {
    return shadow_views.views[index];
}
