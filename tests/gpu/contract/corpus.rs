//! The contract corpus: seeded random cases across realistic ranges, every degenerate case
//! of SPEC.md's numerical rules, grazing angles, and coordinates far from the origin. Each
//! case is built from the crate's own components and conversions, so the kernel and the
//! reference see the same `f32` inputs.

use super::kernel::GpuCase;
use bevy::prelude::*;
use bevy_phong::{
    Decay, PhongDirectionalLight, PhongMaterial, PhongPointLight, PhongSpotLight, SpecularModel,
    extension::PhongLightKind,
    reference::{self, SurfacePoint},
    testing::{GpuLight, PhongMaterialUniform},
};
use glam::DVec3;

/// Which error budget a case is held to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Regime {
    /// Realistic scenes: coordinates within 100 units, shininess up to 512.
    Typical,
    /// `N·L` within 1e-6 of 0: the terminator, where the highlight is switched off.
    Grazing,
    /// Coordinates of 1e5 and 1e7.
    Far,
    /// SPEC.md's degenerate inputs (zero or NaN normal, light at P, zero decay, ...).
    Degenerate,
}

/// A light of any built-in kind with its transform.
#[derive(Clone, Debug)]
pub enum AnyLight {
    Directional(PhongDirectionalLight, Transform),
    Point(PhongPointLight, Transform),
    Spot(PhongSpotLight, Transform),
}

/// One case: what it stresses, the kernel's input, and the reference's identical input.
#[derive(Clone, Debug)]
pub struct Case {
    pub regime: Regime,
    pub stresses: &'static str,
    pub gpu: GpuCase,
    pub surface: SurfacePoint,
    pub material: reference::Material,
    pub light: reference::Light,
}

/// `light`'s record at `transform` as the gather writes it for the exact model (ε = 0):
/// with its reach, its range.
fn gathered<L: PhongLightKind<Gpu = GpuLight>>(light: &L, transform: &GlobalTransform) -> GpuLight {
    let mut record = light.to_gpu(transform);
    let reach = light.reach(&record, 0.0);
    L::set_reach(&mut record, reach);
    record
}

impl Case {
    pub fn new(
        regime: Regime,
        stresses: &'static str,
        (position, normal, camera): (Vec3, Vec3, Vec3),
        material: &PhongMaterial,
        light: &AnyLight,
    ) -> Self {
        let uniform = PhongMaterialUniform::from(material);
        let (kind, gpu_light, reference_light) = match light {
            AnyLight::Directional(light, transform) => {
                let transform = GlobalTransform::from(*transform);
                (
                    0,
                    gathered(light, &transform),
                    reference::Light::directional(light, &transform),
                )
            }
            AnyLight::Point(light, transform) => {
                let transform = GlobalTransform::from(*transform);
                (
                    1,
                    gathered(light, &transform),
                    reference::Light::point(light, &transform),
                )
            }
            AnyLight::Spot(light, transform) => {
                let transform = GlobalTransform::from(*transform);
                (
                    2,
                    gathered(light, &transform),
                    reference::Light::spot(light, &transform),
                )
            }
        };
        Self {
            regime,
            stresses,
            gpu: GpuCase {
                position: position.to_array(),
                kind,
                normal: normal.to_array(),
                shininess: uniform.shininess,
                camera: camera.to_array(),
                specular_model: uniform.flags,
                diffuse: uniform.base_color.truncate().to_array(),
                specular: uniform.specular.to_array(),
                light: gpu_light,
                ..default()
            },
            surface: SurfacePoint {
                position: position.as_dvec3(),
                normal: normal.as_dvec3(),
                camera: camera.as_dvec3(),
            },
            material: material.into(),
            light: reference_light,
        }
    }

    /// The reference result: the light's term in `f64`.
    pub fn expected(&self) -> DVec3 {
        reference::light_contribution(&self.surface, &self.material, &self.light)
    }

    /// For a grazing case, the result on the other side of the terminator (the sign of `N·L`
    /// that `f32` cannot resolve there): the light's term with the highlight gate flipped.
    pub fn other_side_of_terminator(&self) -> Option<DVec3> {
        let normal = self.surface.normal.normalize_or_zero();
        let to_light = match self.light {
            reference::Light::Directional { direction, .. } => -direction.normalize_or_zero(),
            reference::Light::Point { position, .. } | reference::Light::Spot { position, .. } => {
                (position - self.surface.position).normalize_or_zero()
            }
        };
        let n_dot_l = normal.dot(to_light);
        if n_dot_l.abs() > 1e-6 {
            return None;
        }
        // Evaluate with the normal tilted just across the terminator: the diffuse term is
        // ~1e-6 either way, the highlight switches on or off.
        let tilt = to_light * (2e-6 * -n_dot_l.signum());
        let mut across = self.clone();
        across.surface.normal = (normal + tilt).normalize();
        Some(across.expected())
    }
}

/// SplitMix64: a small, seeded, portable generator.
pub struct Random(u64);

impl Random {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[low, high)`.
    pub fn range(&mut self, low: f32, high: f32) -> f32 {
        let unit = (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
        low + (high - low) * unit
    }

    /// Log-uniform in `[low, high)`.
    pub fn log_range(&mut self, low: f32, high: f32) -> f32 {
        self.range(low.ln(), high.ln()).exp()
    }

    pub fn chance(&mut self, probability: f32) -> bool {
        self.range(0.0, 1.0) < probability
    }

    /// A uniformly distributed unit vector.
    pub fn direction(&mut self) -> Vec3 {
        let z = self.range(-1.0, 1.0);
        let angle = self.range(0.0, std::f32::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * angle.cos(), r * angle.sin(), z)
    }

    pub fn vector(&mut self, extent: f32) -> Vec3 {
        Vec3::new(
            self.range(-extent, extent),
            self.range(-extent, extent),
            self.range(-extent, extent),
        )
    }

    pub fn color(&mut self, max: f32) -> Color {
        Color::linear_rgb(
            self.range(0.0, max),
            self.range(0.0, max),
            self.range(0.0, max),
        )
    }
}

/// A unit vector perpendicular to `v`.
fn perpendicular(v: Vec3) -> Vec3 {
    v.any_orthonormal_vector()
}

fn random_material(random: &mut Random, max_shininess: f32) -> PhongMaterial {
    PhongMaterial {
        base_color: random.color(1.0),
        specular_color: random.color(1.0),
        specular_strength: random.range(0.0, 2.0),
        shininess: random.log_range(1.0, max_shininess),
        specular_model: if random.chance(0.5) {
            SpecularModel::Phong
        } else {
            SpecularModel::BlinnPhong
        },
        ..default()
    }
}

fn random_decay(random: &mut Random) -> Decay {
    Decay::new(
        random.range(0.0, 2.0),
        random.range(0.0, 0.5),
        random.range(0.0, 0.2),
    )
}

/// A light of a random kind that reaches `position` from the side of `normal` most of the
/// time, `distance` units away.
fn random_light(random: &mut Random, position: Vec3, normal: Vec3, distance: f32) -> AnyLight {
    let toward = (normal + random.direction() * 0.9).normalize_or(normal);
    let light_position = position + toward * distance;
    let color = random.color(2.0);
    let specular = random.chance(0.5).then(|| random.color(2.0));
    let range = random
        .chance(0.3)
        .then(|| distance * random.range(0.5, 2.0));
    match random.next_u64() % 3 {
        0 => AnyLight::Directional(
            PhongDirectionalLight {
                color,
                specular,
                ..default()
            },
            Transform::default().looking_to(-toward, perpendicular(toward)),
        ),
        1 => AnyLight::Point(
            PhongPointLight {
                color,
                specular,
                decay: random_decay(random),
                range,
                ..default()
            },
            Transform::from_translation(light_position),
        ),
        _ => {
            let inner = random.range(0.0, 40.0).to_radians();
            let outer = inner + random.range(0.0, 25.0).to_radians();
            // Aimed near the point, so that the cone's edge is exercised.
            let aim = (-toward + random.direction() * random.range(0.0, 0.6)).normalize_or(-toward);
            AnyLight::Spot(
                PhongSpotLight {
                    color,
                    specular,
                    decay: random_decay(random),
                    range,
                    inner_angle: inner,
                    outer_angle: outer,
                    exponent: random.range(0.0, 8.0),
                    ..default()
                },
                Transform::from_translation(light_position).looking_to(aim, perpendicular(aim)),
            )
        }
    }
}

/// A camera `distance` units from `position`, on the side of `normal` most of the time.
fn random_camera(random: &mut Random, position: Vec3, normal: Vec3, distance: f32) -> Vec3 {
    let toward = (normal + random.direction() * 0.9).normalize_or(normal);
    position + toward * distance
}

/// `count` typical cases.
pub fn typical(random: &mut Random, count: usize) -> Vec<Case> {
    (0..count)
        .map(|_| {
            let position = random.vector(50.0);
            let normal = random.direction() * random.range(0.5, 2.0);
            let distance = random.range(0.5, 40.0);
            let camera = random_camera(random, position, normal, distance);
            let distance = random.log_range(0.05, 40.0);
            let light = random_light(random, position, normal, distance);
            let material = random_material(random, 512.0);
            Case::new(
                Regime::Typical,
                "random",
                (position, normal, camera),
                &material,
                &light,
            )
        })
        .collect()
}

/// `count` cases with `N·L` within 1e-6 of 0.
pub fn grazing(random: &mut Random, count: usize) -> Vec<Case> {
    (0..count)
        .map(|_| {
            let position = random.vector(20.0);
            let to_light = random.direction();
            let normal =
                (perpendicular(to_light) + to_light * random.range(-1e-6, 1e-6)).normalize();
            let distance = random.range(0.5, 20.0);
            let camera = random_camera(random, position, normal, distance);
            let material = random_material(random, 512.0);
            let distance = random.range(0.5, 20.0);
            let light = match random_light(random, position, normal, distance) {
                AnyLight::Directional(light, _) => AnyLight::Directional(
                    light,
                    Transform::default().looking_to(-to_light, perpendicular(to_light)),
                ),
                AnyLight::Point(light, _) => AnyLight::Point(
                    light,
                    Transform::from_translation(position + to_light * distance),
                ),
                AnyLight::Spot(light, _) => AnyLight::Spot(
                    light,
                    Transform::from_translation(position + to_light * distance)
                        .looking_to(-to_light, perpendicular(to_light)),
                ),
            };
            Case::new(
                Regime::Grazing,
                "N·L near 0",
                (position, normal, camera),
                &material,
                &light,
            )
        })
        .collect()
}

/// `count` typical-looking cases around points 1e5 and 1e7 units from the origin.
pub fn far(random: &mut Random, count: usize) -> Vec<Case> {
    (0..count)
        .map(|i| {
            let scale = if i % 2 == 0 { 1e5 } else { 1e7 };
            let position = random.direction() * scale;
            let normal = random.direction();
            let distance = random.range(1.0, 40.0);
            let camera = random_camera(random, position, normal, distance);
            let distance = random.log_range(0.5, 40.0);
            let light = random_light(random, position, normal, distance);
            let material = random_material(random, 512.0);
            Case::new(
                Regime::Far,
                "coordinates 1e5 and 1e7",
                (position, normal, camera),
                &material,
                &light,
            )
        })
        .collect()
}

/// Every degenerate input of SPEC.md's numerical rules, each crossed with a few lights,
/// materials and views.
pub fn degenerate(random: &mut Random) -> Vec<Case> {
    let mut cases = Vec::new();
    let position = Vec3::new(1.0, 2.0, 3.0);
    let normal = Vec3::Y;
    let camera = position + Vec3::new(0.3, 2.0, 1.0);
    let above = Transform::from_translation(position + Vec3::new(0.5, 3.0, 0.2));
    let point = |decay: Decay| PhongPointLight { decay, ..default() };
    let spot = |inner: f32, outer: f32| PhongSpotLight {
        inner_angle: inner,
        outer_angle: outer,
        ..default()
    };
    let aimed = above.looking_at(position, Vec3::X);
    let lights = |random: &mut Random| random_light(random, position, normal, 3.0);

    let mut add = |stresses: &'static str,
                   geometry: (Vec3, Vec3, Vec3),
                   material: PhongMaterial,
                   light: AnyLight| {
        cases.push(Case::new(
            Regime::Degenerate,
            stresses,
            geometry,
            &material,
            &light,
        ));
    };
    for model in [SpecularModel::Phong, SpecularModel::BlinnPhong] {
        for shininess in [0.0, 1.0, 50.0, 1000.0, 10_000.0] {
            let material = PhongMaterial {
                shininess,
                specular_model: model,
                ..default()
            };
            let m = || material.clone();
            add(
                "zero normal",
                (position, Vec3::ZERO, camera),
                m(),
                lights(random),
            );
            add(
                "NaN normal",
                (position, Vec3::NAN, camera),
                m(),
                lights(random),
            );
            add(
                "denormal normal",
                (position, Vec3::splat(1e-40), camera),
                m(),
                lights(random),
            );
            add(
                "camera at P",
                (position, normal, position),
                m(),
                lights(random),
            );
            add(
                "light at P",
                (position, normal, camera),
                m(),
                AnyLight::Point(point(Decay::NONE), Transform::from_translation(position)),
            );
            add(
                "spot light at P",
                (position, normal, camera),
                m(),
                AnyLight::Spot(spot(0.2, 0.4), Transform::from_translation(position)),
            );
            add(
                "decay (0, 0, 0)",
                (position, normal, camera),
                m(),
                AnyLight::Point(point(Decay::new(0.0, 0.0, 0.0)), above),
            );
            add(
                "decay (0, 0, 1) near the light",
                (position, normal, camera),
                m(),
                AnyLight::Point(
                    point(Decay::new(0.0, 0.0, 1.0)),
                    Transform::from_translation(position + Vec3::Y * 0.01),
                ),
            );
            add(
                "spot inner > outer",
                (position, normal, camera),
                m(),
                AnyLight::Spot(spot(0.5, 0.2), aimed),
            );
            add(
                "spot angle 0",
                (position, normal, camera),
                m(),
                AnyLight::Spot(spot(0.0, 0.0), aimed),
            );
            add(
                "spot angle π/2",
                (position, normal, camera),
                m(),
                AnyLight::Spot(spot(0.3, std::f32::consts::FRAC_PI_2), aimed),
            );
            add(
                "spot angle > π/2",
                (position, normal, camera),
                m(),
                AnyLight::Spot(spot(1.0, 2.5), above.looking_to(Vec3::Y, Vec3::X)),
            );
            add(
                "zero direction (zero scale)",
                (position, normal, camera),
                m(),
                AnyLight::Directional(
                    PhongDirectionalLight::default(),
                    Transform::from_scale(Vec3::ZERO),
                ),
            );
            add(
                "spot zero direction",
                (position, normal, camera),
                m(),
                AnyLight::Spot(spot(0.2, 0.4), above.with_scale(Vec3::ZERO)),
            );
            add(
                "denormal color",
                (position, normal, camera),
                m(),
                AnyLight::Point(
                    PhongPointLight {
                        color: Color::linear_rgb(1e-40, 1e-39, 1e-45),
                        ..default()
                    },
                    above,
                ),
            );
            add(
                "huge color",
                (position, normal, camera),
                m(),
                AnyLight::Point(
                    PhongPointLight {
                        color: Color::linear_rgb(1e30, 1e29, 1.0),
                        ..default()
                    },
                    above,
                ),
            );
            add(
                "highlight peak",
                (position, normal, position + Vec3::new(-0.5, 3.0, -0.2)),
                m(),
                AnyLight::Point(point(Decay::NONE), above),
            );
            add(
                "coordinates 1e7, light at P",
                (Vec3::splat(1e7), normal, Vec3::splat(1e7) + Vec3::Y),
                m(),
                AnyLight::Point(
                    point(Decay::NONE),
                    Transform::from_translation(Vec3::splat(1e7)),
                ),
            );
        }
    }
    cases
}

/// The whole corpus: `random_count` random cases split across the regimes, and every
/// degenerate case.
pub fn corpus(seed: u64, random_count: usize) -> Vec<Case> {
    let mut random = Random::new(seed);
    let mut cases = typical(&mut random, random_count * 6 / 10);
    cases.extend(grazing(&mut random, random_count * 2 / 10));
    cases.extend(far(&mut random, random_count * 2 / 10));
    cases.extend(degenerate(&mut random));
    cases
}
