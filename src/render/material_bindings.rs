//! How a [`PhongMaterial`] is bound: its own surface data (the uniform and the texture maps)
//! beside the plugin's scene data (the lights, their clusters and the shadow maps), which the
//! bind group takes from the render world when Bevy prepares the material.

use super::{PHONG_LIGHT_BUFFER, PHONG_LIGHT_CLUSTER_BUFFER};
use crate::displacement::DisplacementUniform;
use crate::material::{PhongMaterial, PhongMaterialKey, PhongMaterialUniform};
use crate::shadows::{PHONG_SHADOW_VIEW_BUFFER, ShadowAtlas};
use bevy::{
    asset::Handle,
    ecs::system::{Res, SystemParam, SystemParamItem, lifetimeless::SRes},
    image::Image,
    render::{
        render_asset::RenderAssets,
        render_resource::{
            AsBindGroup, AsBindGroupError, BindGroupBuilder, BindGroupLayout, BindGroupLayoutEntry,
            BindingType, BufferBindingType, SamplerBindingType, ShaderStages, TextureSampleType,
            TextureViewDimension, UnpreparedBindingResource,
        },
        renderer::RenderDevice,
        storage::GpuShaderBuffer,
        texture::{FallbackImage, GpuImage},
    },
};

/// The bindings a [`PhongMaterial`] brings itself, laid out by Bevy's derive: binding 0 the
/// uniform, 3 to 10 the four texture maps, 14 to 17 the light and AO maps, 18, 19 the
/// alpha map, 20, 21 the environment cube map and 22, 23 the bump map, each followed by its
/// sampler; 24 to 26 the displacement map, its sampler and its uniform, read in the vertex
/// stage; 27 the toon ramp (read texel by texel: no sampler).
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
    #[texture(14)]
    #[sampler(15)]
    light_map_texture: Option<Handle<Image>>,
    #[texture(16)]
    #[sampler(17)]
    ao_map_texture: Option<Handle<Image>>,
    #[texture(18)]
    #[sampler(19)]
    alpha_map_texture: Option<Handle<Image>>,
    #[texture(20, dimension = "cube")]
    #[sampler(21)]
    environment_map: Option<Handle<Image>>,
    #[texture(22)]
    #[sampler(23)]
    bump_map_texture: Option<Handle<Image>>,
    #[texture(24, visibility(vertex))]
    #[sampler(25, visibility(vertex))]
    displacement_map: Option<Handle<Image>>,
    #[uniform(26)]
    displacement: DisplacementUniform,
    #[texture(27)]
    toon_ramp_texture: Option<Handle<Image>>,
}

impl From<&PhongMaterial> for SurfaceBindings {
    fn from(material: &PhongMaterial) -> Self {
        Self {
            uniform: material.into(),
            base_color_texture: material.base_color_texture.clone(),
            specular_texture: material.specular_texture.clone(),
            emissive_texture: material.emissive_texture.clone(),
            normal_map_texture: material.normal_map_texture.clone(),
            light_map_texture: material.light_map_texture.clone(),
            ao_map_texture: material.ao_map_texture.clone(),
            alpha_map_texture: material.alpha_map_texture.clone(),
            environment_map: material.environment_map.clone(),
            bump_map_texture: material.bump_map_texture.clone(),
            displacement_map: material.displacement_map.clone(),
            displacement: material.into(),
            toon_ramp_texture: material.toon_ramp_texture.clone(),
        }
    }
}

/// The plugin's scene data that every Phong material binds beside its own, read from the
/// render world (the names are those of `bevy_phong::shaders::bindings`): 1 the light buffer
/// (`lights`), 2 the light clusters (`light_clusters`), 11 the shadow views (`shadow_views`), 12 the
/// shadow map array (`shadow_maps`), 13 its comparison sampler (`shadow_sampler`), 28 the
/// light cookie atlas (`cookie_atlas`, a 2D array read texel by texel). A
/// material of its own that lights with the crate's shader functions adds these bindings
/// the same way [`PhongMaterial`] does.
///
/// Where a shader stage has fewer than [`Self::STORAGE_BUFFERS_NEEDED`] storage buffers
/// (WebGL2 has none), binding 1 is instead one `texture_2d<u32>` that holds the lights, the
/// clusters and the shadow views (`scene_data`), and bindings 2, 11 and 28 are absent; the shaders
/// follow the layout through the flag `PHONG_STORAGE_BUFFERS`, which every pipeline drawing
/// with them sets from its material bind group's layout.
#[derive(SystemParam)]
pub struct PhongSceneBindings<'w> {
    device: Res<'w, RenderDevice>,
    buffers: Res<'w, RenderAssets<GpuShaderBuffer>>,
    images: Res<'w, RenderAssets<GpuImage>>,
    shadow_maps: Option<Res<'w, ShadowAtlas>>,
}

impl PhongSceneBindings<'_> {
    /// Binding index of the light buffer.
    pub const LIGHTS: u32 = crate::scene_variants::LIGHT_BUFFER_BINDING;
    /// Binding index of the scene data texture, where storage buffers are missing (in
    /// place of the light buffer).
    pub const SCENE_DATA: u32 = 1;
    /// Binding index of the light clusters.
    pub const LIGHT_CLUSTERS: u32 = 2;
    /// Binding index of the shadow views.
    pub const SHADOW_VIEWS: u32 = 11;
    /// Binding index of the shadow map array.
    pub const SHADOW_MAPS: u32 = 12;
    /// Binding index of the shadow maps' comparison sampler.
    pub const SHADOW_SAMPLER: u32 = 13;
    /// Binding index of the light cookie atlas (absent where the scene data is in the data
    /// texture).
    pub const COOKIE_ATLAS: u32 = 28;
    /// Storage buffers per shader stage the scene data needs to stay in buffers; with fewer
    /// it is read from the data texture.
    pub const STORAGE_BUFFERS_NEEDED: u32 = crate::render::STORAGE_BUFFERS_NEEDED;

    /// The layout entries of the scene bindings (read in the fragment stage) on
    /// `render_device`.
    pub fn layout_entries(render_device: &RenderDevice) -> Vec<BindGroupLayoutEntry> {
        Self::layout_entries_for(crate::render::needs_scene_texture(render_device))
    }

    /// The layout entries of the scene bindings, with the scene data in storage buffers or,
    /// when `scene_texture`, in the data texture.
    pub fn layout_entries_for(scene_texture: bool) -> Vec<BindGroupLayoutEntry> {
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
        let scene_data = if scene_texture {
            vec![entry(
                Self::SCENE_DATA,
                BindingType::Texture {
                    sample_type: TextureSampleType::Uint,
                    view_dimension: TextureViewDimension::D2,
                    multisampled: false,
                },
            )]
        } else {
            vec![
                entry(Self::LIGHTS, storage),
                entry(Self::LIGHT_CLUSTERS, storage),
                entry(Self::SHADOW_VIEWS, storage),
                entry(
                    Self::COOKIE_ATLAS,
                    BindingType::Texture {
                        sample_type: TextureSampleType::Float { filterable: true },
                        view_dimension: TextureViewDimension::D2Array,
                        multisampled: false,
                    },
                ),
            ]
        };
        let shadows = [
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
        ];
        scene_data.into_iter().chain(shadows).collect()
    }

    /// The three storage buffers' bindings.
    fn buffer_bindings(&self) -> Result<Vec<(u32, UnpreparedBindingResource)>, AsBindGroupError> {
        [
            (Self::LIGHTS, &PHONG_LIGHT_BUFFER),
            (Self::LIGHT_CLUSTERS, &PHONG_LIGHT_CLUSTER_BUFFER),
            (Self::SHADOW_VIEWS, &PHONG_SHADOW_VIEW_BUFFER),
        ]
        .into_iter()
        .map(|(binding, handle)| {
            let buffer = self
                .buffers
                .get(handle)
                .ok_or(AsBindGroupError::RetryNextUpdate)?;
            Ok((
                binding,
                UnpreparedBindingResource::Buffer(buffer.buffer.clone()),
            ))
        })
        .collect()
    }

    /// The scene's GPU resources for those entries; `RetryNextUpdate` until the plugin has
    /// uploaded them (in the first frame).
    pub fn bindings(&self) -> Result<Vec<(u32, UnpreparedBindingResource)>, AsBindGroupError> {
        let shadow_maps = self
            .shadow_maps
            .as_ref()
            .ok_or(AsBindGroupError::RetryNextUpdate)?;
        let mut bindings = if crate::render::needs_scene_texture(&self.device) {
            let texture = self
                .images
                .get(&crate::render::PHONG_SCENE_TEXTURE)
                .ok_or(AsBindGroupError::RetryNextUpdate)?;
            vec![(
                Self::SCENE_DATA,
                UnpreparedBindingResource::TextureView(
                    TextureViewDimension::D2,
                    texture.texture_view.clone(),
                ),
            )]
        } else {
            let cookies = self
                .images
                .get(&crate::render::PHONG_COOKIE_ATLAS)
                .ok_or(AsBindGroupError::RetryNextUpdate)?;
            let mut bindings = self.buffer_bindings()?;
            bindings.push((
                Self::COOKIE_ATLAS,
                UnpreparedBindingResource::TextureView(
                    TextureViewDimension::D2Array,
                    cookies.texture_view.clone(),
                ),
            ));
            bindings
        };
        bindings.push((
            Self::SHADOW_MAPS,
            UnpreparedBindingResource::TextureView(
                TextureViewDimension::D2Array,
                shadow_maps.array_view.clone(),
            ),
        ));
        bindings.push((
            Self::SHADOW_SAMPLER,
            UnpreparedBindingResource::Sampler(
                SamplerBindingType::Comparison,
                shadow_maps.sampler.clone(),
            ),
        ));
        Ok(bindings)
    }
}

/// The bindings of the alpha map, the environment map, the bump map (18 to 23) and the toon
/// ramp (27), which a device with fewer storage buffers than the scene data needs (WebGL2)
/// leaves out: there a fragment stage has 16 textures, which Bevy's view (its shadow maps,
/// prepass textures and lookup tables) shares with the material, and every other map of the
/// material fits beside them.
const MAPS_OF_FULL_DEVICES: [u32; 7] = [18, 19, 20, 21, 22, 23, 27];

/// Whether `render_device` binds every map of a [`PhongMaterial`]; where it does not
/// (WebGL2), the alpha map, the environment map, the bump map and the toon ramp are left
/// out, with a warning, and the material is drawn without them (a toon ramp's material in
/// its bands).
pub fn binds_every_map(render_device: &RenderDevice) -> bool {
    !crate::render::needs_scene_texture(render_device)
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

    fn build_bind_group(
        &self,
        layout: &BindGroupLayout,
        render_device: &RenderDevice,
        (surface, scene): &mut SystemParamItem<'_, '_, Self::Param>,
        _force_no_bindless: bool,
        output: &mut BindGroupBuilder,
    ) -> Result<(), AsBindGroupError> {
        // The builder may already hold another material's bindings (an extension's): only
        // the entries written here are filtered.
        let first = output.binding_resources.0.len();
        SurfaceBindings::from(self).build_bind_group(
            layout,
            render_device,
            surface,
            true,
            output,
        )?;
        if !binds_every_map(render_device) {
            if self.scene_variants.cookies {
                bevy::log::warn_once!(
                    "PhongLightCookie is left out on this device (WebGL2's 16 textures a \
                     shader stage): lights are drawn without their cookies"
                );
            }
            let mut index = 0;
            output.binding_resources.0.retain(|(binding, _)| {
                let keep = index < first || !MAPS_OF_FULL_DEVICES.contains(binding);
                index += 1;
                keep
            });
            if self.alpha_map_texture.is_some()
                || self.environment_map.is_some()
                || self.bump_map_texture.is_some()
                || self.toon_ramp_texture.is_some()
            {
                bevy::log::warn_once!(
                    "PhongMaterial.alpha_map_texture, environment_map, bump_map_texture and \
                     toon_ramp_texture are left out on this device (WebGL2's 16 textures a \
                     shader stage): drawn without them (a toon ramp's material in its bands)"
                );
            }
        }
        output.binding_resources.0.extend(scene.bindings()?);
        Ok(())
    }

    fn bind_group_layout_entries(
        render_device: &RenderDevice,
        _force_no_bindless: bool,
    ) -> Vec<BindGroupLayoutEntry> {
        let mut entries = SurfaceBindings::bind_group_layout_entries(render_device, true);
        if !binds_every_map(render_device) {
            entries.retain(|entry| !MAPS_OF_FULL_DEVICES.contains(&entry.binding));
        }
        entries.extend(PhongSceneBindings::layout_entries(render_device));
        entries
    }
}
