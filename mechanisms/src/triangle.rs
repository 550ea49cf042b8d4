//! A triangle's angles from its sides, accurate however needle-like it is.

use mechgen::Real;
use mechgen::grashof::normalised;

/// The angle opposite side `c` of the triangle with sides `a`, `b` and `c`, in [0, π].
///
/// Kahan's formula ("Miscalculating Area and Angles of a Needle-like Triangle"): with
/// `a ≥ b`, `tan(C/2) = √(((a − b) + c)·μ / ((a + (b + c))·((a − c) + b)))`, where
/// `μ = c − (a − b)` if `b ≥ c`, else `b − (a − c)`. Each factor is a sum of lengths whose
/// only cancelling subtraction is exact (Sterbenz), so the angle is good to a few units of
/// rounding even where `acos` of the cosine rule loses half its digits (near 0 and π): a flat
/// triangle gives exactly 0 or π. The sides are scaled by a power of two first, so no square
/// overflows or underflows. Sides that cannot close give the nearer end: 0 when `c` is
/// shorter than `|a − b|`, π when it is longer than `a + b`.
pub(crate) fn angle<T: Real>(a: T, b: T, c: T) -> T {
    let [a, b, c] = normalised([a, b, c]);
    let (a, b) = if a >= b { (a, b) } else { (b, a) };
    let mu = if b >= c { c - (a - b) } else { b - (a - c) };
    let zero = T::zero();
    let opposite = (((a - b) + c) * mu).max(zero).sqrt();
    let adjacent = ((a + (b + c)) * ((a - c) + b)).max(zero).sqrt();
    let half = opposite.atan2(adjacent);
    half + half
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::{FRAC_PI_2, PI};

    fn assert_near(got: f64, want: f64) {
        assert!(
            (got - want).abs() <= 4.0 * f64::EPSILON * want.abs(),
            "{got} != {want}"
        );
    }

    /// Found by mutation testing: the sides beside the angle are sorted, longer first, or a
    /// needle's short side cancels against a long one in two factors, rounded differently.
    /// References from mpmath at 60 digits (`acos` of the cosine rule on the sides as
    /// floats), to 25: 0.8410686151370163390370973, 2.300523926649372387186951 and
    /// 0.840956861578191678260928; unsorted, the first two come out some 10⁵ units of
    /// rounding off.
    #[test]
    fn needles_whose_sides_beside_the_angle_come_in_either_order() {
        for (a, b, c, want) in [
            (1.0, 1.5e-7, 0.9999999, 0.841_068_615_137_016_3),
            (0.9999999, 1.5e-7, 1.0, 2.300_523_926_649_372_4),
            (1.0, 3e-4, 0.9998, 0.840_956_861_578_191_7),
        ] {
            assert_near(angle(a, b, c), want);
            assert_near(angle(b, a, c), want);
        }
    }

    #[test]
    fn a_right_triangle_s_angles_whatever_the_order_of_the_other_sides() {
        for (a, b) in [(3.0, 4.0), (4.0, 3.0)] {
            assert_eq!(angle(a, b, 5.0), FRAC_PI_2);
        }
        for (a, b) in [(4.0, 5.0), (5.0, 4.0)] {
            assert_near(angle(a, b, 3.0), 3f64.atan2(4.0));
        }
        for (a, b) in [(3.0, 5.0), (5.0, 3.0)] {
            assert_near(angle(a, b, 4.0), 4f64.atan2(3.0));
        }
        // At any scale (to the rounding of the sides): they are scaled by a power of two first.
        for s in [1e-300f64, 1e300] {
            assert_near(angle(3.0 * s, 4.0 * s, 5.0 * s), FRAC_PI_2);
        }
    }

    /// Found by mutation testing: of the two forms of `μ`, the one whose subtraction is exact.
    /// Isosceles needles, each angle known in closed form: the apex `2·asin(c/2)` opposite a
    /// short side `c`, and `π/2 − asin(b/2)` at the base, opposite a long side.
    #[test]
    fn needle_like_triangles_keep_their_digits() {
        for short in [1e-10f64, 3e-7, 1e-3] {
            let apex = 2.0 * (short / 2.0).asin();
            assert_near(angle(1.0, 1.0, short), apex);
            let base = FRAC_PI_2 - (short / 2.0).asin();
            assert_near(angle(1.0, short, 1.0), base);
            assert_near(angle(short, 1.0, 1.0), base);
        }
    }

    #[test]
    fn sides_that_close_only_flat_or_not_at_all_give_the_nearer_end() {
        assert_eq!(angle(1.0, 2.0, 3.0), PI);
        assert_eq!(angle(1.0, 2.0, 3.5), PI);
        assert_eq!(angle(2.0, 1.0, 1.0), 0.0);
        assert_eq!(angle(1.0, 3.0, 1.0), 0.0);
    }
}
