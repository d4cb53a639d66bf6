//! Values that Rust writes and WGSL reads, or that both name, agree: read from the composed
//! naga modules and compared with the Rust constants.

use crate::{
    library::{device_defs, library},
    variants,
};
use bevy::{
    prelude::default,
    render::render_resource::{
        BindingType, BufferBindingType, SamplerBindingType, TextureSampleType, TextureViewDimension,
    },
};
use bevy_phong::{
    PhongMaterial, PhongSceneBindings, SpecularModel,
    testing::{GpuAreaLight, GpuClustersHeader, GpuShadowView, PhongMaterialUniform},
};
use naga::{Expression, Literal};

fn global_u32(module: &naga::Module, expression: naga::Handle<Expression>) -> Option<u32> {
    match module.global_expressions[expression] {
        Expression::Literal(Literal::U32(value)) => Some(value),
        _ => None,
    }
}

/// The `u32` constant `name` of `module`.
fn constant(module: &naga::Module, name: &str) -> u32 {
    let (_, constant) = module
        .constants
        .iter()
        .find(|(_, constant)| constant.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("constant {name}"));
    global_u32(module, constant.init).unwrap_or_else(|| panic!("{name} is a u32"))
}

fn flags(material: PhongMaterial) -> u32 {
    PhongMaterialUniform::from(&material).flags
}

#[test]
fn material_flags_are_the_wgsl_constants() {
    let types = library().module("bevy_phong::shaders::types", &[]);
    let phong = constant(&types, "SPECULAR_MODEL_PHONG");
    let blinn_phong = constant(&types, "SPECULAR_MODEL_BLINN_PHONG");
    let flip_y = constant(&types, "FLIP_NORMAL_MAP_Y");
    let double_sided = constant(&types, "DOUBLE_SIDED");
    assert_eq!(PhongMaterialUniform::FLIP_NORMAL_MAP_Y, flip_y);
    assert_eq!(PhongMaterialUniform::DOUBLE_SIDED, double_sided);
    assert_eq!(flags(PhongMaterial::default()), phong);
    let blinn = PhongMaterial {
        specular_model: SpecularModel::BlinnPhong,
        ..default()
    };
    assert_eq!(flags(blinn.clone()), blinn_phong);
    let flipped = PhongMaterial {
        flip_normal_map_y: true,
        ..blinn
    };
    assert_eq!(flags(flipped.clone()), blinn_phong | flip_y);
    let both_sides = PhongMaterial {
        double_sided: true,
        ..flipped
    };
    assert_eq!(flags(both_sides), blinn_phong | flip_y | double_sided);
}

#[test]
fn shadow_projection_kinds_are_the_wgsl_constants() {
    let types = library().module("bevy_phong::shaders::types", &[]);
    assert_eq!(
        GpuShadowView::ORTHOGRAPHIC,
        constant(&types, "SHADOW_PROJECTION_ORTHOGRAPHIC")
    );
    assert_eq!(
        GpuShadowView::PERSPECTIVE,
        constant(&types, "SHADOW_PROJECTION_PERSPECTIVE")
    );
}

#[test]
fn area_light_flags_are_the_wgsl_constants() {
    let types = library().module("bevy_phong::shaders::types", &[]);
    for (flag, name) in [
        (GpuAreaLight::TWO_SIDED, "AREA_TWO_SIDED"),
        (
            GpuAreaLight::REPRESENTATIVE_POINT,
            "AREA_REPRESENTATIVE_POINT",
        ),
        (GpuAreaLight::DISK, "AREA_DISK"),
        (GpuAreaLight::FITTED, "AREA_FITTED"),
        (GpuAreaLight::EXACT, "AREA_EXACT"),
    ] {
        assert_eq!(flag, constant(&types, name), "{name}");
    }
}

/// What a binding holds, in words both sides can be brought to.
fn wgsl_binding_kind(module: &naga::Module, variable: &naga::GlobalVariable) -> String {
    match (&variable.space, &module.types[variable.ty].inner) {
        (naga::AddressSpace::Storage { access }, _) if *access == naga::StorageAccess::LOAD => {
            "read-only storage buffer".into()
        }
        (naga::AddressSpace::Storage { .. }, _) => "writable storage buffer".into(),
        (naga::AddressSpace::Uniform, _) => "uniform buffer".into(),
        (
            _,
            naga::TypeInner::Image {
                dim: naga::ImageDimension::D2,
                arrayed: true,
                class: naga::ImageClass::Depth { multi: false },
            },
        ) => "2D depth texture array".into(),
        (
            _,
            naga::TypeInner::Image {
                dim: naga::ImageDimension::D2,
                arrayed: false,
                class:
                    naga::ImageClass::Sampled {
                        kind: naga::ScalarKind::Uint,
                        multi: false,
                    },
            },
        ) => "2D u32 texture".into(),
        (
            _,
            naga::TypeInner::Image {
                dim: naga::ImageDimension::D2,
                arrayed: true,
                class:
                    naga::ImageClass::Sampled {
                        kind: naga::ScalarKind::Float,
                        multi: false,
                    },
            },
        ) => "2D f32 texture array".into(),
        (_, naga::TypeInner::Sampler { comparison: true }) => "comparison sampler".into(),
        (_, other) => format!("{other:?}"),
    }
}

fn rust_binding_kind(binding: &BindingType) -> String {
    match binding {
        BindingType::Buffer {
            ty: BufferBindingType::Storage { read_only: true },
            ..
        } => "read-only storage buffer".into(),
        BindingType::Texture {
            sample_type: TextureSampleType::Depth,
            view_dimension: TextureViewDimension::D2Array,
            multisampled: false,
        } => "2D depth texture array".into(),
        BindingType::Texture {
            sample_type: TextureSampleType::Uint,
            view_dimension: TextureViewDimension::D2,
            multisampled: false,
        } => "2D u32 texture".into(),
        BindingType::Texture {
            sample_type: TextureSampleType::Float { .. },
            view_dimension: TextureViewDimension::D2Array,
            multisampled: false,
        } => "2D f32 texture array".into(),
        BindingType::Sampler(SamplerBindingType::Comparison) => "comparison sampler".into(),
        other => format!("{other:?}"),
    }
}

#[test]
fn scene_bindings_have_the_wgsl_numbers_and_kinds() {
    let shadows = [
        ("shadow_maps", PhongSceneBindings::SHADOW_MAPS),
        ("shadow_sampler", PhongSceneBindings::SHADOW_SAMPLER),
    ];
    let storage = [
        ("lights", PhongSceneBindings::LIGHTS),
        ("light_clusters", PhongSceneBindings::LIGHT_CLUSTERS),
        ("shadow_views", PhongSceneBindings::SHADOW_VIEWS),
        ("cookie_atlas", PhongSceneBindings::COOKIE_ATLAS),
    ];
    let texture = [("scene_data", PhongSceneBindings::SCENE_DATA)];
    let mut with_records = storage.to_vec();
    with_records.push(("material_records", PhongSceneBindings::MATERIAL_RECORDS));
    // Bevy gives every shader the device's storage buffers per stage (and whether they are at
    // least 3 and 6), the crate's pipelines the flag `PHONG_STORAGE_BUFFERS` for the layout
    // the device gets: one fewer storage buffer than the scene data needs is the texture path,
    // as on the Rust side.
    let needed = PhongSceneBindings::STORAGE_BUFFERS_NEEDED;
    // With one storage buffer more, `PhongMaterial`'s shared bind groups hold every
    // material's records (and its shaders read them, `PHONG_MATERIAL_RECORDS`).
    for (storage_buffers, scene) in [
        (needed + 1, &with_records[..]),
        (needed, &storage[..]),
        (needed - 1, &texture[..]),
    ] {
        let scene_texture = storage_buffers < needed;
        let records = storage_buffers > needed;
        let mut defs = variants::plain_material().swap_remove(0).defs;
        defs.extend(device_defs(storage_buffers));
        if records {
            defs.push("PHONG_MATERIAL_RECORDS".into());
        }
        let bindings = library().module("bevy_phong::shaders::bindings", &defs);
        let group = bevy::pbr::MATERIAL_BIND_GROUP_INDEX as u32;
        let variable = |name: &str| {
            bindings
                .global_variables
                .iter()
                .map(|(_, variable)| variable)
                .find(|variable| variable.name.as_deref() == Some(name))
                .unwrap_or_else(|| panic!("bevy_phong::shaders::bindings::{name}"))
        };
        let named: Vec<_> = scene.iter().chain(&shadows).collect();
        for (name, binding) in &named {
            assert_eq!(
                variable(name).binding,
                Some(naga::ResourceBinding {
                    group,
                    binding: *binding
                }),
                "{name}"
            );
        }
        let entries = PhongSceneBindings::layout_entries_for(scene_texture, records);
        assert_eq!(entries.len(), named.len());
        for entry in entries {
            let (name, _) = named
                .iter()
                .find(|(_, binding)| *binding == entry.binding)
                .unwrap_or_else(|| panic!("binding {} has a name", entry.binding));
            assert_eq!(
                wgsl_binding_kind(&bindings, variable(name)),
                rust_binding_kind(&entry.ty),
                "{name}, scene texture {scene_texture}"
            );
        }
    }
}

#[test]
fn each_material_map_has_its_declared_binding_where_its_devices_bind_it() {
    // `material_maps!` declares each map's binding; the WGSL variable of the map's name must
    // sit there, on every device for a map every device binds, and only with storage buffers
    // for the others.
    let needed = PhongSceneBindings::STORAGE_BUFFERS_NEEDED;
    let group = bevy::pbr::MATERIAL_BIND_GROUP_INDEX as u32;
    let maps = bevy_phong::testing::material_map_bindings();
    assert_eq!(maps.len(), 12, "the material's twelve maps");
    for storage_buffers in [needed, needed - 1] {
        let mut defs = variants::plain_material().swap_remove(0).defs;
        defs.extend(device_defs(storage_buffers));
        // The fragment stage's maps, and the vertex stage's displacement map.
        let modules = ["bindings", "displacement"]
            .map(|name| library().module(&format!("bevy_phong::shaders::{name}"), &defs));
        for &(field, binding, every_device) in &maps {
            let variable = modules
                .iter()
                .flat_map(|module| module.global_variables.iter())
                .map(|(_, variable)| variable)
                .find(|variable| variable.name.as_deref() == Some(field));
            let expected = (storage_buffers == needed || every_device)
                .then_some(naga::ResourceBinding { group, binding });
            assert_eq!(
                variable.and_then(|variable| variable.binding),
                expected,
                "{field} with {storage_buffers} storage buffers"
            );
        }
    }
}

#[test]
fn every_data_texture_has_the_rust_width() {
    let module = library().module("bevy_phong::shaders::data_texture", &[]);
    assert_eq!(
        constant(&module, "DATA_TEXTURE_WIDTH"),
        bevy_phong::testing::DATA_TEXTURE_WIDTH
    );
}

#[test]
fn the_shader_reads_each_view_record_at_the_rust_stride() {
    // A cluster record's stride is in the data's header (`cluster_words`), written by Rust.
    let types = library().module("bevy_phong::shaders::types", &[]);
    assert_eq!(
        constant(&types, "CLUSTER_VIEW_WORDS"),
        GpuClustersHeader::VIEW_WORDS
    );
}
