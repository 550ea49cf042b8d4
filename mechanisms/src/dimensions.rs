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

#[cfg(test)]
mod tests {
    use super::*;

    /// Each check refuses infinities and NaN, and draws its line at zero: a length must be
    /// above it, a distance may be on it, an offset anywhere.
    #[test]
    fn each_dimension_is_checked_against_its_own_requirement() {
        assert_eq!(positive("crank", 2.5), Ok(2.5));
        assert_eq!(non_negative("distance", 0.0), Ok(0.0));
        assert_eq!(non_negative("distance", 2.5), Ok(2.5));
        for offset in [-3.0, 0.0, 3.0] {
            assert_eq!(finite("offset", offset), Ok(offset));
        }
        let refused = |result: Result<f64, DimensionError<f64>>| {
            let error = result.unwrap_err();
            (error.name, error.requirement)
        };
        for bad in [0.0, -1.0, f64::INFINITY, f64::NAN] {
            assert_eq!(
                refused(positive("crank", bad)),
                ("crank", "positive and finite")
            );
        }
        for bad in [-1e-300, f64::INFINITY, f64::NAN] {
            assert_eq!(
                refused(non_negative("distance", bad)),
                ("distance", "non-negative and finite")
            );
        }
        for bad in [f64::NEG_INFINITY, f64::NAN] {
            assert_eq!(refused(finite("offset", bad)), ("offset", "finite"));
        }
    }
}
