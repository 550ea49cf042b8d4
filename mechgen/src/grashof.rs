//! Grashof's law: which links of a four-bar can turn fully, from their lengths alone.
//!
//! With `s` the shortest link, `l` the longest and `p`, `q` the other two:
//! - `s + l < p + q`, class I (Grashof): the shortest link turns fully relative to all the
//!   others. Ground adjacent to it: crank-rocker (or rocker-crank); ground = shortest:
//!   double-crank; ground opposite it: Grashof double-rocker (the coupler turns fully).
//! - `s + l > p + q`, class II (non-Grashof): no link turns fully; a triple-rocker.
//! - `s + l = p + q`, class III (special Grashof, change point): the class I inversions, but
//!   all four links can line up, where the linkage may change branch. The parallelogram
//!   (opposite links equal) and the kite or deltoid (adjacent links equal) are such.
//! - `l = s + p + q`: the links close only all in line, in one position (flat): nothing
//!   moves. `l > s + p + q`: the loop cannot close at all. Neither is a mechanism.
//!
//! Equality is decided within a tolerance relative to the links' total length, so that
//! lengths that are equal up to rounding classify as the change point they are meant to be.
//! The lengths are first scaled by a power of two ([`normalised`]), which is exact: the
//! classification depends only on their ratios, bit for bit the same at any scale, and no
//! sum overflows or underflows however long or short the links are.

use crate::Real;

/// Grashof's class, from `s + l` against `p + q`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Class {
    /// Class I, `s + l < p + q`: the shortest link turns fully.
    Grashof,
    /// Class II, `s + l > p + q`: no link turns fully.
    NonGrashof,
    /// Class III, `s + l = p + q`: as class I, but the links can all line up (change point).
    ChangePoint,
    /// `l = s + p + q`: the longest link is as long as the other three together, so the loop
    /// closes only with all four in line, at a single input: a structure, not a mechanism.
    Flat,
    /// `l > s + p + q`: the longest link is longer than the other three together, so the
    /// loop cannot close at any input.
    CannotClose,
}

/// What the input (crank) and output (rocker) links do, relative to the ground link.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Inversion {
    /// The input turns fully, the output rocks (shortest link is the input).
    CrankRocker,
    /// The output turns fully, the input rocks (shortest link is the output).
    RockerCrank,
    /// Both turn fully (shortest link is the ground).
    DoubleCrank,
    /// Both rock, and the coupler turns fully (shortest link is the coupler): the Grashof
    /// double-rocker.
    DoubleRocker,
    /// Non-Grashof: every link rocks.
    TripleRocker,
    /// Nothing moves: the links close only flat, at one input ([`Class::Flat`]), or not at
    /// all ([`Class::CannotClose`]).
    Immobile,
}

/// Named special cases of class III.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Special {
    /// Opposite links equal (ground = coupler, input = output); includes the rhombus.
    Parallelogram,
    /// Adjacent links equal in two pairs (deltoid), and not a parallelogram.
    Kite,
}

/// A four-bar's Grashof classification.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Grashof {
    /// Class I, II or III.
    pub class: Class,
    /// Which links turn fully. For class III this is the class I inversion the lengths give,
    /// with every link of the shortest length counted as shortest (so a parallelogram with
    /// equal cranks is a double-crank).
    pub inversion: Inversion,
    /// A parallelogram or kite, if it is one (always class III).
    pub special: Option<Special>,
}

impl Grashof {
    /// Whether the input link turns fully relative to the ground.
    ///
    /// ```
    /// use mechgen::grashof::classify;
    /// assert!(classify(180.0, 80.0, 200.0, 150.0).input_turns_fully());
    /// assert!(!classify(100.0, 120.0, 90.0, 80.0).input_turns_fully());
    /// ```
    pub fn input_turns_fully(&self) -> bool {
        matches!(
            self.inversion,
            Inversion::CrankRocker | Inversion::DoubleCrank
        )
    }

    /// Whether the output link turns fully relative to the ground.
    ///
    /// ```
    /// use mechgen::grashof::classify;
    /// // Ground shortest: a double-crank.
    /// assert!(classify(80.0, 180.0, 200.0, 150.0).output_turns_fully());
    /// ```
    pub fn output_turns_fully(&self) -> bool {
        matches!(
            self.inversion,
            Inversion::RockerCrank | Inversion::DoubleCrank
        )
    }
}

/// The default relative tolerance for equal lengths: 64 ε, a few units of rounding in the
/// total length.
///
/// ```
/// assert_eq!(mechgen::grashof::default_tolerance::<f64>(), 64.0 * f64::EPSILON);
/// ```
pub fn default_tolerance<T: Real>() -> T {
    T::constant(64.0) * T::epsilon()
}

/// Classifies the four-bar with these link lengths, with equal lengths decided within
/// [`default_tolerance`] of the total length.
///
/// ```
/// use mechgen::grashof::{classify, Class, Inversion};
/// // The seeds' Example 1: s + l = 80 + 200 < 180 + 150, shortest link is the crank.
/// let g = classify(180.0, 80.0, 200.0, 150.0);
/// assert_eq!((g.class, g.inversion), (Class::Grashof, Inversion::CrankRocker));
/// ```
pub fn classify<T: Real>(ground: T, input: T, coupler: T, output: T) -> Grashof {
    classify_with_tolerance(ground, input, coupler, output, default_tolerance())
}

/// [`classify`] with lengths counted equal when they differ by at most
/// `relative_tolerance` times the total length. A tolerance that is negative or not a
/// number counts as zero: lengths are then equal only exactly, and sums of them (`s + l`
/// against `p + q`) equal to their rounding, which decides a sum within a unit of rounding
/// of another as lengths within rounding of those given would. Lengths of which one is not
/// positive and finite (zero, negative, infinite, NaN) make no linkage:
/// [`Class::CannotClose`], [`Inversion::Immobile`], no special shape.
///
/// ```
/// use mechgen::grashof::{classify, Class};
/// assert_eq!(classify(f64::NAN, 1.0, 1.0, 1.0).class, Class::CannotClose);
/// assert_eq!(classify(1.0, f64::INFINITY, f64::INFINITY, 1.0).special, None);
/// assert_eq!(classify(-1.0, 2.0, 2.0, 2.0).class, Class::CannotClose);
/// // A link of length zero too (the others would make it a Grashof crank-rocker).
/// assert_eq!(classify(0.0, 1.0, 1.0, 1.0).class, Class::CannotClose);
/// ```
///
/// ```
/// use mechgen::grashof::{classify_with_tolerance, Class, Special};
/// // A parallelogram measured to 0.01 mm.
/// let g = classify_with_tolerance(200.0, 80.0, 200.004, 79.998, 1e-4);
/// assert_eq!((g.class, g.special), (Class::ChangePoint, Some(Special::Parallelogram)));
/// ```
///
/// A link as long as the other three together closes the loop only flat, and a longer one
/// not at all: neither moves.
///
/// ```
/// use mechgen::grashof::{classify, Class, Inversion};
/// // 6 = 1 + 3 + 2: assembles only at θ2 = π, all four links in line.
/// let g = classify(1.0, 3.0, 6.0, 2.0);
/// assert_eq!((g.class, g.inversion), (Class::Flat, Inversion::Immobile));
/// assert!(!g.input_turns_fully());
/// assert_eq!(classify(1.0, 3.0, 7.0, 2.0).class, Class::CannotClose);
/// ```
pub fn classify_with_tolerance<T: Real>(
    ground: T,
    input: T,
    coupler: T,
    output: T,
    relative_tolerance: T,
) -> Grashof {
    // Lengths that are not positive and finite make no linkage (NaN was a triple-rocker, an
    // infinity a parallelogram, a negative length a double-crank).
    let lengths = [ground, input, coupler, output];
    if !lengths.iter().all(|l| *l > T::zero() && l.is_finite()) {
        return Grashof {
            class: Class::CannotClose,
            inversion: Inversion::Immobile,
            special: None,
        };
    }
    // Scaled exactly, so that nothing below overflows or underflows and the result is the
    // same at every scale.
    let links = normalised([ground, input, coupler, output]);
    let [ground, input, coupler, output] = links;
    let total = links.iter().fold(T::zero(), |sum, l| sum + *l);
    // `max` passes over a NaN: a tolerance that is NaN, or negative, is zero.
    let margin = relative_tolerance.max(T::zero()) * total;
    let equal = |a: T, b: T| (a - b).abs() <= margin;
    let shortest = links.iter().fold(T::infinity(), |m, l| m.min(*l));
    let longest = links.iter().fold(T::neg_infinity(), |m, l| m.max(*l));
    // l against s + p + q, the total less l.
    let overhang = longest - (total - longest);
    // s + l against p + q, where p + q is the total less s and l.
    let excess = (shortest + longest) - (total - shortest - longest);
    let class = if overhang > margin {
        Class::CannotClose
    } else if overhang >= -margin {
        Class::Flat
    } else if excess.abs() <= margin {
        Class::ChangePoint
    } else if excess < T::zero() {
        Class::Grashof
    } else {
        Class::NonGrashof
    };
    let is_shortest = |l: T| equal(l, shortest);
    let inversion = match class {
        Class::Flat | Class::CannotClose => Inversion::Immobile,
        Class::NonGrashof => Inversion::TripleRocker,
        Class::Grashof | Class::ChangePoint => {
            // The shortest link turns fully relative to every other, so a link turns fully
            // relative to the ground when it or the ground is a shortest link.
            let ground_shortest = is_shortest(ground);
            match (
                ground_shortest || is_shortest(input),
                ground_shortest || is_shortest(output),
            ) {
                (true, true) => Inversion::DoubleCrank,
                (true, false) => Inversion::CrankRocker,
                (false, true) => Inversion::RockerCrank,
                (false, false) => Inversion::DoubleRocker,
            }
        }
    };
    // Only class III: lengths a parallelogram's within the tolerance but whose short pair
    // is within it of nothing close only flat (found by an adversarial review).
    let special = if class != Class::ChangePoint {
        None
    } else if equal(ground, coupler) && equal(input, output) {
        Some(Special::Parallelogram)
    } else if (equal(ground, input) && equal(coupler, output))
        || (equal(ground, output) && equal(input, coupler))
    {
        Some(Special::Kite)
    } else {
        None
    };
    Grashof {
        class,
        inversion,
        special,
    }
}

/// `lengths` multiplied by the power of two that brings the largest magnitude into `[1, 2)`.
///
/// Multiplying by a power of two is exact (unless a result falls below the normal range,
/// where it rounds once), so ratios, equalities and the order of sums are as they were, while
/// squares and sums of the results can neither overflow nor underflow for any ratio below
/// `2^500` (f64) or `2^60` (f32). Any two arrays that are power-of-two multiples of each
/// other give the same result, bit for bit. Lengths whose largest magnitude is zero, NaN or
/// infinite come back unchanged.
///
/// ```
/// use mechgen::grashof::normalised;
/// assert_eq!(normalised([1e300, 3e299]), normalised([1e300 / 1024.0, 3e299 / 1024.0]));
/// assert_eq!(normalised([0.75f32, -3.0]), [0.375, -1.5]);
/// ```
pub fn normalised<T: Real, const N: usize>(lengths: [T; N]) -> [T; N] {
    let largest = lengths.iter().fold(T::zero(), |m, l| m.max(l.abs()));
    let (mantissa, exponent, _) = largest.integer_decode();
    if mantissa == 0 || !largest.is_finite() {
        return lengths;
    }
    // largest = mantissa·2^exponent, so its leading bit is worth 2^top.
    let top = i32::from(exponent) + 63 - mantissa.leading_zeros() as i32;
    // 2^-top in two factors, each a normal number of either type (|top| ≤ 1074).
    let (first, second) = (-top / 2, -top - (-top / 2));
    let (first, second) = (power_of_two::<T>(first), power_of_two::<T>(second));
    // The first product is exact (it stays in the normal range if the second's result is
    // normal), so each result rounds at most once.
    lengths.map(|l| l * first * second)
}

/// `2^k` for `|k| ≤ 538`, exact in f64, and in f32 for `|k| ≤ 126`.
fn power_of_two<T: Real>(k: i32) -> T {
    let biased = u64::from((k + 1023).clamp(1, 2046).unsigned_abs());
    T::constant(f64::from_bits(biased << 52))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tolerance_that_is_negative_or_nan_is_zero() {
        // The seeds' crank-rocker, and a parallelogram off by a part in 10⁶: with no
        // tolerance, the crank is still the one shortest link and the parallelogram no
        // longer one (not every link a shortest, nor a double rocker).
        for tolerance in [-1e-3, f64::NAN, -0.0, 0.0] {
            let g = classify_with_tolerance(180.0, 80.0, 200.0, 150.0, tolerance);
            assert_eq!(
                (g.class, g.inversion),
                (Class::Grashof, Inversion::CrankRocker)
            );
            let g = classify_with_tolerance(200.0, 80.0, 200.0, 80.0001, tolerance);
            assert_eq!((g.class, g.special), (Class::Grashof, None));
            // Exactly equal lengths are equal at any tolerance.
            let g = classify_with_tolerance(200.0, 80.0, 200.0, 80.0, tolerance);
            assert_eq!(
                (g.class, g.special),
                (Class::ChangePoint, Some(Special::Parallelogram))
            );
        }
    }

    fn inversion(ground: f64, input: f64, coupler: f64, output: f64) -> (Class, Inversion) {
        let g = classify(ground, input, coupler, output);
        (g.class, g.inversion)
    }

    #[test]
    fn each_inversion_and_what_turns_fully() {
        use Inversion::*;
        for (links, class, expected, input, output) in [
            (
                [180.0, 80.0, 200.0, 150.0],
                Class::Grashof,
                CrankRocker,
                true,
                false,
            ),
            (
                [180.0, 150.0, 200.0, 80.0],
                Class::Grashof,
                RockerCrank,
                false,
                true,
            ),
            (
                [80.0, 180.0, 200.0, 150.0],
                Class::Grashof,
                DoubleCrank,
                true,
                true,
            ),
            (
                [180.0, 150.0, 80.0, 200.0],
                Class::Grashof,
                DoubleRocker,
                false,
                false,
            ),
            (
                [100.0, 120.0, 90.0, 80.0],
                Class::NonGrashof,
                TripleRocker,
                false,
                false,
            ),
            ([1.0, 3.0, 6.0, 2.0], Class::Flat, Immobile, false, false),
            (
                [1.0, 3.0, 7.0, 2.0],
                Class::CannotClose,
                Immobile,
                false,
                false,
            ),
            // s + l = p + q: the change point, with the class I inversions.
            (
                [2.0, 1.0, 4.0, 3.0],
                Class::ChangePoint,
                CrankRocker,
                true,
                false,
            ),
            (
                [1.0, 2.0, 4.0, 3.0],
                Class::ChangePoint,
                DoubleCrank,
                true,
                true,
            ),
        ] {
            let [ground, crank, coupler, rocker] = links;
            let g = classify(ground, crank, coupler, rocker);
            assert_eq!((g.class, g.inversion), (class, expected), "{links:?}");
            assert_eq!(g.input_turns_fully(), input, "{links:?}");
            assert_eq!(g.output_turns_fully(), output, "{links:?}");
        }
    }

    #[test]
    fn every_link_of_the_shortest_length_counts_as_shortest() {
        // Equal cranks: a double-crank parallelogram; ground and coupler the shortest: the
        // ground's double-crank too; equal cranks of a kite.
        let g = classify(200.0, 80.0, 200.0, 80.0);
        assert_eq!(
            (g.class, g.inversion, g.special),
            (
                Class::ChangePoint,
                Inversion::DoubleCrank,
                Some(Special::Parallelogram)
            )
        );
        assert_eq!(
            inversion(80.0, 200.0, 80.0, 200.0).1,
            Inversion::DoubleCrank
        );
        // Coupler and output equally shortest.
        assert_eq!(
            inversion(200.0, 200.0, 80.0, 80.0).1,
            Inversion::RockerCrank
        );
    }

    #[test]
    fn parallelograms_and_kites() {
        let special = |links: [f64; 4]| classify(links[0], links[1], links[2], links[3]).special;
        assert_eq!(
            special([200.0, 80.0, 200.0, 80.0]),
            Some(Special::Parallelogram)
        );
        assert_eq!(
            special([100.0, 100.0, 100.0, 100.0]),
            Some(Special::Parallelogram)
        );
        // Ground = input and coupler = output; ground = output and input = coupler.
        assert_eq!(special([100.0, 100.0, 200.0, 200.0]), Some(Special::Kite));
        assert_eq!(special([100.0, 200.0, 200.0, 100.0]), Some(Special::Kite));
        // One pair equal is neither.
        assert_eq!(special([100.0, 150.0, 200.0, 100.0]), None);
        assert_eq!(special([100.0, 100.0, 200.0, 150.0]), None);
        assert_eq!(special([200.0, 80.0, 200.0, 90.0]), None);
        assert_eq!(special([180.0, 80.0, 200.0, 150.0]), None);
        // A parallelogram's lengths within the tolerance whose short pair is within it of
        // nothing: flat (it closes only with all four in line), and so no special case, which
        // is class III (it said a parallelogram).
        let flat = classify(1.0, 1e-20, 1.0, 2e-20);
        assert_eq!((flat.class, flat.special), (Class::Flat, None));
        // Class III with ground = coupler but the cranks unequal (30 + 70 = 50 + 50): neither.
        let one_pair = classify(50.0, 30.0, 50.0, 70.0);
        assert_eq!(
            (one_pair.class, one_pair.special),
            (Class::ChangePoint, None)
        );
    }

    #[test]
    fn equality_is_decided_within_the_tolerance_of_the_total_inclusively() {
        // Normalised already (the longest in [1, 2)), and every sum exact: with totals of 4,
        // margins of 1/4.
        let tolerance = 1.0 / 16.0;
        let classify = |links: [f64; 4], tolerance: f64| {
            classify_with_tolerance(links[0], links[1], links[2], links[3], tolerance).class
        };
        // s + l − (p + q) = 1/4 = the margin: a change point; past it, non-Grashof.
        let excess = [0.625, 0.875, 1.5, 1.0];
        assert_eq!(classify(excess, tolerance), Class::ChangePoint);
        assert_eq!(classify(excess, tolerance / 2.0), Class::NonGrashof);
        // s + l − (p + q) = −1/4: a change point; past it, Grashof.
        let short = [0.375, 1.0, 1.5, 1.125];
        assert_eq!(classify(short, tolerance), Class::ChangePoint);
        assert_eq!(classify(short, tolerance / 2.0), Class::Grashof);
        // With a total of 2, a margin of 1/8.
        // l − (s + p + q) = 1/8 = the margin: flat; past it, no closing at all.
        let over = [1.0625, 0.3125, 0.3125, 0.3125];
        assert_eq!(classify(over, tolerance), Class::Flat);
        assert_eq!(classify(over, tolerance / 2.0), Class::CannotClose);
        // l − (s + p + q) = −1/8, doubled by the normalisation as the total is: flat;
        // with less tolerance, a mechanism.
        let under = [0.9375, 0.375, 0.375, 0.3125];
        assert_eq!(classify(under, tolerance), Class::Flat);
        assert_eq!(classify(under, tolerance / 2.0), Class::NonGrashof);
        // Lengths equal within the margin are equal: a parallelogram and its inversion.
        // (Normalised: 1, 1/4, 7/8, 1/4, a total of 19/8: a margin of 0.148 at 1/16.)
        let g = classify_with_tolerance(2.0, 0.5, 1.75, 0.5, tolerance);
        assert_eq!(g.special, Some(Special::Parallelogram));
        let g = classify_with_tolerance(2.0, 0.5, 1.75, 0.5, tolerance / 2.0);
        assert_eq!(g.special, None);
        assert_eq!(default_tolerance::<f32>(), 64.0 * f32::EPSILON);
    }

    #[test]
    fn normalising_scales_by_the_power_of_two_of_the_longest() {
        assert_eq!(normalised([3.0, -5.0]), [0.75, -1.25]);
        assert_eq!(normalised([1.0, 0.5]), [1.0, 0.5]);
        assert_eq!(normalised([1.999, 0.5]), [1.999, 0.5]);
        assert_eq!(normalised([2.0, 0.5]), [1.0, 0.25]);
        assert_eq!(
            normalised([2f64.powi(-1070), -2f64.powi(-1072)]),
            [1.0, -0.25]
        );
        assert_eq!(
            normalised([1e300, 3e299]),
            [1e300, 3e299].map(|l| l * 2f64.powi(-996))
        );
        for unchanged in [[0.0, 0.0], [f64::INFINITY, 1.0], [f64::NAN, f64::NAN]] {
            let scaled = normalised(unchanged);
            for (got, want) in scaled.iter().zip(unchanged) {
                assert!(got == &want || (got.is_nan() && want.is_nan()));
            }
        }
        assert_eq!(power_of_two::<f64>(10), 1024.0);
        assert_eq!(power_of_two::<f64>(-3), 0.125);
        assert_eq!(power_of_two::<f64>(0), 1.0);
        assert_eq!(power_of_two::<f64>(5000), 2f64.powi(1023));
        assert_eq!(power_of_two::<f64>(-5000), 2f64.powi(-1022));
        assert_eq!(power_of_two::<f32>(-126), f32::MIN_POSITIVE);
    }
}
