//! Many materials that differ only in their numbers, drawn as one batch from the record
//! array (`render::batching`): every pixel as the reference model lights its own
//! material's numbers, while the materials are changed, added, removed and moved to
//! another class between frames. Where the device has no storage buffer to spare for the
//! records (WebGL2's limits), every material draws with its own bind group, and the same
//! pictures are asserted.

use crate::frames::{SIZE, TOLERANCE};
use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong::testing::material_batching;
use bevy_phong_headless::Harness;

/// Cubes along each side of the grid.
const SIDE: usize = 8;

/// The `index`-th material of the grid: its own diffuse, specular and ambient colors,
/// shininess and emission, every one distinct; every other one without fog (another
/// shader variant, so the grid has two classes; the scene has no fog).
fn numbered_material(index: usize) -> PhongMaterial {
    let t = index as f32 / (SIDE * SIDE) as f32;
    PhongMaterial {
        base_color: Color::linear_rgb(0.2 + 0.7 * t, 0.9 - 0.6 * t, 0.3 + 0.4 * (t * 7.0).fract()),
        specular_color: Color::linear_rgb(0.3 + 0.5 * (t * 3.0).fract(), 0.5, 0.8 - 0.5 * t),
        shininess: 4.0 + 60.0 * (t * 5.0).fract(),
        ambient_factor: 0.5 + t,
        emissive: LinearRgba::rgb(0.05 * t, 0.0, 0.1 * (1.0 - t)),
        fog_enabled: index.is_multiple_of(2),
        ..default()
    }
}

/// A harness looking down at a grid of cubes, each with its own material, under a
/// directional light and a point light; returns the cubes, row by row.
fn grid(harness: &mut Harness) -> Vec<Entity> {
    harness.look_from(Vec3::new(0.0, 9.0, 6.0));
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.04, 0.04, 0.05),
    });
    world.spawn((
        PhongDirectionalLight {
            color: Color::linear_rgb(0.8, 0.8, 0.75),
            ..default()
        },
        Transform::from_xyz(1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    world.spawn((
        PhongPointLight {
            color: Color::linear_rgb(2.0, 1.6, 1.2),
            ..default()
        },
        Transform::from_xyz(-1.0, 2.0, 1.0),
    ));
    let cube = world
        .resource_mut::<Assets<Mesh>>()
        .add(Cuboid::new(0.7, 0.7, 0.7));
    (0..SIDE * SIDE)
        .map(|index| {
            let material = world
                .resource_mut::<Assets<PhongMaterial>>()
                .add(numbered_material(index));
            let (row, column) = ((index / SIDE) as f32, (index % SIDE) as f32);
            let offset = (SIDE as f32 - 1.0) / 2.0;
            world
                .spawn((
                    Mesh3d(cube.clone()),
                    MeshMaterial3d(material),
                    Transform::from_xyz(column - offset, 0.0, row - offset)
                        .with_rotation(Quat::from_rotation_y(0.3 * row)),
                ))
                .id()
        })
        .collect()
}

/// Changes the material of `cube` in place (its asset, which every mesh that holds it draws).
fn edit_material(world: &mut World, cube: Entity, edit: impl FnOnce(&mut PhongMaterial)) {
    let handle = world
        .get::<MeshMaterial3d<PhongMaterial>>(cube)
        .expect("the cube has a Phong material")
        .0
        .clone();
    let mut materials = world.resource_mut::<Assets<PhongMaterial>>();
    edit(&mut materials.get_mut(&handle).expect("the material exists"));
}

/// Renders a frame and compares every pixel with the reference model.
fn assert_matches_reference(harness: &mut Harness, what: &str) {
    harness.settle();
    let rendered = harness.render_next_frame();
    harness
        .compare_with_reference(&rendered)
        .assert_within(what, TOLERANCE);
}

#[test]
fn distinct_materials_draw_as_one_class_and_as_the_reference_model_says() {
    let mut harness = Harness::new(SIZE, SIZE);
    grid(&mut harness);
    assert_matches_reference(&mut harness, "64 distinct materials");
    let batching = material_batching(&harness.app);
    if !batching.on {
        return;
    }
    assert_eq!(
        batching.classes, 2,
        "64 materials of two kinds: two classes"
    );
    assert_eq!(
        batching.meshes_drawn_by_class,
        SIDE * SIDE,
        "every cube drawn with its class's bind group"
    );
}

#[test]
fn materials_changed_added_removed_and_moved_between_frames_draw_as_the_reference_says() {
    let mut harness = Harness::new(SIZE, SIZE);
    let cubes = grid(&mut harness);
    assert_matches_reference(&mut harness, "the grid before");
    let made = material_batching(&harness.app).class_bind_groups_made;

    // One material's numbers changed: its record, and its class's one bind group again
    // (not the other class's, nor one per material).
    edit_material(harness.world_mut(), cubes[9], |material| {
        material.base_color = Color::linear_rgb(0.1, 0.2, 0.95);
    });
    let rendered = harness.render_next_frame();
    harness
        .compare_with_reference(&rendered)
        .assert_within("one material changed, the next frame", TOLERANCE);
    let after = material_batching(&harness.app);
    assert_eq!(
        after.class_bind_groups_made - made,
        usize::from(after.on),
        "one material's change makes its class's bind group again, and no other"
    );

    // Materials added (new cubes), removed (their cubes despawned and handles dropped),
    // and one moved to another class (the normalized highlight with its Fresnel term: another
    // shader variant; the plain Blinn-Phong one is only a number of the record).
    let world = harness.world_mut();
    for &cube in &cubes[..SIDE] {
        world.despawn(cube);
    }
    edit_material(world, cubes[20], |material| {
        material.specular_model = SpecularModel::NormalizedBlinnPhong;
    });
    let cube = world
        .resource_mut::<Assets<Mesh>>()
        .add(Sphere::new(0.4).mesh().uv(24, 12));
    for index in 0..SIDE {
        let material = world
            .resource_mut::<Assets<PhongMaterial>>()
            .add(numbered_material(SIDE * SIDE - 1 - index));
        let offset = (SIDE as f32 - 1.0) / 2.0;
        world.spawn((
            Mesh3d(cube.clone()),
            MeshMaterial3d(material),
            Transform::from_xyz(index as f32 - offset, 0.0, -offset),
        ));
    }
    assert_matches_reference(&mut harness, "materials added, removed and moved");
    let batching = material_batching(&harness.app);
    if !batching.on {
        return;
    }
    assert_eq!(
        batching.classes, 3,
        "the two classes and the normalized Blinn-Phong one"
    );
    assert_eq!(batching.meshes_drawn_by_class, SIDE * SIDE);
}
