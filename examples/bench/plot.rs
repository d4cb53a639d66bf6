//! The benchmark's plots, as PNG files.

use plotters::{
    coord::ranged1d::{Ranged, ValueFormatter},
    prelude::*,
};
use std::path::Path;

const WIDTH: u32 = 960;
const HEIGHT: u32 = 600;
const COLORS: [RGBColor; 6] = [
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(127, 127, 127),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
];

/// Registers the font the plots' text is drawn with (Fira Mono, shipped in `assets/fonts`).
fn register_font() {
    let font = include_bytes!("../../assets/fonts/FiraMono-subset.ttf");
    // Registering twice replaces the same font: harmless.
    let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, font);
}

/// One line of a plot: a label and its `(x, y)` points.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// A log-log plot of one line per series.
pub fn lines(path: &Path, title: &str, x_label: &str, y_label: &str, series: &[Series]) {
    draw(path, title, x_label, y_label, series, true);
}

/// A log-log plot of one labelled point per series (each series holds one point).
pub fn points(path: &Path, title: &str, x_label: &str, y_label: &str, series: &[Series]) {
    draw(path, title, x_label, y_label, series, false);
}

fn draw(path: &Path, title: &str, x_label: &str, y_label: &str, series: &[Series], joined: bool) {
    register_font();
    let mut pixels = vec![0u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (WIDTH, HEIGHT)).into_drawing_area();
        if let Err(error) = chart(&root, title, x_label, y_label, series, joined) {
            eprintln!("cannot draw {}: {error}", path.display());
            return;
        }
        let _ = root.present();
    }
    match image::save_buffer(path, &pixels, WIDTH, HEIGHT, image::ExtendedColorType::Rgb8) {
        Ok(()) => println!("wrote {}", path.display()),
        Err(error) => eprintln!("cannot write {}: {error}", path.display()),
    }
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

/// The smallest and largest of `values`, widened for a log axis.
fn log_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (low, high) = values.fold((f64::INFINITY, 0.0_f64), |(low, high), v| {
        (low.min(v), high.max(v))
    });
    (low / 2.0).max(1e-12)..(high * 2.0).max(1e-11)
}

fn chart(
    root: &Area,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    joined: bool,
) -> Result<(), Box<dyn std::error::Error>> {
    root.fill(&WHITE)?;
    let all = || series.iter().flat_map(|s| s.points.iter().copied());
    let x_range = log_range(all().map(|(x, _)| x));
    let y_max = all().map(|(_, y)| y).fold(0.0, f64::max) * 1.15;
    let x_scientific = x_range.end < 1.0;
    let x_format = move |x: &f64| {
        if x_scientific {
            format!("{x:.0e}")
        } else if *x < 1.0 {
            format!("{x:.2}")
        } else {
            format!("{x:.0}")
        }
    };
    let mut builder = ChartBuilder::on(root);
    builder
        .caption(title, ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(72);
    // Frame times over light counts span decades (log y); variants' times do not (linear).
    if joined {
        let y_range = log_range(all().map(|(_, y)| y));
        let mut chart = builder.build_cartesian_2d(x_range.log_scale(), y_range.log_scale())?;
        draw_axes(&mut chart, x_label, y_label, &x_format)?;
        for (index, line) in series.iter().enumerate() {
            let color = COLORS[index % COLORS.len()];
            chart
                .draw_series(LineSeries::new(
                    line.points.iter().copied(),
                    color.stroke_width(2),
                ))?
                .label(line.label.as_str())
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2))
                });
            let style = ShapeStyle::from(color).filled();
            chart.draw_series(
                line.points
                    .iter()
                    .map(|&point| Circle::new(point, 5, style)),
            )?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .draw()?;
    } else {
        let mut chart = builder.build_cartesian_2d(x_range.log_scale(), 0.0..y_max)?;
        draw_axes(&mut chart, x_label, y_label, &x_format)?;
        for (index, point) in series.iter().enumerate() {
            let color = COLORS[index % COLORS.len()];
            let style = ShapeStyle::from(color).filled();
            chart.draw_series(point.points.iter().map(|&at| Circle::new(at, 5, style)))?;
            chart.draw_series(point.points.iter().map(|&at| {
                Text::new(
                    format!("  {}", point.label),
                    at,
                    ("sans-serif", 14).into_font(),
                )
            }))?;
        }
    }
    Ok(())
}

/// The grid, tick labels and axis descriptions of a chart with a logarithmic x axis.
fn draw_axes<Y>(
    chart: &mut ChartContext<'_, BitMapBackend<'_>, Cartesian2d<LogCoord<f64>, Y>>,
    x_label: &str,
    y_label: &str,
    x_format: &dyn Fn(&f64) -> String,
) -> Result<(), Box<dyn std::error::Error>>
where
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(x_format)
        .y_label_formatter(&|y| format!("{y:.0}"))
        .label_style(("sans-serif", 14))
        .draw()?;
    Ok(())
}
