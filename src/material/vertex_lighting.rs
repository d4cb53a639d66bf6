//! Lighting per vertex ([`PhongMaterial::vertex_lighting`](super::PhongMaterial), SPEC.md,
//! "Per-vertex lighting"): a material lit so draws its main pass with the crate's vertex
//! shader (`phong_vertex.wesl`), which sums the lights at each vertex
//! (`bevy_phong::shaders::per_vertex`) with the same shader defs as the fragment stage. The
//! prepasses and shadow casters keep their vertex stages: they light nothing.

use crate::displacement::{PHONG_VERTEX_SHADER, is_prepass};
use bevy::render::render_resource::RenderPipelineDescriptor;

/// Makes `descriptor` (a material's main pass or prepass pipeline) light at the vertices where
/// it is the main pass: the crate's vertex shader, given the material's shader defs `defs`
/// (those of its fragment stage, `PHONG_PER_VERTEX` among them).
pub(crate) fn light_at_vertices(descriptor: &mut RenderPipelineDescriptor, defs: &[&'static str]) {
    if is_prepass(descriptor) {
        return;
    }
    descriptor.vertex.shader = PHONG_VERTEX_SHADER;
    descriptor
        .vertex
        .shader_defs
        .extend(defs.iter().map(|&def| def.into()));
}
