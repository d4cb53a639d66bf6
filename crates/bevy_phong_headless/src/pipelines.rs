//! Whether the render pipelines a frame needs have compiled.

use bevy::{
    app::App,
    asset::AssetId,
    render::{
        RenderApp,
        render_resource::{CachedPipeline, CachedPipelineState, PipelineCache, PipelineDescriptor},
    },
    shader::{Shader, ShaderCacheError},
};
use std::time::{Duration, Instant};

/// Frames in a row without a pipeline compiling after which [`run_until_settled`] stops:
/// a material whose data arrives a frame late queues its pipeline a frame late.
const SETTLED_FRAMES: u32 = 3;

/// How long a frame waits, while a pipeline compiles, before the next one: Bevy compiles
/// pipelines on its task pool, and a scene whose frames take a millisecond would otherwise
/// spin through frames on the cores the compiler needs.
const COMPILING_PAUSE: Duration = Duration::from_millis(5);

/// How long [`run_until_settled`] waits while no pipeline finishes compiling: a compile on
/// lavapipe takes seconds, one cold at most tens of them, so pipelines that stay unfinished
/// for this long are waiting for a shader that will not load (its file not found) and go
/// through Bevy's queue again and again.
const NO_PROGRESS_TIMEOUT: Duration = Duration::from_secs(120);

/// Runs `frame` on `app` until no pipeline has been compiling for three frames in a row;
/// `false` if that did not happen within `timeout`, or if no pipeline finished compiling for
/// [`NO_PROGRESS_TIMEOUT`] ([`unfinished_pipelines`] then names those left). The
/// bound is time, not frames: a shader variant compiled cold on a software rasterizer takes
/// seconds, however quick the scene's frames are.
pub fn run_until_settled(
    app: &mut App,
    timeout: Duration,
    mut frame: impl FnMut(&mut App),
) -> bool {
    let start = Instant::now();
    let mut ready_frames = 0;
    let (mut compiled, mut last_progress) = (0, start);
    while start.elapsed() < timeout {
        frame(app);
        let cache = app.sub_app(RenderApp).world().resource::<PipelineCache>();
        let now_compiled = cache
            .pipelines()
            .filter(|pipeline| matches!(pipeline.state, CachedPipelineState::Ok(_)))
            .count();
        if now_compiled != compiled {
            (compiled, last_progress) = (now_compiled, Instant::now());
        }
        if pipelines_compiling(cache) {
            ready_frames = 0;
            if last_progress.elapsed() > NO_PROGRESS_TIMEOUT {
                return false;
            }
            std::thread::sleep(COMPILING_PAUSE);
        } else {
            ready_frames += 1;
        }
        if ready_frames >= SETTLED_FRAMES {
            return true;
        }
    }
    false
}

/// The labels of the pipelines still on their way to compiling (see
/// [`pipelines_compiling`]): what [`run_until_settled`] left unfinished.
pub fn unfinished_pipelines(cache: &PipelineCache) -> Vec<String> {
    unfinished(cache)
        .map(|pipeline| format!("{:?}", pipeline.and_then(|p| label(&p.descriptor))))
        .collect()
}

/// Whether some pipeline is still on its way to compiling.
///
/// A pipeline queued without a shader (its handle the default one) never compiles and is
/// not counted. Bevy (0.19 and 0.20) queues one under WebGL2 limits: its sparse buffer update
/// pipeline, whose compute shader it does not load where storage buffers are missing
/// (`bevy_render::render_resource::sparse_buffer_vec`).
pub fn pipelines_compiling(cache: &PipelineCache) -> bool {
    unfinished(cache).next().is_some()
}

/// The pipelines waiting to compile, those without a shader left out (see
/// [`pipelines_compiling`]); `None` for one the cache lists as waiting but does not hold.
fn unfinished(cache: &PipelineCache) -> impl Iterator<Item = Option<&CachedPipeline>> {
    let pipelines: Vec<&CachedPipeline> = cache.pipelines().collect();
    cache
        .waiting_pipelines()
        .map(move |id| pipelines.get(id).copied())
        .filter(|pipeline| pipeline.is_none_or(|pipeline| has_shader(&pipeline.descriptor)))
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
