//! The gather system: every frame in which a light changed, it writes all visible lights
//! into the light buffer.

use super::light_sections::LightSection;
use super::{
    PHONG_LIGHT_BUFFER, clusters::is_finite_sphere, cookies::PhongCookies,
    gpu_types::GpuLightsHeader, light_records::indirect_light,
};
use crate::culling::PhongLightCulling;
use crate::light_kind::{
    BuiltInCaches, BuiltInLights, BuiltInVisitor, GpuAreaLight, GpuLight, PhongLightKind,
    RecordCache, local_sphere,
};
use crate::lights::{
    BevyAmbientPerView, LightQuery, PhongAmbientLight, PhongHemisphereLight, TrackedLightQuery,
    lit_lights, lit_tracked_lights,
};
use crate::scene_variants::SceneVariants;
use crate::shadows::ShadowSlots;
use crate::storage_buffer::{LightBuffer, LightBufferResized};
use bevy::{
    asset::Assets,
    ecs::{
        change_detection::DetectChanges,
        entity::Entity,
        message::MessageWriter,
        resource::Resource,
        system::{Res, ResMut, SystemParam},
    },
    render::storage::ShaderBuffer,
    shape::BoundingSphere,
};

/// The built-in lights' buffer, and the scratch space the gather system fills it from (kept
/// between frames: no allocation once the scene's size is reached).
#[derive(Resource, Debug)]
pub struct PhongLightBuffer {
    buffer: LightBuffer,
    records: Vec<GpuLight>,
    header: GpuLightsHeader,
    /// What the last gather found of each local kind, kept for its allocation.
    pushed: Vec<Pushed>,
    /// What the last gather found of each area kind.
    area_pushed: Vec<Pushed>,
    /// The local lights, while they are put in order (see [`order_by_reach`]).
    scratch: Vec<GpuLight>,
    /// The per-light ε of the last gather (`NaN` before the first).
    per_light_epsilon: f32,
    /// The records of the local lights, kept while their components are unchanged.
    caches: BuiltInCaches,
    /// Whether the last gather had a hemisphere light.
    hemisphere: bool,
}

impl Default for PhongLightBuffer {
    fn default() -> Self {
        Self {
            buffer: LightBuffer::new(PHONG_LIGHT_BUFFER),
            records: Vec::new(),
            header: GpuLightsHeader::default(),
            pushed: Vec::new(),
            area_pushed: Vec::new(),
            scratch: Vec::new(),
            per_light_epsilon: f32::NAN,
            caches: BuiltInCaches::default(),
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

/// Whether one of `area_lights` has `flag` (a [`GpuAreaLight`] flag).
fn any_flagged(area_lights: &[GpuAreaLight], flag: u32) -> bool {
    area_lights.iter().any(|light| light.flags & flag != 0)
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

/// Writes each built-in kind's lights into the records, as [`BuiltInLights`] hands them over:
/// those that reach everywhere ([`push_visible`]), then the local ones and the area ones with
/// the per-light `epsilon` ([`push_cached`]).
struct Pusher<'a> {
    records: &'a mut Vec<GpuLight>,
    slots: Slots<'a>,
    epsilon: f32,
    clusters: bool,
    /// How many lights reach everywhere.
    directional: u32,
    /// What was found of each local kind.
    pushed: &'a mut Vec<Pushed>,
    /// What was found of each area kind.
    area_pushed: &'a mut Vec<Pushed>,
}

impl BuiltInVisitor for Pusher<'_> {
    fn everywhere<L: PhongLightKind<Gpu = GpuLight>>(&mut self, lights: &LightQuery<L>) {
        self.directional += push_visible(lights, self.slots, self.records);
    }

    fn local<L: PhongLightKind<Gpu = GpuLight> + Clone + PartialEq>(
        &mut self,
        lights: &TrackedLightQuery<L>,
        cache: &mut RecordCache<L>,
    ) {
        let pushed = self.push_cached(lights, cache);
        self.pushed.push(pushed);
    }

    fn area<L: PhongLightKind<Gpu = GpuAreaLight> + Clone + PartialEq>(
        &mut self,
        lights: &TrackedLightQuery<L>,
        cache: &mut RecordCache<L>,
    ) {
        let pushed = self.push_cached(lights, cache);
        self.area_pushed.push(pushed);
    }
}

impl Pusher<'_> {
    /// [`push_cached`] with this gather's slots, ε and clusters.
    fn push_cached<L: PhongLightKind + Clone + PartialEq>(
        &mut self,
        lights: &TrackedLightQuery<L>,
        cache: &mut RecordCache<L>,
    ) -> Pushed {
        push_cached(
            lights,
            self.slots,
            cache,
            self.records,
            self.epsilon,
            self.clusters,
        )
    }
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
/// sphere ([`PhongLightKind::bounding_sphere`]), which [`clustered`] then finds. The records
/// of every built-in kind are as long as a [`GpuLight`], whose place they take.
fn push_cached<L: PhongLightKind + Clone + PartialEq>(
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
            records.push(bytemuck::cast(record));
        }
    }
    cache.truncate(pushed.lit);
    pushed
}

/// Whether a light of kind `L` that reaches `reach` goes into the clusters: with `clusters`
/// ([`PhongLightCulling::clusters`]), where its kind gives a finite bounding sphere for that
/// reach ([`PhongLightKind::bounding_sphere`]), whatever shadow or cookie it has.
fn has_sphere<L: PhongLightKind>(clusters: bool, record: &L::Gpu, reach: f32) -> bool {
    in_clusters(clusters, reach, || L::bounding_sphere(record, reach))
}

/// Whether a light that reaches `reach` goes into the clusters: with `clusters`, where its
/// reach is finite and `sphere` (its bounding sphere for that reach) finite too.
fn in_clusters(
    clusters: bool,
    reach: f32,
    sphere: impl FnOnce() -> Option<BoundingSphere>,
) -> bool {
    (clusters && reach.is_finite())
        .then(sphere)
        .flatten()
        .is_some_and(|sphere| is_finite_sphere(sphere.center.into(), sphere.radius()))
}

/// Whether a local light's record, as [`push_cached`] wrote it (with its reach), goes
/// into the clusters (as [`has_sphere`] found: the built-in local kinds share their sphere,
/// [`local_sphere`]).
fn clustered(culling: &PhongLightCulling, light: &GpuLight) -> bool {
    in_clusters(culling.clusters, light.reach, || {
        local_sphere(light, light.reach)
    })
}

/// Whether an area light's record, as [`push_cached`] wrote it in a [`GpuLight`]'s place
/// (with its reach), goes into the clusters (as [`has_sphere`] found: the built-in area
/// kinds share their sphere, [`GpuAreaLight::bounding_sphere`]).
fn clustered_area(culling: &PhongLightCulling, record: &GpuLight) -> bool {
    let area = GpuAreaLight::in_record(record);
    in_clusters(culling.clusters, area.reach, || {
        area.bounding_sphere(area.reach)
    })
}

/// Puts one section of lights (the records `pushed` of its kinds, `section`) in the order the
/// shader reads them: those of unlimited reach, then the `clustered` ones, each in their
/// order. Returns those two counts. A section whose lights are all of one sort (the usual
/// case) is already in order; a mixed one is sorted through `scratch`.
fn order_by_reach(
    section: &mut [GpuLight],
    pushed: &[Pushed],
    scratch: &mut Vec<GpuLight>,
    clustered: impl Fn(&GpuLight) -> bool,
) -> [u32; 2] {
    let kept: usize = pushed.iter().map(|kind| kind.kept).sum();
    let clustered_count: usize = pushed.iter().map(|kind| kind.clustered).sum();
    let counts = [kept - clustered_count, clustered_count].map(|count| count as u32);
    if clustered_count == 0 || clustered_count == kept {
        return counts;
    }
    scratch.clear();
    scratch.extend_from_slice(section);
    let unclustered = scratch.iter().filter(|light| !clustered(light));
    let ordered = unclustered.chain(scratch.iter().filter(|light| clustered(light)));
    for (place, light) in section.iter_mut().zip(ordered) {
        *place = *light;
    }
    counts
}

/// What the gather reads besides the light entities: the ambient and hemisphere lights (and
/// the share of each view's Bevy ambient light, under the Bevy-light mirror), ε and
/// the clusters ([`PhongLightCulling`]), the lights of extension kinds that share ε, and this
/// frame's shadow and cookie slots.
#[derive(SystemParam)]
pub struct SceneLighting<'w> {
    ambient: Res<'w, PhongAmbientLight>,
    bevy_ambient: Option<Res<'w, BevyAmbientPerView>>,
    hemisphere: Option<Res<'w, PhongHemisphereLight>>,
    culling: Res<'w, PhongLightCulling>,
    sharing: Res<'w, SharedEpsilonLights>,
    shadows: Res<'w, ShadowSlots>,
    cookies: Res<'w, PhongCookies>,
}

impl SceneLighting<'_> {
    /// Whether any of it changed since the last run, or the hemisphere light came or went
    /// (`had_hemisphere`: whether the last gather had one).
    fn changed(&self, had_hemisphere: bool) -> bool {
        self.ambient.is_changed()
            || self
                .bevy_ambient
                .as_ref()
                .is_some_and(DetectChanges::is_changed)
            || self
                .hemisphere
                .as_ref()
                .is_some_and(DetectChanges::is_changed)
            || self.hemisphere.is_some() != had_hemisphere
            || self.culling.is_changed()
            || self.sharing.is_changed()
            || self.shadows.is_changed()
            || self.cookies.is_changed()
    }

    fn slots(&self) -> Slots<'_> {
        Slots {
            shadows: &self.shadows,
            cookies: &self.cookies,
        }
    }
}

/// Where the gather writes: the light buffer, the GPU buffers it is uploaded to (a message
/// when it grows) and the scene's shader variants (the hemisphere light's and the area
/// lights').
#[derive(SystemParam)]
pub struct LightBufferWrites<'w> {
    state: ResMut<'w, PhongLightBuffer>,
    buffers: ResMut<'w, Assets<ShaderBuffer>>,
    resized: MessageWriter<'w, LightBufferResized>,
    variants: ResMut<'w, SceneVariants>,
}

/// Writes every visible built-in light into [`PhongLightBuffer`], those of finite reach
/// last for the clusters ([`assign_lights_to_clusters`](super::assign_lights_to_clusters)),
/// when any of them, the ambient or hemisphere light or [`PhongLightCulling`] changed (and on
/// the first run); otherwise it touches nothing, so no GPU buffer is uploaded again. When
/// the hemisphere light or the last area light comes or goes, every Phong material is
/// prepared again (with or without its shader variant).
pub fn gather_lights(
    mut lights: BuiltInLights,
    scene: SceneLighting,
    mut writes: LightBufferWrites,
) {
    let lights_changed = lights.changed();
    let state = &mut *writes.state;
    if !lights_changed && !scene.changed(state.hemisphere) && state.capacity() != 0 {
        return;
    }
    state.records.clear();
    let counts = state.push_lights(&lights, &scene);
    let [ambient, hemisphere_up, hemisphere_half_difference] =
        indirect_light(&scene.ambient, scene.hemisphere.as_deref());
    state.header = GpuLightsHeader {
        ambient,
        hemisphere_up,
        bevy_ambient_scale: scene.bevy_ambient.map_or(0.0, |bevy| bevy.scale),
        hemisphere_half_difference,
        ..bytemuck::Zeroable::zeroed()
    };
    for (section, count) in LightSection::ALL.into_iter().zip(counts) {
        *state.header.count_mut(section) = count;
    }
    state.append_cookies(&scene.cookies);
    state.hemisphere = scene.hemisphere.is_some();
    if writes.variants.hemisphere != state.hemisphere {
        writes.variants.hemisphere = state.hemisphere;
    }
    let area_records = state
        .header
        .span(LightSection::Area, LightSection::ClusteredArea);
    let area_lights = !area_records.is_empty();
    if writes.variants.area_lights != area_lights {
        writes.variants.area_lights = area_lights;
    }
    let area_records = GpuAreaLight::in_records(&state.records[area_records]);
    let disk_lights = any_flagged(area_records, GpuAreaLight::DISK);
    if writes.variants.disk_lights != disk_lights {
        writes.variants.disk_lights = disk_lights;
    }
    let fitted_highlights = any_flagged(area_records, GpuAreaLight::FITTED);
    if writes.variants.fitted_highlights != fitted_highlights {
        writes.variants.fitted_highlights = fitted_highlights;
    }
    if state
        .buffer
        .write(&mut writes.buffers, &state.header, &state.records)
    {
        writes.resized.write(LightBufferResized);
    }
}

impl PhongLightBuffer {
    /// Writes the records of `lights` in the order the shader reads them: the directional
    /// lights, the local (point and spot) lights of unlimited reach (every fragment loops over
    /// them), then the clustered ones, shadows and cookies or not (the clusters' loop applies
    /// both), then the area lights the same way. Returns the counts of the five sections, in
    /// [`GpuLightsHeader`]'s order.
    fn push_lights(&mut self, lights: &BuiltInLights, scene: &SceneLighting) -> [u32; 5] {
        let culling = &scene.culling;
        let mut pusher = Pusher {
            records: &mut self.records,
            slots: scene.slots(),
            epsilon: self.per_light_epsilon,
            clusters: culling.clusters,
            directional: 0,
            pushed: &mut self.pushed,
            area_pushed: &mut self.area_pushed,
        };
        lights.visit_everywhere(&mut pusher);
        // The local and area lights, kind by kind, written once in place. ε bounds the sum of
        // what every skipped light leaves out: each of the `count` lit local and area lights
        // (and lights of extension kinds that share ε) gets ε / count. The count is known once they are
        // read, so they are written with the last gather's per-light ε, and written again in
        // a frame where the count changed.
        let first_local = pusher.records.len();
        loop {
            pusher.records.truncate(first_local);
            pusher.pushed.clear();
            pusher.area_pushed.clear();
            lights.visit_local(&mut self.caches, &mut pusher);
            lights.visit_area(&mut self.caches, &mut pusher);
            let lit: usize = pusher
                .pushed
                .iter()
                .chain(pusher.area_pushed.iter())
                .map(|kind| kind.lit)
                .sum();
            let count = lit + scene.sharing.total();
            let per_light_epsilon = culling.epsilon / count.max(1) as f32;
            if per_light_epsilon.to_bits() == pusher.epsilon.to_bits() {
                break;
            }
            pusher.epsilon = per_light_epsilon;
        }
        let directional = pusher.directional;
        self.per_light_epsilon = pusher.epsilon;
        let local_kept: usize = self.pushed.iter().map(|kind| kind.kept).sum();
        let first_area = first_local + local_kept;
        let (local_section, area_section) = self.records[first_local..].split_at_mut(local_kept);
        let [local, clustered_local] =
            order_by_reach(local_section, &self.pushed, &mut self.scratch, |light| {
                clustered(culling, light)
            });
        let [area, clustered_area] = order_by_reach(
            area_section,
            &self.area_pushed,
            &mut self.scratch,
            |light| clustered_area(culling, light),
        );
        debug_assert_eq!(
            self.records.len(),
            first_area + (area + clustered_area) as usize
        );
        [directional, local, clustered_local, area, clustered_area]
    }

    /// Appends the cookies after the lights, as records of a light's size ([`GpuCookie`](
    /// super::gpu_types::GpuCookie)); each light's cookie slot becomes the index of its record
    /// (plus one), where 16 bits hold it.
    fn append_cookies(&mut self, cookies: &PhongCookies) {
        let cookie_first = self.records.len() as u32;
        let header = &self.header;
        // The area lights take no cookie: their records' high half holds their flags.
        let with_cookies = header
            .span(LightSection::Directional, LightSection::ClusteredLocal)
            .end;
        if !cookies.records().is_empty() {
            for record in &mut self.records[..with_cookies] {
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
                record.set_cookie_index(index);
            }
        }
        self.records.extend(
            cookies
                .records()
                .iter()
                .map(|cookie| bytemuck::cast::<_, GpuLight>(*cookie)),
        );
    }
}

#[cfg(test)]
mod tests;
