//! The render world's part of the shadows: the shadow map array, the depth-only pipeline
//! that draws casters into it, and the pass that draws every map of the frame before the
//! cameras render.

use super::gather::{AtlasLayout, CasterSource, ShadowFrame};
use bevy::{
    asset::{AssetServer, Handle},
    ecs::{
        resource::Resource,
        system::{Commands, Res, ResMut},
        world::{FromWorld, World},
    },
    log::error,
    mesh::{
        Mesh, MeshVertexBufferLayout, MeshVertexBufferLayoutRef, MeshVertexBufferLayouts,
        PrimitiveTopology, VertexBufferLayout,
    },
    prelude::default,
    render::{
        Extract,
        mesh::{RenderMesh, RenderMeshBufferInfo, allocator::MeshAllocator},
        render_asset::RenderAssets,
        render_phase::TrackedRenderPass,
        render_resource::{
            AddressMode, BufferUsages, CachedRenderPipelineId, CompareFunction, DepthBiasState,
            DepthStencilState, Extent3d, FilterMode, LoadOp, Operations, PipelineCache,
            PrimitiveState, RawBufferVec, RenderPassDepthStencilAttachment, RenderPassDescriptor,
            RenderPipelineDescriptor, Sampler, SamplerDescriptor, SpecializedMeshPipeline,
            SpecializedMeshPipelineError, SpecializedMeshPipelines, StoreOp, Texture,
            TextureDescriptor, TextureDimension, TextureFormat, TextureUsages, TextureView,
            TextureViewDescriptor, TextureViewDimension, VertexAttribute, VertexFormat,
            VertexState, VertexStepMode,
        },
        renderer::{RenderContext, RenderDevice, RenderQueue},
    },
    shader::Shader,
};

/// How far each caster's depth is pushed away from the light as it is drawn, in multiples
/// of its own depth change across one texel (the rasterizer's slope-scaled depth bias): a
/// surface slanted to the light then stays behind its own stored depth over the two texels
/// the bilinear comparison reads, instead of shadowing itself in stripes (acne).
pub(crate) const SLOPE_BIAS_TEXELS: f32 = 2.0;

/// The format of the shadow maps: 32-bit float depth, reversed (near 1, far 0).
pub(crate) const SHADOW_MAP_FORMAT: TextureFormat = TextureFormat::Depth32Float;

/// The shadow map array every Phong material binds, and the comparison sampler it is read
/// with.
#[derive(Resource)]
pub(crate) struct ShadowAtlas {
    layout: AtlasLayout,
    /// The whole array, as materials bind it.
    pub array_view: TextureView,
    /// One view per layer, for the passes that draw the maps.
    layer_views: Vec<TextureView>,
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

/// Copies the main world's [`ShadowFrame`] into the render world.
pub(crate) fn extract_shadow_frame(mut commands: Commands, frame: Extract<Res<ShadowFrame>>) {
    commands.insert_resource(frame.clone());
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

/// The depth-only pipeline that draws a caster into a shadow map: its positions, placed by
/// a per-draw `clip_from_local` matrix read as an instance attribute.
#[derive(Resource)]
pub(crate) struct ShadowCasterPipeline {
    shader: Handle<Shader>,
}

impl FromWorld for ShadowCasterPipeline {
    fn from_world(world: &mut World) -> Self {
        Self {
            shader: world
                .resource::<AssetServer>()
                .load("embedded://bevy_phong/shaders/shadow_caster.wgsl"),
        }
    }
}

impl SpecializedMeshPipeline for ShadowCasterPipeline {
    type Key = PrimitiveTopology;

    fn specialize(
        &self,
        topology: PrimitiveTopology,
        layout: &MeshVertexBufferLayoutRef,
    ) -> Result<RenderPipelineDescriptor, SpecializedMeshPipelineError> {
        let positions = layout
            .0
            .get_layout(&[Mesh::ATTRIBUTE_POSITION.at_shader_location(0)])?;
        let clip_from_local = VertexBufferLayout {
            array_stride: 64,
            step_mode: VertexStepMode::Instance,
            attributes: (0..4)
                .map(|column| VertexAttribute {
                    format: VertexFormat::Float32x4,
                    offset: 16 * column as u64,
                    shader_location: 1 + column,
                })
                .collect(),
        };
        Ok(RenderPipelineDescriptor {
            label: Some("phong_shadow_caster".into()),
            vertex: VertexState {
                shader: self.shader.clone(),
                entry_point: Some("vertex".into()),
                buffers: vec![positions, clip_from_local],
                ..default()
            },
            primitive: PrimitiveState {
                topology,
                // Both faces: open meshes (a plane) cast too.
                cull_mode: None,
                ..default()
            },
            depth_stencil: Some(DepthStencilState {
                format: SHADOW_MAP_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(CompareFunction::GreaterEqual),
                stencil: default(),
                // Reversed depth: away from the light is down.
                bias: DepthBiasState {
                    constant: 0,
                    slope_scale: -SLOPE_BIAS_TEXELS,
                    clamp: 0.0,
                },
            }),
            ..default()
        })
    }
}

/// The pipeline of each caster of the frame's maps, in [`ShadowFrame::instances`] order
/// (`None` for a mesh that is not loaded or not made of triangles), the instance buffer
/// of their `clip_from_local` matrices, and the vertex buffer of the posed (skinned and
/// morphed) casters' triangles.
#[derive(Resource)]
pub(crate) struct ShadowDraws {
    pipelines: Vec<Option<CachedRenderPipelineId>>,
    instances: RawBufferVec<[f32; 16]>,
    deformed_vertices: RawBufferVec<[f32; 3]>,
    /// The vertex layout of `deformed_vertices`: positions only.
    deformed_layout: Option<MeshVertexBufferLayoutRef>,
}

impl Default for ShadowDraws {
    fn default() -> Self {
        Self {
            pipelines: Vec::new(),
            instances: RawBufferVec::new(BufferUsages::VERTEX),
            deformed_vertices: RawBufferVec::new(BufferUsages::VERTEX),
            deformed_layout: None,
        }
    }
}

/// The vertex layout of posed casters' triangles: world positions, `Float32x3`.
fn positions_only_layout(layouts: &mut MeshVertexBufferLayouts) -> MeshVertexBufferLayoutRef {
    layouts.insert(MeshVertexBufferLayout::new(
        vec![Mesh::ATTRIBUTE_POSITION.id],
        VertexBufferLayout {
            array_stride: 12,
            step_mode: VertexStepMode::Vertex,
            attributes: vec![VertexAttribute {
                format: VertexFormat::Float32x3,
                offset: 0,
                shader_location: 0,
            }],
        },
    ))
}

/// Finds each caster's pipeline (compiling it the first time its vertex layout is seen) and
/// uploads the frame's instance matrices and posed triangles.
#[allow(clippy::too_many_arguments)]
pub(crate) fn prepare_shadow_draws(
    frame: Option<Res<ShadowFrame>>,
    meshes: Res<RenderAssets<RenderMesh>>,
    pipeline: Res<ShadowCasterPipeline>,
    mut pipelines: ResMut<SpecializedMeshPipelines<ShadowCasterPipeline>>,
    mut layouts: ResMut<MeshVertexBufferLayouts>,
    cache: Res<PipelineCache>,
    mut draws: ResMut<ShadowDraws>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
) {
    let draws = &mut *draws;
    draws.pipelines.clear();
    draws.instances.clear();
    draws.deformed_vertices.clear();
    let Some(frame) = frame else { return };
    let deformed_layout = draws
        .deformed_layout
        .get_or_insert_with(|| positions_only_layout(&mut layouts))
        .clone();
    let mut specialize = |topology, layout: &MeshVertexBufferLayoutRef| match pipelines
        .specialize(&cache, &pipeline, topology, layout)
    {
        Ok(id) => Some(id),
        Err(err) => {
            error!("cannot draw a shadow caster: {err}");
            None
        }
    };
    for instance in &frame.instances {
        draws
            .instances
            .push(instance.clip_from_local.to_cols_array());
        let pipeline_id = match &instance.source {
            CasterSource::Deformed(_) => {
                specialize(PrimitiveTopology::TriangleList, &deformed_layout)
            }
            CasterSource::Mesh(mesh) => meshes.get(*mesh).and_then(|mesh| {
                let topology = mesh.primitive_topology();
                let is_triangles = matches!(
                    topology,
                    PrimitiveTopology::TriangleList | PrimitiveTopology::TriangleStrip
                );
                is_triangles
                    .then(|| specialize(topology, &mesh.layout))
                    .flatten()
            }),
        };
        draws.pipelines.push(pipeline_id);
    }
    if !draws.instances.is_empty() {
        draws.instances.write_buffer(&device, &queue);
    }
    if !frame.deformed_vertices.is_empty() {
        draws.deformed_vertices.extend(
            frame
                .deformed_vertices
                .iter()
                .map(|vertex| vertex.to_array()),
        );
        draws.deformed_vertices.write_buffer(&device, &queue);
    }
}

/// Draws every shadow map of the frame: each pass clears its layer, then draws its casters.
pub(crate) fn render_shadow_maps(
    frame: Option<Res<ShadowFrame>>,
    atlas: Res<ShadowAtlas>,
    draws: Res<ShadowDraws>,
    cache: Res<PipelineCache>,
    meshes: Res<RenderAssets<RenderMesh>>,
    allocator: Res<MeshAllocator>,
    mut context: RenderContext,
) {
    let Some(frame) = frame else { return };
    // Without a caster at all there is no instance buffer: the maps are only cleared.
    let instance_buffer = draws.instances.buffer();
    for pass in &frame.passes {
        let Some(layer_view) = atlas.layer_views.get(pass.layer as usize) else {
            continue;
        };
        let mut render_pass = clearing_depth_pass(&mut context, layer_view, "phong_shadow_map");
        let size = pass.resolution as f32;
        render_pass.set_viewport(0.0, 0.0, size, size, 0.0, 1.0);
        let Some(instance_buffer) = instance_buffer else {
            continue;
        };
        for index in pass.instances.clone() {
            let Some(pipeline) =
                draws.pipelines[index].and_then(|id| cache.get_render_pipeline(id))
            else {
                continue;
            };
            let offset = index as u64 * 64;
            let mesh_id = match &frame.instances[index].source {
                CasterSource::Deformed(vertices) => {
                    let Some(buffer) = draws.deformed_vertices.buffer() else {
                        continue;
                    };
                    render_pass.set_render_pipeline(pipeline);
                    render_pass.set_vertex_buffer(0, buffer.slice(..));
                    render_pass.set_vertex_buffer(1, instance_buffer.slice(offset..offset + 64));
                    render_pass.draw(vertices.clone(), 0..1);
                    continue;
                }
                CasterSource::Mesh(mesh_id) => *mesh_id,
            };
            let (Some(mesh), Some(vertices)) =
                (meshes.get(mesh_id), allocator.mesh_vertex_slice(&mesh_id))
            else {
                continue;
            };
            render_pass.set_render_pipeline(pipeline);
            render_pass.set_vertex_buffer(0, vertices.buffer.slice(..));
            render_pass.set_vertex_buffer(1, instance_buffer.slice(offset..offset + 64));
            match &mesh.buffer_info {
                RenderMeshBufferInfo::Indexed {
                    count,
                    index_format,
                } => {
                    let Some(indices) = allocator.mesh_index_slice(&mesh_id) else {
                        continue;
                    };
                    render_pass.set_index_buffer(indices.buffer.slice(..), *index_format);
                    render_pass.draw_indexed(
                        indices.range.start..indices.range.start + count,
                        vertices.range.start as i32,
                        0..1,
                    );
                }
                RenderMeshBufferInfo::NonIndexed => {
                    render_pass.draw(
                        vertices.range.start..vertices.range.start + mesh.vertex_count,
                        0..1,
                    );
                }
            }
        }
    }
}

/// A depth-only pass into `view` that starts by clearing it to 0 (reversed depth: nothing
/// in the way).
fn clearing_depth_pass<'a>(
    context: &'a mut RenderContext,
    view: &TextureView,
    label: &'static str,
) -> TrackedRenderPass<'a> {
    context.begin_tracked_render_pass(RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[],
        depth_stencil_attachment: Some(RenderPassDepthStencilAttachment {
            view,
            depth_ops: Some(Operations {
                load: LoadOp::Clear(0.0),
                store: StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}
