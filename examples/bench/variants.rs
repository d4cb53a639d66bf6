//! The speed/accuracy variants of the Phong shading on the field of point lights, and the
//! table and plot of each variant's run time against its error (the rect lights' rows,
//! `panels.rs`, join them).

use crate::scene::{Scene, Shading};
use crate::timing::median_frame_time;
use crate::{Options, accuracy, ms, panels, plot, write};
use bevy_phong::{PhongLightCulling, SpecularModel};
use std::{fmt::Write as _, path::Path};

/// A speed/accuracy variant of the Phong shading, on one of the two variant scenes.
struct Variant {
    name: String,
    /// `true`: the scene's lights have ranges; `false`: only ε bounds their reach.
    ranged: bool,
    /// `PhongMaterial` lit per pixel or per vertex, with its highlight.
    shading: Shading,
    culling: PhongLightCulling,
}

/// The variants `--quick` measures: one of each kind of shading and culling.
const QUICK_VARIANTS: [&str; 4] = [
    "ranges: Phong, no clusters",
    "ranges: default (clusters, eps=1/1024)",
    "ranges: per vertex, fine floor",
    "no ranges: clusters, eps=1/64",
];

fn variants() -> Vec<Variant> {
    let variant = |name: &str, ranged, shading, epsilon: f32, clusters| Variant {
        name: name.into(),
        ranged,
        shading,
        culling: PhongLightCulling { epsilon, clusters },
    };
    let phong = Shading::Phong(Some(SpecularModel::Phong));
    let per_vertex = |fine_floor| Shading::PhongPerVertex {
        specular_model: Some(SpecularModel::Phong),
        fine_floor,
    };
    let default_epsilon = PhongLightCulling::DEFAULT_EPSILON;
    let mut variants = vec![
        variant("ranges: Phong, no clusters", true, phong, 0.0, false),
        variant(
            "ranges: Blinn-Phong, no clusters",
            true,
            Shading::Phong(Some(SpecularModel::BlinnPhong)),
            0.0,
            false,
        ),
        variant(
            "ranges: no specular, no clusters",
            true,
            Shading::Phong(None),
            0.0,
            false,
        ),
        variant("ranges: Phong, clusters", true, phong, 0.0, true),
        variant(
            "ranges: default (clusters, eps=1/1024)",
            true,
            phong,
            default_epsilon,
            true,
        ),
        variant(
            "ranges: per vertex, 2-triangle floor",
            true,
            per_vertex(false),
            default_epsilon,
            true,
        ),
        variant(
            "ranges: per vertex, fine floor",
            true,
            per_vertex(true),
            default_epsilon,
            true,
        ),
        variant("no ranges: Phong, no culling", false, phong, 0.0, false),
    ];
    for (name, epsilon) in [
        ("1/1024", default_epsilon),
        ("1/64", 1.0 / 64.0),
        ("1/8", 0.125),
        ("1", 1.0),
    ] {
        let name = format!("no ranges: clusters, eps={name}");
        variants.push(variant(&name, false, phong, epsilon, true));
    }
    variants.push(variant(
        "no ranges: per vertex, fine floor, eps=1/1024",
        false,
        per_vertex(true),
        default_epsilon,
        true,
    ));
    variants
}

/// The variants a run measures: all, or in the smoke run (`--quick`) [`QUICK_VARIANTS`].
fn picked(options: &Options) -> impl Iterator<Item = Variant> {
    let quick = options.quick;
    variants()
        .into_iter()
        .filter(move |variant| !quick || QUICK_VARIANTS.contains(&variant.name.as_str()))
}

/// How many measurements [`time_against_error`] makes.
pub fn measurements(options: &Options) -> usize {
    picked(options).count() + panels::measurements(options)
}

/// Each variant's frame time next to its error against the reference model.
pub fn time_against_error(options: &Options, directory: &Path) {
    let lights = options.variant_lights;
    let size = options.variant_size;
    let mut table = String::from(
        "| variant | ms | max error | error × 255 | 95 % of pixels within |\n|---|---|---|---|---|\n",
    );
    let mut csv = String::from("variant,median_ms,max_error,p95_error\n");
    let mut series = Vec::new();
    for variant in picked(options) {
        let scene = if variant.ranged {
            Scene::Field { lights }
        } else {
            Scene::FieldWithoutRanges { lights }
        };
        let time = ms(median_frame_time(
            scene,
            size,
            variant.shading,
            variant.culling,
            options.frames,
        ));
        let accuracy = accuracy::measure(scene, variant.shading, variant.culling);
        let (error, p95) = (accuracy.max, accuracy.p95);
        crate::measured!(
            "{}: {time:.1} ms, error {error:.2e} (95 % within {p95:.2e})",
            variant.name
        );
        let _ = writeln!(
            table,
            "| {} | {time:.1} | {error:.2e} | {:.3} | {p95:.2e} |",
            variant.name,
            error * 255.0
        );
        let _ = writeln!(csv, "{},{time:.3},{error:.3e},{p95:.3e}", variant.name);
        let (scene_name, label) = variant
            .name
            .split_once(": ")
            .unwrap_or(("", variant.name.as_str()));
        series.push(plot::Choice {
            label: label.to_string(),
            scene: format!("{scene_name} ({})", scene.name()),
            // Exact variants still carry f32 rounding; the floor keeps them on a log axis.
            error: error.max(1e-9),
            time,
        });
    }
    // The area lights, each highlight choice, on the same plot.
    panels::time_against_error(options, &mut table, &mut csv, &mut series);
    println!(
        "\nRun time against error, the field of {lights} point lights, with ranges (4 units) and \
         without (1 / (1 + 4d²)), and of 1, 16 and 256 rect lights with ranges, at {size}² \
         (error at {}²):\n\n{table}",
        accuracy::ERROR_SIZE
    );
    write(&directory.join("time_vs_error.csv"), &csv);
    plot::pareto(
        &directory.join("time_vs_error.png"),
        &format!(
            "Run time against error: field of {lights} point lights or of rect lights, \
             {size}x{size}"
        ),
        "largest error against the f64 model (1/255 is one 8-bit step)",
        "median frame time, ms",
        &series,
    );
}
