//! The records of one built-in light kind as last gathered, kept so that a gather
//! recomputes only what changed.
//!
//! A record's constants (linear colors, the spot cone's terms in `f64`, the ε-limited reach)
//! depend on the light's component alone, so they are reused while the component is equal
//! to the one they were made from, however often it was marked changed; a moved light costs
//! its placement only. Entries are kept in the order the light query yields its entities,
//! which holds from frame to frame until entities are spawned, despawned or change
//! archetype: an entry whose entity is not the one at its place is simply made again.

use super::{
    gpu_types::GpuLight,
    light_records::{BuiltInLight, limit_reach},
};
use bevy::ecs::entity::Entity;

/// One light's constants and what they were made from.
#[derive(Debug)]
struct CachedRecord<L> {
    entity: Entity,
    /// The component the constants were made from.
    source: L,
    /// The record's constants, with the component's own range.
    constants: GpuLight,
    /// The per-light ε that `limited_range` was computed for (`NaN`: none yet).
    limited_for: f32,
    /// The range shortened to the light's influence radius for `limited_for`.
    limited_range: f32,
}

/// The cached records of the lights of kind `L`, in query order.
#[derive(Debug)]
pub(crate) struct RecordCache<L> {
    entries: Vec<CachedRecord<L>>,
}

impl<L> Default for RecordCache<L> {
    fn default() -> Self {
        Self {
            entries: Vec::new(),
        }
    }
}

impl<L: BuiltInLight> RecordCache<L> {
    /// The constants of the `index`-th visible light (see [`BuiltInLight::constants`]),
    /// made again when `entity` or `light` differ from what the entry was made from.
    pub(crate) fn constants(&mut self, index: usize, entity: Entity, light: &L) -> GpuLight {
        debug_assert!(
            index <= self.entries.len(),
            "entries are asked for in order"
        );
        if index == self.entries.len() {
            self.entries.push(CachedRecord::new(entity, light));
        } else if self.entries[index].entity != entity || self.entries[index].source != *light {
            self.entries[index] = CachedRecord::new(entity, light);
        }
        self.entries[index].constants
    }

    /// Shortens the range of each record in `records` (made from [`Self::constants`] in the
    /// same order, and no others since) to its influence radius for the per-light
    /// `epsilon`, as [`limit_reach`] does, and removes those that reach nowhere. Entries past
    /// the records are dropped: those lights are gone.
    pub(crate) fn limit_reach(&mut self, records: &mut Vec<GpuLight>, epsilon: f32) {
        self.entries.truncate(records.len());
        for (record, entry) in records.iter_mut().zip(&mut self.entries) {
            record.range = entry.limited_range(epsilon);
        }
        records.retain(|record| record.range > 0.0);
    }
}

impl<L: BuiltInLight> CachedRecord<L> {
    fn new(entity: Entity, light: &L) -> Self {
        Self {
            entity,
            source: light.clone(),
            constants: light.constants(),
            limited_for: f32::NAN,
            limited_range: 0.0,
        }
    }

    /// The range limited for `epsilon`, computed once per ε.
    fn limited_range(&mut self, epsilon: f32) -> f32 {
        if self.limited_for.to_bits() != epsilon.to_bits() {
            let mut limited = self.constants;
            limit_reach(&mut limited, epsilon);
            self.limited_for = epsilon;
            self.limited_range = limited.range;
        }
        self.limited_range
    }
}
