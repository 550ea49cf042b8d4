//! `mechanisms sweep`: a full turn (or the reachable range) on one branch, written as CSV, as
//! SVG charts and as an animated SVG of the linkage.

use std::fmt::Write as _;
use std::io::IsTerminal;
use std::path::PathBuf;

use clap::{Parser, ValueEnum};
use mechanisms::{FourBar, InvertedSliderCrank, JansenLeg, SliderCrank};
use mechgen::{Branch, Vec2};

use crate::Mechanism;
use crate::analyse::four_bar_range;
use crate::svg::{self, Chart};

#[derive(Clone, Copy, ValueEnum)]
pub enum BranchName {
    Open,
    Crossed,
}

#[derive(Parser)]
pub struct Args {
    /// The mechanism.
    #[arg(value_enum)]
    pub mechanism: Mechanism,
    /// Its dimensions in mm (an angle in degrees).
    #[arg(allow_negative_numbers = true)]
    pub dimensions: Vec<f64>,
    /// The assembly branch to follow (Jansen's leg is always as drawn).
    #[arg(long, value_enum, default_value_t = BranchName::Open)]
    pub branch: BranchName,
    /// The input's step, degrees.
    #[arg(long, default_value_t = 1.0)]
    pub step: f64,
    /// The input's rate, rad/s.
    #[arg(long, default_value_t = 10.0, allow_negative_numbers = true)]
    pub rate: f64,
    /// The input's acceleration, rad/s².
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub accel: f64,
    /// A coupler point to track and trace: distance from the crank pin (mm), angle from the
    /// coupler (°). Four-bar and slider-crank.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub coupler_point: Option<Vec<f64>>,
    /// Where to write the table.
    #[arg(long, default_value = "sweep.csv")]
    pub csv: PathBuf,
    /// Where to write the charts.
    #[arg(long, default_value = "sweep.svg")]
    pub svg: PathBuf,
    /// Where to write the animation.
    #[arg(long, default_value = "animation.svg")]
    pub animation: PathBuf,
}

/// One sample: the input (°), named values, and joint positions for the drawing.
struct Sample {
    input: f64,
    values: Vec<f64>,
    joints: Vec<(f64, f64)>,
}

/// What a mechanism's sweep produces before it is written out.
struct Sweep {
    title: String,
    /// Column names, grouped: angles or lengths, rates, accelerations, then extras.
    columns: Vec<String>,
    groups: Vec<(String, std::ops::Range<usize>)>,
    band_column: Option<usize>,
    links: Vec<(usize, usize)>,
    traced: usize,
    samples: Vec<Sample>,
}

fn point(v: Vec2<f64>) -> (f64, f64) {
    (v.x, v.y)
}

/// The inputs to visit: every `step` degrees over `[from, to]`.
fn inputs(from: f64, to: f64, step: f64) -> Vec<f64> {
    let count = ((to - from) / step).floor() as usize;
    (0..=count).map(|k| from + step * k as f64).collect()
}

/// Shows progress on a terminal for long sweeps.
fn progress(done: usize, total: usize) {
    if total >= 2000 && std::io::stderr().is_terminal() && done % (total / 20).max(1) == 0 {
        eprint!("\rsweeping: {:>3}%", done * 100 / total);
        if done + 1 >= total {
            eprintln!();
        }
    }
}

/// Visits the inputs (°) in order, showing progress, and keeps what `sample` makes of each:
/// `Ok(None)` skips an input the mechanism cannot reach, an error ends the sweep.
fn sample_inputs(
    angles: &[f64],
    mut sample: impl FnMut(f64, f64) -> Result<Option<Sample>, String>,
) -> Result<Vec<Sample>, String> {
    let mut samples = Vec::with_capacity(angles.len());
    for (k, &input) in angles.iter().enumerate() {
        progress(k, angles.len());
        if let Some(found) = sample(input, input.to_radians())? {
            samples.push(found);
        }
    }
    Ok(samples)
}

fn names(columns: &[&str]) -> Vec<String> {
    columns.iter().map(|&c| c.to_owned()).collect()
}

fn branch(args: &Args) -> Branch {
    match args.branch {
        BranchName::Open => Branch::Open,
        BranchName::Crossed => Branch::Crossed,
    }
}

fn four_bar(args: &Args) -> Result<Sweep, String> {
    let d = &args.dimensions;
    let mut linkage = FourBar::new(d[0], d[1], d[2], d[3]).map_err(|e| e.to_string())?;
    if let Some(p) = &args.coupler_point {
        linkage = linkage
            .with_coupler_point(p[0], p[1].to_radians())
            .map_err(|e| e.to_string())?;
    }
    let limits = linkage.limit_angles();
    // A crank that cannot turn fully is swept between its toggles, just inside them.
    let (from, to) = if limits.full_turn() {
        (0.0, 360.0)
    } else {
        let inside = 1e-6;
        (
            limits.folded.map_or(0.0, |f| f.to_degrees() + inside),
            limits.extended.map_or(180.0, |e| e.to_degrees() - inside),
        )
    };
    let angles = inputs(from, to, args.step);
    let samples = sample_inputs(&angles, |input, t| {
        let m = linkage
            .motion(t, branch(args), args.rate, args.accel)
            .map_err(|e| format!("at {input}°: {e}"))?;
        let p = linkage.points(t, &m.position).map_err(|e| e.to_string())?;
        Ok(Some(Sample {
            input,
            values: vec![
                m.position.theta3.to_degrees(),
                m.position.theta4.to_degrees(),
                m.velocity.theta3,
                m.velocity.theta4,
                m.acceleration.theta3,
                m.acceleration.theta4,
                linkage.transmission_angle(&m.position).to_degrees(),
                p.coupler_point.x,
                p.coupler_point.y,
            ],
            joints: vec![
                (0.0, 0.0),
                point(p.crank_pin),
                point(p.rocker_pin),
                (d[0], 0.0),
                point(p.coupler_point),
            ],
        }))
    })?;
    Ok(Sweep {
        title: format!(
            "Four-bar {} {} {} {} mm, {}",
            d[0],
            d[1],
            d[2],
            d[3],
            four_bar_range(&linkage)
        ),
        columns: names(&[
            "theta3_deg",
            "theta4_deg",
            "omega3",
            "omega4",
            "alpha3",
            "alpha4",
            "transmission_deg",
            "coupler_x",
            "coupler_y",
        ]),
        groups: vec![
            ("output angles (°)".into(), 0..2),
            ("angular velocities (rad/s)".into(), 2..4),
            ("angular accelerations (rad/s²)".into(), 4..6),
            ("transmission angle (°), 40°–140° shaded".into(), 6..7),
        ],
        band_column: Some(6),
        links: vec![(0, 1), (1, 2), (2, 3), (1, 4), (2, 4)],
        traced: 4,
        samples,
    })
}

fn slider_crank(args: &Args) -> Result<Sweep, String> {
    let d = &args.dimensions;
    let mut linkage = SliderCrank::new(d[0], d[1], d[2]).map_err(|e| e.to_string())?;
    if let Some(p) = &args.coupler_point {
        linkage = linkage
            .with_coupler_point(p[0], p[1].to_radians())
            .map_err(|e| e.to_string())?;
    }
    let angles = inputs(0.0, 360.0, args.step);
    let samples = sample_inputs(&angles, |input, t| {
        // A crank that cannot turn fully: the samples the rod can reach.
        let Ok(m) = linkage.motion(t, branch(args), args.rate, args.accel) else {
            return Ok(None);
        };
        let p = linkage.points(t, &m.position).map_err(|e| e.to_string())?;
        Ok(Some(Sample {
            input,
            values: vec![
                m.position.theta3.to_degrees(),
                m.position.d,
                m.velocity.theta3,
                m.velocity.d,
                m.acceleration.theta3,
                m.acceleration.d,
                linkage.transmission_angle(&m.position).to_degrees(),
                p.coupler_point.x,
                p.coupler_point.y,
            ],
            joints: vec![
                (0.0, 0.0),
                point(p.crank_pin),
                point(p.slider_pin),
                point(p.coupler_point),
            ],
        }))
    })?;
    if samples.is_empty() {
        return Err(
            "the slider-crank cannot be assembled at any crank angle on that branch".into(),
        );
    }
    Ok(Sweep {
        title: format!("Slider-crank {} {} mm, offset {} mm", d[0], d[1], d[2]),
        columns: names(&[
            "theta3_deg",
            "d",
            "omega3",
            "d_dot",
            "alpha3",
            "d_ddot",
            "transmission_deg",
            "coupler_x",
            "coupler_y",
        ]),
        groups: vec![
            ("rod angle (°)".into(), 0..1),
            ("slider position (mm)".into(), 1..2),
            ("rates: ω3 (rad/s), ḋ (mm/s)".into(), 2..4),
            ("accelerations: α3 (rad/s²), d̈ (mm/s²)".into(), 4..6),
            ("transmission angle (°), 40°–140° shaded".into(), 6..7),
        ],
        band_column: Some(6),
        links: vec![(0, 1), (1, 2), (1, 3), (2, 3)],
        traced: 3,
        samples,
    })
}

fn inverted(args: &Args) -> Result<Sweep, String> {
    let d = &args.dimensions;
    let linkage =
        InvertedSliderCrank::new(d[0], d[1], d[2], d[3].to_radians()).map_err(|e| e.to_string())?;
    let angles = inputs(0.0, 360.0, args.step);
    let samples = sample_inputs(&angles, |input, t| {
        let Ok(m) = linkage.motion(t, branch(args), args.rate, args.accel) else {
            return Ok(None);
        };
        let p = linkage.points(t, &m.position).map_err(|e| e.to_string())?;
        Ok(Some(Sample {
            input,
            values: vec![
                m.position.theta4.to_degrees(),
                m.position.b,
                m.velocity.theta4,
                m.velocity.b,
                m.acceleration.theta4,
                m.acceleration.b,
            ],
            joints: vec![
                (0.0, 0.0),
                point(p.crank_pin),
                (d[0], 0.0),
                point(p.slide_origin),
            ],
        }))
    })?;
    Ok(Sweep {
        title: format!(
            "Inverted slider-crank {} {} mm, offset {} mm, angle {}°",
            d[0], d[1], d[2], d[3]
        ),
        columns: names(&["theta4_deg", "b", "omega4", "b_dot", "alpha4", "b_ddot"]),
        groups: vec![
            ("rocker angle (°)".into(), 0..1),
            ("slide length (mm)".into(), 1..2),
            ("rates: ω4 (rad/s), ḃ (mm/s)".into(), 2..4),
            ("accelerations: α4 (rad/s²), b̈ (mm/s²)".into(), 4..6),
        ],
        band_column: None,
        links: vec![(0, 1), (2, 3), (3, 1)],
        traced: 1,
        samples,
    })
}

fn jansen(args: &Args) -> Result<Sweep, String> {
    let leg = JansenLeg::<f64>::holy();
    let angles = inputs(0.0, 360.0, args.step);
    let samples = sample_inputs(&angles, |input, t| {
        let m = leg
            .motion(t, JansenLeg::<f64>::DRAWN, args.rate, args.accel)
            .map_err(|e| format!("at {input}°: {e}"))?;
        let p = leg.points(t, &m.position).map_err(|e| e.to_string())?;
        let v = leg
            .point_velocities(t, &m.position, args.rate, &m.velocity)
            .map_err(|e| e.to_string())?;
        let a = leg
            .point_accelerations(
                t,
                &m.position,
                args.rate,
                &m.velocity,
                args.accel,
                &m.acceleration,
            )
            .map_err(|e| e.to_string())?;
        Ok(Some(Sample {
            input,
            values: vec![p.foot.x, p.foot.y, v.foot.x, v.foot.y, a.foot.x, a.foot.y],
            joints: vec![
                (0.0, 0.0),
                point(p.crank_pin),
                (-38.0, -7.8),
                point(p.upper),
                point(p.lower),
                point(p.back),
                point(p.knee),
                point(p.foot),
            ],
        }))
    })?;
    Ok(Sweep {
        title: "Jansen's leg, published lengths".into(),
        columns: names(&[
            "foot_x", "foot_y", "foot_vx", "foot_vy", "foot_ax", "foot_ay",
        ]),
        groups: vec![
            ("foot position (mm)".into(), 0..2),
            ("foot velocity (mm/s)".into(), 2..4),
            ("foot acceleration (mm/s²)".into(), 4..6),
        ],
        band_column: None,
        links: vec![
            (0, 1),
            (1, 3),
            (2, 3),
            (1, 4),
            (2, 4),
            (2, 5),
            (3, 5),
            (5, 6),
            (4, 6),
            (4, 7),
            (6, 7),
        ],
        traced: 7,
        samples,
    })
}

/// The CSV text: the input in degrees, then every column, to 10 significant digits.
fn csv(sweep: &Sweep) -> String {
    let mut out = format!("input_deg,{}\n", sweep.columns.join(","));
    for sample in &sweep.samples {
        let cells: Vec<String> = sample.values.iter().map(|v| format!("{v:.9e}")).collect();
        writeln!(out, "{},{}", sample.input, cells.join(",")).unwrap();
    }
    out
}

fn charts(sweep: &Sweep) -> String {
    let charts: Vec<Chart> = sweep
        .groups
        .iter()
        .map(|(title, columns)| Chart {
            title: title.clone(),
            y_label: title.split(" (").next().unwrap_or(title).to_string(),
            series: columns
                .clone()
                .map(|c| {
                    let points = sweep
                        .samples
                        .iter()
                        .map(|s| (s.input, s.values[c]))
                        .collect();
                    (sweep.columns[c].clone(), points)
                })
                .collect(),
            band: (sweep.band_column == Some(columns.start)).then_some((40.0, 140.0)),
        })
        .collect();
    svg::charts("input angle (°)", &charts)
}

pub fn run(args: &Args) -> Result<(), String> {
    args.mechanism.check(&args.dimensions)?;
    if args.coupler_point.as_ref().is_some_and(|p| p.len() != 2) {
        return Err("--coupler-point takes two numbers: distance,angle".into());
    }
    if !(args.step > 0.0 && args.step.is_finite()) {
        return Err(format!(
            "--step must be a positive number of degrees, got {}",
            args.step
        ));
    }
    let sweep = match args.mechanism {
        Mechanism::FourBar => four_bar(args)?,
        Mechanism::SliderCrank => slider_crank(args)?,
        Mechanism::InvertedSliderCrank => inverted(args)?,
        Mechanism::Jansen => jansen(args)?,
    };
    let write = |path: &PathBuf, text: String| {
        std::fs::write(path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
    };
    write(&args.csv, csv(&sweep))?;
    write(&args.svg, charts(&sweep))?;
    let frames: Vec<Vec<(f64, f64)>> = sweep.samples.iter().map(|s| s.joints.clone()).collect();
    write(
        &args.animation,
        svg::animation(&sweep.title, &sweep.links, &frames, sweep.traced, 6.0),
    )?;
    println!(
        "{}: {} samples from {}° to {}°; wrote {}, {} and {}",
        sweep.title,
        sweep.samples.len(),
        sweep.samples.first().map_or(0.0, |s| s.input),
        sweep.samples.last().map_or(0.0, |s| s.input),
        args.csv.display(),
        args.svg.display(),
        args.animation.display()
    );
    Ok(())
}
