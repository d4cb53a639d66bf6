//! [`SurfaceInputsMaterial`]: renders the per-pixel inputs of the lighting equation.

use bevy::{
    app::{App, Plugin},
    asset::{Asset, embedded_asset},
    pbr::{Material, MaterialPlugin},
    reflect::Reflect,
    render::render_resource::{AsBindGroup, ShaderType},
    shader::ShaderRef,
};

/// Path of the material's fragment shader among the crate's embedded assets.
pub(crate) const SURFACE_INPUTS_SHADER: &str = "embedded://bevy_phong/shaders/surface_inputs.wgsl";

/// Adds [`SurfaceInputsMaterial`]: for tests and tools that check a render against the
/// reference model. Games don't need it.
#[derive(Clone, Copy, Debug, Default)]
pub struct SurfaceInputsPlugin;

impl Plugin for SurfaceInputsPlugin {
    fn build(&self, app: &mut App) {
        embedded_asset!(app, "shaders/surface_inputs.wgsl");
        app.add_plugins(MaterialPlugin::<SurfaceInputsMaterial>::default());
    }
}

/// Which input of the lighting equation a [`SurfaceInputsMaterial`] writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Reflect)]
pub enum SurfaceInput {
    /// The world-space surface point `P` (xyz).
    #[default]
    WorldPosition,
    /// The interpolated world-space mesh normal, before normalization (xyz).
    WorldNormal,
    /// The mesh's first UV set (xy) and the handedness `w` of its tangent (z); zeros where
    /// the mesh has none.
    UvAndTangentSign,
    /// The interpolated world-space tangent, before normalization (xyz); zero where the
    /// mesh has none.
    WorldTangent,
}

/// A material that writes, instead of a lit color, the world position or normal that
/// [`PhongMaterial`](crate::PhongMaterial) would light at each pixel, with a caller's tag in
/// alpha (so that objects, and the background a camera clears to 0, can be told apart).
///
/// It runs Bevy's mesh vertex shader like `PhongMaterial` does, so the same mesh, camera
/// and render target give bit-identical inputs. Add [`SurfaceInputsPlugin`] to use it. Render a scene once lit and once with this
/// material on every mesh (into an `Rgba32Float` target) to evaluate the reference model
/// ([`crate::reference`]) on exactly the inputs the shader saw.
#[derive(Asset, AsBindGroup, Clone, Debug, Default, Reflect)]
pub struct SurfaceInputsMaterial {
    /// What to write.
    #[uniform(0)]
    pub output: SurfaceInputUniform,
}

impl SurfaceInputsMaterial {
    /// A material writing `input` in RGB and `tag` (as a float) in alpha.
    pub fn new(input: SurfaceInput, tag: u32) -> Self {
        let output = match input {
            SurfaceInput::WorldPosition => 0,
            SurfaceInput::WorldNormal => 1,
            SurfaceInput::UvAndTangentSign => 2,
            SurfaceInput::WorldTangent => 3,
        };
        Self {
            output: SurfaceInputUniform { output, tag },
        }
    }
}

/// The uniform of [`SurfaceInputsMaterial`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Reflect, ShaderType)]
pub struct SurfaceInputUniform {
    /// `0`: world position; `1`: world normal; `2`: UV and tangent sign; `3`: world tangent.
    pub output: u32,
    /// Written to alpha.
    pub tag: u32,
}

impl Material for SurfaceInputsMaterial {
    fn fragment_shader() -> ShaderRef {
        SURFACE_INPUTS_SHADER.into()
    }
}
