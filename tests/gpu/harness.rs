//! Renders scenes headless into a linear `Rgba32Float` image, reads the pixels back with the
//! inputs each pixel was lit with, and compares them with the f64 reference model.

use bevy::{
    asset::RecursiveDependencyLoadState,
    camera::RenderTarget,
    core_pipeline::tonemapping::{DebandDither, Tonemapping},
    image::Image,
    prelude::*,
    render::{
        RenderApp,
        error_handler::RenderErrorHandler,
        gpu_readback::{Readback, ReadbackComplete},
        render_resource::{PipelineCache, TextureFormat, TextureUsages},
        view::Msaa,
    },
};
use bevy_phong::{
    SurfaceInput, SurfaceInputsMaterial, SurfaceInputsPlugin,
    prelude::*,
    reference::{self, SurfacePoint},
    validation::is_finite_transform,
};
use glam::DVec3;

use crate::headless::headless_app_with_assets;
use std::{
    collections::HashMap,
    path::PathBuf,
    sync::{Arc, Mutex, MutexGuard},
};

/// The camera every scene is seen from.
pub const CAMERA_POSITION: Vec3 = Vec3::new(0.0, 2.5, 7.0);

/// Frames to wait for pipelines to compile before giving up.
const MAX_SETTLE_FRAMES: u32 = 600;
/// Frames to wait for a scene file and what it names to load before giving up.
const MAX_LOAD_FRAMES: u32 = 2_000;
/// Frames to wait for a readback to arrive before giving up.
const MAX_READBACK_FRAMES: u32 = 60;

/// An RGBA32F image read back from the GPU.
#[derive(Clone)]
pub struct FloatImage {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f32; 4]>,
}

impl FloatImage {
    fn from_readback(width: u32, height: u32, bytes: &[u8]) -> Self {
        let row_bytes = bytes.len() / height as usize;
        let pixels = (0..height as usize)
            .flat_map(|row| {
                let start = row * row_bytes;
                bytemuck::cast_slice::<u8, [f32; 4]>(&bytes[start..start + width as usize * 16])
                    .to_vec()
            })
            .collect();
        Self {
            width,
            height,
            pixels,
        }
    }
}

/// Per-pixel inputs of the lighting equation: world position and normal (with texture maps
/// also UV and tangent), and in alpha the tag of the material that covers the pixel (0 for
/// background).
pub struct SurfaceInputs<M: Material = PhongMaterial> {
    pub positions: FloatImage,
    pub normals: FloatImage,
    /// UV in xy, the tangent's handedness in z (see `SurfaceInput::UvAndTangentSign`).
    pub uvs: Option<FloatImage>,
    /// The interpolated tangent's xyz.
    pub tangents: Option<FloatImage>,
    pub materials: HashMap<u32, Handle<M>>,
}

#[derive(Resource, Clone, Default)]
struct Received(Arc<Mutex<HashMap<Entity, Vec<u8>>>>);

/// A headless app with a float render target, the Phong plugin and a camera.
pub struct Harness {
    pub app: App,
    /// Held while the harness lives: one harness renders at a time. Phong materials take
    /// their shadow variant from a process-wide flag (`PhongMaterialKey::shadows`), which
    /// apps rendering side by side would flip under each other.
    _one_at_a_time: MutexGuard<'static, ()>,
    target: Handle<Image>,
    width: u32,
    height: u32,
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
        static RENDERING: Mutex<()> = Mutex::new(());
        // A test that failed while holding it leaves it poisoned; the next one goes on.
        let one_at_a_time = RENDERING
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let mut app = headless_app_with_assets(asset_root, |app| {
            app.insert_resource(PhongLightCulling::EXACT)
                .add_plugins(SurfaceInputsPlugin);
            add_plugins(app);
        });
        // A wgpu validation error would otherwise stop rendering without a word (the log is
        // off) and surface only as a readback that never arrives.
        app.insert_resource(RenderErrorHandler(|error, _, _| {
            panic!("render error ({:?}): {}", error.ty, error.description)
        }));
        let received = Received::default();
        let sink = received.clone();
        app.insert_resource(received);
        app.add_observer(move |readback: On<ReadbackComplete>| {
            sink.0
                .lock()
                .unwrap()
                .insert(readback.entity, readback.data.clone());
        });

        let mut target = Image::new_target_texture(width, height, TextureFormat::Rgba32Float, None);
        target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
        let target = app.world_mut().resource_mut::<Assets<Image>>().add(target);
        app.world_mut().spawn((
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
        }
    }

    pub fn world_mut(&mut self) -> &mut World {
        self.app.world_mut()
    }

    /// Loads the scene file at `path` (in the asset folder), spawns it, waits until it and
    /// every file it names have loaded, and sees it from its own camera
    /// ([`Self::adopt_scene_camera`]). A file that fails to load is an error with its message.
    #[allow(dead_code, reason = "not used by the benchmark")]
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
            .query_filtered::<(Entity, &GlobalTransform, &Projection), With<PhongSceneCamera>>()
            .iter(world)
            .next()
            .map(|(entity, transform, projection)| {
                (entity, transform.compute_transform(), projection.clone())
            });
        let Some((entity, transform, projection)) = scene_camera else {
            return;
        };
        world.despawn(entity);
        let mut cameras =
            world.query_filtered::<(&mut Transform, &mut Projection), With<Camera3d>>();
        for (mut camera_transform, mut camera_projection) in cameras.iter_mut(world) {
            *camera_transform = transform;
            *camera_projection = projection.clone();
        }
    }

    /// Moves the camera to `position`, looking at the origin (before `capture_inputs`).
    #[allow(
        dead_code,
        reason = "used by the benchmark example, which includes this file"
    )]
    pub fn look_from(&mut self, position: Vec3) {
        let world = self.app.world_mut();
        let mut camera = world.query_filtered::<&mut Transform, With<Camera3d>>();
        for mut transform in camera.iter_mut(world) {
            *transform = Transform::from_translation(position).looking_at(Vec3::ZERO, Vec3::Y);
        }
    }

    /// Runs frames until every pipeline has compiled and two more frames were drawn.
    pub fn settle(&mut self) {
        let mut ready_frames = 0;
        for _ in 0..MAX_SETTLE_FRAMES {
            self.app.update();
            let render_world = self.app.sub_app(RenderApp).world();
            let waiting = render_world
                .resource::<PipelineCache>()
                .waiting_pipelines()
                .count();
            ready_frames = if waiting == 0 { ready_frames + 1 } else { 0 };
            if ready_frames >= 3 {
                return;
            }
        }
        panic!("pipelines did not compile within {MAX_SETTLE_FRAMES} frames");
    }

    /// Runs exactly one frame and returns what it rendered.
    pub fn render_next_frame(&mut self) -> FloatImage {
        let entity = self
            .app
            .world_mut()
            .spawn(Readback::texture(self.target.clone()))
            .id();
        self.app.update();
        self.app.world_mut().despawn(entity);
        let received = self.app.world().resource::<Received>().clone();
        for _ in 0..MAX_READBACK_FRAMES {
            if let Some(bytes) = received.0.lock().unwrap().remove(&entity) {
                return FloatImage::from_readback(self.width, self.height, &bytes);
            }
            self.app.update();
        }
        panic!("readback did not arrive within {MAX_READBACK_FRAMES} frames");
    }

    /// Renders every Phong mesh's world position and normal instead of its color.
    pub fn capture_inputs(&mut self) -> SurfaceInputs {
        self.capture_inputs_of::<PhongMaterial>()
    }

    /// Renders the world position and normal of every mesh made of `M` instead of its color.
    pub fn capture_inputs_of<M: Material>(&mut self) -> SurfaceInputs<M> {
        self.capture::<M>(false)
    }

    /// As [`Self::capture_inputs`], with the UVs and tangents that texture maps need.
    #[allow(
        dead_code,
        reason = "used by the texture tests, not by the benchmark example that includes this file"
    )]
    pub fn capture_inputs_with_maps(&mut self) -> SurfaceInputs {
        self.capture::<PhongMaterial>(true)
    }

    fn capture<M: Material>(&mut self, with_maps: bool) -> SurfaceInputs<M> {
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
            passes.extend([SurfaceInput::UvAndTangentSign, SurfaceInput::WorldTangent]);
        }
        let mut images = Vec::new();
        for input in passes {
            let world = self.app.world_mut();
            for (entity, handle) in &meshes {
                let material = world
                    .resource_mut::<Assets<SurfaceInputsMaterial>>()
                    .add(SurfaceInputsMaterial::new(input, tags[handle]));
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
            materials: tags
                .into_iter()
                .map(|(handle, tag)| (tag, handle))
                .collect(),
        }
    }

    /// The scene's lights as the reference model takes them.
    pub fn reference_lights(&mut self) -> reference::Lights {
        let world = self.app.world_mut();
        let ambient = world.resource::<PhongAmbientLight>().into();
        let mut lights = Vec::new();
        let mut visible = world.query::<(
            &GlobalTransform,
            &InheritedVisibility,
            AnyOf<(&PhongDirectionalLight, &PhongPointLight, &PhongSpotLight)>,
        )>();
        for (transform, visibility, (directional, point, spot)) in visible.iter(world) {
            // As the gather system: hidden lights and lights at a non-finite place are skipped.
            if !visibility.get() || !is_finite_transform(transform) {
                continue;
            }
            lights.extend(directional.map(|l| reference::Light::directional(l, transform)));
            lights.extend(point.map(|l| reference::Light::point(l, transform)));
            lights.extend(spot.map(|l| reference::Light::spot(l, transform)));
        }
        reference::Lights { ambient, lights }
    }

    /// The camera position, as the shader's view uniform holds it.
    pub fn camera_position(&mut self) -> DVec3 {
        let world = self.app.world_mut();
        world
            .query_filtered::<&GlobalTransform, With<Camera3d>>()
            .single(world)
            .expect("the harness has one camera")
            .translation()
            .as_dvec3()
    }

    /// Compares `rendered` with the reference model on `inputs`, pixel by pixel.
    pub fn compare(&mut self, rendered: &FloatImage, inputs: &SurfaceInputs) -> Comparison {
        let lights = self.reference_lights();
        self.compare_with(rendered, inputs, |material: &PhongMaterial, surface| {
            Some(reference::shade(
                surface,
                &reference::Material::from(material),
                &lights,
            ))
        })
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
        let mut comparison = Comparison::new(rendered.width, rendered.height);
        for (index, ((color, position), normal)) in rendered
            .pixels
            .iter()
            .zip(&inputs.positions.pixels)
            .zip(&inputs.normals.pixels)
            .enumerate()
        {
            let Some(material) = inputs
                .materials
                .get(&(position[3] as u32))
                .map(|handle| assets.get(handle).expect("material exists"))
            else {
                comparison.record_background(index, *color);
                continue;
            };
            let surface = SurfacePoint {
                position: DVec3::new(position[0].into(), position[1].into(), position[2].into()),
                normal: DVec3::new(normal[0].into(), normal[1].into(), normal[2].into()),
                camera,
            };
            match expected(material, &surface, index) {
                Some(expected) => comparison.record(index, *color, expected),
                None => comparison.skipped_pixels += 1,
            }
        }
        comparison
    }
}

/// The result of comparing a rendered image with the reference model.
pub struct Comparison {
    width: u32,
    height: u32,
    pub lit_pixels: usize,
    /// Largest `|actual - expected| / max(1, |expected|)` over all channels of lit pixels.
    pub max_error: f64,
    pub worst_pixel: Option<(u32, u32, [f32; 3], DVec3)>,
    /// Pixels not covered by a mesh whose color is not the clear color.
    pub stray_pixels: usize,
    /// Covered pixels the reference could not judge (on a discontinuity).
    pub skipped_pixels: usize,
    actual: Vec<[f32; 3]>,
    expected: Vec<[f32; 3]>,
}

impl Comparison {
    fn new(width: u32, height: u32) -> Self {
        let count = (width * height) as usize;
        Self {
            width,
            height,
            lit_pixels: 0,
            max_error: 0.0,
            worst_pixel: None,
            stray_pixels: 0,
            skipped_pixels: 0,
            actual: vec![[0.0; 3]; count],
            expected: vec![[0.0; 3]; count],
        }
    }

    fn record_background(&mut self, index: usize, color: [f32; 4]) {
        if color != [0.0; 4] {
            self.stray_pixels += 1;
        }
        self.actual[index] = [color[0], color[1], color[2]];
    }

    fn record(&mut self, index: usize, color: [f32; 4], expected: DVec3) {
        let actual = [color[0], color[1], color[2]];
        self.actual[index] = actual;
        self.expected[index] = expected.as_vec3().to_array();
        self.lit_pixels += 1;
        let error = (0..3)
            .map(|c| {
                let difference = f64::from(actual[c]) - expected[c];
                if difference.is_nan() {
                    f64::INFINITY
                } else {
                    difference.abs() / expected[c].abs().max(1.0)
                }
            })
            .fold(0.0, f64::max);
        if error > self.max_error || self.worst_pixel.is_none() {
            self.max_error = error;
            let (x, y) = (index as u32 % self.width, index as u32 / self.width);
            self.worst_pixel = Some((x, y, actual, expected));
        }
    }

    /// Asserts that every lit pixel is within `tolerance` (relative to `max(1, |expected|)`)
    /// and that some pixels were lit; writes actual, expected and difference PNGs under
    /// `target/render-tests/` when it fails.
    pub fn assert_within(&self, case: &str, tolerance: f64) {
        println!(
            "{case}: {} lit pixels ({} skipped), largest error {:.3e} (tolerance {tolerance:.1e}) at {:?}",
            self.lit_pixels, self.skipped_pixels, self.max_error, self.worst_pixel
        );
        let failed = self.lit_pixels == 0 || self.stray_pixels > 0 || self.max_error > tolerance;
        if failed {
            let directory = self.write_pngs(case);
            panic!(
                "{case}: largest error {:.3e} exceeds {tolerance:.1e}, or no lit pixels ({}), \
                 or {} pixels drawn outside every mesh; images in {}",
                self.max_error,
                self.lit_pixels,
                self.stray_pixels,
                directory.display()
            );
        }
    }

    fn write_pngs(&self, case: &str) -> PathBuf {
        // `CARGO_TARGET_TMPDIR` is set for tests; the benchmark example includes this file too.
        let directory = option_env!("CARGO_TARGET_TMPDIR")
            .and_then(|tmp| {
                PathBuf::from(tmp)
                    .parent()
                    .map(|target| target.join("render-tests"))
            })
            .unwrap_or_else(|| PathBuf::from("target/render-tests"));
        std::fs::create_dir_all(&directory).expect("create target/render-tests");
        let difference: Vec<[f32; 3]> = self
            .actual
            .iter()
            .zip(&self.expected)
            .map(|(a, e)| {
                let d = (0..3).map(|c| (a[c] - e[c]).abs()).fold(0.0, f32::max);
                // Scaled so that the tolerance band shows: 1e-3 is full white.
                [d * 1000.0; 3]
            })
            .collect();
        for (suffix, pixels) in [
            ("actual", &self.actual),
            ("expected", &self.expected),
            ("difference", &difference),
        ] {
            let path = directory.join(format!("{case}-{suffix}.png"));
            save_srgb_png(&path, self.width, self.height, pixels);
        }
        directory
    }
}

/// Writes linear RGB pixels as an 8-bit sRGB PNG.
pub fn save_srgb_png(path: &std::path::Path, width: u32, height: u32, pixels: &[[f32; 3]]) {
    let bytes: Vec<u8> = pixels
        .iter()
        .flat_map(|rgb| {
            let srgb = Color::linear_rgb(rgb[0], rgb[1], rgb[2]).to_srgba();
            [srgb.red, srgb.green, srgb.blue].map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
        })
        .collect();
    image::save_buffer(path, &bytes, width, height, image::ExtendedColorType::Rgb8)
        .expect("write PNG");
}
