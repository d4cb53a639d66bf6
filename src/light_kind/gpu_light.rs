//! The record the built-in kinds share in the light buffer (`PhongLight` in
//! `bevy_phong::shaders::types`); a test compares its layout with the one naga reflects.

use bytemuck::{Pod, Zeroable};

/// One light as the shader reads it (`PhongLight` in WGSL): 80 bytes.
///
/// Every kind uses the same record; the fields a kind does not use are zero. Colors are
/// linear RGB, positions world-space. The local lights (point and spot) are one kind to the
/// shader: each has a cone, stored as `1 - cos` (which keeps its precision for narrow cones
/// where the cosine rounds to 1); a point light's is the whole sphere ([`Self::WHOLE_SPHERE`]
/// around a zero direction), whose factor is exactly 1.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    /// World-space position (point, spot).
    pub position: [f32; 3],
    /// Distance past which the light is cut off (point, spot): its reach, its range shortened
    /// where its light falls below ε, which the gather writes
    /// ([`PhongLightKind::set_reach`](crate::extension::PhongLightKind::set_reach));
    /// `f32::MAX` when unlimited, and in a record as `to_gpu` makes it.
    pub reach: f32,
    /// Unit vector along which the light travels (directional, spot); zero for a point light.
    pub direction: [f32; 3],
    /// `1 - cos(outer_angle)` (spot), computed in `f64`; `-1` for an empty cone;
    /// [`Self::WHOLE_SPHERE`] for a point light.
    pub outer_versine: f32,
    /// Diffuse intensity, linear RGB.
    pub color: [f32; 3],
    /// `1 / (cos(inner) - cos(outer))`, computed in `f64`, negated for a smooth edge, or `0`
    /// for a hard edge (spot).
    pub cone_scale: f32,
    /// Specular intensity, linear RGB.
    pub specular: [f32; 3],
    /// Exponent of the `cos(θ)^exponent` rim darkening (spot).
    pub cone_exponent: f32,
    /// `[constant, linear, quadratic]` distance fall-off (point, spot).
    pub decay: [f32; 3],
    /// Two 16-bit indices: in the low half, the index of the light's first shadow view plus
    /// one, or `0` for a light that casts no shadow this frame; in the high half, the index of
    /// its cookie's record (`GpuCookie`, after the lights) plus one, or `0` for none.
    pub shadow: u32,
}

impl GpuLight {
    /// The first bit of the cookie's record index in [`shadow`](Self::shadow).
    pub const COOKIE_SHIFT: u32 = 16;
    /// The bits of the shadow view's index in [`shadow`](Self::shadow).
    pub const SHADOW_BITS: u32 = 0xffff;
    /// The [`outer_versine`](Self::outer_versine) of a point light's cone, `1 - cos π`: with
    /// a zero [`direction`](Self::direction), every ray's `1 - cos θ` is `|L|² / 2 = 1/2`
    /// (or `0` for no ray), inside it, and with a hard edge and no rim darkening the cone's
    /// factor is exactly 1.
    pub const WHOLE_SPHERE: f32 = 2.0;

    /// Stores `slot` (the index of the light's first shadow view plus one, `0` for none) in
    /// [`shadow`](Self::shadow)'s low half.
    pub(crate) fn set_shadow_slot(&mut self, slot: u32) {
        self.shadow = (self.shadow & !Self::SHADOW_BITS) | slot;
    }

    /// Stores `index` (its cookie's record index plus one, `0` for none) in
    /// [`shadow`](Self::shadow)'s high half.
    pub(crate) fn set_cookie_index(&mut self, index: u32) {
        self.shadow = (self.shadow & Self::SHADOW_BITS) | index << Self::COOKIE_SHIFT;
    }
}
