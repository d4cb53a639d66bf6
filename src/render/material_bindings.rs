//! How a [`PhongMaterial`] is bound: its own surface data (the uniform and the texture maps)
//! beside the plugin's scene data (the lights, their clusters and the shadow maps), which the
//! bind group takes from the render world when Bevy prepares the material.

use super::batching::{MaterialRecordBuffer, records_supported};
use super::{PHONG_LIGHT_BUFFER, PHONG_LIGHT_CLUSTER_BUFFER};
use crate::displacement::DisplacementUniform;
use crate::material::{
    MapDevices, PhongMaterial, PhongMaterialKey, PhongMaterialUniform, map_images, material_maps,
};
use crate::scene_variants::SceneVariants;
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

/// Declares [`SurfaceBindings`] and what is read of it from the rows of `material_maps!`.
macro_rules! surface_bindings {
    ($(
        $field:ident: texture($texture:literal $(, $($texture_option:tt)*)?)
            $(sampler($sampler:literal $(, $($sampler_option:tt)*)?))?,
            $devices:ident, $file:ident, $(uv $channel:ident,)? $what:literal;
    )*) => {
        /// The bindings a [`PhongMaterial`] brings itself, laid out by Bevy's derive: binding
        /// 0 the uniform, 26 the displacement's uniform (read in the vertex stage), and each
        /// texture map's as `material_maps!` declares them (3 to 10, 14 to 25, 27, 30, 31).
        #[derive(AsBindGroup)]
        struct SurfaceBindings {
            #[uniform(0)]
            uniform: PhongMaterialUniform,
            #[uniform(26)]
            displacement: DisplacementUniform,
            $(
                #[texture($texture $(, $($texture_option)*)?)]
                $(#[sampler($sampler $(, $($sampler_option)*)?)])?
                $field: Option<Handle<Image>>,
            )*
        }

        impl From<&PhongMaterial> for SurfaceBindings {
            fn from(material: &PhongMaterial) -> Self {
                Self {
                    uniform: material.into(),
                    displacement: material.into(),
                    $($field: material.$field.clone(),)*
                }
            }
        }

        /// Each map: its field, the devices that bind it, and its bindings.
        const MAP_BINDINGS: &[(&str, MapDevices, &[u32])] =
            &[$((stringify!($field), MapDevices::$devices, &[$texture $(, $sampler)?])),*];
    };
}

material_maps!(surface_bindings);

/// The plugin's scene data that every Phong material binds beside its own, read from the render
/// world (the names are those of `bevy_phong::shaders::bindings`): 1 the light buffer (`lights`), 2
/// the light clusters (`light_clusters`), 11 the shadow views (`shadow_views`), 12 the shadow map
/// array (`shadow_maps`), 13 its comparison sampler (`shadow_sampler`), 28 the light cookie atlas
/// (`cookie_atlas`, a 2D array read texel by texel), and where the device has a storage
/// buffer per stage more than the scene data needs, 29 every `PhongMaterial`'s numbers
/// (`material_records`, which only `PhongMaterial`'s own shaders read). A material of its
/// own that lights with the crate's shader functions adds these bindings the same way
/// [`PhongMaterial`] does.
///
/// Where a shader stage has fewer than [`Self::STORAGE_BUFFERS_NEEDED`] storage buffers
/// (WebGL2 has none), binding 1 is instead one `texture_2d<u32>` that holds the lights, the
/// clusters and the shadow views (`scene_data`), and bindings 2, 11, 28 and 29 are absent; the shaders
/// follow the layout through the flag `PHONG_STORAGE_BUFFERS`, which every pipeline drawing
/// with them sets from its material bind group's layout.
#[derive(SystemParam)]
pub struct PhongSceneBindings<'w> {
    device: Res<'w, RenderDevice>,
    buffers: Res<'w, RenderAssets<GpuShaderBuffer>>,
    images: Res<'w, RenderAssets<GpuImage>>,
    shadow_maps: Option<Res<'w, ShadowAtlas>>,
    material_records: Option<Res<'w, MaterialRecordBuffer>>,
    variants: Option<Res<'w, SceneVariants>>,
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
    /// Binding index of every `PhongMaterial`'s numbers, one record each (present where the
    /// device has a storage buffer per stage more than [`Self::STORAGE_BUFFERS_NEEDED`];
    /// read only by `PhongMaterial`'s own shaders).
    pub const MATERIAL_RECORDS: u32 = 29;
    /// Storage buffers per shader stage the scene data needs to stay in buffers; with fewer
    /// it is read from the data texture.
    pub const STORAGE_BUFFERS_NEEDED: u32 = crate::render::STORAGE_BUFFERS_NEEDED;

    /// The layout entries of the scene bindings (read in the vertex stage of a material lit
    /// per vertex, and in the fragment stage) on `render_device`.
    pub fn layout_entries(render_device: &RenderDevice) -> Vec<BindGroupLayoutEntry> {
        Self::layout_entries_for(
            crate::render::needs_scene_texture(render_device),
            records_supported(render_device),
        )
    }

    /// The layout entries of the scene bindings, with the scene data in storage buffers or,
    /// when `scene_texture`, in the data texture; with `material_records` (and storage
    /// buffers), the materials' records too.
    pub fn layout_entries_for(
        scene_texture: bool,
        material_records: bool,
    ) -> Vec<BindGroupLayoutEntry> {
        let entry = |binding, ty| BindGroupLayoutEntry {
            binding,
            visibility: ShaderStages::VERTEX_FRAGMENT,
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
        let records =
            (material_records && !scene_texture).then(|| entry(Self::MATERIAL_RECORDS, storage));
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
        scene_data
            .into_iter()
            .chain(records)
            .chain(shadows)
            .collect()
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
            if let Some(records) = &self.material_records {
                bindings.push((
                    Self::MATERIAL_RECORDS,
                    UnpreparedBindingResource::Buffer(records.buffer().clone()),
                ));
            }
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

/// Whether `binding` is one of the maps that a device with fewer storage buffers than the
/// scene data needs (WebGL2) leaves out ([`MapDevices::Full`]): there a fragment stage has
/// 16 textures, which Bevy's view (its shadow maps, prepass textures and lookup tables)
/// shares with the material, and every other map of the material fits beside them.
fn only_on_full_devices(binding: u32) -> bool {
    MAP_BINDINGS
        .iter()
        .any(|(_, devices, bindings)| *devices == MapDevices::Full && bindings.contains(&binding))
}

/// Each map's field, its texture's binding and whether every device binds it (for the
/// shader tests, which compare them with `bevy_phong::shaders::bindings`).
#[cfg(feature = "testing")]
pub fn material_map_bindings() -> Vec<(&'static str, u32, bool)> {
    MAP_BINDINGS
        .iter()
        .map(|(field, devices, bindings)| (*field, bindings[0], *devices == MapDevices::All))
        .collect()
}

/// Whether `render_device` binds every map of a [`PhongMaterial`]; where it does not
/// (WebGL2), the maps `material_maps!` marks `MapDevices::Full` (the alpha map, the
/// environment map, the bump map and the toon ramp) are left out, with a warning, and the
/// material is drawn without them (a toon ramp's material in its bands).
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
            if scene
                .variants
                .as_ref()
                .is_some_and(|variants| variants.cookies)
            {
                bevy::log::warn_once!(
                    "PhongLightCookie is left out on this device (WebGL2's 16 textures a \
                     shader stage): lights are drawn without their cookies"
                );
            }
            let mut index = 0;
            output.binding_resources.0.retain(|(binding, _)| {
                let keep = index < first || !only_on_full_devices(*binding);
                index += 1;
                keep
            });
            let left_out: Vec<&str> = map_images(self)
                .into_iter()
                .zip(MAP_BINDINGS)
                .filter(|(image, (_, devices, _))| image.is_some() && *devices == MapDevices::Full)
                .map(|(_, (field, ..))| *field)
                .collect();
            if !left_out.is_empty() {
                bevy::log::warn_once!(
                    "PhongMaterial.{} left out on this device (WebGL2's 16 textures a shader \
                     stage): drawn without them (a toon ramp's material in its bands)",
                    left_out.join(", PhongMaterial.")
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
            entries.retain(|entry| !only_on_full_devices(entry.binding));
        }
        entries.extend(PhongSceneBindings::layout_entries(render_device));
        entries
    }
}
