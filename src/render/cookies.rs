//! The lights' cookies: each frame, every kind that takes one
//! ([`PhongLightKind::cookie_projection`]) asks for its lights' ([`request_cookies`]); the
//! gather makes the atlas of their images ([`super::cookie_atlas`]) and the record of each
//! one, which [`gather_lights`](super::gather_lights) stores after the built-in lights.

use super::cookie_atlas::{PHONG_COOKIE_ATLAS, atlas_image};
use super::gpu_types::GpuCookie;
use crate::light_kind::PhongLightKind;
use crate::lights::{PhongCookieProjection, PhongLightCookie, cookie_layer_texels};
use crate::limits::{CONE_ANGLE, MAX_COOKIE_IMAGES, WIDEST_COOKIE_CONE};
use crate::scene_variants::SceneVariants;
use crate::storage_buffer::LightBufferResized;
use bevy::{
    asset::{AssetEvent, AssetId, Assets},
    camera::primitives::CubemapLayout,
    ecs::{
        change_detection::DetectChangesMut,
        entity::{Entity, EntityHashMap},
        message::{MessageReader, MessageWriter},
        resource::Resource,
        system::{Query, ResMut},
    },
    image::Image,
    log::warn,
    platform::collections::HashSet,
    transform::components::GlobalTransform,
};

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
    /// Images whose texels could not be read (until they change).
    unreadable: HashSet<AssetId<Image>>,
    /// Images already warned about past the atlas's capacity.
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

/// The cookies asked for this frame, by every kind of light: each one's entity, cookie,
/// transform and projection. [`gather_cookies`] empties it.
#[derive(Resource, Debug, Default)]
pub struct CookieRequests {
    requests: Vec<CookieRequest>,
}

/// A light that asks for its cookie: its entity, cookie, transform and projection.
type CookieRequest = (
    Entity,
    PhongLightCookie,
    GlobalTransform,
    PhongCookieProjection,
);

/// Asks for the cookie of every light of kind `L` that has one and takes it
/// ([`PhongLightKind::cookie_projection`]); runs before [`gather_cookies`].
pub(crate) fn request_cookies<L: PhongLightKind>(
    lights: Query<(Entity, &L, &PhongLightCookie, &GlobalTransform)>,
    mut requests: ResMut<CookieRequests>,
) {
    for (entity, light, cookie, transform) in &lights {
        if let Some(projection) = light.cookie_projection() {
            requests.bypass_change_detection().requests.push((
                entity,
                cookie.clone(),
                *transform,
                projection,
            ));
        }
    }
}

/// Makes the atlas (first a white layer), rebuilds it when the set of cookie images changes
/// or one of them is modified, and
/// the records of the cookied lights when any of them changed; it touches [`PhongCookies`]
/// only then, so that [`gather_lights`](super::gather_lights) writes the light buffer only
/// when something changed. Sets the scene's cookie variant (`PHONG_LIGHT_COOKIES`).
pub(crate) fn gather_cookies(
    mut requests: ResMut<CookieRequests>,
    mut image_events: MessageReader<AssetEvent<Image>>,
    mut images: ResMut<Assets<Image>>,
    mut cookies: ResMut<PhongCookies>,
    mut resized: MessageWriter<LightBufferResized>,
    mut variants: ResMut<SceneVariants>,
) {
    let modified: HashSet<AssetId<Image>> = image_events
        .read()
        .filter_map(|event| match event {
            AssetEvent::Modified { id } | AssetEvent::LoadedWithDependencies { id } => Some(*id),
            _ => None,
        })
        .collect();
    // This frame's requests, handed back emptied at the end (keeping their allocation).
    let mut lights = core::mem::take(&mut requests.bypass_change_detection().requests);
    let state = cookies.bypass_change_detection();
    // An image that could not be read may be readable once it changed.
    state.unreadable.retain(|id| !modified.contains(id));
    let layers = state.wanted_layers(&lights, &images);
    let rebuild = layers != state.layers
        || layers.iter().any(|id| modified.contains(id))
        || !images.contains(&PHONG_COOKIE_ATLAS);
    if rebuild {
        state.rebuild_atlas(layers, &mut images);
    }
    let records_changed = state.update_records(&lights);
    lights.clear();
    requests.bypass_change_detection().requests = lights;
    let any = !state.records.is_empty();
    if variants.cookies != any {
        variants.cookies = any;
    }
    if rebuild || records_changed {
        cookies.set_changed();
    }
    if rebuild {
        // A new atlas texture: the materials' bind groups are made again.
        resized.write(LightBufferResized);
    }
}

impl PhongCookies {
    /// The images the atlas should hold: each loaded, readable cookie image of `lights` once,
    /// at most [`MAX_COOKIE_IMAGES`] (a light past them is drawn without its cookie, with a
    /// warning once per image).
    fn wanted_layers(
        &mut self,
        lights: &[CookieRequest],
        images: &Assets<Image>,
    ) -> Vec<AssetId<Image>> {
        let mut layers: Vec<AssetId<Image>> = Vec::new();
        for (entity, cookie, _, _) in lights {
            let id = cookie.image.id();
            if layers.contains(&id) || self.unreadable.contains(&id) || !images.contains(id) {
                continue;
            }
            if layers.len() == MAX_COOKIE_IMAGES {
                if self.warned.insert(id) {
                    warn!(
                        "entity {entity}: PhongLightCookie.image is the {}th distinct cookie \
                         image; the atlas holds {MAX_COOKIE_IMAGES}: the light is drawn without it",
                        MAX_COOKIE_IMAGES + 1
                    );
                }
                continue;
            }
            layers.push(id);
        }
        layers
    }

    /// Makes the atlas of `layers` again, leaving out (with a warning) the images whose
    /// texels cannot be read. The images' texels are read only here, when the atlas changes.
    fn rebuild_atlas(&mut self, mut layers: Vec<AssetId<Image>>, images: &mut Assets<Image>) {
        let mut texels = Vec::new();
        layers.retain(|id| {
            let image = images.get(*id).expect("a loaded image");
            match cookie_layer_texels(image) {
                Some(layer) => {
                    texels.push(layer);
                    true
                }
                None => {
                    warn!(
                        "PhongLightCookie.image {id} has a format whose texels cannot be read \
                         ({:?}) or no texels: its lights are drawn without their cookie",
                        image.texture_descriptor.format
                    );
                    self.unreadable.insert(*id);
                    false
                }
            }
        });
        images
            .insert(&PHONG_COOKIE_ATLAS, atlas_image(&texels))
            .expect("the atlas handle accepts an image");
        self.layers = layers;
    }

    /// Makes the records and slots of the `lights` whose image is in the atlas; returns
    /// whether they differ from the last ones.
    fn update_records(&mut self, lights: &[CookieRequest]) -> bool {
        let mut records = Vec::new();
        let mut slots = EntityHashMap::default();
        for (entity, cookie, transform, projection) in lights {
            let Some(layer) = self.layers.iter().position(|id| *id == cookie.image.id()) else {
                continue;
            };
            let Some(record) = cookie_record(cookie, transform, *projection, layer as u32) else {
                continue;
            };
            slots.insert(*entity, records.len() as u32);
            records.push(record);
        }
        let changed = records != self.records || slots != self.slots;
        if changed {
            self.records = records;
            self.slots = slots;
        }
        changed
    }
}

/// The record of `cookie` on a light at `transform` whose kind lays it by `projection`, in
/// atlas layer `layer`; `None` for a transform that cannot be inverted.
fn cookie_record(
    cookie: &PhongLightCookie,
    transform: &GlobalTransform,
    projection: PhongCookieProjection,
    layer: u32,
) -> Option<GpuCookie> {
    let light_from_world = transform.affine().inverse();
    if !(light_from_world.matrix3.is_finite() && light_from_world.translation.is_finite()) {
        return None;
    }
    let (m, t) = (light_from_world.matrix3, light_from_world.translation);
    let row = |i: usize| [m.x_axis[i], m.y_axis[i], m.z_axis[i], t[i]];
    let (projection, tan_outer) = match projection {
        PhongCookieProjection::Cone { half_angle } => {
            let angle = CONE_ANGLE.apply(half_angle).min(WIDEST_COOKIE_CONE);
            (GpuCookie::CONE, f64::from(angle).tan() as f32)
        }
        PhongCookieProjection::Cube => (GpuCookie::CUBE + layout_index(cookie.cubemap_layout), 0.0),
        PhongCookieProjection::Plane => (GpuCookie::PLANE, 0.0),
    };
    let flags = if cookie.red_only {
        GpuCookie::RED_ONLY
    } else {
        0
    } | if cookie.tiled { GpuCookie::TILED } else { 0 }
        | if cookie.dark_outside {
            GpuCookie::DARK_OUTSIDE
        } else {
            0
        };
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PhongSpotLight;
    use crate::render::GpuLight;
    use crate::test_app::{test_app, uploads_in_next_frame};
    use bevy::{
        asset::{AssetApp, RenderAssetUsages},
        ecs::message::Messages,
        prelude::Transform,
        render::render_resource::{Extent3d, TextureDimension, TextureFormat},
    };

    fn image(format: TextureFormat) -> Image {
        Image::new_fill(
            Extent3d {
                width: 4,
                height: 4,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            &[200, 100, 50, 255, 0, 0, 0, 0][..format.block_copy_size(None).unwrap() as usize],
            format,
            RenderAssetUsages::default(),
        )
    }

    /// How many times the atlas was added or modified since the last call.
    fn atlas_writes(app: &mut bevy::app::App) -> usize {
        app.world_mut()
            .resource_mut::<Messages<AssetEvent<Image>>>()
            .drain()
            .filter(|event| {
                event.is_added(&PHONG_COOKIE_ATLAS) || event.is_modified(&PHONG_COOKIE_ATLAS)
            })
            .count()
    }

    #[test]
    fn a_cookie_gets_a_layer_and_a_record_and_the_atlas_is_written_only_when_it_changes() {
        let mut app = test_app(|app| {
            app.init_asset::<Image>();
        });
        atlas_writes(&mut app);
        let readable = app
            .world_mut()
            .resource_mut::<Assets<Image>>()
            .add(image(TextureFormat::Rgba8UnormSrgb));
        let light = app
            .world_mut()
            .spawn((
                PhongSpotLight::default(),
                Transform::from_xyz(0.0, 3.0, 0.0),
                PhongLightCookie {
                    image: readable,
                    ..Default::default()
                },
            ))
            .id();
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "the light and its cookie"
        );
        assert_eq!(
            atlas_writes(&mut app),
            1,
            "the atlas gets the image's layer"
        );
        let cookies = app.world().resource::<PhongCookies>();
        assert_eq!(cookies.records().len(), 1);
        assert_eq!(cookies.slot_of(light), 1);
        let buffer = app.world().resource::<super::super::PhongLightBuffer>();
        // One light, then its cookie's record: the light holds index 1 (plus one).
        assert_eq!(buffer.records().len(), 2);
        assert_eq!(buffer.records()[0].shadow >> GpuLight::COOKIE_SHIFT, 2);

        assert_eq!(uploads_in_next_frame(&mut app), 0, "nothing changed");
        assert_eq!(atlas_writes(&mut app), 0, "nor the atlas");

        // A compressed image: no layer, no record, a warning, and no rebuild after that.
        let compressed = app
            .world_mut()
            .resource_mut::<Assets<Image>>()
            .add(image(TextureFormat::Bc1RgbaUnorm));
        app.world_mut()
            .get_mut::<PhongLightCookie>(light)
            .unwrap()
            .image = compressed;
        app.update();
        assert_eq!(app.world().resource::<PhongCookies>().records().len(), 0);
        atlas_writes(&mut app);
        app.update();
        assert_eq!(
            atlas_writes(&mut app),
            0,
            "an unreadable image is read once"
        );
    }
}
