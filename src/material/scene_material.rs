//! [`PhongSceneMaterial`]: a material that binds the scene data, and where it is made of a
//! [`PhongMaterial`], the key in which the render world sets the scene's shader variant.

use super::{PhongMaterial, PhongMaterialKey};
use bevy::{
    pbr::{ExtendedMaterial, Material, MaterialExtension},
    render::combined_bind_group::CombinedBindGroupData,
};

/// A material that [`add_phong_material`](crate::PhongMaterialAppExt::add_phong_material)
/// registers: one made of a [`PhongMaterial`] (`PhongMaterial` itself and every
/// `ExtendedMaterial<PhongMaterial, _>`) names it and its key, so that the render world sets
/// the scene's shader variant (shadows, hemisphere light, cookies) in its key. A material of
/// its own that binds the scene data implements it with the defaults: `impl
/// PhongSceneMaterial for MyMaterial {}`.
pub trait PhongSceneMaterial: Material {
    /// The [`PhongMaterial`] this material is made of, if any. Default `None`.
    fn phong_material(&self) -> Option<&PhongMaterial> {
        None
    }

    /// The same, to change. Default `None`.
    fn phong_material_mut(&mut self) -> Option<&mut PhongMaterial> {
        None
    }

    /// This material's key (`key`, its
    /// [`AsBindGroup::Data`](bevy::render::render_resource::AsBindGroup::Data)) with the
    /// [`PhongMaterialKey`] in it replaced by `set` of it, where the material is made of a
    /// [`PhongMaterial`]: the render world sets the scene's variant so. Default: `key` as it
    /// is.
    fn with_phong_material_key(
        key: Self::Data,
        set: &dyn Fn(PhongMaterialKey) -> PhongMaterialKey,
    ) -> Self::Data {
        let _ = set;
        key
    }
}

impl PhongSceneMaterial for PhongMaterial {
    fn phong_material(&self) -> Option<&PhongMaterial> {
        Some(self)
    }

    fn phong_material_mut(&mut self) -> Option<&mut PhongMaterial> {
        Some(self)
    }

    fn with_phong_material_key(
        key: PhongMaterialKey,
        set: &dyn Fn(PhongMaterialKey) -> PhongMaterialKey,
    ) -> PhongMaterialKey {
        set(key)
    }
}

impl<E: MaterialExtension> PhongSceneMaterial for ExtendedMaterial<PhongMaterial, E> {
    fn phong_material(&self) -> Option<&PhongMaterial> {
        Some(&self.base)
    }

    fn phong_material_mut(&mut self) -> Option<&mut PhongMaterial> {
        Some(&mut self.base)
    }

    fn with_phong_material_key(
        key: Self::Data,
        set: &dyn Fn(PhongMaterialKey) -> PhongMaterialKey,
    ) -> Self::Data {
        // The combined key is packed: its parts are copied out, not borrowed.
        let (base, extension) = (key.base, key.extension);
        CombinedBindGroupData {
            base: set(base),
            extension,
        }
    }
}
