//! The shader ablation: the showcase drawn with `PhongMaterial`'s fragment shader cut after
//! each stage of its work, beside the constant-color floor, so that each stage's cost is the
//! difference between two rows measured in the same run. Each stage reads only the 16-byte
//! words of the light records that hold the fields its work uses; a row reads every field
//! the full shader reads and computes nothing, and another does the full shader's work
//! with the lights written into the shader: together they split the lights' cost into
//! reading and arithmetic. `StandardMaterial` is the last row, for the ratio to it.
//!
//! A stage is a set of defs of the benchmark's own fragment shader, `ablation.wesl` beside
//! this file, which the benchmark puts in place of `PhongMaterial`'s fragment shader for
//! the row ([`median_frame_time_and_picture`]); the crate's shaders carry no cut. That
//! shader is made of the crate's WGSL functions (`phong_surface`, `incidence`,
//! `phong_light`, `light_at`, the cluster look-up, ...) in the loops of the crate's
//! `direct_lights`, so each cut removes one stage and nothing else:
//!
//! - `NO_LIGHTS`: the fragment returns a color made of the surface set-up alone (normal,
//!   view vector, the material's colors and maps).
//! - `NO_TERMS`: the light loops read the fields of every record they reach that the
//!   diffuse term uses (position, direction, color) and sum them, computing nothing else;
//!   with `ALL_FIELDS`, every field the shader reads without shadows.
//! - `NO_ATTENUATION`: every light arrives at full strength along L (no distance
//!   attenuation, range or cone).
//! - `NO_HIGHLIGHT`: each light's term is its diffuse part.
//! - `NO_AMBIENT`: the color is the lights' sum alone (no ambient, no emissive).
//! - `CONSTANT_LIGHTS`: the full shader with the showcase's three light records written
//!   into it: every light's arithmetic, no record read, no clusters. Its picture is the full
//!   shader's (the table shows the pixels that differ), so the row is the cost of the
//!   lighting if reading the lights cost nothing.
//!
//! The full shader's row draws with the crate's shader itself, unchanged.

use crate::{
    alternating_medians, ms,
    scene::{Scene, Shading},
    timing::{Frames, median_frame_time_and_picture},
    write,
};
use bevy_phong::{PhongLightCulling, SpecularModel};
use std::{fmt::Write as _, path::Path};

/// One row of the table: what the meshes are drawn with.
struct Stage {
    /// The row's name in the table and the CSV file (quoted there: it holds no quotes).
    name: &'static str,
    shading: Shading,
    /// The defs of `ablation.wesl`, drawn in place of `PhongMaterial`'s fragment shader;
    /// none: the crate's shader.
    defs: &'static [&'static str],
    /// The row (index into [`STAGES`]) whose work this one adds to; `None` for the floor.
    builds_on: Option<usize>,
}

const PHONG: Shading = Shading::Phong(Some(SpecularModel::Phong));

/// The rows: from the floor to the shader without cuts, each stage adding one part of the
/// work to the row above; then the loops reading every field the full shader reads, which
/// adds to the surface set-up; then the full shader with the lights written into it; then
/// `StandardMaterial`, which the targets are also stated against.
const STAGES: [Stage; 10] = [
    Stage {
        name: "floor: constant color",
        shading: Shading::Constant,
        defs: &[],
        builds_on: None,
    },
    Stage {
        name: "surface set-up alone",
        shading: PHONG,
        defs: &["NO_LIGHTS"],
        builds_on: Some(0),
    },
    Stage {
        name: "+ the loops reading position, direction and color",
        shading: PHONG,
        defs: &["NO_TERMS", "NO_AMBIENT"],
        builds_on: Some(1),
    },
    Stage {
        name: "+ diffuse (L and N·L)",
        shading: PHONG,
        defs: &["NO_ATTENUATION", "NO_HIGHLIGHT", "NO_AMBIENT"],
        builds_on: Some(2),
    },
    Stage {
        name: "+ attenuation and cone (reading range, decay and the cone's fields)",
        shading: PHONG,
        defs: &["NO_HIGHLIGHT", "NO_AMBIENT"],
        builds_on: Some(3),
    },
    Stage {
        name: "+ highlight (reading the specular color)",
        shading: PHONG,
        defs: &["NO_AMBIENT"],
        builds_on: Some(4),
    },
    Stage {
        name: "full shader (+ ambient and emissive)",
        shading: PHONG,
        defs: &[],
        builds_on: Some(5),
    },
    Stage {
        name: "surface set-up + the loops reading every field the full shader reads",
        shading: PHONG,
        defs: &["NO_TERMS", "ALL_FIELDS", "NO_AMBIENT"],
        builds_on: Some(1),
    },
    Stage {
        name: "full shader, the three lights written into it (no record read)",
        shading: PHONG,
        defs: &["CONSTANT_LIGHTS"],
        builds_on: Some(6),
    },
    Stage {
        name: "StandardMaterial under the equivalent Bevy lights (for scale)",
        shading: Shading::Standard,
        defs: &[],
        builds_on: None,
    },
];

/// How many measurements [`table`] makes.
pub fn measurements(rounds: usize) -> usize {
    STAGES.len() * rounds
}

/// The ablation table of the showcase at `size`²: the rows take turns over `rounds` rounds
/// and each gives the median of its rounds (ms), with its ratio to the floor, its cost over
/// the row it builds on, and how many pixels its picture changes from that row's (a cut
/// that did not reach the shader would change none where the stage has work to do).
/// Writes `ablation.csv` (one line per row and round) into `directory`.
pub fn table(
    size: u32,
    rounds: usize,
    frames: Frames,
    culling: PhongLightCulling,
    directory: &Path,
) {
    let scene = Scene::Showcase;
    let mut csv = String::from("size,stage,round,median_ms\n");
    let mut pictures: [Vec<u8>; STAGES.len()] = [const { Vec::new() }; STAGES.len()];
    let times: [f64; STAGES.len()] = alternating_medians(rounds, |row, round| {
        let stage = &STAGES[row];
        let (median, picture) =
            median_frame_time_and_picture(scene, size, stage.shading, culling, frames, stage.defs);
        let median = ms(median);
        if round == 0 {
            pictures[row] = picture;
        }
        let _ = writeln!(csv, "{size},\"{}\",{round},{median:.3}", stage.name);
        crate::measured!(
            "{} {size}² {}, round {round}: {median:.1} ms",
            scene.name(),
            stage.name
        );
        median
    });
    let floor = times[0];
    let standard = times[STAGES.len() - 1];
    let mut table = String::from(
        "| stage | ms | × floor | × Standard | added ms | pixels changed |\n\
         |---|---|---|---|---|---|\n",
    );
    for (row, stage) in STAGES.iter().enumerate() {
        let (added, changed) = match stage.builds_on {
            Some(base) => (
                format!("{:+.1}", times[row] - times[base]),
                format!("{:.1} %", changed_percent(&pictures[base], &pictures[row])),
            ),
            None => ("".into(), "".into()),
        };
        let _ = writeln!(
            table,
            "| {} | {:.1} | {:.2} | {:.2} | {added} | {changed} |",
            stage.name,
            times[row],
            times[row] / floor,
            times[row] / standard,
        );
    }
    println!(
        "\nThe shader ablation, {} at {size}², median ms (the median of {rounds} rounds); \
         added ms and pixels changed: from the row each builds on (the row above; for the \
         reading row, the surface set-up; for the lights written in, the full shader):\n\n{table}",
        scene.name()
    );
    write(&directory.join("ablation.csv"), &csv);
}

/// The share of pixels (RGBA, 4 bytes each) in which `a` and `b` differ, percent.
pub fn changed_percent(a: &[u8], b: &[u8]) -> f64 {
    let pixels = a.len().min(b.len()) / 4;
    let changed = a
        .chunks_exact(4)
        .zip(b.chunks_exact(4))
        .filter(|(a, b)| a != b)
        .count();
    100.0 * changed as f64 / pixels.max(1) as f64
}
