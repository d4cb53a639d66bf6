//! Whether the render pipelines a frame needs have compiled.

use bevy::{
    app::App,
    asset::AssetId,
    render::{
        RenderApp,
        render_resource::{CachedPipelineState, PipelineCache, PipelineDescriptor},
    },
    shader::{Shader, ShaderCacheError},
};

/// Frames in a row without a pipeline compiling after which [`run_until_settled`] stops:
/// a material whose data arrives a frame late queues its pipeline a frame late.
const SETTLED_FRAMES: u32 = 3;

/// Runs `frame` on `app` until no pipeline has been compiling for three frames in a row;
/// `false` if that did not happen within `max_frames`.
pub fn run_until_settled(app: &mut App, max_frames: u32, mut frame: impl FnMut(&mut App)) -> bool {
    let mut ready_frames = 0;
    for _ in 0..max_frames {
        frame(app);
        let cache = app.sub_app(RenderApp).world().resource::<PipelineCache>();
        ready_frames = if pipelines_compiling(cache) {
            0
        } else {
            ready_frames + 1
        };
        if ready_frames >= SETTLED_FRAMES {
            return true;
        }
    }
    false
}

/// Whether some pipeline is still on its way to compiling.
///
/// A pipeline queued without a shader (its handle the default one) never compiles and is
/// not counted. Bevy (0.19 and 0.20) queues one under WebGL2 limits: its sparse buffer update
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
        PipelineDescriptor::MeshPipelineDescriptor(mesh) => mesh.mesh.shader.id(),
    };
    shader != AssetId::<Shader>::default()
}

/// The pipelines that failed to compile, each with its label and error: a shader that does
/// not compose or validate in some variant. Bevy logs these and draws nothing with them.
/// Waiting for a shader or an import is not a failure.
pub fn failed_pipelines(cache: &PipelineCache) -> Vec<String> {
    cache
        .pipelines()
        .filter_map(|pipeline| match &pipeline.state {
            CachedPipelineState::Err(
                ShaderCacheError::ShaderNotLoaded(_)
                | ShaderCacheError::ShaderImportNotYetAvailable,
            ) => None,
            CachedPipelineState::Err(error) => {
                Some(format!("{:?}: {error}", label(&pipeline.descriptor)))
            }
            _ => None,
        })
        .collect()
}

/// Panics, naming `what` and every failed pipeline ([`failed_pipelines`]), when a pipeline of
/// `app`'s render world failed to compile: Bevy would draw nothing with it, so a test would
/// compare, or a benchmark time, an empty frame.
pub fn assert_no_failed_pipelines(app: &App, what: &str) {
    let cache = app.sub_app(RenderApp).world().resource::<PipelineCache>();
    let failed = failed_pipelines(cache);
    assert!(
        failed.is_empty(),
        "{what}: pipelines failed to compile: {failed:#?}"
    );
}

fn label(descriptor: &PipelineDescriptor) -> Option<String> {
    match descriptor {
        PipelineDescriptor::RenderPipelineDescriptor(render) => {
            render.label.as_ref().map(|label| label.to_string())
        }
        PipelineDescriptor::ComputePipelineDescriptor(compute) => {
            compute.label.as_ref().map(|label| label.to_string())
        }
        PipelineDescriptor::MeshPipelineDescriptor(mesh) => {
            mesh.label.as_ref().map(|label| label.to_string())
        }
    }
}
