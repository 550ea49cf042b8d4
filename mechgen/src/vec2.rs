//! Planar vectors, for tracked points.

/// A point or vector in the plane, in the mechanism's frame (x along the ground link's
/// reference direction, y counter-clockwise from it).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec2<T> {
    /// The x component.
    pub x: T,
    /// The y component.
    pub y: T,
}

impl<T: crate::Real> Vec2<T> {
    /// A vector from its components.
    pub const fn new(x: T, y: T) -> Self {
        Vec2 { x, y }
    }

    /// Its length.
    pub fn norm(self) -> T {
        self.x.hypot(self.y)
    }

    /// Its direction, counter-clockwise from +x, in (-π, π].
    pub fn angle(self) -> T {
        self.y.atan2(self.x)
    }
}

impl<T: crate::Real> core::ops::Add for Vec2<T> {
    type Output = Self;
    fn add(self, other: Self) -> Self {
        Vec2::new(self.x + other.x, self.y + other.y)
    }
}

impl<T: crate::Real> core::ops::Sub for Vec2<T> {
    type Output = Self;
    fn sub(self, other: Self) -> Self {
        Vec2::new(self.x - other.x, self.y - other.y)
    }
}

/// A point's acceleration split into the four parts the course notes name (seed 002). For a
/// vector `r·e^{iθ}` of varying length and angle,
/// `d²/dt²(r·e^{iθ}) = i·r·θ̈·e^{iθ} − r·θ̇²·e^{iθ} + r̈·e^{iθ} + 2·i·ṙ·θ̇·e^{iθ}`:
/// tangential, normal (centripetal), sliding and Coriolis, in that order. A point's parts
/// add these up over the vectors that lead to it.
///
/// ```
/// use mechgen::{AccelerationParts, Vec2};
/// let parts = AccelerationParts {
///     tangential: Vec2::new(1.0, 0.0),
///     normal: Vec2::new(0.0, -4.0),
///     sliding: Vec2::new(0.5, 0.0),
///     coriolis: Vec2::new(0.0, 2.0),
/// };
/// assert_eq!(parts.total(), Ok(Vec2::new(1.5, -2.0)));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AccelerationParts<T> {
    /// `i·r·θ̈·e^{iθ}`: from angular acceleration, perpendicular to each vector.
    pub tangential: Vec2<T>,
    /// `−r·θ̇²·e^{iθ}`: centripetal, toward the start of each vector.
    pub normal: Vec2<T>,
    /// `r̈·e^{iθ}`: from a changing length (a slider), along each vector.
    pub sliding: Vec2<T>,
    /// `2·i·ṙ·θ̇·e^{iθ}`: from a length changing while it turns, perpendicular to it.
    pub coriolis: Vec2<T>,
}

impl<T: crate::Real> AccelerationParts<T> {
    /// The point's acceleration: the sum of the four parts.
    ///
    /// Parts that are finite but whose sum is too large for `T` give an error rather than an
    /// infinity; an intermediate sum that overflows while the total fits is summed again at
    /// half scale (exact for parts that large), so the total is returned whenever it fits.
    ///
    /// Errors: [`Error::NonFinite`](crate::Error::NonFinite) naming `"point acceleration
    /// part"` if a part is NaN or infinite, or `"point acceleration"` if the total overflows.
    ///
    /// ```
    /// use mechgen::{AccelerationParts, Error, Vec2};
    /// let big = Vec2::new(f64::MAX, 0.0);
    /// let overflowing = AccelerationParts { tangential: big, normal: big, ..Default::default() };
    /// assert_eq!(overflowing.total(), Err(Error::NonFinite { quantity: "point acceleration" }));
    /// let cancelling = AccelerationParts { sliding: Vec2::new(-f64::MAX, 1.0), ..overflowing };
    /// assert_eq!(cancelling.total(), Ok(Vec2::new(f64::MAX, 1.0)));
    /// ```
    pub fn total(&self) -> Result<Vec2<T>, crate::Error<T>> {
        let parts = [self.tangential, self.normal, self.sliding, self.coriolis];
        let x = sum(parts.map(|p| p.x))?;
        let y = sum(parts.map(|p| p.y))?;
        Ok(Vec2::new(x, y))
    }
}

/// `((a + b) + c) + d`, or the same at half scale when an intermediate sum overflows.
fn sum<T: crate::Real>(values: [T; 4]) -> Result<T, crate::Error<T>> {
    if !values.iter().all(|v| v.is_finite()) {
        return Err(crate::Error::NonFinite {
            quantity: "point acceleration part",
        });
    }
    let add = |values: [T; 4]| values.iter().fold(T::zero(), |sum, v| sum + *v);
    let direct = add(values);
    if direct.is_finite() {
        return Ok(direct);
    }
    // Some part is within a factor of four of the largest finite number, so halving the parts
    // loses nothing the total could show.
    let half = add(values.map(|v| v * T::constant(0.5)));
    let total = half + half;
    if total.is_finite() {
        Ok(total)
    } else {
        Err(crate::Error::NonFinite {
            quantity: "point acceleration",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Error;

    #[test]
    fn a_vector_has_its_length_direction_sum_and_difference() {
        let a = Vec2::new(3.0, -4.0);
        let b = Vec2::new(0.5, 2.0);
        assert_eq!(a.norm(), 5.0);
        assert_eq!(Vec2::new(-2.0f32, 0.0).angle(), core::f32::consts::PI);
        assert_eq!(Vec2::new(1.0, 1.0).angle(), core::f64::consts::FRAC_PI_4);
        assert_eq!(a + b, Vec2::new(3.5, -2.0));
        assert_eq!(a - b, Vec2::new(2.5, -6.0));
    }

    fn parts(x: [f64; 4], y: [f64; 4]) -> AccelerationParts<f64> {
        AccelerationParts {
            tangential: Vec2::new(x[0], y[0]),
            normal: Vec2::new(x[1], y[1]),
            sliding: Vec2::new(x[2], y[2]),
            coriolis: Vec2::new(x[3], y[3]),
        }
    }

    #[test]
    fn the_total_acceleration_sums_its_parts_even_past_an_overflowing_partial_sum() {
        assert_eq!(
            parts([1.0, 2.0, 4.0, 8.0], [-1.0, 0.5, 0.25, 3.0]).total(),
            Ok(Vec2::new(15.0, 2.75))
        );
        // (MAX + MAX) overflows, but the total, MAX − MAX/2 + … , fits: summed at half scale.
        let max = f64::MAX;
        assert_eq!(
            parts([max, max, -max, -0.5 * max], [0.0; 4]).total(),
            Ok(Vec2::new(0.5 * max, 0.0))
        );
        assert_eq!(
            parts([0.0; 4], [max, max, -max, 3.0]).total(),
            Ok(Vec2::new(0.0, max))
        );
        // The total itself too large.
        assert_eq!(
            parts([max, max, 0.0, 0.0], [0.0; 4]).total(),
            Err(Error::NonFinite {
                quantity: "point acceleration"
            })
        );
        assert_eq!(
            parts([0.0; 4], [0.0, 0.0, -max, -max]).total(),
            Err(Error::NonFinite {
                quantity: "point acceleration"
            })
        );
        for bad in [f64::NAN, f64::INFINITY] {
            assert_eq!(
                parts([0.0, 0.0, 0.0, bad], [0.0; 4]).total(),
                Err(Error::NonFinite {
                    quantity: "point acceleration part"
                })
            );
            assert_eq!(
                parts([0.0; 4], [bad, 0.0, 0.0, 0.0]).total(),
                Err(Error::NonFinite {
                    quantity: "point acceleration part"
                })
            );
        }
    }
}
