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
//! cargo run --example bench -- --frame-times --scene field256 --scene wide60000 --size 32 --orbit
//!                                           # far lights under a camera that moves every frame
//! ```
//!
//! `--orbit` turns every camera half a degree around the scene's middle before each frame.
//!
//! The table flags (`--frame-times`, `--shadows`, `--webgl2`, `--ablation`, `--growth`,
//! `--materials`, `--stylized`, `--lamps`, `--cubes`)
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
//! one's fitted cost per light per megapixel (`--growth`; see `growth.rs`).
//!
//! Each frame is timed from the start of `App::update` until the device has finished the
//! frame's work; the tables give the median over the measured frames, after the pipelines
//! compiled and a few warm-up frames. Errors are the largest per-channel difference from
//! `bevy_phong::reference` over a 128² render (relative to `max(1, |expected|)`), measured
//! with the render tests' harness. It writes `target/bench/*.csv` and `target/bench/*.png`.

mod ablation;
mod accuracy;
mod cubes;
mod features;
mod frame_times;
mod growth;
mod lamps;
mod panels;
mod plot;
mod scene;
mod timing;
mod variants;

use bevy::prelude::*;
use bevy_phong::{PhongLightCulling, SpecularModel};
use scene::{Scene, Shading};
use std::{fmt::Write as _, path::Path, time::Duration};
use timing::{Frames, median_frame_time, median_frame_time_and_picture};

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

impl Options {
    fn from_args() -> Self {
        let args: Vec<String> = std::env::args().skip(1).collect();
        let mut options = Self::defaults(args.iter().any(|arg| arg == "--quick"));
        options.variants = !args.iter().any(|arg| arg == "--no-variants");
        options.tables = Tables::from_args(&args);
        options.one_row = args.iter().any(|arg| arg == "--one-row");
        let values = |flag: &str| -> Vec<String> {
            args.windows(2)
                .filter(|pair| pair[0] == flag)
                .map(|pair| pair[1].clone())
                .collect()
        };
        if let Some(frames) = values("--frames").first().and_then(|v| v.parse().ok()) {
            options.frames.measured = frames;
        }
        for name in values("--culling") {
            match name.as_str() {
                "none" => options.culling = PhongLightCulling::NONE,
                "exact" => options.culling = PhongLightCulling::EXACT,
                "default" => options.culling = PhongLightCulling::default(),
                other => eprintln!("unknown culling {other}: none, exact or default"),
            }
        }
        let counts: Vec<usize> = values("--count")
            .iter()
            .filter_map(|v| v.parse().ok())
            .collect();
        if !counts.is_empty() {
            options.cube_counts = counts;
        }
        let sizes: Vec<u32> = values("--size")
            .iter()
            .filter_map(|v| v.parse().ok())
            .collect();
        if let Some(&size) = sizes.first() {
            options.ablation_size = size;
            options.sizes = sizes;
        }
        let scenes: Vec<Scene> = values("--scene")
            .iter()
            .filter_map(|name| match name.as_str() {
                "showcase" => Some(Scene::Showcase),
                "field16" => Some(Scene::Field { lights: 16 }),
                "field256" => Some(Scene::Field { lights: 256 }),
                "field4096" => Some(Scene::Field { lights: 4096 }),
                "wide3840" => Some(Scene::WideWorld {
                    lights: 256,
                    far: 3_840,
                }),
                "wide60000" => Some(Scene::WideWorld {
                    lights: 256,
                    far: 60_000,
                }),
                lamps if lamps.starts_with("lamps") => {
                    lamps::Lamps::from_name(lamps).map(Scene::Lamps)
                }
                other => {
                    eprintln!(
                        "unknown scene {other}: showcase, field16, field256, field4096, \
                         wide3840, wide60000, or lamps with any of -cookies, -shadows, -far \
                         (in that order)"
                    );
                    None
                }
            })
            .collect();
        if !scenes.is_empty() {
            options.scenes = scenes;
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
    };

    /// The tables whose flags are in `args`, or all of them when none is.
    fn from_args(args: &[String]) -> Self {
        let named = |flag: &str| args.iter().any(|arg| arg == flag);
        let picked = Self {
            frame_times: named("--frame-times"),
            shadows: named("--shadows"),
            fallback: named("--webgl2"),
            ablation: named("--ablation"),
            growth: named("--growth"),
            materials: named("--materials"),
            stylized: named("--stylized"),
            lamps: named("--lamps"),
            cubes: named("--cubes"),
        };
        let any = picked.frame_times
            || picked.shadows
            || picked.fallback
            || picked.ablation
            || picked.growth
            || picked.materials
            || picked.stylized
            || picked.cubes
            || picked.lamps;
        if any { picked } else { Self::ALL }
    }
}

fn ms(duration: Duration) -> f64 {
    duration.as_secs_f64() * 1000.0
}

fn main() {
    let options = Options::from_args();
    if std::env::args().any(|arg| arg == "--orbit") {
        timing::orbit_cameras();
    }
    if options.one_row {
        return one_row(&options);
    }
    let directory = Path::new("target/bench");
    if let Err(error) = std::fs::create_dir_all(directory) {
        eprintln!("cannot create {}: {error}", directory.display());
    }
    let tables = options.tables;
    if tables.frame_times {
        frame_times::table(&options, directory);
        if options.variants {
            variants::time_against_error(&options, directory);
        }
    }
    if tables.ablation {
        ablation::table(
            options.ablation_size,
            options.rounds,
            options.frames,
            options.culling,
            directory,
        );
    }
    if tables.growth {
        growth::table(&options.growth, options.frames, options.culling, directory);
    }
    if tables.shadows {
        shadow_costs(&options, directory);
    }
    if tables.fallback {
        fallback_costs(&options, directory);
    }
    if tables.materials {
        material_costs(&options, directory);
    }
    if tables.stylized {
        stylized_costs(&options, directory);
    }
    if tables.cubes {
        cubes::table(
            64,
            &options.cube_counts,
            Frames {
                warmup: 1,
                measured: options.frames.measured.min(15),
                budget: options.frames.budget,
            },
            directory,
        );
    }
    if tables.lamps {
        lamps::table(
            options
                .sizes
                .first()
                .copied()
                .unwrap_or(256)
                .min(options.shadow_size),
            options.rounds.min(3),
            options.frames,
            options.culling,
            if options.quick {
                &lamps::QUICK_KINDS
            } else {
                &lamps::KINDS
            },
            directory,
        );
    }
}

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
    let times: [f64; 4] = alternating_medians(options.rounds, |row, round| {
        let ((argument, scene), (path, priority)) = (scenes[row / 2], paths[row % 2]);
        let median = one_row_in_own_process(argument, size, options.frames.measured, priority);
        let _ = writeln!(csv, "{},{size},{path},{round},{median:.3}", scene.name());
        eprintln!(
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

/// The cost of shadows: the showcase on a floor with its lights casting shadows or not, and
/// casting them into a split screen (two cameras side by side, each with cascades of its
/// own), Phong beside `StandardMaterial`, all measured in this run.
fn shadow_costs(options: &Options, directory: &Path) {
    let size = options.shadow_size;
    let phong = Shading::Phong(Some(SpecularModel::Phong));
    let mut csv = String::from("size,shading,shadows,split_screen,round,median_ms\n");
    let rows = [
        ("Phong", phong, false, false),
        ("Phong", phong, true, false),
        ("Phong", phong, true, true),
        ("Standard", Shading::Standard, false, false),
        ("Standard", Shading::Standard, true, false),
        ("Standard", Shading::Standard, true, true),
    ];
    let times: [f64; 6] = alternating_medians(options.rounds, |row, round| {
        let (name, shading, shadows, split_screen) = rows[row];
        let scene = Scene::ShowcaseOnFloor {
            shadows,
            split_screen,
        };
        let median = ms(median_frame_time(
            scene,
            size,
            shading,
            options.culling,
            options.frames,
        ));
        let _ = writeln!(
            csv,
            "{size},{name},{shadows},{split_screen},{round},{median:.3}"
        );
        eprintln!(
            "{} {size}² {name}, round {round}: {median:.1} ms",
            scene.name()
        );
        median
    });
    let [
        phong_off,
        phong_on,
        phong_split,
        standard_off,
        standard_on,
        standard_split,
    ] = times;
    let table = format!(
        "| size | cameras | Phong | Phong, shadows | Standard | Standard, shadows | Phong shadows / Standard shadows | Phong shadows / Phong |\n\
         |---|---|---|---|---|---|---|---|\n\
         | {size}² | one | {phong_off:.1} | {phong_on:.1} | {standard_off:.1} | {standard_on:.1} | {:.2} | {:.2} |\n\
         | {size}² | two side by side | | {phong_split:.1} | | {standard_split:.1} | {:.2} | |\n\
         \n\
         Split screen over one camera, shadows on: Phong {:.2}, Standard {:.2}.\n",
        phong_on / standard_on,
        phong_on / phong_off,
        phong_split / standard_split,
        phong_split / phong_on,
        standard_split / standard_on,
    );
    println!(
        "\nShadows, median ms (the median of {} rounds): the showcase on a floor, a cascaded directional light and two \
         point lights casting shadows or not (1024² maps), seen by one camera or by two side by side (each drawing half \
         the picture, each with cascades of its own):\n\n{table}",
        options.rounds
    );
    write(&directory.join("shadows.csv"), &csv);
}

/// The showcase with each group of material features beside the plain showcase, Phong and
/// Standard (with the nearest settings Bevy has), at the shadow table's size, the rows
/// taking turns over the rounds.
fn material_costs(options: &Options, directory: &Path) {
    let size = options.shadow_size;
    let phong = Shading::Phong(Some(SpecularModel::Phong));
    let groups = [
        None,
        Some(features::Features::SurfaceInputs),
        Some(features::Features::BakedLight),
        Some(features::Features::Environment),
        Some(features::Features::Converted),
        Some(features::Features::ConvertedEnvironment),
    ];
    const GROUPS: usize = 6;
    let scene = |group: Option<features::Features>| group.map_or(Scene::Showcase, Scene::Featured);
    let mut csv = String::from("size,scene,shading,round,median_ms\n");
    // Each row's picture (from its first round), to show that its features are drawn.
    let mut pictures: [Vec<u8>; 2 * GROUPS] = [const { Vec::new() }; 2 * GROUPS];
    let times: [f64; 2 * GROUPS] = alternating_medians(options.rounds, |row, round| {
        let (name, shading) = if row < GROUPS {
            ("Phong", phong)
        } else {
            ("Standard", Shading::Standard)
        };
        let scene = scene(groups[row % GROUPS]);
        let (median, picture) = median_frame_time_and_picture(
            scene,
            size,
            shading,
            options.culling,
            options.frames,
            &[],
        );
        let median = ms(median);
        if round == 0 {
            pictures[row] = picture;
        }
        let _ = writeln!(csv, "{size},{},{name},{round},{median:.3}", scene.name());
        eprintln!(
            "{} {size}² {name}, round {round}: {median:.1} ms",
            scene.name()
        );
        median
    });
    let mut table = String::from(
        "| scene | Phong ms | Standard ms | Phong / Standard | Phong / plain Phong | Standard / plain Standard | pixels changed, Phong / Standard |\n|---|---|---|---|---|---|---|\n",
    );
    for (row, group) in groups.iter().enumerate() {
        let (phong, standard) = (times[row], times[GROUPS + row]);
        let _ = writeln!(
            table,
            "| {} | {phong:.1} | {standard:.1} | {:.2} | {:.2} | {:.2} | {:.0} % / {:.0} % |",
            scene(*group).name(),
            phong / standard,
            phong / times[0],
            standard / times[GROUPS],
            ablation::changed_percent(&pictures[0], &pictures[row]),
            ablation::changed_percent(&pictures[GROUPS], &pictures[GROUPS + row]),
        );
    }
    println!(
        "\nMaterial features, median ms at {size}² (the median of {} rounds):\n\n{table}",
        options.rounds
    );
    write(&directory.join("materials.csv"), &csv);
}

/// The showcase drawn with each stylized mode beside the default material, Phong only, at
/// the shadow table's size, the rows taking turns over the rounds.
fn stylized_costs(options: &Options, directory: &Path) {
    use features::Features;
    let size = options.shadow_size;
    let modes = [
        None,
        Some(Features::Wrap),
        Some(Features::ToonBands),
        Some(Features::ToonRamp),
        Some(Features::ToonHighlight),
        Some(Features::Rim),
        Some(Features::RimLitSide),
        Some(Features::Hemisphere),
        Some(Features::Cookies),
    ];
    let scene = |mode: Option<Features>| mode.map_or(Scene::Showcase, Scene::Featured);
    let phong = Shading::Phong(Some(SpecularModel::Phong));
    let mut csv = String::from("size,scene,round,median_ms\n");
    let mut pictures: [Vec<u8>; 9] = [const { Vec::new() }; 9];
    let times: [f64; 9] = alternating_medians(options.rounds, |row, round| {
        let scene = scene(modes[row]);
        let (median, picture) =
            median_frame_time_and_picture(scene, size, phong, options.culling, options.frames, &[]);
        let median = ms(median);
        if round == 0 {
            pictures[row] = picture;
        }
        let _ = writeln!(csv, "{size},{},{round},{median:.3}", scene.name());
        eprintln!(
            "{} {size}² Phong, round {round}: {median:.1} ms",
            scene.name()
        );
        median
    });
    let mut table =
        String::from("| scene | Phong ms | × the default | pixels changed |\n|---|---|---|---|\n");
    for (row, mode) in modes.iter().enumerate() {
        let _ = writeln!(
            table,
            "| {} | {:.1} | {:.2} | {:.0} % |",
            scene(*mode).name(),
            times[row],
            times[row] / times[0],
            ablation::changed_percent(&pictures[0], &pictures[row]),
        );
    }
    println!(
        "\nStylized modes, median ms at {size}² (the median of {} rounds):\n\n{table}",
        options.rounds
    );
    write(&directory.join("stylized.csv"), &csv);
}

fn write(path: &Path, contents: &str) {
    match std::fs::write(path, contents) {
        Ok(()) => println!("wrote {}", path.display()),
        Err(error) => eprintln!("cannot write {}: {error}", path.display()),
    }
}
