//! Alpha-masked shadow casters: a caster whose `PhongMaterial` has `AlphaMode::Mask` cuts
//! the holes the main pass cuts in the shadow maps too (`shadow_caster.wesl`, MASKED). Its
//! alpha is the product the prepass discards by (`phong_prepass.wesl`'s `discard_masked`):
//! the base color's, the vertex color's, the base color map's and (where the device binds it)
//! the alpha map's green, each map read at its UV set (the first moved by the UV transform,
//! the second as it is). The
//! main world notes each masked caster's maps and numbers ([`CasterMask`]); the render world
//! binds the maps (group `MASK_GROUP`) and passes the numbers as instance data.

use super::caster_bind_groups::{image_entries, remake_bind_groups};
use crate::material::{PhongMaterial, PhongMaterialUniform};
use bevy::{
    asset::AssetId,
    ecs::{
        resource::Resource,
        system::{Res, ResMut},
    },
    image::Image,
    math::Mat3,
    mesh::UvChannel,
    platform::collections::HashMap,
    prelude::AlphaMode,
    render::{
        render_asset::RenderAssets,
        render_resource::{
            BindGroup, BindGroupLayoutDescriptor, PipelineCache, SamplerBindingType, ShaderStages,
            TextureSampleType,
            binding_types::{sampler, texture_2d},
        },
        renderer::RenderDevice,
        texture::{FallbackImage, GpuImage},
    },
};

/// A masked caster's maps and numbers: what its alpha is made of, and the cutoff below which
/// a fragment is discarded.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct CasterMask {
    /// The base color map, whose alpha multiplies.
    pub base_color_texture: Option<AssetId<Image>>,
    /// The alpha map, whose green multiplies.
    pub alpha_map: Option<AssetId<Image>>,
    /// Whether the base color map is read at the second UV set (else the first).
    pub base_color_second_uvs: bool,
    /// Whether the alpha map is read at the second UV set (else the first).
    pub alpha_map_second_uvs: bool,
    /// The UV transform of the first UV set.
    pub uv_transform: Mat3,
    /// The base color's alpha, in range.
    pub base_alpha: f32,
    /// `AlphaMode::Mask`'s cutoff, in range.
    pub cutoff: f32,
}

impl CasterMask {
    /// The mask of `material`, if it is alpha-masked; its numbers brought into range as its
    /// uniform's are.
    pub fn of(material: &PhongMaterial) -> Option<Self> {
        if !matches!(material.alpha_mode, AlphaMode::Mask(_)) {
            return None;
        }
        let uniform = PhongMaterialUniform::from(material);
        Some(Self {
            base_color_texture: material.base_color_texture.as_ref().map(|image| image.id()),
            alpha_map: material.alpha_map_texture.as_ref().map(|image| image.id()),
            base_color_second_uvs: material.base_color_channel == UvChannel::Uv1,
            alpha_map_second_uvs: material.alpha_map_channel == UvChannel::Uv1,
            uv_transform: uniform.uv_transform,
            base_alpha: uniform.base_color.w,
            cutoff: uniform.alpha_cutoff,
        })
    }

    /// The instance data the shader reads (`mask_uv_matrix`, `mask_shift_alpha_cutoff`): the
    /// UV transform's matrix by columns, its translation, the base alpha and the cutoff.
    pub fn instance_data(&self) -> [f32; 8] {
        let m = self.uv_transform;
        [
            m.x_axis.x,
            m.x_axis.y,
            m.y_axis.x,
            m.y_axis.y,
            m.z_axis.x,
            m.z_axis.y,
            self.base_alpha,
            self.cutoff,
        ]
    }

    /// The maps its bind group holds on a mesh that has the UV sets `has_uvs` says (first,
    /// second): `(base color map, alpha map)`, each only where the mesh has its set, as the
    /// main pass reads them, and the alpha map only where the device binds it
    /// (`alpha_map_bound`; not under WebGL2's limits, where the main pass leaves it out too).
    pub fn maps(&self, alpha_map_bound: bool, has_uvs: (bool, bool)) -> MaskMaps {
        let has_set = |second: bool| if second { has_uvs.1 } else { has_uvs.0 };
        (
            self.base_color_texture
                .filter(|_| has_set(self.base_color_second_uvs)),
            self.alpha_map
                .filter(|_| alpha_map_bound && has_set(self.alpha_map_second_uvs)),
        )
    }
}

/// A masked caster's maps, as its bind group holds them: the base color map and the alpha
/// map (an absent one is bound as the fallback image and not read).
pub(crate) type MaskMaps = (Option<AssetId<Image>>, Option<AssetId<Image>>);

/// The layout of a masked caster's maps: the base color map and the alpha map with their
/// samplers, read in the fragment stage.
pub(crate) fn mask_layout() -> BindGroupLayoutDescriptor {
    let texture = || texture_2d(TextureSampleType::Float { filterable: true });
    let filtering = || sampler(SamplerBindingType::Filtering);
    BindGroupLayoutDescriptor::new(
        "phong_masked_caster",
        &[
            texture().build(0, ShaderStages::FRAGMENT),
            filtering().build(1, ShaderStages::FRAGMENT),
            texture().build(2, ShaderStages::FRAGMENT),
            filtering().build(3, ShaderStages::FRAGMENT),
        ],
    )
}

/// The bind group of each pair of maps this frame's masked casters read, made anew every
/// frame (an image may be replaced).
#[derive(Resource, Default)]
pub(crate) struct MaskedBindGroups(pub HashMap<MaskMaps, BindGroup>);

/// Makes the bind groups of the masked casters of [`super::ShadowDraws`]; maps not yet on the
/// GPU get none (their casters are not drawn this frame).
pub(crate) fn prepare_masked_bind_groups(
    draws: Res<super::ShadowDraws>,
    images: Res<RenderAssets<GpuImage>>,
    fallback: Res<FallbackImage>,
    device: Res<RenderDevice>,
    cache: Res<PipelineCache>,
    mut groups: ResMut<MaskedBindGroups>,
) {
    let layout = cache.get_bind_group_layout(&mask_layout());
    let image = |map: Option<AssetId<Image>>| match map {
        Some(id) => images.get(id),
        None => Some(&fallback.d2),
    };
    remake_bind_groups(&mut groups.0, draws.mask_maps(), |maps| {
        let [texture, sampler] = image_entries(0, image(maps.0)?);
        let [alpha_texture, alpha_sampler] = image_entries(2, image(maps.1)?);
        Some(device.create_bind_group(
            "phong_masked_caster",
            &layout,
            &[texture, sampler, alpha_texture, alpha_sampler],
        ))
    });
}
