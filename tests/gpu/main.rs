//! The tests that run on the render device (Mesa's lavapipe in CI), in one binary:
//!
//! - `adoption`: the minimal example's scene, and a scene of Bevy's own materials and
//!   lights switched to Phong, against the reference model;
//! - `ambient_specular`: materials converted from `StandardMaterial`, metals and
//!   dielectrics, reflecting the ambient and hemisphere light by their specular color,
//!   against the reference model;
//! - `area_lights`: rectangle lights against the reference model's quadrature over their
//!   area, every pixel: the exact diffuse light and integer highlights, and each
//!   approximation within its stated share of the largest highlight;
//! - `frames`: whole frames of `PhongMaterial` compared pixel by pixel with the f64
//!   reference model, on each pixel's own inputs (hard-edged spots and a mirrored view
//!   among them);
//! - `searchlight`: the same for the searchlight example's extension, its surfaces with
//!   their maps and vertex colors (the crate's shader API);
//! - `searchlight_clusters`: searchlights of finite reach in the light clusters, lit
//!   exactly, and a far beam looped over by no fragment;
//! - `searchlight_shadows`: the searchlight's beam, a light kind added from outside the
//!   crate, casting shadows through the map its rays describe, judged by exact rays;
//! - `clusters`: per-view light clusters against the reference model, around the frustum,
//!   with two cameras, in an orthographic view and through 0 → 3,000 → 0 lights; the shader
//!   finds its own view;
//! - `culling`: light clusters and ε culling against the reference model;
//! - `contract`: the WGSL lighting functions themselves, run in a compute kernel on batches of
//!   thousands of cases (millions with `PHONG_CONTRACT_CASES`) against the reference model;
//!   and the area lights' closed forms (`shaders/area_integrals.wesl`) against the reference
//!   model's quadrature over the light's area;
//! - `game_features`: double-sided materials, fog, HDR, bloom, tonemapping, MSAA, blending,
//!   prepasses, SSAO and the deferred renderer, each against its own formula;
//! - `texture_maps`: base color, specular, emissive and normal maps and alpha masks against
//!   the reference model given each pixel's texels;
//! - `surface_inputs`: vertex colors, the UV transform, unlit materials, light, AO and alpha
//!   maps and Bevy's `Lightmap`, the same way;
//! - `shading_normals`: bump maps and flat shading, the same way;
//! - `displacement`: displacement maps, the positions and the lit colors, after a morph and
//!   a skin too;
//! - `per_vertex`: lighting per vertex against the reference model's per-vertex sums,
//!   interpolated at each pixel;
//! - `morphs`: two morphed meshes with their own weights, in the main pass, the prepass and
//!   the shadow maps, against their closed-form pose; a target that turns normals, on each
//!   vertex stage, against its closed-form color;
//! - `stylized`: the diffuse and specular modes (wrap, toon bands and ramps), the rim and the
//!   hemisphere light, the same way;
//! - `cookies`: light cookies on spot, point and directional lights, the same way;
//! - `bevy_light_textures`: Bevy's spot, directional and point light textures (each cube
//!   layout) on mirrored lights, each pixel's texel found with Bevy's own formulas;
//! - `environment`: environment cube maps reflected and refracted, each combine mode;
//! - `environment_light`: the camera's `EnvironmentMapLight` lighting converted and plain
//!   materials, its diffuse and specular cubes against the reference model;
//! - `gltf`: a glTF file loaded with `PhongGltfPlugin`: its primitives' Phong materials,
//!   skin, morph weights, animation players and lights; posed at a fixed animation time,
//!   each primitive covers the pixels `StandardMaterial` covers, and the scene is lit as the
//!   reference model says on the skinned and morphed inputs;
//! - `scene_files`: a scene file loaded, rendered and compared with the reference model;
//! - `self_check`: `render_scene`'s comparison with the reference model
//!   (`Harness::compare_with_reference`), one scene per material feature and kind of light;
//! - `shadows`: every pixel's shadowing against rays cast in `f64` to each light, within a
//!   band around the exact shadow's edge;
//! - `penumbra`: soft shadows (PCSS): the penumbra widens with the light's size and the
//!   blocker's distance, and has the formula's width;
//! - `stress`: adversarial whole frames, read back as floats: no NaN or infinite pixel;
//! - `many_materials`: materials that differ only in their numbers drawn as one class,
//!   changed, added, removed and moved between frames, against the reference model;
//! - `churn`: cubes, materials and lights created, changed and removed every frame from a
//!   seed, every frame against the reference model, the material slots, records and
//!   classes within the live content;
//! - `huge_vectors`: light directions of any scale and colors past the bound, against the
//!   reference model;
//! - `fuzzed_scenes`: a sample of the fuzzer's files (`tests/fuzz`), rendered: no NaN or
//!   infinite pixel;
//! - `three_js`: a scene described as three.js describes it, converted with
//!   `bevy_phong::from_three`, against the reference model and against three.js r187's own
//!   picture of it (rendered in headless Chromium), pixel by pixel;
//! - `switching`: scenes of Bevy's own materials and lights (spheres of every kind, props
//!   with their maps, spheres under an environment map) rendered as Bevy draws them and switched to Phong, side by side: each
//!   object's sRGB difference within its measured bound (docs/switching.md);
//! - `two_apps`: two apps in one process, one with shadows, a cookie and a hemisphere light
//!   and one without, their frames interleaved: each renders as it does alone.
//!
//! The soak test is the other binary on the render device (`tests/soak`): it measures the
//! CPU time of its process, which it must have to itself.

mod adoption;
mod ambient_specular;
mod area_lights;
mod area_shadows;
mod bevy_light_textures;
#[path = "../fuzz/cases.rs"]
mod cases;
mod churn;
mod clusters;
mod contract;
mod cookies;
mod culling;
mod disk_rims;
mod displacement;
mod environment;
mod environment_light;
mod frames;
mod fuzzed_scenes;
mod game_features;
#[cfg(feature = "gltf")]
mod gltf;
mod huge_vectors;
#[path = "../../examples/searchlight/light.rs"]
mod light;
mod many_materials;
mod masked_casters;
mod morphs;
#[path = "../fuzz/mutations.rs"]
mod mutations;
mod penumbra;
mod per_vertex;
mod probes;
#[path = "../fuzz/random.rs"]
mod random;
mod scene_files;
mod searchlight;
mod searchlight_clusters;
mod searchlight_shadows;
mod self_check;
mod shader_api;
mod shading_normals;
mod shadow_band;
mod shadows;
#[path = "../fuzz/shapes.rs"]
mod shapes;
mod stress;
mod stylized;
mod surface_inputs;
mod switching;
mod texture_maps;
#[cfg(feature = "scene")]
mod three_js;
mod two_apps;
