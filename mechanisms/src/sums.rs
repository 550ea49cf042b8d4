//! Signed sums of a few lengths, rounded once however far they cancel.
//!
//! Where links line up, the analyses ask how far apart two sums of lengths are:
//! `l3 + l4 − (l1 + l2)` for a toggle at θ2 = π, `l3 − l2 − |c|` for a slider-crank's folded
//! dead centre. Added in turn, each addition rounds, and near a line-up the rounding of the
//! partial sums is all that is left: a toggle within rounding of an end came out on the wrong
//! side of it, and one near it as the toggle of lengths a unit of rounding away, which near
//! the ends is far from the given lengths' own. Here each sum is as if computed exactly and
//! rounded once, so its sign is right and it is zero only where the lengths line up exactly.

use mechgen::Real;

/// `(s, e)` with `s = fl(a + b)` and `s + e = a + b` exactly (Knuth's TwoSum; exact under
/// gradual underflow too, where a sum that rounds is not subnormal).
#[inline]
fn two_sum<T: Real>(a: T, b: T) -> (T, T) {
    let s = a + b;
    let b_rounded = s - a;
    let a_rounded = s - b_rounded;
    (s, (a - a_rounded) + (b - b_rounded))
}

/// [`two_sum`] for `|a| ≥ |b|` (or `a` zero): Dekker's Fast2Sum.
#[inline]
fn fast_two_sum<T: Real>(a: T, b: T) -> (T, T) {
    let s = a + b;
    (s, b - (s - a))
}

/// `a + b + c + d`, within `u·(1 + 4u)` of the exact sum's magnitude (`u` the unit roundoff:
/// `2⁻⁵³` for `f64`): the exact sum rounded, but for a second-order term. So its sign is the
/// exact sum's, and it is zero exactly where that is.
///
/// `a + b` and `c + d` each make an exact double-word (TwoSum), which the accurate
/// double-word addition of Joldes, Muller and Popescu ("Tight and rigorous error bounds for
/// basic building blocks of double-word arithmetic", 2017, Algorithm 6, relative error at
/// most `3u²/(1 − 4u)` of the exact result, however it cancels) adds; its high word is the
/// result. The terms must be finite and their sums not overflow (lengths scaled by a power of
/// two first, as [`normalised`](mechgen::grashof::normalised) scales them).
pub(crate) fn sum<T: Real>([a, b, c, d]: [T; 4]) -> T {
    let (x_high, x_low) = two_sum(a, b);
    let (y_high, y_low) = two_sum(c, d);
    let (s_high, s_low) = two_sum(x_high, y_high);
    let (t_high, t_low) = two_sum(x_low, y_low);
    let (v_high, v_low) = fast_two_sum(s_high, s_low + t_high);
    fast_two_sum(v_high, t_low + v_low).0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact sum of four doubles, rounded to the nearest: by integers, each term's
    /// significand shifted to a common exponent (terms within 2⁶⁰ of each other's scale).
    fn rounded_exact(terms: [f64; 4]) -> f64 {
        let lowest = terms
            .iter()
            .filter(|t| **t != 0.0)
            .map(|t| t.abs().log2().floor() as i32 - 53)
            .min()
            .unwrap_or(0);
        let exact: i128 = terms.iter().map(|t| (t / 2f64.powi(lowest)) as i128).sum();
        // i128 to f64 rounds to nearest, and the power of two is exact.
        exact as f64 * 2f64.powi(lowest)
    }

    #[test]
    fn sums_that_cancel_are_the_exact_sum_rounded() {
        let u = f64::EPSILON / 2.0;
        for terms in [
            // A toggle at π: l3 + l4 against l1 + l2, equal but for the last bit of one.
            [1.0 + 2.0 * u, 3.0, -2.0, -2.0],
            [0.1, 0.7, -0.3, -0.5],
            [1.0, 1e-17, -1.0, 3e-18],
            [1e-16, 1.0, -1.0 + u, -1e-16],
            [0.3, -0.1, -0.2, 1e-20],
            // Exactly in line.
            [0.25, 0.5, -0.125, -0.625],
            [1e-10, -1e-10, 1.0, -1.0],
        ] {
            let want = rounded_exact(terms);
            let got = sum(terms);
            assert!(
                (got - want).abs() <= 2.0 * u * want.abs(),
                "{terms:?}: {got:e} vs {want:e}"
            );
            assert_eq!(got == 0.0, want == 0.0, "{terms:?}");
            // Rounded in turn, some come out on the wrong side of zero, or at it.
            let naive = terms.iter().sum::<f64>();
            if want != 0.0 && naive.signum() != want.signum() {
                assert_eq!(got.signum(), want.signum());
            }
        }
        // Left to right, 0.1 + 0.7 − 0.3 − 0.5 is −5.6e-17, twice the exact sum of these
        // doubles, −2.8e-17 (Python's fractions).
        assert_eq!(
            [0.1f64, 0.7, -0.3, -0.5].iter().sum::<f64>(),
            -5.551115123125783e-17
        );
        assert_eq!(sum([0.1, 0.7, -0.3, -0.5]), -2.7755575615628914e-17);
        assert!(sum([1.0f32, 1e-9, -1.0, 0.0]) == 1e-9);
    }

    /// Found by mutation testing: the last correction's sign. `1 + (2⁻⁵³ − 2⁻¹⁰⁵) + 2⁻¹⁰⁵ +
    /// 2⁻¹⁷⁰` is a hair above the midpoint of 1 and its successor; the double-word addition
    /// meets that midpoint as a tie (its last low word, 2⁻¹⁷⁰, below the rounding of the
    /// other) and gives 1, within `u·(1 + 2⁻¹¹⁷)` of the exact sum; a correction that
    /// subtracted the tie's low word gave 1 − 2⁻⁵³, `2u` off (Python's fractions).
    #[test]
    fn a_sum_at_a_rounding_tie_stays_within_its_bound() {
        let u = f64::EPSILON / 2.0;
        let terms = [1.0, u - u * u * 2.0, u * u * 2.0, 2f64.powi(-170)];
        assert_eq!(terms[1] + terms[2], u);
        assert_eq!(sum(terms), 1.0);
    }

    /// Drawn sums that cancel to any depth, each pair of terms rounding when added (so that
    /// every low word of the double-word addition counts): the exact sum rounded, every time.
    #[test]
    fn drawn_sums_that_cancel_are_the_exact_sum_rounded() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut unit = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..20_000 {
            let power = |p: f64| 2f64.powi(p as i32);
            let scale = power((unit() * 40.0).floor() - 20.0);
            let a = (1.0 + unit()) * scale;
            let b = (1.0 + unit()) * scale * power(-(unit() * 40.0).floor());
            // Either the long terms or the short ones cancel to a part in up to 2⁵³, with the
            // other pair's own roundings (the low words of `a + b` and `c + d`) left apart.
            let near = |x: f64, unit: f64| {
                x * (1.0 + (unit - 0.5) * power(-(unit * 997.0 % 53.0).floor()))
            };
            let (c, d) = if unit() < 0.5 {
                (-near(a, unit()), -b + (unit() - 0.5) * scale * power(-50.0))
            } else {
                (-a, -near(b, unit()))
            };
            let terms = [a, b, c, d];
            let want = rounded_exact(terms);
            let got = sum(terms);
            assert!(
                (got - want).abs() <= f64::EPSILON * want.abs(),
                "{terms:?}: {got:e} vs {want:e}"
            );
        }
    }
}
