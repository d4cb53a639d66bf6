//! The disk light: a round panel that emits from every point of its area (a ceiling lamp's
//! diffuser, a round window, a stage light's lens). docs/design/area-lights.md is its design.
//!
//! Everything particular to the kind is in this folder: the component (this file); the kind
//! (`kind.rs`, [`PhongLightKind`](crate::extension::PhongLightKind)): its record
//! (`GpuAreaLight` with its `DISK` flag) and validation; and its light in the reference
//! model (`reference.rs`, feature `reference`). What it shares with the rectangle light is
//! `light_kind::gpu_area_light`. Registered by one line of `PhongPlugin` (`add_light_kind`).

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

/// A disk that emits light from its area, centered on the entity in its local XY plane,
/// facing its local −Z (as every light of the crate points: `Transform::looking_at` aims it).
///
/// Its light is a [`PhongRectLight`](crate::PhongRectLight)'s with a round shape: each
/// element `dA` lights a surface point as a point light of `color / (π · radius²)` would,
/// times the cosine between the disk's facing and the ray and the inverse square of its
/// distance, so that seen face on from far away the disk is a point light of `color`.
/// `decay` and `range` multiply that, taken at the distance to the disk's nearest point.
/// The shader draws the disk, for each surface point, as polygons whose corners sit on its
/// rim crowded toward one rim point (32 toward the nearest for the diffuse light, 16 toward
/// the highlight's lobe for the highlight), and integrates over them as over a rectangle: at
/// every distance from the rim (a disk touching or crossing a surface included), the diffuse
/// light within 5e-4 of the most the disk gives at the point, the highlight within 3e-3 of
/// the whole lobe at shininess 50 (1e-2 at 200); docs/lights.md has the measurements. SPEC.md ("Area lights") has the equation. Scale is ignored; a hidden entity
/// gives no light.
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Component, Default, Debug, Clone)]
#[require(Transform, Visibility)]
#[cfg_attr(feature = "scene", serde(default))]
pub struct PhongDiskLight {
    /// The whole disk's diffuse intensity (see above), converted to linear RGB; each channel
    /// `0` to `1e6` (`MAX_INTENSITY`). Default white.
    pub color: Color,
    /// The whole disk's specular intensity, in the same range; `None` (the default) uses
    /// [`color`](Self::color).
    pub specular: Option<Color>,
    /// World units, `0` to `1e6`; a disk without area gives no light. Default 0.5.
    pub radius: f32,
    /// Whether the disk emits from its back face (local +Z) too. Default `false`: nothing
    /// behind it is lit.
    pub two_sided: bool,
    /// Fall-off with the distance to the disk's nearest point, on top of its own. Default
    /// [`Decay::NONE`].
    pub decay: Decay,
    /// Distance from the disk's nearest point (world units, `> 0`; `∞` is unlimited) past
    /// which it contributes nothing; `None` (the default) means unlimited.
    pub range: Option<f32>,
    /// How the highlight is computed. Default [`AreaHighlight::Bounded`].
    pub highlight: AreaHighlight,
    /// Shadow settings. Default off. The shadow is cast from the disk's center into a cube
    /// of maps, soft as a light of the disk's size (percentage-closer soft shadows whose
    /// light radius is that of the disk of its area: `softness` is replaced by it); its
    /// error against the disk's exact visibility is stated in docs/design/area-lights.md.
    pub shadows: PhongShadows,
}

impl Default for PhongDiskLight {
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            specular: None,
            radius: 0.5,
            two_sided: false,
            decay: Decay::NONE,
            range: None,
            highlight: AreaHighlight::Bounded,
            shadows: PhongShadows::OFF,
        }
    }
}
