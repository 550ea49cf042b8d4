//! Newton-Raphson on the loop-closure equations.
//!
//! The iteration lives here, once, generic over the generated residual: generated code stays
//! short (it only evaluates the residual and Jacobian) and every mechanism gets the same
//! stopping rules.

use crate::{Error, Real};

/// How hard Newton-Raphson tries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOptions<T> {
    /// Stop when every component of the loop residual is at most this, in the mechanism's
    /// length units (the seeds' worked examples use `1e-4` mm). Zero, the default, means
    /// "as accurate as the floating-point type allows": a tolerance below the rounding floor
    /// of the residual (`16 ε Σ|link lengths|`) is raised to that floor, so a tight tolerance
    /// never turns into a spurious failure.
    pub tolerance: T,
    /// The most Newton updates to make before giving up with [`Error::NoConvergence`].
    pub max_iterations: u32,
}

impl<T: Real> NewtonOptions<T> {
    /// Options with the given residual tolerance and iteration cap.
    pub fn new(tolerance: T, max_iterations: u32) -> Self {
        NewtonOptions {
            tolerance,
            max_iterations,
        }
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
}

impl<S, T> Solved<S, T> {
    /// Converts the solution, keeping the iteration count and residual.
    pub fn map<R>(self, f: impl FnOnce(S) -> R) -> Solved<R, T> {
        Solved {
            value: f(self.value),
            iterations: self.iterations,
            residual_norm: self.residual_norm,
        }
    }
}

/// One evaluation of the loop equations at an iterate.
#[derive(Clone, Copy, Debug)]
pub struct Linearisation<T, const N: usize> {
    /// The loop residual `f(x)`.
    pub residual: [T; N],
    /// The Jacobian `∂f/∂x`, row-major.
    pub jacobian: [[T; N]; N],
    /// `Σ|r|` over the loops' vector magnitudes: the size of the numbers whose rounding
    /// bounds how small the residual can get.
    pub scale: T,
}

/// Solves `f(x) = 0` by Newton-Raphson from `guess`.
///
/// `linearise` evaluates the residual and Jacobian; `solve` solves `J·dx = f` (the generator
/// passes the closed-form 2×2 solver, or the LU one).
pub fn newton<T: Real, const N: usize>(
    guess: [T; N],
    options: &NewtonOptions<T>,
    mut linearise: impl FnMut(&[T; N]) -> Linearisation<T, N>,
    solve: impl Fn([[T; N]; N], [T; N]) -> Result<[T; N], Error<T>>,
) -> Result<Solved<[T; N], T>, Error<T>> {
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
    let rounding_floor = T::constant(16.0) * T::epsilon();
    let mut x = guess;
    let mut iterations = 0;
    loop {
        let Linearisation {
            residual,
            jacobian,
            scale,
        } = linearise(&x);
        let residual_norm = max_abs(&residual);
        if !residual_norm.is_finite() {
            return Err(Error::NonFinite {
                quantity: "loop residual",
            });
        }
        if residual_norm <= options.tolerance.max(rounding_floor * scale) {
            return Ok(Solved {
                value: x,
                iterations,
                residual_norm,
            });
        }
        if iterations >= options.max_iterations {
            return Err(Error::NoConvergence {
                iterations,
                residual_norm,
            });
        }
        let step = solve(jacobian, residual)?;
        if !all_finite(&step) {
            return Err(Error::NonFinite {
                quantity: "Newton step",
            });
        }
        for (xi, di) in x.iter_mut().zip(step) {
            *xi = *xi - di;
        }
        iterations += 1;
    }
}

/// The largest absolute component (NaN if any component is NaN).
pub(crate) fn max_abs<T: Real>(values: &[T]) -> T {
    values.iter().fold(T::zero(), |acc, v| {
        if v.is_nan() || acc.is_nan() {
            T::nan()
        } else {
            acc.max(v.abs())
        }
    })
}

/// Whether every component is finite.
pub fn all_finite<T: Real>(values: &[T]) -> bool {
    values.iter().all(|v| v.is_finite())
}

/// `Err(NonFinite)` naming the first of `values` that is NaN or infinite.
#[inline]
pub fn check_finite<T: Real>(values: &[(T, &'static str)]) -> Result<(), Error<T>> {
    match values.iter().find(|(value, _)| !value.is_finite()) {
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
