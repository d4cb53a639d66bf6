//! The CPU cost of the gather and cluster systems: writing 10, 1,000 and 10,000 lights into
//! the light buffer and listing them in a camera's clusters when all of them moved, when all
//! of them changed color, and when all of them were marked changed with nothing different;
//! and checking them when none changed; the 10,000 moved lights system by system. Then the crowd (`crowd.rs`): the main-world CPU time
//! that 100 animated skinned casters cost a cascaded directional light's shadows, beside
//! posing them on the CPU.
//!
//! ```sh
//! cargo bench --bench gather                    # all
//! cargo bench --bench gather -- gather_split    # 10,000 moved lights, system by system
//! cargo bench --bench gather -- crowd           # the crowd alone
//! ```

mod crowd;

use bevy::camera::primitives::Frustum;
use bevy::{
    asset::AssetPlugin,
    camera::visibility::InheritedVisibility,
    ecs::{
        schedule::{IntoScheduleConfigs, SingleThreadedExecutor},
        system::ScheduleSystem,
    },
    prelude::*,
    transform::TransformPlugin,
};
use bevy_phong::{
    prelude::*,
    testing::{assign_lights_to_clusters, gather_lights},
};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::time::{Duration, Instant};

/// An app with the plugin's main-world systems and no renderer.
fn main_world_app() -> App {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin::default(),
        TransformPlugin,
        PhongPlugin,
    ));
    app
}

/// A schedule that runs `systems` alone, single-threaded, so that the timing is the
/// systems' and not the executor's.
fn schedule_of<M>(systems: impl IntoScheduleConfigs<ScheduleSystem, M>) -> Schedule {
    let mut schedule = Schedule::default();
    schedule.set_executor(SingleThreadedExecutor::new());
    schedule.add_systems(systems);
    schedule
}

/// A world with `count` visible point and spot lights, a camera that sees them all, and the
/// plugin's resources, and a schedule that runs the gather and cluster systems alone.
fn world_with_lights(count: usize) -> (App, Schedule) {
    let mut app = main_world_app();
    app.update();
    let world = app.world_mut();
    for i in 0..count {
        let transform = Transform::from_xyz(i as f32 * 0.01, 2.0, (i % 100) as f32);
        let visible = (
            GlobalTransform::from(transform),
            InheritedVisibility::VISIBLE,
        );
        if i % 4 == 0 {
            world.spawn((PhongSpotLight::default(), transform, visible));
        } else {
            world.spawn((
                PhongPointLight {
                    range: Some(5.0),
                    ..default()
                },
                transform,
                visible,
            ));
        }
    }
    // The camera above the lights (x 0 to 100, z 0 to 100), looking down at their middle.
    let transform =
        Transform::from_xyz(50.0, 80.0, 130.0).looking_at(Vec3::new(50.0, 0.0, 50.0), Vec3::Y);
    let projection = Projection::Perspective(PerspectiveProjection {
        aspect_ratio: 16.0 / 9.0,
        ..default()
    });
    let frustum: Frustum = projection.compute_frustum(&GlobalTransform::from(transform));
    world.spawn((
        Camera3d::default(),
        projection,
        frustum,
        transform,
        GlobalTransform::from(transform),
    ));
    let mut schedule = schedule_of((gather_lights, assign_lights_to_clusters).chain());
    schedule.run(app.world_mut());
    (app, schedule)
}

/// How every light is changed before each timed gather.
#[derive(Clone, Copy)]
enum Change {
    /// Moved along x, back and forth: every record's position and the clusters change.
    Moved,
    /// Given another color, back and forth: every record's constants change, and its
    /// ε-limited reach with them.
    Recolored,
    /// Marked changed with the same value: everything is looked at, nothing is different.
    Touched,
}

impl Change {
    const ALL: [Self; 3] = [Self::Moved, Self::Recolored, Self::Touched];

    fn name(self) -> &'static str {
        match self {
            Self::Moved => "all_moved",
            Self::Recolored => "all_recolored",
            Self::Touched => "all_touched",
        }
    }

    /// Changes every light; `odd` alternates between the two values.
    fn apply(self, world: &mut World, odd: bool) {
        match self {
            Self::Moved => {
                let step = Vec3::X * if odd { 0.01 } else { -0.01 };
                let mut lights = world.query_filtered::<&mut GlobalTransform, Or<(
                    With<PhongPointLight>,
                    With<PhongSpotLight>,
                )>>();
                for mut transform in lights.iter_mut(world) {
                    *transform = GlobalTransform::from_translation(transform.translation() + step);
                }
            }
            Self::Recolored | Self::Touched => {
                let color = match (self, odd) {
                    (Self::Recolored, true) => Color::srgb(1.0, 0.9, 0.8),
                    _ => Color::WHITE,
                };
                let mut points = world.query::<&mut PhongPointLight>();
                for mut light in points.iter_mut(world) {
                    light.color = color;
                }
                let mut spots = world.query::<&mut PhongSpotLight>();
                for mut light in spots.iter_mut(world) {
                    light.color = color;
                }
            }
        }
    }
}

fn gather(c: &mut Criterion) {
    let mut group = c.benchmark_group("gather");
    for count in [10, 1_000, 10_000] {
        let (mut app, mut schedule) = world_with_lights(count);
        for change in Change::ALL {
            group.bench_function(BenchmarkId::new(change.name(), count), |b| {
                // Only the gather is timed, not the change.
                b.iter_custom(|iterations| {
                    let mut total = Duration::ZERO;
                    for iteration in 0..iterations {
                        change.apply(app.world_mut(), iteration % 2 == 1);
                        let start = Instant::now();
                        schedule.run(app.world_mut());
                        total += start.elapsed();
                    }
                    total
                });
            });
        }
        group.bench_function(BenchmarkId::new("none_changed", count), |b| {
            b.iter(|| schedule.run(app.world_mut()));
        });
    }
    group.finish();
}

/// The 10,000 moved lights of [`gather`] split between its two systems: the gather (the
/// records written) and the clusters (the records listed in the camera's clusters), each
/// timed alone in the same iterations.
fn gather_split(c: &mut Criterion) {
    let (mut app, _) = world_with_lights(10_000);
    let mut gather = schedule_of(gather_lights);
    let mut clusters = schedule_of(assign_lights_to_clusters);
    let mut group = c.benchmark_group("gather_split");
    for (name, timed_clusters) in [
        ("gather_lights", false),
        ("assign_lights_to_clusters", true),
    ] {
        group.bench_function(BenchmarkId::new(name, "10000_moved"), |b| {
            b.iter_custom(|iterations| {
                let mut total = Duration::ZERO;
                for iteration in 0..iterations {
                    Change::Moved.apply(app.world_mut(), iteration % 2 == 1);
                    let start = Instant::now();
                    gather.run(app.world_mut());
                    let gathered = Instant::now();
                    clusters.run(app.world_mut());
                    total += if timed_clusters {
                        gathered.elapsed()
                    } else {
                        gathered - start
                    };
                }
                total
            });
        });
    }
    group.finish();
}

criterion_group!(benches, gather, gather_split, crowd::crowd);
criterion_main!(benches);
