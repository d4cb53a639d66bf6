//! Light cookies (`PhongLightCookie`): a spot light's image across its cone, a point light's
//! cube map (a vertical cross) and a directional light's tiled image (its red channel
//! alone), rendered on the render device and compared per pixel with the reference model
//! (`reference::Cookie::tint` on each light, then the frame tests' equation).
//!
//! The shader filters the atlas itself, with `f32` weights, as the reference does: the
//! tolerance is the frame tests' ([`TOLERANCE`]). Where a point light's ray is within 10⁻⁵
//! (relative) of a cube edge, the device's `f32` may pick the other face: those pixels are
//! not judged. Under WebGL2 the atlas is not bound: the lights are checked untinted.
//! Cookied lamps of finite reach just outside the frustum are clustered, and tint what they
//! reach inside it exactly.

use crate::frames::{SIZE, TOLERANCE};
use crate::texture_maps::{assert_pixels_follow, assert_scene_follows, expected_color};
use bevy::{
    asset::RenderAssetUsages,
    camera::primitives::CubemapLayout,
    prelude::*,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};
use bevy_phong::{
    extension::PhongCookieProjection, prelude::*, reference, testing::limits::COOKIE_RESOLUTION,
};
use bevy_phong_headless::{CAMERA_POSITION, Harness, pixel_model::near_a_cube_edge};
use glam::DVec3;

/// A cookie image at the atlas's size, 8-bit sRGB: copied into the atlas unchanged.
pub(crate) fn cookie_image(texel: impl Fn(u32, u32) -> [u8; 3]) -> Image {
    let side = COOKIE_RESOLUTION;
    let data = (0..side * side)
        .flat_map(|index| {
            let [r, g, b] = texel(index % side, index / side);
            [r, g, b, 255]
        })
        .collect();
    Image::new(
        Extent3d {
            width: side,
            height: side,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::default(),
    )
}

/// A wave from 0 to 255 along `t` with period `period` texels.
pub(crate) fn wave(t: u32, period: f32) -> u8 {
    (127.5 + 127.5 * (t as f32 * core::f32::consts::TAU / period).sin()).round() as u8
}

/// A light of the reference model and the cookie on it.
type Cookied = (reference::Light, reference::Cookie);

/// The reference model's `light` with `cookie` on it at `at`, laid over its rays by
/// `projection`, its image read from `world`.
fn cookied(
    world: &World,
    light: reference::Light,
    cookie: &PhongLightCookie,
    at: Transform,
    projection: PhongCookieProjection,
) -> Cookied {
    let images = world.resource::<Assets<Image>>();
    let cookie = reference::Cookie::new(
        cookie,
        images.get(&cookie.image).unwrap(),
        &GlobalTransform::from(at),
        projection,
    )
    .expect("a readable cookie");
    (light, cookie)
}

/// Spawns `spot` at `at` with `cookie`; returns it as the reference model takes it.
fn spot_with_cookie(
    world: &mut World,
    spot: PhongSpotLight,
    at: Transform,
    cookie: PhongLightCookie,
) -> Cookied {
    world.spawn((spot.clone(), at, cookie.clone()));
    let light = reference::Light::spot(&spot, &GlobalTransform::from(at));
    let cone = PhongCookieProjection::Cone {
        half_angle: spot.outer_angle,
    };
    cookied(world, light, &cookie, at, cone)
}

/// Spawns `point` at `at` with `cookie`; returns it as the reference model takes it.
fn point_with_cookie(
    world: &mut World,
    point: PhongPointLight,
    at: Transform,
    cookie: PhongLightCookie,
) -> Cookied {
    world.spawn((point.clone(), at, cookie.clone()));
    let light = reference::Light::point(&point, &GlobalTransform::from(at));
    cookied(world, light, &cookie, at, PhongCookieProjection::Cube)
}

/// A floor `floor` units square and a sphere at `sphere_x` for the cookies to fall on.
pub(crate) fn floor_and_sphere(floor: f32, sphere_x: f32) -> [(Mesh, Transform, PhongMaterial); 2] {
    [
        (
            Plane3d::default().mesh().size(floor, floor).into(),
            Transform::from_xyz(0.0, -1.0, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.8, 0.8, 0.8),
                shininess: 8.0,
                ..default()
            },
        ),
        (
            Sphere::new(0.8).mesh().uv(48, 32),
            Transform::from_xyz(sphere_x, -0.2, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.7, 0.75, 0.9),
                shininess: 40.0,
                ..default()
            },
        ),
    ]
}

/// Asserts that every pixel of `objects` follows the reference model under the ambient
/// light of 0.05 and the `lights`, each tinted by its cookie where the atlas is bound
/// (untinted where it is not, under WebGL2); pixels whose ray from the point light of
/// `point_light` (an index in `lights`) is near a cube edge are not judged.
fn assert_cookies_follow(
    harness: Harness,
    objects: [(Mesh, Transform, PhongMaterial); 2],
    name: &str,
    lights: &[Cookied],
    point_light: usize,
) {
    let from_point_light = lights[point_light].1.light_from_world;
    assert_pixels_follow(
        harness,
        objects,
        name,
        &|material, surface, pixel, inputs, images, _| {
            let tinted = inputs.every_map_bound;
            if tinted && near_a_cube_edge(from_point_light.transform_point3(surface.position)) {
                return None;
            }
            let lights = reference::Lights {
                ambient: DVec3::splat(0.05),
                hemisphere: None,
                lights: lights
                    .iter()
                    .map(|(light, cookie)| match tinted {
                        true => light.tinted(cookie.tint(surface.position)),
                        false => *light,
                    })
                    .collect(),
                others: Default::default(),
            };
            expected_color(material, surface, pixel, inputs, images, &lights)
        },
    );
}

/// Each kind of light tinted by its cookie as the reference says, the point light's cube in
/// each of Bevy's four layouts (`CubemapLayout`).
#[test]
fn cookies_tint_each_light_kind_as_the_reference_model_says() {
    for layout in [
        CubemapLayout::CrossVertical,
        CubemapLayout::CrossHorizontal,
        CubemapLayout::SequenceVertical,
        CubemapLayout::SequenceHorizontal,
    ] {
        cookies_tint_each_light_kind(layout);
    }
}

/// The scene of [`cookies_tint_each_light_kind_as_the_reference_model_says`], the point
/// light's cube packed by `layout`.
fn cookies_tint_each_light_kind(layout: CubemapLayout) {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.05, 0.05, 0.05),
    });
    let mut images = world.resource_mut::<Assets<Image>>();
    let spot_image = images.add(cookie_image(|x, y| {
        [wave(x, 40.0), wave(y, 56.0), wave(x + y, 90.0)]
    }));
    let cube_image = images.add(cookie_image(|x, y| {
        [(x & 0xff) as u8, (y & 0xff) as u8, wave(x * 3 + y, 70.0)]
    }));
    let tile_image = images.add(cookie_image(|x, y| {
        let red = if (x / 64 + y / 64) % 2 == 0 { 255 } else { 90 };
        [red, 0, 0]
    }));

    let spot = PhongSpotLight {
        color: Color::linear_rgb(1.2, 1.1, 1.0),
        inner_angle: 25f32.to_radians(),
        outer_angle: 35f32.to_radians(),
        ..default()
    };
    let spot_at =
        Transform::from_xyz(-1.3, 2.2, 0.6).looking_at(Vec3::new(-1.3, -1.0, 0.4), Vec3::Z);
    let point = PhongPointLight {
        color: Color::linear_rgb(0.9, 0.8, 0.7),
        decay: Decay::new(1.0, 0.1, 0.05),
        ..default()
    };
    let point_at = Transform::from_xyz(1.0, 1.3, 1.4).with_rotation(Quat::from_rotation_y(0.4));
    let directional = PhongDirectionalLight {
        color: Color::linear_rgb(0.4, 0.4, 0.45),
        ..default()
    };
    let directional_at = Transform::from_xyz(1.0, 2.0, 1.0)
        .looking_at(Vec3::ZERO, Vec3::Y)
        .with_scale(Vec3::splat(0.6));
    let spot_cookie = PhongLightCookie {
        image: spot_image,
        ..default()
    };
    let cube_cookie = PhongLightCookie {
        image: cube_image,
        cubemap_layout: layout,
        ..default()
    };
    let tile_cookie = PhongLightCookie {
        image: tile_image,
        tiled: true,
        red_only: true,
        ..default()
    };
    world.spawn((directional.clone(), directional_at, tile_cookie.clone()));
    let directional = reference::Light::directional(&directional, &directional_at.into());
    let lights = [
        spot_with_cookie(world, spot, spot_at, spot_cookie),
        point_with_cookie(world, point, point_at, cube_cookie),
        cookied(
            world,
            directional,
            &tile_cookie,
            directional_at,
            PhongCookieProjection::Plane,
        ),
    ];
    let objects = floor_and_sphere(8.0, 1.2);
    assert_cookies_follow(
        harness,
        objects,
        &format!("light cookies, cube {layout:?}"),
        &lights,
        1,
    );
}

#[test]
fn cookied_lights_just_outside_the_frustum_are_clustered_and_tint_their_reach_exactly() {
    // The harness camera looks at the origin from CAMERA_POSITION with Bevy's default
    // perspective (vertical field of view 45°, square target): `half_width` is the view's
    // half-extent at the origin's depth.
    let forward = (-CAMERA_POSITION).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let half_width = std::f32::consts::FRAC_PI_8.tan() * CAMERA_POSITION.length();

    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.05, 0.05, 0.05),
    });
    let mut images = world.resource_mut::<Assets<Image>>();
    let spot_image = images.add(cookie_image(|x, y| {
        [wave(x, 30.0), wave(y, 44.0), wave(x + 2 * y, 80.0)]
    }));
    let cube_image = images.add(cookie_image(|x, y| {
        [wave(x + y, 50.0), (y & 0xff) as u8, (x & 0xff) as u8]
    }));
    // A spot lamp 1.2 past the view's right edge, aimed in and down, reaching 6 units; a
    // point lamp 0.8 above its top edge, reaching 4.
    let spot = PhongSpotLight {
        color: Color::linear_rgb(1.4, 1.2, 1.0),
        inner_angle: 30f32.to_radians(),
        outer_angle: 45f32.to_radians(),
        decay: Decay::new(1.0, 0.1, 0.05),
        range: Some(6.0),
        ..default()
    };
    let spot_at = Transform::from_translation(right * (half_width + 1.2) + Vec3::Y)
        .looking_at(Vec3::new(0.5, -1.0, 0.0), Vec3::Y);
    let point = PhongPointLight {
        color: Color::linear_rgb(1.0, 0.9, 0.8),
        decay: Decay::new(1.0, 0.1, 0.05),
        range: Some(4.0),
        ..default()
    };
    let point_at = Transform::from_translation(up * (half_width + 0.8));
    let spot_cookie = PhongLightCookie {
        image: spot_image,
        ..default()
    };
    let cube_cookie = PhongLightCookie {
        image: cube_image,
        ..default()
    };
    let lights = [
        spot_with_cookie(world, spot, spot_at, spot_cookie),
        point_with_cookie(world, point, point_at, cube_cookie),
    ];
    harness.settle();
    assert_eq!(
        crate::clusters::clustered_light_count(&mut harness),
        2,
        "both cookied lamps are in the clusters, not in every fragment's loop"
    );
    let objects = floor_and_sphere(10.0, 1.0);
    assert_cookies_follow(
        harness,
        objects,
        "cookied lamps outside the frustum",
        &lights,
        1,
    );
}

/// An untiled directional light's image lights its square only; outside it the light is
/// dark with `dark_outside` (Bevy's `DirectionalLightTexture`) and untouched without, each
/// pixel as the reference model says (`Harness::compare`, the cookies read from the lights).
#[test]
fn an_untiled_directional_cookie_leaves_its_light_dark_or_untouched_outside_its_tile() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.05, 0.05, 0.05),
    });
    let image = world
        .resource_mut::<Assets<Image>>()
        .add(cookie_image(|x, y| [wave(x, 40.0), wave(y, 60.0), 180]));
    // Each tile 2 units across (scale 1), seen from above on either side of the floor.
    for (dark_outside, color, from) in [
        (
            true,
            Color::linear_rgb(0.6, 0.5, 0.3),
            Vec3::new(1.5, 3.0, 1.0),
        ),
        (
            false,
            Color::linear_rgb(0.2, 0.3, 0.4),
            Vec3::new(-1.5, 3.0, 0.5),
        ),
    ] {
        world.spawn((
            PhongDirectionalLight { color, ..default() },
            Transform::from_translation(from).looking_at(from - Vec3::Y, Vec3::Z),
            PhongLightCookie {
                image: image.clone(),
                dark_outside,
                ..default()
            },
        ));
    }
    let objects = floor_and_sphere(8.0, 1.2);
    assert_scene_follows(&mut harness, objects, "untiled directional cookies");
}

/// A cookie image edited in place, as hot reloading edits it (the asset modified, its
/// handle kept), tints its light with its new texels from the next frame: every pixel
/// follows the reference model made from the image as it is then, and the frame changed
/// where the image did (under WebGL2, where the atlas is not bound, the light stays
/// untinted and the frame unchanged).
#[test]
fn a_cookie_image_edited_in_place_tints_its_light_with_its_new_texels() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.05, 0.05, 0.05),
    });
    let image = world
        .resource_mut::<Assets<Image>>()
        .add(cookie_image(|x, y| [wave(x, 40.0), wave(y, 56.0), 200]));
    world.spawn((
        PhongSpotLight {
            color: Color::linear_rgb(1.2, 1.1, 1.0),
            inner_angle: 25f32.to_radians(),
            outer_angle: 35f32.to_radians(),
            ..default()
        },
        Transform::from_xyz(0.3, 2.2, 0.6).looking_at(Vec3::new(0.3, -1.0, 0.4), Vec3::Z),
        PhongLightCookie {
            image: image.clone(),
            ..default()
        },
    ));
    let (before, _) = assert_scene_follows(
        &mut harness,
        floor_and_sphere(8.0, 0.6),
        "a cookie before its edit",
    );

    let edited = cookie_image(|x, y| [wave(y, 30.0), 255, wave(x, 70.0)]);
    let world = harness.world_mut();
    world
        .resource_mut::<Assets<Image>>()
        .get_mut(&image)
        .expect("the cookie image")
        .data = edited.data;
    harness.settle();
    let after = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    let comparison = harness.compare(&after, &inputs);
    comparison.assert_within("a cookie after its edit", TOLERANCE);
    comparison.assert_mostly_judged("a cookie after its edit");
    let changed = before
        .pixels
        .iter()
        .zip(&after.pixels)
        .filter(|(a, b)| (a[1] - b[1]).abs() > 0.05)
        .count();
    if harness.binds_every_map() {
        assert!(changed > 500, "{changed} pixels changed with the edit");
    } else {
        assert_eq!(
            changed, 0,
            "no atlas bound: the light is untinted before and after"
        );
    }
}
