//! The shadow map array every Phong material binds: one square depth layer per map, sized
//! to the frame's maps, with the comparison sampler it is read with.

use super::{
    caster_pipeline::SHADOW_MAP_FORMAT,
    gather::{AtlasLayout, ShadowFrame},
};
use bevy::{
    ecs::{
        resource::Resource,
        system::{Res, ResMut},
        world::{FromWorld, World},
    },
    prelude::default,
    render::{
        render_resource::{
            AddressMode, CompareFunction, Extent3d, FilterMode, Sampler, SamplerDescriptor,
            Texture, TextureDescriptor, TextureDimension, TextureUsages, TextureView,
            TextureViewDescriptor, TextureViewDimension,
        },
        renderer::RenderDevice,
    },
};

/// The shadow map array every Phong material binds, and the comparison sampler it is read
/// with.
#[derive(Resource)]
pub(crate) struct ShadowAtlas {
    pub(super) layout: AtlasLayout,
    /// The whole array, as materials bind it.
    pub array_view: TextureView,
    /// One view per layer, for the passes that draw the maps.
    pub(super) layer_views: Vec<TextureView>,
    /// Compares with `GreaterEqual` (lit where the point is at least as near the light as
    /// what the map holds), filtering bilinearly: a 2×2 percentage-closer filter per tap.
    pub sampler: Sampler,
    _texture: Texture,
}

impl ShadowAtlas {
    fn new(device: &RenderDevice, layout: AtlasLayout, sampler: Sampler) -> Self {
        let size = layout.size.max(1);
        let layers = layout.layers.max(1);
        let texture = device.create_texture(&TextureDescriptor {
            label: Some("phong_shadow_maps"),
            size: Extent3d {
                width: size,
                height: size,
                depth_or_array_layers: layers,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: TextureDimension::D2,
            format: SHADOW_MAP_FORMAT,
            usage: TextureUsages::RENDER_ATTACHMENT | TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let array_view = texture.create_view(&TextureViewDescriptor {
            label: Some("phong_shadow_maps_array"),
            dimension: Some(TextureViewDimension::D2Array),
            ..default()
        });
        let layer_views = (0..layers)
            .map(|layer| {
                texture.create_view(&TextureViewDescriptor {
                    label: Some("phong_shadow_map_layer"),
                    dimension: Some(TextureViewDimension::D2),
                    base_array_layer: layer,
                    array_layer_count: Some(1),
                    ..default()
                })
            })
            .collect();
        Self {
            layout,
            array_view,
            layer_views,
            sampler,
            _texture: texture,
        }
    }
}

impl FromWorld for ShadowAtlas {
    fn from_world(world: &mut World) -> Self {
        let device = world.resource::<RenderDevice>();
        let sampler = device.create_sampler(&SamplerDescriptor {
            label: Some("phong_shadow_sampler"),
            address_mode_u: AddressMode::ClampToEdge,
            address_mode_v: AddressMode::ClampToEdge,
            address_mode_w: AddressMode::ClampToEdge,
            mag_filter: FilterMode::Linear,
            min_filter: FilterMode::Linear,
            compare: Some(CompareFunction::GreaterEqual),
            ..default()
        });
        Self::new(device, AtlasLayout::default(), sampler)
    }
}

/// Makes the shadow map array the size this frame needs. The main world marks every Phong
/// material modified in the same frame, so their bind groups are rebuilt after this.
pub(crate) fn prepare_shadow_atlas(
    mut atlas: ResMut<ShadowAtlas>,
    frame: Option<Res<ShadowFrame>>,
    device: Res<RenderDevice>,
) {
    let Some(frame) = frame else { return };
    if frame.layout != atlas.layout && frame.layout.layers > 0 {
        let sampler = atlas.sampler.clone();
        *atlas = ShadowAtlas::new(&device, frame.layout, sampler);
    }
}
