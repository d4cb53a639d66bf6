//! The per-view light clusters (see [`crate::culling`]): each camera's view cut into
//! clusters, tiles of the screen × slices of depth, each listing the lights of finite reach
//! whose sphere may meet it.
//!
//! A tile is a rectangle of normalized device coordinates (`tiles.x × tiles.y` of them over
//! the view, x fastest); a slice an interval of depth in front of the camera, spaced
//! logarithmically for perspective views and evenly for orthographic ones (see
//! [`DepthSlices`]). The first and last slices reach to the camera and to infinity, so
//! every fragment of the view is in some cluster. A light is listed in a cluster unless its
//! sphere, widened by a margin that covers the shader's rounding, lies wholly outside one of
//! the cluster's six bounding planes: a light that can reach a point of the view is listed
//! in that point's cluster, and a light outside every view's frustum is listed nowhere.
//!
//! The data, after [`GpuClustersHeader`], is `u32` words: one record of [`VIEW_WORDS`] per
//! view, `[key, first, tiles.x, tiles.y, slices, logarithmic, scale, bias]` (`scale` and
//! `bias` as `f32` bits; `first` the word where its cluster records start); then every
//! view's cluster records (x fastest, then y, then slice) of the header's `cluster_words`
//! each ([`cluster_words`]); then the entries they point into. The lights come in slots
//! ([`ClusterSlot`]: the built-in local lights, point and spot, then the built-in area
//! lights, rectangle and disk, then each extension kind's); a cluster record `[s_0, s_1, …, s_K]` (zero-padded) lists slot `k`'s lights as
//! the entries `data[s_k..s_{k+1}]`, each the index of a light in its slot's buffer. With
//! the two built-in slots a record is `[s_0, s_1, s_2, 0]`: one 16-byte texel.

use super::gpu_types::GpuClustersHeader;
use crate::light_kind::{GpuAreaLight, GpuLight};
use bevy::math::{DMat4, DVec3, DVec4, Mat4, UVec2, Vec3};
use sphere_tree::{LightAt, SphereTree};
use std::ops::{Range, RangeInclusive};

/// `u32` words per view record.
pub const VIEW_WORDS: usize = GpuClustersHeader::VIEW_WORDS as usize;

/// How a view's depth `d` (world units in front of the camera, view space `-z`) is cut into
/// slices: slice `floor(f(d) · scale + bias)`, clamped to `0..count`, where `f` is `log2` for
/// logarithmic slices and the identity otherwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthSlices {
    /// Number of slices, at least 1.
    pub count: u32,
    /// Whether `f` is `log2` (perspective views).
    pub logarithmic: bool,
    /// Slices per unit of `f(d)`.
    pub scale: f32,
    /// The slice of `f(d) = 0`.
    pub bias: f32,
}

impl DepthSlices {
    /// One slice, for views whose depth range is unknown.
    pub const ONE: Self = Self {
        count: 1,
        logarithmic: false,
        scale: 0.0,
        bias: 0.0,
    };

    /// `count` slices from `near` to `far`, each as many times deeper than the one before
    /// (a perspective view's); [`Self::ONE`] unless `0 < near < far`, both finite.
    pub fn logarithmic(count: u32, near: f32, far: f32) -> Self {
        let (near, far) = (f64::from(near), f64::from(far));
        if !(near > 0.0 && far > near && far.is_finite()) || count <= 1 {
            return Self::ONE;
        }
        let scale = f64::from(count) / (far / near).log2();
        Self {
            count,
            logarithmic: true,
            scale: scale as f32,
            bias: (-near.log2() * scale) as f32,
        }
    }

    /// `count` slices of equal depth from `near` to `far` (an orthographic view's);
    /// [`Self::ONE`] unless `near < far`, both finite.
    pub fn linear(count: u32, near: f32, far: f32) -> Self {
        let (near, far) = (f64::from(near), f64::from(far));
        if !(far > near && near.is_finite() && far.is_finite()) || count <= 1 {
            return Self::ONE;
        }
        let scale = f64::from(count) / (far - near);
        Self {
            count,
            logarithmic: false,
            scale: scale as f32,
            bias: (-near * scale) as f32,
        }
    }

    /// The slice that holds depth `depth`, computed as the shader does but in `f64`.
    fn slice_of(&self, depth: f64) -> u32 {
        let f = if self.logarithmic {
            // The shader takes log2 of max(d, 1e-30): far below any near plane.
            depth.max(1e-30).log2()
        } else {
            depth
        };
        let slice = (f * f64::from(self.scale) + f64::from(self.bias)).floor();
        slice.clamp(0.0, f64::from(self.count - 1)) as u32
    }
}

/// One view as its clusters are built: a camera's transform and projection as Bevy's view
/// uniform holds them, and how it is cut.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClusterView {
    /// The view's key ([`crate::view_key::view_key`]).
    pub key: u32,
    /// World space to view space (Bevy's `view.view_from_world`).
    pub view_from_world: Mat4,
    /// View space to clip space without temporal jitter, as in Bevy's
    /// `view.unjittered_clip_from_world`.
    pub clip_from_view: Mat4,
    /// Tiles across and down the view, each at least 1.
    pub tiles: UVec2,
    /// The depth slices.
    pub slices: DepthSlices,
}

impl ClusterView {
    /// Number of clusters.
    fn cluster_count(&self) -> usize {
        (self.tiles.x * self.tiles.y * self.slices.count) as usize
    }

    /// The view's record in the cluster data, its clusters' records starting at word `first`.
    fn record(&self, first: u32) -> [u32; VIEW_WORDS] {
        [
            self.key,
            first,
            self.tiles.x,
            self.tiles.y,
            self.slices.count,
            u32::from(self.slices.logarithmic),
            self.slices.scale.to_bits(),
            self.slices.bias.to_bits(),
        ]
    }
}

/// Leaves one of each set of identical views in `views`, and none of the views whose keys
/// collide while they differ (their fragments then loop over every light of finite reach,
/// see [`crate::view_key`]). Returns how many views were left out for a collision.
pub fn keep_distinct_views(views: &mut Vec<ClusterView>) -> usize {
    views.sort_by_key(|view| view.key);
    let mut kept: Vec<ClusterView> = Vec::with_capacity(views.len());
    let mut left_out = 0;
    for group in views.chunk_by(|a, b| a.key == b.key) {
        if group.iter().all(|view| view == &group[0]) {
            kept.push(group[0]);
        } else {
            left_out += group.len();
        }
    }
    *views = kept;
    left_out
}

/// A view's cluster boundaries in view space, for testing spheres against them.
struct ViewBounds {
    view_from_world: DMat4,
    /// The planes `ndc.x = -1 + 2i / tiles.x` for `i` in `0..=tiles.x`, each `(n, w)` with
    /// `n` a unit vector: `n · p + w ≥ 0` where `ndc.x` is at least the plane's.
    columns: Vec<DVec4>,
    /// The same for `ndc.y` and `tiles.y`.
    rows: Vec<DVec4>,
    /// The plane `w = 0` of clip space, normalized, `n · p + w > 0` in front of the camera
    /// (zero for an orthographic view, where every point is in front). The tile planes are
    /// met again behind the camera, where no fragment is: this plane leaves that out.
    front: DVec4,
    slices: DepthSlices,
    /// The camera's distance from the world origin, for the rounding margin.
    camera_distance: f64,
}

impl ViewBounds {
    fn new(view: &ClusterView) -> Self {
        let view_from_world = view.view_from_world.as_dmat4();
        let clip_from_view = view.clip_from_view.as_dmat4();
        let world_from_view = view_from_world.inverse();
        Self {
            view_from_world,
            columns: boundary_planes(&clip_from_view, 0, view.tiles.x),
            rows: boundary_planes(&clip_from_view, 1, view.tiles.y),
            front: normalized(clip_from_view.row(3)),
            slices: view.slices,
            camera_distance: world_from_view.w_axis.truncate().length(),
        }
    }

    /// The clusters (columns, rows, slices) that a sphere at `center` (world space) of
    /// radius `radius` may meet; `None` when it meets none.
    fn clusters_met(&self, center: Vec3, radius: f32) -> Option<[RangeInclusive<u32>; 3]> {
        let world_center = center.as_dvec3();
        let center = self.view_from_world.transform_point3(world_center);
        let radius = f64::from(radius);
        // The shader finds a fragment's cluster in f32 from Bevy's f32 matrices: its view
        // space position is off by a few units of f32 rounding of the positions involved,
        // its tile and slice by a few roundings of those. The margin is far above both.
        let reach = radius
            + 1e-4 * (center.length() + radius)
            + 1e-6 * (world_center.length() + self.camera_distance);
        let front = self.front.truncate().dot(center) + self.front.w;
        if front < -reach {
            return None;
        }
        // Wholly in front of the camera (everywhere, for an orthographic view), the sphere
        // is beyond the tile planes in their order: see `tiles_met`.
        let in_front = self.front == DVec4::ZERO || front > reach;
        let columns = tiles_met(&self.columns, center, reach, in_front)?;
        let rows = tiles_met(&self.rows, center, reach, in_front)?;
        let depth = -center.z;
        let slices = self.slices.slice_of(depth - reach)..=self.slices.slice_of(depth + reach);
        Some([columns, rows, slices])
    }

    /// Whether a node of the light tree, a sphere at `center` of `radius` holding the
    /// spheres of the lights below it, may hold a light that meets a cluster: its sphere,
    /// widened by 1 % and a thousandth of a unit (more than the rounding margin of
    /// [`Self::clusters_met`] grows by between a light and a sphere around it, and the `f32`
    /// rounding of the node's centre), meets one.
    fn may_meet(&self, center: DVec3, radius: f64) -> bool {
        let radius = radius * 1.01 + 1e-3 + 1e-6 * center.length();
        self.clusters_met(center.as_vec3(), radius as f32).is_some()
    }
}

/// The planes of `ndc[axis] = -1 + 2i / tiles` in view space, for `i` in `0..=tiles`,
/// normalized (a plane of zero normal stays zero, and meets every sphere).
fn boundary_planes(clip_from_view: &DMat4, axis: usize, tiles: u32) -> Vec<DVec4> {
    let (row, w) = (clip_from_view.row(axis), clip_from_view.row(3));
    (0..=tiles)
        .map(|i| {
            let ndc = -1.0 + 2.0 * f64::from(i) / f64::from(tiles);
            // ndc ≥ x  ⇔  row · p - x · (w · p) ≥ 0, where w · p > 0 (in front of the camera).
            normalized(row - ndc * w)
        })
        .collect()
}

/// `plane` scaled so that its normal is a unit vector; zero if its normal is zero.
fn normalized(plane: DVec4) -> DVec4 {
    let length = plane.truncate().length();
    if length > 0.0 {
        plane / length
    } else {
        DVec4::ZERO
    }
}

/// The tiles between consecutive `planes` that a sphere at `center` reaching `reach` meets:
/// tile `i` lies on the inner side of plane `i` and the outer side of plane `i + 1`. Each
/// plane's distance is computed once, and compared as the boundary of both its tiles.
///
/// With the sphere wholly `in_front` of the camera, the planes' inner sides are nested (the
/// points in front of the camera with `ndc ≥ x` for a larger `x` are fewer), so once the
/// sphere is wholly outside one plane it is outside every later one: the scan stops there.
fn tiles_met(
    planes: &[DVec4],
    center: DVec3,
    reach: f64,
    in_front: bool,
) -> Option<RangeInclusive<u32>> {
    let distance = |plane: &DVec4| plane.truncate().dot(center) + plane.w;
    let (first_plane, rest) = planes.split_first()?;
    let mut inside_left = distance(first_plane) >= -reach;
    let mut met = None::<(u32, u32)>;
    for (tile, right) in rest.iter().enumerate() {
        if in_front && !inside_left {
            break;
        }
        let right = distance(right);
        if inside_left && right <= reach {
            let tile = tile as u32;
            met = Some(met.map_or((tile, tile), |(first, _)| (first, tile)));
        }
        inside_left = right >= -reach;
    }
    met.map(|(first, last)| first..=last)
}

/// The lights of one cluster slot, as a build is given them: slot 0 holds the built-in
/// local (point and spot) lights, slot 1 the built-in area lights, each later slot an
/// extension kind's lights
/// ([`crate::extension::PhongLightKind::bounding_sphere`]).
#[derive(Clone, Copy, Debug)]
pub struct ClusterSlot<'a> {
    /// The index the first sphere's light has in its buffer; the others follow it.
    pub first: u32,
    /// Each light's bounding sphere, as bits ([`sphere_bits`]).
    pub spheres: &'a [[u32; 4]],
}

/// Every view's clusters as last built, and the scratch space they are built in (kept
/// between frames: no allocation once the scene's size is reached).
#[derive(Debug, Default)]
pub struct LightClusters {
    header: GpuClustersHeader,
    data: Vec<u32>,
    /// (the word of a cluster record that counts, then places, a slot's entries; the entry).
    pairs: Vec<(u32, u32)>,
    built_from: BuiltFrom,
    /// The lights' spheres in a tree, to find those near a view.
    tree: SphereTree,
    /// The lights near the view being built.
    near: Vec<LightAt>,
}

/// The input of a build, compared with the next one: the same input gives the same
/// clusters, which are then kept as they are.
#[derive(Debug, Default)]
struct BuiltFrom {
    views: Vec<ClusterView>,
    /// Every slot's spheres, slot after slot.
    spheres: Vec<[u32; 4]>,
    /// Each slot's first index and number of spheres.
    slots: Vec<(u32, usize)>,
}

impl BuiltFrom {
    fn is(&self, views: &[ClusterView], slots: &[ClusterSlot]) -> bool {
        self.views == views && self.has_spheres_of(slots)
    }

    /// Whether `slots` are the spheres of the last build.
    fn has_spheres_of(&self, slots: &[ClusterSlot]) -> bool {
        let mut spheres = self.spheres.as_slice();
        self.slots.len() == slots.len()
            && self.slots.iter().zip(slots).all(|(&(first, count), slot)| {
                let (these, rest) = spheres.split_at(count.min(spheres.len()));
                spheres = rest;
                first == slot.first && these == slot.spheres
            })
    }

    fn set_views(&mut self, views: &[ClusterView]) {
        self.views.clear();
        self.views.extend_from_slice(views);
    }

    fn set_spheres(&mut self, slots: &[ClusterSlot]) {
        self.spheres.clear();
        self.slots.clear();
        for slot in slots {
            self.spheres.extend_from_slice(slot.spheres);
            self.slots.push((slot.first, slot.spheres.len()));
        }
    }

    /// Every light's place, centre and radius (in `f64`), slot after slot.
    fn lights(&self) -> impl Iterator<Item = (LightAt, DVec3, f64)> + '_ {
        self.slots
            .iter()
            .enumerate()
            .flat_map(move |(slot, &(_, count))| {
                (0..count as u32).map(move |index| (slot as u32, index))
            })
            .zip(&self.spheres)
            .map(|((slot, index), bits)| {
                let (center, radius) = sphere(bits);
                (
                    LightAt { slot, index },
                    center.as_dvec3(),
                    f64::from(radius),
                )
            })
    }
}

/// A sphere at `center` of radius `radius`, as bits: what a [`ClusterSlot`] holds.
pub fn sphere_bits(center: Vec3, radius: f32) -> [u32; 4] {
    let [x, y, z] = center.to_array();
    [x, y, z, radius].map(f32::to_bits)
}

/// A built-in point or spot light's sphere of reach, as bits.
pub fn light_sphere_bits(light: &GpuLight) -> [u32; 4] {
    sphere_bits(Vec3::from(light.position), light.reach)
}

/// A built-in area light's sphere of reach, as bits: its reach out from its shape ([`GpuAreaLight::bounding_sphere`]).
pub fn area_light_sphere_bits(area: &GpuAreaLight) -> [u32; 4] {
    area.bounding_sphere(area.reach).map_or_else(
        || sphere_bits(Vec3::from(area.center), f32::MAX),
        |sphere| sphere_bits(sphere.center.into(), sphere.radius()),
    )
}

/// The center and radius of a sphere from [`sphere_bits`].
fn sphere(bits: &[u32; 4]) -> (Vec3, f32) {
    let [x, y, z, radius] = bits.map(f32::from_bits);
    (Vec3::new(x, y, z), radius)
}

/// Whether a sphere at `center` of radius `radius` is finite, so that clusters can hold it.
pub fn is_finite_sphere(center: Vec3, radius: f32) -> bool {
    radius < f32::MAX && (center - radius).is_finite() && (center + radius).is_finite()
}

/// `u32` words of each cluster record for `slots` slots: the start of each slot's entries
/// and the end of the last, padded to whole 16-byte texels.
pub fn cluster_words(slots: usize) -> usize {
    (slots + 1).div_ceil(4) * 4
}

impl LightClusters {
    /// How many views the data holds.
    pub fn header(&self) -> &GpuClustersHeader {
        &self.header
    }

    /// The view records, the cluster records, then the light indices they point into.
    pub fn data(&self) -> &[u32] {
        &self.data
    }

    /// Lists the lights of every slot (every sphere finite: [`is_finite_sphere`]) in the
    /// clusters of each of `views` that they may meet. Returns `false`, keeping the clusters
    /// as they are, when these are the views and spheres of the last build. With no light or
    /// no view there is no cluster: the header says 0 views.
    pub fn build(&mut self, views: &[ClusterView], slots: &[ClusterSlot]) -> bool {
        if self.built_from.is(views, slots) {
            return false;
        }
        if !self.built_from.has_spheres_of(slots) {
            self.built_from.set_spheres(slots);
            self.tree.build(self.built_from.lights());
        }
        self.built_from.set_views(views);
        self.fill();
        true
    }

    /// [`Self::build`] for `views` with the spheres of the last build (the lights did not
    /// change): only the views are compared, and only the lights that the tree finds near
    /// each view are tested against its clusters.
    pub fn build_views(&mut self, views: &[ClusterView]) -> bool {
        if self.built_from.views == views {
            return false;
        }
        self.built_from.set_views(views);
        self.fill();
        true
    }

    /// Builds the clusters of the views and spheres in `built_from`.
    fn fill(&mut self) {
        self.data.clear();
        self.pairs.clear();
        let BuiltFrom {
            views,
            spheres,
            slots,
        } = &self.built_from;
        let words = cluster_words(slots.len());
        if spheres.is_empty() || views.is_empty() {
            self.header = GpuClustersHeader::EMPTY;
            return;
        }
        self.header = GpuClustersHeader {
            view_count: views.len() as u32,
            cluster_words: words as u32,
            ..GpuClustersHeader::EMPTY
        };

        // The view records, each pointing at its cluster records, which follow them.
        let mut first = views.len() * VIEW_WORDS;
        for view in views {
            self.data.extend(view.record(first as u32));
            first += view.cluster_count() * words;
        }
        let records_end = first;
        self.data.resize(records_end, 0);

        let records = views.len() * VIEW_WORDS..records_end;
        let slot_count = slots.len();
        self.count_entries(words);
        place_entries(&mut self.data, &self.pairs, records, words, slot_count);
    }

    /// Counts each cluster's entries of slot k in its word k of [`Self::data`], and notes
    /// every (that word, entry) pair: per view, slot by slot, each slot's lights in order
    /// (those the tree finds near the view).
    fn count_entries(&mut self, words: usize) {
        let BuiltFrom {
            views,
            spheres,
            slots,
        } = &self.built_from;
        let slot_starts: Vec<usize> = slots
            .iter()
            .scan(0, |start, &(_, count)| {
                let this = *start;
                *start += count;
                Some(this)
            })
            .collect();
        let (data, pairs, near) = (&mut self.data, &mut self.pairs, &mut self.near);
        for (view_index, view) in views.iter().enumerate() {
            let bounds = ViewBounds::new(view);
            near.clear();
            self.tree.visit(
                |center, radius| bounds.may_meet(center, radius),
                |at| near.push(at),
            );
            near.sort_unstable();
            let view_first = data[view_index * VIEW_WORDS + 1] as usize;
            let (columns, rows) = (view.tiles.x as usize, view.tiles.y as usize);
            for &LightAt { slot: k, index } in near.iter() {
                let (k, index) = (k as usize, index as usize);
                let entry = slots[k].0 + index as u32;
                let (center, radius) = sphere(&spheres[slot_starts[k] + index]);
                let Some([xs, ys, slices]) = bounds.clusters_met(center, radius) else {
                    continue;
                };
                for slice in slices {
                    for y in ys.clone() {
                        let row = (slice as usize * rows + y as usize) * columns;
                        for x in xs.clone() {
                            let word = view_first + words * (row + x as usize) + k;
                            data[word] += 1;
                            pairs.push((word as u32, entry));
                        }
                    }
                }
            }
        }
    }
}

/// Writes the entries of `pairs` after the cluster records (`data[records]`, `words` words
/// each, whose first `slot_count` words hold their slots' counts), each cluster's slot by
/// slot (a counting sort), and leaves in each record its slots' starts and its end.
fn place_entries(
    data: &mut Vec<u32>,
    pairs: &[(u32, u32)],
    records: Range<usize>,
    words: usize,
    slot_count: usize,
) {
    let records_end = records.end;
    // Turn each count into a write cursor at its slot's start; word K holds the end.
    let mut next = records_end as u32;
    for record in data[records.clone()].chunks_exact_mut(words) {
        for word in &mut record[..slot_count] {
            let count = *word;
            *word = next;
            next += count;
        }
        record[slot_count] = next;
    }
    data.resize(next as usize, 0);
    for &(word, entry) in pairs {
        let cursor = &mut data[word as usize];
        let slot = *cursor as usize;
        *cursor += 1;
        data[slot] = entry;
    }
    // Each cursor has moved to the end of its slot, the start of the next: move them back.
    let mut start = records_end as u32;
    for record in data[records].chunks_exact_mut(words) {
        record.copy_within(0..slot_count - 1, 1);
        record[0] = start;
        start = record[slot_count];
    }
}

mod sphere_tree;

#[cfg(test)]
mod tests;
