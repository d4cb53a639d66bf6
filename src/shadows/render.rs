//! The render world's part of the shadows: each caster's draw of the frame (its pipeline,
//! pose, maps and instance data) and the pass that draws every map before the cameras
//! render.

use super::{
    atlas::ShadowAtlas,
    caster_pipeline::{
        CasterInstance, INSTANCE_SIZE, MaskKey, ShadowCasterKey, ShadowCasterPipeline,
    },
    displaced::DisplacedBindGroups,
    gather::ShadowFrame,
    instance::{CasterSource, ShadowInstance},
    masked::{CasterMask, MaskMaps, MaskedBindGroups},
    posed::{BevyDeformation, PosedBindGroups, PosedCaster, PosedDraw, PosedLayouts},
};
use crate::displacement::can_displace;
use crate::storage_buffer::needs_scene_texture;
use bevy::{
    asset::AssetId,
    ecs::{
        resource::Resource,
        system::{Commands, Local, Res, ResMut, SystemParam},
    },
    image::Image,
    log::{error, warn},
    mesh::{Mesh, MeshVertexBufferLayoutRef, PrimitiveTopology},
    platform::collections::HashSet,
    render::{
        Extract,
        mesh::{RenderMesh, RenderMeshBufferInfo, allocator::MeshAllocator},
        render_asset::RenderAssets,
        render_phase::TrackedRenderPass,
        render_resource::{
            Buffer, BufferUsages, CachedRenderPipelineId, LoadOp, Operations, PipelineCache,
            RawBufferVec, RenderPassDepthStencilAttachment, RenderPassDescriptor,
            SpecializedMeshPipelines, StoreOp, TextureView,
        },
        renderer::{RenderContext, RenderDevice, RenderQueue},
        sync_world::MainEntity,
    },
};

/// Copies the main world's [`ShadowFrame`] into the render world.
pub(crate) fn extract_shadow_frame(mut commands: Commands, frame: Extract<Res<ShadowFrame>>) {
    commands.insert_resource(frame.clone());
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

/// One caster's draw, as [`ShadowDraws`] keeps it.
struct CasterDraw {
    pipeline: Option<CachedRenderPipelineId>,
    posed: Option<PosedDraw>,
    displaced: Option<(AssetId<Image>, u32)>,
    masked: Option<(MaskMaps, u32)>,
    instance: CasterInstance,
}

impl ShadowDraws {
    fn clear(&mut self) {
        self.pipelines.clear();
        self.posed.clear();
        self.displaced.clear();
        self.masked.clear();
        self.instances.clear();
    }

    fn push(&mut self, draw: CasterDraw) {
        self.pipelines.push(draw.pipeline);
        self.posed.push(draw.posed);
        self.displaced.push(draw.displaced);
        self.masked.push(draw.masked);
        self.instances.push(draw.instance);
    }
}

/// The meshes as the render world holds them: their vertex layouts, and where their
/// vertices and indices are.
#[derive(SystemParam)]
pub(crate) struct CasterMeshes<'w> {
    meshes: Res<'w, RenderAssets<RenderMesh>>,
    allocator: Res<'w, MeshAllocator>,
}

/// The caster pipeline and its variants, each compiled the first time it is asked for.
#[derive(SystemParam)]
pub(crate) struct CasterPipelines<'w> {
    pipeline: Res<'w, ShadowCasterPipeline>,
    specialized: ResMut<'w, SpecializedMeshPipelines<ShadowCasterPipeline>>,
    cache: Res<'w, PipelineCache>,
}

impl CasterPipelines<'_> {
    /// The pipeline of variant `key` for a mesh of vertex buffer `layout`; `None` (with an
    /// error) where it cannot be made.
    fn specialize(
        &mut self,
        key: ShadowCasterKey,
        layout: &MeshVertexBufferLayoutRef,
    ) -> Option<CachedRenderPipelineId> {
        match self
            .specialized
            .specialize(&self.cache, &self.pipeline, key, layout)
        {
            Ok(id) => Some(id),
            Err(err) => {
                error!("cannot draw a shadow caster: {err}");
                None
            }
        }
    }
}

/// Finds each caster's pipeline (compiling it the first time its vertex layout is seen) and
/// uploads the frame's instance data.
pub(crate) fn prepare_shadow_draws(
    frame: Option<Res<ShadowFrame>>,
    meshes: CasterMeshes,
    deformation: BevyDeformation,
    mut pipelines: CasterPipelines,
    mut draws: ResMut<ShadowDraws>,
    (device, queue): (Res<RenderDevice>, Res<RenderQueue>),
    mut warned_compressed: Local<HashSet<AssetId<Mesh>>>,
) {
    draws.clear();
    let Some(frame) = frame else { return };
    // The alpha map is bound where the main pass binds it (not under WebGL2's limits).
    let alpha_map_bound = !needs_scene_texture(&device);
    for instance in &frame.instances {
        let mesh = caster_mesh(instance, &meshes, &mut warned_compressed);
        let layouts = &pipelines.pipeline.posed_layouts;
        let posed_draw =
            mesh.and_then(|mesh| posed_draw(instance, mesh, &meshes, &deformation, layouts));
        draws.push(caster_draw(
            instance,
            mesh.map(|(_, mesh)| mesh),
            posed_draw,
            &mut pipelines,
            alpha_map_bound,
        ));
    }
    if !draws.instances.is_empty() {
        draws.instances.write_buffer(&device, &queue);
    }
}

/// The mesh `instance` draws, if it is loaded and made of triangles, with its id.
fn caster_mesh<'a>(
    instance: &ShadowInstance,
    meshes: &'a CasterMeshes,
    warned_compressed: &mut HashSet<AssetId<Mesh>>,
) -> Option<(AssetId<Mesh>, &'a RenderMesh)> {
    let id = match instance.source {
        CasterSource::Mesh(mesh) | CasterSource::Posed { mesh, .. } => mesh,
    };
    let mesh = meshes.meshes.get(id)?;
    let triangles = matches!(
        mesh.primitive_topology(),
        PrimitiveTopology::TriangleList | PrimitiveTopology::TriangleStrip
    );
    (triangles && !is_compressed(&mesh.layout, id, warned_compressed)).then_some((id, mesh))
}

/// Where a posed caster's deformation is this frame and what poses it (joints, morph
/// targets); `None` for a caster that is not posed, or whose deformation Bevy has not
/// prepared.
fn posed_draw(
    instance: &ShadowInstance,
    (id, mesh): (AssetId<Mesh>, &RenderMesh),
    meshes: &CasterMeshes,
    deformation: &BevyDeformation,
    layouts: &PosedLayouts,
) -> Option<(PosedDraw, (bool, bool))> {
    let CasterSource::Posed {
        entity, skinned, ..
    } = instance.source
    else {
        return None;
    };
    let caster = PosedCaster {
        entity: MainEntity::from(entity),
        mesh: id,
        first_vertex: meshes.allocator.mesh_vertex_slice(&id)?.range.start,
        skinned,
        morphed: mesh.has_morph_targets(),
    };
    let draw = deformation.draw(caster, layouts, &meshes.allocator)?;
    Some((draw, (caster.skinned, caster.morphed)))
}

/// The draw of `instance` with its `mesh` (if loaded) and, for a posed caster, where its
/// deformation is and what poses it (`None` where Bevy has not prepared it: not drawn).
fn caster_draw(
    instance: &ShadowInstance,
    mesh: Option<&RenderMesh>,
    posed_draw: Option<(PosedDraw, (bool, bool))>,
    pipelines: &mut CasterPipelines,
    alpha_map_bound: bool,
) -> CasterDraw {
    let is_posed = matches!(instance.source, CasterSource::Posed { .. });
    // A displacement moves the vertices of a mesh that has its UV set and normals.
    let displacement = instance.displacement.as_ref().filter(|displacement| {
        mesh.is_some_and(|mesh| can_displace(&mesh.layout, displacement.second_uvs))
    });
    let mask = instance
        .mask
        .as_ref()
        .zip(mesh)
        .map(|(mask, mesh)| mask_variant(mask, mesh, alpha_map_bound));
    let key = |posed| ShadowCasterKey {
        topology: mesh.map_or(PrimitiveTopology::TriangleList, |m| m.primitive_topology()),
        posed,
        displaced: displacement.map(|displacement| displacement.second_uvs),
        mask: mask.map(|(key, ..)| key),
    };
    let pipeline = match (mesh, is_posed, posed_draw) {
        (Some(mesh), false, _) => pipelines.specialize(key(None), &mesh.layout),
        (Some(mesh), true, Some((_, variant))) => {
            pipelines.specialize(key(Some(variant)), &mesh.layout)
        }
        _ => None,
    };
    let posed_groups = match posed_draw {
        Some((_, (_, true))) => 2,
        Some(_) => 1,
        None => 0,
    };
    let mask_group = posed_groups + u32::from(displacement.is_some());
    CasterDraw {
        pipeline,
        posed: posed_draw.map(|(draw, _)| draw),
        displaced: displacement.map(|displacement| (displacement.map, posed_groups)),
        masked: mask.map(|(_, maps, _)| (maps, mask_group)),
        instance: CasterInstance {
            clip_from_local: instance.clip_from_local.to_cols_array(),
            deform: posed_draw.map_or([0; 4], |(draw, _)| draw.deform),
            displacement: displacement.map_or([0.0; 8], |d| d.instance_data()),
            mask: mask.map_or([0.0; 8], |(.., data)| data),
        },
    }
}

/// A masked caster's variant, maps and instance data on `mesh`: its maps are read where the
/// mesh has their UV sets, as the main pass reads them.
fn mask_variant(
    mask: &CasterMask,
    mesh: &RenderMesh,
    alpha_map_bound: bool,
) -> (MaskKey, MaskMaps, [f32; 8]) {
    let has = |attribute| mesh.layout.0.contains(attribute);
    let has_uvs = (has(Mesh::ATTRIBUTE_UV_0), has(Mesh::ATTRIBUTE_UV_1));
    let maps = mask.maps(alpha_map_bound, has_uvs);
    let key = MaskKey {
        base_color_texture: maps.0.map(|_| mask.base_color_second_uvs),
        alpha_map: maps.1.map(|_| mask.alpha_map_second_uvs),
        vertex_colors: has(Mesh::ATTRIBUTE_COLOR),
    };
    (key, maps, mask.instance_data())
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

/// The bind groups of the frame's posed, displaced and masked casters.
#[derive(SystemParam)]
pub(crate) struct CasterBindGroups<'w> {
    posed: Res<'w, PosedBindGroups>,
    displaced: Res<'w, DisplacedBindGroups>,
    masked: Res<'w, MaskedBindGroups>,
}

/// Draws every shadow map of the frame: each pass clears its layer, then draws its casters.
pub(crate) fn render_shadow_maps(
    frame: Option<Res<ShadowFrame>>,
    atlas: Res<ShadowAtlas>,
    draws: Res<ShadowDraws>,
    groups: CasterBindGroups,
    (pipeline, cache): (Res<ShadowCasterPipeline>, Res<PipelineCache>),
    meshes: CasterMeshes,
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
        let drawer = CasterDrawer {
            frame: &frame,
            draws: &draws,
            groups: &groups,
            uniform_deformation: pipeline.posed_layouts.uniform,
            cache: &cache,
            meshes: &meshes,
            instance_buffer,
        };
        for index in pass.instances.clone() {
            drawer.draw(&mut render_pass, index);
        }
    }
}

/// What drawing one caster of the frame reads.
struct CasterDrawer<'a> {
    frame: &'a ShadowFrame,
    draws: &'a ShadowDraws,
    groups: &'a CasterBindGroups<'a>,
    /// Whether posed casters' deformation is in uniform buffers (bound at dynamic offsets).
    uniform_deformation: bool,
    cache: &'a PipelineCache,
    meshes: &'a CasterMeshes<'a>,
    instance_buffer: &'a Buffer,
}

impl<'a> CasterDrawer<'a> {
    /// Draws caster `index` of the frame; `None` (nothing drawn) where its pipeline, mesh or
    /// bind groups are not ready yet.
    fn draw(&self, render_pass: &mut TrackedRenderPass<'a>, index: usize) -> Option<()> {
        let pipeline =
            self.draws.pipelines[index].and_then(|id| self.cache.get_render_pipeline(id))?;
        let mesh_id = match self.frame.instances[index].source {
            CasterSource::Mesh(mesh) | CasterSource::Posed { mesh, .. } => mesh,
        };
        let mesh = self.meshes.meshes.get(mesh_id)?;
        let vertices = self.meshes.allocator.mesh_vertex_slice(&mesh_id)?;
        render_pass.set_render_pipeline(pipeline);
        self.set_bind_groups(render_pass, index)?;
        let offset = index as u64 * INSTANCE_SIZE;
        render_pass.set_vertex_buffer(0, vertices.buffer.slice(..));
        render_pass.set_vertex_buffer(
            1,
            self.instance_buffer.slice(offset..offset + INSTANCE_SIZE),
        );
        match &mesh.buffer_info {
            RenderMeshBufferInfo::Indexed {
                count,
                index_format,
            } => {
                let indices = self.meshes.allocator.mesh_index_slice(&mesh_id)?;
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
        Some(())
    }

    /// Binds caster `index`'s pose, displacement map and mask maps where it has them;
    /// `None` where one is not on the GPU yet (the caster is drawn from a later frame on).
    fn set_bind_groups(&self, render_pass: &mut TrackedRenderPass<'a>, index: usize) -> Option<()> {
        if let Some(draw) = &self.draws.posed[index] {
            let joints = self.groups.posed.joints.as_ref()?;
            let dynamic = |offset: u32| {
                if self.uniform_deformation {
                    vec![offset]
                } else {
                    Vec::new()
                }
            };
            render_pass.set_bind_group(0, joints, &dynamic(draw.joints_offset));
            if let Some((key, weights_offset)) = draw.morph {
                let morphs = self.groups.posed.morphs.get(&key)?;
                render_pass.set_bind_group(1, morphs, &dynamic(weights_offset));
            }
        }
        if let Some((map, group)) = self.draws.displaced[index] {
            let bind_group = self.groups.displaced.0.get(&map)?;
            render_pass.set_bind_group(group as usize, bind_group, &[]);
        }
        if let Some((maps, group)) = self.draws.masked[index] {
            let bind_group = self.groups.masked.0.get(&maps)?;
            render_pass.set_bind_group(group as usize, bind_group, &[]);
        }
        Some(())
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
