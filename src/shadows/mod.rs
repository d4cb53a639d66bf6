//! Shadow maps: which lights cast shadows, where their maps look from, how they are drawn,
//! and how a surface reads them (SPEC.md, "Shadows").
//!
//! ```text
//!  main world (PostUpdate, PhongSystems::GatherLights)
//!  ──────────────────────────────────────────────────
//!  lights with shadows on ──request──▶ ShadowRequests
//!  (built-in kinds, extension kinds)        │
//!  cameras, casters (Mesh3d + Aabb,         ▼
//!  no NotShadowCaster) ─────────────▶ gather_shadows ──▶ ShadowSlots: first view per light
//!                                           │               │ (into the light records)
//!                                           │               ▼
//!                                           │         gather_lights / extension gathers
//!                                           ├──▶ shadow view buffer (one record per map)
//!                                           ▼
//!                                     ShadowFrame: layers, passes, casters per pass
//!  render world                             │ extract
//!  ────────────                             ▼
//!  PrepareAssets:     prepare_shadow_atlas (the Depth32Float array, resized as needed)
//!  PrepareResources:  prepare_shadow_draws (pipelines per vertex layout, instance matrices)
//!  RenderGraph:       render_shadow_maps (one depth pass per map, before any camera)
//!  materials:         PhongSceneBindings binds the view buffer, the array and a comparison
//!                     sampler beside the lights; the shader's `light_visibility` reads them
//! ```
//!
//! Only visible lights with [`PhongShadows::enabled`](crate::PhongShadows) get maps, and of
//! point and spot lights only those whose range meets some active 3D camera's view. A
//! directional light gets one set of cascades per camera (per distinct frustum), fitted to
//! that camera's view; each set's views carry the camera's view key, by which the fragment
//! shader finds the set of the view it draws (as it finds its light clusters), falling back
//! to the first set for a view that appeared after the gather. A frame has at most
//! [`MAX_SHADOW_VIEWS`] maps: directional lights first, then the others nearest to a camera
//! first; past it the rest cast nothing, with one warning.
//!
//! Casters are the visible meshes without `NotShadowCaster`, culled per map by their
//! bounding spheres. They are drawn from their vertex positions as stored, except skinned
//! and morphed meshes (`SkinnedMesh`, `MeshMorphWeights`), which the maps pose on the GPU
//! with the joint matrices and morph weights Bevy prepared to draw them this frame
//! (`posed`); the gather only bounds their pose, in `O(joints)` (`deformed`). A deformed
//! mesh whose vertex data is not in the main world (its bounds need it), or whose skin
//! names a joint without a transform, casts nothing, with one warning naming it; one whose
//! mesh or inverse bind matrices are still loading casts once they are, and one Bevy has not
//! prepared this frame casts from the next. A mesh without bounds (`Aabb`, absent under
//! `NoFrustumCulling`) casts only if it is skinned or morphed.

mod atlas;
mod cameras;
mod caster_bind_groups;
mod caster_pipeline;
mod casters;
mod deformed;
mod displaced;
mod gather;
mod gpu_types;
mod instance;
mod masked;
mod posed;
mod render;
mod request;
mod views;

pub(crate) use atlas::{ShadowAtlas, prepare_shadow_atlas};
pub use cameras::PhongLit;
pub(crate) use caster_pipeline::ShadowCasterPipeline;
pub(crate) use gather::{PHONG_SHADOW_VIEW_BUFFER, ShadowFrame, gather_shadows};
pub use gather::{PhongShadowViews, ShadowSlots};
/// For [`crate::testing`].
#[cfg(feature = "testing")]
pub use gpu_types::{GpuShadowView, GpuShadowViewsHeader};
pub(crate) use render::{
    ShadowDraws, extract_shadow_frame, prepare_shadow_draws, render_shadow_maps,
};
pub(crate) use request::ShadowRequests;
pub use request::{PhongShadowProjection, PhongShadowRequest};

/// Most shadow maps a frame holds (layers of the shadow map array, which WebGL2 caps at
/// 256): a directional light takes one per cascade, a point light six, a spot light one
/// (six past a 60° cone).
pub const MAX_SHADOW_VIEWS: usize = 256;

use crate::{scene_variants::SceneVariants, schedule::PhongSystems};
use bevy::{
    app::{App, PostUpdate},
    camera::visibility::{
        InheritedVisibility, SetViewVisibility, ViewVisibility, VisibilitySystems,
    },
    core_pipeline::schedule::camera_driver,
    ecs::{
        query::{Or, With, Without},
        schedule::IntoScheduleConfigs,
        system::{Query, Res},
    },
    light::NotShadowCaster,
    mesh::{Mesh3d, morph::MeshMorphWeights, skinning::SkinnedMesh},
    render::{
        ExtractSchedule, GpuResourceAppExt, Render, RenderApp, RenderSystems,
        render_resource::SpecializedMeshPipelines,
        renderer::{RenderGraph, RenderGraphSystems},
    },
};

/// The main world's part: the requests of the built-in lights and the gather.
pub(crate) fn add_shadow_gather(app: &mut App) {
    app.init_resource::<ShadowRequests>()
        .init_resource::<ShadowSlots>()
        .init_resource::<ShadowFrame>()
        .init_resource::<PhongShadowViews>()
        .add_systems(
            PostUpdate,
            (
                gather_shadows.in_set(PhongSystems::GatherShadows),
                keep_posed_casters_prepared
                    .run_if(|variants: Res<SceneVariants>| variants.shadows)
                    .after(VisibilitySystems::CheckVisibility)
                    .before(VisibilitySystems::MarkNewlyHiddenEntitiesInvisible),
            ),
        );
}

/// The skinned and morphed meshes that cast shadows.
type PosedCaster = (
    With<Mesh3d>,
    Or<(With<SkinnedMesh>, With<MeshMorphWeights>)>,
    Without<NotShadowCaster>,
);

/// Marks the visible skinned and morphed meshes that cast shadows as seen, as Bevy's own
/// lights do for their shadow casters: Bevy then prepares their joints and weights this
/// frame, which the shadow maps pose them with, even where no camera sees them (no camera
/// draws them for it: cameras draw what they list as visible).
fn keep_posed_casters_prepared(
    mut casters: Query<(&InheritedVisibility, &mut ViewVisibility), PosedCaster>,
) {
    for (inherited, mut seen) in &mut casters {
        if inherited.get() {
            seen.set_visible();
        }
    }
}

/// The render world's part: the shadow map array, the caster pipeline and the pass.
pub(crate) fn add_shadow_rendering(app: &mut App) {
    let Some(render_app) = app.get_sub_app_mut(RenderApp) else {
        return;
    };
    render_app
        .init_gpu_resource::<ShadowAtlas>()
        .init_gpu_resource::<ShadowCasterPipeline>()
        .init_resource::<ShadowDraws>()
        .init_resource::<posed::PosedBindGroups>()
        .init_resource::<displaced::DisplacedBindGroups>()
        .init_resource::<masked::MaskedBindGroups>()
        .init_resource::<SpecializedMeshPipelines<ShadowCasterPipeline>>()
        .add_systems(ExtractSchedule, extract_shadow_frame)
        .add_systems(
            Render,
            (
                prepare_shadow_atlas.in_set(RenderSystems::PrepareAssets),
                prepare_shadow_draws.in_set(RenderSystems::PrepareResources),
                posed::prepare_posed_bind_groups.in_set(RenderSystems::PrepareBindGroups),
                displaced::prepare_displaced_bind_groups.in_set(RenderSystems::PrepareBindGroups),
                masked::prepare_masked_bind_groups.in_set(RenderSystems::PrepareBindGroups),
            ),
        )
        .add_systems(
            RenderGraph,
            render_shadow_maps
                .in_set(RenderGraphSystems::Render)
                .before(camera_driver),
        );
}
