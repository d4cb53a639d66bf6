use super::*;
use bevy::math::{Quat, UVec3, Vec2, Vec4Swizzles};
use std::ops::Range;

/// `u32` words per cluster record with the two built-in slots.
const CLUSTER_WORDS: usize = 4;

impl LightClusters {
    /// Builds the clusters of the built-in point lights `lights[points]` and spot lights
    /// `lights[spots]`, as `assign_lights_to_clusters` does.
    fn build_lights(
        &mut self,
        views: &[ClusterView],
        lights: &[GpuLight],
        points: Range<usize>,
        spots: Range<usize>,
    ) -> bool {
        let spheres = |range: &Range<usize>| -> Vec<[u32; 4]> {
            lights[range.clone()]
                .iter()
                .map(light_sphere_bits)
                .collect()
        };
        let (point_spheres, spot_spheres) = (spheres(&points), spheres(&spots));
        let slots = [
            ClusterSlot {
                first: points.start as u32,
                spheres: &point_spheres,
            },
            ClusterSlot {
                first: spots.start as u32,
                spheres: &spot_spheres,
            },
        ];
        self.build(views, &slots)
    }
}

fn point(position: Vec3, reach: f32) -> GpuLight {
    GpuLight {
        position: position.to_array(),
        reach,
        ..GpuLight::default()
    }
}

/// A perspective camera at `eye` looking at `target` (Bevy's projection: infinite reverse
/// z, vertical field of view `fov`), `near` to `far`, cut as Bevy cuts its own clusters.
fn perspective_view(
    eye: Vec3,
    target: Vec3,
    fov: f32,
    aspect: f32,
    near: f32,
    far: f32,
) -> ClusterView {
    let world_from_view = glam::camera::rh::view::look_at_mat4(eye, target, Vec3::Y).inverse();
    ClusterView {
        key: 0,
        view_from_world: world_from_view.inverse(),
        clip_from_view: glam::camera::rh::proj::directx::perspective_infinite_reverse(
            fov, aspect, near,
        ),
        tiles: UVec2::new(16, 9),
        slices: DepthSlices::logarithmic(24, near, far),
    }
}

fn orthographic_view(eye: Vec3, target: Vec3) -> ClusterView {
    let world_from_view = glam::camera::rh::view::look_at_mat4(eye, target, Vec3::Y).inverse();
    ClusterView {
        key: 0,
        view_from_world: world_from_view.inverse(),
        // Bevy's orthographic projection: reverse z, near 0, far 1000.
        clip_from_view: glam::camera::rh::proj::directx::orthographic(
            -8.0, 8.0, -4.5, 4.5, 1000.0, 0.0,
        ),
        tiles: UVec2::new(8, 5),
        slices: DepthSlices::linear(16, 0.0, 1000.0),
    }
}

/// The lights listed in the cluster that holds `position` in view `view_index`, found as
/// the shader finds them (in f32, from the view's f32 matrices).
fn lights_at(clusters: &LightClusters, view_index: usize, position: Vec3) -> Vec<u32> {
    let data = clusters.data();
    let words = &data[view_index * VIEW_WORDS..(view_index + 1) * VIEW_WORDS];
    let view = clusters.built_from.views[view_index];
    let p = position.extend(1.0);
    let in_view = view.view_from_world * p;
    let clip = (view.clip_from_view * view.view_from_world) * p;
    let ndc = clip.xy() / clip.w;
    let tiles = UVec2::new(words[2], words[3]);
    let tile = ((ndc * 0.5 + 0.5) * tiles.as_vec2())
        .max(Vec2::ZERO)
        .as_uvec2()
        .min(tiles - 1);
    let depth = -in_view.z;
    let (scale, bias) = (f32::from_bits(words[6]), f32::from_bits(words[7]));
    let f = if words[5] == 1 {
        depth.max(1e-30).log2()
    } else {
        depth
    };
    let slice = ((f * scale + bias).max(0.0) as u32).min(words[4] - 1);
    let cluster = UVec3::new(tile.x, tile.y, slice);
    let record = words[1] as usize
        + CLUSTER_WORDS * (cluster.x + tiles.x * (cluster.y + tiles.y * cluster.z)) as usize;
    data[data[record] as usize..data[record + 2] as usize].to_vec()
}

/// Every light listed in some cluster of some view.
fn listed_anywhere(clusters: &LightClusters) -> std::collections::BTreeSet<u32> {
    let data = clusters.data();
    let mut listed = std::collections::BTreeSet::new();
    for (view_index, view) in clusters.built_from.views.iter().enumerate() {
        let first = data[view_index * VIEW_WORDS + 1] as usize;
        let records = &data[first..first + view.cluster_count() * CLUSTER_WORDS];
        for record in records.chunks_exact(CLUSTER_WORDS) {
            listed.extend(&data[record[0] as usize..record[2] as usize]);
        }
    }
    listed
}

/// Whether a fragment at `position` can be drawn in `view`: in front of the near plane and
/// inside the view's rectangle.
fn is_drawn(view: &ClusterView, position: Vec3, near: f32) -> bool {
    let in_view = view.view_from_world * position.extend(1.0);
    let clip = view.clip_from_view * in_view;
    let ndc = clip.xy() / clip.w;
    clip.w > 0.0 && -in_view.z >= near && ndc.abs().max_element() <= 1.0
}

/// A deterministic scatter in the unit cube, `[0, 1)³`.
fn scatter(i: usize) -> Vec3 {
    let t = i as f32;
    Vec3::new(
        (t * 0.618_034).fract(),
        (t * 0.754_878).fract(),
        (t * 0.569_840).fract(),
    )
}

/// A point in the unit ball for index `i`.
fn in_unit_ball(i: usize) -> Vec3 {
    let s = scatter(i + 7);
    let direction = Quat::from_euler(
        bevy::math::EulerRot::YXZ,
        s.x * std::f32::consts::TAU,
        s.y * std::f32::consts::PI,
        0.0,
    ) * Vec3::Z;
    direction * s.z.cbrt()
}

/// Checks that every light of `lights` is listed in the cluster of every point of its
/// sphere that `view` draws, over `samples` points per light. Returns how many points
/// were drawn.
fn assert_every_reached_point_lists_its_light(
    clusters: &LightClusters,
    view_index: usize,
    near: f32,
    lights: &[GpuLight],
    samples: usize,
) -> usize {
    let view = clusters.built_from.views[view_index];
    let mut drawn = 0;
    for (index, light) in lights.iter().enumerate() {
        for sample in 0..samples {
            let position = Vec3::from(light.position) + in_unit_ball(sample) * light.reach;
            if !is_drawn(&view, position, near) {
                continue;
            }
            drawn += 1;
            assert!(
                lights_at(clusters, view_index, position).contains(&(index as u32)),
                "light {index} at {:?} (reach {}) missing at {position}",
                light.position,
                light.reach
            );
        }
    }
    drawn
}

fn scattered_lights(count: usize, spread: f32, center: Vec3) -> Vec<GpuLight> {
    (0..count)
        .map(|i| {
            let position = center + (scatter(i) - 0.5) * spread;
            point(position, 0.3 + (i as f32 * 0.13).fract() * 3.0)
        })
        .collect()
}

#[test]
fn every_point_a_light_reaches_in_a_view_lists_that_light() {
    let near = 0.1;
    let views = [
        perspective_view(
            Vec3::new(0.0, 4.0, 12.0),
            Vec3::ZERO,
            0.8,
            16.0 / 9.0,
            near,
            1000.0,
        ),
        perspective_view(
            Vec3::new(-9.0, 2.0, -3.0),
            Vec3::new(1.0, 0.0, 2.0),
            1.4,
            1.0,
            near,
            50.0,
        ),
        orthographic_view(Vec3::new(3.0, 20.0, 0.5), Vec3::ZERO),
    ];
    let lights = scattered_lights(300, 24.0, Vec3::ZERO);
    let mut clusters = LightClusters::default();
    assert!(clusters.build_lights(&views, &lights, 0..200, 200..300));
    for view_index in 0..views.len() {
        let drawn =
            assert_every_reached_point_lists_its_light(&clusters, view_index, near, &lights, 200);
        assert!(
            drawn > 10_000,
            "view {view_index}: only {drawn} points drawn"
        );
    }
}

#[test]
fn lights_just_outside_the_frustum_that_reach_into_it_are_listed_and_the_rest_are_not() {
    let near = 0.1;
    let eye = Vec3::new(0.0, 0.0, 10.0);
    let view = perspective_view(eye, Vec3::ZERO, 0.8, 1.0, near, 100.0);
    // The frustum's right edge at depth 10 (z = 0) is at x = 10 · tan(0.4).
    let edge = 10.0 * 0.4f32.tan();
    let reaching_in = point(Vec3::new(edge + 0.5, 0.0, 0.0), 1.0);
    let staying_out = point(Vec3::new(edge + 2.0, 0.0, 0.0), 1.0);
    let behind = point(eye + Vec3::new(0.0, 0.0, 3.0), 2.0);
    let around_the_camera = point(eye + Vec3::new(0.0, 0.0, 0.5), 2.0);
    let straddling_near = point(eye - Vec3::new(0.0, 0.0, near), 0.05);
    let lights = [
        reaching_in,
        staying_out,
        behind,
        around_the_camera,
        straddling_near,
    ];
    let mut clusters = LightClusters::default();
    clusters.build_lights(&[view], &lights, 0..5, 5..5);
    let listed = listed_anywhere(&clusters);
    let listed_anywhere = |index: u32| listed.contains(&index);
    assert!(
        listed_anywhere(0),
        "a light reaching into the view is listed"
    );
    assert!(
        !listed_anywhere(1),
        "a light wholly outside the view is not"
    );
    assert!(
        !listed_anywhere(2),
        "a light wholly behind the camera is not"
    );
    assert!(listed_anywhere(3), "a light around the camera is");
    assert!(listed_anywhere(4), "a light straddling the near plane is");
    assert_every_reached_point_lists_its_light(&clusters, 0, near, &lights, 2_000);
    assert!(lights_at(&clusters, 0, Vec3::new(edge - 0.1, 0.0, 0.0)).contains(&0));
    // The camera inside a light: every tile's nearest cluster lists it.
    let tiles = (view.tiles.x * view.tiles.y) as usize;
    let nearest = &clusters.data()[VIEW_WORDS..VIEW_WORDS + tiles * CLUSTER_WORDS];
    assert!(
        nearest
            .chunks_exact(CLUSTER_WORDS)
            .all(|record| { clusters.data()[record[0] as usize..record[2] as usize].contains(&3) })
    );
}

#[test]
fn far_flung_lights_are_listed_only_where_they_reach() {
    let near = 0.1;
    let view = perspective_view(Vec3::new(0.0, 2.0, 8.0), Vec3::ZERO, 0.8, 1.5, near, 1000.0);
    let mut lights = scattered_lights(50, 8.0, Vec3::ZERO);
    let (mut aside, mut ahead, mut reaching_back) = (Vec::new(), Vec::new(), Vec::new());
    for far in [1e4, 1e30] {
        for direction in [Vec3::X, Vec3::Y] {
            aside.push(lights.len() as u32);
            lights.push(point(direction * far, 4.0));
        }
        ahead.push(lights.len() as u32);
        lights.push(point(Vec3::NEG_Z * far, 4.0));
        reaching_back.push(lights.len() as u32);
        lights.push(point(Vec3::NEG_Z * far, far));
    }
    let mut clusters = LightClusters::default();
    clusters.build_lights(
        &[view],
        &lights,
        0..lights.len(),
        lights.len()..lights.len(),
    );
    assert_every_reached_point_lists_its_light(&clusters, 0, near, &lights[..50], 300);
    let all_listed = listed_anywhere(&clusters);
    let listed = |index: &u32| all_listed.contains(index);
    assert!(
        !aside.iter().any(listed),
        "lights off to the side are in no cluster"
    );
    // Lights far ahead are in the last slice, which reaches to infinity: not where the
    // field is.
    assert!(ahead.iter().all(listed));
    let at_origin = lights_at(&clusters, 0, Vec3::ZERO);
    assert!(!ahead.iter().any(|index| at_origin.contains(index)));
    assert!(reaching_back.iter().all(|index| at_origin.contains(index)));
}

#[test]
fn a_light_is_listed_only_in_the_views_it_reaches() {
    let near = 0.1;
    let left = perspective_view(
        Vec3::new(-50.0, 2.0, 8.0),
        Vec3::new(-50.0, 0.0, 0.0),
        0.8,
        1.0,
        near,
        100.0,
    );
    let right = perspective_view(
        Vec3::new(50.0, 2.0, 8.0),
        Vec3::new(50.0, 0.0, 0.0),
        0.8,
        1.0,
        near,
        100.0,
    );
    let lights = [
        point(Vec3::new(-50.0, 0.0, 0.0), 2.0),
        point(Vec3::new(50.0, 0.0, 0.0), 2.0),
    ];
    let mut clusters = LightClusters::default();
    clusters.build_lights(&[left, right], &lights, 0..2, 2..2);
    assert_eq!(lights_at(&clusters, 0, Vec3::new(-50.0, 0.0, 0.0)), vec![0]);
    assert_eq!(lights_at(&clusters, 1, Vec3::new(50.0, 0.0, 0.0)), vec![1]);
    assert_eq!(clusters.header().view_count, 2);
}

#[test]
fn clusters_list_point_lights_before_spot_lights() {
    let view = perspective_view(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 0.8, 1.0, 0.1, 100.0);
    let lights = [
        point(Vec3::ZERO, 1.0),
        point(Vec3::X * 0.2, 1.0),
        point(Vec3::Y * 0.2, 1.0),
    ];
    let mut clusters = LightClusters::default();
    clusters.build_lights(&[view], &lights, 0..1, 1..3);
    let data = clusters.data();
    let records = &data[VIEW_WORDS..VIEW_WORDS + view.cluster_count() * CLUSTER_WORDS];
    let mut spots_seen = 0;
    for record in records.chunks_exact(CLUSTER_WORDS) {
        let record: [u32; 4] = record.try_into().unwrap();
        let [first, spot, end, unused] = record.map(|word| word as usize);
        assert_eq!(unused, 0);
        assert!(data[first..spot].iter().all(|&index| index == 0));
        assert!(data[spot..end].iter().all(|&index| index > 0));
        spots_seen += end - spot;
    }
    assert!(spots_seen > 0);
}

#[test]
fn each_slot_lists_its_lights_in_its_own_range() {
    let view = perspective_view(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 0.8, 1.0, 0.1, 100.0);
    // Three extension kinds beside the built-in slots: 5 slots, 8 words a record. Each slot
    // has one light at the origin and one far off to the side, which no cluster lists.
    let near = sphere_bits(Vec3::ZERO, 1.0);
    let far = sphere_bits(Vec3::X * 1000.0, 1.0);
    let spheres = [near, far];
    let slots: Vec<ClusterSlot> = [10, 20, 0, 7, 3]
        .into_iter()
        .map(|first| ClusterSlot {
            first,
            spheres: &spheres,
        })
        .collect();
    let mut clusters = LightClusters::default();
    assert!(clusters.build(&[view], &slots));
    assert_eq!(clusters.header().cluster_words, 8);
    assert_eq!(cluster_words(2), 4, "the built-in slots alone: one texel");
    assert_eq!(cluster_words(3), 4, "and one extension kind");
    let data = clusters.data();
    let records = &data[VIEW_WORDS..VIEW_WORDS + view.cluster_count() * 8];
    let mut met = 0;
    for record in records.chunks_exact(8) {
        assert_eq!(record[6..], [0, 0], "padding");
        for (k, slot) in slots.iter().enumerate() {
            let entries = &data[record[k] as usize..record[k + 1] as usize];
            assert!(entries.len() <= 1, "slot {k} lists its far light nowhere");
            assert!(entries.iter().all(|&entry| entry == slot.first));
            met += entries.len();
        }
    }
    assert!(met >= 5, "each slot's near light is listed somewhere");
    let origin = lights_in_slots(&clusters, Vec3::ZERO, 5);
    assert_eq!(origin, [vec![10], vec![20], vec![0], vec![7], vec![3]]);
}

/// Each slot's entries in the cluster that holds `position` in view 0.
fn lights_in_slots(clusters: &LightClusters, position: Vec3, slots: usize) -> Vec<Vec<u32>> {
    let data = clusters.data();
    let words = clusters.header().cluster_words as usize;
    let view = clusters.built_from.views[0];
    let clip = (view.clip_from_view * view.view_from_world) * position.extend(1.0);
    let ndc = clip.xy() / clip.w;
    let tile = ((ndc * 0.5 + 0.5) * view.tiles.as_vec2()).as_uvec2();
    let depth = -(view.view_from_world * position.extend(1.0)).z;
    let slice = view.slices.slice_of(f64::from(depth));
    let index = tile.x + view.tiles.x * (tile.y + view.tiles.y * slice);
    let record = &data[data[1] as usize + words * index as usize..][..words];
    (0..slots)
        .map(|k| data[record[k] as usize..record[k + 1] as usize].to_vec())
        .collect()
}

#[test]
fn the_same_input_keeps_the_clusters_and_any_change_rebuilds_them() {
    let view = perspective_view(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 0.8, 1.0, 0.1, 100.0);
    let mut lights = vec![point(Vec3::ZERO, 1.0), point(Vec3::splat(1.0), 1.0)];
    let mut clusters = LightClusters::default();
    assert!(clusters.build_lights(&[view], &lights, 0..2, 2..2));
    let first = clusters.data().to_vec();
    assert!(!clusters.build_lights(&[view], &lights, 0..2, 2..2));
    assert_eq!(clusters.data(), first);

    lights[1].reach = 0.5;
    assert!(clusters.build_lights(&[view], &lights, 0..2, 2..2));
    let mut moved = view;
    moved.view_from_world *= Mat4::from_translation(Vec3::X);
    assert!(clusters.build_lights(&[moved], &lights, 0..2, 2..2));
    assert!(clusters.build_lights(&[moved], &lights, 0..1, 1..2));
}

#[test]
fn a_moved_view_over_unchanged_lights_gets_what_a_whole_build_gives() {
    // `build_views` reuses the last build's spheres and their tree: the same data as a
    // build from scratch for the moved view, from lights near and far (a world 400 across).
    let lights = scattered_lights(3000, 200.0, Vec3::ZERO);
    let view = perspective_view(Vec3::new(0.0, 5.0, 30.0), Vec3::ZERO, 0.8, 1.6, 0.1, 300.0);
    let moved = perspective_view(Vec3::new(20.0, 5.0, 20.0), Vec3::ZERO, 0.8, 1.6, 0.1, 300.0);
    let mut reused = LightClusters::default();
    reused.build_lights(&[view], &lights, 0..2000, 2000..3000);
    assert!(reused.build_views(&[moved]));
    assert!(!reused.build_views(&[moved]), "the same view again: kept");
    let mut whole = LightClusters::default();
    whole.build_lights(&[moved], &lights, 0..2000, 2000..3000);
    assert!(
        listed_anywhere(&whole).len() > 10,
        "some lights are in the view"
    );
    assert_eq!(reused.data(), whole.data());
}

#[test]
fn no_lights_or_no_views_make_no_clusters() {
    let view = perspective_view(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 0.8, 1.0, 0.1, 100.0);
    let mut clusters = LightClusters::default();
    clusters.build_lights(&[view], &[], 0..0, 0..0);
    assert_eq!(clusters.header().view_count, 0);
    assert!(clusters.data().is_empty());
    clusters.build_lights(&[], &[point(Vec3::ZERO, 1.0)], 0..1, 1..1);
    assert_eq!(clusters.header().view_count, 0);
}

#[test]
fn identical_views_are_kept_once_and_colliding_ones_not_at_all() {
    let a = perspective_view(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 0.8, 1.0, 0.1, 100.0);
    let b = ClusterView { key: 1, ..a };
    let c = ClusterView {
        key: 2,
        tiles: UVec2::new(4, 4),
        ..a
    };
    let c_colliding = ClusterView { key: 2, ..a };
    let mut views = vec![a, b, a, c, c_colliding];
    assert_eq!(keep_distinct_views(&mut views), 2);
    assert_eq!(views, vec![a, b]);
}

#[test]
fn depth_slices_cut_near_to_far_and_reach_beyond_both() {
    let slices = DepthSlices::logarithmic(24, 0.1, 1000.0);
    assert_eq!(slices.slice_of(0.0), 0);
    assert_eq!(slices.slice_of(-5.0), 0);
    assert_eq!(slices.slice_of(0.1001), 0);
    assert_eq!(slices.slice_of(999.0), 23);
    assert_eq!(slices.slice_of(1e30), 23);
    // Each slice is (1000 / 0.1)^(1/24) times deeper than the one before.
    let ratio = 1e4f64.powf(1.0 / 24.0);
    assert_eq!(slices.slice_of(0.1 * ratio * 1.001), 1);
    assert_eq!(slices.slice_of(0.1 * ratio.powi(12) * 1.001), 12);
    let linear = DepthSlices::linear(10, 0.0, 100.0);
    assert_eq!(linear.slice_of(55.0), 5);
    assert_eq!(DepthSlices::logarithmic(24, 0.0, 100.0), DepthSlices::ONE);
    assert_eq!(
        DepthSlices::linear(24, 5.0, f32::INFINITY),
        DepthSlices::ONE
    );
}
