//! # bevy_phong
//!
//! A Phong / Blinn-Phong material for Bevy, lit by its own light entities.
//!
//! Add [`PhongPlugin`], spawn lights as entities, and give meshes a [`PhongMaterial`]:
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_phong::prelude::*;
//!
//! fn main() {
//!     App::new()
//!         .add_plugins((DefaultPlugins, PhongPlugin))
//!         .add_systems(Startup, setup)
//!         .run();
//! }
//!
//! fn setup(
//!     mut commands: Commands,
//!     mut meshes: ResMut<Assets<Mesh>>,
//!     mut materials: ResMut<Assets<PhongMaterial>>,
//! ) {
//!     commands.spawn((
//!         PhongPointLight {
//!             color: Color::srgb(1.0, 0.0, 0.0),
//!             decay: Decay::quadratic(0.02),
//!             ..default()
//!         },
//!         Transform::from_xyz(-3.0, 3.0, 0.0),
//!     ));
//!     commands.spawn((
//!         Mesh3d(meshes.add(Sphere::new(1.0))),
//!         MeshMaterial3d(materials.add(PhongMaterial {
//!             base_color: Color::srgb(1.0, 0.0, 1.0),
//!             specular_strength: 2.0,
//!             shininess: 50.0,
//!             ..default()
//!         })),
//!     ));
//!     commands.spawn((Camera3d::default(), Transform::from_xyz(0.0, 0.0, 6.0)));
//! }
//! ```
//!
//! ## Concepts
//!
//! - **The lighting model** is SPEC.md's equation: ambient, plus for each light a Lambert
//!   diffuse term and a Phong or Blinn-Phong highlight, scaled by distance fall-off
//!   ([`Decay`]) and a spot cone. `bevy_phong::reference` (feature `reference`) evaluates it
//!   in `f64`; it is the specification in code, and the tests compare the shader with it
//!   pixel by pixel.
//! - **Lights** are components: [`PhongDirectionalLight`], [`PhongPointLight`],
//!   [`PhongSpotLight`], and the area lights [`PhongRectLight`] and [`PhongDiskLight`] (a
//!   rectangle or a disk whose light is integrated over its area: SPEC.md, "Area lights"); the ambient light is the resource
//!   [`PhongAmbientLight`]. They
//!   light only [`PhongMaterial`]s; Bevy's own `PointLight` & co. light them too once
//!   [`PhongBevyLightsPlugin`] (opt-in, see [`interop`]) mirrors them. There is no fixed
//!   maximum count.
//! - **Culling** ([`culling`]) skips the lights that cannot reach a point: past each light's
//!   range, and (with [`PhongLightCulling`]'s ε) where it has faded below a bound on the
//!   total error; each camera's view is cut into clusters ([`PhongViewClusters`]) that
//!   list the lights that may reach them, so each fragment loops over only the lights of
//!   its cluster, and a light that reaches no view costs nothing per fragment. Materials
//!   without a highlight use a shader variant without the specular term
//!   ([`PhongMaterialKey`]).
//! - **The light buffer** is a storage buffer (under WebGL2's limits, a data texture) that
//!   the gather system rewrites in the frames where a light changed; [`PhongSceneBindings`]
//!   binds it, with the clusters and the shadow maps, to each material.
//! - **Shaders** are embedded WESL modules, imported at `bevy_phong::shaders::NAME`:
//!   `fragment` (the shader API for extensions: the mapped surface, its lit color, the
//!   camera's effects), `types`, `lighting` (one function per term of the equation),
//!   `bindings` and `shading`. No file from `assets/` is needed.
//! - **New light kinds** plug in from outside the crate: [`extension`] is the guide, with a
//!   searchlight as the worked example.
//! - **Invalid input** (a negative range, a NaN color, ...) is replaced by a documented value
//!   with one warning naming the entity and field, and an [`InvalidInput`] message. Every
//!   float has a documented range (in its field's docs), chosen so that no finite input
//!   overflows to infinity.
//! - **Scene and material files** ([`scene`]): a scene written in RON
//!   (`*.phong_scene.ron`), spawned by a [`PhongSceneRoot`](scene::PhongSceneRoot) and
//!   hot-reloaded; a material alone in a `*.phong.ron` file.
//! - **Texture maps**: base color, specular, emissive, normal, alpha, bump, displacement,
//!   light, ambient occlusion and toon ramp maps and an environment cube map on
//!   [`PhongMaterial`] ([`MaterialFeatures`] lists them), each sampled only by the materials
//!   that have it.
//! - **From Bevy's own types**: `PhongMaterial::from(&StandardMaterial)`;
//!   [`PhongStandardMaterialPlugin`] switches every `StandardMaterial` mesh of a game to it,
//!   and [`PhongBevyLightsPlugin`] mirrors Bevy's lights.
//! - **Shadows**: each light's [`PhongShadows`] turns on shadow maps that the
//!   plugin renders (cascades for directional lights, a cube for point lights, one map for
//!   spot lights), filtered with percentage-closer soft shadows; `NotShadowCaster` and
//!   `NotShadowReceiver` work as on Bevy's meshes.
//! - **glTF files** ([`gltf`], feature `gltf`, on by default): [`PhongGltfPlugin`] gives
//!   each material of a glTF file a `PhongMaterial` made from its metallic/roughness values,
//!   and the file's lights become Phong lights.
//!
//! ## Features
//!
//! - `gltf` (default): [`PhongGltfPlugin`] and Bevy's glTF loader.
//! - `scene` (default): scene and material files ([`scene`]), with `ron` and `serde`.
//! - `reference`: `bevy_phong::reference`, the lighting model in `f64`, for a light kind's
//!   tests and for tools that check frames (the crate's tests compare every pixel with it).
//! - `testing` (with `reference`): `bevy_phong::testing`, the internals the crate's own tests, benchmarks and
//!   render harness read (GPU layouts, gather systems, the limits table, a material that
//!   renders each pixel's world position and normal). Not for games; not a stable API.
//!
//! ## Layers
//!
//! The top-level modules form layers. Besides itself, a module uses only modules of lower
//! layers (none of its own layer or above), so that the imports point one way and no
//! module needs the plugin that ties them together. From the bottom:
//!
//! 1. foundations, which use nothing of the crate: `limits`, `direction`, `displacement`
//!    (the displaced vertex stages), `quoting`,
//!    `schedule` (the [`PhongSystems`] sets), `scene_variants` (the scene's shader
//!    variants: shadows, the hemisphere light, cookies; each app's, carried by its materials), `storage_buffer` (the growable GPU buffer),
//!    `view_key` (how a fragment finds its view's clusters and cascades);
//! 2. the data model: `lights` (what every light shares: fall-off, reach, shadow settings,
//!    cookies, the rule of which lights give light; the ambient and hemisphere lights),
//!    `material`, `culling`;
//! 3. rules over the model: `validation`, `reference`;
//! 4. `shadows`, which lays out and draws the shadow maps;
//! 5. `light_kind`, what the crate needs of each kind of light (the trait every kind,
//!    built-in or an extension's, implements: record, reach, validation, shadows, cookie,
//!    reference light), and the built-in kinds, one folder each (`light_kind/spot/`: the
//!    component, its kind, its cone, its reference light);
//! 6. `render`, which gathers the lights and binds them, with the shadow maps, to materials;
//! 7. features on top of those: `scene`, `interop`, `from_three`, `extension`,
//!    `surface_inputs`;
//! 8. `plugin`, which adds all of it to an app;
//! 9. `gltf`, whose [`PhongGltfPlugin`] adds the mirror of Bevy's lights and expects
//!    [`PhongPlugin`];
//! 10. `testing` (only with the `testing` feature), which re-exports the internals that the
//!     crate's own tests, benchmarks and harness read.
//!
//! `docs/design/layout.md` draws these rooms and the folders of the light kinds.
//!
//! Tests are exempt (the `#[cfg(test)]` items and files, such as `test_app`): they may use
//! any layer. A unit test (`layering_tests`) reads the sources and fails on an import that
//! points up or sideways; another (`file_circle_tests`) fails where two files use each
//! other, so that within a module too each file's imports point one way.
//!
//! ## Worlds
//!
//! Bevy runs a main world (the game's entities, `PostUpdate`) and a render world (extracted
//! copies, the `Render` schedule); values cross only through extraction. Each module's
//! part:
//!
//! | module | main world | render world |
//! |---|---|---|
//! | `lights`, `light_kind` (and its kinds' folders), `culling`, `validation`, `scene`, `interop`, `gltf`, `schedule` | all of it | |
//! | `render` | the gathers: light records, clusters, cookies, the data texture (`gather`, `cluster_views`, `clusters`, `cookies`, `light_records`, `scene_texture`) | the material bind groups (`material_bindings`) and their order after the uploads (`material_upkeep`, which also marks materials in the main world) |
//! | `shadows` | which lights cast, the views and casters (`gather`, `sources`, `request`, `cameras`, `views`) | the shadow passes (`render`, `posed`, `deformed`, `displaced`) |
//! | `material`, `scene_variants` | the asset and the scene's variants | the key and the pipeline (`specialize`) |
//! | `extension` | a kind's gather | its binding |
//! | `displacement`, `surface_inputs` | | vertex stages, a capture material |
//! | `reference`, `limits`, `direction`, `quoting`, `view_key` | pure functions | |

pub mod culling;
mod direction;
mod displacement;
pub mod extension;
pub mod from_three;
#[cfg(feature = "gltf")]
pub mod gltf;
pub mod interop;
mod light_kind;
mod lights;
mod limits;
mod material;
mod plugin;
mod quoting;
#[cfg(feature = "reference")]
pub mod reference;
mod render;
#[cfg(feature = "scene")]
pub mod scene;
mod scene_variants;
mod schedule;
mod shadows;
mod storage_buffer;
#[cfg(feature = "testing")]
mod surface_inputs;
#[cfg(test)]
mod test_app;
#[cfg(feature = "testing")]
pub mod testing;
mod validation;
mod view_key;

#[cfg(test)]
mod docs_tests;
#[cfg(test)]
mod file_circle_tests;
#[cfg(test)]
mod layering_tests;

pub use culling::{PhongLightCulling, PhongViewClusters};
#[cfg(feature = "gltf")]
pub use gltf::PhongGltfPlugin;
pub use interop::{BevyLightExposure, PhongBevyLightsPlugin, PhongStandardMaterialPlugin};
pub use light_kind::{
    PhongDirectionalLight, PhongDiskLight, PhongPointLight, PhongRectLight, PhongSpotLight,
};
pub use lights::{
    AreaHighlight, ConeEdge, Decay, PhongAmbientLight, PhongCascades, PhongHemisphereLight,
    PhongLightCookie, PhongShadows,
};
pub use material::{
    DiffuseMode, EnvironmentCombine, MaterialFeatures, PhongMaterial, PhongMaterialKey,
    PhongSceneMaterial, SpecularMode, SpecularModel,
};
pub use plugin::{PhongMaterialAppExt, PhongPlugin};
pub use render::PhongSceneBindings;
pub use schedule::PhongSystems;
pub use shadows::PhongLit;
pub use validation::{InvalidInput, Owner};

/// `use bevy_phong::prelude::*;` imports the plugins, the material and the lights: everything
/// a game names to set up a scene.
pub mod prelude {
    pub use crate::{
        AreaHighlight, BevyLightExposure, ConeEdge, Decay, DiffuseMode, EnvironmentCombine,
        PhongAmbientLight, PhongBevyLightsPlugin, PhongCascades, PhongDirectionalLight,
        PhongDiskLight, PhongHemisphereLight, PhongLightCookie, PhongLightCulling, PhongMaterial,
        PhongMaterialAppExt, PhongPlugin, PhongPointLight, PhongRectLight, PhongSceneMaterial,
        PhongShadows, PhongSpotLight, PhongStandardMaterialPlugin, PhongViewClusters, SpecularMode,
        SpecularModel,
    };

    #[cfg(feature = "scene")]
    pub use crate::scene::{PhongScene, PhongSceneCamera, PhongSceneRoot};

    #[cfg(feature = "gltf")]
    pub use crate::gltf::PhongGltfPlugin;
}
