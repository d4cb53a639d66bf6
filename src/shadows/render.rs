//! The render world's part of the shadows: the shadow map array, the depth-only pipeline
//! that draws casters into it, and the pass that draws every map of the frame before the
//! cameras render.

use super::{
    displaced::{DisplacedBindGroups, displacement_layout},
    gather::{AtlasLayout, CasterSource, ShadowFrame},
    masked::{MaskMaps, MaskedBindGroups, mask_layout},
    posed::{BevyDeformation, PosedBindGroups, PosedDraw, PosedLayouts},
};
use crate::displacement::can_displace;
use crate::storage_buffer::needs_scene_texture;
use bevy::{
    asset::{AssetId, AssetServer, Handle},
    ecs::{
        resource::Resource,
        system::{Commands, Local, Res, ResMut},
        world::{FromWorld, World},
    },
    image::Image,
    log::{error, warn},
    mesh::{Mesh, MeshVertexBufferLayoutRef, PrimitiveTopology, VertexBufferLayout},
    platform::collections::HashSet,
    prelude::default,
    render::{
        Extract,
        mesh::{RenderMesh, RenderMeshBufferInfo, allocator::MeshAllocator},
        render_asset::RenderAssets,
        render_phase::TrackedRenderPass,
        render_resource::{
            AddressMode, BufferUsages, CachedRenderPipelineId, CompareFunction, DepthBiasState,
            DepthStencilState, Extent3d, FilterMode, FragmentState, LoadOp, Operations,
            PipelineCache, PrimitiveState, RawBufferVec, RenderPassDepthStencilAttachment,
            RenderPassDescriptor, RenderPipelineDescriptor, Sampler, SamplerDescriptor,
            SpecializedMeshPipeline, SpecializedMeshPipelineError, SpecializedMeshPipelines,
            StoreOp, Texture, TextureDescriptor, TextureDimension, TextureFormat, TextureUsages,
            TextureView, TextureViewDescriptor, TextureViewDimension, VertexAttribute,
            VertexFormat, VertexState, VertexStepMode,
        },
        renderer::{RenderContext, RenderDevice, RenderQueue},
        sync_world::MainEntity,
    },
    shader::{Shader, ShaderDefVal},
};
use bytemuck::{Pod, Zeroable};

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
/// a per-draw `clip_from_local` matrix read as an instance attribute; for a skinned or
/// morphed caster, posed first by Bevy's joints and weights ([`super::posed`]).
#[derive(Resource)]
pub(crate) struct ShadowCasterPipeline {
    shader: Handle<Shader>,
    /// The bind group layouts of posed casters' data.
    pub posed_layouts: PosedLayouts,
}

impl FromWorld for ShadowCasterPipeline {
    fn from_world(world: &mut World) -> Self {
        Self {
            shader: world
                .resource::<AssetServer>()
                .load("embedded://bevy_phong/shaders/shadow_caster.wesl"),
            posed_layouts: PosedLayouts::new(&world.resource::<RenderDevice>().limits()),
        }
    }
}

/// A caster pipeline's variant: the mesh's topology, for a posed caster whether its joints
/// and its morph targets pose it, whether a displacement map moves its vertices, and for a
/// masked caster what its alpha is made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct ShadowCasterKey {
    topology: PrimitiveTopology,
    posed: Option<(bool, bool)>,
    /// A displaced caster's UV set: `Some(true)` the second.
    displaced: Option<bool>,
    mask: Option<MaskKey>,
}

/// What a masked caster's alpha is made of besides its base color's: the base color map's
/// alpha, the alpha map's green (each at the UV set it is read at: `Some(true)` the second)
/// and the vertex colors' alpha.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct MaskKey {
    base_color_texture: Option<bool>,
    alpha_map: Option<bool>,
    vertex_colors: bool,
}

impl MaskKey {
    /// Whether the mask reads a map at the second UV set (`second`) or at the first.
    fn reads_uvs(self, second: bool) -> bool {
        [self.base_color_texture, self.alpha_map].contains(&Some(second))
    }

    /// The shader defs of the mask's variant.
    fn shader_defs(self) -> Vec<ShaderDefVal> {
        [
            (true, "MASKED"),
            (self.reads_uvs(false), "MASK_UVS"),
            (self.reads_uvs(true), "MASK_UVS_B"),
            (self.base_color_texture.is_some(), "MASK_BASE_COLOR_TEXTURE"),
            (
                self.base_color_texture == Some(true),
                "MASK_BASE_COLOR_UV_B",
            ),
            (self.alpha_map.is_some(), "MASK_ALPHA_MAP"),
            (self.alpha_map == Some(true), "MASK_ALPHA_MAP_UV_B"),
            (self.vertex_colors, "MASK_VERTEX_COLORS"),
        ]
        .into_iter()
        .filter(|(on, _)| *on)
        .map(|(_, def)| def.into())
        .collect()
    }
}

/// One draw's instance data (`Caster` in `shadow_caster.wesl`): the matrix to the map's
/// clip space by columns, then where a posed caster's deformation is (see
/// [`PosedDraw::deform`]), then a displaced caster's UV transform, scale and bias (see
/// [`super::displaced::CasterDisplacement::instance_data`]), then a masked caster's UV
/// transform, base alpha and cutoff (see [`super::masked::CasterMask::instance_data`]).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct CasterInstance {
    clip_from_local: [f32; 16],
    deform: [u32; 4],
    displacement: [f32; 8],
    mask: [f32; 8],
}

/// Bytes of a [`CasterInstance`].
const INSTANCE_SIZE: u64 = size_of::<CasterInstance>() as u64;

impl SpecializedMeshPipeline for ShadowCasterPipeline {
    type Key = ShadowCasterKey;

    fn specialize(
        &self,
        key: ShadowCasterKey,
        layout: &MeshVertexBufferLayoutRef,
    ) -> Result<RenderPipelineDescriptor, SpecializedMeshPipelineError> {
        let (skinned, morphed) = key.posed.unwrap_or_default();
        let mut attributes = vec![Mesh::ATTRIBUTE_POSITION.at_shader_location(0)];
        if skinned {
            attributes.push(Mesh::ATTRIBUTE_JOINT_INDEX.at_shader_location(6));
            attributes.push(Mesh::ATTRIBUTE_JOINT_WEIGHT.at_shader_location(7));
        }
        if key.displaced.is_some() {
            attributes.push(Mesh::ATTRIBUTE_NORMAL.at_shader_location(8));
        }
        let reads_uvs = |second: bool| {
            key.displaced == Some(second) || key.mask.is_some_and(|mask| mask.reads_uvs(second))
        };
        if reads_uvs(false) {
            attributes.push(Mesh::ATTRIBUTE_UV_0.at_shader_location(9));
        }
        if reads_uvs(true) {
            attributes.push(Mesh::ATTRIBUTE_UV_1.at_shader_location(15));
        }
        if key.mask.is_some_and(|mask| mask.vertex_colors) {
            attributes.push(Mesh::ATTRIBUTE_COLOR.at_shader_location(14));
        }
        let vertices = layout.0.get_layout(&attributes)?;
        let mut instance_attributes: Vec<VertexAttribute> = (0..4)
            .map(|column| VertexAttribute {
                format: VertexFormat::Float32x4,
                offset: 16 * column as u64,
                shader_location: 1 + column,
            })
            .collect();
        let (mut bind_group_layouts, mut shader_defs) = match key.posed {
            Some(_) => {
                instance_attributes.push(VertexAttribute {
                    format: VertexFormat::Uint32x4,
                    offset: 64,
                    shader_location: 5,
                });
                self.posed_layouts.pipeline_parts(skinned, morphed)
            }
            None => (Vec::new(), Vec::new()),
        };
        if let Some(second_uvs) = key.displaced {
            instance_attributes.extend([10, 11].map(|shader_location| VertexAttribute {
                format: VertexFormat::Float32x4,
                offset: 80 + 16 * (shader_location as u64 - 10),
                shader_location,
            }));
            shader_defs.push("DISPLACED".into());
            if second_uvs {
                shader_defs.push("DISPLACED_UV_B".into());
            }
            shader_defs.push(ShaderDefVal::UInt(
                "DISPLACEMENT_GROUP".into(),
                bind_group_layouts.len() as u32,
            ));
            bind_group_layouts.push(displacement_layout());
        }
        let fragment = key.mask.map(|mask| {
            instance_attributes.extend([12, 13].map(|shader_location| VertexAttribute {
                format: VertexFormat::Float32x4,
                offset: 112 + 16 * (shader_location as u64 - 12),
                shader_location,
            }));
            shader_defs.extend(mask.shader_defs());
            shader_defs.push(ShaderDefVal::UInt(
                "MASK_GROUP".into(),
                bind_group_layouts.len() as u32,
            ));
            bind_group_layouts.push(mask_layout());
            FragmentState {
                shader: self.shader.clone(),
                shader_defs: shader_defs.clone(),
                entry_point: Some("masked".into()),
                targets: Vec::new(),
                ..default()
            }
        });
        let instance = VertexBufferLayout {
            array_stride: INSTANCE_SIZE,
            step_mode: VertexStepMode::Instance,
            attributes: instance_attributes,
        };
        Ok(RenderPipelineDescriptor {
            label: Some("phong_shadow_caster".into()),
            layout: bind_group_layouts,
            vertex: VertexState {
                shader: self.shader.clone(),
                shader_defs,
                entry_point: Some("vertex".into()),
                buffers: vec![vertices, instance],
                ..default()
            },
            // Depth only: a masked caster's fragments are discarded where its mask is open.
            fragment,
            primitive: PrimitiveState {
                topology: key.topology,
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
/// (`None` for a mesh that is not loaded or not made of triangles, or a posed caster whose
/// deformation Bevy has not prepared), where each posed caster's deformation is, and the
/// instance buffer of their [`CasterInstance`]s.
#[derive(Resource)]
pub(crate) struct ShadowDraws {
    pipelines: Vec<Option<CachedRenderPipelineId>>,
    posed: Vec<Option<PosedDraw>>,
    /// Each displaced caster's map, and the bind group it is bound at.
    displaced: Vec<Option<(AssetId<Image>, u32)>>,
    /// Each masked caster's maps, and the bind group they are bound at.
    masked: Vec<Option<(MaskMaps, u32)>>,
    instances: RawBufferVec<CasterInstance>,
}

impl Default for ShadowDraws {
    fn default() -> Self {
        Self {
            pipelines: Vec::new(),
            posed: Vec::new(),
            displaced: Vec::new(),
            masked: Vec::new(),
            instances: RawBufferVec::new(BufferUsages::VERTEX),
        }
    }
}

impl ShadowDraws {
    /// The posed casters' draws of this frame.
    pub fn posed(&self) -> impl Iterator<Item = &PosedDraw> {
        self.posed.iter().flatten()
    }

    /// The displacement maps of this frame's displaced casters (repeated per caster).
    pub fn displacement_maps(&self) -> impl Iterator<Item = AssetId<Image>> + '_ {
        self.displaced.iter().flatten().map(|(map, _)| *map)
    }

    /// The maps of this frame's masked casters (repeated per caster).
    pub fn mask_maps(&self) -> impl Iterator<Item = MaskMaps> + '_ {
        self.masked.iter().flatten().map(|(maps, _)| *maps)
    }
}

/// Finds each caster's pipeline (compiling it the first time its vertex layout is seen) and
/// uploads the frame's instance data.
#[allow(clippy::too_many_arguments)]
pub(crate) fn prepare_shadow_draws(
    frame: Option<Res<ShadowFrame>>,
    meshes: Res<RenderAssets<RenderMesh>>,
    allocator: Res<MeshAllocator>,
    deformation: BevyDeformation,
    pipeline: Res<ShadowCasterPipeline>,
    mut pipelines: ResMut<SpecializedMeshPipelines<ShadowCasterPipeline>>,
    cache: Res<PipelineCache>,
    mut draws: ResMut<ShadowDraws>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    mut warned_compressed: Local<HashSet<AssetId<Mesh>>>,
) {
    let draws = &mut *draws;
    draws.pipelines.clear();
    draws.posed.clear();
    draws.displaced.clear();
    draws.masked.clear();
    draws.instances.clear();
    let Some(frame) = frame else { return };
    // The alpha map is bound where the main pass binds it (not under WebGL2's limits).
    let alpha_map_bound = !needs_scene_texture(&device);
    let mut specialize = |key, layout: &MeshVertexBufferLayoutRef| match pipelines
        .specialize(&cache, &pipeline, key, layout)
    {
        Ok(id) => Some(id),
        Err(err) => {
            error!("cannot draw a shadow caster: {err}");
            None
        }
    };
    for instance in &frame.instances {
        let (mesh_id, posed) = match instance.source {
            CasterSource::Mesh(mesh) => (mesh, None),
            CasterSource::Posed {
                entity,
                mesh,
                skinned,
            } => (mesh, Some((entity, skinned))),
        };
        let mesh = meshes.get(mesh_id).filter(|mesh| {
            matches!(
                mesh.primitive_topology(),
                PrimitiveTopology::TriangleList | PrimitiveTopology::TriangleStrip
            ) && !is_compressed(&mesh.layout, mesh_id, &mut warned_compressed)
        });
        let posed_draw = posed.zip(mesh).and_then(|((entity, skinned), mesh)| {
            let first_vertex = allocator.mesh_vertex_slice(&mesh_id)?.range.start;
            let morphed = mesh.has_morph_targets();
            deformation
                .draw(
                    MainEntity::from(entity),
                    mesh_id,
                    first_vertex,
                    skinned,
                    morphed,
                    &pipeline.posed_layouts,
                    &allocator,
                )
                .map(|draw| (draw, (skinned, morphed)))
        });
        // A displacement moves the vertices of a mesh that has its UV set and normals.
        let displacement = instance.displacement.as_ref().filter(|displacement| {
            mesh.is_some_and(|mesh| can_displace(&mesh.layout, displacement.second_uvs))
        });
        // A mask's maps are read where the mesh has their UV sets, as the main pass reads them.
        let mask = instance.mask.as_ref().zip(mesh).map(|(mask, mesh)| {
            let has = |attribute| mesh.layout.0.contains(attribute);
            let has_uvs = (has(Mesh::ATTRIBUTE_UV_0), has(Mesh::ATTRIBUTE_UV_1));
            let maps = mask.maps(alpha_map_bound, has_uvs);
            let key = MaskKey {
                base_color_texture: maps.0.map(|_| mask.base_color_second_uvs),
                alpha_map: maps.1.map(|_| mask.alpha_map_second_uvs),
                vertex_colors: has(Mesh::ATTRIBUTE_COLOR),
            };
            (key, maps, mask.instance_data())
        });
        let key = |posed| ShadowCasterKey {
            topology: mesh.map_or(PrimitiveTopology::TriangleList, |m| m.primitive_topology()),
            posed,
            displaced: displacement.map(|displacement| displacement.second_uvs),
            mask: mask.map(|(key, ..)| key),
        };
        let pipeline_id = match (mesh, posed, posed_draw) {
            (Some(mesh), None, _) => specialize(key(None), &mesh.layout),
            (Some(mesh), Some(_), Some((_, variant))) => {
                specialize(key(Some(variant)), &mesh.layout)
            }
            _ => None,
        };
        let posed_groups = match posed_draw {
            Some((_, (_, true))) => 2,
            Some(_) => 1,
            None => 0,
        };
        draws.pipelines.push(pipeline_id);
        draws.posed.push(posed_draw.map(|(draw, _)| draw));
        draws
            .displaced
            .push(displacement.map(|displacement| (displacement.map, posed_groups)));
        let mask_group = posed_groups + u32::from(displacement.is_some());
        draws
            .masked
            .push(mask.map(|(_, maps, _)| (maps, mask_group)));
        draws.instances.push(CasterInstance {
            clip_from_local: instance.clip_from_local.to_cols_array(),
            deform: posed_draw.map_or([0; 4], |(draw, _)| draw.deform),
            displacement: displacement.map_or([0.0; 8], |d| d.instance_data()),
            mask: mask.map_or([0.0; 8], |(.., data)| data),
        });
    }
    if !draws.instances.is_empty() {
        draws.instances.write_buffer(&device, &queue);
    }
}

/// Whether the mesh `id` (of vertex buffer `layout`) keeps its vertices compressed (Bevy
/// 0.20's `Mesh::with_compressed_*`): the caster reads full-precision attributes, so such a
/// mesh casts no shadow in the crate's maps, with a warning once per mesh.
fn is_compressed(
    layout: &MeshVertexBufferLayoutRef,
    id: AssetId<Mesh>,
    warned: &mut HashSet<AssetId<Mesh>>,
) -> bool {
    let compressed = !layout.0.get_attribute_compression().is_empty();
    if compressed && warned.insert(id) {
        warn!(
            "mesh {id:?} stores compressed vertex attributes: bevy_phong's shadow maps leave it \
             out (it casts no shadow from Phong lights); keep the mesh uncompressed to cast"
        );
    }
    compressed
}

/// Draws every shadow map of the frame: each pass clears its layer, then draws its casters.
#[allow(clippy::too_many_arguments)]
pub(crate) fn render_shadow_maps(
    frame: Option<Res<ShadowFrame>>,
    atlas: Res<ShadowAtlas>,
    draws: Res<ShadowDraws>,
    posed_groups: Res<PosedBindGroups>,
    displaced_groups: Res<DisplacedBindGroups>,
    masked_groups: Res<MaskedBindGroups>,
    pipeline_layouts: Res<ShadowCasterPipeline>,
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
            let offset = index as u64 * INSTANCE_SIZE;
            let mesh_id = match frame.instances[index].source {
                CasterSource::Mesh(mesh) | CasterSource::Posed { mesh, .. } => mesh,
            };
            let (Some(mesh), Some(vertices)) =
                (meshes.get(mesh_id), allocator.mesh_vertex_slice(&mesh_id))
            else {
                continue;
            };
            render_pass.set_render_pipeline(pipeline);
            if let Some(draw) = &draws.posed[index] {
                let Some(joints) = &posed_groups.joints else {
                    continue;
                };
                let uniform = pipeline_layouts.posed_layouts.uniform;
                let dynamic = |offset: u32| if uniform { vec![offset] } else { Vec::new() };
                render_pass.set_bind_group(0, joints, &dynamic(draw.joints_offset));
                if let Some((key, weights_offset)) = draw.morph {
                    let Some(morphs) = posed_groups.morphs.get(&key) else {
                        continue;
                    };
                    render_pass.set_bind_group(1, morphs, &dynamic(weights_offset));
                }
            }
            if let Some((map, group)) = draws.displaced[index] {
                // A map not on the GPU yet: the caster is drawn from the next frame on.
                let Some(bind_group) = displaced_groups.0.get(&map) else {
                    continue;
                };
                render_pass.set_bind_group(group as usize, bind_group, &[]);
            }
            if let Some((maps, group)) = draws.masked[index] {
                // Maps not on the GPU yet: the caster is drawn from the next frame on.
                let Some(bind_group) = masked_groups.0.get(&maps) else {
                    continue;
                };
                render_pass.set_bind_group(group as usize, bind_group, &[]);
            }
            render_pass.set_vertex_buffer(0, vertices.buffer.slice(..));
            render_pass.set_vertex_buffer(1, instance_buffer.slice(offset..offset + INSTANCE_SIZE));
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
