//! Closed-form solutions of one vector loop in two unknowns (Chace's cases).
//!
//! The generated `assemble` writes each loop it can solve this way as known complex
//! coefficients (as [`Vec2`]s) and calls one of these. With `K` the sum of the loop's known
//! vectors, `l` an unknown length and `q` an unknown angle:
//! - [`two_lengths`]: `K + l1·v1 + l2·v2 = 0`, a 2×2 linear solve;
//! - [`length_and_own_angle`]: `K + e^{iq}·(l·w1 + w0) = 0`, the length and angle of one
//!   (compound) vector;
//! - [`length_and_other_angle`]: `K + l·v + e^{iq}·w0 = 0`, a line meeting a circle;
//! - [`two_angles`]: `K + e^{iq1}·w1 + e^{iq2}·w2 = 0`, two circles meeting.
//!
//! The last three have two solutions, told apart by a sign `σ = ±1` that each function
//! documents geometrically; the matching `*_sign` function computes that sign at a position,
//! which is how a position's branch is known.

use crate::real::normaliser;
use crate::{Real, Vec2};

/// Why a loop could not be closed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Failure {
    /// The vectors cannot meet: the input is outside the range of motion.
    CannotClose,
    /// The solution is not determined (a zero-length chord, parallel directions).
    Degenerate,
    /// A coefficient is not finite, or the solution is too large for the number type.
    NonFinite,
}

impl Failure {
    /// The error to report for a loop that failed at `input`.
    pub fn at<T: Real>(self, input: T) -> crate::Error<T> {
        match self {
            Failure::CannotClose => crate::Error::CannotAssemble { input },
            Failure::Degenerate => crate::Error::Singular {
                determinant: T::zero(),
                relative_determinant: T::zero(),
            },
            Failure::NonFinite => crate::Error::NonFinite {
                quantity: "closed-form solution",
            },
        }
    }
}

fn cross<T: Real>(a: Vec2<T>, b: Vec2<T>) -> T {
    a.x * b.y - a.y * b.x
}

fn dot<T: Real>(a: Vec2<T>, b: Vec2<T>) -> T {
    a.x * b.x + a.y * b.y
}

/// `a·b` as complex numbers.
fn times<T: Real>(a: Vec2<T>, b: Vec2<T>) -> Vec2<T> {
    Vec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}

/// `|a|` by a plain square root, for vectors already brought to a unit scale
/// ([`to_unit_scale`]), whose squares cannot overflow or lose digits to underflow.
fn length<T: Real>(a: Vec2<T>) -> T {
    dot(a, a).sqrt()
}

fn scaled<T: Real>(a: Vec2<T>, s: T) -> Vec2<T> {
    Vec2::new(a.x * s, a.y * s)
}

fn largest_component<T: Real>(vectors: &[Vec2<T>]) -> T {
    vectors
        .iter()
        .fold(T::zero(), |m, v| m.max(v.x.abs()).max(v.y.abs()))
}

/// The power of two that brings the largest component of `vectors` into `[1/2, 1)`, so that
/// the closed forms square nothing that can overflow or underflow, at any scale from the
/// smallest to the largest normal number, and give bit-identical angles under power-of-two
/// scalings of a mechanism. Errors: a component that is not finite; all of them zero.
fn to_unit_scale<T: Real>(vectors: &[Vec2<T>]) -> Result<T, Failure> {
    let all_finite = vectors.iter().all(|v| v.x.is_finite() && v.y.is_finite());
    if !all_finite {
        return Err(Failure::NonFinite);
    }
    let largest = largest_component(vectors);
    if largest == T::zero() {
        return Err(Failure::Degenerate);
    }
    Ok(normaliser(largest))
}

/// `v`'s direction and length, `(v/|v|, |v|)`, at any scale. Errors: a zero `v`.
fn direction_and_length<T: Real>(v: Vec2<T>) -> Result<(Vec2<T>, T), Failure> {
    let s = to_unit_scale(&[v])?;
    let unit_scaled = scaled(v, s);
    let norm = length(unit_scaled);
    Ok((scaled(unit_scaled, T::one() / norm), norm / s))
}

/// The turn `e^{iq}` that carries `from` onto `to`'s direction, as the unit vector
/// `(cos q, sin q)`: what generated code wants, so no `sin_cos` (and no `atan2`, unless the
/// angle itself is asked for) of a solved angle is needed after. Both at unit scale.
#[inline]
fn turn<T: Real>(to: Vec2<T>, from: Vec2<T>) -> Result<Vec2<T>, Failure> {
    // to·conj(from), normalised.
    let product = Vec2::new(dot(to, from), cross(from, to));
    let norm = length(product);
    if norm == T::zero() {
        return Err(Failure::Degenerate);
    }
    Ok(scaled(product, T::one() / norm))
}

/// How far below zero, relative to the sizes it is formed from, a gap that can only be
/// positive for a closing loop may come out by rounding alone: the gap is a sum of three
/// terms each known to a couple of units of rounding of the largest length.
const GAP_ROUNDING: f64 = 8.0;

/// How large a closed form's loop residual may be, relative to the sum of the magnitudes of
/// the loop's vectors, and still be rounding: each solution is backward stable, off by a few
/// units of rounding of that sum.
const RESIDUAL_ROUNDING: f64 = 32.0;

/// Whether a gap `gap` (negative where the loop cannot close) is zero to within rounding of
/// `scale`: then the loop closes at a tangency.
fn gap_closes<T: Real>(gap: T, scale: T) -> Result<T, Failure> {
    if gap >= T::zero() {
        Ok(gap)
    } else if gap >= -T::constant(GAP_ROUNDING) * T::epsilon() * scale {
        Ok(T::zero())
    } else {
        Err(Failure::CannotClose)
    }
}

/// The check every closed-form solution passes before it is returned: its loop residual is
/// at the rounding floor of the loop's magnitudes (a solution that is not is not a solution,
/// however it came about).
fn closes<T: Real>(residual: Vec2<T>, magnitudes: T) -> Result<(), Failure> {
    let size = residual.x.abs() + residual.y.abs();
    if size <= T::constant(RESIDUAL_ROUNDING) * T::epsilon() * magnitudes {
        Ok(())
    } else {
        Err(Failure::CannotClose)
    }
}

/// A length solved at unit scale, brought back: `l / s`, or [`Failure::NonFinite`] if that
/// is too large for `T`.
fn unscaled_length<T: Real>(l: T, s: T) -> Result<T, Failure> {
    let l = l / s;
    if l.is_finite() {
        Ok(l)
    } else {
        Err(Failure::NonFinite)
    }
}

/// Where a point moving along a line meets a circle about the origin: with the point at
/// `K + L·u` (`u` a unit vector, `K` at unit scale) and the circle's radius `radius`, the
/// root `L` with `σ·(L − t0) ≥ 0`, `t0 = −u·K` being the foot of the perpendicular from the
/// centre, and the point itself. Backward stable: the root from the gap `radius − |p|`
/// (`p` the line's signed distance from the centre), formed as `(radius − |p|)·(radius + |p|)`
/// rather than as a difference of squares; the root that would cancel against `t0` from the
/// product of the roots, `(|K| − radius)·(|K| + radius)`; the point from its components along
/// and across the line, not as `K + L·u`.
fn line_meets_circle<T: Real>(
    k: Vec2<T>,
    u: Vec2<T>,
    radius: T,
    sign: T,
) -> Result<(T, Vec2<T>), Failure> {
    let foot = -dot(u, k);
    let offset = cross(u, k);
    let k_length = length(k);
    let gap = gap_closes(radius - offset.abs(), radius + k_length)?;
    let half_chord = (gap * (radius + offset.abs())).sqrt();
    let along = sign * half_chord;
    let root = if foot == T::zero() || (foot > T::zero()) == (sign > T::zero()) {
        foot + along
    } else {
        (k_length - radius) * (k_length + radius) / (foot - along)
    };
    // The point from the root itself, so that the two agree to rounding (near a tangency the
    // root's two forms differ by more: the half chord is ill-conditioned there).
    let normal = Vec2::new(-u.y, u.x);
    Ok((root, scaled(u, root - foot) + scaled(normal, offset)))
}

/// `K + l1·v1 + l2·v2 = 0` for the lengths `[l1, l2]`: unique, unless `v1 ∥ v2`.
///
/// ```
/// use mechgen::{closed, Vec2};
/// // 3·(1, 0) + 2·(0, 1) closes (−3, −2).
/// let l = closed::two_lengths(Vec2::new(-3.0, -2.0), Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0));
/// assert_eq!(l, Ok([3.0, 2.0]));
/// ```
pub fn two_lengths<T: Real>(k: Vec2<T>, v1: Vec2<T>, v2: Vec2<T>) -> Result<[T; 2], Failure> {
    let (u1, norm1) = direction_and_length(v1)?;
    let (u2, norm2) = direction_and_length(v2)?;
    let determinant = cross(u1, u2);
    if determinant.abs() <= T::constant(8.0) * T::epsilon() {
        return Err(Failure::Degenerate);
    }
    let s = match to_unit_scale(&[k]) {
        Ok(s) => s,
        Err(Failure::Degenerate) => T::one(),
        Err(failure) => return Err(failure),
    };
    let k = scaled(k, s);
    let along1 = cross(u2, k) / determinant;
    let along2 = cross(k, u1) / determinant;
    closes(
        k + scaled(u1, along1) + scaled(u2, along2),
        length(k) + along1.abs() + along2.abs(),
    )?;
    Ok([
        unscaled_length(along1 / norm1, s)?,
        unscaled_length(along2 / norm2, s)?,
    ])
}

/// `K + e^{iq}·(l·w1 + w0) = 0` for `(l, q, (cos q, sin q))`: the vector `l·w1 + w0`, turned by `q`, must be
/// `−K`, so `|l·w1 + w0| = |K|`, a quadratic in `l`. The branch sign `σ` is that of
/// `Re(conj(w1)·(l·w1 + w0))`: positive when the solved vector points along `w1` (the
/// length grows the vector).
///
/// ```
/// use mechgen::{closed, Vec2};
/// // A slide of length l from the origin must reach (3, 4): l = 5 on the + branch.
/// let (l, q, direction) = closed::length_and_own_angle(
///     Vec2::new(-3.0, -4.0), Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), 1.0,
/// ).unwrap();
/// assert_eq!(l, 5.0);
/// assert!((q - (4.0f64).atan2(3.0)).abs() < 1e-15);
/// assert!((direction.x - 0.6).abs() < 1e-15 && (direction.y - 0.8).abs() < 1e-15);
/// ```
pub fn length_and_own_angle<T: Real>(
    k: Vec2<T>,
    w0: Vec2<T>,
    w1: Vec2<T>,
    sign: T,
) -> Result<(T, T, Vec2<T>), Failure> {
    let (l, direction) = length_and_own_direction(k, w0, w1, sign)?;
    Ok((l, direction.angle(), direction))
}

/// [`length_and_own_angle`] without the angle: `(l, (cos q, sin q))`, with no arc tangent.
#[inline]
pub fn length_and_own_direction<T: Real>(
    k: Vec2<T>,
    w0: Vec2<T>,
    w1: Vec2<T>,
    sign: T,
) -> Result<(T, Vec2<T>), Failure> {
    // The point l·w1 + w0 moves along a line and must lie on the circle of radius |K|.
    let (u, norm) = direction_and_length(w1)?;
    let s = to_unit_scale(&[k, w0])?;
    let (k, w0) = (scaled(k, s), scaled(w0, s));
    let radius = length(k);
    if radius == T::zero() {
        return Err(Failure::Degenerate);
    }
    let (along, point) = line_meets_circle(w0, u, radius, sign)?;
    let direction = turn(scaled(k, -T::one()), point)?;
    closes(
        k + times(direction, scaled(u, along) + w0),
        radius + along.abs() + length(w0),
    )?;
    Ok((unscaled_length(along / norm, s)?, direction))
}

/// The branch sign of a solution of [`length_and_own_angle`].
pub fn length_and_own_angle_sign<T: Real>(w0: Vec2<T>, w1: Vec2<T>, l: T) -> T {
    dot_sign(w1, scaled(w1, l) + w0)
}

/// The sign of `a·b`, at any scale.
fn dot_sign<T: Real>(a: Vec2<T>, b: Vec2<T>) -> T {
    dot(at_unit_scale(a), at_unit_scale(b))
}

/// The sign of `a × b`, at any scale.
fn cross_sign<T: Real>(a: Vec2<T>, b: Vec2<T>) -> T {
    cross(at_unit_scale(a), at_unit_scale(b))
}

/// `v` scaled by a power of two to a largest component in `[1/2, 1)` (as it is, if zero or
/// not finite).
fn at_unit_scale<T: Real>(v: Vec2<T>) -> Vec2<T> {
    match to_unit_scale(&[v]) {
        Ok(s) => scaled(v, s),
        Err(_) => v,
    }
}

/// `K + l·v + e^{iq}·w0 = 0` for `(l, q, (cos q, sin q))`: the point `K + l·v` moves along a line and must lie
/// on the circle of radius `|w0|`, a quadratic in `l`. The branch sign `σ` is that of
/// `Re(conj(v)·(K + l·v))`: positive for the intersection farther along `v`.
///
/// ```
/// use mechgen::{closed, Vec2};
/// // The point (l, 3) moving along x must be 5 from the origin: l = ±4, and the + branch is
/// // the one farther along v = (1, 0).
/// let k = Vec2::new(0.0, 3.0);
/// let (l, _, _) = closed::length_and_other_angle(k, Vec2::new(1.0, 0.0), Vec2::new(5.0, 0.0), 1.0).unwrap();
/// assert_eq!(l, 4.0);
/// ```
pub fn length_and_other_angle<T: Real>(
    k: Vec2<T>,
    v: Vec2<T>,
    w0: Vec2<T>,
    sign: T,
) -> Result<(T, T, Vec2<T>), Failure> {
    let (l, direction) = length_and_other_direction(k, v, w0, sign)?;
    Ok((l, direction.angle(), direction))
}

/// [`length_and_other_angle`] without the angle: `(l, (cos q, sin q))`, with no arc tangent.
#[inline]
pub fn length_and_other_direction<T: Real>(
    k: Vec2<T>,
    v: Vec2<T>,
    w0: Vec2<T>,
    sign: T,
) -> Result<(T, Vec2<T>), Failure> {
    let (u, norm) = direction_and_length(v)?;
    let s = to_unit_scale(&[k, w0])?;
    let (k, w0) = (scaled(k, s), scaled(w0, s));
    let radius = length(w0);
    if radius == T::zero() {
        return Err(Failure::Degenerate);
    }
    let (along, point) = line_meets_circle(k, u, radius, sign)?;
    let direction = turn(scaled(point, -T::one()), w0)?;
    closes(
        k + scaled(u, along) + times(direction, w0),
        length(k) + along.abs() + radius,
    )?;
    Ok((unscaled_length(along / norm, s)?, direction))
}

/// The branch sign of a solution of [`length_and_other_angle`].
pub fn length_and_other_angle_sign<T: Real>(k: Vec2<T>, v: Vec2<T>, l: T) -> T {
    dot_sign(v, k + scaled(v, l))
}

/// `K + e^{iq1}·w1 + e^{iq2}·w2 = 0` for `(q1, q2, (cos q1, sin q1), (cos q2, sin q2))`: the vectors `P1 = e^{iq1}·w1` and
/// `P2 = e^{iq2}·w2` must span the chord `−K`, so P1's tip is where the circles of radii
/// `|w1|` (about the chord's start) and `|w2|` (about its end) meet. The branch sign `σ` is
/// that of `cross(−K, P1)`: positive when P1 lies counter-clockwise of (to the left of) the
/// chord.
///
/// ```
/// use mechgen::{closed, Vec2};
/// // Two links of 5 spanning the chord (6, 0): they meet at (3, ±4).
/// let (q1, q2, _, _) = closed::two_angles(
///     Vec2::new(-6.0, 0.0), Vec2::new(5.0, 0.0), Vec2::new(5.0, 0.0), 1.0,
/// ).unwrap();
/// assert!((q1 - (4.0f64).atan2(3.0)).abs() < 1e-15);
/// assert!((q2 - (-4.0f64).atan2(3.0)).abs() < 1e-15);
/// ```
pub fn two_angles<T: Real>(
    k: Vec2<T>,
    w1: Vec2<T>,
    w2: Vec2<T>,
    sign: T,
) -> Result<(T, T, Vec2<T>, Vec2<T>), Failure> {
    let (direction1, direction2) = two_directions(k, w1, w2, sign)?;
    Ok((
        direction1.angle(),
        direction2.angle(),
        direction1,
        direction2,
    ))
}

/// [`two_angles`] without the angles: `((cos q1, sin q1), (cos q2, sin q2))`, with no arc
/// tangent.
#[inline]
pub fn two_directions<T: Real>(
    k: Vec2<T>,
    w1: Vec2<T>,
    w2: Vec2<T>,
    sign: T,
) -> Result<(Vec2<T>, Vec2<T>), Failure> {
    let s = to_unit_scale(&[k, w1, w2])?;
    let (k, w1, w2) = (scaled(k, s), scaled(w1, s), scaled(w2, s));
    let chord = scaled(k, -T::one());
    let span = length(chord);
    let (r1, r2) = (length(w1), length(w2));
    if span == T::zero() || r1 == T::zero() || r2 == T::zero() {
        return Err(Failure::Degenerate);
    }
    // The triangle of sides r1, r2 and the chord, by Kahan's formula for its area, which
    // keeps every digit of a thin triangle: with the sides sorted a ≥ b ≥ c,
    // 16·area² = (a + (b + c))·(c − (a − b))·(c + (a − b))·(a + (b − c)), where only
    // c − (a − b) can be negative, by no more than rounding where the circles touch.
    let (a, b, c) = sorted_descending(r1, r2, span);
    let gap = gap_closes(c - (a - b), a)?;
    let sixteen_area_squared = (a + (b + c)) * gap * (c + (a - b)) * (a + (b - c));
    // The height of P1's tip over the chord is 2·area/span, on the branch's side.
    let height = sign * sixteen_area_squared.sqrt() / (span + span);
    // Its foot along the chord from each end: (r1² − r2² + span²)/(2·span) with the
    // difference of squares as (r1 − r2)·(r1 + r2), off by rounding of the perimeter at
    // most, since |r1 − r2| ≤ span.
    let along1 = ((r1 - r2) * (r1 + r2) / span + span) * T::constant(0.5);
    let along2 = ((r2 - r1) * (r1 + r2) / span + span) * T::constant(0.5);
    let unit = scaled(chord, T::one() / span);
    let normal = Vec2::new(-unit.y, unit.x);
    let p1 = scaled(unit, along1) + scaled(normal, height);
    let p2 = scaled(unit, along2) - scaled(normal, height);
    let (direction1, direction2) = (turn(p1, w1)?, turn(p2, w2)?);
    closes(
        k + times(direction1, w1) + times(direction2, w2),
        span + r1 + r2,
    )?;
    Ok((direction1, direction2))
}

/// `(x, y, z)` in descending order.
fn sorted_descending<T: Real>(x: T, y: T, z: T) -> (T, T, T) {
    let (x, y) = if x >= y { (x, y) } else { (y, x) };
    let (y, z) = if y >= z { (y, z) } else { (z, y) };
    let (x, y) = if x >= y { (x, y) } else { (y, x) };
    (x, y, z)
}

/// The branch sign of a solution of [`two_angles`].
pub fn two_angles_sign<T: Real>(k: Vec2<T>, w1: Vec2<T>, q1: T) -> T {
    let (sin, cos) = q1.sin_cos();
    let p1 = times(Vec2::new(cos, sin), w1);
    cross_sign(scaled(k, -T::one()), p1)
}
