//! Reading a rendered image back to the CPU: the copy of one frame's render target, without
//! the row padding the GPU's copy adds. The harness, the examples' headless runs and the
//! benchmark all read their pictures this way.

use bevy::{
    prelude::*,
    render::gpu_readback::{Readback, ReadbackComplete},
};
use std::{
    collections::HashMap,
    sync::{Arc, Mutex},
};

/// Frames to wait for a readback to arrive before giving up.
pub const MAX_READBACK_FRAMES: u32 = 60;

/// The readbacks that arrived, by the entity that asked for them.
#[derive(Resource, Clone, Default)]
struct Arrived(Arc<Mutex<HashMap<Entity, Vec<u8>>>>);

/// Runs `frame` once with a readback of `image` requested, then again until that frame's
/// copy arrives, and returns it: `rows` rows of `row_bytes` bytes each, top to bottom,
/// without padding ([`without_row_padding`]). `frame` runs the app one frame (`App::update`,
/// or that and a wait for the device).
///
/// # Panics
///
/// When the copy has not arrived within [`MAX_READBACK_FRAMES`] more frames.
pub fn read_back_frame(
    app: &mut App,
    image: &Handle<Image>,
    row_bytes: usize,
    rows: usize,
    mut frame: impl FnMut(&mut App),
) -> Vec<u8> {
    let arrived = arrivals(app);
    let entity = app.world_mut().spawn(Readback::texture(image.clone())).id();
    frame(app);
    // One frame's copy: the readback asks again every frame while its entity lives.
    app.world_mut().despawn(entity);
    for _ in 0..MAX_READBACK_FRAMES {
        if let Some(bytes) = arrived.0.lock().unwrap().remove(&entity) {
            return without_row_padding(&bytes, row_bytes, rows);
        }
        frame(app);
    }
    panic!("the readback did not arrive within {MAX_READBACK_FRAMES} frames");
}

/// The app's inbox of arrived readbacks, made with its observer on first use.
fn arrivals(app: &mut App) -> Arrived {
    if let Some(arrived) = app.world().get_resource::<Arrived>() {
        return arrived.clone();
    }
    let arrived = Arrived::default();
    let sink = arrived.clone();
    app.insert_resource(arrived.clone())
        .add_observer(move |readback: On<ReadbackComplete>| {
            sink.0
                .lock()
                .unwrap()
                .insert(readback.entity, readback.data.clone());
        });
    arrived
}

/// The first `row_bytes` bytes of each of the `rows` rows of a texture readback, whose rows
/// the GPU pads to its copy alignment (256 bytes): the image's bytes, row by row.
pub fn without_row_padding(bytes: &[u8], row_bytes: usize, rows: usize) -> Vec<u8> {
    let padded_row = bytes.len() / rows.max(1);
    bytes
        .chunks_exact(padded_row.max(1))
        .take(rows)
        .flat_map(|row| &row[..row_bytes])
        .copied()
        .collect()
}
