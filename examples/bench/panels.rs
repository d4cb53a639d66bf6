//! Area lights on the time-against-error plot: 1, 16 or 256 `PhongRectLight` panels over the
//! field, facing down, their highlight integrated (`AreaHighlight::Exact`) or taken at a
//! representative point, beside the point-light variants. Each panel fades as
//! `1 / (1 + 0.2 d²)` from its nearest point on top of its own inverse square, and is cut off
//! 4 units from it, as the field's point lights are.

use crate::scene::{Scene, Shading, scatter};
use crate::timing::median_frame_time;
use crate::{Options, accuracy, ms, plot};
use bevy::prelude::*;
use bevy_phong::prelude::*;
use std::fmt::Write as _;

/// The panels of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Panels {
    pub count: usize,
    pub highlight: AreaHighlight,
}

impl Panels {
    /// The counts the plot measures, and the one the smoke run (`--quick`) does.
    pub const COUNTS: [usize; 3] = [1, 16, 256];
    pub const QUICK_COUNT: usize = 16;

    pub fn name(self) -> String {
        let highlight = match self.highlight {
            AreaHighlight::Bounded => "bounded",
            AreaHighlight::Exact => "integrated",
            AreaHighlight::RepresentativePoint => "representative point",
            AreaHighlight::Fitted => "fitted",
        };
        format!(
            "field, {} rect light{} ({highlight})",
            self.count,
            if self.count == 1 { "" } else { "s" }
        )
    }
}

/// Spawns the panels: 1.2 × 0.6 units, 1.6 to 2.6 units above the field (the first at its
/// middle), each of its own hue and turned about the vertical.
pub fn spawn_panels(world: &mut World, panels: Panels) {
    for i in 0..panels.count {
        let (u, v, w) = if panels.count == 1 {
            (0.5, 0.5, 0.0)
        } else {
            scatter(i)
        };
        let position = Vec3::new(u * 24.0 - 12.0, 1.6 + w, v * 24.0 - 12.0);
        world.spawn((
            PhongRectLight {
                color: Color::hsl(w * 360.0, 1.0, 0.5),
                width: 1.2,
                height: 0.6,
                decay: Decay::quadratic(0.2),
                range: Some(4.0),
                highlight: panels.highlight,
                ..default()
            },
            Transform::from_translation(position).looking_to(
                Vec3::NEG_Y,
                Quat::from_rotation_y(w * std::f32::consts::TAU) * Vec3::Z,
            ),
        ));
    }
}

/// The highlight choices each count of panels is measured with.
const HIGHLIGHTS: [AreaHighlight; 4] = [
    AreaHighlight::Bounded,
    AreaHighlight::Exact,
    AreaHighlight::Fitted,
    AreaHighlight::RepresentativePoint,
];

/// The counts of panels a run measures: 16 only in the smoke run (`--quick`).
fn counts(options: &Options) -> &'static [usize] {
    if options.quick {
        &[Panels::QUICK_COUNT]
    } else {
        &Panels::COUNTS
    }
}

/// How many measurements [`time_against_error`] makes.
pub fn measurements(options: &Options) -> usize {
    counts(options).len() * HIGHLIGHTS.len()
}

/// Times each count of panels with each highlight choice and measures its error, as the
/// point-light variants are: a row of `table` and `csv` and a choice of the plot's `series`
/// each (each count a scene of its own); the smoke run (`--quick`) measures 16 panels only.
pub fn time_against_error(
    options: &Options,
    table: &mut String,
    csv: &mut String,
    series: &mut Vec<plot::Choice>,
) {
    for &count in counts(options) {
        for highlight in HIGHLIGHTS {
            let scene = Scene::Panels(Panels { count, highlight });
            let shading = Shading::Phong(Some(SpecularModel::Phong));
            let culling = PhongLightCulling::default();
            let time = ms(median_frame_time(
                scene,
                options.variant_size,
                shading,
                culling,
                options.frames,
            ));
            let accuracy = accuracy::measure(scene, shading, culling);
            let (error, p95) = (accuracy.max, accuracy.p95);
            let name = scene.name();
            crate::measured!("{name}: {time:.1} ms, error {error:.2e} (95 % within {p95:.2e})");
            let _ = writeln!(
                table,
                "| {name} | {time:.1} | {error:.2e} | {:.3} | {p95:.2e} |",
                error * 255.0
            );
            let _ = writeln!(csv, "{name},{time:.3},{error:.3e},{p95:.3e}");
            series.push(plot::Choice {
                label: format!("{highlight:?}"),
                scene: format!(
                    "field, {count} rect light{}",
                    if count == 1 { "" } else { "s" }
                ),
                error: error.max(1e-9),
                time,
            });
        }
    }
}
