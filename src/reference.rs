//! The lighting model of SPEC.md in `f64`, for one surface point: the specification in
//! code.
//!
//! The shader computes the same equation in `f32`; the tests render a scene, read back each
//! pixel's color together with the world position and normal it was lit with (see
//! `SurfaceInputsMaterial`), and compare the color with
//! [`shade`] evaluated on those inputs. A textured material is first given the texels of
//! the fragment ([`Material::mapped`], [`mapped_normal`]).
//!
//! Every function follows the shader's rules for degenerate input, so that the two can be
//! compared anywhere:
//! - a vector is normalized by its largest component first ([`normalize_or_zero`]); one
//!   that is not finite, or whose largest component is below `f32`'s smallest normal number
//!   (about 1.2e-38), has no direction: such a normal, view or light vector gives no diffuse
//!   or specular light;
//! - a point or spot light at the surface point (closer than 1e-15, [`MIN_LENGTH_SQUARED`])
//!   lights nothing;
//! - a spot light whose outer angle is not positive has an empty cone and lights nothing;
//! - `power(0, 0) = 1`;
//! - an attenuation denominator at or below 1 (a `Decay` of all zeros included) gives 1;
//! - a [`PhongMaterial`]'s values, and a spot light's angles, are first brought into their
//!   ranges (`crate::limits`) as its uniform and light record do.
//!
//! The model is split by concern, each file beside the SPEC.md section it follows:
//! `surface` (the surface point and the material's terms, "Material"), `lights` (each
//! light kind, fall-off and the spot cone, "Light types" and "The equation"), `shading` (the
//! sum and each light's term, "The equation" and "Shadows"), `stylized`, `hemisphere`,
//! `environment`, `environment_light`, `cookies`, `normals`, `texture_maps`,
//! `surface_inputs`, `per_vertex` and `camera_effects` (the sections of the same names). `area` integrates an area light
//! (docs/design/area-lights.md) over its area by adaptive quadrature (`quadrature`); the
//! closed forms the shader uses (`area_closed_forms` and `area_disk_polygon`, test-only, and
//! `shaders/area_integrals.wesl`, `shaders/disk_polygon.wesl`) are measured against it.

mod ambient_specular;
mod area;
#[cfg(test)]
mod area_closed_forms;
#[cfg(test)]
mod area_disk_polygon;
mod area_pieces;
mod camera_effects;
mod cookies;
mod environment;
mod environment_light;
#[cfg(test)]
mod ggx_fit;
mod hemisphere;
mod lights;
mod metallic_roughness;
mod normals;
mod per_vertex;
mod quadrature;
mod shading;
pub(crate) mod stylized;
mod surface;
mod surface_inputs;
mod texture_maps;
pub use ambient_specular::{AmbientSpecular, environment_brdf};
pub use area::{AreaLight, AreaShape, area_light_contribution, visible_area_light_contribution};
pub use camera_effects::{directional_scattering, fogged, reinhard};
pub use cookies::{Cookie, CookieProjection, cube_face_uv};
pub use environment::{cube_direction, environment_direction, environment_lod, with_environment};
pub use environment_light::{environment_light_direction, environment_light_level};
pub use hemisphere::Hemisphere;
pub use lights::{Light, Lights, OtherLights, ReferenceLight, attenuation, cone_factor, rgb};
pub use metallic_roughness::{
    EXPONENT_FIT, MAX_SHININESS, MEAN_N_DOT_V, MetallicRoughness, shininess_from_roughness,
    with_multiple_scattering,
};
pub use normals::{bumped_normal, face_normal, mapped_normal};
pub use per_vertex::VertexLight;
pub use shading::{
    BakedLight, Shadowing, fresnel_weight, highlight, light_contribution, phong_light, power,
    reflect, shade, shade_baked, shade_shadowed, specular_weight,
};
pub use stylized::{Rim, ToonRamp, diffuse_factor, highlight_factor, rim_factor};
pub use surface::{MIN_LENGTH_SQUARED, Material, SurfacePoint, normalize_or_zero};
pub use surface_inputs::transformed_uv;
pub use texture_maps::Texels;

#[cfg(test)]
mod area_disk_tests;
#[cfg(test)]
mod area_tests;
#[cfg(test)]
mod baked_light_tests;
#[cfg(test)]
mod properties;
#[cfg(test)]
mod tests;
