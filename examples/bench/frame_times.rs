//! The first table (`--frame-times`): each picked scene and size with Phong,
//! `StandardMaterial` and the constant floor, each frame's split, and the Phong error.

use crate::scene::{Scene, Shading};
use crate::timing::{self, median_frame_split};
use crate::{Options, accuracy, plot, write};
use bevy_phong::SpecularModel;
use std::{fmt::Write as _, path::Path};

/// The shadings of each row: Phong, Standard and the constant-color floor.
const SHADINGS: usize = 3;

/// How many measurements [`table`] makes.
pub fn measurements(options: &Options) -> usize {
    options.sizes.len() * options.scenes.len() * SHADINGS
}

/// Phong beside Standard and the constant-color floor, each scene at each size.
pub fn table(options: &Options, directory: &Path) {
    let default_culling = options.culling;
    let mut table = String::from(
        "| scene | size | Phong ms | Standard ms | constant ms | Phong/Standard | Phong/constant | Phong error | Phong main / render / device ms | Standard main / render / device ms |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut csv = String::from("scene,size,shading,median_ms,main_ms,render_ms,device_ms\n");
    let mut series: Vec<plot::Series> = Vec::new();
    for &size in &options.sizes {
        let shadings: [_; SHADINGS] = [
            ("Phong", Shading::Phong(Some(SpecularModel::Phong))),
            ("Standard", Shading::Standard),
            ("constant", Shading::Constant),
        ];
        let first_series = series.len();
        series.extend(shadings.iter().map(|(name, _)| plot::Series {
            label: format!("{name} {size}x{size}"),
            points: Vec::new(),
        }));
        for &scene in &options.scenes {
            let splits = shadings.map(|(name, shading)| {
                let split =
                    median_frame_split(scene, size, shading, default_culling, options.frames);
                let median = split.frame_ms();
                let _ = writeln!(
                    csv,
                    "{},{size},{name},{median:.3},{:.3},{:.3},{:.3}",
                    scene.name(),
                    split.main_ms,
                    split.render_ms,
                    split.device_ms
                );
                crate::measured!("{} {size}² {name}: {median:.1} ms", scene.name());
                split
            });
            let times = splits.map(|split| split.frame_ms());
            let split_cell = |split: timing::FrameSplit| {
                format!(
                    "{:.1} / {:.1} / {:.1}",
                    split.main_ms, split.render_ms, split.device_ms
                )
            };
            let error = accuracy::measure(
                scene,
                Shading::Phong(Some(SpecularModel::Phong)),
                default_culling,
            )
            .max;
            let lights = match scene {
                Scene::Showcase | Scene::ShowcaseOnFloor { .. } | Scene::Featured(_) => 3,
                Scene::Field { lights } | Scene::FieldWithoutRanges { lights } => lights,
                Scene::WideWorld { lights, far } => lights + far,
                Scene::Lamps(lamps) => lamps.light_count(),
                Scene::Cubes(_) => 9,
                Scene::Panels(panels) => panels.count,
                Scene::Pairs(pairs) => pairs.lights,
            };
            for (offset, time) in times.iter().enumerate() {
                series[first_series + offset]
                    .points
                    .push((lights as f64, *time));
            }
            let _ = writeln!(
                table,
                "| {} | {size}² | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} | {error:.1e} | {} | {} |",
                scene.name(),
                times[0],
                times[1],
                times[2],
                times[0] / times[1],
                times[0] / times[2],
                split_cell(splits[0]),
                split_cell(splits[1]),
            );
        }
    }
    println!("\nFrame time, median ms (Phong with the default PhongLightCulling):\n\n{table}");
    write(&directory.join("frame_times.csv"), &csv);
    plot::lines(
        &directory.join("frame_times.png"),
        "Frame time on lavapipe: Phong, StandardMaterial, constant color",
        "point lights in the scene",
        "median frame time, ms",
        &series,
    );
}
