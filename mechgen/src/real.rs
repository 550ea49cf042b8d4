//! The scalar type generated code is generic over.

use core::fmt::{Debug, Display};

/// A floating-point scalar the generated kinematics run on: `f32` or `f64`.
///
/// All the maths comes from [`num_traits::Float`]; this trait only adds the one conversion
/// generated code needs, from the `f64` constants the macro folded at compile time, and the
/// per-type constants of the branch-free [`fast::sin_cos`](crate::fast::sin_cos).
pub trait Real: num_traits::Float + Debug + Display + Default + Send + Sync + 'static {
    /// Converts a compile-time constant to this type, rounding to nearest.
    fn constant(value: f64) -> Self;

    /// The largest `|x|` for which [`fast::sin_cos`](crate::fast::sin_cos) meets its error
    /// bound; beyond it that function returns NaN. Read it through
    /// [`fast::sin_cos_limit`](crate::fast::sin_cos_limit).
    #[doc(hidden)]
    const SIN_COS_LIMIT: Self;

    /// Whether generated code's scalar sines and cosines (`__private::sin_cos`) inline
    /// [`fast::sin_cos`](crate::fast::sin_cos) within its limit: for `f64` with the `std`
    /// feature, where its arithmetic takes fewer instructions than a call of the C library's
    /// `sincos`; not for `f32`, whose `sincosf` is cheaper still, nor without `std`, where
    /// `libm`'s is Rust the compiler sees into and inlining ours at every call would only
    /// grow the code (a microcontroller's flash).
    #[doc(hidden)]
    const INLINE_SIN_COS: bool;

    /// `2/π`, rounded to nearest: the quadrant of `x` is `x·(2/π)` rounded to an integer.
    #[doc(hidden)]
    const SIN_COS_TWO_OVER_PI: Self;

    /// `1.5·2^p` for a `p`-bit significand: adding and then subtracting it rounds a number of
    /// magnitude below `2^(p−2)` to the nearest integer (ties to even), with no branch and no
    /// call (`round` is a library call on x86-64's baseline SSE2, and blocks vectorisation).
    #[doc(hidden)]
    const SIN_COS_SHIFTER: Self;

    /// `π/2` in four parts for the Cody–Waite reduction `x − n·π/2`: the first three carry
    /// few enough bits (33 of f64's 53, 14 of f32's 24) that `n·part` is exact for every
    /// quadrant `n` within [`SIN_COS_LIMIT`](Self::SIN_COS_LIMIT) (`|n| < 2^20`, resp.
    /// `2^10`); the fourth is the next full-precision part. Each is truncated, not rounded,
    /// so all are positive and `n·part` is +0 when `n` is (which keeps `sin(−0) = −0`).
    /// Their sum is within `2^-159` (f64) or `2^-68` (f32) of `π/2`.
    #[doc(hidden)]
    const SIN_COS_PI_OVER_2: [Self; 4];

    /// The minimax polynomials of [`fast::sin_cos`](crate::fast::sin_cos) in `z = r²`:
    /// `(S(z), C(z))` with `sin r ≈ r + r³·S(z)` and `cos r ≈ 1 − z/2 + z²·C(z)` for
    /// `|r| ≤ (π/4)(1 + 2^-8)`, fitted by Remez exchange to the relative error of `sin r`
    /// and `cos r` with each coefficient rounded to this type in turn and the rest refitted.
    /// Relative error of the polynomials alone, with the rounded coefficients: f64 sine
    /// `2^-57.3` (degree 13), cosine `2^-63.0` (degree 14); f32 sine `2^-32.5` (degree 9),
    /// cosine `2^-31.3` (degree 8).
    #[doc(hidden)]
    fn sin_cos_polynomials(z: Self) -> (Self, Self);

    /// The two lowest bits of the significand: of `y + 1.5·2^p` (see
    /// [`SIN_COS_SHIFTER`](Self::SIN_COS_SHIFTER)), the rounded `y` modulo 4.
    #[doc(hidden)]
    fn low_two_bits(self) -> u32;

    /// Whether `self` is `+0` or a positive finite number: one integer comparison of the
    /// bits (positive floats order as their bits do; `−0`, negatives, ∞ and NaN lie above
    /// the largest finite's).
    #[doc(hidden)]
    fn positive_finite_or_zero(self) -> bool;

    /// `ε^(1/3)`, rounded to nearest: the accuracy required of a velocity
    /// ([`Accuracy::required`](crate::Accuracy::required)); a constant because `libm`'s
    /// `cbrt`, which `no_std` builds would call, keeps a panic path.
    #[doc(hidden)]
    const EPSILON_CUBE_ROOT: Self;

    /// The sizes (sums of a mechanism's lengths) at which the closed forms and Newton solve
    /// the mechanism as it is given (see `as_given` in the runtime's kernel helpers):
    /// `[2^-200, 2^200]` for `f64`, `[2^-16, 2^24]` for `f32`, well inside the float's range.
    #[doc(hidden)]
    const SIZES_AS_GIVEN: [Self; 2];

    /// The input rates (as `Σ rate² + Σ |acceleration|`) at which the closed forms and
    /// Newton compute rates and accelerations as given (see `rates_as_given` in the
    /// runtime's kernel helpers): `[2^-600, 2^600]` for `f64`, `[2^-60, 2^60]` for `f32`, so
    /// that with a size within [`Self::SIZES_AS_GIVEN`] and links down to 2^-60 of it no
    /// squared rate, nor a length times one, leaves the float's normal range.
    #[doc(hidden)]
    const RATES_AS_GIVEN: [Self; 2];

    /// `π/2` in two parts for [`fast::unit_angle`](crate::fast::unit_angle): the first
    /// rounded to nearest, the second `π/2` minus the first, rounded to nearest.
    #[doc(hidden)]
    const UNIT_ANGLE_PI_OVER_2: [Self; 2];

    /// Veltkamp's splitting constant `2^⌈p/2⌉ + 1` for a `p`-bit significand (`2^27 + 1`,
    /// `2^12 + 1`): `a·C − (a·C − a)` is `a` rounded to its upper half, whose square is exact.
    #[doc(hidden)]
    const UNIT_ANGLE_SPLITTER: Self;

    /// The minimax polynomial `P(s)` of [`fast::unit_angle`](crate::fast::unit_angle) with
    /// `asin w ≈ w + w³·P(w²)` for `w² ≤ ½·(1 + 2^-7)`, fitted (Lawson's iteration towards
    /// minimax) to the relative error of `P`, with each coefficient rounded to this type in
    /// turn and the rest refitted. Relative error of `P` with the rounded coefficients
    /// (hence about a ninth of that in `asin w`): f64 `2^-54.0` (degree 19, `2^-55.8` before rounding), f32 `2^-25.0`
    /// (degree 8, `2^-26.4` before rounding, the floor being `1/6` rounded to f32).
    #[doc(hidden)]
    fn unit_angle_polynomial(s: Self) -> Self;
}

impl Real for f64 {
    #[inline(always)]
    fn constant(value: f64) -> Self {
        value
    }

    const SIN_COS_LIMIT: Self = 1e6;
    const INLINE_SIN_COS: bool = cfg!(feature = "std");
    const SIN_COS_TWO_OVER_PI: Self = core::f64::consts::FRAC_2_PI;
    const SIN_COS_SHIFTER: Self = 6_755_399_441_055_744.0;

    #[inline(always)]
    fn low_two_bits(self) -> u32 {
        (self.to_bits() & 3) as u32
    }

    #[inline(always)]
    fn positive_finite_or_zero(self) -> bool {
        self.to_bits() <= f64::MAX.to_bits()
    }
    const SIN_COS_PI_OVER_2: [Self; 4] = [
        1.570_796_326_734_125_6,
        6.077_100_506_303_966e-11,
        2.022_266_248_711_166_5e-21,
        8.478_427_660_368_9e-32,
    ];

    #[inline(always)]
    fn sin_cos_polynomials(z: Self) -> (Self, Self) {
        // Estrin's scheme, for shorter dependency chains than Horner's in batch loops, with
        // the constant term added last so that only that sum rounds at its magnitude.
        let z2 = z * z;
        let s = -0.166_666_666_666_666_66
            + (z * 0.008_333_333_333_328_558
                + z2 * ((-0.000_198_412_698_336_969 + z * 2.755_731_480_681_524_4e-6)
                    + z2 * (-2.505_090_654_212_933_3e-8 + z * 1.590_425_790_177_191_4e-10)));
        let c = 0.041_666_666_666_666_664
            + (z * -0.001_388_888_888_888_338_8
                + z2 * ((2.480_158_729_440_321_5e-5 + z * -2.755_731_558_799_552e-7)
                    + z2 * (2.087_587_160_434_217_3e-9 + z * -1.136_651_295_506_191_3e-11)));
        (s, c)
    }

    const EPSILON_CUBE_ROOT: Self = 6.055_454_452_393_339e-6;
    const SIZES_AS_GIVEN: [Self; 2] = [6.223_015_277_861_142e-61, 1.606_938_044_258_990_3e60];
    const RATES_AS_GIVEN: [Self; 2] = [2.409_919_865_102_884e-181, 4.149_515_568_880_993e180];
    const UNIT_ANGLE_PI_OVER_2: [Self; 2] =
        [core::f64::consts::FRAC_PI_2, 6.123_233_995_736_766e-17];
    const UNIT_ANGLE_SPLITTER: Self = 134_217_729.0;

    #[inline(always)]
    fn unit_angle_polynomial(s: Self) -> Self {
        // Estrin's scheme in s, s², s⁴, s⁸, s¹⁶, with the constant term added last.
        let s2 = s * s;
        let s4 = s2 * s2;
        let s8 = s4 * s4;
        let s16 = s8 * s8;
        let low = ((0.044_642_857_139_465_5 + s * 0.030_381_944_779_099_238)
            + s2 * (0.022_372_141_643_916_772 + s * 0.017_353_319_256_843_21))
            + s4 * ((0.013_953_122_920_411_122 + s * 0.011_725_608_981_399_415)
                + s2 * (0.007_883_547_513_724_286 + s * 0.023_560_346_338_235_675));
        let high = ((-0.085_866_020_122_537_6 + s * 0.446_175_804_560_728_36)
            + s2 * (-1.595_593_578_571_981_3 + s * 4.497_819_133_953_502))
            + s4 * ((-9.624_493_569_191_385 + s * 15.499_073_346_366_535)
                + s2 * (-18.146_114_737_126_126 + s * 14.652_680_746_673_472));
        0.166_666_666_666_666_66
            + (s * 0.075_000_000_000_013_65
                + s2 * ((low + s8 * high)
                    + s16 * (-7.314_027_219_177_891 + s * 1.724_225_660_826_060_4)))
    }
}

impl Real for f32 {
    #[inline(always)]
    fn constant(value: f64) -> Self {
        // Rounding to nearest is what a literal of type f32 would do.
        value as f32
    }

    const SIN_COS_LIMIT: Self = 1e3;
    const INLINE_SIN_COS: bool = false;
    const SIN_COS_TWO_OVER_PI: Self = core::f32::consts::FRAC_2_PI;
    const SIN_COS_SHIFTER: Self = 12_582_912.0;

    #[inline(always)]
    fn low_two_bits(self) -> u32 {
        self.to_bits() & 3
    }

    #[inline(always)]
    fn positive_finite_or_zero(self) -> bool {
        self.to_bits() <= f32::MAX.to_bits()
    }
    const SIN_COS_PI_OVER_2: [Self; 4] =
        [1.570_678_7, 1.176_148_65e-4, 9.920_313e-10, 6.223_372e-14];

    #[inline(always)]
    fn sin_cos_polynomials(z: Self) -> (Self, Self) {
        let z2 = z * z;
        let s = -0.166_666_67 + (z * 0.008_333_379 + z2 * (-0.000_198_530_4 + z * 2.832_010_8e-6));
        let c = 0.041_666_668 + (z * -0.001_388_822_1 + z2 * 2.452_217_4e-5);
        (s, c)
    }

    const EPSILON_CUBE_ROOT: Self = 4.921_566_6e-3;
    const SIZES_AS_GIVEN: [Self; 2] = [1.525_878_9e-5, 16_777_216.0];
    const RATES_AS_GIVEN: [Self; 2] = [8.673_617_4e-19, 1.152_921_5e18];
    const UNIT_ANGLE_PI_OVER_2: [Self; 2] = [core::f32::consts::FRAC_PI_2, -4.371_139e-8];
    const UNIT_ANGLE_SPLITTER: Self = 4097.0;

    #[inline(always)]
    fn unit_angle_polynomial(s: Self) -> Self {
        let s2 = s * s;
        let s4 = s2 * s2;
        0.166_666_67
            + (s * 0.074_998_59
                + s2 * ((0.044_709_343 + s * 0.029_187_214)
                    + s2 * (0.032_974_478 + s * -0.034_313_325)
                    + s4 * ((0.156_255_5 + s * -0.200_214_12) + s2 * 0.149_462_09)))
    }
}

/// `⌊log₂|x|⌋` for a finite nonzero `x` (subnormals included); 0 for zero.
pub(crate) fn binary_exponent<T: Real>(x: T) -> i32 {
    let (mantissa, exponent, _) = x.integer_decode();
    if mantissa == 0 {
        return 0;
    }
    i32::from(exponent) + 63 - mantissa.leading_zeros() as i32
}

/// `2^k`, with `k` clamped so that both it and its inverse are normal numbers of `T` (to
/// ±1020 in f64, ±124 in f32).
pub(crate) fn power_of_two<T: Real>(k: i32) -> T {
    let limit = -binary_exponent(T::min_positive_value()) - 2;
    // Not `clamp`, whose check of its bounds is a panic path the compiler keeps.
    let k = k.max(-limit).min(limit);
    // Built from its bits in f64, where it is exact, and exact again in f32 within ±124.
    T::constant(f64::from_bits(((k + 1023) as u64) << 52))
}

/// A power of two `s` that brings `largest` (finite, nonzero) into `[1/2, 1)`: multiplying
/// by it is exact, so a computation done on scaled values and scaled back is the same, bit
/// for bit, for every power-of-two scaling of its data, and its squares neither overflow
/// nor underflow. For `largest` beyond what `s` can reach (subnormal numbers), it brings
/// `largest` as close as it can.
pub(crate) fn normaliser<T: Real>(largest: T) -> T {
    power_of_two(-(binary_exponent(largest) + 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positive_finite_or_zero_is_read_from_the_bits() {
        for yes in [0.0, 5e-324, 1e-300, 1.0, f64::MAX] {
            assert!(yes.positive_finite_or_zero(), "{yes:e}");
        }
        for yes in [0.0, 1e-45, 1e-30, 1.0, f32::MAX] {
            assert!(yes.positive_finite_or_zero(), "{yes:e}");
        }
        for no in [
            -0.0,
            -5e-324,
            -1.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ] {
            assert!(!no.positive_finite_or_zero(), "{no:e}");
            assert!(!(no as f32).positive_finite_or_zero(), "{no:e}");
        }
    }

    #[test]
    fn binary_exponent_is_the_floor_of_log2_subnormals_included() {
        assert_eq!(binary_exponent(1.0f64), 0);
        assert_eq!(binary_exponent(0.75f64), -1);
        assert_eq!(binary_exponent(-8.0f64), 3);
        assert_eq!(binary_exponent(f64::MAX), 1023);
        assert_eq!(binary_exponent(f64::MIN_POSITIVE), -1022);
        assert_eq!(binary_exponent(f64::from_bits(3)), -1073);
        assert_eq!(binary_exponent(f64::from_bits(1)), -1074);
        assert_eq!(binary_exponent(0.0f64), 0);
        assert_eq!(binary_exponent(3.0f32), 1);
        assert_eq!(binary_exponent(f32::MAX), 127);
        assert_eq!(binary_exponent(f32::from_bits(1)), -149);
    }

    #[test]
    fn powers_of_two_stop_where_they_and_their_inverses_are_normal() {
        assert_eq!(power_of_two::<f64>(0), 1.0);
        assert_eq!(power_of_two::<f64>(5), 32.0);
        assert_eq!(power_of_two::<f64>(-3), 0.125);
        assert_eq!(power_of_two::<f64>(1020), 2f64.powi(1020));
        assert_eq!(power_of_two::<f64>(1021), 2f64.powi(1020));
        assert_eq!(power_of_two::<f64>(-1020), 0.5f64.powi(1020));
        assert_eq!(power_of_two::<f64>(-5000), 0.5f64.powi(1020));
        assert_eq!(power_of_two::<f32>(124), 2f32.powi(124));
        assert_eq!(power_of_two::<f32>(125), 2f32.powi(124));
        assert_eq!(power_of_two::<f32>(-7), 0.007_812_5);
        assert_eq!(power_of_two::<f32>(-500), 0.5f32.powi(124));
    }

    #[test]
    fn the_normaliser_brings_the_largest_into_a_half_to_one_as_far_as_it_can() {
        assert_eq!(normaliser(1.0f64), 0.5);
        assert_eq!(normaliser(0.75f64), 1.0);
        assert_eq!(normaliser(-3.0f64), 0.25);
        assert_eq!(normaliser(100.0f32), 0.007_812_5);
        // 2^-1024 and 2^1074 are beyond the clamp: the nearest it allows.
        assert_eq!(normaliser(f64::MAX), 0.5f64.powi(1020));
        assert_eq!(normaliser(f64::from_bits(1)), 2f64.powi(1020));
        assert_eq!(normaliser(1e-40f32), 2f32.powi(124));
    }
}
