//! An app for ECS-only unit tests: the gather systems without a renderer.

use crate::{PhongPlugin, render::PHONG_LIGHT_BUFFER};
use bevy::{
    asset::{AssetEvent, AssetPlugin},
    camera::visibility::VisibilitySystems,
    prelude::*,
    render::storage::ShaderBuffer,
    transform::TransformPlugin,
};

/// Counts the `Modified` events of light buffers, i.e. GPU uploads.
#[derive(Resource, Default)]
pub struct BufferUploads(pub usize);

fn count_uploads(
    mut events: MessageReader<AssetEvent<ShaderBuffer>>,
    mut uploads: ResMut<BufferUploads>,
) {
    uploads.0 += events
        .read()
        .filter(|event| {
            matches!(
                event,
                AssetEvent::Modified { .. } | AssetEvent::Added { .. }
            )
        })
        .count();
}

/// Bevy's visibility propagation for entities without parents (its plugin needs a renderer).
fn propagate_visibility(mut entities: Query<(&Visibility, &mut InheritedVisibility)>) {
    for (visibility, mut inherited) in &mut entities {
        let visible = if *visibility == Visibility::Hidden {
            InheritedVisibility::HIDDEN
        } else {
            InheritedVisibility::VISIBLE
        };
        inherited.set_if_neq(visible);
    }
}

/// `MinimalPlugins` with transforms, visibility, assets and [`PhongPlugin`], plus what
/// `add` adds; one frame already run.
pub fn test_app(add: impl FnOnce(&mut App)) -> App {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin::default(),
        TransformPlugin,
        PhongPlugin,
    ))
    .add_systems(
        PostUpdate,
        propagate_visibility.in_set(VisibilitySystems::VisibilityPropagate),
    )
    .init_resource::<BufferUploads>()
    .add_systems(Last, count_uploads);
    add(&mut app);
    app.update();
    app
}

/// Runs one frame and returns how many light buffer uploads it caused.
pub fn uploads_in_next_frame(app: &mut App) -> usize {
    let before = app.world().resource::<BufferUploads>().0;
    app.update();
    app.world().resource::<BufferUploads>().0 - before
}

/// The invalid-input warnings sent since the last call, oldest first.
pub fn invalid_inputs(app: &mut App) -> Vec<crate::validation::InvalidInput> {
    app.world_mut()
        .resource_mut::<bevy::ecs::message::Messages<crate::validation::InvalidInput>>()
        .drain()
        .collect()
}

/// The bytes of the built-in light buffer.
pub fn built_in_buffer_bytes(app: &App) -> Vec<u8> {
    app.world()
        .resource::<Assets<ShaderBuffer>>()
        .get(&PHONG_LIGHT_BUFFER)
        .and_then(crate::storage_buffer::buffer_bytes)
        .map(<[u8]>::to_vec)
        .expect("the light buffer is written on the first frame")
}

/// A cookie whose image is Bevy's default one (a white texel), added to the images of `app`
/// (made by [`test_app`] with `init_asset::<Image>()`).
pub fn white_cookie(app: &mut App) -> crate::PhongLightCookie {
    let image = app
        .world_mut()
        .resource_mut::<Assets<Image>>()
        .add(Image::default());
    crate::PhongLightCookie {
        image,
        ..Default::default()
    }
}
