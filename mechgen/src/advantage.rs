//! Mechanical advantage.

use crate::{Error, Real};

/// The ideal (frictionless, massless) mechanical advantage: output effort over input effort,
/// which by conservation of power is the input rate over the output rate:
/// `MA = T_out / T_in = ω_in / ω_out`.
///
/// ```
/// use mechgen::MechanicalAdvantage;
/// assert_eq!(MechanicalAdvantage::from_rates(10.0, 4.0), Ok(MechanicalAdvantage::Finite(2.5)));
/// // At a dead centre the output stops: any output load is held for no input effort.
/// assert_eq!(MechanicalAdvantage::from_rates(10.0, 0.0), Ok(MechanicalAdvantage::Unbounded));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MechanicalAdvantage<T> {
    /// `ω_in / ω_out`, signed: negative when the output turns against the input.
    Finite(T),
    /// The output is stationary (a dead centre): the ratio is unbounded.
    Unbounded,
}

impl<T: Real> MechanicalAdvantage<T> {
    /// `ω_in / ω_out`, or [`Unbounded`](Self::Unbounded) when the output rate is zero to
    /// rounding (`|ω_out| ≤ 4ε·|ω_in|`) or the ratio overflows.
    ///
    /// Errors: [`Error::NonFinite`] for a rate that is NaN or infinite (`"input rate"`,
    /// `"output rate"`), or for two rates that are both zero (`"mechanical advantage"`: with
    /// nothing moving, `0/0` says nothing).
    ///
    /// ```
    /// use mechgen::{Error, MechanicalAdvantage};
    /// assert_eq!(MechanicalAdvantage::from_rates(0.0, 2.0), Ok(MechanicalAdvantage::Finite(0.0)));
    /// assert_eq!(
    ///     MechanicalAdvantage::from_rates(0.0, 0.0),
    ///     Err(Error::NonFinite { quantity: "mechanical advantage" })
    /// );
    /// assert!(MechanicalAdvantage::from_rates(1.0, f64::NAN).is_err());
    /// ```
    pub fn from_rates(input_rate: T, output_rate: T) -> Result<Self, Error<T>> {
        if !input_rate.is_finite() {
            return Err(Error::NonFinite {
                quantity: "input rate",
            });
        }
        if !output_rate.is_finite() {
            return Err(Error::NonFinite {
                quantity: "output rate",
            });
        }
        if input_rate == T::zero() && output_rate == T::zero() {
            return Err(Error::NonFinite {
                quantity: "mechanical advantage",
            });
        }
        let ratio = input_rate / output_rate;
        let stationary = output_rate.abs() <= T::constant(4.0) * T::epsilon() * input_rate.abs();
        Ok(if stationary || !ratio.is_finite() {
            MechanicalAdvantage::Unbounded
        } else {
            MechanicalAdvantage::Finite(ratio)
        })
    }

    /// The finite value, if any.
    ///
    /// ```
    /// use mechgen::MechanicalAdvantage;
    /// assert_eq!(MechanicalAdvantage::from_rates(3.0, 1.5)?.finite(), Some(2.0));
    /// assert_eq!(MechanicalAdvantage::<f64>::Unbounded.finite(), None);
    /// # Ok::<(), mechgen::Error<f64>>(())
    /// ```
    pub fn finite(self) -> Option<T> {
        match self {
            MechanicalAdvantage::Finite(value) => Some(value),
            MechanicalAdvantage::Unbounded => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use MechanicalAdvantage::{Finite, Unbounded};

    #[test]
    fn the_advantage_is_the_ratio_of_the_rates_with_its_sign() {
        assert_eq!(MechanicalAdvantage::from_rates(10.0, 4.0), Ok(Finite(2.5)));
        assert_eq!(
            MechanicalAdvantage::from_rates(-10.0, 4.0),
            Ok(Finite(-2.5))
        );
        assert_eq!(
            MechanicalAdvantage::from_rates(10.0, -4.0),
            Ok(Finite(-2.5))
        );
        assert_eq!(MechanicalAdvantage::from_rates(0.0, -4.0), Ok(Finite(0.0)));
        assert_eq!(Finite(2.5).finite(), Some(2.5));
        assert_eq!(Unbounded::<f64>.finite(), None);
    }

    #[test]
    fn an_output_stationary_to_rounding_is_unbounded() {
        // At most 4ε of the input rate: stationary; 8ε: a finite ratio of 1/(8ε).
        let e = f64::EPSILON;
        for input in [1.0, -3.0] {
            assert_eq!(
                MechanicalAdvantage::from_rates(input, 4.0 * e * input),
                Ok(Unbounded)
            );
            assert_eq!(
                MechanicalAdvantage::from_rates(input, -4.0 * e * input),
                Ok(Unbounded)
            );
            assert_eq!(
                MechanicalAdvantage::from_rates(input, 8.0 * e * input),
                Ok(Finite(1.0 / (8.0 * e)))
            );
        }
        assert_eq!(MechanicalAdvantage::from_rates(2.0, 0.0), Ok(Unbounded));
    }

    #[test]
    fn rates_that_say_nothing_are_errors_naming_them() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(
                MechanicalAdvantage::from_rates(bad, 1.0),
                Err(Error::NonFinite {
                    quantity: "input rate"
                })
            );
            assert_eq!(
                MechanicalAdvantage::from_rates(1.0, bad),
                Err(Error::NonFinite {
                    quantity: "output rate"
                })
            );
        }
        assert_eq!(
            MechanicalAdvantage::from_rates(0.0, 0.0),
            Err(Error::NonFinite {
                quantity: "mechanical advantage"
            })
        );
    }
}
