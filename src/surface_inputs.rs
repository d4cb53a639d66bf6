//! [`SurfaceInputsMaterial`]: renders the per-pixel inputs of the lighting equation.

use crate::{PhongMaterial, displacement::DisplacementUniform, material::culled_in_view};
use bevy::{
    app::{App, Plugin},
    asset::{Asset, Handle, embedded_asset},
    image::Image,
    mesh::{MeshVertexBufferLayoutRef, UvChannel},
    pbr::{Material, MaterialPipeline, MaterialPipelineKey, MaterialPlugin, MeshPipelineKey},
    reflect::Reflect,
    render::render_resource::{
        AsBindGroup, Face, RenderPipelineDescriptor, ShaderType, SpecializedMeshPipelineError,
    },
    shader::ShaderRef,
};

/// Path of the material's fragment shader among the crate's embedded assets.
pub(crate) const SURFACE_INPUTS_SHADER: &str = "embedded://bevy_phong/shaders/surface_inputs.wesl";

/// Adds [`SurfaceInputsMaterial`]: for tests and tools that check a render against the
/// reference model. Games don't need it.
#[derive(Clone, Copy, Debug, Default)]
pub struct SurfaceInputsPlugin;

impl Plugin for SurfaceInputsPlugin {
    fn build(&self, app: &mut App) {
        embedded_asset!(app, "shaders/surface_inputs.wesl");
        app.add_plugins(MaterialPlugin::<SurfaceInputsMaterial>::default());
    }
}

/// Which input of the lighting equation a [`SurfaceInputsMaterial`] writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Reflect)]
pub enum SurfaceInput {
    /// The world-space surface point `P` (xyz).
    #[default]
    WorldPosition,
    /// The interpolated world-space mesh normal, before normalization (xyz); negated on the
    /// back faces of a double-sided material, as the lighting negates it.
    WorldNormal,
    /// The mesh's first UV set (xy) and the handedness `w` of its tangent (z); zeros where
    /// the mesh has none.
    UvAndTangentSign,
    /// The interpolated world-space tangent, before normalization (xyz); zero where the
    /// mesh has none.
    WorldTangent,
    /// The interpolated vertex color (all four channels, no tag in alpha); white where the
    /// mesh has none.
    VertexColor,
    /// The mesh's second UV set (xy); zeros where the mesh has none.
    SecondUv,
}

/// A material that writes, instead of a lit color, the world position or normal that
/// [`PhongMaterial`](crate::PhongMaterial) would light at each pixel, with a caller's tag in
/// alpha (so that objects, and the background a camera clears to 0, can be told apart).
///
/// It runs Bevy's mesh vertex shader like `PhongMaterial` does, so the same mesh, camera
/// and render target give bit-identical inputs. Add [`SurfaceInputsPlugin`] to use it. Render a scene once lit and once with this
/// material on every mesh (into an `Rgba32Float` target) to evaluate the reference model
/// ([`crate::reference`]) on exactly the inputs the shader saw.
///
/// Like the material it stands in for, it culls the faces of its `cull_mode`, and none when
/// `double_sided`: there the normal it writes on a back face is negated, as `PhongMaterial`
/// negates it to light a back face; and it moves the vertices by the same displacement map
/// ([`SurfaceInputsMaterial::standing_in_for`] copies all three).
#[derive(Asset, AsBindGroup, Clone, Debug, Reflect)]
#[uniform(0, SurfaceInputUniform)]
#[bind_group_data(SurfaceInputsKey)]
pub struct SurfaceInputsMaterial {
    /// What to write.
    pub input: SurfaceInput,
    /// Written to alpha as a float (except by [`SurfaceInput::VertexColor`]).
    pub tag: u32,
    /// Whether back faces are drawn too (no culling). Default `false`.
    pub double_sided: bool,
    /// The faces culled when not `double_sided`. Default `Some(Face::Back)`.
    #[reflect(ignore, clone)]
    pub cull_mode: Option<Face>,
    /// The displacement map that moves the vertices, as `PhongMaterial::displacement_map`.
    /// Default none.
    #[texture(24, visibility(vertex))]
    #[sampler(25, visibility(vertex))]
    pub displacement_map: Option<Handle<Image>>,
    /// Its scale, bias and UV transform.
    #[uniform(26)]
    pub displacement: DisplacementUniform,
    /// Whether the displacement map is read at the mesh's second UV set (else the first), as
    /// `PhongMaterial::displacement_map_channel`. Default `false`.
    pub displacement_second_uvs: bool,
}

impl Default for SurfaceInputsMaterial {
    fn default() -> Self {
        Self::new(SurfaceInput::default(), 0)
    }
}

impl SurfaceInputsMaterial {
    /// A material writing `input` in RGB and `tag` (as a float) in alpha (except
    /// [`SurfaceInput::VertexColor`], which writes the color's alpha), on front faces.
    pub fn new(input: SurfaceInput, tag: u32) -> Self {
        Self {
            input,
            tag,
            double_sided: false,
            cull_mode: Some(Face::Back),
            displacement_map: None,
            displacement: DisplacementUniform::default(),
            displacement_second_uvs: false,
        }
    }

    /// A material writing `input` and `tag` for the surface `material` draws: the same
    /// faces (`double_sided`, `cull_mode`) and the same displaced vertices.
    pub fn standing_in_for(material: &PhongMaterial, input: SurfaceInput, tag: u32) -> Self {
        Self {
            double_sided: material.double_sided,
            cull_mode: material.cull_mode,
            displacement_map: material.displacement_map.clone(),
            displacement: material.into(),
            displacement_second_uvs: material.displacement_map_channel == UvChannel::Uv1,
            ..Self::new(input, tag)
        }
    }

    /// This material culling `cull_mode`'s faces when not double-sided.
    pub fn with_cull_mode(self, cull_mode: Option<Face>) -> Self {
        Self { cull_mode, ..self }
    }

    /// This material drawing back faces too (`double_sided`), or not.
    pub fn with_double_sided(self, double_sided: bool) -> Self {
        Self {
            double_sided,
            ..self
        }
    }
}

/// The pipeline key of a [`SurfaceInputsMaterial`]: the faces it culls, and whether it
/// displaces its vertices.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SurfaceInputsKey {
    /// The faces culled: none when double-sided.
    pub culled: Option<Face>,
    /// Whether it has a displacement map.
    pub displaced: bool,
    /// Whether the map is read at the second UV set.
    pub displacement_second_uvs: bool,
}

impl From<&SurfaceInputsMaterial> for SurfaceInputsKey {
    fn from(material: &SurfaceInputsMaterial) -> Self {
        Self {
            culled: if material.double_sided {
                None
            } else {
                material.cull_mode
            },
            displaced: material.displacement_map.is_some(),
            displacement_second_uvs: material.displacement_second_uvs,
        }
    }
}

/// The uniform of [`SurfaceInputsMaterial`], made from it when it is bound.
#[derive(Clone, Copy, Debug, Default, PartialEq, Reflect, ShaderType)]
pub struct SurfaceInputUniform {
    /// `0`: world position; `1`: world normal; `2`: UV and tangent sign; `3`: world tangent;
    /// `4`: vertex color; `5`: second UV set.
    pub output: u32,
    /// Written to alpha.
    pub tag: u32,
    /// `1` where back faces are lit with their normal negated (double-sided), else `0`.
    pub double_sided: u32,
}

impl From<&SurfaceInputsMaterial> for SurfaceInputUniform {
    fn from(material: &SurfaceInputsMaterial) -> Self {
        let output = match material.input {
            SurfaceInput::WorldPosition => 0,
            SurfaceInput::WorldNormal => 1,
            SurfaceInput::UvAndTangentSign => 2,
            SurfaceInput::WorldTangent => 3,
            SurfaceInput::VertexColor => 4,
            SurfaceInput::SecondUv => 5,
        };
        Self {
            output,
            tag: material.tag,
            double_sided: u32::from(material.double_sided),
        }
    }
}

impl Material for SurfaceInputsMaterial {
    fn fragment_shader() -> ShaderRef {
        SURFACE_INPUTS_SHADER.into()
    }

    fn specialize(
        _pipeline: &MaterialPipeline,
        descriptor: &mut RenderPipelineDescriptor,
        layout: &MeshVertexBufferLayoutRef,
        key: MaterialPipelineKey<Self>,
    ) -> Result<(), SpecializedMeshPipelineError> {
        // As the material it stands in for: the other face in views that mirror the scene.
        let mirrored = key.mesh_key.contains(MeshPipelineKey::INVERT_CULLING);
        descriptor.primitive.cull_mode = culled_in_view(key.bind_group_data.culled, mirrored);
        if key.bind_group_data.displaced {
            crate::displacement::displace(
                descriptor,
                layout,
                "SurfaceInputsMaterial",
                key.bind_group_data.displacement_second_uvs,
            )?;
        }
        crate::scene_variants::add_scene_data_flag(descriptor);
        Ok(())
    }
}
