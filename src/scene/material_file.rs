//! `PhongMaterial` as a file: [`PhongMaterialDescription`] and the `*.phong.ron` loader.

use super::{SceneColor, SceneFileError, relative_path, scene_color};
use crate::material::{
    DiffuseMode, EnvironmentCombine, PhongMaterial, SpecularMode, SpecularModel, material_maps,
};
use bevy::{
    asset::{AssetLoader, LoadContext, io::Reader},
    image::{Image, ImageLoaderSettings},
    math::{Affine2, Vec2},
    mesh::UvChannel,
    prelude::{AlphaMode, Handle},
    reflect::TypePath,
    render::render_resource::Face,
};
use serde::{Deserialize, Serialize};

/// A mesh's UV set, as a file names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum UvChannelDescription {
    /// `Mesh::ATTRIBUTE_UV_0`.
    Uv0,
    /// `Mesh::ATTRIBUTE_UV_1`.
    Uv1,
}

impl UvChannelDescription {
    fn to_channel(self) -> UvChannel {
        match self {
            Self::Uv0 => UvChannel::Uv0,
            Self::Uv1 => UvChannel::Uv1,
        }
    }

    fn from_channel(channel: &UvChannel) -> Self {
        match channel {
            UvChannel::Uv0 => Self::Uv0,
            UvChannel::Uv1 => Self::Uv1,
        }
    }
}

/// The faces a material culls, as a file names them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum CullModeDescription {
    /// Back faces are not drawn.
    #[default]
    Back,
    /// Front faces are not drawn.
    Front,
    /// Both faces are drawn.
    Neither,
}

impl CullModeDescription {
    /// As [`PhongMaterial::cull_mode`] takes it.
    pub fn to_face(self) -> Option<Face> {
        match self {
            Self::Back => Some(Face::Back),
            Self::Front => Some(Face::Front),
            Self::Neither => None,
        }
    }
}

/// A UV transform as glTF's `KHR_texture_transform` writes it: the UVs are scaled, then
/// rotated, then offset. Every field is optional.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct UvTransformDescription {
    /// Added last, in UV units. Default `(0, 0)`.
    pub offset: (f32, f32),
    /// Radians, counterclockwise in UV space as glTF defines it. Default `0`.
    pub rotation: f32,
    /// Applied first, per axis. Default `(1, 1)`.
    pub scale: (f32, f32),
}

impl Default for UvTransformDescription {
    fn default() -> Self {
        Self {
            offset: (0.0, 0.0),
            rotation: 0.0,
            scale: (1.0, 1.0),
        }
    }
}

impl UvTransformDescription {
    /// The transform, as Bevy's glTF loader makes it from the same numbers.
    pub fn to_affine2(self) -> Affine2 {
        Affine2::from_scale_angle_translation(
            Vec2::from(self.scale),
            -self.rotation,
            Vec2::from(self.offset),
        )
    }
}

/// The alpha modes a file can name.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum AlphaModeDescription {
    /// Alpha is ignored.
    #[default]
    Opaque,
    /// Fragments with alpha below the cutoff are discarded.
    Mask(f32),
    /// Blended over what is behind.
    Blend,
}

/// Declares [`PhongMaterialDescription`], its default and its conversion to a
/// [`PhongMaterial`] from the rows of `material_maps!`: each texture map is a path
/// (`Option<String>`) named as the material's field, loaded as the row says.
macro_rules! material_description {
    ($(
        $field:ident: texture($($texture:tt)*) $(sampler($($sampler:tt)*))?,
        $devices:ident, $file:ident, $(uv $channel:ident,)? $what:literal;
    )*) => {
        /// A [`PhongMaterial`] as written in a file; every field is optional and defaults to
        /// `PhongMaterial::default()`'s value.
        ///
        /// ```ron
        /// (
        ///     base_color: Srgb(1.0, 0.0, 1.0),
        ///     specular_strength: 2.0,
        ///     shininess: 50.0,
        ///     base_color_texture: Some("textures/crate.png"),
        ///     uv_transform: (scale: (2.0, 2.0), rotation: 0.5, offset: (0.25, 0.0)),
        /// )
        /// ```
        ///
        /// Texture paths are relative to the file that names them; each map's field says how
        /// its image is loaded (as sRGB color or as linear data, `is_srgb: false`).
        #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
        #[serde(default, deny_unknown_fields)]
        pub struct PhongMaterialDescription {
            /// `k_d` and alpha. Default white.
            pub base_color: SceneColor,
            /// `k_a`. Default `1`.
            pub ambient_factor: f32,
            /// `k_s`. Default white.
            pub specular_color: SceneColor,
            /// Multiplier on `k_s`. Default `1`.
            pub specular_strength: f32,
            /// `α`. Default `32`.
            pub shininess: f32,
            /// `Phong` or `BlinnPhong`. Default `Phong`.
            pub specular_model: SpecularModel,
            /// `Lambert`, `Wrap(w)` or `Toon(bands: n, smoothing: s)`. Default `Lambert`.
            pub diffuse_mode: DiffuseMode,
            /// `Smooth`, `Toon(smoothing: s)` or `Off`. Default `Smooth`.
            pub specular_mode: SpecularMode,
            /// The rim light's color. Default black (no rim).
            pub rim_color: SceneColor,
            /// Multiplier on the rim color. Default `1`.
            pub rim_strength: f32,
            /// Exponent on `1 − N·V`. Default `2`.
            pub rim_power: f32,
            /// The rim only where lights reach. Default `false`.
            pub rim_lit_side: bool,
            /// Unlit color. Default black.
            pub emissive: SceneColor,
            /// `Opaque`, `Mask(cutoff)` or `Blend`. Default `Opaque`.
            pub alpha_mode: AlphaModeDescription,
            /// Multiplies the metallic-roughness map's blue channel, `[0, 1]`. Default `1`.
            pub metallic: f32,
            /// Multiplies the metallic-roughness map's green channel and shapes the ambient
            /// specular, `[0, 1]`. Default `1`.
            pub perceptual_roughness: f32,
            /// Also reflect the ambient light by the specular color, as `StandardMaterial`
            /// does. Default `false`.
            pub ambient_specular: bool,
            /// Lit by the camera's Bevy `EnvironmentMapLight` as `StandardMaterial` is.
            /// Default `false`.
            pub environment_light: bool,
            /// Negate the normal map's green channel. Default `false`.
            pub flip_normal_map_y: bool,
            /// The factors on the normal map's `n.x` and `n.y`. Default `(1, 1)`.
            pub normal_map_scale: (f32, f32),
            /// How far a height step of 1 between neighbouring texels tilts the normal. Default
            /// `1`.
            pub bump_scale: f32,
            /// How far a texel of 1 moves a vertex along its normal, local units. Default `1`.
            pub displacement_scale: f32,
            /// Added to every vertex's displacement, local units. Default `0`.
            pub displacement_bias: f32,
            /// Light each triangle with its face's normal. Default `false`.
            pub flat_shading: bool,
            /// Light the surface at its vertices, interpolated across each triangle. Default
            /// `false`.
            pub vertex_lighting: bool,
            /// Draw back faces too, their normal negated. Default `false`.
            pub double_sided: bool,
            /// How the UVs move before the maps are sampled. Default none.
            pub uv_transform: UvTransformDescription,
            /// Draw without light: `base_color` alone. Default `false`.
            pub unlit: bool,
            /// Whether the camera's fog applies. Default `true`.
            pub fog_enabled: bool,
            /// The faces not drawn: `Back`, `Front` or `Neither`. Default `Back`.
            pub cull_mode: CullModeDescription,
            /// Depth bias, in the depth buffer's steps (positive: toward the camera). Default `0`.
            pub depth_bias: f32,
            /// Multiplier on the light map. Default `1`.
            pub light_map_intensity: f32,
            /// How much the AO map occludes. Default `1`.
            pub ao_map_intensity: f32,
            /// Reflect the camera's Bevy `EnvironmentMapLight` where there is no
            /// `environment_map`. Default `false`.
            pub camera_environment: bool,
            /// `Multiply`, `Mix` or `Add`. Default `Multiply`.
            pub environment_combine: EnvironmentCombine,
            /// The environment's weight. Default `1`.
            pub reflectivity: f32,
            /// `Some(ratio)` refracts the view ray instead of reflecting it. Default `None`.
            pub refraction_ratio: Option<f32>,
            $(
                #[doc = concat!(
            "Path of ", $what, " (", loaded_as!($file), "), relative to the file. Default none."
        )]
                pub $field: Option<String>,
            )*
            $($(
                #[doc = concat!(
            "The UV set ", $what, " is read at: `Uv0` (moved by the UV transform) or `Uv1` \
            (as it is). Default `PhongMaterial`'s."
        )]
                pub $channel: UvChannelDescription,
            )?)*
        }

        impl Default for PhongMaterialDescription {
            fn default() -> Self {
                let material = PhongMaterial::default();
                Self {
                    base_color: SceneColor::white(),
                    ambient_factor: material.ambient_factor,
                    specular_color: SceneColor::white(),
                    specular_strength: material.specular_strength,
                    shininess: material.shininess,
                    specular_model: material.specular_model,
                    diffuse_mode: material.diffuse_mode,
                    specular_mode: material.specular_mode,
                    rim_color: SceneColor::black(),
                    rim_strength: material.rim_strength,
                    rim_power: material.rim_power,
                    rim_lit_side: material.rim_lit_side,
                    emissive: SceneColor::black(),
                    alpha_mode: AlphaModeDescription::Opaque,
                    metallic: material.metallic,
                    perceptual_roughness: material.perceptual_roughness,
                    ambient_specular: material.ambient_specular,
                    environment_light: material.environment_light,
                    flip_normal_map_y: false,
                    normal_map_scale: material.normal_map_scale.into(),
                    bump_scale: material.bump_scale,
                    displacement_scale: material.displacement_scale,
                    displacement_bias: material.displacement_bias,
                    flat_shading: material.flat_shading,
                    vertex_lighting: material.vertex_lighting,
                    double_sided: false,
                    uv_transform: UvTransformDescription::default(),
                    unlit: material.unlit,
                    fog_enabled: material.fog_enabled,
                    cull_mode: CullModeDescription::Back,
                    depth_bias: material.depth_bias,
                    light_map_intensity: material.light_map_intensity,
                    ao_map_intensity: material.ao_map_intensity,
                    camera_environment: material.camera_environment,
                    environment_combine: material.environment_combine,
                    reflectivity: material.reflectivity,
                    refraction_ratio: material.refraction_ratio,
                    $($field: None,)*
                    $($($channel: UvChannelDescription::from_channel(&material.$channel),)?)*
                }
            }
        }

        impl PhongMaterialDescription {
            /// The material, its textures loaded relative to the file being loaded. `field`
            /// names where the description sits in that file, for errors.
            pub(crate) fn to_material(
                &self,
                field: &str,
                load_context: &mut LoadContext,
            ) -> Result<PhongMaterial, SceneFileError> {
                // `objects[0].material.base_color` in a scene, `base_color` in a material file.
                let at = |name: &str| match field {
                    "" => name.to_owned(),
                    _ => format!("{field}.{name}"),
                };
                let color =
                    |name: &str, color: &SceneColor| scene_color(load_context, color, at(name));
                let base_color = color("base_color", &self.base_color)?;
                let specular_color = color("specular_color", &self.specular_color)?;
                let emissive = color("emissive", &self.emissive)?.to_linear();
                let rim_color = color("rim_color", &self.rim_color)?.to_linear();
                Ok(PhongMaterial {
                    base_color,
                    ambient_factor: self.ambient_factor,
                    specular_color,
                    specular_strength: self.specular_strength,
                    shininess: self.shininess,
                    specular_model: self.specular_model,
                    diffuse_mode: self.diffuse_mode,
                    specular_mode: self.specular_mode,
                    rim_color,
                    rim_strength: self.rim_strength,
                    rim_power: self.rim_power,
                    rim_lit_side: self.rim_lit_side,
                    emissive,
                    alpha_mode: match self.alpha_mode {
                        AlphaModeDescription::Opaque => AlphaMode::Opaque,
                        AlphaModeDescription::Mask(cutoff) => AlphaMode::Mask(cutoff),
                        AlphaModeDescription::Blend => AlphaMode::Blend,
                    },
                    metallic: self.metallic,
                    perceptual_roughness: self.perceptual_roughness,
                    ambient_specular: self.ambient_specular,
                    environment_light: self.environment_light,
                    flip_normal_map_y: self.flip_normal_map_y,
                    normal_map_scale: self.normal_map_scale.into(),
                    bump_scale: self.bump_scale,
                    displacement_scale: self.displacement_scale,
                    displacement_bias: self.displacement_bias,
                    flat_shading: self.flat_shading,
                    vertex_lighting: self.vertex_lighting,
                    double_sided: self.double_sided,
                    uv_transform: self.uv_transform.to_affine2(),
                    unlit: self.unlit,
                    fog_enabled: self.fog_enabled,
                    cull_mode: self.cull_mode.to_face(),
                    depth_bias: self.depth_bias,
                    light_map_intensity: self.light_map_intensity,
                    ao_map_intensity: self.ao_map_intensity,
                    camera_environment: self.camera_environment,
                    environment_combine: self.environment_combine,
                    reflectivity: self.reflectivity,
                    refraction_ratio: self.refraction_ratio,
                    $($($channel: self.$channel.to_channel(),)?)*
                    $($field: load_map(
                        load_context,
                        self.$field.as_deref(),
                        &at(stringify!($field)),
                        MapFile::$file,
                    )?,)*
                })
            }
        }
    };
}

/// How a map's image is loaded, in words, for the description's documentation.
macro_rules! loaded_as {
    (Srgb) => {
        "loaded as sRGB"
    };
    (Linear) => {
        "loaded as linear data"
    };
    (AsLoaded) => {
        "loaded with the image loader's defaults"
    };
}

material_maps!(material_description);

/// How a material file loads a map's image (`material_maps!`'s `file`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum MapFile {
    /// As sRGB color.
    Srgb,
    /// As linear data (`is_srgb: false`).
    Linear,
    /// With the image loader's defaults (a file that says what it holds, such as a cube).
    AsLoaded,
}

/// Starts loading the map at `path` (relative to the file being loaded) as `file` says;
/// `field` names it for errors.
fn load_map(
    load_context: &mut LoadContext,
    path: Option<&str>,
    field: &str,
    file: MapFile,
) -> Result<Option<Handle<Image>>, SceneFileError> {
    match file {
        MapFile::Srgb => load_texture(load_context, path, field, true),
        MapFile::Linear => load_texture(load_context, path, field, false),
        MapFile::AsLoaded => path
            .map(|path| relative_path(load_context, path, field))
            .transpose()
            .map(|resolved| resolved.map(|resolved| load_context.load(resolved))),
    }
}

/// Starts loading the image at `path` (relative to the file being loaded), as sRGB or
/// linear data.
pub(super) fn load_texture(
    load_context: &mut LoadContext,
    path: Option<&str>,
    field: &str,
    srgb: bool,
) -> Result<Option<Handle<Image>>, SceneFileError> {
    let Some(path) = path else {
        return Ok(None);
    };
    let resolved = relative_path(load_context, path, field)?;
    Ok(Some(
        load_context
            .load_builder()
            .with_settings(move |settings: &mut ImageLoaderSettings| settings.is_srgb = srgb)
            .load(resolved),
    ))
}

/// Loads a [`PhongMaterial`] from a `*.phong.ron` file ([`PhongMaterialDescription`]).
#[derive(Default, TypePath)]
pub struct PhongMaterialLoader;

impl AssetLoader for PhongMaterialLoader {
    type Asset = PhongMaterial;
    type Settings = ();
    type Error = SceneFileError;

    async fn load(
        &self,
        reader: &mut dyn Reader,
        _settings: &(),
        load_context: &mut LoadContext<'_>,
    ) -> Result<PhongMaterial, SceneFileError> {
        let description: PhongMaterialDescription = super::read_ron(reader, load_context).await?;
        description.to_material("", load_context)
    }

    fn extensions(&self) -> &[&str] {
        &["phong.ron"]
    }
}
