//! # bevy_phong_headless
//!
//! Renders `bevy_phong` scenes without a window and reads them back as linear floats: the
//! harness that `bevy_phong`'s render tests, its `render_scene` example and its benchmark
//! share.
//!
//! - [`headless_app`] builds an app with Bevy's renderer and `PhongPlugin`, no window, no
//!   log and no pipelined rendering: the caller drives frames with `App::update`, and the
//!   render world can be read between frames.
//! - [`Harness`] adds a camera rendering into an `Rgba32Float` image, waits for pipelines
//!   ([`Harness::settle`]), reads frames back ([`Harness::render_next_frame`]) and the
//!   per-pixel inputs each pixel was lit with ([`Harness::capture_inputs`]), and compares a
//!   frame with `bevy_phong::reference` pixel by pixel ([`Harness::compare`], giving a
//!   [`Comparison`]), each pixel's expected color given by [`pixel_model`] with every
//!   material feature and its maps' texels; [`Harness::compare_with_reference`] captures
//!   the inputs itself and follows what shows through masked and blended meshes
//!   ([`see_through`]), for `PhongMaterial` or any material made of one
//!   ([`Harness::compare_with_reference_of`]): the examples' `--compare`.
//! - [`read_back_frame`] reads one frame of a render target back (the harness, the
//!   benchmark), and [`without_row_padding`] strips the GPU copy's row padding (the
//!   examples' headless runs, which read back from a running app).
//!
//! It renders on whatever Vulkan device wgpu picks; `WGPU_ADAPTER_NAME=llvmpipe` selects
//! Mesa's software renderer, on which the render tests' tolerances were set.
//!
//! For wasm32 only [`pipelines_compiling`] is built: the showcase's browser build uses it to
//! tell when it has drawn.

#[cfg(not(target_arch = "wasm32"))]
mod app;
#[cfg(not(target_arch = "wasm32"))]
mod comparison;
#[cfg(not(target_arch = "wasm32"))]
mod float_image;
#[cfg(not(target_arch = "wasm32"))]
mod harness;
mod parallel;
mod pipelines;
#[cfg(not(target_arch = "wasm32"))]
pub mod pixel_model;
#[cfg(not(target_arch = "wasm32"))]
mod readback;
#[cfg(not(target_arch = "wasm32"))]
pub mod see_through;

#[cfg(not(target_arch = "wasm32"))]
pub use app::{
    finish_frame_driven_app, frame_driven_plugins, headless_app, headless_app_with_assets,
    headless_plugins,
};
#[cfg(not(target_arch = "wasm32"))]
pub use comparison::{Comparison, Expected, TOLERANCE};
#[cfg(not(target_arch = "wasm32"))]
pub use float_image::{FloatImage, save_srgb_png};
#[cfg(not(target_arch = "wasm32"))]
pub use harness::{
    CAMERA_POSITION, Harness, HarnessCamera, ReferenceScene, SurfaceInputs, update_in_lockstep,
};
pub use parallel::{Progress, parallel_map};
pub use pipelines::{
    assert_no_failed_pipelines, failed_pipelines, pipelines_compiling, run_until_settled,
    unfinished_pipelines,
};
#[cfg(not(target_arch = "wasm32"))]
pub use readback::{MAX_READBACK_FRAMES, read_back_frame, without_row_padding};
