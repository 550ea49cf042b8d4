//! Dimensional synthesis of any declared mechanism: the dimensions near a start that put its
//! unknowns and tracked points where targets want them, by Levenberg–Marquardt on the
//! sensitivities the macro generates ([`mechgen::Design`]). The four-bar's and the Watt
//! six-bar's own syntheses know their mechanisms (a classical start, constraints); this one
//! knows only the declaration, and serves every one that asks for sensitivities.

use std::vec;
use std::vec::Vec;

use mechgen::{Design, Kinematics, NewtonOptions, Vec2};
use nalgebra::{DMatrix, DVector};

use crate::random::SplitMix64;

use super::{
    Options, Residuals, SynthesisError, minimise, rms, solved_from_first, starts, within_ratio,
    wrapped,
};

/// Where [`fit`] wants the mechanism at one input.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// Unknown number `unknown` (in declaration order) at `value` when the input is `input`:
    /// function generation.
    Unknown {
        /// The input.
        input: f64,
        /// The unknown's index, in declaration order.
        unknown: usize,
        /// Its wanted value (an angle is compared modulo a turn).
        value: f64,
    },
    /// Tracked point number `point` (in declaration order) at `at` when the input is
    /// `input`: path generation with prescribed timing.
    Point {
        /// The input.
        input: f64,
        /// The point's index, in declaration order.
        point: usize,
        /// Its wanted position.
        at: Vec2<f64>,
    },
}

impl Target {
    fn input(&self) -> f64 {
        match *self {
            Target::Unknown { input, .. } | Target::Point { input, .. } => input,
        }
    }

    /// How many residuals it makes: one for an unknown, two for a point.
    fn rows(&self) -> usize {
        match self {
            Target::Unknown { .. } => 1,
            Target::Point { .. } => 2,
        }
    }
}

/// A mechanism [`fit`] found, and how well it meets its targets.
#[derive(Clone, Debug, PartialEq)]
pub struct Fitted<D, const N: usize> {
    /// The mechanism.
    pub mechanism: D,
    /// Its position at each target, in the targets' order.
    pub positions: Vec<[f64; N]>,
    /// The root-mean-square error over the targets' residuals (an unknown's in its own
    /// unit, a point's coordinates in lengths).
    pub rms_error: f64,
    /// The largest residual.
    pub largest_error: f64,
    /// How many starts converged to a mechanism within `max_ratio`.
    pub converged: usize,
}

/// The mechanism near `start` whose unknowns and tracked points meet `targets`, fitting the
/// parameters `free` marks (in declaration order, as [`Design::PARAMETERS`] names them) and
/// holding the others.
///
/// `guess` is near `start`'s position at the first target's input; each target's position is
/// then solved by Newton from the one before (so order the targets along the motion), and
/// kept on that assembly: a step of the fit that would carry a target to another branch
/// (Newton's [`mechgen::Error::OtherBranch`]) or past a toggle is refused, as a mechanism
/// that cannot reach a target is. Lengths are fitted through their logarithms, so they stay
/// positive; angles as they are.
///
/// Levenberg–Marquardt from `start` and from `options.restarts` random perturbations of it
/// (each free length times a factor within e^±0.4, each free angle within ±0.4 rad),
/// reproducible from `options.seed`, in parallel; `options.max_ratio` (over the fitted
/// lengths and the held ones that are not zero) and `options.good_enough` apply; `branch`, `crank` and `transmission` do not (the branch
/// is `guess`'s, and the constraints are the caller's to check on the result).
///
/// ```
/// use mechanisms::synthesis::{fit, Options, Target};
/// use mechanisms::FourBar;
/// use mechgen::{Branch, Design};
/// // Example 1's rocker angle at six crank angles, and a start 10% off it.
/// let example = FourBar::new(180.0, 80.0, 200.0, 150.0)?;
/// let targets: Vec<Target> = (0..6)
///     .map(|k| {
///         let input = 0.9 * k as f64;
///         let value = example.assemble(input, Branch::Open).unwrap().theta4;
///         Target::Unknown { input, unknown: 1, value }
///     })
///     .collect();
/// let start = FourBar::new(180.0, 88.0, 180.0, 165.0)?;
/// let guess = start.assemble(0.0, Branch::Open)?.to_array();
/// // Crank, coupler and rocker free; the ground and the coupler point held.
/// let free = [false, true, true, true, false, false];
/// let found = fit(&start, guess, free, &targets, &Options::default())?;
/// assert!(found.rms_error < 1e-10);
/// let [_, crank, coupler, rocker, ..] = found.mechanism.parameters();
/// assert!((crank - 80.0).abs() < 1e-6 && (coupler - 200.0).abs() < 1e-6);
/// assert!((rocker - 150.0).abs() < 1e-6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit<D, const N: usize, const P: usize, const M: usize>(
    start: &D,
    guess: [f64; N],
    free: [bool; P],
    targets: &[Target],
    options: &Options,
) -> Result<Fitted<D, N>, SynthesisError>
where
    D: Design<f64, N, P, M> + Kinematics<f64, N> + Copy + Send + Sync,
{
    let unknowns = free.iter().filter(|f| **f).count();
    let rows: usize = targets.iter().map(Target::rows).sum();
    if unknowns == 0 || rows < unknowns {
        return Err(SynthesisError::BadTargets(
            "a fit needs a free parameter, and at least as many residuals as free parameters",
        ));
    }
    let valid = targets.iter().all(|target| match *target {
        Target::Unknown {
            input,
            unknown,
            value,
        } => input.is_finite() && value.is_finite() && unknown < N,
        Target::Point { input, point, at } => {
            input.is_finite() && at.x.is_finite() && at.y.is_finite() && point < M
        }
    });
    if !valid || !guess.iter().all(|v| v.is_finite()) {
        return Err(SynthesisError::BadTargets(
            "every target needs a finite input and value and an unknown or point the \
             mechanism has, and the guess must be finite",
        ));
    }
    let Some(positions) = solved_along(start, targets, guess) else {
        return Err(SynthesisError::BadTargets(
            "the start does not reach every target from the guess on one assembly",
        ));
    };
    let dimensions = start.parameters();
    let first: Vec<f64> = (0..P)
        .filter(|&j| free[j])
        .map(|j| to_fitted(D::PARAMETER_LENGTHS[j], dimensions[j]))
        .collect();
    let starts = starts(options, vec![first.clone()], |random| {
        perturbed(&first, random)
    });
    let solve = |x: Vec<f64>| {
        let mut problem: Problem<'_, D, N, P, M> = Problem {
            start: *start,
            free,
            targets,
            positions: positions.clone(),
            solved: None,
            x: DVector::from_vec(x),
        };
        problem.solve();
        let (solved, finished) = minimise(problem);
        finished.then_some(())?;
        let (mechanism, positions) = solved.solved.clone()?;
        let errors = solved.errors()?;
        // The lengths fitted, and those held that are not zero (a coupler point on its
        // link's pin, say): the ratio guards against a fitted length running off.
        let lengths: Vec<f64> = mechanism
            .parameters()
            .iter()
            .zip(D::PARAMETER_LENGTHS)
            .zip(free)
            .filter(|((l, length), free)| *length && (*free || **l != 0.0))
            .map(|((l, _), _)| l.abs())
            .collect();
        (lengths.is_empty() || within_ratio(&lengths, options.max_ratio))
            .then_some(((mechanism, positions), errors))
    };
    let solved = solved_from_first(starts, solve, options);
    let converged = solved.len();
    solved
        .into_iter()
        .map(|((mechanism, positions), errors)| Fitted {
            mechanism,
            positions,
            rms_error: rms(&errors),
            largest_error: errors.iter().fold(0.0f64, |m, e| m.max(e.abs())),
            converged,
        })
        .min_by(|a, b| a.rms_error.total_cmp(&b.rms_error))
        .ok_or(SynthesisError::NothingFeasible { converged })
}

/// A random start near `first`: each value moved by up to ±0.4, uniformly (a length, by its
/// logarithm, times a factor within e^±0.4).
fn perturbed(first: &[f64], random: &mut SplitMix64) -> Vec<f64> {
    first.iter().map(|&x| perturbed_value(x, random)).collect()
}

/// A parameter as the fit moves it: a length by its logarithm, an angle as it is.
fn to_fitted(length: bool, value: f64) -> f64 {
    if length { value.ln() } else { value }
}

/// Each target's position, by Newton from `guess` for the first and from the one before for
/// the rest; `None` if one fails.
fn solved_along<D: Kinematics<f64, N>, const N: usize>(
    mechanism: &D,
    targets: &[Target],
    guess: [f64; N],
) -> Option<Vec<[f64; N]>> {
    let mut positions: Vec<[f64; N]> = Vec::with_capacity(targets.len());
    for target in targets {
        let guess = positions.last().copied().unwrap_or(guess);
        let solved = mechanism
            .solve_near(target.input(), guess, &NewtonOptions::default())
            .ok()?;
        positions.push(solved.value);
    }
    Some(positions)
}

/// The least squares of [`fit`]: `x` the free parameters (lengths by their logarithms), the
/// residuals each target's miss; the positions solved where `x` was last set, each from its
/// position at the last solved `x`.
struct Problem<'a, D, const N: usize, const P: usize, const M: usize> {
    start: D,
    free: [bool; P],
    targets: &'a [Target],
    /// The positions the next solve starts from: the last solved ones.
    positions: Vec<[f64; N]>,
    /// The mechanism at `x` and its positions, where every target was reached.
    solved: Option<(D, Vec<[f64; N]>)>,
    x: DVector<f64>,
}

impl<D, const N: usize, const P: usize, const M: usize> Problem<'_, D, N, P, M>
where
    D: Design<f64, N, P, M> + Kinematics<f64, N> + Copy,
{
    /// The mechanism at `x`.
    fn mechanism(&self) -> D {
        let mut values = self.start.parameters();
        // One x per free parameter, in declaration order.
        let free = values
            .iter_mut()
            .zip(D::PARAMETER_LENGTHS)
            .zip(self.free)
            .filter(|(_, free)| *free);
        for (((value, length), _), &x) in free.zip(self.x.iter()) {
            *value = if length { x.exp() } else { x };
        }
        D::with_parameters(values)
    }

    /// Solves every target at `x`, each from its last position: Newton keeps the assembly
    /// (it says `OtherBranch` where it would change).
    fn solve(&mut self) {
        let mechanism = self.mechanism();
        let mut positions = Vec::with_capacity(self.targets.len());
        for (target, guess) in self.targets.iter().zip(&self.positions) {
            match mechanism.solve_near(target.input(), *guess, &NewtonOptions::default()) {
                Ok(solved) => positions.push(solved.value),
                Err(_) => {
                    self.solved = None;
                    return;
                }
            }
        }
        self.positions.clone_from(&positions);
        self.solved = Some((mechanism, positions));
    }
}

impl<D, const N: usize, const P: usize, const M: usize> Residuals for Problem<'_, D, N, P, M>
where
    D: Design<f64, N, P, M> + Kinematics<f64, N> + Copy,
{
    fn x(&self) -> &DVector<f64> {
        &self.x
    }

    fn x_mut(&mut self) -> &mut DVector<f64> {
        &mut self.x
    }

    fn moved(&mut self) {
        self.solve();
    }

    fn count(&self) -> usize {
        self.targets.iter().map(Target::rows).sum()
    }

    fn errors(&self) -> Option<Vec<f64>> {
        let (mechanism, positions) = self.solved.as_ref()?;
        let mut errors = Vec::with_capacity(self.count());
        for (target, position) in self.targets.iter().zip(positions) {
            match *target {
                Target::Unknown { unknown, value, .. } => {
                    let miss = position[unknown] - value;
                    errors.push(if D::UNKNOWN_ANGLES[unknown] {
                        wrapped(miss)
                    } else {
                        miss
                    });
                }
                Target::Point {
                    input, point, at, ..
                } => {
                    let p = mechanism.point_positions(input, *position).ok()?[point];
                    errors.extend([p.x - at.x, p.y - at.y]);
                }
            }
        }
        Some(errors)
    }

    fn derivatives(&self) -> Option<DMatrix<f64>> {
        let (mechanism, positions) = self.solved.as_ref()?;
        let values = mechanism.parameters();
        let columns: Vec<usize> = (0..P).filter(|&j| self.free[j]).collect();
        // A length moves by its logarithm: d/d(ln p) = p·d/dp.
        let chain = |j: usize| {
            if D::PARAMETER_LENGTHS[j] {
                values[j]
            } else {
                1.0
            }
        };
        let mut jacobian = DMatrix::zeros(self.count(), columns.len());
        let mut row = 0;
        for (target, position) in self.targets.iter().zip(positions) {
            match *target {
                Target::Unknown { input, unknown, .. } => {
                    let by = mechanism.unknown_sensitivities(input, *position).ok()?;
                    for (c, &j) in columns.iter().enumerate() {
                        jacobian[(row, c)] = by[j][unknown] * chain(j);
                    }
                }
                Target::Point { input, point, .. } => {
                    let by = mechanism.point_sensitivities(input, *position).ok()?;
                    for (c, &j) in columns.iter().enumerate() {
                        jacobian[(row, c)] = by[j][point].x * chain(j);
                        jacobian[(row + 1, c)] = by[j][point].y * chain(j);
                    }
                }
            }
            row += target.rows();
        }
        Some(jacobian)
    }
}

/// One value of a random start ([`perturbed`]'s, and the Watt six-bar's): `x` moved by up to
/// ±0.4, uniformly.
pub(super) fn perturbed_value(x: f64, random: &mut SplitMix64) -> f64 {
    x + 0.8 * (random.fraction() - 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FourBar;
    use mechgen::Branch;

    /// The seeds' Example 1 with a coupler point 60 from A at 25°.
    fn example() -> FourBar<f64> {
        FourBar::new(180.0, 80.0, 200.0, 150.0)
            .and_then(|l| l.with_coupler_point(60.0, 25f64.to_radians()))
            .unwrap()
    }

    /// Crank, coupler and rocker free; the ground and the coupler point held.
    const LINKS: [bool; 6] = [false, true, true, true, false, false];

    fn quick() -> Options {
        Options {
            restarts: 4,
            ..Options::default()
        }
    }

    fn rocker_at(input: f64) -> Target {
        let value = example().assemble(input, Branch::Open).unwrap().theta4;
        Target::Unknown {
            input,
            unknown: 1,
            value,
        }
    }

    fn point_at(input: f64) -> Target {
        let linkage = example();
        let q = linkage.assemble(input, Branch::Open).unwrap();
        let at = linkage.points(input, &q).unwrap().coupler_point;
        Target::Point {
            input,
            point: 2,
            at,
        }
    }

    /// 10% off the example in its three links.
    fn start() -> (FourBar<f64>, [f64; 2]) {
        let start = FourBar::new(180.0, 88.0, 180.0, 165.0)
            .and_then(|l| l.with_coupler_point(60.0, 25f64.to_radians()))
            .unwrap();
        let guess = start.assemble(0.0, Branch::Open).unwrap().to_array();
        (start, guess)
    }

    fn refused(result: Result<Fitted<FourBar<f64>, 2>, SynthesisError>) -> &'static str {
        match result {
            Err(SynthesisError::BadTargets(why)) => why,
            other => panic!("not refused: {other:?}"),
        }
    }

    #[test]
    fn a_random_start_moves_each_value_by_up_to_four_tenths_either_way() {
        let first = [1.0, -2.0];
        let (mut low, mut high, mut sum, mut count) = (f64::MAX, f64::MIN, 0.0, 0.0);
        for seed in 0..2000u64 {
            let moved = perturbed(&first, &mut SplitMix64(seed));
            assert_eq!(moved.len(), 2);
            for (x, start) in moved.iter().zip(first) {
                let by = x - start;
                assert!(by.abs() <= 0.4, "{by}");
                (low, high) = (low.min(by), high.max(by));
                sum += by;
                count += 1.0;
            }
        }
        // Uniform over (−0.4, 0.4): both ends reached, centred on the start.
        assert!(low < -0.39 && high > 0.39, "{low} {high}");
        assert!((sum / count).abs() < 0.02, "{}", sum / count);
    }

    #[test]
    fn fit_says_what_is_wrong_with_its_targets() {
        let (start, guess) = start();
        let target = rocker_at(0.0);
        let counts = "a fit needs a free parameter, and at least as many residuals as free \
                      parameters";
        let values = "every target needs a finite input and value and an unknown or point the \
                      mechanism has, and the guess must be finite";
        let fit = |free: [bool; 6], targets: &[Target], guess: [f64; 2]| {
            fit(&start, guess, free, targets, &quick())
        };
        // No parameter free, with residuals to spare; fewer residuals than free parameters.
        assert_eq!(refused(fit([false; 6], &[target; 3], guess)), counts);
        assert_eq!(refused(fit([true; 6], &[target; 3], guess)), counts);
        // Each part of a target wrong alone: its input, its value, an unknown or a point the
        // four-bar (two unknowns, three points: the pins, then the coupler point) does not
        // have.
        let point = point_at(0.0);
        let nan = f64::NAN;
        let mut bad = Vec::new();
        for (input, value, unknown) in [(nan, 1.0, 1), (0.0, nan, 1), (0.0, 1.0, 2)] {
            bad.push(Target::Unknown {
                input,
                unknown,
                value,
            });
        }
        let Target::Point { at, .. } = point else {
            unreachable!()
        };
        for (input, x, y, index) in [
            (nan, at.x, at.y, 2),
            (0.0, nan, at.y, 2),
            (0.0, at.x, nan, 2),
            (0.0, at.x, at.y, 3),
        ] {
            bad.push(Target::Point {
                input,
                point: index,
                at: Vec2 { x, y },
            });
        }
        for bad in bad {
            assert_eq!(refused(fit(LINKS, &[bad; 3], guess)), values, "{bad:?}");
        }
        // Good targets from a guess that is not finite.
        assert_eq!(refused(fit(LINKS, &[target; 3], [nan, 0.0])), values);
        // A start that cannot reach a target: a triple rocker (not Grashof), whose crank
        // cannot get to π, where the crank pin would be 160 from O4 and the dyad reaches 130.
        let stuck = FourBar::new(100.0, 60.0, 50.0, 80.0).unwrap();
        let guess = stuck.assemble(0.0, Branch::Open).unwrap().to_array();
        let beyond = Target::Unknown {
            input: core::f64::consts::PI,
            unknown: 1,
            value: 1.0,
        };
        let unreachable = super::fit(&stuck, guess, LINKS, &[target, target, beyond], &quick());
        assert_eq!(
            refused(unreachable),
            "the start does not reach every target from the guess on one assembly"
        );
    }

    #[test]
    fn as_many_residuals_as_free_parameters_are_enough() {
        // Three rocker angles for three links: the example's, or another linkage through
        // the same three.
        let (start, guess) = start();
        let targets = [rocker_at(0.0), rocker_at(0.6), rocker_at(1.2)];
        let found = fit(&start, guess, LINKS, &targets, &quick()).unwrap();
        assert!(found.rms_error < 1e-10, "{}", found.rms_error);
        for (target, position) in targets.iter().zip(&found.positions) {
            let &Target::Unknown { input, value, .. } = target else {
                unreachable!()
            };
            let solved = found.mechanism.assemble(input, Branch::Open).unwrap();
            assert!((solved.theta4 - value).abs() < 1e-9);
            assert!((position[1] - value).abs() < 1e-9);
        }
    }

    /// Every coupler point of `found` where its target wants it, measured by the linkage's
    /// own point positions.
    fn meets(found: &Fitted<FourBar<f64>, 2>, targets: &[Target]) {
        assert_eq!(found.positions.len(), targets.len());
        for (target, position) in targets.iter().zip(&found.positions) {
            let &Target::Point { input, at, .. } = target else {
                unreachable!()
            };
            let q = found.mechanism.assemble(input, Branch::Open).unwrap();
            assert!((q.theta3 - position[0]).abs() < 1e-9);
            let p = found.mechanism.points(input, &q).unwrap().coupler_point;
            assert!((p.x - at.x).hypot(p.y - at.y) < 1e-8, "{p:?} {at:?}");
        }
    }

    #[test]
    fn a_point_is_two_residuals() {
        // One coupler point, two coordinates, for two free links (the crank and the
        // coupler): as many residuals as unknowns.
        let (start, guess) = start();
        let targets = [point_at(0.3)];
        let free = [false, true, true, false, false, false];
        let guess = start
            .solve_near(0.3, guess, &NewtonOptions::default())
            .unwrap()
            .value;
        let found = fit(&start, guess, free, &targets, &quick()).unwrap();
        assert!(found.rms_error < 1e-10, "{}", found.rms_error);
        meets(&found, &targets);
    }

    #[test]
    fn points_on_the_path_give_back_the_links() {
        // Four coupler points, eight residuals, three links: only the example meets them all.
        let (start, guess) = start();
        let targets = [point_at(0.0), point_at(0.5), point_at(1.0), point_at(1.5)];
        let found = fit(&start, guess, LINKS, &targets, &quick()).unwrap();
        assert!(found.rms_error < 1e-10 && found.largest_error < 1e-9);
        meets(&found, &targets);
        let [ground, crank, coupler, rocker, ..] = found.mechanism.parameters();
        assert_eq!(ground, 180.0);
        for (got, want) in [(crank, 80.0), (coupler, 200.0), (rocker, 150.0)] {
            assert!((got - want).abs() < 1e-7, "{got} {want}");
        }
    }

    #[test]
    fn the_derivatives_are_those_of_the_errors_in_the_fitted_variables() {
        // Both kinds of target, every parameter but the ground free (four lengths through
        // their logarithms, one angle as it is): each column against central differences
        // of the errors.
        let (start, guess) = start();
        let targets = [point_at(0.2), rocker_at(0.7), point_at(1.1)];
        let free = [false, true, true, true, true, true];
        let positions = solved_along(&start, &targets, guess).unwrap();
        let x: Vec<f64> = (1..6)
            .map(|j| to_fitted(FourBar::<f64>::PARAMETER_LENGTHS[j], start.parameters()[j]))
            .collect();
        let at = |x: &[f64]| {
            let mut problem: Problem<'_, FourBar<f64>, 2, 6, 3> = Problem {
                start,
                free,
                targets: &targets,
                positions: positions.clone(),
                solved: None,
                x: DVector::from_vec(x.to_vec()),
            };
            problem.solve();
            problem
        };
        let problem = at(&x);
        assert_eq!(problem.count(), 5);
        let jacobian = problem.derivatives().unwrap();
        assert_eq!(jacobian.shape(), (5, 5));
        let h = 1e-6;
        for c in 0..5 {
            let (mut up, mut down) = (x.clone(), x.clone());
            up[c] += h;
            down[c] -= h;
            let (e_up, e_down) = (at(&up).errors().unwrap(), at(&down).errors().unwrap());
            for r in 0..5 {
                let difference = (e_up[r] - e_down[r]) / (2.0 * h);
                let scale = 1.0 + jacobian[(r, c)].abs();
                assert!(
                    (difference - jacobian[(r, c)]).abs() < 1e-6 * scale,
                    "row {r}, column {c}: {difference} against {}",
                    jacobian[(r, c)]
                );
            }
        }
    }

    #[test]
    fn a_held_length_counts_in_the_ratio_a_zero_one_does_not() {
        // The links fitted are within 2.5 of each other, but the held coupler point is 12.5
        // times the crank: a ratio of 5 refuses every fit, unless the point is on its pin.
        let targets = [
            rocker_at(0.0),
            rocker_at(0.6),
            rocker_at(1.2),
            rocker_at(1.8),
        ];
        let options = Options {
            max_ratio: 5.0,
            ..quick()
        };
        let far = FourBar::new(180.0, 88.0, 180.0, 165.0)
            .and_then(|l| l.with_coupler_point(1000.0, 0.0))
            .unwrap();
        let guess = far.assemble(0.0, Branch::Open).unwrap().to_array();
        let result = fit(&far, guess, LINKS, &targets, &options);
        assert!(
            matches!(
                result,
                Err(SynthesisError::NothingFeasible { converged: 0 })
            ),
            "{result:?}"
        );
        let on_pin = FourBar::new(180.0, 88.0, 180.0, 165.0)
            .and_then(|l| l.with_coupler_point(0.0, 0.0))
            .unwrap();
        let found = fit(&on_pin, guess, LINKS, &targets, &options).unwrap();
        assert!(found.rms_error < 1e-10);
        assert!(found.converged > 0);
    }
}
