//! The drawings: line charts stacked in one figure (plotters, SVG backend), and an animation
//! of a linkage (SVG's own `<animate>`, which plotters does not make).

use std::fmt::Write;

use plotters::prelude::*;

/// A run of a series: the piece (segment) it belongs to, and its points.
pub type Run = (usize, Vec<(f64, f64)>);

/// One chart: a title, the unit of its y-axis, its series `(label, runs)` with each run
/// `(segment, points)` drawn as a line of its own, and an optional shaded band `(low, high)`
/// (the transmission angle's 40° to 140°).
pub struct Chart {
    pub title: String,
    pub unit: String,
    pub series: Vec<(String, Vec<Run>)>,
    pub band: Option<(f64, f64)>,
}

const COLOURS: [RGBColor; 6] = [
    RGBColor(0x1f, 0x6f, 0xeb),
    RGBColor(0xd1, 0x24, 0x2f),
    RGBColor(0x1a, 0x7f, 0x37),
    RGBColor(0x9a, 0x67, 0x00),
    RGBColor(0x82, 0x50, 0xdf),
    RGBColor(0xbc, 0x4c, 0x00),
];
const WIDTH: f64 = 720.0;
const MARGIN: f64 = 60.0;
/// The charts' pixels: each chart's height, the figure's width, and the legend's column at
/// its right, where no curve runs.
const CHART_HEIGHT: u32 = 280;
const FIGURE_WIDTH: u32 = 820;
const LEGEND_WIDTH: u32 = 110;
/// The width of a series' line, which tells it from the grid's and the zero line's.
const SERIES_STROKE: u32 = 2;

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (low, high) = values.fold((f64::MAX, f64::MIN), |(l, h), v| (l.min(v), h.max(v)));
    if low > high {
        (-1.0, 1.0)
    } else if low == high {
        let pad = if low == 0.0 { 1.0 } else { low.abs() * 0.05 };
        (low - pad, high + pad)
    } else {
        (low, high)
    }
}

/// `(low, high)` widened by 5% each way, so no curve runs along the frame.
fn padded((low, high): (f64, f64)) -> (f64, f64) {
    let pad = (high - low) * 0.05;
    (low - pad, high + pad)
}

/// A tick label on an axis spanning `span`: few digits, no trailing zeros, exponent form for
/// the very large or small, and 0 for a value within a billionth of the span of it (the
/// plotting library's tick at zero, rounded from far larger steps: `5.95e284` on an axis
/// of 1e300).
fn tick(value: f64, span: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || magnitude <= 1e-9 * span.abs() {
        "0".into()
    } else if !(1e-3..1e6).contains(&magnitude) {
        format!("{value:.2e}")
    } else {
        let text = format!("{value:.4}");
        let text = text.trim_end_matches('0').trim_end_matches('.');
        if text == "-0" {
            "0".into()
        } else {
            text.into()
        }
    }
}

/// Charts stacked vertically, sharing the x-axis and its label: ticks and a light grid on
/// both axes, a zero line where zero is in range, the unit on every axis, a legend in a
/// column of its own at the right, and a dashed line at each of `markers` (the change points
/// a sweep crossed).
pub fn charts(x_label: &str, charts: &[Chart], markers: &[f64]) -> Result<String, String> {
    let mut svg = String::new();
    let rows = u32::try_from(charts.len()).unwrap_or(u32::MAX).max(1);
    {
        let root = SVGBackend::with_string(&mut svg, (FIGURE_WIDTH, CHART_HEIGHT * rows))
            .into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        for (area, chart) in root.split_evenly((charts.len(), 1)).iter().zip(charts) {
            draw_chart(area, x_label, chart, markers)?;
        }
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}

fn drawing(error: impl std::fmt::Display) -> String {
    format!("cannot draw the charts: {error}")
}

fn draw_chart<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    x_label: &str,
    chart: &Chart,
    markers: &[f64],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let (plot, legend) = area.split_horizontally(FIGURE_WIDTH - LEGEND_WIDTH);
    let points = chart
        .series
        .iter()
        .flat_map(|(_, runs)| runs.iter().flat_map(|(_, p)| p.iter()));
    let (x0, x1) = range(points.clone().map(|p| p.0));
    let (y0, y1) = padded(range(
        points
            .map(|p| p.1)
            .chain(chart.band.iter().flat_map(|b| [b.0, b.1])),
    ));
    let mut context = ChartBuilder::on(&plot)
        .caption(&chart.title, ("sans-serif", 15))
        .margin(8)
        .x_label_area_size(40)
        .y_label_area_size(72)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(drawing)?;
    context
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(&chart.unit)
        .x_labels(12)
        .y_labels(6)
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 13))
        .bold_line_style(BLACK.mix(0.12))
        .light_line_style(BLACK.mix(0.04))
        .x_label_formatter(&|x| tick(*x, x1 - x0))
        .y_label_formatter(&|y| tick(*y, y1 - y0))
        .draw()
        .map_err(drawing)?;
    if let Some((low, high)) = chart.band {
        let shade = RGBColor(0xda, 0xfb, 0xe1).mix(0.7).filled();
        context
            .draw_series(std::iter::once(Rectangle::new(
                [(x0, low), (x1, high)],
                shade,
            )))
            .map_err(drawing)?;
    }
    if y0 < 0.0 && 0.0 < y1 {
        context
            .draw_series(LineSeries::new([(x0, 0.0), (x1, 0.0)], BLACK.mix(0.5)))
            .map_err(drawing)?;
    }
    for &at in markers {
        context
            .draw_series(DashedLineSeries::new(
                [(at, y0), (at, y1)],
                6,
                4,
                RGBColor(0x82, 0x50, 0xdf).stroke_width(1),
            ))
            .map_err(drawing)?;
    }
    if !markers.is_empty() {
        let y = 48 + 20 * i32::try_from(chart.series.len()).unwrap_or(0);
        legend
            .draw(&Text::new("change point", (8, y - 7), ("sans-serif", 12)))
            .map_err(drawing)?;
    }
    for (s, (label, runs)) in chart.series.iter().enumerate() {
        let colour = COLOURS[s % COLOURS.len()];
        for (_, points) in runs {
            context
                .draw_series(LineSeries::new(
                    points.iter().copied(),
                    colour.stroke_width(SERIES_STROKE),
                ))
                .map_err(drawing)?;
        }
        let y = 48 + 20 * i32::try_from(s).unwrap_or(0);
        // A filled swatch, not a line: the figure's only lines this wide are the series'.
        legend
            .draw(&Rectangle::new([(8, y - 1), (32, y + 1)], colour.filled()))
            .map_err(drawing)?;
        legend
            .draw(&Text::new(label.as_str(), (38, y - 7), ("sans-serif", 13)))
            .map_err(drawing)?;
    }
    Ok(())
}

/// An animated drawing of a linkage: each link is a line whose ends move through `frames`
/// (one `(x, y)` per joint and frame), and the traced point's whole curve is drawn, one
/// polyline per reachable piece (`segments`, one per frame).
pub fn animation(
    title: &str,
    links: &[(usize, usize)],
    frames: &[Vec<(f64, f64)>],
    segments: &[usize],
    traced: usize,
    seconds: f64,
) -> String {
    // In half units (exact but for subnormals, which a drawing cannot tell from zero): the
    // extent of a linkage 1e308 across, or of one between −1e308 and 1e308, overflows.
    let half = |v: f64| v * 0.5;
    let all = frames.iter().flatten();
    let (x0, x1) = range(all.clone().map(|p| half(p.0)));
    let (y0, y1) = range(all.map(|p| half(p.1)));
    let size = (x1 - x0).max(y1 - y0);
    let scale = (WIDTH - 2.0 * MARGIN) / size;
    let px = |x: f64| MARGIN + (half(x) - x0) * scale;
    let py = |y: f64| MARGIN + (y1 - half(y)) * scale;
    let height = 2.0 * MARGIN + (y1 - y0) * scale;
    // A long title (a six-bar's ten dimensions) in smaller type, so it fits the width: a
    // character of sans-serif is about 0.55 of the type's size.
    let characters = title.chars().count().max(1) as f64;
    let title_size = (0.95 * WIDTH / (0.55 * characters)).min(14.0);
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{height:.0}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"24\" text-anchor=\"middle\" font-size=\"{title_size:.1}\">{}</text>\n",
        WIDTH / 2.0,
        escape(title)
    );
    let mut start = 0;
    while start < frames.len() {
        let end = start
            + segments[start..]
                .iter()
                .take_while(|&&s| s == segments[start])
                .count();
        let curve: Vec<String> = frames[start..end]
            .iter()
            .map(|f| format!("{:.2},{:.2}", px(f[traced].0), py(f[traced].1)))
            .collect();
        writeln!(svg, "<polyline class=\"coupler-curve\" data-segment=\"{}\" fill=\"none\" stroke=\"#d1242f\" stroke-dasharray=\"4 3\" points=\"{}\"/>", segments[start], curve.join(" ")).unwrap();
        start = end;
    }
    let values = |joint: usize, axis: usize| -> String {
        frames
            .iter()
            .map(|f| {
                let p = f[joint];
                if axis == 0 {
                    format!("{:.2}", px(p.0))
                } else {
                    format!("{:.2}", py(p.1))
                }
            })
            .collect::<Vec<_>>()
            .join(";")
    };
    // The ground pivots, the joints that never move: a grounded triangle under each.
    let ground: Vec<(f64, f64)> = frames
        .first()
        .map(|first| {
            (0..first.len())
                .filter(|&joint| frames.iter().all(|f| f[joint] == first[joint]))
                .map(|joint| (px(first[joint].0), py(first[joint].1)))
                .collect()
        })
        .unwrap_or_default();
    for &(x, y) in &ground {
        writeln!(svg, "<path class=\"ground\" d=\"M{x:.2},{y:.2} l-10,16 h20 z M{:.2},{:.2} h28\" fill=\"#d0d7de\" stroke=\"#57606a\" stroke-width=\"1.5\"/>", x - 14.0, y + 16.0).unwrap();
    }
    for &(from, to) in links {
        let first = &frames[0];
        writeln!(
            svg,
            "<line class=\"link\" stroke=\"#1f2328\" stroke-width=\"3\" stroke-linecap=\"round\" x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\">",
            px(first[from].0), py(first[from].1), px(first[to].0), py(first[to].1)
        )
        .unwrap();
        for (attribute, joint, axis) in [
            ("x1", from, 0),
            ("y1", from, 1),
            ("x2", to, 0),
            ("y2", to, 1),
        ] {
            writeln!(svg, "  <animate attributeName=\"{attribute}\" dur=\"{seconds}s\" repeatCount=\"indefinite\" values=\"{}\"/>", values(joint, axis)).unwrap();
        }
        svg.push_str("</line>\n");
    }
    for &(x, y) in &ground {
        writeln!(svg, "<circle class=\"pivot\" cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"4\" fill=\"white\" stroke=\"#1f2328\" stroke-width=\"2\"/>").unwrap();
    }
    svg.push_str("</svg>\n");
    svg
}
