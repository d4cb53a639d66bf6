//! The CPU cost of the gather system: writing 10, 1,000 and 10,000 lights into the light
//! buffer when all of them changed, and checking them when none did.
//!
//! ```sh
//! cargo bench --bench gather
//! ```

use bevy::{
    asset::AssetPlugin, camera::visibility::InheritedVisibility,
    ecs::schedule::SingleThreadedExecutor, prelude::*, transform::TransformPlugin,
};
use bevy_phong::{prelude::*, render::gather_lights};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::time::{Duration, Instant};

/// A world with `count` visible point and spot lights and the plugin's resources, and a
/// schedule that runs the gather system alone.
fn world_with_lights(count: usize) -> (App, Schedule) {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin::default(),
        TransformPlugin,
        PhongPlugin,
    ));
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
    // Single-threaded, so that the timing is the system's and not the executor's.
    let mut schedule = Schedule::default();
    schedule.set_executor(SingleThreadedExecutor::new());
    schedule.add_systems(gather_lights);
    schedule.run(app.world_mut());
    (app, schedule)
}

/// Marks every light changed, as moving them all would.
fn touch_all(world: &mut World) {
    let mut points = world.query::<&mut PhongPointLight>();
    for mut light in points.iter_mut(world) {
        light.set_changed();
    }
    let mut spots = world.query::<&mut PhongSpotLight>();
    for mut light in spots.iter_mut(world) {
        light.set_changed();
    }
}

fn gather(c: &mut Criterion) {
    let mut group = c.benchmark_group("gather");
    for count in [10, 1_000, 10_000] {
        let (mut app, mut schedule) = world_with_lights(count);
        group.bench_function(BenchmarkId::new("all_changed", count), |b| {
            // Only the gather is timed, not the marking.
            b.iter_custom(|iterations| {
                let mut total = Duration::ZERO;
                for _ in 0..iterations {
                    touch_all(app.world_mut());
                    let start = Instant::now();
                    schedule.run(app.world_mut());
                    total += start.elapsed();
                }
                total
            });
        });
        group.bench_function(BenchmarkId::new("none_changed", count), |b| {
            b.iter(|| schedule.run(app.world_mut()));
        });
    }
    group.finish();
}

criterion_group!(benches, gather);
criterion_main!(benches);
