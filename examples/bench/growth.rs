//! How frame time grows: the field of spheres under 1 to 4,096 point lights (each cut off at
//! 4 units) at two sizes, and under a fixed number of lights at sizes from 128² to 1024²,
//! drawn by Phong with its light clusters, Phong without them, `StandardMaterial` (Bevy's
//! clustered lights) and the constant-color floor. Each shading's frame times are fitted
//! to
//!
//! ```text
//! t = a + d · N + b · P + c · N · P        (ms; P megapixels drawn, N lights in the scene)
//! ```
//!
//! so `c` is its cost per light per megapixel, `b` its cost per megapixel with no light,
//! `d` its cost per light whatever the size (the CPU's share: gathering, clustering) and `a`
//! what a frame costs whatever its size. The lights are spread evenly over the
//! field, so the lights reaching a pixel grow in proportion to `N`: a shading that culls
//! them well has a small `c`. Where the clusters. column drops below the column without them,
//! clusters pay for themselves.

use crate::{
    ms,
    plot::{self, Series},
    scene::{Scene, Shading},
    timing::{Frames, median_frame_time},
    write,
};
use bevy_phong::{PhongLightCulling, SpecularModel};
use std::{fmt::Write as _, path::Path};

/// Which points are measured: light counts at some sizes, then sizes at one light count.
/// Light sweeps at two sizes or more tell a cost per light from one per light and pixel.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// The light counts of the light sweeps.
    pub light_counts: Vec<usize>,
    /// The image sizes of the light sweeps, pixels (square); the plot shows the last.
    pub light_sweep_sizes: Vec<u32>,
    /// The image sizes of the second sweep, pixels (square).
    pub sizes: Vec<u32>,
    /// The light count of the second sweep.
    pub size_sweep_lights: usize,
}

impl Sweep {
    /// 1 to 4,096 lights at 128² and 256², and 128² to 1024² under 64 lights (about 20
    /// minutes on lavapipe, most of it under 4,096 lights).
    pub fn full() -> Self {
        Self {
            light_counts: vec![1, 4, 16, 64, 256, 1024, 4096],
            light_sweep_sizes: vec![128, 256],
            sizes: vec![128, 256, 512, 1024],
            size_sweep_lights: 64,
        }
    }

    /// Four small points, enough for the fit: what `--quick` runs.
    pub fn quick() -> Self {
        Self {
            light_counts: vec![1, 16],
            light_sweep_sizes: vec![48, 64],
            sizes: vec![64],
            size_sweep_lights: 16,
        }
    }

    /// Every `(lights, size)` point of both sweeps, each once.
    fn points(&self) -> Vec<(usize, u32)> {
        let light_sweeps = self
            .light_sweep_sizes
            .iter()
            .flat_map(|&size| self.light_counts.iter().map(move |&lights| (lights, size)));
        let size_sweep = self
            .sizes
            .iter()
            .map(|&size| (self.size_sweep_lights, size));
        let mut points: Vec<(usize, u32)> = Vec::new();
        for point in light_sweeps.chain(size_sweep) {
            if !points.contains(&point) {
                points.push(point);
            }
        }
        points
    }
}

/// One column: a shading and, for Phong, its culling.
struct Column {
    name: &'static str,
    shading: Shading,
    /// `None`: the benchmark's culling (`--culling`, default [`PhongLightCulling::default`]).
    culling: Option<PhongLightCulling>,
}

const PHONG: Shading = Shading::Phong(Some(SpecularModel::Phong));

const COLUMNS: [Column; 4] = [
    Column {
        name: "Phong, clusters",
        shading: PHONG,
        culling: None,
    },
    Column {
        name: "Phong, no clusters",
        shading: PHONG,
        culling: Some(PhongLightCulling {
            epsilon: PhongLightCulling::DEFAULT_EPSILON,
            clusters: false,
        }),
    },
    Column {
        name: "Standard",
        shading: Shading::Standard,
        culling: None,
    },
    Column {
        name: "floor (constant color)",
        shading: Shading::Constant,
        culling: None,
    },
];

/// How many measurements [`table`] makes.
pub fn measurements(sweep: &Sweep) -> usize {
    sweep.points().len() * COLUMNS.len()
}

/// Measures every point of `sweep` in every column (the columns take turns at each point),
/// prints the table of frame times and the fit of each column, and writes `growth.csv`,
/// `growth_lights.png` and `growth_size.png` into `directory`.
pub fn table(sweep: &Sweep, frames: Frames, culling: PhongLightCulling, directory: &Path) {
    let points = sweep.points();
    let mut csv = String::from("lights,size,shading,median_ms\n");
    // times[point][column], ms
    let times: Vec<[f64; COLUMNS.len()]> = points
        .iter()
        .map(|&(lights, size)| {
            let scene = Scene::Field { lights };
            COLUMNS.each_ref().map(|column| {
                let culling = column.culling.unwrap_or(culling);
                let median = ms(median_frame_time(
                    scene,
                    size,
                    column.shading,
                    culling,
                    frames,
                ));
                let _ = writeln!(csv, "{lights},{size},{},{median:.3}", column.name);
                crate::measured!("{} {size}² {}: {median:.1} ms", scene.name(), column.name);
                median
            })
        })
        .collect();

    let mut table = String::from("| lights | size |");
    for column in &COLUMNS {
        let _ = write!(table, " {} ms |", column.name);
    }
    table.push_str(" clusters / none | Phong / Standard |\n|---|---|");
    table.push_str(&"---|".repeat(COLUMNS.len() + 2));
    table.push('\n');
    for (&(lights, size), row) in points.iter().zip(&times) {
        let _ = write!(table, "| {lights} | {size}² |");
        for time in row {
            let _ = write!(table, " {time:.1} |");
        }
        let _ = writeln!(table, " {:.2} | {:.2} |", row[0] / row[1], row[0] / row[2]);
    }

    let mut fits = String::from(
        "| shading | a: ms per frame | d: ms per light | b: ms per MP | c: ms per light per MP | largest misfit |\n\
         |---|---|---|---|---|---|\n",
    );
    for (index, column) in COLUMNS.iter().enumerate() {
        let samples: Vec<Sample> = points
            .iter()
            .zip(&times)
            .map(|(&(lights, size), row)| Sample {
                lights: lights as f64,
                megapixels: megapixels(size),
                ms: row[index],
            })
            .collect();
        match Fit::of(&samples) {
            Some(fit) => {
                let _ = writeln!(
                    fits,
                    "| {} | {:.1} | {:.3} | {:.1} | {:.2} | {:.0} % |",
                    column.name,
                    fit.per_frame,
                    fit.per_light,
                    fit.per_megapixel,
                    fit.per_light_megapixel,
                    100.0 * fit.largest_relative_misfit(&samples)
                );
            }
            None => {
                let _ = writeln!(
                    fits,
                    "| {} | (too few points to fit) | | | | |",
                    column.name
                );
            }
        }
    }
    println!(
        "\nHow frame time grows: the field of spheres under N point lights, median ms; \
         {} to {} lights at {}, then {}² to {}² under {} lights:\n\n{table}\n\
         Each shading fitted to t = a + d·N + b·P + c·N·P (P megapixels; least squares of the \
         relative misfit):\n\n{fits}{}",
        sweep.light_counts.first().unwrap_or(&0),
        sweep.light_counts.last().unwrap_or(&0),
        sweep
            .light_sweep_sizes
            .iter()
            .map(|size| format!("{size}²"))
            .collect::<Vec<_>>()
            .join(" and "),
        sweep.sizes.first().unwrap_or(&0),
        sweep.sizes.last().unwrap_or(&0),
        sweep.size_sweep_lights,
        sweep
            .light_sweep_sizes
            .iter()
            .map(|&size| where_the_clusters_pay(&sweep.light_counts, &points, &times, size))
            .collect::<String>(),
    );
    write(&directory.join("growth.csv"), &csv);
    plot_sweeps(sweep, &points, &times, directory);
}

/// Megapixels in a `size`² image.
fn megapixels(size: u32) -> f64 {
    f64::from(size) * f64::from(size) / 1e6
}

/// The sentence that says from which light count on the clusters. column is faster than the
/// column without it, in the light sweep at `size`².
fn where_the_clusters_pay(
    sweep_lights: &[usize],
    points: &[(usize, u32)],
    times: &[[f64; COLUMNS.len()]],
    size: u32,
) -> String {
    let sweep: Vec<(usize, f64)> = points
        .iter()
        .zip(times)
        .filter(|((lights, at), _)| *at == size && sweep_lights.contains(lights))
        .map(|(&(lights, _), row)| (lights, row[0] / row[1]))
        .collect();
    // The first light count from which on clusters are faster at every measured count.
    let from = (0..sweep.len())
        .find(|&first| sweep[first..].iter().all(|&(_, ratio)| ratio < 1.0))
        .map(|first| sweep[first].0);
    match from {
        Some(lights) => format!(
            "\nAt {size}² clusters are faster than none from {lights} light{} on (at every \
             measured count from there).\n",
            if lights == 1 { "" } else { "s" }
        ),
        None => format!("\nAt {size}² clusters are not faster than none at the largest count.\n"),
    }
}

/// How many costs the fit has.
const TERMS: usize = 4;

/// One measured frame time.
struct Sample {
    lights: f64,
    megapixels: f64,
    ms: f64,
}

impl Sample {
    /// The fit's terms at this sample: `[1, N, P, N · P]`.
    fn terms(&self) -> [f64; TERMS] {
        [
            1.0,
            self.lights,
            self.megapixels,
            self.lights * self.megapixels,
        ]
    }
}

/// `t = a + d · N + b · P + c · N · P`, fitted by least squares of the misfit relative to each
/// measured time (times span four decades: absolute misfits would fit only the slowest).
struct Fit {
    /// `a`, ms.
    per_frame: f64,
    /// `d`, ms per light.
    per_light: f64,
    /// `b`, ms per megapixel.
    per_megapixel: f64,
    /// `c`, ms per light per megapixel.
    per_light_megapixel: f64,
}

impl Fit {
    /// The fit, or `None` when the samples do not determine it (fewer than four points, or
    /// none varying in light count or size).
    fn of(samples: &[Sample]) -> Option<Self> {
        // Normal equations of the weighted problem: rows terms / t, right-hand side 1.
        let mut matrix = [[0.0_f64; TERMS]; TERMS];
        let mut rhs = [0.0_f64; TERMS];
        for sample in samples {
            let row = sample.terms().map(|term| term / sample.ms);
            for i in 0..TERMS {
                for j in 0..TERMS {
                    matrix[i][j] += row[i] * row[j];
                }
                rhs[i] += row[i];
            }
        }
        let [a, d, b, c] = solve(matrix, rhs)?;
        Some(Self {
            per_frame: a,
            per_light: d,
            per_megapixel: b,
            per_light_megapixel: c,
        })
    }

    fn at(&self, sample: &Sample) -> f64 {
        let [one, n, p, np] = sample.terms();
        self.per_frame * one
            + self.per_light * n
            + self.per_megapixel * p
            + self.per_light_megapixel * np
    }

    /// The largest `|fitted − measured| / measured` over `samples`.
    fn largest_relative_misfit(&self, samples: &[Sample]) -> f64 {
        samples
            .iter()
            .map(|sample| (self.at(sample) - sample.ms).abs() / sample.ms)
            .fold(0.0, f64::max)
    }
}

/// `x` with `matrix · x = rhs`, by Gaussian elimination with partial pivoting; `None` when
/// `matrix` is singular (relative to its largest entry).
fn solve(mut matrix: [[f64; TERMS]; TERMS], mut rhs: [f64; TERMS]) -> Option<[f64; TERMS]> {
    let scale = matrix.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    for column in 0..TERMS {
        let pivot = (column..TERMS)
            .max_by(|&i, &j| matrix[i][column].abs().total_cmp(&matrix[j][column].abs()))?;
        if matrix[pivot][column].abs() <= 1e-12 * scale {
            return None;
        }
        matrix.swap(column, pivot);
        rhs.swap(column, pivot);
        let pivot_row = matrix[column];
        for row in column + 1..TERMS {
            let factor = matrix[row][column] / pivot_row[column];
            for (entry, above) in matrix[row][column..].iter_mut().zip(&pivot_row[column..]) {
                *entry -= factor * above;
            }
            rhs[row] -= factor * rhs[column];
        }
    }
    let mut x = [0.0; TERMS];
    for row in (0..TERMS).rev() {
        let known: f64 = (row + 1..TERMS).map(|k| matrix[row][k] * x[k]).sum();
        x[row] = (rhs[row] - known) / matrix[row][row];
    }
    Some(x)
}

/// The two plots: frame time against light count (the light sweep) and against
/// megapixels (the size sweep), one line per column.
fn plot_sweeps(
    sweep: &Sweep,
    points: &[(usize, u32)],
    times: &[[f64; COLUMNS.len()]],
    directory: &Path,
) {
    let series = |keep: &dyn Fn(usize, u32) -> bool, x: &dyn Fn(usize, u32) -> f64| {
        COLUMNS
            .iter()
            .enumerate()
            .map(|(index, column)| {
                let mut line: Vec<(f64, f64)> = points
                    .iter()
                    .zip(times)
                    .filter(|((lights, size), _)| keep(*lights, *size))
                    .map(|(&(lights, size), row)| (x(lights, size), row[index]))
                    .collect();
                line.sort_by(|a, b| a.0.total_cmp(&b.0));
                Series {
                    label: column.name.into(),
                    points: line,
                }
            })
            .collect::<Vec<_>>()
    };
    let size = sweep.light_sweep_sizes.last().copied().unwrap_or(0);
    plot::lines(
        &directory.join("growth_lights.png"),
        &format!("Frame time against light count on lavapipe, {size}x{size}"),
        "point lights in the field",
        "median frame time, ms",
        &series(
            &|lights, at| at == size && sweep.light_counts.contains(&lights),
            &|lights, _| lights as f64,
        ),
    );
    let lights = sweep.size_sweep_lights;
    plot::lines(
        &directory.join("growth_size.png"),
        &format!("Frame time against image size on lavapipe, {lights} point lights"),
        "megapixels drawn",
        "median frame time, ms",
        &series(&|count, _| count == lights, &|_, size| megapixels(size)),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fit_recovers_the_costs_it_was_made_from() {
        let (a, d, b, c) = (3.0, 0.002, 40.0, 0.5);
        let samples: Vec<Sample> = [
            (1.0, 0.065),
            (64.0, 0.065),
            (4096.0, 0.065),
            (64.0, 1.0),
            (1.0, 0.26),
        ]
        .map(|(lights, megapixels)| Sample {
            lights,
            megapixels,
            ms: a + d * lights + b * megapixels + c * lights * megapixels,
        })
        .into();
        let fit = Fit::of(&samples).expect("five points determine four costs");
        // Exact data: only rounding separates the fit from the costs.
        assert!((fit.per_frame - a).abs() < 1e-9);
        assert!((fit.per_light - d).abs() < 1e-9);
        assert!((fit.per_megapixel - b).abs() < 1e-9);
        assert!((fit.per_light_megapixel - c).abs() < 1e-9);
        assert!(fit.largest_relative_misfit(&samples) < 1e-12);
    }

    #[test]
    fn one_size_and_one_light_count_do_not_determine_a_fit() {
        let sample = || Sample {
            lights: 16.0,
            megapixels: 0.25,
            ms: 10.0,
        };
        assert!(Fit::of(&[sample(), sample(), sample(), sample()]).is_none());
    }
}
