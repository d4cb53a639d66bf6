//! The light entities and the ambient light resource.
//!
//! Each light is a component that requires [`Transform`](bevy::prelude::Transform) and
//! [`Visibility`](bevy::prelude::Visibility): spawn it with a transform and it lights every
//! [`PhongMaterial`](crate::PhongMaterial) from the next rendered frame on.

mod ambient;
mod decay;
mod directional;
mod point;
mod shadows;
mod spot;

pub use ambient::PhongAmbientLight;
pub use decay::Decay;
pub use directional::PhongDirectionalLight;
pub use point::PhongPointLight;
pub use shadows::{PhongCascades, PhongShadows};
pub use spot::PhongSpotLight;
