//! The sweep's charts, drawn with plotters as SVG (no system fonts
//! needed): scatter panels with a Pareto front, and log-log line charts.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

/// A labelled point of a scatter panel.
pub struct Point {
    /// Time per frame, ms.
    pub x: f64,
    /// Wrong-face pixels, %.
    pub y: f64,
    /// Its label, in the legend.
    pub label: String,
    /// Its colour's index (the same in every panel).
    pub color: usize,
    /// A peer (drawn as a cross) rather than one of ours (a dot).
    pub peer: bool,
}

/// One scatter panel.
pub struct Panel {
    /// Its title.
    pub title: String,
    /// What y is.
    pub y_desc: String,
    /// Where zero is drawn on the log y axis.
    pub floor: f64,
    /// Where its legend goes (away from the points).
    pub legend: SeriesLabelPosition,
    /// Its points.
    pub points: Vec<Point>,
    /// Indices of the points on the Pareto front.
    pub front: Vec<usize>,
}

/// One named line of a line chart.
pub struct Series {
    /// Its name, in the legend.
    pub name: String,
    /// (x, y) points, in x order.
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// An empty series.
    pub fn new(name: &str) -> Self {
        Self {
            name: name.into(),
            points: Vec::new(),
        }
    }
}

fn err<E: std::fmt::Debug>(e: E) -> String {
    format!("chart: {e:?}")
}

/// Indices of the points no other point beats in both coordinates (both
/// smaller is better), in order of x.
pub fn pareto(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&k| points[k].0.is_finite() && points[k].1.is_finite())
        .collect();
    order.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for k in order {
        if points[k].1 < best {
            best = points[k].1;
            front.push(k);
        }
    }
    front
}

/// Log range covering `values` (positive), with a margin.
fn log_range(values: impl Iterator<Item = f64>, floor: f64) -> std::ops::Range<f64> {
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for v in values.filter(|v| v.is_finite()) {
        let v = v.max(floor);
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return floor..floor * 10.0;
    }
    // Whole decades, so the axis has labelled ticks at both ends.
    let decade = |v: f64, up: bool| {
        let e = v.log10();
        10f64.powf(if up { e.ceil() } else { e.floor() })
    };
    decade(lo, false)..decade(hi * 1.01, true)
}

/// A tick label: `1.5M`, `264k`, `12`, `0.25`.
fn human(v: &f64) -> String {
    let v = *v;
    if v >= 1e6 {
        let s = format!("{:.2}", v / 1e6);
        format!("{}M", s.trim_end_matches('0').trim_end_matches('.'))
    } else if v >= 1e4 {
        format!("{:.0}k", v / 1e3)
    } else if v >= 1.0 {
        format!("{v:.0}")
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

fn header(root: &DrawingArea<SVGBackend, Shift>, title: &str, caption: &str) -> Result<(), String> {
    root.fill(&WHITE).map_err(err)?;
    root.draw(&Text::new(title, (12, 8), ("sans-serif", 20).into_font()))
        .map_err(err)?;
    let (_, h) = root.dim_in_pixel();
    root.draw(&Text::new(
        caption,
        (12, h as i32 - 20),
        ("sans-serif", 12).into_font().color(&RGBColor(90, 90, 90)),
    ))
    .map_err(err)
}

/// Scatter panels side by side: time (log) against a rate or error (log,
/// zero drawn at the panel's floor), each point its own legend entry with
/// its colour and marker (the same index keeps the same colour in every
/// panel), the Pareto front as a grey line.
pub fn scatter(path: &Path, title: &str, caption: &str, panels: &[Panel]) -> Result<(), String> {
    let root = SVGBackend::new(path, (1500, 760)).into_drawing_area();
    header(&root, title, caption)?;
    let body = root.margin(36, 30, 10, 10);
    for (area, panel) in body.split_evenly((1, panels.len())).iter().zip(panels) {
        let xs = log_range(panel.points.iter().map(|p| p.x), 1e-3);
        let ys = log_range(panel.points.iter().map(|p| p.y), panel.floor);
        let ys = panel.floor..ys.end.max(panel.floor * 1e4);
        let mut chart = ChartBuilder::on(area)
            .caption(&panel.title, ("sans-serif", 14))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(xs.log_scale(), ys.log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("ms per frame (sum over the meshes)")
            .x_label_formatter(&human)
            .y_label_formatter(&human)
            .y_desc(panel.y_desc.as_str())
            .draw()
            .map_err(err)?;
        let at = |p: &Point| (p.x, p.y.max(panel.floor));
        if panel.front.len() > 1 {
            let grey = ShapeStyle::from(&RGBColor(170, 170, 170)).stroke_width(6);
            chart
                .draw_series(LineSeries::new(
                    panel.front.iter().map(|&k| at(&panel.points[k])),
                    grey,
                ))
                .map_err(err)?
                .label("Pareto front")
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], grey));
        }
        for p in &panel.points {
            let color = Palette99::pick(p.color).to_rgba();
            let style = ShapeStyle::from(&color).filled();
            if p.peer {
                let cross = style.stroke_width(2);
                chart
                    .draw_series(std::iter::once(Cross::new(at(p), 7, cross)))
                    .map_err(err)?
                    .label(p.label.as_str())
                    .legend(move |(x, y)| Cross::new((x + 10, y), 5, cross));
            } else {
                chart
                    .draw_series(std::iter::once(Circle::new(at(p), 5, style)))
                    .map_err(err)?
                    .label(p.label.as_str())
                    .legend(move |(x, y)| Circle::new((x + 10, y), 4, style));
            }
        }
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.85))
            .label_font(("sans-serif", 11))
            .position(panel.legend.clone())
            .draw()
            .map_err(err)?;
    }
    root.present().map_err(err)
}

/// Log-log line panels side by side, one line per series; `limit` draws a
/// horizontal line (label, y) and marks x on it.
pub fn lines(
    path: &Path,
    title: &str,
    caption: &str,
    x_desc: &str,
    y_desc: &str,
    panels: &[(String, Vec<Series>)],
    limit: Option<(String, f64, f64)>,
) -> Result<(), String> {
    let root = SVGBackend::new(path, (1400, 640)).into_drawing_area();
    header(&root, title, caption)?;
    let body = root.margin(36, 30, 10, 10);
    for (area, (name, series)) in body.split_evenly((1, panels.len())).iter().zip(panels) {
        let xs = log_range(
            series.iter().flat_map(|s| s.points.iter().map(|p| p.0)),
            1.0,
        );
        let ys = log_range(
            series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.1))
                .chain(limit.iter().map(|l| l.1)),
            1e-3,
        );
        let mut chart = ChartBuilder::on(area)
            .caption(name, ("sans-serif", 15))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(xs.clone().log_scale(), ys.log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(y_desc)
            .x_label_formatter(&human)
            .y_label_formatter(&human)
            .draw()
            .map_err(err)?;
        for (k, s) in series.iter().enumerate() {
            let color = Palette99::pick(k).to_rgba();
            let style = ShapeStyle::from(&color).stroke_width(2);
            chart
                .draw_series(LineSeries::new(s.points.iter().copied(), style))
                .map_err(err)?
                .label(&s.name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], style));
            chart
                .draw_series(
                    s.points
                        .iter()
                        .map(|&p| Circle::new(p, 3, ShapeStyle::from(&color).filled())),
                )
                .map_err(err)?;
        }
        if let Some((label, y, x)) = &limit {
            let red = ShapeStyle::from(&RED).stroke_width(2);
            chart
                .draw_series(LineSeries::new([(xs.start, *y), (xs.end, *y)], red))
                .map_err(err)?
                .label(label.as_str())
                .legend(move |(px, py)| PathElement::new([(px, py), (px + 20, py)], red));
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at((*x, *y))
                        + Cross::new((0, 0), 7, red)
                        + Text::new("240x240", (6, 6), ("sans-serif", 12).into_font()),
                ))
                .map_err(err)?;
        }
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(err)?;
    }
    root.present().map_err(err)
}
