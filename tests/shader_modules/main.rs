//! The crate's WGSL, checked on the CPU (no GPU, no window):
//!
//! - `composition`: every entry shader (the material's fragment stage, the shadow caster,
//!   `SurfaceInputsMaterial`, the searchlight example's, the benchmark's floor, the shader
//!   contract's kernel), composed with naga_oil from the modules the crate and Bevy register,
//!   for every set of shader defs it is specialized with, and validated by naga;
//! - `layouts`: the Rust structs written for the GPU have the sizes and offsets naga gives
//!   the WGSL structs;
//! - `shared_values`: flags and binding numbers that Rust and WGSL both name agree.

mod composition;
mod layouts;
mod library;
mod shared_values;
mod variants;
