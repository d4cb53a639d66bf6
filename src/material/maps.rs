//! The texture maps of a [`PhongMaterial`](super::PhongMaterial), each declared once: its
//! field, its bindings (the texture's and its sampler's, as Bevy's `AsBindGroup` attributes
//! take them), the devices that bind it, how a material file loads its image, and what it
//! is. The material's bind group (`render::material_bindings`) and its file syntax
//! (`scene::material_file`) are made from this table; the shader's side is
//! `bevy_phong::shaders::bindings`, which a test compares with the layout.

/// Which devices bind a map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum MapDevices {
    /// Every device, WebGL2 included.
    All,
    /// Devices with the storage buffers of the scene data; WebGL2's 16 textures a shader
    /// stage leave no room for the map (it is left out there, with a warning).
    Full,
}

/// Calls the macro `$then` with one row per texture map of [`PhongMaterial`]:
/// `field: texture(binding, options) sampler(binding, options), devices, file, uv channel,
/// "what"`, where the texture's and sampler's parentheses hold what Bevy's `AsBindGroup`
/// derive takes, a map read texel by texel has no sampler, `devices` is a [`MapDevices`],
/// `file` says how a material file loads the image (`Srgb`, `Linear` data, or `AsLoaded`:
/// with the image loader's defaults, for a file that says what it holds), `uv channel`
/// names the material's field that picks the map's UV set (absent for a map not read at
/// UVs), and `what` names the map in documentation.
///
/// [`PhongMaterial`]: super::PhongMaterial
macro_rules! material_maps {
    ($then:ident) => {
        $then! {
            base_color_texture: texture(3) sampler(4), All, Srgb, uv base_color_channel,
                "the base color map";
            specular_texture: texture(5) sampler(6), All, Linear, uv specular_channel,
                "the specular map";
            emissive_texture: texture(7) sampler(8), All, Srgb, uv emissive_channel,
                "the emissive map";
            metallic_roughness_texture: texture(30) sampler(31), All, Linear,
                uv metallic_roughness_channel,
                "the metallic-roughness map (blue metallic, green roughness)";
            normal_map_texture: texture(9) sampler(10), All, Linear, uv normal_map_channel,
                "the tangent-space normal map";
            light_map_texture: texture(14) sampler(15), All, Srgb, uv light_map_channel,
                "the light map";
            ao_map_texture: texture(16) sampler(17), All, Linear, uv ao_map_channel,
                "the ambient occlusion map (red channel)";
            alpha_map_texture: texture(18) sampler(19), Full, Linear, uv alpha_map_channel,
                "the alpha map (green channel)";
            environment_map: texture(20, dimension = "cube") sampler(21), Full, AsLoaded,
                "the environment cube map (a file that holds a cube, such as KTX2 or DDS)";
            bump_map_texture: texture(22) sampler(23), Full, Linear, uv bump_map_channel,
                "the bump (height) map (red channel)";
            displacement_map: texture(24, visibility(vertex)) sampler(25, visibility(vertex)),
                All, Linear, uv displacement_map_channel,
                "the displacement map (red channel), read in the vertex stage";
            toon_ramp_texture: texture(27, filterable = false), Full, Linear,
                "the toon ramp (red channel, read texel by texel), used with a `Toon` diffuse mode";
        }
    };
}
pub(crate) use material_maps;

use bevy::{asset::Handle, image::Image};

/// Declares [`map_images`] from the rows of [`material_maps!`].
macro_rules! map_images {
    ($(
        $field:ident: texture $texture:tt $(sampler $sampler:tt)?,
            $devices:ident, $file:ident, $(uv $channel:ident,)? $what:literal;
    )*) => {
        /// The image of each of `material`'s maps (`None` where it has none), in
        /// [`material_maps!`]'s order: the bind group's maps and a material's class read them.
        pub(crate) fn map_images(material: &super::PhongMaterial) -> Vec<Option<&Handle<Image>>> {
            vec![$(material.$field.as_ref()),*]
        }
    };
}
material_maps!(map_images);
