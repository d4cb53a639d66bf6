//! A line light, written as a new kind is written: this folder and one line that registers
//! it (`PhongLightKindPlugin::<LineLight>`, in `extension/line_light_tests.rs`). It stands
//! for the next built-in kind: the test shows that validation, the gather into its own
//! buffer, the clusters and the reference model take it with no change anywhere else. Only
//! the tests build it.
//!
//! - this file: the component;
//! - `kind.rs`: its record, reach, bounds and validation ([`PhongLightKind`]);
//! - `reference.rs`: its light in the reference model;
//! - its test is `extension/line_light_tests.rs`, beside the plugin that registers it (a
//!   module of the light-kind layer does not import the extension layer above it).

mod kind;
#[cfg(feature = "reference")]
mod reference;

use bevy::{
    camera::visibility::Visibility, color::Color, ecs::component::Component,
    transform::components::Transform,
};

#[cfg(doc)]
use crate::light_kind::PhongLightKind;

/// A segment of light along its entity's local X axis, centred on its position.
#[derive(Component, Clone, Debug, PartialEq)]
#[require(Transform, Visibility)]
pub struct LineLight {
    /// Diffuse and specular intensity.
    pub color: Color,
    /// Length of the segment, world units, `≥ 0`.
    pub length: f32,
    /// Distance from the segment past which it lights nothing, world units, `> 0`.
    pub range: f32,
}
