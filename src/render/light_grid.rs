//! The world-space light grid (see [`crate::culling`]): cubic cells over the spheres of the
//! lights with a finite reach, each listing the lights whose sphere touches it.
//!
//! The cell edge is the median reach of the lights, so that a typical light is listed in at
//! most 3 cells along each axis (and fewer after the sphere-box test), capped at
//! [`MAX_CELLS_PER_AXIS`] along an axis and [`MAX_CELLS`] in all, which bounds the buffer
//! for scenes of far-flung lights (their cells then get larger). A cell record is
//! `[first, point_count, spot_count, 0]`: the cell's point lights are `data[first..]`, its
//! spot lights follow, each an index into the light buffer's array.

use super::gpu_types::{GpuLight, GpuLightGridHeader};
use bevy::math::{UVec3, Vec3};
use std::ops::Range;

/// Most cells along one axis.
pub const MAX_CELLS_PER_AXIS: u32 = 64;
/// Most cells in all (a 512 KiB table of cell records).
pub const MAX_CELLS: u32 = 1 << 15;
/// `u32` words per cell record.
const CELL_WORDS: usize = GpuLightGridHeader::CELL_WORDS as usize;

/// The grid as last built, and the scratch space it is built in (kept between frames, so
/// that rebuilding allocates nothing once the scene's size is reached).
#[derive(Debug, Default)]
pub struct LightGrid {
    header: GpuLightGridHeader,
    data: Vec<u32>,
    reaches: Vec<f32>,
    pairs: Vec<(u32, u32)>,
    /// What the grid was last built from: the spheres, in light buffer order, and where
    /// the point lights and the spot lights sat in the light buffer.
    built_from: BuiltFrom,
}

/// The input of a build, compared bit for bit with the next one: the same input gives the
/// same grid, which is then kept as it is.
#[derive(Debug, Default)]
struct BuiltFrom {
    /// Each light's position and range, as bits.
    spheres: Vec<[u32; 4]>,
    points: Range<usize>,
    spots: Range<usize>,
}

impl BuiltFrom {
    /// Whether this is the input `lights[points]`, `lights[spots]`.
    fn is(&self, lights: &[GpuLight], points: &Range<usize>, spots: &Range<usize>) -> bool {
        self.points == *points
            && self.spots == *spots
            && self.spheres.len() == spots.end - points.start
            && self
                .spheres
                .iter()
                .zip(&lights[points.start..spots.end])
                .all(|(sphere, light)| *sphere == sphere_bits(light))
    }

    /// Notes the input `lights[points]`, `lights[spots]`.
    fn set(&mut self, lights: &[GpuLight], points: Range<usize>, spots: Range<usize>) {
        self.spheres.clear();
        self.spheres
            .extend(lights[points.start..spots.end].iter().map(sphere_bits));
        (self.points, self.spots) = (points, spots);
    }
}

/// A light's position and range, as bits.
fn sphere_bits(light: &GpuLight) -> [u32; 4] {
    let [x, y, z] = light.position;
    [x, y, z, light.range].map(f32::to_bits)
}

/// Whether `light` (a point or spot light) has a finite sphere of reach that the grid can
/// hold.
pub fn has_finite_reach(light: &GpuLight) -> bool {
    let center = Vec3::from(light.position);
    light.range < f32::MAX
        && (center - light.range).is_finite()
        && (center + light.range).is_finite()
}

impl LightGrid {
    /// Where the grid lies and how many cells it has.
    pub fn header(&self) -> &GpuLightGridHeader {
        &self.header
    }

    /// The cell records, then the light indices they point into.
    pub fn data(&self) -> &[u32] {
        &self.data
    }

    /// Sorts the point lights `lights[points]` and the spot lights `lights[spots]` (every
    /// one with [`has_finite_reach`]; `spots` follows `points`) into cells. When they are
    /// the lights of the last build, at the same places and with the same ranges, the grid
    /// is kept as it is.
    pub fn build(&mut self, lights: &[GpuLight], points: Range<usize>, spots: Range<usize>) {
        debug_assert_eq!(points.end, spots.start);
        if self.built_from.is(lights, &points, &spots) {
            return;
        }
        self.built_from.set(lights, points.clone(), spots.clone());
        self.data.clear();
        let bounded = &lights[points.start..spots.end];
        if bounded.is_empty() {
            self.header = GpuLightGridHeader::EMPTY;
            return;
        }
        let (origin, cell_size, dimensions) = self.layout(bounded);
        self.header = GpuLightGridHeader {
            origin: origin.to_array(),
            cell_size,
            dimensions: dimensions.to_array(),
            padding: 0,
        };
        let cells = (dimensions.x * dimensions.y * dimensions.z) as usize;
        let header = self.header;
        let data = &mut self.data;
        data.resize(cells * CELL_WORDS, 0);

        // One pass over the lights: count each cell's point lights (word 1) and spot lights
        // (word 2), and note every (cell, light) pair.
        let pairs = &mut self.pairs;
        pairs.clear();
        for (index, light) in bounded.iter().enumerate() {
            let light_index = (points.start + index) as u32;
            let word = if light_index < points.end as u32 {
                1
            } else {
                2
            };
            for_each_cell(&header, light, |cell| {
                data[cell * CELL_WORDS + word] += 1;
                pairs.push((cell as u32, light_index));
            });
        }
        // Give each cell its first index (word 0) and a write cursor (word 3).
        let mut next = (cells * CELL_WORDS) as u32;
        for record in data.chunks_exact_mut(CELL_WORDS) {
            record[0] = next;
            record[3] = next;
            next += record[1] + record[2];
        }
        data.resize(next as usize, 0);
        // The pairs are in light order, points before spots: so is each cell's list.
        for &(cell, light_index) in pairs.iter() {
            let cursor = &mut data[cell as usize * CELL_WORDS + 3];
            let slot = *cursor as usize;
            *cursor += 1;
            data[slot] = light_index;
        }
        for record in data[..cells * CELL_WORDS].chunks_exact_mut(CELL_WORDS) {
            record[3] = 0;
        }
    }

    /// The grid's corner, cell edge and cell counts for `lights`.
    fn layout(&mut self, lights: &[GpuLight]) -> (Vec3, f32, UVec3) {
        let (mut min, mut max) = (Vec3::MAX, Vec3::MIN);
        self.reaches.clear();
        for light in lights {
            let center = Vec3::from(light.position);
            min = min.min(center - light.range);
            max = max.max(center + light.range);
            self.reaches.push(light.range);
        }
        let middle = self.reaches.len() / 2;
        let (_, median, _) = self.reaches.select_nth_unstable_by(middle, f32::total_cmp);
        let extent = (max - min).max(Vec3::splat(f32::MIN_POSITIVE));
        let mut cell_size = median
            .max(extent.max_element() / MAX_CELLS_PER_AXIS as f32)
            .max(f32::MIN_POSITIVE);
        loop {
            let dimensions = (extent / cell_size).ceil().max(Vec3::ONE);
            let fits = dimensions.max_element() <= MAX_CELLS_PER_AXIS as f32
                && dimensions.element_product() <= MAX_CELLS as f32;
            if fits {
                return (min, cell_size, dimensions.as_uvec3());
            }
            cell_size *= 1.25;
        }
    }
}

/// Calls `visit` with the index of every cell that `light`'s sphere touches, widened by a
/// margin that covers the rounding of the shader's cell lookup.
fn for_each_cell(header: &GpuLightGridHeader, light: &GpuLight, mut visit: impl FnMut(usize)) {
    let origin = Vec3::from(header.origin);
    let cell_size = header.cell_size;
    let dimensions = UVec3::from(header.dimensions);
    let center = Vec3::from(light.position) - origin;
    // In f64: a grid stretched by lights near f32::MAX has its far corner (the last cell's
    // edge, rounded up) past f32::MAX, which in f32 would make the margin infinite and put
    // every light in every cell.
    let far_corner = f64::from(dimensions.max_element()) * f64::from(cell_size);
    let margin = (f64::from(cell_size) * 1e-3
        + 8.0 * f64::from(f32::EPSILON) * (f64::from(origin.abs().max_element()) + far_corner))
        as f32;
    let reach = light.range + margin;
    // For coordinates ≥ 0 the (saturating) conversion truncates, which is `floor`.
    let cell_of = |x: Vec3| {
        (x / cell_size)
            .max(Vec3::ZERO)
            .as_uvec3()
            .min(dimensions - 1)
    };
    let (first, last) = (cell_of(center - reach), cell_of(center + reach));
    // The squared distance from the center to cell `cell`'s slab along `axis`; summed over
    // the three axes, the squared distance to the cell.
    let slab_distance_squared = |axis: usize, cell: u32| {
        let low = cell as f32 * cell_size;
        let outside = (low - center[axis])
            .max(center[axis] - (low + cell_size))
            .max(0.0);
        outside * outside
    };
    let reach_squared = reach * reach;
    for z in first.z..=last.z {
        let z_distance = slab_distance_squared(2, z);
        for y in first.y..=last.y {
            let yz_distance = z_distance + slab_distance_squared(1, y);
            let row = (dimensions.y * z + y) * dimensions.x;
            for x in first.x..=last.x {
                let touches = yz_distance + slab_distance_squared(0, x) <= reach_squared;
                if touches {
                    visit((row + x) as usize);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(position: Vec3, range: f32) -> GpuLight {
        GpuLight {
            position: position.to_array(),
            range,
            ..GpuLight::default()
        }
    }

    /// The lights the grid lists for the cell holding `position`, as the shader finds them.
    fn lights_at(grid: &LightGrid, position: Vec3) -> Vec<u32> {
        let header = grid.header();
        let dimensions = UVec3::from(header.dimensions);
        let cell = (position - Vec3::from(header.origin)) / header.cell_size;
        if !(cell.cmpge(Vec3::ZERO).all() && cell.cmplt(dimensions.as_vec3()).all()) {
            return Vec::new();
        }
        let cell = cell.as_uvec3();
        let record =
            CELL_WORDS * (cell.x + dimensions.x * (cell.y + dimensions.y * cell.z)) as usize;
        let first = grid.data()[record] as usize;
        let count = (grid.data()[record + 1] + grid.data()[record + 2]) as usize;
        grid.data()[first..first + count].to_vec()
    }

    #[test]
    fn every_point_a_light_reaches_lists_that_light() {
        // A deterministic scatter of lights of different reaches, then points all around.
        let lights: Vec<GpuLight> = (0..200)
            .map(|i| {
                let t = i as f32;
                let position = Vec3::new(
                    (t * 0.618).fract(),
                    (t * 0.382).fract(),
                    (t * 0.754).fract(),
                ) * 20.0;
                point(position, 0.5 + (t * 0.13).fract() * 3.0)
            })
            .collect();
        let mut grid = LightGrid::default();
        grid.build(&lights, 0..150, 150..200);
        for i in 0..20_000 {
            let t = i as f32;
            let probe = Vec3::new(
                (t * 0.7548).fract(),
                (t * 0.5698).fract(),
                (t * 0.1234).fract(),
            ) * 26.0
                - 3.0;
            let listed = lights_at(&grid, probe);
            for (index, light) in lights.iter().enumerate() {
                if probe.distance(Vec3::from(light.position)) <= light.range {
                    assert!(
                        listed.contains(&(index as u32)),
                        "light {index} missing at {probe}"
                    );
                }
            }
        }
    }

    #[test]
    fn cells_list_point_lights_before_spot_lights() {
        let lights = [
            point(Vec3::ZERO, 1.0),
            point(Vec3::X, 1.0),
            point(Vec3::Y, 1.0),
        ];
        let mut grid = LightGrid::default();
        grid.build(&lights, 0..1, 1..3);
        let header = grid.header();
        let cells = (header.dimensions[0] * header.dimensions[1] * header.dimensions[2]) as usize;
        for record in grid.data()[..cells * CELL_WORDS].chunks_exact(CELL_WORDS) {
            let [first, points, spots, unused] = [record[0], record[1], record[2], record[3]];
            assert_eq!(unused, 0);
            let listed = &grid.data()[first as usize..(first + points + spots) as usize];
            assert!(listed[..points as usize].iter().all(|&index| index == 0));
            assert!(listed[points as usize..].iter().all(|&index| index > 0));
        }
    }

    #[test]
    fn far_flung_lights_keep_the_grid_within_its_cell_budget() {
        let lights = [point(Vec3::splat(-1e6), 1.0), point(Vec3::splat(1e6), 1.0)];
        let mut grid = LightGrid::default();
        grid.build(&lights, 0..2, 2..2);
        let dimensions = UVec3::from(grid.header().dimensions);
        assert!(dimensions.max_element() <= MAX_CELLS_PER_AXIS);
        assert!(dimensions.element_product() <= MAX_CELLS);
        assert_eq!(lights_at(&grid, Vec3::splat(1e6)), vec![1]);
        assert_eq!(lights_at(&grid, Vec3::splat(-1e6)), vec![0]);
    }

    #[test]
    fn lights_near_the_largest_float_keep_every_light_in_its_own_cells() {
        // Lights at the edge of f32's range stretch the grid to cells of ~1e37: the grid's
        // far corner then lies past f32::MAX. Every light of reach far below a cell still
        // touches at most 2 cells along each axis, 8 in all.
        let mut lights: Vec<GpuLight> = (0..100)
            .map(|i| point(Vec3::new(i as f32 * 0.1, 0.0, 0.0), 2.0))
            .collect();
        for far in [Vec3::X, Vec3::Y, Vec3::Z] {
            lights.push(point(far * f32::MAX, 2.5));
        }
        let mut grid = LightGrid::default();
        grid.build(&lights, 0..lights.len(), lights.len()..lights.len());
        let cells = UVec3::from(grid.header().dimensions).element_product() as usize;
        assert!(
            grid.data().len() <= cells * CELL_WORDS + lights.len() * 8,
            "{} words for {cells} cells and {} lights",
            grid.data().len(),
            lights.len()
        );
        assert!(lights_at(&grid, Vec3::ZERO).contains(&0));
        assert!(lights_at(&grid, Vec3::X * f32::MAX).contains(&100));
    }

    #[test]
    fn a_build_from_the_same_lights_keeps_the_grid_and_any_change_rebuilds_it() {
        let mut lights = vec![point(Vec3::ZERO, 1.0), point(Vec3::splat(4.0), 1.0)];
        let mut grid = LightGrid::default();
        grid.build(&lights, 0..2, 2..2);
        let first = (*grid.header(), grid.data().to_vec());
        grid.build(&lights, 0..2, 2..2);
        assert_eq!((*grid.header(), grid.data().to_vec()), first);

        lights[1].position = [0.0, 0.0, 4.0];
        grid.build(&lights, 0..2, 2..2);
        assert_eq!(lights_at(&grid, Vec3::new(0.0, 0.0, 4.0)), vec![1]);
        assert!(lights_at(&grid, Vec3::splat(4.0)).is_empty());

        // Cells of edge 1 from z = -1: the light's sphere touches the cell of z 2.6 while its
        // reach is 1, not once it is 0.5.
        assert_eq!(lights_at(&grid, Vec3::new(0.0, 0.0, 2.6)), vec![1]);
        lights[1].range = 0.5;
        grid.build(&lights, 0..2, 2..2);
        assert!(lights_at(&grid, Vec3::new(0.0, 0.0, 2.6)).is_empty());

        // The same spheres, the second one now a spot light: its cells count it as one.
        grid.build(&lights, 0..1, 1..2);
        let dimensions = UVec3::from(grid.header().dimensions);
        let spot_words: u32 = grid.data()[..dimensions.element_product() as usize * CELL_WORDS]
            .chunks_exact(CELL_WORDS)
            .map(|record| record[2])
            .sum();
        assert!(spot_words > 0);
    }

    #[test]
    fn no_bounded_lights_make_an_empty_grid() {
        let mut grid = LightGrid::default();
        grid.build(&[], 0..0, 0..0);
        assert_eq!(grid.header().dimensions, [0; 3]);
        assert!(grid.data().is_empty());
        assert!(lights_at(&grid, Vec3::ZERO).is_empty());
    }
}
