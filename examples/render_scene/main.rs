//! Renders a scene file headless and writes what is needed to check it against the lighting
//! model outside this crate:
//!
//! - `color.png`: the picture, sRGB, 8 bits (values above 1 clipped, no alpha);
//! - `color.exr`: the shader's output, linear, 32-bit float, unclipped;
//! - `position.exr`, `normal.exr`: per pixel, the world position and the interpolated world
//!   normal (not normalized) it was lit with; alpha is the object's material number (0 for
//!   background, where RGB is 0 too).
//!
//! It writes them as soon as the frame is read back. With `--compare` it then prints the
//! largest difference from `bevy_phong::reference` on those inputs, every material feature
//! and light applied (`Harness::compare_with_reference`, on every core, with a progress line;
//! for a scene without shadows: the reference is not given the visibility of a scene file's
//! lights), and how many pixels it could not judge (texel edges, maps sampled with filtering,
//! environment maps). With `--check` it also fails where that difference exceeds the render
//! tests' tolerance (`bevy_phong_headless::TOLERANCE`, 4e-4), or where no pixel could be
//! judged. The reference model integrates an area light by quadrature over its shape: a
//! scene of area lights at 256² compares in seconds (docs/scene-files.md).
//!
//! `cargo run --example render_scene -- assets/scenes/shapes.phong_scene.ron --out DIR`;
//! `--help` lists the options.

mod output;

use bevy::prelude::World;
use bevy_phong::{extension::PhongLightKind, prelude::*};
use bevy_phong_headless::{FloatImage, Harness, SurfaceInputs, TOLERANCE};
use clap::Parser;
use std::{path::PathBuf, process::ExitCode};

/// Render a *.phong_scene.ron file headless to PNG and OpenEXR files.
#[derive(Parser)]
#[command(
    name = "render_scene",
    override_usage = "cargo run --example render_scene -- SCENE [OPTIONS]",
    after_help = "The render device is the first Vulkan adapter (WGPU_ADAPTER_NAME=llvmpipe \
                  picks Mesa's software renderer). The scene's camera is used; without one the \
                  camera is at (0, 2.5, 7) looking at the origin."
)]
struct Options {
    /// The scene file (*.phong_scene.ron).
    scene: PathBuf,
    /// Where to write color.png, color.exr, position.exr and normal.exr.
    #[arg(long, value_name = "DIR", default_value = "target/render_scene")]
    out: PathBuf,
    /// The image size in pixels, each side 1 to 8192.
    #[arg(long, value_name = "WxH", default_value = "512x512", value_parser = parse_size)]
    size: (u32, u32),
    /// After writing the files, compare each pixel with the reference model and print the
    /// largest difference (on every core, with a progress line); not for a scene that casts
    /// shadows.
    #[arg(long)]
    compare: bool,
    /// --compare, and fail where a pixel differs by more than the render tests' tolerance
    /// (4e-4 of max(1, |expected|)), or where no pixel is judged.
    #[arg(long)]
    check: bool,
    /// The asset folder: files the scene names (material files, textures) must be inside it
    /// [default: the nearest folder named `assets` that holds the scene file, else the scene
    /// file's folder].
    #[arg(long, value_name = "DIR")]
    assets: Option<PathBuf>,
}

/// `WxH`, each side 1 to 8192 pixels.
fn parse_size(size: &str) -> Result<(u32, u32), String> {
    size.split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .filter(|&(w, h): &(u32, u32)| (1..=8192).contains(&w) && (1..=8192).contains(&h))
        .ok_or_else(|| format!("expected WxH, each 1 to 8192, not {size}"))
}

fn main() -> ExitCode {
    match render(&Options::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("render_scene: {message}");
            ExitCode::FAILURE
        }
    }
}

fn render(options: &Options) -> Result<(), String> {
    let scene = std::path::absolute(&options.scene)
        .map_err(|error| format!("{}: {error}", options.scene.display()))?;
    if !scene.is_file() {
        return Err(format!("{}: no such file", scene.display()));
    }
    let root = match &options.assets {
        Some(root) => std::path::absolute(root).map_err(|error| error.to_string())?,
        None => scene
            .ancestors()
            .skip(1)
            .find(|folder| folder.file_name().is_some_and(|name| name == "assets"))
            .unwrap_or_else(|| scene.parent().expect("a file has a folder"))
            .to_path_buf(),
    };
    let relative = scene
        .strip_prefix(&root)
        .map_err(|_| {
            format!(
                "{} is not inside --assets {}",
                scene.display(),
                root.display()
            )
        })?
        .to_string_lossy()
        .into_owned();

    let (width, height) = options.size;
    let mut harness =
        Harness::with_assets(width, height, root.to_string_lossy().into_owned(), |_| {});
    harness.load_scene(&relative)?;

    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs();
    write_files(&options.out, &rendered, &inputs)?;
    if options.compare || options.check {
        compare(&mut harness, &rendered, options.check)?;
    }
    Ok(())
}

/// Writes the frame and its inputs into `out`.
fn write_files(
    out: &std::path::Path,
    rendered: &FloatImage,
    inputs: &SurfaceInputs,
) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|error| format!("{}: {error}", out.display()))?;
    for (name, image) in [
        ("color.exr", rendered),
        ("position.exr", &inputs.positions),
        ("normal.exr", &inputs.normals),
    ] {
        output::write_exr(&out.join(name), image)?;
    }
    output::write_png(&out.join("color.png"), rendered)?;
    println!(
        "wrote color.png, color.exr, position.exr, normal.exr in {}",
        out.display()
    );
    Ok(())
}

/// Compares `rendered` with the reference model and prints the largest difference; with
/// `check`, fails past the render tests' tolerance.
fn compare(harness: &mut Harness, rendered: &FloatImage, check: bool) -> Result<(), String> {
    if casts_shadows(harness) {
        // The reference model is given each light's visibility by the render tests, which
        // know the scene's shapes; a scene file's are not modelled here.
        println!("the scene casts shadows: no comparison with the reference model");
        if check {
            return Err("--check: the scene casts shadows, which the check cannot model".into());
        }
        return Ok(());
    }
    harness.show_progress();
    let comparison = harness.compare_with_reference(rendered);
    println!(
        "{} lit pixels, {} of them not judged; largest difference from the reference model \
         {:.2e} (relative to max(1, |expected|))",
        comparison.lit_pixels, comparison.skipped_pixels, comparison.max_error
    );
    if let Some((x, y, rendered, expected)) = comparison.worst_pixel {
        println!(
            "  at pixel ({x}, {y}): rendered {rendered:?}, the reference model {:?}",
            expected.to_array()
        );
    }
    if check && (comparison.lit_pixels == 0 || comparison.max_error > TOLERANCE) {
        return Err(format!(
            "--check: {} pixels judged, largest difference {:.2e} (tolerance {TOLERANCE:.0e})",
            comparison.lit_pixels, comparison.max_error
        ));
    }
    Ok(())
}

/// Whether any light of the loaded scene casts shadows.
fn casts_shadows(harness: &mut Harness) -> bool {
    let world = harness.world_mut();
    kind_casts_shadows::<PhongDirectionalLight>(world)
        || kind_casts_shadows::<PhongPointLight>(world)
        || kind_casts_shadows::<PhongSpotLight>(world)
        || kind_casts_shadows::<PhongRectLight>(world)
        || kind_casts_shadows::<PhongDiskLight>(world)
}

/// Whether any light of kind `L` in `world` casts shadows.
fn kind_casts_shadows<L: PhongLightKind>(world: &mut World) -> bool {
    world.query::<&L>().iter(world).any(L::casts_shadows)
}
