//! The sine and cosine of an angle given as a sum (`theta3 + delta`, `theta2 + gamma`), of
//! the exact sum rather than of its rounding.
//!
//! Rounding the sum first moves the angle by up to half an ulp of the sum: nothing for angles
//! of a turn or two, but 3.6e-12 rad for a crank that has turned ten thousand times and an
//! eighth of a radian for an offset of 1e15, where every term alone is exact and the platform's
//! `sin_cos` reduces any one of them exactly. An adversarial review found both as `Ok`s
//! hundreds of times less accurate than they said.

use crate::Real;
use crate::newton::{TURN_LIMIT, rotate, sin_cos};

/// `(sin, cos)` of the exact sum of `terms`: the sum is rounded as usual, its rounding error
/// kept exactly (Knuth's two-sum, cascaded), and the rounded angle turned by that error, to
/// first order where its square is below `ε/8`, by Newton's rotation series (`rotate`) up to
/// `2⁻¹⁰` rad, and by the angle-sum formulas beyond. Exact for two terms; for more, the parts each addition
/// loses are themselves added rounded (Ogita, Rump and Oishi's Sum2, as if in twice the
/// precision), so three terms of which two beyond 2⁵³ cancel can lose the third (an
/// adversarial review's `[−1e300, f64::MAX, −1e16]`). A NaN or infinite term gives NaN.
///
/// ```
/// use mechgen::__private::sin_cos_of_sum;
/// // A crank ten thousand turns round (62,833 rad) with an offset of 0.3 rad: the sine of
/// // the exact sum is 0.99233814812970418 (mpmath); rounding the sum first gives one
/// // 3.6e-13 off.
/// let (sin, _) = sin_cos_of_sum([62833.0, 0.3]);
/// assert!((sin - 0.9923381481297042_f64).abs() <= 2e-16);
/// assert!(((62833.0_f64 + 0.3).sin() - 0.9923381481297042).abs() > 3e-13);
/// ```
#[inline(always)]
pub fn sin_cos_of_sum<T: Real, const N: usize>(terms: [T; N]) -> (T, T) {
    let Some((&first, rest)) = terms.split_first() else {
        return (T::zero(), T::one());
    };
    let mut sum = first;
    let mut error = T::zero();
    for &term in rest {
        let (rounded, lost) = two_sum(sum, term);
        sum = rounded;
        error = error + lost;
    }
    let (sin, cos) = sin_cos(sum);
    // False for NaN, which then goes through the last formulas, NaN in and out.
    if error * error <= T::epsilon() * T::constant(0.125) {
        (sin + error * cos, cos - error * sin)
    } else if error.abs() <= T::constant(TURN_LIMIT) {
        rotate(sin, cos, error)
    } else {
        let (sin_error, cos_error) = sin_cos(error);
        (
            sin * cos_error + cos * sin_error,
            cos * cos_error - sin * sin_error,
        )
    }
}

/// `a + b` rounded, and what the rounding lost, exactly (Knuth): `rounded + lost = a + b`.
#[inline(always)]
fn two_sum<T: Real>(a: T, b: T) -> (T, T) {
    let rounded = a + b;
    let b_part = rounded - a;
    let a_part = rounded - b_part;
    (rounded, (a - a_part) + (b - b_part))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_sum_keeps_what_rounding_loses() {
        let (rounded, lost) = two_sum(1.0, 1e-20);
        assert_eq!((rounded, lost), (1.0, 1e-20));
        let (rounded, lost) = two_sum(1e-20, 1.0);
        assert_eq!((rounded, lost), (1.0, 1e-20));
        let (rounded, lost) = two_sum(0.1, 0.2);
        assert_eq!(rounded, 0.30000000000000004);
        assert_eq!(lost, -2.7755575615628914e-17);
    }

    /// Each of the three ways of turning by the lost part, against the sine and cosine of
    /// the exact sum (mpmath at 50 digits, of the doubles as given), where rounding the sum
    /// first is 3.6e-13, 2.0e-7 and 0.23 off.
    #[test]
    fn a_sum_is_taken_exactly_at_every_size() {
        for (crank, offset, sin_exact, cos_exact, way) in [
            (
                62833.0,
                0.3,
                0.9923381481297042,
                0.12355160770507714,
                "first order",
            ),
            // The sum rounded 2.9e-8 off, just past where the first-order turn holds
            // (its neglected e²/2 is 4.3e-16).
            (
                268435457.0,
                0.3000000411272049,
                -0.4233421746373641,
                0.9059698687998997,
                "series, near first order",
            ),
            (
                62831853073.0,
                0.3,
                0.9977789717852033,
                0.06661173667802595,
                "series",
            ),
            (
                6283185307179587.0,
                0.3,
                0.7332400049229836,
                0.6799699222616711,
                "angle sum",
            ),
        ] {
            let (sin, cos): (f64, f64) = sin_cos_of_sum([crank, offset]);
            assert!(
                (sin - sin_exact).abs() <= 2e-16 && (cos - cos_exact).abs() <= 2e-16,
                "{way}: {sin} {cos} against {sin_exact} {cos_exact}"
            );
            let (sin, cos) = sin_cos_of_sum([offset, crank]);
            assert!((sin - sin_exact).abs() <= 2e-16 && (cos - cos_exact).abs() <= 2e-16);
        }
    }

    #[test]
    fn three_terms_and_f32() {
        // 62833 + 0.25 + 0.05 is 62833.3 exactly in the reals; the doubles 0.25 and 0.05
        // sum to 0.3 within 1.4e-17.
        let (sin, cos) = sin_cos_of_sum([62833.0, 0.25, 0.05_f64]);
        assert!((sin - 0.9923381481297042).abs() <= 2e-16);
        assert!((cos - 0.12355160770507714).abs() <= 2e-16);
        // f32: 1000 + 0.3 rounds 2.4e-5 away; taken exactly, 1000.3's sine to f32's rounding.
        let (sin, _) = sin_cos_of_sum([1000.0_f32, 0.3]);
        let exact = num_traits::Float::sin(1000.0 + f64::from(0.3_f32)) as f32;
        assert!((sin - exact).abs() <= 1.2e-7, "{sin} {exact}");
    }

    #[test]
    fn non_finite_terms_give_nan() {
        for terms in [
            [f64::NAN, 1.0],
            [f64::INFINITY, 1.0],
            [1.0, f64::NEG_INFINITY],
        ] {
            let (sin, cos) = sin_cos_of_sum(terms);
            assert!(sin.is_nan() && cos.is_nan());
        }
    }
}
