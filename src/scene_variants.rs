//! What the scene holds that changes every Phong material's shader: whether it casts shadows
//! this frame, whether soft ones, whether it has a hemisphere light, area lights and whether cookies
//! ([`SceneVariants`]); and where the scene data is bound (storage buffers, or one data
//! texture under WebGL2's limits). The gathers ([`crate::shadows`], [`crate::render`]) set the
//! app's [`SceneVariants`] resource in the main world; it is extracted into the render world,
//! which sets it in each Phong material's key as the material is prepared ([`SceneKey`],
//! `render::scene_keys`), so that the asset a game writes holds only the material. Nothing is
//! shared between apps, and the render world reads the value of the frame it draws. They sit
//! below both, so that the material needs nothing of the shadows or the lights.

use bevy::{
    ecs::resource::Resource,
    pbr::MATERIAL_BIND_GROUP_INDEX,
    render::render_resource::{BindingType, BufferBindingType, RenderPipelineDescriptor},
    render::{RenderApp, extract_resource::ExtractResource},
    shader::ShaderDefVal,
};

/// The scene's choices that change the shader of every Phong material: a resource of the
/// app's main world, extracted into its render world. Each leaves code out of the shaders of
/// scenes that do not need it: on some devices (lavapipe) the mere presence of the shadow
/// code makes every fragment several times slower. When one changes, every Phong material
/// is prepared again in the same frame, with the new variant in its key (`render::scene_keys`);
/// the first time a variant is seen it is compiled, as any new variant.
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub(crate) struct SceneVariants {
    /// Whether any light casts shadows this frame (shader def `PHONG_SHADOWS`). Set by the
    /// shadow gather.
    pub(crate) shadows: bool,
    /// Whether some shadow-casting light has a size (`softness > 0`) this frame: only then is
    /// the soft-shadow filter compiled in (shader def `PHONG_SOFT_SHADOWS`); hard shadows are
    /// one bilinear comparison per light. Set by the shadow gather.
    pub(crate) soft_shadows: bool,
    /// Whether the scene has a [`PhongHemisphereLight`](crate::PhongHemisphereLight) (shader
    /// def `PHONG_HEMISPHERE`). Set by the light gather.
    pub(crate) hemisphere: bool,
    /// Whether the light buffer holds an area light ([`PhongRectLight`](crate::PhongRectLight))
    /// this frame (shader def `PHONG_AREA_LIGHTS`): a scene without one pays nothing for
    /// their loop. Set by the light gather.
    pub(crate) area_lights: bool,
    /// Whether one of those is a disk ([`PhongDiskLight`](crate::PhongDiskLight), shader def
    /// `PHONG_DISK_LIGHTS`): only then do the area lights' polygons hold a disk's 16 corners
    /// (a rectangle's need 6, and the shader's arrays are zeroed and copied at their full
    /// size). Set by the light gather.
    pub(crate) disk_lights: bool,
    /// Whether one of those takes the fitted highlight
    /// ([`AreaHighlight::Fitted`](crate::AreaHighlight::Fitted), shader def
    /// `PHONG_AREA_FITTED`): only then is its branch compiled in. Set by the light gather.
    pub(crate) fitted_highlights: bool,
    /// Whether some light has a [`PhongLightCookie`](crate::PhongLightCookie) with a record
    /// this frame (shader def `PHONG_LIGHT_COOKIES`). Set by the cookie gather.
    pub(crate) cookies: bool,
}

impl ExtractResource<RenderApp> for SceneVariants {
    type Source = Self;

    fn extract_resource(source: &Self) -> Self {
        *source
    }
}

/// The part of a Phong material's key that the render world sets, not the material: the
/// scene's variants of the frame, and whether the bind group is the one a class of materials
/// shares, which reads the numbers from every material's records (`render::batching`). The
/// feature table's scene rows read it ([`crate::material`]'s `material_features!`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct SceneKey {
    /// The app's scene variants of the frame drawn.
    pub variants: SceneVariants,
    /// Whether the bind group is a class's shared one (shader def `PHONG_MATERIAL_RECORDS`).
    pub from_records: bool,
}

/// Binding index, in the material bind group, of the light buffer (a storage buffer) or, where
/// a shader stage has too few storage buffers (WebGL2), of the data texture that holds the
/// whole scene data in its place (`PhongSceneBindings`).
pub(crate) const LIGHT_BUFFER_BINDING: u32 = 1;

/// Name of the shader flag that says the scene data is in storage buffers (set) or in the
/// data texture (unset): WESL's `@if(PHONG_STORAGE_BUFFERS)`.
pub(crate) const STORAGE_BUFFERS_FLAG: &str = "PHONG_STORAGE_BUFFERS";

/// Sets [`STORAGE_BUFFERS_FLAG`] in both stages of `descriptor`, a pipeline of a material that
/// binds the scene data: true where its material bind group (Bevy's group
/// [`MATERIAL_BIND_GROUP_INDEX`]) holds a storage buffer at [`LIGHT_BUFFER_BINDING`], false
/// where it holds the data texture. That layout is the one the render module chose for the
/// device, so the shaders read exactly what is bound. Every pipeline that draws with the
/// crate's shaders calls it from its `specialize`.
pub(crate) fn add_scene_data_flag(descriptor: &mut RenderPipelineDescriptor) {
    let storage = descriptor
        .layout
        .get(MATERIAL_BIND_GROUP_INDEX)
        .is_some_and(|layout| {
            layout.entries.iter().any(|entry| {
                entry.binding == LIGHT_BUFFER_BINDING
                    && matches!(
                        entry.ty,
                        BindingType::Buffer {
                            ty: BufferBindingType::Storage { .. },
                            ..
                        }
                    )
            })
        });
    let flag = ShaderDefVal::Bool(STORAGE_BUFFERS_FLAG.into(), storage);
    descriptor.vertex.shader_defs.push(flag.clone());
    if let Some(fragment) = descriptor.fragment.as_mut() {
        fragment.shader_defs.push(flag);
    }
}
