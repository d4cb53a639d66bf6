//! Many meshes, many materials (`--cubes`): a grid of cubes under a sun and 8 point lights,
//! each cube with a material of its own (distinct colors, no textures) or all sharing one,
//! and the same count of meshes of 10 kinds with their own materials; Phong beside
//! `StandardMaterial` and the constant floor, at 64² so that the pixels cost little and the
//! frame is the CPU's. Each row gives the frame's split: the main world, the render world
//! (extraction included) and the wait on the device.

use crate::scene::{ConstantColor, Scene, Shading, scatter};
use crate::timing::{Frames, median_frame_split};
use crate::write;
use bevy::prelude::*;
use bevy_phong::{PhongLightCulling, prelude::*};
use std::{fmt::Write as _, path::Path};

/// A grid of meshes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cubes {
    /// Meshes in the grid (a square number).
    pub count: usize,
    /// Whether every mesh shares one material (else each has its own).
    pub shared: bool,
    /// Kinds of mesh (1: cubes; else cubes, spheres, cylinders… in turn).
    pub kinds: usize,
}

impl Cubes {
    pub fn name(self) -> String {
        let meshes = if self.kinds == 1 {
            format!("{} cubes", self.count)
        } else {
            format!("{} meshes of {} kinds", self.count, self.kinds)
        };
        let materials = if self.shared {
            "sharing one material"
        } else {
            "each with its own material"
        };
        format!("{meshes}, {materials}")
    }

    /// Cubes along a side of the grid.
    fn side(self) -> usize {
        (self.count as f64).sqrt().ceil() as usize
    }

    /// Where the camera stands, above the grid, looking at its middle.
    pub fn camera_position(self) -> Vec3 {
        let extent = self.side() as f32 * SPACING;
        Vec3::new(0.0, extent * 0.9, extent * 0.7)
    }
}

/// Units between two meshes of the grid.
const SPACING: f32 = 1.5;

/// The `kind`-th mesh of the ten.
fn mesh_of_kind(kind: usize) -> Mesh {
    match kind % 10 {
        0 => Cuboid::new(1.0, 1.0, 1.0).into(),
        1 => Sphere::new(0.5).mesh().uv(16, 8),
        2 => Cylinder::new(0.4, 1.0).into(),
        3 => Torus::new(0.2, 0.45).into(),
        4 => Capsule3d::new(0.3, 0.5).into(),
        5 => Cone::new(0.5, 1.0).into(),
        6 => Cuboid::new(1.0, 0.4, 0.6).into(),
        7 => Sphere::new(0.5)
            .mesh()
            .ico(2)
            .unwrap_or_else(|_| Sphere::new(0.5).into()),
        8 => ConicalFrustum::default().into(),
        _ => Tetrahedron::default().into(),
    }
}

/// Spawns the grid and its lights drawn with `shading`.
pub fn spawn(world: &mut World, cubes: Cubes, shading: Shading) {
    let meshes: Vec<Handle<Mesh>> = (0..cubes.kinds)
        .map(|kind| world.resource_mut::<Assets<Mesh>>().add(mesh_of_kind(kind)))
        .collect();
    let color = |index: usize| {
        let (u, v, w) = scatter(index);
        Color::srgb(0.2 + 0.8 * u, 0.2 + 0.8 * v, 0.2 + 0.8 * w)
    };
    let mut shared = None;
    let side = cubes.side();
    let offset = (side as f32 - 1.0) * SPACING / 2.0;
    for index in 0..cubes.count {
        let color = color(if cubes.shared { 0 } else { index });
        let position = Vec3::new(
            (index % side) as f32 * SPACING - offset,
            0.0,
            (index / side) as f32 * SPACING - offset,
        );
        let mesh = Mesh3d(meshes[index % cubes.kinds].clone());
        let transform = Transform::from_translation(position);
        let reused = shared.clone().filter(|_| cubes.shared);
        let material: UntypedHandle = reused.unwrap_or_else(|| {
            let handle = material(world, shading, color);
            shared = Some(handle.clone());
            handle
        });
        let mut entity = world.spawn((mesh, transform));
        match shading {
            Shading::Standard => {
                entity.insert(MeshMaterial3d::<StandardMaterial>(material.typed()))
            }
            Shading::Constant => entity.insert(MeshMaterial3d::<ConstantColor>(material.typed())),
            _ => entity.insert(MeshMaterial3d::<PhongMaterial>(material.typed())),
        };
    }
    spawn_lights(world, shading);
}

/// A new material of `color` drawn with `shading`.
fn material(world: &mut World, shading: Shading, color: Color) -> UntypedHandle {
    match shading {
        Shading::Standard => world
            .resource_mut::<Assets<StandardMaterial>>()
            .add(StandardMaterial::from(color))
            .untyped(),
        Shading::Constant => world
            .resource_mut::<Assets<ConstantColor>>()
            .add(ConstantColor::new(color.into()))
            .untyped(),
        _ => world
            .resource_mut::<Assets<PhongMaterial>>()
            .add(PhongMaterial {
                base_color: color,
                shininess: 30.0,
                ..default()
            })
            .untyped(),
    }
}

/// A sun and 8 point lights over the grid.
fn spawn_lights(world: &mut World, shading: Shading) {
    let sun = Transform::default().looking_to(Vec3::new(-0.4, -1.0, -0.3), Vec3::Y);
    let points = (0..8).map(|i| {
        let (u, v, w) = scatter(i + 77);
        (
            Vec3::new(u * 30.0 - 15.0, 2.0, v * 30.0 - 15.0),
            Color::hsl(w * 360.0, 1.0, 0.5),
        )
    });
    match shading {
        Shading::Standard => {
            world.spawn((DirectionalLight::default(), sun));
            for (position, color) in points {
                world.spawn((
                    PointLight {
                        color,
                        range: 8.0,
                        ..default()
                    },
                    Transform::from_translation(position),
                ));
            }
        }
        Shading::Constant => {}
        _ => {
            world.spawn((PhongDirectionalLight::default(), sun));
            for (position, color) in points {
                world.spawn((
                    PhongPointLight {
                        color,
                        range: Some(8.0),
                        ..default()
                    },
                    Transform::from_translation(position),
                ));
            }
        }
    }
}

/// The shadings of each grid's row.
const SHADINGS: [(&str, Shading); 3] = [
    ("Phong", Shading::Phong(Some(SpecularModel::Phong))),
    ("Standard", Shading::Standard),
    ("constant", Shading::Constant),
];

/// The grids of `counts`: each with a material per cube and with one shared material; the
/// largest (from 1,000 cubes) also with meshes of ten kinds.
fn grids(counts: &[usize]) -> Vec<Cubes> {
    let mut grids = Vec::new();
    for &count in counts {
        grids.push(Cubes {
            count,
            shared: false,
            kinds: 1,
        });
        grids.push(Cubes {
            count,
            shared: true,
            kinds: 1,
        });
    }
    // Not in the quick run's grid of 100, where the meshes of 10 kinds add nothing.
    if let Some(&largest) = counts.last().filter(|&&count| count >= 1_000) {
        grids.push(Cubes {
            count: largest,
            shared: false,
            kinds: 10,
        });
    }
    grids
}

/// Whether `grid` is measured with `shading`. Materials that each take a batch of their own
/// cost a frame more than linearly in their number (1,600 of them took 0.8–1 s a frame on
/// lavapipe): past 2,000, only the Phong column is measured for them.
fn measured(grid: Cubes, shading: Shading) -> bool {
    let batched = grid.shared || matches!(shading, Shading::Phong(_));
    grid.count <= 2_000 || batched
}

/// How many measurements [`table`] makes.
pub fn measurements(counts: &[usize]) -> usize {
    grids(counts)
        .into_iter()
        .map(|grid| {
            SHADINGS
                .iter()
                .filter(|&&(_, shading)| measured(grid, shading))
                .count()
        })
        .sum()
}

/// The table: each grid with Phong, `StandardMaterial` and the constant floor, one after
/// the other in this run, at `size`² (64 by default), each the median of `frames`.
pub fn table(size: u32, counts: &[usize], frames: Frames, directory: &Path) {
    let mut csv = String::from("scene,size,shading,main_ms,render_ms,device_ms,frame_ms\n");
    let mut table = String::from(
        "| scene | Phong ms (main / render / device) | Standard ms (main / render / device) | constant ms (main / render / device) | Phong / Standard |\n|---|---|---|---|---|\n",
    );
    for grid in grids(counts) {
        let mut cells = Vec::new();
        let mut totals = Vec::new();
        for (name, shading) in SHADINGS {
            if !measured(grid, shading) {
                cells.push("not measured".to_owned());
                totals.push(f64::NAN);
                continue;
            }
            let split = median_frame_split(
                Scene::Cubes(grid),
                size,
                shading,
                PhongLightCulling::default(),
                frames,
            );
            let total = split.frame_ms();
            crate::measured!("{} {size}² {name}: {total:.1} ms", grid.name());
            let _ = writeln!(
                csv,
                "{},{size},{name},{:.3},{:.3},{:.3},{total:.3}",
                grid.name(),
                split.main_ms,
                split.render_ms,
                split.device_ms
            );
            cells.push(format!(
                "{total:.1} ({:.1} / {:.1} / {:.1})",
                split.main_ms, split.render_ms, split.device_ms
            ));
            totals.push(total);
        }
        let _ = writeln!(
            table,
            "| {} | {} | {} | {} | {} |",
            grid.name(),
            cells[0],
            cells[1],
            cells[2],
            ratio(totals[0], totals[1])
        );
    }
    println!(
        "\nMany meshes and materials at {size}², median ms of a frame and its split:\n\n{table}"
    );
    write(&directory.join("cubes.csv"), &csv);
}

/// `a / b` to two places, or "–" where either was not measured.
fn ratio(a: f64, b: f64) -> String {
    if a.is_nan() || b.is_nan() {
        "–".to_owned()
    } else {
        format!("{:.2}", a / b)
    }
}
