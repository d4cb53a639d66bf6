//! Percentage-closer soft shadows (SPEC.md, "Shadows"): with `softness > 0` the penumbra
//! widens with the light's size and the distance between blocker and receiver,
//! `w = r · (d_P − d_B) / d_B` for a light of radius `r` at distance `d_B` from the blocker
//! and `d_P` from the shaded point. The verdict of `shadows.rs` bounds every soft edge by the
//! widest filter; these tests follow the penumbra itself: it widens with the softness and
//! with the blocker's distance from the receiver, and it has the formula's width.

use crate::shadows::{
    CaseLight, EVERYONE, Roles, SUN, Scene, Shape, directional, harness, judge_frame, on,
    one_cascade, point, spot,
};
use bevy::prelude::*;
use bevy_phong::{
    prelude::*,
    reference::{self, Shadowing},
};
use bevy_phong_headless::{FloatImage, Harness, SurfaceInputs};
use glam::DVec3;

/// The scene's inputs and its frame, each once nothing compiles any more.
fn settled_frame(harness: &mut Harness) -> (SurfaceInputs, FloatImage) {
    harness.settle();
    let inputs = harness.capture_inputs();
    harness.settle();
    (inputs, harness.render_next_frame())
}

/// Each kind of light's penumbra widens with its softness: a spot and a point light's
/// size (world units) and a directional light's angle (degrees), each over no softness
/// and two growing ones; the verdict holds at each.
#[test]
fn the_penumbra_widens_with_softness() {
    type Kind = (
        &'static str,
        [f32; 3],
        &'static dyn Fn(&mut Harness, PhongShadows) -> CaseLight,
    );
    let kinds: [Kind; 3] = [
        ("spot", [0.0, 0.1, 0.3], &|h, shadows| {
            spot(h, Vec3::new(0.3, 4.5, 0.8), Vec3::ZERO, shadows)
        }),
        ("point", [0.0, 0.1, 0.3], &|h, shadows| {
            point(h, Vec3::new(0.3, 3.6, 0.8), shadows)
        }),
        // Angles whose penumbra behind the sphere spans texels of the one cascade (about
        // 0.05 units): the filter's radius is at least a texel, so a softer sun draws the
        // smallest filter.
        ("directional", [0.0, 10.0, 25.0], &|h, shadows| {
            directional(h, SUN, shadows, one_cascade())
        }),
    ];
    for (kind, softnesses, spawn) in kinds {
        let mut widths = Vec::new();
        for softness in softnesses {
            let (mut harness, scene) = harness();
            let lights = vec![spawn(&mut harness, PhongShadows { softness, ..on() })];
            let (inputs, rendered) = settled_frame(&mut harness);
            // The verdict still holds: the widest filter is within the band.
            judge_frame(&mut harness, &scene, &lights, &EVERYONE, &inputs, &rendered)
                .assert_holds(&format!("{kind}, softness {softness}"));
            let (partial, _) = floor_shadow_pixels(&mut harness, &scene, &inputs, &rendered);
            println!("{kind}, softness {softness}: {partial} floor pixels in the penumbra");
            widths.push(partial);
        }
        assert!(
            widths[0] < widths[1] && widths[1] < widths[2],
            "{kind}: the penumbra widens with softness: {widths:?}"
        );
    }
}

/// Floor pixels in the penumbra and in full shadow: the rendered visibility
/// ([`floor_visibilities`]) within 5 % of 0, or between 5 % and 95 %.
fn floor_shadow_pixels(
    harness: &mut Harness,
    scene: &Scene,
    inputs: &SurfaceInputs,
    rendered: &FloatImage,
) -> (usize, usize) {
    let visibilities = floor_visibilities(harness, scene, inputs, rendered);
    let full = visibilities.iter().filter(|(_, v)| *v < 0.05).count();
    let partial = visibilities
        .iter()
        .filter(|(_, v)| (0.05..0.95).contains(v))
        .count();
    (partial, full)
}

#[test]
fn the_penumbra_widens_with_the_distance_between_blocker_and_receiver() {
    // The sphere alone casts, from its place and then 1.5 units higher, nearer the light:
    // the penumbra, `light_size · (d_receiver − d_blocker) / d_blocker`, takes a larger share
    // of its shadow (the shadow grows as `d_receiver / d_blocker`, the penumbra faster).
    let (mut harness, mut scene) = harness();
    let cube = scene.cube();
    *harness.world_mut().get_mut::<Visibility>(cube).unwrap() = Visibility::Hidden;
    let shadows = PhongShadows {
        softness: 0.3,
        ..on()
    };
    let lights = vec![spot(
        &mut harness,
        Vec3::new(0.3, 4.5, 0.8),
        Vec3::ZERO,
        shadows,
    )];
    let roles = Roles {
        casting: &|entity| entity != cube,
        receiving: &|_| true,
    };
    let mut shares = Vec::new();
    for raise in [0.0, 1.5] {
        let sphere = scene.sphere();
        scene.translate(&mut harness, sphere, DVec3::new(0.0, raise, 0.0));
        let (inputs, rendered) = settled_frame(&mut harness);
        judge_frame(&mut harness, &scene, &lights, &roles, &inputs, &rendered)
            .assert_holds(&format!("sphere raised {raise}"));
        let (partial, full) = floor_shadow_pixels(&mut harness, &scene, &inputs, &rendered);
        let share = partial as f64 / (partial + full).max(1) as f64;
        println!(
            "sphere raised {raise}: {partial} penumbra and {full} umbra floor pixels, share {share:.2}"
        );
        shares.push(share);
    }
    assert!(
        shares[1] > shares[0],
        "the penumbra's share grows as the blocker nears the light: {shares:?}"
    );
}

/// Where the spot light of [`the_penumbra_has_the_formulas_width`] is, and its radius
/// (`softness`, world units).
const SOFT_SPOT: Vec3 = Vec3::new(0.3, 4.5, 0.8);
const SOFT_SPOT_RADIUS: f64 = 0.3;
/// How far the sphere is raised: its penumbra on the floor spans about 11 map texels, so
/// that half and twice that width stay within the filter's 1 to 16 texels at each side.
const RAISE: f64 = 0.75;
/// Samples per side of the square over which a point's visibility is averaged.
const FILTER_SAMPLES: usize = 16;
/// The widths tried, as multiples of the formula's: 0.5 to 2 in steps of 0.05.
const WIDTH_SCALES: std::ops::RangeInclusive<u32> = 10..=40;
const WIDTH_SCALE_STEP: f64 = 0.05;
/// How far the best-fitting width may be from the formula's, as a factor: the blockers'
/// depth is their mean over the search (up to 16 texels around the point), nearer the light
/// than the silhouette the formula takes here (about 1.1 fits, measured); the filter's four
/// taps per side and its bilinear reads make a staircase of the ramp. A filter half or twice
/// as wide as the formula's lies far outside.
const WIDTH_FIT: f64 = 1.4;

/// The spot light's visibility at `position` as a filter of the formula's width `scale · w`
/// gives it (SPEC.md, "Shadows"): the share of the square of that side, across the ray from
/// the light, around `position` lifted half the width off the floor, whose rays from the
/// light's centre miss the sphere (the hard shadow the map stores, averaged as the filter
/// averages it).
fn filtered_visibility(position: DVec3, sphere: (DVec3, f64), scale: f64) -> f64 {
    let light = SOFT_SPOT.as_dvec3();
    let (center, radius) = sphere;
    let d_p = position.distance(light);
    // The blocker's distance from the light: its silhouette's, where the penumbra's rays
    // graze it.
    let d_b = (center.distance_squared(light) - radius * radius).sqrt();
    let width = scale * SOFT_SPOT_RADIUS * (d_p - d_b) / d_b;
    // The filter's square is centred on the point lifted half its width off the floor.
    let lifted = position + 0.5 * width * DVec3::Y;
    let axis = (lifted - light).normalize();
    let across = axis.any_orthonormal_vector();
    let up = axis.cross(across);
    let blocked = |sample: DVec3| {
        let direction = (sample - light).normalize();
        let offset = light - center;
        let b = offset.dot(direction);
        b * b - (offset.length_squared() - radius * radius) >= 0.0 && b < 0.0
    };
    let mut lit = 0;
    for i in 0..FILTER_SAMPLES {
        for j in 0..FILTER_SAMPLES {
            let u = ((i as f64 + 0.5) / FILTER_SAMPLES as f64 - 0.5) * width;
            let v = ((j as f64 + 0.5) / FILTER_SAMPLES as f64 - 0.5) * width;
            lit += usize::from(!blocked(lifted + u * across + v * up));
        }
    }
    lit as f64 / (FILTER_SAMPLES * FILTER_SAMPLES) as f64
}

/// The penumbra has the formula's width: on the floor under the sphere, raised ([`RAISE`]),
/// each pixel's rendered visibility `V` (its green channel between the reference's fully
/// shadowed and fully lit values) is compared with the visibility a filter of width
/// `k · w` gives, for `k` from 0.5 to 2; the `k` that fits the penumbra's pixels best lies
/// within [`WIDTH_FIT`] of 1.
#[test]
fn the_penumbra_has_the_formulas_width() {
    let (mut harness, mut scene) = harness();
    let cube = scene.cube();
    *harness.world_mut().get_mut::<Visibility>(cube).unwrap() = Visibility::Hidden;
    let sphere = scene.sphere();
    scene.translate(&mut harness, sphere, DVec3::new(0.0, RAISE, 0.0));
    let Shape::Sphere { center, radius } = scene.shapes[1].1 else {
        unreachable!("the scene's second shape is the sphere")
    };
    let shadows = PhongShadows {
        softness: SOFT_SPOT_RADIUS as f32,
        ..on()
    };
    let lights = vec![spot(&mut harness, SOFT_SPOT, Vec3::ZERO, shadows)];
    let roles = Roles {
        casting: &|entity| entity != cube,
        receiving: &|_| true,
    };
    let (inputs, rendered) = settled_frame(&mut harness);
    judge_frame(&mut harness, &scene, &lights, &roles, &inputs, &rendered)
        .assert_holds("the sphere raised, soft");
    let visibilities = floor_visibilities(&mut harness, &scene, &inputs, &rendered);
    // The penumbra: pixels partly lit (beyond 2 % of either end, clear of the rounding of
    // lit and shadowed pixels) in the picture or under the widest filter tried, so that
    // every width is judged on the same pixels; outside them every width tried gives (nearly)
    // 0 or 1.
    let widest = f64::from(*WIDTH_SCALES.end()) * WIDTH_SCALE_STEP;
    let penumbra: Vec<(DVec3, f64)> = visibilities
        .into_iter()
        .filter(|&(position, rendered)| {
            let modelled = filtered_visibility(position, (center, radius), widest);
            [rendered, modelled]
                .iter()
                .any(|v| (0.02..0.98).contains(v))
        })
        .collect();
    let misfit = |scale: f64| {
        penumbra
            .iter()
            .map(|&(position, rendered)| {
                (rendered - filtered_visibility(position, (center, radius), scale)).powi(2)
            })
            .sum::<f64>()
            / penumbra.len() as f64
    };
    let (best, error) = WIDTH_SCALES
        .map(|step| f64::from(step) * WIDTH_SCALE_STEP)
        .map(|scale| (scale, misfit(scale)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("scales");
    println!(
        "{} penumbra pixels: the width that fits them best is {best:.2} of the formula's \
         (root mean square {:.3}; {:.3} at the formula's)",
        penumbra.len(),
        error.sqrt(),
        misfit(1.0).sqrt()
    );
    // About 200 pixels measured: enough for the fit to see the ramp's slope.
    assert!(
        penumbra.len() > 100,
        "the penumbra covers {} pixels",
        penumbra.len()
    );
    assert!(
        (1.0 / WIDTH_FIT..=WIDTH_FIT).contains(&best),
        "the penumbra fits a width {best:.2} times the formula's"
    );
}

/// Each floor pixel's position and rendered visibility of the scene's one light, from its
/// green channel between the reference's fully shadowed and fully lit values (where those
/// differ by more than 0.05).
fn floor_visibilities(
    harness: &mut Harness,
    scene: &Scene,
    inputs: &SurfaceInputs,
    rendered: &FloatImage,
) -> Vec<(DVec3, f64)> {
    let floor = &scene.shapes[0].2;
    assert!(
        inputs.materials.values().any(|handle| handle == floor),
        "the floor is drawn"
    );
    let reference_lights = harness.reference_lights();
    let camera = harness.camera_position();
    let material = reference::Material::from(
        harness
            .world_mut()
            .resource::<Assets<PhongMaterial>>()
            .get(floor)
            .unwrap(),
    );
    let mut visibilities = Vec::new();
    for (index, color) in rendered.pixels.iter().enumerate() {
        let Some((handle, surface)) = inputs.surface_at(index, camera) else {
            continue;
        };
        if handle != floor {
            continue;
        }
        let shade = |visibility| {
            let shadowing = Shadowing {
                visibility,
                ..Shadowing::LIT
            };
            reference::shade_shadowed(&surface, &material, &reference_lights, &[shadowing]).y
        };
        let (dark, lit) = (shade(0.0), shade(1.0));
        if lit - dark > 0.05 {
            let visibility = (f64::from(color[1]) - dark) / (lit - dark);
            visibilities.push((surface.position, visibility));
        }
    }
    visibilities
}
