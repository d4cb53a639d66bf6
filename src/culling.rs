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

/// The distance (world units) past which a light of largest channel `intensity` with
/// distance fall-off `1 / (constant + linear·d + quadratic·d²)` stays below `epsilon`:
/// `f32::INFINITY` when it never does (no fall-off, or `epsilon ≤ 0`), `0` when it never
/// reaches `epsilon` at all. Computed in `f64`, rounded up. For example
/// `1 / (1 + 0.09·d + 0.032·d²)` falls to 1/256 at about 88 units.
pub fn influence_radius(decay: [f32; 3], intensity: f32, epsilon: f32) -> f32 {
    if epsilon.is_nan() || epsilon <= 0.0 {
        return f32::INFINITY;
    }
    if intensity.is_nan() || intensity < epsilon {
        // A ≤ 1, so the light is below ε everywhere (also for a NaN intensity).
        return 0.0;
    }
    let [constant, linear, quadratic] = decay.map(f64::from);
    // I · A(d) < ε  ⇔  constant + linear·d + quadratic·d² > I / ε  (A's min(1, …) aside,
    // which only matters where I / ε ≤ 1, handled above).
    let threshold = f64::from(intensity) / f64::from(epsilon) - constant;
    let radius = if threshold <= 0.0 {
        0.0
    } else if quadratic > 0.0 {
        // The positive root of quadratic·d² + linear·d - threshold, in the form without
        // cancellation.
        2.0 * threshold / (linear + (linear * linear + 4.0 * quadratic * threshold).sqrt())
    } else if linear > 0.0 {
        threshold / linear
    } else {
        f64::INFINITY
    };
    let rounded = radius as f32;
    if f64::from(rounded) < radius {
        rounded.next_up()
    } else {
        rounded
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The boundaries of `influence_radius`: a light exactly at ε reaches ε out to where its
    /// fall-off begins (1 unit for `1/d²`), one below ε reaches nowhere, and so does a NaN
    /// intensity.
    #[test]
    fn a_light_at_epsilon_reaches_to_its_fall_off_and_one_below_or_nan_nowhere() {
        let epsilon = 1.0 / 256.0;
        let inverse_square = [0.0, 0.0, 1.0];
        assert_eq!(influence_radius(inverse_square, epsilon, epsilon), 1.0);
        assert_eq!(
            influence_radius(inverse_square, 0.5 * epsilon, epsilon),
            0.0
        );
        assert_eq!(influence_radius(inverse_square, f32::NAN, epsilon), 0.0);
    }

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

    /// The radius is rounded up to the next `f32`: at or past the exact radius (the root of
    /// `constant + linear·d + quadratic·d² = I / ε`, worked in `f64` in its textbook form),
    /// and the `f32` just below it falls short of the exact one.
    #[test]
    fn the_radius_is_the_exact_one_rounded_up_to_an_f32() {
        let epsilon = 1.0 / 1024.0;
        for step in 1..200 {
            let intensity = 0.01 * step as f32;
            let decay = [1.0, 0.3, 0.07];
            // The coefficients as the function takes them: `f32`s.
            let [constant, linear, quadratic] = decay.map(f64::from);
            let threshold = f64::from(intensity) / f64::from(epsilon) - constant;
            let exact = (-linear + (linear * linear + 4.0 * quadratic * threshold).sqrt())
                / (2.0 * quadratic);
            let radius = influence_radius(decay, intensity, epsilon);
            assert!(
                f64::from(radius) >= exact && f64::from(radius.next_down()) < exact,
                "intensity {intensity}: radius {:.17}, the f32 below it {:.17}, exact {exact:.17}",
                f64::from(radius),
                f64::from(radius.next_down())
            );
        }
    }

    #[test]
    fn the_common_opengl_decay_falls_to_one_256th_at_about_88_units() {
        let radius = influence_radius([1.0, 0.09, 0.032], 1.0, 1.0 / 256.0);
        assert!((radius - 88.0).abs() < 0.5, "{radius}");
    }
    use crate::reference;

    fn intensity_at(decay: [f32; 3], intensity: f32, distance: f32) -> f64 {
        f64::from(intensity)
            * reference::attenuation(f64::from(distance), decay.map(f64::from), None)
    }

    #[test]
    fn past_the_radius_a_light_stays_below_epsilon() {
        let epsilon = 1.0 / 4096.0;
        for (decay, intensity) in [
            ([1.0, 0.09, 0.032], 1.0),
            ([1.0, 0.0, 0.2], 3.0),
            ([1.0, 0.5, 0.0], 0.5),
            ([0.0, 0.0, 1.0], 100.0),
        ] {
            let radius = influence_radius(decay, intensity, epsilon);
            assert!(radius.is_finite() && radius > 0.0);
            for factor in [1.0, 1.0001, 2.0, 100.0] {
                let beyond = intensity_at(decay, intensity, radius * factor);
                assert!(
                    beyond <= f64::from(epsilon) * (1.0 + 1e-6),
                    "{decay:?} at {factor}× the radius: {beyond}"
                );
            }
            let inside = intensity_at(decay, intensity, radius * 0.999);
            assert!(
                inside > f64::from(epsilon),
                "{decay:?} just inside: {inside}"
            );
        }
    }

    #[test]
    fn lights_without_fall_off_or_epsilon_reach_everywhere() {
        assert_eq!(influence_radius([1.0, 0.0, 0.0], 1.0, 1e-3), f32::INFINITY);
        assert_eq!(influence_radius([1.0, 0.0, 0.2], 1.0, 0.0), f32::INFINITY);
        assert_eq!(
            influence_radius([1.0, 0.0, 0.2], 1.0, f32::NAN),
            f32::INFINITY
        );
    }

    #[test]
    fn lights_dimmer_than_epsilon_reach_nowhere() {
        assert_eq!(influence_radius([1.0, 0.0, 0.2], 1e-4, 1e-3), 0.0);
        assert_eq!(influence_radius([1.0, 0.0, 0.2], 0.0, 1e-3), 0.0);
        assert_eq!(influence_radius([4.0, 0.0, 0.2], 2e-3, 1e-3), 0.0);
    }
}
