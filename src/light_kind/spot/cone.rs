//! The spot cone's terms in its light record: what the shader needs of the cone to compute
//! its edge (SPEC.md, "The equation", the spot cone).

use crate::lights::ConeEdge;
use crate::limits;

/// `(1 - cos(outer), cone_scale)` of a spot cone, computed in `f64` and rounded once:
/// `cone_scale = 1 / (cos(inner) - cos(outer))`, negated for a smooth edge
/// ([`ConeEdge::Smooth`]), or `0` (a hard edge at the outer angle) where the inner cone is
/// not narrower. A cone whose outer angle is not positive is empty:
/// its `1 - cos(outer)` is stored as `-1`, which no `1 - cos θ` reaches. Angles are first
/// brought into `[0, π]` ([`crate::limits::CONE_ANGLE`]).
pub(super) fn spot_cone_terms(inner_angle: f32, outer_angle: f32, edge: ConeEdge) -> (f32, f32) {
    let inner_angle = limits::CONE_ANGLE.apply(inner_angle);
    let outer_angle = limits::CONE_ANGLE.apply(outer_angle);
    if outer_angle <= 0.0 {
        return (-1.0, 0.0);
    }
    let (inner, outer) = (f64::from(inner_angle), f64::from(outer_angle));
    // 1 - cos x = 2 sin²(x/2) and cos i - cos o = 2 sin((o+i)/2) sin((o-i)/2): no
    // cancellation for small or close angles.
    let outer_versine = 2.0 * (outer / 2.0).sin().powi(2);
    let width = 2.0 * ((outer + inner) / 2.0).sin() * ((outer - inner) / 2.0).sin();
    // Beyond f32's range (or for no width at all) the edge is hard.
    let cone_scale = (1.0 / width) as f32;
    let cone_scale = if width > 0.0 && cone_scale.is_finite() {
        match edge {
            ConeEdge::Linear => cone_scale,
            ConeEdge::Smooth => -cone_scale,
        }
    } else {
        0.0
    };
    (outer_versine as f32, cone_scale)
}
