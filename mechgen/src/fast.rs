//! Branch-free maths for batch kernels: code the compiler can auto-vectorise.
//!
//! The platform's `sin_cos` (libm's, or the C library's under `std`) is an opaque call with
//! branches on the argument's size inside: a loop that calls it runs one lane at a time.
//! [`sin_cos`] here is straight-line arithmetic, inlined into the caller, so a loop over a
//! slice of angles becomes packed SSE2 on x86-64's baseline (2 f64 or 4 f32 lanes), or wider
//! with `-C target-cpu`. [`unit_angle`], the angle of a unit vector, likewise stands in
//! for `atan2`.

use crate::Real;

/// `y` rounded to the nearest integer (ties to even), for `|y| < 2^(p−2)`, by adding and
/// subtracting `1.5·2^p`: no branch, no call.
#[inline(always)]
fn round<T: Real>(y: T) -> T {
    (y + T::SIN_COS_SHIFTER) - T::SIN_COS_SHIFTER
}

/// `(s, e)` with `s = fl(a − b)` and `s + e = a − b` exactly (Knuth's TwoSum of `a` and `−b`).
#[inline(always)]
fn two_diff<T: Real>(a: T, b: T) -> (T, T) {
    let s = a - b;
    let b_rounded = a - s;
    let a_rounded = s + b_rounded;
    (s, (a - a_rounded) + (b_rounded - b))
}

/// The largest `|x|` for which [`sin_cos`] meets its error bound: `1e6` for `f64`, `1e3`
/// for `f32`. Beyond it [`sin_cos`] returns NaN.
///
/// ```
/// assert_eq!(mechgen::fast::sin_cos_limit::<f64>(), 1e6);
/// assert_eq!(mechgen::fast::sin_cos_limit::<f32>(), 1e3);
/// ```
#[inline(always)]
pub fn sin_cos_limit<T: Real>() -> T {
    T::SIN_COS_LIMIT
}

/// `(sin x, cos x)` with no branch and no call, for loops the compiler vectorises.
///
/// # Accuracy
///
/// For `|x| ≤` [`sin_cos_limit`] (`1e6` rad for `f64`, `1e3` rad for `f32`), each of the
/// two results is within **0.9 ulp** of the exact value (in ulps of the correctly rounded
/// result), for `f64` and `f32` alike, and is the correctly rounded result for about 94% of
/// inputs spread over the range. `sin_cos(±0) = (±0, 1)`.
///
/// - A priori (worst at `|r| = π/4`): the final rounding, 0.5 ulp; for `cos`, the rounding
///   of `r²` in `1 − r²/2`, 0.25 ulp, and the other terms' roundings, 0.14 ulp: 0.89 ulp;
///   for `sin`, the roundings in the correction `r³·S(r²)`, 0.35 ulp: 0.85 ulp. The
///   polynomials' error (`2^-57` relative for `f64`) is negligible, and so is the
///   reduction's (below `2^-130` absolute for `f64`), even at the closest a double comes to
///   a multiple of π/2 in range (`45.553093477052`, `6.2e-19` from `29·π/2`).
/// - Measured (`tests/tests/fast_math.rs`): `f32` on every input in range (2.3·10⁹, against
///   `f64`'s `sin_cos`): at most 0.783 ulp. `f64` against a double-double reference with an
///   exact reduction, on 2.1·10⁸ inputs (dense grids, random magnitudes from `1e-300` to the
///   limit, and the five doubles nearest every multiple of π/2 up to the limit, where the
///   reduction cancels most): at most 0.794 ulp.
///
/// Beyond the limit, for infinities and for NaN the results are NaN: the Cody–Waite
/// reduction below is exact only while the quadrant fits in 20 bits (`f64`) or 10 bits
/// (`f32`). A batch caller can route larger angles elsewhere (reduce them modulo 2π in
/// higher precision first, or call the platform's `sin_cos`), or detect the NaN lanes after
/// the loop.
///
/// # Method
///
/// - Quadrant `n = round(x·2/π)` by the `1.5·2^p` shifter; the remainder `r = x − n·π/2` by
///   Cody–Waite with π/2 in four parts, the first three short enough that `n·part` is exact
///   ([`Real`] holds the parts), accumulated with TwoSum into a double-length `r + ρ`, so
///   `r` is accurate even within `2^-60` of a multiple of π/2.
/// - Minimax polynomials on `|r| ≤ π/4`: `sin(r + ρ) ≈ r + (r³·S(r²) + ρ·(1 − r²/2))` and
///   `cos(r + ρ) ≈ w + ((1 − w) − r²/2 + r⁴·C(r²) − r·ρ)` with `w = 1 − r²/2`, so the
///   leading term is exact and each result is rounded once at the end (fdlibm's kernels'
///   arrangement; degree 13 and 14 for `f64`, 9 and 8 for `f32`).
/// - Quadrant fix-up by arithmetic: `q = n mod 4` by the shifter (`n − 4·round(n/4 − 3/8)`),
///   `cos(qπ/2)` and `sin(qπ/2)` (each 0 or ±1) as triangle waves in `q`, and the
///   angle-sum formulas with them swap and flip `sin r` and `cos r` exactly.
/// - The range check turns `max(|x| − limit, 0)` into `0` or `∞`, and `∞ − ∞` into a NaN
///   subtracted from `q` (`0` leaves it unchanged), which poisons both results.
///
/// ```
/// use mechgen::fast::sin_cos;
/// let (s, c) = sin_cos(1.0f64);
/// assert!((s - 1f64.sin()).abs() <= f64::EPSILON && (c - 1f64.cos()).abs() <= f64::EPSILON);
/// let (s, c) = sin_cos(-0.0f32);
/// assert!(s == 0.0 && s.is_sign_negative() && c == 1.0);
/// assert!(sin_cos(2e6f64).0.is_nan());
/// ```
#[inline(always)]
pub fn sin_cos<T: Real>(x: T) -> (T, T) {
    // Range check, off the critical path: 0 within the limit; NaN beyond it, for ±∞ and for
    // NaN, subtracted from the quadrant, so that it poisons both results.
    let excess = x.abs() - T::SIN_COS_LIMIT;
    let overflow = (excess + excess.abs()) * T::max_value() * T::max_value();
    // ∞ − ∞ is the NaN wanted; 0 − 0 is 0.
    #[allow(clippy::eq_op)]
    let nan_beyond = overflow - overflow;
    sin_cos_offset(x, nan_beyond)
}

/// [`sin_cos`] for `|x| ≤` [`sin_cos_limit`], which the caller has checked, in lanes: the
/// same bits and the same arithmetic, without the range check's (for a loop over several
/// angles that branches on their range once).
#[inline(always)]
pub(crate) fn sin_cos_lanes_within_limit<T: Real>(x: T) -> (T, T) {
    sin_cos_offset(x, T::zero())
}

/// [`sin_cos`] for `|x| ≤` [`sin_cos_limit`], which the caller has checked: the same bits,
/// for scalar code that branches on the range anyway. Without the range check's
/// arithmetic, and with the quadrant's fix-up a choice on its two low bits rather than
/// [`sin_cos`]'s arithmetic on the quadrant (which is for lanes): the same swaps and sign
/// flips, so the same bits.
#[inline(always)]
pub(crate) fn sin_cos_within_limit<T: Real>(x: T) -> (T, T) {
    let shifted = x * T::SIN_COS_TWO_OVER_PI + T::SIN_COS_SHIFTER;
    let n = shifted - T::SIN_COS_SHIFTER;
    let (s, c) = reduced_sin_cos(x, n);
    // sin(r + qπ/2), cos(r + qπ/2) for q = n mod 4 (the shifted sum holds n in its
    // significand's low bits, in two's complement).
    match shifted.low_two_bits() {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// [`sin_cos`]'s arithmetic, with `offset` (0, or NaN to poison both results) subtracted
/// from the quadrant.
#[inline(always)]
fn sin_cos_offset<T: Real>(x: T, offset: T) -> (T, T) {
    let one = T::one();
    let two = T::constant(2.0);
    let four = T::constant(4.0);
    let quarter = T::constant(0.25);
    let three_eighths = T::constant(0.375);

    let n = round(x * T::SIN_COS_TWO_OVER_PI);
    let (s, c) = reduced_sin_cos(x, n);

    // Quadrant fix-up: sin x = s·cos(nπ/2) + c·sin(nπ/2), cos x = c·cos(nπ/2) − s·sin(nπ/2).
    // With q = n mod 4 in {0, 1, 2, 3}, cos(qπ/2) = |q − 2| − 1 and sin(qπ/2) = −m for
    // m = |q − 1| − 1: triangle waves, each 0 or ±1, so every product below is exact and
    // every sum has a zero term. At q = 0, m is +0, and subtracting c·m = +0 keeps s's sign
    // of zero: sin(−0) = −0.
    let q = (n - four * round(n * quarter - three_eighths)) - offset;
    let cos_n = (q - two).abs() - one;
    let m = (q - one).abs() - one;
    (s * cos_n - c * m, c * cos_n + s * m)
}

/// `(sin r, cos r)` for `r = x − n·π/2`, the quadrant `n` rounded from `x·2/π`.
#[inline(always)]
fn reduced_sin_cos<T: Real>(x: T, n: T) -> (T, T) {
    let one = T::one();
    let half = T::constant(0.5);

    // Cody–Waite reduction: r + ρ = x − n·π/2. The first product is exact and cancels
    // exactly (Sterbenz); the next two products are exact and their differences are kept
    // whole by TwoSum; only n·p4, far below r's last bit, is rounded.
    let [p1, p2, p3, p4] = T::SIN_COS_PI_OVER_2;
    let (h, e1) = two_diff(x - n * p1, n * p2);
    let (h, e2) = two_diff(h, n * p3);
    // −(…) rather than e1 + e2 − n·p4: the same sum, but −0 when everything is zero, which
    // keeps sin(−0) = −0 through the additions below.
    let low = -((n * p4 - e1) - e2);
    // Renormalised (Fast2Sum, |h| ≥ |low|), so that r² and r³ below are as accurate as r.
    let r = h + low;
    let rho = low - (r - h);

    let z = r * r;
    // The polynomials, the longest chain, start from h² without waiting for r: they are
    // multiplied by r³ and r⁴, so the difference, about 2·r·ρ, is far below r's last bit.
    let (ps, pc) = T::sin_cos_polynomials(h * h);
    let hz = half * z;
    let w = one - hz;
    // sin: r − (r³·(−S) − ρ·(1 − z/2)); the inner difference is +0 when r is ±0.
    let s = r - ((z * r) * -ps - rho * w);
    let c = w + (((one - w) - hz) + (z * z * pc - r * rho));
    (s, c)
}

/// The angle of a unit vector `(x, y)`, in (−π, π] as `y.atan2(x)` gives it, with no branch
/// and no call, for loops the compiler vectorises (and for scalar code that would otherwise
/// spill its live values around a call to `atan2`).
///
/// # Accuracy
///
/// For a unit vector, components of `(cos θ, sin θ)` each rounded (length `1 ± ε/2`), the
/// result is within **1 ulp** of the exact `atan2(y, x)` of the given components, for
/// `f64` and `f32` alike, and is the correctly rounded result for about 99% of inputs.
/// `unit_angle(±0, 1) = ±0`, `unit_angle(±0, −1) = ±π` and `unit_angle(±1, ±0) = ±π/2`,
/// as from `atan2`; NaN in either argument (or an infinity) gives NaN.
///
/// - Measured (`tests/tests/fast_math.rs`): `f64` against a double-double `atan2`, on
///   3.7·10⁶ rounded unit vectors (a grid of 2·10⁶ angles over the circle, 4·10⁴ more at
///   steps of `1e-9` and `1e-15` around each multiple of π/4, 10⁶ random ones) and on the
///   pairs within 8 ulps of `|y| = |x|`: at most 0.805 ulp. `f32` against `f64::atan2`, on
///   the same grids and on every 7th `y` in [0, 1] with `x = √(1 − y²)` rounded (1.2·10⁹
///   inputs with the signs and the swap): at most 0.772 ulp.
/// - A priori: the final rounding, 0.5 ulp; the roundings in `w³·P(w²)`, which is at most
///   a tenth of the result, about 0.3 ulp at worst (where `|y| ≈ |x|`); the polynomial
///   (`2^-54` relative to `P`, so `2^-57` to the result for `f64`) and the tail of π/2, far
///   below.
/// - Not unit length: the function is meant for unit vectors, but it corrects for the
///   length to first order, so a vector of length `1 ± k·ε` (`ε` the type's epsilon) has a
///   result within `1 + 0.002·k` ulp of its `atan2` (measured up to `k = 1024`: 1.63 ulp
///   for `f64`, 2.06 ulp for `f32`, the extra error largest near the diagonals). Without
///   the correction the extra error would be up to `2·k` ulp there. For lengths further
///   from 1 (`k` beyond about `2^20` for `f64`) second-order terms take over: normalise
///   first, or call `atan2`.
///
/// # Method
///
/// - Selection by arithmetic, which compiles to sign masks (`andpd`/`orpd`) rather than
///   branches: `σ = ±1`, the sign of `|x| − |y|`, gives `p = (1 + σ)/2` and `q = 1 − p`
///   (each 0 or 1), and with them the magnitude is `φ = k·π/2 + asin(w)`, with `w = |y|`
///   (`k = 0`, `x ≥ 0`), `w = −|y|` (`k = 2`, `x < 0`) or `w = −x` (`k = 1`,
///   `|y| > |x|`), so `|w| ≤ 1/√2`; the result is `φ` with the sign of `y`, which gives
///   the signed zeros and `±π` exactly as `atan2` does.
/// - `asin(w) ≈ w + w³·P(w²)`, a minimax polynomial of degree 19 (`f64`) or 8 (`f32`) in
///   `w²` for `w² ≤ ½·(1 + 2^-7)`, by Estrin's scheme; `k·π/2` in two parts, the first
///   added to `w` exactly (Fast2Sum), and the rest summed small to large, so that the
///   result is rounded once at the end.
/// - The length: `atan2(y, x) = k·π/2 + asin(w/r)` for `r = |(x, y)|`, which differs by
///   `−w·(r − 1)/√(1 − w²)` to first order; `x² + y² − 1 = 2·(r − 1)` comes from exact
///   squares (Veltkamp's splitting) and `1/√(1 − w²)` from a cubic, and the product is
///   added with the other small terms.
///
/// ```
/// use mechgen::fast::unit_angle;
/// let (s, c) = 2f64.sin_cos();
/// assert!((unit_angle(s, c) - 2.0).abs() <= 2.0 * f64::EPSILON);
/// assert_eq!(unit_angle(0.0f64, -1.0), core::f64::consts::PI);
/// assert_eq!(unit_angle(-0.0f32, -1.0), -core::f32::consts::PI);
/// assert!(unit_angle(f64::NAN, 1.0).is_nan());
/// ```
#[inline(always)]
pub fn unit_angle<T: Real>(y: T, x: T) -> T {
    let one = T::one();
    let half = T::constant(0.5);
    let ay = y.abs();
    let ax = x.abs();

    // Selection by arithmetic: p = 1, q = 0 on the arc sine path (|y| ≤ |x|, the sign of
    // |x| − |y| being + for a tie); p = 0, q = 1 on the arc cosine path. Every product with
    // p or q below is exact, and every sum of two such products has a zero term.
    let sigma = one.copysign(ax - ay);
    let p = half + half * sigma;
    let q = half - half * sigma;
    // The angle's magnitude is φ = k·π/2 + asin(w), with |w| = min(|x|, |y|):
    // - |y| ≤ |x|, x ≥ 0: φ = asin|y|            (k = 0, w = |y|);
    // - |y| ≤ |x|, x < 0: φ = π − asin|y|        (k = 2, w = −|y|);
    // - |y| > |x|:        φ = π/2 − asin(x)      (k = 1, w = −x).
    let w = p * ay.copysign(x) - q * x;
    let k = one - p * one.copysign(x);
    let [pi_2_hi, pi_2_lo] = T::UNIT_ANGLE_PI_OVER_2;
    let base = k * pi_2_hi;

    // asin(w) ≈ w + w³·P(w²); the leading term added to the base exactly (Fast2Sum: the
    // base is 0 or at least π/2 > |w|).
    let s = w * w;
    let correction = (w * s) * T::unit_angle_polynomial(s);
    let h = base + w;
    let e = w - (h - base);

    // Input not quite of unit length: atan2(y, x) = k·π/2 + asin(w/r) for r = |(x, y)|,
    // which differs from k·π/2 + asin(w) by −w·(r − 1)/√(1 − w²) to first order, with
    // r − 1 = (x² + y² − 1)/2 to first order. x² + y² − 1 = (M² − 1) + w² for the larger
    // magnitude M, from exact squares (Veltkamp's splits into halves): M² − 1 is exact by
    // Sterbenz's lemma, so is its sum with the head of w², and the tails are small.
    // The larger magnitude, `p·|x| + q·|y|`, by one comparison (a packed `max` in lanes): a
    // NaN in either input makes `w` NaN whichever is chosen.
    let big = if ax > ay { ax } else { ay };
    let (big_hi, big_lo) = split(big);
    let (w_hi, w_lo) = split(w);
    let excess =
        ((big_hi * big_hi - one) + w_hi * w_hi) + (big_lo * (big + big_hi) + w_lo * (w + w_hi));
    // 1/(2·√(1 − s)), within 0.06% for s ≤ ½·(1 + 2^-7) (Chebyshev interpolation): the
    // term is an ulp or two for a vector of length 1 ± ε, so its error is far below an ulp.
    let slope = (T::constant(0.499_784_800_438_018_4) + s * T::constant(0.263_468_239_611_617_2))
        + (s * s)
            * (T::constant(0.064_274_177_991_858_99) + s * T::constant(0.473_709_974_211_285_7));
    let unit = (w * excess) * slope;

    let angle = h + (correction + (e + (k * pi_2_lo - unit)));
    angle.copysign(y)
}

/// `(hi, lo)` with `hi + lo = a` exactly and `hi` holding the upper half of `a`'s bits, so
/// that `hi·hi` is exact (Veltkamp's splitting).
#[inline(always)]
fn split<T: Real>(a: T) -> (T, T) {
    let t = a * T::UNIT_ANGLE_SPLITTER;
    let hi = t - (t - a);
    (hi, a - hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, FRAC_PI_4, PI};

    /// The scalar path (the quadrant's fix-up a choice on its low bits) gives the lanes'
    /// bits: on a dense grid over the range, either side of ±0, at the floats nearest each
    /// multiple of π/2 up to 64 turns, at powers of two, and at random magnitudes.
    #[test]
    fn the_scalar_path_gives_the_lanes_bits() {
        fn check<T: Real>(x: T) {
            let (a, b) = (sin_cos(x), sin_cos_within_limit(x));
            assert!(
                a.0.to_f64().map(f64::to_bits) == b.0.to_f64().map(f64::to_bits)
                    && a.1.to_f64().map(f64::to_bits) == b.1.to_f64().map(f64::to_bits),
                "{x:?}: {a:?} against {b:?}"
            );
        }
        let mut xs: std::vec::Vec<f64> =
            (-200_000..=200_000).map(|k| f64::from(k) * 1e-4).collect();
        xs.extend([
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            1e-300,
            1e6,
            -1e6,
        ]);
        for k in -256..=256 {
            let multiple = f64::from(k) * FRAC_PI_2;
            let mut x = multiple;
            for _ in 0..4 {
                xs.extend([x, -x]);
                x = f64::from_bits(x.to_bits() + 1);
            }
            let mut x = multiple;
            for _ in 0..4 {
                xs.push(x);
                x = f64::from_bits(x.to_bits().wrapping_sub(1));
            }
        }
        xs.extend((-60..20).map(|e| 2f64.powi(e)));
        let mut state: u64 = 0x5eed;
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let unit = (state >> 11) as f64 / (1u64 << 53) as f64;
            xs.push((unit * 2.0 - 1.0) * 10f64.powf(unit * 12.0 - 6.0));
        }
        for &x in &xs {
            if x.abs() <= sin_cos_limit::<f64>() {
                check(x);
            }
            let single = x as f32;
            if single.abs() <= sin_cos_limit::<f32>() {
                check(single);
            }
        }
    }

    /// The number of floats from `a` to `b` (0 for equal values and for `+0` against `−0`).
    fn steps(a: f64, b: f64) -> u64 {
        let key = |x: f64| {
            let bits = x.to_bits() as i64;
            if bits < 0 { i64::MIN - bits } else { bits }
        };
        (key(a) - key(b)).unsigned_abs()
    }

    fn steps32(a: f32, b: f32) -> u32 {
        let key = |x: f32| {
            let bits = x.to_bits() as i32;
            if bits < 0 { i32::MIN - bits } else { bits }
        };
        (key(a) - key(b)).unsigned_abs()
    }

    /// A fixed-seed xorshift, for inputs spread over the range.
    fn random(state: &mut u64) -> f64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    /// `f64` inputs: a grid over a few turns, random ones from `1e-300` to the limit, and the
    /// floats next to multiples of π/2 (where the reduction cancels most), each with its
    /// negative.
    fn sin_cos_inputs() -> std::vec::Vec<f64> {
        let mut inputs = std::vec::Vec::new();
        for k in 0..4000 {
            inputs.push(k as f64 * 0.004_7);
        }
        let mut state = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..4000 {
            let exponent = -997.0 + 1016.0 * random(&mut state);
            inputs.push((2f64.powf(exponent) * (1.0 + random(&mut state))).min(1e6));
        }
        for n in (1..2000).chain((2000..636_620).step_by(997)) {
            let nearest = n as f64 * FRAC_PI_2;
            for offset in -2i64..=2 {
                inputs.push(f64::from_bits((nearest.to_bits() as i64 + offset) as u64));
            }
        }
        // The closest a double comes to a multiple of π/2 in range: 6.2e-19 from 29·π/2.
        inputs.push(45.553_093_477_052);
        inputs.push(1e6);
        let negatives: std::vec::Vec<f64> = inputs.iter().map(|x| -x).collect();
        inputs.extend(negatives);
        inputs
    }

    #[test]
    fn sin_cos_is_within_a_float_of_the_platforms_over_the_range() {
        // The platform's is within an ulp of the exact values, this one within 0.9 ulp: at
        // most one float apart (they differ by under 1.9 ulp, and both round the same value).
        for x in sin_cos_inputs() {
            let (s, c) = sin_cos(x);
            let (sin, cos) = x.sin_cos();
            assert!(steps(s, sin) <= 1, "sin {x:e}: {s:e} against {sin:e}");
            assert!(steps(c, cos) <= 1, "cos {x:e}: {c:e} against {cos:e}");
        }
    }

    #[test]
    fn sin_cos_is_mostly_the_platforms_to_the_last_bit() {
        // Both mostly round the exact value correctly (99.3% agree with glibc's, which is
        // nearly always correctly rounded; a platform whose maths library rounds worse would
        // agree less, and this test says so): a rounding error more in the cosine's leading
        // terms, within the bound of a float, shows as about 2% fewer agreeing.
        let inputs = sin_cos_inputs();
        let (mut sines, mut cosines) = (0, 0);
        for &x in &inputs {
            let (s, c) = sin_cos(x);
            let (sin, cos) = x.sin_cos();
            sines += usize::from(s == sin);
            cosines += usize::from(c == cos);
        }
        let least = inputs.len() * 985 / 1000;
        assert!(
            sines >= least && cosines >= least,
            "{sines}, {cosines} of {}",
            inputs.len()
        );
    }

    /// Found by mutation testing: the reduction's tail `ρ` (below half an ulp of `r`) enters
    /// the sine as `ρ·cos r ≈ ρ·(1 − r²/2)`, up to 0.35 ulp of the result where `|r|` is near
    /// π/4, enough to decide its rounding there. At these inputs (quadrant 0 mod 4, `|r|` in
    /// [0.71, 0.77], `|ρ|` from 6·10⁻¹⁸ to 5·10⁻¹⁷), both results are the correctly
    /// rounded values (from a 200-bit evaluation with mpmath); `ρ/(1 − r²/2)` in place of the
    /// product misses each sine by a float.
    #[test]
    fn sin_cos_carries_the_reductions_tail_into_the_sine() {
        for (x, sin, cos) in [
            (19885.511688908573, -0.695997613001873, 0.7180440952307142),
            (38761.71969697137, 0.6812999007543811, 0.7320044024676835),
            (100517.64971824366, -0.6807792990013517, 0.7324885978984439),
            (275158.769168792, -0.6925287196663344, 0.7213903052005257),
            (363757.96053506876, -0.6958758739892451, 0.7181620764143037),
            (62146.27089480637, -0.6556011872688583, 0.7551073322724813),
        ] {
            assert_eq!(sin_cos(x), (sin, cos), "{x:e}");
            assert_eq!(sin_cos_within_limit(x), (sin, cos), "{x:e}");
        }
    }

    #[test]
    fn sin_cos_f32_is_within_a_float_of_the_rounded_f64_values() {
        let mut state = 0x2545_f491_4f6c_dd1d;
        let grid = (0..20_000).map(|k| k as f32 * 0.05);
        let nearest = (1..637).map(|n| (n as f64 * FRAC_PI_2) as f32);
        let spread = (0..4000).map(|_| (1e3 * random(&mut state)) as f32);
        for x in grid.chain(nearest).chain(spread).chain([1e3, 1e-20, 3e-3]) {
            for x in [x, -x] {
                let (s, c) = sin_cos(x);
                let (sin, cos) = f64::from(x).sin_cos();
                assert!(
                    steps32(s, sin as f32) <= 1,
                    "sin {x:e}: {s:e} against {sin:e}"
                );
                assert!(
                    steps32(c, cos as f32) <= 1,
                    "cos {x:e}: {c:e} against {cos:e}"
                );
            }
        }
    }

    #[test]
    fn sin_cos_keeps_the_signed_zero_and_exact_small_values() {
        for zero in [0.0f64, -0.0] {
            let (s, c) = sin_cos(zero);
            assert_eq!((s.to_bits(), c), (zero.to_bits(), 1.0));
        }
        let (s, c) = sin_cos(-0.0f32);
        assert_eq!((s.to_bits(), c), ((-0.0f32).to_bits(), 1.0));
        // Below √ε, sin x = x and cos x = 1 to the last bit.
        assert_eq!(sin_cos(1e-300), (1e-300, 1.0));
        assert_eq!(sin_cos(-3e-9), (-3e-9, 1.0));
        assert_eq!(sin_cos(1e-20f32), (1e-20, 1.0));
        // Each quadrant's signs.
        assert_eq!(sin_cos(FRAC_PI_2), (1.0, 6.123_233_995_736_766e-17));
        assert_eq!(sin_cos(PI), (1.224_646_799_147_353_2e-16, -1.0));
        assert_eq!(sin_cos(-FRAC_PI_2), (-1.0, 6.123_233_995_736_766e-17));
        assert_eq!(
            sin_cos(3.0 * FRAC_PI_2),
            (-1.0, -1.836_970_198_721_029_8e-16)
        );
    }

    #[test]
    fn sin_cos_is_nan_beyond_its_limit_only() {
        for x in [1e6f64, -1e6] {
            let (s, c) = sin_cos(x);
            assert_eq!((s, c), x.sin_cos());
        }
        let above = f64::from_bits(1e6f64.to_bits() + 1);
        for x in [
            above,
            -above,
            2e6,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ] {
            let (s, c) = sin_cos(x);
            assert!(s.is_nan() && c.is_nan(), "{x:e}: {s:e}, {c:e}");
        }
        assert!(!sin_cos(1e3f32).0.is_nan());
        let above = f32::from_bits(1e3f32.to_bits() + 1);
        for x in [above, -above, f32::INFINITY, f32::NAN] {
            let (s, c) = sin_cos(x);
            assert!(s.is_nan() && c.is_nan(), "{x:e}: {s:e}, {c:e}");
        }
        assert_eq!(sin_cos_limit::<f64>(), 1e6);
    }

    #[test]
    fn unit_angle_is_within_a_float_of_atan2_for_unit_vectors() {
        let mut state = 0x9e37_79b9_7f4a_7c15;
        let grid = (-20_000..=20_000).map(|k| k as f64 * (PI / 20_000.0));
        // Around the axes and the diagonals, where the method switches.
        let switches = (-4..=4)
            .flat_map(|k| (-50..=50).map(move |j| f64::from(k) * FRAC_PI_4 + f64::from(j) * 1e-12));
        let spread: std::vec::Vec<f64> = (0..10_000)
            .map(|_| PI * (2.0 * random(&mut state) - 1.0))
            .collect();
        for angle in grid.chain(switches).chain(spread) {
            let (y, x) = angle.sin_cos();
            let got = unit_angle(y, x);
            let want = y.atan2(x);
            assert!(
                steps(got, want) <= 1,
                "({y:e}, {x:e}): {got:e} against {want:e}"
            );
            let (y, x) = (y as f32, x as f32);
            let got = unit_angle(y, x);
            let want = f64::from(y).atan2(f64::from(x)) as f32;
            assert!(
                steps32(got, want) <= 1,
                "({y:e}, {x:e}): {got:e} against {want:e}"
            );
        }
    }

    #[test]
    fn unit_angle_corrects_for_a_length_off_one() {
        // Off by k·ε, k up to 1024: within 1 + 0.002·k ulp of atan2 (2k without the
        // correction), so within 4 floats of the platform's.
        let mut state = 0x2545_f491_4f6c_dd1d;
        for _ in 0..20_000 {
            let angle = PI * (2.0 * random(&mut state) - 1.0);
            let k = (2048.0 * random(&mut state)).round() - 1024.0;
            let (y, x) = angle.sin_cos();
            let length = 1.0 + k * f64::EPSILON;
            let (y, x) = (y * length, x * length);
            let (got, want) = (unit_angle(y, x), y.atan2(x));
            assert!(
                steps(got, want) <= 4,
                "({y:e}, {x:e}): {got:e} against {want:e}"
            );
            let length = 1.0 + k as f32 * f32::EPSILON;
            let (y, x) = ((y as f32) * length, (x as f32) * length);
            let got = unit_angle(y, x);
            let want = f64::from(y).atan2(f64::from(x)) as f32;
            assert!(
                steps32(got, want) <= 4,
                "({y:e}, {x:e}): {got:e} against {want:e}"
            );
        }
    }

    #[test]
    fn unit_angle_f32_is_mostly_the_correctly_rounded_value() {
        // f64's atan2, rounded to f32, is the correctly rounded f32 value but for inputs
        // within 2^-29 of a rounding boundary: a reference that does not lean on the
        // platform's last bit. 98.7% agree here; a rounding error of a quarter ulp more
        // anywhere (in the Fast2Sum's tail, the length correction, the split) shows as
        // several percent fewer.
        let mut state = 0x9e37_79b9_7f4a_7c15;
        let (mut agree, mut total) = (0, 0);
        for _ in 0..40_000 {
            let angle = PI * (2.0 * random(&mut state) - 1.0);
            let (y, x) = angle.sin_cos();
            let (y, x) = (y as f32, x as f32);
            let want = f64::from(y).atan2(f64::from(x)) as f32;
            agree += usize::from(unit_angle(y, x) == want);
            total += 1;
        }
        assert!(agree * 1000 >= total * 980, "{agree} of {total}");
    }

    #[test]
    fn unit_angle_f32_is_correctly_rounded_where_the_splits_tails_decide() {
        // Inputs where the last bit rests on the rounding of the split's tail products
        // (`hi` need only hold half the bits for `hi² + lo·(a + hi) = a²`, so a split made
        // with another constant, or with `hi` near −a, is still exact, and only those
        // roundings move): a search over every f32 angle's sine and cosine found these among
        // the few hundred where such a split loses the correctly rounded value this one
        // gives (each of length within ε/4 of 1, from a sine and cosine rounded to f32).
        let pairs: [(u32, u32); 8] = [
            (0x3b70_48d5, 0x3f7f_ff8f),
            (0x3b70_48d6, 0x3f7f_ff8f),
            (0x3b82_a8c4, 0x3f7f_ff7b),
            (0x3bba_e271, 0x3f7f_feef),
            (0x3c80_09de, 0x3f7f_f7ff),
            (0x3c80_49da, 0x3f7f_f7f7),
            (0x3c80_69d8, 0x3f7f_f7f3),
            (0x3c80_89d6, 0x3f7f_f7ef),
        ];
        for (y, x) in pairs {
            for y in [f32::from_bits(y), -f32::from_bits(y)] {
                let x = f32::from_bits(x);
                let want = f64::from(y).atan2(f64::from(x)) as f32;
                assert_eq!(unit_angle(y, x).to_bits(), want.to_bits(), "({x:e}, {y:e})");
            }
        }
    }

    #[test]
    fn unit_angle_corrects_for_a_length_far_off_one() {
        // Length 1 + k·ε for k up to 2^16, still first order: within 1 + 0.002·k ulp of
        // atan2 (the slope's 0.06%), against 2·k ulp uncorrected; so within 2 + 0.002·k
        // floats of atan2 (itself within an ulp). A slope off by a few percent, or the
        // correction's sign or size wrong, is hundreds of floats away.
        let mut state = 0x2545_f491_4f6c_dd1d;
        for _ in 0..20_000 {
            let angle = PI * (2.0 * random(&mut state) - 1.0);
            let k = (131_072.0 * random(&mut state)).round() - 65_536.0;
            let (y, x) = angle.sin_cos();
            let length = 1.0 + k * f64::EPSILON;
            let (y, x) = (y * length, x * length);
            let (got, want) = (unit_angle(y, x), y.atan2(x));
            let allowed = 2 + (0.002 * k.abs()) as u64;
            assert!(
                steps(got, want) <= allowed,
                "k {k}, ({y:e}, {x:e}): {got:e} against {want:e}"
            );
        }
    }

    #[test]
    fn unit_angle_gives_atan2s_edges() {
        assert_eq!(unit_angle(0.0f64, 1.0).to_bits(), 0f64.to_bits());
        assert_eq!(unit_angle(-0.0f64, 1.0).to_bits(), (-0f64).to_bits());
        assert_eq!(unit_angle(0.0f64, -1.0), PI);
        assert_eq!(unit_angle(-0.0f64, -1.0), -PI);
        assert_eq!(unit_angle(1.0f64, 0.0), FRAC_PI_2);
        assert_eq!(unit_angle(-1.0f64, -0.0), -FRAC_PI_2);
        assert_eq!(unit_angle(FRAC_1_SQRT_2, FRAC_1_SQRT_2), FRAC_PI_4);
        assert_eq!(unit_angle(FRAC_1_SQRT_2, -FRAC_1_SQRT_2), 3.0 * FRAC_PI_4);
        assert_eq!(unit_angle(0.0f32, -1.0), core::f32::consts::PI);
        assert_eq!(unit_angle(1.0f32, 0.0), core::f32::consts::FRAC_PI_2);
        for (y, x) in [
            (f64::NAN, 1.0),
            (0.0, f64::NAN),
            (f64::INFINITY, 0.0),
            (0.0, f64::INFINITY),
        ] {
            assert!(unit_angle(y, x).is_nan(), "({y}, {x})");
        }
    }
}
