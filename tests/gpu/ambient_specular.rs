//! The ambient specular term (`PhongMaterial::ambient_specular`, SPEC.md "Ambient
//! specular"): materials converted from `StandardMaterial`, metals and dielectrics from rough
//! to smooth, under a bright ambient and hemisphere light (and one directional light), each
//! pixel against the reference model. Tolerance: the frame tests' ([`TOLERANCE`]): the term
//! adds a polynomial of a few `f32` operations, below the highlights' rounding.

use crate::frames::SIZE;
use crate::shading_normals::tangent_sphere;
use crate::texture_maps::assert_follows_the_reference;
use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;

#[test]
fn the_ambient_light_is_reflected_by_the_specular_color_as_the_reference_model_says() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    world.insert_resource(PhongAmbientLight {
        color: Color::linear_rgb(0.6, 0.6, 0.7),
    });
    world.insert_resource(PhongHemisphereLight {
        sky_color: Color::linear_rgb(0.5, 0.6, 0.9),
        ground_color: Color::linear_rgb(0.3, 0.2, 0.1),
        up: Vec3::new(0.2, 1.0, -0.1),
    });
    world.spawn((
        PhongDirectionalLight {
            color: Color::linear_rgb(0.4, 0.4, 0.35),
            ..default()
        },
        Transform::from_xyz(1.0, 2.0, 1.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    let gold = Color::linear_rgb(1.0, 0.78, 0.34);
    // (base color, metallic, perceptual roughness, reflectance): the blue dielectric's
    // F₀ = 0.16 · 0.1² = 0.0016 is below Bevy's specular occlusion's threshold.
    let surfaces = [
        (gold, 1.0, 0.35, 0.5),
        (gold, 1.0, 0.9, 0.5),
        (Color::linear_rgb(0.95, 0.93, 0.88), 1.0, 0.6, 0.5),
        (Color::linear_rgb(0.8, 0.1, 0.1), 0.0, 0.3, 0.5),
        (Color::linear_rgb(0.1, 0.4, 0.8), 0.0, 1.0, 0.1),
        (Color::linear_rgb(0.5, 0.5, 0.5), 0.5, 0.5, 0.5),
    ];
    let objects = surfaces.into_iter().enumerate().map(
        |(index, (base_color, metallic, perceptual_roughness, reflectance))| {
            let material = PhongMaterial::from(&StandardMaterial {
                base_color,
                metallic,
                perceptual_roughness,
                reflectance,
                ..default()
            });
            assert!(material.ambient_specular);
            let (column, row) = ((index % 3) as f32, (index / 3) as f32);
            (
                tangent_sphere(0.7),
                Transform::from_xyz(1.5 * column - 1.5, 0.8 - 1.6 * row, 0.0),
                material,
            )
        },
    );
    assert_follows_the_reference(harness, objects, "ambient specular");
}
