//! What every example shares: a window where a display exists, else (or with
//! `--headless PATH`) a render to a PNG file and exit; with `--compare`, the scene compared
//! with the reference model (with `--headless PATH` too, the picture is written first, in
//! the same run); in a browser (wasm32), a canvas.

#[cfg(not(target_arch = "wasm32"))]
mod compare;
#[cfg(not(target_arch = "wasm32"))]
mod headless;
mod ready;
#[cfg(target_arch = "wasm32")]
mod web;

use bevy::{app::PluginGroupBuilder, core_pipeline::tonemapping::Tonemapping, prelude::*};
#[cfg(not(target_arch = "wasm32"))]
use std::path::PathBuf;

/// Size of the picture: the PNG written in headless mode, the canvas in a browser.
const PICTURE_SIZE: UVec2 = UVec2::new(960, 540);
/// Frames drawn after every pipeline is ready, before the one that is saved (headless) or
/// before the page is told the app has drawn (browser).
const SETTLE_FRAMES: u32 = 3;

/// How an example runs.
#[derive(Clone, Debug, Resource)]
pub enum RunMode {
    /// In a window.
    #[cfg(not(target_arch = "wasm32"))]
    Windowed,
    /// Render one frame into a PNG at this path, then exit.
    #[cfg(not(target_arch = "wasm32"))]
    Headless(PathBuf),
    /// Render the scene into a float image, compare it with the reference model, then exit
    /// (with an error where they differ). With a path, the example's own view is first
    /// written there as a PNG, as [`RunMode::Headless`] writes it.
    #[cfg(not(target_arch = "wasm32"))]
    Compare(Option<PathBuf>),
    /// In a browser, on the page's `<canvas id="bevy">`.
    #[cfg(target_arch = "wasm32")]
    Canvas,
}

impl RunMode {
    /// In a browser, the canvas.
    #[cfg(target_arch = "wasm32")]
    pub fn from_args(_name: &str) -> Self {
        RunMode::Canvas
    }

    /// The mode the command line asks for ([`command_line`]).
    #[cfg(not(target_arch = "wasm32"))]
    pub fn from_args(name: &str) -> Self {
        command_line::<NoMoreOptions>(name).0
    }

    /// `--headless [PATH]` renders to PATH (by default `target/NAME.png`); `--compare`
    /// compares with the reference model (after writing PATH, where both are given);
    /// without a display (no `DISPLAY` or `WAYLAND_DISPLAY`) it renders to
    /// `target/NAME.png`; otherwise it opens a window.
    #[cfg(not(target_arch = "wasm32"))]
    fn from_example_args(name: &str, args: ExampleArgs) -> Self {
        let headless = args
            .headless
            .map(|path| path.unwrap_or_else(|| default_png(name)));
        if args.compare {
            return RunMode::Compare(headless);
        }
        if let Some(path) = headless {
            return RunMode::Headless(path);
        }
        let has_display = ["DISPLAY", "WAYLAND_DISPLAY"]
            .iter()
            .any(|var| std::env::var_os(var).is_some_and(|v| !v.is_empty()));
        if has_display {
            RunMode::Windowed
        } else {
            let path = default_png(name);
            println!("no display found: rendering to {}", path.display());
            RunMode::Headless(path)
        }
    }
}

/// The options every example takes natively.
#[cfg(not(target_arch = "wasm32"))]
#[derive(clap::Args)]
struct ExampleArgs {
    /// Render one frame headless into PATH (by default target/NAME.png), then exit.
    #[arg(long, value_name = "PATH")]
    headless: Option<Option<PathBuf>>,
    /// Compare the scene with the reference model pixel by pixel, then exit (failing where
    /// they differ); with --headless, the picture is written first.
    #[arg(long)]
    compare: bool,
}

/// An example without options of its own.
#[cfg(not(target_arch = "wasm32"))]
#[derive(clap::Args)]
pub struct NoMoreOptions {}

/// The example `name`'s command line: the options every example takes, and its own
/// (`More`). `--help` lists both; an unknown option ends the process with a usage message.
#[cfg(not(target_arch = "wasm32"))]
pub fn command_line<More: clap::Args + clap::FromArgMatches>(name: &str) -> (RunMode, More) {
    use clap::{Args as _, FromArgMatches as _};
    // The about line is set last: each `Args` derive sets its own doc comment as one.
    let matches = More::augment_args(ExampleArgs::augment_args(clap::Command::new(
        name.to_owned(),
    )))
    .about(format!(
        "The bevy_phong example {name}: in a window where a display exists, else rendered \
             headless to a PNG file"
    ))
    .override_usage(format!("cargo run --example {name} -- [OPTIONS]"))
    .get_matches();
    let parsed = ExampleArgs::from_arg_matches(&matches)
        .and_then(|args| Ok((args, More::from_arg_matches(&matches)?)));
    let (args, more) = parsed.unwrap_or_else(|error| error.exit());
    (RunMode::from_example_args(name, args), more)
}

#[cfg(not(target_arch = "wasm32"))]
fn default_png(name: &str) -> PathBuf {
    PathBuf::from("target").join(format!("{name}.png"))
}

/// The render target of the saved picture: [`PICTURE_SIZE`], sRGB, readable back.
#[cfg(not(target_arch = "wasm32"))]
fn picture_target() -> Image {
    use bevy::render::render_resource::{TextureFormat, TextureUsages};
    let mut image = Image::new_target_texture(
        PICTURE_SIZE.x,
        PICTURE_SIZE.y,
        TextureFormat::Rgba8UnormSrgb,
        None,
    );
    image.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    image
}

/// Writes the picture's RGBA bytes (rows unpadded) to `path` as a PNG, making its folder.
#[cfg(not(target_arch = "wasm32"))]
fn save_picture(path: &std::path::Path, pixels: &[u8]) -> Result<(), String> {
    if let Some(parent) = path.parent() {
        let _ = std::fs::create_dir_all(parent);
    }
    image::save_buffer(
        path,
        pixels,
        PICTURE_SIZE.x,
        PICTURE_SIZE.y,
        image::ExtendedColorType::Rgba8,
    )
    .map_err(|error| format!("cannot write {}: {error}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

/// An app with Bevy's default plugins set up for `mode`: a titled window, no window and
/// a loop that renders until the PNG is written, or the page's canvas.
#[allow(
    dead_code,
    reason = "the examples that set plugin options use example_app_with"
)]
pub fn example_app(name: &str) -> App {
    example_app_with(name, |plugins| plugins)
}

/// [`example_app`] with Bevy's default plugins changed by `configure` (to set a plugin's
/// options, say).
pub fn example_app_with(
    name: &str,
    configure: impl FnOnce(PluginGroupBuilder) -> PluginGroupBuilder,
) -> App {
    example_app_in(RunMode::from_args(name), name, configure)
}

/// [`example_app_with`] in `mode` (from an example's own [`command_line`]).
pub fn example_app_in(
    mode: RunMode,
    name: &str,
    configure: impl FnOnce(PluginGroupBuilder) -> PluginGroupBuilder,
) -> App {
    #[cfg(not(target_arch = "wasm32"))]
    warn_without_assets();
    let mut app = App::new();
    match &mode {
        #[cfg(not(target_arch = "wasm32"))]
        RunMode::Windowed => {
            app.add_plugins(configure(DefaultPlugins.set(WindowPlugin {
                primary_window: Some(Window {
                    title: format!("bevy_phong: {name}"),
                    ..default()
                }),
                ..default()
            })));
        }
        #[cfg(not(target_arch = "wasm32"))]
        RunMode::Headless(_) => headless::add_plugins(&mut app, configure),
        #[cfg(not(target_arch = "wasm32"))]
        RunMode::Compare(_) => compare::add_plugins(&mut app, configure),
        #[cfg(target_arch = "wasm32")]
        RunMode::Canvas => web::add_plugins(&mut app, name, configure),
    }
    app.insert_resource(mode);
    app
}

/// Says, at once, when the crate's `assets/` is not where Bevy looks for it (beside the
/// executable, unless `BEVY_ASSET_ROOT` or `CARGO_MANIFEST_DIR` names another folder): an
/// example run from `target/` without `cargo run`, whose shaders and models would never load.
#[cfg(not(target_arch = "wasm32"))]
fn warn_without_assets() {
    let assets = bevy::asset::io::file::FileAssetReader::get_base_path().join("assets");
    if !assets.is_dir() {
        eprintln!(
            "warning: no assets folder at {}: run the example with `cargo run --example`, or \
             set CARGO_MANIFEST_DIR to bevy_phong's folder, so that its shaders and models load",
            assets.display()
        );
    }
}

/// Runs `app` as its mode says: in a window, headless or in a browser, or, with
/// `--compare`, its `PhongMaterial` meshes compared with the reference model.
#[allow(
    dead_code,
    reason = "the searchlight example compares its own material"
)]
pub fn run(app: App) -> AppExit {
    run_comparing::<bevy_phong::PhongMaterial>(app)
}

/// [`run`], with `--compare` comparing the meshes drawn with `M` (a material made of a
/// `PhongMaterial`).
pub fn run_comparing<M: bevy_phong::PhongSceneMaterial>(mut app: App) -> AppExit {
    #[cfg(not(target_arch = "wasm32"))]
    if let RunMode::Compare(picture) = app.world().resource::<RunMode>().clone() {
        return compare::run::<M>(app, picture);
    }
    app.run()
}

/// While this resource exists, a headless run does not save its picture and a browser run
/// does not report its scene drawn: an example inserts it while its scene is still loading.
#[derive(Resource)]
pub struct StillLoading;

/// The camera settings every example uses, so the window and the PNG look the same: the
/// lighting model's colors as they are (no tone mapping).
#[allow(
    dead_code,
    reason = "the glTF scene's camera is a game's (HDR, tonemapped)"
)]
pub fn example_camera(transform: Transform) -> impl Bundle {
    (Camera3d::default(), Tonemapping::Linear, transform)
}

/// Switches every `PhongMaterial` to the next highlight model (key B): Phong, Blinn-Phong,
/// three.js's normalized Blinn-Phong, Phong again.
#[allow(dead_code, reason = "only the examples that take keys use it")]
pub fn switch_specular_model(materials: &mut Assets<bevy_phong::PhongMaterial>) {
    use bevy_phong::SpecularModel;
    for (_, material) in materials.iter_mut() {
        material.specular_model = match material.specular_model {
            SpecularModel::Phong => SpecularModel::BlinnPhong,
            SpecularModel::BlinnPhong => SpecularModel::NormalizedBlinnPhong,
            SpecularModel::NormalizedBlinnPhong => SpecularModel::Phong,
        };
    }
    println!("specular model switched");
}

/// Shows `keys` in the window's title after the example's name (windowed runs only) and
/// prints it (in a browser, to the console). The title rather than on-screen text: Bevy's UI
/// and text would add some fifty crates to every build of the examples and tests.
#[allow(dead_code, reason = "only the examples that take keys use it")]
pub fn show_key_help<'a>(app: &'a mut App, keys: &'static str) -> &'a mut App {
    println!("keys: {keys}");
    #[cfg(target_arch = "wasm32")]
    info!("keys: {keys}");
    #[cfg(not(target_arch = "wasm32"))]
    if matches!(app.world().resource::<RunMode>(), RunMode::Windowed) {
        app.add_systems(
            Startup,
            move |mut windows: Query<&mut Window, With<bevy::window::PrimaryWindow>>| {
                for mut window in &mut windows {
                    window.title = format!("{} (keys: {keys})", window.title);
                }
            },
        );
    }
    app
}

/// Toggles the visibility of every entity with `L` (a light kind): hidden lights give no
/// light.
#[allow(dead_code, reason = "only the examples that take keys use it")]
pub fn toggle_visibility<L: Component>(lights: &mut Query<&mut Visibility, With<L>>) {
    for mut visibility in lights.iter_mut() {
        *visibility = match *visibility {
            Visibility::Hidden => Visibility::Inherited,
            _ => Visibility::Hidden,
        };
    }
}
