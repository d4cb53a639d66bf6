//! # Adding a light kind
//!
//! A new kind of light plugs into Phong lighting without touching this crate: a component,
//! a GPU record, a material extension and a few lines of WESL. The crate's
//! `examples/searchlight` builds a searchlight (a beam of parallel
//! light with a circular, triangular, diamond or square cross-section) this way; the steps
//! below follow it.
//!
//! ## 1. The component and its GPU record
//!
//! The light is a component that requires `Transform` and `Visibility`, like the built-in
//! ones. Its GPU record is a `#[repr(C)]` [`bytemuck::Pod`] struct whose size is a
//! multiple of 16 bytes, laid out like the WGSL struct the shader reads (a `vec3<f32>` takes
//! 16 bytes when an `f32` follows it, so pair each `[f32; 3]` with one `f32`).
//! Implementing [`PhongLightKind`] says how an entity becomes a record:
//!
//! ```
//! use bevy::prelude::*;
//! use bevy_phong::extension::{PhongLightKind, linear_rgb};
//!
//! #[derive(Component, Clone)]
//! #[require(Transform, Visibility)]
//! struct Lamp {
//!     color: Color,
//! }
//!
//! #[repr(C)]
//! #[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
//! struct GpuLamp {
//!     position: [f32; 3],
//!     padding: f32,
//!     color: [f32; 3],
//!     padding2: f32,
//! }
//!
//! impl PhongLightKind for Lamp {
//!     type Gpu = GpuLamp;
//!     fn to_gpu(&self, transform: &GlobalTransform) -> GpuLamp {
//!         GpuLamp {
//!             position: transform.translation().to_array(),
//!             padding: 0.0,
//!             color: linear_rgb(self.color),
//!             padding2: 0.0,
//!         }
//!     }
//! }
//! ```
//!
//! ## 2. The buffer
//!
//! [`PhongLightKindPlugin::<Lamp>`](PhongLightKindPlugin) gathers every visible `Lamp` into
//! a storage buffer of its own with the machinery the built-in lights use: it rewrites the
//! buffer only in frames where a lamp was added, changed, moved, shown, hidden or removed;
//! the buffer grows and shrinks with the count; bind groups follow it when it is
//! reallocated. The buffer holds a 16-byte header, whose first `u32` is the number of
//! records, then the records:
//!
//! ```wgsl
//! struct Lamps {
//!     count: u32,
//!     lights: array<Lamp>,
//! }
//! ```
//!
//! [`PhongLightKindBuffer<Lamp>`](PhongLightKindBuffer) holds its handle, for the material,
//! and a data texture with the same bytes ([`PhongLightKindBuffer::texture`]): devices
//! without storage buffers (WebGL2, where the crate's own lights travel the same way) bind
//! that instead.
//!
//! ## 3. The material
//!
//! The lamp lights meshes whose material binds its lights: Bevy's `ExtendedMaterial` with
//! [`PhongMaterial`](crate::PhongMaterial) as the base keeps every Phong field and adds the
//! binding. The data texture binds on every device:
//!
//! ```
//! # use bevy::prelude::*;
//! # use bevy_phong::extension::{PhongLightKind, linear_rgb};
//! # #[derive(Component, Clone)]
//! # #[require(Transform, Visibility)]
//! # struct Lamp { color: Color }
//! # #[repr(C)]
//! # #[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
//! # struct GpuLamp { position: [f32; 3], padding: f32, color: [f32; 3], padding2: f32 }
//! # impl PhongLightKind for Lamp {
//! #     type Gpu = GpuLamp;
//! #     fn to_gpu(&self, transform: &GlobalTransform) -> GpuLamp {
//! #         GpuLamp { position: transform.translation().to_array(), padding: 0.0,
//! #                   color: linear_rgb(self.color), padding2: 0.0 }
//! #     }
//! # }
//! use bevy::{
//!     pbr::{ExtendedMaterial, MaterialExtension},
//!     render::render_resource::AsBindGroup,
//!     shader::ShaderRef,
//! };
//! use bevy_phong::{extension::PhongLightKindPlugin, prelude::*};
//!
//! #[derive(Asset, AsBindGroup, Reflect, Clone)]
//! struct LampExtension {
//!     #[texture(100, sample_type = "u_int")]
//!     lamps: Handle<Image>,
//! }
//!
//! impl MaterialExtension for LampExtension {
//!     fn fragment_shader() -> ShaderRef {
//!         "shaders/lamp.wesl".into()
//!     }
//! }
//!
//! fn add_lamps(app: &mut App) {
//!     app.add_plugins(PhongLightKindPlugin::<Lamp>::default())
//!         .add_phong_material::<ExtendedMaterial<PhongMaterial, LampExtension>>();
//! }
//! ```
//!
//! Create the material with the texture's handle, from
//! `Res<PhongLightKindBuffer<Lamp>>`: `LampExtension { lamps: buffer.texture().clone() }`.
//! An extension for native devices only can bind the storage buffer instead:
//! `#[storage(100, read_only)] lamps: Handle<ShaderBuffer>` with `buffer.handle()`.
//!
//! Register the material with
//! [`add_phong_material`](crate::PhongMaterialAppExt::add_phong_material) rather than
//! `MaterialPlugin`: it also keeps the material's bind groups on the current buffers.
//!
//! ## 4. The shader
//!
//! The extension's fragment shader (WESL) builds on the crate's shader API,
//! `bevy_phong::shaders::fragment`, in three steps, as Bevy's PBR shaders build on
//! `pbr_input_from_standard_material`, `apply_pbr_lighting` and
//! `main_pass_post_lighting_processing`: `phong_input_from_material` gives the surface as
//! the `PhongMaterial` and its maps give it at the fragment (vertex colors, every map, flat
//! shading, the alpha mask); `apply_phong_lighting` lights it with the crate's lights;
//! `phong_post_lighting_processing` adds what the camera adds (fog, tone mapping). The new
//! kind's term goes between the last two, with the crate's per-light function `phong_light`
//! (diffuse plus highlight for a light direction `L`); attenuation and shape are the kind's
//! own:
//!
//! ```wgsl
//! import bevy_pbr::render::forward_io::VertexOutput;
//! import bevy_phong::shaders::{
//!     data_texture::data_texel,
//!     fragment::{apply_phong_lighting, phong_input_from_material, phong_post_lighting_processing},
//!     lighting::{phong_light, normalize_or_zero},
//! };
//!
//! @group(constants::MATERIAL_BIND_GROUP) @binding(100) var lamps: texture_2d<u32>;
//!
//! struct Lamp { position: vec3<f32>, color: vec3<f32> }
//!
//! // Texel 0 holds the count; each 32-byte lamp takes 2 texels after it.
//! fn lamp_at(index: u32) -> Lamp {
//!     let a = data_texel(lamps, 1u + 2u * index);
//!     let b = data_texel(lamps, 2u + 2u * index);
//!     return Lamp(bitcast<vec3<f32>>(a.xyz), bitcast<vec3<f32>>(b.xyz));
//! }
//!
//! @fragment
//! fn fragment(@builtin(front_facing) is_front: bool, in: VertexOutput) -> @location(0) vec4<f32> {
//!     let input = phong_input_from_material(in, is_front);
//!     var color = apply_phong_lighting(input);
//!     let count = data_texel(lamps, 0u).x;
//!     for (var i = 0u; i < count; i += 1u) {
//!         let lamp = lamp_at(i);
//!         let to_light = normalize_or_zero(lamp.position - input.surface.position);
//!         color += vec4(phong_light(input.surface, to_light, lamp.color, lamp.color), 0.0);
//!     }
//!     return phong_post_lighting_processing(input, color);
//! }
//! ```
//!
//! Bound as a storage buffer, the same lamps read `lamps.lights[i]` from
//! `var<storage, read> lamps: Lamps` (the struct above). The repository's
//! `docs/extension.md` lists every function of the API and what changed from the naga_oil
//! imports of bevy_phong 0.1.
//!
//! ## 5. The reference
//!
//! [`reference::phong_light`](crate::reference::phong_light) is the same term in `f64`:
//! the searchlight example's reference model is built on it, and its render test compares
//! the extended material with it pixel by pixel, as the crate's own tests do.
//!
//! ## 6. Shadows
//!
//! A kind casts shadows by describing its rays in [`PhongLightKind::shadow`], a
//! [`PhongShadowRequest`] with one of the
//! [`PhongShadowProjection`] shapes (sunlight, a
//! parallel beam, a cone, all directions) and [`PhongShadows`](crate::PhongShadows)
//! settings. The plugin renders the maps with the built-in lights' and hands each light its
//! slot through [`PhongLightKind::set_shadow`]: store it in a `u32` of the record. The
//! shader turns the slot into the factors on the two terms:
//!
//! ```wgsl
//! @if(PHONG_SHADOWS)
//! import bevy_phong::shaders::shadows::shadow_factors;
//! // Per light: (diffuse factor, specular factor); `input.surface.receives_shadows` already
//! // honours `NotShadowReceiver`. The flag `PHONG_SHADOWS` is set only while some light
//! // casts shadows: without it the shadow code is left out, which keeps scenes without
//! // shadows as fast as before (see `PhongMaterialKey::shadows`).
//! var shadow = vec2<f32>(1.0);
//! @if(PHONG_SHADOWS)
//! shadow = shadow_factors(lamp.shadow, input.surface, to_light, lamp.position);
//! color += vec4(phong_light(input.surface, to_light, shadow.x * lamp.color, shadow.y * lamp.color), 0.0);
//! ```
//!
//! The searchlight's beams each request a `Beam`: one orthographic map along the beam.
//!
//! ## What it costs the built-in lights
//!
//! Nothing per pixel: `PhongMaterial`'s shader is not changed by an extension; only meshes
//! with the extended material run the new loop. Per frame, the extension's gather system
//! checks its change queries and returns when nothing changed.

pub use crate::lights::light_direction;
pub use crate::render::linear_rgb;
pub use crate::shadows::{PhongShadowProjection, PhongShadowRequest};

use crate::render::DATA_TEXTURE_MAX_TEXELS;
use crate::{
    lights::{LightQuery, lit_lights},
    render::{DataTexture, DataTextureWrite, LightChanges, push_visible, words_of},
    schedule::PhongSystems,
    shadows::{ShadowRequests, ShadowSlots},
    storage_buffer::{LightBuffer, LightBufferResized, MIN_CAPACITY, init_shader_buffers},
};
use bevy::{
    app::{App, Plugin, PostUpdate},
    asset::{AssetApp, Assets, Handle},
    ecs::{
        change_detection::DetectChanges,
        component::Component,
        message::MessageWriter,
        resource::Resource,
        schedule::IntoScheduleConfigs,
        system::{Res, ResMut},
    },
    image::Image,
    log::warn_once,
    render::storage::ShaderBuffer,
    transform::components::GlobalTransform,
};
use bytemuck::{Pod, Zeroable};
use core::marker::PhantomData;

/// A light component that an extension adds, gathered into its own GPU buffer by
/// [`PhongLightKindPlugin`].
pub trait PhongLightKind: Component {
    /// The record the shader reads for one light: `#[repr(C)]`, a multiple of 16 bytes.
    type Gpu: Pod + Send + Sync;

    /// The record of this light, placed by its entity's transform.
    fn to_gpu(&self, transform: &GlobalTransform) -> Self::Gpu;

    /// The shadow this light casts, placed by its entity's transform; `None` (the default),
    /// or a request whose settings are off, casts none. See
    /// [`PhongShadowProjection`] for
    /// the shapes of light that get maps.
    fn shadow(&self, transform: &GlobalTransform) -> Option<PhongShadowRequest> {
        let _ = transform;
        None
    }

    /// Stores the light's shadow slot in its record: the index of its first shadow view plus
    /// one, or `0` when it casts no shadow this frame. The shader passes it to
    /// `bevy_phong::shaders::shadows::light_visibility`. Kinds without shadows keep the default,
    /// which stores nothing.
    fn set_shadow(record: &mut Self::Gpu, shadow: u32) {
        let _ = (record, shadow);
    }
}

/// The 16-byte header of an extension's light buffer: the number of records that follow.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLightCount {
    /// Number of records.
    pub count: u32,
    /// Unused; the records start at a 16-byte boundary.
    pub padding: [u32; 3],
}

/// Every visible `L`, for a material to bind: as a storage buffer ([`Self::handle`]) and
/// as a data texture holding the same bytes ([`Self::texture`]), which devices without
/// storage buffers (WebGL2) can bind too.
#[derive(Resource)]
pub struct PhongLightKindBuffer<L: PhongLightKind> {
    buffer: LightBuffer,
    texture: DataTexture,
    records: Vec<L::Gpu>,
    /// The header and records as `u32`s, for the texture.
    words: Vec<u32>,
}

impl<L: PhongLightKind> PhongLightKindBuffer<L> {
    /// The storage buffer to bind with `#[storage(N, read_only)]`: a [`GpuLightCount`]
    /// header, then the records.
    pub fn handle(&self) -> &Handle<ShaderBuffer> {
        self.buffer.handle()
    }

    /// The same bytes in a data texture, to bind with `#[texture(N, sample_type = "u_int")]`
    /// on every device, WebGL2 included: texel 0 is the [`GpuLightCount`] header, record
    /// `i` starts at texel `1 + i · size_of::<L::Gpu>() / 16`. WGSL reads texel `t` with
    /// `bevy_phong::shaders::data_texture::data_texel(texture, t)`. It holds up to
    /// `DATA_TEXTURE_MAX_TEXELS` texels; past
    /// them the last records are left out, with a warning.
    pub fn texture(&self) -> &Handle<Image> {
        self.texture.handle()
    }

    /// The records last written.
    pub fn records(&self) -> &[L::Gpu] {
        &self.records
    }
}

/// Gathers every visible `L` into [`PhongLightKindBuffer<L>`] in
/// [`PhongSystems::GatherLights`], with the built-in lights' change tracking and growth.
/// Add it after [`PhongPlugin`](crate::PhongPlugin).
pub struct PhongLightKindPlugin<L: PhongLightKind>(PhantomData<fn() -> L>);

impl<L: PhongLightKind> Default for PhongLightKindPlugin<L> {
    fn default() -> Self {
        Self(PhantomData)
    }
}

impl<L: PhongLightKind> Plugin for PhongLightKindPlugin<L> {
    fn build(&self, app: &mut App) {
        const {
            assert!(
                size_of::<L::Gpu>() % 16 == 0 && size_of::<L::Gpu>() > 0,
                "PhongLightKind::Gpu must be a non-empty multiple of 16 bytes, as WGSL lays it out"
            )
        };
        init_shader_buffers(app);
        if !app.world().contains_resource::<Assets<Image>>() {
            app.init_asset::<Image>();
        }
        let world = app.world_mut();
        let buffer = world
            .resource_mut::<Assets<ShaderBuffer>>()
            .reserve_handle();
        let texture = world.resource_mut::<Assets<Image>>().reserve_handle();
        app.insert_resource(PhongLightKindBuffer::<L> {
            buffer: LightBuffer::new(buffer),
            texture: DataTexture::new(texture),
            records: Vec::with_capacity(MIN_CAPACITY),
            words: Vec::new(),
        })
        .add_systems(
            PostUpdate,
            (
                request_kind_shadows::<L>.in_set(PhongSystems::RequestShadows),
                gather_light_kind::<L>.in_set(PhongSystems::GatherLights),
            ),
        );
    }
}

/// Adds the shadow request of every visible `L` that casts one.
fn request_kind_shadows<L: PhongLightKind>(
    lights: LightQuery<L>,
    mut requests: ResMut<ShadowRequests>,
) {
    for (entity, light, transform) in lit_lights(&lights) {
        if let Some(request) = light.shadow(transform) {
            requests.push(entity, request);
        }
    }
}

/// Writes every visible `L` into its buffer when any of them or their shadow slots changed
/// (and on the first run).
pub(crate) fn gather_light_kind<L: PhongLightKind>(
    lights: LightQuery<L>,
    slots: Res<ShadowSlots>,
    mut changes: LightChanges<L>,
    mut state: ResMut<PhongLightKindBuffer<L>>,
    mut buffers: ResMut<Assets<ShaderBuffer>>,
    mut images: ResMut<Assets<Image>>,
    mut resized: MessageWriter<LightBufferResized>,
) {
    let changed = changes.any() || slots.is_changed();
    if !changed && state.buffer.capacity() > 0 {
        return;
    }
    let state = &mut *state;
    state.records.clear();
    let count = push_visible(
        &lights,
        |entity| slots.get(entity),
        &mut state.records,
        |light, transform, shadow| {
            let mut record = light.to_gpu(transform);
            L::set_shadow(&mut record, shadow);
            record
        },
    );
    let header = GpuLightCount {
        count,
        padding: [0; 3],
    };
    let buffer_resized = state.buffer.write(&mut buffers, &header, &state.records);
    let texture_resized = write_texture::<L>(state, &mut images, header);
    if buffer_resized || texture_resized {
        resized.write(LightBufferResized);
    }
}

/// Writes the header and records into the kind's data texture, leaving out the last records
/// past its capacity (with a warning). Returns whether the texture changed size.
fn write_texture<L: PhongLightKind>(
    state: &mut PhongLightKindBuffer<L>,
    images: &mut Assets<Image>,
    mut header: GpuLightCount,
) -> bool {
    let record_texels = size_of::<L::Gpu>() / 16;
    let room = (DATA_TEXTURE_MAX_TEXELS - 1) / record_texels;
    if state.records.len() > room {
        warn_once!(
            "bevy_phong: {} {} lights do not fit their data texture ({room} do): the last ones are left out",
            state.records.len(),
            core::any::type_name::<L>()
        );
        header.count = room as u32;
    }
    let kept = &state.records[..state.records.len().min(room)];
    state.words.clear();
    state.words.extend(words_of(bytemuck::bytes_of(&header)));
    state.words.extend(words_of(bytemuck::cast_slice(kept)));
    state.texture.write(images, &state.words) == DataTextureWrite::Resized
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        PhongPointLight,
        test_app::{built_in_buffer_bytes, test_app, uploads_in_next_frame},
    };
    use bevy::prelude::{Transform, Visibility};

    #[derive(Component, Clone)]
    #[require(Transform, Visibility)]
    struct Lamp;

    #[repr(C)]
    #[derive(Clone, Copy, Pod, Zeroable)]
    struct GpuLamp {
        position: [f32; 3],
        padding: f32,
    }

    impl PhongLightKind for Lamp {
        type Gpu = GpuLamp;
        fn to_gpu(&self, transform: &GlobalTransform) -> GpuLamp {
            GpuLamp {
                position: transform.translation().to_array(),
                padding: 0.0,
            }
        }
    }

    fn with_lamps(app: &mut App) {
        app.add_plugins(PhongLightKindPlugin::<Lamp>::default());
    }

    #[test]
    fn an_extension_without_lights_costs_the_built_in_lights_nothing() {
        let mut plain = test_app(|_| {});
        let mut extended = test_app(with_lamps);
        for app in [&mut plain, &mut extended] {
            app.world_mut().spawn((
                PhongPointLight::default(),
                Transform::from_xyz(0.0, 1.0, 0.0),
            ));
            assert_eq!(
                uploads_in_next_frame(app),
                1,
                "only the built-in buffer changes"
            );
            assert_eq!(uploads_in_next_frame(app), 0, "then nothing is uploaded");
        }
        assert_eq!(
            built_in_buffer_bytes(&plain),
            built_in_buffer_bytes(&extended)
        );
        let lamps = extended.world().resource::<PhongLightKindBuffer<Lamp>>();
        assert!(lamps.records().is_empty());
    }

    #[test]
    fn extension_lights_get_their_own_buffer_with_the_same_change_tracking() {
        let mut app = test_app(with_lamps);
        let lamp = app
            .world_mut()
            .spawn((Lamp, Transform::from_xyz(4.0, 5.0, 6.0)))
            .id();
        assert_eq!(uploads_in_next_frame(&mut app), 1);
        let buffers = app.world().resource::<Assets<ShaderBuffer>>();
        let lamps = app.world().resource::<PhongLightKindBuffer<Lamp>>();
        let bytes = crate::storage_buffer::buffer_bytes(buffers.get(lamps.handle()).unwrap())
            .unwrap()
            .to_vec();
        let header: &GpuLightCount = bytemuck::from_bytes(&bytes[..16]);
        assert_eq!(header.count, 1);
        assert_eq!(
            bytemuck::cast_slice::<u8, f32>(&bytes[16..28]),
            [4.0, 5.0, 6.0]
        );
        assert_eq!(uploads_in_next_frame(&mut app), 0);

        for i in 0..100 {
            app.world_mut()
                .spawn((Lamp, Transform::from_xyz(i as f32, 0.0, 0.0)));
        }
        app.update();
        let lamps = app.world().resource::<PhongLightKindBuffer<Lamp>>();
        assert_eq!(lamps.records().len(), 101);
        app.world_mut().despawn(lamp);
        app.update();
        assert_eq!(
            app.world()
                .resource::<PhongLightKindBuffer<Lamp>>()
                .records()
                .len(),
            100
        );
    }
}
