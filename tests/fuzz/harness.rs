//! Loads generated files through Bevy's asset server in an app without a renderer, spawns
//! the scenes that load, and checks what came of each: an error that says where, or lights
//! and materials whose every float is finite.

use crate::cases::{CANARY_SHININESS, Case, Kind, write_asset_folder};
use bevy::{
    asset::{AssetPlugin, LoadState, UntypedAssetId},
    camera::visibility::VisibilitySystems,
    image::Image,
    mesh::Mesh,
    prelude::*,
    transform::TransformPlugin,
};
use bevy_phong::{
    PhongMaterial, PhongPlugin,
    scene::{PhongScene, PhongSceneRoot},
    testing::{PhongLightBuffer, PhongMaterialUniform},
};
use std::{
    collections::BTreeMap,
    path::{Path, PathBuf},
    sync::{
        Mutex,
        atomic::{AtomicUsize, Ordering},
    },
    time::{Duration, Instant},
};

/// How long a batch may take to load before its unfinished files count as hung.
const BATCH_TIMEOUT: Duration = Duration::from_secs(60);

/// Panics seen by the hook [`count_panics`] installs, on any thread (Bevy catches a
/// loader's panic and turns it into a load error; the hook still sees it).
static PANICS: AtomicUsize = AtomicUsize::new(0);
static PANIC_MESSAGES: Mutex<Vec<String>> = Mutex::new(Vec::new());

/// Counts every panic from now on, keeping (and printing, as usual) the first ten.
pub fn count_panics() {
    let print = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        PANICS.fetch_add(1, Ordering::SeqCst);
        let mut messages = PANIC_MESSAGES.lock().unwrap_or_else(|e| e.into_inner());
        if messages.len() < 10 {
            messages.push(info.to_string());
            print(info);
        }
    }));
}

/// The panics counted so far and their first messages.
pub fn panics() -> (usize, Vec<String>) {
    let messages = PANIC_MESSAGES.lock().unwrap_or_else(|e| e.into_inner());
    (PANICS.load(Ordering::SeqCst), messages.clone())
}

/// What the cases came to.
#[derive(Debug, Default)]
pub struct Counts {
    /// Files generated.
    pub inputs: usize,
    /// Per generator: files, loaded, rejected.
    pub by_generator: BTreeMap<&'static str, [usize; 3]>,
    /// Files that loaded (scenes were spawned).
    pub loaded: usize,
    /// Files refused with an error.
    pub rejected: usize,
    /// Refusals whose error names neither a line and column nor a field.
    pub rejected_without_place: Vec<String>,
    /// Files still loading when their batch timed out.
    pub hung: Vec<String>,
    /// Non-finite floats in the light buffer or a material uniform.
    pub non_finite_floats: usize,
    /// Where non-finite floats were found.
    pub non_finite_examples: Vec<String>,
    /// Times a material with the canary's values appeared.
    pub canary_reads: usize,
}

/// Bevy's visibility propagation for the scene's entities (its plugin needs a renderer);
/// a hidden root hides nothing here, which the fuzzer does not need.
fn propagate_visibility(mut entities: Query<(&Visibility, &mut InheritedVisibility)>) {
    for (visibility, mut inherited) in &mut entities {
        let visible = if *visibility == Visibility::Hidden {
            InheritedVisibility::HIDDEN
        } else {
            InheritedVisibility::VISIBLE
        };
        inherited.set_if_neq(visible);
    }
}

/// An app under `MinimalPlugins` whose asset folder holds the generated files.
pub struct Harness {
    app: App,
    assets: PathBuf,
}

impl Harness {
    /// An app whose asset folder is `root/assets` ([`write_asset_folder`]), with the
    /// canary's absolute path.
    pub fn new(root: &Path) -> (Self, String) {
        let (assets, canary) = write_asset_folder(root);
        let mut app = App::new();
        app.add_plugins((
            MinimalPlugins,
            AssetPlugin {
                file_path: assets.to_string_lossy().into_owned(),
                // The cases are written and removed while earlier ones load: with the
                // file watcher on, Bevy would reload files whose handles were just dropped.
                watch_for_changes_override: Some(false),
                ..default()
            },
            TransformPlugin,
            PhongPlugin,
        ))
        .init_asset::<Mesh>()
        .init_asset::<Image>()
        .add_systems(
            PostUpdate,
            propagate_visibility.in_set(VisibilitySystems::VisibilityPropagate),
        );
        app.update();
        (Self { app, assets }, canary)
    }

    /// Writes, loads and (scenes) spawns every case of `batch`, then checks the light buffer
    /// and every material; adds what happened to `counts`.
    pub fn run_batch(&mut self, batch: &[Case], counts: &mut Counts) {
        for case in batch {
            std::fs::write(self.assets.join(case.kind.path(case.index)), &case.bytes).unwrap();
        }
        let server = self.app.world().resource::<AssetServer>().clone();
        let handles: Vec<(UntypedHandle, &Case)> = batch
            .iter()
            .map(|case| {
                let path = case.kind.path(case.index);
                let handle = match case.kind {
                    Kind::Scene => server.load::<PhongScene>(path).untyped(),
                    Kind::Material => server.load::<PhongMaterial>(path).untyped(),
                };
                (handle, case)
            })
            .collect();
        counts.inputs += batch.len();

        let settled = |server: &AssetServer, id: UntypedAssetId| {
            let own = server.load_state(id);
            let dependencies = server.recursive_dependency_load_state(id);
            own.is_failed() || (own.is_loaded() && !dependencies.is_loading())
        };
        let start = Instant::now();
        while start.elapsed() < BATCH_TIMEOUT
            && !handles
                .iter()
                .all(|(handle, _)| settled(&server, handle.id()))
        {
            self.app.update();
            std::thread::sleep(Duration::from_micros(200));
        }

        let mut roots = Vec::new();
        for (handle, case) in &handles {
            let of_generator = counts.by_generator.entry(case.generator).or_default();
            of_generator[0] += 1;
            match server.load_state(handle.id()) {
                LoadState::Loaded => {
                    of_generator[1] += 1;
                    counts.loaded += 1;
                    if case.kind == Kind::Scene {
                        let scene = handle.clone().typed::<PhongScene>();
                        roots.push(self.app.world_mut().spawn(PhongSceneRoot(scene)).id());
                    }
                }
                LoadState::Failed(error) => {
                    of_generator[2] += 1;
                    counts.rejected += 1;
                    let error = error.to_string();
                    if !names_a_place(&error, &case.kind.path(case.index)) {
                        counts.rejected_without_place.push(describe(case, &error));
                    }
                }
                _ => counts.hung.push(describe(case, "still loading")),
            }
        }
        // Spawn (PreUpdate), validate and gather (PostUpdate); once more for materials
        // whose `Added` event arrives at the end of a frame.
        for _ in 0..3 {
            self.app.update();
        }
        self.check_floats(batch, counts);

        for root in roots {
            self.app.world_mut().entity_mut(root).despawn();
        }
        drop(handles);
        self.app.update();
        for case in batch {
            let _ = std::fs::remove_file(self.assets.join(case.kind.path(case.index)));
        }
    }

    /// Counts the non-finite floats in the light buffer and the material uniforms, and the
    /// materials with the canary's values.
    fn check_floats(&mut self, batch: &[Case], counts: &mut Counts) {
        let world = self.app.world();
        let buffer = world.resource::<PhongLightBuffer>();
        let floats = buffer
            .records()
            .iter()
            .flat_map(|record| bytemuck::cast::<_, [f32; 20]>(*record))
            .chain(buffer.header().ambient);
        let bad_lights = floats.filter(|f| !f.is_finite()).count();
        let materials = world.resource::<Assets<PhongMaterial>>();
        let mut bad_materials = 0;
        for (_, material) in materials.iter() {
            let uniform = PhongMaterialUniform::from(material);
            let floats = uniform
                .base_color
                .to_array()
                .into_iter()
                .chain(uniform.specular.to_array())
                .chain(uniform.emissive.to_array())
                .chain([
                    uniform.shininess,
                    uniform.ambient_factor,
                    uniform.alpha_cutoff,
                ]);
            bad_materials += floats.filter(|f| !f.is_finite()).count();
            if material.shininess == CANARY_SHININESS {
                counts.canary_reads += 1;
            }
        }
        if bad_lights + bad_materials > 0 {
            counts.non_finite_floats += bad_lights + bad_materials;
            let cases: Vec<_> = batch.iter().map(|case| case.index).collect();
            counts.non_finite_examples.push(format!(
                "{bad_lights} in lights, {bad_materials} in materials, batch {cases:?}"
            ));
        }
    }
}

/// Whether `error` says where in the file at `path` the problem is: `path:line:column:` or
/// `path: field: ` (the field one word, as `objects[0].mesh`).
pub fn names_a_place(error: &str, path: &str) -> bool {
    error.match_indices(path).any(|(at, _)| {
        let rest = &error[at + path.len()..];
        if let Some(position) = rest.strip_prefix(':') {
            let mut parts = position.splitn(3, ':');
            let number = |part: Option<&str>| {
                part.is_some_and(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
            };
            if number(parts.next()) && number(parts.next()) {
                return true;
            }
        }
        rest.strip_prefix(": ").is_some_and(|after| {
            after
                .split_once(": ")
                .is_some_and(|(field, _)| !field.is_empty() && !field.contains(' '))
        })
    })
}

fn describe(case: &Case, what: &str) -> String {
    let text = String::from_utf8_lossy(&case.bytes);
    let start: String = text.chars().take(300).collect();
    let what: String = what.chars().take(600).collect();
    format!(
        "case {} ({}, {}): {what}\n  file starts: {start}",
        case.index,
        case.generator,
        case.kind.path(case.index)
    )
}
