//! How a [`PhongMaterial`] is bound: its own surface data (the uniform and the texture maps)
//! beside the plugin's scene data (the lights, the light grid and the shadow maps), which the
//! bind group takes from the render world when Bevy prepares the material.

use super::{PHONG_LIGHT_BUFFER, PHONG_LIGHT_GRID_BUFFER};
use crate::material::{PhongMaterial, PhongMaterialKey, PhongMaterialUniform};
use crate::shadows::{PHONG_SHADOW_VIEW_BUFFER, ShadowAtlas};
use bevy::{
    asset::Handle,
    ecs::system::{Res, SystemParam, SystemParamItem, lifetimeless::SRes},
    image::Image,
    render::{
        render_asset::RenderAssets,
        render_resource::{
            AsBindGroup, AsBindGroupError, BindGroupLayout, BindGroupLayoutEntry, BindingType,
            BufferBindingType, OwnedBindingResource, SamplerBindingType, ShaderStages,
            TextureSampleType, TextureViewDimension, UnpreparedBindGroup,
        },
        renderer::RenderDevice,
        storage::GpuShaderBuffer,
        texture::{FallbackImage, GpuImage},
    },
};

/// The bindings a [`PhongMaterial`] brings itself, laid out by Bevy's derive: binding 0 the
/// uniform, 3 to 10 the four texture maps, each followed by its sampler.
#[derive(AsBindGroup)]
struct SurfaceBindings {
    #[uniform(0)]
    uniform: PhongMaterialUniform,
    #[texture(3)]
    #[sampler(4)]
    base_color_texture: Option<Handle<Image>>,
    #[texture(5)]
    #[sampler(6)]
    specular_texture: Option<Handle<Image>>,
    #[texture(7)]
    #[sampler(8)]
    emissive_texture: Option<Handle<Image>>,
    #[texture(9)]
    #[sampler(10)]
    normal_map_texture: Option<Handle<Image>>,
}

impl From<&PhongMaterial> for SurfaceBindings {
    fn from(material: &PhongMaterial) -> Self {
        Self {
            uniform: material.into(),
            base_color_texture: material.base_color_texture.clone(),
            specular_texture: material.specular_texture.clone(),
            emissive_texture: material.emissive_texture.clone(),
            normal_map_texture: material.normal_map_texture.clone(),
        }
    }
}

/// The plugin's scene data that every Phong material binds beside its own, read from the
/// render world (the names are those of `bevy_phong::bindings`): 1 the light buffer
/// (`lights`), 2 the light grid (`light_grid`), 11 the shadow views (`shadow_views`), 12 the
/// shadow map array (`shadow_maps`), 13 its comparison sampler (`shadow_sampler`). A
/// material of its own that lights with the crate's shader functions adds these bindings
/// the same way [`PhongMaterial`] does.
#[derive(SystemParam)]
pub struct PhongSceneBindings<'w> {
    buffers: Res<'w, RenderAssets<GpuShaderBuffer>>,
    shadow_maps: Option<Res<'w, ShadowAtlas>>,
}

impl PhongSceneBindings<'_> {
    /// Binding index of the light buffer.
    pub const LIGHTS: u32 = 1;
    /// Binding index of the light grid.
    pub const LIGHT_GRID: u32 = 2;
    /// Binding index of the shadow views.
    pub const SHADOW_VIEWS: u32 = 11;
    /// Binding index of the shadow map array.
    pub const SHADOW_MAPS: u32 = 12;
    /// Binding index of the shadow maps' comparison sampler.
    pub const SHADOW_SAMPLER: u32 = 13;

    /// The layout entries of the scene bindings (read in the fragment stage).
    pub fn layout_entries() -> Vec<BindGroupLayoutEntry> {
        let entry = |binding, ty| BindGroupLayoutEntry {
            binding,
            visibility: ShaderStages::FRAGMENT,
            ty,
            count: None,
        };
        let storage = BindingType::Buffer {
            ty: BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        };
        vec![
            entry(Self::LIGHTS, storage),
            entry(Self::LIGHT_GRID, storage),
            entry(Self::SHADOW_VIEWS, storage),
            entry(
                Self::SHADOW_MAPS,
                BindingType::Texture {
                    sample_type: TextureSampleType::Depth,
                    view_dimension: TextureViewDimension::D2Array,
                    multisampled: false,
                },
            ),
            entry(
                Self::SHADOW_SAMPLER,
                BindingType::Sampler(SamplerBindingType::Comparison),
            ),
        ]
    }

    /// The scene's GPU resources for those entries; `RetryNextUpdate` until the plugin has
    /// uploaded them (in the first frame).
    pub fn bindings(&self) -> Result<Vec<(u32, OwnedBindingResource)>, AsBindGroupError> {
        let shadow_maps = self
            .shadow_maps
            .as_ref()
            .ok_or(AsBindGroupError::RetryNextUpdate)?;
        let mut bindings = [
            (Self::LIGHTS, &PHONG_LIGHT_BUFFER),
            (Self::LIGHT_GRID, &PHONG_LIGHT_GRID_BUFFER),
            (Self::SHADOW_VIEWS, &PHONG_SHADOW_VIEW_BUFFER),
        ]
        .into_iter()
        .map(|(binding, handle)| {
            let buffer = self
                .buffers
                .get(handle)
                .ok_or(AsBindGroupError::RetryNextUpdate)?;
            Ok((binding, OwnedBindingResource::Buffer(buffer.buffer.clone())))
        })
        .collect::<Result<Vec<_>, AsBindGroupError>>()?;
        bindings.push((
            Self::SHADOW_MAPS,
            OwnedBindingResource::TextureView(
                TextureViewDimension::D2Array,
                shadow_maps.array_view.clone(),
            ),
        ));
        bindings.push((
            Self::SHADOW_SAMPLER,
            OwnedBindingResource::Sampler(
                SamplerBindingType::Comparison,
                shadow_maps.sampler.clone(),
            ),
        ));
        Ok(bindings)
    }
}

impl AsBindGroup for PhongMaterial {
    type Data = PhongMaterialKey;
    /// The parameters of Bevy's `AsBindGroup` derive (for the surface data) and the scene's.
    type Param = (
        (
            SRes<RenderAssets<GpuImage>>,
            SRes<FallbackImage>,
            SRes<RenderAssets<GpuShaderBuffer>>,
        ),
        PhongSceneBindings<'static>,
    );

    fn label() -> &'static str {
        "PhongMaterial"
    }

    fn bind_group_data(&self) -> Self::Data {
        self.into()
    }

    fn unprepared_bind_group(
        &self,
        layout: &BindGroupLayout,
        render_device: &RenderDevice,
        (surface, scene): &mut SystemParamItem<'_, '_, Self::Param>,
        _force_no_bindless: bool,
    ) -> Result<UnpreparedBindGroup, AsBindGroupError> {
        let mut bind_group = SurfaceBindings::from(self).unprepared_bind_group(
            layout,
            render_device,
            surface,
            true,
        )?;
        bind_group.bindings.0.extend(scene.bindings()?);
        Ok(bind_group)
    }

    fn bind_group_layout_entries(
        render_device: &RenderDevice,
        _force_no_bindless: bool,
    ) -> Vec<BindGroupLayoutEntry> {
        let mut entries = SurfaceBindings::bind_group_layout_entries(render_device, true);
        entries.extend(PhongSceneBindings::layout_entries());
        entries
    }
}
