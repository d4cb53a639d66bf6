//! Skipping the lights that cannot reach a surface point: each point and spot light's
//! influence radius, and the clusters of each camera's view that list the lights that may
//! reach them.
//!
//! A point or spot light reaches no further than its `range`. With [`PhongLightCulling`]'s
//! `epsilon` (ε) above zero it also stops where its light has faded below `ε / n`, `n` being
//! the number of point and spot lights: its *influence radius* is the distance past which
//! `I · A(d) < ε / n`, where `I` is its largest color or specular channel and `A` its
//! [`Decay`](crate::Decay). Out there it is skipped. Together the skipped lights change an
//! output channel by less than `ε · (k_d + k_s · strength)` (under `2ε` for white,
//! full-strength material colors), however many lights the scene has. A light without
//! fall-off (`Decay::NONE`) has no influence radius.
//!
//! Lights with a finite reach (a range, an influence radius, or both) are listed in
//! clusters, per camera: each active 3D camera's view is cut into tiles of the screen ×
//! slices of depth ([`PhongViewClusters`], 16 × 9 × 24 by default, as Bevy cuts its own), and
//! each cluster lists the lights whose sphere may meet it. A fragment finds its view's
//! cluster and loops only over the lights listed there; lights of unlimited reach and
//! directional lights are looped over by every fragment. So a light that reaches no
//! camera's view costs no fragment anything, however large the world. Listing is
//! conservative: a light is listed in every cluster its sphere may touch, so clusters
//! change no result. See `render::clusters` for the cut and `view_key` for how a
//! fragment finds its view.

use bevy::{
    ecs::{component::Component, resource::Resource},
    math::UVec2,
    prelude::{ReflectComponent, ReflectDefault, ReflectResource},
    reflect::Reflect,
};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// How the plugin skips the lights that cannot reach a surface point. A resource: insert
/// it to change the default; changing it rewrites the light buffers in the same frame.
///
/// ```
/// # use bevy::prelude::*;
/// # use bevy_phong::PhongLightCulling;
/// fn setup(app: &mut App) {
///     // Skip lights where they have faded below a quarter of an 8-bit step.
///     app.insert_resource(PhongLightCulling {
///         epsilon: 1.0 / 1024.0,
///         ..default()
///     });
/// }
/// ```
#[derive(Resource, Clone, Copy, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Resource, Default, Debug, PartialEq, Clone)]
#[cfg_attr(feature = "scene", serde(default))]
pub struct PhongLightCulling {
    /// ε, in the units of light colors (linear RGB, where 1 is a full channel): each of the
    /// `n` point and spot lights is skipped where its attenuated intensity falls below
    /// `ε / n`, so that all skipped lights together change an output channel by less than
    /// `ε · (k_d + k_s · strength)`. `0` skips only past each light's `range`: the exact
    /// SPEC.md model. Default [`PhongLightCulling::DEFAULT_EPSILON`].
    pub epsilon: f32,
    /// Whether lights of finite reach are listed in each view's clusters, so that a fragment
    /// loops over the lights of its cluster instead of all of them. Exact either way.
    /// Default `true`.
    pub clusters: bool,
}

impl PhongLightCulling {
    /// The default ε, 1/1024: on a white, full-strength material (`k_d + k_s · strength`
    /// = 2) culling changes a channel by less than 1/512, under half an 8-bit step, so an
    /// 8-bit image rounds to the same value or its neighbour.
    pub const DEFAULT_EPSILON: f32 = 1.0 / 1024.0;

    /// No skipping by ε (only ranges), no clusters: every fragment loops over every light,
    /// as SPEC.md writes the sum.
    pub const NONE: Self = Self {
        epsilon: 0.0,
        clusters: false,
    };

    /// The exact model (ε = 0) with clusters: lights are skipped only past their range.
    pub const EXACT: Self = Self {
        epsilon: 0.0,
        clusters: true,
    };
}

impl Default for PhongLightCulling {
    fn default() -> Self {
        Self {
            epsilon: Self::DEFAULT_EPSILON,
            clusters: true,
        }
    }
}

/// How a camera's view is cut into light clusters: `tiles.x × tiles.y` tiles of the screen
/// times `slices` slices of depth (logarithmic from the projection's `near` to its `far` for
/// a perspective camera, even for an orthographic one, one slice for a custom projection).
/// A component on a camera; without it a camera gets [`PhongViewClusters::default`].
///
/// Finer clusters list fewer lights per fragment but cost more to fill on the CPU and more
/// memory (16 bytes per cluster, 4 per light listed). Values are clamped to
/// `1..=`[`Self::MAX_TILES`] tiles along each axis and `1..=`[`Self::MAX_SLICES`] slices.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, Reflect)]
#[reflect(Component, Default, Debug, PartialEq, Clone)]
pub struct PhongViewClusters {
    /// Tiles across and down the view. Default 16 × 9.
    pub tiles: UVec2,
    /// Slices of depth. Default 24.
    pub slices: u32,
}

impl PhongViewClusters {
    /// Most tiles along one axis.
    pub const MAX_TILES: u32 = 64;
    /// Most depth slices.
    pub const MAX_SLICES: u32 = 64;

    /// These values brought into their ranges.
    pub fn clamped(self) -> Self {
        Self {
            tiles: self.tiles.clamp(UVec2::ONE, UVec2::splat(Self::MAX_TILES)),
            slices: self.slices.clamp(1, Self::MAX_SLICES),
        }
    }
}

impl Default for PhongViewClusters {
    fn default() -> Self {
        Self {
            tiles: UVec2::new(16, 9),
            slices: 24,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A camera's clusters are brought into `1..=64` tiles along each axis and `1..=64`
    /// slices; values inside stay as they are.
    #[test]
    fn view_clusters_are_clamped_into_their_ranges() {
        let clamped = PhongViewClusters {
            tiles: UVec2::new(0, 1000),
            slices: 0,
        }
        .clamped();
        assert_eq!(
            clamped,
            PhongViewClusters {
                tiles: UVec2::new(1, PhongViewClusters::MAX_TILES),
                slices: 1,
            }
        );
        let inside = PhongViewClusters {
            tiles: UVec2::new(7, 3),
            slices: 40,
        };
        assert_eq!(inside.clamped(), inside);
    }
}
