//! Shadows against an independent computation: for each pixel, the reference casts a ray in
//! `f64` from the pixel's read-back world position toward each light, against the scene's
//! analytic shapes (a sphere, a box, a square plane), and takes `V = 0` where a shape is hit
//! first, else `V = 1`; the expected color is `reference::shade_shadowed` with those `V`.
//!
//! Shadow maps only estimate `V`: near the true shadow's edge the two may disagree. A pixel
//! whose color differs from the expected one by more than the render tests' budget
//! ([`TOLERANCE`], see `frames.rs`) must lie within the band of the edge: the exact `V` of
//! some light changes within the band's half-width `b` of `P`, bounded from the light's
//! settings (`shadow_band.rs`). Outside the band every pixel is within [`TOLERANCE`].

use crate::{
    clusters::spawn_second_camera,
    frames::TOLERANCE,
    shadow_band::{MapCover, ViewerCamera, band_width, texel_bound},
};
use bevy::{
    light::{NotShadowCaster, NotShadowReceiver},
    mesh::UvChannel,
    prelude::*,
};
use bevy_phong::{
    prelude::*,
    reference::{self, Shadowing, SurfacePoint},
    testing::PhongShadowViews,
};
use bevy_phong_headless::{CAMERA_POSITION, FloatImage, Harness, HarnessCamera, SurfaceInputs};
use glam::{DMat3, DVec3};

/// Render size.
pub(crate) const SIZE: u32 = 128;
/// Rays start this far along their direction from `P`, world units: past the rounding of
/// the read-back position (a few 1e-7 at these coordinates) so that a surface does not
/// block its own light where it faces it.
const RAY_START: f64 = 1e-4;
/// Directions around `P` at which the band is probed, at two radii (`b` and `b / 2`).
const BAND_PROBES: usize = 24;
/// How much the exact rays must darken a pixel for its shadow to count as shown: ten of the
/// frame tests' budget, a difference no rounding makes.
const SHADOW_SHOWS: f64 = 10.0 * TOLERANCE;

/// An analytic shape of the scene, matching a mesh that is spawned for it.
#[derive(Clone, Debug)]
pub(crate) enum Shape {
    /// A sphere.
    Sphere { center: DVec3, radius: f64 },
    /// A box: centre, half-extents, rotation about +Y (radians).
    Box {
        center: DVec3,
        half: DVec3,
        yaw: f64,
    },
    /// The square `|x|, |z| ≤ half` in the plane `y = 0`.
    Floor { half: f64 },
    /// The square `|x − cx|, |z − cz| ≤ half` in the plane `y = cy`, a checkerboard of
    /// `cells × cells` squares of which only those with an even `column + row` are there
    /// (an alpha mask; `cells` odd, so that the board reads the same mirrored).
    Checkerboard {
        center: DVec3,
        half: f64,
        cells: u32,
    },
    /// Triangles, world space (a posed skinned or morphed mesh).
    Triangles(Vec<[DVec3; 3]>),
}

impl Shape {
    /// The smallest `t > RAY_START` with `origin + t·direction` on the shape, for a unit
    /// `direction`.
    fn hit(&self, origin: DVec3, direction: DVec3) -> Option<f64> {
        match *self {
            Shape::Triangles(ref triangles) => triangles
                .iter()
                .filter_map(|triangle| triangle_hit(triangle, origin, direction))
                .reduce(f64::min),
            Shape::Sphere { center, radius } => {
                let offset = origin - center;
                let b = offset.dot(direction);
                let c = offset.length_squared() - radius * radius;
                let discriminant = b * b - c;
                if discriminant < 0.0 {
                    return None;
                }
                let root = discriminant.sqrt();
                [-b - root, -b + root].into_iter().find(|t| *t > RAY_START)
            }
            Shape::Box { center, half, yaw } => {
                let to_local = DMat3::from_rotation_y(-yaw);
                let o = to_local * (origin - center);
                let d = to_local * direction;
                let (mut near, mut far) = (f64::NEG_INFINITY, f64::INFINITY);
                for axis in 0..3 {
                    if d[axis].abs() < 1e-300 {
                        if o[axis].abs() > half[axis] {
                            return None;
                        }
                        continue;
                    }
                    let a = (-half[axis] - o[axis]) / d[axis];
                    let b = (half[axis] - o[axis]) / d[axis];
                    near = near.max(a.min(b));
                    far = far.min(a.max(b));
                }
                if near > far {
                    return None;
                }
                [near, far].into_iter().find(|t| *t > RAY_START)
            }
            Shape::Floor { half } => {
                if direction.y.abs() < 1e-300 {
                    return None;
                }
                let t = -origin.y / direction.y;
                let point = origin + t * direction;
                (t > RAY_START && point.x.abs() <= half && point.z.abs() <= half).then_some(t)
            }
            Shape::Checkerboard {
                center,
                half,
                cells,
            } => {
                if direction.y.abs() < 1e-300 {
                    return None;
                }
                let t = (center.y - origin.y) / direction.y;
                let local = origin + t * direction - center;
                if !(t > RAY_START && local.x.abs() <= half && local.z.abs() <= half) {
                    return None;
                }
                let cell = |c: f64| ((c + half) / (2.0 * half) * f64::from(cells)).floor() as i64;
                ((cell(local.x) + cell(local.z)) % 2 == 0).then_some(t)
            }
        }
    }
}

/// The `t > RAY_START` at which `origin + t·direction` crosses `triangle`, either side
/// (Möller and Trumbore's test, in `f64`).
fn triangle_hit(triangle: &[DVec3; 3], origin: DVec3, direction: DVec3) -> Option<f64> {
    let [a, b, c] = *triangle;
    let (ab, ac) = (b - a, c - a);
    let p = direction.cross(ac);
    let determinant = ab.dot(p);
    if determinant.abs() < 1e-300 {
        return None;
    }
    let to_origin = origin - a;
    let u = to_origin.dot(p) / determinant;
    let q = to_origin.cross(ab);
    let v = direction.dot(q) / determinant;
    let t = ac.dot(q) / determinant;
    ((0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && t > RAY_START).then_some(t)
}

/// Where a light is, for the rays toward it.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Toward {
    /// Along `-direction`, unbounded.
    Direction(DVec3),
    /// To a point.
    Point(DVec3),
}

/// The exact `V` of a light at `position`: 0 if a caster is on the way. The caster the point
/// lies on is left out by the caller: the shapes are convex, so a ray leaving a surface
/// toward a light it faces never meets that surface again (the mesh's flat facets lie a
/// little inside the analytic sphere, and would otherwise block their own light), and where
/// the surface faces away from the light the light gives nothing whatever `V` is.
pub(crate) fn exact_visibility(position: DVec3, toward: Toward, casters: &[Shape]) -> f64 {
    let (direction, distance) = match toward {
        Toward::Direction(direction) => (-direction.normalize(), f64::INFINITY),
        Toward::Point(light) => ((light - position).normalize(), light.distance(position)),
    };
    let blocked = casters
        .iter()
        .any(|shape| shape.hit(position, direction).is_some_and(|t| t < distance));
    if blocked { 0.0 } else { 1.0 }
}

/// Whether the exact `V` of the light changes within `radius` of `position` on the surface
/// with `normal`.
fn near_edge(
    position: DVec3,
    normal: DVec3,
    radius: f64,
    toward: Toward,
    casters: &[Shape],
) -> bool {
    let here = exact_visibility(position, toward, casters);
    let normal = normal.normalize();
    let u = normal.any_orthonormal_vector();
    let v = normal.cross(u);
    (0..BAND_PROBES).any(|probe| {
        let angle = probe as f64 / BAND_PROBES as f64 * std::f64::consts::TAU;
        [radius, 0.5 * radius].into_iter().any(|r| {
            let point = position + r * (angle.cos() * u + angle.sin() * v);
            exact_visibility(point, toward, casters) != here
        })
    })
}

/// A light of a case, with what the reference needs of it.
pub(crate) struct CaseLight {
    pub toward: Toward,
    pub settings: PhongShadows,
    /// What its maps cover, for the band's texel bound.
    pub cover: MapCover,
    /// A light of a kind added from outside the crate (`PhongLightKindPlugin`): the
    /// reference's [`reference::Lights::others`], in the order these case lights come.
    pub of_other_kind: bool,
}

impl CaseLight {
    /// The bound of a shadow-map texel's world size at `position` (`shadow_band.rs`), seen
    /// by `viewer`.
    fn texel_bound_at(&self, position: DVec3, viewer: &ViewerCamera) -> f64 {
        let light = match self.toward {
            Toward::Point(light) => light,
            // Unused for cascades and beams, whose maps do not widen with the distance.
            Toward::Direction(_) => DVec3::ZERO,
        };
        texel_bound(
            &self.cover,
            self.settings.resolution,
            light,
            position,
            viewer,
        )
    }
}

/// The result of one case.
pub(crate) struct Verdict {
    /// Pixels on a mesh.
    covered: usize,
    /// Of those, the ones within the band of a light that reaches them.
    in_band: usize,
    /// Of those outside the band, the ones the exact rays darken by more than
    /// [`SHADOW_SHOWS`]: where a shadow that went missing would show.
    decided: usize,
    /// Pixels whose color differs from the exact-visibility reference beyond the budget.
    disagreeing: usize,
    /// Of those, the ones outside the band (must be 0).
    outside_band: usize,
    /// The widest band used, world units.
    widest_band: f64,
    /// Largest error of the pixels outside the band: of those that disagree (must be within
    /// the budget, so none) and of those that agree.
    max_error_outside: f64,
}

impl Verdict {
    pub fn assert_holds(&self, case: &str) {
        println!(
            "{case}: {} covered pixels, {} within the band, {} in shadow outside it, {} \
             disagree with the exact visibility, all within the band (widest {:.4} world \
             units) but {}; largest error outside the band {:.3e} (budget {TOLERANCE:.0e})",
            self.covered,
            self.in_band,
            self.decided,
            self.disagreeing,
            self.widest_band,
            self.outside_band,
            self.max_error_outside
        );
        assert!(self.covered > 0, "{case}: nothing rendered");
        // Every pixel that disagrees lies within the band, whose width is bounded from the
        // lights' settings: their count is bounded by the pixels within it.
        assert!(
            self.disagreeing <= self.in_band,
            "{case}: {} pixels disagree, more than the {} within the band",
            self.disagreeing,
            self.in_band
        );
        assert_eq!(
            self.outside_band, 0,
            "{case}: {} pixels disagree with the exact visibility outside the band",
            self.outside_band
        );
        assert!(self.max_error_outside <= TOLERANCE, "{case}");
    }

    /// [`Self::assert_holds`], and the shadows decide at least `share` of the covered pixels
    /// outside the band: a case whose shadows went missing cannot pass.
    pub fn assert_holds_with_shadows_on(&self, case: &str, share: f64) {
        self.assert_holds(case);
        assert!(
            self.decided as f64 >= share * self.covered as f64,
            "{case}: the shadows darken only {} of {} covered pixels",
            self.decided,
            self.covered
        );
    }
}

/// The scene's shapes, with the entity and material of each one's mesh (a `PhongMaterial`
/// or one made of it).
pub(crate) struct Scene<M: Material = PhongMaterial> {
    pub shapes: Vec<(Entity, Shape, Handle<M>)>,
}

impl Scene {
    fn spawn(harness: &mut Harness) -> Self {
        Self::spawn_with(harness, |material| material)
    }
}

impl<M: PhongSceneMaterial> Scene<M> {
    /// The floor, the sphere and the box, each drawn with `made_of` its `PhongMaterial`.
    pub fn spawn_with(harness: &mut Harness, made_of: impl Fn(PhongMaterial) -> M) -> Self {
        let world = harness.world_mut();
        let shapes = [
            Shape::Floor { half: 4.0 },
            Shape::Sphere {
                center: DVec3::new(-0.4, 0.9, 0.2),
                radius: 0.6,
            },
            Shape::Box {
                center: DVec3::new(1.3, 0.4, 0.4),
                half: DVec3::new(0.4, 0.4, 0.5),
                yaw: 0.5,
            },
        ];
        let materials = [
            PhongMaterial {
                base_color: Color::srgb(0.7, 0.7, 0.7),
                specular_strength: 0.5,
                shininess: 8.0,
                ..default()
            },
            PhongMaterial {
                base_color: Color::srgb(0.8, 0.2, 0.2),
                specular_strength: 1.0,
                shininess: 40.0,
                ..default()
            },
            PhongMaterial {
                base_color: Color::srgb(0.2, 0.3, 0.9),
                specular_strength: 0.5,
                shininess: 20.0,
                ..default()
            },
        ];
        let shapes = shapes
            .into_iter()
            .zip(materials)
            .map(|(shape, material)| {
                let (mesh, transform): (Mesh, Transform) = match shape {
                    Shape::Floor { half } => (
                        Plane3d::default()
                            .mesh()
                            .size(2.0 * half as f32, 2.0 * half as f32)
                            .into(),
                        Transform::IDENTITY,
                    ),
                    Shape::Sphere { center, radius } => (
                        Sphere::new(radius as f32).mesh().ico(5).unwrap(),
                        Transform::from_translation(center.as_vec3()),
                    ),
                    Shape::Box { center, half, yaw } => (
                        Cuboid::from_size(2.0 * half.as_vec3()).into(),
                        Transform::from_translation(center.as_vec3())
                            .with_rotation(Quat::from_rotation_y(yaw as f32)),
                    ),
                    Shape::Triangles(_) | Shape::Checkerboard { .. } => {
                        unreachable!("the scene has no posed mesh, no board")
                    }
                };
                let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
                let material = world.resource_mut::<Assets<M>>().add(made_of(material));
                let entity = world
                    .spawn((Mesh3d(mesh), MeshMaterial3d(material.clone()), transform))
                    .id();
                (entity, shape, material)
            })
            .collect();
        Self { shapes }
    }

    pub fn floor(&self) -> Entity {
        self.shapes[0].0
    }

    pub fn sphere(&self) -> Entity {
        self.shapes[1].0
    }

    pub fn cube(&self) -> Entity {
        self.shapes[2].0
    }

    /// Moves a shape's mesh and its analytic twin by `offset`.
    pub fn translate(&mut self, harness: &mut Harness, entity: Entity, offset: DVec3) {
        let (_, shape, _) = self
            .shapes
            .iter_mut()
            .find(|(e, ..)| *e == entity)
            .expect("a shape of the scene");
        match shape {
            Shape::Sphere { center, .. } | Shape::Box { center, .. } => *center += offset,
            Shape::Floor { .. } | Shape::Checkerboard { .. } | Shape::Triangles(_) => {
                panic!("the floor, the board and posed meshes stay")
            }
        }
        harness
            .world_mut()
            .get_mut::<Transform>(entity)
            .unwrap()
            .translation += offset.as_vec3();
    }
}

/// A harness seeing the scene, with a little ambient light.
pub(crate) fn harness() -> (Harness, Scene) {
    let mut harness = Harness::new(SIZE, SIZE);
    harness.world_mut().insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.05, 0.05, 0.05),
    });
    let scene = Scene::spawn(&mut harness);
    (harness, scene)
}

/// Spawns `light` and returns what the reference needs of it.
fn spawn_light(
    harness: &mut Harness,
    light: impl Bundle,
    toward: Toward,
    settings: PhongShadows,
    cover: MapCover,
) -> CaseLight {
    harness.world_mut().spawn(light);
    CaseLight {
        toward,
        settings,
        cover,
        of_other_kind: false,
    }
}

pub(crate) fn directional(
    harness: &mut Harness,
    direction: Vec3,
    shadows: PhongShadows,
    cascades: PhongCascades,
) -> CaseLight {
    spawn_light(
        harness,
        (
            PhongDirectionalLight {
                color: Color::linear_rgb(0.9, 0.9, 0.9),
                shadows,
                cascades,
                ..default()
            },
            Transform::default().looking_to(direction, Vec3::Z),
        ),
        Toward::Direction(direction.as_dvec3()),
        shadows,
        MapCover::Cascades(cascades),
    )
}

pub(crate) fn spot(
    harness: &mut Harness,
    position: Vec3,
    target: Vec3,
    shadows: PhongShadows,
) -> CaseLight {
    let outer_angle = 40f32.to_radians();
    spawn_light(
        harness,
        (
            PhongSpotLight {
                color: Color::linear_rgb(0.9, 0.8, 0.7),
                outer_angle,
                inner_angle: 30f32.to_radians(),
                shadows,
                ..default()
            },
            Transform::from_translation(position).looking_at(target, Vec3::Y),
        ),
        Toward::Point(position.as_dvec3()),
        shadows,
        MapCover::spot(target - position, outer_angle),
    )
}

pub(crate) fn point(harness: &mut Harness, position: Vec3, shadows: PhongShadows) -> CaseLight {
    spawn_light(
        harness,
        (
            PhongPointLight {
                color: Color::linear_rgb(0.6, 0.7, 0.9),
                shadows,
                ..default()
            },
            Transform::from_translation(position),
        ),
        Toward::Point(position.as_dvec3()),
        shadows,
        MapCover::Cube,
    )
}

/// Who casts and who receives.
pub(crate) struct Roles<'a> {
    pub casting: &'a dyn Fn(Entity) -> bool,
    pub receiving: &'a dyn Fn(Entity) -> bool,
}

pub(crate) const EVERYONE: Roles = Roles {
    casting: &|_| true,
    receiving: &|_| true,
};

/// Renders the settled frame and judges every pixel.
pub(crate) fn judge<M: PhongSceneMaterial>(
    harness: &mut Harness,
    scene: &Scene<M>,
    lights: &[CaseLight],
    roles: &Roles,
    inputs: &SurfaceInputs<M>,
) -> Verdict {
    harness.settle();
    let rendered = harness.render_next_frame();
    judge_frame(harness, scene, lights, roles, inputs, &rendered)
}

/// Each of the scene's reference lights with the case light it came from: a built-in one
/// matched by where its rays come from, the others (`reference::Lights::others`) in order.
fn match_case_lights<'a>(
    reference_lights: &reference::Lights,
    lights: &'a [CaseLight],
) -> (Vec<&'a CaseLight>, Vec<&'a CaseLight>) {
    let built_in = reference_lights
        .lights
        .iter()
        .map(|light| {
            lights
                .iter()
                .filter(|case| !case.of_other_kind)
                .find(|case| match (case.toward, light) {
                    (Toward::Direction(d), reference::Light::Directional { direction, .. }) => {
                        d.normalize().distance(direction.normalize()) < 1e-5
                    }
                    (Toward::Point(p), reference::Light::Point { position, .. })
                    | (Toward::Point(p), reference::Light::Spot { position, .. }) => {
                        p.distance(*position) < 1e-5
                    }
                    _ => false,
                })
                .expect("every light of the scene is a case light")
        })
        .collect();
    let others: Vec<&CaseLight> = lights.iter().filter(|case| case.of_other_kind).collect();
    assert_eq!(
        others.len(),
        reference_lights.others.0.len(),
        "every light of another kind is a case light"
    );
    (built_in, others)
}

/// The reference color of `surface` with each light's exact `V`: the built-in lights
/// (`lights`, without `others`) through `reference::shade_shadowed`, each light of another
/// kind's term scaled by `f + (1 − f)·V` (its `ReferenceLight` gives one term, so its case
/// must leave the same fraction `f` of the diffuse and the specular light in shadow).
fn shade_exactly(
    surface: &SurfacePoint,
    material: &reference::Material,
    (lights, others): (&reference::Lights, &reference::OtherLights),
    (built_in_shadowing, others_shadowing): (&[Shadowing], &[Shadowing]),
) -> DVec3 {
    let shaded = reference::shade_shadowed(surface, material, lights, built_in_shadowing);
    others
        .0
        .iter()
        .zip(others_shadowing)
        .fold(shaded, |sum, (light, shadowing)| {
            assert_eq!(
                shadowing.diffuse_in_shadow, shadowing.specular_in_shadow,
                "a light of another kind leaves one fraction of its term in shadow"
            );
            sum + light.term(surface, material) * shadowing.factors().0
        })
}

/// The largest channel of `|actual − expected|`, relative to `max(1, |expected|)`.
fn relative_error(actual: &[f32], expected: DVec3) -> f64 {
    (0..3)
        .map(|c| (f64::from(actual[c]) - expected[c]).abs() / expected[c].abs().max(1.0))
        .fold(0.0, f64::max)
}

/// Judges every pixel of `rendered`, lit from `inputs`.
pub(crate) fn judge_frame<M: PhongSceneMaterial>(
    harness: &mut Harness,
    scene: &Scene<M>,
    lights: &[CaseLight],
    roles: &Roles,
    inputs: &SurfaceInputs<M>,
    rendered: &FloatImage,
) -> Verdict {
    let casters_except = |receiver: Entity| -> Vec<Shape> {
        scene
            .shapes
            .iter()
            .filter(|(entity, ..)| (roles.casting)(*entity) && *entity != receiver)
            .map(|(_, shape, _)| shape.clone())
            .collect()
    };
    let viewer = ViewerCamera::of(harness);
    let reference_lights = harness.reference_lights();
    let (built_in, others) = match_case_lights(&reference_lights, lights);
    let built_in_lights = reference::Lights {
        others: Default::default(),
        ..reference_lights.clone()
    };
    let camera = harness.camera_position();
    let materials = harness.world_mut().resource::<Assets<M>>();
    let mut verdict = Verdict {
        covered: 0,
        in_band: 0,
        decided: 0,
        disagreeing: 0,
        outside_band: 0,
        widest_band: 0.0,
        max_error_outside: 0.0,
    };
    for (index, color) in rendered.pixels.iter().enumerate() {
        let Some((handle, surface)) = inputs.surface_at(index, camera) else {
            continue;
        };
        let (entity, ..) = scene
            .shapes
            .iter()
            .find(|(.., material)| material == handle)
            .expect("a shape's material");
        let phong_material = materials
            .get(handle)
            .and_then(M::phong_material)
            .expect("a material made of a PhongMaterial");
        // The captured inputs do not discard: where a masked surface's holes are, they hold
        // the surface, the frame what is behind it.
        if matches!(phong_material.alpha_mode, AlphaMode::Mask(_)) {
            continue;
        }
        let material = reference::Material::from(phong_material);
        let receives = (roles.receiving)(*entity);
        let casters = casters_except(*entity);
        let shadowing = |cases: &[&CaseLight]| -> Vec<Shadowing> {
            cases
                .iter()
                .map(|case| Shadowing {
                    visibility: if receives {
                        exact_visibility(surface.position, case.toward, &casters)
                    } else {
                        1.0
                    },
                    diffuse_in_shadow: f64::from(case.settings.diffuse_in_shadow),
                    specular_in_shadow: f64::from(case.settings.specular_in_shadow),
                })
                .collect()
        };
        let expected = shade_exactly(
            &surface,
            &material,
            (&built_in_lights, &reference_lights.others),
            (&shadowing(&built_in), &shadowing(&others)),
        );
        let unshadowed = reference::shade(&surface, &material, &reference_lights);
        let error = relative_error(color, expected);
        verdict.covered += 1;
        // Within the band of a light that reaches the pixel: one facing away gives nothing
        // whatever its `V`.
        let in_band = receives
            && lights.iter().any(|case| {
                let to_light = match case.toward {
                    Toward::Direction(direction) => -direction.normalize(),
                    Toward::Point(light) => (light - surface.position).normalize(),
                };
                let cosine = surface.normal.normalize().dot(to_light);
                if cosine <= 0.0 {
                    return false;
                }
                let texel = case.texel_bound_at(surface.position, &viewer);
                let band = band_width(&case.settings, texel, cosine);
                verdict.widest_band = verdict.widest_band.max(band);
                near_edge(
                    surface.position,
                    surface.normal,
                    band,
                    case.toward,
                    &casters,
                )
            });
        verdict.in_band += usize::from(in_band);
        // The shadow decides this pixel: outside the band, exact rays darken it visibly.
        verdict.decided +=
            usize::from(!in_band && (expected - unshadowed).abs().max_element() > SHADOW_SHOWS);
        if error <= TOLERANCE {
            verdict.max_error_outside = verdict.max_error_outside.max(error);
            continue;
        }
        verdict.disagreeing += 1;
        if !in_band {
            verdict.outside_band += 1;
            verdict.max_error_outside = verdict.max_error_outside.max(error);
            if verdict.outside_band <= 5 {
                println!(
                    "outside the band: pixel ({}, {}) at {:?}, rendered {:?}, expected {:?}",
                    index as u32 % rendered.width,
                    index as u32 / rendered.width,
                    surface.position,
                    &color[..3],
                    expected
                );
            }
        }
    }
    verdict
}

/// Shadows of one light, on.
pub(crate) fn on() -> PhongShadows {
    PhongShadows {
        resolution: 512,
        ..PhongShadows::ON
    }
}

/// One cascade reaching past the whole scene.
pub(crate) fn one_cascade() -> PhongCascades {
    PhongCascades {
        count: 1,
        max_distance: 20.0,
        ..default()
    }
}

/// Spawns a case's lights.
pub(crate) type SpawnLights = dyn Fn(&mut Harness) -> Vec<CaseLight>;

pub(crate) const SUN: Vec3 = Vec3::new(-0.5, -1.0, -0.35);

/// Shadows with a share of the light left in them (`diffuse_in_shadow`, `specular_in_shadow`):
/// each light its own pair, so that a pair swapped, or one light's pair read for another's,
/// changes the shadowed pixels by at least a tenth of the blocked light.
fn dimmed(diffuse_in_shadow: f32, specular_in_shadow: f32) -> PhongShadows {
    PhongShadows {
        diffuse_in_shadow,
        specular_in_shadow,
        ..on()
    }
}

#[test]
fn each_light_kind_alone_and_all_together_shadow_where_the_exact_rays_are_blocked() {
    let cases: [(&str, &SpawnLights); 5] = [
        ("directional", &|h| {
            vec![directional(h, SUN, on(), one_cascade())]
        }),
        ("spot", &|h| {
            vec![spot(
                h,
                Vec3::new(1.5, 4.0, 2.0),
                Vec3::new(0.0, 0.0, 0.0),
                on(),
            )]
        }),
        ("point", &|h| {
            vec![point(h, Vec3::new(-1.5, 2.8, 1.8), on())]
        }),
        ("all together", &|h| {
            vec![
                directional(h, SUN, on(), one_cascade()),
                spot(h, Vec3::new(1.5, 4.0, 2.0), Vec3::ZERO, on()),
                point(h, Vec3::new(-1.5, 2.8, 1.8), on()),
            ]
        }),
        ("all together, light left in the shadows", &|h| {
            vec![
                directional(h, SUN, dimmed(0.3, 0.8), one_cascade()),
                spot(h, Vec3::new(1.5, 4.0, 2.0), Vec3::ZERO, dimmed(0.6, 0.1)),
                point(h, Vec3::new(-1.5, 2.8, 1.8), dimmed(0.0, 0.5)),
            ]
        }),
    ];
    for (case, lights) in cases {
        let (mut harness, scene) = harness();
        let lights = lights(&mut harness);
        harness.settle();
        let inputs = harness.capture_inputs();
        judge(&mut harness, &scene, &lights, &EVERYONE, &inputs).assert_holds(case);
    }
}

#[test]
fn a_shadow_casting_light_just_outside_the_frustum_is_clustered_and_shadows_exactly() {
    // The harness camera looks at the origin from CAMERA_POSITION with Bevy's default
    // perspective (vertical field of view 45°, square target): a point light 0.8 above the
    // view's top edge at the origin's depth, reaching 7 units into it.
    let forward = (-CAMERA_POSITION).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let half_width = std::f32::consts::FRAC_PI_8.tan() * CAMERA_POSITION.length();
    let position = up * (half_width + 0.8);
    let (mut harness, scene) = harness();
    let light = spawn_light(
        &mut harness,
        (
            PhongPointLight {
                color: Color::linear_rgb(0.9, 0.8, 0.7),
                range: Some(7.0),
                shadows: on(),
                ..default()
            },
            Transform::from_translation(position),
        ),
        Toward::Point(position.as_dvec3()),
        on(),
        MapCover::Cube,
    );
    harness.settle();
    assert_eq!(
        crate::clusters::clustered_light_count(&mut harness),
        1,
        "the shadow-casting light is in the clusters, not in every fragment's loop"
    );
    let inputs = harness.capture_inputs();
    judge(&mut harness, &scene, &[light], &EVERYONE, &inputs)
        .assert_holds("a shadow-casting light outside the frustum");
}

#[test]
fn a_directional_light_holds_across_its_cascade_splits() {
    let (mut harness, scene) = harness();
    // Splits at 4.6, 6.3 and 8.6 units from the camera: the floor crosses all three.
    let cascades = PhongCascades {
        count: 4,
        first_far_bound: 4.6,
        max_distance: 12.0,
        overlap: 0.2,
    };
    let lights = vec![directional(&mut harness, SUN, on(), cascades)];
    harness.settle();
    let inputs = harness.capture_inputs();
    judge(&mut harness, &scene, &lights, &EVERYONE, &inputs).assert_holds("cascades");
}

#[test]
fn split_screen_cameras_each_get_cascades_fitted_to_their_own_view() {
    let (mut harness, scene) = harness();
    // Two cascades ending 12 units from their camera: those fitted to a camera looking
    // elsewhere do not cover what the harness camera sees.
    let cascades = PhongCascades {
        count: 2,
        first_far_bound: 5.0,
        max_distance: 12.0,
        overlap: 0.2,
    };
    let lights = vec![directional(&mut harness, SUN, on(), cascades)];
    // A camera drawn first (lower order), looking away from the scene at nothing.
    let away = Vec3::new(0.0, 2.5, 40.0);
    let second = spawn_second_camera(&mut harness, Vec3::new(0.0, 2.5, 7.0), away);
    harness.world_mut().get_mut::<Camera>(second).unwrap().order = -1;
    harness.settle();
    let inputs = harness.capture_inputs();
    judge(&mut harness, &scene, &lights, &EVERYONE, &inputs)
        .assert_holds("beside a camera seeing nothing");
    assert_eq!(
        camera_sets(&mut harness),
        1,
        "a camera that sees no Phong-lit mesh gets no cascades"
    );

    // Now it sees a Phong mesh of its own (casting no shadow on the scene, out of the
    // harness camera's view): it gets cascades fitted to its view, which the harness
    // camera's fragments must not read.
    let world = harness.world_mut();
    let mesh = world.resource_mut::<Assets<Mesh>>().add(Cuboid::default());
    let material = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(PhongMaterial::default());
    world.spawn((
        Mesh3d(mesh),
        MeshMaterial3d(material),
        Transform::from_translation(away - Vec3::Y * 2.0),
        NotShadowCaster,
    ));
    harness.settle();
    judge(&mut harness, &scene, &lights, &EVERYONE, &inputs)
        .assert_holds("beside a camera looking away");
    assert_eq!(
        camera_sets(&mut harness),
        2,
        "one set of cascades per camera"
    );

    // Split screen: both cameras see the scene, from two sides; then they trade places.
    let pose =
        |position: Vec3| Transform::from_translation(position).looking_at(Vec3::ZERO, Vec3::Y);
    let (first_pose, second_pose) = (pose(CAMERA_POSITION), pose(Vec3::new(5.5, 3.0, -5.0)));
    for (case, harness_pose, other_pose) in [
        (
            "split screen, the harness camera in front",
            first_pose,
            second_pose,
        ),
        (
            "split screen, the harness camera behind",
            second_pose,
            first_pose,
        ),
    ] {
        let world = harness.world_mut();
        *world.get_mut::<Transform>(second).unwrap() = other_pose;
        let mut camera = world.query_filtered::<&mut Transform, With<HarnessCamera>>();
        *camera.single_mut(world).unwrap() = harness_pose;
        harness.settle();
        let inputs = harness.capture_inputs();
        judge(&mut harness, &scene, &lights, &EVERYONE, &inputs).assert_holds(case);
        assert_eq!(
            camera_sets(&mut harness),
            2,
            "{case}: one set of cascades per camera"
        );
    }
}

/// How many sets of views the first shadow-casting light has: one per camera for a
/// directional light.
fn camera_sets(harness: &mut Harness) -> u32 {
    harness.world_mut().resource::<PhongShadowViews>().views()[0].camera_count
}

#[test]
fn not_shadow_caster_and_not_shadow_receiver_work_on_phong_meshes() {
    let (mut harness, scene) = harness();
    let lights = vec![spot(
        &mut harness,
        Vec3::new(1.5, 4.0, 2.0),
        Vec3::ZERO,
        on(),
    )];
    let (sphere, cube) = (scene.sphere(), scene.cube());
    harness
        .world_mut()
        .entity_mut(sphere)
        .insert(NotShadowCaster);
    harness
        .world_mut()
        .entity_mut(cube)
        .insert(NotShadowReceiver);
    harness.settle();
    let inputs = harness.capture_inputs();
    let roles = Roles {
        casting: &|entity| entity != sphere,
        receiving: &|entity| entity != cube,
    };
    judge(&mut harness, &scene, &lights, &roles, &inputs).assert_holds("markers");
}

/// A caster whose material has a displacement map casts the displaced shape: the scene's
/// sphere, grown by the map's left texel (red 1, scale 0.4, bias −0.2: 0.6 becomes 0.8), is
/// judged against the exact rays to a sphere of that radius, under a directional light
/// (cascade maps) and a point light (cube maps). Every vertex reads the left texel at the
/// map's UV set, first the first set, then the second (`displacement_map_channel`); the
/// other set reads the right texel (red 0), which would shrink the sphere to 0.4, farther
/// than the widest band (0.34). The sphere (`ico(5)`, 10,242 vertices)
/// lies within 10⁻⁴ of its vertices' sphere, far inside the band.
#[test]
fn a_displaced_caster_casts_the_shadow_of_its_displaced_shape() {
    for channel in [UvChannel::Uv0, UvChannel::Uv1] {
        let (mut harness, mut scene) = harness();
        let sphere_entity = scene.sphere();
        let world = harness.world_mut();
        let mut map = Image::new(
            bevy::render::render_resource::Extent3d {
                width: 2,
                height: 1,
                depth_or_array_layers: 1,
            },
            bevy::render::render_resource::TextureDimension::D2,
            vec![255, 0, 0, 255, 0, 0, 0, 255],
            bevy::render::render_resource::TextureFormat::Rgba8Unorm,
            bevy::asset::RenderAssetUsages::default(),
        );
        map.sampler = bevy::image::ImageSampler::nearest();
        let map = world.resource_mut::<Assets<Image>>().add(map);
        let mesh = world
            .get::<Mesh3d>(sphere_entity)
            .expect("the sphere's mesh")
            .0
            .clone();
        let (left, right) = ([0.25f32, 0.5], [0.75f32, 0.5]);
        let (first, second) = match channel {
            UvChannel::Uv0 => (left, right),
            UvChannel::Uv1 => (right, left),
        };
        if let Some(mut sphere_mesh) = world.resource_mut::<Assets<Mesh>>().get_mut(&mesh) {
            let vertices = sphere_mesh.count_vertices();
            sphere_mesh.insert_attribute(Mesh::ATTRIBUTE_UV_0, vec![first; vertices]);
            sphere_mesh.insert_attribute(Mesh::ATTRIBUTE_UV_1, vec![second; vertices]);
        }
        let (scale, bias) = (0.4, -0.2);
        let (_, shape, material) = &mut scene.shapes[1];
        let Shape::Sphere { radius, .. } = shape else {
            panic!("the scene's second shape is its sphere");
        };
        *radius += scale + bias;
        if let Some(mut sphere) = world
            .resource_mut::<Assets<PhongMaterial>>()
            .get_mut(&*material)
        {
            sphere.displacement_map = Some(map);
            sphere.displacement_map_channel = channel.clone();
            sphere.displacement_scale = scale as f32;
            sphere.displacement_bias = bias as f32;
        }
        let lights = vec![
            directional(&mut harness, SUN, on(), one_cascade()),
            point(&mut harness, Vec3::new(-1.5, 2.8, 1.8), on()),
        ];
        harness.settle();
        let inputs = harness.capture_inputs();
        judge(&mut harness, &scene, &lights, &EVERYONE, &inputs)
            .assert_holds(&format!("displaced sphere, map at {channel:?}"));
    }
}

/// A square whose base color map's alpha is a checkerboard, masked at 1/2, casts the board's
/// squares and lets the light through its holes, from each kind of light: the crate's
/// caster discards where the main pass does. The maps are fine (2048 texels) so that the
/// band around each square's shadow (printed; about a tenth of a unit) leaves most of each
/// square's shadow and each hole's light (0.6 units across) judged. In the last case the
/// board is read at the mesh's second UV set, the first set holding one UV at the middle
/// square (opaque): a caster reading the first set casts the whole square.
#[test]
fn an_alpha_masked_caster_lets_the_light_through_its_holes() {
    let board = Shape::Checkerboard {
        center: DVec3::new(0.6, 1.8, -0.2),
        half: 0.9,
        cells: 3,
    };
    fn fine() -> PhongShadows {
        PhongShadows {
            resolution: 2048,
            ..on()
        }
    }
    let cases: [(&str, UvChannel, &SpawnLights); 4] = [
        ("masked board, directional", UvChannel::Uv0, &|h| {
            vec![directional(h, SUN, fine(), one_cascade())]
        }),
        ("masked board, spot", UvChannel::Uv0, &|h| {
            vec![spot(
                h,
                Vec3::new(1.2, 4.5, 0.8),
                Vec3::new(0.4, 0.0, -0.4),
                fine(),
            )]
        }),
        ("masked board, point", UvChannel::Uv0, &|h| {
            vec![point(h, Vec3::new(0.9, 3.6, 0.6), fine())]
        }),
        (
            "masked board on the second UV set, spot",
            UvChannel::Uv1,
            &|h| {
                vec![spot(
                    h,
                    Vec3::new(1.2, 4.5, 0.8),
                    Vec3::new(0.4, 0.0, -0.4),
                    fine(),
                )]
            },
        ),
    ];
    for (case, channel, spawn_lights) in cases {
        let (mut harness, mut scene) = harness();
        let Shape::Checkerboard {
            center,
            half,
            cells,
        } = board
        else {
            unreachable!()
        };
        let world = harness.world_mut();
        let texels: Vec<u8> = (0..cells * cells)
            .flat_map(|index| {
                let alpha = if (index % cells + index / cells) % 2 == 0 {
                    255
                } else {
                    0
                };
                [200, 180, 60, alpha]
            })
            .collect();
        let mut image = Image::new(
            bevy::render::render_resource::Extent3d {
                width: cells,
                height: cells,
                depth_or_array_layers: 1,
            },
            bevy::render::render_resource::TextureDimension::D2,
            texels,
            bevy::render::render_resource::TextureFormat::Rgba8Unorm,
            bevy::asset::RenderAssetUsages::default(),
        );
        image.sampler = bevy::image::ImageSampler::nearest();
        let image = world.resource_mut::<Assets<Image>>().add(image);
        let material = world
            .resource_mut::<Assets<PhongMaterial>>()
            .add(PhongMaterial {
                base_color_texture: Some(image),
                base_color_channel: channel.clone(),
                alpha_mode: AlphaMode::Mask(0.5),
                double_sided: true,
                ..default()
            });
        let size = 2.0 * half as f32;
        let mut plane = Mesh::from(Plane3d::default().mesh().size(size, size));
        if channel == UvChannel::Uv1 {
            let uvs = plane
                .attribute(Mesh::ATTRIBUTE_UV_0)
                .expect("a plane has UVs")
                .clone();
            let corners = uvs.len();
            plane.insert_attribute(Mesh::ATTRIBUTE_UV_1, uvs);
            plane.insert_attribute(Mesh::ATTRIBUTE_UV_0, vec![[0.5f32, 0.5]; corners]);
        }
        let mesh = world.resource_mut::<Assets<Mesh>>().add(plane);
        let entity = world
            .spawn((
                Mesh3d(mesh),
                MeshMaterial3d(material.clone()),
                Transform::from_translation(center.as_vec3()),
            ))
            .id();
        scene.shapes.push((entity, board.clone(), material));
        let lights = spawn_lights(&mut harness);
        harness.settle();
        let inputs = harness.capture_inputs();
        judge(&mut harness, &scene, &lights, &EVERYONE, &inputs).assert_holds(case);
    }
}

#[test]
fn a_light_inside_an_object_is_blocked_everywhere_outside_it() {
    let (mut harness, scene) = harness();
    let center = Vec3::new(-0.4, 0.9, 0.2);
    let lights = vec![point(&mut harness, center, on())];
    harness.settle();
    let inputs = harness.capture_inputs();
    judge(&mut harness, &scene, &lights, &EVERYONE, &inputs).assert_holds("light inside");
}

#[test]
fn a_caster_hidden_moved_and_despawned_between_frames_leaves_no_stale_shadow() {
    let (mut harness, mut scene) = harness();
    let lights = vec![spot(
        &mut harness,
        Vec3::new(1.5, 4.0, 2.0),
        Vec3::ZERO,
        on(),
    )];
    harness.settle();
    let inputs = harness.capture_inputs();
    judge(&mut harness, &scene, &lights, &EVERYONE, &inputs).assert_holds("before");

    let cube = scene.cube();
    *harness.world_mut().get_mut::<Visibility>(cube).unwrap() = Visibility::Hidden;
    harness.settle();
    let inputs = harness.capture_inputs();
    let hidden = Roles {
        casting: &|entity| entity != cube,
        receiving: &|_| true,
    };
    judge(&mut harness, &scene, &lights, &hidden, &inputs).assert_holds("cube hidden");

    *harness.world_mut().get_mut::<Visibility>(cube).unwrap() = Visibility::Inherited;
    let sphere = scene.sphere();
    scene.translate(&mut harness, sphere, DVec3::new(0.3, 0.2, -0.2));
    harness.settle();
    let inputs = harness.capture_inputs();
    judge(&mut harness, &scene, &lights, &EVERYONE, &inputs).assert_holds("sphere moved");

    harness.world_mut().despawn(cube);
    harness.settle();
    let inputs = harness.capture_inputs();
    let despawned = Roles {
        casting: &|entity| entity != cube,
        receiving: &|_| true,
    };
    judge(&mut harness, &scene, &lights, &despawned, &inputs).assert_holds("cube despawned");
}

#[test]
fn a_plane_facing_the_light_has_no_acne_and_shadows_start_at_their_casters() {
    // Light at 30° above the floor: the grazing case for acne; the box rests on the floor,
    // so its shadow must start at its base (no gap wider than the band).
    let (mut harness, scene) = harness();
    let lights = vec![directional(
        &mut harness,
        Vec3::new(-1.0, -0.58, 0.0),
        on(),
        one_cascade(),
    )];
    harness.settle();
    let inputs = harness.capture_inputs();
    let verdict = judge(&mut harness, &scene, &lights, &EVERYONE, &inputs);
    verdict.assert_holds("grazing light");
    let _ = scene.floor();
}

#[test]
fn from_0_to_100_to_0_shadow_casting_lights_every_frame_is_right() {
    let (mut harness, scene) = harness();
    let ring = |index: usize| {
        let angle = index as f32 / 100.0 * std::f32::consts::TAU;
        Vec3::new(3.0 * angle.cos(), 4.0, 3.0 * angle.sin())
    };
    let shadows = PhongShadows {
        resolution: 128,
        ..PhongShadows::ON
    };
    let spawn_ring = |harness: &mut Harness, count: usize| -> (Vec<Entity>, Vec<CaseLight>) {
        (0..count)
            .map(|index| {
                let position = ring(index);
                let entity = harness
                    .world_mut()
                    .spawn((
                        PhongSpotLight {
                            color: Color::linear_rgb(0.012, 0.012, 0.012),
                            outer_angle: 35f32.to_radians(),
                            inner_angle: 30f32.to_radians(),
                            shadows,
                            ..default()
                        },
                        Transform::from_translation(position).looking_at(Vec3::ZERO, Vec3::Y),
                    ))
                    .id();
                let light = CaseLight {
                    toward: Toward::Point(position.as_dvec3()),
                    settings: shadows,
                    cover: MapCover::spot(-position, 35f32.to_radians()),
                    of_other_kind: false,
                };
                (entity, light)
            })
            .unzip()
    };
    // Compile the caster pipelines with one light, then start from none.
    let (warm_up, _) = spawn_ring(&mut harness, 1);
    harness.settle();
    harness.world_mut().despawn(warm_up[0]);
    harness.settle();
    let inputs = harness.capture_inputs();
    for (step, count) in [0, 100, 0, 100, 0].into_iter().enumerate() {
        let world = harness.world_mut();
        let old: Vec<Entity> = world
            .query_filtered::<Entity, With<PhongSpotLight>>()
            .iter(world)
            .collect();
        for entity in old {
            harness.world_mut().despawn(entity);
        }
        let (_, lights) = spawn_ring(&mut harness, count);
        // The very next frame, without waiting: no stale map, no missing one.
        let rendered = harness.render_next_frame();
        judge_frame(&mut harness, &scene, &lights, &EVERYONE, &inputs, &rendered)
            .assert_holds(&format!("step {step}: {count} lights"));
    }
}

/// Lighting per vertex takes each light's shadow at the vertices (SPEC.md, "Per-vertex
/// lighting"): a floor of 0.25-unit cells lit per vertex under the sphere's shadow from the
/// sun is, at each pixel, the reference's sums at its triangle's corners, each corner's sum
/// without the sun where the exact ray from it is blocked, interpolated. Triangles with a
/// corner within the band of a shadow edge (see [`judge_frame`]) are not judged: the map may
/// put such a corner either side. Many floor pixels must lie between corners all in shadow.
#[test]
fn lighting_per_vertex_takes_the_shadow_at_each_vertex() {
    let (mut harness, scene) = harness();
    let floor = scene.floor();
    let floor_material = scene.shapes[0].2.clone();
    let Shape::Floor { half } = scene.shapes[0].1 else {
        panic!("the scene's first shape is its floor");
    };
    let world = harness.world_mut();
    let cells = world.resource_mut::<Assets<Mesh>>().add(
        Plane3d::default()
            .mesh()
            .size(2.0 * half as f32, 2.0 * half as f32)
            .subdivisions(31),
    );
    world.entity_mut(floor).insert(Mesh3d(cells));
    if let Some(mut material) = world
        .resource_mut::<Assets<PhongMaterial>>()
        .get_mut(&floor_material)
    {
        material.vertex_lighting = true;
    }
    // A fine map: a band (about 0.1 units) narrower than a cell.
    let fine = PhongShadows {
        resolution: 2048,
        ..on()
    };
    let lights = [directional(&mut harness, SUN, fine, one_cascade())];
    harness.settle();
    let inputs = harness.capture_inputs();
    harness.settle();
    let rendered = harness.render_next_frame();

    let viewer = ViewerCamera::of(&mut harness);
    let casters: Vec<Shape> = scene.shapes[1..]
        .iter()
        .map(|(_, shape, _)| shape.clone())
        .collect();
    let case = &lights[0];
    let reference_lights = harness.reference_lights();
    let camera = harness.camera_position();
    let world = harness.world_mut();
    let (mesh, transform) = world
        .query::<(&Mesh3d, &GlobalTransform)>()
        .get(world, floor)
        .map(|(mesh, transform)| (mesh.0.clone(), *transform))
        .expect("the floor");
    let mesh = world
        .resource::<Assets<Mesh>>()
        .get(&mesh)
        .expect("the floor's mesh")
        .clone();
    let material = world
        .resource::<Assets<PhongMaterial>>()
        .get(&floor_material)
        .expect("the floor's material")
        .clone();
    let shadowed_corner = std::cell::Cell::new(0usize);
    let mut triangles = bevy_phong_headless::pixel_model::VertexLitTriangles::default();
    triangles.add(
        &mesh,
        &transform,
        &reference::Material::from(&material),
        camera,
        |corner| {
            let up = DVec3::Y;
            let texel = case.texel_bound_at(corner, &viewer);
            let band = band_width(&case.settings, texel, 0.0);
            if near_edge(corner, up, band, case.toward, &casters) {
                return None;
            }
            let mut lights = reference_lights.clone();
            if exact_visibility(corner, case.toward, &casters) == 0.0 {
                lights.lights.clear();
                shadowed_corner.set(shadowed_corner.get() + 1);
            }
            Some(lights)
        },
    );
    let comparison = harness.compare_pixels(&rendered, &inputs, |material, surface, _| {
        if !material.vertex_lighting {
            return None;
        }
        let light = triangles.light_at(surface.position)?;
        let model = reference::Material::from(material);
        let mut lights = reference_lights.clone();
        lights.lights.clear();
        lights.others.0.push(std::sync::Arc::new(light));
        Some(reference::shade(surface, &model, &lights))
    });
    comparison.assert_within("per-vertex floor under a shadow", TOLERANCE);
    // Judged floor pixels the shadow darkens: the sun's sums, interpolated, less than nine
    // tenths of what they are without shadows.
    let mut unshadowed = bevy_phong_headless::pixel_model::VertexLitTriangles::default();
    unshadowed.add(
        &mesh,
        &transform,
        &reference::Material::from(&material),
        camera,
        |_| Some(reference_lights.clone()),
    );
    let darkened: usize = (0..inputs.positions.pixels.len())
        .filter_map(|pixel| inputs.surface_at(pixel, camera))
        .filter_map(|(_, surface)| {
            let shadowed = triangles.light_at(surface.position)?;
            let lit = unshadowed.light_at(surface.position)?;
            Some(shadowed.diffuse.x < 0.9 * lit.diffuse.x)
        })
        .filter(|&darkened| darkened)
        .count();
    println!(
        "per-vertex floor: {} corners in shadow, {darkened} judged pixels darkened by it",
        shadowed_corner.get()
    );
    // Seen at a slant, the sphere's and the cube's shadows cover a few hundred floor
    // pixels, and the triangles with a corner in them and none in the band about 60 (59
    // measured): at least 30 says the judged pixels hold the shadow, so that a vertex stage
    // without shadows fails.
    assert!(
        darkened >= 30,
        "only {darkened} judged pixels darkened by the shadow"
    );
}
