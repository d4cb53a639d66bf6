//! Whether the render pipelines a frame needs have compiled.

use bevy::{
    asset::AssetId,
    render::render_resource::{PipelineCache, PipelineDescriptor},
    shader::Shader,
};

/// Whether some pipeline is still on its way to compiling.
///
/// A pipeline queued without a shader (its handle the default one) never compiles and is
/// not counted. Bevy 0.19 queues one under WebGL2 limits: its sparse buffer update
/// pipeline, whose compute shader it does not load where storage buffers are missing
/// (`bevy_render::render_resource::sparse_buffer_vec`).
pub fn pipelines_compiling(cache: &PipelineCache) -> bool {
    let pipelines: Vec<_> = cache.pipelines().collect();
    cache.waiting_pipelines().any(|id| {
        pipelines
            .get(id)
            .is_none_or(|pipeline| has_shader(&pipeline.descriptor))
    })
}

/// Whether `descriptor` names a shader (rather than the default handle, which is never
/// loaded).
fn has_shader(descriptor: &PipelineDescriptor) -> bool {
    let shader = match descriptor {
        PipelineDescriptor::RenderPipelineDescriptor(render) => render.vertex.shader.id(),
        PipelineDescriptor::ComputePipelineDescriptor(compute) => compute.shader.id(),
    };
    shader != AssetId::<Shader>::default()
}
