//! The cluster system: every frame, each active 3D camera's view, and the clusters of the
//! lights of finite reach in those views, rebuilt when a view or such a light changed.

use super::{
    PHONG_LIGHT_CLUSTER_BUFFER,
    clusters::{ClusterView, DepthSlices, LightClusters, keep_distinct_views},
    gather::PhongLightBuffer,
};
use crate::culling::PhongViewClusters;
use crate::storage_buffer::{LightBuffer, LightBufferResized};
use crate::view_key::view_key;
use bevy::{
    asset::Assets,
    camera::{Camera, Camera3d, Projection, primitives::Frustum},
    ecs::{
        change_detection::{DetectChanges, DetectChangesMut},
        message::MessageWriter,
        query::With,
        resource::Resource,
        system::{Local, Query, Res, ResMut},
    },
    log::warn,
    math::Mat4,
    render::storage::ShaderBuffer,
    transform::components::GlobalTransform,
};

/// The clusters of every view, and the buffer they are written into.
#[derive(Resource, Debug)]
pub struct PhongLightClusters {
    buffer: LightBuffer,
    clusters: LightClusters,
    views: Vec<ClusterView>,
}

impl Default for PhongLightClusters {
    fn default() -> Self {
        Self {
            buffer: LightBuffer::new(PHONG_LIGHT_CLUSTER_BUFFER),
            clusters: LightClusters::default(),
            views: Vec::new(),
        }
    }
}

impl PhongLightClusters {
    /// How many views have clusters (0 when no light is clustered).
    #[cfg(any(test, feature = "testing"))]
    pub fn view_count(&self) -> u32 {
        self.clusters.header().view_count
    }

    /// The cluster data last written (see `render::clusters` for its layout).
    #[cfg(any(test, feature = "testing"))]
    pub fn data(&self) -> &[u32] {
        self.clusters.data()
    }
}

/// The cameras whose views get clusters: active 3D cameras, with a frustum.
type CameraQuery<'w, 's> = Query<
    'w,
    's,
    (
        &'static Camera,
        &'static GlobalTransform,
        &'static Frustum,
        &'static Projection,
        Option<&'static PhongViewClusters>,
    ),
    With<Camera3d>,
>;

/// A camera's view as its clusters are built: its frustum's key, its transform and
/// unjittered projection as Bevy's view uniform gets them, and its cut.
fn cluster_view(
    camera: &Camera,
    transform: &GlobalTransform,
    frustum: &Frustum,
    projection: &Projection,
    cut: PhongViewClusters,
) -> ClusterView {
    let cut = cut.clamped();
    let slices = match projection {
        Projection::Perspective(perspective) => {
            DepthSlices::logarithmic(cut.slices, perspective.near, perspective.far)
        }
        Projection::Orthographic(orthographic) => {
            DepthSlices::linear(cut.slices, orthographic.near, orthographic.far)
        }
        Projection::Custom(_) => DepthSlices::ONE,
    };
    ClusterView {
        key: view_key(frustum),
        view_from_world: transform.to_matrix().inverse(),
        clip_from_view: clip_from_view(camera, projection),
        tiles: cut.tiles,
        slices,
    }
}

/// The camera's projection as Bevy extracts it (`Camera::clip_from_view`, which also
/// applies a sub-view), or its [`Projection`]'s where Bevy has not computed it yet (a camera
/// in its first frame, or an app without Bevy's camera systems).
fn clip_from_view(camera: &Camera, projection: &Projection) -> Mat4 {
    let computed = camera.clip_from_view();
    if computed == Mat4::ZERO {
        projection.get_clip_from_view()
    } else {
        computed
    }
}

/// Lists the clustered lights of [`PhongLightBuffer`] in the clusters of every active 3D
/// camera's view and writes them into the cluster buffer, when a light or a view changed
/// (and on the first run); otherwise it touches nothing, so no GPU buffer is uploaded.
///
/// Runs after the gather, in [`PhongSystems::GatherLights`](crate::PhongSystems), once
/// Bevy has updated the cameras' frusta.
pub fn assign_lights_to_clusters(
    lights: Res<PhongLightBuffer>,
    cameras: CameraQuery,
    mut state: ResMut<PhongLightClusters>,
    mut buffers: ResMut<Assets<ShaderBuffer>>,
    mut resized: MessageWriter<LightBufferResized>,
    mut collisions_said: Local<usize>,
) {
    let state = state.bypass_change_detection();
    let views = &mut state.views;
    views.clear();
    views.extend(cameras.iter().filter(|(camera, ..)| camera.is_active).map(
        |(camera, transform, frustum, projection, cut)| {
            cluster_view(
                camera,
                transform,
                frustum,
                projection,
                cut.copied().unwrap_or_default(),
            )
        },
    ));
    let collisions = keep_distinct_views(views);
    if collisions != *collisions_said {
        if collisions > 0 {
            warn!(
                "bevy_phong: {collisions} camera views have frusta whose keys collide; their \
                 fragments loop over every light of finite reach (exact, but slower)"
            );
        }
        *collisions_said = collisions;
    }

    // The lights' records are rewritten only in frames where a light changed: otherwise only
    // the views can have changed the clusters.
    let unchanged = !lights.is_changed()
        && state.clusters.was_built_for(&state.views)
        && state.buffer.capacity() > 0;
    if unchanged {
        return;
    }
    let header = lights.header();
    let first = (header.directional_count + header.point_count + header.spot_count) as usize;
    let spots = first + header.clustered_point_count as usize;
    let end = spots + header.clustered_spot_count as usize;
    let rebuilt = state
        .clusters
        .build(&state.views, lights.records(), first..spots, spots..end);
    if rebuilt || state.buffer.capacity() == 0 {
        let was_resized =
            state
                .buffer
                .write(&mut buffers, state.clusters.header(), state.clusters.data());
        if was_resized {
            resized.write(LightBufferResized);
        }
    }
}
