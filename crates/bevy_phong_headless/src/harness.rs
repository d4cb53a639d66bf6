//! [`Harness`]: a headless app rendering into a float image, with the per-pixel inputs of the
//! lighting equation read back beside each frame.

use bevy::{
    asset::RecursiveDependencyLoadState,
    camera::RenderTarget,
    core_pipeline::tonemapping::{DebandDither, Tonemapping},
    image::Image,
    math::DVec3,
    prelude::*,
    render::{
        RenderApp,
        error_handler::RenderErrorHandler,
        render_resource::{PipelineCache, TextureFormat, TextureUsages},
        view::Msaa,
    },
};
use bevy_phong::{
    MaterialFeatures,
    extension::PhongLightKind,
    prelude::*,
    reference::{self, SurfacePoint},
    testing::{SurfaceInput, SurfaceInputsMaterial, SurfaceInputsPlugin, is_finite_transform},
};
use std::{
    collections::HashMap,
    rc::Rc,
    sync::{Mutex, MutexGuard},
    time::Duration,
};

use crate::{
    Comparison, Expected, FloatImage, Progress,
    app::{finish_frame_driven_app, headless_app_with_assets},
    assert_no_failed_pipelines, parallel_map,
    pixel_model::{self, SrgbDecoding, near_a_cube_edge},
    read_back_frame, run_until_settled,
    see_through::{self, Behind, SeeThrough},
    unfinished_pipelines,
};

/// The camera every scene is seen from.
pub const CAMERA_POSITION: Vec3 = Vec3::new(0.0, 2.5, 7.0);

/// How long to wait for pipelines to compile before giving up: longer than any cold
/// compile of the crate's shaders on lavapipe (the first frame on a fresh machine takes
/// about a minute).
const SETTLE_TIMEOUT: Duration = Duration::from_secs(300);
/// Frames to wait for a scene file and what it names to load before giving up.
const MAX_LOAD_FRAMES: u32 = 2_000;

/// Per-pixel inputs of the lighting equation: world position and normal (with texture maps
/// also UVs, tangent and vertex color), and in alpha the tag of the material that covers the pixel (0 for
/// background).
pub struct SurfaceInputs<M: Material = PhongMaterial> {
    /// World position in xyz, material tag in alpha.
    pub positions: FloatImage,
    /// The interpolated world normal (not normalized) in xyz, material tag in alpha.
    pub normals: FloatImage,
    /// UV in xy, the tangent's handedness in z (see `SurfaceInput::UvAndTangentSign`).
    pub uvs: Option<FloatImage>,
    /// The interpolated tangent's xyz.
    pub tangents: Option<FloatImage>,
    /// The interpolated vertex color, RGBA (white where the mesh has none).
    pub colors: Option<FloatImage>,
    /// The second UV set in xy (zeros where the mesh has none).
    pub second_uvs: Option<FloatImage>,
    /// Whether the render device binds every map of a material (see
    /// `bevy_phong::testing::binds_every_map`; not under WebGL2's limits).
    pub every_map_bound: bool,
    /// The material behind each tag.
    pub materials: HashMap<u32, Handle<M>>,
}

impl<M: Material> Clone for SurfaceInputs<M> {
    fn clone(&self) -> Self {
        Self {
            positions: self.positions.clone(),
            normals: self.normals.clone(),
            uvs: self.uvs.clone(),
            tangents: self.tangents.clone(),
            colors: self.colors.clone(),
            second_uvs: self.second_uvs.clone(),
            every_map_bound: self.every_map_bound,
            materials: self.materials.clone(),
        }
    }
}

impl<M: Material> SurfaceInputs<M> {
    /// The material and surface point at pixel `index` (row-major), seen from `camera`;
    /// `None` where no mesh of `M` covers the pixel.
    pub fn surface_at(&self, index: usize, camera: DVec3) -> Option<(&Handle<M>, SurfacePoint)> {
        let position = self.positions.pixels[index];
        let normal = self.normals.pixels[index];
        let material = self.materials.get(&(position[3] as u32))?;
        let surface = SurfacePoint {
            position: DVec3::new(position[0].into(), position[1].into(), position[2].into()),
            normal: DVec3::new(normal[0].into(), normal[1].into(), normal[2].into()),
            camera,
        };
        Some((material, surface))
    }
}

/// The lights of a scene as the reference model takes them, each with its cookie.
pub struct ReferenceScene {
    /// The ambient light, the hemisphere light and each light, untinted.
    pub lights: reference::Lights,
    /// Each light's cookie, in the order of `lights.lights`.
    pub cookies: Vec<Option<reference::Cookie>>,
}

impl ReferenceScene {
    /// The lights at world position `position`: each tinted by its cookie where `tinted`
    /// (the device binds the cookie atlas); `None` where a point light's cookie is read
    /// within 10⁻⁵ (relative) of a cube edge, where the device's `f32` may pick the other
    /// face.
    pub fn lights_at(&self, position: DVec3, tinted: bool) -> Option<reference::Lights> {
        let mut lights = self.lights.clone();
        if !tinted {
            return Some(lights);
        }
        for (light, cookie) in lights.lights.iter_mut().zip(&self.cookies) {
            let Some(cookie) = cookie else {
                continue;
            };
            let cube = matches!(cookie.projection, reference::CookieProjection::Cube(_));
            if cube && near_a_cube_edge(cookie.light_from_world.transform_point3(position)) {
                return None;
            }
            *light = light.tinted(cookie.tint(position));
        }
        Some(lights)
    }
}

/// The process's rendering lock, which each harness holds while it lives. A test that failed
/// while holding it leaves it poisoned; the next one goes on.
fn lock_rendering() -> MutexGuard<'static, ()> {
    static RENDERING: Mutex<()> = Mutex::new(());
    RENDERING
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// One frame of two apps in lockstep, as `App::update` runs each but interleaved: both
/// main worlds first (`first`'s, then `second`'s), then each render world extracts its
/// own main world and renders. What one app's main world writes can reach only its own
/// render world.
pub fn update_in_lockstep(first: &mut App, second: &mut App) {
    first.sub_apps_mut().main.run_default_schedule();
    second.sub_apps_mut().main.run_default_schedule();
    for app in [first, second] {
        let sub_apps = app.sub_apps_mut();
        for sub_app in sub_apps.sub_apps.values_mut() {
            sub_app.extract(sub_apps.main.world_mut());
            sub_app.update();
        }
        sub_apps.main.world_mut().clear_trackers();
    }
}

/// Marks the camera that renders into the harness's target (a test may add others).
#[derive(Component)]
pub struct HarnessCamera;

/// A headless app with a float render target, the Phong plugin and a camera.
pub struct Harness {
    /// The app; [`Self::world_mut`] reaches its main world.
    pub app: App,
    /// Held while the harness lives (by both of a [`Self::side_by_side`] pair): one test
    /// renders at a time, so that each has the render device's threads to itself.
    _one_at_a_time: Rc<MutexGuard<'static, ()>>,
    target: Handle<Image>,
    width: u32,
    height: u32,
    /// Whether comparisons with the reference model show a progress line
    /// ([`Self::show_progress`]).
    show_progress: bool,
}

impl Harness {
    /// A `width`×`height` harness; `width` a multiple of 16 keeps rows unpadded.
    pub fn new(width: u32, height: u32) -> Self {
        Self::with_plugins(width, height, |_| {})
    }

    /// A harness whose app also gets what `add_plugins` adds after `PhongPlugin`.
    ///
    /// Lights are culled only past their range ([`PhongLightCulling::EXACT`]), so that
    /// renders follow SPEC.md exactly; tests of ε culling insert their own setting.
    pub fn with_plugins(width: u32, height: u32, add_plugins: impl FnOnce(&mut App)) -> Self {
        Self::with_assets(width, height, AssetPlugin::default().file_path, add_plugins)
    }

    /// [`Self::with_plugins`] with assets loaded from `asset_root`.
    pub fn with_assets(
        width: u32,
        height: u32,
        asset_root: String,
        add_plugins: impl FnOnce(&mut App),
    ) -> Self {
        Self::holding(
            Rc::new(lock_rendering()),
            width,
            height,
            asset_root,
            add_plugins,
        )
    }

    /// Two harnesses whose apps live side by side in this process, as an editor and its
    /// preview do, each with what its `add_plugins` adds. [`Self::render_next_frame_beside`]
    /// runs them in lockstep.
    pub fn side_by_side(
        width: u32,
        height: u32,
        add_first: impl FnOnce(&mut App),
        add_second: impl FnOnce(&mut App),
    ) -> (Self, Self) {
        let lock = Rc::new(lock_rendering());
        let asset_root = AssetPlugin::default().file_path;
        let first = Self::holding(lock.clone(), width, height, asset_root.clone(), add_first);
        let second = Self::holding(lock, width, height, asset_root, add_second);
        (first, second)
    }

    fn holding(
        one_at_a_time: Rc<MutexGuard<'static, ()>>,
        width: u32,
        height: u32,
        asset_root: String,
        add_plugins: impl FnOnce(&mut App),
    ) -> Self {
        let app = headless_app_with_assets(asset_root, |app| {
            add_harness_plugins(app);
            add_plugins(app);
        });
        Self::around(one_at_a_time, app, width, height)
    }

    /// A harness around `app`, whose plugins (Bevy's from
    /// [`frame_driven_plugins`](crate::frame_driven_plugins), `PhongPlugin` and the app's
    /// own) are added but not built: an example's app, checked as it is.
    pub fn adopting(mut app: App, width: u32, height: u32) -> Self {
        add_harness_plugins(&mut app);
        finish_frame_driven_app(&mut app);
        Self::around(Rc::new(lock_rendering()), app, width, height)
    }

    /// Adds the render target and the harness camera to `app`, ready to update.
    fn around(
        one_at_a_time: Rc<MutexGuard<'static, ()>>,
        mut app: App,
        width: u32,
        height: u32,
    ) -> Self {
        // A wgpu validation error would otherwise stop rendering without a word (the log is
        // off) and surface only as a readback that never arrives.
        app.insert_resource(RenderErrorHandler(|error, _, _| {
            panic!("render error ({:?}): {}", error.ty, error.description)
        }));

        let mut target = Image::new_target_texture(width, height, TextureFormat::Rgba32Float, None);
        target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
        let target = app.world_mut().resource_mut::<Assets<Image>>().add(target);
        app.world_mut().spawn((
            HarnessCamera,
            Camera3d::default(),
            Camera {
                clear_color: ClearColorConfig::Custom(Color::NONE),
                ..default()
            },
            RenderTarget::Image(target.clone().into()),
            Msaa::Off,
            Tonemapping::None,
            DebandDither::Disabled,
            Transform::from_translation(CAMERA_POSITION).looking_at(Vec3::ZERO, Vec3::Y),
        ));
        Self {
            app,
            _one_at_a_time: one_at_a_time,
            target,
            width,
            height,
            show_progress: false,
        }
    }

    /// Makes each comparison with the reference model show a progress line on standard
    /// error ([`Progress`]): for tools, whose comparisons can take minutes.
    pub fn show_progress(&mut self) {
        self.show_progress = true;
    }

    /// The harness camera, to give it a game's components (`Hdr`, `Bloom`, `Msaa`,
    /// `Tonemapping`, `DistanceFog`, prepasses…).
    pub fn camera_mut(&mut self) -> EntityWorldMut<'_> {
        let world = self.app.world_mut();
        let camera = world
            .query_filtered::<Entity, With<HarnessCamera>>()
            .single(world)
            .expect("the harness has one camera");
        world.entity_mut(camera)
    }

    /// The app's main world, where scenes are spawned and edited.
    pub fn world_mut(&mut self) -> &mut World {
        self.app.world_mut()
    }

    /// Loads the scene file at `path` (in the asset folder), spawns it, waits until it and
    /// every file it names have loaded, and sees it from its own camera
    /// ([`Self::adopt_scene_camera`]). A file that fails to load is an error with its message.
    pub fn load_scene(&mut self, path: &str) -> Result<Handle<PhongScene>, String> {
        let world = self.app.world_mut();
        let handle: Handle<PhongScene> = world.resource::<AssetServer>().load(path.to_owned());
        world.spawn(PhongSceneRoot(handle.clone()));
        for _ in 0..MAX_LOAD_FRAMES {
            self.app.update();
            let server = self.app.world().resource::<AssetServer>();
            match server.recursive_dependency_load_state(&handle) {
                RecursiveDependencyLoadState::Loaded => {
                    // One more frame for the scene to spawn.
                    self.app.update();
                    self.adopt_scene_camera();
                    return Ok(handle);
                }
                RecursiveDependencyLoadState::Failed(error) => return Err(error.to_string()),
                _ => std::thread::sleep(std::time::Duration::from_millis(5)),
            }
        }
        Err(format!(
            "{path} did not load within {MAX_LOAD_FRAMES} frames"
        ))
    }

    /// Gives the harness camera the transform and projection of the camera a scene file
    /// spawned ([`PhongSceneCamera`]), which is then removed: the scene is seen as its file
    /// says, rendered into the harness's float target. Without one, nothing changes.
    pub fn adopt_scene_camera(&mut self) {
        let world = self.app.world_mut();
        let scene_camera = world
            .query_filtered::<Entity, With<PhongSceneCamera>>()
            .iter(world)
            .next();
        if let Some(camera) = scene_camera {
            self.adopt_camera(camera);
        }
    }

    /// Gives the harness camera the transform and projection of `camera` (an app's own,
    /// with a `GlobalTransform` and a `Projection`), which is then despawned: the app's view
    /// rendered into the harness's float target, without that camera's effects. Nothing
    /// changes where `camera` lacks either component.
    pub fn adopt_camera(&mut self, camera: Entity) {
        let world = self.app.world_mut();
        let Ok((transform, projection)) = world
            .query::<(&GlobalTransform, &Projection)>()
            .get(world, camera)
            .map(|(transform, projection)| (transform.compute_transform(), projection.clone()))
        else {
            return;
        };
        world.despawn(camera);
        let mut cameras =
            world.query_filtered::<(&mut Transform, &mut Projection), With<HarnessCamera>>();
        for (mut camera_transform, mut camera_projection) in cameras.iter_mut(world) {
            *camera_transform = transform;
            *camera_projection = projection.clone();
        }
    }

    /// Moves the camera to `position`, looking at the origin (before `capture_inputs`).
    pub fn look_from(&mut self, position: Vec3) {
        let world = self.app.world_mut();
        let mut camera = world.query_filtered::<&mut Transform, With<HarnessCamera>>();
        for mut transform in camera.iter_mut(world) {
            *transform = Transform::from_translation(position).looking_at(Vec3::ZERO, Vec3::Y);
        }
    }

    /// Runs frames until no pipeline has been compiling for three frames in a row
    /// ([`run_until_settled`]); panics if a pipeline failed to compile
    /// ([`failed_pipelines`](crate::failed_pipelines)), since Bevy would draw nothing with it.
    pub fn settle(&mut self) {
        if !run_until_settled(&mut self.app, SETTLE_TIMEOUT, App::update) {
            let cache = self
                .app
                .sub_app(RenderApp)
                .world()
                .resource::<PipelineCache>();
            panic!(
                "pipelines that did not finish compiling: {:?} (one that waits for a shader \
                 that does not load never finishes: an example's shaders are in the crate's \
                 assets/, found with `cargo run` or with CARGO_MANIFEST_DIR set to the \
                 crate's folder)",
                unfinished_pipelines(cache)
            );
        }
        assert_no_failed_pipelines(&self.app, "the harness's scene");
    }

    /// Runs exactly one frame and returns what it rendered.
    pub fn render_next_frame(&mut self) -> FloatImage {
        let (width, height) = (self.width as usize, self.height as usize);
        let bytes = read_back_frame(&mut self.app, &self.target, 16 * width, height, App::update);
        FloatImage::from_rows(self.width, self.height, &bytes)
    }

    /// Runs frames of this harness's app and `other`'s in lockstep
    /// ([`update_in_lockstep`]) until a frame of this one is read back, and returns it.
    pub fn render_next_frame_beside(&mut self, other: &mut Harness) -> FloatImage {
        let (width, height) = (self.width as usize, self.height as usize);
        let bytes = read_back_frame(&mut self.app, &self.target, 16 * width, height, |app| {
            update_in_lockstep(app, &mut other.app)
        });
        FloatImage::from_rows(self.width, self.height, &bytes)
    }

    /// Renders every Phong mesh's world position and normal instead of its color.
    pub fn capture_inputs(&mut self) -> SurfaceInputs {
        self.capture_inputs_of::<PhongMaterial>()
    }

    /// Renders the world position and normal of every mesh made of `M` instead of its color.
    pub fn capture_inputs_of<M: PhongSceneMaterial>(&mut self) -> SurfaceInputs<M> {
        self.capture::<M>(false)
    }

    /// As [`Self::capture_inputs`], with the UV sets and tangents that texture maps need and
    /// the vertex colors.
    pub fn capture_inputs_with_maps(&mut self) -> SurfaceInputs {
        self.capture::<PhongMaterial>(true)
    }

    /// As [`Self::capture_inputs_of`], with the UV sets and tangents that texture maps need
    /// and the vertex colors: for extensions of `PhongMaterial` drawn with its maps.
    pub fn capture_inputs_with_maps_of<M: PhongSceneMaterial>(&mut self) -> SurfaceInputs<M> {
        self.capture::<M>(true)
    }

    fn capture<M: PhongSceneMaterial>(&mut self, with_maps: bool) -> SurfaceInputs<M> {
        let world = self.app.world_mut();
        let meshes: Vec<(Entity, Handle<M>)> = world
            .query::<(Entity, &MeshMaterial3d<M>)>()
            .iter(world)
            .map(|(entity, material)| (entity, material.0.clone()))
            .collect();
        let mut tags: HashMap<Handle<M>, u32> = HashMap::new();
        for (_, handle) in &meshes {
            let next = tags.len() as u32 + 1;
            tags.entry(handle.clone()).or_insert(next);
        }

        let mut passes = vec![SurfaceInput::WorldPosition, SurfaceInput::WorldNormal];
        if with_maps {
            passes.extend([
                SurfaceInput::UvAndTangentSign,
                SurfaceInput::WorldTangent,
                SurfaceInput::VertexColor,
                SurfaceInput::SecondUv,
            ]);
        }
        let assets = world.resource::<Assets<M>>();
        let drawn: HashMap<Handle<M>, PhongMaterial> = tags
            .keys()
            .map(|handle| {
                let material = assets
                    .get(handle)
                    .map_or_else(PhongMaterial::default, |material| {
                        material.phong_material().cloned().unwrap_or_default()
                    });
                (handle.clone(), material)
            })
            .collect();
        let mut images = Vec::new();
        for input in passes {
            let world = self.app.world_mut();
            for (entity, handle) in &meshes {
                let material = world.resource_mut::<Assets<SurfaceInputsMaterial>>().add(
                    SurfaceInputsMaterial::standing_in_for(&drawn[handle], input, tags[handle]),
                );
                world
                    .entity_mut(*entity)
                    .remove::<MeshMaterial3d<M>>()
                    .insert(MeshMaterial3d(material));
            }
            self.settle();
            images.push(self.render_next_frame());
        }
        let world = self.app.world_mut();
        for (entity, handle) in &meshes {
            world
                .entity_mut(*entity)
                .remove::<MeshMaterial3d<SurfaceInputsMaterial>>()
                .insert(MeshMaterial3d(handle.clone()));
        }
        self.settle();
        let mut images = images.into_iter();
        SurfaceInputs {
            positions: images.next().unwrap(),
            normals: images.next().unwrap(),
            uvs: images.next(),
            tangents: images.next(),
            colors: images.next(),
            second_uvs: images.next(),
            every_map_bound: self.binds_every_map(),
            materials: tags
                .into_iter()
                .map(|(handle, tag)| (tag, handle))
                .collect(),
        }
    }

    /// Whether the render device binds every map of a material. Known from the limits the
    /// device was asked for, not from the crate: under WebGL2's limits
    /// (`WGPU_SETTINGS_PRIO=webgl2`, which Bevy reads; scripts/test.sh's second pass) a
    /// shader stage has 16 textures and no storage buffers, and the crate leaves out the
    /// maps that do not fit (docs/webgl2.md); on every other device it binds them all.
    /// Panics where the crate's own rule (`bevy_phong::testing::binds_every_map`) disagrees,
    /// so that a device wrongly sent down the WebGL2 path fails every test that reads maps
    /// instead of being judged by the path it took.
    pub fn binds_every_map(&self) -> bool {
        let expected = !asks_for_webgl2_limits();
        let bound = bevy_phong::testing::binds_every_map(self.render_device());
        assert_eq!(
            bound,
            expected,
            "the crate binds every map: {bound}, but the device was asked for {} limits",
            if expected { "its own" } else { "WebGL2's" }
        );
        expected
    }

    /// The features the render device was created with (fewer under WebGL2's limits).
    pub fn device_features(&self) -> bevy::render::settings::WgpuFeatures {
        self.render_device().features()
    }

    fn render_device(&self) -> &bevy::render::renderer::RenderDevice {
        self.app
            .get_sub_app(bevy::render::RenderApp)
            .expect("the harness renders")
            .world()
            .resource::<bevy::render::renderer::RenderDevice>()
    }

    /// The scene's lights as the reference model takes them.
    pub fn reference_lights(&mut self) -> reference::Lights {
        self.reference_scene().lights
    }

    /// The camera position, as the shader's view uniform holds it.
    pub fn camera_position(&mut self) -> DVec3 {
        let world = self.app.world_mut();
        world
            .query_filtered::<&GlobalTransform, With<HarnessCamera>>()
            .single(world)
            .expect("the harness has one camera")
            .translation()
            .as_dvec3()
    }

    /// The scene's lights as the reference model takes them, each with its cookie (see
    /// [`ReferenceScene`]).
    pub fn reference_scene(&mut self) -> ReferenceScene {
        let world = self.app.world_mut();
        // The lights of kinds added with `PhongLightKindPlugin`, each as its kind gives it.
        let others = reference::OtherLights(bevy_phong::extension::reference_lights(world));
        let ambient = DVec3::from(world.resource::<PhongAmbientLight>()) + bevy_view_ambient(world);
        let hemisphere = world
            .get_resource::<bevy_phong::PhongHemisphereLight>()
            .map(reference::Hemisphere::from);
        let mut visible = world.query::<(
            &GlobalTransform,
            &InheritedVisibility,
            Option<&PhongLightCookie>,
            AnyOf<(&PhongDirectionalLight, &PhongPointLight, &PhongSpotLight)>,
        )>();
        let images = world.resource::<Assets<Image>>();
        let mut lights = Vec::new();
        let mut cookies = Vec::new();
        for (transform, visibility, cookie, (directional, point, spot)) in visible.iter(world) {
            // As the gather system: hidden lights and lights at a non-finite place are skipped.
            if !visibility.get() || !is_finite_transform(transform) {
                continue;
            }
            // Each light of the entity, with the cookie as its kind lays it over its rays.
            let kinds = [
                directional.map(|l| {
                    (
                        reference::Light::directional(l, transform),
                        l.cookie_projection(),
                    )
                }),
                point.map(|l| (reference::Light::point(l, transform), l.cookie_projection())),
                spot.map(|l| (reference::Light::spot(l, transform), l.cookie_projection())),
            ];
            for (light, projection) in kinds.into_iter().flatten() {
                let projection = projection.expect("a built-in local light takes a cookie");
                let cookie = cookie.and_then(|cookie| {
                    let image = images.get(&cookie.image)?;
                    reference::Cookie::new(cookie, image, transform, projection)
                });
                lights.push(light);
                cookies.push(cookie);
            }
        }
        ReferenceScene {
            lights: reference::Lights {
                ambient,
                hemisphere,
                lights,
                others,
            },
            cookies,
        }
    }

    /// Compares `rendered` with the reference model on `inputs`, pixel by pixel: the
    /// [`pixel_model`](crate::pixel_model) given each pixel's inputs, lit by
    /// [`Self::reference_scene`] (the cookies where the device binds them). Shadows are not
    /// modelled: a scene whose lights cast them is compared as if they did not. A pixel of a
    /// material with an sRGB map is judged between its lowest and highest decodings
    /// ([`SrgbDecoding`](crate::pixel_model::SrgbDecoding)); where an alpha mask discards,
    /// the clear color is expected (nothing is behind).
    pub fn compare(&mut self, rendered: &FloatImage, inputs: &SurfaceInputs) -> Comparison {
        self.compare_over(rendered, inputs, None)
    }

    /// [`Self::compare`] for the meshes of a material `M` made of a [`PhongMaterial`] (an
    /// extension of it, say): each judged on its `PhongMaterial`, lit by every light, those
    /// of extension kinds included.
    pub fn compare_of<M: PhongSceneMaterial>(
        &mut self,
        rendered: &FloatImage,
        inputs: &SurfaceInputs<M>,
    ) -> Comparison {
        self.compare_over(rendered, inputs, None)
    }

    /// As [`Self::compare`], except where a mesh lets what is behind it show: there the pixel
    /// is followed through `behind` ([`see_through`](crate::see_through)).
    fn compare_over<M: PhongSceneMaterial>(
        &mut self,
        rendered: &FloatImage,
        inputs: &SurfaceInputs<M>,
        behind: Option<&Behind<M>>,
    ) -> Comparison {
        let scene = self.reference_scene();
        let images = pixel_model::loaded_images(self);
        let flat_triangles = self.flat_shaded_triangles::<M>();
        let vertex_lit = self.vertex_lit_triangles(&scene, inputs, &images);
        let camera = self.camera_position();
        let materials = self.app.world().resource::<Assets<M>>();
        let expected_on = |inputs: &SurfaceInputs<M>, pixel: usize| -> Expected {
            let Some((handle, surface)) = inputs.surface_at(pixel, camera) else {
                return Expected::Clear;
            };
            let Some(material) = materials.get(handle).and_then(M::phong_material) else {
                return Expected::Unjudged;
            };
            let Some(mut lights) = scene.lights_at(surface.position, inputs.every_map_bound) else {
                return Expected::Unjudged;
            };
            if lit_per_vertex(material) {
                // The built-in lights' sums interpolated from the vertices, weighed at the
                // pixel; the other lights' terms as they are.
                let Some(light) = vertex_lit.light_at(surface.position) else {
                    return Expected::Unjudged;
                };
                lights.lights.clear();
                lights.others.0.push(std::sync::Arc::new(light));
            }
            let surface = if material.flat_shading {
                let Some(face) = pixel_model::face_normal_at(&flat_triangles, surface.position)
                else {
                    return Expected::Unjudged;
                };
                SurfacePoint {
                    normal: reference::face_normal(face, surface.normal),
                    ..surface
                }
            } else {
                surface
            };
            let color = |decoding| {
                pixel_model::expected_color_decoded(
                    material, &surface, pixel, inputs, &images, &lights, decoding,
                )
            };
            let colors = if pixel_model::reads_srgb_map(material, &images) {
                (color(SrgbDecoding::Lowest), color(SrgbDecoding::Highest))
            } else {
                let exact = color(SrgbDecoding::Exact);
                (exact, exact)
            };
            match colors {
                (Some(low), Some(high)) => Expected::Between(low, high),
                _ => Expected::Unjudged,
            }
        };
        let mut progress = self.show_progress.then(|| {
            Progress::new(
                "pixels compared with the reference model",
                rendered.pixels.len(),
            )
        });
        compare_covered_in_parallel(
            rendered,
            inputs,
            camera,
            |index, _, _| match behind {
                Some(behind) => see_through::expected_through(
                    index,
                    inputs,
                    behind,
                    materials,
                    &images,
                    &expected_on,
                ),
                None => expected_on(inputs, index),
            },
            progress.as_mut(),
        )
    }

    /// The triangles of every mesh drawn with a [`PhongMaterial`] lit per vertex, each corner
    /// with the sums of `scene`'s lights there (tinted by their cookies where `inputs` say
    /// the device binds them; the toon ramp where it binds that).
    fn vertex_lit_triangles<M: PhongSceneMaterial>(
        &mut self,
        scene: &ReferenceScene,
        inputs: &SurfaceInputs<M>,
        images: &HashMap<AssetId<Image>, Image>,
    ) -> pixel_model::VertexLitTriangles {
        let camera = self.camera_position();
        let world = self.app.world_mut();
        let mut drawn = world.query::<(&Mesh3d, &MeshMaterial3d<M>, &GlobalTransform)>();
        let meshes = world.resource::<Assets<Mesh>>();
        let materials = world.resource::<Assets<M>>();
        let mut triangles = pixel_model::VertexLitTriangles::default();
        for (mesh, material, transform) in drawn.iter(world) {
            let Some(material) = materials
                .get(&material.0)
                .and_then(M::phong_material)
                .filter(|m| lit_per_vertex(m))
            else {
                continue;
            };
            let Some(mesh) = meshes.get(&mesh.0) else {
                continue;
            };
            let mut model = reference::Material::from(material);
            model.toon_ramp = pixel_model::toon_ramp(material, inputs, images);
            triangles.add(mesh, transform, &model, camera, |position| {
                scene.lights_at(position, inputs.every_map_bound)
            });
        }
        triangles
    }

    /// The world-space triangles of every mesh drawn with a flat-shaded `M`.
    fn flat_shaded_triangles<M: PhongSceneMaterial>(&mut self) -> Vec<[DVec3; 3]> {
        let world = self.app.world_mut();
        let mut drawn = world.query::<(&Mesh3d, &MeshMaterial3d<M>, &GlobalTransform)>();
        let meshes = world.resource::<Assets<Mesh>>();
        let materials = world.resource::<Assets<M>>();
        drawn
            .iter(world)
            .filter(|(_, material, _)| {
                materials
                    .get(&material.0)
                    .and_then(M::phong_material)
                    .is_some_and(|material| material.flat_shading)
            })
            .filter_map(|(mesh, _, transform)| {
                Some(pixel_model::world_triangles(
                    meshes.get(&mesh.0)?,
                    transform,
                ))
            })
            .flatten()
            .collect()
    }

    /// Captures the inputs of every Phong pixel with its maps' and compares `rendered` with
    /// the reference model on them ([`Self::compare`]): the self-check of `render_scene`.
    pub fn compare_with_reference(&mut self, rendered: &FloatImage) -> Comparison {
        self.compare_with_reference_of::<PhongMaterial>(rendered)
    }

    /// [`Self::compare_with_reference`] for the meshes of a material `M` made of a
    /// [`PhongMaterial`] ([`Self::compare_of`]).
    pub fn compare_with_reference_of<M: PhongSceneMaterial>(
        &mut self,
        rendered: &FloatImage,
    ) -> Comparison {
        let inputs = self.capture_inputs_with_maps_of::<M>();
        let blended = self.see_through_meshes::<M>(SeeThrough::Blended);
        let masked = self.see_through_meshes::<M>(SeeThrough::Masked);
        if blended.is_empty() && masked.is_empty() {
            return self.compare_over(rendered, &inputs, None);
        }
        // Where a mask discards or a mesh blends, the frame shows what is behind it.
        let without_blended = if blended.is_empty() {
            inputs.clone()
        } else {
            self.capture_without::<M>(&blended)
        };
        let without_masked = if masked.is_empty() {
            inputs.clone()
        } else {
            self.capture_without::<M>(&masked)
        };
        let without_either = if blended.is_empty() {
            without_masked.clone()
        } else if masked.is_empty() {
            without_blended.clone()
        } else {
            self.capture_without::<M>(&[blended, masked].concat())
        };
        let behind = Behind {
            without_blended,
            without_masked,
            without_either,
        };
        self.compare_over(rendered, &inputs, Some(&behind))
    }

    /// [`Self::capture_inputs_with_maps`] with `meshes` hidden (shown again after).
    fn capture_without<M: PhongSceneMaterial>(&mut self, meshes: &[Entity]) -> SurfaceInputs<M> {
        let world = self.app.world_mut();
        let visibilities: Vec<Visibility> = meshes
            .iter()
            .map(|&mesh| {
                let mut entity = world.entity_mut(mesh);
                let visibility = entity.get::<Visibility>().copied().unwrap_or_default();
                entity.insert(Visibility::Hidden);
                visibility
            })
            .collect();
        let inputs = self.capture_inputs_with_maps_of::<M>();
        let world = self.app.world_mut();
        for (&mesh, visibility) in meshes.iter().zip(visibilities) {
            world.entity_mut(mesh).insert(visibility);
        }
        self.settle();
        inputs
    }

    /// The meshes drawn with an `M` that lets what is behind through as `kind`.
    fn see_through_meshes<M: PhongSceneMaterial>(&mut self, kind: SeeThrough) -> Vec<Entity> {
        let world = self.app.world_mut();
        let mut drawn = world.query::<(Entity, &MeshMaterial3d<M>)>();
        let materials = world.resource::<Assets<M>>();
        drawn
            .iter(world)
            .filter(|(_, material)| {
                materials
                    .get(&material.0)
                    .and_then(M::phong_material)
                    .is_some_and(|material| see_through::lets_through(material) == Some(kind))
            })
            .map(|(entity, _)| entity)
            .collect()
    }

    /// Compares `rendered` with `expected(material, surface)` on `inputs`, pixel by pixel;
    /// `expected` returns `None` for a pixel it cannot judge (one on a discontinuity).
    pub fn compare_with<M: Material>(
        &mut self,
        rendered: &FloatImage,
        inputs: &SurfaceInputs<M>,
        expected: impl Fn(&M, &SurfacePoint) -> Option<DVec3>,
    ) -> Comparison {
        self.compare_pixels(rendered, inputs, |material, surface, _| {
            expected(material, surface)
        })
    }

    /// As [`Self::compare_with`], with `expected` also given the pixel's index into `inputs`.
    pub fn compare_pixels<M: Material>(
        &mut self,
        rendered: &FloatImage,
        inputs: &SurfaceInputs<M>,
        expected: impl Fn(&M, &SurfacePoint, usize) -> Option<DVec3>,
    ) -> Comparison {
        let camera = self.camera_position();
        let assets = self.app.world().resource::<Assets<M>>();
        compare_covered(rendered, inputs, camera, |index, handle, surface| {
            let material = assets.get(handle).expect("material exists");
            expected(material, surface, index).map_or(Expected::Unjudged, Expected::Lit)
        })
    }
}

/// Compares `rendered` with `expected(index, material, surface)` at each pixel that a mesh
/// of `M` covers in `inputs` (seen from `camera`), counting each object's judged and
/// unjudged pixels; elsewhere the clear color is expected.
fn compare_covered<M: Material>(
    rendered: &FloatImage,
    inputs: &SurfaceInputs<M>,
    camera: DVec3,
    expected: impl Fn(usize, &Handle<M>, &SurfacePoint) -> Expected,
) -> Comparison {
    let expectations = (0..rendered.pixels.len())
        .map(|index| expected_at(inputs, camera, &expected, index))
        .collect();
    record_expectations(rendered, inputs, expectations)
}

/// [`compare_covered`], the pixels' expected colors computed on every core
/// ([`parallel_map`]), with a progress line where `progress` is given.
fn compare_covered_in_parallel<M: Material>(
    rendered: &FloatImage,
    inputs: &SurfaceInputs<M>,
    camera: DVec3,
    expected: impl Fn(usize, &Handle<M>, &SurfacePoint) -> Expected + Sync,
    progress: Option<&mut Progress>,
) -> Comparison {
    let expectations = parallel_map(
        rendered.pixels.len(),
        |index| expected_at(inputs, camera, &expected, index),
        progress,
    );
    record_expectations(rendered, inputs, expectations)
}

/// What pixel `index` should show: `expected` of the surface a mesh of `M` shows there, or
/// `None` (the clear color) where none does.
fn expected_at<M: Material>(
    inputs: &SurfaceInputs<M>,
    camera: DVec3,
    expected: &impl Fn(usize, &Handle<M>, &SurfacePoint) -> Expected,
    index: usize,
) -> Option<Expected> {
    inputs
        .surface_at(index, camera)
        .map(|(material, surface)| expected(index, material, &surface))
}

/// Records each pixel of `rendered` against what it should show (`None`: the clear color).
fn record_expectations<M: Material>(
    rendered: &FloatImage,
    inputs: &SurfaceInputs<M>,
    expectations: Vec<Option<Expected>>,
) -> Comparison {
    let mut comparison = Comparison::new(rendered.width, rendered.height);
    for (index, (color, expected)) in rendered.pixels.iter().zip(expectations).enumerate() {
        let Some(expected) = expected else {
            comparison.record_background(index, *color);
            continue;
        };
        let object = inputs.positions.pixels[index][3] as u32;
        comparison.count_object_pixel(object, expected != Expected::Unjudged);
        comparison.record_expected(index, *color, expected);
    }
    comparison
}

/// What the harness adds to an app: lights culled only past their range
/// ([`PhongLightCulling::EXACT`]), so that renders follow SPEC.md exactly, and the passes
/// that capture each pixel's inputs.
fn add_harness_plugins(app: &mut App) {
    app.insert_resource(PhongLightCulling::EXACT)
        .add_plugins(SurfaceInputsPlugin);
}

/// Whether `material`'s lights are summed at its vertices (SPEC.md, "Per-vertex lighting"):
/// the material's own feature, as its shader variant has it.
fn lit_per_vertex(material: &PhongMaterial) -> bool {
    MaterialFeatures::of(material).contains(MaterialFeatures::VERTEX_LIGHTING)
}

/// Whether the harness's device is asked for WebGL2's limits: where `WGPU_SETTINGS_PRIO` is
/// `webgl2` in any case, as Bevy's `settings_priority_from_env` reads it.
pub fn asks_for_webgl2_limits() -> bool {
    std::env::var("WGPU_SETTINGS_PRIO")
        .is_ok_and(|priority| priority.eq_ignore_ascii_case("webgl2"))
}

/// The harness camera's own Bevy ambient light as the Bevy-light mirror lights its view
/// (`bevy_phong::BevyLightExposure`'s module docs): the camera's `AmbientLight`, else
/// `GlobalAmbientLight`, converted by the mirror's exposure; zero without the mirror.
fn bevy_view_ambient(world: &mut World) -> DVec3 {
    let Some(exposure) = world.get_resource::<BevyLightExposure>().copied() else {
        return DVec3::ZERO;
    };
    let camera = world
        .query_filtered::<Option<&AmbientLight>, With<HarnessCamera>>()
        .single(world)
        .expect("the harness has one camera")
        .cloned();
    let light = match camera {
        Some(light) => GlobalAmbientLight {
            color: light.color,
            brightness: light.brightness,
            affects_lightmapped_meshes: light.affects_lightmapped_meshes,
        },
        None => world
            .get_resource::<GlobalAmbientLight>()
            .cloned()
            .unwrap_or(GlobalAmbientLight::NONE),
    };
    DVec3::from(&exposure.ambient(&light))
}
