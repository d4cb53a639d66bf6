//! Every float of a light, the ambient light and a material is brought into its documented
//! range ([`crate::limits`]), with a warning naming the field; the light buffer and the
//! material uniform never hold a non-finite value or one above the bound.

use super::PhongLightBuffer;
use crate::{
    Decay, PhongAmbientLight, PhongDirectionalLight, PhongHemisphereLight, PhongMaterial,
    PhongPointLight, PhongSpotLight, limits,
    material::PhongMaterialUniform,
    reference,
    test_app::{invalid_inputs, test_app, uploads_in_next_frame},
    validation::{InvalidInput, Owner},
};
use bevy::{
    asset::Assets,
    color::{Alpha, Color, ColorToComponents},
    math::{Quat, Vec3},
    prelude::Transform,
};
use core::f32::consts::PI;

/// The fields `owner`'s warnings name, in order.
fn fields_of(warnings: &[InvalidInput], owner: Owner) -> Vec<&'static str> {
    warnings
        .iter()
        .filter(|warning| warning.owner == owner)
        .map(|warning| warning.field)
        .collect()
}

/// Every float of every record in the light buffer.
fn record_floats(app: &bevy::app::App) -> Vec<f32> {
    let buffer = app.world().resource::<PhongLightBuffer>();
    buffer
        .records()
        .iter()
        .flat_map(|record| bytemuck::cast::<_, [f32; 20]>(*record))
        .collect()
}

#[test]
fn huge_finite_light_values_are_clamped_to_the_bound_with_one_warning_each() {
    let mut app = test_app(|_| {});
    let light = app
        .world_mut()
        .spawn((
            PhongPointLight {
                color: Color::linear_rgb(f32::MAX, 0.5, 2e38),
                specular: Some(Color::linear_rgb(f32::INFINITY, 1e7, 0.0)),
                decay: Decay::new(1.0, f32::MAX, f32::INFINITY),
                ..Default::default()
            },
            Transform::from_xyz(0.0, 2.0, 0.0),
        ))
        .id();
    app.world_mut().resource_mut::<PhongAmbientLight>().color = Color::linear_rgb(3e38, 0.0, 0.0);
    app.update();
    let warnings = invalid_inputs(&mut app);
    assert_eq!(
        fields_of(&warnings, Owner::Entity(light)),
        ["color", "specular", "decay.linear", "decay.quadratic"],
        "{warnings:#?}"
    );
    assert_eq!(fields_of(&warnings, Owner::Resource), ["color"]);
    // The values are quoted whole, extreme ones in exponent form.
    let color = warnings
        .iter()
        .find(|w| w.owner == Owner::Entity(light) && w.field == "color")
        .unwrap();
    assert_eq!(color.value, "Linear(3.4028235e38, 0.5, 2e38, alpha 1.0)");
    assert_eq!(
        color.replacement,
        "Linear(1000000.0, 0.5, 1000000.0, alpha 1.0)"
    );
    let point = app.world().get::<PhongPointLight>(light).unwrap();
    assert_eq!(
        point.color.to_linear().to_vec3(),
        Vec3::new(limits::MAX_INTENSITY, 0.5, limits::MAX_INTENSITY)
    );
    assert_eq!(
        point.specular.unwrap().to_linear().to_vec3(),
        Vec3::new(limits::MAX_INTENSITY, 1e6, 0.0)
    );
    assert_eq!(point.decay, Decay::new(1.0, 1e6, 1e6));
    let header = *app.world().resource::<PhongLightBuffer>().header();
    assert_eq!(header.ambient, [1e6, 0.0, 0.0]);
    // Exactly at or below the bound (no tolerance: clamping is exact), and finite; the
    // unlimited range is stored as f32::MAX, the one value above it.
    let floats = record_floats(&app);
    assert!(floats.iter().all(|f| f.is_finite()), "{floats:?}");
    let largest = floats
        .iter()
        .filter(|f| **f != f32::MAX)
        .fold(0.0f32, |a, b| a.max(*b));
    assert_eq!(largest, limits::MAX_INTENSITY);
}

#[test]
fn an_infinite_or_huge_spot_angle_is_reported_and_clamped_to_180_degrees() {
    let mut app = test_app(|_| {});
    let infinite = app
        .world_mut()
        .spawn(PhongSpotLight {
            outer_angle: f32::INFINITY,
            exponent: 3e38,
            ..Default::default()
        })
        .id();
    let huge = app
        .world_mut()
        .spawn(PhongSpotLight {
            inner_angle: 1e9_f32.to_radians(),
            outer_angle: 1e9_f32.to_radians(),
            ..Default::default()
        })
        .id();
    app.update();
    let warnings = invalid_inputs(&mut app);
    let of = |entity| fields_of(&warnings, Owner::Entity(entity));
    assert_eq!(of(infinite), ["outer_angle", "exponent"], "{warnings:#?}");
    assert_eq!(of(huge), ["inner_angle", "outer_angle"], "{warnings:#?}");
    let text = warnings
        .iter()
        .find(|w| w.owner == Owner::Entity(infinite))
        .unwrap()
        .to_string();
    assert!(text.contains("PhongSpotLight.outer_angle = inf"), "{text}");
    assert!(
        text.ends_with("using 3.1415927 (allowed: 0 to 3.1415927)"),
        "{text}"
    );
    for entity in [infinite, huge] {
        let spot = app.world().get::<PhongSpotLight>(entity).unwrap();
        assert_eq!(spot.outer_angle, PI);
    }
    let spot = app.world().get::<PhongSpotLight>(infinite).unwrap();
    assert_eq!(spot.exponent, limits::MAX_EXPONENT);
    assert!(record_floats(&app).iter().all(|f| f.is_finite()));
}

#[test]
fn a_nan_alpha_does_not_survive_sanitising() {
    let mut app = test_app(|_| {});
    let light = app
        .world_mut()
        .spawn(PhongDirectionalLight {
            color: Color::srgba(1.0, 0.5, 0.25, f32::NAN),
            ..Default::default()
        })
        .id();
    app.world_mut().resource_mut::<PhongAmbientLight>().color =
        Color::srgba(0.1, 0.1, 0.1, f32::NAN);
    app.update();
    let warnings = invalid_inputs(&mut app);
    assert_eq!(fields_of(&warnings, Owner::Entity(light)), ["color"]);
    assert_eq!(fields_of(&warnings, Owner::Resource), ["color"]);
    let color = app
        .world()
        .get::<PhongDirectionalLight>(light)
        .unwrap()
        .color;
    assert_eq!(color.alpha(), 1.0);
    assert_eq!(
        app.world().resource::<PhongAmbientLight>().color.alpha(),
        1.0
    );
}

#[test]
fn a_hemisphere_light_gets_finite_colors_and_an_up_with_a_direction() {
    let mut app = test_app(|_| {});
    app.world_mut().insert_resource(PhongHemisphereLight {
        sky_color: Color::linear_rgb(f32::NAN, 0.5, 3e38),
        ground_color: Color::linear_rgb(0.1, 0.2, 0.3),
        up: Vec3::ZERO,
    });
    app.update();
    let warnings = invalid_inputs(&mut app);
    assert_eq!(fields_of(&warnings, Owner::Resource), ["sky_color", "up"]);
    let hemisphere = app.world().resource::<PhongHemisphereLight>();
    assert_eq!(hemisphere.up, Vec3::Y);
    assert!(
        hemisphere
            .sky_color
            .to_linear()
            .to_vec3()
            .cmple(Vec3::splat(limits::MAX_INTENSITY))
            .all()
    );
    let header = app.world().resource::<PhongLightBuffer>().header();
    assert!(header.ambient.iter().all(|channel| channel.is_finite()));
    assert_eq!(header.hemisphere_up, [0.0, 1.0, 0.0]);
}

/// A material with every float invalid in some way.
fn hostile_material() -> PhongMaterial {
    PhongMaterial {
        base_color: Color::srgba(f32::MAX, f32::NAN, -1.0, f32::NAN),
        ambient_factor: f32::INFINITY,
        specular_color: Color::linear_rgba(3e38, 1e7, 0.5, 2.0),
        specular_strength: f32::MAX,
        shininess: f32::NEG_INFINITY,
        emissive: bevy::color::LinearRgba::new(f32::NAN, 2e38, 1.0, 1.0),
        alpha_mode: bevy::prelude::AlphaMode::Mask(f32::NAN),
        ..Default::default()
    }
}

#[test]
fn validation_the_uniform_and_the_reference_apply_the_same_material_ranges() {
    let raw = hostile_material();
    let ((mut app, _handle), fields, sanitised) = validated(&raw);
    assert_eq!(
        fields,
        [
            "base_color",
            "ambient_factor",
            "specular_color",
            "specular_strength",
            "shininess",
            "emissive",
            "alpha_mode"
        ]
    );
    // The uniform of the raw material (what a frame drawn before validation would use)
    // equals the uniform of the sanitised one, and the reference model reads both the same.
    let uniform = PhongMaterialUniform::from(&raw);
    assert_eq!(uniform, PhongMaterialUniform::from(&sanitised));
    assert_eq!(
        reference::Material::from(&raw),
        reference::Material::from(&sanitised)
    );
    // Base color: an sRGB channel of f32::MAX overflows when decoded to linear: +∞, then
    // clamped to the bound.
    assert_eq!(uniform.base_color.to_array(), [1e6, 0.0, 0.0, 1.0]);
    assert_eq!(uniform.specular.to_array(), [1e12, 1e12, 0.5e6]);
    assert_eq!(
        (
            uniform.shininess,
            uniform.ambient_factor,
            uniform.alpha_cutoff
        ),
        (0.0, 1e6, 0.5)
    );
    assert_eq!(uniform.emissive.to_array(), [0.0, 1e6, 1.0]);
    // Validation runs once: a second frame finds nothing new.
    app.update();
    assert!(invalid_inputs(&mut app).is_empty());
}

/// A transform that points -Z along `direction` and scales by `scale`.
fn aimed(direction: Vec3, scale: f32) -> Transform {
    Transform {
        rotation: Quat::from_rotation_arc(Vec3::NEG_Z, direction.normalize()),
        scale: Vec3::splat(scale),
        ..Default::default()
    }
}

#[test]
fn a_light_direction_of_any_scale_points_where_its_transform_says() {
    let mut app = test_app(|_| {});
    let diagonal = Vec3::new(1.0, -1.0, 1.0).normalize();
    // With a scale of 3e38 the squared length of the direction overflows f32; with 1e-30
    // it underflows to zero. Both must still point along `diagonal`.
    for scale in [3e38, 1e-30, 1.0] {
        app.world_mut()
            .spawn((PhongDirectionalLight::default(), aimed(diagonal, scale)));
    }
    app.update();
    let records = app
        .world()
        .resource::<PhongLightBuffer>()
        .records()
        .to_vec();
    assert_eq!(records.len(), 3);
    for record in records {
        let direction = Vec3::from_array(record.direction);
        // Rotation and normalization each round to a few f32 ulps.
        assert!(
            direction.abs_diff_eq(diagonal, 1e-6),
            "{direction} instead of {diagonal}"
        );
    }
}

#[test]
fn the_stylized_modes_numbers_are_brought_into_their_ranges() {
    let raw = PhongMaterial {
        diffuse_mode: crate::DiffuseMode::Toon {
            bands: 0,
            smoothing: 2.0,
        },
        specular_mode: crate::SpecularMode::Toon {
            smoothing: f32::NAN,
        },
        ..PhongMaterial::default()
    };
    let (_, fields, sanitised) = validated(&raw);
    assert_eq!(fields, ["diffuse_mode", "diffuse_mode", "specular_mode"]);
    assert_eq!(
        sanitised.diffuse_mode,
        crate::DiffuseMode::Toon {
            bands: 1,
            smoothing: 1.0
        }
    );
    assert_eq!(
        sanitised.specular_mode,
        crate::SpecularMode::Toon { smoothing: 0.0 }
    );
    assert_eq!(
        PhongMaterialUniform::from(&raw),
        PhongMaterialUniform::from(&sanitised)
    );
    assert_eq!(
        reference::Material::from(&raw),
        reference::Material::from(&sanitised)
    );
}

/// Validates `raw` in a test app: the app and the material's handle (which keeps it alive),
/// the fields warned about, and the material as validation left it.
fn validated(
    raw: &PhongMaterial,
) -> (
    (bevy::app::App, bevy::asset::Handle<PhongMaterial>),
    Vec<&'static str>,
    PhongMaterial,
) {
    let mut app = test_app(|_| {});
    // The handle is kept: the asset lives as long as it.
    let handle = app
        .world_mut()
        .resource_mut::<Assets<PhongMaterial>>()
        .add(raw.clone());
    // The asset's `Added` event is sent at the end of the first frame, read in the second.
    app.update();
    app.update();
    let warnings = invalid_inputs(&mut app);
    let fields = fields_of(&warnings, Owner::Material(handle.id()));
    let sanitised = app
        .world()
        .resource::<Assets<PhongMaterial>>()
        .get(&handle)
        .expect("the validated material")
        .clone();
    ((app, handle), fields, sanitised)
}

#[test]
fn an_invalid_light_is_sanitised_once_with_a_warning_naming_entity_and_field() {
    let mut app = test_app(|_| {});
    let good = app
        .world_mut()
        .spawn((
            PhongPointLight::default(),
            Transform::from_xyz(0.0, 2.0, 0.0),
        ))
        .id();
    let bad = app
        .world_mut()
        .spawn((
            PhongPointLight {
                color: Color::linear_rgb(f32::NAN, 0.5, -1.0),
                range: Some(-3.0),
                decay: Decay::new(1.0, -0.5, 0.1),
                ..Default::default()
            },
            Transform::from_xyz(1.0, 2.0, 0.0),
        ))
        .id();
    app.update();
    let warnings = invalid_inputs(&mut app);
    let fields: Vec<_> = warnings
        .iter()
        .map(|w| (w.owner.clone(), w.field))
        .collect();
    assert_eq!(
        fields,
        [
            (Owner::Entity(bad), "color"),
            (Owner::Entity(bad), "decay.linear"),
            (Owner::Entity(bad), "range"),
        ]
    );
    let text = warnings[2].to_string();
    assert!(text.contains(&format!("entity {bad}")) && text.contains("PhongPointLight.range = -3"));

    let light = app.world().get::<PhongPointLight>(bad).unwrap();
    assert_eq!(light.color.to_linear().to_vec3(), Vec3::new(0.0, 0.5, 0.0));
    assert_eq!((light.range, light.decay.linear), (None, 0.0));

    // Both lights are in the buffer, with finite values.
    let state = app.world().resource::<PhongLightBuffer>();
    assert_eq!(state.header().light_count(), 2);
    assert!(
        state
            .records()
            .iter()
            .all(|r| r.color.iter().all(|c| c.is_finite()))
    );

    // Once: no new warning and no new upload while nothing changes.
    assert_eq!(uploads_in_next_frame(&mut app), 0);
    assert!(invalid_inputs(&mut app).is_empty());
    let _ = good;
}

#[test]
fn a_light_with_a_nan_position_is_skipped_and_others_stay() {
    let mut app = test_app(|_| {});
    app.world_mut().spawn(PhongPointLight::default());
    let bad = app
        .world_mut()
        .spawn((
            PhongPointLight::default(),
            Transform::from_xyz(f32::NAN, 0.0, 0.0),
        ))
        .id();
    app.update();
    let warnings = invalid_inputs(&mut app);
    assert_eq!(warnings.len(), 1);
    assert_eq!(
        (warnings[0].owner.clone(), warnings[0].field),
        (Owner::Entity(bad), "GlobalTransform")
    );
    assert_eq!(
        app.world()
            .resource::<PhongLightBuffer>()
            .header()
            .local_count,
        1
    );
}
