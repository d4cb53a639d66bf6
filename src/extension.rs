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
//! reallocated. The buffer holds a 16-byte header ([`GpuLightCount`]), whose first `u32`
//! is the number of records, then the records (those lit everywhere first, then those the
//! clusters list: step 8):
//!
//! ```wgsl
//! struct Lamps {
//!     count: u32,
//!     clustered_first: u32,
//!     cluster_slot: u32,
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
//! With the `reference` feature, `bevy_phong::reference` is the lighting model in `f64`, and
//! `reference::phong_light` is the same term as the shader's: the searchlight example's
//! reference model is built on it. A kind gives each light's term to the model through
//! `PhongLightKind::reference_light` (a `reference::ReferenceLight`); `reference_lights`
//! collects every kind's lights for `reference::Lights::others`, whose terms
//! `reference::shade` adds. The crate's test harness does so, and the searchlight's render
//! tests compare the extended material with the model pixel by pixel, as the crate's own
//! tests do.
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
//! // shadows as fast as before (see `MaterialFeatures::SHADOWS`).
//! var shadow = vec2<f32>(1.0);
//! @if(PHONG_SHADOWS)
//! shadow = shadow_factors(lamp.shadow, input.surface, to_light, lamp.position);
//! color += vec4(phong_light(input.surface, to_light, shadow.x * lamp.color, shadow.y * lamp.color), 0.0);
//! ```
//!
//! The searchlight's beams each request a `Beam`: one orthographic map along the beam.
//! [`PhongLightKind::casts_shadows`] says which lights to ask (the searchlight: those whose
//! `shadows` are on); the plugin keeps the list as lights change, so lights that cast none
//! cost nothing per frame.
//!
//! ## 7. Validation
//!
//! [`PhongLightKind::validate`] replaces the fields of a light that are out of their range,
//! each reported through the [`Checker`] as a warning and an
//! [`InvalidInput`](crate::InvalidInput) naming the entity and the field, before the light
//! is gathered; the checker has the crate's rules for colors, decay, ranges and shadow
//! settings, and [`Checker::number`] for a kind's own numbers. The built-in kinds are
//! validated this way.
//!
//! ## 8. Clusters
//!
//! A kind whose lights end somewhere is put in the crate's per-view light clusters, so that
//! a fragment loops only over the lights that may reach it and a light far from every
//! camera costs no fragment anything. Three optional functions say where a light ends:
//! [`PhongLightKind::reach`] (how far it lights, world units, given its share of
//! [`PhongLightCulling::epsilon`]; with [`PhongLightKind::SHARES_EPSILON`] a light that
//! fades stops where it falls below that share, as the built-in lights do, by
//! [`influence_radius`]), [`PhongLightKind::set_reach`] (stored in the record for the
//! shader to cut the light off there) and [`PhongLightKind::bounding_sphere`] (a sphere
//! holding everything it lights that far). The plugin writes the lights without a sphere
//! first and those with one after them, and lists each of those in the clusters its sphere
//! meets, in the kind's own slot of each cluster's record. The buffer's header
//! ([`GpuLightCount`]) says where the clustered ones start and which slot is the kind's;
//! `bevy_phong::shaders::clusters` finds a fragment's entries:
//!
//! ```wgsl
//! import bevy_phong::shaders::clusters::{kind_entries, kind_record};
//!
//! let header = data_texel(lamps, 0u); // [count, clustered_first, cluster_slot, 0]
//! for (var i = 0u; i < header.y; i += 1u) {
//!     color += lamp_term(input.surface, lamp_at(i));
//! }
//! let entries = kind_entries(header.z, header.y, header.x, input.surface.position);
//! for (var entry = entries.first; entry < entries.end; entry += 1u) {
//!     let i = kind_record(entries, entry);
//!     if i < header.x { // past a full data texture's count, records were left out
//!         color += lamp_term(input.surface, lamp_at(i));
//!     }
//! }
//! ```
//!
//! In a view without clusters (a camera that appeared after the lights were listed, or no
//! light clustered at all) `kind_entries` gives every clustered record: exact either way.
//! The searchlight gives each beam an optional `range`; its sphere holds the prism of its
//! cross-section that long.
//!
//! ## 9. Cookies
//!
//! A kind that takes a [`PhongLightCookie`](crate::PhongLightCookie) on its lights' entities
//! says how the image lies over its rays in [`PhongLightKind::cookie_projection`] (a
//! [`PhongCookieProjection`]: a cone, a cube around the light, or a plane). The plugin
//! puts the image in its cookie atlas and the cookie's record after the built-in lights,
//! and hands the record's index plus one to [`PhongLightKind::set_cookie`] (`0`: none this
//! frame): store it in a `u32` of the record. While some light has a cookie, the flag
//! `PHONG_LIGHT_COOKIES` is set, and the shader tints the light's colors:
//!
//! ```wgsl
//! @if(PHONG_LIGHT_COOKIES)
//! import bevy_phong::shaders::cookies::light_cookie;
//! var tint = vec3<f32>(1.0);
//! @if(PHONG_LIGHT_COOKIES)
//! if lamp.cookie != 0u {
//!     tint = light_cookie(lamp.cookie - 1u, input.surface.position);
//! }
//! ```
//!
//! As for the built-in lights, cookies are left out where storage buffers are missing
//! (WebGL2).
//!
//! ## The built-in kinds
//!
//! [`PhongDirectionalLight`](crate::PhongDirectionalLight),
//! [`PhongPointLight`](crate::PhongPointLight) and [`PhongSpotLight`](crate::PhongSpotLight)
//! implement [`PhongLightKind`] too, and the crate gathers them through it: their records
//! (cached while a component stays equal, through [`PhongLightKind::place`]), reach and
//! clusters, validation, shadows, cookies and reference lights. They share the scene's light
//! buffer rather than a buffer of their own.
//!
//! ## What it costs the built-in lights
//!
//! Nothing per pixel beyond the clusters' one word per kind in each cluster record (the
//! built-in lights and one kind share a 16-byte record; each further four kinds add 16
//! bytes): `PhongMaterial`'s shader is not changed by an extension; only meshes with the
//! extended material run the new loop. Per frame, the extension's gather system checks its
//! change queries and returns when nothing changed. A kind that shares ε makes each light's
//! share smaller (`n` counts its lights too).

pub use crate::light_kind::{PhongLightKind, linear_rgb};
pub use crate::lights::{PhongCookieProjection, influence_radius, light_direction};
pub use crate::shadows::{PhongShadowProjection, PhongShadowRequest};

pub use crate::validation::Checker;
pub use bevy::shape::BoundingSphere;

mod gather;
#[cfg(test)]
mod line_light_tests;
#[cfg(feature = "reference")]
pub(crate) mod reference_lights;
mod shadow_sources;
mod systems;

#[cfg(feature = "reference")]
pub use reference_lights::reference_lights;
pub(crate) use systems::add_light_kind;

use crate::{
    culling::PhongLightCulling,
    render::{
        DataTexture, ExtensionClusterSlots, SharedEpsilonLights, assign_lights_to_clusters,
        gather_lights,
    },
    schedule::PhongSystems,
    storage_buffer::{LightBuffer, MIN_CAPACITY, init_shader_buffers},
};
use bevy::{
    app::{App, Plugin, PostUpdate},
    asset::{AssetApp, Assets, Handle},
    ecs::{resource::Resource, schedule::IntoScheduleConfigs},
    image::Image,
    log::warn,
    render::storage::ShaderBuffer,
};
use bytemuck::{Pod, Zeroable};
use core::marker::PhantomData;
use gather::{count_sharing_lights, gather_light_kind};

/// The 16-byte header of an extension's light buffer: the number of records that follow,
/// those every fragment loops over first, then those found through the clusters.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLightCount {
    /// Number of records.
    pub count: u32,
    /// The first record of the clustered lights (those with a
    /// [`PhongLightKind::bounding_sphere`]): records `0..clustered_first` are lit
    /// everywhere, `clustered_first..count` where their cluster lists them.
    pub clustered_first: u32,
    /// The kind's slot in the clusters' records, for
    /// `bevy_phong::shaders::clusters::kind_entries`.
    pub cluster_slot: u32,
    /// Unused; the records start at a 16-byte boundary.
    pub padding: u32,
}

/// Every visible `L`, for a material to bind: as a storage buffer ([`Self::handle`]) and
/// as a data texture holding the same bytes ([`Self::texture`]), which devices without
/// storage buffers (WebGL2) can bind too.
#[derive(Resource)]
pub struct PhongLightKindBuffer<L: PhongLightKind> {
    buffer: LightBuffer,
    texture: DataTexture,
    records: Vec<L::Gpu>,
    /// The clustered records while the others are gathered.
    clustered: Vec<L::Gpu>,
    /// The header and records as `u32`s, for the texture.
    words: Vec<u32>,
    /// The last header written.
    header: GpuLightCount,
    /// The kind's slot in the clusters.
    cluster_slot: u32,
    /// The kind's place in [`SharedEpsilonLights`] when it shares ε.
    epsilon_share: Option<usize>,
    /// The per-light ε, culling and first cookie index of the last gather.
    gathered_with: Option<(u32, PhongLightCulling, u32)>,
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

    /// The records last written: those lit everywhere, then the clustered ones
    /// ([`Self::header`]).
    pub fn records(&self) -> &[L::Gpu] {
        &self.records
    }

    /// The header last written.
    pub fn header(&self) -> &GpuLightCount {
        &self.header
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
        if crate::light_kind::is_built_in::<L>() {
            warn!(
                "bevy_phong: PhongLightKindPlugin::<{}> is not needed: PhongPlugin gathers the \
                 built-in kinds of light itself; the plugin adds nothing",
                core::any::type_name::<L>()
            );
            return;
        }
        init_shader_buffers(app);
        if !app.world().contains_resource::<Assets<Image>>() {
            app.init_asset::<Image>();
        }
        let world = app.world_mut();
        let buffer = world
            .resource_mut::<Assets<ShaderBuffer>>()
            .reserve_handle();
        let texture = world.resource_mut::<Assets<Image>>().reserve_handle();
        let cluster_slot = world
            .get_resource_or_init::<ExtensionClusterSlots>()
            .add_slot();
        #[cfg(feature = "reference")]
        reference_lights::add_reference_kind::<L>(world);
        let epsilon_share = L::SHARES_EPSILON.then(|| {
            world
                .get_resource_or_init::<SharedEpsilonLights>()
                .add_kind()
        });
        add_light_kind::<L>(app);
        app.insert_resource(PhongLightKindBuffer::<L> {
            buffer: LightBuffer::new(buffer),
            texture: DataTexture::new(texture),
            records: Vec::with_capacity(MIN_CAPACITY),
            clustered: Vec::new(),
            words: Vec::new(),
            header: GpuLightCount::default(),
            cluster_slot,
            epsilon_share,
            gathered_with: None,
        })
        .add_systems(
            PostUpdate,
            ((
                count_sharing_lights::<L>.before(gather_lights),
                gather_light_kind::<L>
                    .after(gather_lights)
                    .before(assign_lights_to_clusters),
            )
                .in_set(PhongSystems::GatherLights),),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        PhongPointLight,
        render::{PhongLightBuffer, PhongLightClusters},
        test_app::{built_in_buffer_bytes, test_app, uploads_in_next_frame},
    };
    use bevy::ecs::component::Component;
    use bevy::prelude::{Camera3d, Transform, Vec3, Visibility};
    use bevy::transform::components::GlobalTransform;

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

    /// A light of a kind with a reach: a sphere of `range` around it.
    #[derive(Component, Clone)]
    #[require(Transform, Visibility)]
    struct Beacon {
        range: f32,
    }

    impl PhongLightKind for Beacon {
        type Gpu = GpuLamp;
        const SHARES_EPSILON: bool = true;
        fn to_gpu(&self, transform: &GlobalTransform) -> GpuLamp {
            GpuLamp {
                position: transform.translation().to_array(),
                padding: self.range,
            }
        }
        fn reach(&self, _record: &GpuLamp, _epsilon: f32) -> f32 {
            self.range
        }
        fn validate(&mut self, checker: &mut Checker) {
            checker.number("range", &mut self.range, 0.0..=f32::INFINITY, 0.0);
        }
        fn bounding_sphere(record: &GpuLamp, reach: f32) -> Option<BoundingSphere> {
            Some(BoundingSphere::new(Vec3::from(record.position), reach))
        }
    }

    /// A light of a kind that takes a cookie, as a cube around it; its record keeps the
    /// cookie's index.
    #[derive(Component, Clone)]
    #[require(Transform, Visibility)]
    struct Lantern;

    #[repr(C)]
    #[derive(Clone, Copy, Pod, Zeroable)]
    struct GpuLantern {
        position: [f32; 3],
        cookie: u32,
    }

    impl PhongLightKind for Lantern {
        type Gpu = GpuLantern;
        fn to_gpu(&self, transform: &GlobalTransform) -> GpuLantern {
            GpuLantern {
                position: transform.translation().to_array(),
                cookie: 0,
            }
        }
        fn cookie_projection(&self) -> Option<PhongCookieProjection> {
            Some(PhongCookieProjection::Cube)
        }
        fn set_cookie(record: &mut GpuLantern, cookie: u32) {
            record.cookie = cookie;
        }
    }

    #[test]
    fn a_kind_that_takes_a_cookie_gets_its_record_after_the_built_in_lights() {
        use crate::{PhongLightCookie, render::GpuCookie, test_app::white_cookie};
        use bevy::{asset::AssetApp, image::Image};
        let mut app = test_app(|app| {
            app.init_asset::<Image>()
                .add_plugins(PhongLightKindPlugin::<Lantern>::default());
        });
        let cookie = white_cookie(&mut app);
        let world = app.world_mut();
        world.spawn((
            PhongPointLight::default(),
            cookie.clone(),
            Transform::from_xyz(0.0, 1.0, 0.0),
        ));
        let lantern = world
            .spawn((Lantern, cookie, Transform::from_xyz(4.0, 5.0, 6.0)))
            .id();
        app.update();

        let lanterns = app.world().resource::<PhongLightKindBuffer<Lantern>>();
        let index = lanterns.records()[0].cookie;
        let built_in = app.world().resource::<PhongLightBuffer>();
        // The point light, its cookie, the lantern's cookie.
        assert_eq!(built_in.records().len(), 3);
        assert_eq!(index, 3, "the third record, plus one");
        let record: GpuCookie = bytemuck::cast(built_in.records()[index as usize - 1]);
        assert_eq!(
            record.projection,
            GpuCookie::CUBE,
            "a cube, laid out as Bevy's default"
        );
        let translation = record.light_from_world.map(|row| row[3]);
        assert_eq!(
            translation,
            [-4.0, -5.0, -6.0],
            "the lantern's inverse transform"
        );

        app.world_mut()
            .entity_mut(lantern)
            .remove::<PhongLightCookie>();
        app.update();
        let lanterns = app.world().resource::<PhongLightKindBuffer<Lantern>>();
        assert_eq!(lanterns.records()[0].cookie, 0, "no cookie: index 0");
    }

    #[test]
    fn a_plugin_for_a_built_in_kind_adds_nothing() {
        let mut app = test_app(|app| {
            app.add_plugins(PhongLightKindPlugin::<PhongPointLight>::default());
        });
        assert!(
            !app.world()
                .contains_resource::<PhongLightKindBuffer<PhongPointLight>>()
        );
        app.world_mut().spawn((
            PhongPointLight::default(),
            Transform::from_xyz(0.0, 1.0, 0.0),
        ));
        app.update();
        let header = app.world().resource::<PhongLightBuffer>().header();
        assert_eq!(header.local_count, 1, "gathered once, by the plugin");
    }

    #[test]
    fn a_kind_validates_its_lights_as_the_built_in_kinds_do() {
        let mut app = test_app(|app| {
            app.add_plugins(PhongLightKindPlugin::<Beacon>::default());
        });
        let beacon = app.world_mut().spawn(Beacon { range: f32::NAN }).id();
        app.update();
        assert_eq!(app.world().get::<Beacon>(beacon).unwrap().range, 0.0);
        let messages = app
            .world()
            .resource::<bevy::ecs::message::Messages<crate::InvalidInput>>();
        let invalid: Vec<_> = messages.iter_current_update_messages().collect();
        assert_eq!(invalid.len(), 1);
        assert_eq!(
            (
                invalid[0].component,
                invalid[0].field,
                invalid[0].value.as_str()
            ),
            ("Beacon", "range", "NaN")
        );
        assert_eq!(invalid[0].owner, crate::Owner::Entity(beacon));
    }

    #[test]
    fn a_far_light_of_a_kind_with_reach_is_looped_over_by_no_fragment() {
        let mut app = test_app(|app| {
            app.add_plugins((
                PhongLightKindPlugin::<Lamp>::default(),
                PhongLightKindPlugin::<Beacon>::default(),
            ));
        });
        let world = app.world_mut();
        world.spawn((
            Camera3d::default(),
            Transform::from_xyz(0.0, 2.0, 10.0).looking_at(Vec3::ZERO, Vec3::Y),
        ));
        let at = |x: f32| Transform::from_xyz(x, 0.0, 0.0);
        world.spawn((Beacon { range: 2.0 }, at(0.0)));
        world.spawn((Beacon { range: 2.0 }, at(1000.0)));
        world.spawn((Beacon { range: 0.0 }, at(0.0)));
        world.spawn((
            Beacon {
                range: f32::INFINITY,
            },
            at(1000.0),
        ));
        app.update();

        // Every fragment loops over records `0..clustered_first`, then over its cluster's
        // entries of the kind's slot (or, in a view without clusters, the rest).
        let beacons = app.world().resource::<PhongLightKindBuffer<Beacon>>();
        let header = *beacons.header();
        let index_at = |x: f32, range: f32| {
            beacons
                .records()
                .iter()
                .position(|record| record.position[0] == x && record.padding == range)
                .unwrap() as u32
        };
        let (near, far, unlimited) = (
            index_at(0.0, 2.0),
            index_at(1000.0, 2.0),
            index_at(1000.0, f32::INFINITY),
        );
        assert_eq!(header.count, 3, "a light that reaches nowhere is left out");
        assert_eq!((header.clustered_first, unlimited), (1, 0));
        assert!(far >= header.clustered_first && near >= header.clustered_first);
        assert_eq!(
            header.cluster_slot, 3,
            "after the built-in slots (local, area) and the Lamp's"
        );

        let clusters = app.world().resource::<PhongLightClusters>();
        assert_eq!(clusters.view_count(), 1);
        assert_eq!(
            clusters.cluster_words(),
            8,
            "slots 0 to 3 and the end of the last: two texels"
        );
        let slot = header.cluster_slot as usize;
        let listed = clusters.first_view_entries(slot..slot + 1).concat();
        assert!(listed.contains(&near), "the light in view is listed");
        assert!(!listed.contains(&far), "the far one in no cluster");

        // The three lit beacons take their share of ε with the built-in lights.
        let epsilon = app.world().resource::<PhongLightCulling>().epsilon;
        let per_light = app
            .world()
            .resource::<PhongLightBuffer>()
            .per_light_epsilon();
        assert_eq!(per_light, epsilon / 4.0, "4 beacons give light");
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
