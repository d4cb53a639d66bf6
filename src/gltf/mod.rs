//! glTF files drawn with [`PhongMaterial`](crate::PhongMaterial): [`PhongGltfPlugin`] (an
//! extension of Bevy's glTF loader) and the conversion it uses,
//! [`phong_material_from_gltf`], which is usable on its own. Needs the `gltf` feature (on
//! by default).
//!
//! How a glTF material maps to a Phong one, and where the look differs from Bevy's PBR:
//!
//! - the base color is the diffuse color times `1 − metallic`; the specular color is the
//!   Fresnel reflectance at normal incidence `F₀ = mix(0.04, base color, metallic)` with
//!   Bevy's compensation for multiple scattering, on a normalized Blinn-Phong highlight
//!   (three.js's: Schlick's Fresnel and `N·L`) whose exponent is fitted to Bevy's GGX lobe
//!   of roughness `r` (in `[1, 10⁴]`; SPEC.md, "Metallic-roughness map"), at strength π;
//! - there is no geometry term, and the Blinn-Phong lobe lacks GGX's long tails
//!   (docs/switching.md measures the difference);
//! - there is no image-based lighting: metals lit only by punctual lights look darker than
//!   PBR metals under an environment map;
//! - the metallic-roughness map is read per texel and the occlusion map is the AO map;
//!   transmission, volume, clearcoat and anisotropy are not used: one warning per material
//!   that has them, naming the material and what the surface becomes without each.

mod handler;
mod material;
mod plugin;

pub use handler::{PHONG_LABEL_SUFFIX, phong_material_label};
pub use material::phong_material_from_gltf;
pub use plugin::PhongGltfPlugin;
