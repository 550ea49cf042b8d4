//! Walking a mechanism through its motion on one assembly branch.

use crate::{Error, NewtonOptions, Real, Solved};

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
/// silently: it stops and says so.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stop<T> {
    /// Between `last_input` and `next_input` the mechanism meets a toggle (its Jacobian is
    /// singular, or the loops stop closing): the input cannot drive it further.
    Toggle {
        /// The last input solved on the branch.
        last_input: T,
        /// The input that could not be reached.
        next_input: T,
        /// What failed there.
        error: Error<T>,
    },
    /// The position at `next_input` is on the other branch: the sweep passed a change point
    /// (all links in line, where the branches meet) or stepped over a toggle.
    BranchChange {
        /// The last input solved on the branch.
        last_input: T,
        /// The input whose position is on the other branch.
        next_input: T,
    },
}

/// An allocation-free iterator over a mechanism's positions at `start`, `start + step`, …,
/// staying on the starting position's branch: each step starts Newton from the previous
/// position moved along its velocity (a first-order predictor), and checks the result is on
/// the same branch. It yields `Ok` samples, then, if it cannot go on, one `Err(Stop)`.
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
    /// How many samples have been yielded.
    index: u32,
    /// The last solved sample, once the start is solved.
    last: Option<Sample<T, N>>,
    start_guess: [T; N],
    finished: bool,
}

impl<'a, T: Real, M: Kinematics<T, N>, const N: usize> Sweep<'a, T, M, N> {
    /// A sweep of `steps` steps of `step` from `start`, beginning near `position` (a solved
    /// position on the branch to follow, such as `assemble`'s), with Newton `options` for each
    /// step. It yields `steps + 1` samples when nothing stops it.
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
            index: 0,
            last: None,
            start_guess: position,
            finished: false,
        }
    }

    fn advance(&mut self) -> Result<Sample<T, N>, Stop<T>> {
        // From the start each time, so rounding does not accumulate over the steps.
        let input = self.start + self.step * T::constant(f64::from(self.index));
        let Some(last) = self.last else {
            // The start: polish the given position; a failure here is the caller's guess.
            let solved = self
                .mechanism
                .solve_near(input, self.start_guess, &self.options)
                .map_err(|error| Stop::Toggle {
                    last_input: input,
                    next_input: input,
                    error,
                })?;
            return Ok(Sample {
                input,
                position: solved.value,
            });
        };
        let toggle = |error| Stop::Toggle {
            last_input: last.input,
            next_input: input,
            error,
        };
        let slope = self
            .mechanism
            .slope(last.input, last.position)
            .map_err(toggle)?;
        let delta = input - last.input;
        let mut guess = last.position;
        for (g, s) in guess.iter_mut().zip(slope) {
            *g = *g + s * delta;
        }
        let position = self
            .mechanism
            .solve_near(input, guess, &self.options)
            .map_err(toggle)?
            .value;
        if !self
            .mechanism
            .same_branch(last.input, last.position, input, position)
        {
            return Err(Stop::BranchChange {
                last_input: last.input,
                next_input: input,
            });
        }
        Ok(Sample { input, position })
    }
}

impl<T: Real, M: Kinematics<T, N>, const N: usize> Iterator for Sweep<'_, T, M, N> {
    type Item = Result<Sample<T, N>, Stop<T>>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.finished || self.index > self.steps {
            return None;
        }
        let result = self.advance();
        match result {
            Ok(sample) => {
                self.last = Some(sample);
                self.index += 1;
            }
            Err(_) => self.finished = true,
        }
        Some(result)
    }
}
