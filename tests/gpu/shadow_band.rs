//! How far from the true shadow's edge a shadow map's estimate of `V` may differ from the
//! exact one: the band's half-width `b` at a point `P`, bounded from the light's settings and
//! the camera, as SPEC.md ("Shadows") says what each map covers. The crate's own texel sizes
//! are not read: were its maps coarser than its settings promise, pixels would disagree
//! outside this band and the shadow tests would fail.
//!
//! ```text
//! b = (4 + normal_bias) · t + depth_bias / max(N·L, 0.2) + penumbra
//! ```
//!
//! `t` is an upper bound of the world size of a shadow-map texel at `P`:
//!
//! - a spot light whose cone is at most 60° wide at each side has one perspective map over its
//!   cone, widened by at most the filter's 16 texels at each side: at most
//!   `2 · z · tan(outer_angle) / (resolution − 32)` at depth `z` along its axis;
//! - a point light, or a wider spot, has a cube of six 90° faces widened the same way: at
//!   most `2 · m / (resolution − 32)`, `m` the largest of `|P − light|`'s three coordinates
//!   (the depth along the face `P` is seen in);
//! - a beam of parallel rays (an extension kind's `PhongShadowProjection::Beam`) has one
//!   orthographic map over its rectangle: at most `2 · h / resolution`, `h` its larger
//!   half-extent;
//! - a directional light has one orthographic map per cascade, a square around the sphere
//!   through the farthest of its slice's eight corners from their mean, the radius rounded up
//!   to a sixteenth of a world unit: at most `2 · (R + 1/16) / resolution`, the largest over
//!   the cascades whose slices (from where the previous one starts to blend) hold `P`'s view
//!   depth. The slices split the camera's view depth at `PhongCascades`' documented bounds.
//!
//! The terms of `b`: the bilinear comparison reads one texel at each side and the caster's
//! rasterized edge is off by up to one more; the casters' slope-scaled depth offset (their
//! depth change across 2 texels) moves an edge by up to 2 texels; the normal bias moves the
//! compared point `normal_bias` texels; the depth bias moves it `depth_bias` toward the light,
//! which shifts the edge on the receiver by up to `depth_bias / cos` (cosines under 0.2 are on
//! the unlit side of curved shapes, where the light gives nothing anyway); `penumbra` is, for a
//! soft light, the widest filter (16 texels at each side) plus the lift off the surface that
//! comes with it (as many texels along the normal): 32 texels; 0 for hard shadows.

use bevy::prelude::*;
use bevy_phong::prelude::*;
use bevy_phong_headless::{Harness, HarnessCamera};
use glam::DVec3;

/// Texels at each side of a map that its projection may add for the filter (SPEC.md: the
/// filter reaches at most 16 texels at each side).
const FILTER_MARGIN_TEXELS: f64 = 16.0;
/// Widest outer cone angle, radians, that SPEC.md gives a spot light's single map; past it
/// the light has a cube.
const WIDEST_SPOT_MAP: f64 = 60.0 * std::f64::consts::PI / 180.0;
/// The step a cascade's sphere radius is rounded up to, world units.
const CASCADE_RADIUS_STEP: f64 = 1.0 / 16.0;

/// What a light's shadow maps cover, as its settings say.
#[derive(Clone, Debug)]
pub(crate) enum MapCover {
    /// One perspective map over a cone along `axis` (unit) with half-angle `outer_angle`.
    Cone { axis: DVec3, outer_angle: f64 },
    /// A cube of six faces around the light.
    Cube,
    /// A directional light's cascades, fitted to the camera drawing `P`.
    Cascades(PhongCascades),
    /// A beam of parallel rays (`PhongShadowProjection::Beam`): one orthographic map over
    /// its rectangle, whose larger half-extent is `half_size` world units.
    Beam { half_size: f64 },
}

impl MapCover {
    /// A spot light's: one map up to a 60° cone, else a cube.
    pub fn spot(axis: Vec3, outer_angle: f32) -> Self {
        let outer_angle = f64::from(outer_angle);
        if outer_angle <= WIDEST_SPOT_MAP {
            MapCover::Cone {
                axis: axis.as_dvec3().normalize(),
                outer_angle,
            }
        } else {
            MapCover::Cube
        }
    }
}

/// The harness camera, as the cascades are fitted to it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ViewerCamera {
    eye: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    /// `tan` of half the vertical field of view.
    half_height: f64,
    aspect: f64,
    near: f64,
}

impl ViewerCamera {
    /// The harness camera as it is now (a perspective one).
    pub fn of(harness: &mut Harness) -> Self {
        let world = harness.world_mut();
        let (transform, projection) = world
            .query_filtered::<(&GlobalTransform, &Projection), With<HarnessCamera>>()
            .single(world)
            .expect("the harness camera");
        let Projection::Perspective(perspective) = projection else {
            panic!("the shadow tests' camera is a perspective one");
        };
        Self {
            eye: transform.translation().as_dvec3(),
            forward: transform.forward().as_dvec3(),
            right: transform.right().as_dvec3(),
            up: transform.up().as_dvec3(),
            half_height: (f64::from(perspective.fov) / 2.0).tan(),
            aspect: f64::from(perspective.aspect_ratio),
            near: f64::from(perspective.near),
        }
    }

    /// The eight world-space corners of the view between view depths `start` and `end`.
    fn slice_corners(&self, start: f64, end: f64) -> [DVec3; 8] {
        let mut corners = [DVec3::ZERO; 8];
        for (index, corner) in corners.iter_mut().enumerate() {
            let depth = if index < 4 { start } else { end };
            let x = if index % 2 == 0 { -1.0 } else { 1.0 };
            let y = if index % 4 < 2 { -1.0 } else { 1.0 };
            let half_height = depth * self.half_height;
            *corner = self.eye
                + depth * self.forward
                + x * half_height * self.aspect * self.right
                + y * half_height * self.up;
        }
        corners
    }
}

/// Where each cascade ends, nearest first: `first_far_bound` times a constant ratio up to
/// `max_distance` (one cascade ends at `max_distance`), as `PhongCascades` documents it.
fn cascade_ends(cascades: &PhongCascades) -> Vec<f64> {
    let count = cascades.count.clamp(1, PhongCascades::MAX_COUNT);
    let last = f64::from(cascades.max_distance);
    if count == 1 {
        return vec![last];
    }
    let first = f64::from(cascades.first_far_bound).min(last);
    let ratio = (last / first).powf(1.0 / f64::from(count - 1));
    (0..count).map(|i| first * ratio.powi(i as i32)).collect()
}

/// An upper bound of the world size of a texel of the maps of a light at `light` (unused
/// for a directional one and a beam) with `resolution`² maps covering `cover`, at
/// `position`; 0 where no cascade covers it (a beam's texel is the same everywhere: outside
/// its map, where the light is unshadowed, the band only grows).
pub(crate) fn texel_bound(
    cover: &MapCover,
    resolution: u32,
    light: DVec3,
    position: DVec3,
    camera: &ViewerCamera,
) -> f64 {
    let resolution = f64::from(resolution);
    let spanned = resolution - 2.0 * FILTER_MARGIN_TEXELS;
    match cover {
        MapCover::Cone { axis, outer_angle } => {
            let depth = (position - light).dot(*axis).max(0.0);
            2.0 * depth * outer_angle.tan() / spanned
        }
        MapCover::Cube => 2.0 * (position - light).abs().max_element() / spanned,
        MapCover::Beam { half_size } => 2.0 * half_size / resolution,
        MapCover::Cascades(cascades) => {
            let depth = (position - camera.eye).dot(camera.forward);
            let overlap = f64::from(cascades.overlap).clamp(0.0, 0.95);
            let ends = cascade_ends(cascades);
            let mut start = camera.near;
            let mut largest: f64 = 0.0;
            for (index, &end) in ends.iter().enumerate() {
                if (start..=end).contains(&depth) {
                    let corners = camera.slice_corners(start, end);
                    let mean = corners.iter().sum::<DVec3>() / 8.0;
                    let radius = corners
                        .iter()
                        .map(|corner| corner.distance(mean))
                        .fold(0.0, f64::max);
                    largest = largest.max(2.0 * (radius + CASCADE_RADIUS_STEP) / resolution);
                }
                let previous_end = if index == 0 {
                    camera.near
                } else {
                    ends[index - 1]
                };
                start = end - overlap * (end - previous_end);
            }
            largest
        }
    }
}

/// The band's half-width `b` (see the module's documentation) for a light with `settings`,
/// a texel of at most `texel`, on a surface whose cosine to the light is `cosine`.
pub(crate) fn band_width(settings: &PhongShadows, texel: f64, cosine: f64) -> f64 {
    let penumbra = if settings.softness > 0.0 {
        32.0 * texel
    } else {
        0.0
    };
    (4.0 + f64::from(settings.normal_bias)) * texel
        + f64::from(settings.depth_bias) / cosine.max(0.2)
        + penumbra
}
