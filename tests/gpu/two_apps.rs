//! Two apps in one process, as an editor and its preview: one scene with a shadow-casting,
//! cookied spot light and a hemisphere light, the other with the same shapes under the same
//! spot light without shadow, cookie or hemisphere. Each app's shader variants are its own
//! (they travel with its materials through its own extraction), so each renders beside the
//! other exactly as it renders alone, even with the two apps' frames interleaved: both main
//! worlds first, then each render world.

use crate::frames::SIZE;
use bevy::{
    asset::RenderAssetUsages,
    prelude::*,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};
use bevy_phong::prelude::*;
use bevy_phong_headless::{FloatImage, Harness};

/// A picture's pixels may differ this much between a render alone and one beside the other
/// app: none at all, up to the last bits of `f32` (the same scene on the same device runs the
/// same arithmetic).
const SAME_PICTURE: f32 = 1e-6;

/// Pixels that the shadow, the cookie and the hemisphere light must change between the two
/// scenes: the shadowed scene's variant must show.
const CHANGED_PIXELS: usize = 500;

/// A 4×4 cookie of bars: one bright texel column in two.
fn bars() -> Image {
    let data = (0..16u32)
        .flat_map(|index| match index % 2 {
            0 => [255, 255, 255, 255],
            _ => [40, 40, 40, 255],
        })
        .collect();
    Image::new(
        Extent3d {
            width: 4,
            height: 4,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::default(),
    )
}

/// A floor and a cube under a spot light; with `shadowed`, the light casts shadows and
/// carries a cookie, and a hemisphere light is added.
fn build(harness: &mut Harness, shadowed: bool) {
    let world = harness.world_mut();
    let cookie = world.resource_mut::<Assets<Image>>().add(bars());
    let floor = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::default().mesh().size(8.0, 8.0));
    let cube = world
        .resource_mut::<Assets<Mesh>>()
        .add(Cuboid::new(1.0, 1.0, 1.0));
    let material = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(PhongMaterial {
            base_color: Color::linear_rgb(0.8, 0.7, 0.6),
            shininess: 20.0,
            ..default()
        });
    world.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.05, 0.05, 0.05),
    });
    world.spawn((Mesh3d(floor), MeshMaterial3d(material.clone())));
    world.spawn((
        Mesh3d(cube),
        MeshMaterial3d(material),
        Transform::from_xyz(0.0, 0.5, 0.0),
    ));
    let mut spot = world.spawn((
        PhongSpotLight {
            color: Color::linear_rgb(1.5, 1.4, 1.3),
            inner_angle: 30f32.to_radians(),
            outer_angle: 40f32.to_radians(),
            shadows: PhongShadows {
                enabled: shadowed,
                ..default()
            },
            ..default()
        },
        Transform::from_xyz(1.5, 4.0, 1.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    if shadowed {
        spot.insert(PhongLightCookie {
            image: cookie,
            ..default()
        });
        world.insert_resource(PhongHemisphereLight {
            sky_color: Color::linear_rgb(0.1, 0.1, 0.2),
            ground_color: Color::linear_rgb(0.1, 0.05, 0.0),
            ..default()
        });
    }
}

/// The largest difference of any channel of any pixel, and the number of pixels that differ
/// by more than [`SAME_PICTURE`].
fn difference(a: &FloatImage, b: &FloatImage) -> (f32, usize) {
    let mut largest = 0f32;
    let mut differing = 0;
    for (a, b) in a.pixels.iter().zip(&b.pixels) {
        let d = (0..4).map(|c| (a[c] - b[c]).abs()).fold(0f32, f32::max);
        largest = largest.max(d);
        differing += usize::from(d > SAME_PICTURE);
    }
    (largest, differing)
}

#[test]
fn two_apps_side_by_side_each_render_their_own_scene() {
    let (mut shadowed, mut plain) = Harness::side_by_side(SIZE, SIZE, |_| {}, |_| {});
    build(&mut shadowed, true);
    build(&mut plain, false);
    // Each alone first: its own frames, the other app idle.
    shadowed.settle();
    let shadowed_alone = shadowed.render_next_frame();
    plain.settle();
    let plain_alone = plain.render_next_frame();
    let (_, changed) = difference(&shadowed_alone, &plain_alone);
    assert!(
        changed >= CHANGED_PIXELS,
        "the shadow, cookie and hemisphere light change only {changed} pixels"
    );

    // Then interleaved: each app's main world runs before the other's render world. Several
    // frames, so that every variant either app could take is compiled and in use.
    for _ in 0..8 {
        bevy_phong_headless::update_in_lockstep(&mut shadowed.app, &mut plain.app);
    }
    let shadowed_beside = shadowed.render_next_frame_beside(&mut plain);
    let plain_beside = plain.render_next_frame_beside(&mut shadowed);
    for (name, alone, beside) in [
        ("shadowed", &shadowed_alone, &shadowed_beside),
        ("plain", &plain_alone, &plain_beside),
    ] {
        let (largest, differing) = difference(alone, beside);
        assert!(
            differing == 0,
            "the {name} scene rendered beside the other app differs from it alone in \
             {differing} pixels (largest difference {largest:.3e})"
        );
    }
}
