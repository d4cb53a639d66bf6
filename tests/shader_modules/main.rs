//! The crate's WESL, checked on the CPU (no GPU, no window):
//!
//! - `composition`: every entry shader (the material's fragment stage, the shadow caster,
//!   `SurfaceInputsMaterial`, the searchlight example's, the benchmark's floor, the shader
//!   contract's kernel), composed with WESL (the `wesl` crate Bevy 0.20 composes with) from
//!   the modules the crate and Bevy register, and validated by naga: every material key
//!   where the most defs meet, and keys that put each def on and off beside every other
//!   elsewhere (`variants`);
//! - `layouts`: the Rust structs written for the GPU have the sizes and offsets naga gives
//!   the WESL structs;
//! - `shared_values`: flags and binding numbers that Rust and WESL both name agree.

mod composition;
mod layouts;
mod library;
mod shared_values;
mod variants;
