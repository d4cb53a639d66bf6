//! The record of an area light in the light buffer (`PhongAreaLight` in
//! `bevy_phong::shaders::types`): as long as a [`GpuLight`](super::GpuLight), after the
//! local lights (see [`GpuLightsHeader`](crate::render::GpuLightsHeader)).

use super::built_in::{brightest_channel, unlimited_past_max};
use bevy::{math::Vec3, shape::BoundingSphere};
use bytemuck::{Pod, Zeroable};

/// One area light as the shader reads it (`PhongAreaLight` in WGSL): 80 bytes, the size of a
/// [`GpuLight`](super::GpuLight), whose place it takes in the light buffer.
///
/// The shape is a rectangle around `center` spanned by its two half-extent vectors: its
/// corners are `center ± half_width ± half_height`. The light faces
/// `half_height × half_width` (its entity's local −Z). Colors are per unit area (the
/// component's color over `|S|`, computed in `f64`), so that the shader multiplies them by
/// the integrals over the light's solid angle.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuAreaLight {
    /// World-space center of the shape.
    pub center: [f32; 3],
    /// Distance from the light's nearest point past which it is cut off; `f32::MAX` when
    /// unlimited.
    pub range: f32,
    /// Half the width along the light's local X, world units.
    pub half_width: [f32; 3],
    /// Half the height along the light's local Y, world units.
    pub half_height: [f32; 3],
    /// Diffuse intensity per unit area, linear RGB.
    pub color: [f32; 3],
    /// Specular intensity per unit area, linear RGB.
    pub specular: [f32; 3],
    /// `[constant, linear, quadratic]` fall-off, at the distance to the light's nearest
    /// point.
    pub decay: [f32; 3],
    /// In the low 16 bits the light's shadow slot (`0`: none, as
    /// [`GpuLight::shadow`](super::GpuLight::shadow)); above them the flags
    /// [`Self::TWO_SIDED`] and [`Self::REPRESENTATIVE_POINT`].
    pub flags: u32,
}

impl GpuAreaLight {
    /// The light emits from both faces.
    pub const TWO_SIDED: u32 = 1 << 16;
    /// Its highlight is taken at a representative point
    /// ([`AreaHighlight::RepresentativePoint`](crate::AreaHighlight::RepresentativePoint)).
    pub const REPRESENTATIVE_POINT: u32 = 1 << 17;

    /// The shape's area `|S|`, world units squared.
    pub(crate) fn area(&self) -> f32 {
        4.0 * Vec3::from(self.half_width).length() * Vec3::from(self.half_height).length()
    }

    /// How far the light reaches from its nearest point for the per-light `epsilon` (see
    /// [`PhongLightKind::reach`](crate::extension::PhongLightKind::reach)): its range,
    /// shortened where its light falls below ε. At distance `d` from its nearest point, each
    /// of its points is at least `d` away, so its solid angle is at most `|S| / d²` and its
    /// light at most `I · A(d) / d²` (`I` its largest channel times `|S|`, `A` the decay):
    /// below ε past `√(I / ε)`, and past `max(r, 1)` for the decay's influence radius `r`.
    /// `f32::INFINITY` where neither limits it; `0` for a light without area.
    pub(crate) fn reach(&self, epsilon: f32) -> f32 {
        let area = self.area();
        // A NaN area too.
        if area.is_nan() || area <= 0.0 {
            return 0.0;
        }
        let intensity = brightest_channel(self.color, self.specular) * area;
        let inverse_square = (intensity / epsilon).sqrt();
        let decayed = crate::lights::influence_radius(self.decay, intensity, epsilon).max(1.0);
        unlimited_past_max(self.range.min(inverse_square).min(decayed))
    }

    /// A sphere around the light's shape grown by `reach`, for the clusters; `None` for an
    /// unlimited reach.
    pub(crate) fn bounding_sphere(&self, reach: f32) -> Option<BoundingSphere> {
        let corner = Vec3::from(self.half_width) + Vec3::from(self.half_height);
        (reach < f32::MAX)
            .then(|| BoundingSphere::new(Vec3::from(self.center), reach + corner.length()))
    }
}

const _: () = assert!(size_of::<GpuAreaLight>() == size_of::<super::GpuLight>());
