//! Whether every render pipeline a frame needs has compiled, as the main world sees it.

use bevy::{
    prelude::*,
    render::{Render, RenderApp, RenderSystems, render_resource::PipelineCache},
};
use bevy_phong_headless::pipelines_compiling;
use std::sync::{
    Arc,
    atomic::{AtomicBool, Ordering},
};

/// Set by the render world after each frame when no pipeline is waiting to compile.
#[derive(Resource, Clone, Default)]
pub struct PipelinesReady(Arc<AtomicBool>);

impl PipelinesReady {
    /// Whether the last frame rendered had every pipeline it needs.
    pub fn get(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

/// Adds [`PipelinesReady`] to the main world, kept up to date by the render world.
pub struct PipelinesReadyPlugin;

impl Plugin for PipelinesReadyPlugin {
    fn build(&self, app: &mut App) {
        let ready = PipelinesReady::default();
        app.insert_resource(ready.clone());
        if let Some(render_app) = app.get_sub_app_mut(RenderApp) {
            render_app
                .insert_resource(ready)
                .add_systems(Render, report_pipelines.after(RenderSystems::Render));
        }
    }
}

fn report_pipelines(cache: Res<PipelineCache>, ready: Res<PipelinesReady>) {
    ready
        .0
        .store(!pipelines_compiling(&cache), Ordering::Relaxed);
}

/// Counts the frames drawn in a row with every pipeline ready.
#[derive(Default)]
pub struct ReadyFrames(u32);

impl ReadyFrames {
    /// Counts this frame; true once more than [`super::SETTLE_FRAMES`] frames in a row had
    /// every pipeline ready.
    pub fn settled(&mut self, ready: &PipelinesReady) -> bool {
        self.0 = if ready.get() { self.0 + 1 } else { 0 };
        self.0 > super::SETTLE_FRAMES
    }
}
