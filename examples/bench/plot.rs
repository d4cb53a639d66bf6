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
    save(path, |root| chart(root, title, x_label, y_label, series));
}

/// One choice of a speed/accuracy trade-off: its name, the scene it was measured on, its
/// largest error and its frame time.
pub struct Choice {
    pub label: String,
    pub scene: String,
    pub error: f64,
    pub time: f64,
}

/// The choices as a Pareto picture: each a point (error, time), numbered on the chart (the
/// numbers placed where they cover no other) and named in a key beside it with its figures;
/// per scene (a color each), the choices no other of that scene beats in both (its Pareto
/// front) are filled and joined by a step line, the others hollow.
pub fn pareto(path: &Path, title: &str, x_label: &str, y_label: &str, choices: &[Choice]) {
    save(path, |root| {
        pareto_chart(root, title, x_label, y_label, choices)
    });
}

/// Draws a `WIDTH` × `HEIGHT` picture with `draw` and writes it to `path` as PNG.
fn save(path: &Path, draw: impl FnOnce(&Area) -> Result<(), Box<dyn std::error::Error>>) {
    register_font();
    let mut pixels = vec![0u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (WIDTH, HEIGHT)).into_drawing_area();
        if let Err(error) = draw(&root) {
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

/// The indices of `points` (x: error, y: time) that no other point beats in both (smaller or
/// equal in each, smaller in one), by increasing x.
fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut fastest = f64::INFINITY;
    for index in order {
        if points[index].1 < fastest {
            fastest = points[index].1;
            front.push(index);
        }
    }
    front
}

fn pareto_chart(
    whole: &Area,
    title: &str,
    x_label: &str,
    y_label: &str,
    choices: &[Choice],
) -> Result<(), Box<dyn std::error::Error>> {
    whole.fill(&WHITE)?;
    let titled = whole.titled(title, ("sans-serif", 22))?;
    let (plot, key) = titled.split_horizontally(WIDTH * 11 / 20);
    let x_range = log_range(choices.iter().map(|choice| choice.error));
    let y_max = choices.iter().map(|choice| choice.time).fold(0.0, f64::max) * 1.15;
    let mut chart = ChartBuilder::on(&plot)
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d(x_range.log_scale(), 0.0..y_max)?;
    draw_axes(&mut chart, x_label, y_label, &|x| format!("{x:.0e}"))?;
    let mut scenes: Vec<&str> = Vec::new();
    for choice in choices {
        if !scenes.contains(&choice.scene.as_str()) {
            scenes.push(&choice.scene);
        }
    }
    let mut on_front = vec![false; choices.len()];
    for (scene_index, scene) in scenes.iter().enumerate() {
        let members: Vec<usize> = (0..choices.len())
            .filter(|&index| choices[index].scene == *scene)
            .collect();
        let points: Vec<(f64, f64)> = members
            .iter()
            .map(|&index| (choices[index].error, choices[index].time))
            .collect();
        let front = pareto_front(&points);
        // The front as steps: from each choice, right to the next one's error, then down.
        let mut steps = Vec::new();
        for pair in front.windows(2) {
            let (from, to) = (points[pair[0]], points[pair[1]]);
            steps.extend([from, (to.0, from.1)]);
        }
        steps.extend(front.last().map(|&last| points[last]));
        let color = COLORS[scene_index % COLORS.len()];
        chart.draw_series(LineSeries::new(steps, color.mix(0.6).stroke_width(2)))?;
        for &member in &front {
            on_front[members[member]] = true;
        }
    }
    // Markers, then their numbers where they cover no marker and no other number.
    let color_of = |choice: &Choice| {
        let scene = scenes.iter().position(|scene| *scene == choice.scene);
        COLORS[scene.unwrap_or(0) % COLORS.len()]
    };
    for (choice, &front) in choices.iter().zip(&on_front) {
        let color = color_of(choice);
        let style = if front {
            ShapeStyle::from(color).filled()
        } else {
            color.stroke_width(2)
        };
        chart.draw_series([Circle::new((choice.error, choice.time), 6, style)])?;
    }
    let centers: Vec<(i32, i32)> = choices
        .iter()
        .map(|choice| chart.backend_coord(&(choice.error, choice.time)))
        .collect();
    let mut taken: Vec<(i32, i32, i32, i32)> = centers
        .iter()
        .map(|&(x, y)| (x - 7, y - 7, x + 7, y + 7))
        .collect();
    let overlaps = |a: (i32, i32, i32, i32), b: &(i32, i32, i32, i32)| {
        a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
    };
    for (index, &(x, y)) in centers.iter().enumerate() {
        let label = format!("{}", index + 1);
        let (width, height) = (9 * label.len() as i32, 16);
        let candidates = [
            (8, -18),
            (8, 2),
            (-8 - width, -18),
            (-8 - width, 2),
            (-width / 2, -26),
            (-width / 2, 10),
            (20, -8),
            (-20 - width, -8),
        ];
        let (dx, dy) = candidates
            .iter()
            .copied()
            .find(|&(dx, dy)| {
                let rect = (x + dx, y + dy, x + dx + width, y + dy + height);
                !taken.iter().any(|other| overlaps(rect, other))
            })
            .unwrap_or(candidates[0]);
        taken.push((x + dx, y + dy, x + dx + width, y + dy + height));
        whole.draw(&Text::new(
            label,
            (x + dx, y + dy),
            ("sans-serif", 15)
                .into_font()
                .color(&color_of(&choices[index])),
        ))?;
    }
    // The key: per scene, each choice's number, name and figures, a line each.
    let mut line = 0;
    let mut write = |text: String, color: RGBColor| {
        line += 1;
        key.draw(&Text::new(
            text,
            (4, 20 + line * 21),
            ("sans-serif", 13).into_font().color(&color),
        ))
    };
    for scene in &scenes {
        write(format!("{scene}:"), BLACK)?;
        for (index, choice) in choices.iter().enumerate() {
            if choice.scene != *scene {
                continue;
            }
            let mark = if on_front[index] { "*" } else { " " };
            write(
                format!(
                    "{mark}{:>2} {} ({:.0} ms, {:.0e})",
                    index + 1,
                    choice.label,
                    choice.time,
                    choice.error
                ),
                color_of(choice),
            )?;
        }
    }
    write("* on its scene's Pareto front (filled)".into(), BLACK)?;
    Ok(())
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
) -> Result<(), Box<dyn std::error::Error>> {
    root.fill(&WHITE)?;
    let all = || series.iter().flat_map(|s| s.points.iter().copied());
    let x_range = log_range(all().map(|(x, _)| x));
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
    // Frame times over light counts span decades: log y.
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
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2)));
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

#[cfg(test)]
mod tests {
    use super::pareto_front;

    #[test]
    fn the_front_keeps_each_choice_no_other_beats_in_both() {
        // (error, time): 2 beats 4 in both; 3 is as accurate as 2 and slower; 5 is the
        // fastest and least accurate.
        let points = [
            (1e-6, 10.0),
            (1e-4, 8.0),
            (1e-4, 12.0),
            (1e-2, 9.0),
            (1.0, 5.0),
        ];
        assert_eq!(pareto_front(&points), [0, 1, 4]);
    }
}
