//! Dimensional synthesis: the four-bar's dimensions that make its output follow a wanted
//! function of its input ([`function_generation`]) or its coupler point pass through wanted
//! points ([`path_generation`]), and the Watt six-bar's for a function
//! ([`watt_function_generation`]); and, for any declaration with sensitivities, the
//! parameters that put its unknowns and points where targets want them ([`fit`], through
//! [`mechgen::Design`]).
//!
//! Each problem is least squares, solved by Levenberg–Marquardt (the `levenberg-marquardt`
//! crate) on the exact derivatives the macro generates (`generate: sensitivities`, and the
//! velocities for the input angles): no finite differences. Lengths are solved for through
//! their logarithms, so that they stay positive. A start that cannot assemble at a target, or
//! whose solution breaks a constraint (a crank that must turn fully, a transmission angle
//! that must stay within bounds), is discarded: random restarts, run in parallel on every
//! core (rayon) and reproducible from a seed, guard against local minima and infeasible
//! solutions, and the classical precision-point solution seeds the four-bar's function
//! generation (Freudenstein's, [`freudenstein`] for three points and
//! [`freudenstein_least_squares`] for more).
//!
//! The branch asked for is the one every target is solved on, and the crank moves through
//! every target on one circuit: a solution never switches assembly, nor is it taken apart,
//! between targets.

use std::vec;
use std::vec::Vec;

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt, TerminationReason};
use mechgen::grashof::{Class, Inversion};
use mechgen::{Branch, Vec2};
use nalgebra::storage::Owned;
use nalgebra::{DMatrix, DVector, Dyn};
use rayon::prelude::*;

use crate::random::SplitMix64;
use crate::{FourBar, WattSixBar, WattSixBarBranches};

mod fit;

pub use fit::{Fitted, Target, fit};

/// What a synthesis may return, and how hard it looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The assembly branch every target is solved on.
    pub branch: Branch,
    /// Random starts, besides the classical one where there is one.
    pub restarts: usize,
    /// The seed of the random starts: the same seed, the same result, on any number of
    /// cores.
    pub seed: u64,
    /// Require a crank that turns fully (class I Grashof, with the crank or the ground
    /// shortest; not a change point, whose links line up where its branch cannot be kept).
    pub crank: bool,
    /// Require the transmission angle within these bounds (radians, within [0, π]) at every
    /// target; over the whole turn where `crank` is asked too.
    pub transmission: Option<(f64, f64)>,
    /// The largest ratio of the longest link to the shortest: a start that runs off towards
    /// a degenerate linkage (a crank shrinking to nothing, which follows a bad fit exactly
    /// enough) is discarded.
    pub max_ratio: f64,
    /// An rms error that is good enough: where the classical start (Freudenstein's, for
    /// function generation) reaches it and meets the constraints, as it is or once polished,
    /// that solution is returned without the random restarts. `None` always runs them.
    pub good_enough: Option<f64>,
}

impl Default for Options {
    /// The open branch, 64 restarts from seed 1, no link more than 50 times another, every
    /// restart run.
    fn default() -> Self {
        Options {
            branch: Branch::Open,
            restarts: 64,
            seed: 1,
            crank: false,
            transmission: None,
            max_ratio: 50.0,
            good_enough: None,
        }
    }
}

/// A synthesised linkage and how well it meets its targets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Synthesis {
    /// The linkage (for path generation, in its own frame: crank pivot O2 at the origin,
    /// ground along +x; [`placement`](Self::placement) puts it in the targets' frame).
    pub linkage: FourBar<f64>,
    /// For path generation, the crank pivot O2 and the ground line's angle in the targets'
    /// frame; for function generation, the origin and 0.
    pub placement: (Vec2<f64>, f64),
    /// The root-mean-square error at the targets: for function generation the rocker angle's,
    /// radians; for path generation the coupler point's distance from each target, in the
    /// targets' units.
    pub rms_error: f64,
    /// The largest error at a target (radians, or a distance).
    pub largest_error: f64,
    /// How many starts converged.
    pub converged: usize,
    /// How many of those met every constraint.
    pub feasible: usize,
}

/// Why a synthesis found nothing.
#[derive(Clone, Debug, PartialEq)]
pub enum SynthesisError {
    /// Too few targets for the unknowns, or a target that is not finite.
    BadTargets(&'static str),
    /// Options no linkage could meet for themselves, whatever the targets: a largest link
    /// ratio not above 1 (or NaN), transmission bounds not within [0, π] in order.
    BadOptions(&'static str),
    /// No start converged to a linkage that meets the constraints.
    NothingFeasible {
        /// How many starts converged (each to a linkage that breaks a constraint).
        converged: usize,
    },
}

impl core::fmt::Display for SynthesisError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SynthesisError::BadTargets(why) | SynthesisError::BadOptions(why) => {
                write!(f, "{why}")
            }
            SynthesisError::NothingFeasible { converged } => write!(
                f,
                "no linkage meets the targets and the constraints ({converged} starts converged \
                 to linkages that break a constraint or miss the targets)"
            ),
        }
    }
}

impl std::error::Error for SynthesisError {}

/// Freudenstein's three-position function generation in closed form: the four-bar with
/// ground `ground` whose rocker is at `psi[i]` when its crank is at `phi[i]` (radians from
/// the ground line), from the linear equations
/// `K1·cos ψ − K2·cos φ + K3 = cos(φ − ψ)` with `K1 = d/a`, `K2 = d/c`,
/// `K3 = (a² − b² + c² + d²)/(2·a·c)` (crank a, coupler b, rocker c, ground d). `None` where
/// the equations are singular or give no linkage (a length not positive).
///
/// ```
/// use mechanisms::synthesis::freudenstein;
/// use mechanisms::FourBar;
/// use mechgen::Branch;
/// // Example 1's rocker angles at three crank angles give Example 1 back.
/// let example = FourBar::new(180.0, 80.0, 200.0, 150.0)?;
/// let phi = [0.3, 1.2, 2.0];
/// let psi = phi.map(|p| example.assemble(p, Branch::Open).unwrap().theta4);
/// let [d, a, b, c] = freudenstein(180.0, phi, psi).unwrap();
/// assert!((a - 80.0).abs() < 1e-9 && (b - 200.0).abs() < 1e-9 && (c - 150.0).abs() < 1e-9);
/// assert_eq!(d, 180.0);
/// # Ok::<(), mechanisms::DimensionError<f64>>(())
/// ```
pub fn freudenstein(ground: f64, phi: [f64; 3], psi: [f64; 3]) -> Option<[f64; 4]> {
    let rows = core::array::from_fn::<[f64; 3], 3, _>(|i| [psi[i].cos(), -phi[i].cos(), 1.0]);
    let rhs = core::array::from_fn::<f64, 3, _>(|i| (phi[i] - psi[i]).cos());
    let [k1, k2, k3] = solve3(rows, rhs)?;
    lengths_from_freudenstein(ground, k1, k2, k3)
}

/// Freudenstein's equation over any number of precision points (three or more), in least
/// squares: the normal equations of `K1·cos ψ − K2·cos φ + K3 = cos(φ − ψ)`, then the lengths
/// as in [`freudenstein`] (the same for three points, to rounding). The classical start of
/// [`function_generation`]; it minimises the equation's residual, not the angles' errors,
/// which the least squares after it does.
///
/// ```
/// use mechanisms::synthesis::freudenstein_least_squares;
/// use mechanisms::FourBar;
/// use mechgen::Branch;
/// let example = FourBar::new(180.0, 80.0, 200.0, 150.0)?;
/// let phi = [0.0, 0.8, 1.6, 2.4, 3.2];
/// let psi = phi.map(|p| example.assemble(p, Branch::Open).unwrap().theta4);
/// let [_, a, b, c] = freudenstein_least_squares(180.0, &phi, &psi).unwrap();
/// assert!((a - 80.0).abs() < 1e-9 && (b - 200.0).abs() < 1e-9 && (c - 150.0).abs() < 1e-9);
/// # Ok::<(), mechanisms::DimensionError<f64>>(())
/// ```
pub fn freudenstein_least_squares(ground: f64, phi: &[f64], psi: &[f64]) -> Option<[f64; 4]> {
    if phi.len() != psi.len() || phi.len() < 3 {
        return None;
    }
    // AᵀA and Aᵀb, with rows [cos ψ, −cos φ, 1] and right-hand sides cos(φ − ψ).
    let mut normal = [[0.0; 3]; 3];
    let mut rhs = [0.0; 3];
    for (&phi, &psi) in phi.iter().zip(psi) {
        let row = [psi.cos(), -phi.cos(), 1.0];
        let b = (phi - psi).cos();
        for i in 0..3 {
            for j in 0..3 {
                normal[i][j] += row[i] * row[j];
            }
            rhs[i] += row[i] * b;
        }
    }
    let [k1, k2, k3] = solve3(normal, rhs)?;
    lengths_from_freudenstein(ground, k1, k2, k3)
}

/// The lengths `[d, a, b, c]` of Freudenstein's `K1`, `K2`, `K3`, if they make a linkage:
/// found for a ground of 1 and scaled, so that no square overflows or underflows at any
/// ground (1e300 or 1e-300), and `None` only where the linkage itself is not one or not
/// representable.
fn lengths_from_freudenstein(ground: f64, k1: f64, k2: f64, k3: f64) -> Option<[f64; 4]> {
    let (a, c) = (1.0 / k1, 1.0 / k2);
    let b_squared = a * a + c * c + 1.0 - 2.0 * a * c * k3;
    let unit = [1.0, a, b_squared.sqrt(), c];
    let lengths = unit.map(|l| l * ground);
    (a > 0.0
        && c > 0.0
        && b_squared > 0.0
        && b_squared.is_finite()
        && lengths.iter().all(|l| l.is_finite() && *l > 0.0))
    .then_some(lengths)
}

/// `x` with `a·x = b`, by Cramer's rule; `None` where `a` is singular to rounding.
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(a);
    let size = a.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    // Not clearly regular (a NaN is not either).
    let regular = d.abs() > 1e-12 * size * size * size;
    if !regular {
        return None;
    }
    Some(core::array::from_fn(|k| {
        let mut m = a;
        for (row, value) in m.iter_mut().zip(b) {
            row[k] = value;
        }
        det(m) / d
    }))
}

/// Function generation: the four-bar with ground `ground` whose rocker angle θ4 is `psi[i]`
/// when its crank angle θ2 is `phi[i]` (radians from the ground line), for three or more
/// precision points, in least squares past three. The crank, coupler and rocker are solved
/// for; Freudenstein's solution of three of the points ([`freudenstein`]) is the first
/// start.
///
/// ```
/// use mechanisms::synthesis::{function_generation, Options};
/// use mechanisms::FourBar;
/// use mechgen::Branch;
/// // Five precision points of Example 1's output: the synthesis finds Example 1.
/// let example = FourBar::new(180.0, 80.0, 200.0, 150.0)?;
/// let phi = [0.0, 0.8, 1.6, 2.4, 3.2];
/// let psi = phi.map(|p| example.assemble(p, Branch::Open).unwrap().theta4);
/// let found = function_generation(180.0, &phi, &psi, &Options::default())?;
/// let [_, a, b, c] = found.linkage.lengths();
/// assert!((a - 80.0).abs() < 1e-7 && (b - 200.0).abs() < 1e-7 && (c - 150.0).abs() < 1e-7);
/// assert!(found.rms_error < 1e-10);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn function_generation(
    ground: f64,
    phi: &[f64],
    psi: &[f64],
    options: &Options,
) -> Result<Synthesis, SynthesisError> {
    check_options(options)?;
    if phi.len() != psi.len() || phi.len() < 3 {
        return Err(SynthesisError::BadTargets(
            "function generation needs three or more pairs of input and output angles",
        ));
    }
    if !(ground.is_finite() && ground > 0.0) || phi.iter().chain(psi).any(|v| !v.is_finite()) {
        return Err(SynthesisError::BadTargets(
            "the ground length must be positive and every angle finite",
        ));
    }
    if let Some((i, j)) = coinciding(phi) {
        return Err(SynthesisError::BadTargets(if same_angle(psi[i], psi[j]) {
            "a precision point is given twice (two crank angles the same, to within 1e-9 rad \
             and whole turns, with the same rocker angle): give each once"
        } else {
            "a crank angle is given two rocker angles (the same to within 1e-9 rad and whole \
             turns): no four-bar on one branch meets both"
        }));
    }
    let classical = freudenstein_least_squares(ground, phi, psi).map(|[_, a, b, c]| [a, b, c]);
    let starts = starts(options, classical.into_iter().collect(), |random| {
        crank_rocker(ground, random)
    });
    let problem = |start: [f64; 3]| FunctionProblem {
        ground,
        phi,
        psi,
        branch: options.branch,
        x: DVector::from_iterator(3, start.iter().map(|l| l.ln())),
    };
    // The classical solution as it is, where that is good enough: no polish needed.
    if let (Some(enough), Some(start)) = (options.good_enough, classical) {
        let unpolished = problem(start);
        if let (Some(linkage), Some(errors)) = (unpolished.linkage(), unpolished.errors()) {
            if rms(&errors) <= enough && meets(&linkage, phi, options) {
                return best(
                    vec![Some((
                        linkage,
                        (Vec2::default(), 0.0),
                        errors,
                        phi.to_vec(),
                    ))],
                    options,
                );
            }
        }
    }
    let solve = |start: [f64; 3]| {
        let (solved, finished) = minimise(problem(start));
        let linkage = solved.linkage()?;
        let errors = solved.errors()?;
        finished.then_some(())?;
        Some((linkage, (Vec2::default(), 0.0), errors, phi.to_vec()))
    };
    solved_with_restarts(starts, usize::from(classical.is_some()), solve, options)
}

/// Path generation: the four-bar and its placement (crank pivot, ground line's angle) whose
/// coupler point passes through `targets`, at the crank angles `timing` (radians from the
/// ground line) where they are prescribed, else at crank angles it finds too (then it needs
/// nine or more targets for its nine dimensions and placement; five or more with timing).
///
/// ```
/// use mechanisms::synthesis::{path_generation, Options};
/// use mechanisms::FourBar;
/// use mechgen::{Branch, Vec2};
/// // Six points of Example 1's coupler curve (P 100 from A at 30°), with their crank angles.
/// let example = FourBar::new(180.0, 80.0, 200.0, 150.0)?.with_coupler_point(100.0, 0.5236)?;
/// let timing: Vec<f64> = (0..6).map(|k| k as f64).collect();
/// let targets: Vec<Vec2<f64>> = timing
///     .iter()
///     .map(|&t| {
///         let q = example.assemble(t, Branch::Open).unwrap();
///         example.points(t, &q).unwrap().coupler_point
///     })
///     .collect();
/// let found = path_generation(&targets, Some(&timing), &Options::default())?;
/// assert!(found.rms_error < 1e-8);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn path_generation(
    targets: &[Vec2<f64>],
    timing: Option<&[f64]>,
    options: &Options,
) -> Result<Synthesis, SynthesisError> {
    check_options(options)?;
    let needed = if timing.is_some() { 5 } else { 9 };
    if targets.len() < needed {
        return Err(SynthesisError::BadTargets(if timing.is_some() {
            "path generation with prescribed crank angles needs five or more targets"
        } else {
            "path generation without prescribed crank angles needs nine or more targets"
        }));
    }
    if timing.is_some_and(|t| t.len() != targets.len())
        || targets
            .iter()
            .any(|p| !(p.x.is_finite() && p.y.is_finite()))
        || timing.is_some_and(|t| t.iter().any(|v| !v.is_finite()))
    {
        return Err(SynthesisError::BadTargets(
            "every target needs finite coordinates, and a crank angle if any has one",
        ));
    }
    let n = targets.len();
    let (centre, spread) = centre_and_spread(targets);
    if all_coincide(targets) {
        // Found by an adversarial review: with crank angles the fit made a linkage far below
        // the rounding of its own placement, whose errors were true and meant nothing.
        return Err(SynthesisError::BadTargets(
            "the targets all coincide: a coupler curve through one point is any linkage's; \
             give distinct targets",
        ));
    }
    let near = COINCIDENT * spread;
    match timing {
        Some(timing) => {
            if let Some((i, j)) = coinciding(timing) {
                let (p, q) = (targets[i], targets[j]);
                return Err(SynthesisError::BadTargets(
                    if (p.x - q.x).hypot(p.y - q.y) <= near {
                        "a target is given twice at the same crank angle (to within 1e-9 rad \
                         and whole turns): give each once"
                    } else {
                        "two targets are given the same crank angle (to within 1e-9 rad and \
                         whole turns): no four-bar on one branch has its coupler point at both"
                    },
                ));
            }
        }
        None => {
            if coinciding_points(targets, near).is_some() {
                return Err(SynthesisError::BadTargets(
                    "a target is given twice (two within a billionth of the targets' spread): \
                     path generation without prescribed crank angles needs nine or more \
                     distinct targets; give each once",
                ));
            }
        }
    }
    // Coincident targets still start somewhere: at the smallest positive spread.
    let spread = spread.max(f64::MIN_POSITIVE);
    let starts = starts(options, Vec::new(), |random| {
        path_start(centre, spread, timing.is_none().then_some(n), random)
    });
    let solve = |start: Vec<f64>| {
        let problem = PathProblem {
            targets,
            timing,
            branch: options.branch,
            x: DVector::from_vec(start),
        };
        let (solved, finished) = minimise(problem);
        let linkage = solved.linkage()?;
        let errors = solved.errors()?;
        finished.then_some(())?;
        let x = &solved.x;
        let inputs = (0..n).map(|i| solved.input(i)).collect();
        // Each target's error is its distance from the coupler point (the residuals are
        // the two components).
        let distances = errors.chunks(2).map(|d| d[0].hypot(d[1])).collect();
        Some((
            linkage,
            (Vec2 { x: x[0], y: x[1] }, x[2]),
            distances,
            inputs,
        ))
    };
    solved_with_restarts(starts, 0, solve, options)
}

/// How close two angles (radians, whole turns aside) or two targets (a fraction of the
/// targets' spread) may be before they count as the same: a billionth, far closer than any
/// precision point is set, far above rounding.
const COINCIDENT: f64 = 1e-9;

/// Whether two angles are the same to within [`COINCIDENT`] radians, whole turns aside.
fn same_angle(a: f64, b: f64) -> bool {
    let tau = core::f64::consts::TAU;
    let d = (a - b).rem_euclid(tau);
    d.min(tau - d) <= COINCIDENT
}

/// The indices of two of `angles` that are the same (see [`same_angle`]), if any: sorted
/// round the turn, so that only neighbours (and the last with the first) need comparing.
fn coinciding(angles: &[f64]) -> Option<(usize, usize)> {
    let tau = core::f64::consts::TAU;
    let mut order: Vec<(f64, usize)> = angles
        .iter()
        .enumerate()
        .map(|(i, a)| (a.rem_euclid(tau), i))
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    let pairs = order.windows(2).map(|w| (w[0], w[1]));
    let around = order.last().zip(order.first()).map(|(l, f)| (*l, *f));
    pairs
        .chain(around.filter(|_| order.len() > 1))
        .find(|((a, _), (b, _))| same_angle(*a, *b))
        .map(|((_, i), (_, j))| (i.min(j), i.max(j)))
}

/// The indices of two `targets` within `near` of each other, if any: sorted by x, each
/// compared only with those after it whose x is within `near`.
fn coinciding_points(targets: &[Vec2<f64>], near: f64) -> Option<(usize, usize)> {
    let mut order: Vec<usize> = (0..targets.len()).collect();
    order.sort_by(|&a, &b| targets[a].x.total_cmp(&targets[b].x));
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            let (p, q) = (targets[i], targets[j]);
            if q.x - p.x > near {
                break;
            }
            if (p.x - q.x).hypot(p.y - q.y) <= near {
                return Some((i.min(j), i.max(j)));
            }
        }
    }
    None
}

/// `Ok` for options a linkage could meet, else why not (an adversarial review found such
/// options reported as `NothingFeasible`, blaming the targets).
fn check_options(options: &Options) -> Result<(), SynthesisError> {
    // Above 1, and a number; infinite is no limit.
    if options.max_ratio.is_nan() || options.max_ratio <= 1.0 {
        return Err(SynthesisError::BadOptions(
            "the largest ratio of the longest link to the shortest must be above 1",
        ));
    }
    if let Some((low, high)) = options.transmission {
        // In order within [0, π] (false for NaN).
        if !(0.0 <= low && low < high && high <= core::f64::consts::PI) {
            return Err(SynthesisError::BadOptions(
                "the transmission angle's bounds must be in order within [0, π] radians",
            ));
        }
    }
    Ok(())
}

/// Whether the targets are all one point: each the first, or all within the rounding of
/// their centroid (which, summed in shares, need not be the point itself).
pub fn all_coincide(targets: &[Vec2<f64>]) -> bool {
    let Some(first) = targets.first() else {
        return false;
    };
    if targets.iter().all(|p| p == first) {
        return true;
    }
    let (centre, spread) = centre_and_spread(targets);
    spread <= 8.0 * f64::EPSILON * (centre.x.abs() + centre.y.abs())
}

/// The targets' centroid, and their largest distance from it (0 where they all coincide):
/// where path generation's random starts put the linkage, and their scale.
pub fn centre_and_spread(targets: &[Vec2<f64>]) -> (Vec2<f64>, f64) {
    let n = targets.len() as f64;
    let centre = targets
        .iter()
        .fold(Vec2::default(), |c: Vec2<f64>, p| Vec2 {
            x: c.x + p.x / n,
            y: c.y + p.y / n,
        });
    let spread = targets
        .iter()
        .map(|p| (p.x - centre.x).hypot(p.y - centre.y))
        .fold(0.0f64, f64::max);
    (centre, spread)
}

/// A random start of path generation, `[x0, y0, θ1, ln l1, ln l2, ln l3, ln l4, ln a, δ]`:
/// the crank pivot one to three spreads from the centre, any ground angle, a ground of half
/// to twice the spread carrying a random crank-rocker, a coupler point 0.1 to 2 spreads from
/// the crank pin at any angle; and, where the crank angles are to be found (`untimed` of
/// them), each target's, in order round the turn from a random first.
fn path_start(
    centre: Vec2<f64>,
    spread: f64,
    untimed: Option<usize>,
    random: &mut SplitMix64,
) -> Vec<f64> {
    let tau = core::f64::consts::TAU;
    let mut x = Vec::with_capacity(9 + untimed.unwrap_or(0));
    let radius = spread * (1.0 + 2.0 * random.fraction());
    let around = tau * random.fraction();
    x.push(centre.x + radius * around.cos());
    x.push(centre.y + radius * around.sin());
    x.push(tau * random.fraction());
    let ground = spread * (0.5 + 1.5 * random.fraction());
    x.push(ground.ln());
    x.extend(crank_rocker(ground, random).map(f64::ln));
    x.push((spread * (0.1 + 1.9 * random.fraction())).ln());
    x.push(tau * random.fraction());
    if let Some(n) = untimed {
        let first = tau * random.fraction();
        x.extend((0..n).map(|i| first + tau * i as f64 / n as f64));
    }
    x
}

/// The starts: `classical` first, then `options.restarts` random ones, each from its own
/// generator seeded from `options.seed` and its index, so that the result does not depend
/// on how many cores run them.
fn starts<S>(
    options: &Options,
    classical: Vec<S>,
    random_start: impl Fn(&mut SplitMix64) -> S,
) -> Vec<S> {
    let random = (0..options.restarts).map(|k| {
        let mut generator =
            SplitMix64(options.seed ^ (k as u64).wrapping_mul(0xA24B_AED4_963E_E407));
        random_start(&mut generator)
    });
    classical.into_iter().chain(random).collect()
}

/// Every start solved by `solve` and the best kept; the first `classical` starts first, and
/// alone where one of them is [good enough](Options::good_enough), the random ones after them
/// in parallel.
fn solved_with_restarts<S: Send>(
    mut starts: Vec<S>,
    classical: usize,
    solve: impl Fn(S) -> Option<Solved> + Sync,
    options: &Options,
) -> Result<Synthesis, SynthesisError> {
    let random = starts.split_off(classical.min(starts.len()));
    let first: Vec<Option<Solved>> = starts.into_iter().map(&solve).collect();
    if let Some(enough) = options.good_enough {
        if let Ok(found) = best(first.clone(), options) {
            if found.rms_error <= enough {
                return Ok(found);
            }
        }
    }
    let mut solved = first;
    solved.extend(random.into_par_iter().map(&solve).collect::<Vec<_>>());
    best(solved, options)
}

/// A start's solution: the linkage, its placement, its errors at the targets and its crank
/// angles there; `None` for a start that did not converge.
type Solved = (FourBar<f64>, (Vec2<f64>, f64), Vec<f64>, Vec<f64>);

/// The best of the converged starts that meet the constraints: the smallest rms error, ties
/// to the earliest start.
fn best(solved: Vec<Option<Solved>>, options: &Options) -> Result<Synthesis, SynthesisError> {
    let converged = solved.iter().flatten().count();
    let feasible: Vec<_> = solved
        .into_iter()
        .flatten()
        .filter(|(linkage, _, _, inputs)| meets(linkage, inputs, options))
        .collect();
    let count = feasible.len();
    feasible
        .into_iter()
        .map(|(linkage, placement, errors, _)| Synthesis {
            linkage,
            placement,
            rms_error: rms(&errors),
            largest_error: errors.iter().fold(0.0f64, |m, e| m.max(e.abs())),
            converged,
            feasible: count,
        })
        .min_by(|a, b| a.rms_error.total_cmp(&b.rms_error))
        .ok_or(SynthesisError::NothingFeasible { converged })
}

/// Whether `linkage` meets the constraints of `options` at the crank angles `inputs`.
fn meets(linkage: &FourBar<f64>, inputs: &[f64], options: &Options) -> bool {
    if !within_ratio(&linkage.lengths(), options.max_ratio) {
        return false;
    }
    // Solved on one branch at every target, but perhaps on two circuits.
    if !linkage.limit_angles().one_circuit(inputs) {
        return false;
    }
    // Class I: a change point (class III) turns fully too, but its links line up, where the
    // branch it is solved on cannot be kept.
    let grashof = linkage.grashof();
    if options.crank
        && (grashof.class != Class::Grashof
            || !matches!(
                grashof.inversion,
                Inversion::CrankRocker | Inversion::DoubleCrank
            ))
    {
        return false;
    }
    let Some((low, high)) = options.transmission else {
        return true;
    };
    let within = |theta2: f64| {
        linkage
            .assemble(theta2, options.branch)
            .is_ok_and(|q| (low..=high).contains(&linkage.transmission_angle(&q)))
    };
    if options.crank {
        // Over the whole turn, every degree.
        (0..360).all(|k| within(f64::from(k).to_radians()))
    } else {
        inputs.iter().all(|&theta2| within(theta2))
    }
}

/// A least-squares problem in its unknowns `x`, as each synthesis poses it.
trait Residuals {
    fn x(&self) -> &DVector<f64>;
    fn x_mut(&mut self) -> &mut DVector<f64>;
    /// After `x` has moved: where a problem solves its positions once per `x`.
    fn moved(&mut self) {}
    /// How many residuals there are.
    fn count(&self) -> usize;
    /// The residuals at `x`, or `None` where some target cannot be reached.
    fn errors(&self) -> Option<Vec<f64>>;
    /// Their Jacobian at `x`, from the generated derivatives.
    fn derivatives(&self) -> Option<DMatrix<f64>>;
}

/// A [`Residuals`] as Levenberg–Marquardt takes it.
struct Fit<R>(R);

impl<R: Residuals> LeastSquaresProblem<f64, Dyn, Dyn> for Fit<R> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        self.0.x_mut().copy_from(x);
        self.0.moved();
    }

    fn params(&self) -> DVector<f64> {
        self.0.x().clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        Some(not_assembled(self.0.errors(), self.0.count()))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        self.0.derivatives()
    }
}

/// `problem` solved by Levenberg–Marquardt from its `x`: the problem at the solution, and
/// whether it stopped at a minimum.
fn minimise<R: Residuals>(problem: R) -> (R, bool) {
    let (Fit(solved), report) = LevenbergMarquardt::new().minimize(Fit(problem));
    (solved, finished(&report.termination))
}

/// Whether Levenberg–Marquardt stopped at a minimum: converged by its tests, or unable to
/// improve further in the float's precision (where a fit that is not exact ends), not out
/// of evaluations nor on a non-finite value.
fn finished(termination: &TerminationReason) -> bool {
    termination.was_successful()
        || matches!(termination, TerminationReason::NoImprovementPossible(_))
}

/// The residuals, or where some target cannot be reached, `count` NaNs: Levenberg–Marquardt
/// then rejects the step that led there and shortens its trust region, where `None` would end
/// the run.
fn not_assembled(errors: Option<Vec<f64>>, count: usize) -> DVector<f64> {
    errors.map_or_else(|| DVector::from_element(count, f64::NAN), DVector::from_vec)
}

/// Crank, coupler and rocker of a random crank-rocker on `ground` (the crank shortest, and
/// Grashof), so that a start reaches every crank angle.
fn crank_rocker(ground: f64, random: &mut SplitMix64) -> [f64; 3] {
    let mut lengths = [0.0; 3];
    for _ in 0..64 {
        let crank = ground * (0.1 + 0.5 * random.fraction());
        let [coupler, rocker] = [0; 2].map(|_| ground * (0.4 + 1.6 * random.fraction()));
        lengths = [crank, coupler, rocker];
        // Classified as the runtime classifies: a start on (or within rounding of) Grashof's
        // change point is refused, since its crank could stop there at a toggle.
        let grashof = mechgen::grashof::classify(ground, crank, coupler, rocker);
        let kind = (grashof.class, grashof.inversion);
        // Of Grashof's four inversions, the only one whose crank turns fully and rocker not.
        if kind == (Class::Grashof, Inversion::CrankRocker) {
            break;
        }
    }
    lengths
}

/// The root mean square of `errors`, each divided by the largest before it is squared: the
/// squares of errors near 1e300 would overflow to infinity and those of errors near 1e-300
/// underflow to a false zero. Zero for no errors, infinite for an infinite one, NaN for a NaN.
fn rms(errors: &[f64]) -> f64 {
    let largest = errors.iter().fold(0.0f64, |m, e| m.max(e.abs()));
    if largest == 0.0 || largest.is_infinite() {
        return largest;
    }
    let mean_square = errors
        .iter()
        .map(|e| {
            let scaled = e / largest;
            scaled * scaled
        })
        .sum::<f64>()
        / errors.len() as f64;
    largest * mean_square.sqrt()
}

/// Whether the longest of `lengths` is within `max_ratio` of the shortest (not for a NaN):
/// a start that runs off towards a degenerate linkage is discarded.
fn within_ratio(lengths: &[f64], max_ratio: f64) -> bool {
    let longest = lengths.iter().fold(0.0f64, |m, l| m.max(*l));
    let shortest = lengths.iter().fold(f64::INFINITY, |m, l| m.min(*l));
    longest <= max_ratio * shortest
}

/// The solutions `solve` finds from `starts`, with their errors: the first start alone where
/// its solution is [good enough](Options::good_enough), else every start, the rest in
/// parallel.
fn solved_from_first<S: Send, T: Send>(
    mut starts: Vec<S>,
    solve: impl Fn(S) -> Option<(T, Vec<f64>)> + Sync,
    options: &Options,
) -> Vec<(T, Vec<f64>)> {
    let random = starts.split_off(starts.len().min(1));
    let mut solved: Vec<_> = starts.into_iter().filter_map(&solve).collect();
    let first_good = solved
        .first()
        .is_some_and(|(_, errors)| options.good_enough.is_some_and(|g| rms(errors) <= g));
    if !first_good {
        solved.extend(
            random
                .into_par_iter()
                .filter_map(&solve)
                .collect::<Vec<_>>(),
        );
    }
    solved
}

/// Each precision point's output error, `output(φ_i) − ψ_i` wrapped to (−π, π], or `None`
/// where the linkage does not reach one of them.
fn output_errors(
    phi: &[f64],
    psi: &[f64],
    output: impl Fn(f64) -> Option<f64>,
) -> Option<Vec<f64>> {
    phi.iter()
        .zip(psi)
        .map(|(&phi, &psi)| Some(wrapped(output(phi)? - psi)))
        .collect()
}

/// `angle` wrapped to [−π, π] (an exact half turn to −π: a residual's square is the same).
fn wrapped(angle: f64) -> f64 {
    let tau = core::f64::consts::TAU;
    angle - tau * (angle / tau).round()
}

/// Function generation's least squares: `x = [ln a, ln b, ln c]`, residuals
/// `θ4(φ_i) − ψ_i` wrapped.
struct FunctionProblem<'a> {
    ground: f64,
    phi: &'a [f64],
    psi: &'a [f64],
    branch: Branch,
    x: DVector<f64>,
}

impl FunctionProblem<'_> {
    fn linkage(&self) -> Option<FourBar<f64>> {
        let [a, b, c] = [0, 1, 2].map(|k| self.x[k].exp());
        FourBar::new(self.ground, a, b, c).ok()
    }

    fn errors(&self) -> Option<Vec<f64>> {
        let linkage = self.linkage()?;
        output_errors(self.phi, self.psi, |phi| {
            linkage.assemble(phi, self.branch).ok().map(|q| q.theta4)
        })
    }
}

impl Residuals for FunctionProblem<'_> {
    fn x(&self) -> &DVector<f64> {
        &self.x
    }

    fn x_mut(&mut self) -> &mut DVector<f64> {
        &mut self.x
    }

    fn count(&self) -> usize {
        self.phi.len()
    }

    fn errors(&self) -> Option<Vec<f64>> {
        self.errors()
    }

    fn derivatives(&self) -> Option<DMatrix<f64>> {
        let linkage = self.linkage()?;
        let [_, a, b, c] = linkage.lengths();
        let mut jacobian = DMatrix::zeros(self.phi.len(), 3);
        for (i, &phi) in self.phi.iter().enumerate() {
            let q = linkage.assemble(phi, self.branch).ok()?;
            let s = linkage.sensitivities(phi, &q).ok()?;
            // ∂/∂ln l = l·∂/∂l.
            for (k, (length, d)) in [(a, s.l2), (b, s.l3), (c, s.l4)].into_iter().enumerate() {
                jacobian[(i, k)] = length * d.theta4;
            }
        }
        Some(jacobian)
    }
}

/// Path generation's least squares: `x = [x0, y0, θ1, ln l1, ln l2, ln l3, ln l4, ln a, δ]`
/// and, without timing, each target's crank angle; residuals the coupler point's position
/// in the targets' frame, `O + R(θ1)·P(θ2_i)`, less the target, x and y.
struct PathProblem<'a> {
    targets: &'a [Vec2<f64>],
    timing: Option<&'a [f64]>,
    branch: Branch,
    x: DVector<f64>,
}

impl PathProblem<'_> {
    fn linkage(&self) -> Option<FourBar<f64>> {
        let [l1, l2, l3, l4, a] = [3, 4, 5, 6, 7].map(|k| self.x[k].exp());
        FourBar::new(l1, l2, l3, l4)
            .and_then(|l| l.with_coupler_point(a, self.x[8]))
            .ok()
    }

    /// Target `i`'s crank angle.
    fn input(&self, i: usize) -> f64 {
        match self.timing {
            Some(timing) => timing[i],
            None => self.x[9 + i],
        }
    }

    /// The ground line's rotation.
    fn turn(&self, v: Vec2<f64>) -> Vec2<f64> {
        let (s, c) = self.x[2].sin_cos();
        Vec2 {
            x: c * v.x - s * v.y,
            y: s * v.x + c * v.y,
        }
    }

    fn errors(&self) -> Option<Vec<f64>> {
        let linkage = self.linkage()?;
        let mut errors = Vec::with_capacity(2 * self.targets.len());
        for (i, target) in self.targets.iter().enumerate() {
            let theta2 = self.input(i);
            let q = linkage.assemble(theta2, self.branch).ok()?;
            let p = self.turn(linkage.points(theta2, &q).ok()?.coupler_point);
            errors.push(self.x[0] + p.x - target.x);
            errors.push(self.x[1] + p.y - target.y);
        }
        Some(errors)
    }
}

impl Residuals for PathProblem<'_> {
    fn x(&self) -> &DVector<f64> {
        &self.x
    }

    fn x_mut(&mut self) -> &mut DVector<f64> {
        &mut self.x
    }

    fn count(&self) -> usize {
        2 * self.targets.len()
    }

    fn errors(&self) -> Option<Vec<f64>> {
        self.errors()
    }

    fn derivatives(&self) -> Option<DMatrix<f64>> {
        let linkage = self.linkage()?;
        let [l1, l2, l3, l4] = linkage.lengths();
        let (a, _) = linkage.coupler_point();
        let n = self.targets.len();
        let mut jacobian = DMatrix::zeros(2 * n, self.x.len());
        for i in 0..n {
            let theta2 = self.input(i);
            let q = linkage.assemble(theta2, self.branch).ok()?;
            let p = linkage.points(theta2, &q).ok()?.coupler_point;
            let s = linkage.point_sensitivities(theta2, &q).ok()?;
            let (sin, cos) = self.x[2].sin_cos();
            let mut set = |k: usize, v: Vec2<f64>| {
                jacobian[(2 * i, k)] = v.x;
                jacobian[(2 * i + 1, k)] = v.y;
            };
            // The dimensions' columns turn with the ground line; the pivot's do not.
            let mut column = |k: usize, v: Vec2<f64>| {
                set(
                    k,
                    Vec2 {
                        x: cos * v.x - sin * v.y,
                        y: sin * v.x + cos * v.y,
                    },
                )
            };
            column(0, Vec2 { x: cos, y: -sin });
            column(1, Vec2 { x: sin, y: cos });
            // ∂R(θ1)P/∂θ1 = R(θ1)·(i·P).
            column(2, Vec2 { x: -p.y, y: p.x });
            let scaled = |l: f64, v: Vec2<f64>| Vec2 {
                x: l * v.x,
                y: l * v.y,
            };
            column(3, scaled(l1, s.l1.coupler_point));
            column(4, scaled(l2, s.l2.coupler_point));
            column(5, scaled(l3, s.l3.coupler_point));
            column(6, scaled(l4, s.l4.coupler_point));
            column(7, scaled(a, s.a.coupler_point));
            column(8, s.delta.coupler_point);
            if self.timing.is_none() {
                // ∂P/∂θ2: the point's velocity at a unit crank rate.
                let rates = linkage.velocity(theta2, &q, 1.0).ok()?;
                let v = linkage.point_velocities(theta2, &q, 1.0, &rates).ok()?;
                column(9 + i, v.coupler_point);
            }
        }
        Some(jacobian)
    }
}

/// A synthesised Watt six-bar and how well it meets its targets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SixBarSynthesis {
    /// The linkage.
    pub linkage: WattSixBar<f64>,
    /// The root-mean-square error of the output angle at the targets, radians.
    pub rms_error: f64,
    /// The largest error at a target, radians.
    pub largest_error: f64,
    /// How many starts converged.
    pub converged: usize,
    /// How many of those met the constraints (the links' ratio).
    pub feasible: usize,
}

/// Function generation for the Watt six-bar: the linkage near `start` whose output angle θ6
/// is `psi[i]` when its crank is at `phi[i]` (radians), on `branches`, with its ground, its
/// output pivot and its crank's length held (they set the frame and the scale) and the
/// other six dimensions fitted: the coupler, the rocker, the rocker's extension and its
/// angle, and the second dyad's two links. Levenberg–Marquardt from `start` and from
/// `options.restarts` random perturbations of it (each length times a factor within e^±0.4,
/// the angle within ±0.4 rad), in parallel; `options.branch`, `crank` and `transmission`
/// do not apply (the branches are `branches`), `max_ratio` and `good_enough` do.
///
/// ```
/// use mechanisms::synthesis::{watt_function_generation, Options};
/// use mechanisms::{WattSixBar, WattSixBarBranches};
/// let target = WattSixBar::new([180.0, 80.0, 200.0, 150.0], 100.0, 0.8, 220.0, 160.0, (300.0, 150.0))?;
/// let branches = WattSixBarBranches::default();
/// let phi: Vec<f64> = (0..8).map(|k| 0.7 * k as f64).collect();
/// let psi: Vec<f64> = phi.iter().map(|&p| target.assemble(p, branches).unwrap().theta6).collect();
/// // From a start 10% off in every fitted dimension.
/// let start = WattSixBar::new([180.0, 80.0, 220.0, 135.0], 110.0, 0.72, 242.0, 144.0, (300.0, 150.0))?;
/// let found = watt_function_generation(&start, &phi, &psi, branches, &Options::default())?;
/// assert!(found.rms_error < 1e-10);
/// let ([_, _, coupler, rocker], _, _, second_coupler, _, _) = found.linkage.dimensions();
/// assert!((coupler - 200.0).abs() < 1e-6 && (rocker - 150.0).abs() < 1e-6);
/// assert!((second_coupler - 220.0).abs() < 1e-6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn watt_function_generation(
    start: &WattSixBar<f64>,
    phi: &[f64],
    psi: &[f64],
    branches: WattSixBarBranches,
    options: &Options,
) -> Result<SixBarSynthesis, SynthesisError> {
    if phi.len() != psi.len() || phi.len() < 6 {
        return Err(SynthesisError::BadTargets(
            "six-bar function generation needs six or more pairs of input and output angles",
        ));
    }
    if phi.iter().chain(psi).any(|v| !v.is_finite()) {
        return Err(SynthesisError::BadTargets("every angle must be finite"));
    }
    let problem = |x: [f64; 6]| WattProblem {
        start: *start,
        phi,
        psi,
        branches,
        x: DVector::from_iterator(6, x),
    };
    let ([_, _, l3, l4], l5, beta, l6, l7, _) = start.dimensions();
    let first = [l3.ln(), l4.ln(), l5.ln(), beta, l6.ln(), l7.ln()];
    let starts = starts(options, vec![first], |random| {
        core::array::from_fn(|k| fit::perturbed_value(first[k], random))
    });
    let solve = |x: [f64; 6]| {
        let (solved, finished) = minimise(problem(x));
        let linkage = solved.linkage()?;
        let errors = solved.errors()?;
        finished.then_some(())?;
        let ([l1, l2, l3, l4], l5, _, l6, l7, _) = linkage.dimensions();
        within_ratio(&[l1, l2, l3, l4, l5, l6, l7], options.max_ratio).then_some((linkage, errors))
    };
    let solved = solved_from_first(starts, solve, options);
    let converged = solved.len();
    solved
        .into_iter()
        .map(|(linkage, errors)| SixBarSynthesis {
            linkage,
            rms_error: rms(&errors),
            largest_error: errors.iter().fold(0.0f64, |m, e| m.max(e.abs())),
            converged,
            feasible: converged,
        })
        .min_by(|a, b| a.rms_error.total_cmp(&b.rms_error))
        .ok_or(SynthesisError::NothingFeasible { converged })
}

/// The six-bar's least squares: `x = [ln l3, ln l4, ln l5, β, ln l6, ln l7]`, residuals
/// `θ6(φ_i) − ψ_i` wrapped.
struct WattProblem<'a> {
    start: WattSixBar<f64>,
    phi: &'a [f64],
    psi: &'a [f64],
    branches: WattSixBarBranches,
    x: DVector<f64>,
}

impl WattProblem<'_> {
    fn linkage(&self) -> Option<WattSixBar<f64>> {
        let x = &self.x;
        let ([l1, l2, _, _], _, _, _, _, pivot) = self.start.dimensions();
        WattSixBar::new(
            [l1, l2, x[0].exp(), x[1].exp()],
            x[2].exp(),
            x[3],
            x[4].exp(),
            x[5].exp(),
            pivot,
        )
        .ok()
    }

    fn errors(&self) -> Option<Vec<f64>> {
        let linkage = self.linkage()?;
        output_errors(self.phi, self.psi, |phi| {
            linkage.assemble(phi, self.branches).ok().map(|q| q.theta6)
        })
    }
}

impl Residuals for WattProblem<'_> {
    fn x(&self) -> &DVector<f64> {
        &self.x
    }

    fn x_mut(&mut self) -> &mut DVector<f64> {
        &mut self.x
    }

    fn count(&self) -> usize {
        self.phi.len()
    }

    fn errors(&self) -> Option<Vec<f64>> {
        self.errors()
    }

    fn derivatives(&self) -> Option<DMatrix<f64>> {
        let l = self.linkage()?;
        let mut jacobian = DMatrix::zeros(self.phi.len(), 6);
        for (i, &phi) in self.phi.iter().enumerate() {
            let q = l.assemble(phi, self.branches).ok()?;
            let s = l.sensitivities(phi, &q).ok()?;
            // ∂/∂ln l = l·∂/∂l; β as it is.
            let ([_, _, l3, l4], l5, _, l6, l7, _) = l.dimensions();
            let columns = [
                l3 * s.l3.theta6,
                l4 * s.l4.theta6,
                l5 * s.l5.theta6,
                s.beta.theta6,
                l6 * s.l6.theta6,
                l7 * s.l7.theta6,
            ];
            for (k, c) in columns.into_iter().enumerate() {
                jacobian[(i, k)] = c;
            }
        }
        Some(jacobian)
    }
}

#[cfg(test)]
mod tests;
