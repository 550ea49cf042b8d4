//! `mechanisms sweep`: the input's reachable ranges on one branch, streamed sample by sample
//! to a CSV table (a file, or standard output for `-`), with SVG charts and an animated SVG of
//! the linkage drawn from a thinned copy, so a sweep takes the same memory however long.

use std::fmt::Write as _;
use std::fs::File;
use std::io::{self, BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use clap::{Parser, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget};
use mechanisms::{
    FourBar, InvertedSliderCrank, JansenLeg, SliderCrank, StephensonSixBar,
    StephensonSixBarUnknowns,
};
use mechgen::sweep::{Stop, Sweep as Walk};
use mechgen::{Branch, Error, NewtonOptions, Vec2};

use crate::Mechanism;
use crate::analyse::four_bar_range;
use crate::output::{self, say, tidy};
use crate::six_bars::{self, Reach, StephensonDimensions};
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
    /// The assembly branch to follow [default: open]; one per loop for the Watt six-bar, as
    /// `open,crossed` [default: open,open]. Not for Jansen's leg (always as drawn) nor the
    /// Stephenson six-bar (followed by Newton from its first assembly).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub branch: Option<Vec<BranchName>>,
    /// The input's step, degrees.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub step: f64,
    /// The most samples a sweep may take: a smaller step is refused before it starts.
    #[arg(long, default_value_t = 10_000_000)]
    pub max_samples: u64,
    /// The input's rate, rad/s.
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true)]
    pub rate: f64,
    /// The input's acceleration, rad/s².
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub accel: f64,
    /// A coupler point to track and trace: distance from the crank pin (mm), angle from the
    /// coupler (°), as `100,30`. Four-bar and slider-crank.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub coupler_point: Option<Vec<f64>>,
    /// The directory the files are written to, created if missing.
    #[arg(long, default_value = ".")]
    pub out_dir: PathBuf,
    /// Where to write the table, in --out-dir; `-` for standard output.
    #[arg(long, default_value = "sweep.csv")]
    pub csv: PathBuf,
    /// Where to write the charts, in --out-dir; `-` for standard output.
    #[arg(long, default_value = "sweep.svg")]
    pub svg: PathBuf,
    /// Where to write the animation, in --out-dir; `-` for standard output.
    #[arg(long, default_value = "animation.svg")]
    pub animation: PathBuf,
}

/// One sample: named values, and joint positions for the drawing.
struct Sample {
    values: Vec<f64>,
    joints: Vec<(f64, f64)>,
}

/// What a mechanism's sweep is made of, before any sample is computed.
struct Sweep<'a> {
    title: String,
    /// Column names, grouped: angles or lengths, rates, accelerations, then extras.
    columns: Vec<String>,
    groups: Vec<(String, std::ops::Range<usize>)>,
    band_column: Option<usize>,
    links: Vec<(usize, usize)>,
    traced: usize,
    /// The input's reachable ranges, in order.
    pieces: Vec<Piece>,
    /// The inputs (degrees, in `[0°, 360°)`, repeating every turn) where the linkage lies
    /// flat at a change point: singular, the branches meet, and the motion goes on smoothly
    /// only on the other closed-form branch.
    change_points: Vec<f64>,
    /// The sample at an input in degrees, on the requested branch or (`true`) the other one,
    /// after a change point. It may keep state: a mechanism solved by Newton continues from
    /// its last position, so the inputs of a piece come in order.
    sample: Box<dyn FnMut(f64, bool) -> Result<Sample, Error<f64>> + 'a>,
}

/// A reachable range of the input, degrees. A full turn is sampled from its start, ends
/// included; a range that ends at toggles (where the rates are unbounded and the branches
/// meet) is sampled every step from its middle, a regular point, out toward both ends,
/// strictly inside them.
#[derive(Clone, Debug, PartialEq)]
struct Piece {
    from: f64,
    to: f64,
    full_turn: bool,
    /// The piece in words, for the summary.
    words: String,
}

impl Piece {
    fn full_turn() -> Self {
        Piece {
            from: 0.0,
            to: 360.0,
            full_turn: true,
            words: "a full turn".into(),
        }
    }

    fn between(from: f64, to: f64) -> Self {
        Piece {
            from,
            to,
            full_turn: false,
            words: format!(
                "{}° to {}° (toggles at the ends)",
                output::fixed(from, 2),
                output::fixed(to, 2)
            ),
        }
    }

    /// The first input and the number of samples, as a float so a tiny step cannot overflow
    /// the count before it is checked.
    fn grid(&self, step: f64) -> (f64, f64) {
        if self.full_turn {
            (self.from, ((self.to - self.from) / step).floor() + 1.0)
        } else {
            let middle = 0.5 * (self.from + self.to);
            let beside = ((0.5 * (self.to - self.from)) / step).ceil() - 1.0;
            let beside = beside.max(0.0);
            (middle - beside * step, 2.0 * beside + 1.0)
        }
    }
}

fn point(v: Vec2<f64>) -> (f64, f64) {
    (v.x, v.y)
}

fn names(columns: &[&str]) -> Vec<String> {
    columns.iter().map(|&c| c.to_owned()).collect()
}

/// The branch of loop `which` (0 for the first) given by `--branch`, open if not given.
fn branch_of(args: &Args, which: usize) -> Branch {
    match args.branch.as_ref().and_then(|b| b.get(which)) {
        Some(BranchName::Crossed) => Branch::Crossed,
        Some(BranchName::Open) | None => Branch::Open,
    }
}

fn branch(args: &Args) -> Branch {
    branch_of(args, 0)
}

/// A four-bar crank's reachable ranges from its closed-form limit angles: `|θ2|` between the
/// folded limit (or 0) and the extended limit (or 180°), so one range through 0° or 180°, or
/// two mirror-image ranges.
fn four_bar_pieces(linkage: &FourBar<f64>) -> Vec<Piece> {
    let limits = linkage.limit_angles();
    let pieces = match (
        limits.folded.map(f64::to_degrees),
        limits.extended.map(f64::to_degrees),
    ) {
        (None, None) => vec![Piece::full_turn()],
        (Some(f), None) => vec![Piece::between(f, 360.0 - f)],
        (None, Some(e)) => vec![Piece::between(-e, e)],
        (Some(f), Some(e)) => vec![Piece::between(f, e), Piece::between(360.0 - e, 360.0 - f)],
    };
    pieces.into_iter().filter(|p| p.from < p.to).collect()
}

/// A slider-crank's reachable ranges: the rod reaches the slider's line where
/// `|c − l2·sin θ2| ≤ l3`, so where `sin θ2` lies in `[(c − l3)/l2, (c + l3)/l2]`.
fn slider_crank_pieces(linkage: &SliderCrank<f64>) -> Vec<Piece> {
    if linkage.crank_turns_fully() {
        return vec![Piece::full_turn()];
    }
    let [l2, l3, c] = linkage.dimensions();
    let (low, high) = ((c - l3) / l2, (c + l3) / l2);
    let arc = |s: f64| s.clamp(-1.0, 1.0).asin().to_degrees();
    let pieces = if low > -1.0 && high < 1.0 {
        vec![
            Piece::between(arc(low), arc(high)),
            Piece::between(180.0 - arc(high), 180.0 - arc(low)),
        ]
    } else if high < 1.0 {
        vec![Piece::between(180.0 - arc(high), 360.0 + arc(high))]
    } else {
        vec![Piece::between(arc(low), 180.0 - arc(low))]
    };
    pieces.into_iter().filter(|p| p.from < p.to).collect()
}

/// An inverted slider-crank's reachable range: the slide passes at `|c·sin γ|` from O4, so
/// the crank pin A must be at least that far from O4, `|A − O4|² = l1² + l2² − 2·l1·l2·cos θ2`.
fn inverted_pieces(linkage: &InvertedSliderCrank<f64>) -> Vec<Piece> {
    let [l1, l2, c, gamma] = linkage.dimensions();
    // On the linkage scaled to its largest dimension, where no square overflows.
    let scale = l1.max(l2).max(c.abs());
    let (l1, l2, reach) = (l1 / scale, l2 / scale, (c * gamma.sin()).abs() / scale);
    if reach <= (l1 - l2).abs() {
        return vec![Piece::full_turn()];
    }
    let cosine = ((l1 * l1 + l2 * l2 - reach * reach) / (2.0 * l1 * l2)).clamp(-1.0, 1.0);
    let limit = cosine.acos().to_degrees();
    [Piece::between(limit, 360.0 - limit)]
        .into_iter()
        .filter(|p| p.from < p.to)
        .collect()
}

/// Whether two lengths of a linkage whose longest is `longest` are equal to rounding.
fn equal_lengths(a: f64, b: f64, longest: f64) -> bool {
    (a - b).abs() <= 8.0 * f64::EPSILON * longest
}

/// A four-bar's change points: the chord O4 − A is shortest at 0° (`|l1 − l2|`) and longest
/// at 180° (`l1 + l2`); where that extreme equals the shortest (`|l3 − l4|`) or longest
/// (`l3 + l4`) chord the dyad closes over, the linkage lies flat there and goes on, on the
/// other branch. (Where 0°'s chord equals `l3 + l4`, or 180°'s `|l3 − l4|`, it assembles at
/// that input alone: no piece holds it.)
fn four_bar_change_points(linkage: &FourBar<f64>) -> Vec<f64> {
    let longest = linkage.lengths().into_iter().fold(0.0, f64::max);
    // On lengths scaled to the longest, where no sum overflows.
    let [l1, l2, l3, l4] = linkage.lengths().map(|l| l / longest);
    let mut points = Vec::new();
    if equal_lengths((l1 - l2).abs(), (l3 - l4).abs(), 1.0) {
        points.push(0.0);
    }
    if equal_lengths(l1 + l2, l3 + l4, 1.0) {
        points.push(180.0);
    }
    points
}

/// A slider-crank's change points: the rod is square to the slide (`|c − l2·sin θ2| = l3`)
/// at an extreme of `c − l2·sin θ2`, at 90° (`c − l2`) or 270° (`c + l2`): crank and rod
/// equal, say, with no offset.
fn slider_crank_change_points(linkage: &SliderCrank<f64>) -> Vec<f64> {
    let dimensions = linkage.dimensions();
    let longest = dimensions.iter().fold(0.0, |m: f64, d| m.max(d.abs()));
    let [l2, l3, c] = dimensions.map(|d| d / longest);
    [(90.0, c - l2), (270.0, c + l2)]
        .into_iter()
        .filter(|(_, reach)| equal_lengths(reach.abs(), l3, 1.0))
        .map(|(at, _)| at)
        .collect()
}

/// An inverted slider-crank's change point: the crank pin A comes closest to O4 at 0°
/// (`|l1 − l2|`); where that is the slide's distance from O4 (`|c·sin γ|`), the slide passes
/// through A there, square to the chord (the isosceles linkage, `l1 = l2`, `c·sin γ = 0`).
fn inverted_change_points(linkage: &InvertedSliderCrank<f64>) -> Vec<f64> {
    let [l1, l2, c, gamma] = linkage.dimensions();
    let longest = l1.max(l2).max(c.abs());
    let (l1, l2, reach) = (
        l1 / longest,
        l2 / longest,
        (c * gamma.sin()).abs() / longest,
    );
    if equal_lengths((l1 - l2).abs(), reach, 1.0) {
        vec![0.0]
    } else {
        Vec::new()
    }
}

/// The change points (`points`, each repeating every turn) in `(from, to]`.
fn crossed(points: &[f64], from: f64, to: f64) -> impl Iterator<Item = f64> + '_ {
    points.iter().flat_map(move |&point| {
        let first = ((from - point) / 360.0).floor() as i64;
        let last = ((to - point) / 360.0).ceil() as i64;
        (first..=last)
            .map(move |turn| point + 360.0 * turn as f64)
            .filter(move |&at| from < at && at <= to)
    })
}

fn four_bar(args: &Args) -> Result<Sweep<'_>, String> {
    let d = &args.dimensions;
    let mut linkage = FourBar::new(d[0], d[1], d[2], d[3]).map_err(|e| e.to_string())?;
    if let Some(p) = &args.coupler_point {
        linkage = linkage
            .with_coupler_point(p[0], p[1].to_radians())
            .map_err(|e| e.to_string())?;
    }
    let (rate, accel, on) = (args.rate, args.accel, branch(args));
    let ground = d[0];
    Ok(Sweep {
        title: format!(
            "Four-bar {} {} {} {} mm, {}",
            tidy(d[0]),
            tidy(d[1]),
            tidy(d[2]),
            tidy(d[3]),
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
        pieces: four_bar_pieces(&linkage),
        change_points: four_bar_change_points(&linkage),
        sample: Box::new(move |input, flipped| {
            let t = input.to_radians();
            let on = if flipped { on.other() } else { on };
            let m = linkage.motion(t, on, rate, accel)?;
            let p = linkage.points(t, &m.position)?;
            Ok(Sample {
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
                    (ground, 0.0),
                    point(p.coupler_point),
                ],
            })
        }),
    })
}

fn slider_crank(args: &Args) -> Result<Sweep<'_>, String> {
    let d = &args.dimensions;
    let mut linkage = SliderCrank::new(d[0], d[1], d[2]).map_err(|e| e.to_string())?;
    if let Some(p) = &args.coupler_point {
        linkage = linkage
            .with_coupler_point(p[0], p[1].to_radians())
            .map_err(|e| e.to_string())?;
    }
    let (rate, accel, on) = (args.rate, args.accel, branch(args));
    Ok(Sweep {
        title: format!(
            "Slider-crank {} {} mm, offset {} mm",
            tidy(d[0]),
            tidy(d[1]),
            tidy(d[2])
        ),
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
            ("rod angular velocity (rad/s)".into(), 2..3),
            ("slider velocity (mm/s)".into(), 3..4),
            ("rod angular acceleration (rad/s²)".into(), 4..5),
            ("slider acceleration (mm/s²)".into(), 5..6),
            ("transmission angle (°), 40°–140° shaded".into(), 6..7),
        ],
        band_column: Some(6),
        links: vec![(0, 1), (1, 2), (1, 3), (2, 3)],
        traced: 3,
        pieces: slider_crank_pieces(&linkage),
        change_points: slider_crank_change_points(&linkage),
        sample: Box::new(move |input, flipped| {
            let t = input.to_radians();
            let on = if flipped { on.other() } else { on };
            let m = linkage.motion(t, on, rate, accel)?;
            let p = linkage.points(t, &m.position)?;
            Ok(Sample {
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
            })
        }),
    })
}

fn inverted(args: &Args) -> Result<Sweep<'_>, String> {
    let d = &args.dimensions;
    let linkage =
        InvertedSliderCrank::new(d[0], d[1], d[2], d[3].to_radians()).map_err(|e| e.to_string())?;
    let (rate, accel, on) = (args.rate, args.accel, branch(args));
    let ground = d[0];
    Ok(Sweep {
        title: format!(
            "Inverted slider-crank {} {} mm, offset {} mm, angle {}°",
            tidy(d[0]),
            tidy(d[1]),
            tidy(d[2]),
            tidy(d[3])
        ),
        columns: names(&["theta4_deg", "b", "omega4", "b_dot", "alpha4", "b_ddot"]),
        groups: vec![
            ("rocker angle (°)".into(), 0..1),
            ("slide length (mm)".into(), 1..2),
            ("rocker angular velocity (rad/s)".into(), 2..3),
            ("slide velocity (mm/s)".into(), 3..4),
            ("rocker angular acceleration (rad/s²)".into(), 4..5),
            ("slide acceleration (mm/s²)".into(), 5..6),
        ],
        band_column: None,
        links: vec![(0, 1), (2, 3), (3, 1)],
        traced: 1,
        pieces: inverted_pieces(&linkage),
        change_points: inverted_change_points(&linkage),
        sample: Box::new(move |input, flipped| {
            let t = input.to_radians();
            let on = if flipped { on.other() } else { on };
            let m = linkage.motion(t, on, rate, accel)?;
            let p = linkage.points(t, &m.position)?;
            Ok(Sample {
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
                    (ground, 0.0),
                    point(p.slide_origin),
                ],
            })
        }),
    })
}

fn jansen(args: &Args) -> Result<Sweep<'_>, String> {
    let leg = JansenLeg::<f64>::holy();
    let (rate, accel) = (args.rate, args.accel);
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
        pieces: vec![Piece::full_turn()],
        change_points: Vec::new(),
        sample: Box::new(move |input, _| {
            let t = input.to_radians();
            let m = leg.motion(t, JansenLeg::<f64>::DRAWN, rate, accel)?;
            let p = leg.points(t, &m.position)?;
            let v = leg.point_velocities(t, &m.position, rate, &m.velocity)?;
            let a =
                leg.point_accelerations(t, &m.position, rate, &m.velocity, accel, &m.acceleration)?;
            Ok(Sample {
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
            })
        }),
    })
}

/// A six-bar's columns: its four unknowns' angles, rates and accelerations.
fn six_bar_columns() -> (Vec<String>, Vec<(String, std::ops::Range<usize>)>) {
    (
        names(&[
            "theta3_deg",
            "theta4_deg",
            "theta5_deg",
            "theta6_deg",
            "omega3",
            "omega4",
            "omega5",
            "omega6",
            "alpha3",
            "alpha4",
            "alpha5",
            "alpha6",
        ]),
        vec![
            ("link angles (°)".into(), 0..4),
            ("angular velocities (rad/s)".into(), 4..8),
            ("angular accelerations (rad/s²)".into(), 8..12),
        ],
    )
}

/// A six-bar's values: angles in degrees, then rates, then accelerations.
fn six_bar_values(position: [f64; 4], velocity: [f64; 4], acceleration: [f64; 4]) -> Vec<f64> {
    position
        .iter()
        .map(|t| t.to_degrees())
        .chain(velocity)
        .chain(acceleration)
        .collect()
}

fn watt(args: &Args) -> Result<Sweep<'_>, String> {
    let d = &args.dimensions;
    let linkage = six_bars::watt(d)?;
    let (rate, accel) = (args.rate, args.accel);
    let on = [branch_of(args, 0), branch_of(args, 1)];
    let pieces = match six_bars::watt_reach(&linkage, on) {
        Reach::FullTurn => vec![Piece::full_turn()],
        Reach::Ranges(ranges) => ranges
            .into_iter()
            .map(|(from, to)| Piece::between(from, to))
            .collect(),
    };
    let (columns, groups) = six_bar_columns();
    let pivot = (d[8], d[9]);
    let ground = d[0];
    let word = |b: Branch| if b == Branch::Open { "open" } else { "crossed" };
    Ok(Sweep {
        title: format!(
            "Watt six-bar {} {} {} {} mm, extension {} mm at {}°, {} {} mm, O6 ({}, {}) mm, \
             branches {},{}",
            tidy(d[0]),
            tidy(d[1]),
            tidy(d[2]),
            tidy(d[3]),
            tidy(d[4]),
            tidy(d[5]),
            tidy(d[6]),
            tidy(d[7]),
            tidy(d[8]),
            tidy(d[9]),
            word(on[0]),
            word(on[1])
        ),
        columns,
        groups,
        band_column: None,
        // O2 A B O4 C D O6; the rocker O4 B C is a ternary link.
        links: vec![(0, 1), (1, 2), (2, 3), (3, 4), (2, 4), (4, 5), (5, 6)],
        traced: 5,
        pieces,
        change_points: Vec::new(),
        sample: Box::new(move |input, _| {
            let t = input.to_radians();
            let m = linkage.motion(t, on, rate, accel)?;
            let p = linkage.points(t, &m.position)?;
            Ok(Sample {
                values: six_bar_values(
                    m.position.to_array(),
                    m.velocity.to_array(),
                    m.acceleration.to_array(),
                ),
                joints: vec![
                    (0.0, 0.0),
                    point(p.crank_pin),
                    point(p.rocker_pin),
                    (ground, 0.0),
                    point(p.extension_pin),
                    point(p.output_pin),
                    pivot,
                ],
            })
        }),
    })
}

/// Where a walk stopped, in words.
fn stop_words(stop: &Stop<f64>) -> &'static str {
    match stop {
        Stop::Toggle { .. } => "a toggle",
        Stop::BranchChange { .. } => "a change point",
    }
}

/// Where a walk of `steps` steps of `step` from `start` stops: the last input it reaches
/// (radians) and the position there, and why it stopped, if it did. The walk reports only the step it could not
/// finish, so the end is then closed in on by halving: from the last position reached, a
/// step of half the last length is tried, kept if the walk finishes it, halved again if
/// not, down to the input's rounding.
fn edge(
    linkage: &StephensonSixBar<f64>,
    start: f64,
    position: [f64; 4],
    step: f64,
    steps: u32,
) -> ((f64, [f64; 4]), Option<Stop<f64>>) {
    let options = NewtonOptions::default();
    let mut last = (start, position);
    let mut stop = None;
    for sample in Walk::new(linkage, start, position, step, steps, options) {
        match sample {
            Ok(sample) => last = (sample.input, sample.position),
            Err(why) => {
                stop = Some(why);
                break;
            }
        }
    }
    let Some(stop) = stop else {
        return (last, None);
    };
    let mut length = 0.5 * step;
    for _ in 0..200 {
        if last.0 + length == last.0 {
            break;
        }
        match Walk::new(linkage, last.0, last.1, length, 1, options).last() {
            Some(Ok(sample)) => last = (sample.input, sample.position),
            _ => length *= 0.5,
        }
    }
    (last, Some(stop))
}

/// The Stephenson six-bar, which has no closed form. Its start is its first assembly (in
/// the scan's order, see `six_bars::stephenson_assemblies`) at the first whole degree from 0°
/// where it has one. From there `mechgen::sweep::Sweep` walks it up, degree by degree, and
/// down, each way until it stops at a toggle (or a change point) or has gone a full turn
/// between them: that is the reachable piece. Other assemblies' circuits are not followed.
/// Each sample then walks on from the last one, so Newton always starts near its root.
fn stephenson(args: &Args) -> Result<Sweep<'_>, String> {
    let d = &args.dimensions;
    let linkage = six_bars::stephenson(d)?;
    let dimensions = StephensonDimensions::new(d);
    let Some((start, position)) = (0..360).find_map(|degree| {
        let input = f64::from(degree);
        six_bars::stephenson_assemblies(&linkage, &dimensions, input.to_radians())
            .first()
            .map(|q| (input, q.to_array()))
    }) else {
        return Err(
            "the stephenson-six-bar cannot be assembled at any input angle: at no \
                    whole degree does any position close both loops"
                .into(),
        );
    };
    let options = NewtonOptions::default();
    let degree = 1f64.to_radians();
    let walk = |step: f64, steps: u32| edge(&linkage, start.to_radians(), position, step, steps);
    let (piece, shift) = match walk(degree, 360) {
        (end, None) => {
            // A circuit may need more than one turn of the input to close; the sweep draws
            // one, from its start, and says so.
            let turn = std::f64::consts::TAU;
            let back = end.1.iter().zip(position).all(|(a, b)| {
                let d = (a - b).rem_euclid(turn);
                d.min(turn - d) < 1e-6
            });
            let mut piece = Piece::full_turn();
            piece.words = format!(
                "a full turn (followed by Newton from its assembly at {}°{})",
                tidy(start),
                if back {
                    ""
                } else {
                    "; after a turn it is not back where it started: its circuit takes more \
                     turns of the input, and the sweep draws the first"
                }
            );
            (piece, 0.0)
        }
        ((high, _), Some(up)) => {
            let high = high.to_degrees();
            let left = 360 - ((high - start).ceil().max(0.0) as u32).min(360);
            let ((low, _), down) = walk(-degree, left);
            let low = low.to_degrees();
            // Whole turns, so the piece reads as the other mechanisms' do.
            let shift = low - six_bars::normal(low, high).0;
            let mut piece = Piece::between(low - shift, high - shift);
            piece.words = format!(
                "{}° to {}° ({} below, {} above, where Newton's walk from its assembly at {}° \
                 stopped)",
                output::fixed(piece.from, 2),
                output::fixed(piece.to, 2),
                down.as_ref().map_or("a full turn", stop_words),
                stop_words(&up),
                tidy(start - shift)
            );
            (piece, shift)
        }
    };
    let (rate, accel) = (args.rate, args.accel);
    let (ground, pivot) = (d[0], (d[8], d[9]));
    let (columns, groups) = six_bar_columns();
    // Where the walk to the next sample starts: the last position solved.
    let mut last = ((start - shift).to_radians(), position);
    Ok(Sweep {
        title: format!(
            "Stephenson six-bar {} {} {} mm, ternary {} {} mm at {}°, rockers {} {} mm, \
             O6 ({}, {}) mm",
            tidy(d[0]),
            tidy(d[1]),
            tidy(d[2]),
            tidy(d[3]),
            tidy(d[4]),
            tidy(d[5]),
            tidy(d[6]),
            tidy(d[7]),
            tidy(d[8]),
            tidy(d[9])
        ),
        columns,
        groups,
        band_column: None,
        // O2 A B C O4 D O6; B C D is the floating ternary link.
        links: vec![(0, 1), (1, 2), (2, 3), (3, 4), (3, 5), (2, 5), (5, 6)],
        traced: 2,
        pieces: vec![piece],
        change_points: Vec::new(),
        sample: Box::new(move |input, _| {
            let t = input.to_radians();
            let distance = t - last.0;
            let q = if distance == 0.0 {
                last.1
            } else {
                let steps = (distance.abs() / degree)
                    .ceil()
                    .clamp(1.0, f64::from(u32::MAX));
                let mut walk = Walk::new(
                    &linkage,
                    last.0,
                    last.1,
                    distance / steps,
                    steps as u32,
                    options,
                );
                match walk.by_ref().last() {
                    Some(Ok(sample)) => sample.position,
                    Some(Err(Stop::Toggle { error, .. })) => return Err(error),
                    Some(Err(Stop::BranchChange { .. })) | None => return Err(Error::OtherBranch),
                }
            };
            last = (t, q);
            let position = StephensonSixBarUnknowns::from_array(q);
            let m = linkage.motion_at(t, &position, rate, accel)?;
            let p = linkage.points(t, &position)?;
            Ok(Sample {
                values: six_bar_values(q, m.velocity.to_array(), m.acceleration.to_array()),
                joints: vec![
                    (0.0, 0.0),
                    point(p.crank_pin),
                    point(p.b),
                    point(p.c),
                    (ground, 0.0),
                    point(p.d),
                    pivot,
                ],
            })
        }),
    })
}

/// Most points a chart's series keeps, and most frames the animation keeps: a longer sweep
/// is thinned to these, evenly, so the drawings take bounded memory however long it is.
const CHART_POINTS: f64 = 4000.0;
const FRAMES: f64 = 720.0;

/// The thinned samples the drawings are made from, gathered as the sweep streams past.
struct Drawings {
    chart_stride: u64,
    frame_stride: u64,
    /// Per column, its runs of points `(segment, points)`: a new run at each piece and after
    /// each sample that could not be computed, so no line is drawn across either.
    series: Vec<Vec<svg::Run>>,
    frames: Vec<Vec<(f64, f64)>>,
    frame_segments: Vec<usize>,
    broken: bool,
    /// The change points the sweep crossed, degrees, marked on the charts.
    markers: Vec<f64>,
}

impl Drawings {
    fn new(columns: usize, total: u64) -> Self {
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
    fn add(&mut self, index: u64, last: bool, segment: usize, input: f64, sample: &Sample) {
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

/// Samples that could not be computed inside a piece, by reason, with the first few inputs.
#[derive(Default)]
struct Failures {
    singular: u64,
    inaccurate: u64,
    overflow: u64,
    other: u64,
    first: Vec<(f64, String)>,
}

impl Failures {
    fn count(&self) -> u64 {
        self.singular + self.inaccurate + self.overflow + self.other
    }

    fn add(&mut self, input: f64, error: &Error<f64>) {
        let why = match error {
            Error::Singular { .. } => {
                self.singular += 1;
                "singular".to_string()
            }
            Error::Inaccurate { estimate, .. } => {
                self.inaccurate += 1;
                format!("inaccurate, estimated error {estimate:.1e}")
            }
            Error::NonFinite { quantity } => {
                self.overflow += 1;
                format!("{quantity} not finite (overflow)")
            }
            other => {
                self.other += 1;
                other.to_string()
            }
        };
        if self.first.len() < 3 {
            self.first.push((input, why));
        }
    }

    /// "3 not computed (2 singular, 1 inaccurate): at 0° singular, …", or nothing.
    fn words(&self) -> Option<String> {
        if self.count() == 0 {
            return None;
        }
        let kinds: Vec<String> = [
            (self.singular, "singular"),
            (self.inaccurate, "inaccurate"),
            (self.overflow, "not finite"),
            (self.other, "other"),
        ]
        .into_iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, kind)| format!("{n} {kind}"))
        .collect();
        let at: Vec<String> = self
            .first
            .iter()
            .map(|(input, why)| format!("{}° {why}", tidy(*input)))
            .collect();
        Some(format!(
            "{} not computed ({}): at {}{}",
            self.count(),
            kinds.join(", "),
            at.join(", "),
            if self.count() > self.first.len() as u64 {
                ", …"
            } else {
                ""
            }
        ))
    }
}

/// Where an output goes: standard output for `-`, else the path under `--out-dir`.
enum Target {
    Stdout,
    File(PathBuf),
}

impl Target {
    fn new(path: &Path, out_dir: &Path) -> Self {
        if path == Path::new("-") {
            Target::Stdout
        } else {
            Target::File(out_dir.join(path))
        }
    }

    fn name(&self) -> String {
        match self {
            Target::Stdout => "standard output".into(),
            Target::File(path) => path.display().to_string(),
        }
    }

    fn open(&self) -> Result<Box<dyn Write>, String> {
        Ok(match self {
            Target::Stdout => Box::new(BufWriter::new(io::stdout())),
            Target::File(path) => Box::new(BufWriter::new(
                File::create(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?,
            )),
        })
    }

    /// A failed write: a closed pipe ends the program quietly, anything else is an error.
    fn failed(&self, error: io::Error) -> String {
        match self {
            Target::Stdout => output::gone(error),
            Target::File(path) => format!("cannot write {}: {error}", path.display()),
        }
    }

    fn write(&self, text: &str) -> Result<(), String> {
        let mut out = self.open()?;
        out.write_all(text.as_bytes())
            .and_then(|()| out.flush())
            .map_err(|e| self.failed(e))
    }
}

/// The charts, one per unit (a chart's title ends in its unit, in brackets): series
/// labelled with their symbols, angles unwrapped along each run so a turn draws no jump.
fn charts(sweep: &Sweep, drawings: &Drawings) -> Result<String, String> {
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
fn unwrapped(runs: Vec<svg::Run>) -> Vec<svg::Run> {
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
fn symbol(column: &str) -> String {
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

fn check(args: &Args) -> Result<(), String> {
    args.mechanism.check(&args.dimensions)?;
    if let Some(p) = &args.coupler_point {
        if !matches!(args.mechanism, Mechanism::FourBar | Mechanism::SliderCrank) {
            return Err(format!(
                "--coupler-point applies to the four-bar and the slider-crank, not the {}",
                args.mechanism.name()
            ));
        }
        if p.len() != 2 {
            return Err("--coupler-point takes two numbers: distance,angle".into());
        }
    }
    if let Some(branches) = &args.branch {
        match args.mechanism {
            Mechanism::Jansen => {
                return Err(
                    "--branch does not apply to Jansen's leg, which is always as drawn".into(),
                );
            }
            Mechanism::StephensonSixBar => {
                return Err(
                    "--branch does not apply to the stephenson-six-bar, which has no \
                            closed-form branches: it is followed by Newton from its first \
                            assembly"
                        .into(),
                );
            }
            Mechanism::WattSixBar if branches.len() != 2 => {
                return Err(
                    "the watt-six-bar takes a branch per loop, as --branch open,crossed".into(),
                );
            }
            Mechanism::WattSixBar => {}
            _ if branches.len() != 1 => {
                return Err(format!(
                    "the {} has one loop: --branch takes one branch, open or crossed",
                    args.mechanism.name()
                ));
            }
            _ => {}
        }
    }
    finite("--rate", args.rate, "rad/s")?;
    finite("--accel", args.accel, "rad/s²")?;
    if !(args.step > 0.0 && args.step.is_finite()) {
        return Err(format!(
            "--step must be a positive, finite number of degrees, got {}",
            tidy(args.step)
        ));
    }
    let outputs = [&args.csv, &args.svg, &args.animation];
    if outputs.iter().filter(|p| p.as_os_str() == "-").count() > 1 {
        return Err("only one of --csv, --svg and --animation can be - (standard output)".into());
    }
    Ok(())
}

/// `value` if finite, else an error naming the flag and its unit.
pub fn finite(flag: &str, value: f64, unit: &str) -> Result<(), String> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(format!(
            "{flag} must be a finite number of {unit}, got {value}"
        ))
    }
}

pub fn run(args: &Args) -> Result<(), String> {
    check(args)?;
    let mut sweep = match args.mechanism {
        Mechanism::FourBar => four_bar(args)?,
        Mechanism::SliderCrank => slider_crank(args)?,
        Mechanism::InvertedSliderCrank => inverted(args)?,
        Mechanism::Jansen => jansen(args)?,
        Mechanism::WattSixBar => watt(args)?,
        Mechanism::StephensonSixBar => stephenson(args)?,
    };
    if sweep.pieces.is_empty() {
        return Err(format!(
            "the {} cannot be assembled at any input angle",
            args.mechanism.name()
        ));
    }
    // The sample count, checked before anything is computed or written.
    let grids: Vec<(f64, f64)> = sweep.pieces.iter().map(|p| p.grid(args.step)).collect();
    let total: f64 = grids.iter().map(|g| g.1).sum();
    if total > args.max_samples as f64 {
        return Err(format!(
            "a step of {}° makes {} samples, more than --max-samples {}: take a larger \
             --step, or raise --max-samples if you mean it",
            tidy(args.step),
            tidy(total.round()),
            args.max_samples
        ));
    }
    let total = total as u64;
    std::fs::create_dir_all(&args.out_dir)
        .map_err(|e| format!("cannot create {}: {e}", args.out_dir.display()))?;
    let table = Target::new(&args.csv, &args.out_dir);
    let chart_target = Target::new(&args.svg, &args.out_dir);
    let animation_target = Target::new(&args.animation, &args.out_dir);
    let mut writer = csv::Writer::from_writer(table.open()?);
    let csv_failed = |error: csv::Error| match error.into_kind() {
        csv::ErrorKind::Io(error) => table.failed(error),
        other => format!("cannot write {}: {other:?}", table.name()),
    };
    let mut header = vec!["input_deg".to_string(), "segment".to_string()];
    header.extend(sweep.columns.iter().cloned());
    writer.write_record(&header).map_err(csv_failed)?;

    let started = Instant::now();
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
    let mut drawings = Drawings::new(sweep.columns.len(), total);
    let mut lines = Vec::new();
    let mut computed = 0;
    let mut index = 0u64;
    let mut record = Vec::with_capacity(header.len());
    for (segment, (piece, &(first, count))) in sweep.pieces.iter().zip(&grids).enumerate() {
        let segment = segment + 1;
        let mut failures = Failures::default();
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        let count = count as u64;
        // Past each change point the motion goes on on the other branch.
        let mut flipped = false;
        let mut change_points = Vec::new();
        for k in 0..count {
            if index % 4096 == 0 {
                progress(&bar, started, index);
            }
            let input = first + k as f64 * args.step;
            if k > 0 {
                for at in crossed(&sweep.change_points, input - args.step, input) {
                    flipped = !flipped;
                    change_points.push(at);
                }
            }
            match (sweep.sample)(input, flipped) {
                Ok(sample) => {
                    computed += 1;
                    low = low.min(input);
                    high = high.max(input);
                    record.clear();
                    record.push(tidy(input));
                    record.push(segment.to_string());
                    record.extend(sample.values.iter().map(|v| format!("{v:.9e}")));
                    writer.write_record(&record).map_err(csv_failed)?;
                    drawings.add(index, k + 1 == count, segment, input, &sample);
                }
                Err(error) => {
                    failures.add(input, &error);
                    drawings.broken = true;
                }
            }
            index += 1;
        }
        let mut line = format!("  piece {segment}: {}; ", piece.words);
        match count - failures.count() {
            0 => line.push_str("no samples"),
            n => write!(line, "{n} samples from {}° to {}°", tidy(low), tidy(high)).unwrap(),
        }
        if let Some(words) = failures.words() {
            write!(line, "; {words}").unwrap();
        }
        if !change_points.is_empty() {
            let at: Vec<String> = change_points
                .iter()
                .map(|at| format!("{}°", tidy(*at)))
                .collect();
            write!(
                line,
                "; crossed change points at {} onto the other branch",
                at.join(", ")
            )
            .unwrap();
        }
        drawings.markers.extend(change_points);
        lines.push(line);
    }
    bar.finish_and_clear();
    writer
        .into_inner()
        .map_err(|e| table.failed(io::Error::other(e.to_string())))?
        .flush()
        .map_err(|e| table.failed(e))?;
    if computed == 0 {
        return Err(format!(
            "no sample could be computed:\n{}",
            lines.join("\n")
        ));
    }
    chart_target.write(&charts(&sweep, &drawings)?)?;
    animation_target.write(&svg::animation(
        &sweep.title,
        &sweep.links,
        &drawings.frames,
        &drawings.frame_segments,
        sweep.traced,
        6.0,
    ))?;
    // The summary goes where it cannot be mistaken for an output written to standard output.
    let report = |text: &str| {
        if [&table, &chart_target, &animation_target]
            .iter()
            .any(|t| matches!(t, Target::Stdout))
        {
            eprintln!("{text}");
        } else {
            say!("{text}");
        }
    };
    report(&format!(
        "{}: {computed} samples in {} {}; wrote {}, {} and {}",
        sweep.title,
        sweep.pieces.len(),
        if sweep.pieces.len() == 1 {
            "piece"
        } else {
            "pieces"
        },
        table.name(),
        chart_target.name(),
        animation_target.name()
    ));
    for line in lines {
        report(&line);
    }
    Ok(())
}

/// Shows the progress bar once a sweep has taken a second, on a terminal only.
fn progress(bar: &ProgressBar, started: Instant, done: u64) {
    if bar.is_hidden() && started.elapsed() > Duration::from_secs(1) && io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::stderr());
    }
    bar.set_position(done);
}

#[cfg(test)]
mod tests {
    use super::{svg, unwrapped};

    #[test]
    fn an_angle_that_passes_half_a_turn_draws_on_past_it() {
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
