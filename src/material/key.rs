//! [`PhongMaterialKey`]: the shader variant a material is drawn with, and its shader defs on
//! a mesh.

use super::PhongMaterial;
use super::features::{MATERIAL_FEATURES, MaterialFeatures, MeshNeeds};
use crate::{limits, scene_variants::SceneKey};
use bevy::{
    log::warn,
    mesh::{Mesh, MeshVertexBufferLayoutRef},
    render::render_resource::Face,
};

/// The shader variant a [`PhongMaterial`] is drawn with: materials with equal keys share a
/// pipeline.
///
/// Its [`MaterialFeatures`] say which shader code the material needs, each feature with its
/// shader defs (listed on each constant of [`MaterialFeatures`]): materials without maps
/// sample nothing, an unlit material has no lighting code at all, a material without a
/// highlight leaves the specular term out (`PHONG_NO_SPECULAR`). A variant is compiled the
/// first time a material needs it; meanwhile Bevy draws nothing for the meshes that wait for
/// it. To avoid that gap when a material switches a feature on or off while the game runs,
/// create a material of each kind at load time: compiled pipelines are kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PhongMaterialKey {
    /// The features the material has.
    pub features: MaterialFeatures,
    /// The faces culled (before [`MaterialFeatures::DOUBLE_SIDED`] and mirrored views: see
    /// [`PhongMaterialKey::culled_face`]).
    pub cull_mode: Option<Face>,
    /// The constant depth bias, in the depth buffer's steps.
    pub depth_bias: i32,
}

impl From<&PhongMaterial> for PhongMaterialKey {
    fn from(material: &PhongMaterial) -> Self {
        Self {
            features: MaterialFeatures::of(material),
            cull_mode: material.cull_mode,
            depth_bias: limits::DEPTH_BIAS.apply(material.depth_bias) as i32,
        }
    }
}

impl PhongMaterialKey {
    /// This key with the render world's part (the scene's variants, and whether the bind
    /// group is a class's) set to `scene`.
    pub(crate) fn in_scene(self, scene: &SceneKey) -> Self {
        Self {
            features: self
                .features
                .without(MaterialFeatures::of_the_scene_part())
                .with(MaterialFeatures::of_scene(scene)),
            ..self
        }
    }

    /// Whether the material has every feature of `features`.
    pub fn has(&self, features: MaterialFeatures) -> bool {
        self.features.contains(features)
    }

    /// The face a view culls: none for a double-sided material, else `cull_mode`, the
    /// other face in views that mirror the scene (`mirrored`, Bevy's `INVERT_CULLING`).
    pub fn culled_face(&self, mirrored: bool) -> Option<Face> {
        if self.has(MaterialFeatures::DOUBLE_SIDED) {
            return None;
        }
        culled_in_view(self.cull_mode, mirrored)
    }

    /// The fragment shader defs of this variant on a mesh with `layout`, beside those Bevy's
    /// mesh pipeline adds: each feature's defs, where the mesh has what the feature needs
    /// (maps need their UV set, the normal and bump maps tangents too); where it does not, the feature
    /// is left out, with a warning. A material extending [`PhongMaterial`] is specialized
    /// with the same defs.
    pub fn shader_defs(&self, layout: &MeshVertexBufferLayoutRef) -> Vec<&'static str> {
        let has_uvs = layout.0.contains(Mesh::ATTRIBUTE_UV_0);
        let has_second_uvs = layout.0.contains(Mesh::ATTRIBUTE_UV_1);
        let has_tangents = layout.0.contains(Mesh::ATTRIBUTE_TANGENT);
        let features = || {
            MATERIAL_FEATURES
                .iter()
                .filter(|feature| self.has(feature.bit))
        };
        let meets = |needs: MeshNeeds| match needs {
            MeshNeeds::Nothing | MeshNeeds::SampledUv0Map => true,
            MeshNeeds::Uv0 => has_uvs,
            MeshNeeds::Uv1 => has_second_uvs,
            MeshNeeds::Uv0AndTangents => has_uvs && has_tangents,
            MeshNeeds::Uv1AndTangents => has_second_uvs && has_tangents,
        };
        let samples_uv0 = features().any(|feature| {
            matches!(feature.needs, MeshNeeds::Uv0 | MeshNeeds::Uv0AndTangents)
                && meets(feature.needs)
        });
        let mut defs: Vec<&'static str> = Vec::new();
        for feature in features() {
            let drawn = match feature.needs {
                MeshNeeds::SampledUv0Map => samples_uv0,
                needs => meets(needs),
            };
            if drawn {
                for define in feature.defines {
                    if !defs.contains(define) {
                        defs.push(define);
                    }
                }
            } else if let Some(missing) = missing_attributes(feature.needs) {
                warn!(
                    "PhongMaterial.{} is ignored on a mesh without {missing}",
                    feature.field
                );
            }
        }
        defs
    }
}

/// The mesh attributes a feature that needs `needs` is missing, as a warning names them.
fn missing_attributes(needs: MeshNeeds) -> Option<&'static str> {
    match needs {
        MeshNeeds::Nothing | MeshNeeds::SampledUv0Map => None,
        MeshNeeds::Uv0 => Some("UVs (Mesh::ATTRIBUTE_UV_0)"),
        MeshNeeds::Uv1 => Some("its UV set (Mesh::ATTRIBUTE_UV_1)"),
        MeshNeeds::Uv0AndTangents => Some(
            "UVs and tangents (Mesh::ATTRIBUTE_UV_0, Mesh::ATTRIBUTE_TANGENT: \
             Mesh::with_generated_tangents)",
        ),
        MeshNeeds::Uv1AndTangents => Some(
            "its UV set and tangents (Mesh::ATTRIBUTE_UV_1, Mesh::ATTRIBUTE_TANGENT: \
             Mesh::with_generated_tangents)",
        ),
    }
}

/// The face a view culls of a material that culls `cull_mode`: that face, or the other in
/// views that mirror the scene (`mirrored`, Bevy's `INVERT_CULLING`), whose triangles wind
/// the other way.
pub(crate) fn culled_in_view(cull_mode: Option<Face>, mirrored: bool) -> Option<Face> {
    match (cull_mode, mirrored) {
        (Some(Face::Back), false) | (Some(Face::Front), true) => Some(Face::Back),
        (Some(Face::Front), false) | (Some(Face::Back), true) => Some(Face::Front),
        (None, _) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::features::{MATERIAL_FEATURES, Switch};
    use crate::scene_variants::SceneVariants;
    use bevy::{
        asset::{Handle, RenderAssetUsages},
        image::Image,
        mesh::{MeshVertexBufferLayouts, PrimitiveTopology, UvChannel},
        reflect::structs::Struct,
    };
    use std::collections::BTreeSet;

    /// The layout of a mesh with UVs and tangents (`tangents`), or with neither.
    fn layout(uvs_and_tangents: bool) -> MeshVertexBufferLayoutRef {
        let mut mesh = Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::all())
            .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, vec![[0.0f32; 3]; 3])
            .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, vec![[0.0f32, 1.0, 0.0]; 3]);
        if uvs_and_tangents {
            mesh.insert_attribute(Mesh::ATTRIBUTE_UV_0, vec![[0.0f32; 2]; 3]);
            mesh.insert_attribute(Mesh::ATTRIBUTE_TANGENT, vec![[1.0f32, 0.0, 0.0, 1.0]; 3]);
        }
        mesh.get_mesh_vertex_buffer_layout(&mut MeshVertexBufferLayouts::default())
    }

    #[test]
    fn each_feature_has_its_own_bit_and_names_a_field_of_the_material() {
        let material = PhongMaterial::default();
        let mut bits = MaterialFeatures::NONE;
        for feature in MATERIAL_FEATURES {
            assert!(
                !bits.contains(feature.bit),
                "{}: a bit taken",
                feature.field
            );
            bits = bits.with(feature.bit);
            // A scene row names a field of the render world's part of the key.
            assert!(
                matches!(feature.switch, Switch::Scene(_))
                    || material.field(feature.field).is_some(),
                "PhongMaterial has no field {}",
                feature.field
            );
        }
    }

    #[test]
    fn the_render_world_sets_the_scene_part_of_a_key_and_nothing_else() {
        let material = PhongMaterial {
            double_sided: true,
            ..Default::default()
        };
        let key = PhongMaterialKey::from(&material);
        assert!(
            !key.features.contains(MaterialFeatures::SHADOWS),
            "a material has none of the scene's features of itself"
        );
        let scene = SceneKey {
            variants: SceneVariants {
                shadows: true,
                cookies: true,
                ..Default::default()
            },
            from_records: true,
        };
        let in_scene = key.in_scene(&scene);
        for feature in [
            MaterialFeatures::SHADOWS,
            MaterialFeatures::LIGHT_COOKIES,
            MaterialFeatures::MATERIAL_RECORDS,
            MaterialFeatures::DOUBLE_SIDED,
        ] {
            assert!(in_scene.has(feature), "{feature:?}");
        }
        assert!(!in_scene.has(MaterialFeatures::HEMISPHERE));
        let back = in_scene.in_scene(&SceneKey::default());
        assert_eq!(
            back, key,
            "a later scene replaces the scene's part, and only it"
        );
    }

    /// The `PHONG_` names in the conditions (`@if(…)`, `@elif(…)`) of the crate's shaders.
    fn conditions_of_the_shaders() -> BTreeSet<String> {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut names = BTreeSet::new();
        for dir in ["src/shaders", "assets/shaders"] {
            for entry in std::fs::read_dir(root.join(dir)).unwrap() {
                let source = std::fs::read_to_string(entry.unwrap().path()).unwrap();
                for condition in source.split("@if(").chain(source.split("@elif(")).skip(1) {
                    let condition = condition.split(')').next().unwrap_or_default();
                    names.extend(
                        condition
                            .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                            .filter(|word| word.starts_with("PHONG_"))
                            .map(str::to_owned),
                    );
                }
            }
        }
        names
    }

    #[test]
    fn the_table_declares_every_material_def_the_shaders_read_and_only_those() {
        let declared: BTreeSet<String> = MATERIAL_FEATURES
            .iter()
            .flat_map(|feature| feature.defines.iter().map(|def| def.to_string()))
            .collect();
        let mut read = conditions_of_the_shaders();
        // Set by every pipeline from its bind group layout, not by a material.
        assert!(read.remove("PHONG_STORAGE_BUFFERS"));
        // The vertex stage's, set with the crate's vertex shaders (`displacement::displace`)
        // for `MaterialFeatures::DISPLACEMENT`.
        assert!(read.remove("PHONG_DISPLACEMENT_MAP"));
        assert!(read.remove("PHONG_DISPLACEMENT_UV_B"));
        assert_eq!(declared, read);
    }

    #[test]
    fn a_material_gets_the_defs_of_its_features_where_its_mesh_can_draw_them() {
        let image = Handle::<Image>::default();
        let material = PhongMaterial {
            base_color_texture: Some(image.clone()),
            normal_map_texture: Some(image.clone()),
            light_map_texture: Some(image),
            light_map_channel: UvChannel::Uv1,
            uv_transform: bevy::math::Affine2::from_scale(bevy::math::Vec2::splat(2.0)),
            unlit: true,
            ..PhongMaterial::default()
        };
        let key = PhongMaterialKey::from(&material);
        let sorted = |mut defs: Vec<&'static str>| {
            defs.sort_unstable();
            defs
        };
        assert_eq!(
            sorted(key.shader_defs(&layout(true))),
            [
                "PHONG_BASE_COLOR_TEXTURE",
                "PHONG_NORMAL_MAP",
                "PHONG_UNLIT",
                "PHONG_UV_TRANSFORM"
            ],
            "no second UV set: no light map"
        );
        assert_eq!(
            key.shader_defs(&layout(false)),
            ["PHONG_UNLIT"],
            "no UVs: no map, and no UV transform without a map"
        );
        let plain = PhongMaterialKey::from(&PhongMaterial::default());
        assert_eq!(plain.features, MaterialFeatures::NONE);
        assert!(plain.shader_defs(&layout(true)).is_empty());
    }

    #[test]
    fn maps_on_the_second_uv_set_need_it_and_are_not_moved_by_the_uv_transform() {
        let image = Handle::<Image>::default();
        let material = PhongMaterial {
            base_color_texture: Some(image.clone()),
            base_color_channel: UvChannel::Uv1,
            normal_map_texture: Some(image),
            normal_map_channel: UvChannel::Uv1,
            uv_transform: bevy::math::Affine2::from_scale(bevy::math::Vec2::splat(2.0)),
            ..PhongMaterial::default()
        };
        let key = PhongMaterialKey::from(&material);
        let mut with_second_uvs =
            Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::all())
                .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, vec![[0.0f32; 3]; 3])
                .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, vec![[0.0f32, 1.0, 0.0]; 3])
                .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, vec![[0.0f32; 2]; 3])
                .with_inserted_attribute(Mesh::ATTRIBUTE_UV_1, vec![[0.0f32; 2]; 3]);
        with_second_uvs.insert_attribute(Mesh::ATTRIBUTE_TANGENT, vec![[1.0f32, 0.0, 0.0, 1.0]; 3]);
        let layout_b =
            with_second_uvs.get_mesh_vertex_buffer_layout(&mut MeshVertexBufferLayouts::default());
        let mut defs = key.shader_defs(&layout_b);
        defs.sort_unstable();
        assert_eq!(
            defs,
            [
                "PHONG_BASE_COLOR_TEXTURE",
                "PHONG_BASE_COLOR_UV_B",
                "PHONG_NORMAL_MAP",
                "PHONG_NORMAL_MAP_UV_B",
            ],
            "both maps on the second set; the transform moves no map"
        );
        assert!(
            key.shader_defs(&layout(true)).is_empty(),
            "no second UV set: neither map"
        );
    }
}
