//! [`Comparison`]: a rendered frame against the reference model, pixel by pixel.

use bevy::math::DVec3;
use std::{collections::BTreeMap, path::PathBuf};

use crate::float_image::{FloatImage, render_tests_directory, save_srgb_png};

/// The largest difference of a pixel from the reference model the render tests allow, per
/// channel, relative to `max(1, |expected|)`: a tenth of an 8-bit step, invisible on screen,
/// ten times above what the shader's `f32` roundings give on the reference's own inputs
/// (about 1e-6, up to 1e-5 under a sharp highlight), yet far below what a wrong term (a
/// missing attenuation, a wrong reflection) produces.
pub const TOLERANCE: f64 = 4e-4;

/// What a pixel should show, for [`Comparison::of`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Expected {
    /// This color, within the tolerance.
    Lit(DVec3),
    /// Any color from the first to the second, channel by channel, within the tolerance:
    /// where the device may choose within a documented precision (an sRGB texel's decoding,
    /// say).
    Between(DVec3, DVec3),
    /// The clear color: nothing is drawn there.
    Clear,
    /// Not judged (a pixel on a discontinuity, say).
    Unjudged,
}

/// The result of comparing a rendered image with the reference model.
pub struct Comparison {
    width: u32,
    height: u32,
    /// Pixels covered by a mesh and judged.
    pub lit_pixels: usize,
    /// Largest `|actual - expected| / max(1, |expected|)` over all channels of lit pixels.
    pub max_error: f64,
    /// Where the largest error is: `(x, y, actual, expected)`.
    pub worst_pixel: Option<(u32, u32, [f32; 3], DVec3)>,
    /// Pixels not covered by a mesh whose color is not the clear color.
    pub stray_pixels: usize,
    /// Covered pixels the reference could not judge (on a discontinuity).
    pub skipped_pixels: usize,
    /// For each object (its material's tag in the captured inputs), its judged and its
    /// unjudged pixels, where the comparison knows the objects ([`Harness::compare_pixels`]).
    ///
    /// [`Harness::compare_pixels`]: crate::Harness::compare_pixels
    pub objects: BTreeMap<u32, (usize, usize)>,
    actual: Vec<[f32; 3]>,
    expected: Vec<[f32; 3]>,
    /// Each lit pixel's error, as `max_error` measures it.
    errors: Vec<f64>,
}

impl Comparison {
    pub(crate) fn new(width: u32, height: u32) -> Self {
        let count = (width * height) as usize;
        Self {
            width,
            height,
            lit_pixels: 0,
            max_error: 0.0,
            worst_pixel: None,
            stray_pixels: 0,
            skipped_pixels: 0,
            objects: BTreeMap::new(),
            actual: vec![[0.0; 3]; count],
            expected: vec![[0.0; 3]; count],
            errors: Vec::new(),
        }
    }

    /// Compares `rendered` with `expected(index)` pixel by pixel.
    pub fn of(rendered: &FloatImage, expected: impl Fn(usize) -> Expected) -> Self {
        let mut comparison = Self::new(rendered.width, rendered.height);
        for (index, color) in rendered.pixels.iter().enumerate() {
            comparison.record_expected(index, *color, expected(index));
        }
        comparison
    }

    /// Records pixel `index`, which shows `color` and should show `expected`.
    pub(crate) fn record_expected(&mut self, index: usize, color: [f32; 4], expected: Expected) {
        match expected {
            Expected::Lit(expected) => self.record(index, color, expected),
            Expected::Between(low, high) => {
                self.record_between(index, color, low.min(high), low.max(high));
            }
            Expected::Clear => self.record_background(index, color),
            Expected::Unjudged => self.skipped_pixels += 1,
        }
    }

    pub(crate) fn record_background(&mut self, index: usize, color: [f32; 4]) {
        if color != [0.0; 4] {
            self.stray_pixels += 1;
        }
        self.actual[index] = [color[0], color[1], color[2]];
    }

    pub(crate) fn record(&mut self, index: usize, color: [f32; 4], expected: DVec3) {
        self.record_between(index, color, expected, expected);
    }

    /// Records a pixel whose color may be anywhere from `low` to `high`: its error is how far
    /// outside that range it is, relative to `max(1, |high|)`.
    fn record_between(&mut self, index: usize, color: [f32; 4], low: DVec3, high: DVec3) {
        let actual = [color[0], color[1], color[2]];
        let expected = (low + high) / 2.0;
        self.actual[index] = actual;
        self.expected[index] = expected.as_vec3().to_array();
        self.lit_pixels += 1;
        let error = (0..3)
            .map(|c| {
                let value = f64::from(actual[c]);
                let outside = (low[c] - value).max(value - high[c]).max(0.0);
                if value.is_nan() {
                    f64::INFINITY
                } else {
                    outside / high[c].abs().max(1.0)
                }
            })
            .fold(0.0, f64::max);
        self.errors.push(error);
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
        if !self.within(tolerance) {
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

    /// Whether some pixels were judged, none was drawn outside every mesh, and every judged
    /// pixel is within `tolerance` (relative to `max(1, |expected|)`): what
    /// [`Self::assert_within`] asserts.
    pub fn within(&self, tolerance: f64) -> bool {
        self.lit_pixels > 0 && self.stray_pixels == 0 && self.max_error <= tolerance
    }

    /// The error that the share `quantile` (in `[0, 1]`) of the lit pixels stays within (the
    /// nearest rank): 0.5 the median, 1 [`Self::max_error`]; 0 without lit pixels.
    pub fn error_quantile(&self, quantile: f64) -> f64 {
        let mut errors = self.errors.clone();
        errors.sort_by(f64::total_cmp);
        let rank = (quantile.clamp(0.0, 1.0) * errors.len() as f64).ceil() as usize;
        errors
            .get(rank.saturating_sub(1))
            .copied()
            .unwrap_or_default()
    }

    /// Asserts that fewer than a fifth of the lit pixels went unjudged (texel edges, the
    /// alpha mask's cutoff, cube edges: see [`crate::pixel_model`]), and, where the
    /// comparison knows the objects, that each object has more pixels judged than not, so
    /// that a comparison cannot pass by judging next to nothing, nor by leaving one object
    /// of several out. Texel and face edges leave out a few hundredths of an object's
    /// pixels (1/100 of a texel each side, per axis), an alpha cutoff its rim.
    pub fn assert_mostly_judged(&self, case: &str) {
        if let Some(failure) = self.judging_failures().first() {
            panic!("{case}: {failure}");
        }
    }

    /// Why [`Self::assert_mostly_judged`] would fail: empty where it passes.
    pub fn judging_failures(&self) -> Vec<String> {
        let mut failures = Vec::new();
        if self.skipped_pixels >= self.lit_pixels / 5 {
            failures.push(format!(
                "too few pixels judged: {} lit, {} unjudged",
                self.lit_pixels, self.skipped_pixels
            ));
        }
        for (object, &(judged, unjudged)) in &self.objects {
            if judged <= unjudged {
                failures.push(format!(
                    "object {object} has {judged} pixels judged and {unjudged} not"
                ));
            }
        }
        failures
    }

    /// Counts a covered pixel of `object` as judged or not.
    pub(crate) fn count_object_pixel(&mut self, object: u32, judged: bool) {
        let (judged_pixels, unjudged_pixels) = self.objects.entry(object).or_default();
        if judged {
            *judged_pixels += 1;
        } else {
            *unjudged_pixels += 1;
        }
    }

    /// Writes the actual, expected and difference images as PNGs under
    /// `target/render-tests/` (named after `case`) and returns their folder.
    pub fn write_pngs(&self, case: &str) -> PathBuf {
        let directory = render_tests_directory();
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
