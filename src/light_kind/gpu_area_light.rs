//! The record of an area light in the light buffer (`PhongAreaLight` in
//! `bevy_phong::shaders::types`): as long as a [`GpuLight`](super::GpuLight), after the
//! local lights (see [`GpuLightsHeader`](crate::render::GpuLightsHeader)).

use super::GpuLight;
use super::built_in::{brightest_channel, intensities, unlimited_past_max};
use crate::lights::{AreaHighlight, Decay, PhongShadows};
use crate::shadows::{PhongShadowProjection, PhongShadowRequest};
use bevy::{color::Color, math::Vec3, shape::BoundingSphere};
use bytemuck::{Pod, Zeroable};

/// One area light as the shader reads it (`PhongAreaLight` in WGSL): 80 bytes, the size of a
/// [`GpuLight`](super::GpuLight), whose place it takes in the light buffer.
///
/// The shape is a rectangle around `center` spanned by its two half-extent vectors (its
/// corners are `center ± half_width ± half_height`), or with [`Self::DISK`] the disk of
/// radius `|half_width| = |half_height|` in their plane. The light faces
/// `half_height × half_width` (its entity's local −Z). Colors are per unit area (the
/// component's color over `|S|`, computed in `f64`), so that the shader multiplies them by
/// the integrals over the light's solid angle.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuAreaLight {
    /// World-space center of the shape.
    pub center: [f32; 3],
    /// Distance from the light's nearest point past which it is cut off: its reach, its range
    /// shortened where its light falls below ε, which the gather writes
    /// ([`PhongLightKind::set_reach`](crate::extension::PhongLightKind::set_reach));
    /// `f32::MAX` when unlimited, and in a record as `unplaced` makes it.
    pub reach: f32,
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
    /// [`Self::TWO_SIDED`], [`Self::REPRESENTATIVE_POINT`], [`Self::DISK`] and
    /// [`Self::FITTED`].
    pub flags: u32,
}

impl GpuAreaLight {
    /// The area lights of a run of the light buffer's records (its area sections, which
    /// hold them in [`GpuLight`]s' places): the typed view of them.
    pub(crate) fn in_records(records: &[GpuLight]) -> &[Self] {
        bytemuck::cast_slice(records)
    }

    /// The area light of one record of an area section ([`Self::in_records`]).
    pub(crate) fn in_record(record: &GpuLight) -> &Self {
        bytemuck::cast_ref(record)
    }

    /// The light emits from both faces.
    pub const TWO_SIDED: u32 = 1 << 16;
    /// Its highlight is taken at a representative point
    /// ([`AreaHighlight::RepresentativePoint`](crate::AreaHighlight::RepresentativePoint)).
    pub const REPRESENTATIVE_POINT: u32 = 1 << 17;
    /// The shape is a disk ([`PhongDiskLight`](crate::PhongDiskLight)), not a rectangle.
    pub const DISK: u32 = 1 << 18;
    /// Its highlight is the fitted lobe's ([`AreaHighlight::Fitted`](crate::AreaHighlight::Fitted)).
    pub const FITTED: u32 = 1 << 19;
    /// Its highlight is the lobe integrated exactly at any exponent
    /// ([`AreaHighlight::Exact`](crate::AreaHighlight::Exact)); without it (and without
    /// another highlight flag), exactly up to a bounded cost
    /// ([`AreaHighlight::Bounded`](crate::AreaHighlight::Bounded)).
    pub const EXACT: u32 = 1 << 20;

    /// The record of an area light of `shape` at the identity transform (see
    /// [`UnplacedShape`]), its colors per unit area computed in `f64` (zero for a shape
    /// without area).
    pub(crate) fn unplaced(
        shape: UnplacedShape,
        (color, specular): (Color, Option<Color>),
        decay: Decay,
        (two_sided, highlight): (bool, AreaHighlight),
    ) -> Self {
        let (color, specular) = intensities(color, specular);
        let per_area = |channels: [f32; 3]| {
            channels.map(|channel| {
                if shape.area > 0.0 {
                    (f64::from(channel) / shape.area).min(f64::from(f32::MAX)) as f32
                } else {
                    0.0
                }
            })
        };
        let mut flags = shape.flags;
        if two_sided {
            flags |= Self::TWO_SIDED;
        }
        flags |= match highlight {
            AreaHighlight::Bounded => 0,
            AreaHighlight::Exact => Self::EXACT,
            AreaHighlight::RepresentativePoint => Self::REPRESENTATIVE_POINT,
            AreaHighlight::Fitted => Self::FITTED,
        };
        GpuAreaLight {
            center: [0.0; 3],
            reach: f32::MAX,
            half_width: [shape.half_extents[0], 0.0, 0.0],
            half_height: [0.0, shape.half_extents[1], 0.0],
            color: per_area(color),
            specular: per_area(specular),
            decay: decay.to_array(),
            flags,
        }
    }

    /// Moves a record made at the identity transform (its half extents along X and Y) by
    /// `transform`'s translation and rotation (scale ignored).
    pub(crate) fn place(&mut self, transform: &bevy::transform::components::GlobalTransform) {
        let (_, rotation, translation) = transform.to_scale_rotation_translation();
        self.center = translation.to_array();
        self.half_width = (rotation * Vec3::from(self.half_width)).to_array();
        self.half_height = (rotation * Vec3::from(self.half_height)).to_array();
    }

    /// Stores `slot` (the index of the light's first shadow view plus one, `0` for none) in
    /// [`flags`](Self::flags)' low half.
    pub(crate) fn set_shadow_slot(&mut self, slot: u32) {
        let shadow_bits = super::GpuLight::SHADOW_BITS;
        self.flags = (self.flags & !shadow_bits) | (slot & shadow_bits);
    }

    /// The light's size for its soft shadows: the radius of the disk of its area, world
    /// units (a disk's own radius).
    pub(crate) fn light_size(&self) -> f32 {
        (self.area() / core::f32::consts::PI).sqrt()
    }

    /// The shadow the light of `range` casts with `settings`: a cube of maps from its center
    /// (percentage-closer soft shadows with [`Self::light_size`] as the light's size, in
    /// place of `settings.softness`), reaching its range past its shape.
    pub(crate) fn shadow_request(
        &self,
        settings: PhongShadows,
        range: Option<f32>,
    ) -> PhongShadowRequest {
        PhongShadowRequest {
            projection: PhongShadowProjection::Omni {
                position: Vec3::from(self.center),
            },
            settings: PhongShadows {
                softness: self.light_size(),
                ..settings
            },
            reach: range.unwrap_or(f32::INFINITY) + self.circumradius(),
        }
    }

    /// Whether the shape is a disk.
    fn is_disk(&self) -> bool {
        self.flags & Self::DISK != 0
    }

    /// The shape's area `|S|`, world units squared: `4 |w| |h|` for a rectangle, `π |w| |h|`
    /// for a disk.
    pub(crate) fn area(&self) -> f32 {
        let factor = if self.is_disk() {
            core::f32::consts::PI
        } else {
            4.0
        };
        factor * Vec3::from(self.half_width).length() * Vec3::from(self.half_height).length()
    }

    /// The distance from the center to the shape's farthest point: a rectangle's half
    /// diagonal, a disk's radius.
    fn circumradius(&self) -> f32 {
        let (half_width, half_height) = (Vec3::from(self.half_width), Vec3::from(self.half_height));
        if self.is_disk() {
            half_width.length().max(half_height.length())
        } else {
            (half_width + half_height).length()
        }
    }

    /// How far the light of `range` reaches from its nearest point for the per-light
    /// `epsilon` (see
    /// [`PhongLightKind::reach`](crate::extension::PhongLightKind::reach)): its range,
    /// shortened where its light falls below ε. At distance `d` from its nearest point, each
    /// of its points is at least `d` away, so its solid angle is at most `|S| / d²` and its
    /// light at most `I · A(d) / d²` (`I` its largest channel times `|S|`, `A` the decay):
    /// below ε past `√(I / ε)`, and past `max(r, 1)` for the decay's influence radius `r`.
    /// `f32::INFINITY` where neither limits it; `0` for a light without area.
    pub(crate) fn reach(&self, range: Option<f32>, epsilon: f32) -> f32 {
        let area = self.area();
        // A NaN area too.
        if area.is_nan() || area <= 0.0 {
            return 0.0;
        }
        let intensity = brightest_channel(self.color, self.specular) * area;
        let inverse_square = (intensity / epsilon).sqrt();
        let decayed = crate::lights::influence_radius(self.decay, intensity, epsilon).max(1.0);
        let range = range.unwrap_or(f32::INFINITY);
        unlimited_past_max(range.min(inverse_square).min(decayed))
    }

    /// A sphere around the light's shape grown by `reach`, for the clusters; `None` for an
    /// unlimited reach.
    pub(crate) fn bounding_sphere(&self, reach: f32) -> Option<BoundingSphere> {
        (reach < f32::MAX)
            .then(|| BoundingSphere::new(Vec3::from(self.center), reach + self.circumradius()))
    }
}

/// An area light's shape as its record holds it before its transform places it: its half
/// extents along local X and Y, its area (`f64`, for the colors per unit area) and the flag
/// that names it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct UnplacedShape {
    pub half_extents: [f32; 2],
    pub area: f64,
    pub flags: u32,
}

/// What every built-in area kind (rect, disk) does alike as a [`PhongLightKind`](super::PhongLightKind):
/// its record is `Self::unplaced_record()` placed by the transform's translation and
/// rotation, it shares ε with the point and spot lights and reaches as
/// [`GpuAreaLight::reach`] says, it is clustered by the sphere around its shape, it casts
/// the shadow of its `shadows` as [`GpuAreaLight::shadow_request`] says, and its
/// reference-model light is `Self::REFERENCE`.
macro_rules! area_light_kind {
    () => {
        type Gpu = $crate::light_kind::GpuAreaLight;
        const SHARES_EPSILON: bool = true;

        fn to_gpu(
            &self,
            transform: &bevy::transform::components::GlobalTransform,
        ) -> $crate::light_kind::GpuAreaLight {
            let mut record = self.unplaced_record();
            record.place(transform);
            record
        }

        fn place(
            record: &mut $crate::light_kind::GpuAreaLight,
            transform: &bevy::transform::components::GlobalTransform,
        ) -> bool {
            record.place(transform);
            true
        }

        fn reach(&self, record: &$crate::light_kind::GpuAreaLight, epsilon: f32) -> f32 {
            record.reach(self.range, epsilon)
        }

        fn set_reach(record: &mut $crate::light_kind::GpuAreaLight, reach: f32) {
            record.reach = $crate::light_kind::built_in::stored_reach(reach);
        }

        fn bounding_sphere(
            record: &$crate::light_kind::GpuAreaLight,
            reach: f32,
        ) -> Option<bevy::shape::BoundingSphere> {
            record.bounding_sphere(reach)
        }

        fn casts_shadows(&self) -> bool {
            self.shadows.enabled
        }

        fn shadow(
            &self,
            transform: &bevy::transform::components::GlobalTransform,
        ) -> Option<$crate::shadows::PhongShadowRequest> {
            Some(
                self.to_gpu(transform)
                    .shadow_request(self.shadows, self.range),
            )
        }

        fn set_shadow(record: &mut $crate::light_kind::GpuAreaLight, shadow: u32) {
            record.set_shadow_slot(shadow);
        }

        #[cfg(feature = "reference")]
        fn reference_light(
            &self,
            transform: &bevy::transform::components::GlobalTransform,
        ) -> Option<std::sync::Arc<dyn $crate::reference::ReferenceLight>> {
            Some(std::sync::Arc::new(Self::REFERENCE(self, transform)))
        }
    };
}
pub(crate) use area_light_kind;

const _: () = assert!(size_of::<GpuAreaLight>() == size_of::<GpuLight>());
