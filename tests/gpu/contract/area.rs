//! The area lights' closed forms in WGSL (`bevy_phong::shaders::area_integrals`), run on the
//! render device on random rectangular lights and surface points, against the reference
//! model's quadrature over the light's area (`reference::area_light_contribution`).

use super::corpus::Random;
use super::kernel::{AreaCase, ContractKernel};
use bevy::prelude::*;
use bevy_phong::{
    PhongMaterial, SpecularModel,
    reference::{self, AreaLight, AreaShape, SurfacePoint, area_light_contribution},
};
use glam::DVec3;

const SEED: u64 = 0xA12E_A11E;
/// Random cases: each takes a quadrature of the reference model (tens of milliseconds in the
/// tests' unoptimized build), run on both device limits.
const CASES: usize = 100;

/// One random case: a rectangle anywhere within 3 units of the origin, turned any way, 0.1
/// to 4 units a side; a surface point in front of it whose horizon cuts the light in about a
/// fifth of the cases; a camera on the surface's side; a Phong exponent, an integer in half
/// the cases.
fn random_case(random: &mut Random) -> (AreaLight, SurfacePoint, f64) {
    let rotation = Quat::from_axis_angle(random.direction(), random.range(0.0, 6.3));
    let light = AreaLight {
        position: random.vector(3.0).as_dvec3(),
        right: (rotation * Vec3::X).as_dvec3(),
        up: (rotation * Vec3::Y).as_dvec3(),
        shape: AreaShape::Rect {
            width: f64::from(random.log_range(0.1, 4.0)),
            height: f64::from(random.log_range(0.1, 4.0)),
        },
        two_sided: false,
        color: DVec3::ONE,
        specular: DVec3::ONE,
        decay: [1.0, 0.0, 0.0],
        range: None,
    };
    let facing = light.facing();
    let mut position = light.position + random.vector(3.0).as_dvec3();
    let height = facing.dot(position - light.position);
    // In front of the light, at least a hundredth of a unit from its plane.
    position += facing * (height.abs().max(0.01) - height);
    let toward_light = (light.position - position).normalize();
    let mut normal = random.direction().as_dvec3();
    if normal.dot(toward_light) < 0.0 && random.chance(0.8) {
        normal = -normal;
    }
    let mut camera = random.direction().as_dvec3();
    if camera.dot(normal) < 0.0 {
        camera = -camera;
    }
    let shininess = if random.chance(0.5) {
        f64::from(random.range(1.0, 64.0).round())
    } else {
        f64::from(random.log_range(1.0, 100.0))
    };
    let surface = SurfacePoint {
        position,
        normal,
        camera: position + 3.0 * camera,
    };
    (light, surface, shininess)
}

/// The case as the kernel reads it.
fn gpu_case(light: &AreaLight, surface: &SurfacePoint, shininess: f64) -> AreaCase {
    let AreaShape::Rect { width, height } = light.shape else {
        unreachable!("the kernel takes rectangles")
    };
    let (x, y) = (0.5 * width, 0.5 * height);
    let corner = |x: f64, y: f64| {
        let point = light.point(x, y).as_vec3();
        [point.x, point.y, point.z, 0.0]
    };
    AreaCase {
        position: surface.position.as_vec3().to_array(),
        shininess: shininess as f32,
        normal: surface.normal.as_vec3().to_array(),
        specular_model: 0,
        camera: surface.camera.as_vec3().to_array(),
        padding: 0.0,
        corners: [corner(-x, -y), corner(x, -y), corner(x, y), corner(-x, y)],
    }
}

/// The reference's `∫ max(N·ω, 0) dω` and the Phong highlight's `∫ H dω` over the light, in
/// one quadrature: its term for a white material with a white highlight under a light whose
/// diffuse color per unit area is red 1 and specular color green 1.
fn reference_integrals(light: &AreaLight, surface: &SurfacePoint, shininess: f64) -> (f64, f64) {
    let area = light.shape.area();
    let material = reference::Material {
        diffuse: DVec3::ONE,
        specular: DVec3::ONE,
        specular_strength: 1.0,
        shininess,
        specular_model: SpecularModel::Phong,
        ..reference::Material::from(&PhongMaterial::default())
    };
    let light = AreaLight {
        color: DVec3::new(area, 0.0, 0.0),
        specular: DVec3::new(0.0, area, 0.0),
        ..*light
    };
    let term = area_light_contribution(surface, &material, &light);
    (term.x, term.y)
}

#[test]
fn area_light_closed_forms_match_the_quadrature() {
    let mut random = Random::new(SEED);
    let cases: Vec<_> = (0..CASES).map(|_| random_case(&mut random)).collect();
    let gpu: Vec<AreaCase> = cases
        .iter()
        .map(|(light, surface, shininess)| gpu_case(light, surface, *shininess))
        .collect();
    let results = ContractKernel::area().run(&gpu);
    let (mut diffuse_error, mut integer_error, mut fraction_error) = (0.0f64, 0.0f64, 0.0f64);
    for ((light, surface, shininess), result) in cases.iter().zip(&results) {
        let (diffuse, highlight) = reference_integrals(light, surface, *shininess);
        // Against the whole lobe's integral, 2π/(α + 1): the largest the highlight can be.
        let lobe = std::f64::consts::TAU / (shininess + 1.0);
        let highlight_error = (f64::from(result[1]) - highlight).abs() / lobe;
        diffuse_error = diffuse_error.max((f64::from(result[0]) - diffuse).abs());
        if shininess.fract() == 0.0 {
            integer_error = integer_error.max(highlight_error);
        } else {
            fraction_error = fraction_error.max(highlight_error);
        }
    }
    println!(
        "{CASES} rectangles: diffuse off by {diffuse_error:.2e}; the highlight by \
         {integer_error:.2e} (integer exponents) and {fraction_error:.2e} (others) of the \
         whole lobe"
    );
    // f32 rounding of the corners' normalization, the arcs' atan2 and the recurrence's
    // steps: measured 2.1e-6 and 1.2e-6. Between integers, the geometric interpolation's own
    // error (docs/design/area-lights.md): measured 9.5e-5.
    assert!(diffuse_error < 1e-5, "diffuse: {diffuse_error}");
    assert!(integer_error < 1e-5, "integer exponents: {integer_error}");
    assert!(fraction_error < 1e-3, "other exponents: {fraction_error}");
}
