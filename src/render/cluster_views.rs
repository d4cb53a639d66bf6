//! The cluster system: every frame, each active 3D camera's view, and the clusters of the
//! lights of finite reach in those views, rebuilt when a view or such a light changed.

use super::light_sections::LightSection;
use super::{
    PHONG_LIGHT_CLUSTER_BUFFER,
    clusters::{
        ClusterSlot, ClusterView, DepthSlices, LightClusters, area_light_sphere_bits,
        keep_distinct_views, light_sphere_bits,
    },
    gather::PhongLightBuffer,
};
use crate::culling::PhongViewClusters;
use crate::light_kind::GpuAreaLight;
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
    /// The spheres of the clustered local lights, as the last build read them from the
    /// light buffer.
    local_spheres: Vec<[u32; 4]>,
    /// The spheres of the clustered area lights, the same way.
    area_spheres: Vec<[u32; 4]>,
}

/// The clustered lights of each extension kind ([`crate::extension::PhongLightKind`]), as
/// their gathers leave them: slot `2 + i` of the clusters is `slots[i]` (slot 0 is the
/// built-in local lights, point and spot; slot 1 the built-in area lights).
#[derive(Resource, Debug, Default)]
pub struct ExtensionClusterSlots {
    slots: Vec<ExtensionSlot>,
}

/// One extension kind's clustered lights: the index of the first in the kind's buffer (the
/// others follow it), and each one's bounding sphere.
#[derive(Debug, Default)]
pub struct ExtensionSlot {
    pub first: u32,
    pub spheres: Vec<[u32; 4]>,
}

impl ExtensionClusterSlots {
    /// The slots of the clusters that built-in lights take: one for the local (point and
    /// spot) lights, one for the area lights.
    const BUILT_IN_SLOTS: usize = 2;

    /// A new kind's cluster slot (2 for the first kind added, then 3, ...).
    pub fn add_slot(&mut self) -> u32 {
        self.slots.push(ExtensionSlot::default());
        (Self::BUILT_IN_SLOTS + self.slots.len() - 1) as u32
    }

    /// The lights of cluster slot `slot` (from [`Self::add_slot`]), to be rewritten.
    pub fn slot_mut(&mut self, slot: u32) -> &mut ExtensionSlot {
        &mut self.slots[slot as usize - Self::BUILT_IN_SLOTS]
    }
}

impl Default for PhongLightClusters {
    fn default() -> Self {
        Self {
            buffer: LightBuffer::new(PHONG_LIGHT_CLUSTER_BUFFER),
            clusters: LightClusters::default(),
            views: Vec::new(),
            local_spheres: Vec::new(),
            area_spheres: Vec::new(),
        }
    }
}

impl PhongLightClusters {
    /// How many views have clusters (0 when no light is clustered).
    #[cfg(any(test, feature = "testing"))]
    pub fn view_count(&self) -> u32 {
        self.clusters.header().view_count
    }

    /// `u32` words per cluster record in the data last written.
    #[cfg(any(test, feature = "testing"))]
    pub fn cluster_words(&self) -> u32 {
        self.clusters.header().cluster_words
    }

    /// The cluster data last written (see `render::clusters` for its layout).
    #[cfg(any(test, feature = "testing"))]
    pub fn data(&self) -> &[u32] {
        self.clusters.data()
    }

    /// For each cluster of the first view, its light-buffer entries of slots `slots` (slot 0
    /// the local lights, slot 1 the area lights, then each extension kind), as the shader finds
    /// them: from the record's word `slots.start` to its word `slots.end`.
    #[cfg(test)]
    pub(crate) fn first_view_entries(&self, slots: core::ops::Range<usize>) -> Vec<&[u32]> {
        let (data, words) = (self.data(), self.cluster_words() as usize);
        let view = &data[..super::clusters::VIEW_WORDS];
        let cluster_count = (view[2] * view[3] * view[4]) as usize;
        data[data[1] as usize..][..cluster_count * words]
            .chunks_exact(words)
            .map(|record| &data[record[slots.start] as usize..record[slots.end] as usize])
            .collect()
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

/// Lists the clustered lights of [`PhongLightBuffer`] and of every extension kind in the clusters of every active 3D
/// camera's view and writes them into the cluster buffer, when a light or a view changed
/// (and on the first run); otherwise it touches nothing, so no GPU buffer is uploaded.
///
/// Runs after the gather, in [`PhongSystems::GatherLights`](crate::PhongSystems), once
/// Bevy has updated the cameras' frusta.
pub fn assign_lights_to_clusters(
    lights: Res<PhongLightBuffer>,
    extension_lights: Res<ExtensionClusterSlots>,
    cameras: CameraQuery,
    mut state: ResMut<PhongLightClusters>,
    mut buffers: ResMut<Assets<ShaderBuffer>>,
    mut resized: MessageWriter<LightBufferResized>,
    mut collisions_said: Local<usize>,
) {
    let state = state.bypass_change_detection();
    state.set_views(&cameras, &mut collisions_said);
    // The lights' records are rewritten only in frames where a light changed: otherwise only
    // the views can have changed the clusters, which are then built from the spheres of the
    // last build (only the lights near each view are looked at).
    let lights_unchanged =
        !lights.is_changed() && !extension_lights.is_changed() && state.buffer.capacity() > 0;
    let rebuilt = if lights_unchanged {
        state.clusters.build_views(&state.views)
    } else {
        state.build(&lights, &extension_lights) || state.buffer.capacity() == 0
    };
    if rebuilt
        && state
            .buffer
            .write(&mut buffers, state.clusters.header(), state.clusters.data())
    {
        resized.write(LightBufferResized);
    }
}

impl PhongLightClusters {
    /// This frame's views: every active 3D camera's, those whose keys collide left out (a
    /// warning each time their number changes; `collisions_said` is the last number said).
    fn set_views(&mut self, cameras: &CameraQuery, collisions_said: &mut usize) {
        self.views.clear();
        self.views
            .extend(cameras.iter().filter(|(camera, ..)| camera.is_active).map(
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
        let collisions = keep_distinct_views(&mut self.views);
        if collisions != *collisions_said {
            if collisions > 0 {
                warn!(
                    "bevy_phong: {collisions} camera views have frusta whose keys collide; their \
                     fragments loop over every light of finite reach (exact, but slower)"
                );
            }
            *collisions_said = collisions;
        }
    }

    /// Builds the clusters from the spheres of the built-in clustered local and area lights
    /// (the sections of `lights`' records after each kind's unlimited ones) and of every
    /// extension kind's; returns whether they changed.
    fn build(
        &mut self,
        lights: &PhongLightBuffer,
        extension_lights: &ExtensionClusterSlots,
    ) -> bool {
        let header = lights.header();
        let local = header.range(LightSection::ClusteredLocal);
        let area = header.range(LightSection::ClusteredArea);
        self.local_spheres.clear();
        self.local_spheres.extend(
            lights.records()[local.clone()]
                .iter()
                .map(light_sphere_bits),
        );
        self.area_spheres.clear();
        self.area_spheres.extend(
            GpuAreaLight::in_records(&lights.records()[area.clone()])
                .iter()
                .map(area_light_sphere_bits),
        );
        let built_in = [
            ClusterSlot {
                first: local.start as u32,
                spheres: &self.local_spheres,
            },
            ClusterSlot {
                first: area.start as u32,
                spheres: &self.area_spheres,
            },
        ];
        let slots: Vec<ClusterSlot> = built_in
            .into_iter()
            .chain(extension_lights.slots.iter().map(|slot| ClusterSlot {
                first: slot.first,
                spheres: &slot.spheres,
            }))
            .collect();
        self.clusters.build(&self.views, &slots)
    }
}
