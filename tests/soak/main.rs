//! The soak test: frame after frame of random light and mesh churn from a fixed seed, at a
//! small size. Lights of every built-in kind are spawned, moved, recolored, hidden, shown
//! and despawned, their count rising from 0 to [`PEAK_LIGHTS`] and falling back to 0;
//! meshes come and go; invalid values (NaN, ±∞, negative, `f32::MAX`, 1e38, zero and huge
//! scales, angles out of range) are written into light, shadow, transform, ambient and
//! material fields; a few lights cast shadows for a while.
//!
//! It asserts:
//! - no frame panics;
//! - no NaN or infinite pixel in a float readback every [`READBACK_EVERY`] frames;
//! - the resident set grows by at most [`RSS_GROWTH_BOUND`] after the warm-up;
//! - the frame time follows the light count, not the frame number: for each band of light
//!   counts with enough frames (the long run), the median frame time of the falling half of
//!   the run is at most [`BAND_RATIO_BOUND`] times that of the rising half; over all counts
//!   (either run), the mean of the falling half at most [`HALF_RATIO_BOUND`] times that of
//!   the rising half. Frame time here is the CPU time of the whole process (Bevy's threads
//!   and lavapipe's, which rasterize): on a shared machine the wall clock also counts time
//!   the machine gives to others (one CI run's falling half took 4.55 times the wall time
//!   of its rising half; on a quiet machine the same run gives 1.24, and CPU time 1.03 to
//!   1.24 either way). Wall-time ratios are printed beside.
//!
//! It is a test binary of its own, so that nothing else runs in its process while it
//! measures the process's CPU time (`cargo test` runs test binaries one after another, and
//! the tests of one binary side by side).
//!
//! ```sh
//! cargo test --test soak -- --nocapture                             # 150 frames, as CI
//! BEVY_PHONG_SOAK_FRAMES=2000 cargo test --test soak -- --nocapture   # the long run
//! ```

#[path = "../fuzz/random.rs"]
mod random;

use crate::random::Random;
use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::{Harness, Progress};
use std::time::Instant;

/// Render size: small, so that the run measures the crate's per-frame work rather than
/// the rasterizer's.
const SIZE: u32 = 64;
/// Frames run by default (CI): a full rise and fall of the light count and two readbacks,
/// under a minute on two cores with lavapipe in a debug build (a frame of 3,000 lights takes
/// about half a second there).
const DEFAULT_FRAMES: usize = 150;
/// The most lights at once, halfway through the run.
const PEAK_LIGHTS: usize = 3_000;
/// Frames of churn in the warm-up (a quick rise to the peak and back).
const WARM_UP_FRAMES: usize = 30;
/// Pixels are read back every this many frames, and after the last.
const READBACK_EVERY: usize = 100;
/// At most this many lights cast shadows at once (each costs its shadow map passes).
const MAX_SHADOWED: usize = 3;
/// The seed of the run's random choices.
const SEED: u64 = 0x50a4_0013;

/// Largest growth of the resident set between the end of the warm-up and the end of the
/// run, in bytes. The warm-up has already reached the peak light count with shadows on, so
/// every buffer, shadow map and pipeline is as large as it gets; what may still grow is
/// allocator fragmentation and the driver's caches. Measured on lavapipe: 0 to 2 MB in the
/// 150 frames of the short run, 14 MB in the 2,000 of the long one. A leak of one light
/// buffer (3,000 × 80 bytes) per frame would add 36 MB in 150 frames.
const RSS_GROWTH_BOUND: u64 = 48 << 20;

/// Largest ratio of the median frame time in the falling half of the run to that in the
/// rising half, for the same band of light counts. Frames `f` and `frames - f` have the same
/// light count and the same shadow-casting lights, so the ratio is 1 but for which lights
/// they are: how many meshes there are, and which lights reach every pixel. That last one
/// drifts: the falling half's lights have lived through more invalid writes, and a light
/// given a range of 1e38 is listed in every cluster of the view, so that every fragment
/// loops over it; the rising half's frame time jumps about when the first such light is
/// likely to appear. With a dozen frames per band in the short run, the
/// bands of fewer than 1,000 lights differ by up to 4.5 for that reason (see also
/// [`MIN_BAND_FRAMES`]). A cost that grows with the frame number (records left in the light
/// buffer, clusters never cleared, change detection running over dead entities) grows without
/// bound and passes any such ratio within the long run.
const BAND_RATIO_BOUND: f64 = 2.5;
/// Bands with fewer frames than this in either half are printed but not held to
/// [`BAND_RATIO_BOUND`]: the short run has a dozen frames per band, in which the light count
/// changes by 40 a frame and a frame's time still carries some of the previous frame's work
/// (more lights in the falling half, fewer in the rising one); its medians differed by a
/// factor of up to 4 in the band of the fewest lights. The long run has about 160 frames
/// per band and changes the count by 3 a frame.
const MIN_BAND_FRAMES: usize = 30;
/// Largest ratio of the mean frame time of the falling half to that of the rising half,
/// over all light counts: the bands of many lights, where such a light matters least,
/// weigh most in it, and measured 1.03 to 1.24; a cost growing with the frame number grows
/// past any bound.
const HALF_RATIO_BOUND: f64 = 1.5;
/// Light-count bands the frame times are compared in.
const BANDS: usize = 6;

/// Hostile floats written into fields.
const BAD_FLOATS: [f32; 8] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    -1.0,
    f32::MAX,
    1e38,
    -0.0,
    1e-45,
];

/// Spot angles in radians, most of them out of range (`[0, π]`).
const BAD_ANGLES: [f32; 7] = [f32::NAN, f32::INFINITY, 1.745e7, -1.0, 4.0, 0.0, 3.2];

/// Light scales: zero (no direction), huge and tiny (directions that overflow or underflow
/// when squared), `f32::MAX`.
const BAD_SCALES: [f32; 4] = [0.0, 3e38, 1e-30, f32::MAX];

fn uniform(random: &mut Random, low: f32, high: f32) -> f32 {
    low + (high - low) * ((random.next_u64() >> 40) as f32 / (1u64 << 24) as f32)
}

fn bad(random: &mut Random) -> f32 {
    *random.pick(&BAD_FLOATS)
}

/// The resident set size of this process, in bytes (`/proc/self/statm`'s second field, in
/// pages of 4 KiB, the page size of the x86-64 and common aarch64 Linux kernels).
fn resident_bytes() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").expect("read /proc/self/statm");
    let pages: u64 = statm
        .split_whitespace()
        .nth(1)
        .and_then(|field| field.parse().ok())
        .expect("statm's resident field");
    pages * 4096
}

/// The CPU time all of this process's threads have used, in seconds: Bevy's, and lavapipe's,
/// which rasterize the frame. Unlike wall time, other work on the machine does not stretch it.
fn process_cpu_seconds() -> f64 {
    let mut time = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `time` is a valid, writable timespec; the clock id is a constant.
    let status = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut time) };
    assert_eq!(status, 0, "clock_gettime(CLOCK_PROCESS_CPUTIME_ID)");
    time.tv_sec as f64 + time.tv_nsec as f64 * 1e-9
}

fn megabytes(bytes: u64) -> f64 {
    bytes as f64 / f64::from(1 << 20)
}

/// The light count the run aims at in frame `frame` of `frames`: 0, rising to
/// [`PEAK_LIGHTS`] halfway, back to 0 at the last frame.
fn target_lights(frame: usize, frames: usize) -> usize {
    let half = (frames / 2).max(1) as f64;
    let rise = 1.0 - ((frame as f64 - half) / half).abs();
    (rise.max(0.0) * PEAK_LIGHTS as f64).round() as usize
}

/// The window of 10 frames frame `frame` of `frames` is in, counted from the nearer end of
/// the run: frames `f` and `frames - f` are in the same window. Window `w` has `w % 4`
/// shadow-casting lights (none, a spot light, a spot and a point light, all three with a
/// directional light).
fn caster_window(frame: usize, frames: usize) -> usize {
    frame.min(frames - frame) / 10
}

struct Soak {
    harness: Harness,
    random: Random,
    lights: Vec<Entity>,
    shadowed: Vec<Entity>,
    /// The window whose casters [`Self::shadowed`] holds.
    caster_window: Option<usize>,
    meshes: Vec<Entity>,
    mesh_assets: Vec<Handle<Mesh>>,
    /// Materials meshes take; the last one receives invalid values.
    materials: Vec<Handle<PhongMaterial>>,
}

impl Soak {
    fn new() -> Self {
        let mut harness = Harness::new(SIZE, SIZE);
        let world = harness.world_mut();
        let mesh_assets = {
            let mut meshes = world.resource_mut::<Assets<Mesh>>();
            vec![
                meshes.add(Sphere::new(0.8).mesh().uv(16, 8)),
                meshes.add(Cuboid::new(1.0, 1.0, 1.0)),
                meshes.add(Torus::new(0.25, 0.6)),
            ]
        };
        let materials = {
            let mut materials = world.resource_mut::<Assets<PhongMaterial>>();
            vec![
                materials.add(PhongMaterial::default()),
                materials.add(PhongMaterial {
                    base_color: Color::srgb(0.2, 0.5, 0.9),
                    shininess: 80.0,
                    specular_strength: 2.0,
                    ..default()
                }),
                // The variant without the highlight.
                materials.add(PhongMaterial {
                    specular_strength: 0.0,
                    ..default()
                }),
                materials.add(PhongMaterial::default()),
            ]
        };
        let floor = world
            .resource_mut::<Assets<Mesh>>()
            .add(Plane3d::default().mesh().size(14.0, 14.0));
        world.spawn((
            Mesh3d(floor),
            MeshMaterial3d(materials[0].clone()),
            Transform::from_xyz(0.0, -1.0, 0.0),
        ));
        Self {
            harness,
            random: Random::new(SEED),
            lights: Vec::new(),
            shadowed: Vec::new(),
            caster_window: None,
            meshes: Vec::new(),
            mesh_assets,
            materials,
        }
    }

    fn world(&mut self) -> &mut World {
        self.harness.world_mut()
    }

    fn random_position(&mut self) -> Vec3 {
        let r = &mut self.random;
        Vec3::new(
            uniform(r, -6.0, 6.0),
            uniform(r, -0.5, 5.0),
            uniform(r, -6.0, 4.0),
        )
    }

    fn random_color(&mut self) -> Color {
        let r = &mut self.random;
        let [red, green, blue] = [0; 3].map(|_| uniform(r, 0.0, 0.05));
        Color::linear_rgb(red, green, blue)
    }

    /// A light of a random kind: mostly points and spots of short range; a few
    /// directional lights and lights of unlimited range, which reach every pixel.
    fn spawn_light(&mut self) {
        let position = self.random_position();
        let target = self.random_position();
        let color = self.random_color();
        let range = if self.random.one_in(50) {
            None
        } else {
            Some(uniform(&mut self.random, 0.5, 3.0))
        };
        let decay = Decay::new(1.0, 0.5, uniform(&mut self.random, 0.1, 2.0));
        let transform = Transform::from_translation(position).looking_at(target, Vec3::Y);
        let kind = self.random.below(100);
        let world = self.harness.world_mut();
        let entity = match kind {
            0..2 => world.spawn((PhongDirectionalLight { color, ..default() }, transform)),
            2..50 => world.spawn((
                PhongPointLight {
                    color,
                    decay,
                    range,
                    ..default()
                },
                transform,
            )),
            _ => world.spawn((
                PhongSpotLight {
                    color,
                    decay,
                    range,
                    inner_angle: 0.3,
                    outer_angle: 0.6,
                    exponent: 1.0,
                    ..default()
                },
                transform,
            )),
        };
        self.lights.push(entity.id());
    }

    fn despawn_light(&mut self) {
        let index = self.random.below(self.lights.len());
        let entity = self.lights.swap_remove(index);
        if !self.shadowed.contains(&entity) {
            self.world().despawn(entity);
        } else {
            // The casters come and go on their own schedule.
            self.lights.push(entity);
        }
    }

    fn random_light(&mut self) -> Option<Entity> {
        (!self.lights.is_empty()).then(|| self.lights[self.random.below(self.lights.len())])
    }

    /// One change to a random light: move, recolor, hide or show, respawn, or an invalid
    /// value in one of its fields.
    fn churn_light(&mut self) {
        let Some(entity) = self.random_light() else {
            return;
        };
        match self.random.below(10) {
            0..3 => {
                let position = self.random_position();
                let mut entity = self.world().entity_mut(entity);
                entity.get_mut::<Transform>().unwrap().translation = position;
            }
            3..5 => {
                let color = self.random_color();
                set_color(&mut self.world().entity_mut(entity), color);
            }
            5..7 => {
                let mut entity = self.world().entity_mut(entity);
                let mut visibility = entity.get_mut::<Visibility>().unwrap();
                *visibility = match *visibility {
                    Visibility::Hidden => Visibility::Inherited,
                    _ => Visibility::Hidden,
                };
            }
            7 if !self.shadowed.contains(&entity) => {
                let index = self.lights.iter().position(|&e| e == entity).unwrap();
                self.lights.swap_remove(index);
                self.world().despawn(entity);
                self.spawn_light();
            }
            7 => {}
            _ => self.write_invalid(entity),
        }
    }

    /// An invalid value in one field of `entity`'s light, its transform or its shadows.
    fn write_invalid(&mut self, entity: Entity) {
        let r = &mut self.random;
        let (a, b, c) = (bad(r), bad(r), bad(r));
        let (angle, other_angle) = (*r.pick(&BAD_ANGLES), *r.pick(&BAD_ANGLES));
        let scale = *r.pick(&BAD_SCALES);
        let field = r.below(8);
        let world = self.harness.world_mut();
        let mut entity = world.entity_mut(entity);
        match field {
            0 => set_color(&mut entity, Color::linear_rgba(a, b, c, bad(r))),
            1 => {
                let specular = Some(Color::linear_rgb(a, b, c));
                if let Some(mut l) = entity.get_mut::<PhongPointLight>() {
                    l.specular = specular;
                } else if let Some(mut l) = entity.get_mut::<PhongSpotLight>() {
                    l.specular = specular;
                } else if let Some(mut l) = entity.get_mut::<PhongDirectionalLight>() {
                    l.specular = specular;
                }
            }
            2 => {
                let (decay, range) = (Decay::new(a, b, c), Some(bad(r)));
                if let Some(mut l) = entity.get_mut::<PhongPointLight>() {
                    (l.decay, l.range) = (decay, range);
                } else if let Some(mut l) = entity.get_mut::<PhongSpotLight>() {
                    (l.decay, l.range) = (decay, range);
                }
            }
            3 => {
                if let Some(mut l) = entity.get_mut::<PhongSpotLight>() {
                    (l.inner_angle, l.outer_angle, l.exponent) = (angle, other_angle, a);
                }
            }
            4 => {
                let mut transform = entity.get_mut::<Transform>().unwrap();
                transform.translation = Vec3::new(a, b, c);
            }
            5 => entity.get_mut::<Transform>().unwrap().scale = Vec3::splat(scale),
            6 => {
                let mut transform = entity.get_mut::<Transform>().unwrap();
                transform.rotation = Quat::from_xyzw(a, b, c, 1.0);
            }
            _ => {
                let shadows = PhongShadows {
                    depth_bias: a,
                    normal_bias: b,
                    softness: c,
                    near_distance: bad(r),
                    diffuse_in_shadow: bad(r),
                    specular_in_shadow: bad(r),
                    ..current_shadows(&entity)
                };
                set_shadows(&mut entity, shadows);
            }
        }
    }

    /// Brings the shadow-casting lights to those of `window` ([`caster_window`]): a
    /// spot, a point and a directional light, the first few of them, at places and with
    /// settings drawn from the window's own seed; they count among the lights. Shadows cost
    /// far more than any other light, so the mirror windows of the rising and the falling
    /// half get the same casters.
    fn churn_shadows(&mut self, window: usize) {
        if self.caster_window == Some(window) {
            return;
        }
        self.caster_window = Some(window);
        for entity in std::mem::take(&mut self.shadowed) {
            self.lights.retain(|&e| e != entity);
            self.world().despawn(entity);
        }
        let mut random = Random::new(SEED ^ (window as u64 + 1));
        for kind in 0..window % (MAX_SHADOWED + 1) {
            let position = Vec3::new(
                uniform(&mut random, -4.0, 4.0),
                uniform(&mut random, 1.0, 5.0),
                uniform(&mut random, -4.0, 4.0),
            );
            let shadows = PhongShadows {
                resolution: *random.pick(&[64, 128, 0]),
                softness: *random.pick(&[0.0, 0.1, f32::NAN]),
                depth_bias: *random.pick(&[0.02, f32::NAN, -1.0, 1e38]),
                ..PhongShadows::ON
            };
            let transform = Transform::from_translation(position).looking_at(Vec3::ZERO, Vec3::Y);
            let world = self.harness.world_mut();
            let entity = match kind {
                0 => world.spawn((
                    PhongSpotLight {
                        shadows,
                        ..default()
                    },
                    transform,
                )),
                1 => world.spawn((
                    PhongPointLight {
                        shadows,
                        ..default()
                    },
                    transform,
                )),
                _ => world.spawn((
                    PhongDirectionalLight {
                        shadows,
                        ..default()
                    },
                    transform,
                )),
            }
            .id();
            self.shadowed.push(entity);
            self.lights.push(entity);
        }
    }

    /// Spawns `mesh` with `material` at `position`, among [`Self::meshes`].
    fn spawn_mesh(&mut self, mesh: Handle<Mesh>, material: Handle<PhongMaterial>, position: Vec3) {
        let transform = Transform::from_translation(position);
        let entity = self
            .world()
            .spawn((Mesh3d(mesh), MeshMaterial3d(material), transform))
            .id();
        self.meshes.push(entity);
    }

    /// Spawns or despawns a mesh (between 2 and 12 of them), or gives one a degenerate
    /// scale (zero, 1e-30, mirrored) or the last material invalid values. (No huge scale:
    /// a mesh covering the whole frame would make the frame time depend on chance more than
    /// on the light count.)
    fn churn_meshes(&mut self) {
        match self.random.below(8) {
            0..3 if self.meshes.len() < 12 => {
                let mesh = self.random.pick(&self.mesh_assets).clone();
                let material = self.random.pick(&self.materials).clone();
                let mut position = self.random_position();
                position.y = uniform(&mut self.random, -0.5, 1.5);
                self.spawn_mesh(mesh, material, position);
            }
            3..6 if self.meshes.len() > 2 => {
                let entity = self
                    .meshes
                    .swap_remove(self.random.below(self.meshes.len()));
                self.world().despawn(entity);
            }
            6 if !self.meshes.is_empty() => {
                let entity = *self.random.pick(&self.meshes);
                let scale = *self.random.pick(&[0.0, 1e-30, -1.0]);
                self.world()
                    .entity_mut(entity)
                    .get_mut::<Transform>()
                    .unwrap()
                    .scale = Vec3::splat(scale);
            }
            7 => {
                let r = &mut self.random;
                let (a, b, c) = (bad(r), bad(r), bad(r));
                let field = r.below(4);
                let handle = self.materials.last().unwrap().clone();
                let mut materials = self.world().resource_mut::<Assets<PhongMaterial>>();
                let mut material = materials.get_mut(&handle).unwrap();
                match field {
                    0 => material.base_color = Color::linear_rgba(a, b, c, a),
                    1 => material.shininess = a,
                    2 => material.emissive = LinearRgba::rgb(a, b, c),
                    _ => {
                        material.specular_strength = a;
                        material.ambient_factor = b;
                    }
                }
            }
            _ => {}
        }
    }

    /// One frame's changes: the shadow-casting lights of `window` and the light count
    /// brought to `target`, then random changes.
    fn churn(&mut self, target: usize, window: usize) {
        self.churn_shadows(window);
        while self.lights.len() < target {
            self.spawn_light();
        }
        while self.lights.len() > target.max(self.shadowed.len()) {
            self.despawn_light();
        }
        let changes = 5 + self.lights.len() / 100;
        for _ in 0..changes {
            self.churn_light();
        }
        self.churn_meshes();
        if self.random.one_in(50) {
            let color = if self.random.one_in(2) {
                Color::linear_rgb(bad(&mut self.random), 0.1, 0.1)
            } else {
                Color::linear_rgb(0.05, 0.05, 0.05)
            };
            self.world().insert_resource(PhongAmbientLight { color });
        }
    }

    /// Reads the frame back: (covered pixels, NaN or infinite pixels).
    fn read_back(&mut self) -> (usize, usize) {
        let image = self.harness.render_next_frame();
        (image.covered_pixels(), image.non_finite_pixels())
    }

    /// Every pipeline, buffer and table at its largest before measuring: a light of each
    /// kind casting shadows with each softness the run uses, then [`WARM_UP_FRAMES`] frames
    /// of the run's own churn, rising to the peak light count and falling back to none.
    fn warm_up(&mut self) {
        // A mesh of each kind and each material, so that every pipeline the run can use is
        // compiled, with and without shadows, before anything is measured.
        for (index, material) in self.materials.clone().into_iter().enumerate() {
            let mesh = self.mesh_assets[index % self.mesh_assets.len()].clone();
            let position = Vec3::new(index as f32 * 1.5 - 2.0, 0.0, 0.0);
            self.spawn_mesh(mesh, material, position);
        }
        self.harness.settle();
        let world = self.harness.world_mut();
        let mut casters = Vec::new();
        for softness in [0.0, 0.1] {
            let shadows = PhongShadows {
                resolution: 64,
                softness,
                ..PhongShadows::ON
            };
            let aimed = Transform::from_xyz(0.0, 4.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y);
            let lights = [
                world.spawn((PhongSpotLight::default(), aimed)).id(),
                world.spawn((PhongPointLight::default(), aimed)).id(),
                world.spawn((PhongDirectionalLight::default(), aimed)).id(),
            ];
            for light in lights {
                set_shadows(&mut world.entity_mut(light), shadows);
            }
            casters.extend(lights);
        }
        self.harness.settle();
        self.read_back();
        for entity in casters {
            self.world().despawn(entity);
        }
        for frame in 1..=WARM_UP_FRAMES {
            self.churn(
                target_lights(frame, WARM_UP_FRAMES),
                caster_window(frame, WARM_UP_FRAMES),
            );
            self.harness.app.update();
        }
        self.harness.settle();
        self.read_back();
    }
}

fn set_color(entity: &mut EntityWorldMut, color: Color) {
    if let Some(mut l) = entity.get_mut::<PhongPointLight>() {
        l.color = color;
    } else if let Some(mut l) = entity.get_mut::<PhongSpotLight>() {
        l.color = color;
    } else if let Some(mut l) = entity.get_mut::<PhongDirectionalLight>() {
        l.color = color;
    }
}

fn current_shadows(entity: &EntityWorldMut) -> PhongShadows {
    entity
        .get::<PhongPointLight>()
        .map(|l| l.shadows)
        .or_else(|| entity.get::<PhongSpotLight>().map(|l| l.shadows))
        .or_else(|| entity.get::<PhongDirectionalLight>().map(|l| l.shadows))
        .unwrap_or_default()
}

fn set_shadows(entity: &mut EntityWorldMut, shadows: PhongShadows) {
    if let Some(mut l) = entity.get_mut::<PhongPointLight>() {
        l.shadows = shadows;
    } else if let Some(mut l) = entity.get_mut::<PhongSpotLight>() {
        l.shadows = shadows;
    } else if let Some(mut l) = entity.get_mut::<PhongDirectionalLight>() {
        l.shadows = shadows;
    }
}

/// How long one frame took.
struct FrameTimes {
    /// Seconds on the clock.
    wall: f64,
    /// Seconds of CPU time of the whole process ([`process_cpu_seconds`]).
    cpu: f64,
}

/// A frame of the run, without a readback.
struct TimedFrame {
    lights: usize,
    /// In the rising half of the run (else in the falling half).
    rising: bool,
    times: FrameTimes,
}

/// One of the `frames`' times, in milliseconds, sorted.
fn sorted_ms(frames: &[&TimedFrame], time: fn(&FrameTimes) -> f64) -> Vec<f64> {
    let mut ms: Vec<f64> = frames.iter().map(|f| time(&f.times) * 1000.0).collect();
    ms.sort_by(f64::total_cmp);
    ms
}

/// The `q` quantile of sorted `values` (the nearest rank below).
fn quantile(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * q) as usize]
}

/// `frames: lower quartile / median / mean` of sorted frame times.
fn summary(sorted: &[f64]) -> String {
    format!(
        "{:>3}: {:6.1} / {:6.1} / {:6.1}",
        sorted.len(),
        quantile(sorted, 0.25),
        quantile(sorted, 0.5),
        sorted.iter().sum::<f64>() / sorted.len() as f64
    )
}

#[test]
fn soak_of_random_light_and_mesh_churn_stays_finite_flat_and_steady() {
    let frames = std::env::var("BEVY_PHONG_SOAK_FRAMES")
        .ok()
        .and_then(|value| value.replace('_', "").parse().ok())
        .unwrap_or(DEFAULT_FRAMES);
    let start = Instant::now();
    let mut soak = Soak::new();
    soak.warm_up();
    let warm_rss = resident_bytes();
    let warm_up_seconds = start.elapsed().as_secs_f64();

    // Every frame without a readback.
    let mut timings: Vec<TimedFrame> = Vec::with_capacity(frames);
    let (mut panics, mut readbacks, mut covered_pixels, mut bad_pixels) = (0, 0, 0, 0);
    let mut peak_rss = warm_rss;
    let mut most_lights = 0;
    // Frames done and left, and the time left: on a terminal one line drawn over itself, in
    // a log a line every tenth of the run.
    let mut progress = Progress::new("soak frames", frames);
    for frame in 1..=frames {
        progress.report(frame - 1);
        let read = frame % READBACK_EVERY == 0 || frame == frames;
        let run = std::panic::AssertUnwindSafe(|| {
            soak.churn(target_lights(frame, frames), caster_window(frame, frames));
            let lights = soak.lights.len();
            let (started, cpu_started) = (Instant::now(), process_cpu_seconds());
            let pixels = if read {
                Some(soak.read_back())
            } else {
                soak.harness.app.update();
                None
            };
            let times = FrameTimes {
                wall: started.elapsed().as_secs_f64(),
                cpu: process_cpu_seconds() - cpu_started,
            };
            (lights, times, pixels)
        });
        match std::panic::catch_unwind(run) {
            Ok((lights, times, pixels)) => {
                most_lights = most_lights.max(lights);
                if let Some((covered, bad)) = pixels {
                    readbacks += 1;
                    covered_pixels += covered;
                    bad_pixels += bad;
                    peak_rss = peak_rss.max(resident_bytes());
                    println!(
                        "soak frame {frame}: {lights} lights, {covered} covered pixels, \
                         {bad} NaN or infinite, RSS {:.0} MB",
                        megabytes(resident_bytes())
                    );
                } else {
                    timings.push(TimedFrame {
                        lights,
                        rising: frame <= frames / 2,
                        times,
                    });
                }
            }
            Err(_) => {
                // A panic in a system leaves the app unusable: stop there.
                panics += 1;
                println!("soak: frame {frame} panicked");
                break;
            }
        }
    }
    if panics == 0 {
        progress.finish();
    }
    let end_rss = resident_bytes();
    peak_rss = peak_rss.max(end_rss);

    // Frame times per band of light counts, rising half against falling half.
    let mut worst_ratio: f64 = 0.0;
    println!(
        "soak frame times by light count, CPU ms (frames: lower quartile / median / mean), \
         rising half, falling half; the ratio of the medians, of CPU and of wall time:"
    );
    for band in 0..BANDS {
        let in_band = |frame: &&TimedFrame| frame.lights * BANDS / (PEAK_LIGHTS + 1) == band;
        let [early, late] = [true, false].map(|rising| {
            let frames: Vec<&TimedFrame> = timings
                .iter()
                .filter(in_band)
                .filter(|frame| frame.rising == rising)
                .collect();
            [
                sorted_ms(&frames, |t| t.cpu),
                sorted_ms(&frames, |t| t.wall),
            ]
        });
        let ([early_cpu, early_wall], [late_cpu, late_wall]) = (early, late);
        if early_cpu.len() < 5 || late_cpu.len() < 5 {
            continue;
        }
        let ratio = quantile(&late_cpu, 0.5) / quantile(&early_cpu, 0.5);
        let wall_ratio = quantile(&late_wall, 0.5) / quantile(&early_wall, 0.5);
        if early_cpu.len().min(late_cpu.len()) >= MIN_BAND_FRAMES {
            worst_ratio = worst_ratio.max(ratio);
        }
        println!(
            "  {:>4}..{:<4} lights: {}, {}, ratio {ratio:.2}, wall {wall_ratio:.2}",
            band * (PEAK_LIGHTS + 1) / BANDS,
            (band + 1) * (PEAK_LIGHTS + 1) / BANDS,
            summary(&early_cpu),
            summary(&late_cpu),
        );
    }
    let half_ratio = |time: fn(&FrameTimes) -> f64| {
        let mean = |rising: bool| {
            let times: Vec<f64> = timings
                .iter()
                .filter(|frame| frame.rising == rising)
                .map(|frame| time(&frame.times))
                .collect();
            times.iter().sum::<f64>() / times.len().max(1) as f64
        };
        mean(false) / mean(true)
    };
    let (whole_ratio, whole_wall_ratio) = (half_ratio(|t| t.cpu), half_ratio(|t| t.wall));
    println!(
        "soak, seed {SEED:#x}, {SIZE}x{SIZE}: {frames} frames in {:.1} s (warm-up {warm_up_seconds:.1} s)\n  \
         panics {panics}\n  readbacks {readbacks}, covered pixels {covered_pixels}, \
         NaN or infinite pixels {bad_pixels}\n  most lights {most_lights}\n  \
         RSS at warm-up {:.1} MB, at the end {:.1} MB, peak {:.1} MB, growth {:.1} MB \
         (bound {:.0} MB)\n  CPU time per frame, falling half / rising half: worst band held to the bound \
         {worst_ratio:.2} (bound {BAND_RATIO_BOUND}), whole halves {whole_ratio:.2} (bound \
         {HALF_RATIO_BOUND}); in wall time {whole_wall_ratio:.2}",
        start.elapsed().as_secs_f64(),
        megabytes(warm_rss),
        megabytes(end_rss),
        megabytes(peak_rss),
        megabytes(end_rss) - megabytes(warm_rss),
        megabytes(RSS_GROWTH_BOUND),
    );
    assert_eq!(panics, 0, "a frame panicked");
    assert_eq!(bad_pixels, 0, "NaN or infinite pixels");
    assert!(
        readbacks >= 1 && covered_pixels > 0,
        "nothing was read back"
    );
    assert_eq!(most_lights, PEAK_LIGHTS, "the run reaches its peak");
    assert!(
        end_rss <= warm_rss + RSS_GROWTH_BOUND,
        "RSS grew from {:.1} MB to {:.1} MB",
        megabytes(warm_rss),
        megabytes(end_rss)
    );
    assert!(
        worst_ratio <= BAND_RATIO_BOUND,
        "for the same light count, frames late in the run take {worst_ratio:.2} times the \
         CPU time of early ones"
    );
    assert!(
        whole_ratio <= HALF_RATIO_BOUND,
        "the falling half of the run took {whole_ratio:.2} times the CPU time of the rising half"
    );
}
