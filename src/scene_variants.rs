//! What the scene holds that changes every Phong material's shader: whether it casts shadows
//! this frame, whether soft ones, and whether it has a hemisphere light; and where the scene
//! data is bound (storage buffers, or one data texture under WebGL2's limits). Process-wide flags
//! that the gathers ([`crate::shadows`], [`crate::render`]) set in the main world and that
//! [`PhongMaterialKey`](crate::PhongMaterialKey) reads when a material is specialized. They
//! sit below both, so that the material needs nothing of the shadows or the lights.

use bevy::{
    pbr::MATERIAL_BIND_GROUP_INDEX,
    render::render_resource::{BindingType, BufferBindingType, RenderPipelineDescriptor},
    shader::ShaderDefVal,
};
use core::sync::atomic::AtomicBool;

/// Whether any light casts shadows this frame. Phong materials compile the shadow code only
/// in the variant for scenes where one does (shader def `PHONG_SHADOWS`): on some devices
/// (lavapipe) the mere presence of that code makes every fragment several times slower.
/// The shadow gather sets it in the main world and, when it flips, marks every Phong
/// material modified in the same frame, so that each is prepared again with the new key.
pub(crate) static SCENE_CASTS_SHADOWS: AtomicBool = AtomicBool::new(false);

/// Whether some shadow-casting light has a size (`softness > 0`) this frame: only then is
/// the soft-shadow filter compiled in (shader def `PHONG_SOFT_SHADOWS`), as
/// [`SCENE_CASTS_SHADOWS`] and set beside it. Hard shadows are one bilinear comparison per
/// light.
pub(crate) static SCENE_HAS_SOFT_SHADOWS: AtomicBool = AtomicBool::new(false);

/// Whether the scene has a [`PhongHemisphereLight`](crate::PhongHemisphereLight) this frame:
/// only then is its term compiled in (shader def `PHONG_HEMISPHERE`), as
/// [`SCENE_CASTS_SHADOWS`]. The light gather sets it and, when it flips, marks every Phong
/// material modified in the same frame.
pub(crate) static SCENE_HAS_HEMISPHERE_LIGHT: AtomicBool = AtomicBool::new(false);

/// Whether some light of the scene has a [`PhongLightCookie`](crate::PhongLightCookie) this
/// frame: only then is the cookie code compiled in (shader def `PHONG_LIGHT_COOKIES`), as
/// [`SCENE_CASTS_SHADOWS`]. The cookie gather sets it.
pub(crate) static SCENE_HAS_LIGHT_COOKIES: AtomicBool = AtomicBool::new(false);

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
