//! The light entities and the ambient and hemisphere light resources.
//!
//! Each light is a component that requires [`Transform`](bevy::prelude::Transform) and
//! [`Visibility`](bevy::prelude::Visibility): spawn it with a transform and it lights every
//! [`PhongMaterial`](crate::PhongMaterial) from the next rendered frame on. A light gives
//! light while it is visible and its transform is finite; it shines along its entity's -Z
//! (`lit`).

mod ambient;
mod cookie;
mod decay;
mod directional;
mod hemisphere;
mod lit;
mod point;
mod shadows;
mod spot;

pub use ambient::PhongAmbientLight;
pub use cookie::{PhongCookieProjection, PhongLightCookie, cookie_layer_texels};
pub use decay::Decay;
pub use directional::PhongDirectionalLight;
pub use hemisphere::PhongHemisphereLight;
pub(crate) use lit::{
    LightQuery, TrackedLightQuery, gives_light, lit_light, lit_lights, lit_tracked_lights,
};
pub use lit::{is_finite_transform, light_direction};
pub use point::PhongPointLight;
pub use shadows::{PhongCascades, PhongShadows};
pub use spot::{ConeEdge, PhongSpotLight};
