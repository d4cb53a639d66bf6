//! How an area light's highlight is computed (docs/design/area-lights.md, "The closed
//! forms the shader uses").

use bevy::{prelude::ReflectDefault, reflect::Reflect};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// How an area light ([`PhongRectLight`](crate::PhongRectLight),
/// [`PhongDiskLight`](crate::PhongDiskLight)) computes the highlight it gives: the material's
/// lobe integrated over the light's shape (at a bounded cost, or exactly at any cost), a
/// fitted lobe integrated over it, or the lobe taken toward one point of it. The diffuse
/// light is exact either way. Each choice's error, against the
/// reference model's quadrature, is in SPEC.md ("Area lights") and on the time-against-error
/// plot of docs/performance.md.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Default, Debug, PartialEq, Clone)]
pub enum AreaHighlight {
    /// The Phong lobe `max(R·V, 0)^α` integrated over the light as [`Self::Exact`] does up to
    /// `α = 64`, and beyond it at the cost of `α = 64`: the lobes of 32 and 16 integrated
    /// over the light's polygon stretched across the mirror direction by `√(α/32)` and
    /// `√(α/16)` (which narrows each to the lobe of `α` near its peak), combined to cancel
    /// their first error term (`2·S₃₂ − S₁₆`). Within 3e-3 of the largest highlight at every
    /// shininess up to 10⁴ (measured 2.6e-3 just past 64, 1.5e-4 at 10⁴;
    /// docs/design/area-lights.md); Blinn-Phong integrated as
    /// the Phong lobe of `α / (4 N·V)`, as [`Self::Exact`]. What a game should use: a
    /// glossy floor under a panel costs what a matte one does.
    #[default]
    Bounded,
    /// The Phong lobe `max(R·V, 0)^α` integrated over the light by Arvo's recurrence: exact
    /// for an integer shininess, its moments at `⌊α⌋` and `⌈α⌉` interpolated between them
    /// otherwise (at most 8e-3 of the largest highlight measured); Blinn-Phong integrated as
    /// the Phong lobe of `α / (4 N·V)`, the lobe of the same solid angle (at most 0.4). Its
    /// cost grows with the shininess without bound: about `α/2` steps per edge of the
    /// light's lit polygon (4 to 6 edges; a disk's 16 to 18), 5,000 at `α = 10⁴`: 15 times
    /// the bounded choice's cost there (docs/performance.md, "One light on one pixel").
    Exact,
    /// The lobe replaced by a linearly transformed cosine fitted to it (a clamped cosine
    /// around the mirror direction squeezed across it by `s = 1/√(0.585 α + 0.415)`, the
    /// least-squares fit over the hemisphere; exact at `α = 1`), integrated over the light in
    /// closed form as its diffuse light is: a cost that does not grow with the shininess (one
    /// polygon's irradiance), its error docs/design/area-lights.md states.
    Fitted,
    /// The material's highlight toward the light's point nearest the mirror ray, times the
    /// light's solid angle and the whole lobe's joined harmonically (`Ω·W / (Ω + W)`): a cost
    /// that does not grow with the shininess, and a larger error (at most 0.5 of the largest
    /// highlight measured, at grazing angles).
    RepresentativePoint,
}
