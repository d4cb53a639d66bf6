//! Surface inputs beside the texture maps: a mesh's vertex colors (`Mesh::ATTRIBUTE_COLOR`),
//! the material's UV transform, unlit materials, and light and AO maps on either UV set,
//! rendered on the render device and
//! compared per pixel with the reference model given each pixel's captured inputs
//! (`reference::Material::with_vertex_color`, `reference::transformed_uv`,
//! `reference::Material::unlit_color`); and Bevy's `Lightmap` on a Phong mesh compared with
//! `StandardMaterial`'s picture of it.
//!
//! The maps and the texel-edge rule are `texture_maps`'s: the UVs a pixel's maps were
//! sampled at are computed in `f64` from its captured UV, and pixels within 1/100 texel of
//! a texel's edge there are left out (the device moves the UV in `f32`, a few units of
//! rounding away). Tolerance: the frame tests' ([`TOLERANCE`]); the vertex color adds one
//! `f32` product to `k_d`.

use crate::frames::{SIZE, TOLERANCE};
use crate::shading_normals::tangent_sphere;
use crate::texture_maps::{
    SrgbDecoding, assert_follows_the_reference, float_map, lit_color, loaded_images, normal_map,
    spawn_map_lights, texel_at, texels_at,
};
use bevy::{
    camera::Exposure,
    math::Affine2,
    mesh::{UvChannel, VertexAttributeValues},
    pbr::Lightmap,
    prelude::*,
};
use bevy_phong::{BevyLightExposure, prelude::*};
use bevy_phong_headless::Harness;

/// A value in `[0, 1]` that varies smoothly along `x`.
fn wave(x: f32) -> f32 {
    0.5 + 0.5 * (3.0 * x).sin()
}

/// `mesh` with a color at each vertex that varies with its position: RGB in `[0.3, 1]`,
/// alpha in `[0, 1]`.
pub(crate) fn with_vertex_colors(mut mesh: Mesh) -> Mesh {
    let positions = mesh
        .attribute(Mesh::ATTRIBUTE_POSITION)
        .and_then(|positions| positions.as_float3())
        .expect("a mesh with positions")
        .to_vec();
    let colors: Vec<[f32; 4]> = positions
        .iter()
        .map(|&[x, y, z]| {
            let channel = |value: f32| 0.3 + 0.7 * wave(value);
            [
                channel(x),
                channel(y + 0.4),
                channel(z - 0.7),
                wave(x + y + z),
            ]
        })
        .collect();
    mesh.insert_attribute(Mesh::ATTRIBUTE_COLOR, colors);
    mesh
}

/// A base color map of stripes, every texel opaque.
fn stripes() -> Image {
    float_map(|x, y| {
        let level = 0.2 + 0.2 * ((x + 2 * y) % 5) as f32;
        [level, 1.2 - level, 0.5, 1.0]
    })
}

#[test]
fn vertex_colors_and_the_uv_transform_follow_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let mut images = world.resource_mut::<Assets<Image>>();
    let base_color = images.add(stripes());
    let normals = images.add(normal_map());
    // Scaled, turned and moved: most of the sphere samples outside [0, 1], where the maps
    // clamp to their edge.
    let moved =
        Affine2::from_scale_angle_translation(Vec2::new(1.7, 0.6), 0.4, Vec2::new(0.3, -0.2));
    let colored_and_moved = PhongMaterial {
        base_color_texture: Some(base_color.clone()),
        normal_map_texture: Some(normals),
        uv_transform: moved,
        shininess: 40.0,
        ..default()
    };
    // The vertex colors' alpha cuts holes; the map is turned a quarter and shrunk.
    let masked = PhongMaterial {
        base_color_texture: Some(base_color),
        alpha_mode: AlphaMode::Mask(0.5),
        uv_transform: Affine2::from_scale_angle_translation(
            Vec2::splat(0.5),
            core::f32::consts::FRAC_PI_2,
            Vec2::new(0.5, 0.25),
        ),
        emissive: LinearRgba::rgb(0.05, 0.1, 0.05),
        ..default()
    };
    // Vertex colors alone, and a UV transform with no map to move.
    let colored = PhongMaterial {
        base_color: Color::srgb(0.9, 0.8, 1.0),
        uv_transform: moved,
        ..default()
    };
    let objects = [
        (
            with_vertex_colors(tangent_sphere(1.2)),
            Transform::from_xyz(0.0, 0.0, 0.0),
            colored_and_moved,
        ),
        (
            with_vertex_colors(Cuboid::new(1.2, 1.2, 1.2).into()),
            Transform::from_xyz(-2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(0.6)),
            masked,
        ),
        (
            with_vertex_colors(Cuboid::new(1.2, 1.2, 1.2).into()),
            Transform::from_xyz(2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(-0.6)),
            colored,
        ),
    ];
    assert_follows_the_reference(harness, objects, "vertex colors and the UV transform");
}

/// An unlit surface shows `k_d` (with its vertex colors and map) whatever the lights, which
/// are there to be ignored, and without its emissive color, which is there to be left out.
#[test]
fn unlit_materials_show_their_base_colors_only() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let base_color = world.resource_mut::<Assets<Image>>().add(stripes());
    let objects = [
        (
            with_vertex_colors(Sphere::new(1.2).mesh().uv(48, 32)),
            Transform::from_xyz(0.0, 0.0, 0.0),
            PhongMaterial {
                base_color: Color::srgb(0.9, 0.7, 1.0),
                base_color_texture: Some(base_color),
                emissive: LinearRgba::rgb(0.1, 0.05, 0.0),
                unlit: true,
                ..default()
            },
        ),
        (
            Cuboid::new(1.2, 1.2, 1.2).into(),
            Transform::from_xyz(-2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(0.6)),
            PhongMaterial {
                base_color: Color::srgb(0.3, 0.6, 0.2),
                unlit: true,
                ..default()
            },
        ),
        // Lit, beside them.
        (
            Cuboid::new(1.2, 1.2, 1.2).into(),
            Transform::from_xyz(2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(-0.6)),
            PhongMaterial::from(Color::srgb(0.3, 0.6, 0.2)),
        ),
    ];
    assert_follows_the_reference(harness, objects, "unlit materials");
}

/// `mesh` with a second UV set: its first, turned a quarter and shrunk into the middle.
pub(crate) fn with_second_uvs(mut mesh: Mesh) -> Mesh {
    let uvs = mesh
        .attribute(Mesh::ATTRIBUTE_UV_0)
        .and_then(|uvs| match uvs {
            VertexAttributeValues::Float32x2(uvs) => Some(uvs.clone()),
            _ => None,
        })
        .expect("a mesh with UVs");
    let second: Vec<[f32; 2]> = uvs
        .iter()
        .map(|&[u, v]| [0.9 - 0.8 * v, 0.1 + 0.8 * u])
        .collect();
    mesh.insert_attribute(Mesh::ATTRIBUTE_UV_1, second);
    mesh
}

/// Light maps add their light to the ambient light and AO maps scale both, on either UV
/// set (the first moved by the UV transform), as the reference model says on each pixel's
/// texels (`reference::shade_baked`).
#[test]
fn light_and_ao_maps_follow_the_reference_model() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    world.insert_resource(PhongAmbientLight {
        color: Color::srgb(0.35, 0.35, 0.4),
    });
    let mut images = world.resource_mut::<Assets<Image>>();
    let base_color = images.add(stripes());
    let light_map = images.add(float_map(|x, y| {
        let level = 0.1 + 0.2 * ((3 * x + y) % 4) as f32;
        [level, 0.8 - level, 0.4, 1.0]
    }));
    let ao_map = images.add(float_map(|x, y| {
        [0.2 + 0.25 * ((x + 3 * y) % 4) as f32, 0.0, 0.0, 1.0]
    }));
    let objects = [
        (
            with_second_uvs(Sphere::new(1.2).mesh().uv(48, 32)),
            Transform::from_xyz(0.0, 0.0, 0.0),
            PhongMaterial {
                base_color_texture: Some(base_color),
                light_map_texture: Some(light_map.clone()),
                light_map_intensity: 1.5,
                ao_map_texture: Some(ao_map.clone()),
                ao_map_intensity: 0.8,
                uv_transform: Affine2::from_scale_angle_translation(
                    Vec2::new(1.3, 0.7),
                    0.2,
                    Vec2::new(-0.1, 0.2),
                ),
                ..default()
            },
        ),
        (
            with_second_uvs(Cuboid::new(1.2, 1.2, 1.2).into()),
            Transform::from_xyz(-2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(0.6)),
            PhongMaterial {
                base_color: Color::srgb(0.8, 0.7, 0.9),
                light_map_texture: Some(light_map),
                light_map_intensity: 0.5,
                light_map_channel: UvChannel::Uv0,
                ao_map_texture: Some(ao_map),
                ao_map_channel: UvChannel::Uv1,
                ..default()
            },
        ),
    ];
    assert_follows_the_reference(harness, objects, "light and AO maps");
}

/// Bevy's `Lightmap` component lights a Phong mesh as it lights a `StandardMaterial` one:
/// its texture, read at the second UV set mapped into its UV rectangle (whose corners Bevy
/// packs into 16-bit fractions), times the material's light map intensity, adds to the
/// ambient light, and the AO map darkens it.
#[test]
fn bevys_lightmap_component_adds_its_light_as_a_light_map() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let mut images = world.resource_mut::<Assets<Image>>();
    let baked = images.add(float_map(|x, y| {
        let level = 0.15 + 0.2 * ((x + 3 * y) % 4) as f32;
        [0.9 - level, level, 0.3, 1.0]
    }));
    let ao_map = images.add(float_map(|x, y| {
        [0.3 + 0.2 * ((2 * x + y) % 4) as f32, 0.0, 0.0, 1.0]
    }));
    let material = PhongMaterial {
        base_color: Color::srgb(0.8, 0.75, 0.9),
        light_map_intensity: 1.5,
        ao_map_texture: Some(ao_map),
        ..default()
    };
    let uv_rect = Rect::new(0.25, 0.1, 0.85, 0.7);
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(with_second_uvs(Sphere::new(1.2).mesh().uv(48, 32)));
    let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
    world.spawn((
        Mesh3d(mesh),
        MeshMaterial3d(material),
        Lightmap {
            image: baked.clone(),
            uv_rect,
            bicubic_sampling: false,
        },
    ));
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    let lights = harness.reference_lights();
    let images = loaded_images(&mut harness);
    // Bevy packs each corner coordinate into a 16-bit unsigned fraction.
    let packed = |value: f32| (f64::from(value) * 65535.0).round() / 65535.0;
    let (min, max) = (
        uv_rect.min.to_array().map(packed),
        uv_rect.max.to_array().map(packed),
    );
    let comparison = harness.compare_pixels(&rendered, &inputs, |material, surface, pixel| {
        let mut texels = texels_at(material, &inputs, pixel, &images, SrgbDecoding::Exact)?;
        let second = inputs.second_uvs.as_ref().unwrap().pixels[pixel];
        let uv = [0, 1].map(|axis| min[axis] + (max[axis] - min[axis]) * f64::from(second[axis]));
        let texel = texel_at(&images[&baked.id()], uv, SrgbDecoding::Exact)?;
        texels.light_map = Some(texel.truncate());
        lit_color(material, surface, pixel, &inputs, &texels, &images, &lights)
    });
    comparison.assert_within("Bevy's Lightmap", TOLERANCE);
    comparison.assert_mostly_judged("Bevy's Lightmap");
}

/// Bevy's `Lightmap` shows as bright on a Phong mesh as on a `StandardMaterial` one when the
/// Phong material's `light_map_intensity` carries Bevy's exposures
/// (`BevyLightExposure::light_map_intensity`): Bevy weighs the lightmap's texel by the
/// material's `lightmap_exposure` and the camera's exposure and multiplies it by the diffuse
/// color, without π; the crate by the intensity alone. The two apps draw the same sphere
/// with the same lightmap, no light and no ambient light, and agree pixel for pixel.
/// Tolerance: the frame tests' ([`TOLERANCE`]); the two compute the same product of
/// `f32`s in another order (a few units of rounding), and a conversion that left out a factor
/// (the exposure's 1/1.2, say) would differ by a fifth.
#[test]
fn a_bevy_lightmap_shows_on_phong_as_on_standard_material_with_its_exposures_carried() {
    /// Bevy's `lightmaps` example's `lightmap_exposure`.
    const LIGHTMAP_EXPOSURE: f32 = 250.0;
    /// The cameras' exposure value: not Bevy's default, so that it must be carried.
    const EV100: f32 = 8.0;
    let base_color = Color::srgb(0.8, 0.75, 0.9);
    let (mut standard, mut phong) = Harness::side_by_side(SIZE, SIZE, |_| {}, |_| {});
    let intensity = BevyLightExposure { ev100: EV100 }.light_map_intensity(LIGHTMAP_EXPOSURE);
    for (harness, is_phong) in [(&mut standard, false), (&mut phong, true)] {
        harness.camera_mut().insert(Exposure { ev100: EV100 });
        let world = harness.world_mut();
        world.insert_resource(GlobalAmbientLight {
            brightness: 0.0,
            ..default()
        });
        world.insert_resource(PhongAmbientLight {
            color: Color::BLACK,
        });
        let baked = world.resource_mut::<Assets<Image>>().add(float_map(|x, y| {
            let level = 0.15 + 0.2 * ((x + 3 * y) % 4) as f32;
            [0.9 - level, level, 0.3, 1.0]
        }));
        let lightmap = Lightmap {
            image: baked,
            uv_rect: Rect::new(0.25, 0.1, 0.85, 0.7),
            bicubic_sampling: false,
        };
        let mesh = world
            .resource_mut::<Assets<Mesh>>()
            .add(with_second_uvs(Sphere::new(1.2).mesh().uv(48, 32)));
        let object = (Mesh3d(mesh), lightmap);
        if is_phong {
            spawn_with_material(
                world,
                object,
                PhongMaterial {
                    base_color,
                    light_map_intensity: intensity,
                    ..default()
                },
            );
        } else {
            spawn_with_material(
                world,
                object,
                StandardMaterial {
                    base_color,
                    lightmap_exposure: LIGHTMAP_EXPOSURE,
                    ..default()
                },
            );
        }
        harness.settle();
    }
    let bevy = standard.render_next_frame();
    let crate_render = phong.render_next_frame();
    let mut largest: f64 = 0.0;
    let mut lit = 0;
    for (bevy, phong) in bevy.pixels.iter().zip(&crate_render.pixels) {
        if bevy[3] <= 0.0 && phong[3] <= 0.0 {
            continue;
        }
        if bevy[..3].iter().any(|&channel| channel > 0.01) {
            lit += 1;
        }
        for channel in 0..3 {
            largest = largest.max(f64::from((bevy[channel] - phong[channel]).abs()));
        }
    }
    println!(
        "Bevy's Lightmap on StandardMaterial and on PhongMaterial: {lit} lit pixels, largest \
         difference {largest:.3e}"
    );
    // The sphere covers about 2,000 pixels of the frame, nearly all lit by the lightmap.
    assert!(
        lit > (SIZE * SIZE / 16) as usize,
        "the sphere shows its lightmap on only {lit} pixels"
    );
    assert!(
        largest <= TOLERANCE,
        "PhongMaterial with light_map_intensity {intensity} differs from StandardMaterial with \
         lightmap_exposure {LIGHTMAP_EXPOSURE} under EV100 {EV100} by up to {largest:.3e} \
         (tolerance {TOLERANCE:e})"
    );
}

/// Spawns `object` drawn with `material` (added to its assets).
fn spawn_with_material<M: Material>(world: &mut World, object: impl Bundle, material: M) {
    let material = world.resource_mut::<Assets<M>>().add(material);
    world.spawn((object, MeshMaterial3d(material)));
}

/// An alpha map's green channel multiplies the output alpha, and with a mask cuts holes
/// where the product falls below the cutoff (its other channels are ignored: the red and
/// alpha here would keep every texel).
#[test]
fn an_alpha_map_cuts_holes_by_its_green_channel() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let mut images = world.resource_mut::<Assets<Image>>();
    let base_color = images.add(stripes());
    let alpha_map = images.add(float_map(|x, y| {
        [1.0, 0.1 + 0.3 * ((x + 2 * y) % 4) as f32, 0.0, 1.0]
    }));
    let masked = PhongMaterial {
        base_color_texture: Some(base_color),
        alpha_map_texture: Some(alpha_map),
        alpha_mode: AlphaMode::Mask(0.45),
        uv_transform: Affine2::from_angle(0.3),
        ..default()
    };
    let objects = [
        (
            Sphere::new(1.2).mesh().uv(48, 32),
            Transform::from_xyz(0.0, 0.0, 0.0),
            masked.clone(),
        ),
        (
            with_vertex_colors(Cuboid::new(1.2, 1.2, 1.2).into()),
            Transform::from_xyz(-2.4, -0.3, 0.5).with_rotation(Quat::from_rotation_y(0.6)),
            masked,
        ),
    ];
    assert_follows_the_reference(harness, objects, "an alpha map");
}
