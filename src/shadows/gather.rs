//! The shadow gather (main world, every frame with a shadow-casting light): which lights get
//! shadow maps, where each map looks from, and which casters each map draws.

use super::{
    MAX_SHADOW_VIEWS,
    cameras::{PhongLit, ShadowCamera, ShadowCameraQuery, shadow_cameras},
    casters::{Caster, CasterSet},
    gpu_types::{GpuShadowView, GpuShadowViewsHeader},
    instance::ShadowInstance,
    request::{PhongShadowProjection, ShadowRequest, ShadowRequests},
    views::{
        Bounds, MAX_CONE_MAP_ANGLE, ShadowLightView, beam_view, cascade_views, cone_view,
        cube_views,
    },
};
use crate::lights::PhongShadows;
use crate::limits;
use crate::scene_variants::SceneVariants;
use crate::storage_buffer::{LightBuffer, LightBufferResized};
use bevy::{
    asset::{Assets, Handle, uuid_handle},
    camera::primitives::{Frustum, Sphere},
    ecs::{
        entity::{Entity, EntityHashMap, EntityHashSet},
        message::MessageWriter,
        query::With,
        resource::Resource,
        system::{Query, ResMut, SystemParam},
    },
    log::warn,
    math::{Mat4, Vec3A, Vec4},
    render::storage::ShaderBuffer,
};
use core::ops::Range;

/// The storage buffer of the shadow views, bound by every Phong material.
pub(crate) const PHONG_SHADOW_VIEW_BUFFER: Handle<ShaderBuffer> =
    uuid_handle!("3b7e4f0a-8d21-4c6e-9a55-1e2f7c9d0b34");

/// Each shadow-casting light's slot this frame: the index of its first view in
/// [`PhongShadowViews::views`] plus one (`0`: no shadow maps), which the light gathers write
/// into the light records.
#[derive(Resource, Default, Debug, PartialEq)]
pub struct ShadowSlots(EntityHashMap<u32>);

impl ShadowSlots {
    /// The slot of `entity`.
    pub fn get(&self, entity: Entity) -> u32 {
        self.0.get(&entity).copied().unwrap_or(0)
    }
}

/// The size of the shadow map array: square layers of `size` texels, `layers` of them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct AtlasLayout {
    /// Edge length of a layer, texels.
    pub size: u32,
    /// Number of layers.
    pub layers: u32,
}

/// One shadow map to render: a layer, the part of it the map covers, and its casters.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ShadowPass {
    /// The array layer.
    pub layer: u32,
    /// Edge length of the map, texels (the rest of the layer is unused).
    pub resolution: u32,
    /// The casters it draws, in [`ShadowFrame::instances`].
    pub instances: Range<usize>,
}

/// The shadow maps of this frame, which the render world draws.
#[derive(Resource, Clone, Debug, Default)]
pub(crate) struct ShadowFrame {
    /// The shadow map array this frame needs.
    pub layout: AtlasLayout,
    /// The maps, in layer order.
    pub passes: Vec<ShadowPass>,
    /// The casters of every map.
    pub instances: Vec<ShadowInstance>,
}

/// The shadow views of the current frame (one per shadow map, as the shader reads them),
/// with the gather's buffers and scratch space, kept between frames.
#[derive(Resource)]
pub struct PhongShadowViews {
    views_buffer: LightBuffer,
    records: Vec<GpuShadowView>,
    casters: Vec<Caster>,
    warned_over_capacity: bool,
    /// The skinned or morphed casters that could not be posed, each reported once.
    unposed: EntityHashSet,
}

impl PhongShadowViews {
    /// The views last written, in layer order: each shadow-casting light's views are
    /// consecutive, the first holding their count (see [`GpuShadowView`]).
    #[cfg(any(test, feature = "testing"))]
    pub fn views(&self) -> &[GpuShadowView] {
        &self.records
    }
}

impl Default for PhongShadowViews {
    fn default() -> Self {
        Self {
            views_buffer: LightBuffer::new(PHONG_SHADOW_VIEW_BUFFER),
            records: Vec::new(),
            casters: Vec::new(),
            warned_over_capacity: false,
            unposed: EntityHashSet::default(),
        }
    }
}

/// The cameras the shadow maps serve: each active camera that sees Phong-lit meshes.
#[derive(SystemParam)]
pub(crate) struct ShadowViewers<'w, 's> {
    cameras: ShadowCameraQuery<'w, 's>,
    phong_lit: Query<'w, 's, (), With<PhongLit>>,
}

/// Where the shadow gather writes: the views and their GPU buffer (a message when it grows
/// or the array's layout changes), the frame the render world draws, each light's slot, and
/// the scene's shadow variants.
#[derive(SystemParam)]
pub(crate) struct ShadowWrites<'w> {
    state: ResMut<'w, PhongShadowViews>,
    frame: ResMut<'w, ShadowFrame>,
    slots: ResMut<'w, ShadowSlots>,
    buffers: ResMut<'w, Assets<ShaderBuffer>>,
    resized: MessageWriter<'w, LightBufferResized>,
    variants: ResMut<'w, SceneVariants>,
}

/// Lays out every requested shadow map of this frame: the maps' views (written into the
/// shadow view buffer), their casters (for the render world), and each light's first view
/// (for its light record).
pub(crate) fn gather_shadows(
    mut requests: ResMut<ShadowRequests>,
    viewers: ShadowViewers,
    casters: CasterSet,
    mut writes: ShadowWrites,
) {
    let cameras = shadow_cameras(&viewers.cameras, &viewers.phong_lit);
    let requests = in_priority_order(core::mem::take(&mut requests.0), &cameras);
    let state = &mut *writes.state;
    state.records.clear();
    state.casters.clear();
    if !requests.is_empty() {
        casters.collect(&mut state.casters, &mut state.unposed);
    }
    let (mut next, slots) = state.lay_out(&requests, &cameras);
    let size = next
        .passes
        .iter()
        .map(|pass| pass.resolution)
        .max()
        .unwrap_or(1);
    for record in &mut state.records {
        record.uv_scale /= size as f32;
    }
    next.layout = atlas_layout(writes.frame.layout, size, state.records.len() as u32);
    let header = GpuShadowViewsHeader {
        count: state.records.len() as u32,
        padding: [0; 3],
    };
    let buffer_resized = state
        .views_buffer
        .write(&mut writes.buffers, &header, &state.records);
    let casts_shadows = !state.records.is_empty();
    let soft_shadows = state.records.iter().any(|view| view.light_size > 0.0);
    let variants = &mut writes.variants;
    if (variants.shadows, variants.soft_shadows) != (casts_shadows, soft_shadows) {
        variants.shadows = casts_shadows;
        variants.soft_shadows = soft_shadows;
    }
    if buffer_resized || next.layout != writes.frame.layout {
        writes.resized.write(LightBufferResized);
    }
    *writes.frame = next;
    if writes.slots.0 != slots {
        writes.slots.0 = slots;
    }
}

/// The requests of lights that reach a camera's view (all of them without a camera), in
/// the order they get maps ([`priority`]).
fn in_priority_order(
    mut requests: Vec<ShadowRequest>,
    cameras: &[ShadowCamera],
) -> Vec<ShadowRequest> {
    if !cameras.is_empty() {
        requests.retain(|request| {
            cameras
                .iter()
                .any(|camera| reaches_view(request, &camera.frustum))
        });
    }
    requests.sort_by(|a, b| priority(a, cameras).total_cmp(&priority(b, cameras)));
    requests
}

impl PhongShadowViews {
    /// Gives each request's maps their layers and records (until [`MAX_SHADOW_VIEWS`]) and
    /// each map its casters (from the casters, gathered first). Returns the frame's
    /// passes (its layout still to be set) and each light's slot.
    fn lay_out(
        &mut self,
        requests: &[ShadowRequest],
        cameras: &[ShadowCamera],
    ) -> (ShadowFrame, EntityHashMap<u32>) {
        let caster_bounds: Vec<Bounds> = self.casters.iter().map(|caster| caster.bounds).collect();
        let mut slots = EntityHashMap::default();
        let mut next = ShadowFrame::default();
        for request in requests {
            let resolution = request
                .settings
                .resolution
                .clamp(PhongShadows::MIN_RESOLUTION, PhongShadows::MAX_RESOLUTION);
            let sets = light_views(request, cameras, resolution, &caster_bounds);
            let view_count: usize = sets.iter().map(|set| set.views.len()).sum();
            if view_count == 0 {
                continue;
            }
            if self.records.len() + view_count > MAX_SHADOW_VIEWS {
                if !self.warned_over_capacity {
                    warn!(
                        "more than {MAX_SHADOW_VIEWS} shadow maps requested: light {} and the \
                         lights farther from the cameras cast no shadow",
                        request.entity
                    );
                    self.warned_over_capacity = true;
                }
                break;
            }
            slots.insert(request.entity, self.records.len() as u32 + 1);
            for set in &sets {
                self.push_set(set, sets.len(), resolution, &request.settings, &mut next);
            }
        }
        (next, slots)
    }

    /// Appends the records and passes of one set of a light's views (`set_count` sets in
    /// all), each pass drawing the casters whose bounds meet its view.
    fn push_set(
        &mut self,
        set: &ViewSet,
        set_count: usize,
        resolution: u32,
        settings: &PhongShadows,
        next: &mut ShadowFrame,
    ) {
        let first = self.records.len();
        for view in &set.views {
            let layer = self.records.len() as u32;
            let start = next.instances.len();
            next.instances.extend(
                self.casters
                    .iter()
                    .filter(|caster| in_view(&view.clip_from_world, &caster.bounds))
                    .map(|caster| caster.instance(view.clip_from_world)),
            );
            next.passes.push(ShadowPass {
                layer,
                resolution,
                instances: start..next.instances.len(),
            });
            let mut record = view_record(view, layer, resolution, settings);
            record.camera_key = set.camera_key;
            self.records.push(record);
        }
        self.records[first].view_count = set.views.len() as u32;
        self.records[first].camera_count = set_count as u32;
    }
}

/// Directional lights first; the others nearest to a camera first (to the origin where
/// there is no camera).
fn priority(request: &ShadowRequest, cameras: &[ShadowCamera]) -> f32 {
    match request.projection {
        PhongShadowProjection::Directional { .. } | PhongShadowProjection::Beam { .. } => -1.0,
        PhongShadowProjection::Cone { position, .. } | PhongShadowProjection::Omni { position } => {
            cameras
                .iter()
                .map(|camera| position.distance_squared(camera.eye))
                .reduce(f32::min)
                .unwrap_or(position.length_squared())
        }
    }
}

/// Whether a light's reach meets a camera's view (lights out of every view cast into nothing
/// a camera sees).
fn reaches_view(request: &ShadowRequest, frustum: &Frustum) -> bool {
    match request.projection {
        PhongShadowProjection::Cone { position, .. } | PhongShadowProjection::Omni { position }
            if request.reach.is_finite() =>
        {
            frustum.intersects_sphere(
                &Sphere {
                    center: Vec3A::from(position),
                    radius: request.reach,
                },
                true,
            )
        }
        _ => true,
    }
}

/// The views of one light's maps: for a directional light, one set of cascades per camera
/// (none without a camera); for the others, one set.
fn light_views(
    request: &ShadowRequest,
    cameras: &[ShadowCamera],
    resolution: u32,
    casters: &[Bounds],
) -> Vec<ViewSet> {
    let near = limits::SHADOW_NEAR.apply(request.settings.near_distance);
    let views = match request.projection {
        PhongShadowProjection::Directional {
            direction,
            cascades,
        } => {
            return cameras
                .iter()
                .map(|camera| ViewSet {
                    camera_key: camera.key,
                    views: cascade_views(
                        direction,
                        &camera.cascades,
                        &cascades,
                        resolution,
                        casters,
                    ),
                })
                .collect();
        }
        PhongShadowProjection::Beam {
            origin,
            direction,
            right,
            half_size,
            length,
        } => vec![beam_view(
            origin,
            direction,
            right,
            half_size.to_array(),
            length,
            resolution,
        )],
        PhongShadowProjection::Cone {
            position,
            direction,
            half_angle,
        } if half_angle <= MAX_CONE_MAP_ANGLE => {
            vec![cone_view(position, direction, half_angle, near, resolution)]
        }
        PhongShadowProjection::Cone { position, .. } | PhongShadowProjection::Omni { position } => {
            cube_views(position, near, resolution).to_vec()
        }
    };
    vec![ViewSet {
        camera_key: 0,
        views,
    }]
}

/// A set of a light's views that the shader reads together: a directional light's cascades
/// fitted to one camera, or all the views of another light.
struct ViewSet {
    /// The view key of the camera the cascades were fitted to; 0 for other lights.
    camera_key: u32,
    views: Vec<ShadowLightView>,
}

/// The record of one view. `uv_scale` holds the resolution until the array's size is known.
fn view_record(
    view: &ShadowLightView,
    layer: u32,
    resolution: u32,
    settings: &PhongShadows,
) -> GpuShadowView {
    // The ranges `validate_lights` warns about, applied again so that no frame draws with an
    // invalid value.
    let softness = limits::SHADOW_SOFTNESS.apply(settings.softness);
    let light_size = match view.projection {
        GpuShadowView::ORTHOGRAPHIC => softness.min(45.0).to_radians().tan(),
        _ => softness,
    };
    GpuShadowView {
        clip_from_world: view.clip_from_world.to_cols_array_2d(),
        view_plane: view.view_plane.to_array(),
        projection: view.projection,
        layer,
        view_count: 0,
        uv_scale: resolution as f32,
        texel_size: view.texel_size,
        depth_range: view.depth_range,
        near: view.near,
        depth_bias: limits::SHADOW_BIAS.apply(settings.depth_bias),
        normal_bias: limits::SHADOW_BIAS.apply(settings.normal_bias),
        light_size,
        cascade_far: view.cascade_far,
        cascade_blend_start: view.cascade_blend_start,
        diffuse_in_shadow: limits::SHADOW_FRACTION.apply(settings.diffuse_in_shadow),
        specular_in_shadow: limits::SHADOW_FRACTION.apply(settings.specular_in_shadow),
        camera_key: 0,
        camera_count: 1,
    }
}

/// The array for `layers` maps of at most `size`²: the current one while it fits and is
/// more than a quarter used, else room for the next power of two of layers.
fn atlas_layout(current: AtlasLayout, size: u32, layers: u32) -> AtlasLayout {
    let fits = current.size == size && layers <= current.layers && layers * 4 > current.layers;
    if fits {
        current
    } else {
        AtlasLayout {
            size,
            layers: layers.max(1).next_power_of_two(),
        }
    }
}

/// Whether a sphere meets the view volume of `clip_from_world` (reversed depth: the near
/// plane at depth 1, the far plane at 0).
fn in_view(clip_from_world: &Mat4, bounds: &Bounds) -> bool {
    let [x, y, z, w] = [0, 1, 2, 3].map(|row| clip_from_world.row(row));
    let point = bounds.center.extend(1.0);
    [w + x, w - x, w + y, w - y, z, w - z]
        .into_iter()
        .all(|plane: Vec4| {
            let length = plane.truncate().length();
            length == 0.0 || plane.dot(point) >= -bounds.radius * length
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{PhongPointLight, shadows::instance::CasterSource, test_app::test_app};
    use bevy::{
        asset::{AssetApp, Handle},
        camera::primitives::Aabb,
        math::Vec3,
        mesh::{
            Mesh, Mesh3d, MeshBuilder, Meshable,
            morph::MeshMorphWeights,
            skinning::{SkinnedMesh, SkinnedMeshInverseBindposes},
        },
        prelude::{Cuboid, Transform, Visibility},
    };

    #[test]
    fn posed_meshes_cast_a_loading_skin_waits_and_a_broken_one_is_reported() {
        // A cuboid (24 vertices) whose vertices all follow joint 0 with weight 1.
        let jointed = Cuboid::default()
            .mesh()
            .build()
            .with_inserted_attribute(
                Mesh::ATTRIBUTE_JOINT_INDEX,
                bevy::mesh::VertexAttributeValues::Uint16x4(vec![[0; 4]; 24]),
            )
            .with_inserted_attribute(
                Mesh::ATTRIBUTE_JOINT_WEIGHT,
                vec![[1.0f32, 0.0, 0.0, 0.0]; 24],
            );
        let mut app = test_app(|app| {
            app.init_asset::<Mesh>()
                .init_asset::<SkinnedMeshInverseBindposes>();
            let world = app.world_mut();
            let mut meshes = world.resource_mut::<Assets<Mesh>>();
            let [plain, jointed] = [
                meshes.add(Cuboid::default().mesh().build()),
                meshes.add(jointed),
            ];
            let bind_poses = world
                .resource_mut::<Assets<SkinnedMeshInverseBindposes>>()
                .add(SkinnedMeshInverseBindposes::from(vec![Mat4::IDENTITY]));
            let joint = world.spawn(Transform::from_xyz(0.0, 1.0, 0.0)).id();
            // A joint that is no longer there.
            let gone = world.spawn_empty().id();
            world.despawn(gone);
            let caster = |mesh: Handle<Mesh>| {
                (
                    Mesh3d(mesh),
                    Aabb::from_min_max(Vec3::splat(-0.5), Vec3::splat(0.5)),
                    Transform::default(),
                    Visibility::default(),
                )
            };
            world.spawn(caster(plain.clone()));
            // Its inverse bind matrices are not loaded: it waits, without a warning.
            world.spawn((caster(jointed.clone()), SkinnedMesh::default()));
            // Its joint has no transform: reported once.
            world.spawn((
                caster(jointed.clone()),
                SkinnedMesh {
                    inverse_bindposes: bind_poses.clone(),
                    joints: vec![gone],
                },
            ));
            // Placed by its joint, a unit up.
            world.spawn((
                caster(jointed),
                SkinnedMesh {
                    inverse_bindposes: bind_poses,
                    joints: vec![joint],
                },
            ));
            // No morph targets: placed as stored, by its transform.
            world.spawn((
                caster(plain),
                MeshMorphWeights::Value { weights: vec![0.5] },
            ));
            world.spawn((
                PhongPointLight {
                    shadows: PhongShadows::ON,
                    ..Default::default()
                },
                Transform::from_xyz(0.0, 3.0, 0.0),
            ));
        });
        app.update();
        app.update();
        let views = app.world().resource::<PhongShadowViews>();
        assert!(!views.views().is_empty(), "the light has shadow maps");
        let casters: Vec<_> = views
            .casters
            .iter()
            .map(|c| (c.source.clone(), c.bounds))
            .collect();
        assert_eq!(
            casters.len(),
            3,
            "the plain, the skinned and the morphed mesh cast"
        );
        // In the order Bevy's queries give them, which is not the order of spawning.
        let of_kind = |kind: fn(&CasterSource) -> bool| {
            let found: Vec<_> = casters.iter().filter(|(source, _)| kind(source)).collect();
            assert_eq!(found.len(), 1, "one caster of the kind in {casters:?}");
            found[0].1
        };
        of_kind(|source| matches!(source, CasterSource::Mesh(_)));
        let skinned = of_kind(|source| matches!(source, CasterSource::Posed { skinned: true, .. }));
        assert!(
            skinned.center.distance(Vec3::Y) < 1e-6,
            "the skinned cube's bounds follow its joint"
        );
        of_kind(|source| matches!(source, CasterSource::Posed { skinned: false, .. }));
        assert_eq!(
            views.unposed.len(),
            1,
            "one entity reported, the skin without its joint"
        );
    }

    #[test]
    fn the_array_grows_by_powers_of_two_and_holds_while_a_quarter_is_used() {
        let empty = AtlasLayout::default();
        let four = atlas_layout(empty, 1024, 3);
        assert_eq!(
            four,
            AtlasLayout {
                size: 1024,
                layers: 4
            }
        );
        assert_eq!(atlas_layout(four, 1024, 2), four);
        assert_eq!(atlas_layout(four, 1024, 5).layers, 8);
        assert_eq!(atlas_layout(four, 2048, 2).size, 2048);
        let sixteen = AtlasLayout {
            size: 1024,
            layers: 16,
        };
        assert_eq!(atlas_layout(sixteen, 1024, 4).layers, 4);
    }

    #[test]
    fn a_sphere_is_in_view_when_it_meets_the_volume() {
        let clip_from_world =
            glam::camera::rh::proj::directx::orthographic(-1.0, 1.0, -1.0, 1.0, 10.0, 0.0);
        let sphere = |x: f32, z: f32, radius: f32| Bounds {
            center: Vec3::new(x, 0.0, z),
            radius,
        };
        assert!(in_view(&clip_from_world, &sphere(0.0, -5.0, 0.1)));
        assert!(in_view(&clip_from_world, &sphere(1.05, -5.0, 0.1)));
        assert!(!in_view(&clip_from_world, &sphere(1.2, -5.0, 0.1)));
        assert!(
            !in_view(&clip_from_world, &sphere(0.0, 0.5, 0.1)),
            "behind the near plane"
        );
        assert!(
            !in_view(&clip_from_world, &sphere(0.0, -10.5, 0.1)),
            "past the far plane"
        );
    }
}
