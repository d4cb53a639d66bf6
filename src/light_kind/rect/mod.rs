//! The rectangle light: a panel that emits from every point of its area (a window, a screen,
//! a ceiling panel). docs/design/area-lights.md is its design.
//!
//! Everything particular to the kind is in this folder: the component (this file); the kind
//! (`kind.rs`, [`PhongLightKind`](crate::extension::PhongLightKind)): its record
//! (`GpuAreaLight`), reach, bounds and validation; and its light in the
//! reference model (`reference.rs`, feature `reference`). Registered by one line of
//! `PhongPlugin` (`add_light_kind`).

mod kind;
#[cfg(feature = "reference")]
mod reference;

use crate::lights::{AreaHighlight, Decay, PhongShadows};
use bevy::{
    camera::visibility::Visibility,
    color::Color,
    ecs::component::Component,
    prelude::{ReflectComponent, ReflectDefault},
    reflect::Reflect,
    transform::components::Transform,
};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// A rectangle that emits light from its area, centered on the entity, `width` along its
/// local X and `height` along its local Y, facing its local −Z (as every light of the crate
/// points: `Transform::looking_at` aims it).
///
/// Each element `dA` of the panel lights a surface point as a point light of
/// `color / (width · height)` would, times the cosine between the panel's facing and the
/// ray (the panel seen edge on gives nothing) and the inverse square of its distance: seen
/// face on from far away the whole panel is a point light of `color` with the inverse-square
/// fall-off, so a point light can become a panel of the same color and keep its brightness.
/// Close to it the light stays finite. `decay` and `range` multiply that, taken at the
/// distance to the panel's nearest point. The diffuse light is integrated exactly over the
/// part of the panel above the surface's horizon; the highlight as
/// [`highlight`](Self::highlight) chooses. SPEC.md ("Area lights") has the equation. Scale is
/// ignored; a hidden entity gives no light.
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Component, Default, Debug, Clone)]
#[require(Transform, Visibility)]
#[cfg_attr(feature = "scene", serde(default))]
pub struct PhongRectLight {
    /// The whole panel's diffuse intensity (see above), converted to linear RGB; each
    /// channel `0` to `1e6` (`MAX_INTENSITY`). Default white.
    pub color: Color,
    /// The whole panel's specular intensity, in the same range; `None` (the default) uses
    /// [`color`](Self::color).
    pub specular: Option<Color>,
    /// Extent along local X, world units, `0` to `1e6`; a panel without area gives no
    /// light. Default 1.
    pub width: f32,
    /// Extent along local Y, world units, `0` to `1e6`. Default 1.
    pub height: f32,
    /// Whether the panel emits from its back face (local +Z) too. Default `false`: nothing
    /// behind it is lit.
    pub two_sided: bool,
    /// Fall-off with the distance to the panel's nearest point, on top of its own. Default
    /// [`Decay::NONE`].
    pub decay: Decay,
    /// Distance from the panel's nearest point (world units, `> 0`; `∞` is unlimited) past
    /// which it contributes nothing; `None` (the default) means unlimited.
    pub range: Option<f32>,
    /// How the highlight is computed. Default [`AreaHighlight::Bounded`].
    pub highlight: AreaHighlight,
    /// Shadow settings. Default off. The shadow is cast from the panel's center into a cube
    /// of maps, soft as a light of the panel's size (percentage-closer soft shadows whose
    /// light radius is that of the disk of its area: `softness` is replaced by it); its
    /// error against the panel's exact visibility is stated in docs/design/area-lights.md.
    pub shadows: PhongShadows,
}

impl Default for PhongRectLight {
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            specular: None,
            width: 1.0,
            height: 1.0,
            two_sided: false,
            decay: Decay::NONE,
            range: None,
            highlight: AreaHighlight::Bounded,
            shadows: PhongShadows::OFF,
        }
    }
}
