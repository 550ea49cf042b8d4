//! `mechanisms sweep`: the input's reachable ranges on one branch, streamed sample by sample
//! to a CSV table (a file, or standard output for `-`), with SVG charts and an animated SVG of
//! the linkage drawn from a thinned copy, so a sweep takes the same memory however long.

use std::fmt::Write as _;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::{Parser, ValueEnum};
use mechanisms::{
    FourBar, InvertedSliderCrank, JansenLeg, SliderCrank, StephensonSixBar,
    StephensonSixBarUnknowns,
};
use mechgen::sweep::{Stop, Sweep as Walk};
use mechgen::{Branch, Error, NewtonOptions, Vec2};

use crate::Mechanism;
use crate::analyse::{four_bar_range, refused};
use crate::angle;
use crate::output::{self, filled, say, tidy};
use crate::progress;
use crate::six_bars::{self, Reach, StephensonDimensions};
use crate::svg::{self, Chart};

mod drawings;
mod linkages;
mod outputs;
mod pieces;
mod six_bar_sweeps;

pub(crate) use pieces::four_bar_toggles;

use drawings::*;
use linkages::*;
use outputs::*;
use pieces::*;
use six_bar_sweeps::*;

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
    #[arg(long, default_value_t = 10_000_000, allow_hyphen_values = true)]
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

/// The smallest step, as written to three significant digits, whose samples over `pieces`
/// number at most `most`; `None` if no step is that coarse (`most` of 0).
fn least_step(pieces: &[Piece], most: u64) -> Option<String> {
    let samples = |step: f64| pieces.iter().map(|p| p.grid(step).1).sum::<f64>();
    let span: f64 = pieces.iter().map(|p| p.to - p.from).sum();
    let mut step = span / most as f64;
    // Written to three digits, a step can round below the one that fits: go up by a tenth of
    // a percent, less than the three digits' resolution, until the written one fits.
    for _ in 0..100 {
        let written = output::significant(step, 3);
        if written
            .parse()
            .is_ok_and(|w: f64| samples(w) <= most as f64)
        {
            return Some(written);
        }
        step *= 1.001;
    }
    None
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
        let samples = if total.is_finite() {
            format!("{} samples", tidy(total.round()))
        } else {
            "more samples than can be counted".into()
        };
        let least = least_step(&sweep.pieces, args.max_samples).map_or_else(String::new, |least| {
            format!(": here the step must be at least {least}°")
        });
        return Err(format!(
            "--step {}° is too small: it makes {samples}, more than --max-samples {}{least} \
             (or raise --max-samples if you mean it)",
            tidy(args.step),
            args.max_samples
        ));
    }
    let total = total as u64;
    std::fs::create_dir_all(&args.out_dir)
        .map_err(|e| format!("cannot create {}: {e}", args.out_dir.display()))?;
    let table = Target::new(&args.csv, &args.out_dir);
    let chart_target = Target::new(&args.svg, &args.out_dir);
    let animation_target = Target::new(&args.animation, &args.out_dir);
    outputs::distinct(&[
        ("--csv", &table),
        ("--svg", &chart_target),
        ("--animation", &animation_target),
    ])?;
    let mut writer = csv::Writer::from_writer(table.open()?);
    let csv_failed = |error: csv::Error| match error.into_kind() {
        csv::ErrorKind::Io(error) => table.failed(error),
        other => format!("cannot write {}: {other:?}", table.name()),
    };
    let mut header = vec!["input_deg".to_string(), "segment".to_string()];
    header.extend(sweep.columns.iter().cloned());
    writer.write_record(&header).map_err(csv_failed)?;

    let started = Instant::now();
    let bar = progress::bar(total);
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
                progress::advance(&bar, started, index);
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
            crate::output::tell!("{text}");
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
