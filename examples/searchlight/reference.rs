//! The searchlight term of the lighting equation in `f64`, built on
//! `bevy_phong::reference`: the specification the searchlight shader is tested against.

use super::{BeamShape, Searchlight, beam_up};
use bevy::prelude::*;
use bevy_phong::{
    extension::light_direction,
    reference::{self, ReferenceLight, SurfacePoint},
};
use glam::DVec3;

/// Signed distance of the cross-section point `(x, y)` (world units, in the light's X/Y
/// plane) from the boundary of `shape` inscribed in `radius`: negative inside. Polygons use
/// the largest signed distance to their edge lines, so a soft edge keeps their corners
/// sharp.
pub fn beam_distance(shape: BeamShape, x: f64, y: f64, radius: f64) -> f64 {
    let half_sqrt_3 = 3f64.sqrt() / 2.0;
    match shape {
        BeamShape::Circle => x.hypot(y) - radius,
        BeamShape::Triangle => {
            let edges = (-y)
                .max(half_sqrt_3 * x + 0.5 * y)
                .max(-half_sqrt_3 * x + 0.5 * y);
            edges - 0.5 * radius
        }
        BeamShape::Diamond => (x.abs() + y.abs() - radius) * std::f64::consts::FRAC_1_SQRT_2,
        BeamShape::Square => x.abs().max(y.abs()) - radius * std::f64::consts::FRAC_1_SQRT_2,
    }
}

/// A searchlight in world space, for the reference model.
#[derive(Clone, Copy, Debug)]
pub struct ReferenceSearchlight {
    pub position: DVec3,
    pub direction: DVec3,
    pub up: DVec3,
    pub color: DVec3,
    pub specular: DVec3,
    pub radius: f64,
    pub shape: BeamShape,
    pub edge: f64,
    pub decay: [f64; 3],
    /// How far along the beam it lights; `None` without end.
    pub range: Option<f64>,
}

impl ReferenceSearchlight {
    /// The reference form of a searchlight entity.
    pub fn new(light: &Searchlight, transform: &GlobalTransform) -> Self {
        let direction = light_direction(transform);
        Self {
            position: transform.translation().as_dvec3(),
            direction: direction.as_dvec3(),
            up: beam_up(transform, direction).as_dvec3(),
            color: reference::rgb(light.color),
            specular: reference::rgb(light.specular.unwrap_or(light.color)),
            radius: light.radius.into(),
            shape: light.shape,
            edge: light.edge.into(),
            decay: light.decay.to_array().map(f64::from),
            range: light.range.map(f64::from),
        }
    }

    /// `(distance along the beam, signed distance from the cross-section's boundary)` of
    /// the point `p`.
    pub fn beam_coordinates(&self, p: DVec3) -> (f64, f64) {
        let offset = p - self.position;
        let along = offset.dot(self.direction);
        let right = self.direction.cross(self.up);
        let boundary = beam_distance(
            self.shape,
            offset.dot(right),
            offset.dot(self.up),
            self.radius,
        );
        (along, boundary)
    }
}

/// `1` inside the cross-section, `0` past `edge` outside it, a smoothstep between; a step
/// at the boundary when `edge` is 0.
pub fn beam_coverage(boundary_distance: f64, edge: f64) -> f64 {
    if edge <= 0.0 {
        return if boundary_distance <= 0.0 { 1.0 } else { 0.0 };
    }
    let t = (boundary_distance / edge).clamp(0.0, 1.0);
    1.0 - t * t * (3.0 - 2.0 * t)
}

/// The searchlight's term of the lighting equation at `surface`: Phong lighting from
/// `L = -direction`, scaled by the beam's coverage and its decay along the beam, and zero
/// behind the light.
pub fn searchlight_term(
    surface: &SurfacePoint,
    material: &reference::Material,
    light: &ReferenceSearchlight,
) -> DVec3 {
    let (along, boundary) = light.beam_coordinates(surface.position);
    if along <= 0.0 {
        return DVec3::ZERO;
    }
    let coverage = beam_coverage(boundary, light.edge);
    if coverage == 0.0 {
        return DVec3::ZERO;
    }
    let attenuation = reference::attenuation(along, light.decay, light.range);
    let light_term = reference::phong_light(
        surface,
        material,
        -light.direction,
        light.color,
        light.specular,
    );
    coverage * attenuation * light_term
}

/// The searchlight in the crate's reference model, as its plugin's
/// `PhongLightKind::reference_light` gives it: the harness adds its term to each pixel's.
impl ReferenceLight for ReferenceSearchlight {
    fn term(&self, surface: &SurfacePoint, material: &reference::Material) -> DVec3 {
        searchlight_term(surface, material, self)
    }
}
