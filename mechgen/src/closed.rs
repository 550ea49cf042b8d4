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
/// ([`to_unit_scale`]), whose squares cannot overflow; where one might be below the float's
/// normal range (a vector some 1e-154 of the unit scale), the caller asks [`tiny_length`].
fn length<T: Real>(a: Vec2<T>) -> T {
    dot(a, a).sqrt()
}

/// `|a|` of a vector whose square is below the float's normal range, where it has lost digits
/// or all of them (a loop whose links differ by 1e170, a Watt six-bar's second pivot 1e170
/// away, squares its short links to zero): from the vector scaled to unit size by a power of
/// two, and back (exact both ways, but where the length itself is subnormal). Zero for the
/// zero vector.
#[cold]
#[inline(never)]
fn tiny_length<T: Real>(a: Vec2<T>) -> T {
    let largest = largest_component(&[a]);
    if largest == T::zero() {
        return T::zero();
    }
    let s = normaliser(largest);
    dot(scaled(a, s), scaled(a, s)).sqrt() / s
}

/// The lengths of `vectors` at unit scale, none of them zero: by plain square roots where
/// every square is a normal number (one comparison of the smallest, which also says none is
/// zero), else each by [`tiny_length`], out of line. Errors: a zero vector.
#[inline]
fn nonzero_lengths<T: Real, const N: usize>(vectors: [Vec2<T>; N]) -> Result<[T; N], Failure> {
    let squares = vectors.map(|v| dot(v, v));
    let smallest = squares.iter().fold(T::infinity(), |m, s| m.min(*s));
    if smallest >= T::min_positive_value() {
        Ok(squares.map(T::sqrt))
    } else {
        tiny_lengths(vectors)
    }
}

/// [`nonzero_lengths`] where a square is below the float's normal range.
#[cold]
#[inline(never)]
fn tiny_lengths<T: Real, const N: usize>(vectors: [Vec2<T>; N]) -> Result<[T; N], Failure> {
    let lengths = vectors.map(tiny_length);
    if lengths.iter().any(|l| *l == T::zero()) {
        return Err(Failure::Degenerate);
    }
    Ok(lengths)
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

/// The sum of a loop's magnitudes, which scales [`closes`]'s tolerance: one function, tested
/// on its own, for every closed form (a wrong sum would only loosen or tighten the tolerance,
/// which the solutions, closing far inside it, would not show).
fn sum_of<T: Real, const M: usize>(magnitudes: [T; M]) -> T {
    magnitudes.iter().fold(T::zero(), |sum, m| sum + *m)
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
    // Cramer's rule leaves a residual of κ = 1/|det| units of the magnitudes' rounding (each
    // length is off by that relative to the rest): the loop closes to that, however nearly
    // opposite the directions, so long as they are not parallel to rounding.
    closes(
        k + scaled(u1, along1) + scaled(u2, along2),
        sum_of([length(k), along1.abs(), along2.abs()]) / determinant.abs(),
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
    let radius = match nonzero_lengths([k]) {
        Ok([radius]) => radius,
        Err(_) => return Err(line_through_centre(w0, u)),
    };
    let (along, point) = line_meets_circle(w0, u, radius, sign)?;
    let direction = turn(scaled(k, -T::one()), point)?;
    closes(
        k + times(direction, scaled(u, along) + w0),
        sum_of([radius, along.abs(), length(w0)]),
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
    let [radius] = nonzero_lengths([w0])?;
    let (along, point) = line_meets_circle(k, u, radius, sign)?;
    let direction = turn(scaled(point, -T::one()), w0)?;
    closes(
        k + scaled(u, along) + times(direction, w0),
        sum_of([length(k), along.abs(), radius]),
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
    let [span, r1, r2] = match nonzero_lengths([chord, w1, w2]) {
        Ok(lengths) => lengths,
        Err(failure) => return Err(concentric(chord, w1, w2, failure)),
    };
    // The triangle of sides r1, r2 and the chord, by Kahan's formula for its area, which
    // keeps every digit of a thin triangle: with the sides sorted a ≥ b ≥ c,
    // 16·area² = (a + (b + c))·(c − (a − b))·(c + (a − b))·(a + (b − c)), where only
    // c − (a − b) can be negative, by no more than rounding where the circles touch.
    let (a, b, c) = sorted_descending(r1, r2, span);
    let gap = gap_closes(c - (a - b), a)?;
    let sixteen_area_squared = (a + (b + c)) * gap * (c + (a - b)) * (a + (b - c));
    // A triangle whose short side is some 1e-154 of the others (or a tangency, flat), out
    // of line, where the same arithmetic gives the same bits.
    if sixteen_area_squared < T::min_positive_value() {
        return thin_triangle(k, w1, w2, sign);
    }
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
        sum_of([span, r1, r2]),
    )?;
    Ok((direction1, direction2))
}

/// [`two_directions`] for a triangle whose short side is some 1e-154 of the others (a short
/// link across a chord as long as the other link), where the area's two small factors
/// multiply below the float's normal range, and a short link's tip over the chord times the
/// link would underflow: the area's root from each factor apart, and each turn from its two
/// vectors at their own unit scales. The same arithmetic otherwise.
#[cold]
#[inline(never)]
fn thin_triangle<T: Real>(
    k: Vec2<T>,
    w1: Vec2<T>,
    w2: Vec2<T>,
    sign: T,
) -> Result<(Vec2<T>, Vec2<T>), Failure> {
    let [span, r1, r2] = nonzero_lengths([scaled(k, -T::one()), w1, w2])?;
    let (a, b, c) = sorted_descending(r1, r2, span);
    let gap = gap_closes(c - (a - b), a)?;
    let sixteen_area = ((a + (b + c)) * (a + (b - c))).sqrt() * gap.sqrt() * (c + (a - b)).sqrt();
    let height = sign * sixteen_area / (span + span);
    let along1 = ((r1 - r2) * (r1 + r2) / span + span) * T::constant(0.5);
    let along2 = ((r2 - r1) * (r1 + r2) / span + span) * T::constant(0.5);
    let unit = scaled(k, -T::one() / span);
    let normal = Vec2::new(-unit.y, unit.x);
    let p1 = scaled(unit, along1) + scaled(normal, height);
    let p2 = scaled(unit, along2) - scaled(normal, height);
    let turned = |to: Vec2<T>, from: Vec2<T>| turn(at_unit_scale(to), at_unit_scale(from));
    let (direction1, direction2) = (turned(p1, w1)?, turned(p2, w2)?);
    closes(
        k + times(direction1, w1) + times(direction2, w2),
        sum_of([span, r1, r2]),
    )?;
    Ok((direction1, direction2))
}

/// Why two circles whose centres coincide (`chord`, at unit scale, is zero) cannot be met at
/// one point: their radii differ (beyond rounding), so they never meet, or they are the same
/// circle, met everywhere, and the angles are undetermined. `failure` where the chord is not
/// zero (a link of zero length). (A crank pin on the rocker's pivot: a four-bar whose ground
/// is its crank, at zero.)
#[cold]
#[inline(never)]
fn concentric<T: Real>(chord: Vec2<T>, w1: Vec2<T>, w2: Vec2<T>, failure: Failure) -> Failure {
    if chord != Vec2::new(T::zero(), T::zero()) {
        return failure;
    }
    match nonzero_lengths([w1, w2]) {
        Ok([r1, r2]) => meets_where_undetermined(-(r1 - r2).abs(), r1.max(r2)),
        Err(failure) => failure,
    }
}

/// Why the point `w0 + L·u` (`u` a unit vector, `w0` at unit scale) cannot be placed on a
/// circle of radius zero about the origin at one solution: the line misses the centre (beyond
/// rounding), or passes through it, where the turn about the centre is undetermined. (An
/// inverted slider-crank whose crank pin is on the slide's pivot.)
#[cold]
#[inline(never)]
fn line_through_centre<T: Real>(w0: Vec2<T>, u: Vec2<T>) -> Failure {
    meets_where_undetermined(-cross(u, w0).abs(), length(w0))
}

/// [`Failure::Degenerate`] where a gap that is zero for a loop that closes is zero to
/// rounding of `scale` (the loop closes, at a solution it does not determine), else
/// [`Failure::CannotClose`].
fn meets_where_undetermined<T: Real>(gap: T, scale: T) -> Failure {
    match gap_closes(gap, scale) {
        Ok(_) => Failure::Degenerate,
        Err(failure) => failure,
    }
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

/// [`two_angles_sign`], or zero where the loop's other assembly is within `margin` of the
/// solution (see `side`).
pub fn two_angles_side<T: Real>(k: Vec2<T>, w1: Vec2<T>, q1: T, margin: T) -> T {
    let (sin, cos) = q1.sin_cos();
    let p1 = times(Vec2::new(cos, sin), w1);
    side(scaled(k, -T::one()), p1, margin, cross)
}

/// [`length_and_own_angle_sign`], or zero where the loop's other assembly is within `margin`
/// of the solution (see `side`).
pub fn length_and_own_angle_side<T: Real>(w0: Vec2<T>, w1: Vec2<T>, l: T, margin: T) -> T {
    side(w1, scaled(w1, l) + w0, margin, dot)
}

/// [`length_and_other_angle_sign`], or zero where the loop's other assembly is within
/// `margin` of the solution (see `side`).
pub fn length_and_other_angle_side<T: Real>(k: Vec2<T>, v: Vec2<T>, l: T, margin: T) -> T {
    side(v, k + scaled(v, l), margin, dot)
}

/// A branch sign, `product(a, b)`, where it is decided; zero where the loop's other assembly
/// is within `margin` (a length: a position's error) of this one. The two assemblies are
/// mirror images whose moving points are `2·|product(â, b)|` apart (`â` the unit vector along
/// `a`): across the chord `a` for [`cross`] (twice the height of `b`'s tip over it), along
/// the line `a` for [`dot`] (the two roots of a slide). Within `margin` of each other the
/// solution is on both to within its error, and its sign is rounding. Beyond it, a solution
/// returned for the other would be further from it than its error: the sign decides. (A
/// test of whether moving `a` and `b` each by `margin` could flip the sign, as this was until
/// edge run case 502593, leaves undecided assemblies up to four margins apart: an f32 Watt
/// six-bar's solution on the other assembly of its first loop, 1.5 times its error from the
/// one asked, was returned as on both.)
fn side<T: Real>(a: Vec2<T>, b: Vec2<T>, margin: T, product: fn(Vec2<T>, Vec2<T>) -> T) -> T {
    let (Ok(sa), Ok(sb)) = (to_unit_scale(&[a]), to_unit_scale(&[b])) else {
        return T::zero();
    };
    let (a, b) = (scaled(a, sa), scaled(b, sb));
    let value = product(a, b);
    // In these units the assemblies are `2·|value|/(sb·|a|)` apart (`|a|` here `sa` times
    // the given length, `value` `sa·sb` times the given product); plus the product's own
    // rounding. An overflow, or NaN, is undecided.
    let (la, lb) = (length(a), length(b));
    let apart = T::constant(2.0) * value.abs();
    let within = margin * sb * la + T::constant(8.0) * T::epsilon() * la * lb;
    if apart > within { value } else { T::zero() }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> Vec2<f64> {
        Vec2::new(x, y)
    }

    /// `e^{iq}·w`.
    fn turned(q: f64, w: Vec2<f64>) -> Vec2<f64> {
        let (sin, cos) = q.sin_cos();
        times(v(cos, sin), w)
    }

    fn assert_near(got: f64, want: f64) {
        let tolerance = 8.0 * f64::EPSILON * want.abs().max(1.0);
        assert!((got - want).abs() <= tolerance, "{got} != {want}");
    }

    fn assert_closes(residual: Vec2<f64>, size: f64) {
        let tolerance = 32.0 * f64::EPSILON * size;
        assert!(
            residual.x.abs() <= tolerance && residual.y.abs() <= tolerance,
            "residual {residual:?}"
        );
    }

    /// The angle of `direction` is `q`, and `direction` is its unit vector.
    fn assert_direction(direction: Vec2<f64>, angle: f64, q: f64) {
        let (sin, cos) = q.sin_cos();
        assert_near(direction.x, cos);
        assert_near(direction.y, sin);
        assert_near(angle, q);
    }

    #[test]
    fn failures_are_the_errors_they_stand_for() {
        assert_eq!(
            Failure::CannotClose.at(2.5),
            crate::Error::CannotAssemble { input: 2.5 }
        );
        assert_eq!(
            Failure::Degenerate.at(2.5),
            crate::Error::Singular {
                determinant: 0.0,
                relative_determinant: 0.0
            }
        );
        assert_eq!(
            Failure::NonFinite.at(2.5),
            crate::Error::NonFinite {
                quantity: "closed-form solution"
            }
        );
    }

    #[test]
    fn complex_products_and_sorting_are_exact() {
        // (1 + 2i)(3 − 4i) = 11 + 2i.
        assert_eq!(times(v(1.0, 2.0), v(3.0, -4.0)), v(11.0, 2.0));
        assert_eq!(cross(v(1.0, 2.0), v(3.0, -4.0)), -10.0);
        assert_eq!(dot(v(1.0, 2.0), v(3.0, -4.0)), -5.0);
        for (x, y, z) in [
            (1.0, 2.0, 3.0),
            (1.0, 3.0, 2.0),
            (2.0, 1.0, 3.0),
            (2.0, 3.0, 1.0),
            (3.0, 1.0, 2.0),
            (3.0, 2.0, 1.0),
        ] {
            assert_eq!(sorted_descending(x, y, z), (3.0, 2.0, 1.0));
        }
        assert_eq!(sorted_descending(2.0, 2.0, 1.0), (2.0, 2.0, 1.0));
    }

    /// A loop turning about a point of zero length: two circles about one centre meet
    /// nowhere unless their radii are equal (to rounding), and then everywhere; a line meets
    /// a circle of radius zero only if it passes through its centre, and then turns about it
    /// freely. `CannotClose` where they do not meet (a four-bar whose crank, as long as its
    /// ground, lays its pin on the rocker's pivot, at zero, said `Singular` where it cannot
    /// assemble), `Degenerate` where the solution is undetermined.
    #[test]
    fn a_loop_about_a_point_closes_only_where_it_is_undetermined() {
        let zero = v(0.0, 0.0);
        for sign in [1.0, -1.0] {
            assert_eq!(
                two_directions(zero, v(100.0, 0.0), v(0.0, -80.0), sign),
                Err(Failure::CannotClose)
            );
            assert_eq!(
                two_directions(zero, v(100.0, 0.0), v(0.0, -100.0), sign),
                Err(Failure::Degenerate)
            );
            // Equal to rounding.
            let nearly = 100.0 * (1.0 + 2.0 * f64::EPSILON);
            assert_eq!(
                two_directions(zero, v(100.0, 0.0), v(-nearly, 0.0), sign),
                Err(Failure::Degenerate)
            );
            // The slide 5 from the pivot its crank pin is on; along a line through it.
            assert_eq!(
                length_and_own_direction(zero, v(0.0, 5.0), v(1.0, 0.0), sign),
                Err(Failure::CannotClose)
            );
            assert_eq!(
                length_and_own_direction(zero, v(3.0, 0.0), v(1.0, 0.0), sign),
                Err(Failure::Degenerate)
            );
            assert_eq!(
                length_and_own_direction(zero, v(3.0, 1e-17), v(1.0, 0.0), sign),
                Err(Failure::Degenerate)
            );
            // A link of zero length is not a chord of zero length.
            assert_eq!(
                two_directions(v(1.0, 0.0), zero, v(0.0, -1.0), sign),
                Err(Failure::Degenerate)
            );
        }
    }

    /// A loop whose vectors differ by more than the float's normal range can square: the
    /// short ones' lengths from the vectors scaled up, not from squares that lost their
    /// digits or underflowed to zero (a Watt six-bar whose second pivot is 1e170 away was
    /// `Singular`, its short links of length zero, where it cannot assemble).
    #[test]
    fn lengths_in_a_loop_of_vastly_different_vectors() {
        assert_eq!(
            nonzero_lengths([
                v(3e-170, 4e-170),
                v(-3e-160, 4e-160),
                v(0.0, -1e-200),
                v(3.0, 4.0)
            ]),
            Ok([5e-170, 5e-160, 1e-200, 5.0])
        );
        assert_eq!(nonzero_lengths([v(3.0, 4.0), v(0.0, 0.5)]), Ok([5.0, 0.5]));
        assert_eq!(
            nonzero_lengths::<f64, 2>([v(0.0, 0.0), v(1.0, 0.0)]),
            Err(Failure::Degenerate)
        );
        assert_eq!(tiny_length(v(f64::MIN_POSITIVE, 0.0)), f64::MIN_POSITIVE);
        // Two short links 1e-170 of the chord: they cannot reach across it.
        assert_eq!(
            two_angles(v(1.0, 0.0), v(2e-170, 0.0), v(-1e-170, 0.0), 1.0).map(|_| ()),
            Err(Failure::CannotClose)
        );
        // A slide's line 1 from the pivot and a rod 1e-170 long: it cannot reach the line.
        assert_eq!(
            length_and_other_direction(v(0.0, 1.0), v(1.0, 0.0), v(1e-170, 0.0), 1.0).map(|_| ()),
            Err(Failure::CannotClose)
        );
        assert_eq!(
            length_and_own_direction(v(1e-170, 0.0), v(0.0, 1.0), v(1.0, 0.0), 1.0).map(|_| ()),
            Err(Failure::CannotClose)
        );
        // A long link as long as the chord and a short one: they close, thin as it is. The
        // short link stands across the chord, on the branch's side; the long one is turned
        // off the chord by the short one's length, the other way.
        for sign in [1.0, -1.0] {
            let (_, _, d1, d2) =
                two_angles(v(-1.5, 0.0), v(1e-170, 0.0), v(1.5, 0.0), sign).unwrap();
            assert!(
                (d1.x).abs() < 1e-15 && (d1.y - sign).abs() < 1e-15,
                "{d1:?}"
            );
            assert!((d2.x - 1.0).abs() < 1e-15, "{d2:?}");
            assert!(
                (d2.y / (-sign * 1e-170 / 1.5) - 1.0).abs() < 1e-12,
                "{d2:?}"
            );
        }
        // Two equal long links folded over a chord 1e-170 long: they meet high above its
        // middle, each leaning in by half the chord over its length.
        for sign in [1.0, -1.0] {
            let (_, _, d1, d2) =
                two_angles(v(-1e-170, 0.0), v(1.5, 0.0), v(1.5, 0.0), sign).unwrap();
            assert!((d1.x / (0.5e-170 / 1.5) - 1.0).abs() < 1e-12, "{d1:?}");
            assert!((d1.y - sign).abs() < 1e-15, "{d1:?}");
            assert!((d2.x / (0.5e-170 / 1.5) - 1.0).abs() < 1e-12, "{d2:?}");
            assert!((d2.y + sign).abs() < 1e-15, "{d2:?}");
        }
        // The same across a chord turned by 0.3 rad.
        let (s, c) = 0.3f64.sin_cos();
        let (_, _, d1, d2) = two_angles(v(-c, -s), v(1e-170, 0.0), v(1.0, 0.0), 1.0).unwrap();
        assert!(
            (d1.x + s).abs() < 1e-15 && (d1.y - c).abs() < 1e-15,
            "{d1:?}"
        );
        assert!(
            (d2.x - c).abs() < 1e-15 && (d2.y - s).abs() < 1e-15,
            "{d2:?}"
        );
    }

    /// Tangencies, whose area is zero, take the thin triangle's path and come out exact: two
    /// links stretched along the chord, and folded back along it.
    #[test]
    fn tangent_loops_close_along_their_chord() {
        let (s, c) = 0.3f64.sin_cos();
        let along = v(c, s);
        let chord = |l: f64| v(-l * c, -l * s);
        // Stretched: 1 + 2 = 3, both along the chord.
        let (_, _, d1, d2) = two_angles(chord(3.0), v(1.0, 0.0), v(2.0, 0.0), 1.0).unwrap();
        for d in [d1, d2] {
            assert!(
                (d.x - along.x).abs() < 1e-15 && (d.y - along.y).abs() < 1e-15,
                "{d:?}"
            );
        }
        // Folded: 3 forward, 2 back, 1 across.
        let (_, _, d1, d2) = two_angles(chord(1.0), v(3.0, 0.0), v(2.0, 0.0), -1.0).unwrap();
        assert!(
            (d1.x - along.x).abs() < 1e-15 && (d1.y - along.y).abs() < 1e-15,
            "{d1:?}"
        );
        assert!(
            (d2.x + along.x).abs() < 1e-15 && (d2.y + along.y).abs() < 1e-15,
            "{d2:?}"
        );
        // The other branch sign: a tangency has one solution.
        let (_, _, e1, e2) = two_angles(chord(1.0), v(3.0, 0.0), v(2.0, 0.0), 1.0).unwrap();
        assert_eq!((e1, e2), (d1, d2));
    }

    #[test]
    fn unit_scale_brings_the_largest_component_into_a_half_to_one() {
        assert_eq!(to_unit_scale(&[v(3.0, -0.5), v(0.25, 1.0)]), Ok(0.25));
        assert_eq!(to_unit_scale(&[v(0.0, 0.0), v(-0.75, 0.0)]), Ok(1.0));
        assert_eq!(
            to_unit_scale::<f64>(&[v(0.0, 0.0)]),
            Err(Failure::Degenerate)
        );
        // One component not finite, in either place, is enough.
        for bad in [v(f64::NAN, 1.0), v(1.0, f64::INFINITY)] {
            assert_eq!(to_unit_scale(&[v(1.0, 1.0), bad]), Err(Failure::NonFinite));
        }
        let (direction, norm) = direction_and_length(v(-3.0, 4.0)).unwrap();
        assert_near(direction.x, -0.6);
        assert_near(direction.y, 0.8);
        assert_eq!(norm, 5.0);
        assert_eq!(at_unit_scale(v(3.0, 0.0)), v(0.75, 0.0));
        assert_eq!(at_unit_scale(v(0.0, 0.0)), v(0.0, 0.0));
    }

    #[test]
    fn two_lengths_in_oblique_directions_at_any_scale() {
        let (v1, v2) = (v(3.0, 4.0), v(-1.0, 2.0));
        let lengths = [1.5, -2.25];
        let k = v(-6.75, -1.5);
        assert_closes(k + scaled(v1, lengths[0]) + scaled(v2, lengths[1]), 1.0);
        let solved = two_lengths(k, v1, v2).unwrap();
        assert_near(solved[0], lengths[0]);
        assert_near(solved[1], lengths[1]);
        // Powers of two scale the solution exactly, however large or small.
        let big = 2f64.powi(1000);
        let tiny = 2f64.powi(-1000);
        let scaled_solution = |s: f64| solved.map(|l| l * s);
        assert_eq!(
            two_lengths(scaled(k, big), v1, v2),
            Ok(scaled_solution(big))
        );
        assert_eq!(
            two_lengths(scaled(k, tiny), v1, v2),
            Ok(scaled_solution(tiny))
        );
        assert_eq!(
            two_lengths(k, scaled(v1, tiny), scaled(v2, tiny)),
            Ok(scaled_solution(big))
        );
        // Lengths too large for f64.
        assert_eq!(
            two_lengths(scaled(k, big), scaled(v1, tiny), v2),
            Err(Failure::NonFinite)
        );
        // Nothing to close: zero lengths.
        assert_eq!(two_lengths(v(0.0, 0.0), v1, v2), Ok([0.0, 0.0]));
        assert_eq!(
            two_lengths(v(f64::NAN, 0.0), v1, v2),
            Err(Failure::NonFinite)
        );
    }

    #[test]
    fn two_lengths_are_degenerate_only_for_directions_parallel_to_rounding() {
        let k = v(-1.0, -1.0);
        assert_eq!(
            two_lengths(k, v(1.0, 2.0), v(-2.0, -4.0)),
            Err(Failure::Degenerate)
        );
        assert_eq!(
            two_lengths(k, v(0.0, 0.0), v(1.0, 0.0)),
            Err(Failure::Degenerate)
        );
        // Unit directions whose cross product is exactly 8ε: degenerate; 16ε: solved.
        let e = f64::EPSILON;
        assert_eq!(
            two_lengths(k, v(1.0, 0.0), v(1.0, 8.0 * e)),
            Err(Failure::Degenerate)
        );
        assert!(two_lengths(v(0.0, -16.0 * e), v(1.0, 0.0), v(1.0, 16.0 * e)).is_ok());
    }

    #[test]
    fn length_and_own_angle_on_both_branches() {
        let (w0, w1) = (v(0.5, -1.5), v(2.0, 1.0));
        let (l, q) = (1.75, 0.9);
        // l·w1 + w0 = (4, 0.25), turned by q, closes K.
        let k = scaled(turned(q, v(4.0, 0.25)), -1.0);
        let sign = length_and_own_angle_sign(w0, w1, l);
        assert!(sign > 0.0);
        let (solved, angle, direction) = length_and_own_angle(k, w0, w1, 1.0).unwrap();
        assert_near(solved, l);
        assert_direction(direction, angle, q);
        // |l·w1 + w0| = |K| is 5l² − l − 13.5625 = 0: the other root is 0.2 − 1.75.
        let (other, angle, direction) = length_and_own_angle(k, w0, w1, -1.0).unwrap();
        assert_near(other, -1.55);
        assert!(length_and_own_angle_sign(w0, w1, other) < 0.0);
        // w1·(l·w1 + w0) = 5l − 1/2: negative below l = 1/10, though w1·(l·w1 − w0) is not.
        assert!(length_and_own_angle_sign(w0, w1, 0.05) < 0.0);
        assert!(length_and_own_angle_sign(w0, w1, 0.15) > 0.0);
        assert_near(angle, direction.angle());
        assert_closes(k + times(direction, scaled(w1, other) + w0), 10.0);
        assert_near(direction.norm(), 1.0);
        // The same at a scale whose squares overflow.
        let big = 2f64.powi(600);
        let (huge, angle, _) =
            length_and_own_angle(scaled(k, big), scaled(w0, big), w1, 1.0).unwrap();
        assert_eq!(huge, solved * big);
        assert_near(angle, q);
    }

    #[test]
    fn length_and_own_angle_fails_as_it_should() {
        let (w0, w1) = (v(0.5, -1.5), v(2.0, 1.0));
        // A circle of radius |K| = 0 that the line l·w1 + w0 misses.
        assert_eq!(
            length_and_own_angle(v(0.0, 0.0), w0, w1, 1.0),
            Err(Failure::CannotClose)
        );
        // The line l·w1 + w0 passes farther from the origin than |K|.
        assert_eq!(
            length_and_own_angle(v(0.1, 0.0), v(0.0, 1.0), v(1.0, 0.0), 1.0),
            Err(Failure::CannotClose)
        );
        assert_eq!(
            length_and_own_angle(v(f64::INFINITY, 0.0), w0, w1, 1.0),
            Err(Failure::NonFinite)
        );
        // A length too large for f64.
        let tiny = 2f64.powi(-1000);
        assert_eq!(
            length_and_own_angle(v(f64::MAX, 0.0), v(0.0, 0.0), v(tiny, 0.0), 1.0),
            Err(Failure::NonFinite)
        );
    }

    #[test]
    fn length_and_other_angle_on_both_branches() {
        let (v1, w0) = (v(1.0, 2.0), v(1.5, 2.0));
        let (l, q) = (1.2, 2.0);
        let k = scaled(scaled(v1, l) + turned(q, w0), -1.0);
        let sign = length_and_other_angle_sign(k, v1, l);
        let sigma = if sign > 0.0 { 1.0 } else { -1.0 };
        let (solved, angle, direction) = length_and_other_angle(k, v1, w0, sigma).unwrap();
        assert_near(solved, l);
        assert_direction(direction, angle, q);
        // |K + l·v|² = |w0|²: the roots sum to −2 v·K / |v|².
        let other = -2.0 * dot(v1, k) / dot(v1, v1) - l;
        let (solved, angle, direction) = length_and_other_angle(k, v1, w0, -sigma).unwrap();
        assert_near(solved, other);
        assert!(length_and_other_angle_sign(k, v1, solved) * sign < 0.0);
        assert_near(angle, direction.angle());
        assert_closes(k + scaled(v1, solved) + times(direction, w0), 10.0);
        // The same at a scale whose squares underflow.
        let tiny = 2f64.powi(-600);
        let (small, angle, _) =
            length_and_other_angle(scaled(k, tiny), v1, scaled(w0, tiny), -sigma).unwrap();
        assert_eq!(small, solved * tiny);
        assert_near(angle, direction.angle());
    }

    #[test]
    fn length_and_other_angle_fails_as_it_should() {
        let v1 = v(1.0, 0.0);
        assert_eq!(
            length_and_other_angle(v(0.0, 3.0), v1, v(0.0, 0.0), 1.0),
            Err(Failure::Degenerate)
        );
        // The line y = 3 misses the circle of radius 2.
        assert_eq!(
            length_and_other_angle(v(0.0, 3.0), v1, v(2.0, 0.0), 1.0),
            Err(Failure::CannotClose)
        );
        assert_eq!(
            length_and_other_angle(v(0.0, 3.0), v(0.0, 0.0), v(5.0, 0.0), 1.0),
            Err(Failure::Degenerate)
        );
    }

    #[test]
    fn a_line_meets_a_circle_at_its_roots_from_either_side() {
        // The point (l, 3) on the circle of radius 5: l = ±4, the + branch farther along u.
        let u = v(1.0, 0.0);
        for (k, sign, root) in [
            (v(0.0, 3.0), 1.0, 4.0),
            (v(0.0, 3.0), -1.0, -4.0),
            // The foot ahead (t0 = 2), then behind (t0 = −2): the root that would cancel
            // against t0 comes from the product of the roots.
            (v(-2.0, 3.0), 1.0, 6.0),
            (v(-2.0, 3.0), -1.0, -2.0),
            (v(2.0, 3.0), 1.0, 2.0),
            (v(2.0, 3.0), -1.0, -6.0),
        ] {
            let (l, point) = line_meets_circle(k, u, 5.0, sign).unwrap();
            assert_near(l, root);
            assert_near(point.x, k.x + root);
            assert_near(point.y, 3.0);
        }
        // Tangent: one root, the foot.
        let (l, point) = line_meets_circle(v(-2.0, 5.0), u, 5.0, -1.0).unwrap();
        assert_near(l, 2.0);
        assert_near(point.x, 0.0);
        assert_eq!(point.y, 5.0);
    }

    #[test]
    fn a_line_meets_a_circle_without_cancellation() {
        // The point K + l·(1, 0), K = (−3/8, 1/2) (|K| = 5/8 exactly), on a circle of radius
        // 5/8 − 2⁻⁴⁰: l = 3/8 ± √(r² − 1/4), one root about 1.5e-12 beside a foot of 3/8,
        // the other twice the foot; each to a few units of rounding, where the difference
        // that cancels would keep only five digits of the small one. Mirrored (the foot
        // behind the line's start), the roots are negated.
        let r = 0.625 - 2f64.powi(-40);
        let h = (r * r - 0.25).sqrt();
        let (large, small) = (
            0.375 + h,
            2f64.powi(-40) * (1.25 - 2f64.powi(-40)) / (0.375 + h),
        );
        for (mirror, sign, root) in [
            (1.0, 1.0, large),
            (1.0, -1.0, small),
            (-1.0, -1.0, -large),
            (-1.0, 1.0, -small),
        ] {
            let (l, _) = line_meets_circle(v(-0.375 * mirror, 0.5), v(1.0, 0.0), r, sign).unwrap();
            assert!(
                (l - root).abs() <= 8.0 * f64::EPSILON * root.abs(),
                "{l} != {root}"
            );
        }
    }

    #[test]
    fn a_line_touches_a_circle_within_rounding_of_its_size_only() {
        // The line y = 5 + δ and the circle of radius 5, seen from (−2, 5 + δ): a tangency
        // for δ within 8ε of 5 + |K| (about 83ε, 21 units of rounding of 5), else apart.
        let ulp = 4.0 * f64::EPSILON;
        for (ulps, touches) in [(1.0, true), (10.0, true), (30.0, false)] {
            let k = v(-2.0, 5.0 + ulps * ulp);
            let met = line_meets_circle(k, v(1.0, 0.0), 5.0, 1.0);
            match met {
                Ok((l, _)) if touches => assert_near(l, 2.0),
                Err(Failure::CannotClose) if !touches => {}
                other => panic!("{ulps} units: {other:?}"),
            }
        }
    }

    /// Near-collinear loops, where the sum of the magnitudes that bounds each solution's
    /// residual is far from its difference: the residual is a rounding of the long vectors,
    /// not of the short sum they close.
    #[test]
    fn nearly_collinear_loops_close_to_the_rounding_of_their_long_vectors() {
        let thin = 3e-6;
        // Lengths 1.3 and 0.7, and 0.7 and 1.3, along directions 0.1 from opposite, turned
        // by 0.5. (Nearer to opposite, see `two_lengths_of_nearly_opposite_directions`.)
        let (v1, v2) = (turned(0.5, v(1.0, 0.0)), turned(0.5, v(-1.0, 0.1)));
        for lengths in [[1.3, 0.7], [0.7, 1.3], [0.71, 1.37]] {
            let k = scaled(scaled(v1, lengths[0]) + scaled(v2, lengths[1]), -1.0);
            let solved = two_lengths(k, v1, v2).unwrap();
            for (l, want) in solved.iter().zip(lengths) {
                assert!((l - want).abs() < 1e-14, "{solved:?} != {lengths:?}");
            }
        }
        // A slide 1.9 long and an offset 0.7 back along it: the vector (1.2, 3e-6), turned.
        let (w0, w1) = (v(-0.7, thin), v(1.0, 0.0));
        let k = scaled(turned(0.4, v(1.2, thin)), -1.0);
        let (l, q, _) = length_and_own_angle(k, w0, w1, 1.0).unwrap();
        assert!((l - 1.9).abs() < 1e-9 && (q - 0.4).abs() < 1e-9, "{l}, {q}");
        // The point K + l·(1, 0), K = (−0.8, 3e-6), on the circle of radius 0.5: l ≈ 1.3.
        let k = v(-0.8, thin);
        let (l, q, _) = length_and_other_angle(k, v(1.0, 0.0), v(0.5, 0.0), 1.0).unwrap();
        let far = 0.8 + (0.25 - thin * thin).sqrt();
        assert!((l - far).abs() < 1e-12 && q.abs() > 3.0, "{l}, {q}");
        // A slide 0.5 long with an offset 1.2 back along it, and the point K + 0.5·(1, 0),
        // K = (0.3, 3e-6), on the circle of radius 0.8: the other sums that nearly cancel.
        let k = scaled(turned(0.4, v(-0.7, thin)), -1.0);
        let (l, q, _) = length_and_own_angle(k, v(-1.2, thin), v(1.0, 0.0), -1.0).unwrap();
        assert!((l - 0.5).abs() < 1e-9 && (q - 0.4).abs() < 1e-9, "{l}, {q}");
        let (l, _, _) =
            length_and_other_angle(v(0.3, thin), v(1.0, 0.0), v(0.8, 0.0), 1.0).unwrap();
        assert!((l - 0.5).abs() < 1e-9, "{l}");
    }

    /// Found by mutation testing: two lengths along directions 3e-6 from opposite (a relative
    /// determinant far above √ε) are determined to about κ·ε = 1e-10, but Cramer's rule
    /// leaves a loop residual of that size too, which `closes` accepts as the condition's
    /// (it once held it to 32ε of the magnitudes and said `CannotClose`).
    #[test]
    fn two_lengths_of_nearly_opposite_directions() {
        let (v1, v2) = (turned(0.5, v(1.0, 0.0)), turned(0.5, v(-1.0, 3e-6)));
        let k = scaled(scaled(v1, 1.3) + scaled(v2, 0.7), -1.0);
        let [l1, l2] = two_lengths(k, v1, v2).unwrap();
        assert!(
            (l1 - 1.3).abs() < 1e-9 && (l2 - 0.7).abs() < 1e-9,
            "{l1}, {l2}"
        );
    }

    #[test]
    fn two_angles_on_both_branches() {
        let (w1, w2) = (v(2.0, 1.0), v(1.5, -2.0));
        let (q1, q2) = (0.8, -0.5);
        let k = scaled(turned(q1, w1) + turned(q2, w2), -1.0);
        let sign = two_angles_sign(k, w1, q1);
        let sigma = if sign > 0.0 { 1.0 } else { -1.0 };
        let (a1, a2, d1, d2) = two_angles(k, w1, w2, sigma).unwrap();
        assert_direction(d1, a1, q1);
        assert_direction(d2, a2, q2);
        // The other branch: P1's tip mirrored in the chord.
        let (a1, a2, d1, d2) = two_angles(k, w1, w2, -sigma).unwrap();
        assert!(two_angles_sign(k, w1, a1) * sign < 0.0);
        assert_near(a1, d1.angle());
        assert_near(a2, d2.angle());
        assert_closes(k + times(d1, w1) + times(d2, w2), 10.0);
        // With the links swapped, the same triangle from the chord's other end.
        let (b2, b1, _, _) = two_angles(k, w2, w1, sigma).unwrap();
        assert!((b1 - a1).abs() + (b2 - a2).abs() < 1e-12 || two_angles_sign(k, w1, b1) > 0.0);
        // Powers of two scale nothing in the angles.
        let big = 2f64.powi(700);
        let (h1, h2, _, _) =
            two_angles(scaled(k, big), scaled(w1, big), scaled(w2, big), -sigma).unwrap();
        assert_eq!((h1, h2), (a1, a2));
    }

    #[test]
    fn two_angles_over_a_chord_of_a_power_of_two() {
        // Links of 5 over a chord of 8 (1/2 at unit scale, exactly): they meet at (4, ±3).
        let (q1, q2, d1, d2) = two_angles(v(-8.0, 0.0), v(5.0, 0.0), v(5.0, 0.0), 1.0).unwrap();
        assert_direction(d1, q1, 3f64.atan2(4.0));
        assert_direction(d2, q2, (-3f64).atan2(4.0));
    }

    #[test]
    fn two_angles_meet_inside_at_a_tangency() {
        // A chord |r1 − r2| long, turned: the smaller circle touches the larger from inside,
        // so the long link lies along the chord and the short one back along it. The
        // residual guard's sum is far from its difference here.
        for (angle, r1, r2, along) in [
            (0.5, 3.0, 2.0, 1.0),
            (0.5, 2.0, 3.0, -1.0),
            (2.1, 3.7, 2.3, 1.0),
            (-1.3, 2.3, 3.7, -1.0),
        ] {
            let unit = turned(angle, v(1.0, 0.0));
            let k = scaled(unit, -(r1 - r2) * along);
            let (_, _, d1, d2) = two_angles(k, v(r1, 0.0), v(r2, 0.0), 1.0).unwrap();
            for (got, want) in [(d1, scaled(unit, along)), (d2, scaled(unit, -along))] {
                assert!((got - want).norm() < 1e-7, "{got:?} != {want:?}");
            }
        }
    }

    /// Found by mutation testing: just off the inside tangency (the chord a little longer
    /// than `|r1 − r2|`), the solution's residual is rounding of the three lengths, not zero,
    /// and it is held to their sum, not to `span − r1 + r2` (nearly zero there), which would
    /// reject it.
    #[test]
    fn two_angles_meet_inside_near_a_tangency() {
        for (q1, r1, r2, bend) in [
            (0.5, 3.0, 2.0, 1e-3),
            (0.5, 2.0, 3.0, 1e-3),
            (2.1, 3.7, 2.3, -1e-5),
            (-1.3, 2.3, 3.7, 1e-5),
        ] {
            // Link 2 nearly back along link 1, bent by `bend`.
            let (w1, w2) = (v(r1, 0.0), v(r2, 0.0));
            let q2 = q1 + core::f64::consts::PI - bend;
            let k = scaled(turned(q1, w1) + turned(q2, w2), -1.0);
            let sigma = two_angles_sign(k, w1, q1).signum();
            let (_, _, d1, d2) = two_angles(k, w1, w2, sigma).unwrap();
            // The angles are known to ε over the bend, about 1e-11 rad.
            for (got, q) in [(d1, q1), (d2, q2)] {
                let want = turned(q, v(1.0, 0.0));
                assert!((got - want).norm() < 1e-9, "{got:?} != {want:?}");
            }
        }
    }

    /// Found by mutation testing: two equal links over a chord 1e-100 of their length stand
    /// square to it, each reaching half the chord along it. The chord's direction is the
    /// chord over its length; the chord times its length (whose square underflows) leaves
    /// nothing to turn to.
    #[test]
    fn two_angles_over_a_chord_far_shorter_than_the_links() {
        let chord = 1e-100;
        let w = v(1.0, 0.0);
        let (q1, q2, d1, d2) = two_angles(v(-chord, 0.0), w, w, 1.0).unwrap();
        let half = core::f64::consts::FRAC_PI_2;
        assert_direction(d1, q1, half);
        assert_direction(d2, q2, -half);
        for d in [d1, d2] {
            assert!((d.x / (chord / 2.0) - 1.0).abs() < 1e-14, "{d:?}");
        }
    }

    #[test]
    fn two_angles_meet_at_a_tangency_and_fail_beyond_it() {
        // Links of 2 and 3 over a chord of 5: the circles touch, both angles zero.
        let (w1, w2) = (v(2.0, 0.0), v(3.0, 0.0));
        for sign in [1.0, -1.0] {
            let (q1, q2, _, _) = two_angles(v(-5.0, 0.0), w1, w2, sign).unwrap();
            assert_eq!((q1, q2), (0.0, 0.0));
        }
        // A chord one unit of rounding too long still touches; sixteen do not.
        let ulp = 4.0 * f64::EPSILON;
        let (q1, q2, _, _) = two_angles(v(-5.0 - ulp, 0.0), w1, w2, 1.0).unwrap();
        assert_eq!((q1, q2), (0.0, 0.0));
        assert_eq!(
            two_angles(v(-5.0 - 16.0 * ulp, 0.0), w1, w2, 1.0),
            Err(Failure::CannotClose)
        );
        // Too short for the difference of the links: the small circle inside the large one.
        assert_eq!(
            two_angles(v(-0.5, 0.0), w1, w2, 1.0),
            Err(Failure::CannotClose)
        );
        // Links of 2 and 3 about one centre never meet.
        assert_eq!(
            two_angles(v(0.0, 0.0), w1, w2, 1.0),
            Err(Failure::CannotClose)
        );
        for (k, w1, w2) in [
            (v(-5.0, 0.0), v(0.0, 0.0), w2),
            (v(-5.0, 0.0), w1, v(0.0, 0.0)),
        ] {
            assert_eq!(two_angles(k, w1, w2, 1.0), Err(Failure::Degenerate));
        }
    }

    #[test]
    fn gaps_close_within_rounding_of_their_scale_only() {
        let e = f64::EPSILON;
        assert_eq!(gap_closes(0.5, 1.0), Ok(0.5));
        assert_eq!(gap_closes(0.0, 1.0), Ok(0.0));
        assert_eq!(gap_closes(-8.0 * e * 4.0, 4.0), Ok(0.0));
        assert_eq!(gap_closes(-9.0 * e * 4.0, 4.0), Err(Failure::CannotClose));
        assert_eq!(closes(v(16.0 * e, -16.0 * e), 1.0), Ok(()));
        assert_eq!(
            closes(v(16.0 * e, -17.0 * e), 1.0),
            Err(Failure::CannotClose)
        );
        assert_eq!(closes(v(32.0 * e * 3.0, 0.0), 3.0), Ok(()));
        assert_eq!(sum_of([1.0, 2.0, 4.0]), 7.0);
        assert_eq!(sum_of([0.5f32, 0.25]), 0.75);
        assert_eq!(unscaled_length(3.0, 0.5), Ok(6.0));
        assert_eq!(unscaled_length(f64::MAX, 0.5), Err(Failure::NonFinite));
    }

    #[test]
    fn a_side_is_its_sign_unless_the_other_assembly_is_within_the_margin() {
        // Links of 5 spanning the chord (6, 0) meet at (3, ±4): the two assemblies' joints
        // are 8 apart, so a margin below 8 leaves the sign decided.
        let (k, w1) = (v(-6.0, 0.0), v(5.0, 0.0));
        let q1 = 4f64.atan2(3.0);
        let sign = two_angles_sign(k, w1, q1);
        assert!(sign > 0.0);
        assert_eq!(two_angles_side(k, w1, q1, 0.0), sign);
        assert_eq!(two_angles_side(k, w1, q1, 7.9), sign);
        assert_eq!(two_angles_side(k, w1, q1, 8.1), 0.0);
        assert_eq!(two_angles_side(k, w1, -q1, 8.1), 0.0);
        assert!(two_angles_side(k, w1, -q1, 7.9) < 0.0);
        // The same at 1e-300 and 1e300: the margin is a length, at the mechanism's scale.
        for s in [1e-300, 1e300] {
            assert!(two_angles_side(scaled(k, s), scaled(w1, s), q1, 7.9 * s) > 0.0);
            assert_eq!(
                two_angles_side(scaled(k, s), scaled(w1, s), q1, 8.1 * s),
                0.0
            );
        }
        // A longer chord, the same joints: the height over it, not the chord's length or the
        // link's, sets how far apart the assemblies are. Links of 5 and √(16 + 81) spanning
        // (12, 0) meet at (3, ±4): again 8 apart.
        let long = v(-12.0, 0.0);
        assert!(two_angles_side(long, w1, q1, 7.9) > 0.0);
        assert_eq!(two_angles_side(long, w1, q1, 8.1), 0.0);
        // Undecided where there is no sign to decide, or the margin is not a number.
        assert_eq!(two_angles_side(v(0.0, 0.0), w1, q1, 0.0), 0.0);
        assert_eq!(two_angles_side(k, w1, q1, f64::NAN), 0.0);
        assert_eq!(two_angles_side(k, w1, q1, f64::INFINITY), 0.0);
        // The dot-product signs, likewise: the slide point 3 along from the circle's centre,
        // its other root 3 behind it: 6 apart.
        assert!(length_and_other_angle_side(v(0.0, 0.0), v(1.0, 0.0), 3.0, 5.9) > 0.0);
        assert_eq!(
            length_and_other_angle_side(v(0.0, 0.0), v(1.0, 0.0), 3.0, 6.1),
            0.0
        );
        assert!(length_and_own_angle_side(v(0.0, 0.0), v(1.0, 0.0), -3.0, 5.9) < 0.0);
        assert_eq!(
            length_and_own_angle_side(v(0.0, 0.0), v(1.0, 0.0), -3.0, 6.1),
            0.0
        );
        // A direction of any length: the roots' distance, not the product's size.
        assert!(length_and_other_angle_side(v(0.0, 0.0), v(8.0, 0.0), 0.375, 5.9) > 0.0);
        assert_eq!(
            length_and_other_angle_side(v(0.0, 0.0), v(8.0, 0.0), 0.375, 6.1),
            0.0
        );
    }

    /// Found by mutation testing: where one length is zero, the loop's residual (rounding of
    /// the other) is still held to the magnitudes of all three vectors; a tolerance from
    /// `|k| + |l1| − |l2|`, zero there, rejects it.
    #[test]
    fn two_lengths_close_where_one_of_them_is_zero() {
        for turn in [0.1, 0.137, 0.248] {
            let (v1, v2) = (turned(turn, v(1.0, 0.0)), turned(turn, v(0.3, 0.8)));
            for lengths in [[0.0, 0.7], [1.3, 0.0]] {
                let k = scaled(scaled(v1, lengths[0]) + scaled(v2, lengths[1]), -1.0);
                let solved = two_lengths(k, v1, v2).unwrap();
                for (l, want) in solved.iter().zip(lengths) {
                    assert!((l - want).abs() < 1e-14, "{solved:?} != {lengths:?}");
                }
            }
        }
    }

    /// Found by mutation testing: a side is undecided within its own rounding (4ε of the
    /// two vectors' lengths at unit scale), even with no margin; and a slide's side is that
    /// of the point it reaches, its offset included.
    #[test]
    fn a_side_within_its_own_rounding_is_undecided() {
        let e = f64::EPSILON;
        // (0.5, 0) × (0.5, δ) = δ/2, twice it against 8ε·0.5·0.5 = 2ε: exactly at it for
        // δ = 2ε, beyond it for δ = 4ε.
        assert_eq!(side(v(0.5, 0.0), v(0.5, 2.0 * e), 0.0, cross), 0.0);
        assert_eq!(side(v(0.5, 0.0), v(0.5, 4.0 * e), 0.0, cross), 2.0 * e);
        assert_eq!(side(v(0.5, 0.0), v(0.5, -4.0 * e), 0.0, cross), -2.0 * e);
        // A slide 3 along (1, 0) from an offset 5 back reaches (−2, 0), behind its direction.
        assert!(length_and_own_angle_side(v(-5.0, 0.0), v(1.0, 0.0), 3.0, 0.0) < 0.0);
        assert!(length_and_own_angle_side(v(-1.0, 0.0), v(1.0, 0.0), 3.0, 0.0) > 0.0);
    }
}
