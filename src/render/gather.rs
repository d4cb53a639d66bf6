//! The gather system: every frame in which a light changed, it writes all visible lights
//! into the light buffer.

use super::{
    PHONG_LIGHT_BUFFER, clusters::is_finite_sphere, cookies::PhongCookies,
    gpu_types::GpuLightsHeader, light_records::indirect_light, record_cache::RecordCache,
};
use crate::culling::PhongLightCulling;
use crate::light_kind::{GpuLight, PhongLightKind};
use crate::lights::{
    LightQuery, PhongAmbientLight, PhongDirectionalLight, PhongHemisphereLight, PhongPointLight,
    PhongSpotLight, TrackedLightQuery, lit_lights, lit_tracked_lights,
};
use crate::scene_variants::SceneVariants;
use crate::shadows::ShadowSlots;
use crate::storage_buffer::{LightBuffer, LightBufferResized};
use bevy::{
    asset::Assets,
    camera::visibility::InheritedVisibility,
    ecs::{
        change_detection::DetectChanges,
        component::Component,
        entity::Entity,
        lifecycle::RemovedComponents,
        message::MessageWriter,
        query::{Changed, Or, With},
        resource::Resource,
        system::{Query, Res, ResMut, SystemParam},
    },
    render::storage::ShaderBuffer,
    transform::components::GlobalTransform,
};

/// The built-in lights' buffer, and the scratch space the gather system fills it from (kept
/// between frames: no allocation once the scene's size is reached).
#[derive(Resource, Debug)]
pub struct PhongLightBuffer {
    buffer: LightBuffer,
    records: Vec<GpuLight>,
    header: GpuLightsHeader,
    /// The point and spot lights, while they are put in order (see [`order_by_reach`]).
    scratch: Vec<GpuLight>,
    /// The per-light ε of the last gather (`NaN` before the first).
    per_light_epsilon: f32,
    point_cache: RecordCache<PhongPointLight>,
    spot_cache: RecordCache<PhongSpotLight>,
    /// Whether the last gather had a hemisphere light.
    hemisphere: bool,
}

impl Default for PhongLightBuffer {
    fn default() -> Self {
        Self {
            buffer: LightBuffer::new(PHONG_LIGHT_BUFFER),
            records: Vec::new(),
            header: GpuLightsHeader::default(),
            scratch: Vec::new(),
            per_light_epsilon: f32::NAN,
            point_cache: RecordCache::default(),
            spot_cache: RecordCache::default(),
            hemisphere: false,
        }
    }
}

/// How many lit lights of each extension kind that shares ε
/// ([`PhongLightKind::SHARES_EPSILON`](crate::extension::PhongLightKind::SHARES_EPSILON))
/// there are, kind by kind: the gather splits ε among them and the point and spot lights.
#[derive(Resource, Debug, Default)]
pub struct SharedEpsilonLights {
    counts: Vec<u32>,
}

impl SharedEpsilonLights {
    /// A new kind's place.
    pub(crate) fn add_kind(&mut self) -> usize {
        self.counts.push(0);
        self.counts.len() - 1
    }

    /// Kind `kind`'s count.
    pub(crate) fn count(&self, kind: usize) -> u32 {
        self.counts[kind]
    }

    /// Sets kind `kind`'s count.
    pub(crate) fn set_count(&mut self, kind: usize, count: u32) {
        self.counts[kind] = count;
    }

    fn total(&self) -> usize {
        self.counts.iter().map(|&count| count as usize).sum()
    }
}

impl PhongLightBuffer {
    /// The ε each light gets, of [`PhongLightCulling::epsilon`], in the last gather: `ε / n`
    /// for the `n` lit point and spot lights and lights of extension kinds that share ε.
    pub(crate) fn per_light_epsilon(&self) -> f32 {
        self.per_light_epsilon
    }

    /// What a light whose cookie has slot `slot` plus one ([`PhongCookies::slot_of`]) stores
    /// with [`PhongLightKind::set_cookie`]: the index of the cookie's record in the last
    /// gather plus one, or `0` for none.
    pub(crate) fn cookie_index(&self, slot: u32) -> u32 {
        cookie_index(self.header.light_count() as u32, slot)
    }

    /// What was last written: the ambient light and the count of each kind.
    pub fn header(&self) -> &GpuLightsHeader {
        &self.header
    }

    /// The records last written, in the order [`GpuLightsHeader`] describes, then the
    /// cookies' ([`GpuCookie`](super::gpu_types::GpuCookie), as records of a light's size).
    pub fn records(&self) -> &[GpuLight] {
        &self.records
    }

    /// How many lights the GPU buffer has room for.
    pub fn capacity(&self) -> usize {
        self.buffer.capacity()
    }
}

/// Matches the lights of kind `L` whose component, transform or visibility changed.
pub type LightChanged<L> = (
    With<L>,
    Or<(
        Changed<L>,
        Changed<GlobalTransform>,
        Changed<InheritedVisibility>,
    )>,
);

/// Whether any light of kind `L` was added, changed, moved, shown, hidden or removed since
/// the last run of the system that holds this parameter.
#[derive(SystemParam)]
pub struct LightChanges<'w, 's, L: Component> {
    changed: Query<'w, 's, (), LightChanged<L>>,
    removed: RemovedComponents<'w, 's, L>,
}

impl<L: Component> LightChanges<'_, '_, L> {
    /// `true` if any light of kind `L` changed. Call it once per run: it consumes the
    /// removals it has seen.
    pub fn any(&mut self) -> bool {
        let removed = self.removed.read().count() > 0;
        removed || !self.changed.is_empty()
    }
}

/// Appends the record of every light in `lights` that gives light ([`lit_lights`]) to
/// `records`, with its shadow and cookie slots ([`Slots::set`]). Returns how many.
fn push_visible<L: PhongLightKind>(
    lights: &LightQuery<L>,
    slots: Slots,
    records: &mut Vec<L::Gpu>,
) -> u32 {
    let start = records.len();
    records.extend(lit_lights(lights).map(|(entity, light, transform)| {
        let mut record = light.to_gpu(transform);
        slots.set::<L>(&mut record, entity);
        record
    }));
    (records.len() - start) as u32
}

/// This frame's shadow slots and cookie slots.
#[derive(Clone, Copy)]
struct Slots<'a> {
    shadows: &'a ShadowSlots,
    cookies: &'a PhongCookies,
}

impl Slots<'_> {
    /// Stores the shadow slot of `entity`'s light in its record
    /// ([`PhongLightKind::set_shadow`], see [`ShadowSlots`]) and its cookie's
    /// ([`PhongLightKind::set_cookie`]): for the built-in lights the cookie's slot plus one,
    /// which [`gather_lights`] turns into its record's index once the lights are counted.
    fn set<L: PhongLightKind>(self, record: &mut L::Gpu, entity: Entity) {
        L::set_shadow(record, self.shadows.get(entity));
        L::set_cookie(record, self.cookies.slot_of(entity));
    }
}

/// The index plus one of the record of the cookie whose slot is `slot` plus one
/// ([`PhongCookies::slot_of`]), the cookie records starting at index `cookie_first`; `0`
/// for none.
fn cookie_index(cookie_first: u32, slot: u32) -> u32 {
    if slot == 0 { 0 } else { cookie_first + slot }
}

/// What [`push_cached`] found of one kind of light.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Pushed {
    /// The lights that give light ([`lit_tracked_lights`]).
    lit: usize,
    /// Those written: the ones that reach somewhere for the per-light ε.
    kept: usize,
    /// Those of the kept ones that go into the clusters.
    clustered: usize,
}

/// Appends the record of every light in `lights` that gives light
/// ([`lit_tracked_lights`]) and reaches somewhere for the per-light `epsilon`
/// ([`PhongLightKind::reach`]) to `records`, from `cache` ([`RecordCache::record`]), with
/// its slots and its reach ([`PhongLightKind::set_reach`]); counts those that go into the
/// clusters: with [`PhongLightCulling::clusters`], those whose kind gives a finite bounding
/// sphere ([`PhongLightKind::bounding_sphere`]), which [`clustered`] then finds.
fn push_cached<L: PhongLightKind<Gpu = GpuLight> + Clone + PartialEq>(
    lights: &TrackedLightQuery<L>,
    slots: Slots,
    cache: &mut RecordCache<L>,
    records: &mut Vec<GpuLight>,
    epsilon: f32,
    clusters: bool,
) -> Pushed {
    let mut pushed = Pushed::default();
    for (index, (entity, light, transform)) in lit_tracked_lights(lights).enumerate() {
        pushed.lit += 1;
        let (mut record, reach) = cache.record(
            index,
            entity,
            &light,
            light.is_changed(),
            transform,
            epsilon,
        );
        // A light that reaches nowhere for ε is left out.
        if reach > 0.0 {
            slots.set::<L>(&mut record, entity);
            L::set_reach(&mut record, reach);
            pushed.kept += 1;
            pushed.clustered += usize::from(has_sphere::<L>(clusters, &record, reach));
            records.push(record);
        }
    }
    cache.truncate(pushed.lit);
    pushed
}

/// Whether a light of kind `L` that reaches `reach` goes into the clusters: with `clusters`
/// ([`PhongLightCulling::clusters`]), where its kind gives a finite bounding sphere for that
/// reach ([`PhongLightKind::bounding_sphere`]), whatever shadow or cookie it has.
fn has_sphere<L: PhongLightKind>(clusters: bool, record: &L::Gpu, reach: f32) -> bool {
    (clusters && reach.is_finite())
        .then(|| L::bounding_sphere(record, reach))
        .flatten()
        .is_some_and(|sphere| is_finite_sphere(sphere.center.into(), sphere.radius()))
}

/// Whether a point or spot light's record, as [`push_cached`] wrote it (its reach in
/// `range`), goes into the clusters ([`has_sphere`]; the two kinds share their sphere).
fn clustered(culling: &PhongLightCulling, light: &GpuLight) -> bool {
    has_sphere::<PhongPointLight>(culling.clusters, light, light.range)
}

/// Puts the point lights (`points.kept` records from `records[first]`) and the spot lights
/// after them (to the end) in the order the shader reads them: the unlimited point lights,
/// the unlimited spot lights, then the `clustered` point lights and spot lights, each in
/// their order. Returns those four counts. A scene whose lights are all of one sort (the
/// usual case) is already in order; a mixed one is sorted through `scratch`.
fn order_by_reach(
    records: &mut Vec<GpuLight>,
    first: usize,
    [points, spots]: [Pushed; 2],
    scratch: &mut Vec<GpuLight>,
    clustered: impl Fn(&GpuLight) -> bool,
) -> [u32; 4] {
    let counts = [
        points.kept - points.clustered,
        spots.kept - spots.clustered,
        points.clustered,
        spots.clustered,
    ]
    .map(|count| count as u32);
    let all_clustered = points.clustered == points.kept && spots.clustered == spots.kept;
    let none_clustered = points.clustered == 0 && spots.clustered == 0;
    if all_clustered || none_clustered {
        return counts;
    }
    scratch.clear();
    scratch.extend(records.drain(first..));
    let (point_lights, spot_lights) = scratch.split_at(points.kept);
    for lights in [point_lights, spot_lights] {
        records.extend(lights.iter().filter(|light| !clustered(light)));
    }
    for lights in [point_lights, spot_lights] {
        records.extend(lights.iter().filter(|light| clustered(light)));
    }
    counts
}

/// Writes every visible built-in light into [`PhongLightBuffer`], those of finite reach
/// last for the clusters ([`assign_lights_to_clusters`](super::assign_lights_to_clusters)),
/// when any of them, the ambient or hemisphere light or [`PhongLightCulling`] changed (and on
/// the first run); otherwise it touches nothing, so no GPU buffer is uploaded again. When
/// the hemisphere light comes or goes, every Phong material is prepared again (with or
/// without its shader variant).
#[allow(clippy::too_many_arguments)]
pub fn gather_lights(
    ambient: Res<PhongAmbientLight>,
    hemisphere: Option<Res<PhongHemisphereLight>>,
    culling: Res<PhongLightCulling>,
    sharing: Res<SharedEpsilonLights>,
    directional: LightQuery<PhongDirectionalLight>,
    point: TrackedLightQuery<PhongPointLight>,
    spot: TrackedLightQuery<PhongSpotLight>,
    slots: Res<ShadowSlots>,
    cookies: Res<PhongCookies>,
    mut directional_changes: LightChanges<PhongDirectionalLight>,
    mut point_changes: LightChanges<PhongPointLight>,
    mut spot_changes: LightChanges<PhongSpotLight>,
    mut state: ResMut<PhongLightBuffer>,
    mut buffers: ResMut<Assets<ShaderBuffer>>,
    mut resized: MessageWriter<LightBufferResized>,
    mut variants: ResMut<SceneVariants>,
) {
    // Evaluate every detector: each one drains its removals.
    let changes = [
        directional_changes.any(),
        point_changes.any(),
        spot_changes.any(),
        ambient.is_changed(),
        hemisphere.as_ref().is_some_and(DetectChanges::is_changed),
        hemisphere.is_some() != state.hemisphere,
        culling.is_changed(),
        sharing.is_changed(),
        slots.is_changed(),
        cookies.is_changed(),
        state.capacity() == 0,
    ];
    if !changes.contains(&true) {
        return;
    }

    let state = &mut *state;
    let records = &mut state.records;
    records.clear();
    let light_slots = Slots {
        shadows: &slots,
        cookies: &cookies,
    };
    let directional_count = push_visible(&directional, light_slots, records);
    // Unlimited reach first (every fragment loops over them), then the clustered lights,
    // shadows and cookies or not (the clusters' loop applies both).
    let clustered = |light: &GpuLight| clustered(&culling, light);
    // The point lights, then the spot lights, written once in place. ε bounds the sum of
    // what every skipped light leaves out: each of the `count` lit point and spot lights
    // (and lights of extension kinds that share ε) gets ε / count. The count is known once they are read, so they are written with the
    // last gather's per-light ε, and written again in a frame where the count changed.
    let first_point = records.len();
    let mut epsilon = state.per_light_epsilon;
    let pushed = loop {
        records.truncate(first_point);
        let pushed = [
            push_cached(
                &point,
                light_slots,
                &mut state.point_cache,
                records,
                epsilon,
                culling.clusters,
            ),
            push_cached(
                &spot,
                light_slots,
                &mut state.spot_cache,
                records,
                epsilon,
                culling.clusters,
            ),
        ];
        let count = pushed[0].lit + pushed[1].lit + sharing.total();
        let per_light_epsilon = culling.epsilon / count.max(1) as f32;
        if per_light_epsilon.to_bits() == epsilon.to_bits() {
            break pushed;
        }
        epsilon = per_light_epsilon;
    };
    state.per_light_epsilon = epsilon;
    let [
        point_count,
        spot_count,
        clustered_point_count,
        clustered_spot_count,
    ] = order_by_reach(records, first_point, pushed, &mut state.scratch, clustered);

    let [ambient, hemisphere_up, hemisphere_half_difference] =
        indirect_light(&ambient, hemisphere.as_deref());
    state.header = GpuLightsHeader {
        ambient,
        directional_count,
        point_count,
        spot_count,
        clustered_point_count,
        clustered_spot_count,
        hemisphere_up,
        padding_up: 0,
        hemisphere_half_difference,
        padding_difference: 0,
    };
    // The cookies after the lights, as records of a light's size (`GpuCookie`); each light's
    // cookie slot becomes the index of its record (plus one), where 16 bits hold it.
    let cookie_first = state.records.len() as u32;
    if !cookies.records().is_empty() {
        for record in &mut state.records {
            let index = cookie_index(cookie_first, record.shadow >> GpuLight::COOKIE_SHIFT);
            let index = if index <= GpuLight::SHADOW_BITS {
                index
            } else {
                bevy::log::warn_once!(
                    "PhongLightCookie: more than 65,534 lights and cookies; the cookies past \
                     that are left out"
                );
                0
            };
            // Every built-in kind stores it alike (`GpuLight::shadow`'s high half).
            PhongPointLight::set_cookie(record, index);
        }
    }
    state.records.extend(
        cookies
            .records()
            .iter()
            .map(|cookie| bytemuck::cast::<_, GpuLight>(*cookie)),
    );
    state.hemisphere = hemisphere.is_some();
    if variants.hemisphere != state.hemisphere {
        variants.hemisphere = state.hemisphere;
    }
    if state
        .buffer
        .write(&mut buffers, &state.header, &state.records)
    {
        resized.write(LightBufferResized);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_app::{built_in_buffer_bytes, test_app, uploads_in_next_frame};
    use bevy::prelude::{App, Entity, Transform, Vec3, Visibility, World};

    #[test]
    fn lights_are_uploaded_only_in_frames_where_they_change() {
        let mut app = test_app(|_| {});
        let light = app
            .world_mut()
            .spawn((
                PhongPointLight::default(),
                Transform::from_xyz(1.0, 2.0, 3.0),
            ))
            .id();
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "a new light is uploaded"
        );
        let state = app.world().resource::<PhongLightBuffer>();
        assert_eq!(state.header().point_count, 1);
        assert_eq!(state.records()[0].position, [1.0, 2.0, 3.0]);

        assert_eq!(
            uploads_in_next_frame(&mut app),
            0,
            "nothing changed: no upload"
        );
        assert_eq!(
            uploads_in_next_frame(&mut app),
            0,
            "nothing changed: no upload"
        );

        app.world_mut()
            .get_mut::<Transform>(light)
            .unwrap()
            .translation = Vec3::X;
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "a moved light is uploaded"
        );
        let state = app.world().resource::<PhongLightBuffer>();
        assert_eq!(state.records()[0].position, [1.0, 0.0, 0.0]);

        *app.world_mut().get_mut::<Visibility>(light).unwrap() = Visibility::Hidden;
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "a hidden light is removed"
        );
        assert_eq!(
            app.world()
                .resource::<PhongLightBuffer>()
                .header()
                .light_count(),
            0
        );

        *app.world_mut().get_mut::<Visibility>(light).unwrap() = Visibility::Inherited;
        assert_eq!(uploads_in_next_frame(&mut app), 1, "a shown light is back");
        app.world_mut().despawn(light);
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "a despawned light is removed"
        );
        assert_eq!(
            app.world()
                .resource::<PhongLightBuffer>()
                .header()
                .light_count(),
            0
        );

        app.world_mut().resource_mut::<PhongAmbientLight>().color = bevy::color::Color::BLACK;
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "a changed ambient light is uploaded"
        );
        assert_eq!(
            app.world().resource::<PhongLightBuffer>().header().ambient,
            [0.0; 3]
        );
        assert!(!built_in_buffer_bytes(&app).is_empty());
    }

    #[test]
    fn a_hemisphere_light_adds_its_mean_to_the_ambient_and_its_half_difference_along_up() {
        let mut app = test_app(|_| {});
        app.world_mut().resource_mut::<PhongAmbientLight>().color =
            bevy::color::Color::linear_rgb(0.1, 0.1, 0.1);
        uploads_in_next_frame(&mut app);
        app.world_mut().insert_resource(PhongHemisphereLight {
            sky_color: bevy::color::Color::linear_rgb(0.5, 0.25, 1.0),
            ground_color: bevy::color::Color::linear_rgb(0.25, 0.5, 0.0),
            up: Vec3::new(0.0, 0.0, -4.0),
        });
        assert_eq!(uploads_in_next_frame(&mut app), 1, "inserted: uploaded");
        let header = *app.world().resource::<PhongLightBuffer>().header();
        // Exact in binary: 0.1 + 0.375 and the others are each rounded once.
        assert_eq!(header.ambient, [0.475, 0.475, 0.6].map(|x: f64| x as f32));
        assert_eq!(header.hemisphere_up, [0.0, 0.0, -1.0]);
        assert_eq!(header.hemisphere_half_difference, [0.125, -0.125, 0.5]);
        assert_eq!(uploads_in_next_frame(&mut app), 0, "unchanged: no upload");

        app.world_mut().remove_resource::<PhongHemisphereLight>();
        assert_eq!(uploads_in_next_frame(&mut app), 1, "removed: uploaded");
        let header = *app.world().resource::<PhongLightBuffer>().header();
        assert_eq!(header.ambient, [0.1; 3]);
        assert_eq!(header.hemisphere_up, [0.0; 3]);
        assert_eq!(header.hemisphere_half_difference, [0.0; 3]);
    }

    /// The records a gather must write for the lights in `app`, made afresh (no cache):
    /// sorted by their bits, as the gather's own are by [`sorted_records`].
    fn fresh_records(app: &mut App) -> Vec<[u32; 20]> {
        let world = app.world_mut();
        let epsilon = world.resource::<PhongLightCulling>().epsilon;
        let mut records: Vec<GpuLight> = Vec::new();
        push_fresh::<PhongPointLight>(world, &mut records);
        push_fresh::<PhongSpotLight>(world, &mut records);
        let per_light_epsilon = epsilon / records.len().max(1) as f32;
        records.retain_mut(|record| {
            // Point and spot lights alike: the point light's reach is the spot light's.
            let reach = PhongPointLight::reach(record, per_light_epsilon);
            PhongPointLight::set_reach(record, reach);
            reach > 0.0
        });
        let mut bits: Vec<[u32; 20]> = records.iter().map(|r| bytemuck::cast(*r)).collect();
        bits.sort();
        bits
    }

    /// Appends the whole record of every visible light of kind `L`, made afresh.
    fn push_fresh<L: PhongLightKind<Gpu = GpuLight>>(
        world: &mut World,
        records: &mut Vec<GpuLight>,
    ) {
        let mut lights = world.query::<(&L, &GlobalTransform, &InheritedVisibility)>();
        for (light, transform, visibility) in lights.iter(world) {
            if visibility.get() {
                records.push(light.to_gpu(transform));
            }
        }
    }

    /// The records the gather wrote, sorted by their bits.
    fn sorted_records(app: &App) -> Vec<[u32; 20]> {
        let state = app.world().resource::<PhongLightBuffer>();
        let mut bits: Vec<[u32; 20]> = state.records().iter().map(|r| bytemuck::cast(*r)).collect();
        bits.sort();
        bits
    }

    #[test]
    fn kept_constants_never_outlive_a_change() {
        let mut app = test_app(|app| {
            app.insert_resource(PhongLightCulling {
                epsilon: 1e-2,
                clusters: true,
            });
        });
        let decay = crate::Decay::DISTANCE_50;
        let mut lights: Vec<Entity> = (0..6)
            .map(|i| {
                let position = Transform::from_xyz(i as f32, 1.0, 0.0);
                let world = app.world_mut();
                if i % 3 == 0 {
                    world.spawn((
                        PhongSpotLight {
                            decay,
                            ..Default::default()
                        },
                        position,
                    ))
                } else {
                    world.spawn((
                        PhongPointLight {
                            decay,
                            ..Default::default()
                        },
                        position,
                    ))
                }
                .id()
            })
            .collect();
        app.update();
        assert_eq!(
            sorted_records(&app),
            fresh_records(&mut app),
            "first gather"
        );

        type Step = fn(&mut World, &mut Vec<Entity>);
        let steps: [(&str, Step); 9] = [
            ("a point light recolored", |world, lights| {
                world.get_mut::<PhongPointLight>(lights[1]).unwrap().color =
                    bevy::color::Color::srgb(0.2, 0.4, 0.9);
            }),
            ("a spot light's cone narrowed", |world, lights| {
                world
                    .get_mut::<PhongSpotLight>(lights[0])
                    .unwrap()
                    .outer_angle = 0.2;
            }),
            ("a light moved", |world, lights| {
                world.get_mut::<Transform>(lights[2]).unwrap().translation.y = 4.0;
            }),
            ("a spot light turned", |world, lights| {
                world.get_mut::<Transform>(lights[3]).unwrap().rotate_x(0.5);
            }),
            ("a light despawned from the middle", |world, lights| {
                world.despawn(lights.remove(1));
            }),
            ("a light hidden", |world, lights| {
                *world.get_mut::<Visibility>(lights[1]).unwrap() = Visibility::Hidden;
            }),
            ("a light spawned: ε per light shrinks", |world, lights| {
                let light = PhongPointLight {
                    decay: crate::Decay::DISTANCE_50,
                    color: bevy::color::Color::srgb(3.0, 3.0, 3.0),
                    ..Default::default()
                };
                lights.push(
                    world
                        .spawn((light, Transform::from_xyz(0.0, 0.0, 2.0)))
                        .id(),
                );
            }),
            ("the hidden light shown", |world, lights| {
                *world.get_mut::<Visibility>(lights[1]).unwrap() = Visibility::Inherited;
            }),
            ("ε changed", |world, _| {
                world.resource_mut::<PhongLightCulling>().epsilon = 1e-3;
            }),
        ];
        for (name, step) in steps {
            step(app.world_mut(), &mut lights);
            app.update();
            assert_eq!(
                sorted_records(&app),
                fresh_records(&mut app),
                "after {name}"
            );
        }
    }

    #[test]
    fn cookied_and_shadow_casting_lights_are_listed_only_in_the_clusters_they_reach() {
        use crate::render::PhongLightClusters;
        use crate::{PhongShadows, test_app::white_cookie};
        use bevy::{asset::AssetApp, image::Image, prelude::Camera3d};
        let mut app = test_app(|app| {
            app.init_asset::<Image>();
        });
        let cookie = white_cookie(&mut app);
        let world = app.world_mut();
        world.spawn((
            Camera3d::default(),
            Transform::from_xyz(0.0, 2.0, 10.0).looking_at(Vec3::ZERO, Vec3::Y),
        ));
        let spot = |x: f32| {
            (
                PhongSpotLight {
                    range: Some(2.0),
                    ..Default::default()
                },
                cookie.clone(),
                Transform::from_xyz(x, 1.0, 0.0).looking_at(Vec3::new(x, 0.0, 0.0), Vec3::Z),
            )
        };
        world.spawn(spot(-3.0));
        world.spawn(spot(1000.0));
        world.spawn((
            PhongPointLight {
                range: Some(2.0),
                shadows: PhongShadows::ON,
                ..Default::default()
            },
            Transform::from_xyz(3.0, 1.0, 0.0),
        ));
        app.update();

        let state = app.world().resource::<PhongLightBuffer>();
        let header = *state.header();
        assert_eq!(
            [
                header.point_count,
                header.spot_count,
                header.clustered_point_count,
                header.clustered_spot_count
            ],
            [0, 0, 1, 2],
            "no light is looped over by every fragment: all three are clustered"
        );
        let index_at = |x: f32| {
            state
                .records()
                .iter()
                .position(|record| record.position[0] == x)
                .unwrap() as u32
        };
        let (shadowed, near, far) = (index_at(3.0), index_at(-3.0), index_at(1000.0));
        let records = state.records();
        assert_eq!(
            records[shadowed as usize].shadow, 1,
            "its first view, plus one"
        );
        assert_ne!(records[near as usize].shadow >> GpuLight::COOKIE_SHIFT, 0);

        let clusters = app.world().resource::<PhongLightClusters>();
        assert_eq!(clusters.view_count(), 1);
        // Each cluster's point and spot lights (slots 0 and 1).
        let entries = clusters.first_view_entries(0..2);
        let cluster_count = entries.len();
        let clusters_listing = |light: u32| {
            entries
                .iter()
                .filter(|entries| entries.contains(&light))
                .count()
        };
        let (near_clusters, shadowed_clusters) =
            (clusters_listing(near), clusters_listing(shadowed));
        assert!(
            0 < near_clusters && near_clusters < cluster_count / 4,
            "the cookied lamp in view is listed in the few clusters it reaches: {near_clusters} of \
             {cluster_count}"
        );
        assert!(
            0 < shadowed_clusters && shadowed_clusters < cluster_count / 4,
            "the shadow-casting light too: {shadowed_clusters} of {cluster_count}"
        );
        assert_eq!(clusters_listing(far), 0, "the far cookied lamp in none");
    }

    #[test]
    fn mixed_lights_are_ordered_unlimited_then_clustered_each_kind_in_its_order() {
        // Points 1 and 3 then spots 4 and 5 after one directional light (0); `shadow` marks
        // the unlimited ones.
        let light = |id: f32, shadow: u32| GpuLight {
            position: [id, 0.0, 0.0],
            shadow,
            ..Default::default()
        };
        let mut records = vec![light(0.0, 0), light(1.0, 0), light(3.0, 1), light(4.0, 1)];
        records.push(light(5.0, 0));
        let clustered = |light: &GpuLight| light.shadow == 0;
        let pushed = |kept: usize, clustered: usize| Pushed {
            lit: kept,
            kept,
            clustered,
        };
        let mut scratch = Vec::new();
        let counts = order_by_reach(
            &mut records,
            1,
            [pushed(2, 1), pushed(2, 1)],
            &mut scratch,
            clustered,
        );
        assert_eq!(counts, [1, 1, 1, 1]);
        let order: Vec<f32> = records.iter().map(|light| light.position[0]).collect();
        assert_eq!(order, [0.0, 3.0, 4.0, 1.0, 5.0]);

        // All of one sort: left where they are.
        let counts = order_by_reach(
            &mut records,
            1,
            [pushed(2, 2), pushed(2, 2)],
            &mut scratch,
            |_| true,
        );
        assert_eq!(counts, [0, 0, 2, 2]);
        let again: Vec<f32> = records.iter().map(|light| light.position[0]).collect();
        assert_eq!(again, order);
    }

    #[test]
    fn lights_are_ordered_directional_point_spot() {
        let mut app = test_app(|_| {});
        let world = app.world_mut();
        world.spawn(PhongSpotLight::default());
        world.spawn(PhongPointLight::default());
        world.spawn(PhongDirectionalLight::default());
        world.spawn(PhongPointLight::default());
        app.update();
        let state = app.world().resource::<PhongLightBuffer>();
        let header = state.header();
        assert_eq!(
            (
                header.directional_count,
                header.point_count,
                header.spot_count
            ),
            (1, 2, 1)
        );
        // A directional light has no range; point and spot lights keep "unlimited".
        assert_eq!(state.records()[0].range, 0.0);
        assert_eq!(state.records()[1].range, f32::MAX);
        assert!(state.records()[3].cone_scale > 0.0);
    }
}
