//! [`PhongMaterial`]: the surface a Phong or Blinn-Phong mesh is made of.

mod features;
mod from_standard;
mod key;
mod maps;
pub(crate) mod metallic_roughness;
mod ranges;
mod scene_material;
mod vertex_lighting;

pub use features::MaterialFeatures;
pub(crate) use from_standard::{
    Unmapped, converted_standard_material, unmapped_standard_features, warn_unmapped,
};
// What the glTF conversion shares with the StandardMaterial one.
#[cfg(feature = "gltf")]
pub(crate) use from_standard::{ANISOTROPY, CLEARCOAT, TRANSMISSION, VOLUME, bevy_dielectric_f0};
pub use key::PhongMaterialKey;
#[cfg(feature = "testing")]
pub(crate) use key::culled_in_view;
pub(crate) use maps::{MapDevices, map_images, material_maps};
pub(crate) use metallic_roughness::MetallicRoughness;
pub(crate) use ranges::{NumberVisitor, visit_color, visit_numbers};
pub use scene_material::PhongSceneMaterial;

use crate::displacement::DisplacementUniform;
use crate::limits;
use bevy::{
    asset::{Asset, Handle},
    color::{Color, ColorToComponents, LinearRgba},
    image::Image,
    math::{Affine2, Mat3, Vec2, Vec3, Vec4},
    mesh::{MeshVertexBufferLayoutRef, UvChannel},
    pbr::{Material, MaterialPipeline, MaterialPipelineKey, MeshPipelineKey},
    prelude::{AlphaMode, ReflectDefault},
    reflect::Reflect,
    render::render_resource::{
        Face, RenderPipelineDescriptor, ShaderType, SpecializedMeshPipelineError,
    },
    shader::{ShaderDefVal, ShaderRef},
};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};

/// The shader def of [`MaterialFeatures::MATERIAL_RECORDS`], which the vertex stage takes too.
const MATERIAL_RECORDS_DEF: &str = "PHONG_MATERIAL_RECORDS";

/// Path of the material's fragment shader among the crate's embedded assets.
pub(crate) const PHONG_MATERIAL_SHADER: &str = "embedded://bevy_phong/shaders/phong_material.wesl";
/// Path of the material's prepass fragment shader among the crate's embedded assets.
pub(crate) const PHONG_PREPASS_SHADER: &str = "embedded://bevy_phong/shaders/phong_prepass.wesl";

/// How the highlight of a light is shaped (SPEC.md's `H`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Default, Debug, PartialEq, Clone)]
pub enum SpecularModel {
    /// `max(R·V, 0)^α` with `R` the light reflected about the normal.
    #[default]
    Phong,
    /// `max(N·H, 0)^α` with `H = normalize(L + V)`, the half vector. For the same
    /// look as Phong, use about four times the shininess.
    BlinnPhong,
    /// three.js's `MeshPhongMaterial` highlight: `F · (α + 2)/(8π) · max(N·H, 0)^α · N·L`, its
    /// Blinn-Phong lobe normalized and weighed by `N·L`, and `k_s · strength` replaced by
    /// Schlick's Fresnel term `F = f₀ + (1 − f₀) · w(V·H)` with `f₀ = k_s · strength` and
    /// three.js's weight `w(c) = 2^((−5.55473·c − 6.98316)·c)`: brighter toward grazing
    /// angles, and present (as `w`) even on a black specular color. A zero
    /// `specular_strength` still turns the highlight off. SPEC.md, "Normalized Blinn-Phong".
    NormalizedBlinnPhong,
}

impl SpecularModel {
    /// The value the shader's `SPECULAR_MODEL_*` constants give this model.
    pub(crate) fn shader_flag(self) -> u32 {
        match self {
            SpecularModel::Phong => 0,
            SpecularModel::BlinnPhong => 1,
            SpecularModel::NormalizedBlinnPhong => 2,
        }
    }
}

/// How the diffuse term of each light is shaped from `N·L` (SPEC.md, "Stylized shading").
#[derive(Clone, Copy, Debug, Default, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Default, Debug, PartialEq, Clone)]
pub enum DiffuseMode {
    /// `max(N·L, 0)` (Lambert's).
    #[default]
    Lambert,
    /// `max((N·L + w) / (1 + w), 0)` with the wrap `w` in `[0, 1]`: the light reaches past the
    /// terminator, down to `N·L = −w` (soft, skin-like falloff; Godot's Lambert Wrap).
    Wrap(f32),
    /// `N·L` in `bands` flat steps (cel shading): `(⌊x·n⌋ + e(fract(x·n))) / n` with
    /// `x = max(N·L, 0)`, where `e` rises from 0 to 1 over the last `smoothing` (in `[0, 1]`)
    /// of each step (0: hard steps). `bands` in `[1, 256]`.
    Toon {
        /// The number of steps from dark to fully lit.
        bands: u32,
        /// The share of each step over which it rises to the next, `[0, 1]`.
        smoothing: f32,
    },
}

/// How the highlight of each light is drawn (SPEC.md, "Stylized shading").
#[derive(Clone, Copy, Debug, Default, PartialEq, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Default, Debug, PartialEq, Clone)]
pub enum SpecularMode {
    /// `H` as the specular model gives it.
    #[default]
    Smooth,
    /// A flat spot where `H > 1/2` (cel shading): `H` through a step at 1/2 that rises over
    /// `smoothing` (in `[0, 1]`; 0: a hard edge).
    Toon {
        /// The width of the spot's edge, in units of `H`, `[0, 1]`.
        smoothing: f32,
    },
    /// No highlight (the variant without the specular term, as a zero specular strength).
    Off,
}

/// How the environment map's color joins the lit color (three.js's `combine`), weighted by
/// `k = reflectivity` times the specular map's red channel (1 without one).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Reflect)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[reflect(Default, Debug, PartialEq, Clone)]
pub enum EnvironmentCombine {
    /// `mix(lit, lit ⊙ environment, k)`: the environment tints the surface.
    #[default]
    Multiply,
    /// `mix(lit, environment, k)`: a mirror at `k = 1`.
    Mix,
    /// `lit + environment · k`: a glossy coat.
    Add,
}

/// A surface lit by the Phong reflection model with this crate's light entities.
///
/// Per SPEC.md, a surface point receives
///
/// ```text
/// emissive + ambient ⊙ k_a ⊙ k_d
///   + Σ_lights A · S · [color ⊙ k_d · max(N·L, 0) + specular ⊙ k_s · strength · H]
/// ```
///
/// with `k_d = base_color`, `k_a = ambient_factor`, `k_s = specular_color`,
/// `strength = specular_strength`, and `H` the highlight of [`specular_model`] with exponent
/// [`shininess`]. All colors are taken in linear RGB.
///
/// # Vertex colors
///
/// On a mesh with colors (`Mesh::ATTRIBUTE_COLOR`, glTF's `COLOR_0`), `k_d` is multiplied
/// by the interpolated vertex color, alpha too, as Bevy's `StandardMaterial` does: the
/// mesh's vertex layout selects the shader variant (Bevy's `VERTEX_COLORS`), a mesh without
/// colors pays nothing.
///
/// # Texture maps
///
/// Each map is optional and multiplies its color, sampled at its UV set (below): `k_d ⊙
/// base_color_texture` (alpha too), `k_s ⊙ specular_texture`, `emissive ⊙
/// emissive_texture`, output alpha `⊙ alpha_map_texture.g`. The [`normal_map_texture`] replaces the
/// interpolated normal by one in tangent space (it needs `Mesh::ATTRIBUTE_TANGENT`:
/// `Mesh::with_generated_tangents`). Values are what the sampler returns: images Bevy loads
/// as sRGB are decoded to linear first, so load specular and normal maps with
/// `is_srgb: false` (`ImageLoaderSettings`). A material's shader variant samples only the
/// maps it has; on a mesh without the map's UV set (or, for the normal and bump maps,
/// without tangents) a map is left out, with a warning.
///
/// # UV sets
///
/// Each map sampled at UVs has a channel field (`base_color_channel`, …,
/// `light_map_channel`): [`UvChannel::Uv0`] reads the mesh's first UV set
/// (`Mesh::ATTRIBUTE_UV_0`, glTF's `TEXCOORD_0`) moved by
/// [`uv_transform`](Self::uv_transform); [`UvChannel::Uv1`] reads the second
/// (`Mesh::ATTRIBUTE_UV_1`, `TEXCOORD_1`) as it is, where baked light and AO maps are laid
/// out and a tiling transform of the first set should not move them. They are Bevy's
/// `StandardMaterial::base_color_channel` and its kin, glTF's `texCoord` and three.js's
/// `Texture.channel` (0 or 1). Bevy moves the second set by its `uv_transform` too, and
/// three.js gives each map its own transform: SPEC.md, "Texture maps", says how to port
/// them. The normal and bump maps keep the mesh's tangent frame on either set, as Bevy and
/// three.js do.
///
/// [`specular_model`]: Self::specular_model
/// [`shininess`]: Self::shininess
/// [`normal_map_texture`]: Self::normal_map_texture
/// # Lights and shadows
///
/// The material holds only surface data. The lights, their clusters and the shadow maps
/// are the plugin's: its bind group gets them from the render world when it is built (see
/// `crate::render`).
#[derive(Asset, Clone, Debug, Reflect)]
#[reflect(Default, Debug, Clone)]
pub struct PhongMaterial {
    /// Diffuse reflectance `k_d`; its alpha is the output alpha (see
    /// [`alpha_mode`](Self::alpha_mode)). Default white.
    pub base_color: Color,
    /// Scalar `k_a` on the ambient term, `≥ 0`. Default `1`.
    pub ambient_factor: f32,
    /// Specular reflectance `k_s`. Default white.
    pub specular_color: Color,
    /// Scalar multiplier on `k_s`, `≥ 0` (`0` turns the highlight off). Default `1`.
    pub specular_strength: f32,
    /// Highlight exponent `α`, `≥ 0`: higher is a smaller, sharper highlight. Default `32`.
    pub shininess: f32,
    /// Reflection-vector (Phong) or half-vector (Blinn-Phong) highlight. Default Phong.
    pub specular_model: SpecularModel,
    /// How each light's diffuse term is shaped from `N·L`: Lambert's, wrapped, or in toon
    /// bands. Default [`DiffuseMode::Lambert`].
    pub diffuse_mode: DiffuseMode,
    /// A toon ramp (three.js's `gradientMap`): with [`DiffuseMode::Toon`], each light's
    /// diffuse factor is this image's red channel, read nearest (no filtering) along its
    /// middle row at `u = (1 + N·L) / 2` and clamped to `[0, 1]`, in place of the bands (SPEC.md,
    /// "Stylized shading"). A ramp whose left half is not black lights the surface past the
    /// terminator. Load it as linear data (`is_srgb: false`) to read its bytes as they are.
    /// Ignored with another diffuse mode; left out under WebGL2
    /// (`crate::render::binds_every_map`), where the bands are drawn. Default none.
    #[dependency]
    pub toon_ramp_texture: Option<Handle<Image>>,
    /// How each light's highlight is drawn: as computed, as a toon spot, or not at all.
    /// Default [`SpecularMode::Smooth`].
    pub specular_mode: SpecularMode,
    /// The rim light's color (Godot's rim, a Fresnel-like glow at grazing angles):
    /// `rim_color · rim_strength · (1 − max(N·V, 0))^rim_power` is added to the surface, or,
    /// with [`rim_lit_side`](Self::rim_lit_side), to each light's term weighted by its
    /// `max(N·L, 0)` (SPEC.md, "Stylized shading"). Linear RGB. Default black: no rim (no
    /// shader work).
    pub rim_color: LinearRgba,
    /// Multiplies the rim color, `≥ 0`. Default `1`.
    pub rim_strength: f32,
    /// How tightly the rim hugs the silhouette: the exponent on `1 − N·V`, `≥ 0`. Default `2`.
    pub rim_power: f32,
    /// Lights the rim only where lights reach the surface, by each light's color, attenuation,
    /// shadow and `max(N·L, 0)`. Default `false`: the rim glows everywhere.
    pub rim_lit_side: bool,
    /// Color added without lighting, linear RGB. Default black.
    pub emissive: LinearRgba,
    /// How the output alpha (`base_color.a`, times the base color map's alpha) is used.
    /// `Opaque`, `Mask(cutoff)` (fragments below the cutoff are discarded) and `Blend` are
    /// the ones a lit surface needs; with the others the color is written as computed.
    /// Default [`AlphaMode::Opaque`].
    pub alpha_mode: AlphaMode,
    /// Multiplies `base_color` (all four channels). Default none.
    #[dependency]
    pub base_color_texture: Option<Handle<Image>>,
    /// The UV set [`base_color_texture`](Self::base_color_texture) is read at (see "UV sets" above). Default `Uv0`.
    pub base_color_channel: UvChannel,
    /// Multiplies `specular_color`. Default none.
    #[dependency]
    pub specular_texture: Option<Handle<Image>>,
    /// The UV set [`specular_texture`](Self::specular_texture) is read at (see "UV sets" above). Default `Uv0`.
    pub specular_channel: UvChannel,
    /// Multiplies `emissive`. Default none.
    #[dependency]
    pub emissive_texture: Option<Handle<Image>>,
    /// The UV set [`emissive_texture`](Self::emissive_texture) is read at (see "UV sets" above). Default `Uv0`.
    pub emissive_channel: UvChannel,
    /// Multiplies the output alpha by its green channel (three.js's `alphaMap`): a
    /// grayscale cut-out or fade without touching the base color map. Load it as linear
    /// data (`is_srgb: false`). Left out under WebGL2 (`crate::render::binds_every_map`).
    /// Default none.
    #[dependency]
    pub alpha_map_texture: Option<Handle<Image>>,
    /// The UV set [`alpha_map_texture`](Self::alpha_map_texture) is read at (see "UV sets" above). Default `Uv0`.
    pub alpha_map_channel: UvChannel,
    /// glTF's `metallicRoughnessTexture` (Bevy's `StandardMaterial::metallic_roughness_texture`):
    /// each texel gives the surface its metallic `m = metallic · B` and perceptual roughness
    /// `r = perceptual_roughness · G` (blue and green, linear data), and the surface is the
    /// metallic/roughness one of those numbers, drawn with the material's specular model
    /// (SPEC.md, "Metallic-roughness map"):
    ///
    /// - `k_d ← k_d · (1 − m)`, with `k_d` the base color as its map and the vertex colors
    ///   give it;
    /// - `k_s ← k · (1 + k · (1/E − 1))` with `k = mix(k_s, k_d, m)`, `k_s` the dielectric
    ///   reflectance at normal incidence (`specular_color` and its map; glTF's 0.04) and
    ///   `E` the single-scattering albedo of a GGX lobe of roughness `r` (Bevy's compensation
    ///   for multiple scattering);
    /// - `α ←` the exponent fitted to Bevy's GGX lobe of roughness `r`, in `[1, 10⁴]`
    ///   (SPEC.md, "Metallic-roughness map": `0.669/r⁴ + 1.42/r² − 1.59`).
    ///
    /// So `shininess` is not read where the map is drawn (a material lit per vertex takes it
    /// at its vertices), and `specular_strength` stays a factor on the highlight (π for a
    /// converted material, drawn with `SpecularModel::NormalizedBlinnPhong`). Load the map as linear data (`is_srgb: false`). A mesh without
    /// the map's UV set draws the material's plain fields, with a warning. Default none.
    #[dependency]
    pub metallic_roughness_texture: Option<Handle<Image>>,
    /// The UV set [`metallic_roughness_texture`](Self::metallic_roughness_texture) is read at
    /// (see "UV sets" above). Default `Uv0`.
    pub metallic_roughness_channel: UvChannel,
    /// Multiplies the metallic-roughness map's blue channel, `[0, 1]` (NaN → 0). Read only
    /// with [`metallic_roughness_texture`](Self::metallic_roughness_texture). Default `1`
    /// (the texel as it is, glTF's default factor).
    pub metallic: f32,
    /// The surface's perceptual roughness, `[0, 1]` (NaN → 0.5): it multiplies the
    /// metallic-roughness map's green channel, and it shapes the
    /// [`ambient_specular`](Self::ambient_specular) weights. Read only with either. Default
    /// `1` (the texel as it is, glTF's default factor).
    pub perceptual_roughness: f32,
    /// Also reflects the ambient and hemisphere light by the specular color, as
    /// `StandardMaterial` reflects its ambient light: the indirect term gains
    /// `(ambient + hemisphere(N)) ⊙ (k_s · A + B)` times the ambient occlusion, with `(A, B)`
    /// Bevy's fit of the split-sum integral of its GGX lobe (bevy_pbr's `F_AB`) at
    /// [`perceptual_roughness`](Self::perceptual_roughness) (times the metallic-roughness
    /// map's green) and `N·V` (SPEC.md, "Ambient specular"). `k_s` is the specular color with
    /// its maps, without `specular_strength` (a strength of 0 turns the term off too), so a
    /// metal's body is lit by its ambient light as a `StandardMaterial` metal's is. The
    /// conversions from `StandardMaterial` and glTF set it. Default `false`.
    pub ambient_specular: bool,
    /// Lights the surface with the camera's Bevy `EnvironmentMapLight` as it lights a
    /// `StandardMaterial`: its diffuse cube, read along the normal, lights
    /// `k_d ⊙ (1 − S)`, and its specular cube, read along the lobe's dominant direction at
    /// mip level `r · (levels − 1)` (`r` the
    /// [`perceptual_roughness`](Self::perceptual_roughness), times the metallic-roughness
    /// map's green), is reflected by `S`, the [`ambient_specular`](Self::ambient_specular)
    /// reflectance (zero without it: then the cube lights the diffuse color only); both
    /// times the light's `intensity` and rotated by its `rotation`, times the camera's
    /// exposure, and added to the ambient term before the ambient occlusion (SPEC.md,
    /// "Environment light"). A camera without one adds nothing. Independent of
    /// [`camera_environment`](Self::camera_environment), three.js's reflection, which
    /// joins a cube to the lit color by a combine mode. The conversions from
    /// `StandardMaterial` and glTF set it. Default `false`.
    pub environment_light: bool,
    /// A tangent-space normal map: texel `t` gives `n = 2t − 1`, and the normal is
    /// `n.x·T + n.y·B + n.z·N` with the interpolated normal `N`, tangent `T` and
    /// `B = T.w · N × T` (MikkTSpace's convention, as Bevy's own materials). Default none.
    #[dependency]
    pub normal_map_texture: Option<Handle<Image>>,
    /// The UV set [`normal_map_texture`](Self::normal_map_texture) is read at (see "UV sets" above). Default `Uv0`.
    pub normal_map_channel: UvChannel,
    /// Negates the normal map's green channel, for maps made with the other convention
    /// (Direct3D's, green pointing down). Default `false`.
    pub flip_normal_map_y: bool,
    /// Scales the normal map's `n.x` and `n.y` before the normal is built (three.js's
    /// `normalScale`, glTF's `normalTexture.scale` on both): `(0, 0)` leaves the interpolated
    /// normal, larger values deepen the relief. Each in `[−10⁶, 10⁶]` (NaN → 1). Default
    /// `(1, 1)`.
    pub normal_map_scale: Vec2,
    /// A height map (three.js's `bumpMap`): its red channel `h` is a height whose slope
    /// tilts the normal, after the normal map, by `−bump_scale · (Δu·T + Δv·B)`, where `Δu`
    /// and `Δv` are the changes of `h` one texel along `u` and `v` (of its largest mip) and
    /// `T`, `B` the normal map's tangent frame (SPEC.md, "Bump map"). It needs UVs and
    /// tangents, as the normal map. Load it as linear data (`is_srgb: false`). Left out under
    /// WebGL2 (`crate::render::binds_every_map`). Default none.
    #[dependency]
    pub bump_map_texture: Option<Handle<Image>>,
    /// The UV set [`bump_map_texture`](Self::bump_map_texture) is read at (see "UV sets" above). Default `Uv0`.
    pub bump_map_channel: UvChannel,
    /// How far a height step of 1 between neighbouring texels tilts the normal: at 1 such
    /// a step tilts it by 45°. Negative values make the bumps dents. Default `1`.
    pub bump_scale: f32,
    /// A height map that moves the mesh's vertices (three.js's `displacementMap`): each
    /// vertex moves along its normal, in the mesh's local space, by
    /// `red · displacement_scale + displacement_bias`, the map read at the vertex's UV set
    /// ([`displacement_map_channel`](Self::displacement_map_channel)) at its largest mip, after the morph targets and
    /// before skinning (SPEC.md, "Displacement"). Every pass moves it alike: the main pass,
    /// the prepasses, Bevy's shadow maps and the crate's. The normals are not recomputed
    /// (pair it with a normal map of the same heights); the mesh's bounds are not grown, so
    /// a displacement beyond them can be culled early (add `NoFrustumCulling`, or a larger
    /// `Aabb`). It needs its UV set and normals. Load it as linear data (`is_srgb: false`). Default
    /// none.
    #[dependency]
    pub displacement_map: Option<Handle<Image>>,
    /// The UV set [`displacement_map`](Self::displacement_map) is read at (see "UV sets"
    /// above). Default `Uv0`.
    pub displacement_map_channel: UvChannel,
    /// How far a texel of 1 moves a vertex, in the mesh's local units. Default `1`.
    pub displacement_scale: f32,
    /// Added to every vertex's distance, local units. Default `0`.
    pub displacement_bias: f32,
    /// Lights each triangle with its own plane's normal (three.js's `flatShading`): the
    /// geometric normal of the face, turned to the side of the interpolated normal, in place
    /// of the interpolated one, in the main pass and the normal prepass. The normal and bump
    /// maps then tilt the face normal. Default `false`.
    pub flat_shading: bool,
    /// Lights the surface at its vertices (Gouraud shading; SPEC.md, "Per-vertex lighting"):
    /// the vertex stage sums every light at each vertex, with its cookie and shadow, at the
    /// vertex's position and normal, and each fragment weighs the sums interpolated across
    /// its triangle with the material as its maps give it there. Ambient, hemisphere and
    /// emissive light, the rim everywhere and the environment map stay per fragment. A
    /// speed option: a light then costs once per vertex, not once per pixel, at the cost of
    /// highlights, shadow and cookie edges and light pools smaller than the mesh's triangles
    /// (docs/performance.md measures the error on the benchmark's scenes). Normal and bump
    /// maps, flat shading and double-sided back faces tilt only the per-fragment terms; the
    /// lights see the mesh's vertex normal. Default `false`.
    pub vertex_lighting: bool,
    /// Draws the back faces too, lit with the normal turned toward the viewer (negated on
    /// back faces, before the normal map), as glTF's `doubleSided` and Bevy's
    /// `StandardMaterial::double_sided`. Default `false`: back faces are culled.
    pub double_sided: bool,
    /// Moves the mesh's first UV set before the maps on it are sampled: such a map is read
    /// at `uv_transform · uv` (glTF's `KHR_texture_transform`, Bevy's
    /// `StandardMaterial::uv_transform`). The normal map's tangent frame stays the mesh's,
    /// as in Bevy and three.js. A transform that is not finite is replaced by the identity,
    /// with a warning. Default [`Affine2::IDENTITY`] (no shader work).
    pub uv_transform: Affine2,
    /// Draws the surface without light: its color is `k_d` alone (with its map and the vertex
    /// colors), alpha as a lit surface's; no light, ambient or shadow changes it, and the
    /// emissive color and map are not drawn, as with glTF's `KHR_materials_unlit` and Bevy's
    /// `StandardMaterial::unlit`. The camera's fog and tonemapping still apply. Default
    /// `false`.
    pub unlit: bool,
    /// Whether the camera's `DistanceFog` applies to this surface, as
    /// `StandardMaterial::fog_enabled` (turn it off for a sky or a far backdrop that
    /// carries its own haze). Default `true`.
    pub fog_enabled: bool,
    /// Which faces are not drawn: `Some(Face::Back)`, `Some(Face::Front)` (the inside of
    /// a closed mesh shows), or `None` (both; a back face is lit with the mesh's normal,
    /// which faces away from the viewer: [`double_sided`](Self::double_sided) lights it
    /// from the side seen). With `double_sided`, no face is culled whatever this says.
    /// Views that mirror the scene (Bevy's `INVERT_CULLING`) swap the faces, as for
    /// `StandardMaterial::cull_mode`. Default `Some(Face::Back)`.
    #[reflect(ignore, clone)]
    pub cull_mode: Option<Face>,
    /// Moves the surface's depth toward the camera (positive) or away (negative) by this
    /// many of the depth buffer's smallest steps (wgpu's constant depth bias, truncated to
    /// an integer), so that coplanar surfaces such as decals draw in a chosen order; also
    /// Bevy's sorting bias. As `StandardMaterial::depth_bias`. NaN becomes 0 and values
    /// beyond ±2.1·10⁹ are clamped (`limits::DEPTH_BIAS`), with a warning. Default `0`.
    pub depth_bias: f32,
    /// Light baked into a texture (three.js's `lightMap`): its RGB times
    /// [`light_map_intensity`](Self::light_map_intensity) is added to the ambient light the
    /// surface receives, before `k_d` (SPEC.md, "Baked light"). Load it as the color data it
    /// is (sRGB for an 8-bit image). Bevy's `Lightmap` component on the mesh adds its light
    /// the same way, times the same intensity. Default none.
    #[dependency]
    pub light_map_texture: Option<Handle<Image>>,
    /// Multiplies the light map and Bevy's `Lightmap`, `≥ 0`. Default `1`.
    pub light_map_intensity: f32,
    /// The UV set the light map is read at (see "UV sets" above). Default `Uv1`, where baked
    /// light maps are laid out.
    pub light_map_channel: UvChannel,
    /// Ambient occlusion baked into a texture (three.js's `aoMap`, glTF's occlusion
    /// texture): its red channel `r` scales the ambient light and the light map's light by
    /// `1 + ao_map_intensity · (r − 1)`. Load it as linear data (`is_srgb: false`). Default
    /// none.
    #[dependency]
    pub ao_map_texture: Option<Handle<Image>>,
    /// How much the AO map occludes: 0 not at all, 1 fully, `≥ 0`. Default `1`.
    pub ao_map_intensity: f32,
    /// The UV set the AO map is read at (see "UV sets" above). Default `Uv0`, glTF's.
    pub ao_map_channel: UvChannel,
    /// A cube map of what the surface reflects (three.js's `envMap`): an image of six
    /// square layers viewed as a cube (`TextureViewDimension::Cube`), in linear color.
    /// The ray from the camera, reflected about the lit normal (or refracted, with
    /// [`refraction_ratio`](Self::refraction_ratio)), reads it at a mip level as wide as
    /// the highlight's lobe (SPEC.md, "Environment map"), in Bevy's cube frame (`z` negated:
    /// the cube shows the same sky as Bevy's `Skybox` of it), and
    /// [`environment_combine`](Self::environment_combine) joins it to the lit color. Not
    /// drawn on unlit materials, nor under WebGL2 (`crate::render::binds_every_map`).
    /// Default none.
    #[dependency]
    pub environment_map: Option<Handle<Image>>,
    /// Reflects the specular map of the camera's Bevy `EnvironmentMapLight` where the
    /// material has no [`environment_map`](Self::environment_map): the same lookup, with the
    /// direction turned by the light's `rotation` and the texel times its `intensity` and the
    /// camera's exposure (Bevy's `Exposure`: `2^−EV100 / 1.2`), as `StandardMaterial` weighs
    /// it. A camera without one leaves the lit color as it is. Works under WebGL2 too (the
    /// cube is Bevy's view binding). Default `false`.
    pub camera_environment: bool,
    /// How the environment joins the lit color. Default [`EnvironmentCombine::Multiply`].
    pub environment_combine: EnvironmentCombine,
    /// The environment's weight `k`, `[0, 1]` (times the specular map's red). Default `1`.
    pub reflectivity: f32,
    /// `None` reflects the view ray; `Some(η)` refracts it with the ratio of refractive
    /// indices `η` (three.js's `refractionRatio`, 0.98 there; glass in air ≈ 0.66), `≥ 0`.
    /// Default `None`.
    pub refraction_ratio: Option<f32>,
}

impl Default for PhongMaterial {
    fn default() -> Self {
        Self {
            base_color: Color::WHITE,
            ambient_factor: 1.0,
            specular_color: Color::WHITE,
            specular_strength: 1.0,
            shininess: 32.0,
            specular_model: SpecularModel::Phong,
            diffuse_mode: DiffuseMode::Lambert,
            toon_ramp_texture: None,
            specular_mode: SpecularMode::Smooth,
            rim_color: LinearRgba::BLACK,
            rim_strength: 1.0,
            rim_power: 2.0,
            rim_lit_side: false,
            emissive: LinearRgba::BLACK,
            alpha_mode: AlphaMode::Opaque,
            base_color_texture: None,
            base_color_channel: UvChannel::Uv0,
            specular_texture: None,
            specular_channel: UvChannel::Uv0,
            emissive_texture: None,
            emissive_channel: UvChannel::Uv0,
            alpha_map_texture: None,
            alpha_map_channel: UvChannel::Uv0,
            metallic_roughness_texture: None,
            metallic_roughness_channel: UvChannel::Uv0,
            metallic: 1.0,
            perceptual_roughness: 1.0,
            ambient_specular: false,
            environment_light: false,
            normal_map_texture: None,
            normal_map_channel: UvChannel::Uv0,
            flip_normal_map_y: false,
            normal_map_scale: Vec2::ONE,
            bump_map_texture: None,
            bump_map_channel: UvChannel::Uv0,
            bump_scale: 1.0,
            displacement_map: None,
            displacement_map_channel: UvChannel::Uv0,
            displacement_scale: 1.0,
            displacement_bias: 0.0,
            flat_shading: false,
            vertex_lighting: false,
            double_sided: false,
            uv_transform: Affine2::IDENTITY,
            unlit: false,
            fog_enabled: true,
            cull_mode: Some(Face::Back),
            depth_bias: 0.0,
            light_map_texture: None,
            light_map_intensity: 1.0,
            light_map_channel: UvChannel::Uv1,
            ao_map_texture: None,
            ao_map_intensity: 1.0,
            ao_map_channel: UvChannel::Uv0,
            environment_map: None,
            camera_environment: false,
            environment_combine: EnvironmentCombine::Multiply,
            reflectivity: 1.0,
            refraction_ratio: None,
        }
    }
}

impl From<Color> for PhongMaterial {
    fn from(base_color: Color) -> Self {
        Self {
            base_color,
            ..Self::default()
        }
    }
}

/// [`PhongMaterial`] as the shader reads it (`PhongMaterialUniform` in
/// `bevy_phong::shaders::types`).
#[derive(Clone, Copy, Debug, Default, PartialEq, ShaderType)]
pub struct PhongMaterialUniform {
    /// `k_d`, linear RGB, with the output alpha.
    pub base_color: Vec4,
    /// `k_s · specular_strength`, linear RGB.
    pub specular: Vec3,
    /// `α`.
    pub shininess: f32,
    /// Emissive color, linear RGB.
    pub emissive: Vec3,
    /// `k_a`.
    pub ambient_factor: f32,
    /// The specular model in bits 0..1; [`FLIP_NORMAL_MAP_Y`](Self::FLIP_NORMAL_MAP_Y),
    /// [`DOUBLE_SIDED`](Self::DOUBLE_SIDED).
    pub flags: u32,
    /// Fragments whose alpha is below this are discarded (with `AlphaMode::Mask`).
    pub alpha_cutoff: f32,
    /// [`PhongMaterial::uv_transform`] as a matrix of homogeneous UVs.
    pub uv_transform: Mat3,
    /// [`PhongMaterial::light_map_intensity`].
    pub light_map_intensity: f32,
    /// [`PhongMaterial::ao_map_intensity`].
    pub ao_map_intensity: f32,
    /// [`PhongMaterial::reflectivity`].
    pub reflectivity: f32,
    /// [`PhongMaterial::refraction_ratio`] (0 when it reflects).
    pub refraction_ratio: f32,
    /// [`PhongMaterial::bump_scale`].
    pub bump_scale: f32,
    /// [`PhongMaterial::metallic`], in `[0, 1]`.
    pub metallic: f32,
    /// [`PhongMaterial::perceptual_roughness`], in `[0, 1]`.
    pub perceptual_roughness: f32,
    /// [`PhongMaterial::specular_strength`] alone (the metallic-roughness map's metal
    /// reflects `k_d · strength`).
    pub specular_strength: f32,
    /// The stylized modes' numbers: the diffuse wrap, the toon bands (as a float) and their
    /// smoothing, the toon highlight's smoothing (`PhongMaterial::style_of`).
    pub style: Vec4,
    /// The rim: `rim_color · rim_strength` (linear RGB) and `rim_power`.
    pub rim: Vec4,
    /// [`PhongMaterial::normal_map_scale`].
    pub normal_map_scale: Vec2,
}

impl PhongMaterialUniform {
    /// Flag bit: negate the normal map's green channel.
    pub const FLIP_NORMAL_MAP_Y: u32 = 4;
    /// Flag bit: negate the normal on back faces.
    pub const DOUBLE_SIDED: u32 = 8;
}

// Bevy's `AsBindGroupShaderType` comes with this conversion. Every value is brought into its
// range ([`crate::limits`], the rule `validate_materials` applies) here too, so no frame
// draws with an invalid value before `validate_materials` has replaced it.
impl From<&PhongMaterial> for PhongMaterialUniform {
    fn from(material: &PhongMaterial) -> Self {
        let material = material.in_range();
        let specular = material.specular_color.to_linear().to_vec3() * material.specular_strength;
        Self {
            base_color: material.base_color.to_linear().to_vec4(),
            specular,
            shininess: material.shininess,
            emissive: material.emissive.to_vec3(),
            ambient_factor: material.ambient_factor,
            flags: material.specular_model.shader_flag()
                | if material.flip_normal_map_y {
                    Self::FLIP_NORMAL_MAP_Y
                } else {
                    0
                }
                | if material.double_sided {
                    Self::DOUBLE_SIDED
                } else {
                    0
                },
            alpha_cutoff: match material.alpha_mode {
                AlphaMode::Mask(cutoff) => cutoff,
                _ => 0.0,
            },
            uv_transform: Mat3::from(material.uv_transform),
            light_map_intensity: material.light_map_intensity,
            ao_map_intensity: material.ao_map_intensity,
            reflectivity: material.reflectivity,
            refraction_ratio: material.refraction_ratio.unwrap_or(0.0),
            bump_scale: material.bump_scale,
            style: Self::style_of(material.diffuse_mode, material.specular_mode),
            rim: (material.rim_color.to_vec3() * material.rim_strength).extend(material.rim_power),
            normal_map_scale: material.normal_map_scale,
            metallic: material.metallic,
            perceptual_roughness: material.perceptual_roughness,
            specular_strength: material.specular_strength,
        }
    }
}

impl PhongMaterialUniform {
    /// `(wrap, bands, band smoothing, highlight smoothing)` of the modes (their numbers in
    /// range: see [`PhongMaterial::in_range`]); `(0, 1, 0, 0)` for the modes without numbers.
    fn style_of(diffuse: DiffuseMode, specular: SpecularMode) -> Vec4 {
        let mut style = Vec4::new(0.0, 1.0, 0.0, 0.0);
        match diffuse {
            DiffuseMode::Lambert => {}
            DiffuseMode::Wrap(wrap) => style.x = wrap,
            DiffuseMode::Toon { bands, smoothing } => {
                style.y = bands as f32;
                style.z = smoothing;
            }
        }
        if let SpecularMode::Toon { smoothing } = specular {
            style.w = smoothing;
        }
        style
    }
}

/// The material's displacement as the vertex stage reads it, each value in its range
/// (`PhongMaterial::in_range`).
impl From<&PhongMaterial> for DisplacementUniform {
    fn from(material: &PhongMaterial) -> Self {
        let material = material.in_range();
        Self {
            uv_transform: match material.displacement_map_channel {
                UvChannel::Uv0 => Mat3::from(material.uv_transform),
                UvChannel::Uv1 => Mat3::IDENTITY,
            },
            scale: material.displacement_scale,
            bias: material.displacement_bias,
        }
    }
}

impl Material for PhongMaterial {
    fn fragment_shader() -> ShaderRef {
        PHONG_MATERIAL_SHADER.into()
    }

    /// Discards what the main pass discards and writes the normal it lights with (see
    /// `phong_prepass.wesl`).
    fn prepass_fragment_shader() -> ShaderRef {
        PHONG_PREPASS_SHADER.into()
    }

    fn specialize(
        _pipeline: &MaterialPipeline,
        descriptor: &mut RenderPipelineDescriptor,
        layout: &MeshVertexBufferLayoutRef,
        key: MaterialPipelineKey<Self>,
    ) -> Result<(), SpecializedMeshPipelineError> {
        let mirrored = key.mesh_key.contains(MeshPipelineKey::INVERT_CULLING);
        descriptor.primitive.cull_mode = key.bind_group_data.culled_face(mirrored);
        if let Some(depth_stencil) = descriptor.depth_stencil.as_mut() {
            depth_stencil.bias.constant = key.bind_group_data.depth_bias;
        }
        if key.bind_group_data.has(MaterialFeatures::DISPLACEMENT) {
            let second_uvs = key.bind_group_data.has(MaterialFeatures::DISPLACEMENT_UV_B);
            crate::displacement::displace(descriptor, layout, "PhongMaterial", second_uvs)?;
        }
        crate::scene_variants::add_scene_data_flag(descriptor);
        let defs = key.bind_group_data.shader_defs(layout);
        if key.bind_group_data.has(MaterialFeatures::VERTEX_LIGHTING) {
            vertex_lighting::light_at_vertices(descriptor, &defs);
        }
        if let Some(fragment) = descriptor.fragment.as_mut() {
            fragment
                .shader_defs
                .extend(defs.into_iter().map(Into::into));
        }
        // The crate's vertex stages (displaced, lit per vertex) read the material too.
        let records: ShaderDefVal = MATERIAL_RECORDS_DEF.into();
        if key.bind_group_data.has(MaterialFeatures::MATERIAL_RECORDS)
            && !descriptor.vertex.shader_defs.contains(&records)
        {
            descriptor.vertex.shader_defs.push(records);
        }
        Ok(())
    }

    fn alpha_mode(&self) -> AlphaMode {
        self.alpha_mode
    }

    fn depth_bias(&self) -> f32 {
        limits::DEPTH_BIAS.apply(self.depth_bias)
    }
}
