//! Checks on the dimensions a shipped mechanism is built from.

use core::fmt;

use mechgen::Real;

/// A dimension a constructor refused, and why.
///
/// ```
/// use mechanisms::{DimensionError, FourBar};
/// let error = FourBar::new(180.0, -80.0, 200.0, 150.0).unwrap_err();
/// assert_eq!(error.name, "crank");
/// assert_eq!(error.to_string(), "crank = -80 must be positive and finite");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DimensionError<T> {
    /// The dimension's name, as in the constructor's arguments.
    pub name: &'static str,
    /// The value given.
    pub value: T,
    /// What it must be.
    pub requirement: &'static str,
}

impl<T: fmt::Display> fmt::Display for DimensionError<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} = {} must be {}",
            self.name, self.value, self.requirement
        )
    }
}

impl<T: fmt::Debug + fmt::Display> core::error::Error for DimensionError<T> {}

/// `value` if it is a positive, finite length.
pub(crate) fn positive<T: Real>(name: &'static str, value: T) -> Result<T, DimensionError<T>> {
    if value.is_finite() && value > T::zero() {
        Ok(value)
    } else {
        Err(DimensionError {
            name,
            value,
            requirement: "positive and finite",
        })
    }
}

/// `value` if it is finite (an offset or an angle, which may be zero or negative).
pub(crate) fn finite<T: Real>(name: &'static str, value: T) -> Result<T, DimensionError<T>> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(DimensionError {
            name,
            value,
            requirement: "finite",
        })
    }
}

/// `value` if it is a finite, non-negative distance (a coupler point may sit on a pin).
pub(crate) fn non_negative<T: Real>(name: &'static str, value: T) -> Result<T, DimensionError<T>> {
    if value.is_finite() && value >= T::zero() {
        Ok(value)
    } else {
        Err(DimensionError {
            name,
            value,
            requirement: "non-negative and finite",
        })
    }
}
