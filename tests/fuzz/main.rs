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

mod cases;
mod harness;
mod mutations;
mod random;
mod shapes;

use cases::{Case, Cases};
use harness::{Counts, Harness};

/// Cases run by default: a few thousand, well under a minute in a debug build.
const DEFAULT_CASES: usize = 4_000;

/// Files loaded at once: the asset server loads them in parallel.
const BATCH: usize = 32;

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
    let seed = env_number("BEVY_PHONG_FUZZ_SEED", cases::DEFAULT_SEED);
    let root = std::env::temp_dir().join(format!("bevy_phong_fuzz_{}", std::process::id()));
    let (mut harness, canary) = Harness::new(&root);
    let mut generator = Cases::new(seed, canary);
    let mut counts = Counts::default();
    let start = std::time::Instant::now();
    let first = env_number("BEVY_PHONG_FUZZ_FIRST", 0) as usize;
    let only = std::env::var("BEVY_PHONG_FUZZ_ONLY").ok();
    let mut generated = 0;
    while generated < cases {
        let mut batch: Vec<Case> = (generated..(generated + BATCH).min(cases))
            .map(|index| generator.generate(index))
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
