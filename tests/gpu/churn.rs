//! Churn: every frame a seeded random share of the scene is created, changed or removed
//! (cubes spawned with new or shared materials and despawned, materials edited in place and
//! moved between classes by a map, a highlight model or fog, materials dropped, point, spot
//! and rectangle lights added and removed, a second camera added and removed), through the
//! material slots, records and classes, the light buffer and each view's clusters. Every frame is compared pixel by pixel with the reference model, so that a
//! mesh that reads a freed or stale slot shows; and the slot table, the record buffer and
//! the classes stay within what the live content needs:
//!
//! - slots given (the table's high-water mark) ≤ the most materials alive at once (a freed
//!   slot is given again before a new one);
//! - live slots = live materials, once a frame has passed since the last change;
//! - the record buffer's capacity ≤ the next power of two of the slots given (it doubles),
//!   or its initial capacity;
//! - classes ≤ the distinct classes of the live materials (an empty class is dropped);
//! - the light buffer holds the live lights: the directional one, each point and spot
//!   light, each rectangle light (none reaches nowhere: ε is 0);
//! - the clusters hold at most one view per live camera.
//!
//! ```sh
//! cargo test --features testing --test gpu -- churn                               # as CI
//! BEVY_PHONG_CHURN_FRAMES=2000 cargo test --features testing --test gpu -- churn   # longer
//! ```
//!
//! Where the device has no storage buffer to spare for the records (WebGL2's limits), each
//! material draws with its own bind group: the frames are compared the same way, and the
//! slot and class bounds are not asked.

use crate::frames::TOLERANCE;
use crate::random::Random;
use bevy::{
    asset::RenderAssetUsages,
    camera::RenderTarget,
    image::ImageSampler,
    prelude::*,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};
use bevy_phong::prelude::*;
use bevy_phong::testing::{
    MaterialBatching, PhongLightBuffer, PhongLightClusters, material_batching,
};
use bevy_phong_headless::Harness;
use std::collections::HashSet;

/// Render size: small, so that a frame and its comparison take a fraction of a second.
const SIZE: u32 = 64;
/// Cells along each side of the grid the cubes stand on.
const SIDE: usize = 5;
/// Frames run by default (CI).
const DEFAULT_FRAMES: usize = 40;
/// At least this many cubes stand after each frame's changes.
const MIN_CUBES: usize = 4;
/// At most this many point, spot and rectangle lights at once (besides the directional
/// light).
const MAX_LIGHTS: usize = 4;
/// The seed of the run's random choices.
const SEED: u64 = 0xc4a2_0064;

/// The frames to run: `BEVY_PHONG_CHURN_FRAMES`, or [`DEFAULT_FRAMES`].
fn frames() -> usize {
    std::env::var("BEVY_PHONG_CHURN_FRAMES")
        .ok()
        .and_then(|frames| frames.parse().ok())
        .unwrap_or(DEFAULT_FRAMES)
}

/// The scene and what the test holds of it: each cell's cube, the materials the test keeps
/// alive (a material dropped here is removed once no cube holds it), the lights.
struct Churn {
    random: Random,
    cells: Vec<Option<Entity>>,
    materials: Vec<Handle<PhongMaterial>>,
    lights: Vec<Entity>,
    /// The second camera, while there is one.
    second_camera: Option<Entity>,
    cube: Handle<Mesh>,
    checker: Handle<Image>,
    /// Materials made this frame.
    added: usize,
}

/// A checkered base color map, 8 × 8 texels of two colors, sampled at its nearest texel.
fn checker_image() -> Image {
    let data = (0..64)
        .flat_map(|index| {
            if (index % 8 + index / 8) % 2 == 0 {
                [230, 200, 120, 255]
            } else {
                [90, 140, 210, 255]
            }
        })
        .collect();
    let mut image = Image::new(
        Extent3d {
            width: 8,
            height: 8,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::default(),
    );
    image.sampler = ImageSampler::nearest();
    image
}

impl Churn {
    /// The grid's directional light, ambient light and camera, with no cube and no local
    /// light yet.
    fn new(harness: &mut Harness) -> Self {
        harness.look_from(Vec3::new(0.0, 7.0, 5.0));
        let world = harness.world_mut();
        world.insert_resource(PhongAmbientLight {
            color: Color::linear_rgb(0.05, 0.05, 0.06),
        });
        world.spawn((
            PhongDirectionalLight {
                color: Color::linear_rgb(0.6, 0.6, 0.55),
                ..default()
            },
            Transform::from_xyz(1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
        ));
        let cube = world
            .resource_mut::<Assets<Mesh>>()
            .add(Cuboid::new(0.7, 0.7, 0.7));
        let checker = world.resource_mut::<Assets<Image>>().add(checker_image());
        Self {
            random: Random::new(SEED),
            cells: vec![None; SIDE * SIDE],
            materials: Vec::new(),
            lights: Vec::new(),
            second_camera: None,
            cube,
            checker,
            added: 0,
        }
    }

    /// A number in `[low, high)`.
    fn uniform(&mut self, low: f32, high: f32) -> f32 {
        low + (high - low) * (self.random.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A material of random numbers, in one of the classes the churn moves materials
    /// between: with or without a base color map, the plain or the normalized highlight,
    /// with or without fog.
    fn new_material(&mut self) -> PhongMaterial {
        let mut material = PhongMaterial {
            base_color: Color::linear_rgb(
                self.uniform(0.1, 0.9),
                self.uniform(0.1, 0.9),
                self.uniform(0.1, 0.9),
            ),
            specular_color: Color::linear_rgb(
                self.uniform(0.1, 0.8),
                self.uniform(0.1, 0.8),
                self.uniform(0.1, 0.8),
            ),
            shininess: self.uniform(2.0, 80.0),
            emissive: LinearRgba::rgb(self.uniform(0.0, 0.1), 0.0, self.uniform(0.0, 0.1)),
            ..default()
        };
        self.move_class(&mut material);
        material
    }

    /// Moves `material` to a random class (it may stay in its own).
    fn move_class(&mut self, material: &mut PhongMaterial) {
        material.base_color_texture = self.random.one_in(3).then(|| self.checker.clone());
        material.specular_model = if self.random.one_in(3) {
            SpecularModel::NormalizedBlinnPhong
        } else {
            SpecularModel::BlinnPhong
        };
        material.fog_enabled = self.random.one_in(2);
    }

    /// The cell's place on the grid.
    fn place(cell: usize) -> Transform {
        let offset = (SIDE as f32 - 1.0) / 2.0;
        let (row, column) = ((cell / SIDE) as f32, (cell % SIDE) as f32);
        Transform::from_xyz(column - offset, 0.0, row - offset)
            .with_rotation(Quat::from_rotation_y(0.4 * row + 0.2 * column))
    }

    /// One frame's changes: a few of each kind, each at random. Returns the most materials
    /// alive at once during the frame: those alive before it and those it made (the ones it
    /// drops may be removed after the new ones are given their slots).
    fn change(&mut self, world: &mut World) -> usize {
        let before = world.resource::<Assets<PhongMaterial>>().len();
        self.added = 0;
        for _ in 0..1 + self.random.below(4) {
            match self.random.below(8) {
                0 | 1 => self.spawn_cube(world),
                2 => self.despawn_cube(world),
                3 => self.edit_material(world),
                4 => self.reassign_cube(world),
                5 => self.drop_material(world),
                6 => self.churn_light(world),
                _ if self.random.one_in(3) => self.churn_camera(world),
                _ => self.churn_light(world),
            }
        }
        // A few cubes always stand, so that every frame has lit pixels to compare.
        while self.cubes().len() < MIN_CUBES {
            self.spawn_cube(world);
        }
        before + self.added
    }

    /// A cube in an empty cell, with a new material or (one time in three) a live one.
    fn spawn_cube(&mut self, world: &mut World) {
        let empty: Vec<usize> = (0..self.cells.len())
            .filter(|&cell| self.cells[cell].is_none())
            .collect();
        if empty.is_empty() {
            return;
        }
        let cell = *self.random.pick(&empty);
        let material = if !self.materials.is_empty() && self.random.one_in(3) {
            self.random.pick(&self.materials).clone()
        } else {
            let material = self.new_material();
            let handle = world.resource_mut::<Assets<PhongMaterial>>().add(material);
            self.materials.push(handle.clone());
            self.added += 1;
            handle
        };
        let cube = world
            .spawn((
                Mesh3d(self.cube.clone()),
                MeshMaterial3d(material),
                Self::place(cell),
            ))
            .id();
        self.cells[cell] = Some(cube);
    }

    /// The cubes standing on the grid, by cell.
    fn cubes(&self) -> Vec<(usize, Entity)> {
        (0..self.cells.len())
            .filter_map(|cell| self.cells[cell].map(|cube| (cell, cube)))
            .collect()
    }

    fn despawn_cube(&mut self, world: &mut World) {
        let cubes = self.cubes();
        if cubes.is_empty() {
            return;
        }
        let &(cell, cube) = self.random.pick(&cubes);
        world.despawn(cube);
        self.cells[cell] = None;
    }

    /// A live material's numbers changed in place, or (one time in two) its class.
    fn edit_material(&mut self, world: &mut World) {
        if self.materials.is_empty() {
            return;
        }
        let handle = self.random.pick(&self.materials).clone();
        let fresh = self.new_material();
        let move_class = self.random.one_in(2);
        let mut materials = world.resource_mut::<Assets<PhongMaterial>>();
        let Some(mut material) = materials.get_mut(&handle) else {
            return;
        };
        material.base_color = fresh.base_color;
        material.shininess = fresh.shininess;
        if move_class {
            material.base_color_texture = fresh.base_color_texture;
            material.specular_model = fresh.specular_model;
            material.fog_enabled = fresh.fog_enabled;
        }
    }

    /// A cube given another live material.
    fn reassign_cube(&mut self, world: &mut World) {
        let cubes = self.cubes();
        if cubes.is_empty() || self.materials.is_empty() {
            return;
        }
        let &(_, cube) = self.random.pick(&cubes);
        let material = self.random.pick(&self.materials).clone();
        world.entity_mut(cube).insert(MeshMaterial3d(material));
    }

    /// A material dropped by the test, with every cube that holds it despawned: its asset
    /// is removed, and its slot freed.
    fn drop_material(&mut self, world: &mut World) {
        if self.materials.is_empty() {
            return;
        }
        let index = self.random.below(self.materials.len());
        let handle = self.materials.swap_remove(index);
        for (cell, cube) in self.cubes() {
            let holds = world
                .get::<MeshMaterial3d<PhongMaterial>>(cube)
                .is_some_and(|material| material.0 == handle);
            if holds {
                world.despawn(cube);
                self.cells[cell] = None;
            }
        }
    }

    /// The live lights: (directional, point and spot, rectangle).
    fn live_lights(&self, world: &World) -> (u32, u32, u32) {
        let is = |light: &Entity, kind: fn(&World, Entity) -> bool| kind(world, *light);
        let local = self
            .lights
            .iter()
            .filter(|light| is(light, |w, e| w.get::<PhongRectLight>(e).is_none()))
            .count();
        (1, local as u32, (self.lights.len() - local) as u32)
    }

    /// A point, spot or rectangle light added above the grid, or (at the most, or one time
    /// in two) one removed.
    fn churn_light(&mut self, world: &mut World) {
        if !self.lights.is_empty() && (self.lights.len() == MAX_LIGHTS || self.random.one_in(2)) {
            let index = self.random.below(self.lights.len());
            world.despawn(self.lights.swap_remove(index));
            return;
        }
        let color = Color::linear_rgb(
            self.uniform(0.5, 2.0),
            self.uniform(0.5, 2.0),
            self.uniform(0.5, 2.0),
        );
        let position = Vec3::new(
            self.uniform(-2.5, 2.5),
            self.uniform(1.0, 3.0),
            self.uniform(-2.5, 2.5),
        );
        let light = match self.random.below(3) {
            0 => world.spawn((
                PhongPointLight {
                    color,
                    range: Some(self.uniform(2.0, 8.0)),
                    ..default()
                },
                Transform::from_translation(position),
            )),
            // Without a highlight: a Blinn-Phong lobe over an area is drawn as the Phong lobe
            // of its solid angle, within a stated share (tests/gpu/area_lights.rs), where the
            // diffuse light is exact.
            1 => world.spawn((
                PhongRectLight {
                    color,
                    specular: Some(Color::BLACK),
                    width: self.uniform(0.3, 1.2),
                    height: self.uniform(0.3, 1.2),
                    ..default()
                },
                Transform::from_translation(position).looking_at(Vec3::ZERO, Vec3::Z),
            )),
            _ => world.spawn((
                PhongSpotLight {
                    color,
                    inner_angle: 0.3,
                    outer_angle: 0.7,
                    ..default()
                },
                Transform::from_translation(position).looking_at(Vec3::ZERO, Vec3::Y),
            )),
        };
        self.lights.push(light.id());
    }

    /// A second camera added, looking at the grid from the side into an image of its own,
    /// or the one there is removed: another view, with clusters of its own.
    fn churn_camera(&mut self, world: &mut World) {
        if let Some(camera) = self.second_camera.take() {
            world.despawn(camera);
            return;
        }
        let target = Image::new_target_texture(32, 32, TextureFormat::Rgba8UnormSrgb, None);
        let target = world.resource_mut::<Assets<Image>>().add(target);
        let camera = world
            .spawn((
                Camera3d::default(),
                Camera {
                    order: 1,
                    ..default()
                },
                RenderTarget::Image(target.into()),
                Transform::from_xyz(6.0, 2.0, 0.0).looking_at(Vec3::ZERO, Vec3::Y),
            ))
            .id();
        self.second_camera = Some(camera);
    }
}

/// The classes `materials` fall in: with or without a base color map, the highlight model,
/// fog.
fn distinct_classes(materials: &Assets<PhongMaterial>) -> usize {
    materials
        .iter()
        .map(|(_, material)| {
            (
                material.base_color_texture.is_some(),
                material.specular_model == SpecularModel::NormalizedBlinnPhong,
                material.fog_enabled,
            )
        })
        .collect::<HashSet<_>>()
        .len()
}

/// Fails naming `frame` where the slots, records or classes outgrow the live content
/// (see the module docs).
fn assert_within_live_content(
    batching: &MaterialBatching,
    most_materials: usize,
    classes: usize,
    frame: usize,
) {
    assert!(
        batching.slots_given <= most_materials,
        "frame {frame}: {} slots given for at most {most_materials} materials alive at once",
        batching.slots_given
    );
    let capacity = batching.slots_given.next_power_of_two();
    assert!(
        batching.record_capacity <= capacity.max(batching.initial_record_capacity),
        "frame {frame}: room for {} records, for {} slots given",
        batching.record_capacity,
        batching.slots_given
    );
    assert!(
        batching.classes <= classes,
        "frame {frame}: {} classes for materials of {classes}",
        batching.classes
    );
}

#[test]
fn churned_materials_meshes_and_lights_draw_as_the_reference_says_within_their_live_content() {
    let mut harness = Harness::new(SIZE, SIZE);
    let mut churn = Churn::new(&mut harness);
    let frames = frames();
    let mut most_materials = 0;
    let mut checked = 0;
    for frame in 0..frames {
        most_materials = most_materials.max(churn.change(harness.world_mut()));
        harness.settle();
        let rendered = harness.render_next_frame();
        harness
            .compare_with_reference(&rendered)
            .assert_within(&format!("churn, frame {frame}"), TOLERANCE);
        checked += 1;
        let materials = harness.app.world().resource::<Assets<PhongMaterial>>();
        most_materials = most_materials.max(materials.len());
        let classes = distinct_classes(materials);
        let (directional, local, area) = churn.live_lights(harness.app.world());
        let header = *harness.app.world().resource::<PhongLightBuffer>().header();
        assert_eq!(
            (
                header.directional_count,
                header.local_count + header.clustered_local_count,
                header.area_count + header.clustered_area_count,
            ),
            (directional, local, area),
            "frame {frame}: the light buffer holds the live lights"
        );
        let cameras = 1 + u32::from(churn.second_camera.is_some());
        let views = harness
            .app
            .world()
            .resource::<PhongLightClusters>()
            .view_count();
        assert!(
            views <= cameras,
            "frame {frame}: {views} views clustered for {cameras} cameras"
        );
        let batching = material_batching(&harness.app);
        if batching.on {
            assert_within_live_content(&batching, most_materials, classes, frame);
            assert_eq!(
                batching.slots,
                materials.len(),
                "frame {frame}: a slot per live material"
            );
        }
    }
    let batching = material_batching(&harness.app);
    println!(
        "churn: {checked} frames checked, {} materials alive at the most, {} slots given, \
         record capacity {}, {} classes at the end",
        most_materials, batching.slots_given, batching.record_capacity, batching.classes
    );
}
