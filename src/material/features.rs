//! The switches of a material's shader variant, each declared once: its bit in
//! [`MaterialFeatures`], when a material has it, the shader defs it sets and what it needs of
//! the mesh. [`PhongMaterialKey`](super::PhongMaterialKey) holds the bits, and
//! `shader_defs` turns them into defs; a material feature that switches shader code adds one
//! row to [`material_features!`]'s table below and nothing else on the Rust side.

use super::{
    DiffuseMode, EnvironmentCombine, PhongMaterial, PhongMaterialUniform, SpecularMode,
    SpecularModel,
};
use crate::{limits, scene_variants::SceneKey};
use bevy::{
    asset::Handle,
    math::{Affine2, Vec3},
    mesh::UvChannel,
    prelude::{AlphaMode, Image},
};

/// What a feature needs of the mesh to be drawn: a mesh without it draws the material
/// without the feature, with a warning naming the field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum MeshNeeds {
    /// Nothing.
    Nothing,
    /// UVs (`Mesh::ATTRIBUTE_UV_0`).
    Uv0,
    /// A second UV set (`Mesh::ATTRIBUTE_UV_1`).
    Uv1,
    /// UVs and tangents (`Mesh::ATTRIBUTE_UV_0`, `Mesh::ATTRIBUTE_TANGENT`).
    Uv0AndTangents,
    /// A second UV set and tangents (`Mesh::ATTRIBUTE_UV_1`, `Mesh::ATTRIBUTE_TANGENT`).
    Uv1AndTangents,
    /// Some other feature of the material sampling a map at the first UV set (what a UV
    /// transform moves).
    SampledUv0Map,
}

/// What switches a feature on: the material's own fields, or the part of its key that the
/// render world sets ([`SceneKey`]).
#[derive(Clone, Copy)]
pub(crate) enum Switch {
    /// Whether a material has the feature, its numbers as the shader reads them (the
    /// uniform).
    Material(fn(&PhongMaterial, &PhongMaterialUniform) -> bool),
    /// Whether the render world's part of the key has it.
    Scene(fn(&SceneKey) -> bool),
}

/// One row of the table: the field that switches the feature (of the material, for
/// warnings, or of [`SceneKey`]), its shader defs, what it needs of the mesh, and what
/// switches it on.
pub(crate) struct MaterialFeature {
    pub bit: MaterialFeatures,
    pub field: &'static str,
    pub defines: &'static [&'static str],
    pub needs: MeshNeeds,
    pub switch: Switch,
}

/// Declares each feature once: a constant of [`MaterialFeatures`] (its bit, in order) and a
/// row of [`MATERIAL_FEATURES`]. A row's switch is `|material, uniform| …` (a
/// [`Switch::Material`]) or `scene |key| …` (a [`Switch::Scene`]).
macro_rules! material_features {
    ($(
        $(#[doc = $doc:literal])*
        $name:ident: $field:literal, [$($define:literal),*], $needs:ident,
            $($scene:ident)? |$($argument:ident),+| $on:expr;
    )*) => {
        impl MaterialFeatures {
            material_features!(@bits 0u64; $($(#[doc = $doc])* $name,)*);
        }

        /// Every feature, in the order of its bit.
        pub(crate) const MATERIAL_FEATURES: &[MaterialFeature] = &[$(
            MaterialFeature {
                bit: MaterialFeatures::$name,
                field: $field,
                defines: &[$($define),*],
                needs: MeshNeeds::$needs,
                switch: material_features!(@switch [$($scene)?] |$($argument),+| $on),
            },
        )*];
    };
    (@switch [] |$material:ident, $uniform:ident| $on:expr) => {
        Switch::Material(|$material, $uniform| {
            let _ = (&$material, &$uniform);
            $on
        })
    };
    (@switch [scene] |$key:ident| $on:expr) => {
        Switch::Scene(|$key| $on)
    };
    (@bits $bit:expr; $(#[doc = $doc:literal])* $name:ident, $($rest:tt)*) => {
        $(#[doc = $doc])*
        pub const $name: Self = Self(1 << $bit);
        material_features!(@bits $bit + 1; $($rest)*);
    };
    (@bits $bit:expr;) => {};
}

/// The shader-variant switches a material has (see [`PhongMaterialKey`](super::PhongMaterialKey)):
/// a set of bits, one per feature, each declared with its shader defs in one table.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct MaterialFeatures(u64);

impl MaterialFeatures {
    /// No feature.
    pub const NONE: Self = Self(0);

    /// Whether every feature of `other` is in `self`.
    pub const fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }

    /// `self` with the features of `other` added.
    #[must_use]
    pub const fn with(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }

    /// `self` without the features of `other`.
    #[must_use]
    pub const fn without(self, other: Self) -> Self {
        Self(self.0 & !other.0)
    }

    /// The features `material` has of itself (the scene's, which the render world adds to
    /// its key, left out).
    pub fn of(material: &PhongMaterial) -> Self {
        // The numbers in their ranges, as the shader reads them.
        let uniform = PhongMaterialUniform::from(material);
        Self::switched(|switch| match switch {
            Switch::Material(on) => on(material, &uniform),
            Switch::Scene(_) => false,
        })
    }

    /// The features the render world's part of a key (`scene`) switches on.
    pub(crate) fn of_scene(scene: &SceneKey) -> Self {
        Self::switched(|switch| matches!(switch, Switch::Scene(on) if on(scene)))
    }

    /// Every feature the render world's part of a key switches.
    pub(crate) fn of_the_scene_part() -> Self {
        Self::switched(|switch| matches!(switch, Switch::Scene(_)))
    }

    /// The features whose switch `on` says is on.
    fn switched(on: impl Fn(Switch) -> bool) -> Self {
        MATERIAL_FEATURES
            .iter()
            .filter(|feature| on(feature.switch))
            .fold(Self::NONE, |features, feature| features.with(feature.bit))
    }
}

/// Whether `material` has a specular term, its numbers in range (`uniform`): a non-zero
/// `k_s · strength`, or for the normalized model, whose Fresnel term lights grazing angles
/// even on a black specular color, a non-zero strength.
fn has_specular(material: &PhongMaterial, uniform: &PhongMaterialUniform) -> bool {
    // A metallic-roughness map's metal reflects its base color, whatever `k_s`.
    let lit = if material.specular_model == SpecularModel::NormalizedBlinnPhong
        || has_metallic_roughness_map(material)
    {
        material.in_range().specular_strength > 0.0
    } else {
        uniform.specular != Vec3::ZERO
    };
    lit && material.specular_mode != SpecularMode::Off
}

/// Whether `material` draws a metallic-roughness map: it has one and is lit.
fn has_metallic_roughness_map(material: &PhongMaterial) -> bool {
    material.metallic_roughness_texture.is_some() && !material.unlit
}

/// Whether `material` has an environment (its own cube, or the camera's).
fn has_environment(material: &PhongMaterial) -> bool {
    material.environment_map.is_some() || material.camera_environment
}

/// Whether a map `texture` is present and read at the second UV set (`second`) or the
/// first, as `channel` says.
fn map_at(texture: &Option<Handle<Image>>, channel: &UvChannel, second: bool) -> bool {
    texture.is_some() && matches!(channel, UvChannel::Uv1) == second
}

material_features! {
    /// No specular term: a black `specular_color`, a zero `specular_strength` or
    /// `SpecularMode::Off` (`PHONG_NO_SPECULAR`).
    NO_SPECULAR: "specular_color", ["PHONG_NO_SPECULAR"], Nothing,
        |m, u| !has_specular(m, u);
    /// Schlick's Fresnel term on the highlight (`PHONG_FRESNEL`, normalized Blinn-Phong).
    FRESNEL: "specular_model", ["PHONG_FRESNEL"], Nothing,
        |m, u| has_specular(m, u) && m.specular_model == SpecularModel::NormalizedBlinnPhong;
    /// A toon highlight (`PHONG_SPECULAR_TOON`).
    SPECULAR_TOON: "specular_mode", ["PHONG_SPECULAR_TOON"], Nothing,
        |m, u| has_specular(m, u) && matches!(m.specular_mode, SpecularMode::Toon { .. });
    /// A rim light everywhere (`PHONG_RIM`).
    RIM: "rim_color", ["PHONG_RIM"], Nothing,
        |m, u| u.rim.truncate() != Vec3::ZERO && !m.rim_lit_side;
    /// A rim light on the lit side only (`PHONG_RIM_LIT`).
    RIM_LIT: "rim_color", ["PHONG_RIM_LIT"], Nothing,
        |m, u| u.rim.truncate() != Vec3::ZERO && m.rim_lit_side;
    /// Wrapped diffuse light (`PHONG_DIFFUSE_WRAP`, lit past the terminator).
    DIFFUSE_WRAP: "diffuse_mode", ["PHONG_DIFFUSE_WRAP", "PHONG_LIT_PAST_TERMINATOR"], Nothing,
        |m, u| matches!(m.diffuse_mode, DiffuseMode::Wrap(_));
    /// Toon bands (`PHONG_DIFFUSE_TOON`).
    DIFFUSE_TOON: "diffuse_mode", ["PHONG_DIFFUSE_TOON"], Nothing,
        |m, u| matches!(m.diffuse_mode, DiffuseMode::Toon { .. }) && m.toon_ramp_texture.is_none();
    /// A toon ramp texture (`PHONG_DIFFUSE_TOON` with `PHONG_TOON_RAMP`, lit past the
    /// terminator).
    TOON_RAMP: "toon_ramp_texture",
        ["PHONG_DIFFUSE_TOON", "PHONG_TOON_RAMP", "PHONG_LIT_PAST_TERMINATOR"], Nothing,
        |m, u| matches!(m.diffuse_mode, DiffuseMode::Toon { .. }) && m.toon_ramp_texture.is_some();
    /// Drawn without light (`PHONG_UNLIT`).
    UNLIT: "unlit", ["PHONG_UNLIT"], Nothing, |m, u| m.unlit;
    /// Lit with its faces' normals (`PHONG_FLAT_SHADING`).
    FLAT_SHADING: "flat_shading", ["PHONG_FLAT_SHADING"], Nothing, |m, u| m.flat_shading;
    /// Lit per vertex (`PHONG_PER_VERTEX`, in both stages: the crate's vertex shader sums
    /// the lights, the fragment weighs them); an unlit material has no light to sum.
    VERTEX_LIGHTING: "vertex_lighting", ["PHONG_PER_VERTEX"], Nothing,
        |m, u| m.vertex_lighting && !m.unlit;
    /// An environment map, multiplied in unless a combine feature follows
    /// (`PHONG_ENVIRONMENT_MAP`).
    ENVIRONMENT_MAP: "environment_map", ["PHONG_ENVIRONMENT_MAP"], Nothing,
        |m, u| has_environment(m);
    /// The environment mixed in (`PHONG_ENV_MIX`).
    ENV_MIX: "environment_combine", ["PHONG_ENV_MIX"], Nothing,
        |m, u| has_environment(m) && m.environment_combine == EnvironmentCombine::Mix;
    /// The environment added (`PHONG_ENV_ADD`).
    ENV_ADD: "environment_combine", ["PHONG_ENV_ADD"], Nothing,
        |m, u| has_environment(m) && m.environment_combine == EnvironmentCombine::Add;
    /// The environment looked up along the refracted view ray (`PHONG_ENV_REFRACTION`).
    ENV_REFRACTION: "refraction_ratio", ["PHONG_ENV_REFRACTION"], Nothing,
        |m, u| has_environment(m) && m.refraction_ratio.is_some();
    /// The environment is the camera's `EnvironmentMapLight` (`PHONG_ENV_CAMERA`).
    ENV_CAMERA: "camera_environment", ["PHONG_ENV_CAMERA"], Nothing,
        |m, u| m.environment_map.is_none() && m.camera_environment;
    /// The camera's fog left out (`PHONG_NO_FOG`).
    NO_FOG: "fog_enabled", ["PHONG_NO_FOG"], Nothing, |m, u| !m.fog_enabled;
    /// Fragments below the alpha cutoff discarded (`PHONG_ALPHA_MASK`).
    ALPHA_MASK: "alpha_mode", ["PHONG_ALPHA_MASK"], Nothing,
        |m, u| matches!(m.alpha_mode, AlphaMode::Mask(_));
    /// A base color map on the first UV set (`PHONG_BASE_COLOR_TEXTURE`).
    BASE_COLOR_TEXTURE: "base_color_texture", ["PHONG_BASE_COLOR_TEXTURE"], Uv0,
        |m, u| map_at(&m.base_color_texture, &m.base_color_channel, false);
    /// A base color map on the second UV set (`PHONG_BASE_COLOR_TEXTURE`,
    /// `PHONG_BASE_COLOR_UV_B`).
    BASE_COLOR_TEXTURE_UV_B: "base_color_texture",
        ["PHONG_BASE_COLOR_TEXTURE", "PHONG_BASE_COLOR_UV_B"], Uv1,
        |m, u| map_at(&m.base_color_texture, &m.base_color_channel, true);
    /// A specular map on the first UV set, with a specular term (`PHONG_SPECULAR_TEXTURE`).
    SPECULAR_TEXTURE: "specular_texture", ["PHONG_SPECULAR_TEXTURE"], Uv0,
        |m, u| has_specular(m, u) && map_at(&m.specular_texture, &m.specular_channel, false);
    /// A specular map on the second UV set, with a specular term (`PHONG_SPECULAR_TEXTURE`,
    /// `PHONG_SPECULAR_UV_B`).
    SPECULAR_TEXTURE_UV_B: "specular_texture", ["PHONG_SPECULAR_TEXTURE", "PHONG_SPECULAR_UV_B"],
        Uv1,
        |m, u| has_specular(m, u) && map_at(&m.specular_texture, &m.specular_channel, true);
    /// A metallic-roughness map on the first UV set, on a lit material
    /// (`PHONG_METALLIC_ROUGHNESS_MAP`).
    METALLIC_ROUGHNESS_MAP: "metallic_roughness_texture", ["PHONG_METALLIC_ROUGHNESS_MAP"], Uv0,
        |m, u| has_metallic_roughness_map(m)
            && map_at(&m.metallic_roughness_texture, &m.metallic_roughness_channel, false);
    /// A metallic-roughness map on the second UV set (`PHONG_METALLIC_ROUGHNESS_MAP`,
    /// `PHONG_METALLIC_ROUGHNESS_UV_B`).
    METALLIC_ROUGHNESS_MAP_UV_B: "metallic_roughness_texture",
        ["PHONG_METALLIC_ROUGHNESS_MAP", "PHONG_METALLIC_ROUGHNESS_UV_B"], Uv1,
        |m, u| has_metallic_roughness_map(m)
            && map_at(&m.metallic_roughness_texture, &m.metallic_roughness_channel, true);
    /// The ambient light reflected by the specular color (`PHONG_AMBIENT_SPECULAR`; a
    /// strength of 0 leaves nothing to reflect).
    AMBIENT_SPECULAR: "ambient_specular", ["PHONG_AMBIENT_SPECULAR"], Nothing,
        |m, u| m.ambient_specular && !m.unlit && u.specular_strength > 0.0;
    /// The camera's environment map light (`PHONG_ENV_LIGHT`), on a lit material.
    ENV_LIGHT: "environment_light", ["PHONG_ENV_LIGHT"], Nothing,
        |m, u| m.environment_light && !m.unlit;
    /// An emissive map on the first UV set (`PHONG_EMISSIVE_TEXTURE`).
    EMISSIVE_TEXTURE: "emissive_texture", ["PHONG_EMISSIVE_TEXTURE"], Uv0,
        |m, u| !m.unlit && map_at(&m.emissive_texture, &m.emissive_channel, false);
    /// An emissive map on the second UV set (`PHONG_EMISSIVE_TEXTURE`, `PHONG_EMISSIVE_UV_B`).
    EMISSIVE_TEXTURE_UV_B: "emissive_texture", ["PHONG_EMISSIVE_TEXTURE", "PHONG_EMISSIVE_UV_B"],
        Uv1,
        |m, u| !m.unlit && map_at(&m.emissive_texture, &m.emissive_channel, true);
    /// An alpha map on the first UV set (`PHONG_ALPHA_MAP`).
    ALPHA_MAP: "alpha_map_texture", ["PHONG_ALPHA_MAP"], Uv0,
        |m, u| map_at(&m.alpha_map_texture, &m.alpha_map_channel, false);
    /// An alpha map on the second UV set (`PHONG_ALPHA_MAP`, `PHONG_ALPHA_MAP_UV_B`).
    ALPHA_MAP_UV_B: "alpha_map_texture", ["PHONG_ALPHA_MAP", "PHONG_ALPHA_MAP_UV_B"], Uv1,
        |m, u| map_at(&m.alpha_map_texture, &m.alpha_map_channel, true);
    /// A light map on the first UV set (`PHONG_LIGHT_MAP`).
    LIGHT_MAP: "light_map_texture", ["PHONG_LIGHT_MAP"], Uv0,
        |m, u| map_at(&m.light_map_texture, &m.light_map_channel, false);
    /// A light map on the second UV set (`PHONG_LIGHT_MAP`, `PHONG_LIGHT_MAP_UV_B`).
    LIGHT_MAP_UV_B: "light_map_texture", ["PHONG_LIGHT_MAP", "PHONG_LIGHT_MAP_UV_B"], Uv1,
        |m, u| map_at(&m.light_map_texture, &m.light_map_channel, true);
    /// An AO map on the first UV set (`PHONG_AO_MAP`).
    AO_MAP: "ao_map_texture", ["PHONG_AO_MAP"], Uv0,
        |m, u| map_at(&m.ao_map_texture, &m.ao_map_channel, false);
    /// An AO map on the second UV set (`PHONG_AO_MAP`, `PHONG_AO_MAP_UV_B`).
    AO_MAP_UV_B: "ao_map_texture", ["PHONG_AO_MAP", "PHONG_AO_MAP_UV_B"], Uv1,
        |m, u| map_at(&m.ao_map_texture, &m.ao_map_channel, true);
    /// A normal map on the first UV set (`PHONG_NORMAL_MAP`).
    NORMAL_MAP: "normal_map_texture", ["PHONG_NORMAL_MAP"], Uv0AndTangents,
        |m, u| map_at(&m.normal_map_texture, &m.normal_map_channel, false);
    /// A normal map on the second UV set (`PHONG_NORMAL_MAP`, `PHONG_NORMAL_MAP_UV_B`).
    NORMAL_MAP_UV_B: "normal_map_texture", ["PHONG_NORMAL_MAP", "PHONG_NORMAL_MAP_UV_B"],
        Uv1AndTangents,
        |m, u| map_at(&m.normal_map_texture, &m.normal_map_channel, true);
    /// A bump map on the first UV set (`PHONG_BUMP_MAP`).
    BUMP_MAP: "bump_map_texture", ["PHONG_BUMP_MAP"], Uv0AndTangents,
        |m, u| map_at(&m.bump_map_texture, &m.bump_map_channel, false);
    /// A bump map on the second UV set (`PHONG_BUMP_MAP`, `PHONG_BUMP_MAP_UV_B`).
    BUMP_MAP_UV_B: "bump_map_texture", ["PHONG_BUMP_MAP", "PHONG_BUMP_MAP_UV_B"], Uv1AndTangents,
        |m, u| map_at(&m.bump_map_texture, &m.bump_map_channel, true);
    /// The maps sampled at moved UVs: a UV transform other than the identity, on a material
    /// that samples a map at the first UV set (`PHONG_UV_TRANSFORM`).
    UV_TRANSFORM: "uv_transform", ["PHONG_UV_TRANSFORM"], SampledUv0Map,
        |m, u| limits::uv_transform(m.uv_transform) != Affine2::IDENTITY;
    /// Back faces drawn (no culling): a pipeline setting, no shader def.
    DOUBLE_SIDED: "double_sided", [], Nothing, |m, u| m.double_sided;
    /// Vertices displaced (the crate's vertex shaders, with their vertex def
    /// `PHONG_DISPLACEMENT_MAP`).
    DISPLACEMENT: "displacement_map", [], Nothing, |m, u| m.displacement_map.is_some();
    /// The displacement map read at the second UV set (the vertex def
    /// `PHONG_DISPLACEMENT_UV_B`).
    DISPLACEMENT_UV_B: "displacement_map", [], Nothing,
        |m, u| map_at(&m.displacement_map, &m.displacement_map_channel, true);
    /// Some light of the material's app casts shadows: only then is the shadow code
    /// compiled in (`PHONG_SHADOWS`). This row and the next six are the app's scene
    /// (`SceneKey::variants`), which the render world sets in each material's key.
    SHADOWS: "variants", ["PHONG_SHADOWS"], Nothing, scene |s| s.variants.shadows;
    /// Some shadow-casting light of the app has a size (`PhongShadows::softness`): the
    /// soft-shadow filter (PCSS) is compiled in (`PHONG_SOFT_SHADOWS`).
    SOFT_SHADOWS: "variants", ["PHONG_SOFT_SHADOWS"], Nothing,
        scene |s| s.variants.shadows && s.variants.soft_shadows;
    /// The app has a `PhongHemisphereLight` (`PHONG_HEMISPHERE`).
    HEMISPHERE: "variants", ["PHONG_HEMISPHERE"], Nothing, scene |s| s.variants.hemisphere;
    /// The app's light buffer holds an area light (`PHONG_AREA_LIGHTS`).
    AREA_LIGHTS: "variants", ["PHONG_AREA_LIGHTS"], Nothing, scene |s| s.variants.area_lights;
    /// One of them is a disk (`PHONG_DISK_LIGHTS`): the polygons hold 18 corners, not 6.
    DISK_LIGHTS: "variants", ["PHONG_DISK_LIGHTS"], Nothing,
        scene |s| s.variants.area_lights && s.variants.disk_lights;
    /// One of them takes the fitted highlight (`PHONG_AREA_FITTED`).
    AREA_FITTED: "variants", ["PHONG_AREA_FITTED"], Nothing,
        scene |s| s.variants.area_lights && s.variants.fitted_highlights;
    /// Some light of the app has a `PhongLightCookie` (`PHONG_LIGHT_COOKIES`).
    LIGHT_COOKIES: "variants", ["PHONG_LIGHT_COOKIES"], Nothing, scene |s| s.variants.cookies;
    /// The numbers read from the array of every material's records at the mesh instance's
    /// tag, not from the material's uniform (`PHONG_MATERIAL_RECORDS`, in every stage): the
    /// bind group a class of materials shares (`render::batching`,
    /// `SceneKey::from_records`).
    MATERIAL_RECORDS: "from_records", ["PHONG_MATERIAL_RECORDS"], Nothing,
        scene |s| s.from_records;
}
