//! Hostile scene and material files: paths out of the asset folder are refused before
//! anything outside it is read, errors quote at most 80 characters of a value, and
//! directions of any scale keep their direction.

use super::tests::{LoadErrors, run_until, scene_app, scene_app_with, scratch_directory, spawned};
use super::*;
use crate::{PhongDirectionalLight, PhongMaterial, PhongSpotLight, lights::light_direction};
use bevy::{asset::UnapprovedPathMode, prelude::*};
use std::{path::Path, time::Duration};

/// A file that must never be read: a valid material whose shininess no other file uses.
const CANARY: &str = "(shininess: 4242.0)";
const CANARY_SHININESS: f32 = 4242.0;

/// A file under the asset folder, what loads it as, and what its error must say.
struct Refused {
    file: &'static str,
    text: String,
    expected: &'static [&'static str],
}

fn write(directory: &Path, file: &str, text: &str) {
    let path = directory.join(file);
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

fn scene_naming(material: &str) -> String {
    format!("(objects: [(mesh: Sphere(radius: 1.0), material: File({material:?}))])")
}

/// Loads every file in `refused` and `good_scene`, and returns the load errors once there is
/// one per refused file and the good scene has spawned its sphere.
fn load_all(app: &mut App, refused: &[Refused], good_scene: &str) -> Vec<String> {
    let server = app.world().resource::<AssetServer>().clone();
    let _handles: Vec<UntypedHandle> = refused
        .iter()
        .map(|file| {
            if file.file.ends_with(".phong.ron") {
                server.load::<PhongMaterial>(file.file).untyped()
            } else {
                server.load::<PhongScene>(file.file).untyped()
            }
        })
        .collect();
    let good = server.load::<PhongScene>(good_scene.to_owned());
    app.world_mut().spawn(PhongSceneRoot(good));
    let timeout = Duration::from_secs(30);
    let all_in = run_until(app, timeout, |app| {
        app.world().resource::<LoadErrors>().0.len() >= refused.len() && spawned(app)[4] == 1
    });
    // A few more frames: a canary read late would show up now.
    for _ in 0..20 {
        app.update();
        std::thread::sleep(Duration::from_millis(5));
    }
    let errors = app.world().resource::<LoadErrors>().0.clone();
    assert!(all_in, "errors so far: {errors:#?}");
    errors
}

#[test]
fn paths_out_of_the_asset_folder_are_refused_and_the_canary_outside_is_never_read() {
    // Bevy's own check on such paths (`Forbid`, the default, which panicked inside the
    // loader) and none at all (`Allow`, which read the file): the crate refuses them either
    // way.
    for (name, mode) in [
        ("forbid", UnapprovedPathMode::Forbid),
        ("allow", UnapprovedPathMode::Allow),
    ] {
        let root = scratch_directory(&format!("canary_{name}"));
        let assets = root.join("assets");
        write(&root, "canary.phong.ron", CANARY);
        let canary = root.join("canary.phong.ron");
        let canary = canary.to_str().unwrap();
        let refused = [
            Refused {
                file: "scenes/climb.phong_scene.ron",
                text: scene_naming("../../canary.phong.ron"),
                expected: &[
                    "objects[0].material",
                    "../../canary.phong.ron",
                    "climbs out",
                ],
            },
            Refused {
                file: "scenes/absolute.phong_scene.ron",
                text: scene_naming(canary),
                expected: &["objects[0].material", "is absolute"],
            },
            Refused {
                file: "scenes/source.phong_scene.ron",
                text: scene_naming("other://canary.phong.ron"),
                expected: &["objects[0].material", "another asset source"],
            },
            Refused {
                file: "scenes/itself.phong_scene.ron",
                text: scene_naming("itself.phong_scene.ron"),
                expected: &["objects[0].material", "this file itself"],
            },
            Refused {
                file: "scenes/folder.phong_scene.ron",
                text: scene_naming("../materials/"),
                expected: &["objects[0].material", "names a folder"],
            },
            Refused {
                file: "materials/texture.phong.ron",
                text: "(base_color_texture: Some(\"../../../../../etc/passwd\"))".into(),
                expected: &[
                    "materials/texture.phong.ron: base_color_texture:",
                    "climbs out",
                ],
            },
            Refused {
                file: "materials/long.phong.ron",
                text: format!("(normal_map_texture: Some({:?}))", "a/".repeat(100_000)),
                expected: &["normal_map_texture", "(200,000 characters) is too long"],
            },
        ];
        for file in &refused {
            write(&assets, file.file, &file.text);
        }
        // A `..` that stays inside the folder is fine.
        write(&assets, "materials/fine.phong.ron", "(shininess: 7.0)");
        write(
            &assets,
            "scenes/fine.phong_scene.ron",
            &scene_naming("../materials/fine.phong.ron"),
        );

        let mut app = scene_app_with(&assets, mode);
        let errors = load_all(&mut app, &refused, "scenes/fine.phong_scene.ron");
        for file in &refused {
            let error = errors
                .iter()
                .find(|error| error.contains(file.file))
                .unwrap_or_else(|| panic!("{name}: no error for {}: {errors:#?}", file.file));
            for expected in file.expected {
                assert!(
                    error.contains(expected),
                    "{name}: {error:?} lacks {expected:?}"
                );
            }
            assert!(!error.contains("panicked"), "{name}: {error}");
        }
        let materials = app.world().resource::<Assets<PhongMaterial>>();
        assert!(
            materials
                .iter()
                .all(|(_, material)| material.shininess != CANARY_SHININESS),
            "{name}: the canary outside the asset folder was read"
        );
    }
}

#[test]
fn an_error_quotes_at_most_80_characters_of_a_value_and_names_its_length() {
    let directory = scratch_directory("long_values");
    let hex = format!("#{}", "f".repeat(5_000_000));
    let long_field = "m".repeat(200_000);
    let long_variant = "T".repeat(300_000);
    let refused = [
        Refused {
            file: "hex.phong_scene.ron",
            text: format!("(ambient: Some(Hex({hex:?})))"),
            expected: &[
                "hex.phong_scene.ron: ambient:",
                "(5,000,001 characters) is not a hex color",
            ],
        },
        Refused {
            file: "field.phong.ron",
            text: format!("({long_field}: 1.0)"),
            expected: &["field.phong.ron:1:", "…` (200,000 characters)"],
        },
        Refused {
            file: "variant.phong_scene.ron",
            text: format!("(objects: [(mesh: {long_variant}(size: 1.0))])"),
            expected: &["variant.phong_scene.ron:1:", "…` (300,000 characters)"],
        },
    ];
    for file in &refused {
        write(&directory, file.file, &file.text);
    }
    write(
        &directory,
        "fine.phong_scene.ron",
        "(objects: [(mesh: Sphere(radius: 1.0))])",
    );
    let mut app = scene_app(&directory);
    let errors = load_all(&mut app, &refused, "fine.phong_scene.ron");
    for file in &refused {
        let error = errors
            .iter()
            .find(|error| error.contains(file.file))
            .unwrap_or_else(|| panic!("no error for {}", file.file));
        // The path, the field or position, the 80 quoted characters and the rest of the
        // message: a few hundred bytes, however long the value, beside the list of the
        // fields a description accepts where it gives one. (Bevy may append a backtrace on
        // the following lines.)
        let message = error.lines().next().unwrap_or_default();
        let listed = message
            .find("expected one of")
            .map_or(0, |start| message.len() - start);
        let start: String = message.chars().take(600).collect();
        assert!(
            message.len() - listed < 600,
            "{} bytes, {listed} of them the list of fields: {start}",
            message.len()
        );
        for expected in file.expected {
            assert!(error.contains(expected), "{error:?} lacks {expected:?}");
        }
    }
    // The first 80 characters of the value are quoted.
    let quoted = format!("\"{}…\"", &hex[..80]);
    assert!(
        errors.iter().any(|error| error.contains(&quoted)),
        "{errors:#?}"
    );
}

#[test]
fn file_directions_of_any_scale_point_where_they_say() {
    let directory = scratch_directory("directions");
    write(
        &directory,
        "aimed.phong_scene.ron",
        "(lights: [
            Directional(direction: (3e38, 3e38, 3e38)),
            Spot(position: (0.0, 0.0, 0.0), direction: (1e-30, -1e-30, 0.0)),
        ], objects: [(mesh: Sphere(radius: 1.0))])",
    );
    let mut app = scene_app(&directory);
    let scene = app
        .world()
        .resource::<AssetServer>()
        .load("aimed.phong_scene.ron");
    app.world_mut().spawn(PhongSceneRoot(scene));
    assert!(
        run_until(&mut app, Duration::from_secs(20), |app| spawned(app)
            == [0, 1, 0, 1, 1]),
        "spawned {:?}, errors {:?}",
        spawned(&mut app),
        app.world().resource::<LoadErrors>().0
    );
    let world = app.world_mut();
    let directional = *world
        .query_filtered::<&GlobalTransform, With<PhongDirectionalLight>>()
        .single(world)
        .unwrap();
    let spot = *world
        .query_filtered::<&GlobalTransform, With<PhongSpotLight>>()
        .single(world)
        .unwrap();
    // The direction the light record gets; a rotation built from it and read back rounds
    // to a few f32 ulps.
    let pairs = [
        (light_direction(&directional), Vec3::ONE.normalize()),
        (
            light_direction(&spot),
            Vec3::new(1.0, -1.0, 0.0).normalize(),
        ),
    ];
    for (actual, expected) in pairs {
        assert!(
            actual.abs_diff_eq(expected, 1e-6),
            "{actual} instead of {expected}"
        );
    }
}

#[test]
fn a_spot_angle_of_1e400_degrees_in_a_file_is_reported_and_clamped_to_180_degrees() {
    let directory = scratch_directory("huge_angle");
    // RON reads 1e400 as f32 infinity; 1e9° is finite but far past 180°.
    write(
        &directory,
        "spots.phong_scene.ron",
        "(lights: [
            Spot(position: (0.0, 2.0, 0.0), direction: (0.0, -1.0, 0.0), outer_angle_degrees: 1e400),
            Spot(position: (0.0, 2.0, 0.0), direction: (0.0, -1.0, 0.0), outer_angle_degrees: 1e9),
        ])",
    );
    let mut app = scene_app(&directory);
    let scene = app
        .world()
        .resource::<AssetServer>()
        .load("spots.phong_scene.ron");
    app.world_mut().spawn(PhongSceneRoot(scene));
    assert!(run_until(&mut app, Duration::from_secs(20), |app| spawned(
        app
    ) == [
        0, 0, 0, 2, 0
    ]));
    app.update();
    let warnings: Vec<_> = crate::test_app::invalid_inputs(&mut app)
        .into_iter()
        .filter(|warning| warning.field == "outer_angle")
        .map(|warning| warning.value)
        .collect();
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert!(warnings.contains(&"inf".to_owned()), "{warnings:?}");
    let world = app.world_mut();
    for spot in world.query::<&PhongSpotLight>().iter(world) {
        assert_eq!(spot.outer_angle, core::f32::consts::PI);
    }
}
