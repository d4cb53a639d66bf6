//! Area lights (docs/design/area-lights.md): a rectangle or a disk that emits from each point of
//! its area, integrated over that area by adaptive quadrature ([`super::quadrature`]), to
//! within [`RELATIVE_TOLERANCE`] of the result. No closed form enters: this is what the
//! shader's closed forms and fits are measured against.
//!
//! Each area element `dA` at `y` lights the surface point `P` as a point light of color
//! `color / |S|` (`|S|` the light's area) would, times the emission's cosine
//! `e = max(cos θ_y, 0)` (both sides: `|cos θ_y|`) and the inverse square `1 / r²`
//! (`r = |y − P|`, `cos θ_y` between the light's facing and `P − y`): the whole light seen
//! face on from far away is a point light of `color` with the inverse-square fall-off.
//! Seen from `P`, `e · dA / r²` is the solid angle `dω` the element fills, so the diffuse
//! term is `color / |S| ⊙ k_d · ∫ max(N·ω, 0) dω` over the light's solid angle.

use super::area_pieces::{cut, integrate_disk, integrate_polygon};
use super::{Material, SurfacePoint, attenuation, phong_light};
use bevy::math::DVec3;

/// The quadrature's tolerance, relative to the light's largest channel at the point.
pub const RELATIVE_TOLERANCE: f64 = 1e-9;

/// The tolerance's floor, relative to the light's color per unit area.
const ABSOLUTE_FLOOR: f64 = 1e-14;

/// The shininess from which the quadrature cuts the light through its highlight's peak (a
/// lobe of 64 is about 0.3 radians wide, as wide as a light a few units away).
const SHARP_HIGHLIGHT: f64 = 64.0;

/// An area light's shape, in its own plane (its local X and Y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AreaShape {
    /// A rectangle centered on the light's position.
    Rect {
        /// Along local X, world units.
        width: f64,
        /// Along local Y, world units.
        height: f64,
    },
    /// A disk centered on the light's position.
    Disk {
        /// World units.
        radius: f64,
    },
}

impl AreaShape {
    /// `|S|`, world units squared.
    pub fn area(self) -> f64 {
        match self {
            Self::Rect { width, height } => width * height,
            Self::Disk { radius } => std::f64::consts::PI * radius * radius,
        }
    }

    /// The point of the shape nearest `(x, y)` of its plane, in the same coordinates.
    pub fn nearest_point(self, x: f64, y: f64) -> (f64, f64) {
        match self {
            Self::Rect { width, height } => (
                x.clamp(-0.5 * width, 0.5 * width),
                y.clamp(-0.5 * height, 0.5 * height),
            ),
            Self::Disk { radius } => {
                let length = x.hypot(y);
                if length <= radius {
                    (x, y)
                } else {
                    (x * radius / length, y * radius / length)
                }
            }
        }
    }
}

/// An area light in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaLight {
    /// The shape's center.
    pub position: DVec3,
    /// The light's local X, unit.
    pub right: DVec3,
    /// The light's local Y, unit and perpendicular to `right`. The light faces along local
    /// −Z, `up × right`, as every light of the crate points.
    pub up: DVec3,
    /// Its shape in its plane.
    pub shape: AreaShape,
    /// Whether it emits from its back face too.
    pub two_sided: bool,
    /// The whole light's diffuse color, linear RGB (see the module docs).
    pub color: DVec3,
    /// The whole light's specular color, linear RGB.
    pub specular: DVec3,
    /// `(constant, linear, quadratic)`, at the distance from the surface point to the
    /// light's nearest point ([`attenuation`]).
    pub decay: [f64; 3],
    /// The range, at the same distance.
    pub range: Option<f64>,
}

impl AreaLight {
    /// An area light entity's reference form (`AreaLight::rect`, `AreaLight::disk`): `shape`
    /// placed by `transform`'s translation and rotation (scale ignored, as its record's), its
    /// specular color `color`'s where it has none.
    pub(crate) fn placed(
        transform: &bevy::transform::components::GlobalTransform,
        shape: AreaShape,
        two_sided: bool,
        (color, specular): (bevy::color::Color, Option<bevy::color::Color>),
        decay: crate::lights::Decay,
        range: Option<f32>,
    ) -> Self {
        let (_, rotation, translation) = transform.to_scale_rotation_translation();
        let rotation = rotation.as_dquat();
        AreaLight {
            position: translation.as_dvec3(),
            right: rotation * DVec3::X,
            up: rotation * DVec3::Y,
            shape,
            two_sided,
            color: super::rgb(color),
            specular: super::rgb(specular.unwrap_or(color)),
            decay: decay.to_array().map(f64::from),
            range: range.map(f64::from),
        }
    }

    /// The direction the light faces (its local −Z).
    pub fn facing(&self) -> DVec3 {
        self.up.cross(self.right)
    }

    /// The world point at `(x, y)` of the light's plane.
    pub fn point(&self, x: f64, y: f64) -> DVec3 {
        self.position + x * self.right + y * self.up
    }

    /// The distance from `point` to the light's nearest point.
    pub fn distance(&self, point: DVec3) -> f64 {
        let offset = point - self.position;
        let (x, y) = self
            .shape
            .nearest_point(offset.dot(self.right), offset.dot(self.up));
        (point - self.point(x, y)).length()
    }

    /// The emission's weight toward `to_surface` (unit, from the light): the cosine with the
    /// facing, its absolute value for a two-sided light, 0 behind a one-sided one.
    pub fn emission(&self, to_surface: DVec3) -> f64 {
        let cosine = self.facing().dot(to_surface);
        if self.two_sided {
            cosine.abs()
        } else {
            cosine.max(0.0)
        }
    }
}

/// An area light's term is [`area_light_contribution`]'s: the rectangle light gives its own
/// through [`PhongLightKind::reference_light`](crate::extension::PhongLightKind::reference_light).
impl super::ReferenceLight for AreaLight {
    fn term(&self, surface: &SurfacePoint, material: &Material) -> DVec3 {
        area_light_contribution(surface, material, self)
    }
}

/// The light's term at `surface`: each area element's `phong_light` (the material's diffuse
/// and specular terms toward it) weighed by its emission and inverse square, integrated over
/// the area; times the fall-off at the light's nearest point.
pub fn area_light_contribution(
    surface: &SurfacePoint,
    material: &Material,
    light: &AreaLight,
) -> DVec3 {
    visible_area_light_contribution(surface, material, light, &|_| 1.0, RELATIVE_TOLERANCE)
}

/// [`area_light_contribution`] with each element `y` of the light weighed by `visible(y)`
/// (`1` where the segment from the surface point to `y` meets nothing, `0` where it is
/// blocked): the light's exact term past what is in the way, SPEC.md's `V` taken per element.
/// Integrated to `relative_tolerance` of the term (the visibility's edges are jumps, which
/// the adaptive rule halves intervals down to; the unshadowed term takes 1e-9).
pub fn visible_area_light_contribution(
    surface: &SurfacePoint,
    material: &Material,
    light: &AreaLight,
    visible: &dyn Fn(DVec3) -> f64,
    relative_tolerance: f64,
) -> DVec3 {
    let fall_off = attenuation(light.distance(surface.position), light.decay, light.range);
    let area = light.shape.area();
    if fall_off <= 0.0 || area.is_nan() || area <= 0.0 {
        return DVec3::ZERO;
    }
    let (color, specular) = (light.color / area, light.specular / area);
    let element = |x: f64, y: f64| -> DVec3 {
        let point = light.point(x, y);
        let offset = point - surface.position;
        let distance_squared = offset.length_squared();
        if distance_squared <= super::MIN_LENGTH_SQUARED {
            return DVec3::ZERO;
        }
        let to_light = offset / distance_squared.sqrt();
        let weight = light.emission(-to_light) / distance_squared;
        if weight == 0.0 {
            return DVec3::ZERO;
        }
        let weight = weight * visible(point);
        if weight == 0.0 {
            return DVec3::ZERO;
        }
        weight * phong_light(surface, material, to_light, color, specular)
    };
    // The integrand has kinks (`area_pieces`) along the surface's horizon and the mirror
    // direction's plane, each a line of the light's plane: a rectangle is cut along both, a
    // disk's rays split where they cross them.
    let view = super::normalize_or_zero(surface.camera - surface.position);
    let normal = super::normalize_or_zero(surface.normal);
    let mirror = super::reflect(-view, normal);
    let offset = light.position - surface.position;
    let line = |plane: DVec3| {
        (
            plane.dot(light.right),
            plane.dot(light.up),
            plane.dot(offset),
        )
    };
    let mut lines = vec![line(normal), line(mirror)];
    // The surface point's foot on the light's plane: where `1 / r²` peaks.
    let mut near = (-offset.dot(light.right), -offset.dot(light.up));
    // A narrow highlight peaks where the mirror ray meets the light's plane, a peak narrower
    // than the rule's nodes are apart: the pieces are also cut along the two lines through
    // that point, and integrated around it (a peak inside a piece could be missed, and one on
    // a piece's far corner takes every inner integral's halving).
    let reach = light.facing().dot(offset) / light.facing().dot(mirror);
    if material.shininess > SHARP_HIGHLIGHT && reach > 0.0 && reach.is_finite() {
        let hit = mirror * reach - offset;
        near = (hit.dot(light.right), hit.dot(light.up));
        lines.extend([(1.0, 0.0, -near.0), (0.0, 1.0, -near.1)]);
    }
    let pieces = match light.shape {
        AreaShape::Rect { width, height } => {
            let (x, y) = (0.5 * width, 0.5 * height);
            cut(vec![(-x, -y), (x, -y), (x, y), (-x, y)], &lines)
        }
        AreaShape::Disk { .. } => Vec::new(),
    };
    // A first pass at a loose tolerance gives the scale the tolerance is relative to.
    let integral = |tolerance: f64| -> DVec3 {
        match light.shape {
            AreaShape::Rect { .. } => pieces
                .iter()
                .map(|piece| {
                    integrate_polygon(
                        &mut |x, y| element(x, y),
                        piece,
                        near,
                        tolerance / pieces.len() as f64,
                    )
                })
                .fold(DVec3::ZERO, |sum, part| sum + part),
            AreaShape::Disk { radius } => {
                integrate_disk(&mut |x, y| element(x, y), radius, near, &lines, tolerance)
            }
        }
    };
    let brightest = color.max(specular).max_element();
    let scale = integral(1e-3 * brightest);
    // Below ABSOLUTE_FLOOR of the light's color per unit area no term matters; the floor
    // keeps a point the light barely reaches from being halved down to the last bit.
    let tolerance = (relative_tolerance * scale.max_element()).max(ABSOLUTE_FLOOR * brightest);
    fall_off * integral(tolerance)
}
