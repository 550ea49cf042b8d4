//! What can go wrong when a mechanism is solved, as values rather than panics.

use core::fmt;

/// Why a position, velocity or acceleration could not be computed.
///
/// Every generated solver returns this instead of panicking or handing back NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Error<T> {
    /// An argument, a parameter or a result is NaN or infinite.
    NonFinite {
        /// Which quantity: `"parameter l3"`, `"input theta2"`, `"velocity"`, ...
        quantity: &'static str,
    },
    /// The loops cannot close at this input: the links are too short or too long to meet
    /// (the input is outside the mechanism's range of motion).
    CannotAssemble {
        /// The input at which assembly was asked for (for a mechanism of several inputs,
        /// the first declared).
        input: T,
    },
    /// The Jacobian of the loop equations with respect to the unknowns is singular at this
    /// configuration (a toggle or change point), so the unknowns are not determined by the
    /// input there and their rates are unbounded.
    Singular {
        /// The determinant of the row-normalised Jacobian.
        determinant: T,
        /// The determinant divided by the product of the Jacobian's column norms (Hadamard's
        /// bound): 1 when the unknowns move the loops in orthogonal directions, 0 for a
        /// singular matrix; singular means at most `mechgen::singular_threshold()` (`√ε`).
        /// The inverse of the condition estimate.
        relative_determinant: T,
    },
    /// A rate or acceleration whose estimated error (see [`crate::Accuracy`]) exceeds the
    /// accuracy a result must have: near a toggle or change point, where the position is
    /// itself known only to `κ·ε`, its rates have fewer correct digits than required; so do a
    /// link's angle where the link is shorter than `√ε` of the mechanism, and results that
    /// leave the float's range (an angular acceleration of 1e-400 rad/s²).
    Inaccurate {
        /// The first derivative order whose estimate is too large.
        order: crate::Order,
        /// Its estimated relative error.
        estimate: T,
        /// The most it may be ([`crate::Accuracy::required`]).
        required: T,
    },
    /// Newton-Raphson converged, but on the other assembly branch than its guess was on (by
    /// the generated `branch_of`): the guess was too far from the branch it started on.
    OtherBranch,
    /// Newton-Raphson did not bring the residual below the tolerance within the
    /// iteration cap.
    NoConvergence {
        /// Newton updates made.
        iterations: u32,
        /// Largest absolute loop residual at the last iterate, in length units.
        residual_norm: T,
    },
}

impl<T: fmt::Display> fmt::Display for Error<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite { quantity } => write!(f, "{quantity} is not finite"),
            Error::CannotAssemble { input } => write!(
                f,
                "the mechanism cannot be assembled at input {input}: it is outside the range \
                 of motion"
            ),
            Error::Singular {
                determinant,
                relative_determinant,
            } => write!(
                f,
                "the loop Jacobian is singular (determinant {determinant}, relative \
                 determinant {relative_determinant}): the mechanism is at a toggle or \
                 change point"
            ),
            Error::Inaccurate {
                order,
                estimate,
                required,
            } => write!(
                f,
                "the {} would be off by up to {estimate} relative (more than the {required} \
                 required): too near a toggle or change point, with a link too short against \
                 the mechanism, or with rates whose results leave the float's range",
                match order {
                    crate::Order::Position => "position",
                    crate::Order::Velocity => "velocity",
                    crate::Order::Acceleration => "acceleration",
                }
            ),
            Error::OtherBranch => write!(
                f,
                "Newton-Raphson converged on the other assembly branch than its guess's"
            ),
            Error::NoConvergence {
                iterations,
                residual_norm,
            } => write!(
                f,
                "Newton-Raphson did not converge in {iterations} iterations \
                 (residual norm {residual_norm})"
            ),
        }
    }
}

impl<T: fmt::Debug + fmt::Display> core::error::Error for Error<T> {}

/// A batch (a scene's `*_batch`) stopped: the input at `index` failed with `error`. The
/// outputs before it are results; the one at `index` and those after are not (the fast
/// path's values, unchecked: NaN or infinite where it failed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BatchError<T> {
    /// The position of the failing input in the batch's inputs.
    pub index: usize,
    /// Why it failed, as the scene's kernel says at that input.
    pub error: Error<T>,
}

impl<T: fmt::Display> fmt::Display for BatchError<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "input {} of the batch: {}", self.index, self.error)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::format;

    #[test]
    fn each_error_says_what_went_wrong() {
        let cases = [
            (
                Error::NonFinite {
                    quantity: "input theta2",
                },
                "input theta2 is not finite",
            ),
            (
                Error::CannotAssemble { input: 2.5 },
                "the mechanism cannot be assembled at input 2.5: it is outside the range of \
                 motion",
            ),
            (
                Error::Singular {
                    determinant: 0.0,
                    relative_determinant: 1e-9,
                },
                "the loop Jacobian is singular (determinant 0, relative determinant \
                 0.000000001): the mechanism is at a toggle or change point",
            ),
            (
                Error::Inaccurate {
                    order: crate::Order::Velocity,
                    estimate: 0.5,
                    required: 0.25,
                },
                "the velocity would be off by up to 0.5 relative (more than the 0.25 required): \
                 too near a toggle or change point, with a link too short against the \
                 mechanism, or with rates whose results leave the float's range",
            ),
            (
                Error::OtherBranch,
                "Newton-Raphson converged on the other assembly branch than its guess's",
            ),
            (
                Error::NoConvergence {
                    iterations: 50,
                    residual_norm: 0.125,
                },
                "Newton-Raphson did not converge in 50 iterations (residual norm 0.125)",
            ),
        ];
        for (error, message) in cases {
            assert_eq!(format!("{error}"), message);
        }
        let batch = BatchError {
            index: 7,
            error: Error::CannotAssemble { input: 3.0 },
        };
        assert_eq!(
            format!("{batch}"),
            "input 7 of the batch: the mechanism cannot be assembled at input 3: it is outside \
             the range of motion"
        );
    }
}
