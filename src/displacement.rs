//! Displacement maps: a mesh's vertices moved along their normals by a texture, in every pass
//! that draws the mesh (SPEC.md, "Displacement"). The uniform is made from a material in
//! `material` (`From<&PhongMaterial>`). A displaced material's pipelines run the
//! crate's vertex shaders (`phong_vertex.wesl`, `phong_prepass_vertex.wesl`), copies of
//! Bevy's with the displacement step; the others keep Bevy's own.

use bevy::{
    asset::{Handle, uuid_handle},
    log::warn,
    math::Mat3,
    mesh::{Mesh, MeshAttributeCompressionFlags, MeshVertexAttribute, MeshVertexBufferLayoutRef},
    reflect::Reflect,
    render::render_resource::{RenderPipelineDescriptor, ShaderType, SpecializedMeshPipelineError},
    shader::Shader,
};

/// The main pass's vertex shader of a displaced material or one lit per vertex, at a fixed
/// handle: a pipeline is specialized without the asset server, in every app of the process
/// (`PhongPlugin` inserts it).
pub(crate) const PHONG_VERTEX_SHADER: Handle<Shader> =
    uuid_handle!("ce73eaa7-033c-45da-97a1-26b4474aa77d");
/// The prepass's displaced vertex shader, as [`PHONG_VERTEX_SHADER`].
pub(crate) const PHONG_PREPASS_VERTEX_SHADER: Handle<Shader> =
    uuid_handle!("2f0b5dc0-ea15-4831-9e0c-cd9085647ac7");

/// The shader def of a displaced material's vertex stage.
pub(crate) const DISPLACEMENT_DEF: &str = "PHONG_DISPLACEMENT_MAP";

/// The shader def of a displaced material's vertex stage that reads the map at the mesh's
/// second UV set.
pub(crate) const DISPLACEMENT_UV_B_DEF: &str = "PHONG_DISPLACEMENT_UV_B";

/// A displacement as the vertex stage reads it (`PhongDisplacement` in
/// `bevy_phong::shaders::displacement`, binding 26).
#[derive(Clone, Copy, Debug, PartialEq, Reflect, ShaderType)]
pub struct DisplacementUniform {
    /// The UV transform applied before the map is read: the material's on the first UV set,
    /// the identity on the second (read as it is).
    pub uv_transform: Mat3,
    /// How far a texel of 1 moves a vertex, local units.
    pub scale: f32,
    /// Added to every vertex's distance, local units.
    pub bias: f32,
}

impl Default for DisplacementUniform {
    /// No transform, scale 1, bias 0 (`PhongMaterial`'s defaults).
    fn default() -> Self {
        Self {
            uv_transform: Mat3::IDENTITY,
            scale: 1.0,
            bias: 0.0,
        }
    }
}

/// The UV set a displacement map is read at.
fn uv_attribute(second_uvs: bool) -> MeshVertexAttribute {
    if second_uvs {
        Mesh::ATTRIBUTE_UV_1
    } else {
        Mesh::ATTRIBUTE_UV_0
    }
}

/// Whether a mesh of `layout` can be displaced by a map read at its second UV set
/// (`second_uvs`) or its first: the mesh has that set, and normals to move the vertices
/// along.
pub(crate) fn can_displace(layout: &MeshVertexBufferLayoutRef, second_uvs: bool) -> bool {
    layout.0.contains(uv_attribute(second_uvs)) && layout.0.contains(Mesh::ATTRIBUTE_NORMAL)
}

/// Bevy's prepass pipelines are labelled so (`bevy_pbr::prepass`); its main pass ones are not.
pub(crate) fn is_prepass(descriptor: &RenderPipelineDescriptor) -> bool {
    descriptor.label.as_deref() == Some("prepass_pipeline")
}

/// Makes `descriptor` (a material's main pass or prepass pipeline on a mesh of `layout`)
/// displace its vertices: the crate's vertex shader for that pass, with the mesh's normal
/// among the prepass's vertex attributes, the map read at the mesh's second UV set where
/// `second_uvs` says so. On a mesh without that UV set or normals the displacement is left
/// out, with a warning naming `material`.
pub(crate) fn displace(
    descriptor: &mut RenderPipelineDescriptor,
    layout: &MeshVertexBufferLayoutRef,
    material: &str,
    second_uvs: bool,
) -> Result<(), SpecializedMeshPipelineError> {
    if !can_displace(layout, second_uvs) {
        warn!(
            "{material}.displacement_map is ignored on a mesh without its UV set and normals \
             ({}, Mesh::ATTRIBUTE_NORMAL)",
            if second_uvs {
                "Mesh::ATTRIBUTE_UV_1"
            } else {
                "Mesh::ATTRIBUTE_UV_0"
            }
        );
        return Ok(());
    }
    let prepass = is_prepass(descriptor);
    descriptor.vertex.shader = if prepass {
        PHONG_PREPASS_VERTEX_SHADER
    } else {
        PHONG_VERTEX_SHADER
    };
    descriptor.vertex.shader_defs.push(DISPLACEMENT_DEF.into());
    if second_uvs {
        descriptor
            .vertex
            .shader_defs
            .push(DISPLACEMENT_UV_B_DEF.into());
    }
    let Some(buffer) = descriptor.vertex.buffers.first_mut() else {
        return Ok(());
    };
    if prepass && !buffer.attributes.iter().any(|a| a.shader_location == 3) {
        let normal = layout
            .0
            .get_layout(&[Mesh::ATTRIBUTE_NORMAL.at_shader_location(3)])?;
        buffer.attributes.extend(normal.attributes);
        // The normal as the mesh stores it: Bevy 0.20 may keep it compressed (octahedral),
        // as its own prepass says with the same def where it binds the normal itself.
        if layout
            .0
            .get_attribute_compression()
            .contains(MeshAttributeCompressionFlags::COMPRESS_NORMAL)
        {
            descriptor
                .vertex
                .shader_defs
                .push("VERTEX_NORMALS_COMPRESSED".into());
        }
    }
    Ok(())
}
