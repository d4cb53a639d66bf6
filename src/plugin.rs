//! [`PhongPlugin`], which adds every part of the crate to an app, and
//! [`PhongMaterialAppExt`] for the materials that bind its lights.

mod order;

use crate::light_kind::{BuiltInRegistrar, PhongLightKind, register_built_in_kinds};
use crate::{
    culling::{PhongLightCulling, PhongViewClusters},
    extension::add_light_kind,
    lights::{
        AreaHighlight, Decay, PhongAmbientLight, PhongCascades, PhongHemisphereLight,
        PhongLightCookie, PhongShadows,
    },
    material::{PhongMaterial, PhongSceneMaterial, SpecularModel},
    render::{
        ExtensionClusterSlots, PhongCookies, PhongLightBuffer, PhongLightClusters,
        SharedEpsilonLights, assign_lights_to_clusters, gather_cookies, gather_lights,
        prepare_again_on_new_variants, refresh_material_bind_groups,
    },
    scene_variants::SceneVariants,
    schedule::{PhongSystems, configure_phong_systems},
    shadows::PhongLit,
    storage_buffer::{LightBufferResized, init_shader_buffers},
    validation::{
        InvalidInput, check_metallic_roughness_maps, validate_ambient_light,
        validate_hemisphere_light, validate_materials,
    },
};
use bevy::{
    app::{App, Plugin, PostUpdate},
    asset::{AssetApp, Assets, embedded_asset, load_internal_asset},
    camera::visibility::VisibilitySystems,
    ecs::schedule::{IntoScheduleConfigs, common_conditions::resource_exists},
    image::Image,
    log::warn,
    pbr::{MaterialPlugin, MeshMaterial3d},
    reflect::GetTypeRegistration,
    render::{RenderApp, extract_resource::ExtractResourcePlugin},
    shader::{Shader, load_shader_library},
};
use core::hash::Hash;

/// Adds Phong lighting to an app: the light components and [`PhongAmbientLight`], the
/// gather system that writes them into the light buffer each frame, [`PhongMaterial`], and
/// the loaders of scene and material files ([`crate::scene`], feature `scene`).
///
/// Add it after Bevy's `DefaultPlugins`: `.add_plugins((DefaultPlugins, PhongPlugin))`.
/// Added before Bevy's `AssetPlugin` or `RenderPlugin`, it stops with a message that says
/// so. Without a renderer (`MinimalPlugins` and `AssetPlugin`, as ECS-only tests use) it
/// still gathers and validates lights, and warns once that nothing is drawn.
#[derive(Clone, Copy, Debug, Default)]
pub struct PhongPlugin;

impl Plugin for PhongPlugin {
    fn build(&self, app: &mut App) {
        order::check_build(app);
        init_shader_buffers(app);
        configure_phong_systems(app);
        add_resources(app);
        register_types(app);
        add_validation_and_gathers(app);
        crate::shadows::add_shadow_gather(app);
        // The built-in kinds of light, through the path every kind takes.
        register_built_in_kinds(&mut KindRegistrar(app));
        load_shaders(app);
        add_rendering(app);
    }

    fn finish(&self, app: &mut App) {
        match order::check_finish(app) {
            Ok(None) => {}
            Ok(Some(warning)) => warn!("{warning}"),
            Err(message) => panic!("{message}"),
        }
    }
}

/// The plugin's resources and messages.
fn add_resources(app: &mut App) {
    app.init_resource::<PhongAmbientLight>()
        .init_resource::<SceneVariants>()
        .init_resource::<PhongLightCulling>()
        .init_resource::<PhongLightBuffer>()
        .init_resource::<PhongCookies>()
        .init_resource::<PhongLightClusters>()
        .init_resource::<ExtensionClusterSlots>()
        .init_resource::<SharedEpsilonLights>()
        .add_message::<LightBufferResized>()
        .add_message::<InvalidInput>();
}

/// Registers each built-in kind of light as every kind is registered
/// ([`add_light_kind`]), with its reflection; an area kind's reference-model light is
/// collected as an extension kind's.
struct KindRegistrar<'a>(&'a mut App);

impl BuiltInRegistrar for KindRegistrar<'_> {
    fn kind<L: PhongLightKind + GetTypeRegistration>(&mut self) {
        add_light_kind::<L>(self.0);
        self.0.register_type::<L>();
    }

    fn area_kind<L: PhongLightKind>(&mut self) {
        #[cfg(feature = "reference")]
        crate::extension::reference_lights::add_reference_kind::<L>(self.0.world_mut());
    }
}

/// The reflection of the light components, the culling and the material.
fn register_types(app: &mut App) {
    app.register_type::<PhongAmbientLight>()
        .register_type::<PhongHemisphereLight>()
        .register_type::<PhongLightCookie>()
        .register_type::<PhongLightCulling>()
        .register_type::<PhongViewClusters>()
        .register_type::<AreaHighlight>()
        .register_type::<Decay>()
        .register_type::<PhongShadows>()
        .register_type::<PhongCascades>()
        .register_type::<SpecularModel>()
        .register_asset_reflect::<PhongMaterial>();
}

/// The validation of the ambient and hemisphere lights and the materials, and the gathers of
/// the cookies, the built-in lights and the clusters, in their sets.
fn add_validation_and_gathers(app: &mut App) {
    app.add_systems(
        PostUpdate,
        (
            validate_ambient_light,
            validate_hemisphere_light,
            validate_materials,
            check_metallic_roughness_maps.run_if(resource_exists::<Assets<Image>>),
        )
            .in_set(PhongSystems::Validate),
    )
    .add_systems(
        PostUpdate,
        (
            gather_cookies.run_if(resource_exists::<Assets<Image>>),
            gather_lights,
            assign_lights_to_clusters,
        )
            .chain()
            .after(VisibilitySystems::UpdateFrusta)
            .in_set(PhongSystems::GatherLights),
    );
}

/// The shaders, registered wherever Bevy's renderer is added, also without a render device
/// (`WgpuSettings::backends: None`), as Bevy's own plugins do: tools can then compose them
/// without a GPU. ECS-only apps (`MinimalPlugins`) have no shader assets.
fn load_shaders(app: &mut App) {
    if app.world().contains_resource::<Assets<Shader>>() {
        load_shader_library!(app, "shaders/types.wesl");
        load_shader_library!(app, "shaders/lighting.wesl");
        load_shader_library!(app, "shaders/area_integrals.wesl");
        load_shader_library!(app, "shaders/disk_polygon.wesl");
        load_shader_library!(app, "shaders/area_lighting.wesl");
        load_shader_library!(app, "shaders/bindings.wesl");
        load_shader_library!(app, "shaders/data_texture.wesl");
        load_shader_library!(app, "shaders/scene.wesl");
        load_shader_library!(app, "shaders/view_key.wesl");
        load_shader_library!(app, "shaders/clusters.wesl");
        load_shader_library!(app, "shaders/shading.wesl");
        load_shader_library!(app, "shaders/ambient_specular.wesl");
        load_shader_library!(app, "shaders/normals.wesl");
        load_shader_library!(app, "shaders/uv.wesl");
        load_shader_library!(app, "shaders/environment.wesl");
        load_shader_library!(app, "shaders/environment_light.wesl");
        load_shader_library!(app, "shaders/texture_maps.wesl");
        load_shader_library!(app, "shaders/shadows.wesl");
        load_shader_library!(app, "shaders/camera_effects.wesl");
        load_shader_library!(app, "shaders/per_vertex.wesl");
        load_shader_library!(app, "shaders/fragment.wesl");
        embedded_asset!(app, "shaders/phong_material.wesl");
        embedded_asset!(app, "shaders/phong_prepass.wesl");
        embedded_asset!(app, "shaders/shadow_caster.wesl");
        load_shader_library!(app, "shaders/displacement.wesl");
        load_shader_library!(app, "shaders/toon_ramp.wesl");
        load_shader_library!(app, "shaders/cookies.wesl");
        load_internal_asset!(
            app,
            crate::displacement::PHONG_VERTEX_SHADER,
            "shaders/phong_vertex.wesl",
            |source, _path| Shader::from_wesl(
                source,
                "embedded://bevy_phong/shaders/phong_vertex.wesl"
            )
        );
        load_internal_asset!(
            app,
            crate::displacement::PHONG_PREPASS_VERTEX_SHADER,
            "shaders/phong_prepass_vertex.wesl",
            |source, _path| Shader::from_wesl(
                source,
                "embedded://bevy_phong/shaders/phong_prepass_vertex.wesl"
            )
        );
    }
}

/// The render world's part (the shadow passes, the scene texture, the material and its
/// batching) where a renderer is added; the scene files everywhere.
fn add_rendering(app: &mut App) {
    if app.get_sub_app(RenderApp).is_none() {
        app.init_asset::<PhongMaterial>();
        #[cfg(feature = "scene")]
        crate::scene::add_scene_files(app);
        return;
    }
    crate::shadows::add_shadow_rendering(app);
    // Where the device lacks storage buffers, the scene data also goes into a texture.
    app.add_systems(
        PostUpdate,
        crate::render::pack_scene_texture
            .after(assign_lights_to_clusters)
            .in_set(PhongSystems::GatherLights),
    );
    app.sub_app_mut(RenderApp).add_systems(
        bevy::render::RenderStartup,
        crate::render::announce_scene_data_path,
    );
    // The scene's variants, which the render world sets in each material's key.
    app.add_plugins(ExtractResourcePlugin::<SceneVariants>::default());
    app.add_phong_material::<PhongMaterial>();
    crate::render::add_material_batching(app);
    #[cfg(feature = "scene")]
    crate::scene::add_scene_files(app);
}

/// Registers a material that binds the plugin's scene data (see
/// [`PhongSceneBindings`](crate::render::PhongSceneBindings)) or an extension's light
/// buffer, such as [`PhongMaterial`] or an `ExtendedMaterial<PhongMaterial, _>`.
pub trait PhongMaterialAppExt {
    /// Adds `MaterialPlugin::<M>` and keeps `M`'s bind groups on the current light buffers:
    /// when a buffer is reallocated, every `M` is rebuilt in the same frame, after the new
    /// buffer is uploaded; and where `M` is made of a [`PhongMaterial`], keeps its shader
    /// variant on the app's scene (see [`PhongSceneMaterial`]). Meshes drawn with `M` are marked
    /// [`PhongLit`](crate::PhongLit), so that the cameras that see them get shadow
    /// maps.
    fn add_phong_material<M: PhongSceneMaterial>(&mut self) -> &mut Self
    where
        M::Data: PartialEq + Eq + Hash + Clone;
}

impl PhongMaterialAppExt for App {
    fn add_phong_material<M: PhongSceneMaterial>(&mut self) -> &mut Self
    where
        M::Data: PartialEq + Eq + Hash + Clone,
    {
        self.add_plugins(MaterialPlugin::<M>::default())
            .add_systems(
                PostUpdate,
                (
                    refresh_material_bind_groups::<M>,
                    prepare_again_on_new_variants::<M>,
                )
                    .in_set(PhongSystems::RefreshMaterials),
            );
        // Already required where `M` was added before: that requirement stands.
        let _ = self.try_register_required_components::<MeshMaterial3d<M>, PhongLit>();
        if let Some(render_app) = self.get_sub_app_mut(RenderApp) {
            crate::render::schedule_light_buffers_before::<M>(render_app);
            crate::render::key_materials_in_scene::<M>(render_app);
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use crate::test_app::test_app;
    use bevy::{asset::ReflectAsset, ecs::reflect::AppTypeRegistry, reflect::TypePath};

    #[test]
    fn components_resources_and_the_material_are_registered_for_reflection() {
        let app = test_app(|_| {});
        let registry = app.world().resource::<AppTypeRegistry>().read();
        for path in [
            crate::PhongPointLight::type_path(),
            crate::PhongSpotLight::type_path(),
            crate::PhongRectLight::type_path(),
            crate::PhongDiskLight::type_path(),
            crate::PhongDirectionalLight::type_path(),
            crate::PhongAmbientLight::type_path(),
            crate::PhongLightCulling::type_path(),
            crate::Decay::type_path(),
        ] {
            assert!(registry.get_with_type_path(path).is_some(), "{path}");
        }
        let material = registry
            .get_with_type_path(crate::PhongMaterial::type_path())
            .expect("PhongMaterial is registered");
        assert!(material.data::<ReflectAsset>().is_some());
    }
}
