// The bindings of `PhongMaterial` in the material bind group.
#define_import_path bevy_phong::bindings

#import bevy_phong::types::{PhongLightGrid, PhongLights, PhongMaterialUniform}

@group(#{MATERIAL_BIND_GROUP}) @binding(0) var<uniform> material: PhongMaterialUniform;
@group(#{MATERIAL_BIND_GROUP}) @binding(1) var<storage, read> lights: PhongLights;
@group(#{MATERIAL_BIND_GROUP}) @binding(2) var<storage, read> light_grid: PhongLightGrid;
