//! Probes: extensions of `PhongMaterial` whose fragment shader shows what a test reads (a
//! view record, a motion vector, a public shader function's value) instead of a color.

use crate::frames::SIZE;
use bevy::prelude::*;
use bevy_phong::{PhongSceneMaterial, prelude::*};
use bevy_phong_headless::Harness;
use core::hash::Hash;

/// A harness whose app draws the probe material `M` (an `ExtendedMaterial<PhongMaterial, _>`),
/// with its fragment shader the WESL `source` (read from `path`) at `handle`, which the
/// extension's `fragment_shader` names.
pub(crate) fn harness_with_probe<M: PhongSceneMaterial>(
    handle: &Handle<Shader>,
    source: &'static str,
    path: &'static str,
) -> Harness
where
    M::Data: PartialEq + Eq + Hash + Clone,
{
    let id = handle.id();
    Harness::with_plugins(SIZE, SIZE, move |app| {
        app.add_phong_material::<M>();
        app.world_mut()
            .resource_mut::<Assets<Shader>>()
            .insert(id, Shader::from_wesl(source, path))
            .expect("the probe shader's handle is free");
    })
}
