//! Every number of a [`PhongMaterial`] with its range, written once: [`visit_numbers`] walks
//! the fields, naming each and its range ([`crate::limits`]). Validation walks them to warn
//! about and replace what is out of range; [`PhongMaterial::in_range`] walks them to bring
//! a copy into range, and the material's uniform and the reference model read that copy. A
//! new number of the material is added here once, and all three follow.

use super::metallic_roughness::{METALLIC, ROUGHNESS};
use super::{DiffuseMode, PhongMaterial, SpecularMode};
use crate::limits::{self, Limits};
use bevy::{
    color::{Color, LinearRgba},
    math::Affine2,
    prelude::AlphaMode,
};

/// What is done with each number of a material: each method gets the field's name (as a
/// warning names it) and the value, to bring into its range.
pub(crate) trait NumberVisitor {
    /// A scalar whose range is `limits`.
    fn scalar(&mut self, field: &'static str, value: &mut f32, limits: Limits);
    /// A color: its red, green and blue in [`limits::INTENSITY`]'s range, its alpha in
    /// [`limits::ALPHA`]'s ([`limits::linear_color`]).
    fn color(&mut self, field: &'static str, value: &mut LinearRgba);
    /// A count from 1 to `max`.
    fn count(&mut self, field: &'static str, value: &mut u32, max: u32);
    /// A UV transform: finite, else the identity ([`limits::uv_transform`]).
    fn uv_transform(&mut self, field: &'static str, value: &mut Affine2);
}

/// Walks every number of `material` with `visitor`, in the order of the fields.
pub(crate) fn visit_numbers(material: &mut PhongMaterial, visitor: &mut impl NumberVisitor) {
    visit_color(visitor, "base_color", &mut material.base_color);
    visitor.scalar(
        "ambient_factor",
        &mut material.ambient_factor,
        limits::INTENSITY,
    );
    visit_color(visitor, "specular_color", &mut material.specular_color);
    let strength = &mut material.specular_strength;
    visitor.scalar("specular_strength", strength, limits::INTENSITY);
    visitor.scalar("shininess", &mut material.shininess, limits::EXPONENT);
    match &mut material.diffuse_mode {
        DiffuseMode::Lambert => {}
        DiffuseMode::Wrap(wrap) => visitor.scalar("diffuse_mode", wrap, limits::FRACTION),
        DiffuseMode::Toon { bands, smoothing } => {
            visitor.count("diffuse_mode", bands, limits::TOON_BANDS);
            visitor.scalar("diffuse_mode", smoothing, limits::FRACTION);
        }
    }
    if let SpecularMode::Toon { smoothing } = &mut material.specular_mode {
        visitor.scalar("specular_mode", smoothing, limits::FRACTION);
    }
    visitor.color("rim_color", &mut material.rim_color);
    visitor.scalar(
        "rim_strength",
        &mut material.rim_strength,
        limits::INTENSITY,
    );
    visitor.scalar("rim_power", &mut material.rim_power, limits::EXPONENT);
    visitor.color("emissive", &mut material.emissive);
    if let AlphaMode::Mask(cutoff) = &mut material.alpha_mode {
        visitor.scalar("alpha_mode", cutoff, limits::ALPHA_CUTOFF);
    }
    visitor.scalar("metallic", &mut material.metallic, METALLIC);
    let roughness = &mut material.perceptual_roughness;
    visitor.scalar("perceptual_roughness", roughness, ROUGHNESS);
    visitor.scalar("bump_scale", &mut material.bump_scale, limits::SIGNED_SCALE);
    let normal_map_scale = &mut material.normal_map_scale;
    visitor.scalar(
        "normal_map_scale",
        &mut normal_map_scale.x,
        limits::NORMAL_MAP_SCALE,
    );
    visitor.scalar(
        "normal_map_scale",
        &mut normal_map_scale.y,
        limits::NORMAL_MAP_SCALE,
    );
    let scale = &mut material.displacement_scale;
    visitor.scalar("displacement_scale", scale, limits::SIGNED_SCALE);
    let bias = &mut material.displacement_bias;
    visitor.scalar("displacement_bias", bias, limits::SIGNED_SCALE);
    visitor.uv_transform("uv_transform", &mut material.uv_transform);
    visitor.scalar("depth_bias", &mut material.depth_bias, limits::DEPTH_BIAS);
    let intensity = &mut material.light_map_intensity;
    visitor.scalar("light_map_intensity", intensity, limits::INTENSITY);
    let intensity = &mut material.ao_map_intensity;
    visitor.scalar("ao_map_intensity", intensity, limits::INTENSITY);
    visitor.scalar("reflectivity", &mut material.reflectivity, limits::FRACTION);
    if let Some(ratio) = &mut material.refraction_ratio {
        visitor.scalar("refraction_ratio", ratio, limits::REFRACTION_RATIO);
    }
}

/// A [`Color`] field, visited as the linear color it is drawn with; written back only where
/// the visitor changed it, so that a color in range keeps its color space.
pub(crate) fn visit_color(
    visitor: &mut impl NumberVisitor,
    field: &'static str,
    value: &mut Color,
) {
    let linear = value.to_linear();
    let mut visited = linear;
    visitor.color(field, &mut visited);
    // NaN never equals itself: a NaN channel is written back (replaced).
    if visited != linear {
        *value = visited.into();
    }
}

/// Brings every number into its range, silently.
struct Clamp;

impl NumberVisitor for Clamp {
    fn scalar(&mut self, _: &'static str, value: &mut f32, limits: Limits) {
        *value = limits.apply(*value);
    }

    fn color(&mut self, _: &'static str, value: &mut LinearRgba) {
        *value = limits::linear_color(*value);
    }

    fn count(&mut self, _: &'static str, value: &mut u32, max: u32) {
        *value = (*value).clamp(1, max);
    }

    fn uv_transform(&mut self, _: &'static str, value: &mut Affine2) {
        *value = limits::uv_transform(*value);
    }
}

impl PhongMaterial {
    /// A copy with every number in its range, as validation would leave it (without its
    /// warnings): what the shader's uniform and the reference model read.
    pub(crate) fn in_range(&self) -> Self {
        let mut material = self.clone();
        visit_numbers(&mut material, &mut Clamp);
        material
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Records the field names it is shown.
    struct Names(Vec<&'static str>);

    impl NumberVisitor for Names {
        fn scalar(&mut self, field: &'static str, _: &mut f32, _: Limits) {
            self.0.push(field);
        }
        fn color(&mut self, field: &'static str, _: &mut LinearRgba) {
            self.0.push(field);
        }
        fn count(&mut self, field: &'static str, _: &mut u32, _: u32) {
            self.0.push(field);
        }
        fn uv_transform(&mut self, field: &'static str, _: &mut Affine2) {
            self.0.push(field);
        }
    }

    /// A material with every optional number present.
    fn every_number() -> PhongMaterial {
        PhongMaterial {
            diffuse_mode: DiffuseMode::Toon {
                bands: 3,
                smoothing: 0.1,
            },
            specular_mode: SpecularMode::Toon { smoothing: 0.1 },
            alpha_mode: AlphaMode::Mask(0.5),
            refraction_ratio: Some(0.9),
            ..PhongMaterial::default()
        }
    }

    #[test]
    fn the_validation_table_lists_every_number_of_a_material() {
        let mut names = Names(Vec::new());
        visit_numbers(&mut every_number(), &mut names);
        let table = include_str!("../validation.rs");
        for name in names.0 {
            assert!(
                table.contains(&format!("`{name}`")),
                "validation.rs's table does not list PhongMaterial.{name}"
            );
        }
    }

    #[test]
    fn in_range_brings_each_number_into_its_range_and_keeps_the_rest() {
        let mut wild = every_number();
        wild.shininess = f32::NAN;
        wild.rim_power = f32::INFINITY;
        wild.bump_scale = -1e30;
        wild.base_color = Color::linear_rgba(2e6, 0.5, f32::NAN, 3.0);
        wild.diffuse_mode = DiffuseMode::Toon {
            bands: 0,
            smoothing: 2.0,
        };
        let fixed = wild.in_range();
        assert_eq!(fixed.shininess, limits::EXPONENT.apply(f32::NAN));
        assert_eq!(fixed.rim_power, limits::MAX_EXPONENT);
        assert_eq!(fixed.bump_scale, -limits::MAX_INTENSITY);
        assert_eq!(
            fixed.base_color.to_linear(),
            LinearRgba::new(limits::MAX_INTENSITY, 0.5, 0.0, 1.0)
        );
        assert_eq!(
            fixed.diffuse_mode,
            DiffuseMode::Toon {
                bands: 1,
                smoothing: 1.0
            }
        );
        // What was in range is unchanged.
        assert_eq!(fixed.specular_strength, wild.specular_strength);
        assert_eq!(fixed.specular_color, wild.specular_color);
    }
}
