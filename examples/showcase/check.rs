//! `--check PNG`: whether a picture of the showcase shows the sphere's three highlights where
//! the lighting model puts them.
//!
//! For each light, the sphere point where that light's highlight term `H(N, L, V)` peaks is
//! found from the scene's own constants (the camera, the sphere, the lights and the
//! sphere's material, through `bevy_phong::reference`), projected by the camera onto the
//! picture, and the picture must show a near-white peak there. The same check runs on the
//! native headless render (`scripts/test.sh`) and on the browser's screenshot
//! (`scripts/browser.sh`).

use super::{
    SPHERE_CENTER, SPHERE_COLOR, SPHERE_RADIUS, SceneLight, camera_transform, lights, seed_material,
};
use bevy::{
    camera::{CameraProjection, PerspectiveProjection},
    math::{DVec2, DVec3},
    prelude::*,
};
use bevy_phong::reference::{self, Light};
use std::path::{Path, PathBuf};

/// The least `min(r, g, b)` (8-bit sRGB) of a near-white pixel. The highlight is white with
/// specular strength 2 on a magenta sphere, so green, the smallest channel, is the highlight
/// alone: near-white is `2 · H ≥ 0.79` in linear light (sRGB 230), `H ≥ 0.4`.
const NEAR_WHITE: u8 = 230;

/// How far (pixels) the center of the near-white spot may lie from the projected peak. The
/// spot's center is not exactly the peak: the sphere curving away squeezes the spot's far
/// side on screen, and the UV sphere's 64 × 48 quads bend the interpolated normals off the
/// true sphere's by up to about a degree (a pixel on this 76-pixel radius). Measured: at
/// most 0.5 pixel on lavapipe and in Chromium's WebGL2; the highlights lie 30 pixels and
/// more apart, so a few pixels still tell each from its neighbors.
const POSITION_TOLERANCE: f64 = 3.0;

/// How far (pixels) from its center the near-white spot may reach. `H ≥ 0.4` holds where
/// the reflected ray lies within 11° of the eye, normals within about 5.5° of the peak's: 7
/// pixels on this 76-pixel radius, more where the sphere is seen at a slant (measured: 9.6
/// at most). A spot that reaches twice as far is no peak but a white area, or highlights
/// run together.
const SPOT_RADIUS: f64 = 20.0;

/// The showcase's own option.
#[derive(clap::Args)]
pub struct CheckOption {
    /// Check that the picture at PATH (by default target/showcase.png) shows the sphere's
    /// three highlights where the lighting model puts them, then exit.
    #[arg(long, value_name = "PATH")]
    check: Option<Option<PathBuf>>,
}

impl CheckOption {
    /// The picture to check, if `--check` was given.
    pub fn path(self) -> Option<PathBuf> {
        self.check
            .map(|path| path.unwrap_or_else(|| PathBuf::from("target/showcase.png")))
    }
}

/// Checks the picture at `path`; returns the process exit code (0 when every highlight is
/// there, 1 when one is missing, 2 when the picture cannot be read).
pub fn run(path: &Path) -> i32 {
    let picture = match image::open(path) {
        Ok(picture) => picture.to_rgb8(),
        Err(error) => {
            eprintln!("cannot read {}: {error}", path.display());
            return 2;
        }
    };
    let size = DVec2::new(picture.width().into(), picture.height().into());
    let mut missing = Vec::new();
    for (name, expected) in expected_highlights(size) {
        let verdict = match near_white_spot(&picture, expected) {
            None => Err(format!(
                "no near-white pixel (min(r, g, b) ≥ {NEAR_WHITE}) within {POSITION_TOLERANCE} px"
            )),
            Some(spot) => {
                let offset = spot.center.distance(expected);
                let found = format!(
                    "near-white spot of {} px centered at ({:.1}, {:.1}), {offset:.1} px away, reaching {:.1} px from its center",
                    spot.pixels, spot.center.x, spot.center.y, spot.reach
                );
                if offset > POSITION_TOLERANCE {
                    Err(format!("{found}: more than {POSITION_TOLERANCE} px away"))
                } else if spot.reach > SPOT_RADIUS {
                    Err(format!(
                        "{found}: not a peak (reaches past {SPOT_RADIUS} px)"
                    ))
                } else {
                    Ok(found)
                }
            }
        };
        let (word, detail) = match &verdict {
            Ok(detail) => ("there", detail),
            Err(detail) => ("MISSING", detail),
        };
        println!(
            "Highlight of {name}, expected at ({:.1}, {:.1}): {word}: {detail}",
            expected.x, expected.y,
        );
        if verdict.is_err() {
            missing.push(name);
        }
    }
    if missing.is_empty() {
        println!(
            "{}: the sphere's three highlights are there",
            path.display()
        );
        0
    } else {
        eprintln!(
            "{}: the sphere lacks the highlight of {}",
            path.display(),
            missing.join(", of ")
        );
        1
    }
}

/// Where each light's highlight peaks on the sphere, in pixels (x right, y down, from the
/// top-left corner) of a picture of `size` taken by the showcase's camera.
fn expected_highlights(size: DVec2) -> Vec<(&'static str, DVec2)> {
    let camera = camera_transform();
    let material = reference::Material::from(&seed_material(SPHERE_COLOR));
    let eye = camera.translation.as_dvec3();
    let projection = PerspectiveProjection {
        aspect_ratio: (size.x / size.y) as f32,
        ..default()
    };
    let clip_from_world =
        projection.get_clip_from_view() * GlobalTransform::from(camera).to_matrix().inverse();
    lights()
        .into_iter()
        .map(|(name, light, transform)| {
            let transform = GlobalTransform::from(transform);
            let light = match light {
                SceneLight::Directional(light) => Light::directional(&light, &transform),
                SceneLight::Point(light) => Light::point(&light, &transform),
            };
            let normal = highlight_peak(&light, &material, eye);
            let point = SPHERE_CENTER + SPHERE_RADIUS * normal.as_vec3();
            let ndc = clip_from_world.project_point3(point).as_dvec3();
            let pixel = DVec2::new((ndc.x + 1.0) / 2.0 * size.x, (1.0 - ndc.y) / 2.0 * size.y);
            (name, pixel)
        })
        .collect()
}

/// The unit normal of the sphere point, seen from `eye`, where `light`'s highlight term is
/// largest: a grid search over the sphere, then a pattern search refining it.
fn highlight_peak(light: &Light, material: &reference::Material, eye: DVec3) -> DVec3 {
    let term = |normal: DVec3| {
        let normal = normal.normalize();
        let position = SPHERE_CENTER.as_dvec3() + f64::from(SPHERE_RADIUS) * normal;
        if (eye - position).dot(normal) <= 0.0 {
            return -1.0;
        }
        let to_light = match *light {
            Light::Directional { direction, .. } => -direction.normalize(),
            Light::Point { position: at, .. } | Light::Spot { position: at, .. } => {
                (at - position).normalize()
            }
        };
        if normal.dot(to_light) <= 0.0 {
            return -1.0;
        }
        let view = (eye - position).normalize();
        reference::highlight(
            material.specular_model,
            normal,
            to_light,
            view,
            material.shininess,
        )
    };
    let steps = 180;
    let mut best = DVec3::Z;
    for i in 0..=steps {
        let polar = std::f64::consts::PI * f64::from(i) / f64::from(steps);
        for j in 0..2 * steps {
            let azimuth = std::f64::consts::PI * f64::from(j) / f64::from(steps);
            let normal = DVec3::new(
                polar.sin() * azimuth.cos(),
                polar.cos(),
                polar.sin() * azimuth.sin(),
            );
            if term(normal) > term(best) {
                best = normal;
            }
        }
    }
    let mut step = 0.02;
    while step > 1e-9 {
        let candidates = [
            DVec3::X,
            DVec3::NEG_X,
            DVec3::Y,
            DVec3::NEG_Y,
            DVec3::Z,
            DVec3::NEG_Z,
        ]
        .map(|axis| (best + step * axis).normalize());
        match candidates
            .into_iter()
            .find(|candidate| term(*candidate) > term(best))
        {
            Some(better) => best = better,
            None => step /= 2.0,
        }
    }
    best
}

/// `min(r, g, b)` of a pixel: 255 for white, low for any saturated or dark color.
fn whiteness(picture: &image::RgbImage, pixel: UVec2) -> u8 {
    let [r, g, b] = picture.get_pixel(pixel.x, pixel.y).0;
    r.min(g).min(b)
}

/// A connected patch of near-white pixels.
struct Spot {
    /// Its pixel count.
    pixels: usize,
    /// The mean of its pixels' centers.
    center: DVec2,
    /// The largest distance from `center` to one of its pixels' centers.
    reach: f64,
}

/// The near-white pixels connected (4-neighbors) to those within [`POSITION_TOLERANCE`] of
/// `expected`; `None` where none is near-white there.
fn near_white_spot(picture: &image::RgbImage, expected: DVec2) -> Option<Spot> {
    let (width, height) = picture.dimensions();
    let near_white = |pixel: UVec2| whiteness(picture, pixel) >= NEAR_WHITE;
    let center_of = |pixel: UVec2| pixel.as_dvec2() + 0.5;
    let mut stack: Vec<UVec2> = Vec::new();
    let mut seen = std::collections::HashSet::new();
    let low = (expected - POSITION_TOLERANCE)
        .floor()
        .max(DVec2::ZERO)
        .as_uvec2();
    let high = (expected + POSITION_TOLERANCE).ceil().as_uvec2();
    for y in low.y..high.y.min(height) {
        for x in low.x..high.x.min(width) {
            let pixel = UVec2::new(x, y);
            if center_of(pixel).distance(expected) <= POSITION_TOLERANCE && near_white(pixel) {
                seen.insert(pixel);
                stack.push(pixel);
            }
        }
    }
    let mut spot = Vec::new();
    while let Some(pixel) = stack.pop() {
        spot.push(pixel);
        let neighbors = [
            pixel.x.checked_sub(1).map(|x| UVec2::new(x, pixel.y)),
            (pixel.x + 1 < width).then(|| UVec2::new(pixel.x + 1, pixel.y)),
            pixel.y.checked_sub(1).map(|y| UVec2::new(pixel.x, y)),
            (pixel.y + 1 < height).then(|| UVec2::new(pixel.x, pixel.y + 1)),
        ];
        for neighbor in neighbors.into_iter().flatten() {
            if near_white(neighbor) && seen.insert(neighbor) {
                stack.push(neighbor);
            }
        }
    }
    if spot.is_empty() {
        return None;
    }
    let center = spot.iter().map(|&pixel| center_of(pixel)).sum::<DVec2>() / spot.len() as f64;
    let reach = spot
        .iter()
        .map(|&pixel| center_of(pixel).distance(center))
        .fold(0.0, f64::max);
    Some(Spot {
        pixels: spot.len(),
        center,
        reach,
    })
}
