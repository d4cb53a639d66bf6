//! Every WESL module a Phong shader imports, Bevy's included, collected without a GPU, and
//! composed the way Bevy's pipeline cache composes them (`wesl::compile`, as in bevy_shader
//! 0.20.1's `ShaderCache::get`).

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
use bevy_phong::{PhongPlugin, testing::SurfaceInputsPlugin};
use bevy_phong_headless::headless_plugins;
use std::{
    borrow::Cow,
    cell::RefCell,
    collections::{BTreeMap, HashMap, HashSet},
    sync::OnceLock,
};
use wesl::{
    error::ResolveError,
    syntax::{ModulePath, PathOrigin},
};

// The entry shaders: each has a fragment, vertex or compute stage of its own.

/// `PhongMaterial`'s fragment stage.
pub const PHONG_MATERIAL: &str = "embedded://bevy_phong/shaders/phong_material.wesl";
/// `PhongMaterial`'s prepass fragment stage.
pub const PHONG_PREPASS: &str = "embedded://bevy_phong/shaders/phong_prepass.wesl";
/// The shadow maps' vertex stage.
pub const SHADOW_CASTER: &str = "embedded://bevy_phong/shaders/shadow_caster.wesl";
/// `SurfaceInputsMaterial`'s fragment stage.
pub const SURFACE_INPUTS: &str = "embedded://bevy_phong/shaders/surface_inputs.wesl";
/// The searchlight example's fragment stage, an extension of `PhongMaterial`.
pub const SEARCHLIGHT: &str = "shaders/searchlight.wesl";
/// The benchmark's constant-color floor.
pub const CONSTANT_COLOR: &str = "shaders/constant_color.wesl";
/// The shader contract's kernel (`tests/gpu/contract/`), not an asset.
pub const CONTRACT_KERNEL: &str = "tests/gpu/contract/kernel.wesl";
/// A displaced material's main pass vertex stage (an internal asset, at a fixed handle).
pub const PHONG_VERTEX: &str = "src/shaders/phong_vertex.wesl";
/// A displaced material's prepass vertex stage (an internal asset, at a fixed handle).
pub const PHONG_PREPASS_VERTEX: &str = "src/shaders/phong_prepass_vertex.wesl";

/// Frames to wait for the shaders to load before giving up (a frame takes a millisecond or
/// more).
const MAX_LOAD_FRAMES: u32 = 10_000;

/// The shaders the crate and Bevy register, by import path, and the entry shaders by path.
pub struct ShaderLibrary {
    /// Every WESL shader importable as Bevy's shader cache makes it (its `import_path`), by
    /// [`import_name`]: `bevy_phong::shaders::types`, or `/shaders/searchlight` for one at an
    /// asset path. The entry shaders are among them.
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
            (CONTRACT_KERNEL, include_str!("../gpu/contract/kernel.wesl")),
            (
                PHONG_VERTEX,
                include_str!("../../src/shaders/phong_vertex.wesl"),
            ),
            (
                PHONG_PREPASS_VERTEX,
                include_str!("../../src/shaders/phong_prepass_vertex.wesl"),
            ),
        ];
        let mut missing = Vec::new();
        for _ in 0..MAX_LOAD_FRAMES {
            app.update();
            let shaders = app.world().resource::<Assets<Shader>>();
            let mut entries: HashMap<&'static str, Shader> = sources
                .iter()
                .map(|&(path, source)| (path, Shader::from_wesl(source, path)))
                .collect();
            for (path, handle) in &handles {
                if let LoadState::Failed(error) = server.load_state(handle) {
                    panic!("{path} did not load: {error}");
                }
                entries.extend(shaders.get(handle).map(|shader| (*path, shader.clone())));
            }
            // As Bevy's shader cache, which registers WESL shaders only at a module path.
            let modules: HashMap<String, Shader> = shaders
                .iter()
                .map(|(_, shader)| shader)
                .chain(entries.values())
                .filter(|shader| matches!(shader.source, Source::Wesl(_)))
                .map(|shader| (import_name(&shader.import_path), shader.clone()))
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

    /// Imports of the entry shaders, direct or not, that no loaded module provides. Bevy lists
    /// each imported item both as a module and as an item of its module (`a::b::item` gives
    /// `a::b` and `a::b::item`), so an import is provided where it names a module, an item of
    /// one, or the package or folder of some module (`a::b` in `import a::b::{c::item}`).
    fn missing_imports(&self) -> Vec<String> {
        let mut missing = Vec::new();
        let mut seen = HashSet::new();
        let mut pending: Vec<&ShaderImport> = self
            .entries
            .values()
            .flat_map(|shader| &shader.imports)
            .collect();
        while let Some(import) = pending.pop() {
            let name = import_name(import);
            if !seen.insert(name.clone()) {
                continue;
            }
            if let Some(module) = self.modules.get(&name) {
                pending.extend(&module.imports);
                continue;
            }
            let item_of_module = name
                .rsplit_once(if name.starts_with('/') { "/" } else { "::" })
                .is_some_and(|(parent, _)| self.modules.contains_key(parent));
            let folder = format!("{name}{}", if name.starts_with('/') { "/" } else { "::" });
            let folder_of_module = self
                .modules
                .keys()
                .any(|module| module.starts_with(&folder));
            if !item_of_module && !folder_of_module {
                missing.push(name);
            }
        }
        missing
    }

    /// The entry shader at `path`, or the module with that import path.
    pub fn shader(&self, path: &str) -> &Shader {
        self.entries
            .get(path)
            .or_else(|| self.modules.get(path))
            .unwrap_or_else(|| panic!("no shader {path}"))
    }

    /// The import paths of the crate's own modules (`bevy_phong::shaders::…`): the libraries
    /// the entry shaders import, not the entry shaders that Bevy 0.20 registers at an import
    /// path too (`embedded://` assets, the displaced vertex stages' internal assets).
    pub fn crate_modules(&self) -> Vec<&str> {
        let mut names: Vec<&str> = self
            .modules
            .iter()
            .filter(|(name, module)| {
                name.starts_with("bevy_phong::")
                    && !self
                        .entries
                        .values()
                        .any(|entry| entry.source.as_str() == module.source.as_str())
            })
            .map(|(name, _)| name.as_str())
            .collect();
        names.sort_unstable();
        names
    }

    /// `path` (an entry shader or a module) composed alone with `defs`: a module's own items
    /// keep their names.
    pub fn module(&self, path: &str, defs: &[ShaderDefVal]) -> naga::Module {
        self.compose(path, defs)
            .unwrap_or_else(|error| panic!("{error}"))
    }

    /// The shader `path` (see [`Self::shader`]) composed with `defs` (and the defs Bevy's
    /// pipeline cache adds to every shader) by `wesl::compile` with Bevy's options, then
    /// parsed and validated by naga's validator with every check on; the error, printed with
    /// its source, if any step fails. An entry shader keeps all its own items, used or not
    /// (where Bevy keeps those its entry points reach), and of its imports the items it uses;
    /// a module composed alone keeps all its items and those of every module it reaches
    /// (`strip: false`). The root's items keep their names (WESL mangles only the imports').
    pub fn compose(&self, path: &str, defs: &[ShaderDefVal]) -> Result<naga::Module, String> {
        let shader = self.shader(path);
        let Source::Wesl(_) = &shader.source else {
            panic!("{path} is WESL");
        };
        let alone = !self.entries.contains_key(path);
        // Bevy gathers the defs of the modules a shader imports by its import statements
        // (`Shader::imports`). A module composed alone keeps every item of every module it
        // reaches, also of those only a path in code names (Bevy's `forward_io` calls
        // `package::render::mesh_functions::…`, whose imports bring the mesh view types and
        // their defs): it gets the defs of every module its composition loads, as an entry
        // shader would that used all of them.
        let mut reached = Vec::new();
        loop {
            let (wgsl, loaded) = self.compile(shader, alone, defs, &reached);
            let imported = self.imported_modules(shader, &reached);
            let unseen: Vec<String> = loaded
                .into_iter()
                .filter(|name| self.modules.contains_key(name) && !imported.contains(name))
                .collect();
            if alone && !unseen.is_empty() {
                reached.extend(unseen);
                continue;
            }
            let wgsl = wgsl.map_err(|error| format!("{path}: {error}"))?;
            let module = naga::front::wgsl::parse_str(&wgsl)
                .map_err(|error| format!("{path}: {}", error.emit_to_string(&wgsl)))?;
            naga::valid::Validator::new(naga::valid::ValidationFlags::all(), capabilities())
                .validate(&module)
                .map_err(|error| format!("{path}: {}", error.emit_to_string(&wgsl)))?;
            return Ok(module);
        }
    }

    /// `shader` compiled to WGSL (see [`Self::compose`]), with the defs of the modules it
    /// imports and of the modules `reached`; and the modules the composition loaded.
    fn compile(
        &self,
        shader: &Shader,
        alone: bool,
        defs: &[ShaderDefVal],
        reached: &[String],
    ) -> (Result<String, String>, Vec<String>) {
        let mut options = wesl::CompileOptions {
            imports: true,
            condcomp: true,
            visibility: false,
            strip: !alone,
            keep_main: true,
            ..default()
        };
        // As `ShaderCache::get`: the defs of the modules the shader imports (directly or not),
        // then the pipeline cache's global defs and the pipeline's, then the shader's own; a
        // later def of a name replaces an earlier one. Bool defs are flags, Int and UInt defs
        // constants of the virtual module `constants` that also set a flag.
        let global = global_defs();
        let mut constants = BTreeMap::new();
        for def in self
            .imported_modules(shader, reached)
            .iter()
            .filter(|&name| *name != import_name(&shader.import_path))
            .flat_map(|name| &self.modules[name].shader_defs)
            .chain(&global)
            .chain(defs)
            .chain(&shader.shader_defs)
        {
            match def {
                ShaderDefVal::Bool(name, value) => {
                    options
                        .features
                        .flags
                        .insert(name.to_string(), (*value).into());
                }
                ShaderDefVal::Int(name, value) => {
                    options.features.flags.insert(name.to_string(), true.into());
                    constants.insert(name.as_ref(), value.to_string());
                }
                ShaderDefVal::UInt(name, value) => {
                    options.features.flags.insert(name.to_string(), true.into());
                    constants.insert(name.as_ref(), value.to_string());
                }
            }
        }
        let resolver = LibraryResolver {
            library: self,
            constants: constants
                .iter()
                .map(|(name, value)| format!("const {name} = {value};\n"))
                .collect(),
            loaded: RefCell::default(),
        };
        let wgsl = wesl::compile(&module_path(&shader.import_path), &options, &resolver)
            .map(|compiled| compiled.to_string())
            .map_err(|error| error.diagnostic().render_plain());
        (wgsl, resolver.loaded.into_inner())
    }

    /// The modules `shader` imports, directly or not, itself first, in the order Bevy's shader
    /// cache gathers their defs (`ShaderCache::get`: Bevy's mesh view types bring their array
    /// sizes this way); then those `reached` and the modules they import.
    fn imported_modules(&self, shader: &Shader, reached: &[String]) -> Vec<String> {
        let mut modules = Vec::new();
        let mut visited = HashSet::new();
        let mut to_visit: Vec<String> = reached.iter().rev().cloned().collect();
        to_visit.push(import_name(&shader.import_path));
        while let Some(name) = to_visit.pop() {
            if !visited.insert(name.clone()) {
                continue;
            }
            let module = match self.modules.get(&name) {
                Some(module) => module,
                None if modules.is_empty() => shader,
                None => continue,
            };
            for import in &module.imports {
                let import = import_name(import);
                if self.modules.contains_key(&import) {
                    to_visit.push(import);
                }
            }
            modules.push(name);
        }
        modules
    }
}

/// Bevy's `ShaderResolver` over the library: every module at its import path, and the virtual
/// module `constants`.
struct LibraryResolver<'a> {
    library: &'a ShaderLibrary,
    constants: String,
    /// The modules the composition loaded, by [`module_name`].
    loaded: RefCell<Vec<String>>,
}

impl wesl::Resolver for LibraryResolver<'_> {
    fn resolve_source(&self, path: &ModulePath) -> Result<Cow<'_, str>, ResolveError> {
        let path = self.canonical_path(path);
        if path.origin == PathOrigin::Package("constants".into()) && path.components.is_empty() {
            return Ok(Cow::Borrowed(&self.constants));
        }
        let name = module_name(&path);
        let shader = self.library.modules.get(&name);
        self.loaded.borrow_mut().push(name);
        shader
            .map(|shader| Cow::Borrowed(shader.source.as_str()))
            .ok_or_else(|| {
                ResolveError::ModuleNotFound(
                    path.clone(),
                    "no shader registered for this module path".into(),
                )
            })
    }

    /// A package named by a path (`a/b`) is its last component, as Bevy's resolver has it.
    fn canonical_path(&self, path: &ModulePath) -> ModulePath {
        match &path.origin {
            PathOrigin::Package(package) if package.contains('/') => ModulePath {
                origin: PathOrigin::Package(package.rsplit('/').next().unwrap().to_string()),
                components: path.components.clone(),
            },
            _ => path.clone(),
        }
    }

    fn display_name(&self, path: &ModulePath) -> Option<String> {
        let shader = self
            .library
            .modules
            .get(&module_name(&self.canonical_path(path)))?;
        Some(shader.path.clone())
    }
}

/// The WESL module path of a shader's import path, as Bevy's `wesl_module_path` makes it:
/// `bevy_phong::shaders::types` is in package `bevy_phong`, an asset path absolute.
fn module_path(import: &ShaderImport) -> ModulePath {
    let split = |name: &str, separator: &str| -> Vec<String> {
        name.split(separator)
            .filter(|component| !component.is_empty())
            .map(str::to_string)
            .collect()
    };
    match import {
        ShaderImport::Custom(name) => {
            let mut components = split(name, "::");
            let package = components.remove(0);
            ModulePath {
                origin: PathOrigin::Package(package),
                components,
            }
        }
        ShaderImport::AssetPath(path) => ModulePath {
            origin: PathOrigin::Absolute,
            components: split(path, "/"),
        },
    }
}

/// A module path as one string, the library's key: `package::a::b`, or `/a/b` for an absolute
/// one.
fn module_name(path: &ModulePath) -> String {
    match &path.origin {
        PathOrigin::Package(package) => std::iter::once(package.as_str())
            .chain(path.components.iter().map(String::as_str))
            .collect::<Vec<_>>()
            .join("::"),
        PathOrigin::Absolute => format!("/{}", path.components.join("/")),
        PathOrigin::Relative(_) => panic!("a relative module path: {path}"),
    }
}

/// The library's key of an import path.
fn import_name(import: &ShaderImport) -> String {
    module_name(&module_path(import))
}

/// What the validator may assume of the device: naga's defaults (multisampled shading, cube
/// map arrays) and binding arrays of textures, which Bevy's view declares only where the
/// device has them (its `MULTIPLE_LIGHT_PROBES_IN_ARRAY`, for `EnvironmentMapLight`s).
fn capabilities() -> naga::valid::Capabilities {
    naga::valid::Capabilities::default()
        | naga::valid::Capabilities::TEXTURE_AND_SAMPLER_BINDING_ARRAY
}

/// The defs a device with `storage_buffers` storage buffers per shader stage gives a Phong
/// pipeline: Bevy's pipeline cache adds the count and the comparisons WESL flags cannot make,
/// baked in (`PipelineCache::new`); every Phong pipeline adds the crate's flag
/// `PHONG_STORAGE_BUFFERS` for the layout such a device gets
/// (`scene_variants::add_scene_data_flag`): the scene data in storage buffers from
/// `PhongSceneBindings::STORAGE_BUFFERS_NEEDED` on, else in the data texture.
pub fn device_defs(storage_buffers: u32) -> Vec<ShaderDefVal> {
    vec![
        ShaderDefVal::UInt("AVAILABLE_STORAGE_BUFFER_BINDINGS".into(), storage_buffers),
        ShaderDefVal::Bool(
            "AVAILABLE_STORAGE_BUFFER_BINDINGS__GE_3".into(),
            storage_buffers >= 3,
        ),
        ShaderDefVal::Bool(
            "AVAILABLE_STORAGE_BUFFER_BINDINGS__GE_6".into(),
            storage_buffers >= 6,
        ),
        ShaderDefVal::Bool(
            "PHONG_STORAGE_BUFFERS".into(),
            storage_buffers >= bevy_phong::PhongSceneBindings::STORAGE_BUFFERS_NEEDED,
        ),
    ]
}

/// The defs every shader is composed with unless a test names a device: those of a device
/// with wgpu's default limits ([`device_defs`]).
fn global_defs() -> Vec<ShaderDefVal> {
    device_defs(WgpuLimits::default().max_storage_buffers_per_shader_stage)
}
