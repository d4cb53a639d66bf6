//! The Rust structs the crate writes for the GPU have the layout the WESL declares: sizes and
//! field offsets as naga lays out the structs of the composed module
//! `bevy_phong::shaders::types`.

use crate::library::library;
use bevy::render::render_resource::ShaderType;
use bevy_phong::testing::{
    GpuClustersHeader, GpuLight, GpuLightsHeader, GpuShadowView, GpuShadowViewsHeader,
    PhongMaterialUniform,
};
use std::mem::offset_of;

/// The WESL module `bevy_phong::shaders::types`, composed.
fn types_module() -> naga::Module {
    library().module("bevy_phong::shaders::types", &[])
}

/// `(size, [(member, offset)])` of the WGSL struct `name`, as naga's front end lays it out.
fn wgsl_struct(module: &naga::Module, name: &str) -> (u32, Vec<(String, u32)>) {
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("struct {name} in bevy_phong::shaders::types"));
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        panic!("{name} is a struct");
    };
    let members = members
        .iter()
        .map(|member| (member.name.clone().unwrap_or_default(), member.offset))
        .collect();
    (*span, members)
}

/// `[(member, offset)]` of a Rust struct in the form [`wgsl_struct`] gives.
fn rust_members(members: &[(&str, usize)]) -> Vec<(String, u32)> {
    members
        .iter()
        .map(|(name, offset)| (name.to_string(), *offset as u32))
        .collect()
}

#[test]
fn gpu_light_matches_wgsl_phong_light() {
    let (size, members) = wgsl_struct(&types_module(), "PhongLight");
    assert_eq!(size as usize, size_of::<GpuLight>());
    let rust = [
        ("position", offset_of!(GpuLight, position)),
        ("reach", offset_of!(GpuLight, reach)),
        ("direction", offset_of!(GpuLight, direction)),
        ("outer_versine", offset_of!(GpuLight, outer_versine)),
        ("color", offset_of!(GpuLight, color)),
        ("cone_scale", offset_of!(GpuLight, cone_scale)),
        ("specular", offset_of!(GpuLight, specular)),
        ("cone_exponent", offset_of!(GpuLight, cone_exponent)),
        ("decay", offset_of!(GpuLight, decay)),
        ("shadow", offset_of!(GpuLight, shadow)),
    ];
    assert_eq!(members, rust_members(&rust));
}

#[test]
fn each_light_in_the_wgsl_light_buffer_takes_one_gpu_light() {
    let module = types_module();
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some("PhongLights"))
        .expect("struct PhongLights in bevy_phong::shaders::types");
    let naga::TypeInner::Struct { members, .. } = &ty.inner else {
        panic!("PhongLights is a struct");
    };
    let lights = members.last().expect("PhongLights ends with its lights");
    let naga::TypeInner::Array { stride, .. } = module.types[lights.ty].inner else {
        panic!("PhongLights.lights is an array");
    };
    assert_eq!(stride as usize, size_of::<GpuLight>());
}

#[test]
fn light_buffer_header_matches_wgsl_phong_lights() {
    let (_, members) = wgsl_struct(&types_module(), "PhongLights");
    let rust = [
        ("ambient", offset_of!(GpuLightsHeader, ambient)),
        (
            "directional_count",
            offset_of!(GpuLightsHeader, directional_count),
        ),
        ("local_count", offset_of!(GpuLightsHeader, local_count)),
        (
            "clustered_local_count",
            offset_of!(GpuLightsHeader, clustered_local_count),
        ),
        ("area_count", offset_of!(GpuLightsHeader, area_count)),
        (
            "clustered_area_count",
            offset_of!(GpuLightsHeader, clustered_area_count),
        ),
        ("hemisphere_up", offset_of!(GpuLightsHeader, hemisphere_up)),
        (
            "bevy_ambient_scale",
            offset_of!(GpuLightsHeader, bevy_ambient_scale),
        ),
        (
            "hemisphere_half_difference",
            offset_of!(GpuLightsHeader, hemisphere_half_difference),
        ),
        ("lights", size_of::<GpuLightsHeader>()),
    ];
    assert_eq!(members, rust_members(&rust));
}

#[test]
fn light_clusters_header_matches_wgsl_phong_light_clusters() {
    let (_, members) = wgsl_struct(&types_module(), "PhongLightClusters");
    let rust = [
        ("view_count", offset_of!(GpuClustersHeader, view_count)),
        (
            "cluster_words",
            offset_of!(GpuClustersHeader, cluster_words),
        ),
        ("padding", offset_of!(GpuClustersHeader, padding)),
        ("data", size_of::<GpuClustersHeader>()),
    ];
    assert_eq!(members, rust_members(&rust));
}

#[test]
fn shadow_view_matches_wgsl_phong_shadow_view() {
    let (size, members) = wgsl_struct(&types_module(), "PhongShadowView");
    assert_eq!(size as usize, size_of::<GpuShadowView>());
    let rust = [
        (
            "clip_from_world",
            offset_of!(GpuShadowView, clip_from_world),
        ),
        ("view_plane", offset_of!(GpuShadowView, view_plane)),
        ("projection", offset_of!(GpuShadowView, projection)),
        ("layer", offset_of!(GpuShadowView, layer)),
        ("view_count", offset_of!(GpuShadowView, view_count)),
        ("uv_scale", offset_of!(GpuShadowView, uv_scale)),
        ("texel_size", offset_of!(GpuShadowView, texel_size)),
        ("depth_range", offset_of!(GpuShadowView, depth_range)),
        ("near", offset_of!(GpuShadowView, near)),
        ("depth_bias", offset_of!(GpuShadowView, depth_bias)),
        ("normal_bias", offset_of!(GpuShadowView, normal_bias)),
        ("light_size", offset_of!(GpuShadowView, light_size)),
        ("cascade_far", offset_of!(GpuShadowView, cascade_far)),
        (
            "cascade_blend_start",
            offset_of!(GpuShadowView, cascade_blend_start),
        ),
        (
            "diffuse_in_shadow",
            offset_of!(GpuShadowView, diffuse_in_shadow),
        ),
        (
            "specular_in_shadow",
            offset_of!(GpuShadowView, specular_in_shadow),
        ),
        ("camera_key", offset_of!(GpuShadowView, camera_key)),
        ("camera_count", offset_of!(GpuShadowView, camera_count)),
    ];
    assert_eq!(members, rust_members(&rust));
    let (_, views) = wgsl_struct(&types_module(), "PhongShadowViews");
    let views_offset = views.iter().find(|(name, _)| name == "views").unwrap().1;
    assert_eq!(views_offset as usize, size_of::<GpuShadowViewsHeader>());
}

#[test]
fn material_uniform_matches_wgsl_phong_material_uniform() {
    let (size, _) = wgsl_struct(&types_module(), "PhongMaterialUniform");
    assert_eq!(u64::from(size), PhongMaterialUniform::min_size().get());
}
