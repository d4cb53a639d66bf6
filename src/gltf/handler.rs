//! The glTF extension handler that gives each material of a glTF file a [`PhongMaterial`]
//! and each spawned primitive a `MeshMaterial3d<PhongMaterial>`.

use super::material::phong_material_from_gltf;
use crate::material::PhongMaterial;
use bevy::{
    asset::{Handle, LoadContext},
    ecs::world::EntityWorldMut,
    gltf::{
        GltfAssetLabel, GltfLoaderSettings, GltfMaterial,
        extensions::{ErasedGltfExtensionHandler, GltfExtensionHandler},
        gltf,
    },
    log::warn,
    mesh::UvChannel,
    pbr::MeshMaterial3d,
};

/// The suffix of the Phong sub-asset of a glTF material: `Material0/phong`,
/// `DefaultMaterial/phong`.
pub const PHONG_LABEL_SUFFIX: &str = "/phong";

/// The label of the [`PhongMaterial`] made from the glTF material labeled `material_label`
/// (`"Material0"` gives `"Material0/phong"`, `"DefaultMaterial"` gives
/// `"DefaultMaterial/phong"`). Load one alone with
/// `asset_server.load("scene.gltf#Material0/phong")`.
pub fn phong_material_label(material_label: &str) -> String {
    format!("{material_label}{PHONG_LABEL_SUFFIX}")
}

/// Sets on `phong` what Bevy's loader drops from the file's `material` (its `GltfMaterial`
/// has no field for them): `occlusionTexture.strength` as `ao_map_intensity`, glTF's
/// `1 + strength · (texel − 1)` being the crate's AO formula; `normalTexture.scale` as
/// `normal_map_scale` (glTF scales the map's x and y alike); and each map's UV set with
/// `KHR_texture_transform`'s `texCoord`, which overrides the texture's own. `label` names
/// the material in warnings: a texCoord past 1 reads the first set, and a transform on a
/// texture read at the second set is not applied (the crate moves the first set only).
pub(crate) fn with_what_bevy_drops(
    phong: &mut PhongMaterial,
    material: &gltf::Material,
    label: &str,
) {
    let pbr = material.pbr_metallic_roughness();
    if let Some(info) = pbr.base_color_texture() {
        phong.base_color_channel = info_channel(&info, "baseColorTexture", label);
    }
    if let Some(info) = pbr.metallic_roughness_texture() {
        phong.metallic_roughness_channel = info_channel(&info, "metallicRoughnessTexture", label);
    }
    if let Some(info) = material.emissive_texture() {
        phong.emissive_channel = info_channel(&info, "emissiveTexture", label);
    }
    if let Some(normal) = material.normal_texture() {
        phong.normal_map_scale = bevy::math::Vec2::splat(normal.scale());
        let transform = TransformOf::json(normal.extension_value(TEXTURE_TRANSFORM));
        phong.normal_map_channel =
            uv_channel(normal.tex_coord(), transform, "normalTexture", label);
    }
    if let Some(occlusion) = material.occlusion_texture() {
        phong.ao_map_intensity = occlusion.strength();
        let transform = TransformOf::json(occlusion.extension_value(TEXTURE_TRANSFORM));
        phong.ao_map_channel =
            uv_channel(occlusion.tex_coord(), transform, "occlusionTexture", label);
    }
}

/// The extension whose `texCoord` overrides a texture's.
const TEXTURE_TRANSFORM: &str = "KHR_texture_transform";

/// A texture's `KHR_texture_transform`: the UV set it names, and whether it moves the UVs.
#[derive(Clone, Copy, Debug, Default)]
struct TransformOf {
    tex_coord: Option<u64>,
    moves: bool,
}

impl TransformOf {
    /// As the gltf crate parses it on a `textureInfo`.
    fn parsed(info: &gltf::texture::Info) -> Self {
        info.texture_transform()
            .map_or_else(Self::default, |transform| Self {
                tex_coord: transform.tex_coord().map(u64::from),
                moves: transform.offset() != [0.0; 2]
                    || transform.rotation() != 0.0
                    || transform.scale() != [1.0; 2],
            })
    }

    /// As JSON, where the gltf crate leaves it (normal and occlusion textures).
    fn json(extension: Option<&gltf::json::Value>) -> Self {
        extension.map_or_else(Self::default, |transform| Self {
            tex_coord: transform
                .get("texCoord")
                .and_then(gltf::json::Value::as_u64),
            moves: ["offset", "rotation", "scale"]
                .iter()
                .any(|key| transform.get(key).is_some()),
        })
    }
}

/// The UV set of a `textureInfo` (base color, emissive).
fn info_channel(info: &gltf::texture::Info, texture: &str, label: &str) -> UvChannel {
    uv_channel(info.tex_coord(), TransformOf::parsed(info), texture, label)
}

/// The UV set a texture is read at: its `KHR_texture_transform`'s `texCoord` where it has
/// one, else the texture's `tex_coord`; 0 is the first set, 1 the second, and a later set
/// (which Bevy's meshes do not carry) the first, with a warning.
fn uv_channel(tex_coord: u32, transform: TransformOf, texture: &str, label: &str) -> UvChannel {
    match transform.tex_coord.unwrap_or(u64::from(tex_coord)) {
        0 => UvChannel::Uv0,
        1 => {
            if transform.moves {
                warn!(
                    "glTF material {label}: the {texture}'s KHR_texture_transform is not \
                     applied to the second UV set it reads (PhongMaterial::uv_transform moves \
                     the first only)"
                );
            }
            UvChannel::Uv1
        }
        set => {
            warn!(
                "glTF material {label}: the {texture} reads TEXCOORD_{set}; PhongMaterial reads \
                 the first UV set instead (a Bevy mesh carries two)"
            );
            UvChannel::Uv0
        }
    }
}

/// Registered by [`PhongGltfPlugin`](super::PhongGltfPlugin); cloned for each load.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PhongGltfExtensionHandler;

impl GltfExtensionHandler for PhongGltfExtensionHandler {
    fn dyn_clone(&self) -> Box<dyn ErasedGltfExtensionHandler> {
        Box::new(*self)
    }

    /// Adds `DefaultMaterial/phong`, for primitives without a material.
    fn on_root(
        &mut self,
        load_context: &mut LoadContext<'_>,
        _gltf: &gltf::Gltf,
        _settings: &GltfLoaderSettings,
    ) {
        let label = GltfAssetLabel::DefaultMaterial.to_string();
        load_context.add_labeled_asset(
            phong_material_label(&label),
            phong_material_from_gltf(&GltfMaterial::default(), None),
        );
    }

    /// Adds `Material{n}/phong` (also for the `Material{n} (inverted)` copies Bevy makes for
    /// nodes of negative scale), warning once about what it leaves out.
    fn on_material(
        &mut self,
        load_context: &mut LoadContext<'_>,
        gltf_material: &gltf::Material,
        _material: Handle<GltfMaterial>,
        material_asset: &GltfMaterial,
        material_label: &str,
    ) {
        let path = load_context.path().clone();
        let named = format!("{path}#{material_label}");
        let mut phong = phong_material_from_gltf(material_asset, Some(&named));
        with_what_bevy_drops(&mut phong, gltf_material, &named);
        load_context.add_labeled_asset(phong_material_label(material_label), phong);
    }

    /// Inserts `MeshMaterial3d<PhongMaterial>` with the primitive's material.
    fn on_spawn_mesh_and_material(
        &mut self,
        load_context: &mut LoadContext<'_>,
        _primitive: &gltf::Primitive,
        _mesh: &gltf::Mesh,
        _material: &gltf::Material,
        entity: &mut EntityWorldMut,
        material_label: &str,
    ) {
        let handle =
            load_context.get_label_handle::<PhongMaterial>(phong_material_label(material_label));
        entity.insert(MeshMaterial3d(handle));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first material of a file whose materials are `materials` (JSON), with one texture.
    fn first_material(materials: &str, check: impl FnOnce(&gltf::Material)) {
        let json = format!(
            r#"{{"asset": {{"version": "2.0"}}, "extensionsUsed": ["KHR_texture_transform"],
                "images": [{{"uri": "ao.png"}}], "textures": [{{"source": 0}}],
                "materials": {materials}}}"#
        );
        let file = gltf::Gltf::from_slice(json.as_bytes()).expect("a valid glTF document");
        check(&file.materials().next().expect("one material"));
    }

    #[test]
    fn the_normal_texture_scale_is_read_from_the_file_as_the_normal_map_scale() {
        first_material(
            r#"[{"normalTexture": {"index": 0, "scale": 0.25}}]"#,
            |material| {
                let mut phong = PhongMaterial::default();
                with_what_bevy_drops(&mut phong, material, "test");
                assert_eq!(phong.normal_map_scale, bevy::math::Vec2::splat(0.25));
            },
        );
    }

    #[test]
    fn each_map_reads_the_uv_set_its_texture_transform_names_over_its_own() {
        first_material(
            r#"[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 0,
                    "extensions": {"KHR_texture_transform": {"texCoord": 1}}}},
                 "emissiveTexture": {"index": 0, "texCoord": 1},
                 "normalTexture": {"index": 0,
                    "extensions": {"KHR_texture_transform": {"texCoord": 1}}},
                 "occlusionTexture": {"index": 0, "texCoord": 1,
                    "extensions": {"KHR_texture_transform": {"texCoord": 0}}}}]"#,
            |material| {
                let mut phong = PhongMaterial::default();
                with_what_bevy_drops(&mut phong, material, "test");
                assert_eq!(phong.base_color_channel, UvChannel::Uv1);
                assert_eq!(phong.emissive_channel, UvChannel::Uv1);
                assert_eq!(phong.normal_map_channel, UvChannel::Uv1);
                assert_eq!(phong.ao_map_channel, UvChannel::Uv0);
            },
        );
        // A set past the second reads the first (with a warning).
        first_material(
            r#"[{"emissiveTexture": {"index": 0, "texCoord": 2}}]"#,
            |material| {
                let mut phong = PhongMaterial {
                    emissive_channel: UvChannel::Uv1,
                    ..PhongMaterial::default()
                };
                with_what_bevy_drops(&mut phong, material, "test");
                assert_eq!(phong.emissive_channel, UvChannel::Uv0);
            },
        );
    }

    #[test]
    fn the_occlusion_strength_is_read_from_the_file_as_the_ao_map_intensity() {
        first_material(
            r#"[{"occlusionTexture": {"index": 0, "strength": 0.5}}]"#,
            |material| {
                let mut phong = PhongMaterial::default();
                with_what_bevy_drops(&mut phong, material, "test");
                assert_eq!(phong.ao_map_intensity, 0.5);
            },
        );
        // Absent, glTF's default strength 1.
        first_material(r#"[{"occlusionTexture": {"index": 0}}]"#, |material| {
            let mut phong = PhongMaterial {
                ao_map_intensity: 0.25,
                ..PhongMaterial::default()
            };
            with_what_bevy_drops(&mut phong, material, "test");
            assert_eq!(phong.ao_map_intensity, 1.0);
        });
    }
}
