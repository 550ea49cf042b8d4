//! The charts and the animation, from a thinned copy of the samples gathered as the sweep
//! streams past.

use super::*;

/// Most points a chart's series keeps, and most frames the animation keeps: a longer sweep
/// is thinned to these, evenly, so the drawings take bounded memory however long it is.
pub(super) const CHART_POINTS: f64 = 4000.0;

pub(super) const FRAMES: f64 = 720.0;

/// The thinned samples the drawings are made from, gathered as the sweep streams past.
pub(super) struct Drawings {
    pub(super) chart_stride: u64,
    pub(super) frame_stride: u64,
    /// Per column, its runs of points `(segment, points)`: a new run at each piece and after
    /// each sample that could not be computed, so no line is drawn across either.
    pub(super) series: Vec<Vec<svg::Run>>,
    pub(super) frames: Vec<Vec<(f64, f64)>>,
    pub(super) frame_segments: Vec<usize>,
    pub(super) broken: bool,
    /// The change points the sweep crossed, degrees, marked on the charts.
    pub(super) markers: Vec<f64>,
}

impl Drawings {
    pub(super) fn new(columns: usize, total: u64) -> Self {
        let stride = |most: f64| ((total as f64 / most).ceil() as u64).max(1);
        Drawings {
            chart_stride: stride(CHART_POINTS),
            frame_stride: stride(FRAMES),
            series: vec![Vec::new(); columns],
            frames: Vec::new(),
            frame_segments: Vec::new(),
            broken: true,
            markers: Vec::new(),
        }
    }

    /// Takes the sample numbered `index` of the whole sweep if the thinning keeps it (or
    /// `last`, the end of a piece, which is always kept).
    pub(super) fn add(
        &mut self,
        index: u64,
        last: bool,
        segment: usize,
        input: f64,
        sample: &Sample,
    ) {
        if index % self.chart_stride == 0 || last || self.broken {
            for (column, runs) in self.series.iter_mut().enumerate() {
                if self.broken || runs.last().is_none_or(|run| run.0 != segment) {
                    runs.push((segment, Vec::new()));
                }
                let run = &mut runs.last_mut().expect("a run was just pushed").1;
                run.push((input, sample.values[column]));
            }
            self.broken = false;
        }
        if index % self.frame_stride == 0 || last {
            self.frames.push(sample.joints.clone());
            self.frame_segments.push(segment);
        }
    }
}

/// The charts, one per unit (a chart's title ends in its unit, in brackets): series
/// labelled with their symbols, angles unwrapped along each run so a turn draws no jump.
pub(super) fn charts(sweep: &Sweep, drawings: &Drawings) -> Result<String, String> {
    let charts: Vec<Chart> = sweep
        .groups
        .iter()
        .map(|(title, columns)| {
            let unit = title
                .rsplit_once(" (")
                .and_then(|(_, unit)| unit.split(')').next())
                .unwrap_or("")
                .to_string();
            let band = (sweep.band_column == Some(columns.start)).then_some((40.0, 140.0));
            let angles = unit == "°" && band.is_none();
            Chart {
                title: title.clone(),
                unit: if unit == "°" {
                    "angle (°)".into()
                } else {
                    unit
                },
                series: columns
                    .clone()
                    .map(|c| {
                        let runs = drawings.series[c].clone();
                        let runs = if angles { unwrapped(runs) } else { runs };
                        (symbol(&sweep.columns[c]), runs)
                    })
                    .collect(),
                band,
            }
        })
        .collect();
    svg::charts("input angle (°)", &charts, &drawings.markers)
}

/// Runs of angles in degrees with every jump of more than half a turn taken out, so an
/// angle that passes ±180° draws on past it: within a run, and from one run to the next of
/// the same piece (across a sample that could not be computed, such as a change point).
pub(super) fn unwrapped(runs: Vec<svg::Run>) -> Vec<svg::Run> {
    let mut turns = 0.0;
    let mut last: Option<(usize, f64)> = None;
    runs.into_iter()
        .map(|(segment, points)| {
            if last.is_some_and(|(piece, _)| piece != segment) {
                (turns, last) = (0.0, None);
            }
            let points = points
                .into_iter()
                .map(|(x, y)| {
                    if let Some((_, previous)) = last {
                        turns -= 360.0 * ((y - previous) / 360.0).round();
                    }
                    last = Some((segment, y));
                    (x, y + turns)
                })
                .collect();
            (segment, points)
        })
        .collect()
}

/// A column's symbol for a legend.
pub(super) fn symbol(column: &str) -> String {
    let symbol = match column {
        "theta3_deg" => "θ3",
        "theta4_deg" => "θ4",
        "omega3" => "ω3",
        "omega4" => "ω4",
        "alpha3" => "α3",
        "alpha4" => "α4",
        "transmission_deg" => "μ",
        "d_dot" => "ḋ",
        "d_ddot" => "d̈",
        "b_dot" => "ḃ",
        "b_ddot" => "b̈",
        "foot_x" => "x",
        "foot_y" => "y",
        "foot_vx" => "vx",
        "foot_vy" => "vy",
        "foot_ax" => "ax",
        "foot_ay" => "ay",
        "theta5_deg" => "θ5",
        "theta6_deg" => "θ6",
        "omega5" => "ω5",
        "omega6" => "ω6",
        "alpha5" => "α5",
        "alpha6" => "α6",
        other => other,
    };
    symbol.to_string()
}

#[cfg(test)]
mod tests {
    use super::{svg, unwrapped};

    #[test]
    pub(super) fn an_angle_that_passes_half_a_turn_draws_on_past_it() {
        let angles = |runs: Vec<svg::Run>| -> Vec<Vec<f64>> {
            unwrapped(runs)
                .into_iter()
                .map(|(_, points)| points.iter().map(|p| p.1).collect())
                .collect()
        };
        let run = (
            1,
            vec![(0.0, 170.0), (1.0, 179.0), (2.0, -172.0), (3.0, -160.0)],
        );
        assert_eq!(angles(vec![run]), [[170.0, 179.0, 188.0, 200.0]]);
        // Down through −180° and back up through it.
        let run = vec![
            (0.0, -170.0),
            (1.0, 175.0),
            (2.0, 165.0),
            (3.0, -178.0),
            (4.0, 176.0),
        ];
        assert_eq!(
            angles(vec![(2, run)]),
            [[-170.0, -185.0, -195.0, -178.0, -184.0]]
        );
        // Across a gap in the same piece (a change point), but not into another piece.
        let runs = vec![
            (1, vec![(178.0, 178.0), (179.0, 179.0)]),
            (1, vec![(181.0, -179.0), (182.0, -178.0)]),
            (2, vec![(300.0, -60.0)]),
        ];
        assert_eq!(
            angles(runs),
            [vec![178.0, 179.0], vec![181.0, 182.0], vec![-60.0]]
        );
    }
}
