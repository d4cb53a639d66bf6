//! Input validation: invalid values in light components, the ambient light and
//! [`PhongMaterial`]s are replaced by documented values once, when they
//! change, with one warning that names the entity (or asset) and the field.
//!
//! Every float has a range ([`crate::limits`]); NaN takes the range's fallback and anything
//! else outside it is clamped, `±∞` included. The upper bounds keep every sum the shader
//! forms finite (see [`crate::limits`] for the arithmetic).
//!
//! | field | range | NaN becomes | outside the range |
//! |---|---|---|---|
//! | any light color channel, the ambient light's, the hemisphere light's | 0 to 1e6, linear RGB | `0` | clamped |
//! | `Decay` coefficients | 0 to 1e6 | `0` | clamped (a `Decay` of all zeros does not fade) |
//! | `range` | above 0; `∞` means unlimited | `None` (unlimited) | `≤ 0`: `None` |
//! | spot `inner_angle`, `outer_angle` | 0 to π radians (0° to 180°) | `0` (an outer angle of 0 lights nothing) | clamped |
//! | spot `inner_angle` | at most `outer_angle` | | `outer_angle` (a hard edge) |
//! | spot `exponent` | 0 to 1e6 | `0` | clamped |
//! | a light's `shadows` and `cascades` | each field's documented range | its default | clamped |
//! | a light's transform | finite translation and rotation | the light is skipped while it lasts | |
//!
//! A material's numbers, each named as [`PhongMaterial`]'s field (one walk over them is
//! shared by validation, the material's uniform and the reference model):
//!
//! | field | range | NaN becomes | outside the range |
//! |---|---|---|---|
//! | `base_color`, `specular_color`, `emissive`, `rim_color` | channels 0 to 1e6 (linear RGB), alpha 0 to 1 | `0`, alpha `1` | clamped |
//! | `ambient_factor`, `specular_strength`, `rim_strength`, `light_map_intensity`, `ao_map_intensity` | 0 to 1e6 | `0` | clamped |
//! | `shininess`, `rim_power` | 0 to 1e6 | `0` | clamped |
//! | `diffuse_mode` | wrap and smoothing 0 to 1, toon bands 1 to 256 | `0` (bands: none is NaN) | clamped |
//! | `specular_mode` | toon smoothing 0 to 1 | `0` | clamped |
//! | `alpha_mode` | a `Mask` cutoff 0 to 1 | `0.5` | clamped |
//! | `bump_scale`, `displacement_scale`, `displacement_bias` | -1e6 to 1e6 | `0` | clamped |
//! | `normal_map_scale` (each of x and y) | -1e6 to 1e6 | `1` | clamped |
//! | `uv_transform` | every number finite | the identity | the identity |
//! | `depth_bias` | what wgpu's `i32` holds (±2.1e9) | `0` | clamped |
//! | `reflectivity` | 0 to 1 | `0` | clamped |
//! | `refraction_ratio` | 0 to 1e6 | `1` | clamped |
//! | `metallic` | 0 to 1 | `0` | clamped |
//! | `perceptual_roughness` | 0 to 1 | `0.5` | clamped |
//!
//! Each replacement is also sent as an [`InvalidInput`] message, for tools and tests. Its
//! value is quoted at most 80 characters long.

mod map_checks;

use crate::{
    lights::{Decay, PhongAmbientLight, PhongCascades, PhongHemisphereLight, PhongShadows},
    limits::{self, Limits},
    material::{NumberVisitor, PhongMaterial, visit_color, visit_numbers},
    quoting::bounded,
};
use bevy::{
    asset::{AssetEvent, AssetId, Assets},
    color::{Color, LinearRgba},
    ecs::{
        change_detection::{DetectChanges, DetectChangesMut},
        entity::Entity,
        message::{Message, MessageReader, MessageWriter},
        system::ResMut,
    },
    log::warn,
    math::{Affine2, Vec3},
};
use core::fmt;
pub(crate) use map_checks::check_metallic_roughness_maps;

/// What was invalid and what replaced it; also logged as a warning.
#[derive(Message, Clone, Debug, PartialEq)]
pub struct InvalidInput {
    /// Whose field it is.
    pub owner: Owner,
    /// The type that holds the field, e.g. `PhongPointLight`.
    pub component: &'static str,
    /// The field, e.g. `range`.
    pub field: &'static str,
    /// The invalid value, as written (at most 80 characters of it, then its length).
    pub value: String,
    /// What the crate uses instead.
    pub replacement: String,
}

/// The holder of an invalid field.
#[derive(Clone, Debug, PartialEq)]
pub enum Owner {
    /// An entity: a light, or a camera (its Bevy `AmbientLight`).
    Entity(Entity),
    /// A material asset.
    Material(AssetId<PhongMaterial>),
    /// A resource (the ambient or hemisphere light, Bevy's `GlobalAmbientLight`): the
    /// component names which.
    Resource,
}

impl fmt::Display for InvalidInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let owner = match &self.owner {
            Owner::Entity(entity) => format!("entity {entity}"),
            Owner::Material(id) => format!("material {id}"),
            Owner::Resource => "resource".to_string(),
        };
        write!(
            f,
            "{owner}: {}.{} = {} is invalid; using {}",
            self.component, self.field, self.value, self.replacement
        )
    }
}

/// Collects the replacements made in one light component or material asset: each invalid
/// field is replaced by a valid value and reported, as a warning and an [`InvalidInput`]
/// message naming the owner and the field. A light kind's
/// [`PhongLightKind::validate`](crate::extension::PhongLightKind::validate) is given one.
pub struct Checker {
    owner: Owner,
    component: &'static str,
    found: Vec<InvalidInput>,
}

impl Checker {
    pub(crate) fn new(owner: Owner, component: &'static str) -> Self {
        Self {
            owner,
            component,
            found: Vec::new(),
        }
    }

    /// Reports that `field`, which was `value` (as written, for the warning), is now
    /// `replacement`: for a rule of the kind's own; the functions below apply the crate's.
    pub fn replace(&mut self, field: &'static str, value: String, replacement: String) {
        self.found.push(InvalidInput {
            owner: self.owner.clone(),
            component: self.component,
            field,
            value: bounded(&value),
            replacement,
        });
    }

    /// A light's color: each linear channel `0` to `1e6`, a NaN channel `0`, its alpha
    /// `0` to `1` (the rule of a material's colors).
    pub fn color(&mut self, field: &'static str, color: &mut Color) {
        visit_color(self, field, color);
    }

    /// A color as [`Self::color`] says, where there is one.
    pub fn optional_color(&mut self, field: &'static str, color: &mut Option<Color>) {
        if let Some(color) = color {
            self.color(field, color);
        }
    }

    /// A number within `allowed`: one outside it is clamped into it, NaN becomes `if_nan`.
    pub fn number(
        &mut self,
        field: &'static str,
        value: &mut f32,
        allowed: core::ops::RangeInclusive<f32>,
        if_nan: f32,
    ) {
        let limits = Limits::new(*allowed.start(), *allowed.end(), if_nan);
        self.scalar(field, value, limits);
    }

    /// A scalar in the range of `limits`.
    pub(crate) fn scalar(&mut self, field: &'static str, value: &mut f32, limits: Limits) {
        let fixed = limits.apply(*value);
        // NaN never equals itself: it is replaced.
        if fixed == *value {
            return;
        }
        // `{:?}` writes 3e38 as `3e38` where `{}` writes 39 digits.
        self.replace(
            field,
            format!("{value:?}"),
            format!("{fixed:?} (allowed: {limits})"),
        );
        *value = fixed;
    }

    /// Shadow settings in their ranges (those [`PhongShadows`] documents); a resolution
    /// within `[16, 4096]`.
    pub fn shadows(&mut self, shadows: &mut PhongShadows) {
        self.scalar(
            "shadows.depth_bias",
            &mut shadows.depth_bias,
            limits::SHADOW_BIAS,
        );
        self.scalar(
            "shadows.normal_bias",
            &mut shadows.normal_bias,
            limits::SHADOW_BIAS,
        );
        self.scalar(
            "shadows.softness",
            &mut shadows.softness,
            limits::SHADOW_SOFTNESS,
        );
        self.scalar(
            "shadows.near_distance",
            &mut shadows.near_distance,
            limits::SHADOW_NEAR,
        );
        self.scalar(
            "shadows.diffuse_in_shadow",
            &mut shadows.diffuse_in_shadow,
            limits::SHADOW_FRACTION,
        );
        self.scalar(
            "shadows.specular_in_shadow",
            &mut shadows.specular_in_shadow,
            limits::SHADOW_FRACTION,
        );
        let resolution = shadows
            .resolution
            .clamp(PhongShadows::MIN_RESOLUTION, PhongShadows::MAX_RESOLUTION);
        if resolution != shadows.resolution {
            self.replace(
                "shadows.resolution",
                shadows.resolution.to_string(),
                format!(
                    "{resolution} (allowed: {} to {})",
                    PhongShadows::MIN_RESOLUTION,
                    PhongShadows::MAX_RESOLUTION
                ),
            );
            shadows.resolution = resolution;
        }
    }

    /// Cascade settings in their ranges: 1 to 4 cascades, the first ending at or before the
    /// last.
    pub(crate) fn cascades(&mut self, cascades: &mut PhongCascades) {
        let count = cascades.count.clamp(1, PhongCascades::MAX_COUNT);
        if count != cascades.count {
            self.replace(
                "cascades.count",
                cascades.count.to_string(),
                format!("{count} (allowed: 1 to {})", PhongCascades::MAX_COUNT),
            );
            cascades.count = count;
        }
        self.scalar(
            "cascades.max_distance",
            &mut cascades.max_distance,
            limits::CASCADE_DISTANCE,
        );
        self.scalar(
            "cascades.first_far_bound",
            &mut cascades.first_far_bound,
            limits::CASCADE_DISTANCE,
        );
        self.at_most(
            "cascades.first_far_bound",
            &mut cascades.first_far_bound,
            ("max_distance", cascades.max_distance),
            "one cascade",
        );
        self.scalar(
            "cascades.overlap",
            &mut cascades.overlap,
            limits::CASCADE_OVERLAP,
        );
    }

    /// Each coefficient of a [`Decay`] `0` to `1e6`, NaN `0`.
    pub fn decay(&mut self, decay: &mut Decay) {
        self.scalar("decay.constant", &mut decay.constant, limits::DECAY);
        self.scalar("decay.linear", &mut decay.linear, limits::DECAY);
        self.scalar("decay.quadratic", &mut decay.quadratic, limits::DECAY);
    }

    /// Brings `value` (field `field`) down to `bound`, the value of another field `(name,
    /// value)`, where it is above it, reporting the replacement and what it means.
    pub(crate) fn at_most(
        &mut self,
        field: &'static str,
        value: &mut f32,
        (bound_field, bound): (&str, f32),
        meaning: &str,
    ) {
        if *value > bound {
            self.replace(
                field,
                format!("{value} (> {bound_field})"),
                format!("{bound} (= {bound_field}: {meaning})"),
            );
            *value = bound;
        }
    }

    /// A positive range, or `None` (infinity is taken as `None` without a warning).
    pub fn range(&mut self, range: &mut Option<f32>) {
        if let Some(value) = *range
            && !(value.is_finite() && value > 0.0)
        {
            // Infinity is a valid "unlimited"; say so without a warning.
            if value != f32::INFINITY {
                self.replace("range", value.to_string(), "None (unlimited)".into());
            }
            *range = None;
        }
    }

    /// Every number of a material, as [`visit_numbers`] lists them.
    fn material(&mut self, material: &mut PhongMaterial) {
        visit_numbers(material, self);
    }

    /// Logs and sends what was replaced.
    pub(crate) fn report(self, messages: &mut MessageWriter<InvalidInput>) {
        for invalid in self.found {
            warn!("{invalid}");
            messages.write(invalid);
        }
    }
}

/// Validation's walk over a material's numbers: each out of its range is replaced, with a
/// warning naming the field.
impl NumberVisitor for Checker {
    fn scalar(&mut self, field: &'static str, value: &mut f32, limits: Limits) {
        Checker::scalar(self, field, value, limits);
    }

    fn color(&mut self, field: &'static str, value: &mut LinearRgba) {
        let fixed = limits::linear_color(*value);
        // NaN never equals itself: a NaN channel is replaced.
        if fixed != *value {
            self.replace(field, color_text(*value), color_text(fixed));
            *value = fixed;
        }
    }

    fn count(&mut self, field: &'static str, value: &mut u32, max: u32) {
        let fixed = (*value).clamp(1, max);
        if fixed != *value {
            self.replace(
                field,
                format!("bands {value}"),
                format!("bands {fixed} (allowed: 1 to {max})"),
            );
            *value = fixed;
        }
    }

    fn uv_transform(&mut self, field: &'static str, value: &mut Affine2) {
        let fixed = limits::uv_transform(*value);
        if fixed != *value {
            self.replace(field, format!("{value:?}"), "the identity".into());
            *value = fixed;
        }
    }
}

/// `color` as a warning quotes it: `Linear(3.4028235e38, 0.5, 0.0, alpha NaN)`.
fn color_text(color: LinearRgba) -> String {
    let LinearRgba {
        red,
        green,
        blue,
        alpha,
    } = color;
    format!("Linear({red:?}, {green:?}, {blue:?}, alpha {alpha:?})")
}

/// Replaces an invalid ambient color when the resource changed.
pub fn validate_ambient_light(
    mut ambient: ResMut<PhongAmbientLight>,
    mut messages: MessageWriter<InvalidInput>,
) {
    if !ambient.is_changed() {
        return;
    }
    let mut checker = Checker::new(Owner::Resource, "PhongAmbientLight");
    checker.color("color", &mut ambient.bypass_change_detection().color);
    checker.report(&mut messages);
}

/// Replaces the hemisphere light's invalid colors and an `up` without a direction (by `+Y`)
/// when the resource was inserted or changed.
pub fn validate_hemisphere_light(
    hemisphere: Option<ResMut<PhongHemisphereLight>>,
    mut messages: MessageWriter<InvalidInput>,
) {
    let Some(mut hemisphere) = hemisphere.filter(|hemisphere| hemisphere.is_changed()) else {
        return;
    };
    let hemisphere = hemisphere.bypass_change_detection();
    let mut checker = Checker::new(Owner::Resource, "PhongHemisphereLight");
    checker.color("sky_color", &mut hemisphere.sky_color);
    checker.color("ground_color", &mut hemisphere.ground_color);
    if crate::direction::normalize_or_zero(hemisphere.up) == Vec3::ZERO {
        checker.replace(
            "up",
            format!("{:?}", hemisphere.up),
            "(0.0, 1.0, 0.0): it has no direction".into(),
        );
        hemisphere.up = Vec3::Y;
    }
    checker.report(&mut messages);
}

/// Replaces the invalid fields of every material added or modified, and warns once per
/// replacement. (The uniform the shader reads is clamped the same way on its own, so no
/// frame ever draws with an invalid value.)
pub fn validate_materials(
    mut events: MessageReader<AssetEvent<PhongMaterial>>,
    mut materials: ResMut<Assets<PhongMaterial>>,
    mut messages: MessageWriter<InvalidInput>,
) {
    for event in events.read() {
        let (AssetEvent::Added { id } | AssetEvent::Modified { id }) = event else {
            continue;
        };
        let Some(material) = materials.get_mut_untracked(*id) else {
            continue;
        };
        let mut checker = Checker::new(Owner::Material(*id), "PhongMaterial");
        checker.material(material);
        checker.report(&mut messages);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        PhongDirectionalLight, PhongPointLight, PhongSpotLight,
        test_app::{invalid_inputs, test_app},
    };

    #[test]
    fn invalid_shadow_settings_are_replaced_with_a_warning_per_field() {
        let mut app = test_app(|_| {});
        let light = app
            .world_mut()
            .spawn(PhongDirectionalLight {
                shadows: PhongShadows {
                    depth_bias: f32::NAN,
                    resolution: 100_000,
                    diffuse_in_shadow: 2.0,
                    ..PhongShadows::ON
                },
                cascades: PhongCascades {
                    count: 9,
                    first_far_bound: 50.0,
                    max_distance: 20.0,
                    ..Default::default()
                },
                ..Default::default()
            })
            .id();
        app.update();
        let fields: Vec<&str> = invalid_inputs(&mut app)
            .iter()
            .map(|warning| warning.field)
            .collect();
        assert_eq!(
            fields,
            [
                "shadows.depth_bias",
                "shadows.diffuse_in_shadow",
                "shadows.resolution",
                "cascades.count",
                "cascades.first_far_bound",
            ]
        );
        let light = app.world().get::<PhongDirectionalLight>(light).unwrap();
        assert_eq!(light.shadows.depth_bias, 0.0);
        assert_eq!(light.shadows.diffuse_in_shadow, 1.0);
        assert_eq!(light.shadows.resolution, PhongShadows::MAX_RESOLUTION);
        assert_eq!(light.cascades.count, PhongCascades::MAX_COUNT);
        assert_eq!(light.cascades.first_far_bound, 20.0);
    }

    /// The boundaries of two rules: a first cascade that ends where the last does is valid
    /// (one split at `max_distance`), and a range of exactly 0 is not (it is replaced with
    /// `None`, with a warning).
    #[test]
    fn a_first_cascade_ending_at_the_last_is_valid_and_a_zero_range_is_not() {
        let mut app = test_app(|_| {});
        let sun = app
            .world_mut()
            .spawn(PhongDirectionalLight {
                cascades: PhongCascades {
                    first_far_bound: 20.0,
                    max_distance: 20.0,
                    ..Default::default()
                },
                ..Default::default()
            })
            .id();
        let lamp = app
            .world_mut()
            .spawn(PhongPointLight {
                range: Some(0.0),
                ..Default::default()
            })
            .id();
        app.update();
        let warnings = invalid_inputs(&mut app);
        let fields: Vec<(&Owner, &str)> = warnings
            .iter()
            .map(|warning| (&warning.owner, warning.field))
            .collect();
        assert_eq!(fields, [(&Owner::Entity(lamp), "range")]);
        let sun = app.world().get::<PhongDirectionalLight>(sun).unwrap();
        assert_eq!(sun.cascades.first_far_bound, 20.0);
        assert_eq!(
            app.world().get::<PhongPointLight>(lamp).unwrap().range,
            None
        );
    }

    #[test]
    fn a_spot_with_inner_above_outer_gets_a_hard_edge() {
        let mut app = test_app(|_| {});
        let spot = app
            .world_mut()
            .spawn(PhongSpotLight {
                inner_angle: 0.6,
                outer_angle: 0.4,
                exponent: f32::NAN,
                ..Default::default()
            })
            .id();
        app.update();
        let warnings = invalid_inputs(&mut app);
        assert_eq!(warnings.len(), 2, "{warnings:?}");
        let light = app.world().get::<PhongSpotLight>(spot).unwrap();
        assert_eq!(
            (light.inner_angle, light.outer_angle, light.exponent),
            (0.4, 0.4, 0.0)
        );
    }

    #[test]
    fn an_invalid_material_is_sanitised_with_a_warning_naming_the_asset() {
        let mut app = test_app(|_| {});
        let handle = app
            .world_mut()
            .resource_mut::<Assets<PhongMaterial>>()
            .add(PhongMaterial {
                shininess: -5.0,
                ..Default::default()
            });
        let id = handle.id();
        app.update();
        app.update();
        let warnings = invalid_inputs(&mut app);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert_eq!(
            (warnings[0].owner.clone(), warnings[0].field),
            (Owner::Material(id), "shininess")
        );
        let material = app
            .world()
            .resource::<Assets<PhongMaterial>>()
            .get(id)
            .unwrap();
        assert_eq!(material.shininess, 0.0);
    }

    #[test]
    fn a_material_with_a_broken_uv_transform_or_depth_bias_gets_the_identity_and_zero() {
        let mut app = test_app(|_| {});
        let handle = app
            .world_mut()
            .resource_mut::<Assets<PhongMaterial>>()
            .add(PhongMaterial {
                uv_transform: bevy::math::Affine2::from_scale(bevy::math::Vec2::new(f32::NAN, 1.0)),
                depth_bias: f32::NAN,
                ..Default::default()
            });
        app.update();
        app.update();
        let fields: Vec<&str> = invalid_inputs(&mut app)
            .iter()
            .map(|warning| warning.field)
            .collect();
        assert_eq!(fields, ["uv_transform", "depth_bias"]);
        let material = app
            .world()
            .resource::<Assets<PhongMaterial>>()
            .get(handle.id())
            .unwrap();
        assert_eq!(material.uv_transform, bevy::math::Affine2::IDENTITY);
        assert_eq!(material.depth_bias, 0.0);
    }
}
