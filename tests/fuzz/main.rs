//! A fuzzer for scene and material files, on the CPU only: files generated from a fixed seed
//! (byte mutations of the sample files, mutations that know the format, scenes of edge
//! cases) are loaded through Bevy's asset server and spawned in an app without a renderer.
//!
//! It asserts: no panic, anywhere; every refused file's error names a line and column or a
//! field; no non-finite float in the gathered light buffer or in a material's uniform; the
//! canary, a material file just outside the asset folder, is never read; no file hangs.
//!
//! ```sh
//! cargo test --test fuzz                                   # 4,000 cases, as CI runs it (~15 s)
//! BEVY_PHONG_FUZZ_CASES=100000 cargo test --test fuzz -- --nocapture   # ~7 minutes
//! BEVY_PHONG_FUZZ_SEED=7 cargo test --test fuzz            # another sequence of cases
//! BEVY_PHONG_FUZZ_FIRST=3648 BEVY_PHONG_FUZZ_CASES=3680 cargo test --test fuzz  # cases 3648..3680
//! BEVY_PHONG_FUZZ_ONLY=paths cargo test --test fuzz       # the cases of one generator
//! ```

mod harness;
mod mutations;
mod random;
mod shapes;

use harness::{Case, Counts, Harness, Kind};
use random::Random;

/// Cases run by default: a few thousand, well under a minute in a debug build.
const DEFAULT_CASES: usize = 4_000;

/// Files loaded at once: the asset server loads them in parallel.
const BATCH: usize = 32;

/// A second scene and material that use every field and variant the samples leave out.
const FULL_SCENE: &str = r##"(
    camera: Some((position: (0.0, 3.0, 9.0), looking_at: (0.0, 0.0, 0.0), fov_degrees: 45.0)),
    ambient: Some(Srgba(0.1, 0.1, 0.1, 1.0)),
    lights: [
        Directional(color: Srgb(1.0, 1.0, 1.0), specular: Some(Linear(0.5, 0.5, 0.5)), direction: (-1.0, -1.0, -0.5)),
        Point(color: Hex("#ff8800"), position: (1.0, 2.0, 3.0), decay: (constant: 1.0, linear: 0.09, quadratic: 0.032), range: Some(20.0)),
        Spot(color: Linear(1.0, 1.0, 1.0), position: (0.0, 6.0, 3.0), direction: (0.0, -1.0, -0.5), decay: (constant: 1.0, linear: 0.0, quadratic: 0.01), range: None, inner_angle_degrees: 12.5, outer_angle_degrees: 17.5, exponent: 2.0),
    ],
    objects: [
        (mesh: Sphere(radius: 1.0), transform: (translation: (0.0, 1.0, 0.0), rotation: (0.0, 45.0, 0.0), scale: (1.0, 1.0, 1.0)), material: Inline((base_color: Srgb(1.0, 0.0, 1.0), ambient_factor: 1.0, specular_color: Srgb(1.0, 1.0, 1.0), specular_strength: 2.0, shininess: 50.0, specular_model: BlinnPhong, emissive: Linear(0.0, 0.0, 0.0), alpha_mode: Mask(0.5), flip_normal_map_y: true))),
        (mesh: Cuboid(size: (1.0, 2.0, 1.0)), material: File("../materials/textured.phong.ron")),
        (mesh: Plane(size: (10.0, 10.0))),
        (mesh: Torus(minor_radius: 0.25, major_radius: 0.75)),
        (mesh: Cylinder(radius: 0.5, height: 1.0)),
        (mesh: Capsule(radius: 0.5, length: 1.0)),
        (mesh: Cone(radius: 0.5, height: 1.0)),
    ],
)"##;

const FULL_MATERIAL: &str = r##"(
    base_color: Hex("#ffcc00"),
    specular_color: Srgba(1.0, 0.9, 0.8, 1.0),
    specular_strength: 1.5,
    shininess: 120.0,
    specular_model: Phong,
    emissive: Linear(0.1, 0.0, 0.0),
    alpha_mode: Blend,
    base_color_texture: Some("crate.png"),
    specular_texture: Some("crate_specular.png"),
    emissive_texture: None,
    normal_map_texture: Some("../textures/normal.png"),
    flip_normal_map_y: false,
)"##;

fn sample(path: &str) -> String {
    let path = format!("{}/assets/{path}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|error| panic!("{path}: {error}"))
}

/// The `index`th case of the sequence `random` draws.
fn generate(random: &mut Random, index: usize, seeds: &[(Kind, String)], canary: &str) -> Case {
    let (kind, seed) = random.pick(seeds);
    let (kind, seed) = (*kind, seed.as_str());
    let self_name = match kind {
        Kind::Scene => format!("case{index}.phong_scene.ron"),
        Kind::Material => format!("case{index}.phong.ron"),
    };
    let (kind, generator, bytes) = match random.below(100) {
        0..25 => (kind, "bytes", mutations::bytes(random, seed.as_bytes())),
        25..45 => (
            kind,
            "numbers",
            mutations::numbers_replaced(random, seed).into(),
        ),
        45..55 => (
            kind,
            "variants",
            mutations::variant_swapped(random, seed).into(),
        ),
        55..58 => (kind, "nesting", mutations::nested(random, seed)),
        58..62 => (
            kind,
            "long strings",
            mutations::long_string(random, seed).into(),
        ),
        62..67 => (kind, "non-UTF-8", mutations::not_utf8(random, seed)),
        67..82 => {
            let text = mutations::path_replaced(random, seed, &self_name, canary);
            (kind, "paths", text.into())
        }
        _ => (Kind::Scene, "shapes", shapes::scene(random).into()),
    };
    Case {
        index,
        kind,
        generator,
        bytes,
    }
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|value| value.replace('_', "").parse().ok())
        .unwrap_or(default)
}

#[test]
fn generated_files_never_panic_always_say_where_and_never_reach_the_gpu_non_finite() {
    harness::count_panics();
    let cases = env_number("BEVY_PHONG_FUZZ_CASES", DEFAULT_CASES as u64) as usize;
    let seed = env_number("BEVY_PHONG_FUZZ_SEED", 0x5eed_0013);
    let root = std::env::temp_dir().join(format!("bevy_phong_fuzz_{}", std::process::id()));
    let brass = sample("materials/brass.phong.ron");
    let mut harness = Harness::new(
        &root,
        &[
            ("materials/brass.phong.ron", brass.as_str()),
            ("materials/textured.phong.ron", FULL_MATERIAL),
        ],
    );
    let seeds = [
        (Kind::Scene, sample("scenes/shapes.phong_scene.ron")),
        (Kind::Scene, FULL_SCENE.to_owned()),
        (Kind::Material, brass),
        (Kind::Material, FULL_MATERIAL.to_owned()),
    ];
    let canary = harness.canary();
    let mut random = Random::new(seed);
    let mut counts = Counts::default();
    let start = std::time::Instant::now();
    let first = env_number("BEVY_PHONG_FUZZ_FIRST", 0) as usize;
    let only = std::env::var("BEVY_PHONG_FUZZ_ONLY").ok();
    let mut generated = 0;
    while generated < cases {
        let mut batch: Vec<Case> = (generated..(generated + BATCH).min(cases))
            .map(|index| generate(&mut random, index, &seeds, &canary))
            .collect();
        generated += batch.len();
        batch.retain(|case| {
            case.index >= first && only.as_ref().is_none_or(|g| g == case.generator)
        });
        // A panic in a system leaves the app unusable: stop there and report.
        let run = std::panic::AssertUnwindSafe(|| harness.run_batch(&batch, &mut counts));
        if std::panic::catch_unwind(run).is_err() {
            let cases: Vec<_> = batch
                .iter()
                .map(|case| (case.index, case.generator))
                .collect();
            println!("the app panicked in the batch of cases {cases:?}");
            break;
        }
    }
    let _ = std::fs::remove_dir_all(&root);
    let (panics, panic_messages) = harness::panics();

    println!(
        "fuzz, seed {seed:#x}, {:.1} s:\n  inputs {}\n  loaded {}\n  rejected {}\n  \
         rejected without line:column or field {}\n  hung {}\n  panics {panics}\n  \
         non-finite floats {}\n  canary reads {}",
        start.elapsed().as_secs_f64(),
        counts.inputs,
        counts.loaded,
        counts.rejected,
        counts.rejected_without_place.len(),
        counts.hung.len(),
        counts.non_finite_floats,
        counts.canary_reads,
    );
    for (generator, [inputs, loaded, rejected]) in &counts.by_generator {
        println!(
            "    {generator:>12}: {inputs:>6} files, {loaded:>6} loaded, {rejected:>6} rejected"
        );
    }
    assert_eq!(panics, 0, "{panic_messages:#?}");
    assert!(
        counts.rejected_without_place.is_empty(),
        "{:#?}",
        &counts.rejected_without_place[..counts.rejected_without_place.len().min(10)]
    );
    assert!(counts.hung.is_empty(), "{:#?}", counts.hung);
    assert_eq!(
        counts.non_finite_floats, 0,
        "{:#?}",
        counts.non_finite_examples
    );
    assert_eq!(counts.canary_reads, 0);
    if only.is_none() {
        assert_eq!(counts.inputs, cases - first.min(cases));
    }
    assert_eq!(counts.loaded + counts.rejected, counts.inputs);
}
