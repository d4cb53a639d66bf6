//! The cost of one light on one pixel (`--pairs`), what a game budgets: a floor that fills
//! the picture under lights of one kind, each of which lights every pixel (no range, no
//! fall-off of its own, every pixel in front of it), timed beside the same floor without
//! lights. `(t_lit − t_dark) / (lights · pixels)` is the cost of a light-pixel pair. The
//! number of lights ([`Pairs::lit`]) keeps each lit frame well above the dark one's noise
//! and the slowest rows within seconds a frame.
//! Each kind (point, spot, and rect and disk lights with each highlight choice) at shininess
//! 1, 50, 1,000 and 10,000 with Lambert's diffuse light, and the default rect light with
//! wrapped and toon diffuse light at 50. Each row's error is that of one such light against
//! the reference model (its quadrature over an area light's area), on a smaller picture.

use crate::accuracy;
use crate::scene::{Scene, Shading};
use crate::timing::{Frames, median_frame_time};
use crate::{ms, write};
use bevy::prelude::*;
use bevy_phong::prelude::*;
use std::{fmt::Write as _, path::Path};

/// The side of the picture each row's error is measured on, pixels (the area lights'
/// reference integrates each pixel's light over the light's area).
const ERROR_SIZE: u32 = 32;

/// The kind of light a row measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairKind {
    Point,
    Spot,
    Rect(AreaHighlight),
    Disk(AreaHighlight),
}

impl PairKind {
    fn name(self) -> String {
        let highlight = |highlight: AreaHighlight| match highlight {
            AreaHighlight::Bounded => "bounded",
            AreaHighlight::Exact => "exact",
            AreaHighlight::Fitted => "fitted",
            AreaHighlight::RepresentativePoint => "representative point",
        };
        match self {
            Self::Point => "point".into(),
            Self::Spot => "spot".into(),
            Self::Rect(choice) => format!("rect, {}", highlight(choice)),
            Self::Disk(choice) => format!("disk, {}", highlight(choice)),
        }
    }
}

/// The floor and its lights: `lights` of `kind` (none for the dark floor), the floor's
/// shininess (Phong) and diffuse mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pairs {
    pub kind: PairKind,
    pub lights: usize,
    pub shininess: f32,
    pub diffuse: DiffuseMode,
}

impl Pairs {
    /// The floor of a row, lit: 64 point or spot lights, 16 area lights, 1 area light with
    /// the exact highlight from shininess 1,000 on (whose frame then takes seconds).
    fn lit(kind: PairKind, shininess: f32, diffuse: DiffuseMode) -> Self {
        let lights = match kind {
            PairKind::Point | PairKind::Spot => 64,
            PairKind::Rect(AreaHighlight::Exact) | PairKind::Disk(AreaHighlight::Exact)
                if shininess >= 1000.0 =>
            {
                1
            }
            PairKind::Rect(_) | PairKind::Disk(_) => 16,
        };
        Self {
            kind,
            lights,
            shininess,
            diffuse,
        }
    }

    pub fn name(self) -> String {
        format!(
            "floor, {} × {}, shininess {}, {}",
            self.lights,
            self.kind.name(),
            self.shininess,
            diffuse_name(self.diffuse)
        )
    }
}

fn diffuse_name(diffuse: DiffuseMode) -> &'static str {
    match diffuse {
        DiffuseMode::Lambert => "Lambert",
        DiffuseMode::Wrap(_) => "wrapped",
        DiffuseMode::Toon { .. } => "toon",
    }
}

/// Where the camera stands, looking at the origin: the floor (60 units across) fills the
/// picture.
pub const CAMERA: Vec3 = Vec3::new(0.0, 5.0, 3.0);

/// The floor, 60 units across at height 0.
pub fn floor() -> Mesh {
    Plane3d::default().mesh().size(60.0, 60.0).into()
}

/// Sets the floor's material as `pairs` says and spawns its lights: on a square grid 6
/// units across, 2.5 units up, the area lights facing down (a 1 × 0.5 panel, a disk of
/// radius 0.4), the spot lights pointing down with a cone of 80°.
pub fn apply(world: &mut World, pairs: Pairs) {
    for (_, material) in world.resource_mut::<Assets<PhongMaterial>>().iter_mut() {
        material.shininess = pairs.shininess;
        material.diffuse_mode = pairs.diffuse;
        material.specular_strength = 1.0;
    }
    let side = (pairs.lights as f32).sqrt().ceil().max(1.0) as usize;
    let step = 6.0 / side as f32;
    for i in 0..pairs.lights {
        let (x, z) = (
            ((i % side) as f32 + 0.5) * step - 3.0,
            ((i / side) as f32 + 0.5) * step - 3.0,
        );
        let transform = Transform::from_xyz(x, 2.5, z).looking_to(Vec3::NEG_Y, Vec3::Z);
        let color = Color::hsl(i as f32 * 22.5, 1.0, 0.5);
        match pairs.kind {
            PairKind::Point => {
                world.spawn((PhongPointLight { color, ..default() }, transform));
            }
            PairKind::Spot => {
                world.spawn((
                    PhongSpotLight {
                        color,
                        outer_angle: 80f32.to_radians(),
                        inner_angle: 70f32.to_radians(),
                        ..default()
                    },
                    transform,
                ));
            }
            PairKind::Rect(highlight) => {
                world.spawn((
                    PhongRectLight {
                        color,
                        width: 1.0,
                        height: 0.5,
                        highlight,
                        ..default()
                    },
                    transform,
                ));
            }
            PairKind::Disk(highlight) => {
                world.spawn((
                    PhongDiskLight {
                        color,
                        radius: 0.4,
                        highlight,
                        ..default()
                    },
                    transform,
                ));
            }
        }
    }
}

/// The kinds each shininess is measured with.
const KINDS: [PairKind; 10] = [
    PairKind::Point,
    PairKind::Spot,
    PairKind::Rect(AreaHighlight::Bounded),
    PairKind::Rect(AreaHighlight::Exact),
    PairKind::Rect(AreaHighlight::Fitted),
    PairKind::Rect(AreaHighlight::RepresentativePoint),
    PairKind::Disk(AreaHighlight::Bounded),
    PairKind::Disk(AreaHighlight::Exact),
    PairKind::Disk(AreaHighlight::Fitted),
    PairKind::Disk(AreaHighlight::RepresentativePoint),
];

/// The shininesses each kind is measured at.
const SHININESSES: [f32; 4] = [1.0, 50.0, 1000.0, 10_000.0];

/// The smoke run's rows (`--quick`): a point light and the default rect and disk lights, at
/// 50 and 10,000.
const QUICK_KINDS: [PairKind; 3] = [
    PairKind::Point,
    PairKind::Rect(AreaHighlight::Bounded),
    PairKind::Disk(AreaHighlight::Bounded),
];
const QUICK_SHININESSES: [f32; 2] = [50.0, 10_000.0];

/// The diffuse modes beside Lambert's, measured with the default rect light at 50.
const OTHER_DIFFUSE: [DiffuseMode; 2] = [
    DiffuseMode::Wrap(0.5),
    DiffuseMode::Toon {
        bands: 3,
        smoothing: 0.05,
    },
];

/// The rows of a run: each lit floor.
fn rows(quick: bool) -> Vec<Pairs> {
    let (kinds, shininesses): (&[PairKind], &[f32]) = if quick {
        (&QUICK_KINDS, &QUICK_SHININESSES)
    } else {
        (&KINDS, &SHININESSES)
    };
    let lambert = shininesses.iter().flat_map(|&shininess| {
        kinds
            .iter()
            .map(move |&kind| Pairs::lit(kind, shininess, DiffuseMode::Lambert))
    });
    let others = OTHER_DIFFUSE
        .iter()
        .map(|&diffuse| Pairs::lit(PairKind::Rect(AreaHighlight::Bounded), 50.0, diffuse));
    let mut rows: Vec<Pairs> = lambert.collect();
    if !quick {
        rows.extend(others);
    }
    rows
}

/// The dark floors the rows are timed against: one per diffuse mode.
fn dark(diffuse: DiffuseMode) -> Pairs {
    Pairs {
        kind: PairKind::Point,
        lights: 0,
        shininess: 50.0,
        diffuse,
    }
}

/// How many measurements [`table`] makes: each row's time and error, and the dark floors'.
pub fn measurements(quick: bool) -> usize {
    2 * rows(quick).len() + if quick { 1 } else { 1 + OTHER_DIFFUSE.len() }
}

/// The table: each row's cost per light-pixel pair (ns) at `size`², its ratio to a point
/// light's at the same shininess and diffuse mode, and its largest error against the
/// reference model.
pub fn table(size: u32, quick: bool, frames: Frames, directory: &Path) {
    let shading = Shading::Phong(Some(SpecularModel::Phong));
    let culling = PhongLightCulling::default();
    let time = |pairs: Pairs| {
        let median = ms(median_frame_time(
            Scene::Pairs(pairs),
            size,
            shading,
            culling,
            frames,
        ));
        crate::measured!("{} {size}²: {median:.1} ms", pairs.name());
        median
    };
    let mut dark_times: Vec<(DiffuseMode, f64)> = Vec::new();
    let mut csv =
        String::from("kind,lights,shininess,diffuse,frame_ms,dark_ms,ns_per_pair,error\n");
    let mut measured: Vec<(Pairs, f64, f64)> = Vec::new();
    for pairs in rows(quick) {
        let dark_ms = match dark_times.iter().find(|(mode, _)| *mode == pairs.diffuse) {
            Some(&(_, dark_ms)) => dark_ms,
            None => {
                let dark_ms = time(dark(pairs.diffuse));
                dark_times.push((pairs.diffuse, dark_ms));
                dark_ms
            }
        };
        let lit_ms = time(pairs);
        let pair_count = (pairs.lights as f64) * f64::from(size * size);
        let per_pair = (lit_ms - dark_ms).max(0.0) * 1e6 / pair_count;
        let one = Pairs { lights: 1, ..pairs };
        let error = accuracy::measure_at(Scene::Pairs(one), shading, culling, ERROR_SIZE).max;
        crate::measured!(
            "{}: {per_pair:.2} ns a pair, error {error:.2e}",
            pairs.name()
        );
        let _ = writeln!(
            csv,
            "{},{},{},{},{lit_ms:.3},{dark_ms:.3},{per_pair:.4},{error:.3e}",
            pairs.kind.name().replace(',', ""),
            pairs.lights,
            pairs.shininess,
            diffuse_name(pairs.diffuse)
        );
        measured.push((pairs, per_pair, error));
    }
    let mut table = String::from(
        "| kind | lights | shininess | diffuse | ns per light-pixel pair | × point | largest error |\n|---|---|---|---|---|---|---|\n",
    );
    for &(pairs, per_pair, error) in &measured {
        let point = measured
            .iter()
            .find(|(other, _, _)| {
                other.kind == PairKind::Point
                    && other.shininess == pairs.shininess
                    && other.diffuse == pairs.diffuse
            })
            .map(|&(_, point, _)| point);
        let ratio = match point {
            Some(point) if point > 0.0 => format!("{:.1}", per_pair / point),
            _ => "–".into(),
        };
        let _ = writeln!(
            table,
            "| {} | {} | {} | {} | {per_pair:.2} | {ratio} | {error:.1e} |",
            pairs.kind.name(),
            pairs.lights,
            pairs.shininess,
            diffuse_name(pairs.diffuse)
        );
    }
    println!(
        "\nOne light on one pixel at {size}², lights over every pixel against none (each the \
         median frame), the error of one light at {ERROR_SIZE}²:\n\n{table}"
    );
    write(&directory.join("pairs.csv"), &csv);
}
