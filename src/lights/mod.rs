//! What every light shares (fall-off and reach, shadow settings, cookies, the cone edge, which
//! lights give light and which way they point), and the ambient and hemisphere light
//! resources. Each kind of light entity is in its own folder under `light_kind` (`spot/`).
//!
//! Each light is a component that requires [`Transform`](bevy::prelude::Transform) and
//! [`Visibility`](bevy::prelude::Visibility): spawn it with a transform and it lights every
//! [`PhongMaterial`](crate::PhongMaterial) from the next rendered frame on. A light gives
//! light while it is visible and its transform is finite; it shines along its entity's -Z
//! (`lit`).

mod ambient;
mod area_highlight;
mod cone_edge;
mod cookie;
mod decay;
mod hemisphere;
mod lit;
mod reach;
#[cfg(test)]
mod reach_tests;
mod shadows;

pub(crate) use ambient::BevyAmbientPerView;
pub use ambient::PhongAmbientLight;
pub use area_highlight::AreaHighlight;
pub use cone_edge::ConeEdge;
pub use cookie::{PhongCookieProjection, PhongLightCookie, cookie_layer_texels};
pub use decay::Decay;
pub use hemisphere::PhongHemisphereLight;
#[cfg(feature = "reference")]
pub(crate) use lit::gives_light;
pub(crate) use lit::{
    LightChanges, LightQuery, TrackedLightQuery, lit_light, lit_lights, lit_tracked_lights,
};
pub use lit::{is_finite_transform, light_direction};
pub use reach::influence_radius;
pub use shadows::{PhongCascades, PhongShadows};
