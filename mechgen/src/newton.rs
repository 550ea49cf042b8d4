//! Newton-Raphson on the loop-closure equations.
//!
//! The iteration lives here, once, generic over the generated residual: generated code stays
//! short (it only evaluates the residual and Jacobian) and every mechanism gets the same
//! stopping rules.

use core::cmp::Ordering;

use crate::linear::{Columns, Factored};
use crate::{Accuracy, Error, Real};

/// What a generated `{Name}Newton` computes once from the dimensions, for its
/// `motion_near`: the mechanism's size and aspect, which the accuracy of every solution is
/// stated against, and whether the mechanism is solved as it is given (its size well inside
/// the float's range). Computed by the same expressions as the general `motion_near` computes
/// on each call, so the two give the same bits.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonConstants<T> {
    /// The sum of the lengths the loops declare.
    pub size: T,
    /// The loops' scale ([`Linearisation::scale`]), where the declaration gives every
    /// magnitude over the parameters (else unused).
    pub scale: T,
    /// The size over the shortest column of an angle unknown, where the dimensions fix the
    /// columns (else unused), with what the rates' estimates read of it.
    pub aspect: crate::accuracy::KnownAspect<T>,
    /// The Jacobian's column norms, where the dimensions fix them (else unused).
    pub columns: crate::linear::KnownColumns<T>,
    /// Whether the dimensions are solved as given (`kernel::as_given`).
    pub as_given: bool,
}

/// How hard Newton-Raphson tries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOptions<T> {
    /// Stop when every component of the loop residual is at most this, in the mechanism's
    /// length units (the seeds' worked examples use `1e-4` mm); a tolerance below the
    /// rounding floor of the residual (`16 ε Σ|r|` over each loop's own vectors, for that
    /// loop's components) is raised to that floor, so a tight tolerance never turns into a spurious failure. Zero, the default,
    /// means "as accurate as the floating-point type allows": Newton stops at the floor only
    /// after a step that started within `√ε/κ` of the root (relative), so a step that lands
    /// on the floor from farther is followed by one more, and a solve restarted from its own
    /// result polishes it rather than returning it untouched.
    pub tolerance: T,
    /// The most Newton updates to make before giving up with [`Error::NoConvergence`].
    pub max_iterations: u32,
    /// The accuracy the rates of `motion_near` must have, else [`Error::Inaccurate`]:
    /// [`Accuracy::required`] by default; loosen it to get rates nearer a toggle, with fewer
    /// correct digits, or tighten it.
    pub accuracy: Accuracy<T>,
}

impl<T: Real> NewtonOptions<T> {
    /// Options with the given residual tolerance and iteration cap.
    pub fn new(tolerance: T, max_iterations: u32) -> Self {
        NewtonOptions {
            tolerance,
            max_iterations,
            accuracy: Accuracy::required(),
        }
    }

    /// These options, with the rates of `motion_near` required to be within `accuracy`.
    ///
    /// ```
    /// use mechgen::{Accuracy, NewtonOptions};
    /// let loose = NewtonOptions::<f64>::default().with_accuracy(Accuracy {
    ///     position: 1e-6,
    ///     velocity: 1e-3,
    ///     acceleration: 1e-2,
    /// });
    /// assert_eq!(loose.accuracy.velocity, 1e-3);
    /// ```
    pub fn with_accuracy(self, accuracy: Accuracy<T>) -> Self {
        NewtonOptions { accuracy, ..self }
    }
}

impl<T: Real> Default for NewtonOptions<T> {
    /// Converge to the rounding floor in at most 50 updates.
    fn default() -> Self {
        NewtonOptions::new(T::zero(), 50)
    }
}

/// A converged solution with what it cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solved<S, T> {
    /// The solution.
    pub value: S,
    /// Newton updates made (0 if the guess already met the tolerance).
    pub iterations: u32,
    /// Largest absolute loop residual at the solution, in length units.
    pub residual_norm: T,
    /// The Jacobian's condition estimate at the solution, `κ = Π‖column‖ / |det|` (see
    /// [`crate::condition`]), from 1 up to `1/√ε` near a toggle. Errors in the position grow
    /// with it; see the accuracy contract.
    pub condition: T,
}

impl<S, T> Solved<S, T> {
    /// Converts the solution, keeping the iteration count and residual.
    pub fn map<R>(self, f: impl FnOnce(S) -> R) -> Solved<R, T> {
        Solved {
            value: f(self.value),
            iterations: self.iterations,
            residual_norm: self.residual_norm,
            condition: self.condition,
        }
    }
}

/// One evaluation of the loop equations at an iterate.
#[derive(Clone, Copy, Debug)]
pub struct Linearisation<T, const N: usize, P = ()> {
    /// The loop residual `f(x)`.
    pub residual: [T; N],
    /// The Jacobian `∂f/∂x`, row-major.
    pub jacobian: [[T; N]; N],
    /// `Σ|r|` over the loops' vector magnitudes: the size of the numbers whose rounding
    /// bounds how small the residual can get.
    pub scale: T,
    /// Each residual component's weight: `scale` over its own loop's `Σ|r|` (1 for one
    /// loop). Every test of the residual reads it weighted, so that each loop is closed to its
    /// own rounding: a small loop beside a large one would otherwise pass at the large one's,
    /// which can exceed the small one's size.
    pub weights: [T; N],
    /// What else the generated code computed at the iterate (sines, cosines, products) and
    /// wants back at the solution, so the rates after Newton need not compute them again.
    pub payload: P,
    /// The Jacobian's column norms where the dimensions fix them (a one-loop mechanism whose
    /// unknowns are angles, each turning one vector of fixed length), for its factoring;
    /// else computed from it.
    pub columns: Columns<T>,
}

/// Newton's solution, with the evaluation and the factored Jacobian it converged on: what
/// the rates at the solution need, so they cost no new evaluation or factorisation.
#[derive(Clone, Copy, Debug)]
pub struct Converged<T, const N: usize, P> {
    /// The solution and what it cost.
    pub solved: Solved<[T; N], T>,
    /// The loops evaluated at the solution.
    pub at: Linearisation<T, N, P>,
    /// The Jacobian at the solution, factored.
    pub jacobian: Factored<T, N>,
}

impl<T: Real, const N: usize, P> Converged<T, N, P> {
    /// The position's estimated error, relative to `size` (the sum of the lengths the loops
    /// declare) as [`Accuracy::estimate`](crate::Accuracy::estimate)'s position:
    /// `2·κ·max(16·ε, r/Σ|r|)` for the weighted residual `r` it stopped at, times the largest
    /// loop's magnitudes over `size` where that exceeds 1. The inverse of the column-scaled
    /// Jacobian has entries up to κ and the errors of two unknowns can add, so a residual `r`
    /// leaves the position up to `2·κ·r` off; on the floor (`16·ε·Σ|r|`, which also covers
    /// the rounding of evaluating the residual) that is the contract's `32·ε·κ`, and above it
    /// (a tolerance looser than the floor) the residual itself. Each loop closes to its own
    /// magnitudes' rounding, and a loop's magnitudes can exceed the declared lengths (a
    /// slide's extension counts): relative to `size`, the error is that much larger (edge run
    /// case 914340, a slider-crank whose slide is as long as its crank, 66,000 times its rod:
    /// its rates were 1.2 times further off than stated, which read this error against
    /// `size`).
    pub fn position_accuracy(&self, size: T) -> T {
        self.position_accuracy_at(self.solved.condition, size)
    }

    /// [`Converged::position_accuracy`] with the condition `condition` instead of the
    /// iteration's: the full Jacobian's, where Newton iterates on fewer unknowns than the
    /// position has (the rest in closed form, to rounding, inside each evaluation).
    pub fn position_accuracy_at(&self, condition: T, size: T) -> T {
        self.stretched(self.error_within(condition, T::one()), size)
    }

    /// [`Converged::position_accuracy_at`] where no loop's magnitudes can sum to more than
    /// the size (every magnitude one of the declared lengths, none twice in a loop, as the
    /// generated code knows from the declaration): no stretch to compute.
    pub fn position_accuracy_within_size_at(&self, condition: T) -> T {
        self.error_within(condition, T::one())
    }

    /// The position's error as a length, for telling a loop's two assemblies apart at it
    /// (`mechgen::closed::*_side`): the contract's `32·ε·κ` of `size` (stretched as
    /// [`Converged::position_accuracy`] is) for any residual a default solve accepts, up to
    /// the four floors where no step lowers it, and the residual's own estimate where a stated
    /// tolerance stopped above those. Not [`Converged::position_accuracy`]'s floor alone: a
    /// solution 2.6 floors up, whose estimate grew to 2.6 times `32·ε·κ`, read the other
    /// assembly of a loop 1.5 times `32·ε·κ` away as within its error (edge run seed 15, case
    /// 502593, an f32 Watt six-bar whose asked assembly does not close), where the contract
    /// holds a default solve's position to `32·ε·κ` and so to one assembly.
    pub fn error_length(&self, size: T) -> T {
        let error = self.error_within(self.solved.condition, T::constant(STAGNATION_FLOOR));
        self.stretched(error, size) * size
    }

    /// The position's error relative to the largest loop's magnitudes, with a residual up to
    /// `floors` times the rounding floor counted as on it.
    fn error_within(&self, condition: T, floors: T) -> T {
        let kappa = condition.max(T::one());
        let floor = T::constant(16.0) * T::epsilon();
        // On the floor, as a default solve stops: no norm and no division.
        let on_floor_of = floors * floor * self.at.scale;
        let on_floor = self
            .at
            .residual
            .iter()
            .zip(&self.at.weights)
            .fold(true, |on, (r, w)| on & (r.abs() * *w <= on_floor_of));
        let relative = if on_floor {
            floor
        } else {
            // Above it, or not a number (an undefined size): the residual itself.
            weighted_norm(&self.at.residual, &self.at.weights) / self.at.scale
        };
        T::constant(2.0) * kappa * relative
    }

    /// `error`, relative to the largest loop's magnitudes, relative to `size` instead where
    /// that loop is the longer.
    fn stretched(&self, error: T, size: T) -> T {
        // The largest loop's magnitudes: the scale over the least weight (each loop's weight
        // is the scale over its own; 1 for one loop, where this is the scale itself).
        let least_weight = self
            .at
            .weights
            .iter()
            .fold(T::infinity(), |least, w| least.min(*w));
        // At least 1, without a branch (`max` passes over a NaN stretch, which comes only with
        // a scale that is not a number, and leaves `error` NaN already).
        let stretch = (self.at.scale / least_weight / size).max(T::one());
        error * stretch
    }
}

/// How far above the rounding floor `16 ε Σ|r|` a residual that no step lowers still counts as
/// converged: the floor is an estimate, and a coupled evaluation (closed forms inside the
/// iteration) rounds at intermediate magnitudes somewhat above its vectors'.
const STAGNATION_FLOOR: f64 = 4.0;

/// How many times a Newton step is halved, at most, looking for a smaller residual.
const MAX_HALVINGS: u32 = 10;

/// The fewest iterations after which running out of them, with no root certain to be near,
/// says the iterates are creeping along a toggle (Newton from within Kantorovich's ball
/// reaches the floor in far fewer): below it, a cap the caller set low says nothing of the
/// loops, and the answer is [`Error::NoConvergence`].
const CREEPING: u32 = 16;

/// Solves `f(x) = 0` by a safeguarded Newton-Raphson from `guess`.
///
/// `linearise` evaluates the residual and Jacobian; each Jacobian is factored once
/// ([`Factored`]: the explicit inverse of a 2×2, LU with partial pivoting otherwise), for
/// the step and, at the solution, for the rates. Every test reads the residual weighted
/// ([`Linearisation::weights`]), so each loop's components are held to the rounding floor
/// `16 ε Σ|r|` of that loop's own vectors. The safeguards:
/// - a step that does not reduce the largest residual component is halved, up to
///   10 times; if none does, the iteration has stagnated;
/// - with the default zero tolerance, a point is accepted when its residual is at the
///   rounding floor `16 ε Σ|r|` and the step to it started within `√ε·Σ|r|/κ` (so, Newton
///   being quadratic, the loops' curvature leaves less than the floor: `polished`), or the
///   Jacobian is near singular
///   (κ ≥ ε^(-1/4), where a step from the floor would move along the singular direction
///   rather than polish), or no step lowers it;
/// - with a stated tolerance, a point is accepted when its residual is at most the tolerance
///   (raised to the rounding floor) and, unless it is at that floor, a root is certain to lie
///   near it
///   (Kantorovich's `‖J⁻¹‖²·L·‖f‖ ≤ 1/4`, estimated from the condition `κ` and the
///   Jacobian's columns), so a loose tolerance cannot accept a point past a toggle where the
///   loops do not close;
/// - stagnation is [`Error::CannotAssemble`] at `input` where `assembles()` says the loops
///   cannot close there (a closed form knows), [`Error::NoConvergence`] where it says they
///   can; where it cannot say (`None`), [`Error::CannotAssemble`] if the Jacobian is
///   ill-conditioned (the iterates press against a toggle the loops cannot pass), else
///   [`Error::NoConvergence`]. Running out of iterations is decided the same way (a guess
///   that Kantorovich certifies reaches the floor in a handful of steps, so iterates still
///   outside every such ball after `max_iterations`, if that is at least 16, are pressing
///   against a toggle as surely as stalled ones). `assembles()` is called only then;
/// - where the closed forms cannot say, iterates that have turned an angle through more
///   than a whole turn from the guess have run away from it (from a guess Kantorovich
///   certifies they stay within twice its ball's radius, below 1 rad), as they do past a
///   toggle: stagnation or the cap is then [`Error::CannotAssemble`].
///
/// Angles of the guess (the unknowns `keep_orientation` marks) beyond ±16 rad are first taken
/// by whole turns to within `[−π, π]`: a float that large holds an angle only to its spacing,
/// coarser than the rounding floor the tests read (a guess counting a thousand turns stalled
/// above it, or stopped at an angle less accurate than stated). So is an angle of an iterate
/// that would be accepted beyond ±17 rad (`RETURNED_TURNS_BEYOND`), which the iteration
/// then goes on from: every angle returned is within ±17 rad.
///
/// With `keep_orientation`, the Jacobian's orientation (the sign of its determinant) must be
/// the same at the solution as at the guess, else [`Error::OtherBranch`]: for a single loop
/// that sign is what tells its two assemblies apart, so Newton never switches branch silently.
/// Unless the assemblies cannot be told apart: where a whole turn of an unknown angle moves
/// the loops by no more than their rounding floor (a link shorter than rounding of the
/// mechanism's size), that angle is undetermined and the two assemblies are the same position
/// to rounding, so the solution is returned ([`Orientation`]).
#[inline]
pub fn newton<T: Real, const N: usize, P: Copy>(
    input: T,
    guess: [T; N],
    options: &NewtonOptions<T>,
    keep_orientation: impl Into<Orientation<N>>,
    assembles: impl FnOnce() -> Option<bool>,
    mut linearise: impl FnMut(&[T; N]) -> Linearisation<T, N, P>,
) -> Result<Converged<T, N, P>, Error<T>> {
    if !options.tolerance.is_finite() || options.tolerance < T::zero() {
        return Err(Error::NonFinite {
            quantity: "Newton tolerance",
        });
    }
    if !all_finite(&guess) {
        return Err(Error::NonFinite {
            quantity: "initial guess",
        });
    }
    let kept: Orientation<N> = keep_orientation.into();
    let angles = kept.angles();
    let rounding_floor = T::constant(16.0) * T::epsilon();
    let quarter = T::constant(0.25);
    let start = within_a_turn(guess, angles);
    let mut x = start;
    let mut here = linearise(&x);
    // The residual as the tests read it: each loop's against its own rounding. Finite only
    // if every component is (the weights are positive), and zero only if each is. Carried
    // from the step's test to the next iteration, which reads the same evaluation.
    let mut weighted = weighted_norm(&here.residual, &here.weights);
    let mut iterations = 0;
    let mut orientation = None;
    // The residual before the last step. Newton squares the relative error at each step, so
    // a residual at the floor is the attainable one only if the step to it started within
    // √ε/κ of the root; otherwise (a big step that landed near the floor, or no step at all,
    // as for a guess that is already a solution) a default solve takes one more step, which
    // polishes the result rather than stopping short of what the float type allows.
    let mut previous_residual = T::infinity();
    'iterate: loop {
        if !weighted.is_finite() || !here.scale.is_finite() {
            return Err(Error::NonFinite {
                quantity: "loop residual",
            });
        }
        let jacobian = Factored::new_with(here.jacobian, here.columns)?;
        let relative_determinant = jacobian.relative();
        let positive = relative_determinant > T::zero();
        let started_positive = *orientation.get_or_insert(positive);
        // κ, wanted only at the end and by the convergence test: no division per iteration.
        let condition = || T::one() / relative_determinant.abs();
        let floor = rounding_floor * here.scale;
        let accept = |here: Linearisation<T, N, P>, jacobian: Factored<T, N>, x: [T; N]| {
            if positive != started_positive && kept.tells_apart(&here, floor) {
                return Err(Error::OtherBranch);
            }
            Ok(Converged {
                solved: Solved {
                    value: x,
                    iterations,
                    residual_norm: max_abs(&here.residual),
                    condition: T::one() / relative_determinant.abs(),
                },
                at: here,
                jacobian,
            })
        };
        // An iterate that would be accepted with an angle many turns out (a step through a
        // nearly vanishing column can throw one by hundreds of radians) holds that angle only
        // to its float's spacing, coarser than the accuracy stated: taken by whole turns to
        // within `[−π, π]` and solved on from there, which a step or two polishes. (Newton's
        // common path never gets so far: its iterates stay within 2⁻¹⁰ of a guess within
        // ±16 rad.)
        macro_rules! within_turns_or_accept {
            ($here:expr, $jacobian:expr, $x:expr) => {{
                if beyond_turns(&$x, angles) {
                    (x, here, weighted) = taken_by_turns(&$x, angles, &mut linearise);
                    previous_residual = T::infinity();
                    continue 'iterate;
                }
                return accept($here, $jacobian, $x);
            }};
        }
        // A stated tolerance is met when the residual is within it (and, above the rounding
        // floor, a root is certain to be near); the default one when the residual is at the
        // floor and the steps have stopped shrinking it (or it is zero).
        let met = if options.tolerance > T::zero() {
            weighted <= floor
                || (max_abs(&here.residual) <= options.tolerance
                    && kantorovich(&here, condition()) <= quarter)
        } else {
            // At the floor after a step that started near enough (or near a singular
            // position, where a step from the floor moves along the singular direction).
            weighted == T::zero()
                || (weighted <= floor && polished(previous_residual, here.scale, condition()))
        };
        if met {
            within_turns_or_accept!(here, jacobian, x);
        }
        if iterations >= options.max_iterations {
            if weighted <= floor {
                within_turns_or_accept!(here, jacobian, x);
            }
            // Where a closed form says no assembly closes at this input, that is why. Where
            // the closed forms cannot say for the guess's assembly (some other assembly
            // closes), it is decided as stagnation is: iterates that no root is certain to be
            // near after this many steps (Newton from within Kantorovich's ball reaches the
            // floor in a handful) are creeping along a toggle the loops cannot pass.
            let stalled = Error::NoConvergence {
                iterations,
                residual_norm: max_abs(&here.residual),
            };
            return Err(match assembles() {
                Some(true) => stalled,
                Some(false) => Error::CannotAssemble { input },
                None if ran_away(&x, &start, &angles)
                    || (iterations >= CREEPING && kantorovich(&here, condition()) > quarter) =>
                {
                    Error::CannotAssemble { input }
                }
                None => stalled,
            });
        }
        let step = jacobian.solve(here.residual);
        if !all_finite(&step) {
            // From a finite residual and a Jacobian that factors, a step that overflows is
            // the iterates running away; where a closed form says the loops cannot close at
            // this input, that is why.
            return Err(match assembles() {
                Some(false) => Error::CannotAssemble { input },
                _ => Error::NonFinite {
                    quantity: "Newton step",
                },
            });
        }
        // The full step, which the common path takes; else the largest of 1/2, 1/4, ...
        // times it that lowers the residual.
        let stepped = |fraction: T| {
            let mut trial = x;
            for (t, d) in trial.iter_mut().zip(step) {
                *t = *t - fraction * d;
            }
            trial
        };
        let mut next = stepped(T::one());
        let mut there = linearise(&next);
        let mut there_weighted = weighted_norm(&there.residual, &there.weights);
        let mut fraction = T::one();
        let mut halvings = 0;
        // Not lower (a NaN residual is not lower either).
        while there_weighted.partial_cmp(&weighted) != Some(Ordering::Less) {
            if weighted <= T::constant(STAGNATION_FLOOR) * floor {
                // Within a few units of the rounding floor no step lowers the residual: this is
                // what rounding lets the loops close to (intermediate values of a coupled
                // evaluation can exceed its vectors' magnitudes), so converged.
                within_turns_or_accept!(here, jacobian, x);
            }
            if halvings == MAX_HALVINGS && beyond_turns(&x, angles) {
                // An angle many turns out holds only to its float's spacing, and the loops'
                // residual with it (once an angle given as a sum is taken of its exact sum, no
                // rounding of that sum happens to land nearer): taken by whole turns, where
                // the steps can close them.
                (x, here, weighted) = taken_by_turns(&x, angles, &mut linearise);
                previous_residual = T::infinity();
                continue 'iterate;
            }
            if halvings == MAX_HALVINGS {
                // No step lowers the residual: a local minimum of |f| that is not a root.
                // Where a closed form can say whether the loops close at this input, it
                // decides; else, near a singular Jacobian, it is taken for a toggle the loops
                // cannot pass (a guess far from every assembly can stall the same way).
                let stalled = Error::NoConvergence {
                    iterations,
                    residual_norm: max_abs(&here.residual),
                };
                return Err(match assembles() {
                    Some(true) => stalled,
                    Some(false) => Error::CannotAssemble { input },
                    None if ran_away(&x, &start, &angles)
                        || kantorovich(&here, condition()) > quarter =>
                    {
                        Error::CannotAssemble { input }
                    }
                    None => stalled,
                });
            }
            halvings += 1;
            fraction = fraction * T::constant(0.5);
            next = stepped(fraction);
            there = linearise(&next);
            there_weighted = weighted_norm(&there.residual, &there.weights);
        }
        previous_residual = weighted;
        x = next;
        here = there;
        weighted = there_weighted;
        iterations += 1;
    }
}

/// Whether a solution keeps its guess's branches, loop by loop, from their sides (the
/// `closed::*_side` values: a branch sign, or zero where the loop's other assembly is within
/// the position's error). Only a loop decided both at the guess and at the solution, and
/// opposite, is another assembly; where the two assemblies are within the error of each
/// other (near a tangency, where they meet), the solution is on both to within its
/// accuracy.
pub fn same_sides<T: Real, const N: usize>(guess: [T; N], solution: [T; N]) -> bool {
    let zero = T::zero();
    guess
        .iter()
        .zip(&solution)
        .all(|(g, s)| !((*g > zero && *s < zero) || (*g < zero && *s > zero)))
}

/// Whether Newton keeps the Jacobian's orientation (see [`newton`]), and which unknowns are
/// angles. `true` keeps it with every unknown an angle, `false` leaves it free.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Orientation<const N: usize> {
    /// Any orientation at the solution.
    Free {
        /// Which unknowns are angles (the others lengths).
        angles: [bool; N],
    },
    /// The guess's orientation at the solution, unless the assemblies cannot be told apart.
    Kept {
        /// Which unknowns are angles (the others lengths).
        angles: [bool; N],
    },
}

impl<const N: usize> From<bool> for Orientation<N> {
    fn from(keep: bool) -> Self {
        if keep {
            Orientation::Kept { angles: [true; N] }
        } else {
            Orientation::Free { angles: [true; N] }
        }
    }
}

impl<const N: usize> Orientation<N> {
    /// Which unknowns are angles.
    fn angles(&self) -> [bool; N] {
        match self {
            Orientation::Free { angles } | Orientation::Kept { angles } => *angles,
        }
    }

    /// Whether an orientation kept can tell the assemblies apart at the evaluation `at` with
    /// rounding floor `floor` (the weighted residual's): not where a whole turn of some
    /// unknown angle moves every loop by less than the floor, for that angle is then
    /// undetermined and the two assemblies (mirror images across a chord, or a line, that
    /// the angle's link spans) lie within rounding of each other.
    fn tells_apart<T: Real, P>(&self, at: &Linearisation<T, N, P>, floor: T) -> bool {
        let Orientation::Kept { angles } = self else {
            return false;
        };
        let turn = T::constant(core::f64::consts::TAU);
        !angles.iter().enumerate().any(|(j, &angle)| {
            angle
                && at
                    .jacobian
                    .iter()
                    .zip(&at.weights)
                    .all(|(row, w)| turn * (row[j] * *w).abs() <= floor)
        })
    }
}

/// Whether a residual at the rounding floor is the attainable one (for a default solve):
/// the step to it started within `√ε/κ` of the root (relative to `scale`), or the Jacobian is
/// near singular.
///
/// A Newton step from a residual `f` leaves the loops' curvature, about `κ²·f²/(2·c)` with
/// `c` the shortest column (each loop is a sum of `r·e^{iθ}`, whose second derivative is as
/// long as its first): from `f ≤ √ε·scale` alone that is `κ²·ρ·ε/2` of the scale, and the
/// position's error κ times it: a slider-crank of κ 3 and aspect 3 stopped 61 units of
/// rounding off (its closed form is 0.1 off), and its velocity, κ·ρ times that, past its
/// estimate. From `κ·f ≤ √ε·scale` it is at most `ρ·ε/2`, under the floor for the
/// mechanisms whose rates the estimate covers without widening (ρ below 16); beyond, the
/// residual's test at the floor still bounds it. Near a singular position (κ beyond
/// ε^(-1/4)) the position is known only to about κ·ε whatever the residual, and a step from
/// the floor there is no polish but a move of that size along the singular direction, onto
/// whichever branch meets this one: there the floor is the stop.
#[inline(always)]
fn polished<T: Real>(previous_residual: T, scale: T, condition: T) -> bool {
    previous_residual * condition <= T::epsilon().sqrt() * scale
        || condition * T::epsilon().sqrt().sqrt() >= T::one()
}

/// Whether a default solve (zero tolerance) was accepted above the rounding floor
/// `16 ε Σ|r|`, because no step lowered its residual further. Where the iteration evaluates
/// loops in closed form inside each step, that evaluation rounds at the magnitudes of the
/// points its closed forms start from, not at those of its own short links, and the position
/// can be off by more than the accuracy contract states: generated code then polishes it by
/// Newton on every unknown, whose evaluation rounds only at the loops' own magnitudes.
#[inline]
pub fn stagnated<T: Real, const N: usize, P>(
    converged: &Converged<T, N, P>,
    options: &NewtonOptions<T>,
) -> bool {
    options.tolerance == T::zero()
        && weighted_norm(&converged.at.residual, &converged.at.weights)
            > T::constant(16.0) * T::epsilon() * converged.at.scale
}

/// Whether `guess` lies in the ball about `solution` from every point of which Newton on
/// every unknown converges to `solution` (Kantorovich, estimated as Newton's own test does from
/// the columns of the loops' full Jacobian at the solution, `columns` their squared norms,
/// and its relative determinant `relative`): then the solution is the guess's own, whatever
/// way it was reached.
///
/// An iteration on some unknowns with the rest solved in closed form (generated code's
/// reduced Newton) is not Newton on the loops: where a loop it solves in closed form turns
/// fast with the iterated unknowns (a short link beside long ones), one step can carry the
/// iterate past the guess's assembly to another of the same orientation, which no sign
/// tells apart. Generated code asks this of its solution first, on the common path (a few
/// dozen instructions); where it fails, [`root_elsewhere`] looks from the guess's side.
///
/// The radius is `1/(4·β²·L·(‖J‖ + L))` (Frobenius norms), with `L = max‖column‖` (a turn
/// `δ` of an angle moves its column, a sum of `r·e^{iθ}`, by at most `|δ|` times its
/// length) and `β = ‖J⁻¹‖ ≤ κ·N/min‖column‖` (each cofactor is at most the product of the
/// other columns), bounded with `L·(‖J‖ + L) ≤ 2·L·‖J‖`: certified where
/// `64·d²·N⁴·L²·‖J‖² ≤ (min‖column‖²·relative²)²` for `d = ‖guess − solution‖`. No square
/// root and one division; a column that is zero, or a bound that underflows, certifies
/// nothing.
#[inline(always)]
pub fn certified_start<T: Real, const N: usize>(
    guess: &[T; N],
    solution: &[T; N],
    columns: [T; N],
    relative: T,
) -> bool {
    let distance_squared = guess
        .iter()
        .zip(solution)
        .fold(T::zero(), |acc, (g, s)| acc + (*g - *s) * (*g - *s));
    let (mut norm_squared, mut longest, mut shortest) = (T::zero(), T::zero(), T::infinity());
    for column in columns {
        norm_squared = norm_squared + column;
        longest = longest.max(column);
        shortest = shortest.min(column);
    }
    let n_squared = T::constant((N * N) as f64);
    // min‖column‖²·relative², the reach of ‖J⁻¹‖ (squared, inverted, over N²).
    let bound = shortest * relative * relative;
    let left =
        T::constant(64.0) * n_squared * n_squared * distance_squared * longest * norm_squared;
    // A zero bound gives NaN or infinity, which compare false: not certified.
    left / bound <= bound
}

/// Kantorovich at `guess`, from the loops' residual `residual` and full Jacobian `jacobian`
/// there: where `h = β·L·η ≤ 1/2` (`β = ‖J⁻¹‖` and `η = ‖J⁻¹·f‖` computed, Frobenius and
/// Euclidean norms; `L = max‖column‖` as in [`certified_start`]), a root lies within `2·η`
/// of the guess, Newton on every unknown from the guess converges to it, and no other root
/// lies within `1/(β·L)`. That radius, or `None` where the guess is not certified (or the
/// Jacobian is singular there).
fn guess_radius<T: Real, const N: usize>(residual: &[T; N], jacobian: &[[T; N]; N]) -> Option<T> {
    let factored = Factored::new(*jacobian).ok()?;
    let step = factored.solve(*residual);
    let eta_squared = step.iter().fold(T::zero(), |acc, v| acc + *v * *v);
    let mut beta_squared = T::zero();
    for k in 0..N {
        let mut unit = [T::zero(); N];
        unit[k] = T::one();
        beta_squared = factored
            .solve(unit)
            .iter()
            .fold(beta_squared, |acc, v| acc + *v * *v);
    }
    let mut columns = [T::zero(); N];
    for row in jacobian {
        for (column, v) in columns.iter_mut().zip(row) {
            *column = *column + *v * *v;
        }
    }
    let lipschitz_squared = columns.iter().fold(T::zero(), |m, c| m.max(*c));
    let reach_squared = beta_squared * lipschitz_squared;
    // h² = β²·L²·η² ≤ 1/4; NaN compares false.
    (reach_squared * eta_squared <= T::constant(0.25)).then(|| T::one() / reach_squared.sqrt())
}

/// Whether the loops close at a position to their rounding floor, `16·ε·size` for the sum
/// of the declared lengths `size`: then the mechanism assembles there (within rounding), and
/// no solver's `CannotAssemble` from it stands. Generated code asks this where a reduced
/// iteration's `CannotAssemble` meets Newton's `Singular` on every unknown from the same
/// guess. NaN closes nothing.
#[cold]
#[inline(never)]
pub fn closes_within_rounding<T: Real, const N: usize>(residual: &[T; N], size: T) -> bool {
    let floor = T::constant(16.0) * T::epsilon() * size;
    residual.iter().all(|r| r.abs() <= floor)
}

/// Whether Kantorovich certifies `guess` (`h = β·L·η ≤ 1/2` there, see `guess_radius`):
/// Newton on every unknown from it converges to the root it is near. Generated code asks
/// this before it lets Newton on every unknown answer for a reduced iteration that landed
/// on another orientation: from a guess it certifies, that answer is the guess's root;
/// from any other, the reduced iteration's [`Error::OtherBranch`] stands.
#[cold]
#[inline(never)]
pub fn guess_certified<T: Real, const N: usize>(residual: &[T; N], jacobian: &[[T; N]; N]) -> bool {
    guess_radius(residual, jacobian).is_some()
}

/// Whether `solution` is certainly not the root `guess` is near: Kantorovich certifies the
/// guess (see `guess_radius`) and `solution` lies farther from it than the radius within
/// which that root is the only one. Generated code asks this where [`certified_start`]
/// could not vouch for a reduced iteration's solution, and then solves by Newton on every
/// unknown from the guess, which converges to the guess's root; where the guess is not
/// certified, nothing says which root is the guess's, and the solution stands.
#[cold]
#[inline(never)]
pub fn root_elsewhere<T: Real, const N: usize>(
    residual: &[T; N],
    jacobian: &[[T; N]; N],
    guess: &[T; N],
    solution: &[T; N],
) -> bool {
    let Some(radius) = guess_radius(residual, jacobian) else {
        return false;
    };
    let distance_squared = guess
        .iter()
        .zip(solution)
        .fold(T::zero(), |acc, (g, s)| acc + (*g - *s) * (*g - *s));
    distance_squared > radius * radius
}

/// [`newton`]'s common path, for generated code to inline: `then` of the solution where
/// Newton takes full steps each of which lowers the residual, else `otherwise()` (which
/// generated code makes an out-of-line call of [`newton`] from `guess` again, with an
/// evaluation in its initial state). The common path makes the same iterates from the same
/// evaluations, the same factors (`Factored::quick`, which defers the relative determinant's
/// square root and division to the solution) and the same tests in the same arithmetic, so
/// that what it hands `then` is what [`newton`] returns, bit for bit. It leaves the solve to
/// `otherwise` wherever [`newton`] would do something else or its verdict is not certain
/// here: an argument or a value that is not finite (generated code's evaluation, whose sines
/// and cosines are [`Started`]'s, gives NaN where an angle has moved beyond a turn from the
/// guess), a Jacobian near singular or in need of scaling, a step that does not lower the
/// residual (which [`newton`] halves, or takes as stagnation), the iteration cap, the other
/// branch. (The solution goes to `then` rather
/// than out in an `Option`, whose tag would share a byte with the factors' and keep them in
/// memory.)
#[inline(always)]
pub fn newton_common<T: Real, const N: usize, P: Copy, R>(
    guess: [T; N],
    options: &NewtonOptions<T>,
    keep_orientation: impl Into<Orientation<N>>,
    linearise: impl FnMut(&[T; N]) -> Linearisation<T, N, P>,
    then: impl FnOnce(Converged<T, N, P>) -> R,
    otherwise: impl FnOnce() -> R,
) -> R {
    common_path(
        guess,
        options,
        keep_orientation,
        linearise,
        then,
        otherwise,
        false,
    )
}

/// [`newton_common`] for loops whose scale (every evaluation's [`Linearisation::scale`], the
/// same at each: the dimensions fix it) the caller has found finite already, as a generated
/// `{Name}Newton` does once, when it is made: the test at the solution is left out.
#[inline(always)]
pub fn newton_common_at_finite_scale<T: Real, const N: usize, P: Copy, R>(
    guess: [T; N],
    options: &NewtonOptions<T>,
    keep_orientation: impl Into<Orientation<N>>,
    linearise: impl FnMut(&[T; N]) -> Linearisation<T, N, P>,
    then: impl FnOnce(Converged<T, N, P>) -> R,
    otherwise: impl FnOnce() -> R,
) -> R {
    common_path(
        guess,
        options,
        keep_orientation,
        linearise,
        then,
        otherwise,
        true,
    )
}

/// [`newton_common`], which tests the scale at the solution unless `scale_finite` says it is
/// finite.
#[inline(always)]
fn common_path<T: Real, const N: usize, P: Copy, R>(
    guess: [T; N],
    options: &NewtonOptions<T>,
    keep_orientation: impl Into<Orientation<N>>,
    mut linearise: impl FnMut(&[T; N]) -> Linearisation<T, N, P>,
    then: impl FnOnce(Converged<T, N, P>) -> R,
    otherwise: impl FnOnce() -> R,
    scale_finite: bool,
) -> R {
    let tolerance = options.tolerance;
    let keep_orientation = matches!(keep_orientation.into(), Orientation::Kept { .. });
    'common: {
        // Finite and not negative (false for NaN), in one comparison of the bits, which also
        // leaves `−0` (zero to [`newton`]) to `otherwise`. A guess that is not finite is not
        // tested here: its residual is not finite either (every unknown moves the loops), so
        // the first evaluation leaves the solve to `otherwise`, as [`newton`]'s test would.
        if !tolerance.positive_finite_or_zero() {
            break 'common;
        }
        let rounding_floor = T::constant(16.0) * T::epsilon();
        let quarter = T::constant(0.25);
        let mut x = guess;
        let mut iterations = 0;
        let mut started_negative = false;
        let mut previous_residual = T::max_value();
        loop {
            let here = linearise(&x);
            // Every weighted component lower than the weighted residual before the step
            // (which [`newton`] takes whole only then), so finite and not NaN; at the guess,
            // below the largest float (a float comparison, where infinity's is a test of the
            // bits: a residual of exactly the largest, which [`newton`] takes, is left to
            // `otherwise`, which is [`newton`]). Then their largest is [`weighted_norm`]'s, and the unweighted
            // components, finite too, give [`max_abs`]'s where it is wanted.
            // The tests together (`&`, not `&&`), for one branch.
            let lower = here
                .residual
                .iter()
                .zip(&here.weights)
                .fold(true, |lower, (r, w)| {
                    lower & (r.abs() * *w < previous_residual)
                });
            if !lower {
                break 'common;
            }
            let weighted = here
                .residual
                .iter()
                .zip(&here.weights)
                .fold(T::zero(), |norm, (r, w)| norm.max(r.abs() * *w));
            let residual_norm = || {
                here.residual
                    .iter()
                    .fold(T::zero(), |norm, r| norm.max(r.abs()))
            };
            let Some(jacobian) = Factored::quick_with(here.jacobian, here.columns) else {
                break 'common;
            };
            let negative = jacobian.negative();
            if iterations == 0 {
                started_negative = negative;
            }
            let condition = || T::one() / jacobian.relative().abs();
            let floor = rounding_floor * here.scale;
            let met = if tolerance > T::zero() {
                weighted <= floor
                    || (residual_norm() <= tolerance
                        && kantorovich_aside(here.residual, here.jacobian, condition()) <= quarter)
            } else {
                weighted == T::zero()
                    || (weighted <= floor && polished(previous_residual, here.scale, condition()))
            };
            if met {
                // A scale that is not finite makes no floor: tested here rather than at each
                // evaluation, since an iteration that goes on cannot end anywhere else (and
                // not at all where the caller found it finite). (A float comparison, false
                // for NaN, where `is_finite` tests the bits.)
                let finite_scale = scale_finite || here.scale.abs() <= T::max_value();
                if !finite_scale || (keep_orientation && negative != started_negative) {
                    break 'common;
                }
                let jacobian = jacobian.finish();
                let residual_norm = residual_norm();
                return then(Converged {
                    solved: Solved {
                        value: x,
                        iterations,
                        residual_norm,
                        condition: T::one() / jacobian.relative().abs(),
                    },
                    at: here,
                    jacobian,
                });
            }
            if iterations >= options.max_iterations {
                break 'common;
            }
            // A step that is not finite is not tested here: it makes an iterate that is not
            // finite, whose residual is not finite either (every unknown moves the loops),
            // so the next evaluation leaves the solve to `otherwise`, as [`newton`]'s test
            // of the step would.
            let step = jacobian.solve(here.residual);
            // [`newton`]'s full step, `x − 1·step`.
            for (t, d) in x.iter_mut().zip(step) {
                *t = *t - T::one() * d;
            }
            previous_residual = weighted;
            iterations += 1;
        }
    }
    otherwise()
}

/// [`kantorovich`] out of line, from copies: the evaluation it reads stays in registers on
/// the common path.
#[cold]
#[inline(never)]
fn kantorovich_aside<T: Real, const N: usize>(
    residual: [T; N],
    jacobian: [[T; N]; N],
    condition: T,
) -> T {
    let at = Linearisation {
        residual,
        jacobian,
        scale: T::zero(),
        weights: [T::one(); N],
        payload: (),
        columns: Columns::FromMatrix,
    };
    kantorovich(&at, condition)
}

/// Kantorovich's `h = ‖J⁻¹‖²·L·‖f‖` at an iterate, estimated from the Jacobian's columns:
/// `‖J⁻¹‖ ≈ κ / min‖column‖` and, the loops being sums of `r·e^{iθ}`, `L ≈ max‖column‖`.
/// Below 1/2 a root is certain to lie near the iterate.
fn kantorovich<T: Real, const N: usize, P>(at: &Linearisation<T, N, P>, condition: T) -> T {
    // In units where the largest entry is about 1 (a power of two, exact: h is a ratio of
    // lengths), so that no square overflows or underflows at any scale.
    let largest = at
        .jacobian
        .iter()
        .flatten()
        .fold(T::zero(), |m, v| m.max(v.abs()));
    let scale = if largest > T::zero() && largest.is_finite() {
        crate::real::normaliser(largest)
    } else {
        T::one()
    };
    let mut squares = [T::zero(); N];
    for row in &at.jacobian {
        for (square, v) in squares.iter_mut().zip(row) {
            let v = *v * scale;
            *square = *square + v * v;
        }
    }
    let shortest = squares.iter().fold(T::infinity(), |m, c| m.min(*c));
    let longest = squares.iter().fold(T::zero(), |m, c| m.max(*c)).sqrt();
    let residual = at
        .residual
        .iter()
        .fold(T::zero(), |acc, f| acc + (*f * scale) * (*f * scale))
        .sqrt();
    condition * condition * residual * longest / shortest
}

/// The largest absolute component (NaN if any component is NaN).
/// The largest `|r|·w`, NaN if any is.
fn weighted_norm<T: Real, const N: usize>(residual: &[T; N], weights: &[T; N]) -> T {
    // The largest by `max` (which passes over NaN), and NaN by the sum, without a branch per
    // component: a sum of values that are not negative is NaN only if one of them is.
    let (largest, sum) =
        residual
            .iter()
            .zip(weights)
            .fold((T::zero(), T::zero()), |(largest, sum), (r, w)| {
                let v = r.abs() * *w;
                (largest.max(v), sum + v)
            });
    if sum.is_nan() { T::nan() } else { largest }
}

/// The weight of a loop whose own vectors' magnitudes sum to `own` in a mechanism whose
/// loops' sum to `scale` (see [`Linearisation::weights`]); 1 where `own` is not positive.
#[inline(always)]
pub fn loop_weight<T: Real>(scale: T, own: T) -> T {
    if own > T::zero() {
        scale / own
    } else {
        T::one()
    }
}

pub(crate) fn max_abs<T: Real>(values: &[T]) -> T {
    values.iter().fold(T::zero(), |acc, v| {
        if v.is_nan() || acc.is_nan() {
            T::nan()
        } else {
            acc.max(v.abs())
        }
    })
}

/// Whether every component is finite: on the common path (all finite, their sum too) one
/// addition per component, a product and a single comparison, no branch per component. The
/// sum of finite values is finite unless it overflows, and infinite or NaN with an infinity
/// or NaN among them; finite, it times zero is zero, else NaN. Only where it is not (an
/// overflow, or a value not finite) are the components looked at one by one, out of line.
#[inline(always)]
pub fn all_finite<T: Real>(values: &[T]) -> bool {
    let Some((first, rest)) = values.split_first() else {
        return true;
    };
    let sum = rest.iter().fold(*first, |sum, value| sum + *value);
    sum * T::zero() == T::zero() || each_finite(values)
}

/// Whether every component is finite, one by one: [`all_finite`]'s rare path.
#[cold]
#[inline(never)]
fn each_finite<T: Real>(values: &[T]) -> bool {
    values.iter().all(|value| value.is_finite())
}

/// `Err(NonFinite)` naming the first of `values` that is NaN or infinite.
#[inline]
pub fn check_finite<T: Real>(values: &[(T, &'static str)]) -> Result<(), Error<T>> {
    match values.iter().find(|(value, _)| !value.is_finite()) {
        Some((_, quantity)) => Err(Error::NonFinite { quantity }),
        None => Ok(()),
    }
}

/// As [`check_finite`], with the values and their names apart: on the common path (every
/// value finite) one addition per value and a single comparison ([`all_finite`]'s sum), the
/// names read only to blame one.
#[inline(always)]
pub fn check_all_finite<T: Real, const N: usize>(
    values: [T; N],
    quantities: &[&'static str; N],
) -> Result<(), Error<T>> {
    let Some((first, rest)) = values.split_first() else {
        return Ok(());
    };
    let sum = rest.iter().fold(*first, |sum, value| sum + *value);
    if sum * T::zero() == T::zero() {
        Ok(())
    } else {
        // Either a value is not finite, or the sum overflowed and none is to blame.
        blame_non_finite(values, quantities)
    }
}

/// `Err(NonFinite)` naming the first of `values` that is not finite, out of line.
#[cold]
#[inline(never)]
fn blame_non_finite<T: Real, const N: usize>(
    values: [T; N],
    quantities: &[&'static str; N],
) -> Result<(), Error<T>> {
    match values
        .iter()
        .zip(quantities)
        .find(|(value, _)| !value.is_finite())
    {
        Some((_, quantity)) => Err(Error::NonFinite { quantity }),
        None => Ok(()),
    }
}

/// `values` if they are all finite, else `Err(NonFinite)` naming `quantity`.
#[inline]
pub fn finite<T: Real, const N: usize>(
    values: [T; N],
    quantity: &'static str,
) -> Result<[T; N], Error<T>> {
    if all_finite(&values) {
        Ok(values)
    } else {
        Err(Error::NonFinite { quantity })
    }
}

/// A position with its velocity and acceleration, as the generated `motion`, `motion_at` and
/// `motion_near` return them, with the estimate of their errors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion<U, T> {
    /// The unknowns' values.
    pub position: U,
    /// Their rates.
    pub velocity: U,
    /// Their accelerations.
    pub acceleration: U,
    /// The estimated relative error of each ([`Accuracy::estimate`] at the position): within
    /// what was required (else the call was [`Error::Inaccurate`](crate::Error::Inaccurate)),
    /// and a bound on the true error, which the edge tests check against a multiple-precision
    /// oracle.
    pub accuracy: Accuracy<T>,
}

/// An unknown angle's sine and cosine along a Newton iteration: the first from `sin_cos`, the
/// next by rotating that pair through the way the angle has moved since (a short series for
/// the step's sine and cosine, good to rounding for steps up to 2⁻¹⁰ rad), which costs a
/// fraction of a `sin_cos`. Every rotation starts from the last pair `sin_cos` computed, so
/// rounding in the rotations cannot accumulate however many there are; an angle more than
/// 2⁻¹⁰ from that pair's calls `sin_cos` afresh.
#[derive(Clone, Copy, Debug)]
pub struct Turning<T> {
    /// The angle of the last pair from `sin_cos`.
    angle: T,
    sin: T,
    cos: T,
}

impl<T: Real> Turning<T> {
    /// No angle yet: the first call computes `sin_cos`.
    #[inline]
    pub fn new() -> Self {
        Turning {
            angle: T::nan(),
            sin: T::nan(),
            cos: T::nan(),
        }
    }

    /// `(sin angle, cos angle)`.
    #[inline]
    pub fn sin_cos(&mut self, angle: T) -> (T, T) {
        // Two nearby floats differ exactly (Sterbenz), so the step is the true one. Not
        // small for NaN (no pair yet, or a NaN angle).
        let step = angle - self.angle;
        if step.abs() <= T::constant(TURN_LIMIT) {
            return rotate(self.sin, self.cos, step);
        }
        (self.sin, self.cos) = angle.sin_cos();
        self.angle = angle;
        (self.sin, self.cos)
    }
}

impl<T: Real> Default for Turning<T> {
    fn default() -> Self {
        Self::new()
    }
}

/// The largest step, in radians, through which [`rotate`] turns a sine and cosine.
pub(crate) const TURN_LIMIT: f64 = 1.0 / 1024.0;

/// The largest magnitude, in radians, of a guess's angle that Newton starts from as it is;
/// beyond it, [`newton`] first takes the angle by whole turns to within `[−π, π]`. A float
/// holds an angle only to its spacing: at 16, to `ε·16/2` (1.8e-15 rad in `f64`), which moves
/// a vector by less than the rounding floor `16 ε Σ|r|` every test reads; at a few hundred (a
/// guess that counts a linkage's turns) to more than that, so that Newton stalls above the
/// floor, or stops at an angle less accurate than the one stated.
pub(crate) const WHOLE_TURNS_BEYOND: f64 = 16.0;

/// `angle` where within 16 rad (`WHOLE_TURNS_BEYOND`), else NaN (and NaN for NaN). The
/// common path's evaluation reads through it each angle unknown whose own sine and cosine no
/// [`Started`] keeps (one the loops turn only with an offset, `ψ + π/2`), so that a guess or
/// an iterate beyond leaves the solve to [`newton`], which takes such an angle by whole turns
/// as it does the others: [`Started`] gives NaN for the others beyond the same bound, and
/// without this an offset angle's iterates ran on unchecked, to a solution thousands of
/// radians out whose stated accuracy the float's spacing there did not hold.
#[inline(always)]
pub fn within_whole_turns<T: Real>(angle: T) -> T {
    if angle.abs() <= T::constant(WHOLE_TURNS_BEYOND) {
        angle
    } else {
        T::nan()
    }
}

/// Whether some angle (`angles`) of the iterate `x` has turned through more than a whole
/// turn from its value at `start` (the iterates are never taken by whole turns, so the
/// difference counts them): the iterates have run away from the guess, as they do from one
/// near no root (past a toggle they spin through thousands of radians, to another assembly
/// or to a stall where a float holds the angle too coarsely to reach the floor). From a guess
/// Kantorovich certifies they never do: they stay within twice its ball's radius, which is
/// below 1 rad (`1/(‖J⁻¹‖·L)`, `L` at least the Jacobian's smallest singular value).
fn ran_away<T: Real, const N: usize>(x: &[T; N], start: &[T; N], angles: &[bool; N]) -> bool {
    let whole_turn = T::constant(core::f64::consts::TAU);
    x.iter()
        .zip(start)
        .zip(angles)
        .any(|((x, start), &angle)| angle && (*x - *start).abs() > whole_turn)
}

/// The largest magnitude, in radians, of an angle [`newton`] returns as the iterates left it:
/// [`WHOLE_TURNS_BEYOND`] and a radian, beyond the most the common path's iterates reach
/// (a guess within ±16 rad, moved at most 2⁻¹⁰), so that the two still agree bit for bit.
const RETURNED_TURNS_BEYOND: f64 = WHOLE_TURNS_BEYOND + 1.0;

/// Whether some angle (`angles`) of `x` is beyond [`RETURNED_TURNS_BEYOND`] (false for NaN:
/// an iterate that is not finite is not accepted).
#[inline(always)]
fn beyond_turns<T: Real, const N: usize>(x: &[T; N], angles: [bool; N]) -> bool {
    let bound = T::constant(RETURNED_TURNS_BEYOND);
    x.iter()
        .zip(&angles)
        .any(|(value, &angle)| angle && value.abs() > bound)
}

/// `x` with its angles taken by whole turns ([`within_a_turn`]), the loops evaluated there,
/// and their weighted residual: where [`newton`] solves on from an iterate
/// [`beyond_turns`]. Out of line: it is rare, and inline at each of the three places that
/// accept an iterate it would crowd the iteration.
#[cold]
#[inline(never)]
fn taken_by_turns<T: Real, const N: usize, P>(
    x: &[T; N],
    angles: [bool; N],
    linearise: &mut impl FnMut(&[T; N]) -> Linearisation<T, N, P>,
) -> ([T; N], Linearisation<T, N, P>, T) {
    let within = within_a_turn(*x, angles);
    let here = linearise(&within);
    let weighted = weighted_norm(&here.residual, &here.weights);
    (within, here, weighted)
}

/// `x` with each angle (`angles`) beyond [`WHOLE_TURNS_BEYOND`] taken by whole turns to the
/// angle in `[−π, π]` with the same sine and cosine (the platform's, whose argument reduction
/// is exact at any magnitude; `θ − 2π·round(θ/2π)` is not, beyond 2^53 or so). A value that
/// is not finite is left as it is.
fn within_a_turn<T: Real, const N: usize>(x: [T; N], angles: [bool; N]) -> [T; N] {
    let bound = T::constant(WHOLE_TURNS_BEYOND);
    let mut x = x;
    for (value, &angle) in x.iter_mut().zip(&angles) {
        if angle && value.abs() > bound && value.is_finite() {
            let (sin, cos) = value.sin_cos();
            *value = sin.atan2(cos);
        }
    }
    x
}

/// The sines and cosines of several unknown angles along a Newton iteration: each rotated as
/// [`Turning`] rotates it (the same arithmetic, from the last fresh pair), and where any has
/// moved more than 2⁻¹⁰ from its pair, fresh pairs of every angle from
/// [`fast::sin_cos`](crate::fast::sin_cos) at once, straight-line code the compiler packs into
/// vector instructions (two angles for the price of about one platform `sin_cos`; the
/// platform's for an angle beyond [`fast::sin_cos_limit`](crate::fast::sin_cos_limit), or not
/// finite). The fresh pairs are read, never written, while the angles turn, so they stay in
/// registers through the iteration.
#[derive(Clone, Copy, Debug)]
pub struct Turnings<T, const K: usize> {
    /// The angles of the last fresh pairs.
    angle: [T; K],
    sin: [T; K],
    cos: [T; K],
}

impl<T: Real, const K: usize> Turnings<T, K> {
    /// No angles yet: the first call computes their sines and cosines.
    #[inline]
    pub fn new() -> Self {
        Turnings {
            angle: [T::nan(); K],
            sin: [T::nan(); K],
            cos: [T::nan(); K],
        }
    }

    /// `(sin angles, cos angles)`.
    #[inline(always)]
    pub fn sin_cos(&mut self, angles: [T; K]) -> ([T; K], [T; K]) {
        // As `Turning::sin_cos`, lane by lane.
        if let Some(turned) = turned(self.angle, self.sin, self.cos, angles) {
            return turned;
        }
        (self.sin, self.cos) = fresh_sin_cos(angles);
        self.angle = angles;
        (self.sin, self.cos)
    }
}

/// The sines and cosines of the unknown angles along [`newton_common`]'s iteration: fresh
/// pairs at the guess, computed before it ([`Started::at`]), then those pairs turned as
/// [`Turnings`] turns them, the same arithmetic from the same pairs, while every angle stays
/// within 2⁻¹⁰ of its pair's; beyond, NaN, which leaves the solve to [`newton`] (whose
/// turnings then compute pairs afresh). The iteration so makes no call, which would clobber
/// every register it keeps.
#[derive(Clone, Copy, Debug)]
pub struct Started<T, const K: usize> {
    /// The angles of the fresh pairs.
    angle: [T; K],
    sin: [T; K],
    cos: [T; K],
    /// Whether the pairs have been handed out yet (the first evaluation, at the guess, takes
    /// them as they are).
    turning: bool,
}

impl<T: Real, const K: usize> Started<T, K> {
    /// The pairs at `angles`, fresh: as the safeguarded iteration's evaluation computes them
    /// (one angle's by [`Turning`], the platform's `sin_cos`; several by [`Turnings`]), so
    /// that either path makes the same iterates.
    ///
    /// An angle beyond ±16 rad gives NaN pairs: [`newton`] takes it by whole
    /// turns first.
    #[inline(always)]
    pub fn at(angles: [T; K]) -> Self {
        let (sin, cos) = if K == 1 {
            let (mut sin, mut cos) = (angles, angles);
            for ((s, c), a) in sin.iter_mut().zip(&mut cos).zip(angles) {
                (*s, *c) = if a.abs() <= T::constant(WHOLE_TURNS_BEYOND) {
                    a.sin_cos()
                } else {
                    (T::nan(), T::nan())
                };
            }
            (sin, cos)
        } else {
            started_sin_cos(angles)
        };
        Started {
            angle: angles,
            sin,
            cos,
            turning: false,
        }
    }

    /// `(sin angles, cos angles)`: the fresh pairs the first time, turned after.
    #[inline(always)]
    pub fn sin_cos(&mut self, angles: [T; K]) -> ([T; K], [T; K]) {
        if !self.turning {
            self.turning = true;
            return (self.sin, self.cos);
        }
        turned(self.angle, self.sin, self.cos, angles).unwrap_or(([T::nan(); K], [T::nan(); K]))
    }
}

/// The pairs `(sin, cos)` of `from` turned to `angles`, or `None` if some angle is more than
/// 2⁻¹⁰ from its pair's (a NaN step is not small either).
#[inline(always)]
fn turned<T: Real, const K: usize>(
    from: [T; K],
    sin: [T; K],
    cos: [T; K],
    angles: [T; K],
) -> Option<([T; K], [T; K])> {
    let mut steps = angles;
    for (step, last) in steps.iter_mut().zip(from) {
        *step = *step - last;
    }
    if !steps
        .iter()
        .all(|step| step.abs() <= T::constant(TURN_LIMIT))
    {
        return None;
    }
    let (mut sines, mut cosines) = (sin, cos);
    for ((sin, cos), step) in sines.iter_mut().zip(&mut cosines).zip(steps) {
        (*sin, *cos) = rotate(*sin, *cos, step);
    }
    Some((sines, cosines))
}

/// `(sin, cos)` of an angle rotated by `step`, `|step| ≤ 2⁻¹⁰`: [`Turning`]'s rotation.
#[inline(always)]
pub(crate) fn rotate<T: Real>(sin: T, cos: T, step: T) -> (T, T) {
    let squared = step * step;
    // sin δ = δ(1 − δ²/6·(1 − δ²/20)), cos δ = 1 − δ²/2·(1 − δ²/12): the next terms are
    // below 2⁻⁶⁹ relative for |δ| ≤ 2⁻¹⁰.
    let sin_step = step
        * (T::one() - squared * T::constant(1.0 / 6.0) * (T::one() - squared * T::constant(0.05)));
    let cos_step =
        T::one() - squared * T::constant(0.5) * (T::one() - squared * T::constant(1.0 / 12.0));
    (
        sin * cos_step + cos * sin_step,
        cos * cos_step - sin * sin_step,
    )
}

impl<T: Real, const K: usize> Default for Turnings<T, K> {
    fn default() -> Self {
        Self::new()
    }
}

/// `(sin x, cos x)` for generated code: for `f64`, inline
/// [`fast::sin_cos`](crate::fast::sin_cos) within its limit (within 0.9 ulp; no call, so no
/// live value is spilled around one, and fewer instructions than the platform's), else the
/// platform's, out of line; for `f32`, the platform's (see [`Real::INLINE_SIN_COS`]). Every
/// generated function takes its input's sine and cosine from here, so that they all see the
/// same bits.
#[inline(always)]
pub fn sin_cos<T: Real>(x: T) -> (T, T) {
    if !T::INLINE_SIN_COS {
        return x.sin_cos();
    }
    // False for NaN, which the platform's maps to NaN as well.
    if x.abs() <= crate::fast::sin_cos_limit::<T>() {
        crate::fast::sin_cos_within_limit(x)
    } else {
        let ([sin], [cos]) = platform_sin_cos([x]);
        (sin, cos)
    }
}

/// Whether every angle is within the range where [`sin_cos`] takes the inline
/// [`fast::sin_cos`](crate::fast::sin_cos) (false for NaN and ±∞): a caller that needs its
/// angles finite tests this instead, and the compiler then knows the range at `sin_cos`
/// (the same comparison), one test for both.
#[inline(always)]
pub fn within_sin_cos_range<T: Real>(angles: &[T]) -> bool {
    let limit = crate::fast::sin_cos_limit::<T>();
    angles.iter().all(|a| a.abs() <= limit)
}

/// Every angle's sine and cosine: [`fast::sin_cos`](crate::fast::sin_cos) lane by lane where
/// all are within its limit, else the platform's `sin_cos`. Out of line: called once per
/// solve, inline it would only crowd the iteration's registers.
#[inline(never)]
fn fresh_sin_cos<T: Real, const K: usize>(angles: [T; K]) -> ([T; K], [T; K]) {
    let limit = crate::fast::sin_cos_limit::<T>();
    // Not all within (NaN is not within either).
    if !angles.iter().all(|a| a.abs() <= limit) {
        return platform_sin_cos(angles);
    }
    let mut sines = angles;
    let mut cosines = angles;
    for ((s, c), a) in sines.iter_mut().zip(&mut cosines).zip(angles) {
        (*s, *c) = crate::fast::sin_cos_lanes_within_limit(a);
    }
    (sines, cosines)
}

/// `angle` (within `[−π, π]`, a closed form's) moved by whole turns to within half a turn of
/// `guess`, as Newton on every unknown would continue it from there; `angle` itself where the
/// guess is beyond ±16 rad, which [`newton`] takes by whole turns first (a
/// guess that counts a thousand turns would hand them on to a solution it cannot hold to the
/// accuracy stated), and where the angle so moved would be beyond ±17 rad, where [`newton`]
/// takes an iterate by whole turns (a guess of 15.99 rad took an angle to 18.2, where every
/// angle of a solution is said to be within ±17). An offset under 3 rad from the guess (the
/// common case) needs no whole turns taken off: `round` would give zero there.
#[inline(always)]
pub fn angle_near<T: Real>(angle: T, guess: T) -> T {
    let offset = angle - guess;
    if offset.abs() < T::constant(3.0) {
        return guess + offset;
    }
    // Not beyond (a NaN guess, refused before any closed form is solved, is beyond).
    if guess.abs() <= T::constant(WHOLE_TURNS_BEYOND) {
        let turn = T::constant(core::f64::consts::TAU);
        let near = guess + (offset - (offset / turn).round() * turn);
        if near.abs() <= T::constant(RETURNED_TURNS_BEYOND) {
            return near;
        }
    }
    angle
}

/// [`fresh_sin_cos`] for [`Started::at`]: NaN pairs if some angle is beyond
/// [`WHOLE_TURNS_BEYOND`] (or not finite), which [`newton`] takes by whole turns first.
#[inline(never)]
fn started_sin_cos<T: Real, const K: usize>(angles: [T; K]) -> ([T; K], [T; K]) {
    let bound = T::constant(WHOLE_TURNS_BEYOND);
    // Not all within (NaN is not within either).
    if !angles.iter().all(|a| a.abs() <= bound) {
        return ([T::nan(); K], [T::nan(); K]);
    }
    // The bound is within `fast::sin_cos`'s limit: `fresh_sin_cos`'s lanes.
    let mut sines = angles;
    let mut cosines = angles;
    for ((s, c), a) in sines.iter_mut().zip(&mut cosines).zip(angles) {
        (*s, *c) = crate::fast::sin_cos_lanes_within_limit(a);
    }
    (sines, cosines)
}

/// Every angle's sine and cosine by the platform's `sin_cos`, out of line.
#[cold]
#[inline(never)]
fn platform_sin_cos<T: Real, const K: usize>(angles: [T; K]) -> ([T; K], [T; K]) {
    let mut sines = angles;
    let mut cosines = angles;
    for ((s, c), a) in sines.iter_mut().zip(&mut cosines).zip(angles) {
        (*s, *c) = a.sin_cos();
    }
    (sines, cosines)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_angle_beyond_sixteen_radians_is_not_a_number_to_the_common_path() {
        for within in [0.0, -16.0, 16.0, 15.99, -1e-300] {
            assert_eq!(within_whole_turns(within), within);
        }
        for beyond in [
            16.000_000_000_000_004,
            -17.0,
            1e300,
            f64::INFINITY,
            f64::NAN,
        ] {
            assert!(within_whole_turns(beyond).is_nan(), "{beyond:e}");
        }
        assert!(within_whole_turns(16.5f32).is_nan());
    }

    #[test]
    fn angles_within_sin_cos_range_are_finite_and_within_its_limit() {
        let limit = crate::fast::sin_cos_limit::<f64>();
        assert!(within_sin_cos_range::<f64>(&[]));
        assert!(within_sin_cos_range(&[0.0, -limit, limit]));
        for beyond in [limit * (1.0 + f64::EPSILON), f64::INFINITY, f64::NAN] {
            assert!(!within_sin_cos_range(&[0.5, beyond]), "{beyond:e}");
            assert!(!within_sin_cos_range(&[-beyond]), "{beyond:e}");
        }
    }

    /// The loops close to their rounding floor, `16·ε·size`, and not a bit beyond it; NaN
    /// closes nothing.
    #[test]
    fn loops_close_within_rounding_up_to_the_floor() {
        let size = 3.0;
        let floor = 16.0 * f64::EPSILON * size;
        assert!(closes_within_rounding(&[floor, -floor], size));
        assert!(closes_within_rounding(&[0.0, floor / 2.0], size));
        assert!(!closes_within_rounding(
            &[floor * (1.0 + f64::EPSILON), 0.0],
            size
        ));
        assert!(!closes_within_rounding(&[0.0, -floor * 1.5], size));
        assert!(!closes_within_rounding(&[f64::NAN, 0.0], size));
        let floor32 = 16.0 * f32::EPSILON * 2.0;
        assert!(closes_within_rounding(&[floor32], 2.0f32));
        assert!(!closes_within_rounding(&[floor32 * 1.25], 2.0f32));
    }

    /// The four-bar of the seeds' Example 1 at `theta2`, as generated code evaluates it.
    fn four_bar(theta2: f64) -> impl FnMut(&[f64; 2]) -> Linearisation<f64, 2, [f64; 4]> + Clone {
        let mut turnings = Turnings::<f64, 2>::new();
        move |x: &[f64; 2]| evaluated(theta2, turnings.sin_cos(*x))
    }

    /// The four-bar's loop at `theta2`, from θ3's and θ4's sines and cosines.
    fn evaluated(
        theta2: f64,
        ([s3, s4], [c3, c4]): ([f64; 2], [f64; 2]),
    ) -> Linearisation<f64, 2, [f64; 4]> {
        let [l1, l2, l3, l4] = [180.0, 80.0, 200.0, 150.0];
        let (s2, c2) = theta2.sin_cos();
        let (t0, t1, t2, t3) = (l3 * c3, l3 * s3, l4 * c4, l4 * s4);
        Linearisation {
            residual: [l2 * c2 + t0 - t2 - l1, l2 * s2 + t1 - t3],
            jacobian: [[-t1, t3], [t0, -t2]],
            scale: l1 + l2 + l3 + l4,
            weights: [1.0; 2],
            payload: [s3, c3, s4, c4],
            columns: Columns::FromMatrix,
        }
    }

    /// [`four_bar`] as generated code evaluates it on Newton's common path: the sines and
    /// cosines at `guess` computed first, then only turned.
    fn four_bar_started(
        theta2: f64,
        guess: [f64; 2],
    ) -> impl FnMut(&[f64; 2]) -> Linearisation<f64, 2, [f64; 4]> {
        let mut started = Started::<f64, 2>::at(guess);
        move |x: &[f64; 2]| evaluated(theta2, started.sin_cos(*x))
    }

    /// The residual `x − (1, 2)` with its exact Jacobian (one step lands on the root), each
    /// component weighted by `weight`.
    fn shifted(weight: f64) -> impl Fn(&[f64; 2]) -> Linearisation<f64, 2, ()> + Copy {
        move |x: &[f64; 2]| Linearisation {
            residual: [x[0] - 1.0, x[1] - 2.0],
            jacobian: [[1.0, 0.0], [0.0, 1.0]],
            scale: 1.0,
            weights: [weight; 2],
            payload: (),
            columns: Columns::FromMatrix,
        }
    }

    fn bits(converged: &Converged<f64, 2, [f64; 4]>) -> [u64; 6] {
        let [a, b] = converged.solved.value;
        let [c, d] = converged.jacobian.solve([1.0, -2.0]);
        [
            a,
            b,
            c,
            d,
            converged.solved.residual_norm,
            converged.solved.condition,
        ]
        .map(f64::to_bits)
    }

    #[test]
    fn the_common_path_returns_what_newton_returns_bit_for_bit() {
        let mut common = 0;
        // The open branch around the turn, by continuation.
        let mut solutions = [[0.37, 1.26]; 360];
        let mut solution = solutions[0];
        for (k, slot) in solutions.iter_mut().enumerate() {
            let theta2 = (k as f64).to_radians();
            let options = NewtonOptions::default();
            let solved = newton(theta2, solution, &options, true, || None, four_bar(theta2));
            solution = solved.expect("the open branch").solved.value;
            *slot = solution;
        }
        for tolerance in [0.0, 1e-12, 1e-4] {
            let options = NewtonOptions::new(tolerance, 50);
            for (k, solution) in solutions.iter().enumerate() {
                let theta2 = (k as f64).to_radians();
                // From near the solution (a turn of the sines and cosines reaches every
                // iterate) to far from it (the common path leaves it to `newton`).
                for offset in [1e-9, 1e-6, 1e-4, 5e-4, 1e-2, 0.3, 2.0] {
                    let guess = [solution[0] + offset, solution[1] - offset];
                    let safeguarded =
                        newton(theta2, guess, &options, true, || None, four_bar(theta2));
                    let quick = newton_common(
                        guess,
                        &options,
                        true,
                        four_bar_started(theta2, guess),
                        Some,
                        || None,
                    );
                    if let Some(quick) = quick {
                        common += 1;
                        let safeguarded = safeguarded.expect("the common path solved it");
                        assert_eq!(bits(&quick), bits(&safeguarded), "θ2 = {theta2}");
                        assert_eq!(quick.solved.iterations, safeguarded.solved.iterations);
                        assert_eq!(
                            quick.at.payload.map(f64::to_bits),
                            safeguarded.at.payload.map(f64::to_bits)
                        );
                    }
                }
            }
        }
        // The solves from near the solution take the common path.
        assert!(common >= 3 * 360 * 4, "{common}");
    }

    /// A four-bar of any lengths at `theta2`.
    fn linkage(
        [l1, l2, l3, l4]: [f64; 4],
        theta2: f64,
    ) -> impl FnMut(&[f64; 2]) -> Linearisation<f64, 2, ()> {
        move |&[theta3, theta4]: &[f64; 2]| {
            let (s2, c2) = theta2.sin_cos();
            let (s3, c3) = theta3.sin_cos();
            let (s4, c4) = theta4.sin_cos();
            Linearisation {
                residual: [
                    l2 * c2 + l3 * c3 - l4 * c4 - l1,
                    l2 * s2 + l3 * s3 - l4 * s4,
                ],
                jacobian: [[-l3 * s3, l4 * s4], [l3 * c3, -l4 * c4]],
                scale: l1 + l2 + l3 + l4,
                weights: [1.0; 2],
                payload: (),
                columns: Columns::FromMatrix,
            }
        }
    }

    /// Example 1's position by the closed form, on the branch nearest `near`.
    fn closed_form(theta2: f64, near: [f64; 2]) -> [f64; 2] {
        let k = crate::Vec2::new(80.0 * theta2.cos() - 180.0, 80.0 * theta2.sin());
        let (w3, w4) = (crate::Vec2::new(200.0, 0.0), crate::Vec2::new(-150.0, 0.0));
        let [open, crossed] = [1.0, -1.0].map(|sign| {
            let (q3, q4, _, _) = crate::closed::two_angles(k, w3, w4, sign).unwrap();
            [q3, q4]
        });
        // Angles a turn apart are one angle.
        let distance = |q: [f64; 2]| 2.0 - (q[0] - near[0]).cos() - (q[1] - near[1]).cos();
        if distance(open) < distance(crossed) {
            open
        } else {
            crossed
        }
    }

    #[test]
    fn newton_solves_example_1_as_the_closed_form_does() {
        let theta2 = 60f64.to_radians();
        let guess = [15f64.to_radians(), 80f64.to_radians()];
        let exact = closed_form(theta2, guess);
        let scale = 610.0;
        // To the rounding floor (one more step after landing there), then to 1e-4 mm (the
        // seeds' tolerance: one step fewer), then to 1e-12 mm.
        for (tolerance, iterations, within) in [(0.0, 4, 1e-15), (1e-4, 3, 1e-9), (1e-12, 4, 1e-15)]
        {
            let options = NewtonOptions::new(tolerance, 20);
            let converged =
                newton(theta2, guess, &options, true, || None, four_bar(theta2)).unwrap();
            let solved = converged.solved;
            assert_eq!(solved.iterations, iterations, "tolerance {tolerance}");
            for (q, exact) in solved.value.iter().zip(exact) {
                assert!(
                    (q - exact).abs() <= within,
                    "{:?} != {exact:?}",
                    solved.value
                );
            }
            assert!(solved.residual_norm <= tolerance.max(16.0 * f64::EPSILON * scale));
            let [theta3, theta4] = solved.value;
            let condition = 1.0 / (theta4 - theta3).sin().abs();
            assert!((solved.condition - condition).abs() <= 1e-9 * condition);
            // The evaluation handed back is the one at the solution (to the rounding of its
            // turned sines and cosines).
            let fresh = four_bar(theta2)(&solved.value).residual;
            for (at, fresh) in converged.at.residual.iter().zip(fresh) {
                assert!((at - fresh).abs() <= 1e-12, "{at} != {fresh}");
            }
            // The open branch's orientation.
            assert_eq!(converged.jacobian.relative().signum(), -1.0);
        }
        // The crossed branch, from a guess near it.
        let crossed = newton(
            theta2,
            [-1.2, -2.1],
            &NewtonOptions::default(),
            true,
            || None,
            four_bar(theta2),
        )
        .unwrap()
        .solved
        .value;
        let exact = closed_form(theta2, crossed);
        assert!((crossed[0] - exact[0]).abs() + (crossed[1] - exact[1]).abs() <= 4e-15);
        assert!(exact[1] < 0.0);
    }

    #[test]
    fn newton_rejects_what_it_cannot_use() {
        let theta2 = 1.0;
        let guess = [0.4, 1.2];
        for tolerance in [-1.0, f64::NAN, f64::INFINITY] {
            let options = NewtonOptions::new(tolerance, 20);
            assert!(matches!(
                newton(theta2, guess, &options, true, || None, four_bar(theta2)),
                Err(Error::NonFinite {
                    quantity: "Newton tolerance"
                })
            ));
        }
        for guess in [[f64::NAN, 1.2], [0.4, f64::INFINITY]] {
            assert!(matches!(
                newton(
                    theta2,
                    guess,
                    &NewtonOptions::default(),
                    true,
                    || None,
                    four_bar(theta2)
                ),
                Err(Error::NonFinite {
                    quantity: "initial guess"
                })
            ));
        }
        // A non-finite residual or scale.
        let mut nan = |_: &[f64; 2]| Linearisation {
            residual: [f64::NAN, 0.0],
            jacobian: [[1.0, 0.0], [0.0, 1.0]],
            scale: 1.0,
            weights: [1.0; 2],
            payload: (),
            columns: Columns::FromMatrix,
        };
        assert!(matches!(
            newton(
                theta2,
                guess,
                &NewtonOptions::default(),
                true,
                || None,
                &mut nan
            ),
            Err(Error::NonFinite {
                quantity: "loop residual"
            })
        ));
        let infinite_scale = |_: &[f64; 2]| Linearisation {
            residual: [1.0, 0.0],
            jacobian: [[1.0, 0.0], [0.0, 1.0]],
            scale: f64::INFINITY,
            weights: [1.0; 2],
            payload: (),
            columns: Columns::FromMatrix,
        };
        assert!(matches!(
            newton(
                theta2,
                guess,
                &NewtonOptions::default(),
                true,
                || None,
                infinite_scale
            ),
            Err(Error::NonFinite {
                quantity: "loop residual"
            })
        ));
        // A singular Jacobian at the guess (θ3 = θ4: the coupler and rocker in line).
        assert!(matches!(
            newton(
                theta2,
                [0.5, 0.5],
                &NewtonOptions::default(),
                true,
                || None,
                four_bar(theta2)
            ),
            Err(Error::Singular { .. })
        ));
    }

    #[test]
    fn newton_stops_at_its_cap_and_says_why() {
        let theta2 = 60f64.to_radians();
        let far = [15f64.to_radians(), 80f64.to_radians()];
        let at_guess = four_bar(theta2)(&far).residual;
        let none = NewtonOptions::new(0.0, 0);
        assert_eq!(
            newton(theta2, far, &none, true, || None, four_bar(theta2)).map(|c| c.solved),
            Err(Error::NoConvergence {
                iterations: 0,
                residual_norm: max_abs(&at_guess)
            })
        );
        assert_eq!(
            newton(theta2, far, &none, true, || Some(false), four_bar(theta2)).map(|c| c.solved),
            Err(Error::CannotAssemble { input: theta2 })
        );
        assert!(matches!(
            newton(theta2, far, &none, true, || Some(true), four_bar(theta2)),
            Err(Error::NoConvergence { iterations: 0, .. })
        ));
        // A solution already, with no update allowed: accepted as it is.
        let solution = newton(
            theta2,
            far,
            &NewtonOptions::default(),
            true,
            || None,
            four_bar(theta2),
        )
        .unwrap()
        .solved
        .value;
        let accepted = newton(theta2, solution, &none, true, || None, four_bar(theta2)).unwrap();
        assert_eq!(accepted.solved.iterations, 0);
        assert_eq!(accepted.solved.value, solution);
        // Loops that cannot close (a ground of 10 with links of 1, 2 and 2): Newton stalls,
        // or runs out of updates, short of a root.
        let apart = [10.0, 1.0, 2.0, 2.0];
        let two = NewtonOptions::new(0.0, 2);
        // From near the closest approach (θ3 = 0, θ4 = π), where the iterates creep rather
        // than run away.
        let capped = newton(0.0, [0.2, 2.8], &two, true, || None, linkage(apart, 0.0));
        match capped {
            Err(Error::NoConvergence {
                iterations: 2,
                residual_norm,
            }) => assert!(
                (residual_norm - 5.007688608355575).abs() < 1e-9,
                "{residual_norm}"
            ),
            other => panic!("{other:?}"),
        }
        assert_eq!(
            newton(
                0.0,
                [0.2, 2.8],
                &two,
                true,
                || Some(false),
                linkage(apart, 0.0)
            )
            .map(|c| c.solved),
            Err(Error::CannotAssemble { input: 0.0 })
        );
        let options = NewtonOptions::default();
        for (assembles, cannot) in [(None, true), (Some(false), true), (Some(true), false)] {
            let stalled = newton(
                0.0,
                [0.3, 0.5],
                &options,
                true,
                || assembles,
                linkage(apart, 0.0),
            );
            match stalled {
                Err(Error::CannotAssemble { input }) if cannot => assert_eq!(input, 0.0),
                Err(Error::NoConvergence {
                    iterations,
                    residual_norm,
                }) if !cannot => {
                    assert!(iterations > 0 && iterations < 50);
                    assert!(residual_norm > 4.0);
                }
                other => panic!("{assembles:?}: {other:?}"),
            }
        }
    }

    /// Found by mutation testing: running out of iterations far from any root, after at least
    /// 16 of them, is decided as stagnation is, by Kantorovich's test.
    #[test]
    fn iterates_still_outside_kantorovichs_ball_at_a_cap_of_16_press_against_a_toggle() {
        // A Jacobian twice the residual's slope: each step halves the residual, which goes
        // on lowering and never reaches the floor. From x = (2^k, 0), after 16 steps
        // Kantorovich's h is |f|/2 = 2^(k−17).
        let creeping = |x: &[f64; 2]| Linearisation {
            residual: *x,
            jacobian: [[2.0, 0.0], [0.0, 2.0]],
            scale: 1.0,
            weights: [1.0; 2],
            payload: (),
            columns: Columns::FromMatrix,
        };
        let at = |k: i32| [2f64.powi(k), 0.0];
        assert_eq!(kantorovich(&creeping(&at(-1)), 1.0), 0.25);
        let solve = |k, cap| {
            let options = NewtonOptions::new(0.0, cap);
            // Lengths, not angles: 2^16 is a place, not a number of turns.
            let lengths = Orientation::Kept { angles: [false; 2] };
            newton(0.5, at(k), &options, lengths, || None, creeping).map(|c| c.solved)
        };
        let stalled = |iterations, k| Error::NoConvergence {
            iterations,
            residual_norm: 2f64.powi(k),
        };
        assert_eq!(solve(16, 16), Err(Error::CannotAssemble { input: 0.5 }));
        // h at 1/4 is within the ball; 15 iterations say nothing of the loops.
        assert_eq!(solve(15, 16), Err(stalled(16, -1)));
        assert_eq!(solve(16, 15), Err(stalled(15, 1)));
    }

    /// Found by mutation testing: a default solve from a guess already at the rounding floor
    /// takes one more step (no step led there, so nothing says it is the attainable
    /// accuracy), and the common path does the same.
    #[test]
    fn a_default_solve_takes_a_step_from_a_guess_already_at_the_floor() {
        // The residual x − (1, 2), with its exact Jacobian: one step lands on the root.
        let line = shifted(1.0);
        // A residual of 4ε, under the floor of 16ε.
        let near = [1.0 + 4.0 * f64::EPSILON, 2.0];
        let default = NewtonOptions::default();
        let solved = newton(0.0, near, &default, true, || None, line).unwrap();
        let common = newton_common(near, &default, true, line, Some, || None).unwrap();
        for solved in [solved.solved, common.solved] {
            assert_eq!(
                (solved.value, solved.iterations, solved.residual_norm),
                ([1.0, 2.0], 1, 0.0)
            );
        }
        // A stated tolerance is met at the floor at once.
        let stated = NewtonOptions::new(1e-9, 50);
        let solved = newton(0.0, near, &stated, true, || None, line).unwrap();
        assert_eq!((solved.solved.value, solved.solved.iterations), (near, 0));
    }

    /// Found by mutation testing: a default solve stops at the floor only after a step that
    /// started within `√ε·scale/κ` of the root, where the loops' curvature leaves less than
    /// the floor (see `polished`).
    #[test]
    fn a_default_solve_stops_at_the_floor_after_a_step_from_within_root_epsilon_over_kappa() {
        // The residual A·x, A = [[1, 16], [0, 1]] (κ = √257), with a Jacobian 1 + 2⁻³⁰ times
        // A: each step leaves 2⁻³⁰ of the error. From x = (√ε, 0) the first step lands
        // under the floor, but it started √257·√ε from the root, relative to a scale of 1:
        // one more step. Relative to a scale of 32, it started near enough.
        let skewed = |scale: f64| {
            move |x: &[f64; 2]| {
                let d = 1.0 + 2f64.powi(-30);
                Linearisation {
                    residual: [x[0] + 16.0 * x[1], x[1]],
                    jacobian: [[d, 16.0 * d], [0.0, d]],
                    scale,
                    weights: [1.0; 2],
                    payload: (),
                    columns: Columns::FromMatrix,
                }
            }
        };
        let guess = [f64::EPSILON.sqrt(), 0.0];
        let default = NewtonOptions::default();
        for (scale, iterations) in [(1.0, 2), (32.0, 1)] {
            let solved = newton(0.0, guess, &default, true, || None, skewed(scale)).unwrap();
            let common =
                newton_common(guess, &default, true, skewed(scale), Some, || None).unwrap();
            for solved in [solved.solved, common.solved] {
                assert_eq!(solved.iterations, iterations, "scale {scale}");
                assert!((solved.condition - 257f64.sqrt()).abs() < 1e-12);
                assert!(solved.residual_norm <= 16.0 * f64::EPSILON * scale);
            }
        }
    }

    #[test]
    fn a_step_that_overflows_is_an_error_saying_why() {
        // A finite residual, a Jacobian that factors, and a step of 1e318.
        let runaway = |_: &[f64; 2]| Linearisation {
            residual: [1e308, 1e308],
            jacobian: [[1e-10, 0.0], [0.0, 1e-10]],
            scale: 1.0,
            weights: [1.0; 2],
            payload: (),
            columns: Columns::FromMatrix,
        };
        let options = NewtonOptions::default();
        assert_eq!(
            newton(2.0, [0.0; 2], &options, true, || None, runaway).map(|c| c.solved),
            Err(Error::NonFinite {
                quantity: "Newton step"
            })
        );
        assert_eq!(
            newton(2.0, [0.0; 2], &options, true, || Some(false), runaway).map(|c| c.solved),
            Err(Error::CannotAssemble { input: 2.0 })
        );
        assert_eq!(
            newton(2.0, [0.0; 2], &options, true, || Some(true), runaway).map(|c| c.solved),
            Err(Error::NonFinite {
                quantity: "Newton step"
            })
        );
    }

    #[test]
    fn a_residual_no_step_lowers_is_a_stall_judged_by_kantorovich() {
        // The same residual everywhere: no step lowers it. Small beside the Jacobian
        // (Kantorovich's h = 1e-3): no convergence; large (h = 10): taken for a toggle.
        let flat = |size: f64| {
            move |_: &[f64; 2]| Linearisation {
                residual: [size, 0.0],
                jacobian: [[1.0, 0.0], [0.0, 1.0]],
                scale: 1.0,
                weights: [1.0; 2],
                payload: (),
                columns: Columns::FromMatrix,
            }
        };
        let options = NewtonOptions::default();
        assert_eq!(
            newton(0.5, [0.0; 2], &options, true, || None, flat(1e-3)).map(|c| c.solved),
            Err(Error::NoConvergence {
                iterations: 0,
                residual_norm: 1e-3
            })
        );
        assert_eq!(
            newton(0.5, [0.0; 2], &options, true, || None, flat(10.0)).map(|c| c.solved),
            Err(Error::CannotAssemble { input: 0.5 })
        );
        // h = 1/4 exactly (here h is the residual): still no convergence.
        assert_eq!(
            newton(0.5, [0.0; 2], &options, true, || None, flat(0.25)).map(|c| c.solved),
            Err(Error::NoConvergence {
                iterations: 0,
                residual_norm: 0.25
            })
        );
        assert_eq!(kantorovich(&flat(0.25)(&[0.0; 2]), 1.0), 0.25);
        assert_eq!(
            newton(0.5, [0.0; 2], &options, true, || Some(false), flat(1e-3)).map(|c| c.solved),
            Err(Error::CannotAssemble { input: 0.5 })
        );
        assert_eq!(
            newton(0.5, [0.0; 2], &options, true, || Some(true), flat(10.0)).map(|c| c.solved),
            Err(Error::NoConvergence {
                iterations: 0,
                residual_norm: 10.0
            })
        );
    }

    #[test]
    fn a_small_linkage_that_cannot_close_stalls_short_of_a_root() {
        // The linkage of `newton_stops_at_its_cap_and_says_why` a tenth the size: its
        // residual stalls near 0.5, far above the rounding floor (a few 1e-15).
        let apart = [1.0, 0.1, 0.2, 0.2];
        let options = NewtonOptions::default();
        assert_eq!(
            newton(
                0.0,
                [0.2, 2.8],
                &options,
                true,
                || None,
                linkage(apart, 0.0)
            )
            .map(|c| c.solved),
            Err(Error::CannotAssemble { input: 0.0 })
        );
        match newton(
            0.0,
            [0.2, 2.8],
            &options,
            true,
            || Some(true),
            linkage(apart, 0.0),
        ) {
            Err(Error::NoConvergence { residual_norm, .. }) => {
                assert!(
                    residual_norm > 0.4 && residual_norm < 0.6,
                    "{residual_norm}"
                )
            }
            other => panic!("{:?}", other.map(|c| c.solved)),
        }
    }

    /// Iterates that turn an angle through more than a whole turn from the guess have run
    /// away from it (a certified guess's stay within 2 rad): where no closed form can say,
    /// their stall, or the cap however low, is `CannotAssemble`.
    #[test]
    fn iterates_that_ran_a_whole_turn_from_the_guess_stall_at_a_toggle() {
        // The linkage that cannot close, from a guess whose first step turns θ4 by more than a
        // turn; from near its closest approach, the iterates creep and do not run away.
        let apart = [10.0, 1.0, 2.0, 2.0];
        let solve = |guess: [f64; 2], cap: u32, assembles: Option<bool>| {
            newton(
                0.0,
                guess,
                &NewtonOptions::new(0.0, cap),
                true,
                || assembles,
                linkage(apart, 0.0),
            )
            .map(|c| c.solved)
        };
        let cannot = Err(Error::CannotAssemble { input: 0.0 });
        assert_eq!(solve([0.3, 0.5], 2, None), cannot);
        assert_eq!(solve([0.3, 0.5], 50, None), cannot);
        // A closed form that says the guess's assembly closes decides, as ever.
        assert!(matches!(
            solve([0.3, 0.5], 2, Some(true)),
            Err(Error::NoConvergence { iterations: 2, .. })
        ));
        assert!(matches!(
            solve([0.2, 2.8], 2, None),
            Err(Error::NoConvergence { iterations: 2, .. })
        ));
        // Travel counts turns: the same guess a turn up runs away just as far.
        let up = [0.3 + core::f64::consts::TAU, 0.5 + core::f64::consts::TAU];
        assert_eq!(solve(up, 2, None), cannot);
        let angles = [true; 2];
        assert!(ran_away(&[0.0, 7.3], &[0.0, 1.0], &angles));
        assert!(ran_away(&[-6.3, 0.0], &[0.0, 0.0], &angles));
        assert!(!ran_away(&[6.2, -6.2], &[0.0, 0.0], &angles));
        assert!(!ran_away(&[100.0, 0.0], &[0.0, 0.0], &[false, true]));
        // Exactly a whole turn is not more than one; the travel is from the start.
        assert!(!ran_away(
            &[core::f64::consts::TAU, 0.0],
            &[0.0, 0.0],
            &angles
        ));
        assert!(!ran_away(&[7.3, 0.0], &[7.0, 0.0], &angles));
    }

    /// A closed form's angle continued from the guess's: within half a turn of it, unless the
    /// guess is beyond 16 rad, where it is the closed form's own, within a turn of zero.
    #[test]
    fn a_closed_forms_angle_is_carried_to_the_guesss_turn_unless_that_is_beyond_sixteen_rad() {
        use core::f64::consts::TAU;
        // Near the guess: the angle as it is.
        assert_eq!(angle_near(1.0, 0.5), 1.0);
        assert_eq!(angle_near(-1.0, -0.5), -1.0);
        // Across ±π from the guess: the turn nearer it.
        assert!((angle_near(-3.0, 3.0) - (TAU - 3.0)).abs() < 1e-15);
        assert!((angle_near(3.0, -3.0) - (3.0 - TAU)).abs() < 1e-15);
        // The guess two turns up: the angle two turns up.
        let up = angle_near(1.0, 1.0 + 2.0 * TAU);
        assert!((up - (1.0 + 2.0 * TAU)).abs() < 1e-14, "{up}");
        assert!((angle_near(0.9, 1.0 + 2.0 * TAU) - (0.9 + 2.0 * TAU)).abs() < 1e-14);
        // Beyond 16 rad: the closed form's own angle, bit for bit.
        assert_eq!(angle_near(0.3, 1000.1), 0.3);
        assert_eq!(angle_near(-2.5, -16.5), -2.5);
        let within = angle_near(-2.5, -15.5);
        assert!((within - (-2.5 - 2.0 * TAU)).abs() < 1e-14, "{within}");
        // Within 16 rad, but carried beyond 17: the closed form's own angle, as Newton takes
        // an iterate beyond 17 rad by whole turns.
        assert_eq!(angle_near(-0.363, 15.99), -0.363);
        assert_eq!(angle_near(0.363, -15.99), 0.363);
        let carried = angle_near(-0.363, 14.0);
        assert!((carried - (-0.363 + 2.0 * TAU)).abs() < 1e-14, "{carried}");
    }

    /// A guess that counts turns (a linkage that has turned a thousand times, its angles
    /// carried along) solves as the same guess within a turn of zero: at 6283 rad a float
    /// holds an angle only to 4.5e-13, and Newton stalled above its floor
    /// (`NoConvergence`), or stopped at an angle less accurate than stated.
    #[test]
    fn newton_takes_angles_beyond_sixteen_radians_by_whole_turns() {
        let theta2 = 60f64.to_radians();
        let options = NewtonOptions::default();
        let near = [0.4, 1.4];
        let plain = newton(theta2, near, &options, true, || None, four_bar(theta2)).unwrap();
        let exact = closed_form(theta2, near);
        let [theta3, theta4] = plain.solved.value;
        assert!((theta3 - exact[0]).abs() + (theta4 - exact[1]).abs() < 1e-14);
        let tau = core::f64::consts::TAU;
        for turns in [3.0, -3.0, 1e3, -1e3, 1e6, 1e12] {
            let guess = near.map(|q| q + turns * tau);
            let solved = newton(theta2, guess, &options, true, || None, four_bar(theta2))
                .unwrap_or_else(|e| panic!("{turns} turns: {e:?}"));
            for (q, e) in solved.solved.value.iter().zip(exact) {
                assert!((q - e).abs() < 1e-14, "{turns} turns: {q} against {e}");
            }
            // The common path leaves such a guess to `newton`.
            assert!(left_to_newton(theta2, guess, &options), "{turns} turns");
        }
        // Within 16 rad the angles are iterated as they are: the solution a turn up.
        let guess = near.map(|q| q + 2.0 * tau);
        let solved = newton(theta2, guess, &options, true, || None, four_bar(theta2)).unwrap();
        for (q, e) in solved.solved.value.iter().zip(exact) {
            assert!((q - 2.0 * tau - e).abs() < 1e-14, "{q} against {e}");
        }
        // Lengths are not angles: a length of 1e6 is left as it is.
        assert_eq!(within_a_turn([1e6, 20.0], [false, true])[0], 1e6);
        let [_, reduced] = within_a_turn([1e6, 20.0], [false, true]);
        assert!((reduced - (20.0 - 3.0 * tau)).abs() < 1e-14, "{reduced}");
        assert_eq!(within_a_turn([16.0, -16.0], [true; 2]), [16.0, -16.0]);
        // An iterate about to be returned is taken within a turn beyond ±17 rad (past the
        // common path's reach, a guess within ±16 moved by 2⁻¹⁰): an angle, not a length.
        assert!(!beyond_turns(&[16.9, -16.9], [true; 2]));
        assert!(beyond_turns(&[17.1, 0.0], [true; 2]));
        assert!(beyond_turns(&[0.0, -17.1], [true; 2]));
        assert!(!beyond_turns(&[1e6, 0.0], [false, true]));
        assert!(!beyond_turns(&[f64::NAN, 0.0], [true; 2]));
        assert!(
            within_a_turn([f64::NAN, f64::INFINITY], [true; 2])
                .iter()
                .all(|q| !q.is_finite())
        );
    }

    /// An iterate thrown thousands of turns out by a step through a nearly vanishing column
    /// (an inverted slider-crank whose slide passes the rocker's pivot, its slide's direction
    /// `θ4 + γ` taken of the exact sum) stalls there above the floor, the angle held only to
    /// its float's spacing: taken by whole turns, it solves (it was `NoConvergence`).
    #[test]
    fn an_iterate_stalled_many_turns_out_is_taken_by_whole_turns() {
        let [l1, l2, c, gamma] = [
            0.21710343491033884,
            4.267721272431143,
            -3.248335012819581e-5,
            -0.677156358032005,
        ];
        let theta2 = 1.2103985349065578_f64;
        let (s2, c2) = theta2.sin_cos();
        let mut turning = Turning::new();
        let slider = move |x: &[f64; 2]| {
            let [theta4, b] = *x;
            let (s4, c4) = turning.sin_cos(theta4);
            let (s, co) = crate::angle_sum::sin_cos_of_sum([gamma, theta4]);
            Linearisation {
                residual: [l2 * c2 - b * co - c * c4 - l1, l2 * s2 - b * s - c * s4],
                jacobian: [[b * s + c * s4, -co], [-(b * co + c * c4), -s]],
                scale: l1 + l2 + c.abs() + b.abs(),
                weights: [1.0; 2],
                payload: (),
                columns: Columns::FromMatrix,
            }
        };
        let kept = Orientation::Kept {
            angles: [true, false],
        };
        let guess = [16.07320220829527, 7.551825209634181];
        let solved = newton(
            theta2,
            guess,
            &NewtonOptions::default(),
            kept,
            || None,
            slider,
        )
        .unwrap()
        .solved;
        let [theta4, b] = solved.value;
        assert!(theta4.abs() <= core::f64::consts::PI, "{theta4}");
        assert!(
            solved.residual_norm <= 16.0 * f64::EPSILON * (l1 + l2 + b.abs()),
            "{solved:?}"
        );
    }

    #[test]
    fn newton_keeps_to_the_branch_of_its_guess_when_asked() {
        let theta2 = 60f64.to_radians();
        let guess = [-3.0, -2.6];
        let options = NewtonOptions::default();
        assert!(matches!(
            newton(theta2, guess, &options, true, || None, four_bar(theta2)),
            Err(Error::OtherBranch)
        ));
        let other = newton(theta2, guess, &options, false, || None, four_bar(theta2)).unwrap();
        let exact = closed_form(theta2, other.solved.value);
        let [theta3, theta4] = other.solved.value;
        let wrapped = |q: f64, exact: f64| (q - exact).sin().abs();
        assert!(wrapped(theta3, exact[0]) + wrapped(theta4, exact[1]) < 1e-14);
        assert!(left_to_newton(theta2, guess, &options));
    }

    /// Whether the common path, on the four-bar from `guess`, leaves the solve to [`newton`].
    fn left_to_newton(theta2: f64, guess: [f64; 2], options: &NewtonOptions<f64>) -> bool {
        newton_common(
            guess,
            options,
            true,
            four_bar_started(theta2, guess),
            Some,
            || None,
        )
        .is_none()
    }

    #[test]
    fn a_solution_is_on_another_assembly_only_where_a_loop_is_decided_both_times_and_opposite() {
        assert!(same_sides([1.0, -1.0], [2.0, -0.5]));
        assert!(!same_sides([1.0, -1.0], [1.0, 1.0]));
        assert!(!same_sides([1.0, 1.0], [-1.0, 1.0]));
        // Undecided (zero) at the guess or at the solution: a tangency, on both branches.
        assert!(same_sides([0.0, 1.0], [-1.0, 1.0]));
        assert!(same_sides([0.0, 1.0], [1.0, 1.0]));
        assert!(same_sides([1.0, -1.0], [0.0, 0.0]));
        assert!(same_sides::<f64, 0>([], []));
    }

    #[test]
    fn assemblies_are_told_apart_unless_a_turn_of_an_angle_moves_no_loop_beyond_rounding() {
        // Weighted, the first column is (1, −1): a turn moves the loops by 2π·1, exactly the
        // floor here, so that angle is undetermined; 2 would be beyond it.
        let at = Linearisation {
            residual: [0.0f64; 2],
            jacobian: [[0.5, 3.0], [-0.25, 1.0]],
            scale: 1.0,
            weights: [2.0, 4.0],
            payload: (),
            columns: Columns::FromMatrix,
        };
        let floor = core::f64::consts::TAU;
        let kept = Orientation::from(true);
        assert!(!kept.tells_apart(&at, floor));
        assert!(kept.tells_apart(&at, floor * (1.0 - f64::EPSILON)));
        // A length's column is no angle's: a turn of it means nothing.
        assert!(
            Orientation::Kept {
                angles: [false, true]
            }
            .tells_apart(&at, floor)
        );
        assert!(!Orientation::Free { angles: [true; 2] }.tells_apart(&at, 0.0));
        let wider = Linearisation {
            weights: [4.0, 8.0],
            ..at
        };
        assert!(kept.tells_apart(&wider, floor));
        assert_eq!(
            Orientation::<2>::from(false),
            Orientation::Free { angles: [true; 2] }
        );
    }

    #[test]
    fn a_stated_tolerance_needs_a_root_nearby() {
        // The loops cannot close, and the residual never gets within 6 mm: a tolerance of
        // 10 mm would accept it but for Kantorovich's test.
        let apart = [10.0, 1.0, 2.0, 2.0];
        let loose = NewtonOptions::new(10.0, 50);
        assert!(newton(0.0, [0.3, 0.5], &loose, true, || None, linkage(apart, 0.0)).is_err());
        // Kantorovich's h, from the Jacobian's columns at a unit scale: κ²·‖f‖·max/min.
        let at = Linearisation {
            residual: [3.0f64, 4.0],
            jacobian: [[2.0, 0.0], [0.0, 1.0]],
            scale: 0.0,
            weights: [1.0; 2],
            payload: (),
            columns: Columns::FromMatrix,
        };
        // Scaled by 1/4: columns 1/2 and 1/4, residual 5/4: h = κ²·(5/4)·(1/2)/(1/16).
        assert_eq!(kantorovich(&at, 1.0), 10.0);
        assert_eq!(kantorovich(&at, 2.0), 40.0);
        assert_eq!(kantorovich_aside(at.residual, at.jacobian, 2.0), 40.0);
        let tiny = Linearisation {
            residual: [3e-300, 4e-300],
            jacobian: [[2e-300, 0.0], [0.0, 1e-300]],
            ..at
        };
        assert!((kantorovich(&tiny, 1.0) - 10.0).abs() < 1e-12);
    }

    #[test]
    fn a_default_solve_is_stagnated_only_above_the_rounding_floor() {
        let theta2 = 60f64.to_radians();
        let guess = [15f64.to_radians(), 80f64.to_radians()];
        let default = NewtonOptions::default();
        let mut converged =
            newton(theta2, guess, &default, true, || None, four_bar(theta2)).unwrap();
        assert!(!stagnated(&converged, &default));
        let floor = 16.0 * f64::EPSILON * converged.at.scale;
        converged.at.residual = [floor, -floor];
        assert!(!stagnated(&converged, &default));
        converged.at.residual = [0.0, -2.0 * floor];
        assert!(stagnated(&converged, &default));
        assert!(!stagnated(&converged, &NewtonOptions::new(1e-4, 50)));
        converged.at.weights = [1.0, 0.25];
        assert!(!stagnated(&converged, &default));
    }

    #[test]
    fn norms_weights_and_finiteness() {
        assert_eq!(weighted_norm(&[1.0, -3.0], &[2.0, 0.5]), 2.0);
        assert_eq!(weighted_norm(&[-1.0, 3.0], &[0.5, 2.0]), 6.0);
        assert!(weighted_norm(&[f64::NAN, 3.0], &[1.0, 1.0]).is_nan());
        assert!(weighted_norm(&[3.0, f64::NAN], &[1.0, 1.0]).is_nan());
        assert_eq!(
            weighted_norm(&[f64::INFINITY, 1.0], &[1.0, 1.0]),
            f64::INFINITY
        );
        assert_eq!(max_abs(&[1.0, -3.0, 2.0]), 3.0);
        assert!(max_abs(&[1.0, f64::NAN, 2.0]).is_nan());
        assert!(max_abs(&[f64::NAN, 1.0]).is_nan());
        assert_eq!(loop_weight(10.0, 4.0), 2.5);
        assert_eq!(loop_weight(10.0, 0.0), 1.0);
        assert_eq!(loop_weight(10.0, -1.0), 1.0);
        assert!(all_finite::<f64>(&[]));
        assert!(all_finite(&[1.0, -2.0]));
        // A sum that overflows from finite values: each is looked at.
        assert!(all_finite(&[f64::MAX, f64::MAX]));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(!all_finite(&[1.0, bad]));
            assert!(!all_finite(&[bad]));
            assert!(!each_finite(&[1.0, bad]));
        }
        assert!(each_finite(&[1.0, f64::MAX]));
        assert_eq!(check_finite(&[(1.0, "a"), (2.0, "b")]), Ok(()));
        assert_eq!(
            check_finite(&[(1.0, "a"), (f64::NAN, "b"), (f64::INFINITY, "c")]),
            Err(Error::NonFinite { quantity: "b" })
        );
        let names = ["a", "b", "c"];
        assert_eq!(check_all_finite([1.0, 2.0, 3.0], &names), Ok(()));
        assert_eq!(check_all_finite::<f64, 0>([], &[]), Ok(()));
        assert_eq!(check_all_finite([f64::MAX, f64::MAX, 0.0], &names), Ok(()));
        assert_eq!(
            check_all_finite([1.0, f64::INFINITY, f64::NAN], &names),
            Err(Error::NonFinite { quantity: "b" })
        );
        assert_eq!(
            blame_non_finite([f64::NAN, 1.0, 1.0], &names),
            Err(Error::NonFinite { quantity: "a" })
        );
        assert_eq!(finite([1.0, 2.0], "rates"), Ok([1.0, 2.0]));
        assert_eq!(
            finite([1.0, f64::NAN], "rates"),
            Err(Error::NonFinite { quantity: "rates" })
        );
    }

    #[test]
    fn options_and_solutions_carry_what_they_were_given() {
        let default = NewtonOptions::<f64>::default();
        assert_eq!(default, NewtonOptions::new(0.0, 50));
        assert_eq!(default.accuracy, Accuracy::required());
        let loose = Accuracy {
            position: 1.0,
            velocity: 2.0,
            acceleration: 3.0,
        };
        let options = NewtonOptions::new(1e-4, 7).with_accuracy(loose);
        assert_eq!((options.tolerance, options.max_iterations), (1e-4, 7));
        assert_eq!(options.accuracy, loose);
        let solved = Solved {
            value: 2,
            iterations: 3,
            residual_norm: 0.5,
            condition: 4.0,
        };
        assert_eq!(
            solved.map(|v| v * 10),
            Solved {
                value: 20,
                iterations: 3,
                residual_norm: 0.5,
                condition: 4.0
            }
        );
    }

    #[test]
    fn rotations_and_sines_are_good_to_rounding() {
        let limit = TURN_LIMIT;
        for angle in [0.3f64, -2.0, 3.1, 1e-3] {
            let (sin, cos) = angle.sin_cos();
            for step in [limit, -limit, 0.5 * limit, 1e-7, 0.0] {
                let (s, c) = rotate(sin, cos, step);
                let (want_s, want_c) = (angle + step).sin_cos();
                assert!((s - want_s).abs() <= 4.0 * f64::EPSILON, "{angle} + {step}");
                assert!((c - want_c).abs() <= 4.0 * f64::EPSILON, "{angle} + {step}");
            }
            let mut turning = Turning::new();
            assert_eq!(turning.sin_cos(angle), (sin, cos));
            let (s, c) = turning.sin_cos(angle + 0.5 * limit);
            assert_eq!((s, c), rotate(sin, cos, (angle + 0.5 * limit) - angle));
            // Farther than a turn: afresh.
            assert_eq!(
                turning.sin_cos(angle + 2.0 * limit),
                (angle + 2.0 * limit).sin_cos()
            );
            for x in [angle, 100.0 * angle] {
                let (s, c) = sin_cos(x);
                assert!((s - x.sin()).abs() <= 2.0 * f64::EPSILON);
                assert!((c - x.cos()).abs() <= 2.0 * f64::EPSILON);
            }
        }
        // From zero, the turned sine is the step's own, to rounding of itself (the series'
        // fifth-order term is some 30 units of it at the largest step).
        for step in [limit, -limit, 0.75 * limit, 0.3 * limit] {
            let (s, c) = rotate(0.0, 1.0, step);
            assert!(
                (s - step.sin()).abs() <= 2.0 * f64::EPSILON * step.abs(),
                "{step}"
            );
            assert!((c - step.cos()).abs() <= 2.0 * f64::EPSILON, "{step}");
        }
        // Beyond the fast one's limit, and NaN: the platform's.
        assert_eq!(sin_cos(1e300), 1e300f64.sin_cos());
        assert!(sin_cos(f64::NAN).0.is_nan());
        assert_eq!(fresh_sin_cos([1e300, 1.0]), platform_sin_cos([1e300, 1.0]));
        assert_eq!(
            fresh_sin_cos([1e300, -1e300]),
            platform_sin_cos([1e300, -1e300])
        );
        let (sines, cosines) = fresh_sin_cos([0.3, -2.0]);
        assert!((sines[1] - (-2f64).sin()).abs() <= 2.0 * f64::EPSILON);
        assert!((cosines[0] - 0.3f64.cos()).abs() <= 2.0 * f64::EPSILON);
        assert_eq!(
            Turnings::<f64, 2>::default().sin_cos([0.3, -2.0]),
            (sines, cosines)
        );
        assert_eq!(Turning::<f64>::default().sin_cos(0.3), 0.3f64.sin_cos());
        assert_eq!(
            turned([0.0], [0.0], [1.0], [limit]),
            Some(([limit.sin()], [limit.cos()])).map(|_| {
                let (s, c) = rotate(0.0, 1.0, limit);
                ([s], [c])
            })
        );
        assert_eq!(turned([0.0], [0.0], [1.0], [2.0 * limit]), None);
    }

    #[test]
    fn generated_code_takes_the_fast_sine_or_the_platform_s_as_its_type_says() {
        // Within the fast one's limit the two differ in the last bit for some of these
        // angles: each type must take its own, in f64 (with std) the fast one, in f32 the
        // platform's.
        fn expected<T: Real>(x: T) -> (T, T) {
            if T::INLINE_SIN_COS {
                crate::fast::sin_cos(x)
            } else {
                x.sin_cos()
            }
        }
        for i in -400..=400 {
            let x = f64::from(i) * 0.0123;
            assert_eq!(sin_cos(x), expected(x), "{x}");
            let x = x as f32;
            assert_eq!(sin_cos(x), expected(x), "{x}");
        }
    }

    #[test]
    fn the_common_path_accepts_a_guess_that_is_a_solution_on_either_branch() {
        // Met at the guess (a tolerance of 1e-4): no update, on the branch of the guess,
        // whichever orientation that branch has.
        let theta2 = 60f64.to_radians();
        let options = NewtonOptions::new(1e-4, 20);
        for guess in [[0.4, 1.2], [-1.2, -2.1]] {
            let solution = newton(
                theta2,
                guess,
                &NewtonOptions::default(),
                true,
                || None,
                four_bar(theta2),
            )
            .unwrap()
            .solved
            .value;
            let quick = newton_common(
                solution,
                &options,
                true,
                four_bar_started(theta2, solution),
                Some,
                || None,
            )
            .expect("the common path");
            assert_eq!(quick.solved.iterations, 0);
            assert_eq!(quick.solved.value, solution);
        }
    }

    /// `evaluate` with both components weighted 1/2.
    fn halved(
        mut evaluate: impl FnMut(&[f64; 2]) -> Linearisation<f64, 2, [f64; 4]>,
    ) -> impl FnMut(&[f64; 2]) -> Linearisation<f64, 2, [f64; 4]> {
        move |x: &[f64; 2]| Linearisation {
            weights: [0.5, 0.5],
            ..evaluate(x)
        }
    }

    #[test]
    fn the_common_path_reads_the_residual_weighted() {
        // Example 1 with its two components weighted 1/2 (as a small loop's beside a large
        // one): the common path solves it as Newton does, to the bit.
        let theta2 = 60f64.to_radians();
        for offset in [1e-6, 1e-4] {
            let guess = [0.3762517082634387 + offset, 1.2590395150231335 - offset];
            for options in [NewtonOptions::default(), NewtonOptions::new(1e-9, 50)] {
                let safeguarded = newton(
                    theta2,
                    guess,
                    &options,
                    true,
                    || None,
                    halved(four_bar(theta2)),
                )
                .unwrap();
                let quick = newton_common(
                    guess,
                    &options,
                    true,
                    halved(four_bar_started(theta2, guess)),
                    Some,
                    || None,
                )
                .expect("the common path");
                assert_eq!(bits(&quick), bits(&safeguarded));
            }
        }
    }

    /// Found by mutation testing: where a weight alone puts the residual above the floor,
    /// the common path does not accept it either.
    #[test]
    fn the_common_path_weighs_the_residual_where_the_weight_decides() {
        // The residual x − (1, 2), 4ε at the guess, weighted 8: 32ε, above the floor of 16ε
        // (unweighted, or divided by the weight, it is under it). With a stated tolerance
        // of ε the guess is not accepted, and one step lands on the root.
        let weighted = shifted(8.0);
        let near = [1.0 + 4.0 * f64::EPSILON, 2.0];
        let options = NewtonOptions::new(f64::EPSILON, 50);
        let safeguarded = newton(0.0, near, &options, true, || None, weighted).unwrap();
        let quick = newton_common(near, &options, true, weighted, Some, || None).unwrap();
        for solved in [safeguarded.solved, quick.solved] {
            assert_eq!((solved.value, solved.iterations), ([1.0, 2.0], 1));
        }
    }

    #[test]
    fn the_common_path_leaves_the_unusual_to_newton() {
        let options = NewtonOptions::default();
        let fallback = || None;
        // A guess that is not finite, a negative tolerance, no updates allowed.
        assert!(
            newton_common(
                [f64::NAN, 1.0],
                &options,
                true,
                four_bar(1.0),
                Some,
                fallback
            )
            .is_none()
        );
        let negative = NewtonOptions::new(-1.0, 50);
        assert!(
            newton_common([0.4, 1.2], &negative, true, four_bar(1.0), Some, fallback).is_none()
        );
        let none = NewtonOptions::new(0.0, 0);
        assert!(newton_common([0.4, 1.2], &none, true, four_bar(1.0), Some, fallback).is_none());
    }

    #[test]
    fn the_common_path_leaves_a_step_that_does_not_lower_the_residual_to_newton() {
        // The residual grows on both components over the first full step, then vanishes:
        // the common path must not take that step.
        let rising = |x: &[f64; 2]| {
            let residual = match x[0] {
                0.0 => [1.0, 1.0],
                -1.0 => [2.0, 2.0],
                _ => [0.0, 0.0],
            };
            Linearisation {
                residual,
                jacobian: [[1.0, 0.0], [0.0, 1.0]],
                scale: 1.0,
                weights: [1.0; 2],
                payload: (),
                columns: Columns::FromMatrix,
            }
        };
        let options = NewtonOptions::default();
        assert!(newton_common([0.0; 2], &options, false, rising, Some, || None).is_none());
        // Nor one that leaves it as it was.
        let level = |x: &[f64; 2]| Linearisation {
            residual: if x[0] < -1.5 { [0.0; 2] } else { [1.0, 1.0] },
            ..rising(&[0.0; 2])
        };
        assert!(newton_common([0.0; 2], &options, false, level, Some, || None).is_none());
        // Read weighted: a rise from 4·1 to 4·2.
        let heavy = |x: &[f64; 2]| Linearisation {
            weights: [4.0; 2],
            ..rising(x)
        };
        assert!(newton_common([0.0; 2], &options, false, heavy, Some, || None).is_none());
        // Newton itself halves that step instead, to a point the residual is lower at.
        let halved = newton(0.0, [0.0; 2], &options, false, || None, rising).unwrap();
        assert_eq!(halved.solved.value, [-0.5, -0.5]);
    }

    #[test]
    fn the_common_path_leaves_another_orientation_and_a_scale_that_is_not_finite_to_newton() {
        // x0³ − x0 from 0.5, where the Jacobian's determinant 3·x0² − 1 is negative: one
        // full step lands exactly on the root −1 (the residual falls from 0.375 to 0), where
        // the determinant is positive. Asked to keep the orientation, the common path must
        // not hand that root on; without the ask, it may.
        let cubic = |scale: f64| {
            move |x: &[f64; 2]| Linearisation {
                residual: [x[0] * x[0] * x[0] - x[0], x[1]],
                jacobian: [[3.0 * x[0] * x[0] - 1.0, 0.0], [0.0, 1.0]],
                scale,
                weights: [1.0; 2],
                payload: (),
                columns: Columns::FromMatrix,
            }
        };
        let options = NewtonOptions::default();
        let guess = [0.5, 0.0];
        assert!(newton_common(guess, &options, true, cubic(1.0), Some, || None).is_none());
        let flipped = newton_common(guess, &options, false, cubic(1.0), Some, || None).unwrap();
        assert_eq!(flipped.solved.value, [-1.0, 0.0]);
        // A scale that is not finite sets no floor: even a guess that is a root is left to
        // Newton, which says why.
        for scale in [f64::INFINITY, f64::NAN] {
            let root = [1.0, 0.0];
            assert!(newton_common(root, &options, true, cubic(scale), Some, || None).is_none());
        }
    }

    #[test]
    fn turnings_rotate_as_a_turning_does() {
        let mut turnings = Turnings::<f64, 2>::new();
        let mut turning = [Turning::<f64>::new(), Turning::new()];
        for angles in [
            [0.3, -2.0],
            [0.3001, -2.0002],
            [0.30010001, -2.00020001],
            [1.0, -2.0],
        ] {
            let (sines, cosines) = turnings.sin_cos(angles);
            for k in 0..2 {
                let (s, c) = turning[k].sin_cos(angles[k]);
                // Fresh pairs differ by rounding (the platform's against `fast::sin_cos`).
                assert!((s - sines[k]).abs() <= 2.0 * f64::EPSILON);
                assert!((c - cosines[k]).abs() <= 2.0 * f64::EPSILON);
            }
        }
        // The common path's: the fresh pairs as they are, then turned the same way (one
        // angle's, as a `Turning` turns it), and NaN beyond a turn.
        let mut started = Started::<f64, 2>::at([0.3, -2.0]);
        let mut one = Started::<f64, 1>::at([0.3]);
        let (mut turnings, mut turning) = (Turnings::<f64, 2>::new(), Turning::<f64>::new());
        for angles in [[0.3, -2.0], [0.3001, -2.0002], [0.30010001, -2.00020001]] {
            let (sines, cosines) = turnings.sin_cos(angles);
            assert_eq!(started.sin_cos(angles), (sines, cosines));
            let (s, c) = turning.sin_cos(angles[0]);
            assert_eq!(one.sin_cos([angles[0]]), ([s], [c]));
        }
        let (sines, cosines) = started.sin_cos([1.0, -2.0]);
        assert!(sines.iter().chain(&cosines).all(|v| v.is_nan()));
        let (sines, _) = Turnings::<f64, 2>::new().sin_cos([2e6, f64::NAN]);
        assert_eq!(sines[0], 2e6f64.sin());
        assert!(sines[1].is_nan());
    }

    /// Found by mutation testing: the common path's first evaluation takes the fresh pairs as
    /// they are, the bits [`Turnings`]' and [`Turning`]'s first evaluation takes, the sign of
    /// a zero included. Turned through a step of zero instead, they would be the same values
    /// but for the sine of −0, which would come out +0 (`−0·1 + 1·0`).
    #[test]
    fn the_common_paths_first_pairs_are_the_fresh_ones_to_the_bit() {
        let bits = |(s, c): ([f64; 2], [f64; 2])| (s.map(f64::to_bits), c.map(f64::to_bits));
        for angles in [[-0.0, 0.0], [0.0, -0.0], [-0.0, -1.5], [0.3, -2.0]] {
            let fresh = Turnings::<f64, 2>::new().sin_cos(angles);
            let started = Started::<f64, 2>::at(angles).sin_cos(angles);
            assert_eq!(bits(started), bits(fresh), "{angles:?}");
        }
        let (sines, cosines) = Started::<f64, 2>::at([-0.0, 0.0]).sin_cos([-0.0, 0.0]);
        assert_eq!(
            sines.map(f64::to_bits),
            [(-0.0f64).to_bits(), 0.0f64.to_bits()]
        );
        assert_eq!(cosines, [1.0, 1.0]);
        // One angle's, the platform's `sin_cos` as a `Turning` computes it.
        let (sin, cos) = Turning::<f64>::new().sin_cos(-0.0);
        let ([s], [c]) = Started::<f64, 1>::at([-0.0]).sin_cos([-0.0]);
        assert_eq!((s.to_bits(), c), (sin.to_bits(), cos));
        assert_eq!(s.to_bits(), (-0.0f64).to_bits());
    }

    /// A `Converged` at a residual of `residual` (weights `weights`, loops' magnitudes summing
    /// to `scale`) and condition `condition`.
    fn converged_at(
        residual: [f64; 2],
        weights: [f64; 2],
        scale: f64,
        condition: f64,
    ) -> Converged<f64, 2, ()> {
        let jacobian = [[1.0, 0.0], [0.0, 1.0]];
        Converged {
            solved: Solved {
                value: [0.0; 2],
                iterations: 1,
                residual_norm: residual[0].abs().max(residual[1].abs()),
                condition,
            },
            at: Linearisation {
                residual,
                jacobian,
                scale,
                weights,
                payload: (),
                columns: Columns::FromMatrix,
            },
            jacobian: Factored::new(jacobian).unwrap(),
        }
    }

    #[test]
    fn a_position_is_known_to_its_floor_or_to_the_residual_above_it() {
        let e = f64::EPSILON;
        // On the floor, 16·ε of the loops' magnitudes (here 10), each component weighted:
        // 2·κ·16·ε, the contract's 32·ε·κ.
        let floor = converged_at([1e-15, -3e-14], [1.0, 1.0], 10.0, 3.0);
        assert_eq!(floor.position_accuracy(10.0), 2.0 * 3.0 * 16.0 * e);
        assert_eq!(floor.position_accuracy_at(5.0, 10.0), 2.0 * 5.0 * 16.0 * e);
        // A condition below 1 counts as 1.
        assert_eq!(floor.position_accuracy_at(0.5, 10.0), 2.0 * 16.0 * e);
        // Above it in one component (the other on it): the weighted residual over the
        // magnitudes, 2·κ·r/Σ|r|. (A weight below 1, which no mechanism's is, makes a loop
        // larger than the scale: 10/0.5, taken as the size here.)
        let above = converged_at([1e-15, 4e-9], [1.0, 0.5], 10.0, 3.0);
        assert_eq!(
            above.position_accuracy(20.0),
            2.0 * 3.0 * (4e-9 * 0.5 / 10.0)
        );
        let first = converged_at([2e-9, 1e-15], [1.0, 0.5], 10.0, 3.0);
        assert_eq!(first.position_accuracy(20.0), 2.0 * 3.0 * (2e-9 / 10.0));
        // Just above the floor, weighted under it: on it.
        let weighted = converged_at([1e-15, 5e-14], [1.0, 0.5], 10.0, 3.0);
        assert_eq!(weighted.position_accuracy(20.0), 2.0 * 3.0 * 16.0 * e);
        // Loops whose magnitudes exceed the declared lengths (here 10 against 4): the error
        // relative to those lengths is that much larger. Two loops, the larger of magnitudes
        // 10/2 = 5 (weight 2) and 10/1.25 = 8 (weight 1.25): 8/4 times the error.
        assert_eq!(
            floor.position_accuracy(4.0),
            2.0 * 3.0 * 16.0 * e * (10.0 / 4.0)
        );
        // Where the declaration rules a longer loop out, nothing is stretched.
        assert_eq!(
            floor.position_accuracy_within_size_at(3.0),
            2.0 * 3.0 * 16.0 * e
        );
        let two_loops = converged_at([1e-15, -1e-14], [2.0, 1.25], 10.0, 3.0);
        assert_eq!(
            two_loops.position_accuracy(4.0),
            2.0 * 3.0 * 16.0 * e * (8.0 / 4.0)
        );
        // Declared lengths longer than every loop's magnitudes: the error as it is.
        assert_eq!(two_loops.position_accuracy(9.0), 2.0 * 3.0 * 16.0 * e);
        // As a length for telling assemblies apart: 32·ε·κ of the size for any residual up to
        // the four floors a default solve accepts; the residual's own estimate above them.
        assert_eq!(floor.error_length(10.0), 2.0 * 3.0 * 16.0 * e * 10.0);
        let stalled = converged_at([1e-15, 3.0 * 16.0 * e * 10.0], [1.0, 1.0], 10.0, 3.0);
        assert_eq!(stalled.error_length(10.0), 2.0 * 3.0 * 16.0 * e * 10.0);
        assert!(stalled.position_accuracy(10.0) > 2.0 * 3.0 * 16.0 * e);
        let loose = converged_at([1e-15, 5.0 * 16.0 * e * 10.0], [1.0, 1.0], 10.0, 3.0);
        assert_eq!(
            loose.error_length(10.0),
            2.0 * 3.0 * (5.0 * 16.0 * e * 10.0 / 10.0) * 10.0
        );
        // An undefined size leaves it not a number, or infinite: no rates' estimate holds.
        assert!(
            !converged_at([1e-9, 1e-9], [1.0, 1.0], 0.0, 3.0)
                .position_accuracy(10.0)
                .is_finite()
        );
    }

    #[test]
    fn a_guess_is_certified_within_the_kantorovich_ball_it_estimates() {
        // Two unit columns, relative determinant 1: certified where 64·N⁴·d²·L²·‖J‖² =
        // 64·16·d²·1·2 ≤ 1, d ≤ 1/√2048 ≈ 0.0221.
        let solution = [0.3, -1.2];
        let at = |d: f64| [0.3 + d * 0.6, -1.2 - d * 0.8];
        let unit = [1.0, 1.0];
        let edge = 1.0 / 2048f64.sqrt();
        assert!(certified_start(&solution, &solution, unit, 1.0));
        assert!(certified_start(&at(0.99 * edge), &solution, unit, 1.0));
        assert!(!certified_start(&at(1.01 * edge), &solution, unit, 1.0));
        // Half the relative determinant: a quarter of the radius (β² is four times as big).
        assert!(certified_start(&at(0.24 * edge), &solution, unit, 0.5));
        assert!(!certified_start(&at(0.26 * edge), &solution, unit, 0.5));
        assert!(certified_start(&at(0.24 * edge), &solution, unit, -0.5));
        // Columns of squared norms 4 and 1: L² = 4, ‖J‖² = 5, min‖column‖² = 1, so
        // 64·16·d²·20 ≤ 1; the same scaled by 9 (a mechanism three times the size) alike.
        let uneven = 1.0 / (1024.0f64 * 20.0).sqrt();
        for factor in [1.0, 9.0] {
            let columns = [4.0 * factor, factor];
            assert!(certified_start(&at(0.99 * uneven), &solution, columns, 1.0));
            assert!(!certified_start(
                &at(1.01 * uneven),
                &solution,
                columns,
                1.0
            ));
            let swapped = [factor, 4.0 * factor];
            assert!(certified_start(&at(0.99 * uneven), &solution, swapped, 1.0));
            assert!(!certified_start(
                &at(1.01 * uneven),
                &solution,
                swapped,
                1.0
            ));
        }
        // Three unit columns: N⁴ = 81, ‖J‖² = 3, d ≤ 1/√(64·81·3).
        let three = [0.3, -1.2, 2.0];
        let edge3 = 1.0 / (64.0f64 * 81.0 * 3.0).sqrt();
        let near3 = |d: f64| [0.3, -1.2, 2.0 + d];
        assert!(certified_start(&near3(0.99 * edge3), &three, [1.0; 3], 1.0));
        assert!(!certified_start(
            &near3(1.01 * edge3),
            &three,
            [1.0; 3],
            1.0
        ));
        // A zero column, a singular Jacobian, or a guess not finite certifies nothing.
        assert!(!certified_start(&at(1e-9), &solution, [1.0, 0.0], 1.0));
        assert!(!certified_start(&at(1e-9), &solution, unit, 0.0));
        assert!(!certified_start(&[f64::NAN, -1.2], &solution, unit, 1.0));
        assert!(!certified_start(
            &[f64::INFINITY, -1.2],
            &solution,
            unit,
            1.0
        ));
    }

    #[test]
    fn a_guess_kantorovich_certifies_says_where_its_root_is_alone() {
        // J = I: β = ‖I‖ = √2 (Frobenius), L = 1, η = |f|: h = √2·|f| ≤ 1/2 for |f| ≤ 0.3536,
        // and the guess's root is alone within 1/(β·L) = 0.7071.
        let unit = [[1.0, 0.0], [0.0, 1.0]];
        let origin = [0.0, 0.0];
        assert!(guess_certified(&[0.35, 0.0], &unit));
        assert!(guess_certified(&[0.0, -0.35], &unit));
        assert!(!guess_certified(&[0.36, 0.0], &unit));
        assert!(!root_elsewhere(&[0.1, 0.0], &unit, &origin, &[0.70, 0.0]));
        assert!(root_elsewhere(&[0.1, 0.0], &unit, &origin, &[0.72, 0.0]));
        assert!(root_elsewhere(&[0.1, 0.0], &unit, &origin, &[0.0, -0.72]));
        assert!(root_elsewhere(&[0.1, 0.0], &unit, &[1.0, 1.0], &[1.5, 1.5]));
        assert!(!root_elsewhere(
            &[0.1, 0.0],
            &unit,
            &[1.0, 1.0],
            &[1.4, 1.5]
        ));
        // Not certified: nothing says which root is the guess's.
        assert!(!root_elsewhere(&[0.4, 0.0], &unit, &origin, &[5.0, 0.0]));
        // J = 2·I: β = √2/2, L = 2, η = |f|/2: h = |f|/√2, the same radius.
        let double = [[2.0, 0.0], [0.0, 2.0]];
        assert!(guess_certified(&[0.70, 0.0], &double));
        assert!(!guess_certified(&[0.72, 0.0], &double));
        assert!(!root_elsewhere(&[0.1, 0.0], &double, &origin, &[0.70, 0.0]));
        assert!(root_elsewhere(&[0.1, 0.0], &double, &origin, &[0.72, 0.0]));
        // Columns of lengths 1 and 3 (L = 3), J⁻¹ = diag(1, 1/3): β² = 10/9, η = |f₁|/3.
        let uneven = [[1.0, 0.0], [0.0, 3.0]];
        let edge = 0.5 * 3.0 / (3.0 * (10.0f64 / 9.0).sqrt());
        assert!(guess_certified(&[0.0, 0.99 * edge], &uneven));
        assert!(!guess_certified(&[0.0, 1.01 * edge], &uneven));
        // A singular Jacobian, or a residual not finite, certifies nothing.
        assert!(!guess_certified(&[0.0, 0.0], &[[1.0, 2.0], [2.0, 4.0]]));
        assert!(!guess_certified(&[f64::NAN, 0.0], &unit));
        assert!(!root_elsewhere(
            &[f64::NAN, 0.0],
            &unit,
            &origin,
            &[5.0, 0.0]
        ));
    }
}
