//! What a scene kernel's rates are held to: the relative determinant below which a block's
//! velocities or accelerations would be less accurate than required, from the required
//! accuracy and the mechanism's aspect.
//!
//! A scene solves its rates block by block, each block judged by its own condition; the
//! general functions judge the whole Jacobian's (see [`crate::Accuracy::estimate`]). Both
//! count the aspect, the mechanism's size over its shortest angle column: a link far shorter
//! than the linkage it hangs from has a direction located only to the rounding of the whole
//! linkage, however well conditioned its own block is. A scene computes the aspect once per
//! mechanism, from the columns whose length is fixed by the dimensions. An angle whose vector
//! is a slide moves its column's length with the position (an inverted slider-crank's rocker
//! column is the distance from its pivot to the crank pin), so its block is judged at the
//! aspect it has there: within the ordinary aspect, by the thresholds computed once (which an
//! aspect up to it does not move); beyond, by the estimate at that aspect.

use crate::{Accuracy, Error, Order, Real};

/// A scene's limits on its rates: see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RateLimits<T> {
    /// The relative determinants at or below which a block's velocities (`[0]`) and
    /// accelerations (`[1]`) are refused: infinite where no condition would do.
    pub thresholds: [T; 2],
    /// The thresholds squared, for kernels that test `det² > threshold²·norms²`.
    pub squared_thresholds: [T; 2],
    /// The least squared length of a turning angle's column (one whose length moves) at
    /// which the thresholds hold: the size's square over 15.9² (the ordinary aspect, with
    /// `accuracy.rs`'s margin for rounding).
    pub least_turning_column: T,
    aspect: T,
    size: T,
    required: Accuracy<T>,
}

impl<T: Real> RateLimits<T> {
    /// The limits for rates required to be within `required`, in a mechanism whose loops'
    /// declared lengths sum to `size` and whose columns of fixed length give it the aspect
    /// `aspect` (see [`aspect`]).
    pub fn new(required: &Accuracy<T>, size: T, aspect: T) -> Self {
        let thresholds = [
            rate_threshold(Order::Velocity, required, aspect),
            rate_threshold(Order::Acceleration, required, aspect),
        ];
        RateLimits {
            thresholds,
            squared_thresholds: thresholds.map(|threshold| threshold * threshold),
            least_turning_column: size * size / T::constant(252.81),
            aspect,
            size,
            required: *required,
        }
    }

    /// These limits with the requirement `required` instead.
    pub fn with_accuracy(&self, required: &Accuracy<T>) -> Self {
        RateLimits::new(required, self.size, self.aspect)
    }

    /// [`RateLimits::inverse_determinant`] for a block with an angle whose column's length
    /// moves, `turning_column` its square at this position: within the ordinary aspect the
    /// same; beyond it (a slide passing near its pivot), judged by the estimate at the
    /// aspect the column gives, so a direction the rounding of the whole linkage leaves
    /// undetermined has no rates.
    #[inline]
    pub fn inverse_determinant_turning(
        &self,
        det: T,
        inverse_norms: T,
        order: Order,
        turning_column: T,
    ) -> Result<T, Error<T>> {
        if turning_column >= self.least_turning_column {
            return self.inverse_determinant(det, inverse_norms, order);
        }
        self.judged_at_column(det, inverse_norms, order, turning_column)
    }

    /// The rest of [`RateLimits::inverse_determinant_turning`], out of line.
    #[cold]
    fn judged_at_column(
        &self,
        det: T,
        inverse_norms: T,
        order: Order,
        turning_column: T,
    ) -> Result<T, Error<T>> {
        let relative = det * inverse_norms;
        singular(det, relative)?;
        // The larger of the mechanism's and this column's, NaN (no rates) for a NaN column.
        let here = self.size / turning_column.sqrt();
        let aspect = if here <= self.aspect {
            self.aspect
        } else {
            here
        };
        let required = Accuracy {
            position: T::infinity(),
            ..self.required
        };
        Accuracy::estimate(relative.abs().recip(), aspect).within(&required, order)?;
        Ok(det.recip())
    }

    /// `1/det` of a rate block whose columns' norms multiply to `1/inverse_norms`, for rates
    /// up to `order`; [`Error::Singular`] at or below [`crate::singular_threshold`], else
    /// [`Error::Inaccurate`] for `order` at or below its threshold, with the estimate at the
    /// block's condition and the mechanism's aspect.
    #[inline]
    pub fn inverse_determinant(
        &self,
        det: T,
        inverse_norms: T,
        order: Order,
    ) -> Result<T, Error<T>> {
        let threshold = match order {
            Order::Acceleration => self.thresholds[1],
            _ => self.thresholds[0],
        };
        let relative = det * inverse_norms;
        if relative.abs() > threshold {
            return Ok(det.recip());
        }
        self.refused(det, relative, order)
    }

    /// Why a block at relative determinant `relative` is refused.
    #[cold]
    fn refused(&self, det: T, relative: T, order: Order) -> Result<T, Error<T>> {
        singular(det, relative)?;
        let estimate = Accuracy::estimate(relative.abs().recip(), self.aspect);
        let (estimate, required) = match order {
            Order::Position => (estimate.position, self.required.position),
            Order::Velocity => (estimate.velocity, self.required.velocity),
            Order::Acceleration => (estimate.acceleration, self.required.acceleration),
        };
        Err(Error::Inaccurate {
            order,
            estimate,
            required,
        })
    }
}

/// [`Error::Singular`] for a block of determinant `det` whose relative determinant `relative`
/// is at or below [`crate::singular_threshold`], or not a number.
fn singular<T: Real>(det: T, relative: T) -> Result<(), Error<T>> {
    if relative.is_nan() || relative.abs() <= crate::singular_threshold::<T>() {
        return Err(Error::Singular {
            determinant: det,
            relative_determinant: relative.abs(),
        });
    }
    Ok(())
}

/// The aspect of a mechanism whose declared lengths sum to `size` and whose angle unknowns'
/// columns have squared norms `squared_columns`: `size` over the shortest column (1 without
/// one), infinite where that column is zero. The caller brings the lengths to about 1 first
/// (a scene's scaled mechanism), so no square overflows.
pub fn aspect<T: Real, const N: usize>(size: T, squared_columns: [T; N]) -> T {
    match squared_columns.into_iter().reduce(T::min) {
        Some(shortest) => size.abs() / shortest.sqrt(),
        None => T::one(),
    }
}

/// The relative determinant (`1/κ`) at or below which `order`'s estimate
/// ([`Accuracy::estimate`] at aspect `aspect`) exceeds `required`: at least `√ε`, where
/// [`crate::Error::Singular`] starts, and infinite where the estimate exceeds it at every
/// condition (an aspect beyond `1/√ε`, or a requirement tighter than rounding). Found by
/// bisection.
pub fn rate_threshold<T: Real>(order: Order, required: &Accuracy<T>, aspect: T) -> T {
    let required = Accuracy {
        position: T::infinity(),
        ..*required
    };
    let too_far = |kappa: T| {
        Accuracy::estimate(kappa, aspect)
            .within(&required, order)
            .is_err()
    };
    // κ from 1 to 1/√ε, bisected on its logarithm (60 halvings: to rounding).
    let (mut low, mut high) = (T::one(), T::one() / T::epsilon().sqrt());
    if too_far(low) {
        return T::infinity();
    }
    if !too_far(high) {
        return T::epsilon().sqrt();
    }
    for _ in 0..60 {
        let middle = (low * high).sqrt();
        if too_far(middle) {
            high = middle;
        } else {
            low = middle;
        }
    }
    T::one() / high
}

#[cfg(test)]
mod tests {
    use super::*;

    const E: f64 = f64::EPSILON;

    #[test]
    fn thresholds_are_where_the_estimates_reach_the_requirement() {
        let required = Accuracy::<f64>::required();
        // ε·κ·(64 + 12κ) = r at κ = (−64 + √(64² + 48r/ε))/24.
        let kappa = (-64.0 + (64.0f64 * 64.0 + 48.0 * required.velocity / E).sqrt()) / 24.0;
        let threshold = rate_threshold(Order::Velocity, &required, 1.0);
        assert!(
            (threshold * kappa - 1.0).abs() < 1e-9,
            "{threshold} vs {}",
            1.0 / kappa
        );
        let acceleration = rate_threshold(Order::Acceleration, &required, 1.0);
        assert!(acceleration > threshold);
        let estimate = Accuracy::estimate(1.0 / acceleration, 1.0);
        assert!((estimate.acceleration / required.acceleration - 1.0).abs() < 1e-9);
        // A requirement no condition up to 1/√ε exceeds: √ε.
        let loose = Accuracy {
            position: 1.0,
            velocity: 1e9,
            acceleration: 1e12,
        };
        assert_eq!(rate_threshold(Order::Acceleration, &loose, 1.0), E.sqrt());
        // The position's requirement is not the rates': one tighter than any position's
        // estimate (32ε at the best condition) leaves both thresholds as they were.
        let exact_positions = Accuracy {
            position: 1e-20,
            ..required
        };
        assert_eq!(
            rate_threshold(Order::Velocity, &exact_positions, 1.0),
            threshold
        );
        assert_eq!(
            rate_threshold(Order::Acceleration, &exact_positions, 1.0),
            acceleration
        );
    }

    #[test]
    fn thresholds_count_the_aspect() {
        let required = Accuracy::<f64>::required();
        // Up to the ordinary aspect, none; beyond it, stricter (a larger relative
        // determinant) as the estimate grows with it.
        let ordinary = rate_threshold(Order::Velocity, &required, 1.0);
        assert_eq!(rate_threshold(Order::Velocity, &required, 16.0), ordinary);
        let shrunk = rate_threshold(Order::Velocity, &required, 1e3);
        assert!(shrunk > 5.0 * ordinary, "{shrunk} vs {ordinary}");
        let estimate = Accuracy::estimate(1.0 / shrunk, 1e3);
        assert!((estimate.velocity / required.velocity - 1.0).abs() < 1e-9);
        // A link shorter than √ε of the size: no rate is accurate enough.
        assert_eq!(
            rate_threshold(Order::Velocity, &required, 1.0 / E.sqrt()),
            f64::INFINITY
        );
        assert_eq!(
            rate_threshold(Order::Acceleration, &required, f64::INFINITY),
            f64::INFINITY
        );
    }

    #[test]
    fn the_aspect_is_the_size_over_the_shortest_column() {
        assert_eq!(aspect(6.0, [4.0, 0.25, 1.0]), 12.0);
        assert_eq!(aspect(6.0f64, []), 1.0);
        assert_eq!(aspect(6.0, [4.0, 0.0]), f64::INFINITY);
    }

    #[test]
    fn rate_determinants_are_singular_then_inaccurate_then_solved() {
        let required = Accuracy::<f64>::required();
        let limits = RateLimits::new(&required, 1.0, 1.0);
        let threshold = limits.thresholds[0];
        assert_eq!(
            limits.inverse_determinant(-0.5, 0.25, Order::Velocity),
            Ok(-2.0)
        );
        // Between √ε and the threshold: inaccurate, with the estimate at the block's
        // condition and the requirement.
        let relative = threshold / 10.0;
        for (order, required) in [
            (Order::Velocity, required.velocity),
            (Order::Acceleration, required.acceleration),
        ] {
            let estimate = Accuracy::estimate(1.0 / relative, 1.0);
            let estimate = match order {
                Order::Velocity => estimate.velocity,
                _ => estimate.acceleration,
            };
            assert_eq!(
                limits.inverse_determinant(-relative * 4.0, 0.25, order),
                Err(Error::Inaccurate {
                    order,
                    estimate,
                    required,
                })
            );
        }
        // Each order reads its own threshold.
        let between = (limits.thresholds[0] + limits.thresholds[1]) / 2.0;
        assert!(
            limits
                .inverse_determinant(between, 1.0, Order::Velocity)
                .is_ok()
        );
        assert!(
            limits
                .inverse_determinant(between, 1.0, Order::Acceleration)
                .is_err()
        );
        // At or below √ε: singular.
        let sqrt_epsilon = E.sqrt();
        assert_eq!(
            limits.inverse_determinant(sqrt_epsilon, 1.0, Order::Velocity),
            Err(Error::Singular {
                determinant: sqrt_epsilon,
                relative_determinant: sqrt_epsilon
            })
        );
        assert!(matches!(
            limits.inverse_determinant(f64::NAN, 1.0, Order::Velocity),
            Err(Error::Singular { .. })
        ));
        // At the threshold itself: not solved.
        assert!(
            limits
                .inverse_determinant(threshold, 1.0, Order::Velocity)
                .is_err()
        );
        // A mechanism whose aspect leaves no rate accurate: every block refused as
        // inaccurate, with an infinite estimate, however well conditioned.
        let thin = RateLimits::new(&required, 1.0, 1e9);
        assert_eq!(
            thin.inverse_determinant(1.0, 1.0, Order::Velocity),
            Err(Error::Inaccurate {
                order: Order::Velocity,
                estimate: f64::INFINITY,
                required: required.velocity,
            })
        );
        // A new requirement keeps the aspect.
        let loose = Accuracy {
            position: 1.0,
            velocity: 1e9,
            acceleration: 1e12,
        };
        assert_eq!(thin.with_accuracy(&loose).thresholds, [f64::INFINITY; 2]);
        assert_eq!(limits.with_accuracy(&loose).thresholds, [sqrt_epsilon; 2]);
    }

    #[test]
    fn a_turning_column_is_judged_at_its_own_aspect() {
        let required = Accuracy::<f64>::required();
        // Size 16: a turning column down to 16/15.9 long keeps the mechanism's thresholds.
        let limits = RateLimits::new(&required, 16.0, 2.0);
        assert_eq!(limits.least_turning_column, 256.0 / 252.81);
        let ordinary = 256.0 / 252.81;
        for order in [Order::Velocity, Order::Acceleration] {
            for det in [0.5, 1e-3, 1e-9] {
                assert_eq!(
                    limits.inverse_determinant_turning(det, 1.0, order, ordinary),
                    limits.inverse_determinant(det, 1.0, order)
                );
            }
        }
        // Shorter: the estimate at the aspect it gives. A column of 1e-6 (aspect 1.6e7, s 1e6)
        // with a well conditioned block: its velocity's estimate is ε·(64 + 12)·1e6, within;
        // its acceleration's ε·(256 + 1)·1e12, not.
        let short = 1e-12;
        assert_eq!(
            limits.inverse_determinant_turning(0.5, 2.0, Order::Velocity, short),
            Ok(2.0)
        );
        let estimate = Accuracy::estimate(1.0, 16.0 / 1e-6);
        assert_eq!(
            limits.inverse_determinant_turning(0.5, 2.0, Order::Acceleration, short),
            Err(Error::Inaccurate {
                order: Order::Acceleration,
                estimate: estimate.acceleration,
                required: required.acceleration,
            })
        );
        // Shorter than √ε of the size: no rates.
        assert!(matches!(
            limits.inverse_determinant_turning(0.5, 2.0, Order::Velocity, 1e-20),
            Err(Error::Inaccurate {
                estimate,
                ..
            }) if estimate.is_infinite()
        ));
        // A NaN column is no column; a singular block is singular first.
        assert!(matches!(
            limits.inverse_determinant_turning(0.5, 2.0, Order::Velocity, f64::NAN),
            Err(Error::Inaccurate { .. })
        ));
        assert!(matches!(
            limits.inverse_determinant_turning(1e-9, 1.0, Order::Velocity, short),
            Err(Error::Singular { .. })
        ));
        // The position is not judged here (it was returned already): a block whose
        // condition puts the position's estimate past what is required is refused for its
        // velocity.
        assert!(matches!(
            limits.inverse_determinant_turning(1e-7, 1.0, Order::Velocity, short),
            Err(Error::Inaccurate {
                order: Order::Velocity,
                ..
            })
        ));
        // The size is kept with a new requirement.
        assert_eq!(
            limits.with_accuracy(&required).least_turning_column,
            limits.least_turning_column
        );
    }
}
