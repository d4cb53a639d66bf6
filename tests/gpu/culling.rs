//! Light culling (`PhongLightCulling`): clusters change no pixel, and ε culling
//! renders exactly the model with each light's range shortened to its influence radius,
//! whose distance from the exact model is measured here and bounded by
//! `ε · (k_d + k_s · strength)` for all skipped lights together.

use crate::clusters::clustered_light_count;
use crate::frames::{SIZE, TOLERANCE, spawn_objects};
use bevy::prelude::*;
use bevy_phong::{prelude::*, reference};
use bevy_phong_headless::{Harness, SurfaceInputs};

/// The frame tests' objects under `count` point lights scattered over the floor, each fading
/// with `decay` and cut off at `range`.
fn scene(count: usize, decay: Decay, range: Option<f32>) -> (Harness, SurfaceInputs) {
    let mut harness = Harness::new(SIZE, SIZE);
    harness.world_mut().insert_resource(PhongAmbientLight::NONE);
    spawn_objects(&mut harness);
    let world = harness.world_mut();
    for i in 0..count {
        let t = i as f32;
        let position = Vec3::new(
            (t * 0.618_034).fract() * 12.0 - 6.0,
            -0.5 + (t * 0.381_966).fract() * 2.5,
            (t * 0.754_878).fract() * 12.0 - 6.0,
        );
        let color = Color::hsl((t * 0.569_840).fract() * 360.0, 1.0, 0.5);
        world.spawn((
            PhongPointLight {
                color: color.to_linear().with_luminance(0.1).into(),
                decay,
                range,
                ..default()
            },
            Transform::from_translation(position),
        ));
    }
    harness.settle();
    let inputs = harness.capture_inputs();
    (harness, inputs)
}

fn set_culling(harness: &mut Harness, culling: PhongLightCulling) {
    harness.world_mut().insert_resource(culling);
}

#[test]
fn clusters_change_no_pixel() {
    let (mut harness, inputs) = scene(600, Decay::new(1.0, 0.5, 0.5), Some(3.0));
    for (case, culling, clustered) in [
        ("clusters_of_600_lights", PhongLightCulling::EXACT, 600),
        ("no_clusters_600_lights", PhongLightCulling::NONE, 0),
        ("clusters_again_600_lights", PhongLightCulling::EXACT, 600),
    ] {
        set_culling(&mut harness, culling);
        let rendered = harness.render_next_frame();
        assert_eq!(clustered_light_count(&mut harness), clustered, "{case}");
        harness
            .compare(&rendered, &inputs)
            .assert_within(case, TOLERANCE);
    }
}

#[test]
fn epsilon_culling_renders_the_model_with_influence_radii() {
    // Unlimited range: only ε bounds each light's reach. With intensity ≤ 0.3, 1 / (1 + 4d²)
    // and ε / 300 per light, the influence radius is under 4.7 units at ε = 1 (the floor is
    // 12 wide), 13 at 1/8 and 38 at 1/64.
    let (mut harness, inputs) = scene(300, Decay::new(1.0, 0.0, 4.0), None);
    let exact_lights = harness.reference_lights();
    let materials = harness.world_mut().resource::<Assets<PhongMaterial>>();
    // The largest k_d + k_s · strength of the scene's materials, per channel.
    let response = materials
        .iter()
        .map(|(_, material)| {
            let material = reference::Material::from(material);
            (material.diffuse + material.specular * material.specular_strength).max_element()
        })
        .fold(0.0, f64::max);
    for epsilon in [1.0, 1.0 / 8.0, 1.0 / 64.0] {
        set_culling(
            &mut harness,
            PhongLightCulling {
                epsilon,
                clusters: true,
            },
        );
        let rendered = harness.render_next_frame();
        let case = format!("epsilon_{epsilon}");
        // What the shader is meant to compute: the model with shortened ranges.
        let culled_lights = exact_lights.culled(epsilon);
        let culled = harness.compare_with(&rendered, &inputs, |material, surface| {
            let material = reference::Material::from(material);
            Some(reference::shade(surface, &material, &culled_lights))
        });
        culled.assert_within(&format!("{case}_against_culled_model"), TOLERANCE);
        // Its distance from the exact model: all skipped lights together leave out less than
        // ε per unit of the material's response.
        let exact = harness.compare(&rendered, &inputs);
        let bound = f64::from(epsilon) * response + TOLERANCE;
        exact.assert_within(&format!("{case}_against_exact_model"), bound);
        assert!(
            clustered_light_count(&mut harness) > 0,
            "{case}: lights of finite reach are clustered"
        );
    }
}
