//! Properties the reference model holds for all valid input (non-negative colors,
//! decays and material scalars).

use super::*;
use crate::{lights::ConeEdge, material::SpecularModel};
use glam::DQuat;
use glam::DVec3;
use proptest::prelude::*;

fn unit_vector() -> impl Strategy<Value = DVec3> {
    (-1.0..1.0f64, 0.0..std::f64::consts::TAU).prop_map(|(z, angle)| {
        let r = (1.0 - z * z).sqrt();
        DVec3::new(r * angle.cos(), r * angle.sin(), z)
    })
}

fn point() -> impl Strategy<Value = DVec3> {
    (-20.0..20.0f64, -20.0..20.0f64, -20.0..20.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn color() -> impl Strategy<Value = DVec3> {
    (0.0..2.0f64, 0.0..2.0f64, 0.0..2.0f64).prop_map(|(r, g, b)| DVec3::new(r, g, b))
}

fn decay() -> impl Strategy<Value = [f64; 3]> {
    (0.0..2.0f64, 0.0..1.0f64, 0.0..1.0f64).prop_map(|(c, l, q)| [c, l, q])
}

fn model() -> impl Strategy<Value = SpecularModel> {
    prop_oneof![
        Just(SpecularModel::Phong),
        Just(SpecularModel::BlinnPhong),
        Just(SpecularModel::NormalizedBlinnPhong)
    ]
}

fn material() -> impl Strategy<Value = Material> {
    (
        color(),
        color(),
        0.0..3.0f64,
        0.0..1000.0f64,
        model(),
        color(),
    )
        .prop_map(
            |(diffuse, specular, specular_strength, shininess, specular_model, emissive)| {
                Material {
                    toon_ramp: None,
                    diffuse,
                    ambient_factor: 1.0,
                    specular,
                    specular_strength,
                    shininess,
                    specular_model,
                    emissive,
                    diffuse_mode: crate::DiffuseMode::Lambert,
                    specular_mode: crate::SpecularMode::Smooth,
                    rim: crate::reference::Rim::NONE,
                    metallic_roughness: None,
                    ambient_specular: None,
                }
            },
        )
}

fn light() -> impl Strategy<Value = Light> {
    prop_oneof![
        (unit_vector(), color(), color()).prop_map(|(direction, color, specular)| {
            Light::Directional {
                direction,
                color,
                specular,
            }
        }),
        (
            point(),
            color(),
            color(),
            decay(),
            proptest::option::of(0.1..30.0f64)
        )
            .prop_map(|(position, color, specular, decay, range)| Light::Point {
                position,
                color,
                specular,
                decay,
                range,
            }),
        (
            point(),
            unit_vector(),
            color(),
            decay(),
            0.0..1.2f64,
            0.0..0.5f64,
            0.0..8.0f64
        )
            .prop_map(
                |(position, direction, color, decay, inner, width, exponent)| {
                    Light::Spot {
                        position,
                        direction,
                        color,
                        specular: color,
                        decay,
                        range: None,
                        inner_angle: inner,
                        outer_angle: inner + width,
                        exponent,
                        edge: ConeEdge::Linear,
                    }
                }
            ),
    ]
}

fn rotate(mut light: Light, rotation: DQuat) -> Light {
    match &mut light {
        Light::Directional { direction, .. } => *direction = rotation * *direction,
        Light::Point { position, .. } => *position = rotation * *position,
        Light::Spot {
            position,
            direction,
            ..
        } => {
            *position = rotation * *position;
            *direction = rotation * *direction;
        }
    }
    light
}

proptest! {
    #[test]
    fn output_is_never_negative(
        position in point(), normal in unit_vector(), camera in point(),
        material in material(), light in light(), ambient in color(),
    ) {
        let surface = SurfacePoint { position, normal, camera };
        let lights = Lights { ambient, hemisphere: None, lights: vec![light], others: Default::default() };
        let color = shade(&surface, &material, &lights);
        prop_assert!(color.min_element() >= 0.0, "{color}");
    }

    #[test]
    fn attenuation_never_increases_with_distance(
        decay in decay(), near in 0.0..100.0f64, further in 0.0..100.0f64,
        range in proptest::option::of(0.0..100.0f64),
    ) {
        let far = near + further;
        prop_assert!(attenuation(far, decay, range) <= attenuation(near, decay, range));
    }

    #[test]
    fn rotating_the_whole_scene_does_not_change_the_result(
        position in point(), normal in unit_vector(), camera in point(),
        material in material(), light in light(),
        axis in unit_vector(), angle in 0.0..std::f64::consts::TAU,
    ) {
        let rotation = DQuat::from_axis_angle(axis, angle);
        let surface = SurfacePoint { position, normal, camera };
        let rotated = SurfacePoint {
            position: rotation * position,
            normal: rotation * normal,
            camera: rotation * camera,
        };
        let before = light_contribution(&surface, &material, &light);
        let after = light_contribution(&rotated, &material, &rotate(light, rotation));
        // Rotation rounds each coordinate (~1e-15 relative); the highlight multiplies
        // that by at most α = 1000, the cone edge by 1 / (cos inner - cos outer).
        let tolerance = 1e-7 * before.max_element().max(1.0);
        prop_assert!((before - after).abs().max_element() <= tolerance, "{before} vs {after}");
    }

    #[test]
    fn phong_equals_blinn_phong_where_they_coincide(
        normal in unit_vector(), tilt in unit_vector(), distance in 0.5..20.0f64,
        material in material(), color in color(), zero_shininess in any::<bool>(),
    ) {
        // Looking down the mirror direction, R = V and H = N: both highlights peak at 1;
        // with α = 0 both are 1 everywhere on the lit side.
        let to_light = (normal + tilt * 0.9).normalize_or_zero();
        prop_assume!(normal.dot(to_light) > 1e-3);
        let view = reflect(-to_light, normal);
        let surface = SurfacePoint { position: DVec3::ZERO, normal, camera: view * distance };
        let material = Material {
            shininess: if zero_shininess { 0.0 } else { material.shininess },
            ..material
        };
        let light = Light::Directional { direction: -to_light, color, specular: color };
        let phong = light_contribution(&surface, &Material { specular_model: SpecularModel::Phong, ..material.clone() }, &light);
        let blinn = light_contribution(&surface, &Material { specular_model: SpecularModel::BlinnPhong, ..material }, &light);
        prop_assert!((phong - blinn).abs().max_element() <= 1e-9 * phong.max_element().max(1.0));
    }
}
