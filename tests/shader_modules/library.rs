//! Every WGSL module a Phong shader imports, Bevy's included, collected without a GPU, and
//! composed the way Bevy's pipeline cache composes them.

use bevy::{
    app::PluginsState,
    asset::LoadState,
    log::LogPlugin,
    prelude::*,
    render::{
        RenderPlugin,
        settings::{WgpuLimits, WgpuSettings},
    },
    shader::{Shader, ShaderDefVal, ShaderImport, Source},
};
use bevy_phong::{PhongPlugin, SurfaceInputsPlugin};
use bevy_phong_headless::headless_plugins;
use naga_oil::compose::{
    ComposableModuleDescriptor, Composer, NagaModuleDescriptor, ShaderDefValue,
};
use std::{collections::HashMap, sync::OnceLock};

// The entry shaders: each has a fragment, vertex or compute stage of its own.

/// `PhongMaterial`'s fragment stage.
pub const PHONG_MATERIAL: &str = "embedded://bevy_phong/shaders/phong_material.wgsl";
/// `PhongMaterial`'s prepass fragment stage.
pub const PHONG_PREPASS: &str = "embedded://bevy_phong/shaders/phong_prepass.wgsl";
/// The shadow maps' vertex stage.
pub const SHADOW_CASTER: &str = "embedded://bevy_phong/shaders/shadow_caster.wgsl";
/// `SurfaceInputsMaterial`'s fragment stage.
pub const SURFACE_INPUTS: &str = "embedded://bevy_phong/shaders/surface_inputs.wgsl";
/// The searchlight example's fragment stage, an extension of `PhongMaterial`.
pub const SEARCHLIGHT: &str = "shaders/searchlight.wgsl";
/// The benchmark's constant-color floor.
pub const CONSTANT_COLOR: &str = "shaders/constant_color.wgsl";
/// The shader contract's kernel (`tests/gpu/contract/`), not an asset.
pub const CONTRACT_KERNEL: &str = "tests/gpu/contract/kernel.wgsl";
/// A displaced material's main pass vertex stage (an internal asset, at a fixed handle).
pub const PHONG_VERTEX: &str = "src/shaders/phong_vertex.wgsl";
/// A displaced material's prepass vertex stage (an internal asset, at a fixed handle).
pub const PHONG_PREPASS_VERTEX: &str = "src/shaders/phong_prepass_vertex.wgsl";

/// Frames to wait for the shaders to load before giving up (a frame takes a millisecond or
/// more).
const MAX_LOAD_FRAMES: u32 = 10_000;

/// The shaders the crate and Bevy register, by import path, and the entry shaders by path.
pub struct ShaderLibrary {
    modules: HashMap<String, Shader>,
    entries: HashMap<&'static str, Shader>,
}

/// The library, collected once per test binary.
pub fn library() -> &'static ShaderLibrary {
    static LIBRARY: OnceLock<ShaderLibrary> = OnceLock::new();
    LIBRARY.get_or_init(ShaderLibrary::collect)
}

impl ShaderLibrary {
    /// Builds an app with Bevy's default plugins and `PhongPlugin` but no render backend
    /// (`WgpuSettings::backends` `None`: no render world, no GPU): every plugin still
    /// registers its shader modules, as `load_shader_library!` does in `build` or `finish`.
    /// Then loads the entry shaders through the asset server and waits for all of them.
    fn collect() -> Self {
        let mut app = App::new();
        app.add_plugins(
            headless_plugins()
                .set(RenderPlugin {
                    render_creation: WgpuSettings {
                        backends: None,
                        ..default()
                    }
                    .into(),
                    ..default()
                })
                .disable::<LogPlugin>(),
        )
        .add_plugins((PhongPlugin, SurfaceInputsPlugin));
        while app.plugins_state() == PluginsState::Adding {
            bevy::tasks::tick_global_task_pools_on_main_thread();
        }
        app.finish();
        app.cleanup();

        let server = app.world().resource::<AssetServer>().clone();
        let handles: Vec<(&'static str, Handle<Shader>)> = [
            PHONG_MATERIAL,
            PHONG_PREPASS,
            SHADOW_CASTER,
            SURFACE_INPUTS,
            SEARCHLIGHT,
            CONSTANT_COLOR,
        ]
        .into_iter()
        .map(|path| (path, server.load(path)))
        .collect();
        // Entries that are no asset of a path: included as the crate includes them.
        let sources = [
            (CONTRACT_KERNEL, include_str!("../gpu/contract/kernel.wgsl")),
            (
                PHONG_VERTEX,
                include_str!("../../src/shaders/phong_vertex.wgsl"),
            ),
            (
                PHONG_PREPASS_VERTEX,
                include_str!("../../src/shaders/phong_prepass_vertex.wgsl"),
            ),
        ];
        let mut missing = Vec::new();
        for _ in 0..MAX_LOAD_FRAMES {
            app.update();
            let shaders = app.world().resource::<Assets<Shader>>();
            let mut entries: HashMap<&'static str, Shader> = sources
                .iter()
                .map(|&(path, source)| (path, Shader::from_wgsl(source, path)))
                .collect();
            for (path, handle) in &handles {
                if let LoadState::Failed(error) = server.load_state(handle) {
                    panic!("{path} did not load: {error}");
                }
                entries.extend(shaders.get(handle).map(|shader| (*path, shader.clone())));
            }
            let modules: HashMap<String, Shader> = shaders
                .iter()
                .filter_map(|(_, shader)| match &shader.import_path {
                    ShaderImport::Custom(path) => Some((path.clone(), shader.clone())),
                    ShaderImport::AssetPath(_) => None,
                })
                .collect();
            let library = Self { modules, entries };
            missing = library.missing_imports();
            if library.entries.len() == handles.len() + sources.len() && missing.is_empty() {
                return library;
            }
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
        panic!(
            "the shaders did not load within {MAX_LOAD_FRAMES} frames; imports no module \
             provides: {missing:?}"
        );
    }

    /// Imports of the entry shaders, direct or not, that no loaded module provides.
    fn missing_imports(&self) -> Vec<String> {
        let mut missing = Vec::new();
        let mut seen = std::collections::HashSet::new();
        let mut pending: Vec<&ShaderImport> = self
            .entries
            .values()
            .flat_map(|shader| &shader.imports)
            .collect();
        while let Some(import) = pending.pop() {
            let name = import.module_name().into_owned();
            if !seen.insert(name.clone()) {
                continue;
            }
            match self.modules.get(&name) {
                Some(module) => pending.extend(&module.imports),
                None => missing.push(name),
            }
        }
        missing
    }

    /// A composer, validating as Bevy's is in debug builds, that holds every module the
    /// shader `path` (see [`Self::shader`]) imports, directly or not.
    pub fn composer_for(&self, path: &str) -> Composer {
        let mut composer = Composer::default().with_capabilities(capabilities());
        for import in &self.shader(path).imports {
            self.add_module(&mut composer, import);
        }
        composer
    }

    fn add_module(&self, composer: &mut Composer, import: &ShaderImport) {
        let name = import.module_name();
        if composer.contains_module(&name) {
            return;
        }
        let shader = &self.modules[name.as_str()];
        for import in &shader.imports {
            self.add_module(composer, import);
        }
        if let Err(error) = composer.add_composable_module(ComposableModuleDescriptor::from(shader))
        {
            panic!("{}", error.emit_to_string(composer));
        }
    }

    /// The entry shader at `path`, or the module with that import path.
    pub fn shader(&self, path: &str) -> &Shader {
        self.entries
            .get(path)
            .or_else(|| self.modules.get(path))
            .unwrap_or_else(|| panic!("no shader {path}"))
    }

    /// The import paths of the crate's own modules (`bevy_phong::…`).
    pub fn crate_modules(&self) -> Vec<&str> {
        let mut names: Vec<&str> = self
            .modules
            .keys()
            .map(String::as_str)
            .filter(|name| name.starts_with("bevy_phong::"))
            .collect();
        names.sort_unstable();
        names
    }

    /// `path` (an entry shader or a module) composed alone with `defs`: a module's own items
    /// keep their names.
    pub fn module(&self, path: &str, defs: &[ShaderDefVal]) -> naga::Module {
        self.compose(&mut self.composer_for(path), path, defs)
            .unwrap_or_else(|error| panic!("{error}"))
    }

    /// The shader `path` (see [`Self::shader`]) composed with `defs` (and the defs Bevy's
    /// pipeline cache adds to every shader) by `composer` (from [`Self::composer_for`]), then
    /// validated by naga's validator with every check on; the error, printed with its source,
    /// if either fails. A module composed this way keeps all its items, used or not.
    pub fn compose(
        &self,
        composer: &mut Composer,
        path: &str,
        defs: &[ShaderDefVal],
    ) -> Result<naga::Module, String> {
        let shader = self.shader(path);
        let Source::Wgsl(source) = &shader.source else {
            panic!("{path} is WGSL");
        };
        let shader_defs = global_defs()
            .iter()
            .chain(defs)
            .chain(&shader.shader_defs)
            .map(naga_def)
            .collect();
        let module = composer
            .make_naga_module(NagaModuleDescriptor {
                source,
                file_path: path,
                shader_defs,
                ..default()
            })
            .map_err(|error| error.emit_to_string(composer))?;
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), capabilities())
            .validate(&module)
            .map_err(|error| format!("{path}: {error:?}"))?;
        Ok(module)
    }
}

/// What the validator may assume of the device: naga's defaults (multisampled shading, cube
/// map arrays) and binding arrays of textures, which Bevy's view declares only where the
/// device has them (its `MULTIPLE_LIGHT_PROBES_IN_ARRAY`, for `EnvironmentMapLight`s).
fn capabilities() -> naga::valid::Capabilities {
    naga::valid::Capabilities::default()
        | naga::valid::Capabilities::TEXTURE_AND_SAMPLER_BINDING_ARRAY
}

/// The defs Bevy's pipeline cache adds to every shader: storage buffer bindings as wgpu's
/// default limits give (a device with storage buffers).
fn global_defs() -> Vec<ShaderDefVal> {
    vec![ShaderDefVal::UInt(
        "AVAILABLE_STORAGE_BUFFER_BINDINGS".into(),
        WgpuLimits::default().max_storage_buffers_per_shader_stage,
    )]
}

fn naga_def(def: &ShaderDefVal) -> (String, ShaderDefValue) {
    match def.clone() {
        ShaderDefVal::Bool(name, value) => (name, ShaderDefValue::Bool(value)),
        ShaderDefVal::Int(name, value) => (name, ShaderDefValue::Int(value)),
        ShaderDefVal::UInt(name, value) => (name, ShaderDefValue::UInt(value)),
    }
}
