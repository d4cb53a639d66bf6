//! The shader defs each entry shader is specialized with: the crate's own (from
//! `PhongMaterialKey::shader_defs`) and those Bevy's mesh and material pipelines add.
//!
//! Two sets of material keys: [`every_key`] (each of the ten map, shadow and side switches
//! on and off in every combination, and each further feature over two of them) and
//! [`covering_keys`] (each switch on alone and off alone, and each further feature over no
//! map and over every map). Every key is composed where the most defs meet: on the mesh with
//! every attribute, under the render tests' camera, on both devices. Every other mesh and
//! camera is composed with the covering keys, so that each of its defs meets each of the
//! crate's, on and off, without composing the whole product again (tens of thousands of
//! compositions, each a few tens of milliseconds).

use crate::library::device_defs;
use bevy::{
    asset::RenderAssetUsages,
    mesh::{Mesh, MeshVertexBufferLayoutRef, MeshVertexBufferLayouts, PrimitiveTopology},
    pbr::{
        MATERIAL_BIND_GROUP_INDEX, TONEMAPPING_LUT_SAMPLER_BINDING_INDEX,
        TONEMAPPING_LUT_TEXTURE_BINDING_INDEX,
    },
    shader::ShaderDefVal,
};
use bevy_phong::{MaterialFeatures, PhongMaterialKey};
use std::collections::BTreeSet;

/// One set of shader defs, with a name that says where it comes from.
pub struct Variant {
    /// The mesh's attributes, the camera, the crate's defs.
    pub name: String,
    pub defs: Vec<ShaderDefVal>,
}

/// The mesh with every attribute a material reads: [`every_key`] is composed on it.
const RICHEST_MESH: &str = "positions, normals, UVs, tangents, colors";

/// The camera the render tests use: [`every_key`] is composed under it, on both devices.
const RENDER_TESTS_CAMERA: &str = "render tests' camera";

/// The vertex attributes of the meshes a material may be drawn on: without UVs, with UVs
/// (Bevy's primitive shapes), with UVs and tangents (`Mesh::with_generated_tangents`), with
/// tangents but no UVs, and with a second UV set and vertex colors beside UVs and tangents
/// (glTF's `TEXCOORD_1`, `COLOR_0`).
fn mesh_layouts() -> Vec<(&'static str, MeshVertexBufferLayoutRef)> {
    let mut layouts = MeshVertexBufferLayouts::default();
    let kinds: [(&str, bool, bool, bool); 5] = [
        ("positions, normals", false, false, false),
        ("positions, normals, UVs", true, false, false),
        ("positions, normals, UVs, tangents", true, true, false),
        ("positions, normals, tangents", false, true, false),
        (RICHEST_MESH, true, true, true),
    ];
    kinds
        .into_iter()
        .map(|(name, uvs, tangents, colors)| {
            let mut mesh = Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::all())
                .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, vec![[0.0f32; 3]; 3])
                .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, vec![[0.0f32, 0.0, 1.0]; 3]);
            if uvs {
                mesh.insert_attribute(Mesh::ATTRIBUTE_UV_0, vec![[0.0f32; 2]; 3]);
            }
            if tangents {
                mesh.insert_attribute(Mesh::ATTRIBUTE_TANGENT, vec![[1.0f32, 0.0, 0.0, 1.0]; 3]);
            }
            if colors {
                mesh.insert_attribute(Mesh::ATTRIBUTE_UV_1, vec![[0.0f32; 2]; 3]);
                mesh.insert_attribute(Mesh::ATTRIBUTE_COLOR, vec![[1.0f32; 4]; 3]);
            }
            (name, mesh.get_mesh_vertex_buffer_layout(&mut layouts))
        })
        .collect()
}

/// The defs Bevy's `MeshPipeline::specialize` derives from a mesh's vertex attributes
/// (bevy_pbr 0.20.1, `render/mesh.rs`), with those it always adds.
fn mesh_defs(layout: &MeshVertexBufferLayoutRef) -> Vec<ShaderDefVal> {
    let mut defs: Vec<ShaderDefVal> = vec![
        "MESH_PIPELINE".into(),
        "VERTEX_OUTPUT_INSTANCE_INDEX".into(),
    ];
    let attributes = [
        (Mesh::ATTRIBUTE_POSITION, &["VERTEX_POSITIONS"][..]),
        (Mesh::ATTRIBUTE_NORMAL, &["VERTEX_NORMALS"]),
        (Mesh::ATTRIBUTE_UV_0, &["VERTEX_UVS", "VERTEX_UVS_A"]),
        (Mesh::ATTRIBUTE_UV_1, &["VERTEX_UVS", "VERTEX_UVS_B"]),
        (Mesh::ATTRIBUTE_TANGENT, &["VERTEX_TANGENTS"]),
        (Mesh::ATTRIBUTE_COLOR, &["VERTEX_COLORS"]),
    ];
    for (attribute, names) in attributes {
        if layout.0.contains(attribute) {
            defs.extend(names.iter().map(|&name| name.into()));
        }
    }
    defs
}

/// `AVAILABLE_STORAGE_BUFFER_BINDINGS` and its comparisons `__GE_3` and `__GE_6`, which
/// Bevy's pipeline cache gives every shader, and the crate's `PHONG_STORAGE_BUFFERS`, which
/// every Phong pipeline sets from its material bind group (`add_scene_data_flag`), on the two
/// kinds of device: wgpu's default limits (8 storage buffers per stage: the scene data in
/// storage buffers) and WebGL2's (none: the crate reads its scene data from a texture, Bevy
/// its lights from uniforms).
pub fn devices() -> [(&'static str, Vec<ShaderDefVal>); 2] {
    [
        (
            "full limits",
            device_defs(
                bevy::render::settings::WgpuLimits::default().max_storage_buffers_per_shader_stage,
            ),
        ),
        (
            "WebGL2 limits",
            device_defs(
                bevy::render::settings::WgpuLimits::downlevel_webgl2_defaults()
                    .max_storage_buffers_per_shader_stage,
            ),
        ),
    ]
}

/// The defs Bevy's mesh pipeline derives from the camera, for three cameras: the render
/// tests' (no MSAA, no tone mapping), a default `Camera3d` (4× MSAA, tone mapping in the
/// shader with Bevy's default method, deband dithering) and an HDR camera with distance fog,
/// SSAO and the depth and normal prepasses, each on both [`devices`]. All see
/// in perspective, with Bevy's default shadow filter, and add the material bind group's
/// index.
fn view_setups() -> Vec<(String, Vec<ShaderDefVal>)> {
    cameras()
        .into_iter()
        .flat_map(|(camera, camera_defs)| {
            devices().map(|(device, device_defs)| {
                let mut defs = camera_defs.clone();
                defs.extend(device_defs);
                (format!("{camera}, {device}"), defs)
            })
        })
        .collect()
}

fn cameras() -> Vec<(&'static str, Vec<ShaderDefVal>)> {
    let common = || -> Vec<ShaderDefVal> {
        vec![
            "VIEW_PROJECTION_PERSPECTIVE".into(),
            "SHADOW_FILTER_METHOD_GAUSSIAN".into(),
            "IRRADIANCE_VOLUMES_ARE_USABLE".into(),
            ShaderDefVal::Int("SCREEN_SPACE_SPECULAR_TRANSMISSION_BLUR_TAPS".into(), 8),
            ShaderDefVal::UInt(
                "MATERIAL_BIND_GROUP".into(),
                MATERIAL_BIND_GROUP_INDEX as u32,
            ),
        ]
    };
    let mut default_camera = common();
    default_camera.extend([
        "MULTISAMPLED".into(),
        "TONEMAP_IN_SHADER".into(),
        ShaderDefVal::UInt(
            "TONEMAPPING_LUT_TEXTURE_BINDING_INDEX".into(),
            TONEMAPPING_LUT_TEXTURE_BINDING_INDEX,
        ),
        ShaderDefVal::UInt(
            "TONEMAPPING_LUT_SAMPLER_BINDING_INDEX".into(),
            TONEMAPPING_LUT_SAMPLER_BINDING_INDEX,
        ),
        "TONEMAP_METHOD_TONY_MC_MAPFACE".into(),
        "DEBAND_DITHER".into(),
        // An `EnvironmentMapLight`, in Bevy's binding arrays.
        "ENVIRONMENT_MAP".into(),
        "MULTIPLE_LIGHT_PROBES_IN_ARRAY".into(),
    ]);
    let mut game_camera = common();
    game_camera.extend([
        "DISTANCE_FOG".into(),
        "SCREEN_SPACE_AMBIENT_OCCLUSION".into(),
        "DEPTH_PREPASS".into(),
        "NORMAL_PREPASS".into(),
        // An `EnvironmentMapLight`, without binding arrays.
        "ENVIRONMENT_MAP".into(),
    ]);
    vec![
        (RENDER_TESTS_CAMERA, common()),
        ("default Camera3d", default_camera),
        ("HDR camera with fog, SSAO and prepasses", game_camera),
    ]
}

/// A further feature: the features it adds to a key, and those it takes out.
type Extra = (MaterialFeatures, MaterialFeatures);

/// Every `PhongMaterialKey`: its ten map, shadow and side switches in every combination, and
/// each further feature ([`extra_features`]) with no map and with every map, under each
/// kind of shadows.
fn every_key() -> Vec<PhongMaterialKey> {
    let mut keys: Vec<PhongMaterialKey> = (0..1u32 << SWITCHES).map(key_of_switches).collect();
    let every_map = 0b11_0011_1111;
    for maps in [0, every_map] {
        for shadows in [0, 1 << 6, 3 << 6] {
            keys.extend(
                extra_features()
                    .into_iter()
                    .map(|extra| with_extra(key_of_switches(maps | shadows), extra)),
            );
        }
    }
    keys
}

/// The keys that put each def of the crate on and off beside every other def: no switch on,
/// every switch on, each switch alone on and each alone off; and each further feature over
/// no switch and over every switch.
fn covering_keys() -> Vec<PhongMaterialKey> {
    let all = (1u32 << SWITCHES) - 1;
    let mut keys: Vec<PhongMaterialKey> = [0, all]
        .into_iter()
        .chain((0..SWITCHES).flat_map(|switch| [1 << switch, all & !(1 << switch)]))
        .map(key_of_switches)
        .collect();
    for switches in [0, all] {
        keys.extend(
            extra_features()
                .into_iter()
                .map(|extra| with_extra(key_of_switches(switches), extra)),
        );
    }
    keys
}

/// How many switches [`key_of_switches`] reads.
const SWITCHES: u32 = 10;

/// `key` with the extra's features added and its second taken out.
fn with_extra(mut key: PhongMaterialKey, (added, taken): Extra) -> PhongMaterialKey {
    key.features = key.features.with(added).without(taken);
    key
}

/// The key with the switches of `bits` on: a highlight (bit 0), the base color, specular
/// and emissive maps, the normal map, an alpha mask, shadows, soft shadows (with shadows
/// only), both sides, the UV transform.
fn key_of_switches(bits: u32) -> PhongMaterialKey {
    use MaterialFeatures as F;
    let bit = |index: u32| bits & (1 << index) != 0;
    let switches = [
        (!bit(0), F::NO_SPECULAR),
        (bit(1), F::BASE_COLOR_TEXTURE),
        (bit(2), F::SPECULAR_TEXTURE),
        (bit(3), F::EMISSIVE_TEXTURE),
        (bit(4), F::NORMAL_MAP),
        (bit(5), F::ALPHA_MASK),
        (bit(6), F::SHADOWS),
        // Soft shadows only where some light casts shadows.
        (bit(6) && bit(7), F::SOFT_SHADOWS),
        // No shader def: a pipeline setting.
        (bit(8), F::DOUBLE_SIDED),
        (bit(9), F::UV_TRANSFORM),
    ];
    PhongMaterialKey {
        features: switches
            .into_iter()
            .filter(|(on, _)| *on)
            .fold(F::NONE, |all, (_, feature)| all.with(feature)),
        // Neither changes a shader def.
        cull_mode: Some(bevy::render::render_resource::Face::Back),
        depth_bias: 0,
    }
}

/// The features beside the ten switches: each changes only a few steps, so each is
/// composed over a few sets of switches. Each adds its features and takes out the second (a
/// highlight switched on).
fn extra_features() -> Vec<Extra> {
    use MaterialFeatures as F;
    let environment = F::ENVIRONMENT_MAP;
    [
        F::UNLIT,
        F::NO_FOG,
        F::UNLIT.with(F::NO_FOG),
        F::LIGHT_MAP,
        F::LIGHT_MAP_UV_B,
        F::AO_MAP,
        F::AO_MAP_UV_B,
        F::LIGHT_MAP_UV_B.with(F::AO_MAP),
        F::ALPHA_MAP,
        environment,
        environment.with(F::ENV_MIX),
        environment.with(F::ENV_ADD),
        environment.with(F::ENV_REFRACTION),
        environment.with(F::ENV_MIX).with(F::ENV_REFRACTION),
        environment.with(F::ENV_ADD).with(F::ENV_REFRACTION),
        F::BUMP_MAP,
        F::FLAT_SHADING,
        F::BUMP_MAP.with(F::FLAT_SHADING),
        environment.with(F::ENV_MIX).with(F::ENV_CAMERA),
        environment
            .with(F::ENV_ADD)
            .with(F::ENV_REFRACTION)
            .with(F::ENV_CAMERA),
        F::DIFFUSE_WRAP,
        F::DIFFUSE_TOON,
        F::RIM,
        F::RIM_LIT,
        F::TOON_RAMP,
        F::HEMISPHERE,
        F::LIGHT_COOKIES,
        F::VERTEX_LIGHTING,
        F::VERTEX_LIGHTING.with(F::RIM_LIT),
        F::FRESNEL,
        F::VERTEX_LIGHTING.with(F::FRESNEL),
        F::BASE_COLOR_TEXTURE_UV_B,
        F::SPECULAR_TEXTURE_UV_B,
        F::EMISSIVE_TEXTURE_UV_B,
        F::ALPHA_MAP_UV_B,
        F::NORMAL_MAP_UV_B,
        F::BUMP_MAP_UV_B,
        F::METALLIC_ROUGHNESS_MAP,
        F::METALLIC_ROUGHNESS_MAP_UV_B,
        F::METALLIC_ROUGHNESS_MAP.with(F::VERTEX_LIGHTING),
        F::METALLIC_ROUGHNESS_MAP
            .with(environment)
            .with(F::ENV_CAMERA),
        F::BASE_COLOR_TEXTURE_UV_B
            .with(F::SPECULAR_TEXTURE_UV_B)
            .with(F::EMISSIVE_TEXTURE_UV_B)
            .with(F::ALPHA_MAP_UV_B)
            .with(F::NORMAL_MAP_UV_B)
            .with(F::BUMP_MAP_UV_B)
            .with(F::LIGHT_MAP_UV_B)
            .with(F::AO_MAP_UV_B)
            .with(F::METALLIC_ROUGHNESS_MAP_UV_B),
    ]
    .into_iter()
    .map(|features| (features, F::NONE))
    .chain([
        (F::SPECULAR_TOON, F::NO_SPECULAR),
        (F::DIFFUSE_TOON.with(F::SPECULAR_TOON), F::NO_SPECULAR),
    ])
    .collect()
}

/// The fragment variants of a material that specializes as `PhongMaterial` does: every key
/// on the mesh with every attribute under the render tests' camera on both devices, the
/// covering keys on every other mesh and under every other camera.
pub fn phong_material() -> Vec<Variant> {
    material_variants(|mesh, view| {
        if mesh == RICHEST_MESH && view.starts_with(RENDER_TESTS_CAMERA) {
            every_key()
        } else {
            covering_keys()
        }
    })
}

/// The fragment variants of an extension of `PhongMaterial` (the searchlight example's), which
/// adds its own code but no defs: its code meets each of the crate's defs on and off, on both
/// devices ([`covering_def_sets`]). The meshes and cameras change only the crate's code
/// around it, which [`phong_material`] composes with each of them; composing the extension
/// on each again (about ten times the variants) would test nothing more of its own code.
pub fn phong_extension() -> Vec<Variant> {
    covering_def_sets()
}

/// A Phong material's variant for each distinct set of defs that `keys(mesh, view)` gives, on
/// every mesh under every camera.
fn material_variants(keys: impl Fn(&str, &str) -> Vec<PhongMaterialKey>) -> Vec<Variant> {
    let mut variants = Vec::new();
    for (mesh, layout) in mesh_layouts() {
        for (view, view_defs) in view_setups() {
            for phong in &distinct_phong_defs(&layout, &keys(mesh, &view)) {
                variants.push(phong_variant(mesh, &layout, &view, &view_defs, phong));
            }
        }
    }
    variants
}

/// The distinct sets of the crate's own defs that `keys` give on a mesh with `layout`, each
/// sorted.
fn distinct_phong_defs(
    layout: &MeshVertexBufferLayoutRef,
    keys: &[PhongMaterialKey],
) -> BTreeSet<Vec<&'static str>> {
    keys.iter()
        .map(|key| {
            let mut defs = key.shader_defs(layout);
            defs.sort_unstable();
            defs
        })
        .collect()
}

/// The variant of a Phong material on `mesh` (with `layout`), under `view`, with the
/// crate's defs `phong`.
fn phong_variant(
    mesh: &str,
    layout: &MeshVertexBufferLayoutRef,
    view: &str,
    view_defs: &[ShaderDefVal],
    phong: &[&'static str],
) -> Variant {
    let mut defs = mesh_defs(layout);
    defs.extend(view_defs.iter().cloned());
    defs.extend(phong.iter().map(|&def| def.into()));
    Variant {
        name: format!("mesh of {mesh}, {view}, {phong:?}"),
        defs,
    }
}

/// The crate's own defs in the combinations of the covering keys, on the mesh with every
/// attribute, seen by the render tests' camera on both [`devices`]: for the crate's modules
/// composed alone (all their functions, used or not), whose other defs the entry shaders
/// vary.
pub fn covering_def_sets() -> Vec<Variant> {
    let layout = mesh_layout(RICHEST_MESH);
    let combinations = distinct_phong_defs(&layout, &covering_keys());
    let mut variants = Vec::new();
    for (view, view_defs) in view_setups() {
        if !view.starts_with(RENDER_TESTS_CAMERA) {
            continue;
        }
        for phong in &combinations {
            variants.push(phong_variant(
                RICHEST_MESH,
                &layout,
                &view,
                &view_defs,
                phong,
            ));
        }
    }
    variants
}

/// Every def of the crate's own that some key gives on the mesh with every attribute.
pub fn every_crate_def() -> BTreeSet<&'static str> {
    let layout = mesh_layout(RICHEST_MESH);
    distinct_phong_defs(&layout, &every_key())
        .into_iter()
        .flatten()
        .collect()
}

/// The layout of the mesh named `mesh` in [`mesh_layouts`].
fn mesh_layout(mesh: &str) -> MeshVertexBufferLayoutRef {
    mesh_layouts()
        .into_iter()
        .find(|(name, _)| *name == mesh)
        .map(|(_, layout)| layout)
        .unwrap_or_else(|| panic!("no mesh {mesh}"))
}

/// The fragment variants of a material that adds no defs of its own (`SurfaceInputsMaterial`,
/// the benchmark's constant color): one per mesh and camera.
pub fn plain_material() -> Vec<Variant> {
    let mut variants = Vec::new();
    for (mesh, layout) in mesh_layouts() {
        for (view, view_defs) in view_setups() {
            let mut defs = mesh_defs(&layout);
            defs.extend(view_defs);
            variants.push(Variant {
                name: format!("mesh of {mesh}, {view}"),
                defs,
            });
        }
    }
    variants
}

/// A pipeline the crate builds itself, without defs (the shadow caster, the contract kernel).
pub fn without_defs() -> Vec<Variant> {
    vec![Variant {
        name: "no defs".into(),
        defs: Vec::new(),
    }]
}

/// The shadow caster's variants (`ShadowCasterKey` in `src/shadows/render.rs`): a mesh as
/// stored, and a posed one skinned, morphed or both, its deformation in storage buffers or
/// (under WebGL2's limits) in uniform buffers and a texture; displaced or not; opaque, or
/// masked by its base color alone, with its base color map, or with every map and its
/// vertex colors.
pub fn shadow_caster() -> Vec<Variant> {
    let mut variants = without_defs();
    let poses: [&[&str]; 4] = [&[], &["SKINNED"], &["MORPHED"], &["SKINNED", "MORPHED"]];
    let masks: [&[&str]; 6] = [
        &[],
        &["MASKED"],
        &["MASKED", "MASK_UVS", "MASK_BASE_COLOR_TEXTURE"],
        &[
            "MASKED",
            "MASK_UVS",
            "MASK_BASE_COLOR_TEXTURE",
            "MASK_ALPHA_MAP",
            "MASK_VERTEX_COLORS",
        ],
        &[
            "MASKED",
            "MASK_UVS",
            "MASK_UVS_B",
            "MASK_BASE_COLOR_TEXTURE",
            "MASK_ALPHA_MAP",
            "MASK_ALPHA_MAP_UV_B",
        ],
        &[
            "MASKED",
            "MASK_UVS_B",
            "MASK_BASE_COLOR_TEXTURE",
            "MASK_BASE_COLOR_UV_B",
            "MASK_ALPHA_MAP",
            "MASK_ALPHA_MAP_UV_B",
            "MASK_VERTEX_COLORS",
        ],
    ];
    for pose in poses {
        for uniforms in [false, true] {
            // Not displaced, displaced at the first UV set, at the second.
            for (displaced, mask) in [None, Some(false), Some(true)]
                .into_iter()
                .flat_map(|displaced| masks.map(|mask| (displaced, mask)))
            {
                let second_uvs = displaced == Some(true);
                let displaced = displaced.is_some();
                let mut defs: Vec<ShaderDefVal> = Vec::new();
                if !pose.is_empty() {
                    defs.push("POSED".into());
                    defs.extend(pose.iter().map(|&def| def.into()));
                    if uniforms {
                        defs.push("DEFORMATION_IN_UNIFORMS".into());
                    }
                } else if uniforms {
                    continue;
                }
                if displaced {
                    // After the posed groups: joints (0) and morphs (1).
                    let group = if pose.contains(&"MORPHED") {
                        2
                    } else {
                        pose.len().min(1)
                    };
                    defs.push("DISPLACED".into());
                    if second_uvs {
                        defs.push("DISPLACED_UV_B".into());
                    }
                    defs.push(ShaderDefVal::UInt(
                        "DISPLACEMENT_GROUP".into(),
                        group as u32,
                    ));
                }
                if !mask.is_empty() {
                    // After the posed groups and the displacement's.
                    let group = if pose.contains(&"MORPHED") {
                        2
                    } else {
                        pose.len().min(1)
                    } + usize::from(displaced);
                    defs.extend(mask.iter().map(|&def| def.into()));
                    defs.push(ShaderDefVal::UInt("MASK_GROUP".into(), group as u32));
                }
                if defs.is_empty() {
                    continue;
                }
                variants.push(Variant {
                    name: format!(
                        "{pose:?}, uniforms {uniforms}, displaced {displaced} \
                         (second UVs {second_uvs}), mask {mask:?}"
                    ),
                    defs,
                });
            }
        }
    }
    variants
}

/// The prepasses Bevy runs a fragment stage for (see [`phong_prepass`]).
const PREPASS_SETUPS: [(&str, &[&str]); 4] = [
    ("masked depth prepass", &["DEPTH_PREPASS", "MAY_DISCARD"]),
    (
        "normal prepass",
        &[
            "DEPTH_PREPASS",
            "NORMAL_PREPASS",
            "NORMAL_PREPASS_OR_DEFERRED_PREPASS",
        ],
    ),
    (
        "normal and motion-vector prepasses",
        &[
            "DEPTH_PREPASS",
            "NORMAL_PREPASS",
            "NORMAL_PREPASS_OR_DEFERRED_PREPASS",
            "MOTION_VECTOR_PREPASS",
            "MOTION_VECTOR_PREPASS_OR_DEFERRED_PREPASS",
        ],
    ),
    (
        "directional shadow map",
        &["UNCLIPPED_DEPTH_ORTHO_EMULATION", "MAY_DISCARD"],
    ),
];

/// The prepass fragment variants of a material that specializes as `PhongMaterial` does:
/// the defs of every key on the mesh with every attribute and of the covering keys on every
/// other mesh, in the prepasses Bevy runs a
/// fragment stage for (an alpha-masked depth prepass, the normal prepass, the normal and
/// motion-vector prepasses, a shadow map of a directional light emulating unclipped depth),
/// on both [`devices`] (Bevy's prepass pipeline, bevy_pbr 0.20.1 `prepass/mod.rs`).
pub fn phong_prepass() -> Vec<Variant> {
    let mut variants = Vec::new();
    for (mesh, layout) in mesh_layouts() {
        let keys = if mesh == RICHEST_MESH {
            every_key()
        } else {
            covering_keys()
        };
        let phong_defs = distinct_phong_defs(&layout, &keys);
        for (setup, setup_defs) in PREPASS_SETUPS {
            let prepass = prepass_defs(&layout, setup_defs);
            for (device, device_defs) in devices() {
                for phong in &phong_defs {
                    let mut defs = prepass.clone();
                    defs.extend(device_defs.iter().cloned());
                    defs.extend(phong.iter().map(|&def| def.into()));
                    variants.push(Variant {
                        name: format!("mesh of {mesh}, {setup}, {device}, {phong:?}"),
                        defs,
                    });
                }
            }
        }
    }
    variants
}

/// The defs of Bevy's prepass pipeline for a mesh of `layout` in the prepass `setup_defs`.
fn prepass_defs(
    layout: &MeshVertexBufferLayoutRef,
    setup_defs: &[&'static str],
) -> Vec<ShaderDefVal> {
    let normals = setup_defs.contains(&"NORMAL_PREPASS");
    let mut prepass: Vec<ShaderDefVal> = [
        "PREPASS_PIPELINE",
        "VERTEX_POSITIONS",
        "VERTEX_OUTPUT_INSTANCE_INDEX",
        "VIEW_PROJECTION_PERSPECTIVE",
    ]
    .into_iter()
    .chain(setup_defs.iter().copied())
    .map(Into::into)
    .collect();
    // Bevy declares the fragment's outputs only where it has some to write.
    if setup_defs != ["DEPTH_PREPASS", "MAY_DISCARD"] {
        prepass.push("PREPASS_FRAGMENT".into());
    }
    if layout.0.contains(Mesh::ATTRIBUTE_UV_0) {
        prepass.extend(["VERTEX_UVS".into(), "VERTEX_UVS_A".into()]);
    }
    if layout.0.contains(Mesh::ATTRIBUTE_UV_1) {
        prepass.extend(["VERTEX_UVS".into(), "VERTEX_UVS_B".into()]);
    }
    if layout.0.contains(Mesh::ATTRIBUTE_COLOR) {
        prepass.push("VERTEX_COLORS".into());
    }
    if normals {
        prepass.push("VERTEX_NORMALS".into());
        if layout.0.contains(Mesh::ATTRIBUTE_TANGENT) {
            prepass.push("VERTEX_TANGENTS".into());
        }
    }
    prepass.push(ShaderDefVal::UInt(
        "MATERIAL_BIND_GROUP".into(),
        MATERIAL_BIND_GROUP_INDEX as u32,
    ));
    prepass
}

/// How a displaced mesh may be posed: not at all, skinned, morphed, or both (each with last
/// frame's pose for motion vectors).
const POSES: [&[&str]; 4] = [
    &[],
    &["SKINNED", "HAS_PREVIOUS_SKIN"],
    &["MORPH_TARGETS", "HAS_PREVIOUS_MORPH"],
    &[
        "SKINNED",
        "HAS_PREVIOUS_SKIN",
        "MORPH_TARGETS",
        "HAS_PREVIOUS_MORPH",
    ],
];

/// The variants of the main pass's vertex stage of a material lit per vertex
/// (`PHONG_PER_VERTEX`; `light_at_vertices` gives it the fragment stage's defs): every
/// distinct set of the crate's defs with that feature that some key gives on some mesh,
/// under every camera and device, displaced too where the mesh can be.
pub fn vertex_lit_vertex() -> Vec<Variant> {
    let keys: Vec<PhongMaterialKey> = every_key()
        .into_iter()
        .filter(|key| key.has(MaterialFeatures::VERTEX_LIGHTING))
        .collect();
    let mut variants = Vec::new();
    for (mesh, layout) in mesh_layouts() {
        let phong_defs = distinct_phong_defs(&layout, &keys);
        let displaced =
            layout.0.contains(Mesh::ATTRIBUTE_UV_0) && layout.0.contains(Mesh::ATTRIBUTE_NORMAL);
        for (view, view_defs) in view_setups() {
            for phong in &phong_defs {
                let mut variant = phong_variant(mesh, &layout, &view, &view_defs, phong);
                if displaced {
                    variant.defs.push("PHONG_DISPLACEMENT_MAP".into());
                }
                variants.push(variant);
            }
        }
    }
    variants
}

/// The variants of the displaced vertex stages (`PHONG_DISPLACEMENT_MAP`): every mesh with
/// UVs and normals, each pose, under every camera and device (`prepass`: in every prepass).
pub fn displaced_vertex(prepass: bool) -> Vec<Variant> {
    let mut variants = Vec::new();
    for (mesh, layout) in mesh_layouts() {
        if !(layout.0.contains(Mesh::ATTRIBUTE_UV_0) && layout.0.contains(Mesh::ATTRIBUTE_NORMAL)) {
            continue;
        }
        let setups: Vec<(String, Vec<ShaderDefVal>)> = if prepass {
            PREPASS_SETUPS
                .iter()
                .flat_map(|(setup, setup_defs)| {
                    let defs = prepass_defs(&layout, setup_defs);
                    devices().map(|(device, device_defs)| {
                        let mut defs = defs.clone();
                        defs.extend(device_defs);
                        (format!("{setup}, {device}"), defs)
                    })
                })
                .collect()
        } else {
            view_setups()
                .into_iter()
                .map(|(view, view_defs)| {
                    let mut defs = mesh_defs(&layout);
                    defs.extend(view_defs);
                    (view, defs)
                })
                .collect()
        };
        // The map at the second UV set, on the mesh that has one.
        let uv_sets: &[bool] = if layout.0.contains(Mesh::ATTRIBUTE_UV_1) {
            &[false, true]
        } else {
            &[false]
        };
        for (setup, setup_defs) in &setups {
            for pose in POSES {
                for &second_uvs in uv_sets {
                    let mut defs = setup_defs.clone();
                    defs.push("PHONG_DISPLACEMENT_MAP".into());
                    if second_uvs {
                        defs.push("PHONG_DISPLACEMENT_UV_B".into());
                    }
                    defs.extend(pose.iter().map(|&def| def.into()));
                    variants.push(Variant {
                        name: format!("mesh of {mesh}, {setup}, {pose:?}, second UVs {second_uvs}"),
                        defs,
                    });
                }
            }
        }
    }
    variants
}
