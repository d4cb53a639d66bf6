//! A material's texture maps in the reference model: what a fragment's texels do to the
//! terms of the equation (SPEC.md, "Texture maps").

use super::Material;
use glam::{DVec2, DVec3, DVec4};

/// The values a fragment's maps gave it, as the sampler returns them (linear; `None` for a
/// map the material does not have).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Texels {
    /// The base color map's RGBA; RGB multiplies `k_d` (alpha only the output alpha).
    pub base_color: Option<DVec4>,
    /// The specular map's RGB; multiplies `k_s`.
    pub specular: Option<DVec3>,
    /// The emissive map's RGB; multiplies the emissive color.
    pub emissive: Option<DVec3>,
    /// The normal map's RGB, in `[0, 1]`.
    pub normal: Option<DVec3>,
    /// The light map's RGB; times its intensity, added to the ambient light.
    pub light_map: Option<DVec3>,
    /// The AO map's red channel.
    pub ao_map: Option<f64>,
    /// The alpha map's green channel; multiplies the output alpha only.
    pub alpha_map: Option<f64>,
    /// The metallic-roughness map's blue and green channels, as `(metallic, roughness)`
    /// (before the material's factors).
    pub metallic_roughness: Option<DVec2>,
}

impl Material {
    /// This material at a fragment whose maps gave `texels`: each present map multiplies
    /// its color, channel by channel; then, where the material draws a metallic-roughness
    /// map, its texel makes the surface ([`Material::at_metallic_roughness_texel`]).
    pub fn mapped(&self, texels: &Texels) -> Material {
        let times = |color: DVec3, texel: Option<DVec3>| texel.map_or(color, |t| color * t);
        let mapped = Material {
            diffuse: times(self.diffuse, texels.base_color.map(|t| t.truncate())),
            specular: times(self.specular, texels.specular),
            emissive: times(self.emissive, texels.emissive),
            ..self.clone()
        };
        match (self.metallic_roughness, texels.metallic_roughness) {
            (Some(factors), Some(texel)) => {
                mapped.at_metallic_roughness_texel(factors, texel.x, texel.y)
            }
            _ => mapped,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::SpecularModel;

    fn material() -> Material {
        Material {
            toon_ramp: None,
            diffuse: DVec3::new(0.5, 0.6, 0.7),
            ambient_factor: 1.0,
            specular: DVec3::ONE,
            specular_strength: 2.0,
            shininess: 32.0,
            specular_model: SpecularModel::Phong,
            emissive: DVec3::splat(0.1),
            diffuse_mode: crate::DiffuseMode::Lambert,
            specular_mode: crate::SpecularMode::Smooth,
            rim: crate::reference::Rim::NONE,
            metallic_roughness: None,
            ambient_specular: None,
        }
    }

    #[test]
    fn no_texels_leave_the_material_as_it_is() {
        assert_eq!(material().mapped(&Texels::default()), material());
    }

    #[test]
    fn each_texel_multiplies_its_own_color() {
        let texels = Texels {
            base_color: Some(DVec4::new(0.5, 0.5, 1.0, 0.25)),
            specular: Some(DVec3::new(0.0, 1.0, 0.5)),
            emissive: Some(DVec3::splat(2.0)),
            normal: None,
            light_map: Some(DVec3::ONE),
            ao_map: Some(0.5),
            alpha_map: Some(0.5),
            metallic_roughness: None,
        };
        let mapped = material().mapped(&texels);
        assert_eq!(mapped.diffuse, DVec3::new(0.25, 0.3, 0.7));
        assert_eq!(mapped.specular, DVec3::new(0.0, 1.0, 0.5));
        assert_eq!(mapped.emissive, DVec3::splat(0.2));
        assert_eq!(mapped.specular_strength, 2.0);
    }
}
