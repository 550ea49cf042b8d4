//! Plain SVG: line charts stacked in one figure, and an animation of a linkage.

use std::fmt::Write;

/// A run of a series: the piece (segment) it belongs to, and its points.
pub type Run = (usize, Vec<(f64, f64)>);

/// One chart: a title, a y-axis label, its series `(name, runs)` with each run
/// `(segment, points)` drawn as a polyline of its own, and an optional shaded band
/// `(low, high)` (the transmission angle's 40° to 140°).
pub struct Chart {
    pub title: String,
    pub y_label: String,
    pub series: Vec<(String, Vec<Run>)>,
    pub band: Option<(f64, f64)>,
}

const COLOURS: [&str; 6] = [
    "#1f6feb", "#d1242f", "#1a7f37", "#9a6700", "#8250df", "#bc4c00",
];
const WIDTH: f64 = 720.0;
const HEIGHT: f64 = 260.0;
const MARGIN: f64 = 60.0;

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (low, high) = values.fold((f64::MAX, f64::MIN), |(l, h), v| (l.min(v), h.max(v)));
    if low >= high {
        (low - 1.0, high + 1.0)
    } else {
        (low, high)
    }
}

/// Charts stacked vertically, sharing the x axis label.
pub fn charts(x_label: &str, charts: &[Chart]) -> String {
    let total = HEIGHT * charts.len() as f64;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{total}\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    for (k, chart) in charts.iter().enumerate() {
        let top = HEIGHT * k as f64;
        let points = chart
            .series
            .iter()
            .flat_map(|(_, runs)| runs.iter().flat_map(|(_, p)| p.iter()));
        let (x0, x1) = range(points.clone().map(|p| p.0));
        let (y0, y1) = range(
            points
                .map(|p| p.1)
                .chain(chart.band.iter().flat_map(|b| [b.0, b.1])),
        );
        let px = |x: f64| MARGIN + (x - x0) / (x1 - x0) * (WIDTH - 2.0 * MARGIN);
        let py =
            |y: f64| top + HEIGHT - MARGIN * 0.7 - (y - y0) / (y1 - y0) * (HEIGHT - MARGIN * 1.4);
        writeln!(svg, "<g class=\"chart\"><text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"13\">{}</text>", WIDTH / 2.0, top + 18.0, escape(&chart.title)).unwrap();
        if let Some((low, high)) = chart.band {
            writeln!(
                svg,
                "<rect x=\"{MARGIN}\" y=\"{:.1}\" width=\"{}\" height=\"{:.1}\" fill=\"#dafbe1\"/>",
                py(high),
                WIDTH - 2.0 * MARGIN,
                py(low) - py(high)
            )
            .unwrap();
        }
        writeln!(svg, "<rect x=\"{MARGIN}\" y=\"{:.1}\" width=\"{}\" height=\"{:.1}\" fill=\"none\" stroke=\"#888\"/>", py(y1), WIDTH - 2.0 * MARGIN, py(y0) - py(y1)).unwrap();
        for (value, anchor_y) in [(y0, py(y0)), (y1, py(y1))] {
            writeln!(
                svg,
                "<text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{value:.3}</text>",
                MARGIN - 4.0,
                anchor_y + 4.0
            )
            .unwrap();
        }
        for (value, anchor_x) in [(x0, px(x0)), (x1, px(x1))] {
            writeln!(
                svg,
                "<text x=\"{anchor_x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{value:.1}</text>",
                py(y0) + 14.0
            )
            .unwrap();
        }
        writeln!(
            svg,
            "<text x=\"{}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
            WIDTH / 2.0,
            py(y0) + 26.0,
            escape(x_label)
        )
        .unwrap();
        writeln!(svg, "<text x=\"14\" y=\"{:.1}\" transform=\"rotate(-90 14 {:.1})\" text-anchor=\"middle\">{}</text>", top + HEIGHT / 2.0, top + HEIGHT / 2.0, escape(&chart.y_label)).unwrap();
        for (s, (name, runs)) in chart.series.iter().enumerate() {
            let colour = COLOURS[s % COLOURS.len()];
            for (segment, points) in runs {
                let path: Vec<String> = points
                    .iter()
                    .map(|(x, y)| format!("{:.2},{:.2}", px(*x), py(*y)))
                    .collect();
                writeln!(svg, "<polyline class=\"series\" data-name=\"{}\" data-segment=\"{segment}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\" points=\"{}\"/>", escape(name), path.join(" ")).unwrap();
            }
            writeln!(
                svg,
                "<text x=\"{}\" y=\"{:.1}\" fill=\"{colour}\">{}</text>",
                MARGIN + 8.0,
                top + 44.0 + 14.0 * s as f64,
                escape(name)
            )
            .unwrap();
        }
        svg.push_str("</g>\n");
    }
    svg.push_str("</svg>\n");
    svg
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
    let all = frames.iter().flatten();
    let (x0, x1) = range(all.clone().map(|p| p.0));
    let (y0, y1) = range(all.map(|p| p.1));
    let size = (x1 - x0).max(y1 - y0);
    let scale = (WIDTH - 2.0 * MARGIN) / size;
    let px = |x: f64| MARGIN + (x - x0) * scale;
    let py = |y: f64| MARGIN + (y1 - y) * scale;
    let height = 2.0 * MARGIN + (y1 - y0) * scale;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{height:.0}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"24\" text-anchor=\"middle\" font-size=\"14\">{}</text>\n",
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
    svg.push_str("</svg>\n");
    svg
}
