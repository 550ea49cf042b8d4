//! `mechanisms tolerance`: how far a four-bar's output angle and coupler point move when its
//! dimensions are off by their tolerances, over a turn: the first-order worst case and
//! root-sum-square stack-up from the generated sensitivities, beside the nonlinear model at
//! every corner of the tolerance box and Monte Carlo, as a table and an SVG chart.

use std::fs;
use std::path::PathBuf;
use std::time::Instant;

use clap::Parser;
use mechanisms::{FourBar, FourBarTolerances};
use mechgen::{Branch, Error};

use crate::Mechanism;
use crate::analyse::{four_bar_range, refused};
use crate::angle;
use crate::output::{self, fixed, say, tidy};
use crate::progress;
use crate::svg::{self, Chart};
use crate::sweep::BranchName;

#[derive(Parser)]
pub struct Args {
    /// The mechanism (the four-bar).
    #[arg(value_enum)]
    pub mechanism: Mechanism,
    /// Its dimensions in mm.
    #[arg(allow_negative_numbers = true)]
    pub dimensions: Vec<f64>,
    /// The ± tolerance of every length, mm: under a tenth of each length it applies to (the
    /// coupler point's distance, which may be zero: a tenth of the shortest link).
    #[arg(long, default_value_t = 0.1, allow_hyphen_values = true)]
    pub tolerance: f64,
    /// The ± tolerances of ground, crank, coupler and rocker, mm, joined by commas: each
    /// length its own, in place of --tolerance (the coupler point's distance keeps
    /// --tolerance); each under a tenth of its length.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub tolerances: Option<Vec<f64>>,
    /// A coupler point to follow: distance from the crank pin (mm), angle from the coupler
    /// (°), as `100,30` [default: the crank pin].
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub coupler_point: Option<Vec<f64>>,
    /// The ± tolerance of the coupler point's angle, degrees: under a tenth of a radian
    /// (5.73°).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub angle_tolerance: f64,
    /// The assembly branch.
    #[arg(long, value_enum, default_value = "open")]
    pub branch: BranchName,
    /// The crank angle's step, degrees, from 0.0036 (10⁵ crank angles) to 360 (0° alone).
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true)]
    pub step: f64,
    /// Monte Carlo linkages per crank angle (normal errors, each tolerance 3σ), at most 10⁷.
    /// A run past a second shows its progress on standard error, on a terminal.
    #[arg(long, default_value_t = 2000, allow_hyphen_values = true)]
    pub samples: usize,
    /// The Monte Carlo generator's seed.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    pub seed: u64,
    /// Where to write the chart; `-` for standard output, nothing for no chart.
    #[arg(long)]
    pub svg: Option<PathBuf>,
}

/// The most crank angles and Monte Carlo linkages a run takes, each and together (some 2.5 s
/// per 10⁷ linkages), so that a huge argument is refused at once rather than run for hours.
const MOST_STEPS: f64 = 100_000.0;
const MOST_SAMPLES: usize = 10_000_000;
const MOST_LINKAGES: f64 = 1e8;

/// How large a tolerance must be against what it applies to, where it is not zero: the
/// nonlinear columns subtract the nominal linkage's solution from each perturbed one's, both
/// rounded to the float's 16 digits, so a tolerance below a billionth of its length would
/// leave them fewer than the 5 digits printed (and one below 1e-16 of it, nothing at all:
/// the perturbed length rounds to the nominal one).
const SMALLEST_FRACTION: f64 = 1e-9;

/// How far first order and the nonlinear model's worst corner may differ before a row is
/// flagged: first order holds while the tolerances are small against the distance to a
/// toggle, and where they are not, its worst case is no bound.
const FIRST_ORDER_AGREEMENT: f64 = 0.1;

/// How small a tolerance must be against what it applies to: first order holds for small
/// errors, and the tolerance box's corners and the Monte Carlo linkages must still be
/// linkages much like the nominal one (a length off by its whole length is no tolerance).
const LARGEST_FRACTION: f64 = 0.1;

/// The table's columns, as an error names one.
const COLUMNS: [&str; 8] = [
    "θ4's first-order worst case",
    "θ4's worst corner",
    "θ4's RSS/3",
    "θ4's Monte Carlo rms",
    "the coupler point's first-order worst case",
    "the coupler point's worst corner",
    "the coupler point's RSS/3",
    "the coupler point's Monte Carlo rms",
];

/// Each length and its tolerance checked against the float's range: the nonlinear model
/// draws linkages up to three tolerances out (a Monte Carlo error of `t/3` standard
/// deviation is within `2.9·t`), and one beyond the largest number is an overflow, not a
/// linkage that fails to assemble.
fn check_representable(values: [f64; 5], lengths: [f64; 4], distance: f64) -> Result<(), String> {
    let names = [
        "ground",
        "crank",
        "coupler",
        "rocker",
        "coupler point's distance",
    ];
    let tolerances = [lengths[0], lengths[1], lengths[2], lengths[3], distance];
    for ((name, value), tolerance) in names.into_iter().zip(values).zip(tolerances) {
        if !(value.abs() + 3.0 * tolerance).is_finite() {
            return Err(format!(
                "the {name} ({} mm) with three times its tolerance (±{} mm) overflows: the \
                 nonlinear model's linkages would be beyond the largest number",
                tidy(value),
                tidy(tolerance)
            ));
        }
    }
    Ok(())
}

/// Each tolerance checked against what it applies to (see [`LARGEST_FRACTION`]): the four
/// links' against their lengths, the coupler point distance's against the shortest link (the
/// distance itself may be zero), its angle's against a radian.
fn check_small(args: &Args, links: [f64; 4], lengths: [f64; 4]) -> Result<(), String> {
    let flag = if args.tolerances.is_some() {
        "--tolerances"
    } else {
        "--tolerance"
    };
    let names = ["ground", "crank", "coupler", "rocker"];
    let shortest = links.into_iter().fold(f64::INFINITY, f64::min);
    let checks = names
        .into_iter()
        .zip(links)
        .zip(lengths)
        .map(|((name, link), tolerance)| (flag, tolerance, name, link))
        .chain([("--tolerance", args.tolerance, "shortest link", shortest)]);
    for (flag, tolerance, name, link) in checks {
        if tolerance != 0.0 && tolerance < SMALLEST_FRACTION * link {
            return Err(format!(
                "{flag} ±{} mm is too small against the {name} ({} mm) for the nonlinear \
                 model to resolve in f64: each ± tolerance must be zero (exact) or at least a \
                 billionth of the length it applies to",
                tidy(tolerance),
                tidy(link)
            ));
        }
        if tolerance >= LARGEST_FRACTION * link {
            return Err(format!(
                "{flag} ±{} mm is not small against the {name} ({} mm): each ± tolerance \
                 must be under a tenth of the length it applies to (the coupler point's \
                 distance, under a tenth of the shortest link)",
                tidy(tolerance),
                tidy(link)
            ));
        }
    }
    let angle = args.angle_tolerance.to_radians();
    // Zero as given: one that underflows to zero in radians is too small, not exact.
    if args.angle_tolerance != 0.0 && angle < SMALLEST_FRACTION {
        return Err(format!(
            "--angle-tolerance ±{}° is too small for the nonlinear model to resolve in f64: \
             it must be zero (exact) or at least a billionth of a radian",
            tidy(args.angle_tolerance)
        ));
    }
    if angle >= LARGEST_FRACTION {
        return Err(format!(
            "--angle-tolerance ±{}° is not small: it must be under a tenth of a radian ({}°)",
            tidy(args.angle_tolerance),
            output::significant(LARGEST_FRACTION.to_degrees(), 3)
        ));
    }
    Ok(())
}

pub fn run(args: &Args) -> Result<(), String> {
    if args.svg.as_deref().is_some_and(output::is_stdout) {
        output::report_on_stderr();
    }
    if args.mechanism != Mechanism::FourBar {
        return Err(format!(
            "tolerance analysis covers the four-bar, not the {}",
            args.mechanism.name()
        ));
    }
    args.mechanism.check(&args.dimensions)?;
    let &[ground, crank, coupler, rocker] = args.dimensions.as_slice() else {
        unreachable!("checked: four dimensions");
    };
    let (distance, angle_degrees) = match args.coupler_point.as_deref() {
        None => (0.0, 0.0),
        Some(&[distance, angle]) => (distance, angle),
        Some(_) => return Err("--coupler-point takes a distance and an angle, as 100,30".into()),
    };
    let linkage = FourBar::new(ground, crank, coupler, rocker)
        .and_then(|l| l.with_coupler_point(distance, angle::radians(angle_degrees)))
        .map_err(refused)?;
    let lengths = match args.tolerances.as_deref() {
        None => [args.tolerance; 4],
        Some(&[a, b, c, d]) => [a, b, c, d],
        Some(_) => return Err("--tolerances takes four lengths, as 0.1,0.05,0.1,0.1".into()),
    };
    let tolerances = FourBarTolerances {
        ground: lengths[0],
        crank: lengths[1],
        coupler: lengths[2],
        rocker: lengths[3],
        distance: args.tolerance,
        angle: args.angle_tolerance.to_radians(),
    };
    let every = [
        lengths[0],
        lengths[1],
        lengths[2],
        lengths[3],
        args.tolerance,
        args.angle_tolerance,
    ];
    if every.iter().any(|t| !t.is_finite() || *t < 0.0) {
        return Err("a tolerance must be finite and not negative".into());
    }
    check_small(args, [ground, crank, coupler, rocker], lengths)?;
    check_representable(
        [ground, crank, coupler, rocker, distance],
        lengths,
        args.tolerance,
    )?;
    if !(args.step.is_finite()
        && args.step > 0.0
        && args.step <= 360.0
        && 360.0 / args.step <= MOST_STEPS)
    {
        return Err(format!(
            "--step must be a positive number of degrees from {} to 360 (a turn), got {}",
            tidy(360.0 / MOST_STEPS),
            tidy(args.step)
        ));
    }
    // The rms of no linkages is no number.
    if args.samples == 0 {
        return Err(
            "--samples takes at least 1: the Monte Carlo rms of no linkages is undefined".into(),
        );
    }
    if args.samples > MOST_SAMPLES {
        return Err(format!("--samples takes at most {MOST_SAMPLES}"));
    }
    let steps = crank_angles(args.step);
    if steps as f64 * args.samples as f64 > MOST_LINKAGES {
        return Err(format!(
            "{steps} crank angles times {} Monte Carlo linkages is more than {} linkages in \
             all (some 2.5 s per 10⁷): take a larger --step or fewer --samples",
            args.samples,
            tidy(MOST_LINKAGES)
        ));
    }
    let branch = match args.branch {
        BranchName::Open => Branch::Open,
        BranchName::Crossed => Branch::Crossed,
    };

    // Every row before any is printed, so that a figure that overflowed is an error before
    // the report starts, never a row of it.
    let decimals = step_decimals(args.step);
    let bar = progress::bar(steps as u64);
    let started = Instant::now();
    let mut rows = Vec::new();
    let mut skipped = Vec::new();
    // Crank angles where some linkages within the tolerances do not assemble (the nonlinear
    // columns are over those that do), and where first order and the worst corner differ.
    let mut short = Vec::new();
    let mut disagree = Vec::new();
    for k in 0..steps {
        progress::advance(&bar, started, k as u64);
        let degrees = k as f64 * args.step;
        let theta2 = degrees.to_radians();
        let row = (|| -> Result<[f64; 8], Error<f64>> {
            let linear = linkage.tolerance(theta2, branch, &tolerances)?;
            let corners = linkage.corners(theta2, branch, &tolerances)?;
            let sampled =
                linkage.monte_carlo(theta2, branch, &tolerances, args.samples, args.seed)?;
            if corners.failed > 0 || sampled.failed > 0 {
                short.push(format!(
                    "{}° ({} of {} corners, {} of {} Monte Carlo linkages)",
                    fixed(degrees, decimals),
                    corners.failed,
                    corners.failed + corners.assembled,
                    sampled.failed,
                    args.samples
                ));
            }
            let [first, corner] = [linear.output.worst_case, corners.output_largest];
            if (corner - first).abs() > FIRST_ORDER_AGREEMENT * first.max(corner) {
                disagree.push(format!(
                    "{}° (θ4: {}° against {}°)",
                    fixed(degrees, decimals),
                    output::figure(first.to_degrees()),
                    output::figure(corner.to_degrees())
                ));
            }
            Ok([
                linear.output.worst_case.to_degrees(),
                corners.output_largest.to_degrees(),
                (linear.output.root_sum_square / 3.0).to_degrees(),
                sampled.output_rms.to_degrees(),
                linear.coupler_point.worst_case,
                corners.coupler_point_largest,
                linear.coupler_point.root_sum_square / 3.0,
                sampled.coupler_point_rms,
            ])
        })();
        match row {
            Ok(values) => {
                if let Some(column) = values.iter().position(|v| !v.is_finite()) {
                    bar.finish_and_clear();
                    return Err(format!(
                        "{} at θ2 = {}° overflowed (it is not finite): the dimensions or \
                         tolerances are too large for the analysis",
                        COLUMNS[column],
                        fixed(degrees, decimals)
                    ));
                }
                rows.push((degrees, values));
            }
            Err(error) => skipped.push(format!(
                "{}° ({})",
                fixed(degrees, decimals),
                output::error(&error)
            )),
        }
    }
    bar.finish_and_clear();
    let Some(worst) = rows.iter().max_by(|a, b| a.1[0].total_cmp(&b.1[0])) else {
        return Err(format!(
            "the linkage assembles at none of the crank angles analysed ({}): {}",
            four_bar_range(&linkage),
            skipped.join(", ")
        ));
    };

    say!(
        "Four-bar {}/{}/{}/{} mm, coupler point {} mm at {}°, {} branch",
        tidy(ground),
        tidy(crank),
        tidy(coupler),
        tidy(rocker),
        tidy(distance),
        tidy(angle_degrees),
        match args.branch {
            BranchName::Open => "open",
            BranchName::Crossed => "crossed",
        }
    );
    say!(
        "tolerances ±: ground {} crank {} coupler {} rocker {} mm, point distance {} mm, point \
         angle {}°",
        tidy(lengths[0]),
        tidy(lengths[1]),
        tidy(lengths[2]),
        tidy(lengths[3]),
        tidy(args.tolerance),
        tidy(args.angle_tolerance)
    );
    say!(
        "First order from the generated sensitivities: worst case over the tolerance box, and \
         the root-sum-square stack-up over 3 (the standard deviation when each tolerance is \
         3σ). Beside them the nonlinear model: its worst corner of the box, and the rms of {} \
         Monte Carlo linkages (normal errors, seed {}).",
        args.samples,
        args.seed
    );
    say!("");
    say!(
        "| θ2 (°) | θ4 worst (°) | corners (°) | θ4 RSS/3 (°) | Monte Carlo rms (°) | P worst \
         (mm) | corners (mm) | P RSS/3 (mm) | Monte Carlo rms (mm) |"
    );
    say!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (degrees, values) in &rows {
        say!(
            "| {} | {} |",
            fixed(*degrees, decimals),
            values.map(|v| format!("{v:.4e}")).join(" | ")
        );
    }
    say!("");
    if !skipped.is_empty() {
        say!("Not analysed: {}.", listed(&skipped));
    }
    if !short.is_empty() {
        say!(
            "Some linkages within the tolerances do not assemble (the nonlinear columns are \
             over those that do) at: {}.",
            listed(&short)
        );
    }
    if !disagree.is_empty() {
        say!(
            "First order and the worst corner differ by more than {}% (the tolerances are not \
             small against the distance to a toggle or a limit, and first order is no bound \
             there) at: {}.",
            tidy(100.0 * FIRST_ORDER_AGREEMENT),
            listed(&disagree)
        );
    }
    say!(
        "Largest first-order worst case of θ4: ±{}° at θ2 = {}°; of the coupler point: {} mm.",
        output::figure(worst.1[0]),
        fixed(worst.0, decimals),
        output::figure(rows.iter().map(|r| r.1[4]).fold(0.0, f64::max))
    );
    if let Some(path) = &args.svg {
        let chart = |title: &str, unit: &str, columns: [(usize, &str); 4]| Chart {
            title: title.into(),
            unit: unit.into(),
            series: columns
                .iter()
                .map(|&(c, label)| {
                    let points = rows.iter().map(|(x, v)| (*x, v[c])).collect();
                    (label.to_string(), vec![(0, points)])
                })
                .collect(),
            band: None,
        };
        let labels = ["worst case", "worst corner", "RSS/3", "MC rms"];
        let charts = [
            chart(
                "output angle θ4: deviation",
                "°",
                [0, 1, 2, 3].map(|c| (c, labels[c])),
            ),
            chart(
                "coupler point: deviation",
                "mm",
                [4, 5, 6, 7].map(|c| (c, labels[c - 4])),
            ),
        ];
        let drawing = svg::charts("θ2 (°)", &charts, &[])?;
        if output::is_stdout(path) {
            output::drawing_to_stdout(&drawing);
        } else {
            fs::write(path, drawing)
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            output::tell!("wrote {}", path.display());
        }
    }
    Ok(())
}

/// How many crank angles a turn in steps of `step` degrees has: every `k·step` short of 360°
/// (0°, 200° for a step of 200; up to 359.8° for 0.7), a rounding short of a turn counted as
/// the turn (10⁵ for 0.0036, not 10⁵ + 1).
fn crank_angles(step: f64) -> usize {
    (360.0 / step * (1.0 - 1e-12)).ceil().max(1.0) as usize
}

/// The decimals that tell every crank angle of the turn apart: the step's own (to 6 places;
/// at least 1).
fn step_decimals(step: f64) -> usize {
    (1..=6)
        .find(|&d| {
            let scaled = step * 10f64.powi(d as i32);
            (scaled - scaled.round()).abs() < 1e-6 * scaled.max(1.0)
        })
        .unwrap_or(6)
}

/// At most ten of `items`, joined, and how many more.
fn listed(items: &[String]) -> String {
    const SHOWN: usize = 10;
    let mut text = items[..items.len().min(SHOWN)].join(", ");
    if items.len() > SHOWN {
        text.push_str(&format!(" and {} more", items.len() - SHOWN));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_turn_has_every_crank_angle_short_of_360_degrees() {
        assert_eq!(crank_angles(10.0), 36);
        assert_eq!(crank_angles(200.0), 2);
        assert_eq!(crank_angles(0.7), 515);
        assert_eq!(crank_angles(360.0), 1);
        assert_eq!(crank_angles(0.0036), 100_000);
        assert_eq!(crank_angles(7.0), 52);
    }

    #[test]
    fn crank_angles_print_with_the_steps_decimals() {
        assert_eq!(step_decimals(10.0), 1);
        assert_eq!(step_decimals(0.05), 2);
        assert_eq!(step_decimals(0.0036), 4);
        assert_eq!(step_decimals(20.3), 1);
        assert_eq!(step_decimals(1.0 / 3.0), 6);
    }
}
