//! Worked cases of the model's terms: each formula against values computed by hand.

use super::*;
use crate::{lights::ConeEdge, material::SpecularModel};
use glam::DVec3;

const EPSILON: f64 = 1e-12;

fn close(actual: f64, expected: f64) -> bool {
    (actual - expected).abs() <= EPSILON * expected.abs().max(1.0)
}

pub(super) fn matte(diffuse: DVec3) -> Material {
    Material {
        toon_ramp: None,
        diffuse,
        ambient_factor: 1.0,
        specular: DVec3::ONE,
        specular_strength: 0.0,
        shininess: 1.0,
        specular_model: SpecularModel::Phong,
        emissive: DVec3::ZERO,
        diffuse_mode: crate::DiffuseMode::Lambert,
        specular_mode: crate::SpecularMode::Smooth,
        rim: crate::reference::Rim::NONE,
        metallic_roughness: None,
        ambient_specular: None,
    }
}

#[test]
fn visibility_scales_the_diffuse_term_and_the_highlight_by_their_shadow_fractions() {
    let surface = SurfacePoint {
        position: DVec3::ZERO,
        normal: DVec3::Y,
        camera: DVec3::new(-1.0, 1.0, 0.0),
    };
    let material = Material {
        specular_strength: 1.0,
        shininess: 8.0,
        emissive: DVec3::splat(0.01),
        ..matte(DVec3::splat(0.5))
    };
    let lights = Lights {
        hemisphere: None,
        ambient: DVec3::splat(0.1),
        lights: vec![Light::Directional {
            direction: DVec3::new(-1.0, -1.0, 0.0),
            color: DVec3::ONE,
            specular: DVec3::ONE,
        }],
        others: Default::default(),
    };
    let diffuse_only = Material {
        specular_strength: 0.0,
        ..material.clone()
    };
    let base = material.emissive + lights.ambient * 0.5;
    let diffuse = shade(&surface, &diffuse_only, &lights) - base;
    let specular = shade(&surface, &material, &lights) - base - diffuse;
    let shaded = |visibility, diffuse_in_shadow, specular_in_shadow| {
        let shadowing = Shadowing {
            visibility,
            diffuse_in_shadow,
            specular_in_shadow,
        };
        shade_shadowed(&surface, &material, &lights, &[shadowing])
    };
    assert!((shaded(1.0, 0.0, 0.0) - shade(&surface, &material, &lights)).length() < EPSILON);
    assert!(
        (shaded(0.0, 0.0, 0.0) - base).length() < EPSILON,
        "blocked: ambient only"
    );
    let seed_003 = base + 0.1 * diffuse + specular;
    assert!((shaded(0.0, 0.1, 1.0) - seed_003).length() < EPSILON);
    let half = base + 0.5 * (diffuse + specular);
    assert!((shaded(0.5, 0.0, 0.0) - half).length() < EPSILON);
}

#[test]
fn reflection_is_two_n_dot_l_n_minus_l_as_seed_002_derives() {
    // N = +Y, L at 45° in the XY plane: R mirrors L's x component.
    let normal = DVec3::Y;
    let to_light = DVec3::new(1.0, 1.0, 0.0).normalize();
    let reflected = reflect(-to_light, normal);
    let by_hand = DVec3::new(-1.0, 1.0, 0.0) / 2f64.sqrt();
    assert!((reflected - by_hand).length() < EPSILON);
    assert!((reflected - (2.0 * normal.dot(to_light) * normal - to_light)).length() < EPSILON);
}

#[test]
fn phong_highlight_is_one_when_looking_down_the_reflection() {
    let to_light = DVec3::new(1.0, 1.0, 0.0).normalize();
    let view = DVec3::new(-1.0, 1.0, 0.0).normalize();
    let h = highlight(SpecularModel::Phong, DVec3::Y, to_light, view, 50.0);
    assert!(close(h, 1.0));
    // And Blinn-Phong agrees there: H = N.
    let h = highlight(SpecularModel::BlinnPhong, DVec3::Y, to_light, view, 50.0);
    assert!(close(h, 1.0));
}

#[test]
fn seed_000_demo_highlight_is_two_times_cos_to_the_fiftieth() {
    // specular = 2.0 * pow(eyeCos, 50.0), eyeCos = cos(10°) between R and V.
    let to_light = DVec3::Y;
    let angle = 10f64.to_radians();
    let view = DVec3::new(angle.sin(), angle.cos(), 0.0);
    let surface = SurfacePoint {
        position: DVec3::ZERO,
        normal: DVec3::Y,
        camera: view * 5.0,
    };
    let material = Material {
        diffuse: DVec3::ZERO,
        specular_strength: 2.0,
        shininess: 50.0,
        ..matte(DVec3::ZERO)
    };
    let color = phong_light(&surface, &material, to_light, DVec3::ZERO, DVec3::ONE);
    let by_hand = 2.0 * 0.984_807_753_012_208_f64.powf(50.0); // = 0.9323…
    assert!(close(color.x, by_hand), "{color} vs {by_hand}");
}

#[test]
fn normalized_blinn_phong_is_three_js_brdf_worked_by_hand() {
    // L and V 60° either side of N: H = N, N·H = 1, N·L = V·H = c = 1/2. Schlick's
    // weight w = 2^((−5.55473·c − 6.98316)·c) = 2^(−4.8802625) = 0.0339543;
    // F = f₀ + (1 − f₀)·w with f₀ = k_s = 0.2: 0.2271634; the term
    // F · (α + 2)/(8π) · (N·H)^α · N·L = 0.2271634 · 8/(8π) · 1 · 0.5 = 0.0361542 (α = 6).
    let angle = 60f64.to_radians();
    let to_light = DVec3::new(angle.sin(), angle.cos(), 0.0);
    let view = DVec3::new(-angle.sin(), angle.cos(), 0.0);
    let surface = SurfacePoint {
        position: DVec3::ZERO,
        normal: DVec3::Y,
        camera: view * 4.0,
    };
    let material = Material {
        specular: DVec3::splat(0.2),
        specular_strength: 1.0,
        shininess: 6.0,
        specular_model: SpecularModel::NormalizedBlinnPhong,
        ..matte(DVec3::ZERO)
    };
    let color = phong_light(&surface, &material, to_light, DVec3::ZERO, DVec3::ONE);
    let by_hand = 0.036_154_182_566_8;
    assert!(close(color.x, by_hand), "{color} vs {by_hand}");
    // A black specular color keeps the grazing part alone: w · 1/π · 0.5 = 0.0054040.
    let black = Material {
        specular: DVec3::ZERO,
        ..material
    };
    let color = phong_light(&surface, &black, to_light, DVec3::ZERO, DVec3::ONE);
    let by_hand = 0.033_954_285_871_0 / std::f64::consts::PI * 0.5;
    assert!(close(color.x, by_hand), "{color} vs {by_hand}");
}

#[test]
fn seed_004_attenuation_constants_give_one_over_five_point_one_at_ten_units() {
    // 1 / (1.0 + 0.09·10 + 0.032·100) = 1 / 5.1
    assert!(close(
        attenuation(10.0, [1.0, 0.09, 0.032], None),
        1.0 / 5.1
    ));
    assert!(close(attenuation(0.0, [1.0, 0.09, 0.032], None), 1.0));
}

#[test]
fn seed_000_caps_attenuation_at_one_near_the_light() {
    // decay x·d² + y·d + z with (x, y, z) = (1, 0, 0): 1/d² would be 4 at d = 0.5.
    assert!(close(attenuation(0.5, [0.0, 0.0, 1.0], None), 1.0));
    assert!(close(attenuation(2.0, [0.0, 0.0, 1.0], None), 0.25));
    // A zero decay is no fall-off rather than a division by zero.
    assert!(close(attenuation(3.0, [0.0, 0.0, 0.0], None), 1.0));
}

#[test]
fn attenuation_is_zero_past_the_range_as_seed_001_cuts_it() {
    assert!(close(attenuation(4.99, [1.0, 0.0, 0.0], Some(5.0)), 1.0));
    assert_eq!(attenuation(5.01, [1.0, 0.0, 0.0], Some(5.0)), 0.0);
}

#[test]
fn seed_004_soft_cone_is_full_inside_12_5_degrees_and_dark_past_17_5() {
    let (inner, outer) = (12.5f64.to_radians().cos(), 17.5f64.to_radians().cos());
    assert!(close(
        cone_factor(
            10f64.to_radians().cos(),
            inner,
            outer,
            0.0,
            ConeEdge::Linear
        ),
        1.0
    ));
    assert_eq!(
        cone_factor(
            18f64.to_radians().cos(),
            inner,
            outer,
            0.0,
            ConeEdge::Linear
        ),
        0.0
    );
    // At 15°: (cos 15° - cos 17.5°) / (cos 12.5° - cos 17.5°), worked by hand
    // (0.965925826 - 0.953716951) / (0.976296007 - 0.953716951) = 0.540717…
    let by_hand = (0.965_925_826_289_068 - 0.953_716_950_748_227)
        / (0.976_296_007_119_933_4 - 0.953_716_950_748_227);
    assert!(close(
        cone_factor(
            15f64.to_radians().cos(),
            inner,
            outer,
            0.0,
            ConeEdge::Linear
        ),
        by_hand
    ));
}

/// three.js's `smoothstep(cos outer, cos inner, cos θ)`: at 15° between 12.5° and 17.5°,
/// `t = 0.540717…` (above) gives `t² (3 − 2t) = 0.560940…`, worked by hand.
#[test]
fn a_smooth_cone_edge_is_the_smoothstep_of_the_linear_one() {
    let (inner, outer) = (12.5f64.to_radians().cos(), 17.5f64.to_radians().cos());
    let smooth = cone_factor(
        15f64.to_radians().cos(),
        inner,
        outer,
        0.0,
        ConeEdge::Smooth,
    );
    assert!((smooth - 0.560_940_2).abs() < 1e-6, "{smooth}");
    assert_eq!(
        cone_factor(
            10f64.to_radians().cos(),
            inner,
            outer,
            0.0,
            ConeEdge::Smooth
        ),
        1.0
    );
    assert_eq!(
        cone_factor(
            18f64.to_radians().cos(),
            inner,
            outer,
            0.0,
            ConeEdge::Smooth
        ),
        0.0
    );
}

#[test]
fn seed_000_hard_cone_is_a_step_at_the_angle() {
    let edge = 20f64.to_radians().cos();
    assert_eq!(
        cone_factor(19f64.to_radians().cos(), edge, edge, 0.0, ConeEdge::Linear),
        1.0
    );
    assert_eq!(
        cone_factor(21f64.to_radians().cos(), edge, edge, 0.0, ConeEdge::Linear),
        0.0
    );
}

#[test]
fn seed_001_spot_exponent_darkens_by_cos_theta_to_the_exponent() {
    let cos_theta = 5f64.to_radians().cos();
    let cone = cone_factor(
        cos_theta,
        1.0_f64.cos(),
        1.2_f64.cos(),
        8.0,
        ConeEdge::Linear,
    );
    assert!(close(cone, cos_theta.powi(8)));
}

#[test]
fn unlit_side_gets_neither_diffuse_nor_highlight() {
    let surface = SurfacePoint {
        position: DVec3::ZERO,
        normal: DVec3::Y,
        camera: DVec3::new(0.0, -1.0, 1.0),
    };
    let material = Material {
        specular_strength: 1.0,
        shininess: 0.0,
        ..matte(DVec3::ONE)
    };
    let color = phong_light(&surface, &material, -DVec3::Y, DVec3::ONE, DVec3::ONE);
    assert_eq!(color, DVec3::ZERO);
}

#[test]
fn shade_adds_emissive_ambient_and_lights() {
    let surface = SurfacePoint {
        position: DVec3::ZERO,
        normal: DVec3::Y * 3.0,
        camera: DVec3::new(0.0, 4.0, 0.0),
    };
    let material = Material {
        emissive: DVec3::new(0.1, 0.0, 0.0),
        ambient_factor: 0.5,
        ..matte(DVec3::new(0.5, 0.25, 1.0))
    };
    let lights = Lights {
        hemisphere: None,
        ambient: DVec3::splat(0.2),
        lights: vec![Light::Directional {
            direction: DVec3::new(0.0, -1.0, -1.0),
            color: DVec3::ONE,
            specular: DVec3::ONE,
        }],
        others: Default::default(),
    };
    let n_dot_l = 1.0 / 2f64.sqrt();
    let by_hand = DVec3::new(0.1, 0.0, 0.0)
        + DVec3::splat(0.2 * 0.5) * material.diffuse
        + material.diffuse * n_dot_l;
    assert!((shade(&surface, &material, &lights) - by_hand).length() < EPSILON);
}

#[test]
fn degenerate_inputs_give_finite_colors() {
    let material = Material {
        specular_strength: 1.0,
        shininess: 0.0,
        ..matte(DVec3::ONE)
    };
    let light_at_origin = Light::Point {
        position: DVec3::ZERO,
        color: DVec3::ONE,
        specular: DVec3::ONE,
        decay: [0.0; 3],
        range: None,
    };
    let lights = Lights {
        hemisphere: None,
        ambient: DVec3::ONE,
        lights: vec![light_at_origin],
        others: Default::default(),
    };
    for normal in [DVec3::ZERO, DVec3::NAN, DVec3::Y] {
        let surface = SurfacePoint {
            position: DVec3::ZERO,
            normal,
            camera: DVec3::ZERO,
        };
        assert!(shade(&surface, &material, &lights).is_finite());
    }
}

/// The model takes a material's numbers into their ranges before using them, as its uniform
/// does; the values here are worked from the ranges `limits` documents (colors and factors
/// `[0, 1e6]` with NaN → 0, shininess `[0, 1e6]` with NaN → 0), not from the crate's walk.
#[test]
fn a_material_out_of_its_ranges_enters_the_model_at_its_documented_values() {
    use bevy::color::Color;
    let cases = [
        // (base color, specular strength, ambient factor, shininess) → (k_d, strength, k_a, α)
        (
            Color::linear_rgb(2e6, f32::NAN, -1.0),
            f32::NAN,
            -2.0,
            -5.0,
            (DVec3::new(1e6, 0.0, 0.0), 0.0, 0.0, 0.0),
        ),
        (
            Color::linear_rgb(0.25, 1e6, f32::INFINITY),
            f32::INFINITY,
            3.0,
            f32::NAN,
            (DVec3::new(0.25, 1e6, 1e6), 1e6, 3.0, 0.0),
        ),
        (
            Color::linear_rgb(0.5, 0.5, 0.5),
            2.0,
            f32::NEG_INFINITY,
            f32::INFINITY,
            (DVec3::splat(0.5), 2.0, 0.0, 1e6),
        ),
    ];
    for (base_color, strength, ambient, shininess, expected) in cases {
        let material = Material::from(&crate::PhongMaterial {
            base_color,
            specular_strength: strength,
            ambient_factor: ambient,
            shininess,
            ..Default::default()
        });
        assert_eq!(
            (
                material.diffuse,
                material.specular_strength,
                material.ambient_factor,
                material.shininess
            ),
            expected,
            "{base_color:?}, strength {strength}, ambient {ambient}, shininess {shininess}"
        );
    }
}

/// SPEC.md's lit-side rim is weighted by `max(N·L, 0)`: on the far side of a wrapped
/// diffuse term, which lights there, it adds nothing.
#[test]
fn a_lit_side_rim_adds_nothing_on_the_far_side() {
    let surface = SurfacePoint {
        position: DVec3::ZERO,
        normal: DVec3::Y,
        camera: DVec3::new(0.0, 1.0, 3.0),
    };
    let wrapped = Material {
        diffuse_mode: crate::DiffuseMode::Wrap(0.5),
        ..matte(DVec3::splat(0.5))
    };
    let with_rim = Material {
        rim: crate::reference::Rim {
            color: DVec3::ONE,
            power: 1.0,
            lit_side: true,
        },
        ..wrapped.clone()
    };
    // N·L = −0.2: the wrapped diffuse term lights the point, the rim does not.
    let to_light = DVec3::new(0.0, -0.2, (1.0f64 - 0.04).sqrt());
    let light =
        |material: &Material| phong_light(&surface, material, to_light, DVec3::ONE, DVec3::ONE);
    assert!(
        light(&wrapped).max_element() > 0.0,
        "the wrap lights the far side"
    );
    assert_eq!(light(&with_rim), light(&wrapped));
}

/// The fall-off cuts a light off past its range, not at it: at exactly `range` the light
/// still arrives (SPEC.md: `A = 0` for `d > range`).
#[test]
fn a_light_reaches_a_point_at_exactly_its_range() {
    assert_eq!(attenuation(2.0, [1.0, 0.0, 0.0], Some(2.0)), 1.0);
    assert_eq!(attenuation(2.0, [1.0, 0.0, 0.0], Some(1.999_999)), 0.0);
}

/// A hard-edged spot (inner ≥ outer) is `step(cos_outer, cos θ)`: lit at exactly its outer
/// angle, dark just past it.
#[test]
fn a_hard_edged_spot_lights_its_outer_angle_itself() {
    for edge in [ConeEdge::Linear, ConeEdge::Smooth] {
        assert_eq!(cone_factor(0.5, 0.5, 0.5, 0.0, edge), 1.0);
        assert_eq!(cone_factor(0.499_999, 0.5, 0.5, 0.0, edge), 0.0);
    }
}

/// With ε culling, the `n` point and spot lights share ε: each is cut where it falls below
/// `ε / n`. For `1/d²` fall-off and intensity 1 that is `d = √(n / ε)`, here √200 for two
/// lights and ε = 1/100 (worked by hand, not by `influence_radius`), to `f32` rounding.
#[test]
fn culled_lights_share_epsilon_among_them() {
    let point = |x: f64| Light::Point {
        position: DVec3::new(x, 0.0, 0.0),
        color: DVec3::ONE,
        specular: DVec3::ONE,
        decay: [0.0, 0.0, 1.0],
        range: None,
    };
    let lights = Lights {
        lights: vec![point(0.0), point(5.0)],
        ..Default::default()
    };
    for light in lights.culled(0.01).lights {
        let Light::Point { range, .. } = light else {
            unreachable!()
        };
        let range = range.expect("a range from ε");
        assert!(
            (range - 200f64.sqrt()).abs() < 1e-5,
            "range {range}, expected √200 = {}",
            200f64.sqrt()
        );
    }
}
