//! Shadow settings: every built-in light has a [`PhongShadows`], the directional light also
//! [`PhongCascades`].

use bevy::{prelude::ReflectDefault, reflect::Reflect};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// How a light casts shadows (SPEC.md, "Shadows"). Off by default, as Bevy's lights.
///
/// The light's shadow maps are rendered from its point of view each frame by the plugin:
/// one map for a spot light, six (a cube) for a point light, one per cascade for a
/// directional light (see [`PhongCascades`]). Meshes with Bevy's `NotShadowCaster` cast no
/// shadow; meshes with `NotShadowReceiver` are lit as if nothing were in the way.
///
/// Values out of range are replaced with one warning naming the entity and field (see
/// `crate::validation`): a NaN bias, softness or fraction counts as 0 and a NaN
/// `near_distance` as 0.1; biases and softness are clamped to `[0, 1e6]`, fractions to
/// `[0, 1]`, `near_distance` to `[1e-6, 1e6]`, the resolution to `[16, 4096]`.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Default, Debug, PartialEq, Clone)]
#[cfg_attr(feature = "scene", serde(default, deny_unknown_fields))]
pub struct PhongShadows {
    /// Whether the light casts shadows. Default `false`.
    pub enabled: bool,
    /// Edge length of each of the light's shadow maps, in texels, within `[16, 4096]`.
    /// Default 1024.
    pub resolution: u32,
    /// How far the comparison point is moved toward the light, in world units, `≥ 0`: fights
    /// acne on surfaces facing the light; too large and shadows detach from their casters.
    /// Default `0.02`.
    pub depth_bias: f32,
    /// How far the comparison point is moved along the surface normal, in shadow-map texels
    /// (the world size of one texel where the surface is), `≥ 0`: fights acne on surfaces at
    /// grazing angles. Default `1.0`.
    pub normal_bias: f32,
    /// The size of the light, which sets how fast the penumbra widens with the distance
    /// between a blocker and the surface it shades (percentage-closer soft shadows): the
    /// radius in world units of a point or spot light, the angular radius in degrees of a
    /// directional light (the sun: about `0.27`). `0` (the default) gives the sharpest edge
    /// the map resolves (a bilinear comparison, one texel wide).
    pub softness: f32,
    /// Point and spot lights: the distance from the light, world units, `> 0`, inside which
    /// nothing casts a shadow (the near plane of their shadow maps; larger values give
    /// their depth finer precision). Default `0.1`.
    pub near_distance: f32,
    /// The fraction of the light's diffuse term that reaches a fully shadowed point, in
    /// `[0, 1]`. Default `0`: a shadowed point gets none of the light.
    pub diffuse_in_shadow: f32,
    /// The fraction of the light's highlight that reaches a fully shadowed point, in
    /// `[0, 1]`. Default `0`.
    pub specular_in_shadow: f32,
}

impl Default for PhongShadows {
    fn default() -> Self {
        Self::OFF
    }
}

impl PhongShadows {
    /// The defaults: shadows off.
    pub const OFF: Self = Self {
        enabled: false,
        resolution: 1024,
        depth_bias: 0.02,
        normal_bias: 1.0,
        softness: 0.0,
        near_distance: 0.1,
        diffuse_in_shadow: 0.0,
        specular_in_shadow: 0.0,
    };

    /// Shadows on, with the default settings.
    pub const ON: Self = Self {
        enabled: true,
        ..Self::OFF
    };

    /// Shadows that dim the diffuse term to 10 % and leave the highlight whole, the look of
    /// classic per-pixel lighting demos.
    pub const DIFFUSE_DIMMED: Self = Self {
        diffuse_in_shadow: 0.1,
        specular_in_shadow: 1.0,
        ..Self::ON
    };

    /// Smallest [`resolution`](Self::resolution).
    pub const MIN_RESOLUTION: u32 = 16;
    /// Largest [`resolution`](Self::resolution).
    pub const MAX_RESOLUTION: u32 = 4096;
}

/// How a directional light's shadow is split along the camera's view (cascaded shadow maps):
/// each cascade is a shadow map covering one slice of the view's depth, nearer slices with
/// finer texels. Every active 3D camera gets cascades of its own, fitted to its own view
/// (cameras with the same frustum share them); the settings here apply to each.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Default, Debug, PartialEq, Clone)]
#[cfg_attr(feature = "scene", serde(default, deny_unknown_fields))]
pub struct PhongCascades {
    /// Number of cascades, `1..=4`. Default 4.
    pub count: u32,
    /// View depth (world units from the camera) where the first cascade ends; the others
    /// end at distances growing geometrically from it to [`max_distance`](Self::max_distance).
    /// Default 5.
    pub first_far_bound: f32,
    /// View depth past which nothing is shadowed, world units. Default 100.
    pub max_distance: f32,
    /// The fraction of each cascade, at its far end, over which it blends into the next
    /// (no visible seam), in `[0, 1)`. Default `0.2`.
    pub overlap: f32,
}

impl Default for PhongCascades {
    fn default() -> Self {
        Self {
            count: 4,
            first_far_bound: 5.0,
            max_distance: 100.0,
            overlap: 0.2,
        }
    }
}

impl PhongCascades {
    /// Largest [`count`](Self::count).
    pub const MAX_COUNT: u32 = 4;

    /// The view depth where each cascade ends, nearest first: `first_far_bound` times a
    /// constant ratio up to `max_distance` (one cascade ends at `max_distance`).
    pub fn far_bounds(&self) -> Vec<f32> {
        let count = self.count.clamp(1, Self::MAX_COUNT);
        if count == 1 {
            return vec![self.max_distance];
        }
        let first = self.first_far_bound.min(self.max_distance);
        let ratio = (self.max_distance / first).powf(1.0 / (count - 1) as f32);
        (0..count).map(|i| first * ratio.powi(i as i32)).collect()
    }
}
