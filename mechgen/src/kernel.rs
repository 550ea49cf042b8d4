//! The checked steps of straight-line scene kernels.
//!
//! A scene kernel writes a closed form out as arithmetic (see the macro's
//! `symbolic::straight`); the few steps that can fail are these, each returning the value or
//! the reason there is none.

use crate::closed::Failure;
use crate::{Accuracy, Error, Order, Real};

/// The error to report: a non-finite argument if there is one (its NaN or infinity is what
/// made the computation fail), else `error`. Kernels check their arguments only on this,
/// the failing path, so the common path pays nothing for it.
#[cold]
pub fn blame<T: Real, const N: usize>(
    arguments: [(T, &'static str); N],
    error: Error<T>,
) -> Error<T> {
    match arguments.iter().find(|(value, _)| !value.is_finite()) {
        Some(&(_, quantity)) => Error::NonFinite { quantity },
        None => error,
    }
}

/// `values` if they are all finite, else [`Error::NonFinite`] naming `quantity`: one
/// product and sum per value (an infinity or NaN times zero is NaN), a single comparison.
#[inline(always)]
pub fn all_finite<T: Real, const N: usize>(
    values: [T; N],
    quantity: &'static str,
) -> Result<[T; N], Error<T>> {
    let zero = values
        .iter()
        .fold(T::zero(), |sum, value| sum + *value * T::zero());
    if zero == T::zero() {
        Ok(values)
    } else {
        Err(Error::NonFinite { quantity })
    }
}

/// Whether every one of `values` is finite, as far as a fast kernel needs to know: their sum
/// is NaN or infinite if one of them is (an infinity plus anything finite is infinite, and
/// opposite infinities make NaN), and `sum − sum` is then NaN, else 0, so that it equals
/// itself says all are finite (a test of its own bits, with no constant to load). Two sums,
/// of the even-placed and the odd-placed values, each tested so. A sum that overflows from
/// finite values says no, wrongly but safely: the checked kernel then decides.
#[inline(always)]
pub fn outputs_finite<T: Real, const N: usize>(values: &[T; N]) -> bool {
    // Two running sums, of the even-placed and the odd-placed values: a point's x and y sit
    // side by side in one register, so the sums are one vector sum and one final addition,
    // where a single running sum takes each value apart. `-0` is the sum of none (adding
    // it is no instruction).
    let mut sums = [-T::zero(); 2];
    for (k, value) in values.iter().enumerate() {
        sums[k % 2] = sums[k % 2] + *value;
    }
    #[allow(clippy::eq_op)]
    let [even, odd] = sums.map(|sum| sum - sum);
    // Both tested (`&`, not `&&`): one comparison of the pair where it sits in one register.
    #[allow(clippy::eq_op)]
    let not_nan = (even == even) & (odd == odd);
    not_nan
}

/// `sign·√(plus − minus)`: a loop's branch-dependent root. A radicand below zero by no more
/// than rounding of `plus + |minus|` is a tangency (the root is zero); further below, the
/// loop cannot close.
#[inline]
pub fn branch_root<T: Real>(plus: T, minus: T, sign: T) -> Result<T, Failure> {
    let radicand = plus - minus;
    if radicand >= T::zero() {
        Ok(sign * radicand.sqrt())
    } else if radicand >= -T::constant(16.0) * T::epsilon() * (plus.abs() + minus.abs()) {
        Ok(T::zero())
    } else {
        Err(Failure::CannotClose)
    }
}

/// `(scale, 1/scale)`: the power of two that brings the longest of `lengths` to about 1
/// (1 if there are none, or all are zero). Scene kernels compute with every length times
/// `scale`, exactly, so no square overflows or underflows at any scale.
pub fn length_scale<T: Real>(lengths: &[T]) -> (T, T) {
    let longest = lengths.iter().fold(T::zero(), |m, l| m.max(l.abs()));
    if longest == T::zero() || !longest.is_finite() {
        return (T::one(), T::one());
    }
    let scale = crate::real::normaliser(longest);
    (scale, scale.recip())
}

/// `values` with each length among them (where `lengths` is true) multiplied by `unscale`,
/// back from a computation on the mechanism scaled by [`length_scale`] to its own units; an
/// error naming `quantity` if one is then not finite (a length beyond the float's range).
#[inline(always)]
pub fn unscaled<T: Real, const N: usize>(
    values: [T; N],
    lengths: [bool; N],
    unscale: T,
    quantity: &'static str,
) -> Result<[T; N], Error<T>> {
    let mut values = values;
    for (value, length) in values.iter_mut().zip(lengths) {
        if length {
            *value = *value * unscale;
        }
    }
    crate::newton::finite(values, quantity)
}

/// The power of two `tempo` that brings the input rates and accelerations, as the larger of
/// `max|rate|` and `√max|acceleration|`, into `[1/2, 1)`, and its inverse: time counted in
/// units of `tempo`, for a computation on the mechanism scaled by [`length_scale`], where
/// rates as far from 1 as its lengths were would leave a squared rate, or a rate times a
/// length, outside the float's range (lengths of 1e300 turning at 1e-200 rad/s have a
/// slider acceleration of 1e-100, whose squared rate of 1e-400 underflows). `(1, 1)` where
/// every one is zero or one is infinite; a NaN is passed over (the callers refuse both).
/// Exact, like the lengths' scaling: the same bits at every scale.
pub fn rate_scale<T: Real>(rates: &[T], accelerations: &[T]) -> (T, T) {
    let fastest = rates.iter().fold(T::zero(), |m, r| m.max(r.abs()));
    let sharpest = accelerations.iter().fold(T::zero(), |m, a| m.max(a.abs()));
    let largest = fastest.max(sharpest.sqrt());
    if largest == T::zero() || !largest.is_finite() {
        return (T::one(), T::one());
    }
    let tempo = crate::real::normaliser(largest);
    (tempo, tempo.recip())
}

/// `values` back from a computation on the mechanism scaled by [`length_scale`] with time
/// counted in units of [`rate_scale`]'s `tempo` (or, given `scale` and `tempo`, into it):
/// each times `unscale` where it is a length (`lengths`), and `untempo` `order` times (1,
/// rates; 2, accelerations). The factors are powers of two, applied as one, in steps that
/// all move the value the same way, so nothing overflows or underflows on the way to a
/// result that does not; an error naming `quantity` if one is then not finite.
pub fn untimed<T: Real, const N: usize>(
    values: [T; N],
    lengths: [bool; N],
    unscale: T,
    untempo: T,
    order: i32,
    quantity: &'static str,
) -> Result<[T; N], Error<T>> {
    let time = order * crate::real::binary_exponent(untempo);
    let length = crate::real::binary_exponent(unscale);
    let mut values = values;
    for (value, is_length) in values.iter_mut().zip(lengths) {
        *value = times_power_of_two(*value, if is_length { time + length } else { time });
    }
    crate::newton::finite(values, quantity)
}

/// The accuracy a result computed in the units of [`length_scale`] and [`rate_scale`]
/// states once [`untimed`] has brought it back to the mechanism's own: `stated` (the scaled
/// computation's, which scaling by powers of two leaves as it is), plus what the float's
/// smallest numbers cost where rates or accelerations leave its normal range (a rod of 1e300
/// turning at 1e-180 rad/s has an angular acceleration of about 1e-360, which no f64 holds:
/// 0 is the best there is, and it says nothing of the rod's end, which accelerates at about
/// 1e-60).
///
/// A result rounded into the subnormal numbers is within their spacing `μ` of the true
/// value: in the scaled computation's units, against the sizes the accuracy is relative to
/// there (see [`Accuracy`]: an angle's rate weighted by its column, at most twice the size;
/// a length's against the size, at least 1/2), at most `2μ/s`, with `s` the scaled input
/// rates' `Σ|ω|` (velocities, `k = 1`) or `Σω² + Σ|α|` (accelerations, `k = 2`); in the
/// mechanism's own units, where time counts `tempo` times as much and a length `scale`
/// times less, at most `2μ·tempo^k·scale/s` for a length and `2μ·tempo^k/s` for an angle.
/// The floor is `16μ·(1 + e/ε + tempo^k·scale)/s`, 16 for those factors and an input that
/// is a length, with `scale` the larger of the lengths' scale, where an unknown is a length,
/// and 1, where one is an angle (an angle's rates are no nearer the floor on a tiny
/// mechanism, nor further from it on a huge one), and `e` the stated estimate: rounding
/// inside the scaled computation is amplified as its own is (by κ and more), which matters
/// where a scaled rate is itself near the subnormal numbers (a crank at 1e-300 rad/s
/// accelerating at 1e30 rad/s², time counted by the acceleration). `rates` and
/// `accelerations` are the inputs' as the scaled computation took them, `given` the
/// caller's rates.
///
/// Zero rates add nothing (their results are exact zeros), but rates the caller gave that
/// rounded to zero in the scaled units (a crank at 1e-230 rad/s accelerating at 1e200
/// rad/s², in the acceleration's time) left the velocities nothing to go on: an infinite
/// floor. A result whose accuracy with its floor is beyond `required`, at the rates' orders
/// up to `highest`, is [`Error::Inaccurate`]; the position's is the caller's to judge, as on
/// the path that does not scale. (Velocities are linear in the rates and do not need the
/// acceleration's time: where an acceleration dwarfs the squared rate, 1e60 rad/s² beside
/// 1e-290 rad/s, they are refused where they could be had.)
#[cold]
#[allow(clippy::too_many_arguments)]
pub fn stated_in_own_units<T: Real>(
    stated: Accuracy<T>,
    given: &[T],
    rates: &[T],
    accelerations: &[T],
    tempo: T,
    scale: T,
    required: &Accuracy<T>,
    highest: Order,
) -> Result<Accuracy<T>, Error<T>> {
    let speed = rates.iter().fold(T::zero(), |sum, r| sum + r.abs());
    let spin = accelerations.iter().fold(
        rates.iter().fold(T::zero(), |sum, r| sum + *r * *r),
        |sum, a| sum + a.abs(),
    );
    let spacing = T::min_positive_value() * T::epsilon();
    // Inside the scaled computation, amplified as its own rounding is (the estimate over ε:
    // κ and more); on the way back, not.
    let floor = |order: i32, rate: T, estimate: T| {
        if rate == T::zero() {
            return T::zero();
        }
        let inside = times_power_of_two(spacing, 4) * (T::one() + estimate / T::epsilon());
        let exponent =
            order * crate::real::binary_exponent(tempo) + crate::real::binary_exponent(scale) + 4;
        (inside + times_power_of_two(spacing, exponent)) / rate
    };
    let lost = speed == T::zero() && given.iter().any(|rate| *rate != T::zero());
    let accuracy = Accuracy {
        position: stated.position,
        velocity: stated.velocity
            + if lost {
                T::infinity()
            } else {
                floor(1, speed, stated.velocity)
            },
        acceleration: stated.acceleration + floor(2, spin, stated.acceleration),
    };
    let rates_required = Accuracy {
        position: T::infinity(),
        ..*required
    };
    accuracy.within(&rates_required, highest)?;
    Ok(accuracy)
}

/// Whether the closed forms and Newton compute rates and accelerations as given: the input
/// rates' squares plus the accelerations' magnitudes within [`Real::RATES_AS_GIVEN`], and
/// the squares alone too unless every rate is zero (a crank at 1e-320 rad/s accelerating at
/// 1 rad/s² has velocities below the float's normal range), or all zero. Elsewhere (rates of
/// 1e-200 on a mechanism of 1e50, whose squares underflow while a length's acceleration
/// does not) they compute with time counted in units of [`rate_scale`], out of line, where
/// the accuracy stated says what the float's range costs ([`stated_in_own_units`]). Two
/// sums, three comparisons and a branch on the common path.
#[inline(always)]
pub fn rates_as_given<T: Real>(rates: &[T], accelerations: &[T]) -> bool {
    let squares = rates.iter().fold(T::zero(), |sum, r| sum + *r * *r);
    let sum = accelerations.iter().fold(squares, |sum, a| sum + a.abs());
    let [slowest, fastest] = T::RATES_AS_GIVEN;
    // The three together (`&`, not `&&`), for one branch; still rates, out of line.
    ((sum >= slowest) & (sum <= fastest) & (squares >= slowest))
        || still_as_given(rates, accelerations, sum)
}

/// [`rates_as_given`] where the rates' squares are not within the range: rates that are all
/// zero, with accelerations whose sum is within it, or zero too.
#[cold]
#[inline(never)]
fn still_as_given<T: Real>(rates: &[T], accelerations: &[T], sum: T) -> bool {
    let [slowest, fastest] = T::RATES_AS_GIVEN;
    rates.iter().all(|rate| *rate == T::zero())
        && ((sum >= slowest && sum <= fastest)
            || accelerations.iter().all(|value| *value == T::zero()))
}

/// `value` times `untempo` `order` times (a rate, 1; an acceleration, 2), as one power of
/// two applied in steps that all move it the same way, so that it does not overflow or
/// underflow on the way to a result that does not (see [`untimed`]).
#[inline]
pub fn retimed<T: Real>(value: T, untempo: T, order: i32) -> T {
    times_power_of_two(value, order * crate::real::binary_exponent(untempo))
}

/// `value · 2^exponent`, in steps of at most `2^60` (within every float type's normal range),
/// all moving it the same way: no step overflows or underflows unless the result does.
fn times_power_of_two<T: Real>(value: T, exponent: i32) -> T {
    let (mut value, mut exponent) = (value, exponent);
    while exponent != 0 {
        // Not `clamp`, whose check of its bounds is a panic path the no-panic check reads.
        #[allow(clippy::manual_clamp)]
        let step = exponent.max(-60).min(60);
        value = value * crate::real::power_of_two::<T>(step);
        exponent -= step;
    }
    value
}

/// Whether the closed forms and Newton solve a mechanism with these lengths as it is given:
/// its size, the sum of their magnitudes, within [`Real::SIZES_AS_GIVEN`] (not a NaN, not
/// zero). Elsewhere they solve the mechanism scaled by [`length_scale`], out of line. Within
/// those bounds no product the solvers form leaves the float's normal range (they are of
/// degree two in any one length, but for a nearly tangent triangle's area, a few units of
/// rounding times three lengths, and of lengths times squared rates), down to links some
/// 2^-40 of the size in `f32`, far shorter than its rounding can tell from nothing: rounding
/// is then the same as on the scaled mechanism, and so are the bits of the answer. One sum
/// and two comparisons.
#[inline(always)]
pub fn as_given<T: Real>(lengths: &[T]) -> bool {
    let size = lengths.iter().fold(T::zero(), |sum, l| sum + l.abs());
    let [smallest, largest] = T::SIZES_AS_GIVEN;
    size >= smallest && size <= largest
}

/// Whether the loops' scale (`Σ |magnitude|`, which the dimensions fix) is finite (false
/// for NaN): a generated `{Name}Newton` asks this once, when it is made, where Newton's common
/// path would test the scale at each solution.
#[inline(always)]
pub fn scale_within_range<T: Real>(scale: T) -> bool {
    scale.abs() <= T::max_value()
}

/// `values` with each length among them (where `lengths` is true) multiplied by `scale`: a
/// Newton guess in the units of the mechanism scaled by [`length_scale`].
#[inline(always)]
pub fn scaled<T: Real, const N: usize>(values: [T; N], lengths: [bool; N], scale: T) -> [T; N] {
    let mut values = values;
    for (value, length) in values.iter_mut().zip(lengths) {
        if length {
            *value = *value * scale;
        }
    }
    values
}

/// `error` from Newton on the mechanism scaled by [`length_scale`], in the mechanism's own
/// units: a residual times `unscale`, and the input it names the caller's own.
#[cold]
pub fn newton_at_scale<T: Real>(error: Error<T>, unscale: T, input: T) -> Error<T> {
    match error {
        Error::CannotAssemble { .. } => Error::CannotAssemble { input },
        Error::NoConvergence {
            iterations,
            residual_norm,
        } => Error::NoConvergence {
            iterations,
            residual_norm: residual_norm * unscale,
        },
        other => other,
    }
}

/// `error` from a computation at the input scaled by [`length_scale`], with the input it
/// names (where it cannot assemble) the caller's own.
#[cold]
pub fn at_input<T>(error: Error<T>, input: T) -> Error<T> {
    match error {
        Error::CannotAssemble { .. } => Error::CannotAssemble { input },
        other => other,
    }
}

/// `sign·½·√((sum − span)(sum + span)(span − |difference|)(span + |difference|))`: twice the
/// area of the triangle with sides `r1`, `r2` and `span`, given `sum = r1 + r2` and
/// `difference = r1 − r2` (Heron's formula in factors, which keeps the digits of a thin
/// triangle). Where a gap, `sum − span` or `span − |difference|`, is below zero by no more
/// than rounding of the sides, the circles touch (the area is zero); further below, they do
/// not meet and the loop cannot close.
#[inline]
pub fn triangle_root<T: Real>(sum: T, difference: T, span: T, sign: T) -> Result<T, Failure> {
    let difference = difference.abs();
    let (outer, inner) = (sum - span, span - difference);
    let band = -T::constant(8.0) * T::epsilon() * (sum + span);
    if outer >= T::zero() && inner >= T::zero() {
        Ok(sign * T::constant(0.5) * (outer * (sum + span) * inner * (span + difference)).sqrt())
    } else if outer >= band && inner >= band {
        Ok(T::zero())
    } else {
        Err(Failure::CannotClose)
    }
}

/// `1/x`, where a zero `x` (a zero-length chord) leaves the solution undetermined.
#[inline]
pub fn inverse<T: Real>(x: T) -> Result<T, Failure> {
    if x == T::zero() {
        Err(Failure::Degenerate)
    } else {
        Ok(x.recip())
    }
}

/// `1/det` of a 2×2 block whose columns' norms multiply to `1/inverse_norms`, or
/// [`Error::Singular`] where the relative determinant `|det|·inverse_norms` is at or below
/// `threshold` (or not a number).
#[inline]
pub fn inverse_determinant<T: Real>(det: T, inverse_norms: T, threshold: T) -> Result<T, Error<T>> {
    let relative = det * inverse_norms;
    if relative.abs() > threshold {
        Ok(det.recip())
    } else {
        Err(Error::Singular {
            determinant: det,
            relative_determinant: relative.abs(),
        })
    }
}

/// The angle of a unit vector `(x, y)`, in (−π, π] as `atan2(y, x)` gives it, from an arc
/// sine or arc cosine of whichever component is the smaller (where each is well
/// conditioned): less than half the cost of `atan2`, to within a few units of rounding of it
/// for a vector of length 1 to rounding.
#[inline]
pub fn unit_angle<T: Real>(y: T, x: T) -> T {
    if y.abs() <= x.abs() {
        let angle = y.asin();
        if x < T::zero() {
            T::constant(core::f64::consts::PI).copysign(y) - angle
        } else {
            angle
        }
    } else {
        x.acos().copysign(y)
    }
}

/// The angle of `(x, y)` for a checked kernel, of any length: [`unit_angle`] of the vector
/// brought to unit length. A fast kernel's [`unit_angle`] needs a vector of unit length to
/// rounding; where a link is shorter than the rounding of the linkage it hangs from, its
/// vector comes out of the triangle only to that rounding, and its direction is still the
/// best the position has. (Not `atan2`, which a microcontroller's firmware would then link
/// for this rare path alone.)
#[cold]
pub fn angle<T: Real>(y: T, x: T) -> T {
    // By the larger component first, so that no square overflows or underflows.
    let larger = x.abs().max(y.abs());
    if larger.is_infinite() {
        return T::nan();
    }
    if larger == T::zero() {
        return unit_angle(y, x);
    }
    let (x, y) = (x / larger, y / larger);
    let length = (x * x + y * y).sqrt();
    unit_angle(y / length, x / length)
}

/// The batch forms of the checked steps: the same values where those succeed, NaN where they
/// fail, and no branch, so a loop of them vectorises. The batch then redoes any non-finite
/// lane with the checked kernel, which says why.
pub mod lanes {
    use crate::Real;

    /// [`super::branch_root`], with NaN for "cannot close" and for a tangency within
    /// rounding (a slightly negative radicand): the checked kernel redoes those lanes and
    /// decides.
    #[inline(always)]
    pub fn branch_root<T: Real>(plus: T, minus: T, sign: T) -> T {
        sign * (plus - minus).sqrt()
    }

    /// [`super::triangle_root`] from the squares of its sides, `½·√((sum² − span²)·(span² −
    /// difference²))` with `sign`: no square root for the span, and NaN where the circles do
    /// not meet (a tangency within rounding included), for the checked kernel to decide.
    /// The product is negative exactly when one gap is: both cannot be, since
    /// `sum² ≥ difference²`. The squared gaps are as accurate as the linear ones where the
    /// span's square is what was computed (its rounding dominates either way).
    #[inline(always)]
    pub fn triangle_root<T: Real>(
        sum_squared: T,
        difference_squared: T,
        span_squared: T,
        sign: T,
    ) -> T {
        // `sign·½` first: a choice between two constants, not a product on each call.
        (sign * T::constant(0.5))
            * ((sum_squared - span_squared) * (span_squared - difference_squared)).sqrt()
    }

    /// [`inverse_determinant`] for a block whose columns' norms move, from the squares of
    /// their product and of the threshold: `det² > threshold²·norms²` without a square root
    /// or a division (the relative determinant's rounding aside, the same test).
    #[inline(always)]
    pub fn inverse_determinant_squared<T: Real>(det: T, squared_norms: T, squared: T) -> T {
        let inverse = det.recip();
        if det * det > squared * squared_norms {
            inverse
        } else {
            T::nan()
        }
    }

    /// `value` where a turning angle's column (its square `turning_column`) is at least as
    /// long as [`crate::rate_limits::RateLimits::least_turning_column`] (`least`), else NaN
    /// for the checked kernel to judge at the aspect the column gives (NaN for a NaN column).
    #[inline(always)]
    pub fn within_ordinary_aspect<T: Real>(value: T, turning_column: T, least: T) -> T {
        if turning_column >= least {
            value
        } else {
            T::nan()
        }
    }

    /// [`super::inverse_determinant`], with NaN for "singular". The norms' inverse is
    /// positive, so `|det|·inverse_norms` is `|det·inverse_norms|` bit for bit, and a
    /// determinant passed negated costs no negation here.
    #[inline(always)]
    pub fn inverse_determinant<T: Real>(det: T, inverse_norms: T, threshold: T) -> T {
        let inverse = det.recip();
        if det.abs() * inverse_norms > threshold {
            inverse
        } else {
            T::nan()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failure_is_blamed_on_the_first_argument_that_is_not_finite() {
        let singular = Error::Singular {
            determinant: 0.0,
            relative_determinant: 0.0,
        };
        assert_eq!(blame([(1.0, "a"), (2.0, "b")], singular), singular);
        assert_eq!(
            blame(
                [(1.0, "a"), (f64::NAN, "b"), (f64::INFINITY, "c")],
                singular
            ),
            Error::NonFinite { quantity: "b" }
        );
        assert_eq!(all_finite([1.0, -2.0, 0.0], "rates"), Ok([1.0, -2.0, 0.0]));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(
                all_finite([1.0, bad], "rates"),
                Err(Error::NonFinite { quantity: "rates" })
            );
        }
    }

    #[test]
    fn branch_roots_close_at_a_tangency_within_rounding_only() {
        assert_eq!(branch_root(13.0, 4.0, -1.0), Ok(-3.0));
        assert_eq!(branch_root(4.0, 4.0, 1.0), Ok(0.0));
        // Below zero by 16ε of plus + |minus| (here 8): a tangency; by more, no root.
        let e = f64::EPSILON;
        assert_eq!(branch_root(4.0, 4.0 + 64.0 * e, 1.0), Ok(0.0));
        assert_eq!(branch_root(4.0 - 64.0 * e, 4.0 + 64.0 * e, 1.0), Ok(0.0));
        assert_eq!(
            branch_root(4.0 - 128.0 * e, 4.0 + 128.0 * e, 1.0),
            Err(Failure::CannotClose)
        );
        assert_eq!(branch_root(-1.0, 1.0, 1.0), Err(Failure::CannotClose));
        assert_eq!(branch_root(1.0, f64::NAN, 1.0), Err(Failure::CannotClose));
    }

    #[test]
    fn a_scale_is_within_range_where_finite() {
        assert!(scale_within_range(610.0));
        assert!(scale_within_range(f64::MAX));
        assert!(!scale_within_range(f64::INFINITY));
        assert!(!scale_within_range(f64::NAN));
        assert!(scale_within_range(f32::MAX));
        assert!(!scale_within_range(f32::INFINITY));
    }

    #[test]
    fn mechanisms_are_solved_as_given_only_well_inside_the_range() {
        assert!(as_given(&[180.0, 80.0, 0.0, 200.0]));
        assert!(!as_given::<f64>(&[]));
        assert!(!as_given(&[1e-61, 1e-62]));
        assert!(!as_given(&[180.0, 2e60]));
        assert!(!as_given(&[180.0, f64::NAN]));
        assert!(!as_given(&[180.0, f64::INFINITY]));
        assert!(as_given(&[2f64.powi(-200), 1e-300]));
        assert!(as_given(&[2f64.powi(200)]));
        // f32's bounds are narrower.
        assert!(as_given(&[180.0f32, 1e-9]));
        assert!(!as_given(&[1e-5f32, 1e-6]));
        assert!(!as_given(&[3e7f32]));
    }

    /// Found by mutation testing: a mechanism solved at another scale comes back in its own
    /// units, lengths multiplied and angles left alone, and so does Newton's residual.
    #[test]
    fn lengths_go_to_the_scaled_mechanism_and_back_and_angles_stay() {
        let lengths = [true, false, true];
        assert_eq!(scaled([1.5, 0.25, -3.0], lengths, 4.0), [6.0, 0.25, -12.0]);
        assert_eq!(
            unscaled([6.0, 0.25, -12.0], lengths, 0.25, "position"),
            Ok([1.5, 0.25, -3.0])
        );
        assert_eq!(
            unscaled([f64::MAX, 0.25, 1.0], lengths, 4.0, "position"),
            Err(Error::NonFinite {
                quantity: "position"
            })
        );
        let stalled = Error::NoConvergence {
            iterations: 7,
            residual_norm: 3.0,
        };
        assert_eq!(
            newton_at_scale(stalled, 0.5, 2.0),
            Error::NoConvergence {
                iterations: 7,
                residual_norm: 1.5
            }
        );
        assert_eq!(
            newton_at_scale(Error::CannotAssemble { input: 1.0 }, 0.5, 2.0),
            Error::CannotAssemble { input: 2.0 }
        );
        assert_eq!(
            newton_at_scale(Error::OtherBranch, 0.5, 2.0),
            Error::OtherBranch
        );
    }

    #[test]
    fn triangle_roots_close_at_a_tangency_within_rounding_only() {
        let e = f64::EPSILON;
        // Sides 2 and 3 over a span of 5 (sum 5), or of 1 (difference 1): touching circles.
        assert_eq!(triangle_root(5.0, 1.0, 5.0, 1.0), Ok(0.0));
        assert_eq!(triangle_root(5.0, -1.0, 1.0, -1.0), Ok(0.0));
        // Within 8ε of sum + span (here 10) beyond either: still touching; farther, not.
        assert_eq!(triangle_root(5.0, 1.0, 5.0 + 64.0 * e, 1.0), Ok(0.0));
        assert_eq!(
            triangle_root(5.0, 1.0, 5.0 + 96.0 * e, 1.0),
            Err(Failure::CannotClose)
        );
        assert_eq!(triangle_root(5.0, 1.0, 1.0 - 32.0 * e, 1.0), Ok(0.0));
        assert_eq!(
            triangle_root(5.0, 1.0, 1.0 - 128.0 * e, 1.0),
            Err(Failure::CannotClose)
        );
        assert_eq!(triangle_root(5.0, 1.0, 6.0, 1.0), Err(Failure::CannotClose));
        assert_eq!(triangle_root(5.0, 1.0, 0.5, 1.0), Err(Failure::CannotClose));
        // Sides 5 and 3 over a span of 4: a right triangle, twice its area 12, on each side.
        assert_eq!(triangle_root(8.0, 2.0, 4.0, -1.0), Ok(-12.0));
        assert_eq!(triangle_root(8.0, -2.0, 4.0, 1.0), Ok(12.0));
    }

    #[test]
    fn lengths_are_scaled_by_the_power_of_two_of_the_longest() {
        assert_eq!(length_scale(&[3.0, -5.0, 1.0]), (0.125, 8.0));
        assert_eq!(length_scale(&[0.25f64]), (2.0, 0.5));
        assert_eq!(length_scale::<f64>(&[]), (1.0, 1.0));
        assert_eq!(length_scale(&[0.0, 0.0]), (1.0, 1.0));
        assert_eq!(length_scale(&[1.0, f64::INFINITY]), (1.0, 1.0));
        assert_eq!(inverse(4.0), Ok(0.25));
        assert_eq!(inverse(0.0f64), Err(Failure::Degenerate));
    }

    #[test]
    fn determinants_at_or_below_the_threshold_are_singular() {
        // Relative determinant 0.5·0.25 = 0.125 against thresholds on either side of it.
        assert_eq!(inverse_determinant(0.5, 0.25, 0.1), Ok(2.0));
        assert_eq!(inverse_determinant(-0.5, 0.25, 0.1), Ok(-2.0));
        for threshold in [0.125f64, 0.2] {
            assert_eq!(
                inverse_determinant(-0.5, 0.25, threshold),
                Err(Error::Singular {
                    determinant: -0.5,
                    relative_determinant: 0.125
                })
            );
            assert!(lanes::inverse_determinant(-0.5, 0.25, threshold).is_nan());
        }
        assert_eq!(lanes::inverse_determinant(-0.5, 0.25, 0.1), -2.0);
        assert!(inverse_determinant(f64::NAN, 1.0, 0.1).is_err());
    }

    #[test]
    fn checked_angles_have_any_vector_s_direction() {
        // Norms of 1.5, 3, 1, 1e-300 and 1e300, where the arc sine or cosine of a component
        // is wrong or NaN, or a square would underflow or overflow; and (found by mutation
        // testing) components in a ratio of 2 and 3.5, where the component whose arc sine or
        // cosine is taken would still be the smaller one if it were multiplied rather than
        // divided by the length.
        for (y, x) in [
            (1.2, -0.9),
            (-2.4, 1.8),
            (0.9, 1.2),
            (0.6, 0.8),
            (-0.6e-300, -0.8e-300),
            (1.2e300, -0.9e300),
            (1.5, 3.0),
            (-3.0, 1.5),
            (2.0, -7.0),
            (-7.0, -2.0),
        ] {
            let at = angle(y, x);
            assert!(
                (at - f64::atan2(y, x)).abs() <= 4.0 * f64::EPSILON,
                "{y} {x}: {at}"
            );
        }
        assert_eq!(angle(0.0f64, 0.0), 0.0);
        assert!(angle(f64::NAN, 1.0).is_nan());
        assert!(angle(1.0, f64::INFINITY).is_nan());
    }

    #[test]
    fn unit_angles_are_atan2_in_every_quadrant() {
        for degrees in (-179..=180)
            .step_by(7)
            .chain([0, 45, 90, 135, 180, -45, -90, -135])
        {
            let angle = f64::from(degrees).to_radians();
            let (y, x) = angle.sin_cos();
            let got = unit_angle(y, x);
            assert!(
                (got - y.atan2(x)).abs() <= 4.0 * f64::EPSILON,
                "{degrees}°: {got} != {}",
                y.atan2(x)
            );
        }
    }

    #[test]
    fn the_zero_vector_has_atan2s_angle() {
        assert_eq!(unit_angle(0.0f64, 0.0).to_bits(), 0f64.atan2(0.0).to_bits());
        assert_eq!(
            unit_angle(-0.0f64, 0.0).to_bits(),
            (-0f64).atan2(0.0).to_bits()
        );
    }

    #[test]
    fn a_turning_column_passes_at_the_least_length_and_above() {
        assert_eq!(lanes::within_ordinary_aspect(2.5f64, 4.0, 4.0), 2.5);
        assert_eq!(lanes::within_ordinary_aspect(2.5f64, 5.0, 4.0), 2.5);
        assert!(lanes::within_ordinary_aspect(2.5f64, 3.9, 4.0).is_nan());
        assert!(lanes::within_ordinary_aspect(2.5f64, f64::NAN, 4.0).is_nan());
    }

    #[test]
    fn the_squared_condition_test_fails_at_the_threshold_itself() {
        // |det|·inverse_norms = 0.5/2 = 1/4, the threshold, exactly: singular either way.
        assert!(inverse_determinant(0.5, 0.5, 0.25).is_err());
        assert!(lanes::inverse_determinant_squared(0.5f64, 4.0, 0.25 * 0.25).is_nan());
        assert_eq!(
            lanes::inverse_determinant_squared(0.5f64, 4.0, 0.2499 * 0.2499),
            2.0
        );
    }

    #[test]
    fn lane_branch_roots_are_the_checked_ones_or_nan() {
        assert_eq!(lanes::branch_root(13.0, 4.0, -1.0), -3.0);
        assert!(lanes::branch_root(4.0f64, 5.0, 1.0).is_nan());
    }

    #[test]
    fn outputs_are_finite_only_when_every_one_is() {
        assert!(outputs_finite(&[1.0, -2.0, 3.0e300]));
        assert!(outputs_finite::<f64, 0>(&[]));
        // Five values: the even-placed and the odd-placed in two sums; large values of
        // opposite signs in the two sums add to zero.
        assert!(outputs_finite(&[1.0, 2.0, 3.0, 4.0, 5.0]));
        assert!(!outputs_finite(&[1.0, 2.0, 3.0, 4.0, f64::NAN]));
        assert!(outputs_finite(&[f64::MAX, -f64::MAX]));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(!outputs_finite(&[1.0, bad, 2.0]));
            assert!(!outputs_finite(&[bad]));
        }
        // Opposite infinities sum to NaN, not to a finite value.
        assert!(!outputs_finite(&[f64::INFINITY, f64::NEG_INFINITY]));
        // A sum that overflows from finite values says no (the checked kernel decides):
        // two values in one of the sums, not one in each.
        assert!(!outputs_finite(&[f64::MAX, 0.0, f64::MAX]));
        assert!(outputs_finite(&[f64::MAX, f64::MAX]));
    }

    #[test]
    fn the_squared_triangle_root_is_the_linear_one_and_nan_where_circles_miss() {
        // Sides 3 and 4 about a span of 5: a right triangle, twice its area is 12.
        let (sum, difference, span) = (7.0f64, -1.0f64, 5.0f64);
        let checked = triangle_root(sum, difference, span, 1.0).unwrap();
        let squared = lanes::triangle_root(sum * sum, difference * difference, span * span, 1.0);
        assert_eq!(checked, 12.0);
        assert!((squared - checked).abs() <= 4.0 * f64::EPSILON * checked);
        assert_eq!(lanes::triangle_root(49.0, 1.0, 25.0, -1.0), -12.0);
        // A span longer than the sum, or shorter than the difference: NaN.
        assert!(lanes::triangle_root(49.0f64, 1.0, 64.0, 1.0).is_nan());
        assert!(lanes::triangle_root(49.0f64, 1.0, 0.25, 1.0).is_nan());
    }

    #[test]
    fn the_squared_condition_test_agrees_with_the_relative_determinant() {
        let (norms, threshold) = (2.0f64, 0.1f64);
        for det in [0.5, 0.21, 0.19, -0.21, -0.19, 0.0] {
            let relative = inverse_determinant(det, 1.0 / norms, threshold);
            let squared =
                lanes::inverse_determinant_squared(det, norms * norms, threshold * threshold);
            assert_eq!(relative.is_ok(), !squared.is_nan(), "det {det}");
            if let Ok(inverse) = relative {
                assert_eq!(inverse, squared);
            }
        }
    }

    #[test]
    fn time_is_counted_in_a_power_of_two_that_brings_the_rates_near_1() {
        // The larger of max|ω| and √max|α|, brought into [1/2, 1).
        assert_eq!(rate_scale(&[3.0f64], &[1.0]), (0.25, 4.0));
        assert_eq!(rate_scale(&[-3.0f64, 0.5], &[100.0]), (1.0 / 16.0, 16.0));
        assert_eq!(rate_scale(&[0.0f64], &[-100.0]), (1.0 / 16.0, 16.0));
        assert_eq!(rate_scale(&[1e-200f64], &[0.0]).0, 2f64.powi(664));
        assert_eq!(rate_scale(&[0.75f32], &[0.0]), (1.0, 1.0));
        // Nothing to scale by: as given.
        assert_eq!(rate_scale(&[0.0f64], &[0.0]), (1.0, 1.0));
        assert_eq!(rate_scale::<f64>(&[], &[]), (1.0, 1.0));
        // A NaN is passed over (the callers have refused it).
        assert_eq!(rate_scale(&[f64::NAN], &[4.0]), (0.25, 4.0));
        assert_eq!(rate_scale(&[f64::INFINITY], &[1.0]), (1.0, 1.0));
    }

    #[test]
    fn rates_come_back_in_the_callers_units_and_time() {
        let unscale = 2f64.powi(997);
        let untempo = 2f64.powi(-664);
        // A rate: times untempo, and unscale where it is a length.
        assert_eq!(
            untimed([0.5, 0.25], [false, true], 4.0, 8.0, 1, "velocity"),
            Ok([4.0, 8.0])
        );
        // An acceleration: untempo twice; 0.26 · 2^997 · 2^-1328 is about 1e-100, where
        // untempo² alone (2^-1328) would underflow.
        let [angle, length] = untimed(
            [0.26, 0.26],
            [false, true],
            unscale,
            untempo,
            2,
            "acceleration",
        )
        .unwrap();
        assert_eq!(angle, 0.0);
        assert_eq!(length, 0.26 * 2f64.powi(997 - 1328));
        // Overflow on the way but not at the end, and the other way round.
        let [up] = untimed(
            [2f64.powi(-1000)],
            [true],
            2f64.powi(1000),
            2f64.powi(500),
            2,
            "a",
        )
        .unwrap();
        assert_eq!(up, 2f64.powi(1000));
        assert_eq!(
            untimed([1.0f64], [false], 1.0, 2f64.powi(600), 2, "acceleration"),
            Err(Error::NonFinite {
                quantity: "acceleration"
            })
        );
        // f32: steps within its range.
        let [small] = untimed([0.5f32], [true], 2f32.powi(100), 2f32.powi(-60), 2, "a").unwrap();
        assert_eq!(small, 2f32.powi(-21));
    }

    #[test]
    fn rates_are_taken_as_given_within_their_range_or_all_zero() {
        assert_eq!(f64::RATES_AS_GIVEN, [2f64.powi(-600), 2f64.powi(600)]);
        assert_eq!(f32::RATES_AS_GIVEN, [2f32.powi(-60), 2f32.powi(60)]);
        assert!(rates_as_given(&[10.0f64], &[2.0]));
        assert!(rates_as_given(&[0.0f64], &[0.0]));
        assert!(rates_as_given::<f64>(&[], &[]));
        // The squares and magnitudes summed: each side of the range.
        assert!(rates_as_given(&[2f64.powi(-300)], &[0.0]));
        assert!(!rates_as_given(&[2f64.powi(-301)], &[0.0]));
        assert!(!rates_as_given(&[2f64.powi(-301)], &[2f64.powi(-600)]));
        assert!(!rates_as_given(&[2f64.powi(-301)], &[2f64.powi(-601)]));
        // The squares alone within the range too, unless the rates are all zero: a rate of
        // 1e-320 beside an acceleration of 1 is not taken as given.
        assert!(rates_as_given(&[2f64.powi(-300)], &[1.0]));
        assert!(!rates_as_given(&[1e-320f64], &[1.0]));
        assert!(rates_as_given(&[0.0f64], &[1.0]));
        assert!(rates_as_given(&[0.0f64, 1.0], &[1.0, 0.0]));
        assert!(!rates_as_given(&[1e-40f32], &[1.0]));
        assert!(rates_as_given(&[0.0f64], &[-(2f64.powi(-600))]));
        assert!(!rates_as_given(&[0.0f64], &[-(2f64.powi(-601))]));
        assert!(rates_as_given(&[2f64.powi(300)], &[0.0]));
        assert!(!rates_as_given(&[2f64.powi(300)], &[2f64.powi(548)]));
        assert!(!rates_as_given(&[1e-170f64], &[0.0]));
        assert!(rates_as_given(&[1e-9f32], &[0.0]));
        assert!(!rates_as_given(&[1e-20f32], &[0.0]));
        assert!(!rates_as_given(&[f64::NAN], &[0.0]));
    }

    #[test]
    fn a_rate_is_retimed_by_untempo_once_and_an_acceleration_twice() {
        assert_eq!(retimed(3.0f64, 4.0, 1), 12.0);
        assert_eq!(retimed(3.0f64, 4.0, 2), 48.0);
        assert_eq!(retimed(3.0f64, 0.25, 2), 0.1875);
        assert_eq!(retimed(-3.0f64, 4.0, 0), -3.0);
        // Past the float's range on the way, not at the end: 2^-1000 · (2^600)².
        assert_eq!(retimed(2f64.powi(-1000), 2f64.powi(600), 2), 2f64.powi(200));
        assert_eq!(retimed(0.5f32, 2f32.powi(-100), 1), 2f32.powi(-101));
    }
    #[test]
    fn results_back_in_their_own_units_state_the_floats_floor() {
        use crate::{Accuracy, Error, Order};
        let none = Accuracy {
            position: 0.0f64,
            velocity: 0.0,
            acceleration: 0.0,
        };
        let required = Accuracy::<f64>::required();
        let state = |rates: &[f64], accelerations: &[f64], tempo: f64, scale: f64| {
            stated_in_own_units(
                none,
                rates,
                rates,
                accelerations,
                tempo,
                scale,
                &required,
                Order::Acceleration,
            )
        };
        // The subnormals' spacing 2^-1074 over the sizes the accuracy is relative to, 16
        // times: (2^(4 − 1074)·(1 + e/ε) + 2^(k·log2(tempo) + log2(scale) + 4 − 1074)) over
        // Σ|ω| or Σω² + Σ|α| as the scaled computation took them, e the stated estimate.
        let floor = state(&[0.5], &[0.25], 2f64.powi(500), 1.0).unwrap();
        assert_eq!(floor.position, 0.0);
        assert_eq!(floor.velocity, 2f64.powi(500 + 4 - 1074) / 0.5);
        assert_eq!(floor.acceleration, 2f64.powi(1000 + 4 - 1074) / 0.5);
        // Lengths scaled up (a tiny mechanism with a length unknown) are that much nearer the
        // floor, scaled down that much further from it, down to the scaled computation's.
        let tiny = state(&[0.5], &[0.25], 2f64.powi(400), 2f64.powi(60)).unwrap();
        assert_eq!(tiny.velocity, 2f64.powi(460 + 4 - 1074) / 0.5);
        assert_eq!(tiny.acceleration, 2f64.powi(860 + 4 - 1074) / 0.5);
        let huge = state(&[0.5], &[0.25], 2f64.powi(400), 2f64.powi(-60)).unwrap();
        assert_eq!(huge.velocity, 2f64.powi(340 + 4 - 1074) / 0.5);
        assert_eq!(huge.acceleration, 2f64.powi(740 + 4 - 1074) / 0.5);
        let lower = state(&[0.5], &[0.25], 2f64.powi(40), 2f64.powi(-60)).unwrap();
        assert_eq!(lower.velocity, 2f64.powi(4 - 1074) / 0.5);
        assert_eq!(
            lower.acceleration,
            (2f64.powi(4 - 1074) + 2f64.powi(20 + 4 - 1074)) / 0.5
        );
        // A tiny mechanism turning fast, time counted in units below 1: no nearer the floor
        // than its lengths' scale times the tempo says (the slider of 1e-300 at 1e100 rad/s
        // and 1e300 rad/s², its slider's velocity 1e-200, is far from it).
        let quick = state(&[0.25], &[0.5], 2f64.powi(-499), 2f64.powi(997)).unwrap();
        assert_eq!(quick.velocity, 2f64.powi(498 + 4 - 1074) / 0.25);
        assert_eq!(
            quick.acceleration,
            (2f64.powi(4 - 1074) + 2f64.powi(-1 + 4 - 1074)) / 0.5625
        );
        // Time counted in units below 1 (fast rates) does not shrink the floor below the
        // scaled computation's own rounding.
        let fast = state(&[0.5], &[0.25], 2f64.powi(-300), 1.0).unwrap();
        assert_eq!(fast.velocity, 2f64.powi(4 - 1074) / 0.5);
        assert_eq!(fast.acceleration, 2f64.powi(4 - 1074) / 0.5);
        // Where the scaled rate is itself near the subnormal numbers (time counted by a
        // dominant acceleration), their spacing is amplified inside as the estimate says.
        let near = stated_in_own_units(
            Accuracy {
                position: 0.0,
                velocity: 1e-10,
                acceleration: 0.0,
            },
            &[1e-300],
            &[1e-310],
            &[1.0],
            2f64.powi(-100),
            1.0,
            &required,
            Order::Velocity,
        )
        .unwrap();
        let inside = 2f64.powi(4 - 1074) * (1.0 + 1e-10 / f64::EPSILON);
        assert_eq!(near.velocity, 1e-10 + inside / 1e-310);
        assert!(near.velocity > 1e-7);
        // Added to what the scaled computation stated.
        let stated = Accuracy {
            position: 1e-15,
            velocity: 2e-14,
            acceleration: 3e-13,
        };
        let stating = |stated: Accuracy<f64>| {
            stated_in_own_units(
                stated,
                &[0.5],
                &[0.5],
                &[0.25],
                2f64.powi(500),
                1.0,
                &required,
                Order::Acceleration,
            )
            .unwrap()
        };
        let sum = stating(stated);
        assert_eq!(sum.position, 1e-15);
        assert_eq!(sum.velocity, 2e-14 + floor.velocity);
        assert_eq!(sum.acceleration, 3e-13 + floor.acceleration);
        // The position's accuracy is the caller's to judge, as where nothing is scaled.
        let kept = stating(Accuracy {
            position: 1.0,
            ..stated
        });
        assert_eq!(kept.position, 1.0);
        // No rates, no floor: their results are exact zeros.
        let still = state(&[0.0], &[0.0], 2f64.powi(900), 2f64.powi(900)).unwrap();
        assert_eq!(still, none);
        // Rates the caller gave that rounded to zero in the scaled units: no velocity left.
        let lost = stated_in_own_units(
            none,
            &[1e-230],
            &[0.0],
            &[0.5],
            2f64.powi(-333),
            1.0,
            &required,
            Order::Acceleration,
        );
        assert!(matches!(
            lost,
            Err(Error::Inaccurate {
                order: Order::Velocity,
                estimate,
                ..
            }) if estimate.is_infinite()
        ));
        // Accelerations from the input's acceleration alone, and squares of several rates.
        let pushed = state(&[0.0], &[-0.5], 2f64.powi(500), 1.0).unwrap();
        assert_eq!(pushed.velocity, 0.0);
        assert_eq!(pushed.acceleration, 2f64.powi(1000 + 4 - 1074) / 0.5);
        let two = state(&[0.5, -0.5], &[0.0, 0.0], 2f64.powi(500), 1.0).unwrap();
        assert_eq!(two.velocity, 2f64.powi(500 + 4 - 1074));
        assert_eq!(two.acceleration, 2f64.powi(1000 + 4 - 1074) / 0.5);
        // Slower still (1e-200 rad/s: tempo 2^665), the accelerations are below the float's
        // range: beyond what is required, up to the order asked for.
        let slow = state(&[0.75], &[0.0], 2f64.powi(665), 1.0);
        assert!(matches!(
            slow,
            Err(Error::Inaccurate {
                order: Order::Acceleration,
                estimate,
                ..
            }) if estimate > 1e70
        ));
        let rates_only = stated_in_own_units(
            none,
            &[0.75],
            &[0.75],
            &[],
            2f64.powi(665),
            1.0,
            &required,
            Order::Velocity,
        )
        .unwrap();
        assert_eq!(rates_only.velocity, 2f64.powi(665 + 4 - 1074) / 0.75);
        // f32: spacing 2^-149.
        let single = stated_in_own_units(
            Accuracy {
                position: 0.0f32,
                velocity: 0.0,
                acceleration: 0.0,
            },
            &[0.5],
            &[0.5],
            &[0.0],
            2f32.powi(60),
            1.0,
            &Accuracy::required(),
            Order::Acceleration,
        )
        .unwrap();
        assert_eq!(single.acceleration, 2f32.powi(120 + 4 - 149) / 0.25);
    }
}
