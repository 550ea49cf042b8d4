//! How accurate a result is: an estimate of its error for each derivative order, from the
//! Jacobian's condition at the position, and the accuracy a result must have to be returned.
//!
//! With ε the machine epsilon and κ the Jacobian's condition estimate (`Π‖column‖ / |det|`,
//! at least 1), the estimated relative errors are
//!
//! | order | estimate | relative to |
//! |---|---|---|
//! | position | `32·ε·κ` | the mechanism's size |
//! | velocity | `ε·(64·κ + 12·κ²)·s` | the rates' size |
//! | acceleration | `ε·(256·κ + κ³)·s²` | the accelerations' size |
//!
//! each unknown weighted by its Jacobian column. A position's error is the input's and the
//! loops' rounding amplified by κ; a rate solve multiplies it by κ once more through the
//! Jacobian it is solved with, and the acceleration's right-hand side carries the rates'
//! error, so once more again. The terms linear in κ are the rounding of the right-hand sides
//! themselves (sums of many products), which dominate away from singular positions. The
//! rates' factors are fitted, with a margin of two or more, to the worst errors against the
//! 60-digit references (`docs/ACCURACY.md`) and the multiple-precision oracle of the edge
//! tests, which check every returned `Motion` against the accuracy it states: the
//! velocity's `κ²` factor was 4 until those checks found a closed form's velocity 1e-6 rad
//! inside a four-bar's limit 1.4 times that (one case in 200,000), and is 12 since. The
//! position's is derived: Newton accepts a residual up to `16·ε` of the loops'
//! magnitudes, and the inverse of the column-scaled Jacobian has entries up to κ, so the
//! errors of two unknowns can add (an edge run found positions up to 1.3 times `16·ε·κ`
//! off; none in the run of `docs/EDGES.md` exceeds `32·ε·κ`). That derivation holds a
//! Newton position to the largest loop's magnitudes at the position (a slide's extension
//! counted, which can exceed the declared lengths): relative to the size, its estimate is
//! stretched by their ratio where that exceeds 1, and so is the error the rates carry from it
//! (edge run seed 15, case 914340: a slider-crank's rates, read against the declared lengths
//! alone, were 1.2 times further off than stated). Near a change point the κ³ of the
//! acceleration is reached; near a toggle the true error grows only as κ², so there the
//! estimate is pessimistic by up to κ.
//!
//! Here `s = max(1, ρ/16)`, with ρ the aspect: the sum of the lengths the mechanism's loops
//! declare over the shortest column of an angle unknown. An angle whose vector shrinks (a slide
//! passing near its pivot) is less determined than κ says, since κ does not see a column's
//! scale; ordinary mechanisms have ρ below 16, where `s` is 1.
//!
//! An angle unknown whose vector has shrunk to less than `√ε` of the mechanism's size (the
//! sum of its declared lengths) has an undetermined direction whatever κ says (κ does not
//! see a column's scale): its rates' estimates are infinite.
//!
//! Rates or accelerations below the float's normal range (a rod of 1e300 turning at 1e-200
//! rad/s has an angular acceleration of about 1e-400 rad/s², which no f64 holds) are known
//! only to the spacing of its subnormal numbers: the estimates of results computed where
//! that can happen (the mechanism or its rates far from 1) add that floor, against the
//! sizes above, so such a result is `Inaccurate` rather than a 0 stated to 14 digits.

use crate::real::normaliser;
use crate::{Error, Real};

/// The aspect up to which a mechanism's rates are as accurate as its condition says: the
/// shipped linkages, the Jansen leg included, stay below it over their whole motion.
const ORDINARY_ASPECT: f64 = 16.0;

/// A derivative order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Order {
    /// The unknowns' values.
    Position,
    /// Their rates.
    Velocity,
    /// Their accelerations.
    Acceleration,
}

/// Relative errors, one per derivative order: an estimate of a result's, or the most a
/// result may have.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Accuracy<T> {
    /// Relative to the mechanism's size.
    pub position: T,
    /// Relative to the rates' size.
    pub velocity: T,
    /// Relative to the accelerations' size.
    pub acceleration: T,
}

impl<T: Real> Accuracy<T> {
    /// The accuracy every result the solvers return must have: half the digits of `T` for a
    /// position (`√ε`), a third for a velocity (`ε^(1/3)`) and a quarter for an acceleration
    /// (`ε^(1/4)`): about 8, 5 and 4 digits in f64, 3.5, 2.3 and 1.7 in f32. Each derivative
    /// multiplies the error by the condition once more, so a fixed share of the digits per
    /// order keeps the three usable over about the same range of positions. A result whose
    /// estimate exceeds it is [`Error::Inaccurate`].
    ///
    /// ```
    /// let required = mechgen::Accuracy::<f64>::required();
    /// assert!((required.velocity - 6.06e-6).abs() < 1e-8);
    /// assert!((required.acceleration - 1.22e-4).abs() < 1e-6);
    /// ```
    pub fn required() -> Self {
        let half = T::epsilon().sqrt();
        Accuracy {
            position: half,
            velocity: T::EPSILON_CUBE_ROOT,
            acceleration: half.sqrt(),
        }
    }

    /// The estimate at a position whose Jacobian has condition `condition` (taken as at
    /// least 1) and aspect `aspect`, the mechanism's size over the shortest column of an
    /// angle unknown.
    ///
    /// ```
    /// let estimate = mechgen::Accuracy::<f64>::estimate(10.0, 2.0);
    /// assert_eq!(estimate.position, 32.0 * f64::EPSILON * 10.0);
    /// assert_eq!(estimate.acceleration, f64::EPSILON * 10.0 * (256.0 + 100.0));
    /// // A vector shrunk below √ε of the size: its angle's rates are undetermined.
    /// assert!(mechgen::Accuracy::<f64>::estimate(1.0, 1e9).velocity.is_infinite());
    /// ```
    #[inline]
    pub fn estimate(condition: T, aspect: T) -> Self {
        Self::estimate_known(condition, &KnownAspect::new(aspect))
    }

    /// [`Accuracy::estimate`] with what it reads of the aspect computed already.
    #[inline(always)]
    fn estimate_known(condition: T, aspect: &KnownAspect<T>) -> Self {
        let kappa = condition.max(T::one());
        let e = T::epsilon();
        let position = T::constant(32.0) * e * kappa;
        if aspect.lost {
            return Accuracy {
                position,
                velocity: T::infinity(),
                acceleration: T::infinity(),
            };
        }
        let c = T::constant;
        let shrunk = aspect.shrunk;
        Accuracy {
            position,
            velocity: e * kappa * (c(64.0) + c(12.0) * kappa) * shrunk,
            acceleration: e * kappa * (c(256.0) + kappa * kappa) * shrunk * shrunk,
        }
    }

    /// The estimate for rates solved at a position known only to within `position` (its
    /// estimated error, relative to the size as [`Accuracy::estimate`]'s position), rather
    /// than one a closed form computed, which [`Accuracy::estimate`] is for: a Newton
    /// position, which stops at a residual up to its floor (or its tolerance), or a position
    /// the caller gives. The position is then the larger of `position` and the closed form's
    /// `32·ε·κ`, and the rates carry what its error does to the Jacobian they are solved
    /// with. With the unknowns off by `Δq` (each weighted by its column at most `δ` of the
    /// size `S`), the Jacobian is off by the loops' second derivatives, `ΔJ·q̇ = f''[Δq, q̇]`,
    /// and the weighted rates by κ times that over the rates' size `V`:
    ///
    /// - an angle unknown's own term, `∂²f/∂θ² = i·∂f/∂θ` (a turn of its column), has its
    ///   column's length `c`, so `c·|Δθ|·|θ̇| ≤ δ·S·V/c ≤ ρ·δ·V`, with ρ (the aspect, at
    ///   least 1) the size over the shortest angle's column;
    /// - a length unknown `b` along an angle unknown's direction adds `|Δb|·|θ̇| + |ḃ|·|Δθ|`,
    ///   up to `2·ρ·δ·V`; one along a fixed direction, nothing;
    ///
    /// and these add up: `moving` is their count, the unknowns' columns the position's error
    /// moves (the four-bar's two angles, 2; the slider-crank's coupler angle and its slide
    /// along a fixed line, 1; the inverted slider-crank's angle and its slide along it, 3;
    /// generated code counts them from the loops). The accelerations' right-hand side carries
    /// the velocities' error twice (a squared rate's error is twice the rate's), so twice
    /// once more by κ:
    ///
    /// - velocity: the closed form's, plus `m·κ·ρ·δ`;
    /// - acceleration: the closed form's, plus `2·κ·m·κ·ρ·δ`.
    ///
    /// At a Newton position on its floor (`δ = 32·ε·κ`) these are `32·m·ε·κ²·ρ` and
    /// `64·m·ε·κ³·ρ`, against the bounds the edge tests hold Newton's rates to against the
    /// multiple-precision oracle (`16·ε·κ²·ρ` and `16·ε·κ³·ρ²`). Until positions a stated
    /// tolerance left short of the floor were drawn too, these were `κ·ρ·δ/2` and `κ²·ρ·δ/2`,
    /// which such positions exceeded: an inverted slider-crank at κ 1 and ρ 1 whose slide's
    /// velocity was off by its turn, 0.55 of `δ` (1.1 times `κ·ρ·δ/2`), and a slider-crank at
    /// κ 1.9 and ρ 2.2 whose coupler, turning 1.5 times as fast as the crank, had its
    /// acceleration 2.1 times `κ²·ρ·δ/2` off; and until an adversarial review drew guesses
    /// farther off, `κ·ρ·δ` and `2·κ²·ρ·δ` for every mechanism (`m` = 1), which a four-bar
    /// stopped by a tolerance short of its floor exceeded, its two angles' errors adding:
    /// its velocity 1.25 times, its acceleration 1.07 times.
    ///
    /// ```
    /// use mechgen::Accuracy;
    /// let closed = Accuracy::<f64>::estimate(10.0, 2.0);
    /// let near = Accuracy::<f64>::estimate_at(10.0, 2.0, 0.0, 2.0);
    /// assert_eq!(near.position, closed.position);
    /// assert_eq!(near.velocity, closed.velocity + 2.0 * 10.0 * 2.0 * closed.position);
    /// // A position known to 1e-9 only (a loose tolerance): rates far less accurate.
    /// assert!(Accuracy::<f64>::estimate_at(10.0, 2.0, 1e-9, 2.0).velocity > 1e-8);
    /// ```
    #[inline]
    pub fn estimate_at(condition: T, aspect: T, position: T, moving: T) -> Self {
        Self::estimate_at_known(condition, &KnownAspect::new(aspect), position, moving)
    }

    /// [`Accuracy::estimate_at`] with what it reads of the aspect computed already.
    #[inline(always)]
    fn estimate_at_known(condition: T, aspect: &KnownAspect<T>, position: T, moving: T) -> Self {
        let closed = Self::estimate_known(condition, aspect);
        let kappa = condition.max(T::one());
        // The larger, and NaN (an unknown error) where `position` is.
        let delta = if position <= closed.position {
            closed.position
        } else {
            position
        };
        // m·κ·ρ·δ, which the acceleration's term takes twice, once more by κ.
        let carried = moving * kappa * aspect.at_least_one * delta;
        Accuracy {
            position: delta,
            velocity: closed.velocity + carried,
            acceleration: closed.acceleration + T::constant(2.0) * kappa * carried,
        }
    }

    /// `Ok` if every order up to `highest` is within `required`, else the first that is not,
    /// as [`Error::Inaccurate`]. A NaN estimate (an undefined condition) is not within.
    pub fn within(&self, required: &Self, highest: Order) -> Result<(), Error<T>> {
        let orders = [
            (Order::Position, self.position, required.position),
            (Order::Velocity, self.velocity, required.velocity),
            (
                Order::Acceleration,
                self.acceleration,
                required.acceleration,
            ),
        ];
        for (order, estimate, required) in orders {
            if order > highest {
                break;
            }
            let within = matches!(
                estimate.partial_cmp(&required),
                Some(core::cmp::Ordering::Less | core::cmp::Ordering::Equal)
            );
            if !within {
                return Err(Error::Inaccurate {
                    order,
                    estimate,
                    required,
                });
            }
        }
        Ok(())
    }
}

/// The error of a position that Newton's default solve returns, relative to `size` (the sum
/// of the lengths the loops declare), for rates at a position the caller gives: `32·ε·κ`
/// of the largest loop's magnitudes `largest_loop` at that position (the floor each loop
/// closes to), which can exceed `size` where a slide's extension counts.
///
/// ```
/// let e = f64::EPSILON;
/// assert_eq!(mechgen::__private::floor_position_accuracy(3.0, 8.0, 4.0), 32.0 * e * 3.0 * 2.0);
/// assert_eq!(mechgen::__private::floor_position_accuracy(3.0, 2.0, 4.0), 32.0 * e * 3.0);
/// ```
#[inline]
pub fn floor_position_accuracy<T: Real>(condition: T, largest_loop: T, size: T) -> T {
    let error = T::constant(32.0) * T::epsilon() * condition.max(T::one());
    let stretch = largest_loop / size;
    // Not above 1 (false for NaN).
    if stretch > T::one() {
        error * stretch
    } else {
        error
    }
}

/// How far off a position the caller gives may be, relative to `size` (the sum of the lengths
/// the loops declare), from the loops' `residual` there. Where they close within `64·ε·size`
/// (what a closed form or Newton's floor leaves, with room), `otherwise`: the position is
/// judged as the caller's function says (`None` as a closed form's, `Some` as Newton's).
/// Beyond, the step Newton would take from it, `J·Δq = r` with the loops' `jacobian` there,
/// twice over (`Δq` is the error to first order), each unknown's part weighted by the sum of
/// its column's magnitudes over the size, as [`Accuracy::estimate_at`] reads a position's
/// error (or `otherwise`'s, if larger; `κ·max|r|/size` where the Jacobian does not factor).
/// A position the loops do not close at (another input's, or one made up) is so known to be
/// far off, and rates or sensitivities there are [`Error::Inaccurate`], not numbers for a
/// mechanism that is not there (an adversarial review found them returned); a Newton position
/// stopped by a loose tolerance has its rates judged as they are; and an angle many turns
/// out, whose float holds it only to its spacing, is off by that spacing, not by the worst
/// its residual could mean near a toggle (`κ·|r|` refused one 1000 turns out there).
///
/// ```
/// use mechgen::__private::given_position;
/// let identity = [[1.0, 0.0], [0.0, 1.0]];
/// // Closed within rounding: as the caller says.
/// assert_eq!(given_position(10.0, &identity, &[1e-14, 0.0], 600.0, None), None);
/// let given = given_position(10.0, &identity, &[1e-14, 0.0], 600.0, Some(1e-13));
/// assert_eq!(given, Some(1e-13));
/// // Open by half a unit on a linkage of 4 whose unknowns' columns are unit vectors: the step
/// // is half a unit, an eighth of the size, twice over; or the larger given.
/// assert_eq!(given_position(1.0, &identity, &[0.5, 0.0], 4.0, None), Some(0.25));
/// assert_eq!(given_position(1.0, &identity, &[0.5, 0.0], 4.0, Some(0.5)), Some(0.5));
/// // Columns of length 100 whose residual moves one unknown by 0.01: 1/4 of a size of 8.
/// let long = [[100.0, 0.0], [0.0, 100.0]];
/// assert_eq!(given_position(1.0, &long, &[1.0, 0.0], 8.0, None), Some(0.25));
/// // A Jacobian that does not factor: the condition's bound, κ·max|r|/size.
/// let flat = [[1.0, 1.0], [1.0, 1.0]];
/// assert_eq!(given_position(3.0, &flat, &[0.5, 0.0], 4.0, None), Some(0.375));
/// assert!(given_position(2.0, &identity, &[f64::NAN, 0.0], 612.0, None).unwrap().is_nan());
/// ```
#[inline(always)]
pub fn given_position<T: Real, const N: usize>(
    condition: T,
    jacobian: &[[T; N]; N],
    residual: &[T; N],
    size: T,
    otherwise: Option<T>,
) -> Option<T> {
    let bound = T::constant(64.0) * T::epsilon() * size;
    // Within (false for NaN).
    if residual.iter().all(|r| r.abs() <= bound) {
        return otherwise;
    }
    let error = position_error(condition, *jacobian, *residual, size);
    Some(otherwise.map_or(error, |given| given.max(error)))
}

/// [`given_position`]'s error for a position the loops do not close at: rare, so out of line.
#[cold]
#[inline(never)]
fn position_error<T: Real, const N: usize>(
    condition: T,
    jacobian: [[T; N]; N],
    residual: [T; N],
    size: T,
) -> T {
    if residual.iter().any(|r| r.is_nan()) {
        return T::nan();
    }
    if let Ok((step, _)) = crate::linear::solve_lu(jacobian, residual)
        && step.iter().all(|s| s.is_finite())
    {
        // Each column's magnitudes summed, without indexing (no bounds check to panic).
        let mut columns = [T::zero(); N];
        for row in &jacobian {
            for (column, entry) in columns.iter_mut().zip(row) {
                *column = *column + entry.abs();
            }
        }
        let largest = step
            .iter()
            .zip(&columns)
            .fold(T::zero(), |m, (part, column)| m.max(part.abs() * *column));
        return T::constant(2.0) * largest / size;
    }
    let largest = residual.iter().fold(T::zero(), |m, r| m.max(r.abs()));
    condition.max(T::one()) * largest / size
}

/// The estimate for rates solved with `jacobian` (whose condition estimate is `condition`)
/// at a position of a mechanism whose declared lengths sum to `size`, `angles[j]` telling
/// whether unknown `j` is an angle; an error if the velocity's or (with `highest` the
/// acceleration) the acceleration's exceeds `required`. `position` says where the position
/// came from: `None`, a closed form ([`Accuracy::estimate`]); `Some(δ)`, a position known to
/// within `δ` or the closed form's `32·ε·κ`, whichever is larger ([`Accuracy::estimate_at`],
/// with `moving` the count of columns its error moves): Newton's (from its residual), or a
/// position the caller gives (`Some(0)`: any position within the contract).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn rates_accuracy<T: Real, const N: usize>(
    condition: T,
    jacobian: &[[T; N]; N],
    size: T,
    angles: [bool; N],
    position: Option<T>,
    moving: T,
    highest: Order,
    required: &Accuracy<T>,
) -> Result<Accuracy<T>, Error<T>> {
    let within = |estimate: &Accuracy<T>| {
        estimate.velocity <= required.velocity
            && (highest < Order::Acceleration || estimate.acceleration <= required.acceleration)
    };
    // An ordinary aspect: the common case, without the aspect's scaling. A closed form's
    // estimate is then that of an aspect of 1, without a square root and division either.
    if let Some(aspect) = ordinary(jacobian, size, angles, position.is_some()) {
        let estimate = match position {
            None => Accuracy::estimate(condition, T::one()),
            Some(position) => Accuracy::estimate_at(condition, aspect, position, moving),
        };
        if within(&estimate) {
            return Ok(estimate);
        }
    }
    rates_accuracy_aside(
        condition, *jacobian, size, angles, position, moving, highest, required,
    )
}

/// An aspect the dimensions fix (see [`rates_accuracy_at_aspect`]), with what the estimates
/// read of it computed once: a prepared solve (`{Name}::newton()`) keeps it for every call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KnownAspect<T> {
    /// A number from 1 up and finite (false for NaN): the estimates read it; else the
    /// Jacobian decides.
    usable: bool,
    /// `aspect·√ε ≥ 1`, or NaN: the rates are undetermined.
    lost: bool,
    /// `max(aspect / ORDINARY_ASPECT, 1)`: by how much a shrunk vector amplifies the rates'
    /// errors (the accelerations' by its square) once it exceeds what ordinary mechanisms
    /// have.
    shrunk: T,
    /// `max(aspect, 1)` (1 for NaN): ρ in [`Accuracy::estimate_at`]'s terms.
    at_least_one: T,
}

impl<T: Real> KnownAspect<T> {
    /// The terms of `aspect`.
    #[inline(always)]
    pub fn new(aspect: T) -> Self {
        KnownAspect {
            usable: aspect >= T::one() && aspect < T::infinity(),
            lost: aspect * T::epsilon().sqrt() >= T::one() || aspect.is_nan(),
            shrunk: (aspect / T::constant(ORDINARY_ASPECT)).max(T::one()),
            at_least_one: aspect.max(T::one()),
        }
    }
}

impl<T: Real> From<T> for KnownAspect<T> {
    #[inline(always)]
    fn from(aspect: T) -> Self {
        KnownAspect::new(aspect)
    }
}

/// [`rates_accuracy`] for a mechanism whose angle unknowns' columns have lengths the dimensions
/// fix (each angle turns one vector of fixed length in each loop it is in), so that its aspect
/// is known without the Jacobian: `aspect`, from the squared lengths (or its terms, computed
/// once). Where those squares overflowed or underflowed (lengths beyond about 1e±154 in
/// `f64`), so that `aspect` is not a number from 1 up, [`rates_accuracy`] decides from the
/// Jacobian, out of line.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn rates_accuracy_at_aspect<T: Real, const N: usize>(
    condition: T,
    aspect: impl Into<KnownAspect<T>>,
    jacobian: &[[T; N]; N],
    size: T,
    angles: [bool; N],
    position: Option<T>,
    moving: T,
    highest: Order,
    required: &Accuracy<T>,
) -> Result<Accuracy<T>, Error<T>> {
    let aspect = aspect.into();
    if aspect.usable {
        let estimate = match position {
            None => Accuracy::estimate_known(condition, &aspect),
            Some(position) => Accuracy::estimate_at_known(condition, &aspect, position, moving),
        };
        if estimate.velocity <= required.velocity
            && (highest < Order::Acceleration || estimate.acceleration <= required.acceleration)
        {
            return Ok(estimate);
        }
    }
    rates_accuracy_aside(
        condition, *jacobian, size, angles, position, moving, highest, required,
    )
}

/// [`rates_accuracy`] in full, out of line, from a copy of the Jacobian (so that the caller
/// need not keep it in memory for this rare path).
#[cold]
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn rates_accuracy_aside<T: Real, const N: usize>(
    condition: T,
    jacobian: [[T; N]; N],
    size: T,
    angles: [bool; N],
    position: Option<T>,
    moving: T,
    highest: Order,
    required: &Accuracy<T>,
) -> Result<Accuracy<T>, Error<T>> {
    let aspect = aspect(&jacobian, size, angles);
    let estimate = match position {
        None => Accuracy::estimate(condition, aspect),
        Some(position) => Accuracy::estimate_at(condition, aspect, position, moving),
    };
    estimate.within(&rates_only(required), highest)?;
    Ok(estimate)
}

/// `Some(aspect)` where [`aspect`] is certainly at most [`ORDINARY_ASPECT`], where
/// [`Accuracy::estimate`] is that of an aspect of 1 (`shrunk` is 1): every angle's column at
/// least `size/15.9` long, tested on squares without scaling where the size's square is
/// normal (else `None`, and [`aspect`] decides). Then a column's square that overflows is
/// long enough, and one that is NaN or too small fails; a subnormal one passes only when at
/// least `size²/252.81`, where it keeps over 40 bits, more than the margin of 15.9 against 16
/// needs. With no angle unknown the aspect is 1. The aspect itself (`size` over the shortest
/// angle's column, from the same squares) only `with_aspect`, else 1: a closed form's
/// estimate does not read it below the ordinary aspect.
#[inline(always)]
fn ordinary<T: Real, const N: usize>(
    jacobian: &[[T; N]; N],
    size: T,
    angles: [bool; N],
    with_aspect: bool,
) -> Option<T> {
    let size_squared = size * size;
    // Normal and finite (false for NaN).
    let normal = size_squared >= T::min_positive_value() && size_squared <= T::max_value();
    if !normal {
        return None;
    }
    // The first row's squares to start with, not zeros: the same sums as a factorisation's
    // column norms, which the compiler can then share.
    let Some((first, rest)) = jacobian.split_first() else {
        return Some(T::one());
    };
    let mut squares = first.map(|v| v * v);
    for row in rest {
        for (square, v) in squares.iter_mut().zip(row) {
            *square = *square + *v * *v;
        }
    }
    // 15.9² = 252.81: a margin over the rounding of `aspect`'s arithmetic.
    let bound = T::constant(252.81);
    let ordinary = squares
        .iter()
        .zip(angles)
        .all(|(square, angle)| !angle || size_squared <= bound * *square);
    if !ordinary {
        return None;
    }
    if !with_aspect {
        return Some(T::one());
    }
    // Every angle's square is normal here (at least size²/252.81), so is its root.
    let shortest = squares
        .iter()
        .zip(angles)
        .filter(|(_, angle)| *angle)
        .fold(T::infinity(), |m, (square, _)| m.min(*square));
    Some(if shortest.is_infinite() {
        T::one()
    } else {
        size / shortest.sqrt()
    })
}

/// `ρ`: `size` over the shortest column of an angle unknown (1 without one), with `size` and
/// the columns (lengths alike) brought to about 1 by one power of two, so no square
/// overflows; a column too short to square at that scale counts as zero (ρ infinite).
fn aspect<T: Real, const N: usize>(jacobian: &[[T; N]; N], size: T, angles: [bool; N]) -> T {
    let size = size.abs();
    if size == T::zero() || !size.is_finite() {
        return T::one();
    }
    let scale = normaliser(size);
    let mut squares = [T::zero(); N];
    for row in jacobian {
        for (square, v) in squares.iter_mut().zip(row) {
            let v = *v * scale;
            *square = *square + v * v;
        }
    }
    let shortest = squares
        .iter()
        .zip(angles)
        .filter(|(_, angle)| *angle)
        .fold(T::infinity(), |m, (square, _)| m.min(*square));
    if shortest.is_infinite() {
        T::one()
    } else {
        size * scale / shortest.sqrt()
    }
}

/// `required` of the rates alone: the position they are solved at was returned already, and
/// its own estimate is the caller's to judge.
fn rates_only<T: Real>(required: &Accuracy<T>) -> Accuracy<T> {
    Accuracy {
        position: T::infinity(),
        ..*required
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const E: f64 = f64::EPSILON;

    #[test]
    fn estimates_grow_with_the_condition_and_the_aspect() {
        let at_10 = Accuracy::estimate(10.0, 1.0);
        assert_eq!(at_10.position, 32.0 * E * 10.0);
        assert_eq!(at_10.velocity, E * 10.0 * (64.0 + 120.0));
        assert_eq!(at_10.acceleration, E * 10.0 * (256.0 + 100.0));
        // An aspect of 32, twice the ordinary: the velocity's twice, the acceleration's four
        // times; 16 and below, no change.
        let shrunk = Accuracy::estimate(10.0, 32.0);
        assert_eq!(shrunk.position, at_10.position);
        assert_eq!(shrunk.velocity, 2.0 * at_10.velocity);
        assert_eq!(shrunk.acceleration, 4.0 * at_10.acceleration);
        assert_eq!(Accuracy::estimate(10.0, 16.0), at_10);
        // A condition below 1 is 1.
        assert_eq!(Accuracy::estimate(0.5, 1.0), Accuracy::estimate(1.0, 1.0));
        // A vector shrunk to √ε of the size, or an undefined aspect: rates undetermined.
        for aspect in [1.0 / E.sqrt(), f64::NAN] {
            let lost = Accuracy::estimate(10.0, aspect);
            assert_eq!(lost.position, at_10.position);
            assert!(lost.velocity.is_infinite() && lost.acceleration.is_infinite());
        }
        assert!(
            Accuracy::estimate(10.0, 0.5 / E.sqrt())
                .velocity
                .is_finite()
        );
    }

    #[test]
    fn required_accuracy_is_a_share_of_the_digits_per_order() {
        let required = Accuracy::<f64>::required();
        assert_eq!(required.position, E.sqrt());
        assert!((required.velocity - E.cbrt()).abs() <= 2.0 * E * E.cbrt());
        assert_eq!(required.acceleration, E.sqrt().sqrt());
    }

    #[test]
    fn within_checks_each_order_up_to_the_highest_inclusively() {
        let required = Accuracy {
            position: 1.0,
            velocity: 2.0,
            acceleration: 3.0,
        };
        assert_eq!(required.within(&required, Order::Acceleration), Ok(()));
        for (order, estimate) in [
            (
                Order::Position,
                Accuracy {
                    position: 1.5,
                    ..required
                },
            ),
            (
                Order::Velocity,
                Accuracy {
                    velocity: 2.5,
                    ..required
                },
            ),
            (
                Order::Acceleration,
                Accuracy {
                    acceleration: f64::NAN,
                    ..required
                },
            ),
        ] {
            let error = estimate.within(&required, Order::Acceleration).unwrap_err();
            match error {
                Error::Inaccurate {
                    order: got,
                    estimate: _,
                    required: limit,
                } => {
                    assert_eq!(got, order);
                    assert_eq!(limit, [1.0, 2.0, 3.0][order as usize]);
                }
                other => panic!("{other:?}"),
            }
        }
        // Orders above the highest are not looked at.
        let fast = Accuracy {
            velocity: 2.5,
            acceleration: 9.0,
            ..required
        };
        assert_eq!(fast.within(&required, Order::Position), Ok(()));
        let fast = Accuracy {
            acceleration: 9.0,
            ..required
        };
        assert_eq!(fast.within(&required, Order::Velocity), Ok(()));
    }

    #[test]
    fn the_aspect_is_the_size_over_the_shortest_angle_column() {
        // Columns (3, 4) and (0, 1): 5 and 1 long.
        let jacobian = [[3.0, 0.0], [4.0, 1.0]];
        assert_eq!(aspect(&jacobian, 10.0, [true, true]), 10.0);
        assert_eq!(aspect(&jacobian, 10.0, [true, false]), 2.0);
        assert_eq!(aspect(&jacobian, 10.0, [false, false]), 1.0);
        assert_eq!(aspect(&jacobian, -10.0, [true, false]), 2.0);
        assert_eq!(aspect(&jacobian, 0.0, [true, true]), 1.0);
        assert_eq!(aspect(&jacobian, f64::INFINITY, [true, true]), 1.0);
        // At any scale.
        let big = jacobian.map(|row| row.map(|v| v * 1e300));
        assert!((aspect(&big, 1e301, [true, false]) - 2.0).abs() < 1e-15);
        // Ordinary: every angle's column at least size/15.9.
        assert!(ordinary(&jacobian, 10.0, [true, true], false).is_some());
        assert!(ordinary(&jacobian, 15.9, [true, true], false).is_some());
        assert!(ordinary(&jacobian, 16.0, [true, true], false).is_none());
        assert!(ordinary(&jacobian, 16.0, [true, false], false).is_some());
        // The first column, 5 long, up to a size of 15.9·5.
        assert!(ordinary(&jacobian, 79.0, [true, false], false).is_some());
        assert!(ordinary(&jacobian, 80.0, [true, false], false).is_none());
        assert!(ordinary(&jacobian, 1e3, [false, false], false).is_some());
        assert!(ordinary(&jacobian, 1e300, [false, false], false).is_none());
        assert!(ordinary(&jacobian, f64::NAN, [false, false], false).is_none());
        assert!(ordinary(&jacobian, 1e-300, [false, false], false).is_none());
        let three = [[3.0, 0.0, 0.0], [4.0, 1.0, 0.0], [0.0, 0.0, 0.5]];
        assert!(ordinary(&three, 10.0, [false, false, true], false).is_none());
        assert!(ordinary(&three, 7.9, [false, false, true], false).is_some());
    }

    #[test]
    fn rates_are_estimated_and_checked_on_either_path() {
        let jacobian = [[3.0, 0.0], [4.0, 1.0]];
        let required = Accuracy::<f64>::required();
        // Ordinary: the estimate of an aspect of 1.
        assert_eq!(
            rates_accuracy(
                10.0,
                &jacobian,
                10.0,
                [true, true],
                None,
                1.0,
                Order::Acceleration,
                &required
            ),
            Ok(Accuracy::estimate(10.0, 1.0))
        );
        // An aspect of 64: shrunk by 4.
        assert_eq!(
            rates_accuracy(
                10.0,
                &jacobian,
                64.0,
                [true, true],
                None,
                1.0,
                Order::Acceleration,
                &required
            ),
            Ok(Accuracy::estimate(10.0, 64.0))
        );
        // Too near a singular position for an acceleration, not for a velocity.
        let kappa = 1e4;
        let estimate = Accuracy::estimate(kappa, 1.0);
        assert!(
            estimate.velocity < required.velocity && estimate.acceleration > required.acceleration
        );
        assert_eq!(
            rates_accuracy(
                kappa,
                &jacobian,
                10.0,
                [true, true],
                None,
                1.0,
                Order::Velocity,
                &required
            ),
            Ok(estimate)
        );
        assert_eq!(
            rates_accuracy(
                kappa,
                &jacobian,
                10.0,
                [true, true],
                None,
                1.0,
                Order::Acceleration,
                &required
            ),
            Err(Error::Inaccurate {
                order: Order::Acceleration,
                estimate: estimate.acceleration,
                required: required.acceleration
            })
        );
        // Too near for a velocity as well.
        let nearer = Accuracy::estimate(1e7, 1.0);
        assert_eq!(
            rates_accuracy(
                1e7,
                &jacobian,
                10.0,
                [true, true],
                None,
                1.0,
                Order::Velocity,
                &required
            ),
            Err(Error::Inaccurate {
                order: Order::Velocity,
                estimate: nearer.velocity,
                required: required.velocity
            })
        );
        // The position is not judged here, however far off.
        let strict = Accuracy {
            position: 0.0,
            ..required
        };
        assert_eq!(
            rates_accuracy(
                10.0,
                &jacobian,
                64.0,
                [true, true],
                None,
                1.0,
                Order::Acceleration,
                &strict
            ),
            Ok(Accuracy::estimate(10.0, 64.0))
        );
    }

    #[test]
    fn rates_at_a_position_not_a_closed_form_carry_its_error() {
        let e = f64::EPSILON;
        // At a Newton position on its floor (32·ε·κ): 32·ε·κ²·ρ and 64·ε·κ³·ρ more, each
        // times the columns the position's error moves (here two angles').
        let (kappa, aspect, moving) = (100.0, 4.0, 2.0);
        let closed = Accuracy::<f64>::estimate(kappa, aspect);
        let floor = Accuracy::<f64>::estimate_at(kappa, aspect, 0.0, moving);
        assert_eq!(floor.position, closed.position);
        assert_eq!(
            floor.velocity,
            closed.velocity + moving * kappa * aspect * (32.0 * e * kappa)
        );
        assert_eq!(
            floor.acceleration,
            closed.acceleration + 2.0 * kappa * (moving * kappa * aspect * (32.0 * e * kappa))
        );
        assert!(
            (floor.velocity - closed.velocity) / (moving * 32.0 * e * kappa * kappa * aspect) - 1.0
                < 1e-12
        );
        // A position off by more than the floor (a loose tolerance) is that far off, and so
        // are its rates, in proportion.
        let loose = Accuracy::<f64>::estimate_at(kappa, aspect, 1e-6, moving);
        assert_eq!(loose.position, 1e-6);
        assert_eq!(
            loose.velocity,
            closed.velocity + moving * kappa * aspect * 1e-6
        );
        // An aspect below 1 counts as 1; an unknown error is unknown.
        assert_eq!(
            Accuracy::<f64>::estimate_at(kappa, 0.5, 0.0, moving),
            Accuracy::<f64>::estimate_at(kappa, 1.0, 0.0, moving)
        );
        assert!(
            Accuracy::<f64>::estimate_at(kappa, aspect, f64::NAN, moving)
                .velocity
                .is_nan()
        );
        // rates_accuracy passes it on, at the aspect of the Jacobian's columns (here 10 over
        // the shortest angle's column, 1), on the ordinary path and off it alike.
        let jacobian = [[3.0, 0.0], [4.0, 1.0]];
        let required = Accuracy::<f64>::required();
        for (size, position) in [(10.0, 0.0), (10.0, 1e-12), (64.0, 0.0)] {
            let aspect = size / 1.0;
            assert_eq!(
                rates_accuracy(
                    10.0,
                    &jacobian,
                    size,
                    [true, true],
                    Some(position),
                    3.0,
                    Order::Acceleration,
                    &required
                ),
                Ok(Accuracy::estimate_at(10.0, aspect, position, 3.0))
            );
        }
        // Accelerations refused where the closed form's position would pass (κ 2000: ε·κ³ is
        // 1.8e-6 of the 1.2e-4 required, 64·ε·κ³·ρ at ρ 10 is 1.1e-3).
        let kappa = 2e3;
        assert!(
            rates_accuracy(
                kappa,
                &jacobian,
                10.0,
                [true, true],
                None,
                1.0,
                Order::Acceleration,
                &required
            )
            .is_ok()
        );
        assert!(matches!(
            rates_accuracy(
                kappa,
                &jacobian,
                10.0,
                [true, true],
                Some(0.0),
                1.0,
                Order::Acceleration,
                &required
            ),
            Err(Error::Inaccurate {
                order: Order::Acceleration,
                ..
            })
        ));
    }

    #[test]
    fn a_known_aspect_is_read_where_it_is_a_number_from_one_up() {
        let jacobian = [[3.0, 0.0], [4.0, 1.0]];
        let required = Accuracy::<f64>::required();
        let angles = [true, true];
        for position in [None, Some(0.0)] {
            let at = |aspect: f64, size: f64| {
                rates_accuracy_at_aspect(
                    10.0,
                    aspect,
                    &jacobian,
                    size,
                    angles,
                    position,
                    1.0,
                    Order::Acceleration,
                    &required,
                )
            };
            let want = |aspect: f64| match position {
                None => Accuracy::estimate(10.0, aspect),
                Some(p) => Accuracy::estimate_at(10.0, aspect, p, 1.0),
            };
            // Read as given (here 4, though the Jacobian's columns would say 10).
            assert_eq!(at(4.0, 10.0), Ok(want(4.0)));
            assert_eq!(at(1.0, 10.0), Ok(want(1.0)));
            // Not a number from 1 up (squares that overflowed, or underflowed to zero): the
            // Jacobian's, as `rates_accuracy` computes it.
            let from_jacobian = rates_accuracy(
                10.0,
                &jacobian,
                10.0,
                angles,
                position,
                1.0,
                Order::Acceleration,
                &required,
            );
            for aspect in [f64::NAN, f64::INFINITY, 0.0, 0.5] {
                assert_eq!(at(aspect, 10.0), from_jacobian, "{aspect}");
            }
        }
        // Refused as rates_accuracy refuses.
        assert!(matches!(
            rates_accuracy_at_aspect(
                1e5,
                1.0,
                &jacobian,
                10.0,
                angles,
                None,
                1.0,
                Order::Velocity,
                &required
            ),
            Err(Error::Inaccurate {
                order: Order::Velocity,
                ..
            })
        ));
    }

    #[test]
    fn a_known_aspect_judges_the_acceleration_only_when_asked() {
        let jacobian = [[3.0, 0.0], [4.0, 1.0]];
        let required = Accuracy::<f64>::required();
        // κ 1e4: the velocity within what is required, the acceleration not.
        let kappa = 1e4;
        let estimate = Accuracy::estimate(kappa, 2.0);
        assert!(
            estimate.velocity < required.velocity && estimate.acceleration > required.acceleration
        );
        let at = |highest| {
            rates_accuracy_at_aspect(
                kappa,
                2.0,
                &jacobian,
                10.0,
                [true, true],
                None,
                1.0,
                highest,
                &required,
            )
        };
        assert_eq!(at(Order::Velocity), Ok(estimate));
        // The known aspect is read, not the Jacobian's, for a velocity alone too (here a size
        // of 40 over a column of 1 would say 40).
        assert_eq!(
            rates_accuracy_at_aspect(
                kappa,
                2.0,
                &jacobian,
                40.0,
                [true, true],
                None,
                1.0,
                Order::Velocity,
                &required,
            ),
            Ok(estimate)
        );
        assert_eq!(
            at(Order::Acceleration),
            Err(Error::Inaccurate {
                order: Order::Acceleration,
                estimate: estimate.acceleration,
                required: required.acceleration,
            })
        );
    }

    #[test]
    fn the_ordinary_path_reads_the_aspect_of_the_shortest_column() {
        // Columns 5 and 2 long: the aspect of a size of 10 is 5, on the ordinary path (up to
        // 15.9) as off it.
        let jacobian = [[3.0, 0.0], [4.0, 2.0]];
        let required = Accuracy::<f64>::required();
        for size in [10.0, 31.0, 40.0] {
            assert_eq!(
                rates_accuracy(
                    10.0,
                    &jacobian,
                    size,
                    [true, true],
                    Some(0.0),
                    1.0,
                    Order::Acceleration,
                    &required
                ),
                Ok(Accuracy::estimate_at(10.0, size / 2.0, 0.0, 1.0)),
                "{size}"
            );
        }
        assert_eq!(ordinary(&jacobian, 10.0, [true, true], true), Some(5.0));
        assert_eq!(ordinary(&jacobian, 10.0, [true, false], true), Some(2.0));
        assert_eq!(ordinary(&jacobian, 10.0, [false, false], true), Some(1.0));
    }
}
