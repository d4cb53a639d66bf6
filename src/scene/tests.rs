//! Scene and material files through Bevy's asset server, without a renderer: broken files
//! give errors that say where, nothing panics, and a hot-reloaded scene keeps its last good
//! version.

use super::*;
use crate::scene::error::parse_ron;
use crate::{PhongDirectionalLight, PhongMaterial, PhongPlugin, PhongPointLight, PhongSpotLight};
use bevy::{
    asset::{AssetLoadFailedEvent, AssetPlugin, UnapprovedPathMode},
    image::Image,
    mesh::Mesh,
    prelude::*,
    transform::TransformPlugin,
};
use std::{
    path::{Path, PathBuf},
    time::{Duration, Instant},
};

/// A fresh directory for one test's files.
pub(super) fn scratch_directory(name: &str) -> PathBuf {
    let directory = std::env::temp_dir().join(format!("bevy_phong_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&directory);
    std::fs::create_dir_all(&directory).unwrap();
    directory
}

/// An app whose asset root is `directory`, watching it for changes.
pub(super) fn scene_app(directory: &Path) -> App {
    scene_app_with(directory, UnapprovedPathMode::default())
}

/// [`scene_app`] with Bevy's handling of paths outside the asset folder set to `unapproved`.
pub(super) fn scene_app_with(directory: &Path, unapproved: UnapprovedPathMode) -> App {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin {
            file_path: directory.to_string_lossy().into_owned(),
            watch_for_changes_override: Some(true),
            unapproved_path_mode: unapproved,
            ..default()
        },
        TransformPlugin,
        PhongPlugin,
    ))
    .init_asset::<Mesh>()
    .init_asset::<Image>()
    .init_resource::<LoadErrors>()
    .add_systems(Last, collect_load_errors);
    app.update();
    app
}

/// Every load error the asset server reported, as text.
#[derive(Resource, Default)]
pub(super) struct LoadErrors(pub(super) Vec<String>);

fn collect_load_errors(
    mut scenes: MessageReader<AssetLoadFailedEvent<PhongScene>>,
    mut materials: MessageReader<AssetLoadFailedEvent<PhongMaterial>>,
    mut errors: ResMut<LoadErrors>,
) {
    errors
        .0
        .extend(scenes.read().map(|event| event.error.to_string()));
    errors
        .0
        .extend(materials.read().map(|event| event.error.to_string()));
}

/// Runs frames until `done` or `timeout`, sleeping a little between them (file events and
/// loads arrive from other threads).
pub(super) fn run_until(
    app: &mut App,
    timeout: Duration,
    mut done: impl FnMut(&mut App) -> bool,
) -> bool {
    let start = Instant::now();
    while start.elapsed() < timeout {
        app.update();
        if done(app) {
            return true;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    false
}

/// Counts of (cameras, directional, point, spot lights, meshes) spawned.
pub(super) fn spawned(app: &mut App) -> [usize; 5] {
    let world = app.world_mut();
    [
        world.query::<&PhongSceneCamera>().iter(world).count(),
        world.query::<&PhongDirectionalLight>().iter(world).count(),
        world.query::<&PhongPointLight>().iter(world).count(),
        world.query::<&PhongSpotLight>().iter(world).count(),
        world.query::<&Mesh3d>().iter(world).count(),
    ]
}

const GOOD_SCENE: &str = r##"(
    camera: Some((position: (0.0, 2.5, 7.0))),
    ambient: Some(Srgb(0.1, 0.1, 0.2)),
    hemisphere: Some((sky_color: Linear(0.3, 0.4, 0.5), ground_color: Srgb(0.2, 0.1, 0.0))),
    lights: [
        Directional(direction: (-1.0, -1.0, -1.0)),
        Point(position: (0.0, 3.0, 0.0), decay: (constant: 1.0, linear: 0.09, quadratic: 0.032)),
        Spot(position: (0.0, 4.0, 0.0), direction: (0.0, -1.0, 0.0), color: Hex("#ffcc88"),
             cookie: Some((image: "gobo.png", red_only: true))),
        Rect(position: (0.0, 3.0, 0.0), direction: (0.0, -1.0, 0.0), up: Some((0.0, 0.0, 2.0)),
             width: 2.0, height: 0.5, two_sided: true, highlight: RepresentativePoint),
        Disk(position: (1.0, 3.0, 0.0), direction: (0.0, 0.0, 1.0), radius: 0.25, range: Some(4.0)),
    ],
    objects: [
        (mesh: Sphere(radius: 1.0), material: Inline((base_color: Srgb(1.0, 0.0, 1.0), shininess: 50.0))),
        (mesh: Cuboid(size: (1.0, 2.0, 1.0)), transform: (translation: (2.0, 0.0, 0.0), rotation: (0.0, 30.0, 0.0))),
        (mesh: Torus(minor_radius: 0.25, major_radius: 0.75), material: File("shiny.phong.ron")),
    ],
)"##;

const GOOD_MATERIAL: &str = "(specular_model: BlinnPhong, shininess: 160.0, \
    uv_transform: (scale: (2.0, 4.0), rotation: 0.5), unlit: true, fog_enabled: false, \
    cull_mode: Front, depth_bias: 3.0)";

#[test]
fn a_scene_file_spawns_its_camera_lights_and_objects_with_their_values() {
    let directory = scratch_directory("spawn");
    std::fs::write(directory.join("a.phong_scene.ron"), GOOD_SCENE).unwrap();
    std::fs::write(directory.join("shiny.phong.ron"), GOOD_MATERIAL).unwrap();
    let mut app = scene_app(&directory);
    let scene = app
        .world()
        .resource::<AssetServer>()
        .load("a.phong_scene.ron");
    app.world_mut().spawn(PhongSceneRoot(scene));
    assert!(
        run_until(&mut app, Duration::from_secs(20), |app| spawned(app)
            == [1, 1, 1, 1, 3]),
        "spawned {:?}, errors {:?}",
        spawned(&mut app),
        app.world().resource::<LoadErrors>().0
    );
    let ambient = app.world().resource::<crate::PhongAmbientLight>().color;
    assert_eq!(ambient, Color::srgb(0.1, 0.1, 0.2));
    let world = app.world_mut();
    let cookies: Vec<crate::PhongLightCookie> = world
        .query_filtered::<&crate::PhongLightCookie, With<PhongSpotLight>>()
        .iter(world)
        .cloned()
        .collect();
    // Its image is a handle on the file's path (this app has no image loader).
    assert_eq!(cookies.len(), 1, "the spot light's cookie");
    assert!(cookies[0].red_only && !cookies[0].tiled);
    assert_eq!(
        world.resource::<AssetServer>().get_path(&cookies[0].image),
        Some("gobo.png".into())
    );
    let hemisphere = app.world().resource::<crate::PhongHemisphereLight>();
    assert_eq!(
        (hemisphere.sky_color, hemisphere.ground_color, hemisphere.up),
        (
            Color::linear_rgb(0.3, 0.4, 0.5),
            Color::srgb(0.2, 0.1, 0.0),
            bevy::math::Vec3::Y
        )
    );
    // The material file's values arrive once it has loaded.
    assert!(run_until(&mut app, Duration::from_secs(20), |app| {
        let world = app.world_mut();
        let materials = world.resource::<Assets<PhongMaterial>>();
        materials.iter().any(|(_, material)| {
            material.shininess == 160.0
                && material.specular_model == crate::SpecularModel::BlinnPhong
                && material.unlit
                && !material.fog_enabled
                && material.cull_mode == Some(bevy::render::render_resource::Face::Front)
                && material.depth_bias == 3.0
                // As Bevy's glTF loader reads KHR_texture_transform: the angle negated.
                && material.uv_transform
                    == bevy::math::Affine2::from_scale_angle_translation(
                        bevy::math::Vec2::new(2.0, 4.0),
                        -0.5,
                        bevy::math::Vec2::ZERO,
                    )
        })
    }));
    let world = app.world_mut();
    let point = world.query::<&PhongPointLight>().single(world).unwrap();
    assert_eq!(point.decay, crate::Decay::new(1.0, 0.09, 0.032));
    let spot_direction = world
        .query_filtered::<&Transform, With<PhongSpotLight>>()
        .single(world)
        .unwrap()
        .forward();
    assert!(spot_direction.dot(Vec3::NEG_Y) > 0.999_999);
    let (rect, transform) = world
        .query::<(&crate::PhongRectLight, &Transform)>()
        .single(world)
        .unwrap();
    assert_eq!(
        (rect.width, rect.height, rect.two_sided, rect.highlight),
        (2.0, 0.5, true, crate::AreaHighlight::RepresentativePoint)
    );
    assert!(
        transform.forward().dot(Vec3::NEG_Y) > 0.999_999,
        "it faces down"
    );
    assert!(
        transform.up().dot(Vec3::Z) > 0.999_999,
        "its height runs along up"
    );
    let (disk, transform) = world
        .query::<(&crate::PhongDiskLight, &Transform)>()
        .single(world)
        .unwrap();
    assert_eq!((disk.radius, disk.range), (0.25, Some(4.0)));
    assert!(transform.forward().dot(Vec3::Z) > 0.999_999, "it faces +Z");
}

/// A broken file and what its error must say.
struct Broken {
    file: &'static str,
    text: &'static str,
    expected: &'static [&'static str],
}

const BROKEN: &[Broken] = &[
    Broken {
        file: "unclosed.phong_scene.ron",
        text: "(\n  objects: [\n    (mesh: Sphere(radius: 1.0)),\n",
        expected: &["unclosed.phong_scene.ron:3:33:", "Expected opening `(`"],
    },
    Broken {
        file: "misspelt.phong_scene.ron",
        text: "(\n  objects: [\n    (mesh: Sphere(radius: 1.0), materail: Inline(())),\n  ],\n)",
        expected: &["misspelt.phong_scene.ron:3:33:", "`materail`", "`material`"],
    },
    Broken {
        file: "wrong_type.phong_scene.ron",
        text: "(objects: [(mesh: Sphere(radius: \"one\"))])",
        expected: &["wrong_type.phong_scene.ron:1:33:", "Expected float"],
    },
    Broken {
        file: "unknown_mesh.phong_scene.ron",
        text: "(objects: [(mesh: Teapot(size: 1.0))])",
        expected: &["unknown_mesh.phong_scene.ron:1:19:", "`Teapot`", "`Sphere`"],
    },
    Broken {
        file: "negative.phong_scene.ron",
        text: "(objects: [(mesh: Cuboid(size: (1.0, 1.0, 1.0))), (mesh: Sphere(radius: -1.0))])",
        expected: &[
            "objects[1].mesh",
            "radius must be positive and finite, got -1",
        ],
    },
    Broken {
        file: "no_direction.phong_scene.ron",
        text: "(lights: [Directional(direction: (0.0, 0.0, 0.0))])",
        expected: &["lights[0].direction", "non-zero"],
    },
    Broken {
        file: "bad_hex.phong_scene.ron",
        text: "(objects: [(mesh: Sphere(radius: 1.0), material: Inline((base_color: Hex(\"#12345\"))))])",
        expected: &["objects[0].material.base_color", "#12345"],
    },
    Broken {
        file: "bad_fov.phong_scene.ron",
        text: "(camera: Some((position: (0.0, 0.0, 5.0), fov_degrees: 0.0)))",
        expected: &["camera.fov_degrees", "between 0 and 180"],
    },
    Broken {
        file: "camera_at_target.phong_scene.ron",
        text: "(camera: Some((position: (1.0, 2.0, 3.0), looking_at: (1.0, 2.0, 3.0))))",
        expected: &["camera.looking_at", "must differ from position"],
    },
    Broken {
        file: "nan_scale.phong_scene.ron",
        text: "(objects: [(mesh: Sphere(radius: 1.0)), (mesh: Sphere(radius: 1.0), transform: (scale: (1.0, NaN, 1.0)))])",
        expected: &["objects[1].transform.scale", "must be finite"],
    },
    Broken {
        file: "far_light.phong_scene.ron",
        text: "(lights: [Point(position: (0.0, inf, 0.0))])",
        expected: &["lights[0].position", "must be finite"],
    },
    Broken {
        file: "empty.phong_scene.ron",
        text: "",
        expected: &["empty.phong_scene.ron:1:1"],
    },
    Broken {
        file: "not_text.phong_scene.ron",
        text: "\u{0}\u{1}\u{2}",
        expected: &["not_text.phong_scene.ron:1:1"],
    },
    Broken {
        file: "model.phong.ron",
        text: "(\n  specular_model: Blinn,\n)",
        expected: &["model.phong.ron:2:19:", "`Blinn`", "`BlinnPhong`"],
    },
];

#[test]
fn broken_files_give_errors_that_say_where_and_what_was_expected() {
    let directory = scratch_directory("broken");
    for broken in BROKEN {
        std::fs::write(directory.join(broken.file), broken.text).unwrap();
    }
    let mut app = scene_app(&directory);
    let server = app.world().resource::<AssetServer>().clone();
    let _handles: Vec<UntypedHandle> = BROKEN
        .iter()
        .map(|broken| {
            if broken.file.ends_with(".phong.ron") {
                server.load::<PhongMaterial>(broken.file).untyped()
            } else {
                server.load::<PhongScene>(broken.file).untyped()
            }
        })
        .collect();
    assert!(
        run_until(&mut app, Duration::from_secs(20), |app| {
            app.world().resource::<LoadErrors>().0.len() >= BROKEN.len()
        }),
        "errors so far: {:#?}",
        app.world().resource::<LoadErrors>().0
    );
    let errors = &app.world().resource::<LoadErrors>().0;
    for error in errors {
        println!("{}", error.lines().next().unwrap_or_default());
    }
    for broken in BROKEN {
        let error = errors
            .iter()
            .find(|error| error.contains(broken.file))
            .unwrap_or_else(|| panic!("no error for {}: {errors:#?}", broken.file));
        for expected in broken.expected {
            assert!(error.contains(expected), "{:?} lacks {expected:?}", error);
        }
    }
}

#[test]
fn hot_reload_respawns_a_changed_scene_and_keeps_the_last_good_one_after_a_broken_edit() {
    let directory = scratch_directory("reload");
    let path = directory.join("live.phong_scene.ron");
    std::fs::write(&path, "(objects: [(mesh: Sphere(radius: 1.0))])").unwrap();
    let mut app = scene_app(&directory);
    let scene = app
        .world()
        .resource::<AssetServer>()
        .load("live.phong_scene.ron");
    app.world_mut().spawn(PhongSceneRoot(scene));
    let timeout = Duration::from_secs(20);
    assert!(run_until(&mut app, timeout, |app| spawned(app)[4] == 1));

    // A broken edit: an error, and the sphere stays.
    std::fs::write(
        &path,
        "(objects: [(mesh: Sphere(radius: 1.0)), (mesh: Cone(",
    )
    .unwrap();
    assert!(
        run_until(&mut app, timeout, |app| !app
            .world()
            .resource::<LoadErrors>()
            .0
            .is_empty()),
        "the broken edit was not reported"
    );
    for _ in 0..10 {
        app.update();
    }
    assert_eq!(
        spawned(&mut app),
        [0, 0, 0, 0, 1],
        "the last good scene stays"
    );

    // A good edit: respawned, with the new contents only.
    std::fs::write(
        &path,
        "(lights: [Point(position: (0.0, 2.0, 0.0))], objects: [(mesh: Sphere(radius: 1.0)), (mesh: Cone(radius: 1.0, height: 2.0))])",
    )
    .unwrap();
    assert!(
        run_until(&mut app, timeout, |app| spawned(app) == [0, 0, 1, 0, 2]),
        "not respawned: {:?}",
        spawned(&mut app)
    );
}

#[test]
fn parse_ron_reports_line_and_column() {
    let error = parse_ron::<PhongSceneDescription>("x.ron", b"(\n  lights: [\n    Sun(),\n  ],\n)")
        .unwrap_err();
    let SceneFileError::Syntax {
        line,
        column,
        message,
        ..
    } = &error
    else {
        panic!("{error}");
    };
    assert_eq!((*line, *column), (3, 5), "{error}");
    assert!(
        message.contains("Sun") && message.contains("Directional"),
        "{error}"
    );
}
