//! A triangle's angles from its sides, accurate however needle-like it is.

use mechgen::Real;
use mechgen::grashof::normalised;

use crate::sums;

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

/// A triangle with sides `a` and `b` and a third side `c = c₀ + c₁` given as a sum of two
/// lengths (`c₁` negative for a difference), where the links it stands for line up: the
/// toggle at `|A O4| = l3 ± l4`, a dead centre at `|O2 B| = l3 ± l2`. Kahan's formula reads
/// four factors, `c − |a − b|`, `c + |a − b|`, `a + b + c` and `a + b − c`; [`angle`] has
/// them from `c` as rounded, which near a line-up is what the rounding of `c₀ + c₁` left of
/// them. Here each is a sum of the four lengths themselves, rounded once ([`sums::sum`]), so
/// the angle is the given lengths' own to a few units of rounding, and whether `c` reaches
/// `|a − b|` or `a + b` is decided exactly.
pub(crate) struct Triangle<T> {
    /// `c − |a − b|`: not positive where `c` is no longer than the difference.
    beyond_difference: T,
    /// `c + |a − b|`.
    with_difference: T,
    /// `a + b + c`.
    perimeter: T,
    /// `a + b − c`: not positive where `c` is no shorter than the sum.
    within_sum: T,
}

impl<T: Real> Triangle<T> {
    /// The triangle with sides `a`, `b` and `c₀ + c₁` (finite, `a` and `b` positive, the third
    /// side not negative), on lengths scaled together by a power of two.
    pub(crate) fn with_third_side(a: T, b: T, [c0, c1]: [T; 2]) -> Self {
        let [a, b, c0, c1] = normalised([a, b, c0, c1]);
        let (a, b) = longer_first(a, b);
        Triangle {
            beyond_difference: sums::sum([c0, c1, -a, b]),
            with_difference: sums::sum([c0, c1, a, -b]),
            perimeter: sums::sum([a, b, c0, c1]),
            within_sum: sums::sum([a, b, -c0, -c1]),
        }
    }

    /// Whether the third side is no longer than `|a − b|`, exactly.
    pub(crate) fn within_difference(&self) -> bool {
        self.beyond_difference <= T::zero()
    }

    /// Whether the third side is no shorter than `a + b`, exactly.
    pub(crate) fn beyond_sum(&self) -> bool {
        self.within_sum <= T::zero()
    }

    /// The angle opposite the third side, in [0, π]: 0 where it is no longer than
    /// `|a − b|`, π where it is no shorter than `a + b`.
    pub(crate) fn angle(&self) -> T {
        let zero = T::zero();
        let opposite = root_of_product(self.beyond_difference.max(zero), self.with_difference);
        let adjacent = root_of_product(self.perimeter, self.within_sum.max(zero));
        let half = opposite.atan2(adjacent);
        half + half
    }
}

/// `√(x·y)` for `x, y ≥ 0`: of the product where it is a normal number (`√(r·r)` is `r`
/// exactly), else of each apart, so that two small factors do not underflow to 0.
pub(crate) fn root_of_product<T: Real>(x: T, y: T) -> T {
    let product = x * y;
    if product >= T::min_positive_value() {
        product.sqrt()
    } else {
        x.sqrt() * y.sqrt()
    }
}

/// The two lengths, the longer first.
pub(crate) fn longer_first<T: Real>(x: T, y: T) -> (T, T) {
    if x >= y { (x, y) } else { (y, x) }
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

    /// Found by mutation testing: two factors whose product underflows are rooted apart. An
    /// isosceles triangle of unit sides about a base of 1e-170, whose apex angle is the base
    /// itself to rounding (`2·asin(c/2)`), and whose Kahan factors `c ∓ |a − b|` are both
    /// 1e-170.
    #[test]
    fn factors_whose_product_underflows_keep_their_digits() {
        assert_eq!(root_of_product(1e-200, 1e-200), 1e-200);
        assert_eq!(root_of_product(4.0, 9.0), 6.0);
        assert_near(
            Triangle::with_third_side(1.0, 1.0, [1e-170, 0.0]).angle(),
            1e-170,
        );
        assert_near(
            Triangle::with_third_side(1.0, 1.0, [2e-170, -1e-170]).angle(),
            1e-170,
        );
    }

    #[test]
    fn sides_that_close_only_flat_or_not_at_all_give_the_nearer_end() {
        assert_eq!(angle(1.0, 2.0, 3.0), PI);
        assert_eq!(angle(1.0, 2.0, 3.5), PI);
        assert_eq!(angle(2.0, 1.0, 1.0), 0.0);
        assert_eq!(angle(1.0, 3.0, 1.0), 0.0);
    }
}
