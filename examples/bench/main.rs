//! Frame time of `PhongMaterial` beside Bevy's `StandardMaterial` (lit by the equivalent
//! Bevy lights) and a constant-color material (the floor: rasterization and Bevy's overhead
//! without lighting), rendered headless on the render device, measured side by side in one
//! run; then the frame time of each speed/accuracy variant next to its error against the
//! f64 reference model.
//!
//! ```sh
//! cargo run --example bench             # every table (about 45 minutes)
//! cargo run --example bench -- --quick  # a small smoke run (what CI runs)
//! cargo run --example bench -- --frame-times --scene showcase --size 1024 --no-variants
//! cargo run --example bench -- --shadows  # only the cost of shadows
//! cargo run --example bench -- --webgl2   # only the storage path beside the WebGL2 one
//! cargo run --example bench -- --ablation # only the shader ablation (--size N: at N²)
//! cargo run --example bench -- --growth   # only how frame time grows with lights and size
//! cargo run --example bench -- --materials  # only the material features (see features.rs)
//! cargo run --example bench -- --stylized   # only the stylized modes (see features.rs)
//! cargo run --example bench -- --lamps      # only the street lamps (see lamps.rs; --size N)
//! cargo run --example bench -- --cubes      # only many meshes and materials (cubes.rs; --count N)
//! cargo run --example bench -- --pairs      # only one light on one pixel, per kind (pairs.rs)
//! cargo run --example bench -- --frame-times --scene field256 --scene wide60000 --size 32 --orbit
//!                                           # far lights under a camera that moves every frame
//! ```
//!
//! `--orbit` turns every camera half a degree around the scene's middle before each frame.
//!
//! The table flags (`--frame-times`, `--shadows`, `--webgl2`, `--ablation`, `--growth`,
//! `--materials`, `--stylized`, `--lamps`, `--cubes`, `--pairs`)
//! combine: with any of them, the run measures those tables and no other.
//!
//! `--one-row --scene S --size N [--frames F]` prints one Phong median (ms) and exits: the
//! fourth table runs each of its measurements that way, in a process of its own.
//!
//! The first table is the frame times (`--frame-times`): `--scene` (`showcase`, `field16`,
//! `field256`, `field4096`, and `wide3840` / `wide60000`: the 256-light field with that
//! many more lights spread over a world 1,000 units across, reaching no visible pixel) and
//! `--size` may be repeated to pick its rows; `--culling`
//! (`none`, `exact`, `default`) sets the Phong column's `PhongLightCulling`;
//! `--no-variants` skips the second table. A third table
//! gives the cost of shadows: the showcase on a floor with its three lights casting shadows
//! or not, Phong beside `StandardMaterial` (each with 1024² shadow maps), at 1024²
//! (`--shadows` runs it alone; its rows take turns over five rounds, each the median of
//! its rounds). A fourth table sets the scene data's two paths side by side: storage
//! buffers, and the data texture that devices without them (WebGL2) read, on a device
//! created with WebGL2's limits; the showcase and the 256-light field at 1024², taking turns
//! in the same way (`--webgl2` runs it alone). A fifth table is the shader ablation: the
//! showcase with the Phong fragment shader cut after each stage of its work, from the
//! constant-color floor to the full shader, at 1024² or the first `--size`, taking turns in
//! the same way (`--ablation`; see `ablation.rs`). A sixth shows how frame time grows: the
//! field under 1 to 4,096 lights at 128² and 256², and under 64 lights from 128² to
//! 1024², Phong with and without its light clusters beside Standard and the floor, with each
//! one's fitted cost per light per megapixel (`--growth`; see `growth.rs`). Another gives
//! the cost of one light on one pixel for each kind of light, highlight choice and
//! shininess, with its error (`--pairs`; see `pairs.rs`).
//!
//! Each frame is timed from the start of `App::update` until the device has finished the
//! frame's work; the tables give the median over the measured frames, after the pipelines
//! compiled and a few warm-up frames. Errors are the largest per-channel difference from
//! `bevy_phong::reference` over a 128² render (relative to `max(1, |expected|)`), measured
//! with the render tests' harness. It writes `target/bench/*.csv` and `target/bench/*.png`.
//!
//! Each measurement prints a line on standard error ending with how far the run is:
//! `[12 of 79 measurements done, 67 left, about 3 min left]` (`progress.rs`). `--help`
//! lists the options.

mod ablation;
mod accuracy;
mod cubes;
mod features;
mod frame_times;
mod growth;
mod lamps;
mod pairs;
mod panels;
mod plot;
mod progress;
mod scene;
mod showcase_costs;
mod timing;
mod variants;

use bevy::prelude::*;
use bevy_phong::{PhongLightCulling, SpecularModel};
use clap::{Parser, ValueEnum};
use scene::{Scene, Shading};
use std::{fmt::Write as _, path::Path, time::Duration};
use timing::{Frames, median_frame_time};

struct Options {
    /// `--quick`: a smoke run of every table, each over a few of its rows, which CI runs.
    quick: bool,
    variants: bool,
    /// The tables to run.
    tables: Tables,
    /// Whether to print one measurement and exit (see `one_row_in_own_process`).
    one_row: bool,
    /// The image size of the shadow table and the WebGL2 one, pixels.
    shadow_size: u32,
    /// The grids of the many-materials table (`--cubes`).
    cube_counts: Vec<usize>,
    /// The image size of the shader ablation, pixels.
    ablation_size: u32,
    /// The points of the table of how frame time grows.
    growth: growth::Sweep,
    /// How many times each row of the tables whose rows take turns (shadows, WebGL2,
    /// ablation) is measured.
    rounds: usize,
    culling: PhongLightCulling,
    sizes: Vec<u32>,
    scenes: Vec<Scene>,
    /// The variants' scenes: the same field with and without ranges.
    variant_lights: usize,
    variant_size: u32,
    frames: Frames,
}

/// The command line; see the module's documentation for what each table measures.
#[derive(Parser)]
#[command(
    name = "bench",
    about = "Frame time of PhongMaterial beside StandardMaterial and a constant-color floor, \
             headless on the render device, and each variant's time against its error",
    override_usage = "cargo run --example bench -- [OPTIONS]",
    after_help = "The table flags combine: with any of them, the run measures those tables and \
                  no other; without any, every table (about 45 minutes). Writes \
                  target/bench/*.csv and target/bench/*.png."
)]
struct Args {
    /// A small smoke run of every table, each over a few of its rows (what CI runs).
    #[arg(long)]
    quick: bool,
    /// Skip the variants' time against error (after the frame times).
    #[arg(long)]
    no_variants: bool,
    /// Table: the frame times of the picked scenes and sizes.
    #[arg(long)]
    frame_times: bool,
    /// Table: the cost of shadows.
    #[arg(long)]
    shadows: bool,
    /// Table: the storage path beside the WebGL2 one (the data texture).
    #[arg(long)]
    webgl2: bool,
    /// Table: the shader ablation (at the first --size).
    #[arg(long)]
    ablation: bool,
    /// Table: how frame time grows with lights and size.
    #[arg(long)]
    growth: bool,
    /// Table: the material features.
    #[arg(long)]
    materials: bool,
    /// Table: the stylized modes.
    #[arg(long)]
    stylized: bool,
    /// Table: the street lamps with cookies and shadows, near and far (at the first --size).
    #[arg(long)]
    lamps: bool,
    /// Table: many meshes and materials (the grids of --count).
    #[arg(long)]
    cubes: bool,
    /// Table: the cost of one light on one pixel, per kind, highlight and shininess.
    #[arg(long)]
    pairs: bool,
    /// Print one Phong median (ms) of --scene at --size and exit (the WebGL2 table runs each
    /// of its measurements so, in a process of its own).
    #[arg(long)]
    one_row: bool,
    /// Turn every camera half a degree around the scene's middle before each frame.
    #[arg(long)]
    orbit: bool,
    /// Frames measured per measurement.
    #[arg(long, value_name = "F")]
    frames: Option<usize>,
    /// The Phong column's PhongLightCulling.
    #[arg(long, value_enum)]
    culling: Option<Culling>,
    /// A grid of the many-materials table: N cubes (repeatable).
    #[arg(long = "count", value_name = "N")]
    counts: Vec<usize>,
    /// An image size, N² pixels (repeatable): the frame times' rows; the first also sizes
    /// the ablation and the lamps.
    #[arg(long = "size", value_name = "N")]
    sizes: Vec<u32>,
    /// A scene of the frame times (repeatable): showcase, field16, field256, field4096,
    /// wide3840, wide60000, or lamps with any of -cookies, -shadows, -far (in that order).
    #[arg(long = "scene", value_name = "S", value_parser = parse_scene)]
    scenes: Vec<Scene>,
}

/// `--culling`.
#[derive(Clone, Copy, ValueEnum)]
enum Culling {
    /// `PhongLightCulling::NONE`.
    None,
    /// `PhongLightCulling::EXACT`.
    Exact,
    /// `PhongLightCulling::default()`.
    Default,
}

/// A scene named on the command line.
fn parse_scene(name: &str) -> Result<Scene, String> {
    match name {
        "showcase" => Ok(Scene::Showcase),
        "field16" => Ok(Scene::Field { lights: 16 }),
        "field256" => Ok(Scene::Field { lights: 256 }),
        "field4096" => Ok(Scene::Field { lights: 4096 }),
        "wide3840" => Ok(Scene::WideWorld {
            lights: 256,
            far: 3_840,
        }),
        "wide60000" => Ok(Scene::WideWorld {
            lights: 256,
            far: 60_000,
        }),
        lamps => lamps::Lamps::from_name(lamps)
            .map(Scene::Lamps)
            .ok_or_else(|| {
                String::from(
                    "expected showcase, field16, field256, field4096, wide3840, wide60000, or \
                     lamps with any of -cookies, -shadows, -far (in that order)",
                )
            }),
    }
}

impl Options {
    fn from_args(args: &Args) -> Self {
        let mut options = Self::defaults(args.quick);
        options.variants = !args.no_variants;
        options.tables = Tables::from_args(args);
        options.one_row = args.one_row;
        if let Some(frames) = args.frames {
            options.frames.measured = frames;
        }
        if let Some(culling) = args.culling {
            options.culling = match culling {
                Culling::None => PhongLightCulling::NONE,
                Culling::Exact => PhongLightCulling::EXACT,
                Culling::Default => PhongLightCulling::default(),
            };
        }
        if !args.counts.is_empty() {
            options.cube_counts.clone_from(&args.counts);
        }
        if let Some(&size) = args.sizes.first() {
            options.ablation_size = size;
            options.sizes.clone_from(&args.sizes);
        }
        if !args.scenes.is_empty() {
            options.scenes.clone_from(&args.scenes);
        }
        options
    }

    fn defaults(quick: bool) -> Self {
        if quick {
            return Self {
                quick,
                variants: true,
                tables: Tables::ALL,
                one_row: false,
                shadow_size: 128,
                cube_counts: vec![100],
                ablation_size: 128,
                growth: growth::Sweep::quick(),
                rounds: 1,
                culling: PhongLightCulling::default(),
                sizes: vec![128],
                scenes: vec![Scene::Showcase, Scene::Field { lights: 16 }],
                variant_lights: 16,
                variant_size: 128,
                frames: Frames {
                    warmup: 1,
                    measured: 3,
                    budget: Duration::ZERO,
                },
            };
        }
        Self {
            quick,
            variants: true,
            tables: Tables::ALL,
            one_row: false,
            shadow_size: 1024,
            cube_counts: vec![1_600, 10_000],
            ablation_size: 1024,
            growth: growth::Sweep::full(),
            rounds: 5,
            culling: PhongLightCulling::default(),
            sizes: vec![512, 1024],
            scenes: vec![
                Scene::Showcase,
                Scene::Field { lights: 16 },
                Scene::Field { lights: 256 },
                Scene::Field { lights: 4096 },
            ],
            variant_lights: 256,
            variant_size: 512,
            frames: Frames {
                warmup: 2,
                measured: 31,
                budget: Duration::from_secs(20),
            },
        }
    }
}

/// Which tables a run measures.
#[derive(Clone, Copy, Debug)]
struct Tables {
    /// The frame times of the picked scenes and sizes, then (unless `--no-variants`) the
    /// variants' run time against error.
    frame_times: bool,
    /// The cost of shadows.
    shadows: bool,
    /// The storage path beside the WebGL2 one.
    fallback: bool,
    /// The shader ablation.
    ablation: bool,
    /// How frame time grows.
    growth: bool,
    /// The material feature groups.
    materials: bool,
    /// The stylized modes.
    stylized: bool,
    /// The street lamps with cookies and shadows, near and far.
    lamps: bool,
    /// Many meshes and materials.
    cubes: bool,
    /// The cost of one light on one pixel.
    pairs: bool,
}

impl Tables {
    const ALL: Self = Self {
        frame_times: true,
        shadows: true,
        fallback: true,
        ablation: true,
        growth: true,
        materials: true,
        stylized: true,
        lamps: true,
        cubes: true,
        pairs: true,
    };

    /// The tables whose flags are in `args`, or all of them when none is.
    fn from_args(args: &Args) -> Self {
        let picked = Self {
            frame_times: args.frame_times,
            shadows: args.shadows,
            fallback: args.webgl2,
            ablation: args.ablation,
            growth: args.growth,
            materials: args.materials,
            stylized: args.stylized,
            lamps: args.lamps,
            cubes: args.cubes,
            pairs: args.pairs,
        };
        let any = picked.frame_times
            || picked.shadows
            || picked.fallback
            || picked.ablation
            || picked.growth
            || picked.materials
            || picked.stylized
            || picked.cubes
            || picked.lamps
            || picked.pairs;
        if any { picked } else { Self::ALL }
    }
}

fn ms(duration: Duration) -> f64 {
    duration.as_secs_f64() * 1000.0
}

fn main() {
    let args = Args::parse();
    let options = Options::from_args(&args);
    if args.orbit {
        timing::orbit_cameras();
    }
    if options.one_row {
        return one_row(&options);
    }
    let directory = Path::new("target/bench");
    if let Err(error) = std::fs::create_dir_all(directory) {
        eprintln!("cannot create {}: {error}", directory.display());
    }
    let tables = picked_tables(&options, directory);
    progress::start(tables.iter().map(|table| table.measurements).sum());
    for table in tables {
        (table.run)();
    }
}

/// A table the run measures: how many measurements it makes, and the run that makes them,
/// prints the table and writes its files.
struct Table<'a> {
    measurements: usize,
    run: Box<dyn FnOnce() + 'a>,
}

impl<'a> Table<'a> {
    fn new(measurements: usize, run: impl FnOnce() + 'a) -> Self {
        Self {
            measurements,
            run: Box::new(run),
        }
    }
}

/// The tables `options` picks, in the order they run, their files written into `directory`.
fn picked_tables<'a>(options: &'a Options, directory: &'a Path) -> Vec<Table<'a>> {
    let picked = options.tables;
    let mut tables = Vec::new();
    if picked.frame_times {
        tables.push(Table::new(frame_times::measurements(options), || {
            frame_times::table(options, directory);
        }));
        if options.variants {
            tables.push(Table::new(variants::measurements(options), || {
                variants::time_against_error(options, directory);
            }));
        }
    }
    if picked.ablation {
        tables.push(Table::new(ablation::measurements(options.rounds), || {
            ablation::table(
                options.ablation_size,
                options.rounds,
                options.frames,
                options.culling,
                directory,
            );
        }));
    }
    if picked.growth {
        tables.push(Table::new(growth::measurements(&options.growth), || {
            growth::table(&options.growth, options.frames, options.culling, directory);
        }));
    }
    if picked.shadows {
        tables.push(Table::new(
            showcase_costs::SHADOW_ROWS * options.rounds,
            || {
                showcase_costs::shadow_costs(options, directory);
            },
        ));
    }
    if picked.fallback {
        tables.push(Table::new(FALLBACK_ROWS * options.rounds, || {
            fallback_costs(options, directory);
        }));
    }
    if picked.materials {
        tables.push(Table::new(
            showcase_costs::MATERIAL_ROWS * options.rounds,
            || {
                showcase_costs::material_costs(options, directory);
            },
        ));
    }
    if picked.stylized {
        tables.push(Table::new(
            showcase_costs::STYLIZED_ROWS * options.rounds,
            || {
                showcase_costs::stylized_costs(options, directory);
            },
        ));
    }
    if picked.cubes {
        tables.push(Table::new(
            cubes::measurements(&options.cube_counts),
            || {
                let frames = Frames {
                    warmup: 1,
                    measured: options.frames.measured.min(15),
                    budget: options.frames.budget,
                };
                cubes::table(64, &options.cube_counts, frames, directory);
            },
        ));
    }
    if picked.lamps {
        // The smoke run measures cookies and shadows both only; at most three rounds.
        let kinds: &[_] = if options.quick {
            &lamps::QUICK_KINDS
        } else {
            &lamps::KINDS
        };
        let rounds = options.rounds.min(3);
        let size = options
            .sizes
            .first()
            .copied()
            .unwrap_or(256)
            .min(options.shadow_size);
        tables.push(Table::new(lamps::measurements(kinds, rounds), move || {
            lamps::table(
                size,
                rounds,
                options.frames,
                options.culling,
                kinds,
                directory,
            );
        }));
    }
    if picked.pairs {
        let size = if options.quick { 32 } else { PAIRS_SIZE };
        tables.push(Table::new(pairs::measurements(options.quick), move || {
            pairs::table(size, options.quick, options.frames, directory);
        }));
    }
    tables
}

/// The picture side of the table of one light on one pixel (`--pairs`), pixels: small, since
/// the exact highlight at shininess 10,000 takes seconds a frame on lavapipe.
const PAIRS_SIZE: u32 = 128;

/// The median of each row's measurements over `rounds` rounds in which the rows take turns:
/// a change in the machine's load then falls on every row alike, not on one.
/// `measure(row, round)` gives one measurement in ms.
fn alternating_medians<const ROWS: usize>(
    rounds: usize,
    measure: impl FnMut(usize, usize) -> f64,
) -> [f64; ROWS] {
    alternating_medians_of(ROWS, rounds, measure)
        .try_into()
        .expect("one median per row")
}

/// [`alternating_medians`] of a number of rows known at run time.
fn alternating_medians_of(
    rows: usize,
    rounds: usize,
    mut measure: impl FnMut(usize, usize) -> f64,
) -> Vec<f64> {
    let mut times = vec![Vec::new(); rows];
    for round in 0..rounds {
        for (row, row_times) in times.iter_mut().enumerate() {
            row_times.push(measure(row, round));
        }
    }
    times
        .into_iter()
        .map(|mut times: Vec<f64>| {
            times.sort_by(f64::total_cmp);
            times[times.len() / 2]
        })
        .collect()
}

/// The rows of the WebGL2 table: two scenes, each on both paths.
const FALLBACK_ROWS: usize = 4;

/// The scene data in storage buffers beside the data texture of devices without them
/// (WebGL2), all measured in this run. Each measurement runs in a process of its own, the
/// texture's with `WGPU_SETTINGS_PRIO=webgl2`, as a game gets its device: Bevy 0.19 did
/// not load shaders in a second app of one process whose device has WebGL2's limits after
/// one with full limits.
fn fallback_costs(options: &Options, directory: &Path) {
    let size = options.shadow_size;
    let scenes = [
        ("showcase", Scene::Showcase),
        ("field256", Scene::Field { lights: 256 }),
    ];
    let paths = [
        ("storage buffers", None),
        ("data texture (WebGL2 limits)", Some("webgl2")),
    ];
    let mut csv = String::from("scene,size,path,round,median_ms\n");
    let times: [f64; FALLBACK_ROWS] = alternating_medians(options.rounds, |row, round| {
        let ((argument, scene), (path, priority)) = (scenes[row / 2], paths[row % 2]);
        let median = one_row_in_own_process(argument, size, options.frames.measured, priority);
        let _ = writeln!(csv, "{},{size},{path},{round},{median:.3}", scene.name());
        crate::measured!(
            "{} {size}² {path}, round {round}: {median:.1} ms",
            scene.name()
        );
        median
    });
    let mut table = String::from(
        "| scene | size | storage buffers ms | data texture ms | texture / storage |\n|---|---|---|---|---|\n",
    );
    for ((_, scene), pair) in scenes.iter().zip(times.chunks(2)) {
        let _ = writeln!(
            table,
            "| {} | {size}² | {:.1} | {:.1} | {:.2} |",
            scene.name(),
            pair[0],
            pair[1],
            pair[1] / pair[0]
        );
    }
    println!(
        "\nThe scene data's two paths, Phong, median ms (the median of {} rounds):\n\n{table}",
        options.rounds
    );
    write(&directory.join("webgl2.csv"), &csv);
}

/// The Phong median frame time (ms) of `scene` at `size`², measured by this benchmark in a
/// child process (`--one-row`) whose `WGPU_SETTINGS_PRIO` is `priority` (unset for `None`).
fn one_row_in_own_process(scene: &str, size: u32, frames: usize, priority: Option<&str>) -> f64 {
    let mut command = std::process::Command::new(std::env::current_exe().expect("own path"));
    command.args(["--one-row", "--scene", scene, "--size", &size.to_string()]);
    command.args(["--frames", &frames.to_string()]);
    match priority {
        Some(priority) => command.env("WGPU_SETTINGS_PRIO", priority),
        None => command.env_remove("WGPU_SETTINGS_PRIO"),
    };
    let output = command.output().expect("the benchmark runs itself");
    let stdout = String::from_utf8_lossy(&output.stdout);
    stdout.trim().parse().unwrap_or_else(|_| {
        panic!(
            "--one-row {scene} {size} printed {stdout:?}: {}",
            String::from_utf8_lossy(&output.stderr)
        )
    })
}

/// `--one-row`: prints the Phong median frame time (ms) of the first `--scene` at the first
/// `--size`, for [`one_row_in_own_process`].
fn one_row(options: &Options) {
    let time = median_frame_time(
        options.scenes[0],
        options.sizes[0],
        Shading::Phong(Some(SpecularModel::Phong)),
        options.culling,
        options.frames,
    );
    println!("{:.3}", ms(time));
}

fn write(path: &Path, contents: &str) {
    match std::fs::write(path, contents) {
        Ok(()) => println!("wrote {}", path.display()),
        Err(error) => eprintln!("cannot write {}: {error}", path.display()),
    }
}
