//! The metallic-roughness map's image, checked once it has loaded: a map that
//! cannot hold what the shader reads of it is drawn as it is, with one warning (and an
//! [`InvalidInput`] message) naming the material and the field.
//!
//! - An sRGB image (`is_srgb: true`, the loader's default for PNG and JPEG files) is read
//!   decoded from sRGB: its metallic and roughness come out darker than stored. Load the map
//!   as linear data (`ImageLoaderSettings { is_srgb: false, .. }`; glTF files do).
//! - An image of fewer than three channels has no blue channel: the GPU reads its metallic
//!   as 0 (and, with one channel, its roughness as 0: a mirror).
//! - An image that fails to load is never bound: Bevy logs the failure with the file's path,
//!   and the material is not drawn while its map is missing (Bevy's rule for a material's
//!   textures).

use super::{Checker, InvalidInput, Owner};
use crate::material::PhongMaterial;
use bevy::{
    asset::{AssetEvent, AssetId, Assets},
    image::Image,
    platform::collections::HashMap,
    prelude::{Local, MessageReader, MessageWriter, Res},
};

/// The field the checks name.
const FIELD: &str = "metallic_roughness_texture";

/// What is wrong with a loaded map's image, if anything: the replacement text of its
/// [`InvalidInput`].
fn format_problem(image: &Image) -> Option<String> {
    let format = image.texture_descriptor.format;
    if format.components() < 3 {
        Some(format!(
            "the image as it is ({format:?} has no blue channel: metallic reads 0); give it \
             blue metallic and green roughness"
        ))
    } else if format.is_srgb() {
        Some(format!(
            "the image decoded from sRGB ({format:?}: metallic and roughness read darker); \
             load it with is_srgb: false"
        ))
    } else {
        None
    }
}

/// Checks the metallic-roughness map of every material added or changed, once its image has
/// loaded.
pub(crate) fn check_metallic_roughness_maps(
    mut events: MessageReader<AssetEvent<PhongMaterial>>,
    materials: Res<Assets<PhongMaterial>>,
    images: Res<Assets<Image>>,
    mut waiting: Local<HashMap<AssetId<PhongMaterial>, AssetId<Image>>>,
    mut messages: MessageWriter<InvalidInput>,
) {
    for event in events.read() {
        match event {
            AssetEvent::Added { id } | AssetEvent::Modified { id } => {
                match materials
                    .get(*id)
                    .and_then(|material| material.metallic_roughness_texture.as_ref())
                {
                    Some(texture) => waiting.insert(*id, texture.id()),
                    None => waiting.remove(id),
                };
            }
            AssetEvent::Removed { id } | AssetEvent::Unused { id } => {
                waiting.remove(id);
            }
            AssetEvent::LoadedWithDependencies { .. } => {}
        }
    }
    waiting.retain(|&material, &mut image| {
        // Not loaded yet, or never: Bevy logs a failed load with its path.
        let Some(loaded) = images.get(image) else {
            return true;
        };
        if let Some(problem) = format_problem(loaded) {
            let mut checker = Checker::new(Owner::Material(material), "PhongMaterial");
            let value = format!("an image in {:?}", loaded.texture_descriptor.format);
            checker.replace(FIELD, value, problem);
            checker.report(&mut messages);
        }
        false
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_app::{invalid_inputs, test_app};
    use bevy::{
        asset::{AssetApp, RenderAssetUsages},
        render::render_resource::{Extent3d, TextureDimension, TextureFormat},
    };

    fn image(format: TextureFormat) -> Image {
        let size = Extent3d {
            width: 1,
            height: 1,
            depth_or_array_layers: 1,
        };
        let bytes = vec![0; format.block_copy_size(None).unwrap_or(4) as usize];
        Image::new(
            size,
            TextureDimension::D2,
            bytes,
            format,
            RenderAssetUsages::default(),
        )
    }

    #[test]
    fn a_map_in_srgb_or_without_a_blue_channel_is_named_once_and_a_linear_one_is_not() {
        for (format, warned) in [
            (TextureFormat::Rgba8Unorm, false),
            (TextureFormat::Rgba8UnormSrgb, true),
            (TextureFormat::Rg8Unorm, true),
            (TextureFormat::R8Unorm, true),
        ] {
            let mut app = test_app(|app| {
                app.init_asset::<Image>();
            });
            let texture = app
                .world_mut()
                .resource_mut::<Assets<Image>>()
                .add(image(format));
            let material =
                app.world_mut()
                    .resource_mut::<Assets<PhongMaterial>>()
                    .add(PhongMaterial {
                        metallic_roughness_texture: Some(texture),
                        ..Default::default()
                    });
            app.update();
            app.update();
            let found: Vec<_> = invalid_inputs(&mut app)
                .into_iter()
                .filter(|invalid| invalid.field == FIELD)
                .collect();
            assert_eq!(found.len(), usize::from(warned), "{format:?}: {found:?}");
            if let Some(invalid) = found.first() {
                assert_eq!(invalid.owner, Owner::Material(material.id()));
                assert!(invalid.value.contains(&format!("{format:?}")), "{invalid}");
            }
        }
    }
}
