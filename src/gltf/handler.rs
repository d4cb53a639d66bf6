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
/// `1 + strength · (texel − 1)` being the crate's AO formula, and `normalTexture.scale` as
/// `normal_map_scale` (glTF scales the map's x and y alike).
pub(crate) fn with_what_bevy_drops(phong: &mut PhongMaterial, material: &gltf::Material) {
    if let Some(occlusion) = material.occlusion_texture() {
        phong.ao_map_intensity = occlusion.strength();
    }
    if let Some(normal) = material.normal_texture() {
        phong.normal_map_scale = bevy::math::Vec2::splat(normal.scale());
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
        with_what_bevy_drops(&mut phong, gltf_material);
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
            r#"{{"asset": {{"version": "2.0"}}, "images": [{{"uri": "ao.png"}}],
                "textures": [{{"source": 0}}], "materials": {materials}}}"#
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
                with_what_bevy_drops(&mut phong, material);
                assert_eq!(phong.normal_map_scale, bevy::math::Vec2::splat(0.25));
            },
        );
    }

    #[test]
    fn the_occlusion_strength_is_read_from_the_file_as_the_ao_map_intensity() {
        first_material(
            r#"[{"occlusionTexture": {"index": 0, "strength": 0.5}}]"#,
            |material| {
                let mut phong = PhongMaterial::default();
                with_what_bevy_drops(&mut phong, material);
                assert_eq!(phong.ao_map_intensity, 0.5);
            },
        );
        // Absent, glTF's default strength 1.
        first_material(r#"[{"occlusionTexture": {"index": 0}}]"#, |material| {
            let mut phong = PhongMaterial {
                ao_map_intensity: 0.25,
                ..PhongMaterial::default()
            };
            with_what_bevy_drops(&mut phong, material);
            assert_eq!(phong.ao_map_intensity, 1.0);
        });
    }
}
