//! `mechanisms synthesise`: a four-bar whose output follows precision points of a function
//! (`function`), or whose coupler point passes through target points (`path`), by
//! Levenberg–Marquardt on the generated derivatives (`mechanisms::synthesis`), with its
//! errors at the targets and a chart.

use std::fs;
use std::path::PathBuf;

use clap::{Args as ClapArgs, Subcommand};
use mechanisms::FourBar;
use mechanisms::synthesis::{self, Options, Synthesis};
use mechgen::{Branch, Vec2};

use crate::angle;
use crate::output::{self, fixed, say, tidy};
use crate::progress;
use crate::svg::{self, Chart};
use crate::sweep::BranchName;

#[derive(Subcommand)]
pub enum Task {
    /// Function generation: the rocker angle θ4 at each crank angle θ2 given, degrees from
    /// the ground line, as `--crank 30,45,60 --rocker 60,75,95`.
    Function(FunctionArgs),
    /// Path generation: the coupler point through target points, as `--x 0,10,20 --y 5,8,4`,
    /// at crank angles `--timing` (degrees) where given, else at crank angles it finds (nine
    /// or more targets then).
    Path(PathArgs),
}

#[derive(ClapArgs)]
pub struct FunctionArgs {
    /// The crank angles θ2, degrees, joined by commas.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true
    )]
    pub crank: Vec<f64>,
    /// The rocker angles θ4 wanted there, degrees.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true
    )]
    pub rocker: Vec<f64>,
    /// The ground link's length, mm: it sets the scale.
    #[arg(long, default_value_t = 100.0, allow_hyphen_values = true)]
    pub ground: f64,
    #[command(flatten)]
    pub common: Common,
}

#[derive(ClapArgs)]
pub struct PathArgs {
    /// The targets' x coordinates, mm.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true
    )]
    pub x: Vec<f64>,
    /// The targets' y coordinates, mm.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true
    )]
    pub y: Vec<f64>,
    /// The crank angle at each target, degrees from the ground line (prescribed timing).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub timing: Option<Vec<f64>>,
    #[command(flatten)]
    pub common: Common,
}

#[derive(ClapArgs)]
pub struct Common {
    /// The assembly branch every target is solved on [default: each, the better kept].
    #[arg(long, value_enum)]
    pub branch: Option<BranchName>,
    /// The largest ratio of the longest link to the shortest.
    #[arg(long, default_value_t = 50.0, allow_hyphen_values = true)]
    pub max_ratio: f64,
    /// Require a crank that turns fully.
    #[arg(long)]
    pub crank_turns: bool,
    /// Require the transmission angle within these bounds, degrees, as `40,140` (at every
    /// target; all the turn with --crank-turns).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub transmission: Option<Vec<f64>>,
    /// Random starts on each branch tried, run in parallel on every core: at most 1000 (path
    /// generation without --timing takes tens of seconds for that many at nine targets, and
    /// its cost grows as the cube of the targets: past nine, the starts times (targets/9)³
    /// may be at most 2000 over the branches tried). A run past a second shows a spinner on
    /// standard error, on a terminal.
    #[arg(long, default_value_t = 64, allow_hyphen_values = true)]
    pub restarts: usize,
    /// The random starts' seed: the same seed, the same linkage.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    pub seed: u64,
    /// Where to write the chart; `-` for standard output.
    #[arg(long)]
    pub svg: Option<PathBuf>,
}

/// The most starts a run takes on each branch, so that a run ends within a minute on two
/// cores even for path generation without timing (its slowest: some 15 ms a start).
const MOST_RESTARTS: usize = 1000;

impl Common {
    /// The options for each branch tried: the one asked for, or both.
    fn each_options(&self) -> Result<Vec<Options>, String> {
        let options = self.options()?;
        let branches = match self.branch {
            Some(BranchName::Open) => vec![Branch::Open],
            Some(BranchName::Crossed) => vec![Branch::Crossed],
            None => vec![Branch::Open, Branch::Crossed],
        };
        Ok(branches
            .into_iter()
            .map(|branch| Options { branch, ..options })
            .collect())
    }

    fn options(&self) -> Result<Options, String> {
        // As the library requires (a ratio of 1, every link as long, leaves nothing to fit).
        if !(self.max_ratio.is_finite() && self.max_ratio > 1.0) {
            return Err("--max-ratio must be a finite number above 1".into());
        }
        if self.restarts > MOST_RESTARTS {
            return Err(format!("--restarts takes at most {MOST_RESTARTS}"));
        }
        // None would try nothing, and report that nothing meets the targets.
        if self.restarts == 0 {
            return Err("--restarts must be at least 1".into());
        }
        let transmission = match self.transmission.as_deref() {
            None => None,
            Some(&[low, high]) if 0.0 <= low && low < high && high <= 180.0 => {
                Some((low.to_radians(), high.to_radians()))
            }
            Some(_) => {
                return Err(
                    "--transmission takes two angles in degrees within 0..180, the smaller \
                     first, as 40,140"
                        .into(),
                );
            }
        };
        Ok(Options {
            branch: Branch::Open,
            max_ratio: self.max_ratio,
            good_enough: None,
            restarts: self.restarts,
            seed: self.seed,
            crank: self.crank_turns,
            transmission,
        })
    }
}

pub fn run(task: &Task) -> Result<(), String> {
    let common = match task {
        Task::Function(args) => &args.common,
        Task::Path(args) => &args.common,
    };
    if common.svg.as_deref().is_some_and(output::is_stdout) {
        output::report_on_stderr();
    }
    match task {
        Task::Function(args) => function(args),
        Task::Path(args) => path(args),
    }
}

fn function(args: &FunctionArgs) -> Result<(), String> {
    if args.crank.len() != args.rocker.len() {
        return Err(format!(
            "--crank and --rocker give {} and {} angles: one rocker angle per crank angle",
            args.crank.len(),
            args.rocker.len()
        ));
    }
    let phi: Vec<f64> = args.crank.iter().map(|&d| angle::radians(d)).collect();
    let psi: Vec<f64> = args.rocker.iter().map(|&d| angle::radians(d)).collect();
    let each = args.common.each_options()?;
    within_budget(phi.len(), &each, "function generation")?;
    let (found, options) = searching(&each, || {
        better(each.clone(), |options| {
            synthesis::function_generation(args.ground, &phi, &psi, options)
        })
    })?;
    report(&found, &options, Fitted::Function);
    if phi.len() == 3 {
        match synthesis::freudenstein(
            args.ground,
            [phi[0], phi[1], phi[2]],
            [psi[0], psi[1], psi[2]],
        ) {
            Some([d, a, b, c]) => say!(
                "Freudenstein's closed form of the three points: crank {}, coupler {}, rocker {} \
                 mm{}",
                length(a),
                length(b),
                length(c),
                closed_form_branches(d, a, b, c, &args.crank, &phi, &psi)
            ),
            None => say!("Freudenstein's closed form of the three points gives no linkage."),
        }
    }
    say!("");
    say!("| θ2 (°) | wanted θ4 (°) | θ4 (°) | error (°) |");
    say!("|---:|---:|---:|---:|");
    let linkage = found.linkage;
    for (k, (&phi, &psi)) in phi.iter().zip(&psi).enumerate() {
        let theta4 = linkage
            .assemble(phi, options.branch)
            .map(|q| q.theta4)
            .map_err(|e| output::error(&e))?;
        let error = wrapped(theta4 - psi);
        // The angles as given; θ4 in the wanted angle's turn, less whole turns.
        say!(
            "| {} | {} | {} | {} |",
            tidy(args.crank[k]),
            tidy(args.rocker[k]),
            fixed((psi + error).to_degrees(), 4),
            format!("{:.3e}", error.to_degrees())
        );
    }
    if let Some(path) = &args.common.svg {
        // θ4 over the crank angles the linkage reaches, beside the precision points.
        let curve = (0..=720)
            .filter_map(|k| {
                let theta2 = f64::from(k) * 0.5;
                linkage
                    .assemble(theta2.to_radians(), options.branch)
                    .ok()
                    .map(|q| (theta2, wrapped(q.theta4).to_degrees()))
            })
            .collect();
        let wanted = phi
            .iter()
            .zip(&psi)
            .map(|(p, s)| (p.to_degrees().rem_euclid(360.0), wrapped(*s).to_degrees()))
            .collect();
        let chart = Chart {
            title: "function generation: rocker angle θ4".into(),
            unit: "°".into(),
            series: vec![
                ("synthesised".into(), vec![(0, curve)]),
                ("targets".into(), vec![(1, wanted)]),
            ],
            band: None,
        };
        write(path, &svg::charts("θ2 (°)", &[chart], &[])?)?;
    }
    Ok(())
}

fn path(args: &PathArgs) -> Result<(), String> {
    if args.x.len() != args.y.len() {
        return Err(format!(
            "--x and --y give {} and {} coordinates: one y per x",
            args.x.len(),
            args.y.len()
        ));
    }
    if let Some(timing) = &args.timing {
        if timing.len() != args.x.len() {
            return Err(format!(
                "--timing gives {} crank angles for {} targets: one crank angle per target",
                timing.len(),
                args.x.len()
            ));
        }
    }
    let targets: Vec<Vec2<f64>> = args
        .x
        .iter()
        .zip(&args.y)
        .map(|(&x, &y)| Vec2 { x, y })
        .collect();
    if targets
        .iter()
        .any(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err("--x and --y must be finite numbers of mm".into());
    }
    let frame = Frame::of(&targets)?;
    let unit: Vec<Vec2<f64>> = targets.iter().map(|&p| frame.inside(p)).collect();
    let timing: Option<Vec<f64>> = args
        .timing
        .as_ref()
        .map(|t| t.iter().map(|&d| angle::radians(d)).collect());
    let each = args.common.each_options()?;
    match timing {
        None => untimed_within_budget(targets.len(), &each)?,
        Some(_) => within_budget(targets.len(), &each, "path generation with --timing")?,
    }
    let (found, options) = searching(&each, || {
        better(each.clone(), |options| {
            synthesis::path_generation(&unit, timing.as_deref(), options)
                .and_then(|found| frame.put_back(found))
        })
    })?;
    report(&found, &options, Fitted::Path);
    let (pivot, angle) = found.placement;
    say!(
        "placed with its crank pivot at ({}, {}) mm and its ground line at {}°",
        output::figure(pivot.x),
        output::figure(pivot.y),
        output::degrees(angle, 4)
    );
    let linkage = found.linkage;
    let placed = |theta2: f64| -> Option<Vec2<f64>> {
        let q = linkage.assemble(theta2, options.branch).ok()?;
        let p = linkage.points(theta2, &q).ok()?.coupler_point;
        let (s, c) = angle.sin_cos();
        Some(Vec2 {
            x: pivot.x + c * p.x - s * p.y,
            y: pivot.y + s * p.x + c * p.y,
        })
    };
    if let Some(path) = &args.common.svg {
        let curve = (0..=720)
            .filter_map(|k| placed(f64::from(k).to_radians() * 0.5))
            .map(|p| (p.x, p.y))
            .collect();
        let wanted = targets.iter().map(|p| (p.x, p.y)).collect();
        let chart = Chart {
            title: "path generation: the coupler curve through the targets".into(),
            unit: "y (mm)".into(),
            series: vec![
                ("coupler curve".into(), vec![(0, curve)]),
                ("targets".into(), vec![(1, wanted)]),
            ],
            band: None,
        };
        write(path, &svg::charts("x (mm)", &[chart], &[])?)?;
    }
    Ok(())
}

/// The targets' frame for path generation: their centroid and a power of two near their
/// spread. Levenberg–Marquardt squares the errors, which overflow for targets 1e300 mm apart
/// and underflow for targets 1e-300 mm apart, so the fit is made on the targets moved to
/// their centroid and scaled to a spread near 1 (exactly, by the power of two), and the
/// linkage found is scaled back.
struct Frame {
    centre: Vec2<f64>,
    scale: f64,
}

impl Frame {
    /// The frame of `targets` (finite), or why they have none: they all coincide (a path
    /// through one point is any linkage's), or lie too far apart for a float.
    fn of(targets: &[Vec2<f64>]) -> Result<Self, String> {
        let (centre, spread) = mechanisms::synthesis::centre_and_spread(targets);
        if mechanisms::synthesis::all_coincide(targets) {
            return Err(format!(
                "--x and --y give {} targets all at ({}, {}) mm: a coupler curve through one \
                 point is any linkage's; give distinct targets",
                targets.len(),
                tidy(centre.x),
                tidy(centre.y)
            ));
        }
        if !spread.is_finite() {
            return Err(
                "--x and --y give targets too far apart to measure in a float (their \
                        distances overflow)"
                    .into(),
            );
        }
        // Within the exponents a normal float has, so that the power of two is exact.
        let exponent = spread.log2().round().clamp(-1000.0, 1000.0) as i32;
        Ok(Frame {
            centre,
            scale: 2f64.powi(exponent),
        })
    }

    /// A target in the frame.
    fn inside(&self, p: Vec2<f64>) -> Vec2<f64> {
        Vec2 {
            x: (p.x - self.centre.x) / self.scale,
            y: (p.y - self.centre.y) / self.scale,
        }
    }

    /// A synthesis made in the frame, put back among the targets: lengths and errors scaled
    /// (exactly), the crank pivot moved too; an error where the linkage scaled back is no
    /// linkage (a length overflowed).
    fn put_back(&self, found: Synthesis) -> Result<Synthesis, synthesis::SynthesisError> {
        let s = self.scale;
        let [l1, l2, l3, l4] = found.linkage.lengths().map(|l| l * s);
        let (distance, delta) = found.linkage.coupler_point();
        let linkage = FourBar::new(l1, l2, l3, l4)
            .and_then(|l| l.with_coupler_point(distance * s, delta))
            .map_err(|_| {
                synthesis::SynthesisError::BadTargets(
                    "the linkage found is too large to represent at the targets' scale",
                )
            })?;
        let (pivot, angle) = found.placement;
        Ok(Synthesis {
            linkage,
            placement: (
                Vec2 {
                    x: self.centre.x + pivot.x * s,
                    y: self.centre.y + pivot.y * s,
                },
                angle,
            ),
            rms_error: found.rms_error * s,
            largest_error: found.largest_error * s,
            ..found
        })
    }
}

/// Path generation without timing solves for every target's crank angle too: each start's
/// least squares has `9 + n` unknowns and `2n` residuals, and costs about `n³` (13 ms a start
/// on one core at 20 targets, 86 ms at 40, 340 ms at 60). The starts over every branch
/// tried, times `(n/9)³` past nine targets, may be at most 2000, what 1000 restarts on each
/// branch cost at nine (tens of seconds): a run that would take many minutes is refused at
/// once, with what would fit.
fn untimed_within_budget(targets: usize, each: &[Options]) -> Result<(), String> {
    const BUDGET: f64 = 2000.0;
    let starts: usize = each.iter().map(|o| o.restarts).sum();
    let weight = (targets as f64 / 9.0).powi(3).max(1.0);
    if starts as f64 * weight <= BUDGET {
        return Ok(());
    }
    let branches = each.len().max(1);
    let fits = ((BUDGET / weight) as usize) / branches;
    Err(format!(
        "path generation without --timing finds every target's crank angle too, at a cost \
         growing as the cube of the targets: {targets} targets with {} random starts on {} \
         would take many minutes; give --timing, fewer targets, or --restarts {} or fewer{}",
        starts / branches,
        if branches == 1 {
            "one branch"
        } else {
            "each branch"
        },
        fits,
        if branches > 1 {
            " (or one --branch)"
        } else {
            ""
        }
    ))
}

/// Function generation and timed path generation cost each start about its targets' count
/// (path generation at 2000 targets with 1000 restarts on each branch took 286 s; function
/// generation at 12000 points with 10, 8 s): the starts over every branch tried, times the
/// targets, may be at most two million (a minute or two), else the run is refused at once,
/// with what would fit.
fn within_budget(targets: usize, each: &[Options], what: &str) -> Result<(), String> {
    const BUDGET: usize = 2_000_000;
    let starts: usize = each.iter().map(|o| o.restarts).sum();
    if starts.saturating_mul(targets) <= BUDGET {
        return Ok(());
    }
    let branches = each.len().max(1);
    let fits = BUDGET / targets.max(1) / branches;
    Err(format!(
        "{what} costs each random start about its {targets} targets: {} starts on {} would \
         take many minutes; give fewer targets, or --restarts {fits} or fewer{}",
        starts / branches,
        if branches == 1 {
            "one branch"
        } else {
            "each branch"
        },
        if branches > 1 {
            " (or one --branch)"
        } else {
            ""
        }
    ))
}

/// `search`'s result, with a spinner on a terminal past a second: the restarts run inside
/// the library, which cannot report them one by one.
fn searching<T>(each: &[Options], search: impl FnOnce() -> T) -> T {
    let starts = each.first().map_or(0, |o| o.restarts);
    let what = format!(
        "synthesising: {starts} random starts on {}",
        if each.len() == 1 {
            "one branch"
        } else {
            "each branch"
        }
    );
    progress::while_running(&what, search)
}

/// The best synthesis over the branches tried (the smallest rms error, ties to the first),
/// with the options it was found with; the last error if none found one. A fit whose error
/// is not finite is no fit: it counts as an error.
fn better(
    each: Vec<Options>,
    synthesise: impl Fn(&Options) -> Result<Synthesis, synthesis::SynthesisError>,
) -> Result<(Synthesis, Options), String> {
    let mut best: Option<(Synthesis, Options)> = None;
    let mut last_error = String::new();
    for options in each {
        match synthesise(&options) {
            Ok(found) if !(found.rms_error.is_finite() && found.largest_error.is_finite()) => {
                last_error = format!(
                    "the best fit's error at the targets is not finite (rms {}, largest {}): \
                     no linkage was found",
                    found.rms_error, found.largest_error
                );
            }
            Ok(found)
                if best
                    .as_ref()
                    .is_none_or(|(b, _)| found.rms_error < b.rms_error) =>
            {
                best = Some((found, options));
            }
            Ok(_) => {}
            Err(error) => last_error = error.to_string(),
        }
    }
    best.ok_or(last_error)
}

/// The linkage found and how well it meets its targets.
fn report(found: &Synthesis, options: &Options, task: Fitted) {
    say!(
        "{} branch",
        if options.branch == Branch::Open {
            "open"
        } else {
            "crossed"
        }
    );
    let [l1, l2, l3, l4] = found.linkage.lengths();
    let (a, delta) = found.linkage.coupler_point();
    say!(
        "Four-bar ground {} crank {} coupler {} rocker {} mm, coupler point {} mm at {}°",
        length(l1),
        length(l2),
        length(l3),
        length(l4),
        length(a),
        output::degrees(delta, 4)
    );
    let (what, unit, scale) = match task {
        Fitted::Function => ("", "°", f64::to_degrees as fn(f64) -> f64),
        Fitted::Path => (
            " (the coupler point's distance from each target)",
            " mm",
            (|e| e) as fn(f64) -> f64,
        ),
    };
    say!(
        "rms error{what} {:.3e}{unit}, largest {:.3e}{unit}; {} starts converged, {} met the \
         constraints",
        scale(found.rms_error),
        scale(found.largest_error),
        found.converged,
        found.feasible
    );
}

/// What a synthesis fitted, for its errors' units.
#[derive(Clone, Copy)]
enum Fitted {
    /// Rocker angles (the errors in radians, printed in degrees).
    Function,
    /// Coupler points (the errors distances).
    Path,
}

/// Where Freudenstein's closed form meets its three points: its equation holds on either
/// branch (it is the loop's, squared), so the linkage may meet them only by changing
/// assembly between them, which no linkage does while it moves.
fn closed_form_branches(
    d: f64,
    a: f64,
    b: f64,
    c: f64,
    crank_degrees: &[f64],
    phi: &[f64],
    psi: &[f64],
) -> String {
    let Ok(linkage) = FourBar::new(d, a, b, c) else {
        return ", which is no four-bar".into();
    };
    let meets = |branch: Branch, phi: f64, psi: f64| {
        linkage
            .assemble(phi, branch)
            .is_ok_and(|q| wrapped(q.theta4 - psi).abs() <= 1e-6)
    };
    let on = |branch: Branch| phi.iter().zip(psi).all(|(&f, &s)| meets(branch, f, s));
    if on(Branch::Open) {
        return ", on the open branch".into();
    }
    if on(Branch::Crossed) {
        return ", on the crossed branch".into();
    }
    let each: Vec<String> = crank_degrees
        .iter()
        .zip(phi.iter().zip(psi))
        .map(|(degrees, (&f, &s))| {
            let branch = if meets(Branch::Open, f, s) {
                "open"
            } else if meets(Branch::Crossed, f, s) {
                "crossed"
            } else {
                "neither"
            };
            format!("{branch} at {}°", tidy(*degrees))
        })
        .collect();
    format!(
        ", which meets them only on different branches ({}): no one assembly does",
        each.join(", ")
    )
}

/// A synthesised length: to 4 decimals from a tenth up (at least 5 significant digits),
/// else in exponent form to 5 significant digits, so that a fit made at any scale can be
/// reproduced from what is printed.
fn length(value: f64) -> String {
    if value == 0.0 || (0.1..1e9).contains(&value.abs()) {
        fixed(value, 4)
    } else {
        format!("{value:.4e}")
    }
}

fn wrapped(angle: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    angle - tau * (angle / tau).round()
}

fn write(path: &PathBuf, drawing: &str) -> Result<(), String> {
    if output::is_stdout(path) {
        output::drawing_to_stdout(drawing);
    } else {
        fs::write(path, drawing).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        output::tell!("wrote {}", path.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Example 1 at three crank angles, the last on the crossed branch: Freudenstein's
    /// closed form gives Example 1 back (its equation holds on either branch), and the report
    /// says it meets the points only by changing assembly.
    #[test]
    fn a_closed_form_met_on_two_branches_says_so() {
        let example = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
        let crank = [20.0, 70.0, 120.0];
        let phi = crank.map(f64::to_radians);
        let branches = [Branch::Open, Branch::Open, Branch::Crossed];
        let psi: Vec<f64> = phi
            .iter()
            .zip(branches)
            .map(|(&p, b)| example.assemble(p, b).unwrap().theta4)
            .collect();
        let [d, a, b, c] = synthesis::freudenstein(180.0, phi, [psi[0], psi[1], psi[2]]).unwrap();
        assert!((a - 80.0).abs() < 1e-9 && (b - 200.0).abs() < 1e-9 && (c - 150.0).abs() < 1e-9);
        assert_eq!(
            closed_form_branches(d, a, b, c, &crank, &phi, &psi),
            ", which meets them only on different branches (open at 20°, open at 70°, crossed \
             at 120°): no one assembly does"
        );
        let open: Vec<f64> = phi
            .iter()
            .map(|&p| example.assemble(p, Branch::Open).unwrap().theta4)
            .collect();
        assert_eq!(
            closed_form_branches(d, a, b, c, &crank, &phi, &open),
            ", on the open branch"
        );
    }

    #[test]
    fn lengths_print_five_significant_digits_at_any_scale() {
        assert_eq!(length(180.0), "180.0000");
        assert_eq!(length(0.0018), "1.8000e-3");
        assert_eq!(length(0.25), "0.2500");
        assert_eq!(length(0.0), "0.0000");
        assert_eq!(length(6.7547e299), "6.7547e299");
    }

    #[test]
    fn untimed_path_generation_is_held_to_its_budget() {
        let each = |restarts: usize, branches: usize| {
            vec![
                Options {
                    restarts,
                    ..Options::default()
                };
                branches
            ]
        };
        assert!(untimed_within_budget(9, &each(1000, 2)).is_ok());
        assert!(untimed_within_budget(20, &each(64, 2)).is_ok());
        let refused = untimed_within_budget(40, &each(64, 2)).unwrap_err();
        assert!(
            refused.contains("40 targets with 64 random starts on each branch")
                && refused.contains("--restarts 11 or fewer (or one --branch)"),
            "{refused}"
        );
        assert!(untimed_within_budget(100, &each(1, 1)).is_ok());
        assert!(untimed_within_budget(1000, &each(1, 1)).is_err());
        // Linear in the targets where their crank angles are given: 1000 restarts on each
        // branch up to 1000 targets; at 2000, refused, with the 500 that fit.
        assert!(within_budget(1000, &each(1000, 2), "path").is_ok());
        let refused = within_budget(2000, &each(1000, 2), "path").unwrap_err();
        assert!(
            refused.contains("--restarts 500 or fewer (or one --branch)"),
            "{refused}"
        );
        assert!(within_budget(usize::MAX, &each(1, 1), "function").is_err());
    }
}
