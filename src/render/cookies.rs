//! The cookies of the built-in lights: each frame, the atlas of their images
//! ([`super::cookie_atlas`]) and the record of each light that has one, which
//! [`gather_lights`](super::gather_lights) stores after the lights.

use super::cookie_atlas::{PHONG_COOKIE_ATLAS, atlas_image};
use super::gpu_types::GpuCookie;
use crate::lights::{
    PhongDirectionalLight, PhongLightCookie, PhongPointLight, PhongSpotLight, cookie_layer_texels,
};
use crate::limits::{MAX_COOKIE_IMAGES, SPOT_ANGLE};
use crate::scene_variants::SCENE_HAS_LIGHT_COOKIES;
use crate::storage_buffer::LightBufferResized;
use bevy::{
    asset::{AssetEvent, AssetId, Assets},
    camera::primitives::CubemapLayout,
    ecs::{
        change_detection::DetectChangesMut,
        entity::{Entity, EntityHashMap},
        message::{MessageReader, MessageWriter},
        query::AnyOf,
        resource::Resource,
        system::{Query, ResMut},
    },
    image::Image,
    log::warn,
    platform::collections::HashSet,
    transform::components::GlobalTransform,
};
use core::sync::atomic::Ordering;

/// The widest angle a spot cookie's projection takes (a cone past 90° has no plane to lay
/// the image on): 89.5°.
const WIDEST_SPOT_PROJECTION: f32 = 89.5 * core::f32::consts::PI / 180.0;

/// The cookies of this frame: the atlas's images, layer by layer, and each cookied light's
/// record with the light's slot in them.
#[derive(Resource, Debug, Default)]
pub struct PhongCookies {
    /// The image of each atlas layer.
    layers: Vec<AssetId<Image>>,
    /// The cookie records, in slot order.
    records: Vec<GpuCookie>,
    /// Each cookied light's slot in `records`.
    slots: EntityHashMap<u32>,
    /// Images already warned about (unreadable, or past the atlas's capacity).
    warned: HashSet<AssetId<Image>>,
}

impl PhongCookies {
    /// The cookie slot of `entity` plus one, or `0` for a light without a cookie this frame
    /// (the gather turns it into the index of the cookie's record).
    pub fn slot_of(&self, entity: Entity) -> u32 {
        self.slots.get(&entity).map_or(0, |slot| slot + 1)
    }

    /// The records of this frame, in slot order.
    pub fn records(&self) -> &[GpuCookie] {
        &self.records
    }
}

/// The lights with a cookie.
type CookiedLights<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        &'static PhongLightCookie,
        &'static GlobalTransform,
        AnyOf<(
            &'static PhongSpotLight,
            &'static PhongPointLight,
            &'static PhongDirectionalLight,
        )>,
    ),
>;

/// Makes the atlas (first a white layer), rebuilds it when the set of cookie images changes
/// or one of them is modified, and
/// the records of the cookied lights when any of them changed; it touches [`PhongCookies`]
/// only then, so that [`gather_lights`](super::gather_lights) writes the light buffer only
/// when something changed. Sets the scene's cookie variant (`PHONG_LIGHT_COOKIES`).
pub fn gather_cookies(
    lights: CookiedLights,
    mut image_events: MessageReader<AssetEvent<Image>>,
    mut images: ResMut<Assets<Image>>,
    mut cookies: ResMut<PhongCookies>,
    mut resized: MessageWriter<LightBufferResized>,
) {
    let modified: HashSet<AssetId<Image>> = image_events
        .read()
        .filter_map(|event| match event {
            AssetEvent::Modified { id } | AssetEvent::LoadedWithDependencies { id } => Some(*id),
            _ => None,
        })
        .collect();
    let state = cookies.bypass_change_detection();
    let mut layers: Vec<AssetId<Image>> = Vec::new();
    let mut texels = Vec::new();
    for (entity, cookie, _, _) in &lights {
        let id = cookie.image.id();
        if layers.contains(&id) {
            continue;
        }
        let Some(image) = images.get(id) else {
            continue;
        };
        if layers.len() == MAX_COOKIE_IMAGES {
            if state.warned.insert(id) {
                warn!(
                    "entity {entity}: PhongLightCookie.image is the {}th distinct cookie \
                     image; the atlas holds {MAX_COOKIE_IMAGES}: the light is drawn without it",
                    MAX_COOKIE_IMAGES + 1
                );
            }
            continue;
        }
        match cookie_layer_texels(image) {
            Some(layer) => {
                layers.push(id);
                texels.push(layer);
            }
            None if state.warned.insert(id) => warn!(
                "entity {entity}: PhongLightCookie.image has a format whose texels cannot be \
                 read ({:?}) or no texels: the light is drawn without its cookie",
                image.texture_descriptor.format
            ),
            None => {}
        }
    }
    let rebuild = layers != state.layers
        || layers.iter().any(|id| modified.contains(id))
        || !images.contains(&PHONG_COOKIE_ATLAS);
    let mut changed = false;
    if rebuild {
        images
            .insert(&PHONG_COOKIE_ATLAS, atlas_image(&texels))
            .expect("the atlas handle accepts an image");
        state.layers = layers;
        changed = true;
    }

    let mut records = Vec::new();
    let mut slots = EntityHashMap::default();
    for (entity, cookie, transform, kind) in &lights {
        let Some(layer) = state.layers.iter().position(|id| *id == cookie.image.id()) else {
            continue;
        };
        let Some(record) = cookie_record(cookie, transform, kind, layer as u32) else {
            continue;
        };
        slots.insert(entity, records.len() as u32);
        records.push(record);
    }
    if records != state.records || slots != state.slots {
        state.records = records;
        state.slots = slots;
        changed = true;
    }
    let any = !state.records.is_empty();
    let variant_changed = SCENE_HAS_LIGHT_COOKIES.swap(any, Ordering::Relaxed) != any;
    if changed {
        cookies.set_changed();
    }
    if rebuild || variant_changed {
        // A new atlas texture, or a new variant: the materials' bind groups are made again.
        resized.write(LightBufferResized {
            buffer: super::PHONG_LIGHT_BUFFER,
        });
    }
}

/// The record of `cookie` on a light at `transform` of kind `kind`, in atlas layer `layer`;
/// `None` for a transform that cannot be inverted.
fn cookie_record(
    cookie: &PhongLightCookie,
    transform: &GlobalTransform,
    (spot, point, _): (
        Option<&PhongSpotLight>,
        Option<&PhongPointLight>,
        Option<&PhongDirectionalLight>,
    ),
    layer: u32,
) -> Option<GpuCookie> {
    let light_from_world = transform.affine().inverse();
    if !(light_from_world.matrix3.is_finite() && light_from_world.translation.is_finite()) {
        return None;
    }
    let (m, t) = (light_from_world.matrix3, light_from_world.translation);
    let row = |i: usize| [m.x_axis[i], m.y_axis[i], m.z_axis[i], t[i]];
    let (projection, tan_outer) = match (spot, point) {
        (Some(spot), _) => {
            let angle = SPOT_ANGLE
                .apply(spot.outer_angle)
                .min(WIDEST_SPOT_PROJECTION);
            (GpuCookie::SPOT, f64::from(angle).tan() as f32)
        }
        (None, Some(_)) => (GpuCookie::POINT + layout_index(cookie.cubemap_layout), 0.0),
        (None, None) => (GpuCookie::DIRECTIONAL, 0.0),
    };
    let flags = if cookie.red_only {
        GpuCookie::RED_ONLY
    } else {
        0
    } | if cookie.tiled { GpuCookie::TILED } else { 0 };
    Some(GpuCookie {
        light_from_world: [row(0), row(1), row(2)],
        layer,
        projection,
        tan_outer,
        flags,
        padding: [0; 4],
    })
}

/// The index the shader gives `layout` (Bevy's `CUBEMAP_TYPE_*`).
fn layout_index(layout: CubemapLayout) -> u32 {
    match layout {
        CubemapLayout::CrossVertical => 0,
        CubemapLayout::CrossHorizontal => 1,
        CubemapLayout::SequenceVertical => 2,
        CubemapLayout::SequenceHorizontal => 3,
    }
}
