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

use crate::{Real, Vec2};

/// Why a loop could not be closed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Failure {
    /// The vectors cannot meet: the input is outside the range of motion.
    CannotClose,
    /// The solution is not determined (a zero-length chord, parallel directions).
    Degenerate,
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

/// `|a|` by a plain square root: `hypot` guards against overflow the closed forms cannot meet
/// (squares of lengths up to 1e19 in f32 and 1e154 in f64) at several times the cost.
fn length<T: Real>(a: Vec2<T>) -> T {
    dot(a, a).sqrt()
}

fn scaled<T: Real>(a: Vec2<T>, s: T) -> Vec2<T> {
    Vec2::new(a.x * s, a.y * s)
}

/// The turn `e^{iq}` that carries `from` onto `to`'s direction, as the unit vector
/// `(cos q, sin q)`: what generated code wants, so no `sin_cos` (and no `atan2`, unless the
/// angle itself is asked for) of a solved angle is needed after.
#[inline]
fn turn<T: Real>(to: Vec2<T>, from: Vec2<T>) -> Vec2<T> {
    // to·conj(from), normalised.
    let product = Vec2::new(dot(to, from), cross(from, to));
    scaled(product, T::one() / length(product))
}

/// A square root that treats a slightly negative argument, within rounding of `scale`, as a
/// tangency (zero) rather than a failure.
fn rooted<T: Real>(discriminant: T, scale: T) -> Result<T, Failure> {
    if discriminant >= T::zero() {
        Ok(discriminant.sqrt())
    } else if discriminant >= -T::constant(16.0) * T::epsilon() * scale {
        Ok(T::zero())
    } else {
        Err(Failure::CannotClose)
    }
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
    let determinant = cross(v1, v2);
    let scale = length(v1) * length(v2);
    if determinant.abs() <= T::constant(8.0) * T::epsilon() * scale {
        return Err(Failure::Degenerate);
    }
    Ok([cross(v2, k) / determinant, cross(k, v1) / determinant])
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
    let a = dot(w1, w1);
    if a == T::zero() {
        return Err(Failure::Degenerate);
    }
    let half_b = dot(w1, w0);
    let c = dot(w0, w0) - dot(k, k);
    let discriminant = half_b * half_b - a * c;
    let scale = half_b * half_b + (a * c).abs();
    let l = (-half_b + sign * rooted(discriminant, scale)?) / a;
    let vector = scaled(w1, l) + w0;
    if vector.x == T::zero() && vector.y == T::zero() {
        return Err(Failure::Degenerate);
    }
    Ok((l, turn(scaled(k, -T::one()), vector)))
}

/// The branch sign of a solution of [`length_and_own_angle`].
pub fn length_and_own_angle_sign<T: Real>(w0: Vec2<T>, w1: Vec2<T>, l: T) -> T {
    dot(w1, scaled(w1, l) + w0)
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
    let a = dot(v, v);
    let radius_squared = dot(w0, w0);
    if a == T::zero() || radius_squared == T::zero() {
        return Err(Failure::Degenerate);
    }
    let half_b = dot(v, k);
    let c = dot(k, k) - radius_squared;
    let discriminant = half_b * half_b - a * c;
    let scale = half_b * half_b + (a * c).abs();
    let l = (-half_b + sign * rooted(discriminant, scale)?) / a;
    Ok((l, turn(scaled(k + scaled(v, l), -T::one()), w0)))
}

/// The branch sign of a solution of [`length_and_other_angle`].
pub fn length_and_other_angle_sign<T: Real>(k: Vec2<T>, v: Vec2<T>, l: T) -> T {
    dot(v, k + scaled(v, l))
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
    let chord = scaled(k, -T::one());
    let chord_squared = dot(chord, chord);
    if chord_squared == T::zero() {
        return Err(Failure::Degenerate);
    }
    let span = chord_squared.sqrt();
    let (r1_squared, r2_squared) = (dot(w1, w1), dot(w2, w2));
    let along = (r1_squared - r2_squared + chord_squared) / (span + span);
    let height = sign * rooted(r1_squared - along * along, r1_squared)?;
    let unit = scaled(chord, T::one() / span);
    let normal = Vec2::new(-unit.y, unit.x);
    let p1 = scaled(unit, along) + scaled(normal, height);
    let p2 = chord - p1;
    Ok((turn(p1, w1), turn(p2, w2)))
}

/// The branch sign of a solution of [`two_angles`].
pub fn two_angles_sign<T: Real>(k: Vec2<T>, w1: Vec2<T>, q1: T) -> T {
    let (sin, cos) = q1.sin_cos();
    let p1 = times(Vec2::new(cos, sin), w1);
    cross(scaled(k, -T::one()), p1)
}
