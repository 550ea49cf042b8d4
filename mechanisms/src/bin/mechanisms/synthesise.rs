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
    /// generation without --timing takes tens of seconds for that many). A run past a second
    /// shows a spinner on standard error, on a terminal.
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
        if !(self.max_ratio.is_finite() && self.max_ratio >= 1.0) {
            return Err("--max-ratio must be a finite number, at least 1".into());
        }
        if self.restarts > MOST_RESTARTS {
            return Err(format!("--restarts takes at most {MOST_RESTARTS}"));
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
    let (found, options) = searching(&each, || {
        better(each.clone(), |options| {
            synthesis::function_generation(args.ground, &phi, &psi, options)
        })
    })?;
    report(&found, &options);
    if phi.len() == 3 {
        match synthesis::freudenstein(
            args.ground,
            [phi[0], phi[1], phi[2]],
            [psi[0], psi[1], psi[2]],
        ) {
            Some([_, a, b, c]) => say!(
                "Freudenstein's closed form of the three points: crank {}, coupler {}, rocker {} \
                 mm",
                fixed(a, 4),
                fixed(b, 4),
                fixed(c, 4)
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
    let (found, options) = searching(&each, || {
        better(each.clone(), |options| {
            synthesis::path_generation(&unit, timing.as_deref(), options)
                .and_then(|found| frame.put_back(found))
        })
    })?;
    report(&found, &options);
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
        if spread == 0.0 {
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
fn report(found: &Synthesis, options: &Options) {
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
        output::figure(l1),
        output::figure(l2),
        output::figure(l3),
        output::figure(l4),
        output::figure(a),
        fixed(delta.to_degrees(), 4)
    );
    say!(
        "rms error {:.3e}, largest {:.3e}; {} starts converged, {} met the constraints",
        found.rms_error,
        found.largest_error,
        found.converged,
        found.feasible
    );
}

fn wrapped(angle: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    angle - tau * (angle / tau).round()
}

fn write(path: &PathBuf, drawing: &str) -> Result<(), String> {
    if path.as_os_str() == "-" {
        say!("{drawing}");
    } else {
        fs::write(path, drawing).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
