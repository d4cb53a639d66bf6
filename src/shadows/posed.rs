//! Skinned and morphed casters posed on the GPU as the shadow maps draw them: by the joint
//! matrices and morph weights that Bevy prepared to draw the same meshes this frame
//! (`bevy_pbr`'s `SkinUniforms`, `MorphIndices` and `MorphUniforms`, and the morph targets
//! Bevy keeps per mesh), read by `shadow_caster.wesl` the way Bevy's mesh vertex stage reads
//! them. Nothing is posed or copied on the CPU.
//!
//! Where the device has storage buffers, the joints, the weights, the morph descriptors and
//! each slab of morph targets are bound whole, and each draw names its first joint and its
//! morph descriptor in an instance attribute. Under WebGL2's limits Bevy keeps them in
//! uniform buffers and a 3D texture per mesh instead: each draw then binds a window of the
//! joint and weight buffers at a dynamic offset, and its mesh's texture.
//!
//! A caster whose data Bevy has not prepared this frame (a skin whose joints are still
//! loading, an entity Bevy does not draw yet) is left out of the maps for that frame.

use bevy::{
    asset::AssetId,
    ecs::{
        resource::Resource,
        system::{Res, ResMut, SystemParam},
    },
    mesh::Mesh,
    pbr::{MorphIndices, MorphUniforms, SkinUniforms, skins_use_uniform_buffers},
    platform::collections::HashMap,
    render::{
        mesh::{
            allocator::{MeshAllocator, MeshSlabId},
            morph::RenderMorphTargetAllocator,
        },
        render_resource::{
            BindGroup, BindGroupEntry, BindGroupLayoutDescriptor, BindingResource, Buffer,
            BufferBinding, BufferSize, PipelineCache, ShaderStages, TextureSampleType,
            binding_types::{storage_buffer_read_only_sized, texture_3d, uniform_buffer_sized},
        },
        renderer::RenderDevice,
        settings::WgpuLimits,
        sync_world::MainEntity,
    },
    shader::ShaderDefVal,
};

/// The window of joint matrices a draw binds from a uniform buffer: 256 matrices (Bevy's
/// `MAX_JOINTS`), bytes.
const JOINT_WINDOW_BYTES: u64 = 256 * 64;
/// The window of morph weights a draw binds from a uniform buffer: 256 weights (Bevy's
/// `MAX_MORPH_WEIGHTS`), bytes.
const WEIGHT_WINDOW_BYTES: u64 = 256 * 4;

/// Which morph bind group a draw uses: the slab holding its mesh's targets (storage
/// buffers), or its mesh's target texture (uniform buffers).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum MorphGroupKey {
    Slab(MeshSlabId),
    Mesh(AssetId<Mesh>),
}

/// Where a posed caster's deformation is this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PosedDraw {
    /// The instance attribute the vertex shader reads: (first joint, morph descriptor,
    /// first vertex of the mesh in its vertex buffer, 0).
    pub deform: [u32; 4],
    /// Uniform buffers: the byte offset of the draw's window of joints (0 otherwise).
    pub joints_offset: u32,
    /// Morphed: its morph bind group and, with uniform buffers, the byte offset of its
    /// window of weights.
    pub morph: Option<(MorphGroupKey, u32)>,
}

/// The bind group layouts of the posed casters' data: the joints (group 0, bound for every
/// posed caster) and the morph data (group 1, for morphed ones).
#[derive(Clone)]
pub(crate) struct PosedLayouts {
    /// Whether the data is in uniform buffers (no storage buffers on the device).
    pub uniform: bool,
    pub joints: BindGroupLayoutDescriptor,
    pub morphs: BindGroupLayoutDescriptor,
}

impl PosedLayouts {
    pub fn new(limits: &WgpuLimits) -> Self {
        let uniform = skins_use_uniform_buffers(limits);
        let joints = if uniform {
            uniform_buffer_sized(true, BufferSize::new(JOINT_WINDOW_BYTES))
        } else {
            storage_buffer_read_only_sized(false, None)
        };
        let morphs = if uniform {
            vec![
                uniform_buffer_sized(true, BufferSize::new(WEIGHT_WINDOW_BYTES))
                    .build(0, ShaderStages::VERTEX),
                texture_3d(TextureSampleType::Float { filterable: false })
                    .build(1, ShaderStages::VERTEX),
            ]
        } else {
            (0..3)
                .map(|binding| {
                    storage_buffer_read_only_sized(false, None).build(binding, ShaderStages::VERTEX)
                })
                .collect()
        };
        Self {
            uniform,
            joints: BindGroupLayoutDescriptor::new(
                "phong_posed_caster_joints",
                &[joints.build(0, ShaderStages::VERTEX)],
            ),
            morphs: BindGroupLayoutDescriptor::new("phong_posed_caster_morphs", &morphs),
        }
    }

    /// The bind group layouts and shader defs of a caster's pipeline.
    pub fn pipeline_parts(
        &self,
        skinned: bool,
        morphed: bool,
    ) -> (Vec<BindGroupLayoutDescriptor>, Vec<ShaderDefVal>) {
        let mut layouts = vec![self.joints.clone()];
        let mut defs = vec![ShaderDefVal::from("POSED")];
        if skinned {
            defs.push("SKINNED".into());
        }
        if morphed {
            layouts.push(self.morphs.clone());
            defs.push("MORPHED".into());
        }
        if self.uniform {
            defs.push("DEFORMATION_IN_UNIFORMS".into());
        }
        (layouts, defs)
    }
}

/// A caster that Bevy poses: its entity, its mesh whose vertices start at `first_vertex` of
/// its vertex buffer, and whether joints, morph targets or both pose it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PosedCaster {
    pub entity: MainEntity,
    pub mesh: AssetId<Mesh>,
    pub first_vertex: u32,
    pub skinned: bool,
    pub morphed: bool,
}

/// What Bevy prepared for posing this frame. Absent in an app that does not draw meshes
/// with Bevy's mesh pipeline (no posed caster is drawn there).
#[derive(SystemParam)]
pub(crate) struct BevyDeformation<'w> {
    skins: Option<Res<'w, SkinUniforms>>,
    morph_indices: Option<Res<'w, MorphIndices>>,
    morph_uniforms: Option<Res<'w, MorphUniforms>>,
    morph_targets: Option<Res<'w, RenderMorphTargetAllocator>>,
}

impl BevyDeformation<'_> {
    /// Where `caster`'s deformation is this frame, in the pipeline whose bind groups are
    /// `layouts`; `None` where Bevy has not prepared what it needs.
    pub fn draw(
        &self,
        caster: PosedCaster,
        layouts: &PosedLayouts,
        allocator: &MeshAllocator,
    ) -> Option<PosedDraw> {
        let PosedCaster {
            entity,
            mesh,
            first_vertex,
            skinned,
            morphed,
        } = caster;
        let mut draw = PosedDraw {
            deform: [0, 0, first_vertex, 0],
            joints_offset: 0,
            morph: None,
        };
        let uniform = layouts.uniform;
        if skinned {
            let first_joint = self.skins.as_ref()?.skin_index(entity)?;
            if uniform {
                draw.joints_offset = first_joint * 64;
            } else {
                draw.deform[0] = first_joint;
            }
        }
        if morphed {
            draw.morph = Some(match self.morph_indices.as_deref()? {
                MorphIndices::Uniform { current, .. } => {
                    let weights = current.get(&entity)?.index;
                    (MorphGroupKey::Mesh(mesh), weights)
                }
                indices @ MorphIndices::Storage { .. } => {
                    draw.deform[1] = indices.morph_descriptor_index(entity)?.0;
                    let slab = allocator.mesh_slabs(&mesh)?.morph_target_slab_id?;
                    (MorphGroupKey::Slab(slab), 0)
                }
            });
        }
        Some(draw)
    }

    /// The joint bind group of this frame; `None` without skins.
    fn joint_group(
        &self,
        layouts: &PosedLayouts,
        device: &RenderDevice,
        cache: &PipelineCache,
    ) -> Option<BindGroup> {
        let joints = &self.skins.as_ref()?.current_buffer;
        Some(device.create_bind_group(
            "phong_posed_caster_joints",
            &cache.get_bind_group_layout(&layouts.joints),
            &[buffer_entry(
                0,
                joints,
                layouts.uniform.then_some(JOINT_WINDOW_BYTES),
            )],
        ))
    }

    /// The morph bind group `key` of this frame; `None` where Bevy has none of its data.
    fn morph_group(
        &self,
        key: MorphGroupKey,
        layouts: &PosedLayouts,
        device: &RenderDevice,
        cache: &PipelineCache,
        allocator: &MeshAllocator,
    ) -> Option<BindGroup> {
        let uniforms = self.morph_uniforms.as_ref()?;
        let weights = uniforms.current_buffer.buffer()?;
        let layout = cache.get_bind_group_layout(&layouts.morphs);
        let group = match key {
            MorphGroupKey::Mesh(mesh) => {
                let RenderMorphTargetAllocator::Image { mesh_id_to_image } =
                    self.morph_targets.as_deref()?
                else {
                    return None;
                };
                let image = mesh_id_to_image.get(&mesh)?;
                device.create_bind_group(
                    "phong_posed_caster_morphs",
                    &layout,
                    &[
                        buffer_entry(0, weights, Some(WEIGHT_WINDOW_BYTES)),
                        BindGroupEntry {
                            binding: 1,
                            resource: BindingResource::TextureView(&image.texture_view),
                        },
                    ],
                )
            }
            MorphGroupKey::Slab(slab) => {
                let targets = allocator.buffer_for_slab(slab)?;
                let descriptors = uniforms.descriptors_buffer.as_ref()?.buffer()?;
                device.create_bind_group(
                    "phong_posed_caster_morphs",
                    &layout,
                    &[
                        buffer_entry(0, weights, None),
                        buffer_entry(1, targets, None),
                        buffer_entry(2, descriptors, None),
                    ],
                )
            }
        };
        Some(group)
    }
}

/// A buffer bound from its start: `window` bytes of it, or all of it.
fn buffer_entry(binding: u32, buffer: &Buffer, window: Option<u64>) -> BindGroupEntry<'_> {
    BindGroupEntry {
        binding,
        resource: BindingResource::Buffer(BufferBinding {
            buffer,
            offset: 0,
            size: window.and_then(BufferSize::new),
        }),
    }
}

/// The bind groups the posed casters of this frame's maps use, made anew every frame: Bevy
/// swaps and regrows its buffers from frame to frame.
#[derive(Resource, Default)]
pub(crate) struct PosedBindGroups {
    pub joints: Option<BindGroup>,
    pub morphs: HashMap<MorphGroupKey, BindGroup>,
}

/// Makes the bind groups of the posed casters of [`super::ShadowDraws`], once Bevy has
/// written this frame's joints and weights.
pub(crate) fn prepare_posed_bind_groups(
    draws: Res<super::ShadowDraws>,
    deformation: BevyDeformation,
    pipeline: Res<super::ShadowCasterPipeline>,
    device: Res<RenderDevice>,
    cache: Res<PipelineCache>,
    allocator: Res<MeshAllocator>,
    mut groups: ResMut<PosedBindGroups>,
) {
    groups.joints = None;
    groups.morphs.clear();
    let mut posed = draws.posed().peekable();
    if posed.peek().is_none() {
        return;
    }
    let layouts = &pipeline.posed_layouts;
    groups.joints = deformation.joint_group(layouts, &device, &cache);
    for draw in posed {
        let Some((key, _)) = draw.morph else { continue };
        if groups.morphs.contains_key(&key) {
            continue;
        }
        if let Some(group) = deformation.morph_group(key, layouts, &device, &cache, &allocator) {
            groups.morphs.insert(key, group);
        }
    }
}
