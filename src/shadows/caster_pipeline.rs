//! The depth-only pipeline that draws a caster into a shadow map, and its variants: posed
//! by Bevy's joints and morph weights, moved by a displacement map, cut by an alpha mask.

use super::{displaced::displacement_layout, masked::mask_layout, posed::PosedLayouts};
use bevy::{
    asset::{AssetServer, Handle},
    ecs::{
        resource::Resource,
        world::{FromWorld, World},
    },
    mesh::{
        Mesh, MeshVertexBufferLayoutRef, PrimitiveTopology, VertexAttributeDescriptor,
        VertexBufferLayout,
    },
    prelude::default,
    render::{
        render_resource::{
            BindGroupLayoutDescriptor, CompareFunction, DepthBiasState, DepthStencilState,
            FragmentState, PrimitiveState, RenderPipelineDescriptor, SpecializedMeshPipeline,
            SpecializedMeshPipelineError, TextureFormat, VertexAttribute, VertexFormat,
            VertexState, VertexStepMode,
        },
        renderer::RenderDevice,
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
    pub topology: PrimitiveTopology,
    pub posed: Option<(bool, bool)>,
    /// A displaced caster's UV set: `Some(true)` the second.
    pub displaced: Option<bool>,
    pub mask: Option<MaskKey>,
}

/// What a masked caster's alpha is made of besides its base color's: the base color map's
/// alpha, the alpha map's green (each at the UV set it is read at: `Some(true)` the second)
/// and the vertex colors' alpha.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct MaskKey {
    pub base_color_texture: Option<bool>,
    pub alpha_map: Option<bool>,
    pub vertex_colors: bool,
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
    pub clip_from_local: [f32; 16],
    pub deform: [u32; 4],
    pub displacement: [f32; 8],
    pub mask: [f32; 8],
}

/// Bytes of a [`CasterInstance`].
pub(crate) const INSTANCE_SIZE: u64 = size_of::<CasterInstance>() as u64;

impl SpecializedMeshPipeline for ShadowCasterPipeline {
    type Key = ShadowCasterKey;

    fn specialize(
        &self,
        key: ShadowCasterKey,
        layout: &MeshVertexBufferLayoutRef,
    ) -> Result<RenderPipelineDescriptor, SpecializedMeshPipelineError> {
        let vertices = layout.0.get_layout(&key.vertex_attributes())?;
        let variant = self.variant(key);
        // Depth only: a masked caster's fragments are discarded where its mask is open.
        let fragment = key.mask.map(|_| FragmentState {
            shader: self.shader.clone(),
            shader_defs: variant.shader_defs.clone(),
            entry_point: Some("masked".into()),
            targets: Vec::new(),
            ..default()
        });
        let instance = VertexBufferLayout {
            array_stride: INSTANCE_SIZE,
            step_mode: VertexStepMode::Instance,
            attributes: variant.instance_attributes,
        };
        Ok(RenderPipelineDescriptor {
            label: Some("phong_shadow_caster".into()),
            layout: variant.bind_group_layouts,
            vertex: VertexState {
                shader: self.shader.clone(),
                shader_defs: variant.shader_defs,
                entry_point: Some("vertex".into()),
                buffers: vec![vertices, instance],
                ..default()
            },
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

impl ShadowCasterKey {
    /// The mesh's attributes the variant reads, at their shader locations: the positions,
    /// a skinned caster's joints, a displaced caster's normals, the UV sets a displacement
    /// or mask reads, and a masked caster's vertex colors.
    fn vertex_attributes(self) -> Vec<VertexAttributeDescriptor> {
        let (skinned, _) = self.posed.unwrap_or_default();
        let mut attributes = vec![Mesh::ATTRIBUTE_POSITION.at_shader_location(0)];
        if skinned {
            attributes.push(Mesh::ATTRIBUTE_JOINT_INDEX.at_shader_location(6));
            attributes.push(Mesh::ATTRIBUTE_JOINT_WEIGHT.at_shader_location(7));
        }
        if self.displaced.is_some() {
            attributes.push(Mesh::ATTRIBUTE_NORMAL.at_shader_location(8));
        }
        let reads_uvs = |second: bool| {
            self.displaced == Some(second) || self.mask.is_some_and(|mask| mask.reads_uvs(second))
        };
        if reads_uvs(false) {
            attributes.push(Mesh::ATTRIBUTE_UV_0.at_shader_location(9));
        }
        if reads_uvs(true) {
            attributes.push(Mesh::ATTRIBUTE_UV_1.at_shader_location(15));
        }
        if self.mask.is_some_and(|mask| mask.vertex_colors) {
            attributes.push(Mesh::ATTRIBUTE_COLOR.at_shader_location(14));
        }
        attributes
    }
}

/// What a caster variant reads besides its mesh: its instance's attributes (see
/// [`CasterInstance`]), its bind groups' layouts (a posed caster's, then a displaced
/// caster's, then a masked caster's) and its shader defs.
struct CasterVariant {
    instance_attributes: Vec<VertexAttribute>,
    bind_group_layouts: Vec<BindGroupLayoutDescriptor>,
    shader_defs: Vec<ShaderDefVal>,
}

impl ShadowCasterPipeline {
    /// The instance attributes, bind groups and defs of variant `key`.
    fn variant(&self, key: ShadowCasterKey) -> CasterVariant {
        // `count` attributes of `format` from `offset`, each 16 bytes, from `location`.
        let attributes = |format, offset: u64, location: u32, count: u32| {
            (0..count).map(move |i| VertexAttribute {
                format,
                offset: offset + 16 * u64::from(i),
                shader_location: location + i,
            })
        };
        let mut instance_attributes: Vec<VertexAttribute> =
            attributes(VertexFormat::Float32x4, 0, 1, 4).collect();
        let (mut bind_group_layouts, mut shader_defs) = match key.posed {
            Some((skinned, morphed)) => {
                instance_attributes.extend(attributes(VertexFormat::Uint32x4, 64, 5, 1));
                self.posed_layouts.pipeline_parts(skinned, morphed)
            }
            None => (Vec::new(), Vec::new()),
        };
        if let Some(second_uvs) = key.displaced {
            instance_attributes.extend(attributes(VertexFormat::Float32x4, 80, 10, 2));
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
        if let Some(mask) = key.mask {
            instance_attributes.extend(attributes(VertexFormat::Float32x4, 112, 12, 2));
            shader_defs.extend(mask.shader_defs());
            shader_defs.push(ShaderDefVal::UInt(
                "MASK_GROUP".into(),
                bind_group_layouts.len() as u32,
            ));
            bind_group_layouts.push(mask_layout());
        }
        CasterVariant {
            instance_attributes,
            bind_group_layouts,
            shader_defs,
        }
    }
}
