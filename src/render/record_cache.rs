//! The records of one built-in light kind as last gathered, kept so that a gather
//! recomputes only what changed.
//!
//! A record's constants (linear colors, the spot cone's terms in `f64`, the ε-limited reach)
//! depend on the light's component alone, so they are reused while the component is equal
//! to the one they were made from, however often it was marked changed; a component Bevy
//! has not marked changed since the last gather is not even compared, so a moved light
//! costs its placement only. Entries are kept in the order the light query yields its entities,
//! which holds from frame to frame until entities are spawned, despawned or change
//! archetype: an entry whose entity is not the one at its place is simply made again.

use super::{
    gpu_types::GpuLight,
    light_records::{BuiltInLight, limit_reach},
};
use bevy::ecs::entity::Entity;

/// The cached records of the lights of kind `L`, in query order: entry `i` of each vector
/// belongs to the same light (kept apart so that a frame of moved lights reads only the
/// entities and constants).
#[derive(Debug)]
pub(crate) struct RecordCache<L> {
    /// The entity each entry was made for.
    entities: Vec<Entity>,
    /// The component each entry's constants were made from.
    sources: Vec<L>,
    /// The record's constants, with the component's own range.
    constants: Vec<GpuLight>,
    /// The range limited for a per-light ε.
    reaches: Vec<LimitedReach>,
}

/// A light's range shortened to its influence radius for one per-light ε.
#[derive(Clone, Copy, Debug)]
struct LimitedReach {
    /// The per-light ε that `range` was computed for (`NaN`: none yet).
    epsilon: f32,
    range: f32,
}

impl LimitedReach {
    const NONE: Self = Self {
        epsilon: f32::NAN,
        range: 0.0,
    };
}

impl<L> Default for RecordCache<L> {
    fn default() -> Self {
        Self {
            entities: Vec::new(),
            sources: Vec::new(),
            constants: Vec::new(),
            reaches: Vec::new(),
        }
    }
}

impl<L: BuiltInLight> RecordCache<L> {
    /// The record of the `index`-th visible light without its placement: its constants
    /// (see [`BuiltInLight::constants`]) with the range shortened to its influence radius
    /// for the per-light `epsilon`, as [`limit_reach`] does (0 where it reaches nowhere).
    ///
    /// The constants are made again when `entity` differs from the entry's, or when `light`
    /// was `changed` (Bevy's change ticks since the last gather) and differs from what the
    /// entry was made from: a light not changed since the last gather, where it had this
    /// entry, is the one the entry was made from or checked against. The limited range is
    /// computed again when they are, or when `epsilon` differs.
    pub(crate) fn record(
        &mut self,
        index: usize,
        entity: Entity,
        light: &L,
        changed: bool,
        epsilon: f32,
    ) -> GpuLight {
        debug_assert!(
            index <= self.entities.len(),
            "entries are asked for in order"
        );
        if index == self.entities.len() {
            self.entities.push(entity);
            self.sources.push(light.clone());
            self.constants.push(light.constants());
            self.reaches.push(LimitedReach::NONE);
        } else if self.entities[index] != entity || (changed && self.sources[index] != *light) {
            self.entities[index] = entity;
            self.sources[index] = light.clone();
            self.constants[index] = light.constants();
            self.reaches[index] = LimitedReach::NONE;
        }
        let reach = &mut self.reaches[index];
        if reach.epsilon.to_bits() != epsilon.to_bits() {
            let mut limited = self.constants[index];
            limit_reach(&mut limited, epsilon);
            *reach = LimitedReach {
                epsilon,
                range: limited.range,
            };
        }
        GpuLight {
            range: reach.range,
            ..self.constants[index]
        }
    }

    /// Keeps the first `count` entries: the lights past them are gone.
    pub(crate) fn truncate(&mut self, count: usize) {
        self.entities.truncate(count);
        self.sources.truncate(count);
        self.constants.truncate(count);
        self.reaches.truncate(count);
    }
}
