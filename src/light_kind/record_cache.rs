//! The records of one light kind as last gathered, kept so that a gather recomputes only
//! what changed.
//!
//! For a kind that can move a record ([`PhongLightKind::place`]), a record's constants
//! (for the built-in kinds: linear colors, the spot cone's terms in `f64`) and its ε-limited
//! reach ([`PhongLightKind::reach`]) depend on the light's component alone, so they are reused while the component is equal
//! to the one they were made from, however often it was marked changed; a component Bevy
//! has not marked changed since the last gather is not even compared, so a moved light
//! costs its placement only. Entries are kept in the order the light query yields its entities,
//! which holds from frame to frame until entities are spawned, despawned or change
//! archetype: an entry whose entity is not the one at its place is simply made again.

use super::PhongLightKind;
use bevy::{ecs::entity::Entity, transform::components::GlobalTransform};

/// The cached records of the lights of kind `L`, in query order: entry `i` of each vector
/// belongs to the same light (kept apart so that a frame of moved lights reads only the
/// entities and constants).
#[derive(Debug)]
pub(crate) struct RecordCache<L: PhongLightKind> {
    /// The entity each entry was made for.
    entities: Vec<Entity>,
    /// The component each entry's constants were made from.
    sources: Vec<L>,
    /// The record made at the identity transform: its constants, as `to_gpu` made them.
    constants: Vec<L::Gpu>,
    /// The reach for a per-light ε.
    reaches: Vec<LimitedReach>,
}

/// A light's [`PhongLightKind::reach`] for one per-light ε.
#[derive(Clone, Copy, Debug)]
struct LimitedReach {
    /// The per-light ε that `reach` was computed for (`NaN`: none yet).
    epsilon: f32,
    reach: f32,
}

impl LimitedReach {
    const NONE: Self = Self {
        epsilon: f32::NAN,
        reach: 0.0,
    };
}

impl<L: PhongLightKind> Default for RecordCache<L> {
    fn default() -> Self {
        Self {
            entities: Vec::new(),
            sources: Vec::new(),
            constants: Vec::new(),
            reaches: Vec::new(),
        }
    }
}

impl<L: PhongLightKind + Clone + PartialEq> RecordCache<L> {
    /// The record of the `index`-th visible light, placed at `transform` (with
    /// [`PhongLightKind::place`] on its cached constants), and its reach for the per-light
    /// `epsilon` ([`PhongLightKind::reach`], of the light and its record as `to_gpu` made
    /// it; `0` where
    /// it reaches nowhere). A kind that cannot place a record gets `to_gpu` each time.
    ///
    /// The constants are made again when `entity` differs from the entry's, or when `light`
    /// was `changed` (Bevy's change ticks since the last gather) and differs from what the
    /// entry was made from: a light not changed since the last gather, where it had this
    /// entry, is the one the entry was made from or checked against. The reach is computed
    /// again when they are, or when `epsilon` differs.
    pub(crate) fn record(
        &mut self,
        index: usize,
        entity: Entity,
        light: &L,
        changed: bool,
        transform: &GlobalTransform,
        epsilon: f32,
    ) -> (L::Gpu, f32) {
        debug_assert!(
            index <= self.entities.len(),
            "entries are asked for in order"
        );
        let constants = || light.to_gpu(&GlobalTransform::IDENTITY);
        if index == self.entities.len() {
            self.entities.push(entity);
            self.sources.push(light.clone());
            self.constants.push(constants());
            self.reaches.push(LimitedReach::NONE);
        } else if self.entities[index] != entity || (changed && self.sources[index] != *light) {
            self.entities[index] = entity;
            self.sources[index] = light.clone();
            self.constants[index] = constants();
            self.reaches[index] = LimitedReach::NONE;
        }
        let limited = &mut self.reaches[index];
        if limited.epsilon.to_bits() != epsilon.to_bits() {
            *limited = LimitedReach {
                epsilon,
                reach: light.reach(&self.constants[index], epsilon),
            };
        }
        let mut record = self.constants[index];
        if !L::place(&mut record, transform) {
            record = light.to_gpu(transform);
        }
        (record, limited.reach)
    }

    /// Keeps the first `count` entries: the lights past them are gone.
    pub(crate) fn truncate(&mut self, count: usize) {
        self.entities.truncate(count);
        self.sources.truncate(count);
        self.constants.truncate(count);
        self.reaches.truncate(count);
    }
}
