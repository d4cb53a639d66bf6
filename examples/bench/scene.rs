//! The benchmark's scenes, drawn with `PhongMaterial`, `StandardMaterial` or a constant color.

use bevy::camera::Viewport;
use bevy::{
    light::{DirectionalLightShadowMap, PointLightShadowMap},
    prelude::*,
    render::render_resource::AsBindGroup,
    shader::ShaderRef,
};
use bevy_phong::prelude::*;

use crate::cubes::{self, Cubes};
use crate::features::{self, Features};
use crate::lamps::{self, Lamps};
use crate::pairs::{self, Pairs};
use crate::panels::{self, Panels};

/// What the scene's meshes are made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shading {
    /// `PhongMaterial` with this crate's lights, the given highlight, or none.
    Phong(Option<SpecularModel>),
    /// The same lit per vertex (`PhongMaterial::vertex_lighting`); with `fine_floor`, the
    /// field's floor cut into squares of half a unit (12,800 triangles) in place of its two
    /// triangles, so that a light's pool spans many vertices.
    PhongPerVertex {
        specular_model: Option<SpecularModel>,
        fine_floor: bool,
    },
    /// Bevy's `StandardMaterial` with the equivalent Bevy lights.
    Standard,
    /// [`ConstantColor`]: no lighting at all.
    Constant,
}

/// The scenes: the showcase (3 lights), the showcase on a floor with or without shadows, or
/// a field of 100 spheres on a floor under point lights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scene {
    /// Seed 000's four shapes under a directional and two point lights.
    Showcase,
    /// The showcase's shapes on a floor, under a directional light aimed down at it (four
    /// cascades) and the two point lights, all casting shadows or none; the shadow maps
    /// 1024² for both materials. With `split_screen`, two cameras side by side draw half of
    /// the picture each, from either side of the usual camera: each gets cascades of its own.
    ShowcaseOnFloor { shadows: bool, split_screen: bool },
    /// `lights` point lights that fade as `1 / (1 + 0.2 d²)` and are cut off at 4 units.
    Field { lights: usize },
    /// `lights` point lights that fade as `1 / (1 + 4 d²)`, with no range: only ε culling
    /// bounds their reach.
    FieldWithoutRanges { lights: usize },
    /// The field under `lights` point lights as [`Scene::Field`], and `far` more of the same
    /// kind spread over a world 1,000 units across, each at least 40 units from the field's
    /// middle along x or z: none reaches a visible pixel.
    WideWorld { lights: usize, far: usize },
    /// The showcase with a group of material features on (`features.rs`).
    Featured(Features),
    /// Street lamps over the field (`lamps.rs`).
    Lamps(Lamps),
    /// A grid of many meshes and materials (`cubes.rs`).
    Cubes(Cubes),
    /// Rectangle lights over the field (`panels.rs`).
    Panels(Panels),
    /// A floor under lights of one kind that each light all of it (`pairs.rs`).
    Pairs(Pairs),
}

impl Scene {
    pub fn name(self) -> String {
        match self {
            Scene::Showcase => "showcase (3 lights)".into(),
            Scene::ShowcaseOnFloor {
                shadows,
                split_screen,
            } => format!(
                "showcase on a floor, shadows {}{}",
                if shadows { "on" } else { "off" },
                if split_screen { ", split screen" } else { "" }
            ),
            Scene::Field { lights } => {
                format!("field, {} with range", counted_point_lights(lights))
            }
            Scene::FieldWithoutRanges { lights } => {
                format!("field, {} without range", counted_point_lights(lights))
            }
            Scene::WideWorld { lights, far } => format!(
                "wide world, {} + {far} far away",
                counted_point_lights(lights)
            ),
            Scene::Featured(features) => format!("showcase, {}", features.name()),
            Scene::Lamps(lamps) => lamps.name(),
            Scene::Cubes(cubes) => cubes.name(),
            Scene::Panels(panels) => panels.name(),
            Scene::Pairs(pairs) => pairs.name(),
        }
    }

    /// Where the camera stands (looking at the origin).
    pub fn camera_position(self) -> Vec3 {
        match self {
            Scene::Showcase | Scene::ShowcaseOnFloor { .. } | Scene::Featured(_) => {
                Vec3::new(0.0, 1.0, 8.5)
            }
            Scene::Cubes(cubes) => cubes.camera_position(),
            Scene::Pairs(_) => pairs::CAMERA,
            _ => Vec3::new(0.0, 14.0, 16.0),
        }
    }

    /// Where each camera stands (looking at the origin), and the part of the picture it
    /// draws: `None` for the whole, else the left or right half of a `size`² picture.
    pub fn cameras(self, size: u32) -> Vec<(Vec3, Option<Viewport>)> {
        let Scene::ShowcaseOnFloor {
            split_screen: true, ..
        } = self
        else {
            return vec![(self.camera_position(), None)];
        };
        let half = |left: bool| Viewport {
            physical_position: UVec2::new(if left { 0 } else { size / 2 }, 0),
            physical_size: UVec2::new(size / 2, size),
            ..default()
        };
        let side = Vec3::new(3.0, 0.0, 0.0);
        vec![
            (self.camera_position() - side, Some(half(true))),
            (self.camera_position() + side, Some(half(false))),
        ]
    }
}

/// "1 point light", "16 point lights".
fn counted_point_lights(count: usize) -> String {
    format!("{count} point light{}", if count == 1 { "" } else { "s" })
}

/// Edge length of every shadow map, both materials' (Bevy's directional and point light
/// maps), texels.
pub const SHADOW_MAP_SIZE: u32 = 1024;

/// A material whose fragment shader returns a constant color.
#[derive(Asset, AsBindGroup, TypePath, Clone)]
pub struct ConstantColor {
    #[uniform(0)]
    color: LinearRgba,
}

impl ConstantColor {
    pub fn new(color: LinearRgba) -> Self {
        Self { color }
    }
}

impl Material for ConstantColor {
    fn fragment_shader() -> ShaderRef {
        "shaders/constant_color.wesl".into()
    }
}

/// A small deterministic generator for light positions and colors: the R2 sequence (evenly
/// spread over the unit square) and a golden-ratio sequence.
pub fn scatter(i: usize) -> (f32, f32, f32) {
    let t = i as f32;
    (
        (0.5 + t * 0.754_877_7).fract(),
        (0.5 + t * 0.569_840_3).fract(),
        (t * 0.618_034).fract(),
    )
}

/// The meshes of `scene` and their colors, the field's floor cut into half-unit squares where
/// `fine_floor`.
fn objects(scene: Scene, fine_floor: bool) -> Vec<(Mesh, Vec3, Color)> {
    let mut objects: Vec<(Mesh, Vec3, Color)> = Vec::new();
    if let Scene::Pairs(_) = scene {
        objects.push((pairs::floor(), Vec3::ZERO, Color::srgb(0.6, 0.6, 0.6)));
        return objects;
    }
    if let Scene::ShowcaseOnFloor { .. } = scene {
        objects.push((
            Plane3d::default().mesh().size(30.0, 30.0).into(),
            Vec3::new(0.0, -1.6, 0.0),
            Color::srgb(0.6, 0.6, 0.6),
        ));
    }
    if matches!(
        scene,
        Scene::Showcase | Scene::ShowcaseOnFloor { .. } | Scene::Featured(_)
    ) {
        objects.push((
            Cuboid::new(1.6, 1.6, 1.6).into(),
            Vec3::new(-4.5, 0.0, 0.0),
            Color::srgb(0.0, 0.0, 1.0),
        ));
        objects.push((
            Sphere::new(1.0).mesh().uv(64, 48),
            Vec3::new(-1.5, 0.0, 0.0),
            Color::srgb(1.0, 0.0, 1.0),
        ));
        objects.push((
            Cylinder::new(0.9, 1.8).into(),
            Vec3::new(1.5, 0.0, 0.0),
            Color::srgb(0.0, 0.5, 0.0),
        ));
        objects.push((
            Torus::new(0.45, 1.0).into(),
            Vec3::new(4.5, 0.0, 0.0),
            Color::srgb(1.0, 0.0, 0.0),
        ));
        return objects;
    }
    let floor = Plane3d::default().mesh().size(40.0, 40.0);
    objects.push((
        if fine_floor {
            floor.subdivisions(79).into()
        } else {
            floor.into()
        },
        Vec3::new(0.0, -0.8, 0.0),
        Color::srgb(0.7, 0.7, 0.7),
    ));
    for x in -5..5 {
        for z in -5..5 {
            let position = Vec3::new(x as f32 * 2.4 + 1.2, 0.0, z as f32 * 2.4 + 1.2);
            let hue = ((x + 5) * 10 + z + 5) as f32 * 3.6;
            objects.push((
                Sphere::new(0.8).mesh().uv(24, 16),
                position,
                Color::hsl(hue, 0.7, 0.5),
            ));
        }
    }
    objects
}

/// A point light of the scene: position, color, this crate's decay and range.
struct Light {
    position: Vec3,
    color: Color,
    decay: Decay,
    range: Option<f32>,
}

fn point_lights(scene: Scene) -> Vec<Light> {
    let field = |count: usize, decay: Decay, range: Option<f32>| {
        (0..count)
            .map(|i| {
                let (u, v, w) = scatter(i);
                Light {
                    position: Vec3::new(u * 24.0 - 12.0, 0.5 + 2.5 * w, v * 24.0 - 12.0),
                    color: Color::hsl(w * 360.0, 1.0, 0.5),
                    decay,
                    range,
                }
            })
            .collect()
    };
    match scene {
        Scene::Showcase | Scene::ShowcaseOnFloor { .. } | Scene::Featured(_) => [
            (Vec3::new(-3.0, 3.0, 0.0), Color::linear_rgb(1.0, 0.0, 0.0)),
            (Vec3::new(3.0, 3.0, 0.0), Color::linear_rgb(0.0, 0.0, 1.0)),
        ]
        .map(|(position, color)| Light {
            position,
            color,
            decay: Decay::quadratic(0.2),
            range: None,
        })
        .into(),
        Scene::Field { lights } => field(lights, Decay::quadratic(0.2), Some(4.0)),
        Scene::WideWorld { lights, far } => {
            let mut near = field(lights, Decay::quadratic(0.2), Some(4.0));
            near.extend(far_lights(far));
            near
        }
        Scene::FieldWithoutRanges { lights } => field(lights, Decay::quadratic(4.0), None),
        Scene::Lamps(_) | Scene::Cubes(_) | Scene::Panels(_) | Scene::Pairs(_) => Vec::new(),
    }
}

/// `count` point lights like the field's, spread over the square 1,000 units across
/// around the field, each at least 40 units from its middle along x or z.
fn far_lights(count: usize) -> Vec<Light> {
    (0..)
        .map(|i| {
            let (u, v, w) = scatter(i + 1_000_003);
            let position = Vec3::new(u * 1000.0 - 500.0, 0.5 + 2.5 * w, v * 1000.0 - 500.0);
            (position, w)
        })
        .filter(|(position, _)| position.x.abs().max(position.z.abs()) >= 40.0)
        .take(count)
        .map(|(position, w)| Light {
            position,
            color: Color::hsl(w * 360.0, 1.0, 0.5),
            decay: Decay::quadratic(0.2),
            range: Some(4.0),
        })
        .collect()
}

/// Spawns the meshes and lights of `scene` drawn with `shading` (no camera).
pub fn spawn_scene(world: &mut World, scene: Scene, shading: Shading) {
    if let Scene::Cubes(grid) = scene {
        return cubes::spawn(world, grid, shading);
    }
    let fine_floor = matches!(
        shading,
        Shading::PhongPerVertex {
            fine_floor: true,
            ..
        }
    );
    for (mesh, position, color) in objects(scene, fine_floor) {
        let mesh = Mesh3d(world.resource_mut::<Assets<Mesh>>().add(mesh));
        let transform = Transform::from_translation(position);
        match shading {
            Shading::Phong(specular_model) | Shading::PhongPerVertex { specular_model, .. } => {
                let material = world
                    .resource_mut::<Assets<PhongMaterial>>()
                    .add(PhongMaterial {
                        base_color: color,
                        specular_strength: if specular_model.is_some() { 2.0 } else { 0.0 },
                        shininess: 50.0,
                        specular_model: specular_model.unwrap_or_default(),
                        vertex_lighting: matches!(shading, Shading::PhongPerVertex { .. }),
                        ..default()
                    });
                world.spawn((mesh, MeshMaterial3d(material), transform));
            }
            Shading::Standard => {
                let material = world
                    .resource_mut::<Assets<StandardMaterial>>()
                    .add(StandardMaterial::from(color));
                world.spawn((mesh, MeshMaterial3d(material), transform));
            }
            Shading::Constant => {
                let material = world
                    .resource_mut::<Assets<ConstantColor>>()
                    .add(ConstantColor {
                        color: color.into(),
                    });
                world.spawn((mesh, MeshMaterial3d(material), transform));
            }
        }
    }

    let (directional, has_directional, shadows) = match scene {
        Scene::Showcase | Scene::Featured(_) => (
            Transform::default().looking_to(Vec3::NEG_X, Vec3::Y),
            true,
            false,
        ),
        Scene::ShowcaseOnFloor { shadows, .. } => (
            Transform::default().looking_to(Vec3::new(-1.0, -1.2, -0.6), Vec3::Y),
            true,
            shadows,
        ),
        _ => (Transform::default(), false, false),
    };
    let phong_shadows = PhongShadows {
        enabled: shadows,
        resolution: SHADOW_MAP_SIZE,
        ..default()
    };
    match shading {
        Shading::Phong(_) | Shading::PhongPerVertex { .. } => {
            if has_directional {
                world.spawn((
                    PhongDirectionalLight {
                        shadows: phong_shadows,
                        ..default()
                    },
                    directional,
                ));
            }
            for light in point_lights(scene) {
                world.spawn((
                    PhongPointLight {
                        color: light.color,
                        decay: light.decay,
                        range: light.range,
                        shadows: phong_shadows,
                        ..default()
                    },
                    Transform::from_translation(light.position),
                ));
            }
        }
        Shading::Standard => {
            world.insert_resource(DirectionalLightShadowMap {
                size: SHADOW_MAP_SIZE as usize,
            });
            world.insert_resource(PointLightShadowMap {
                size: SHADOW_MAP_SIZE as usize,
            });
            if has_directional {
                world.spawn((
                    DirectionalLight {
                        shadow_maps_enabled: shadows,
                        ..default()
                    },
                    directional,
                ));
            }
            for light in point_lights(scene) {
                world.spawn((
                    PointLight {
                        color: light.color,
                        range: light.range.unwrap_or(20.0),
                        shadow_maps_enabled: shadows,
                        ..default()
                    },
                    Transform::from_translation(light.position),
                ));
            }
        }
        Shading::Constant => {}
    }
    if let Scene::Featured(group) = scene {
        features::apply(world, group, shading);
    }
    if let Scene::Lamps(lamps) = scene {
        lamps::spawn_lamps(world, lamps, shading);
    }
    if let Scene::Panels(panels) = scene {
        panels::spawn_panels(world, panels);
    }
    if let Scene::Pairs(pairs) = scene {
        pairs::apply(world, pairs);
    }
}
