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
