//! Walking a mechanism through its motion on one assembly branch.

use crate::{Error, NewtonOptions, Order, Real, Solved};

/// What the sweep needs of a mechanism: generated code implements it for every declaration
/// that asks for velocities, with positions as arrays of the unknowns in declaration order.
pub trait Kinematics<T: Real, const N: usize> {
    /// Newton-Raphson from `guess` (the generated `position`).
    fn solve_near(
        &self,
        input: T,
        guess: [T; N],
        options: &NewtonOptions<T>,
    ) -> Result<Solved<[T; N], T>, Error<T>>;

    /// `dq/d(input)` at a solved position (the generated `velocity` at unit input rate).
    fn slope(&self, input: T, position: [T; N]) -> Result<[T; N], Error<T>>;

    /// Whether two solved positions are on the same assembly branch (by the generated
    /// `branch_of`; always true for a mechanism without closed-form branches).
    fn same_branch(&self, input_a: T, a: [T; N], input_b: T, b: [T; N]) -> bool;

    /// [`slope`](Self::slope), with how far each unknown of the solved `position` may lie from
    /// the loops' root: `Σ_k |J⁻¹_ik|·e_k` for each residual component's error `e_k`, its
    /// value there plus the rounding of its evaluation (generated code: 4·ε of its own
    /// loop's declared lengths), in the unknown's own units. By default (a hand
    /// implementation) zeros: nothing known.
    ///
    /// Generated code computes both from one factored Jacobian. Where an unknown's link
    /// shrinks to nothing (a slide through its pivot, the isosceles inverted slider-crank's
    /// change point), the loops stop fixing its angle, and a position that closes them to
    /// rounding may hold any angle there: the sweep must not read a path from such positions.
    fn slope_within(&self, input: T, position: [T; N]) -> Result<([T; N], [T; N]), Error<T>> {
        Ok((self.slope(input, position)?, [T::zero(); N]))
    }

    /// What counts as a unit of each unknown for the sweep's tests (positive and finite): a
    /// radian for an angle, the sum of the loops' declared lengths for a length (generated
    /// code); by default 1 for every unknown.
    fn units(&self) -> [T; N] {
        [T::one(); N]
    }

    /// What counts as a unit of the input, as [`units`](Self::units) for the unknowns: a radian
    /// for a crank, the loops' declared lengths for a slide (generated code); 1 by default.
    /// No piece of a step is longer, and the look beyond a stuck walk starts `√ε` of it away.
    fn input_unit(&self) -> T {
        T::one()
    }
}

/// A solved position of a sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<T, const N: usize> {
    /// The input.
    pub input: T,
    /// The unknowns, in declaration order.
    pub position: [T; N],
}

/// Why a sweep stopped before its last step. The sweep never crosses to another branch
/// silently, nor steps over inputs where the mechanism cannot be assembled, nor reads a path
/// through positions the loops do not fix: it stops and says so.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stop<T> {
    /// Between `last_input` and `next_input` the mechanism meets a toggle (its Jacobian is
    /// singular, and beyond it the loops do not close): the input cannot drive it further.
    /// Also what a sweep whose start cannot be solved reports, with both inputs the start; one
    /// whose next input is not finite (`Error::NonFinite` naming `"sweep input"`); and one
    /// stuck where the loops fix some unknown more loosely than the walk's resolution (a
    /// sixteenth of a unit, see [`Kinematics::units`]) and nothing beyond says which
    /// (`Error::Inaccurate` of the position).
    Toggle {
        /// The last input solved on the branch.
        last_input: T,
        /// The input that could not be reached.
        next_input: T,
        /// What failed: the nearest failure past the toggle.
        error: Error<T>,
    },
    /// Between `last_input` and `next_input` the motion continues only on the other branch:
    /// the sweep reached a change point (all links in line, where the branches meet), where
    /// the input does not say which way the linkage goes on.
    BranchChange {
        /// The last input solved on the branch.
        last_input: T,
        /// The input whose position is on the other branch.
        next_input: T,
    },
}

/// An allocation-free iterator over a mechanism's positions at `start`, `start + step`, …,
/// staying on the starting position's branch. It yields `Ok` samples, then, if it cannot go
/// on, one `Err(Stop)`.
///
/// Each step is a predictor-corrector walk: Newton starts from the previous position moved
/// along its velocity, and the result is accepted if it is on the same branch, the loops fix
/// it (no unknown can be off by a sixteenth of its unit, from each loop's residual and rounding
/// through the Jacobian's inverse: near a change point where a link shrinks to nothing, its
/// angle is free, in f32 for some 1e-3 rad of input), and the path between is smooth: the
/// change in the unknowns, each in its unit ([`Kinematics::units`]), agrees with the piece's
/// length times the mean of the velocities at its two ends (the trapezoidal rule, exact to
/// third order, dead centres included) to within an eighth, and the piece is no longer than
/// the reaches of its two ends: how far the motion goes on from each before the Jacobian can
/// be singular (from Newton's condition estimate and the velocity there, as the implicit
/// function theorem bounds it; about half the distance to a toggle, where the motion ends).
/// A gap in the motion lies between two toggles, so a piece within the reaches steps over
/// none, however smoothly the motion on either side of a narrow gap lines up (near a change
/// point it can, to within the rule's eighth: a four-bar whose crank cannot pass 0.02 rad
/// about θ2 = 0 was stepped over in one radian, before the reaches). Otherwise the piece is
/// halved
/// (and grows again, doubling, after each accepted one); a halved piece whose landing is more
/// than sixteen times less certain than that test's tolerance is refused too (the blur of a
/// change point, where Newton's landings lie within rounding of either branch and their
/// velocities turn with the noise). No piece is longer than one unit of the input (a
/// radian: no piece spans a turn, whose ends alone cannot tell a full turn from a gap in the
/// motion; for a slide, the loops' declared lengths, [`Kinematics::input_unit`]), or than
/// `4·ε·|input|` where that is longer (from 3e8 rad in f32, whose neighbours are 32 apart,
/// `x + 1` is `x`); a step of more than 2¹⁶ units is walked in pieces of
/// `step/2¹⁶`, checked only for the branch and Newton's convergence (past 96 refused pieces
/// in one step, the sweep ends:
/// [`Stop::Toggle`] with Newton's error, for from a predictor that far off Newton lands on
/// either branch, or on none). Only the requested inputs are yielded. So the
/// sweep follows the motion around sharp turns, never steps over inputs where the loops do
/// not close, and stops where no piece down to `step·2⁻⁴⁰` (or the input's rounding) gets
/// further. There it solves at inputs beyond, at distances growing fourfold from
/// `√ε·max(unit, |input|)`, and counts what they say:
/// - mostly that the loops cannot be solved there: [`Stop::Toggle`], with the nearest such
///   error;
/// - mostly a position on the other branch: [`Stop::BranchChange`].
///
/// (A gap in the motion narrower than about `√ε` of the input may be taken for a change
/// point; in f32 that is about 10⁻² rad near a change point. Pieces are not held to reaches
/// shorter than `√ε` of the input, 1/256 of the step, or the input over which the motion
/// moves the position by 32 times its uncertainty, below which the walk cannot read a path:
/// a gap narrower than those may be stepped over. A mechanism that says nothing of its
/// uncertainty, whose [`Kinematics::slope_within`] is the default, has reaches without
/// bound.) A step that needs no halving, within the reaches, costs one Newton solve and one
/// velocity, as a plain predictor-corrector does; near a singular position the reaches
/// shorten the pieces, in proportion to the distance to it.
///
/// ```
/// use mechgen::{mechanism, sweep::Sweep, NewtonOptions, Branch};
/// mechanism! {
///     pub struct FourBar {
///         params: l1, l2, l3, l4;
///         input: theta2: angle;
///         unknowns: theta3: angle, theta4: angle;
///         loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
///     }
/// }
/// let crank_rocker = FourBar { l1: 180.0, l2: 80.0, l3: 200.0, l4: 150.0 };
/// let start = crank_rocker.assemble(0.0, Branch::Open)?.to_array();
/// let step = std::f64::consts::TAU / 3600.0;
/// let samples: Vec<_> = Sweep::new(&crank_rocker, 0.0, start, step, 3600, NewtonOptions::default())
///     .collect::<Result<_, _>>()
///     .expect("a Grashof crank turns fully on its branch");
/// let end = samples.last().unwrap().position;
/// let back = crank_rocker.assemble(step * 3600.0, Branch::Open)?.to_array();
/// assert!((end[1] - back[1]).abs() < 1e-9);
/// # Ok::<(), mechgen::Error<f64>>(())
/// ```
pub struct Sweep<'a, T, M, const N: usize> {
    mechanism: &'a M,
    options: NewtonOptions<T>,
    start: T,
    step: T,
    steps: u32,
    /// The index of the next sample to yield, at most `steps`.
    next: u32,
    /// The last solved sample, once the start is solved.
    last: Option<Last<T, N>>,
    start_guess: [T; N],
    /// The mechanism's [`Kinematics::units`].
    units: [T; N],
    /// The mechanism's [`Kinematics::input_unit`].
    input_unit: T,
    finished: bool,
}

/// The last solved sample of a sweep, with what the walk on from it reads.
#[derive(Clone, Copy)]
struct Last<T, const N: usize> {
    sample: Sample<T, N>,
    /// Newton's condition estimate there.
    condition: T,
    /// `dq/d(input)` there and its reach ([`Sweep::reach`]), once computed.
    heading: Option<([T; N], T)>,
}

/// A piece of a step shorter than this fraction of the step is not halved again.
const SMALLEST_PIECE: f64 = 1.0 / (1u64 << 40) as f64;

/// A step is walked in pieces of at most one unit of the input, or this fraction of the step
/// if that is longer (then without the smoothness check, to bound the work).
const COARSE_PIECE: f64 = 1.0 / 65536.0;

/// The most refused pieces a step walked in coarse pieces takes before it ends (enough to halve
/// toward a toggle from a piece of 2^16 units down to 2^-40 of the step).
const COARSE_REFUSALS: u32 = 96;

/// The fraction of a step below which a piece is not held to the reaches of its ends (nor
/// below `√ε` of the input): it bounds the work in a stretch where the loops are near singular
/// throughout (a kite of a crank 1e-6 of its coupler, whose condition is 2e6 at every
/// position), at the cost of gaps narrower than it there.
const FINEST_REACH: f64 = 1.0 / 256.0;

/// How far the change over a piece may differ from the trapezoidal rule's, relative to the
/// sizes of the change and of the two velocity terms.
const SMOOTHNESS: f64 = 0.125;

/// The most a piece's landing may be uncertain by (in units of each unknown, see
/// [`Kinematics::units`]) for the walk to read a path from it: a sixteenth of a radian, far
/// below the distance between assemblies (π, for a rocker turned over), far above what
/// rounding leaves of a position wherever the loops fix it.
const RESOLUTION: f64 = 1.0 / 16.0;

/// How many times less certain than the smoothness test's tolerance a landing of a halved
/// piece may be (see [`Sweep::piece`]): well beyond rounding, where the test's floor and the
/// landing's stated uncertainty agree to within a few times, far below a change point's blur,
/// where they part by thousands.
const BLUR: f64 = 16.0;

/// How much of the rest of a step a piece must cover to go to its end: all but 2⁻²⁰, far
/// more than the rounding of a sum of pieces, far less than what a halved piece leaves
/// (half the rest).
const ALL_BUT_ROUNDING: f64 = 1.0 - 1.0 / 1_048_576.0;

/// Where a piece of a step landed ([`Sweep::piece`]).
struct Landing<T, const N: usize> {
    position: [T; N],
    velocity: [T; N],
    /// Whether the path from the piece's start is smooth (the trapezoidal rule's test).
    smooth: bool,
    /// [`Sweep::reach`] at the landing.
    reach: T,
    /// Newton's condition estimate at the landing.
    condition: T,
}

/// Why a piece of a step was refused.
#[derive(Clone, Copy, Debug)]
enum Refusal<T> {
    /// Newton, or the velocity at the piece's end, failed (other than by converging on the
    /// other branch).
    Failed(Error<T>),
    /// Newton converged on the other branch.
    OtherBranch,
}

impl<'a, T: Real, M: Kinematics<T, N>, const N: usize> Sweep<'a, T, M, N> {
    /// A sweep of `steps` steps of `step` from `start`, beginning near `position` (a solved
    /// position on the branch to follow, such as `assemble`'s), with Newton `options` for each
    /// solve. It yields `steps + 1` samples when nothing stops it (for any `steps`, up to
    /// `u32::MAX`).
    pub fn new(
        mechanism: &'a M,
        start: T,
        position: [T; N],
        step: T,
        steps: u32,
        options: NewtonOptions<T>,
    ) -> Self {
        Sweep {
            mechanism,
            options,
            start,
            step,
            steps,
            next: 0,
            last: None,
            start_guess: position,
            units: mechanism.units(),
            input_unit: mechanism.input_unit(),
            finished: false,
        }
    }

    fn advance(&mut self) -> Result<Sample<T, N>, Stop<T>> {
        // From the start each time, so rounding does not accumulate over the steps (and the
        // start is the start, whatever the step).
        let input = match self.next {
            0 => self.start,
            next => self.start + self.step * T::constant(f64::from(next)),
        };
        let Some(Last {
            sample: last,
            condition,
            heading,
        }) = self.last
        else {
            // The start: polish the given position; a failure here is the caller's guess.
            let solved = self
                .mechanism
                .solve_near(input, self.start_guess, &self.options)
                .map_err(|error| Stop::Toggle {
                    last_input: input,
                    next_input: input,
                    error,
                })?;
            return Ok(self.keep(input, solved.value, solved.condition, None));
        };
        let toggle = |error| Stop::Toggle {
            last_input: last.input,
            next_input: input,
            error,
        };
        let (slope, reach) = match heading {
            Some(known) => known,
            None => {
                let (slope, uncertainty) = self
                    .mechanism
                    .slope_within(last.input, last.position)
                    .map_err(toggle)?;
                (slope, self.reach(slope, condition, uncertainty))
            }
        };
        let landing = self.walk(last, slope, reach, input)?;
        let heading = Some((landing.velocity, landing.reach));
        Ok(self.keep(input, landing.position, landing.condition, heading))
    }

    /// `position` at `input` kept as the last sample (with Newton's `condition` there, and
    /// its heading if known), and returned.
    fn keep(
        &mut self,
        input: T,
        position: [T; N],
        condition: T,
        heading: Option<([T; N], T)>,
    ) -> Sample<T, N> {
        let sample = Sample { input, position };
        self.last = Some(Last {
            sample,
            condition,
            heading,
        });
        sample
    }

    /// Walks from `from` (with velocity `slope`, and [`Sweep::reach`] `reach`) to `target` in
    /// pieces as long as the motion allows, returning the landing there.
    fn walk(
        &self,
        from: Sample<T, N>,
        slope: [T; N],
        reach: T,
        target: T,
    ) -> Result<Landing<T, N>, Stop<T>> {
        let half = T::constant(0.5);
        let direction = target - from.input;
        if !direction.is_finite() {
            return Err(Stop::Toggle {
                last_input: from.input,
                next_input: target,
                error: Error::NonFinite {
                    quantity: "sweep input",
                },
            });
        }
        let smallest = direction.abs() * T::constant(SMALLEST_PIECE);
        // No piece is longer than one unit of the input (a radian, or the loops' length for a
        // slide), so none can span a turn of an angle input, from whose ends alone a full
        // turn and a gap look alike; except that a step of more than 2^16 units is walked in
        // 2^16 pieces, each accepted if Newton converges on the branch, so that the work is
        // bounded.
        let unit = self.input_unit;
        let coarse = direction.abs() * T::constant(COARSE_PIECE);
        // Nor shorter than the input's rounding where it is coarser than a unit (a start of
        // 3e8 rad in f32, whose neighbours are 32 apart): `x + 1` would be `x`, and the walk
        // would accept the same input for ever.
        let resolution = T::constant(4.0) * T::epsilon() * from.input.abs().max(target.abs());
        let (longest, roughest) = if coarse > unit {
            (coarse, coarse)
        } else {
            (direction.abs().min(unit.max(resolution)), smallest)
        };
        let longest = if direction < T::zero() {
            -longest
        } else {
            longest
        };
        // Below this a piece is not held to the reaches of its ends: a gap in the motion
        // narrower than it may be stepped over (see the type's docs). Coarse pieces are not
        // held to them at all (they are checked only for the branch).
        let finest_reach = (T::epsilon().sqrt() * unit.max(from.input.abs().max(target.abs())))
            .max(direction.abs() * T::constant(FINEST_REACH));
        let held_to_reaches = coarse <= unit;
        let (mut x, mut q, mut m, mut r) = (from.input, from.position, slope, reach);
        let mut piece = longest;
        let mut coarse_refusals = 0;
        loop {
            let remaining = target - x;
            // The longest piece from here: within half again the reach of its start, which a
            // landing's own reach (shorter toward a singular point) covers the rest of. A
            // piece at it is not a halved one, whose landing the walk reads more strictly.
            let limit = if held_to_reaches {
                let cap = (r * T::constant(1.5)).max(finest_reach);
                if cap < longest.abs() {
                    cap
                } else {
                    longest.abs()
                }
            } else {
                longest.abs()
            };
            if piece.abs() > limit {
                piece = if piece < T::zero() { -limit } else { limit };
            }
            // A piece within rounding of the rest goes to the target: halves of a step sum to
            // it only within rounding, and would leave a piece of a few ulps, whose change
            // rounding alone decides (the walk cannot read it, below).
            let (y, piece_used) = if piece.abs() >= remaining.abs() * T::constant(ALL_BUT_ROUNDING)
            {
                (target, remaining)
            } else {
                (x + piece, piece)
            };
            let shorter = piece_used * half;
            // The last chance: a shorter piece would be below the resolution, so a rough path
            // is accepted (Newton converged on the branch: that is all that can be known).
            let last_chance = unresolved(x, shorter, smallest);
            let rough = unresolved(x, shorter, roughest);
            let halved = piece.abs() < limit;
            let refusal = match self.piece(x, q, m, y, halved) {
                // Within the reach of its ends (no toggle between, so no gap), or too short to
                // tell.
                Ok(landing)
                    if (landing.smooth
                        && piece_used.abs() <= (r + landing.reach).max(finest_reach))
                        || rough =>
                {
                    if y == target {
                        return Ok(landing);
                    }
                    (x, q, m, r) = (y, landing.position, landing.velocity, landing.reach);
                    piece = if (piece_used + piece_used).abs() < longest.abs() {
                        piece_used + piece_used
                    } else {
                        longest
                    };
                    continue;
                }
                Ok(_) => None,
                Err(refusal) => Some(refusal),
            };
            // A coarse piece (of a step beyond 2^16 units) starts Newton from a guess the
            // predictor cannot place (a velocity times millions of units), which lands on
            // either branch, or on none: refused pieces are halved (toward a toggle, which
            // needs some forty halvings to be found), but past `COARSE_REFUSALS` of them the
            // walk would crawl, halving and doubling, for longer than any sweep may. It ends
            // there, saying what Newton said.
            if coarse > unit && refusal.is_some() {
                coarse_refusals += 1;
                if let Some(refusal) = refusal
                    .as_ref()
                    .filter(|_| coarse_refusals > COARSE_REFUSALS)
                {
                    return Err(Stop::Toggle {
                        last_input: from.input,
                        next_input: target,
                        error: match refusal {
                            Refusal::OtherBranch => Error::OtherBranch,
                            Refusal::Failed(error) => *error,
                        },
                    });
                }
            }
            let Some(refusal) = refusal.filter(|_| last_chance) else {
                piece = shorter;
                continue;
            };
            // Stuck at a singular point just past `x`: what lies beyond it says which.
            return Err(match self.beyond(x, q, m, piece_used, longest) {
                Some(Refusal::OtherBranch) => Stop::BranchChange {
                    last_input: from.input,
                    next_input: target,
                },
                Some(Refusal::Failed(error)) => Stop::Toggle {
                    last_input: from.input,
                    next_input: target,
                    error,
                },
                None => match refusal {
                    Refusal::OtherBranch => Stop::BranchChange {
                        last_input: from.input,
                        next_input: target,
                    },
                    Refusal::Failed(error) => Stop::Toggle {
                        last_input: from.input,
                        next_input: target,
                        error,
                    },
                },
            });
        }
    }

    /// What lies beyond the singular point the walk is stuck at, just past `x` (within
    /// `piece`): solves (from the predictor) at distances growing fourfold from `√ε·|x|` (or
    /// `4·piece`, or `√ε` of the input's unit, if larger) to four times `reach` (and at least
    /// four of them), and
    /// counts the answers that say: a position on the other branch, from a guess the
    /// predictor places near the motion (the motion goes on there: a change point), or a
    /// failure other than a singular Jacobian or a position the loops do not fix (it goes on
    /// nowhere: a toggle). The more frequent answer, with the nearest such failure, or `None`
    /// if none says. Nearer than `√ε`, rounding lets Newton converge a hair past a toggle,
    /// and fail at a change point itself; farther, one answer alone could see past a narrow
    /// gap, hence the count.
    fn beyond(&self, x: T, q: [T; N], m: [T; N], piece: T, reach: T) -> Option<Refusal<T>> {
        let four = T::constant(4.0);
        let root_epsilon = T::epsilon().sqrt();
        let sign = if piece < T::zero() {
            -T::one()
        } else {
            T::one()
        };
        let nearest = (piece * four)
            .abs()
            .max(root_epsilon * x.abs().max(self.input_unit));
        let farthest = (reach * four).abs().max(nearest * T::constant(256.0));
        let mut distance = nearest;
        let (mut branches, mut failures) = (0u32, 0u32);
        let mut first_failure = None;
        while distance <= farthest {
            // Where the predictor moves some unknown by more than its own size and a unit (a
            // radian, or the loops' length: the same at every scale), its guess is no place
            // on the motion: near a toggle,
            // whose velocities grow without bound, it is thousands of radians off, and Newton
            // from it lands on any assembly. Such a landing says nothing of a change point.
            let placed = q
                .iter()
                .zip(m)
                .zip(self.units)
                .all(|((q, m), unit)| (m * distance).abs() <= unit + q.abs());
            match self.piece(x, q, m, x + sign * distance, false) {
                Err(Refusal::OtherBranch) if placed => branches += 1,
                Err(Refusal::OtherBranch) => {}
                // Singular, or with an unknown the loops do not fix there: no more a verdict
                // than a position on the branch is.
                Err(Refusal::Failed(Error::Singular { .. } | Error::Inaccurate { .. })) | Ok(_) => {
                }
                Err(Refusal::Failed(error)) => {
                    failures += 1;
                    first_failure = first_failure.or(Some(error));
                }
            }
            distance = distance * four;
        }
        if branches > failures {
            Some(Refusal::OtherBranch)
        } else {
            first_failure.map(Refusal::Failed)
        }
    }

    /// How far along the input the motion goes on from a solved position with velocity
    /// `slope` and Newton's `condition` there before its Jacobian can be singular, as the
    /// implicit function theorem bounds it: `1/(8·κ·(1 + |q'|))` in units of the input and
    /// the unknowns. A toggle, where the motion ends, has a singular Jacobian, and near one κ
    /// and `q'` both grow as the inverse square root of the distance to it: the reach is then
    /// about half that distance (measured on four-bars from 1 to 1e-8 rad from their
    /// toggles), so a piece no longer than the reaches of its two ends steps over no gap.
    /// Never shorter than the input over which the motion moves the position by 32 times its
    /// uncertainty: below that the walk cannot read a path anyway (a landing's rounding would
    /// be most of its change; in f32, a parallelogram a thousand times as long as its cranks
    /// has positions uncertain by 7e-3 rad), so a gap narrower than it may be stepped over.
    /// Infinite where the mechanism says nothing of its uncertainty (`uncertainty` zeros,
    /// [`Kinematics::slope_within`]'s default: a hand implementation, whose condition may not
    /// be the loops'), or the condition is not a number.
    fn reach(&self, slope: [T; N], condition: T, uncertainty: [T; N]) -> T {
        if uncertainty.iter().all(|u| *u == T::zero()) || condition.is_nan() {
            return T::infinity();
        }
        let (mut speed, mut loosest) = (T::zero(), T::zero());
        for ((m, u), unit) in slope.iter().zip(uncertainty).zip(self.units) {
            speed = speed.max((*m * self.input_unit / unit).abs());
            loosest = loosest.max(u / unit);
        }
        let regular = self.input_unit / (T::constant(8.0) * condition * (T::one() + speed));
        let readable = T::constant(32.0) * loosest * self.input_unit / speed;
        // The larger (`readable` is infinite where nothing moves, NaN never: `loosest` and
        // `speed` are finite here, not both zero).
        if readable > regular {
            readable
        } else {
            regular
        }
    }

    /// One piece, from `x` (position `q`, velocity `m`) to `y`, `halved` from a longer one
    /// the walk could not read: the position and velocity at `y`, whether the path between
    /// is smooth, and [`Sweep::reach`] at `y`, or why the piece is refused.
    fn piece(
        &self,
        x: T,
        q: [T; N],
        m: [T; N],
        y: T,
        halved: bool,
    ) -> Result<Landing<T, N>, Refusal<T>> {
        let h = y - x;
        let mut guess = q;
        for (g, s) in guess.iter_mut().zip(m) {
            *g = *g + s * h;
        }
        let (position, condition) = match self.mechanism.solve_near(y, guess, &self.options) {
            Ok(solved) => (solved.value, solved.condition),
            Err(Error::OtherBranch) => return Err(Refusal::OtherBranch),
            Err(error) => return Err(Refusal::Failed(error)),
        };
        if !self.mechanism.same_branch(x, q, y, position) {
            return Err(Refusal::OtherBranch);
        }
        let (velocity, uncertainty) = self
            .mechanism
            .slope_within(y, position)
            .map_err(Refusal::Failed)?;
        // A landing the loops fix only loosely (near a change point where a link shrinks to
        // nothing, in f32 some 1e-3 rad of input wide) may hold any value of the loose
        // unknown, and a path read from such landings may turn it over on the same branch:
        // refused, so the walk stops short and looks beyond.
        let resolution = T::constant(RESOLUTION);
        // The loosest unknown, in its units; NaN (from an uncertainty that overflows) is
        // taken for infinite, and refuses too.
        let loosest = uncertainty
            .iter()
            .zip(self.units)
            .fold(T::zero(), |loosest, (u, unit)| {
                let relative = *u / unit;
                if relative.is_nan() {
                    T::infinity()
                } else {
                    loosest.max(relative)
                }
            });
        if loosest > resolution {
            return Err(Refusal::Failed(Error::Inaccurate {
                order: Order::Position,
                estimate: loosest,
                required: resolution,
            }));
        }
        // The trapezoidal rule, Δq ≈ h·(m_x + m_y)/2, holds to third order in h for a smooth
        // path, through dead centres (where m_x or m_y vanishes) too. Each unknown in its own
        // units, so that an angle and a slide weigh alike at any size, and rounding is that
        // of a unit at least: a slide that stays at 0 still moves by the rounding of the
        // loops' lengths (the crossed isosceles slider-crank's, whose every piece was refused
        // as rough against a noise of the angles' rounding: a crawl, from sizes of 1e16).
        let half = T::constant(0.5);
        let (mut error, mut size, mut magnitude) = (T::zero(), T::zero(), T::one());
        for i in 0..N {
            let unit = self.units[i];
            let change = (position[i] - q[i]) / unit;
            let (before, after) = (m[i] * h / unit, velocity[i] * h / unit);
            error = error.max((change - (before + after) * half).abs());
            size = size.max(change.abs() + before.abs() + after.abs());
            magnitude = magnitude.max(q[i].abs().max(position[i].abs()) / unit);
        }
        let noise = T::constant(64.0) * T::epsilon() * magnitude;
        let tolerance = T::constant(SMOOTHNESS) * size + noise;
        // The walk halves a piece to read a path the longer one could not, and a landing far
        // less certain than the shorter piece's own change cannot say it: within a change
        // point's blur, Newton's landings lie anywhere within rounding of either branch, and
        // their velocities are those of a neighbouring linkage's motion, which turns from one
        // mode to the other (a parallelogram 1000 times as long as its cranks, stepped onto its
        // flat position, went on `Ok` on the same branch's other mode, a path read from
        // positions a thousand times less certain than their changes). Refused, so the walk
        // stops short and looks beyond. A piece the walk has not halved is read where its
        // landing agrees with the predictor, however loose (within the resolution); one a few
        // times less certain than the test's tolerance, near its rounding floor, as before (a
        // halved piece of an ulp of the input, in f32, is as uncertain as its change).
        let blurred = tolerance * T::constant(BLUR);
        if halved && loosest > blurred {
            return Err(Refusal::Failed(Error::Inaccurate {
                order: Order::Position,
                estimate: loosest,
                required: blurred,
            }));
        }
        let smooth = error <= tolerance;
        Ok(Landing {
            position,
            velocity,
            smooth,
            reach: self.reach(velocity, condition, uncertainty),
            condition,
        })
    }
}

impl<T: Real, M: Kinematics<T, N>, const N: usize> Iterator for Sweep<'_, T, M, N> {
    type Item = Result<Sample<T, N>, Stop<T>>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.finished {
            return None;
        }
        let result = self.advance();
        if result.is_err() || self.next == self.steps {
            self.finished = true;
        } else {
            self.next += 1;
        }
        Some(result)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        if self.finished {
            return (0, Some(0));
        }
        let left = u64::from(self.steps - self.next) + 1;
        (0, usize::try_from(left).ok())
    }
}

/// Whether a piece `piece` long from `x` is below the walk's resolution: shorter than
/// `finest`, or lost in rounding at `x`.
fn unresolved<T: Real>(x: T, piece: T, finest: T) -> bool {
    piece.abs() < finest || x + piece == x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Solved;
    use std::vec;
    use std::vec::Vec;

    #[test]
    fn a_piece_is_unresolved_below_the_finest_or_where_rounding_loses_it() {
        assert!(unresolved(0.0, 0.25, 0.5));
        assert!(unresolved(0.0, -0.25, 0.5));
        // A piece exactly the finest is resolved.
        assert!(!unresolved(0.0, 0.5, 0.5));
        // At 1, a power of two, half an ulp of 1 is lost upwards (a tie, rounded to even) but
        // not downwards, where the floats are twice as dense.
        let half_ulp = f64::EPSILON / 2.0;
        assert!(unresolved(1.0, half_ulp, 0.0));
        assert!(!unresolved(1.0, -half_ulp, 0.0));
        assert!(!unresolved(1.0, f64::EPSILON, 0.0));
    }

    /// `q = input`, on one branch, everywhere.
    struct Line;

    impl Kinematics<f64, 1> for Line {
        fn solve_near(
            &self,
            input: f64,
            _guess: [f64; 1],
            _options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            Ok(Solved {
                value: [input],
                iterations: 0,
                residual_norm: 0.0,
                condition: 1.0,
            })
        }

        fn slope(&self, _input: f64, _position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Ok([1.0])
        }

        fn same_branch(&self, _: f64, _: [f64; 1], _: f64, _: [f64; 1]) -> bool {
            true
        }
    }

    /// `x² + y² = 1` for `y`, on the branch of `y`'s sign: toggles at `x = ±1`, beyond
    /// which it cannot be assembled.
    struct Circle;

    impl Kinematics<f64, 1> for Circle {
        fn solve_near(
            &self,
            input: f64,
            guess: [f64; 1],
            _options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            if input.abs() > 1.0 {
                return Err(Error::CannotAssemble { input });
            }
            Ok(Solved {
                value: [(1.0 - input * input).sqrt().copysign(guess[0])],
                iterations: 1,
                residual_norm: 0.0,
                condition: 1.0,
            })
        }

        fn slope(&self, input: f64, [y]: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            if y == 0.0 {
                return Err(Error::Singular {
                    determinant: 0.0,
                    relative_determinant: 0.0,
                });
            }
            Ok([-input / y])
        }

        fn same_branch(&self, _: f64, [a]: [f64; 1], _: f64, [b]: [f64; 1]) -> bool {
            (a < 0.0) == (b < 0.0)
        }
    }

    /// `y² = x²` for `y`, on the branch of `y`'s sign: the branches `y = x` and `y = −x`
    /// cross at the change point `x = 0`.
    struct Cross;

    impl Kinematics<f64, 1> for Cross {
        fn solve_near(
            &self,
            input: f64,
            guess: [f64; 1],
            _options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            Ok(Solved {
                value: [input.abs().copysign(guess[0])],
                iterations: 1,
                residual_norm: 0.0,
                condition: 1.0,
            })
        }

        fn slope(&self, input: f64, [y]: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Ok([if (y < 0.0) == (input < 0.0) {
                1.0
            } else {
                -1.0
            }])
        }

        fn same_branch(&self, _: f64, [a]: [f64; 1], _: f64, [b]: [f64; 1]) -> bool {
            (a < 0.0) == (b < 0.0)
        }
    }

    /// [`Cross`] as Newton solves it: to a thousandth of the rounding floor of a loop with a
    /// link of length 1 beside `x` and `y` (as Newton's polish goes below the floor the
    /// uncertainty is stated from), with the residual biased by half that: within some
    /// `√ε/6` of the change point every landing is within rounding of a solution, its
    /// uncertainty hundreds of times its distance from the change point, and its velocity,
    /// `x/y`, that of the neighbouring curve `y² − x² = bias`, which turns smoothly from one
    /// branch's mode to the other (a parallelogram 1000 times as long as its cranks does
    /// this at its flat position, in f64).
    struct BlurredCross;

    impl BlurredCross {
        /// The residual as computed, and its rounding floor.
        fn residual(input: f64, y: f64) -> (f64, f64) {
            let floor = 16.0 * f64::EPSILON * (1.0 + input * input + y * y);
            (y * y - input * input - floor / 2048.0, floor)
        }
    }

    impl Kinematics<f64, 1> for BlurredCross {
        fn solve_near(
            &self,
            input: f64,
            [mut y]: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            for iterations in 0..options.max_iterations {
                let (residual, floor) = Self::residual(input, y);
                // At least one update, as Newton polishes a guess already within rounding.
                if iterations > 0 && residual.abs() <= floor.max(options.tolerance) / 1024.0 {
                    return Ok(Solved {
                        value: [y],
                        iterations,
                        residual_norm: residual.abs(),
                        condition: 1.0,
                    });
                }
                y -= residual / (2.0 * y);
            }
            Err(Error::NoConvergence {
                iterations: options.max_iterations,
                residual_norm: Self::residual(input, y).0.abs(),
            })
        }

        fn slope(&self, input: f64, [y]: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Ok([input / y])
        }

        fn slope_within(
            &self,
            input: f64,
            [y]: [f64; 1],
        ) -> Result<([f64; 1], [f64; 1]), Error<f64>> {
            let (residual, floor) = Self::residual(input, y);
            Ok(([input / y], [(residual.abs() + floor) / (2.0 * y).abs()]))
        }

        fn same_branch(&self, _: f64, [a]: [f64; 1], _: f64, [b]: [f64; 1]) -> bool {
            (a < 0.0) == (b < 0.0)
        }
    }

    /// `y² = (1 − x²)(4 − x²)` for `y`, on the branch of `y`'s sign: it cannot be assembled
    /// for `1 < |x| < 2`, a gap in the motion with a solution on the branch either side.
    struct Gap;

    impl Kinematics<f64, 1> for Gap {
        fn solve_near(
            &self,
            input: f64,
            guess: [f64; 1],
            _options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            let square = (1.0 - input * input) * (4.0 - input * input);
            if square < 0.0 {
                return Err(Error::CannotAssemble { input });
            }
            Ok(Solved {
                value: [square.sqrt().copysign(guess[0])],
                iterations: 1,
                residual_norm: 0.0,
                condition: 1.0,
            })
        }

        fn slope(&self, input: f64, [y]: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            if y == 0.0 {
                return Err(Error::Singular {
                    determinant: 0.0,
                    relative_determinant: 0.0,
                });
            }
            Ok([(4.0 * input * input - 10.0) * input / (2.0 * y)])
        }

        fn same_branch(&self, _: f64, [a]: [f64; 1], _: f64, [b]: [f64; 1]) -> bool {
            (a < 0.0) == (b < 0.0)
        }
    }

    #[test]
    fn a_sweep_does_not_step_over_a_gap_in_the_motion() {
        // One step from 0 to 3, where the branch goes on past the gap: walked in pieces of at
        // most one unit, the sweep stops at the gap's edge.
        let (samples, stop) = sweep(&Gap, 0.0, 1.0, 3.0, 1);
        assert_eq!(
            samples,
            [Sample {
                input: 0.0,
                position: [2.0]
            }]
        );
        match stop {
            Some(Stop::Toggle {
                last_input: 0.0,
                next_input: 3.0,
                error: Error::CannotAssemble { input },
            }) => assert!(input > 1.0 && input < 2.0, "{input}"),
            other => panic!("{other:?}"),
        }
    }

    /// `q = min(input, 0.1)`, on one branch: a corner in the path at 0.1.
    struct Corner;

    impl Kinematics<f64, 1> for Corner {
        fn solve_near(
            &self,
            input: f64,
            _guess: [f64; 1],
            _options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            Line.solve_near(input.min(0.1), [0.0], &NewtonOptions::default())
        }

        fn slope(&self, input: f64, _position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Ok([if input < 0.1 { 1.0 } else { 0.0 }])
        }

        fn same_branch(&self, _: f64, _: [f64; 1], _: f64, _: [f64; 1]) -> bool {
            true
        }
    }

    #[test]
    fn a_long_step_backwards_is_walked_backwards() {
        // From 0 to −3 in unit pieces, stopped at the gap's edge near −1, not at +1.
        let (samples, stop) = sweep(&Gap, 0.0, 1.0, -3.0, 1);
        assert_eq!(samples.len(), 1);
        match stop {
            Some(Stop::Toggle {
                last_input: 0.0,
                next_input: -3.0,
                error: Error::CannotAssemble { input },
            }) => assert!(input < -1.0 && input > -2.0, "{input}"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_walk_from_an_input_coarser_than_a_unit_goes_on() {
        // From 1e17, whose neighbours are 16 apart, `x + 1` is `x`: pieces as long as the
        // input's rounding, not a unit accepted for ever (the solves are counted, and fail
        // past a thousand, so that a walk that spins stops rather than hang the test).
        let solves = core::cell::Cell::new(0u32);
        let counted = Failing {
            inner: Line,
            fail: |_| {
                solves.set(solves.get() + 1);
                (solves.get() > 1000).then_some(Error::NoConvergence {
                    iterations: 0,
                    residual_norm: 0.0,
                })
            },
        };
        let (samples, stop) = sweep(&counted, 1e17, 1e17, 64.0, 3);
        assert!(stop.is_none(), "{stop:?}");
        let inputs: Vec<f64> = samples.iter().map(|s| s.input).collect();
        assert_eq!(inputs, [1e17, 1e17 + 64.0, 1e17 + 128.0, 1e17 + 192.0]);
        assert!(solves.get() < 20, "{} solves", solves.get());
    }

    /// `inner`, but its solve failing with `fail`'s error where `fail` gives one.
    struct Failing<M, F> {
        inner: M,
        fail: F,
    }

    impl<M: Kinematics<f64, 1>, F: Fn(f64) -> Option<Error<f64>>> Kinematics<f64, 1> for Failing<M, F> {
        fn solve_near(
            &self,
            input: f64,
            guess: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            match (self.fail)(input) {
                Some(error) => Err(error),
                None => self.inner.solve_near(input, guess, options),
            }
        }

        fn slope(&self, input: f64, position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            self.inner.slope(input, position)
        }

        fn same_branch(&self, a: f64, p: [f64; 1], b: f64, q: [f64; 1]) -> bool {
            self.inner.same_branch(a, p, b, q)
        }
    }

    /// [`Circle`], but converging on the other branch for inputs just past 1 (up to
    /// 1 + 1e-7), where a toggle's fringe can send Newton.
    fn fringe() -> impl Kinematics<f64, 1> {
        Failing {
            inner: Circle,
            fail: |input: f64| (input > 1.0 && input <= 1.0 + 1e-7).then_some(Error::OtherBranch),
        }
    }

    #[test]
    fn a_toggle_is_told_by_most_of_what_lies_beyond_it() {
        // Beyond the stuck point, the nearest two solves land on the other branch and the
        // farther ones cannot assemble: more failures, so a toggle.
        let (samples, stop) = sweep(&fringe(), 0.0, 1.0, 0.1, 15);
        assert_eq!(samples.len(), 10);
        match stop {
            Some(Stop::Toggle {
                last_input: 0.9,
                next_input: 1.0,
                error: Error::CannotAssemble { input },
            }) => assert!(input > 1.0 + 1e-7 && input < 1.0 + 1e-5, "{input}"),
            other => panic!("{other:?}"),
        }
    }

    /// [`Circle`], but past its toggle Newton from a guess far off the motion lands on some
    /// other assembly (`OtherBranch`), as a six-bar's does on another circuit; from one near
    /// it, it cannot assemble.
    struct Spinning;

    impl Kinematics<f64, 1> for Spinning {
        fn solve_near(
            &self,
            input: f64,
            guess: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            if input > 1.0 && guess[0].abs() > 2.0 {
                return Err(Error::OtherBranch);
            }
            Circle.solve_near(input, guess, options)
        }

        fn slope(&self, input: f64, position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Circle.slope(input, position)
        }

        fn same_branch(&self, a: f64, p: [f64; 1], b: f64, q: [f64; 1]) -> bool {
            Circle.same_branch(a, p, b, q)
        }
    }

    /// Near a toggle the velocity grows without bound, so the predictor's guesses beyond it
    /// are far off the motion: where Newton lands from those says nothing of a change point
    /// (the Stephenson six-bar of the command line's tests was told to have one at its
    /// toggle). Those that fail still count.
    #[test]
    fn landings_from_guesses_the_predictor_cannot_place_do_not_make_a_change_point() {
        let (samples, stop) = sweep(&Spinning, 0.0, 1.0, 0.1, 15);
        assert_eq!(samples.len(), 10);
        assert!(
            matches!(
                stop,
                Some(Stop::Toggle {
                    last_input: 0.9,
                    next_input: 1.0,
                    error: Error::CannotAssemble { .. },
                })
            ),
            "{stop:?}"
        );
    }

    /// The line `y = x`, whose velocity is said to be twice what it is: the predictor is off
    /// by the piece's length, and Newton lands on the other branch from a guess more than a
    /// unit off (as from a coarse piece's, millions of units off).
    struct Misled;

    impl Kinematics<f64, 1> for Misled {
        fn solve_near(
            &self,
            input: f64,
            guess: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            if (guess[0] - input).abs() > 1.0 {
                return Err(Error::OtherBranch);
            }
            Line.solve_near(input, guess, options)
        }

        fn slope(&self, _input: f64, _position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Ok([2.0])
        }

        fn same_branch(&self, a: f64, p: [f64; 1], b: f64, q: [f64; 1]) -> bool {
            Line.same_branch(a, p, b, q)
        }
    }

    /// A step of 1e12 is walked in pieces of 1.5e7, from guesses the predictor cannot place:
    /// refused, halved to a unit, accepted, doubled and refused again, it would crawl through
    /// millions of solves a piece. It ends after 96 refusals, saying what Newton said.
    #[test]
    fn a_coarse_step_ends_after_its_refused_pieces() {
        let misled = Counted::new(Misled);
        let (samples, stop) = sweep(&misled, 0.0, 0.0, 1e12, 2);
        assert_eq!(samples.len(), 1);
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: 0.0,
                next_input: 1e12,
                error: Error::OtherBranch
            })
        );
        // The 97th refusal ends it (171 solves in all: the refused pieces, and those between
        // them that Newton converged on).
        assert_eq!(misled.solves.get(), 171);
    }

    fn sweep<M: Kinematics<f64, 1>>(
        mechanism: &M,
        start: f64,
        position: f64,
        step: f64,
        steps: u32,
    ) -> (Vec<Sample<f64, 1>>, Option<Stop<f64>>) {
        let mut samples = Vec::new();
        for result in Sweep::new(
            mechanism,
            start,
            [position],
            step,
            steps,
            NewtonOptions::default(),
        ) {
            match result {
                Ok(sample) => samples.push(sample),
                Err(stop) => return (samples, Some(stop)),
            }
        }
        (samples, None)
    }

    #[test]
    fn a_sweep_follows_its_branch_to_a_toggle_and_says_where() {
        let (samples, stop) = sweep(&Circle, 0.0, 1.0, 0.1, 15);
        assert_eq!(samples.len(), 10);
        for (k, sample) in samples.iter().enumerate() {
            let x = 0.1 * k as f64;
            assert_eq!(sample.input, x);
            assert!((sample.position[0] - (1.0 - x * x).sqrt()).abs() <= 1e-15);
        }
        // Stuck just short of x = 1, the first solve beyond (√ε past it) cannot assemble.
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: 0.9,
                next_input: 1.0,
                error: Error::CannotAssemble {
                    input: 1.0000000149009793
                }
            })
        );
        // Backwards, on the other branch.
        let (samples, stop) = sweep(&Circle, 0.0, -1.0, -0.25, 6);
        let positions: Vec<f64> = samples.iter().map(|s| s.position[0]).collect();
        assert_eq!(
            positions,
            [
                -1.0,
                -(0.9375f64.sqrt()),
                -(0.75f64.sqrt()),
                -(0.4375f64.sqrt())
            ]
        );
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: -0.75,
                next_input: -1.0,
                error: Error::CannotAssemble {
                    input: -1.0000000149009338
                }
            })
        );
        // One step far beyond: walked in pieces, stuck at the same toggle.
        let (samples, stop) = sweep(&Circle, 0.0, 1.0, 1e6, 2);
        assert_eq!(samples.len(), 1);
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: 0.0,
                next_input: 1e6,
                error: Error::CannotAssemble {
                    input: 1.0000030670198612
                }
            })
        );
    }

    /// A step that lands on a change point, where Newton's landings lie anywhere within its
    /// blur and their velocities turn with the noise, stops there, as a step over it does: it
    /// went on `Ok` on the same branch's other mode, `y = −x` after `y = x`, with a smooth
    /// path read from positions hundreds of times less certain than their changes.
    #[test]
    fn a_step_onto_a_change_point_stops_there() {
        // 0.5 − 50 · 0.01 is 0 exactly.
        let (samples, stop) = sweep(&BlurredCross, 0.5, 0.5, -0.01, 100);
        assert!(samples.len() >= 50, "{samples:?}");
        for sample in &samples {
            assert!(sample.input >= 0.0, "{samples:?}");
            let [y] = sample.position;
            assert!((y - sample.input).abs() < 1e-7, "{sample:?}");
        }
        match stop {
            Some(Stop::BranchChange {
                last_input,
                next_input,
            }) => assert!(
                (0.0..0.0101).contains(&last_input) && next_input <= 0.0,
                "{last_input} {next_input}"
            ),
            other => panic!("{other:?} after {samples:?}"),
        }
        // Stepping over the change point stops the same way.
        let (samples, stop) = sweep(&BlurredCross, 0.5, 0.5, -0.015, 100);
        assert!(samples.iter().all(|s| s.input > 0.0), "{samples:?}");
        assert!(matches!(stop, Some(Stop::BranchChange { .. })), "{stop:?}");
    }

    #[test]
    fn a_sweep_stops_where_its_branch_meets_the_other() {
        let (samples, stop) = sweep(&Cross, -1.0, 1.0, 0.3, 8);
        let inputs: Vec<f64> = samples.iter().map(|s| s.input).collect();
        assert_eq!(inputs, [-1.0, -0.7, -0.4, -1.0 + 0.3 * 3.0]);
        assert!(samples.iter().all(|s| s.position[0] == -s.input));
        assert_eq!(
            stop,
            Some(Stop::BranchChange {
                last_input: -1.0 + 0.3 * 3.0,
                next_input: -1.0 + 0.3 * 4.0
            })
        );
        let (samples, stop) = sweep(&Cross, 1.0, 1.0, -0.5, 4);
        assert_eq!(samples.len(), 3);
        assert_eq!(
            stop,
            Some(Stop::BranchChange {
                last_input: 0.0,
                next_input: -0.5
            })
        );
    }

    #[test]
    fn a_sweep_that_cannot_start_or_go_on_says_why() {
        assert_eq!(
            sweep(&Circle, 2.0, 1.0, 0.1, 3),
            (
                vec![],
                Some(Stop::Toggle {
                    last_input: 2.0,
                    next_input: 2.0,
                    error: Error::CannotAssemble { input: 2.0 }
                })
            )
        );
        let (samples, stop) = sweep(&Circle, 0.0, 1.0, f64::NAN, 2);
        assert_eq!(samples.len(), 1);
        match stop {
            Some(Stop::Toggle {
                last_input: 0.0,
                next_input,
                error:
                    Error::NonFinite {
                        quantity: "sweep input",
                    },
            }) => assert!(next_input.is_nan()),
            other => panic!("{other:?}"),
        }
        // A zero step: the start, again and again.
        let (samples, stop) = sweep(&Circle, 0.5, 1.0, 0.0, 3);
        assert_eq!(stop, None);
        assert_eq!(samples.len(), 4);
        assert!(
            samples
                .iter()
                .all(|s| s.input == 0.5 && s.position == [0.75f64.sqrt()])
        );
        let mut counted = Sweep::new(&Line, 0.0, [0.0], 1.0, 3, NewtonOptions::default());
        assert_eq!(counted.size_hint(), (0, Some(4)));
        counted.next();
        assert_eq!(counted.size_hint(), (0, Some(3)));
        assert_eq!(counted.count(), 3);
    }

    /// A mechanism with its solves and velocities counted: the work a sweep does.
    struct Counted<M> {
        mechanism: M,
        solves: core::cell::Cell<u32>,
        slopes: core::cell::Cell<u32>,
    }

    impl<M> Counted<M> {
        fn new(mechanism: M) -> Self {
            Counted {
                mechanism,
                solves: core::cell::Cell::new(0),
                slopes: core::cell::Cell::new(0),
            }
        }

        fn work(&self) -> (u32, u32) {
            (self.solves.get(), self.slopes.get())
        }
    }

    impl<M: Kinematics<f64, 1>> Kinematics<f64, 1> for Counted<M> {
        fn solve_near(
            &self,
            input: f64,
            guess: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            self.solves.set(self.solves.get() + 1);
            self.mechanism.solve_near(input, guess, options)
        }

        fn slope(&self, input: f64, position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            self.slopes.set(self.slopes.get() + 1);
            self.mechanism.slope(input, position)
        }

        fn same_branch(&self, a: f64, p: [f64; 1], b: f64, q: [f64; 1]) -> bool {
            self.mechanism.same_branch(a, p, b, q)
        }

        // `slope_within` is the default's, which counts through `slope`.

        fn units(&self) -> [f64; 1] {
            self.mechanism.units()
        }

        fn input_unit(&self) -> f64 {
            self.mechanism.input_unit()
        }
    }

    /// `inner` with its unknowns' and its input's units as given.
    struct WithUnits<M> {
        inner: M,
        units: f64,
        input_unit: f64,
    }

    impl<M: Kinematics<f64, 1>> Kinematics<f64, 1> for WithUnits<M> {
        fn solve_near(
            &self,
            input: f64,
            guess: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            self.inner.solve_near(input, guess, options)
        }

        fn slope(&self, input: f64, position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            self.inner.slope(input, position)
        }

        fn same_branch(&self, a: f64, p: [f64; 1], b: f64, q: [f64; 1]) -> bool {
            self.inner.same_branch(a, p, b, q)
        }

        fn slope_within(
            &self,
            input: f64,
            position: [f64; 1],
        ) -> Result<([f64; 1], [f64; 1]), Error<f64>> {
            self.inner.slope_within(input, position)
        }

        fn units(&self) -> [f64; 1] {
            [self.units]
        }

        fn input_unit(&self) -> f64 {
            self.input_unit
        }
    }

    /// [`Circle`] of radius 1e-20, in units of its radius: `x² + y² = 1e-40`.
    struct SmallCircle;

    impl Kinematics<f64, 1> for SmallCircle {
        fn solve_near(
            &self,
            input: f64,
            [guess]: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            match Circle.solve_near(input * 1e20, [guess], options) {
                Ok(solved) => Ok(solved.map(|[y]| [y * 1e-20])),
                Err(Error::CannotAssemble { .. }) => Err(Error::CannotAssemble { input }),
                Err(error) => Err(error),
            }
        }

        fn slope(&self, input: f64, [y]: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Circle.slope(input * 1e20, [y * 1e20])
        }

        fn same_branch(&self, a: f64, p: [f64; 1], b: f64, q: [f64; 1]) -> bool {
            Circle.same_branch(a, p, b, q)
        }

        fn units(&self) -> [f64; 1] {
            [1e-20]
        }

        fn input_unit(&self) -> f64 {
            1e-20
        }
    }

    /// Stuck at the toggle of a circle of 1e-20, the walk looks beyond from `√ε` of the
    /// input's unit, and names the nearest failure there; in units of 1 it would look from
    /// 1.5e-8, a million million radii away.
    #[test]
    fn what_lies_beyond_starts_at_the_input_s_unit() {
        let (samples, stop) = sweep(&SmallCircle, 0.0, 1e-20, 1e-21, 15);
        assert_eq!(samples.len(), 10);
        let Some(Stop::Toggle {
            error: Error::CannotAssemble { input },
            ..
        }) = stop
        else {
            panic!("{stop:?}");
        };
        let past = input * 1e20 - 1.0;
        assert!(past > 0.0 && past < 1e-7, "{input}");
    }

    /// Steps of 1e18 on an input whose unit is 1e20 take one piece each; in units of 1 they
    /// would take 2¹⁶ coarse pieces each.
    #[test]
    fn a_step_is_walked_in_pieces_of_the_input_s_unit() {
        let long = Counted::new(WithUnits {
            inner: Line,
            units: 1.0,
            input_unit: 1e20,
        });
        let (samples, stop) = sweep(&long, 0.0, 0.0, 1e18, 2);
        assert_eq!((samples.len(), stop, long.work()), (3, None, (3, 3)));
        let line = Counted::new(Line);
        let (samples, stop) = sweep(&line, 0.0, 0.0, 1e18, 2);
        assert_eq!((samples.len(), stop), (3, None));
        assert!(line.work().0 > 1 << 17, "{:?}", line.work());
    }

    #[test]
    fn a_sweep_costs_one_solve_and_one_velocity_a_smooth_step_and_halves_near_a_toggle() {
        // (solves, velocities) for the start and each step: one of each where the motion is
        // smooth; a step longer than a unit is walked in unit pieces, one of more than 2^16
        // units in 2^16 pieces.
        let line = |step, steps| {
            let line = Counted::new(Line);
            let (samples, stop) = sweep(&line, 0.0, 0.0, step, steps);
            assert_eq!((samples.len(), stop), (steps as usize + 1, None));
            line.work()
        };
        assert_eq!(line(0.1, 10), (11, 11));
        assert_eq!(line(3.0, 2), (7, 7));
        assert_eq!(line(1e6, 1), (65537, 65537));
        assert_eq!(line(-3.0, 2), (7, 7));
        // A corner in the path: the unit piece across it is refused as not smooth, and so is
        // its first half; the quarter is accepted, and the pieces double again.
        let corner = Counted::new(Corner);
        let (samples, stop) = sweep(&corner, 0.0, 0.0, 1.0, 1);
        assert_eq!((samples[1].position, stop), ([0.1], None));
        assert_eq!(corner.work(), (6, 6));
        // 2^16 units: still unit pieces, checked for smoothness (the corner's halved); beyond,
        // 2^16 pieces, checked only for the branch.
        let corner = Counted::new(Corner);
        let (samples, stop) = sweep(&corner, 0.0, 0.0, 65536.0, 1);
        assert_eq!((samples[1].position, stop), ([0.1], None));
        assert_eq!(corner.work(), (65541, 65541));
        let corner = Counted::new(Corner);
        let (samples, stop) = sweep(&corner, 0.0, 0.0, 65540.0, 1);
        assert_eq!((samples[1].position, stop), ([0.1], None));
        assert_eq!(corner.work(), (65537, 65537));
        // Near a toggle, pieces halve (and double again) down to the stuck point, then solve
        // beyond it: the count pins the halving, the doubling and the look beyond.
        let circle = Counted::new(Circle);
        let (samples, _) = sweep(&circle, 0.0, 1.0, 0.1, 15);
        assert_eq!((samples.len(), circle.work()), (10, (102, 89)));
        let circle = Counted::new(Circle);
        let (samples, _) = sweep(&circle, 0.0, -1.0, -0.25, 6);
        assert_eq!((samples.len(), circle.work()), (4, (99, 44)));
        let circle = Counted::new(Circle);
        let (samples, _) = sweep(&circle, 0.0, 1.0, 1e6, 2);
        assert_eq!((samples.len(), circle.work()), (1, (63, 13)));
        let cross = Counted::new(Cross);
        let (samples, _) = sweep(&cross, -1.0, 1.0, 0.3, 8);
        assert_eq!((samples.len(), cross.work()), (4, (99, 24)));
        let gap = Counted::new(Gap);
        let (samples, _) = sweep(&gap, 0.0, 1.0, 3.0, 1);
        assert_eq!((samples.len(), gap.work()), (1, (131, 78)));
        let fringe = Counted::new(fringe());
        let (samples, stop) = sweep(&fringe, 0.0, 1.0, 0.1, 15);
        assert_eq!((samples.len(), fringe.work()), (10, (102, 89)));
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: 0.9,
                next_input: 1.0,
                error: Error::CannotAssemble {
                    input: 1.0000002384183972
                }
            })
        );
        let (_, stop) = sweep(&Gap, 0.0, 1.0, 3.0, 1);
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: 0.0,
                next_input: 3.0,
                error: Error::CannotAssemble {
                    input: 1.0000000148975232
                }
            })
        );
    }

    /// `q = input`, but it cannot be assembled for `40 < input < 100`.
    struct Window;

    impl Kinematics<f64, 1> for Window {
        fn solve_near(
            &self,
            input: f64,
            guess: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            if input > 40.0 && input < 100.0 {
                return Err(Error::CannotAssemble { input });
            }
            Line.solve_near(input, guess, options)
        }

        fn slope(&self, input: f64, position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Line.slope(input, position)
        }

        fn same_branch(&self, _: f64, _: [f64; 1], _: f64, _: [f64; 1]) -> bool {
            true
        }
    }

    #[test]
    fn what_lies_beyond_is_looked_for_at_distances_scaled_to_the_input_and_the_step() {
        // Stuck at x = 2: the first solve beyond is √ε·|x| past it.
        let gap = Counted::new(Gap);
        let (samples, stop) = sweep(&gap, 3.0, -1.0, -3.0, 1);
        assert_eq!((samples.len(), gap.work()), (1, (130, 39)));
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: 3.0,
                next_input: 0.0,
                error: Error::CannotAssemble {
                    input: 1.9999999702013156
                }
            })
        );
        // Steps of 1e-8, shorter than √ε: still solves up to 256·√ε beyond.
        let circle = Counted::new(Circle);
        let (samples, stop) = sweep(&circle, 1.0 - 1e-7, 1.0, 1e-8, 20);
        assert_eq!((samples.len(), circle.work()), (10, (71, 66)));
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: 0.9999999900000001,
                next_input: 1.0,
                error: Error::CannotAssemble {
                    input: 1.0000000149011612
                }
            })
        );
        // Pieces of 2^5 in a step of 2^21: refused at 64, halved to 8 (accepted, to 40), and
        // grown again by doubling (to 56), not back to 2^5 at once.
        let window = Counted::new(Window);
        let (samples, stop) = sweep(&window, 0.0, 0.0, 2097152.0, 1);
        assert_eq!((samples.len(), window.work()), (1, (42, 4)));
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: 0.0,
                next_input: 2097152.0,
                error: Error::CannotAssemble {
                    input: 40.00000762939453
                }
            })
        );
    }

    /// [`Cross`], but Newton does not converge for inputs in `(0, window]`, just past the
    /// change point.
    fn tangle(window: f64) -> impl Kinematics<f64, 1> {
        Failing {
            inner: Cross,
            fail: move |input: f64| {
                (input > 0.0 && input <= window).then_some(Error::NoConvergence {
                    iterations: 50,
                    residual_norm: input,
                })
            },
        }
    }

    #[test]
    fn a_change_point_is_told_by_most_of_what_lies_beyond_it_and_a_tie_is_a_toggle() {
        // Beyond the stuck point, 14 solves at distances growing fourfold from √ε: the
        // nearest 2 fail and 12 land on the other branch, a change point; with the nearest 7
        // failing, a tie, which is not enough to say the motion goes on.
        let (samples, stop) = sweep(&tangle(1e-7), -1.0, 1.0, 0.3, 8);
        assert_eq!(samples.len(), 4);
        assert_eq!(
            stop,
            Some(Stop::BranchChange {
                last_input: -1.0 + 0.3 * 3.0,
                next_input: -1.0 + 0.3 * 4.0
            })
        );
        let (samples, stop) = sweep(&tangle(1e-4), -1.0, 1.0, 0.3, 8);
        assert_eq!(samples.len(), 4);
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: -1.0 + 0.3 * 3.0,
                next_input: -1.0 + 0.3 * 4.0,
                error: Error::NoConvergence {
                    iterations: 50,
                    residual_norm: 1.4901070170362611e-8
                }
            })
        );
    }

    /// `y = x` walked down through the change point at 0, beyond which nothing past −0.5
    /// assembles: of the solves beyond it, the nearest 13 land on the other branch from
    /// guesses the predictor places (a step `m·d` of at most a unit, `m` = 1) and the farthest
    /// fails, a change point. A count that took no guess for placed (as `|m + d| ≤ 1` would
    /// not) would say a toggle.
    #[test]
    fn landings_from_placed_guesses_make_a_change_point() {
        let cut = Failing {
            inner: Cross,
            fail: |input: f64| (input < -0.5).then_some(Error::CannotAssemble { input }),
        };
        let (samples, stop) = sweep(&cut, 1.0, 1.0, -0.5, 4);
        assert_eq!(samples.len(), 3);
        assert_eq!(
            stop,
            Some(Stop::BranchChange {
                last_input: 0.0,
                next_input: -0.5
            })
        );
    }

    /// [`Cross`] with `y` in units of `unit`: `y = ±unit·|x|`, which cannot be assembled
    /// below −0.5.
    struct Steep {
        unit: f64,
        /// What [`Kinematics::units`] says (the default's 1 where `None`).
        told: Option<f64>,
    }

    impl Kinematics<f64, 1> for Steep {
        fn solve_near(
            &self,
            input: f64,
            [guess]: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            if input < -0.5 {
                return Err(Error::CannotAssemble { input });
            }
            let solved = Cross.solve_near(input, [guess], options)?;
            Ok(solved.map(|[y]| [y * self.unit]))
        }

        fn slope(&self, input: f64, [y]: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Ok([Cross.slope(input, [y])?[0] * self.unit])
        }

        fn same_branch(&self, a: f64, p: [f64; 1], b: f64, q: [f64; 1]) -> bool {
            Cross.same_branch(a, p, b, q)
        }

        fn units(&self) -> [f64; 1] {
            [self.told.unwrap_or(1.0)]
        }
    }

    /// The look beyond a change point weighs the predictor's move in the unknowns' units: a
    /// motion of 1e8 units a radian is [`Cross`] at another size, a change point; taken in
    /// units of 1, every guess beyond is "no place", and the one failure says a toggle.
    #[test]
    fn what_lies_beyond_is_placed_in_the_unknowns_units() {
        let change = Stop::BranchChange {
            last_input: 0.0,
            next_input: -0.5,
        };
        let told = Steep {
            unit: 1e8,
            told: Some(1e8),
        };
        assert_eq!(sweep(&told, 1.0, 1e8, -0.5, 4).1, Some(change));
        let untold = Steep {
            unit: 1e8,
            told: None,
        };
        assert!(matches!(
            sweep(&untold, 1.0, 1e8, -0.5, 4).1,
            Some(Stop::Toggle { .. })
        ));
    }

    /// [`Cross`] lifted by 1000: `y = 1000 ± |x|`, on the branch of `y − 1000`'s sign, which
    /// cannot be assembled below −0.5.
    struct Lifted;

    impl Kinematics<f64, 1> for Lifted {
        fn solve_near(
            &self,
            input: f64,
            [guess]: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            if input < -0.5 {
                return Err(Error::CannotAssemble { input });
            }
            let solved = Cross.solve_near(input, [guess - 1000.0], options)?;
            Ok(solved.map(|[y]| [y + 1000.0]))
        }

        fn slope(&self, input: f64, [y]: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Cross.slope(input, [y - 1000.0])
        }

        fn same_branch(&self, a: f64, [p]: [f64; 1], b: f64, [q]: [f64; 1]) -> bool {
            Cross.same_branch(a, [p - 1000.0], b, [q - 1000.0])
        }
    }

    /// An unknown a thousand units from zero moves by a unit and its own size before a
    /// predicted landing counts as no place on the motion: the change point at 0 is found by
    /// its landings beyond, as [`Cross`]'s is (a test that took a unit less the unknown's size
    /// would place none, and say a toggle).
    #[test]
    fn a_landing_is_placed_within_the_unknowns_own_size() {
        assert_eq!(
            sweep(&Lifted, 1.0, 1001.0, -0.5, 4).1,
            Some(Stop::BranchChange {
                last_input: 0.0,
                next_input: -0.5,
            })
        );
    }

    /// `y = 10⁸·|x|` on one branch, in units of 10⁸: a corner at 0.
    struct Vee;

    impl Kinematics<f64, 1> for Vee {
        fn solve_near(
            &self,
            input: f64,
            _guess: [f64; 1],
            _options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            Ok(Solved {
                value: [1e8 * input.abs()],
                iterations: 1,
                residual_norm: 0.0,
                condition: 1.0,
            })
        }

        fn slope(&self, input: f64, _position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Ok([1e8 * input.signum()])
        }

        fn same_branch(&self, _: f64, _: [f64; 1], _: f64, _: [f64; 1]) -> bool {
            true
        }

        fn units(&self) -> [f64; 1] {
            [1e8]
        }
    }

    /// A corner in an unknown of large units is rough in those units: the piece across it is
    /// refused and halved (until the trapezoidal rule's eighth lets a piece with the corner
    /// near its middle through), as at any size, in six solves; were rounding that of the
    /// unknown's value times its unit, the step would be one piece, taken at once.
    #[test]
    fn a_corner_is_rough_in_the_unknowns_units() {
        let vee = Counted::new(Vee);
        let (samples, stop) = sweep(&vee, 0.9, 0.9e8, -1.0, 1);
        assert_eq!((samples.len(), stop, vee.work()), (2, None, (6, 6)));
    }

    /// `q = 10⁸ + 10⁻¹⁰·input`: a motion far below the rounding of the position.
    struct Offset;

    impl Kinematics<f64, 1> for Offset {
        fn solve_near(
            &self,
            input: f64,
            _guess: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            Line.solve_near(1e8 + 1e-10 * input, [0.0], options)
        }

        fn slope(&self, _input: f64, _position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Ok([1e-10])
        }

        fn same_branch(&self, _: f64, _: [f64; 1], _: f64, _: [f64; 1]) -> bool {
            true
        }
    }

    #[test]
    fn a_change_lost_in_the_rounding_of_the_position_is_smooth() {
        // Each step's change rounds to 0 against 10⁻¹⁰ predicted: within 64ε of the position's
        // size, so accepted at once, not halved.
        let offset = Counted::new(Offset);
        let (samples, stop) = sweep(&offset, 0.0, 1e8, 1.0, 10);
        assert_eq!((samples.len(), stop, offset.work()), (11, None, (11, 11)));
        assert!(samples.iter().all(|s| s.position == [1e8]));
    }

    /// `q = slope·input`, whose loops' condition at each input is `condition(input)`, and
    /// which says its uncertainty (`within`), so that the sweep holds its pieces to their
    /// reaches; its unknown's unit `unit` and its input's `input_unit`; its solves counted.
    struct Conditioned<F> {
        condition: F,
        slope: f64,
        within: f64,
        unit: f64,
        input_unit: f64,
        solves: core::cell::Cell<u32>,
    }

    impl<F> Conditioned<F> {
        /// A line of slope 1 and unit units, uncertain by the rounding (4ε).
        fn line(condition: F) -> Self {
            Conditioned {
                condition,
                slope: 1.0,
                within: 4.0 * f64::EPSILON,
                unit: 1.0,
                input_unit: 1.0,
                solves: core::cell::Cell::new(0),
            }
        }
    }

    impl<F: Fn(f64) -> f64> Kinematics<f64, 1> for Conditioned<F> {
        fn solve_near(
            &self,
            input: f64,
            _guess: [f64; 1],
            _options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            self.solves.set(self.solves.get() + 1);
            Ok(Solved {
                value: [self.slope * input],
                iterations: 0,
                residual_norm: 0.0,
                condition: (self.condition)(input),
            })
        }

        fn slope(&self, _input: f64, _position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            Ok([self.slope])
        }

        fn same_branch(&self, _: f64, _: [f64; 1], _: f64, _: [f64; 1]) -> bool {
            true
        }

        fn slope_within(
            &self,
            input: f64,
            position: [f64; 1],
        ) -> Result<([f64; 1], [f64; 1]), Error<f64>> {
            Ok((self.slope(input, position)?, [self.within]))
        }

        fn units(&self) -> [f64; 1] {
            [self.unit]
        }

        fn input_unit(&self) -> f64 {
            self.input_unit
        }
    }

    /// A piece is no longer than the reaches of its ends: on a line of condition 10 (and
    /// slope 1), every position's reach is `1/(8·10·(1 + 1))` = 1/160, so a unit step is
    /// walked in pieces of half again that (within the two ends' 1/80), not in one; a landing
    /// whose reach is far shorter than its start's is refused, and the piece halved; and no
    /// piece is held to reaches below 1/256 of the step, however ill-conditioned the line.
    #[test]
    fn pieces_are_no_longer_than_the_reaches_of_their_ends() {
        let walked = |line: Conditioned<fn(f64) -> f64>, start: f64, step: f64| {
            let (samples, stop) = sweep(&line, start, line.slope * start, step, 1);
            assert_eq!((samples.len(), stop), (2, None));
            assert_eq!(samples[1].position, [line.slope * (start + step)]);
            line.solves.get()
        };
        let solves_from =
            |start, condition, step| walked(Conditioned::line(condition), start, step);
        let solves = |condition, step| solves_from(0.0, condition, step);
        assert_eq!(solves(|_| 10.0, 1.0), 108);
        assert_eq!(solves(|_| 10.0, -1.0), 108);
        // Toward a singular point, the condition growing as 10 + 10⁴·x.
        assert_eq!(solves(|x| 10.0 + 1e4 * x, 0.1), 229);
        // Condition 1e7: reaches of 6e-9, below 1/256 of the step; from 1e4, below √ε of the
        // input (1.5e-4), which takes 7 pieces.
        assert_eq!(solves(|_| 1e7, 1e-3), 257);
        assert_eq!(solves_from(1e4, |_| 1e7, 1e-3), 8);
        // In units: a slope of 3 per input unit of 4 and unknown unit of 2 is a speed of 6, so
        // a reach of 4/(8·10·7) input.
        let scaled = Conditioned {
            slope: 3.0,
            unit: 2.0,
            input_unit: 4.0,
            ..Conditioned::line((|_| 10.0) as fn(f64) -> f64)
        };
        assert_eq!(walked(scaled, 0.0, 1.0), 95);
        // Landings uncertain by 1e-3 (5e-4 of the unknown's unit of 2), moving at 2 (a unit
        // an input): no reach below the 32·5e-4 input over which the motion moves 32 times
        // that, longer here than the regular reach of 1/(8·10·2).
        let loose = Conditioned {
            slope: 2.0,
            within: 1e-3,
            unit: 2.0,
            ..Conditioned::line((|_| 10.0) as fn(f64) -> f64)
        };
        assert_eq!(walked(loose, 0.0, 1.0), 43);
        // What says nothing of its uncertainty has reaches without bound: one piece.
        let line = Counted::new(Line);
        assert_eq!(sweep(&line, 0.0, 0.0, 1.0, 1).0.len(), 2);
        assert_eq!(line.work(), (2, 2));
    }

    /// `inner`, its landings uncertain by `within(input)`.
    struct Uncertain<M, F> {
        inner: M,
        within: F,
    }

    impl<M: Kinematics<f64, 1>, F: Fn(f64) -> f64> Kinematics<f64, 1> for Uncertain<M, F> {
        fn solve_near(
            &self,
            input: f64,
            guess: [f64; 1],
            options: &NewtonOptions<f64>,
        ) -> Result<Solved<[f64; 1], f64>, Error<f64>> {
            self.inner.solve_near(input, guess, options)
        }

        fn slope(&self, input: f64, position: [f64; 1]) -> Result<[f64; 1], Error<f64>> {
            self.inner.slope(input, position)
        }

        fn same_branch(&self, a: f64, p: [f64; 1], b: f64, q: [f64; 1]) -> bool {
            self.inner.same_branch(a, p, b, q)
        }

        fn slope_within(
            &self,
            input: f64,
            position: [f64; 1],
        ) -> Result<([f64; 1], [f64; 1]), Error<f64>> {
            Ok((self.slope(input, position)?, [(self.within)(input)]))
        }
    }

    /// A halved piece whose landing is a few times less certain than the smoothness test's
    /// tolerance, near its rounding floor, is read: in steps of 1e-13, the halved first
    /// piece's tolerance is about 3e-14 and its landing's uncertainty 6e-14 (a threshold of
    /// the tolerance itself, or less, stops there; a tenth of the change point's blur is
    /// thousands of times that).
    #[test]
    fn a_halved_piece_near_rounding_is_read() {
        // `q = input`, whose landings are uncertain by 256·ε, four times the smoothness
        // test's rounding floor at a unit, and whose second solve (the first piece's) fails,
        // so that the walk halves its first piece.
        let solves = core::cell::Cell::new(0);
        let fuzzy = Uncertain {
            inner: Failing {
                inner: Line,
                fail: |_| {
                    solves.set(solves.get() + 1);
                    (solves.get() == 2).then_some(Error::NoConvergence {
                        iterations: 1,
                        residual_norm: 1.0,
                    })
                },
            },
            within: |_| 256.0 * f64::EPSILON,
        };
        let (samples, stop) = sweep(&fuzzy, 0.0, 0.0, 1e-13, 4);
        assert_eq!((samples.len(), stop), (5, None));
        // The start, the refused first piece, its two halves, then a piece a step.
        assert_eq!(solves.get(), 7);
    }

    /// `q = input`, which the loops fix only loosely (to a unit) within 0.01 of 1, and to the
    /// rounding of the line elsewhere.
    fn loose() -> impl Kinematics<f64, 1> {
        Uncertain {
            inner: Line,
            within: |input: f64| {
                if (input - 1.0).abs() < 0.01 {
                    1.0
                } else {
                    1e-15
                }
            },
        }
    }

    /// A walk into inputs where the loops do not fix the position stops short of them, with
    /// the position's `Inaccurate` (the landings beyond, on the branch or as loose, say
    /// neither a toggle nor a change point); with units of 100, a looseness of 1 is within the
    /// resolution, and the walk goes on, in long steps or short.
    #[test]
    fn a_walk_stops_short_of_positions_the_loops_do_not_fix() {
        let (samples, stop) = sweep(&loose(), 0.0, 0.0, 0.5, 4);
        assert_eq!(samples.len(), 2);
        assert_eq!(
            stop,
            Some(Stop::Toggle {
                last_input: 0.5,
                next_input: 1.0,
                error: Error::Inaccurate {
                    order: crate::Order::Position,
                    estimate: 1.0,
                    required: 1.0 / 16.0,
                },
            })
        );

        let wide = WithUnits {
            inner: loose(),
            units: 100.0,
            input_unit: 1.0,
        };
        let (samples, stop) = sweep(&wide, 0.0, 0.0, 0.5, 4);
        assert_eq!((samples.len(), stop), (5, None));
        // In steps of 0.05, a hundredth of a unit is 16 times the smoothness test's eighth of
        // a piece's change, and more: a piece the walk did not halve is read all the same.
        let (samples, stop) = sweep(&wide, 0.0, 0.0, 0.05, 40);
        assert_eq!((samples.len(), stop), (41, None));
    }

    /// The last two of `u32::MAX + 1` samples, then the end: no overflow of the index.
    #[test]
    fn the_longest_sweep_ends_after_its_last_sample() {
        let mut sweep = Sweep::new(&Line, 0.0, [0.0], 1.0, u32::MAX, NewtonOptions::default());
        assert_eq!(sweep.size_hint(), (0, Some(1 << 32)));
        assert_eq!(sweep.next().map(|s| s.map(|s| s.input)), Some(Ok(0.0)));
        sweep.next = u32::MAX - 1;
        let last_two: [_; 2] = core::array::from_fn(|_| sweep.next().unwrap().unwrap().input);
        assert_eq!(last_two, [f64::from(u32::MAX - 1), f64::from(u32::MAX)]);
        assert_eq!(sweep.size_hint(), (0, Some(0)));
        assert!(sweep.next().is_none());
        assert!(sweep.next().is_none());
    }
}
