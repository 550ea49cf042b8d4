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
}

impl Real for f64 {
    #[inline(always)]
    fn constant(value: f64) -> Self {
        value
    }

    const SIN_COS_LIMIT: Self = 1e6;
    const SIN_COS_TWO_OVER_PI: Self = core::f64::consts::FRAC_2_PI;
    const SIN_COS_SHIFTER: Self = 6_755_399_441_055_744.0;
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
}

impl Real for f32 {
    #[inline(always)]
    fn constant(value: f64) -> Self {
        // Rounding to nearest is what a literal of type f32 would do.
        value as f32
    }

    const SIN_COS_LIMIT: Self = 1e3;
    const SIN_COS_TWO_OVER_PI: Self = core::f32::consts::FRAC_2_PI;
    const SIN_COS_SHIFTER: Self = 12_582_912.0;
    const SIN_COS_PI_OVER_2: [Self; 4] =
        [1.570_678_7, 1.176_148_65e-4, 9.920_313e-10, 6.223_372e-14];

    #[inline(always)]
    fn sin_cos_polynomials(z: Self) -> (Self, Self) {
        let z2 = z * z;
        let s = -0.166_666_67 + (z * 0.008_333_379 + z2 * (-0.000_198_530_4 + z * 2.832_010_8e-6));
        let c = 0.041_666_668 + (z * -0.001_388_822_1 + z2 * 2.452_217_4e-5);
        (s, c)
    }
}
