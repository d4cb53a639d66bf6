//! Lighting per vertex (SPEC.md, "Per-vertex lighting"): the lights' sums at a triangle's
//! vertices, interpolated to a point of the triangle by its barycentric weights, and weighed
//! there with the material.

use super::{Light, Material, ReferenceLight, SurfacePoint, light_contribution, normalize_or_zero};
use crate::material::DiffuseMode;
use glam::DVec3;

/// The lights' sums at a vertex, unweighed by the material's colors: `diffuse` (each light's
/// `color · f_d(N·L)`, for `k_d`), `specular` (`specular · f_s(H)`, for `k_s · strength`;
/// times `1 − w` under a Fresnel term), `grazing` (`specular · f_s(H) · w`, for 1: the
/// normalized model's Fresnel share) and `rim` (`color · max(N·L, 0)`, for a lit-side rim's
/// color and factor), each light with its attenuation, cone and whatever scales it. A
/// [`ReferenceLight`]: its term at a point is the sums weighed with the material there.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct VertexLight {
    /// `Σ color · f_d(N·L)`, linear RGB.
    pub diffuse: DVec3,
    /// `Σ specular · f_s(H(N, L, V))` (times `1 − w` under a Fresnel term), linear RGB.
    pub specular: DVec3,
    /// `Σ specular · f_s(H(N, L, V)) · w`, linear RGB; zero without a Fresnel term.
    pub grazing: DVec3,
    /// `Σ color · max(N·L, 0)`, linear RGB; zero unless the material's rim is on its lit side.
    pub rim: DVec3,
}

impl VertexLight {
    /// The sums of `lights` at `vertex` (its position and normal, seen from its camera) for
    /// `material`: each is the model's own sum of the lights' terms for the material with that
    /// part's weight set to one and the others to zero (the terms are affine in them: with
    /// every weight zero, what remains is the Fresnel share `grazing`).
    pub fn at(vertex: &SurfacePoint, material: &Material, lights: &[Light]) -> Self {
        let sum = |weights: Material| -> DVec3 {
            lights
                .iter()
                .map(|light| light_contribution(vertex, &weights, light))
                .sum()
        };
        let unweighed = Material {
            diffuse: DVec3::ZERO,
            specular: DVec3::ZERO,
            specular_strength: 1.0,
            rim: super::Rim::NONE,
            ..material.clone()
        };
        let grazing = sum(unweighed.clone());
        Self {
            diffuse: sum(Material {
                diffuse: DVec3::ONE,
                ..unweighed.clone()
            }) - grazing,
            specular: sum(Material {
                specular: DVec3::ONE,
                ..unweighed.clone()
            }) - grazing,
            grazing,
            rim: if material.rim.lit_side {
                sum(Material {
                    diffuse: DVec3::ONE,
                    diffuse_mode: DiffuseMode::Lambert,
                    toon_ramp: None,
                    ..unweighed
                }) - grazing
            } else {
                DVec3::ZERO
            },
        }
    }

    /// The sums at a point of a triangle whose vertices have `corners`, at barycentric
    /// `weights` (summing to one).
    pub fn interpolated(corners: &[VertexLight; 3], weights: [f64; 3]) -> Self {
        corners
            .iter()
            .zip(weights)
            .fold(Self::default(), |sum, (corner, weight)| Self {
                diffuse: sum.diffuse + weight * corner.diffuse,
                specular: sum.specular + weight * corner.specular,
                grazing: sum.grazing + weight * corner.grazing,
                rim: sum.rim + weight * corner.rim,
            })
    }
}

/// `diffuse ⊙ k_d + specular ⊙ k_s · strength + grazing + rim ⊙ rim color · rim factor`,
/// the material and the rim factor those of `surface`.
impl ReferenceLight for VertexLight {
    fn term(&self, surface: &SurfacePoint, material: &Material) -> DVec3 {
        let rim = if material.rim.lit_side {
            let normal = normalize_or_zero(surface.normal);
            let view = normalize_or_zero(surface.camera - surface.position);
            self.rim * material.rim.color * super::rim_factor(normal, view, material.rim.power)
        } else {
            DVec3::ZERO
        };
        self.diffuse * material.diffuse
            + self.specular * material.specular * material.specular_strength
            + if material.specular_strength > 0.0 {
                self.grazing
            } else {
                DVec3::ZERO
            }
            + rim
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::{Lights, OtherLights, shade};
    use std::sync::Arc;

    fn lights() -> Vec<Light> {
        vec![
            Light::Directional {
                direction: DVec3::new(-1.0, -2.0, -0.5),
                color: DVec3::new(0.7, 0.6, 0.5),
                specular: DVec3::new(0.3, 0.4, 0.5),
            },
            Light::Point {
                position: DVec3::new(1.0, 2.0, 1.5),
                color: DVec3::new(0.9, 0.4, 0.2),
                specular: DVec3::new(1.0, 0.8, 0.6),
                decay: [1.0, 0.1, 0.05],
                range: Some(20.0),
            },
        ]
    }

    fn material(lit_side: bool) -> Material {
        Material {
            diffuse: DVec3::new(0.8, 0.5, 0.3),
            specular: DVec3::new(0.6, 0.7, 0.9),
            specular_strength: 1.5,
            shininess: 12.0,
            rim: crate::reference::Rim {
                color: DVec3::new(0.2, 0.3, 0.4),
                power: 2.0,
                lit_side,
            },
            ..Material::from(&crate::PhongMaterial::default())
        }
    }

    /// At a vertex itself (weights (1, 0, 0)), the weighed sums are the per-pixel model's
    /// sum of the light terms: the decomposition loses nothing.
    #[test]
    fn at_a_vertex_the_weighed_sums_are_the_light_terms_of_the_model() {
        let vertex = SurfacePoint {
            position: DVec3::new(0.2, 0.0, 0.1),
            normal: DVec3::new(0.1, 1.0, 0.3),
            camera: DVec3::new(0.0, 1.0, 4.0),
        };
        use crate::SpecularModel::{NormalizedBlinnPhong, Phong};
        for (lit_side, specular_model) in [
            (false, Phong),
            (true, Phong),
            (false, NormalizedBlinnPhong),
            (true, NormalizedBlinnPhong),
        ] {
            let material = Material {
                specular_model,
                ..material(lit_side)
            };
            let corner = VertexLight::at(&vertex, &material, &lights());
            let other = VertexLight::at(
                &SurfacePoint {
                    position: DVec3::X,
                    ..vertex
                },
                &material,
                &lights(),
            );
            let at_vertex = VertexLight::interpolated(&[corner, other, other], [1.0, 0.0, 0.0]);
            let per_vertex = Lights {
                others: OtherLights(vec![Arc::new(at_vertex)]),
                ..Lights::default()
            };
            let per_pixel = Lights {
                lights: lights(),
                ..Lights::default()
            };
            let (a, b) = (
                shade(&vertex, &material, &per_vertex),
                shade(&vertex, &material, &per_pixel),
            );
            assert!(
                (a - b).abs().max_element() < 1e-12,
                "rim on the lit side {lit_side}, {specular_model:?}: {a} against {b}"
            );
        }
    }

    #[test]
    fn between_the_vertices_the_sums_are_interpolated_linearly() {
        let corner = |value: f64| VertexLight {
            diffuse: DVec3::splat(value),
            specular: DVec3::splat(2.0 * value),
            grazing: DVec3::splat(4.0 * value),
            rim: DVec3::splat(3.0 * value),
        };
        let middle =
            VertexLight::interpolated(&[corner(1.0), corner(2.0), corner(4.0)], [0.5, 0.25, 0.25]);
        assert_eq!(middle, corner(0.5 + 0.5 + 1.0));
    }
}
