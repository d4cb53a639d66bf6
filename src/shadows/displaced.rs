//! Displaced shadow casters: a caster whose `PhongMaterial` has a displacement map moves its
//! vertices in the shadow maps as the material's own vertex stages move them
//! (`shadow_caster.wesl`, DISPLACED). The main world notes each caster's map and numbers
//! ([`CasterDisplacement`]); the render world binds the map (group `DISPLACEMENT_GROUP`) and
//! passes the numbers as instance data.

use super::caster_bind_groups::{image_entries, remake_bind_groups};
use crate::displacement::DisplacementUniform;
use crate::material::PhongMaterial;
use bevy::{
    asset::AssetId,
    ecs::{
        resource::Resource,
        system::{Res, ResMut},
    },
    image::Image,
    mesh::UvChannel,
    platform::collections::HashMap,
    render::{
        render_asset::RenderAssets,
        render_resource::{
            BindGroup, BindGroupLayoutDescriptor, PipelineCache, SamplerBindingType, ShaderStages,
            TextureSampleType,
            binding_types::{sampler, texture_2d},
        },
        renderer::RenderDevice,
        texture::GpuImage,
    },
};

/// A caster's displacement: its map and how the map moves the vertices.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct CasterDisplacement {
    pub map: AssetId<Image>,
    pub uniform: DisplacementUniform,
    /// Whether the map is read at the mesh's second UV set (else the first).
    pub second_uvs: bool,
}

impl CasterDisplacement {
    /// The displacement of `material`, if it has a map.
    pub fn of(material: &PhongMaterial) -> Option<Self> {
        let map = material.displacement_map.as_ref()?.id();
        Some(Self {
            map,
            uniform: material.into(),
            second_uvs: material.displacement_map_channel == UvChannel::Uv1,
        })
    }

    /// The farthest a vertex moves, local units: the map's red is in `[0, 1]`, so the
    /// distance is between `bias` and `scale + bias`.
    pub fn reach(&self) -> f32 {
        let DisplacementUniform { scale, bias, .. } = self.uniform;
        bias.abs().max((scale + bias).abs())
    }

    /// The instance data the shader reads (`uv_matrix`, `shift_scale_bias`): the UV
    /// transform's matrix by columns, its translation, the scale and the bias.
    pub fn instance_data(&self) -> [f32; 8] {
        let m = self.uniform.uv_transform;
        [
            m.x_axis.x,
            m.x_axis.y,
            m.y_axis.x,
            m.y_axis.y,
            m.z_axis.x,
            m.z_axis.y,
            self.uniform.scale,
            self.uniform.bias,
        ]
    }
}

/// The layout of a displaced caster's map: the texture and its sampler, read in the vertex
/// stage.
pub(crate) fn displacement_layout() -> BindGroupLayoutDescriptor {
    BindGroupLayoutDescriptor::new(
        "phong_displaced_caster",
        &[
            texture_2d(TextureSampleType::Float { filterable: true })
                .build(0, ShaderStages::VERTEX),
            sampler(SamplerBindingType::Filtering).build(1, ShaderStages::VERTEX),
        ],
    )
}

/// The bind group of each displacement map this frame's casters read, made anew every frame
/// (a map's image may be replaced).
#[derive(Resource, Default)]
pub(crate) struct DisplacedBindGroups(pub HashMap<AssetId<Image>, BindGroup>);

/// Makes the bind groups of the displaced casters of [`super::ShadowDraws`]; a map not yet on
/// the GPU gets none (its casters are not drawn this frame).
pub(crate) fn prepare_displaced_bind_groups(
    draws: Res<super::ShadowDraws>,
    images: Res<RenderAssets<GpuImage>>,
    device: Res<RenderDevice>,
    cache: Res<PipelineCache>,
    mut groups: ResMut<DisplacedBindGroups>,
) {
    let layout = cache.get_bind_group_layout(&displacement_layout());
    remake_bind_groups(&mut groups.0, draws.displacement_maps(), |map| {
        let image = images.get(map)?;
        Some(device.create_bind_group("phong_displaced_caster", &layout, &image_entries(0, image)))
    });
}
