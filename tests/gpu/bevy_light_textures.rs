//! Bevy's light textures on the lights `PhongBevyLightsPlugin` mirrors: a `SpotLightTexture`,
//! an untiled, scaled `DirectionalLightTexture` and a `PointLightTexture` in each cube layout
//! light `PhongMaterial` meshes where Bevy's own shader would read them. The expectation
//! does not come from the crate's cookies: each pixel's texel is found with Bevy's formulas
//! (bevy_pbr 0.20.1, `pbr_lighting.wesl`'s `spot_light`, `directional_light` and
//! `cubemap_uv`, on the light's `GlobalTransform` inverted as `decal/clustered.rs` extracts
//! it), written again here, and the mirrored light is scaled by that texel's red channel, as
//! Bevy scales its own.
//!
//! The images are flat quadrants, each a different red: pixels whose texel lies within
//! [`EDGE_TEXELS`] of a quadrant's or a face's edge are not judged. Under WebGL2's limits
//! cookies are not bound and the lights are untextured.

use crate::{
    cookies::{cookie_image, floor_and_sphere},
    texture_maps::{assert_pixels_follow, expected_color},
};
use bevy::{
    camera::primitives::CubemapLayout,
    color::{Color, ColorToComponents},
    light::{
        DirectionalLight, DirectionalLightTexture, PointLight, PointLightTexture, SpotLight,
        SpotLightTexture,
    },
    prelude::*,
};
use bevy_phong::{
    PhongBevyLightsPlugin, prelude::*, reference, testing::limits::COOKIE_RESOLUTION,
};
use bevy_phong_headless::Harness;
use glam::{DAffine3, DVec2, DVec3};

/// Render size.
const SIZE: u32 = 128;
/// How near (in the image's texels) a quadrant's or a face's edge a pixel's texel may lie and
/// still be judged: an edge of a cube face falls inside a texel where the face is not a whole
/// number of texels wide (256 / 3), and the filtered read blends half a texel either side;
/// one texel holds both (the pixels judged just past it match to 8e-7).
const EDGE_TEXELS: f64 = 1.0;

/// The red byte of each quadrant (top left, top right, bottom left, bottom right of the
/// image): four values whose decoded reds all differ, so that a flipped or turned image
/// fails.
type Quadrants = [u8; 4];
const SPOT_QUADRANTS: Quadrants = [255, 60, 160, 110];
const SUN_QUADRANTS: Quadrants = [90, 230, 30, 180];

/// The quadrant of `uv` (0 to 1 across, `v` down): 0 top left, 1 top right, 2 bottom left,
/// 3 bottom right.
fn quadrant(uv: DVec2) -> usize {
    usize::from(uv.x >= 0.5) + 2 * usize::from(uv.y >= 0.5)
}

/// Whether `uv` lies within `margin` of a quadrant's edge (0, ½ or 1 on either axis).
fn near_an_edge(uv: DVec2, margin: DVec2) -> bool {
    let near = |t: f64, margin: f64| [0.0, 0.5, 1.0].iter().any(|edge| (t - edge).abs() < margin);
    near(uv.x, margin.x) || near(uv.y, margin.y)
}

/// [`EDGE_TEXELS`] in the image's coordinates.
fn image_margin() -> DVec2 {
    DVec2::splat(EDGE_TEXELS / f64::from(COOKIE_RESOLUTION))
}

/// The red of an sRGB byte, decoded as the sampler decodes it.
fn decoded_red(byte: u8) -> f64 {
    f64::from(Color::srgb_u8(byte, 0, 0).to_linear().to_f32_array()[0])
}

/// The inverse of a light's transform: its local space, as Bevy extracts it for the texture.
fn local_from_world(transform: Transform) -> DAffine3 {
    GlobalTransform::from(transform)
        .affine()
        .inverse()
        .as_daffine3()
}

/// An sRGB image of four quadrants.
fn quadrant_image(quadrants: Quadrants) -> Image {
    cookie_image(move |x, y| [quadrants[quadrant(texel_center(x, y))], 0, 0])
}

/// The centre of the texel `(x, y)` of an image at the atlas's size, 0 to 1 across.
fn texel_center(x: u32, y: u32) -> DVec2 {
    (DVec2::new(f64::from(x), f64::from(y)) + 0.5) / f64::from(COOKIE_RESOLUTION)
}

/// The decoded red of the texel at `uv` (0 to 1 across the image, `v` down), `None` within
/// [`EDGE_TEXELS`] of a quadrant's edge.
fn quadrant_red(quadrants: Quadrants, uv: DVec2) -> Option<f64> {
    (!near_an_edge(uv, image_margin())).then(|| decoded_red(quadrants[quadrant(uv)]))
}

/// Bevy's spot light texture coordinates of `position`: in the light's local space
/// (`local_from_world`), `xy / (z · tan(outer_angle))` scaled by `(−½, ½)` about ½, in
/// front of the light only (`z < 0`).
fn bevy_spot_uv(local_from_world: DAffine3, tan_outer: f64, position: DVec3) -> Option<DVec2> {
    let local = local_from_world.transform_point3(position);
    (local.z < 0.0).then(|| local.truncate() / (local.z * tan_outer) * DVec2::new(-0.5, 0.5) + 0.5)
}

/// Bevy's directional light texture coordinates of `position`: its local `xy` scaled by
/// `(−½, ½)` about ½ (one tile two local units across).
fn bevy_directional_uv(local_from_world: DAffine3, position: DVec3) -> DVec2 {
    let local = local_from_world.transform_point3(position);
    local.truncate() * DVec2::new(-0.5, 0.5) + 0.5
}

/// A harness that mirrors Bevy's lights, under an ambient light of 0.05.
fn mirroring_harness() -> Harness {
    let mut harness = Harness::with_plugins(SIZE, SIZE, |app| {
        app.add_plugins(PhongBevyLightsPlugin);
    });
    harness.world_mut().insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.05, 0.05, 0.05),
    });
    harness
}

#[test]
fn bevy_light_textures_light_where_bevys_shader_reads_them() {
    let mut harness = mirroring_harness();
    let world = harness.world_mut();
    let outer_angle = 0.6f32;
    let spot_at = Transform::from_xyz(-1.2, 3.0, 0.6)
        .looking_at(Vec3::new(-0.6, -1.0, 0.2), Vec3::new(0.3, 0.0, 1.0));
    let spot_image = world
        .resource_mut::<Assets<Image>>()
        .add(quadrant_image(SPOT_QUADRANTS));
    world.spawn((
        SpotLight {
            intensity: 500_000.0,
            range: 20.0,
            outer_angle,
            inner_angle: 0.45,
            shadow_maps_enabled: false,
            ..default()
        },
        SpotLightTexture { image: spot_image },
        spot_at,
    ));
    // Scaled by 1.5: a tile three units across, centred where the light's axis meets the
    // floor, turned about it, dark outside.
    let sun_at = Transform::from_xyz(1.3, 3.0, -0.2)
        .looking_to(Vec3::new(0.15, -1.0, 0.1), Vec3::new(1.0, 0.0, 0.4))
        .with_scale(Vec3::splat(1.5));
    let sun_image = world
        .resource_mut::<Assets<Image>>()
        .add(quadrant_image(SUN_QUADRANTS));
    world.spawn((
        DirectionalLight {
            illuminance: 2_500.0,
            shadow_maps_enabled: false,
            ..default()
        },
        DirectionalLightTexture {
            image: sun_image,
            tiled: false,
        },
        sun_at,
    ));
    let spot_from_world = local_from_world(spot_at);
    let sun_from_world = local_from_world(sun_at);
    let tan_outer = f64::from(outer_angle).tan();
    let inside = |uv: DVec2| uv.min_element() >= 0.0 && uv.max_element() <= 1.0;
    assert_pixels_follow(
        harness,
        floor_and_sphere(8.0, 1.2),
        "Bevy's light textures",
        &|material, surface, pixel, inputs, images, lights| {
            let textured = inputs.every_map_bound;
            let position = surface.position;
            let mut lit = Vec::new();
            for light in &lights.lights {
                let red = match light {
                    // Past the image's square the cone gives no light (it is inscribed in
                    // it), whatever the texel.
                    reference::Light::Spot { .. } => {
                        match bevy_spot_uv(spot_from_world, tan_outer, position) {
                            Some(uv) if inside(uv) => quadrant_red(SPOT_QUADRANTS, uv)?,
                            _ => 1.0,
                        }
                    }
                    // Dark outside the untiled image.
                    reference::Light::Directional { .. } => {
                        let uv = bevy_directional_uv(sun_from_world, position);
                        match inside(uv) {
                            true => quadrant_red(SUN_QUADRANTS, uv)?,
                            false if near_an_edge(uv, image_margin()) => return None,
                            false => 0.0,
                        }
                    }
                    reference::Light::Point { .. } => unreachable!("no point light"),
                };
                let red = if textured { red } else { 1.0 };
                lit.push(light.tinted(DVec3::splat(red)));
            }
            let lights = reference::Lights {
                lights: lit,
                ..lights.clone()
            };
            expected_color(material, surface, pixel, inputs, images, &lights)
        },
    );
}

/// The red byte of `face` (Bevy's order: +X, −X, +Y, −Y, −Z, +Z) at `quadrant` of it (top
/// left, top right, bottom left, bottom right): 24 values whose decoded reds all differ.
fn cube_red_byte(face: usize, quadrant: usize) -> u8 {
    (20 + 40 * face + 10 * quadrant) as u8
}

/// Where each face lies in an image of `layout`: its size and its corner, as fractions of
/// the image (bevy_pbr 0.20.1, `pbr_lighting.wesl`'s `cubemap_uv`).
fn face_placement(layout: CubemapLayout, face: usize) -> (DVec2, DVec2) {
    let nibble = |packed: u32| f64::from((packed >> (4 * face)) & 0xF);
    let (size, corner) = match layout {
        CubemapLayout::CrossVertical => (
            DVec2::new(1.0 / 3.0, 1.0 / 4.0),
            DVec2::new(nibble(0x111102), nibble(0x132011)),
        ),
        CubemapLayout::CrossHorizontal => (
            DVec2::new(1.0 / 4.0, 1.0 / 3.0),
            DVec2::new(nibble(0x131102), nibble(0x112011)),
        ),
        CubemapLayout::SequenceHorizontal => {
            (DVec2::new(1.0 / 6.0, 1.0), DVec2::new(face as f64, 0.0))
        }
        CubemapLayout::SequenceVertical => {
            (DVec2::new(1.0, 1.0 / 6.0), DVec2::new(0.0, face as f64))
        }
    };
    (size, corner * size)
}

/// Bevy's face and the coordinates on it (0 to 1, `v` down) of a direction from the light,
/// in its local space (`cubemap_uv`).
fn bevy_cube_face_uv(direction: DVec3) -> (usize, DVec2) {
    let a = direction.abs();
    let (face, uv, divisor) = if a.x >= a.y.max(a.z) {
        if direction.x < 0.0 {
            (1, DVec2::new(-direction.z, -direction.y), -direction.x)
        } else {
            (0, DVec2::new(direction.z, -direction.y), direction.x)
        }
    } else if a.y >= a.z {
        if direction.y < 0.0 {
            (3, DVec2::new(direction.x, direction.z), -direction.y)
        } else {
            (2, DVec2::new(direction.x, -direction.z), direction.y)
        }
    } else if direction.z < 0.0 {
        (4, DVec2::new(direction.x, -direction.y), -direction.z)
    } else {
        (5, DVec2::new(direction.x, direction.y), direction.z)
    };
    (face, uv / divisor * 0.5 + 0.5)
}

/// A cube image of `layout` at the atlas's size: each face's four quadrants their
/// [`cube_red_byte`], the cells no face uses black.
fn cube_image(layout: CubemapLayout) -> Image {
    cookie_image(move |x, y| {
        let at = texel_center(x, y);
        let red = (0..6)
            .find_map(|face| {
                let (size, corner) = face_placement(layout, face);
                let uv = (at - corner) / size;
                let inside = uv.min_element() >= 0.0 && uv.max_element() < 1.0;
                inside.then(|| cube_red_byte(face, quadrant(uv)))
            })
            .unwrap_or(0);
        [red, 0, 0]
    })
}

/// A `PointLightTexture` in each of Bevy's four layouts lights a mirrored point light's
/// surroundings where Bevy's `cubemap_uv` reads it: each face, and each quadrant of it, at
/// its place in the image. Pixels whose texel lies within [`EDGE_TEXELS`] of a face's or a
/// quadrant's edge are not judged.
#[test]
fn a_point_light_texture_lights_where_bevys_cube_layouts_place_each_face() {
    for layout in [
        CubemapLayout::CrossVertical,
        CubemapLayout::CrossHorizontal,
        CubemapLayout::SequenceVertical,
        CubemapLayout::SequenceHorizontal,
    ] {
        let mut harness = mirroring_harness();
        let world = harness.world_mut();
        let point_at = Transform::from_xyz(0.6, 0.9, 1.2).with_rotation(Quat::from_euler(
            EulerRot::YXZ,
            0.5,
            0.3,
            0.0,
        ));
        let image = world
            .resource_mut::<Assets<Image>>()
            .add(cube_image(layout));
        world.spawn((
            PointLight {
                intensity: 200_000.0,
                range: 20.0,
                shadow_maps_enabled: false,
                ..default()
            },
            PointLightTexture {
                image,
                cubemap_layout: layout,
            },
            point_at,
        ));
        let point_from_world = local_from_world(point_at);
        assert_pixels_follow(
            harness,
            floor_and_sphere(8.0, -1.2),
            &format!("Bevy's point light texture, {layout:?}"),
            &|material, surface, pixel, inputs, images, lights| {
                let direction = point_from_world.transform_point3(surface.position);
                let (face, uv) = bevy_cube_face_uv(direction);
                // The image's margin, in the face's coordinates.
                let (size, _) = face_placement(layout, face);
                if near_an_edge(uv, image_margin() / size) {
                    return None;
                }
                let red = match inputs.every_map_bound {
                    true => decoded_red(cube_red_byte(face, quadrant(uv))),
                    false => 1.0,
                };
                let lights = reference::Lights {
                    lights: lights
                        .lights
                        .iter()
                        .map(|light| light.tinted(DVec3::splat(red)))
                        .collect(),
                    ..lights.clone()
                };
                expected_color(material, surface, pixel, inputs, images, &lights)
            },
        );
    }
}
