//! The fuzzer's cases: scene and material files generated from a seed, and the asset folder
//! they are loaded from. Shared by the fuzzer and by the render test that draws a sample of
//! the scenes that load (`tests/gpu/fuzzed_scenes.rs`), so that both see the same files.

use crate::{mutations, random::Random, shapes};
use std::path::{Path, PathBuf};

/// The seed the fuzzer starts from unless `BEVY_PHONG_FUZZ_SEED` names another.
pub const DEFAULT_SEED: u64 = 0x5eed_0013;

/// The shininess of the canary, a material file just outside the asset folder that no case
/// may read.
pub const CANARY_SHININESS: f32 = 4242.0;

/// Scene or material file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `*.phong_scene.ron`, in `scenes/`.
    Scene,
    /// `*.phong.ron`, in `materials/`.
    Material,
}

impl Kind {
    /// The asset path of case `index`.
    pub fn path(self, index: usize) -> String {
        match self {
            Kind::Scene => format!("scenes/case{index}.phong_scene.ron"),
            Kind::Material => format!("materials/case{index}.phong.ron"),
        }
    }
}

/// One generated file.
pub struct Case {
    /// Its number, which names the file.
    pub index: usize,
    /// Scene or material.
    pub kind: Kind,
    /// What generated it, for reports.
    pub generator: &'static str,
    /// Its contents.
    pub bytes: Vec<u8>,
}

/// A second scene and material that use every field and variant the samples leave out.
const FULL_SCENE: &str = r##"(
    camera: Some((position: (0.0, 3.0, 9.0), looking_at: (0.0, 0.0, 0.0), fov_degrees: 45.0)),
    ambient: Some(Srgba(0.1, 0.1, 0.1, 1.0)),
    lights: [
        Directional(color: Srgb(1.0, 1.0, 1.0), specular: Some(Linear(0.5, 0.5, 0.5)), direction: (-1.0, -1.0, -0.5)),
        Point(color: Hex("#ff8800"), position: (1.0, 2.0, 3.0), decay: (constant: 1.0, linear: 0.09, quadratic: 0.032), range: Some(20.0)),
        Spot(color: Linear(1.0, 1.0, 1.0), position: (0.0, 6.0, 3.0), direction: (0.0, -1.0, -0.5), decay: (constant: 1.0, linear: 0.0, quadratic: 0.01), range: None, inner_angle_degrees: 12.5, outer_angle_degrees: 17.5, exponent: 2.0),
    ],
    objects: [
        (mesh: Sphere(radius: 1.0), transform: (translation: (0.0, 1.0, 0.0), rotation: (0.0, 45.0, 0.0), scale: (1.0, 1.0, 1.0)), material: Inline((base_color: Srgb(1.0, 0.0, 1.0), ambient_factor: 1.0, specular_color: Srgb(1.0, 1.0, 1.0), specular_strength: 2.0, shininess: 50.0, specular_model: BlinnPhong, emissive: Linear(0.0, 0.0, 0.0), alpha_mode: Mask(0.5), flip_normal_map_y: true))),
        (mesh: Cuboid(size: (1.0, 2.0, 1.0)), material: File("../materials/textured.phong.ron")),
        (mesh: Plane(size: (10.0, 10.0))),
        (mesh: Torus(minor_radius: 0.25, major_radius: 0.75)),
        (mesh: Cylinder(radius: 0.5, height: 1.0)),
        (mesh: Capsule(radius: 0.5, length: 1.0)),
        (mesh: Cone(radius: 0.5, height: 1.0)),
    ],
)"##;

const FULL_MATERIAL: &str = r##"(
    base_color: Hex("#ffcc00"),
    specular_color: Srgba(1.0, 0.9, 0.8, 1.0),
    specular_strength: 1.5,
    shininess: 120.0,
    specular_model: Phong,
    emissive: Linear(0.1, 0.0, 0.0),
    alpha_mode: Blend,
    base_color_texture: Some("crate.png"),
    specular_texture: Some("crate_specular.png"),
    emissive_texture: None,
    normal_map_texture: Some("../textures/normal.png"),
    flip_normal_map_y: false,
    double_sided: true,
)"##;

fn sample(path: &str) -> String {
    let path = format!("{}/assets/{path}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|error| panic!("{path}: {error}"))
}

/// Makes `root/assets` with `scenes/`, `materials/` and the material files the seeds name,
/// and beside it the canary; returns the asset folder and the canary's absolute path.
pub fn write_asset_folder(root: &Path) -> (PathBuf, String) {
    let _ = std::fs::remove_dir_all(root);
    let assets = root.join("assets");
    for folder in ["scenes", "materials"] {
        std::fs::create_dir_all(assets.join(folder)).unwrap();
    }
    for (path, text) in [
        (
            "materials/brass.phong.ron",
            sample("materials/brass.phong.ron"),
        ),
        ("materials/textured.phong.ron", FULL_MATERIAL.to_owned()),
    ] {
        std::fs::write(assets.join(path), text).unwrap();
    }
    let canary = root.join("canary.phong.ron");
    std::fs::write(&canary, format!("(shininess: {CANARY_SHININESS:?})")).unwrap();
    (assets, canary.to_string_lossy().into_owned())
}

/// The sequence of cases one seed draws.
pub struct Cases {
    random: Random,
    /// The files mutations start from.
    seeds: [(Kind, String); 4],
    /// The canary's absolute path, which some path mutations name.
    canary: String,
}

impl Cases {
    /// The cases of `seed`; `canary` as [`write_asset_folder`] returned it.
    pub fn new(seed: u64, canary: String) -> Self {
        Self {
            random: Random::new(seed),
            seeds: [
                (Kind::Scene, sample("scenes/shapes.phong_scene.ron")),
                (Kind::Scene, FULL_SCENE.to_owned()),
                (Kind::Material, sample("materials/brass.phong.ron")),
                (Kind::Material, FULL_MATERIAL.to_owned()),
            ],
            canary,
        }
    }

    /// Case `index`, the next of the sequence (cases are drawn in order: case `n` depends
    /// on every case before it).
    pub fn generate(&mut self, index: usize) -> Case {
        let (random, canary) = (&mut self.random, self.canary.as_str());
        let (kind, seed) = random.pick(&self.seeds);
        let (kind, seed) = (*kind, seed.as_str());
        let self_name = match kind {
            Kind::Scene => format!("case{index}.phong_scene.ron"),
            Kind::Material => format!("case{index}.phong.ron"),
        };
        let (kind, generator, bytes) = match random.below(100) {
            0..25 => (kind, "bytes", mutations::bytes(random, seed.as_bytes())),
            25..45 => (
                kind,
                "numbers",
                mutations::numbers_replaced(random, seed).into(),
            ),
            45..55 => (
                kind,
                "variants",
                mutations::variant_swapped(random, seed).into(),
            ),
            55..58 => (kind, "nesting", mutations::nested(random, seed)),
            58..62 => (
                kind,
                "long strings",
                mutations::long_string(random, seed).into(),
            ),
            62..67 => (kind, "non-UTF-8", mutations::not_utf8(random, seed)),
            67..82 => {
                let text = mutations::path_replaced(random, seed, &self_name, canary);
                (kind, "paths", text.into())
            }
            _ => (Kind::Scene, "shapes", shapes::scene(random).into()),
        };
        Case {
            index,
            kind,
            generator,
            bytes,
        }
    }
}
