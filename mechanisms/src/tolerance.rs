//! Tolerance analysis: how far a four-bar's output angle and coupler point move when each
//! dimension is off by up to its tolerance, to first order, from the generated
//! sensitivities (`generate: sensitivities`), at no cost of a new loop solve.
//!
//! With `v_p` the derivative of an output with respect to dimension `p` (the input held) and
//! `t_p` that dimension's tolerance (±), the output moves by `Σ v_p·δ_p` for errors
//! `|δ_p| ≤ t_p`:
//! - **worst case**: the largest that deviation can be over the whole box of errors: for an
//!   angle `Σ |v_p|·t_p`; for a point the largest length of `Σ v_p·δ_p`, which lies at a
//!   corner of the box (the length is convex), found exactly by trying every corner;
//! - **root sum square**: `√(Σ (|v_p|·t_p)²)`, the statistical stack-up: where the errors are
//!   independent and each tolerance is the same multiple of its error's standard deviation
//!   (3σ, say), the output's deviation is that multiple of its own standard deviation.
//!
//! Both are first-order: they hold while the tolerances are small against the distance to a
//! toggle, where the sensitivities grow without bound (there the analysis is
//! [`mechgen::Error::Singular`]). The command-line program checks them against Monte Carlo
//! on the nonlinear model (`mechanisms tolerance`).

use mechgen::{Branch, Error, Real, Vec2};

use crate::four_bar::{FourBar, FourBarSensitivities};
use crate::random::SplitMix64;

/// The ± tolerance of each of a four-bar's dimensions: lengths in its units, the coupler
/// point's angle in radians. Zero for a dimension taken as exact.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FourBarTolerances<T> {
    /// Ground `l1`.
    pub ground: T,
    /// Crank `l2`.
    pub crank: T,
    /// Coupler `l3`.
    pub coupler: T,
    /// Rocker `l4`.
    pub rocker: T,
    /// The coupler point's distance from A.
    pub distance: T,
    /// The coupler point's angle from A B, radians.
    pub angle: T,
}

impl<T: Real> FourBarTolerances<T> {
    /// The same tolerance `length` on every length (the angle exact).
    pub fn lengths(length: T) -> Self {
        FourBarTolerances {
            ground: length,
            crank: length,
            coupler: length,
            rocker: length,
            distance: length,
            angle: T::zero(),
        }
    }

    /// In the order of the four-bar's parameters (`l1`, `l2`, `l3`, `l4`, `a`, `delta`).
    fn as_array(&self) -> [T; 6] {
        [
            self.ground,
            self.crank,
            self.coupler,
            self.rocker,
            self.distance,
            self.angle,
        ]
    }
}

/// How far an output can move: the first-order worst case over the tolerance box, and the
/// root-sum-square stack-up (see the [module](self) docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Deviation<T> {
    /// The largest first-order deviation over every combination of errors within the
    /// tolerances.
    pub worst_case: T,
    /// The root-sum-square stack-up of the dimensions' deviations.
    pub root_sum_square: T,
}

/// A four-bar's deviations at one crank angle: the rocker's angle θ4 (radians) and the
/// coupler point (a distance).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FourBarDeviations<T> {
    /// The rocker's angle θ4, radians.
    pub output: Deviation<T>,
    /// The coupler point, a distance in the linkage's units.
    pub coupler_point: Deviation<T>,
}

impl<T: Real> FourBar<T> {
    /// The first-order deviations of the rocker angle θ4 and of the coupler point at the crank
    /// angle `theta2` on `branch`, for dimensions off by up to `tolerances` (see the
    /// [module](crate::tolerance) docs). The crank angle is held: the deviations are of the
    /// mechanism as built, not of its input.
    ///
    /// Errors: as [`assemble`](Self::assemble) and [`sensitivities`](Self::sensitivities)
    /// (outside the range of motion; `Singular` at a toggle, where the deviations are
    /// unbounded); a tolerance that is negative or not finite is
    /// [`mechgen::Error::NonFinite`] for a NaN or infinity and taken by its magnitude
    /// otherwise; a deviation beyond the largest float is [`mechgen::Error::NonFinite`] too.
    ///
    /// ```
    /// use mechanisms::{FourBar, FourBarTolerances};
    /// use mechgen::Branch;
    /// // Example 1 with every length ±0.1 mm, at 60°.
    /// let linkage = FourBar::new(180.0f64, 80.0, 200.0, 150.0)?.with_coupler_point(100.0, 0.5)?;
    /// let d = linkage.tolerance(1.0472, Branch::Open, &FourBarTolerances::lengths(0.1))?;
    /// // θ4 within ±0.166° and P within 0.263 mm, at worst; 0.084° and 0.168 mm as a stack-up.
    /// assert!((d.output.worst_case.to_degrees() - 0.1656).abs() < 1e-4);
    /// assert!((d.output.root_sum_square.to_degrees() - 0.0839).abs() < 1e-4);
    /// assert!((d.coupler_point.worst_case - 0.2626).abs() < 1e-4);
    /// assert!((d.coupler_point.root_sum_square - 0.1677).abs() < 1e-4);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn tolerance(
        &self,
        theta2: T,
        branch: Branch,
        tolerances: &FourBarTolerances<T>,
    ) -> Result<FourBarDeviations<T>, Error<T>> {
        let t = finite_tolerances(tolerances)?;
        let q = self.assemble(theta2, branch)?;
        let s = self.sensitivities(theta2, &q)?;
        let p = self.point_sensitivities(theta2, &q)?;
        let output = per_parameter(&s).map(|u| u.theta4);
        let point = per_parameter(&p).map(|points| points.coupler_point);
        let deviations = FourBarDeviations {
            output: angle_deviation(&output, &t),
            coupler_point: point_deviation(&point, &t),
        };
        // Tolerances of 1e10 on a linkage of 1e-300 (or of the largest float on any) move it
        // by more than a float holds: said, not returned as an infinite deviation.
        let figures = [deviations.output, deviations.coupler_point]
            .map(|d| [d.worst_case, d.root_sum_square]);
        if !figures.as_flattened().iter().all(|x| x.is_finite()) {
            return Err(Error::NonFinite {
                quantity: "first-order deviation",
            });
        }
        Ok(deviations)
    }
}

/// The tolerances by their magnitudes, or [`mechgen::Error::NonFinite`] for a NaN or an
/// infinity (which no linkage can be built from: the sampled models would all fail and say
/// nothing, an adversarial review found, where the first-order one refused).
fn finite_tolerances<T: Real>(tolerances: &FourBarTolerances<T>) -> Result<[T; 6], Error<T>> {
    let t = tolerances.as_array();
    if t.iter().any(|t| !t.is_finite()) {
        return Err(Error::NonFinite {
            quantity: "tolerance",
        });
    }
    Ok(t.map(T::abs))
}

/// The nonlinear model's deviations from a tolerance box, against which the first-order ones
/// are checked (see [`FourBar::corners`] and [`FourBar::monte_carlo`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sampled<T> {
    /// The largest `|Δθ4|` over the linkages tried, radians.
    pub output_largest: T,
    /// The root mean square of `Δθ4`.
    pub output_rms: T,
    /// The largest distance the coupler point moved.
    pub coupler_point_largest: T,
    /// The root mean square of that distance.
    pub coupler_point_rms: T,
    /// How many linkages were tried and assembled.
    pub assembled: usize,
    /// How many could not be built or assembled at the crank angle (they count in neither).
    pub failed: usize,
}

impl<T: Real> FourBar<T> {
    /// The nonlinear model at every corner of the tolerance box (each dimension at `+t` or
    /// `−t`): the exact worst case where it lies at a corner, as the first-order worst case
    /// does. `2^k` linkages for the `k` dimensions with a tolerance.
    ///
    /// Errors: as [`tolerance`](Self::tolerance), for the nominal linkage.
    pub fn corners(
        &self,
        theta2: T,
        branch: Branch,
        tolerances: &FourBarTolerances<T>,
    ) -> Result<Sampled<T>, Error<T>> {
        let t = finite_tolerances(tolerances)?;
        self.representable(&t, T::one())?;
        let (indices, count) = varied(&t);
        let mut sampled = Accumulated::new(self, theta2, branch)?;
        for corner in 0..(1u32 << count) {
            let mut errors = [T::zero(); 6];
            for (bit, &p) in indices[..count].iter().enumerate() {
                errors[p] = if at_lower_limit(corner, bit) {
                    -t[p]
                } else {
                    t[p]
                };
            }
            sampled.add(self, theta2, branch, errors);
        }
        Ok(sampled.finish())
    }

    /// Monte Carlo on the nonlinear model: `samples` linkages with each dimension off by an
    /// independent normal error of standard deviation `t/3` (the tolerance taken as 3σ),
    /// from a generator seeded with `seed`, each assembled at `theta2` on `branch`. The
    /// root-mean-square deviations estimate the first-order root-sum-square stack-up over 3.
    ///
    /// Errors: as [`tolerance`](Self::tolerance), for the nominal linkage.
    pub fn monte_carlo(
        &self,
        theta2: T,
        branch: Branch,
        tolerances: &FourBarTolerances<T>,
        samples: usize,
        seed: u64,
    ) -> Result<Sampled<T>, Error<T>> {
        let t = finite_tolerances(tolerances)?;
        // The generator's normals are within 8.6σ = 2.9·t.
        self.representable(&t, T::constant(3.0))?;
        let mut random = SplitMix64(seed);
        let mut sampled = Accumulated::new(self, theta2, branch)?;
        for _ in 0..samples {
            let errors = t.map(|t| t / T::constant(3.0) * random.normal::<T>());
            sampled.add(self, theta2, branch, errors);
        }
        Ok(sampled.finish())
    }

    /// `Err(NonFinite)` where a dimension moved by `reach` times its tolerance `t` (`l1`, `l2`,
    /// `l3`, `l4`, `a`, `delta`) is beyond the float's range: such a linkage is not one that
    /// fails to assemble, and counting it so would hide the overflow.
    fn representable(&self, t: &[T; 6], reach: T) -> Result<(), Error<T>> {
        let (a, delta) = self.coupler_point();
        let [l1, l2, l3, l4] = self.lengths();
        let moved = [l1, l2, l3, l4, a, delta]
            .iter()
            .zip(t)
            .all(|(d, t)| (d.abs() + reach * *t).is_finite());
        if moved {
            Ok(())
        } else {
            Err(Error::NonFinite {
                quantity: "dimension moved by its tolerance",
            })
        }
    }

    /// This linkage with its dimensions (`l1`, `l2`, `l3`, `l4`, `a`, `delta`) moved by
    /// `errors`, if they still make one. A coupler point's distance moved below zero (a point
    /// at the crank pin, `a = 0 ± t`) is the same point at the opposite angle: `−a` at
    /// `δ + π`, exactly, rather than no linkage.
    fn perturbed(&self, errors: [T; 6]) -> Option<Self> {
        let (a, delta) = self.coupler_point();
        let [l1, l2, l3, l4] = self.lengths();
        let (a, delta) = (a + errors[4], delta + errors[5]);
        let (a, delta) = if a < T::zero() {
            (-a, delta + T::constant(core::f64::consts::PI))
        } else {
            (a, delta)
        };
        FourBar::new(
            l1 + errors[0],
            l2 + errors[1],
            l3 + errors[2],
            l4 + errors[3],
        )
        .and_then(|l| l.with_coupler_point(a, delta))
        .ok()
    }
}

/// Running sums of [`Sampled`]'s deviations from the nominal linkage's.
struct Accumulated<T> {
    theta4: T,
    point: Vec2<T>,
    sampled: Sampled<T>,
    output_squares: SumOfSquares<T>,
    point_squares: SumOfSquares<T>,
}

impl<T: Real> Accumulated<T> {
    fn new(nominal: &FourBar<T>, theta2: T, branch: Branch) -> Result<Self, Error<T>> {
        let q = nominal.assemble(theta2, branch)?;
        let point = nominal.points(theta2, &q)?.coupler_point;
        Ok(Accumulated {
            theta4: q.theta4,
            point,
            sampled: Sampled::default(),
            output_squares: SumOfSquares::default(),
            point_squares: SumOfSquares::default(),
        })
    }

    fn add(&mut self, nominal: &FourBar<T>, theta2: T, branch: Branch, errors: [T; 6]) {
        let solved = nominal.perturbed(errors).and_then(|l| {
            let q = l.assemble(theta2, branch).ok()?;
            Some((q.theta4, l.points(theta2, &q).ok()?.coupler_point))
        });
        let Some((theta4, point)) = solved else {
            self.sampled.failed += 1;
            return;
        };
        // The angle's change wrapped to (−π, π].
        let turn = T::constant(core::f64::consts::TAU);
        let mut output = theta4 - self.theta4;
        output = output - turn * (output / turn).round();
        let moved = (point.x - self.point.x).hypot(point.y - self.point.y);
        let s = &mut self.sampled;
        s.assembled += 1;
        s.output_largest = s.output_largest.max(output.abs());
        s.coupler_point_largest = s.coupler_point_largest.max(moved);
        self.output_squares.add(output);
        self.point_squares.add(moved);
    }

    fn finish(self) -> Sampled<T> {
        let n = T::from(self.sampled.assembled.max(1)).unwrap_or_else(T::one);
        Sampled {
            output_rms: self.output_squares.root_mean(n),
            coupler_point_rms: self.point_squares.root_mean(n),
            ..self.sampled
        }
    }
}

/// A sum of squares kept as `scale²·sum`, `scale` the largest magnitude added so far (as
/// LAPACK's `nrm2` keeps it): no square overflows or underflows, whatever the linkage's size
/// (a point moved by 1e-302 on a linkage of 1e-300, or by 1e298 on one of 1e300).
#[derive(Clone, Copy, Debug)]
struct SumOfSquares<T> {
    scale: T,
    sum: T,
}

impl<T: Real> Default for SumOfSquares<T> {
    fn default() -> Self {
        SumOfSquares {
            scale: T::zero(),
            sum: T::zero(),
        }
    }
}

impl<T: Real> SumOfSquares<T> {
    fn add(&mut self, value: T) {
        let magnitude = value.abs();
        if magnitude == T::zero() {
            return;
        }
        if magnitude > self.scale {
            let ratio = self.scale / magnitude;
            self.sum = T::one() + self.sum * ratio * ratio;
            self.scale = magnitude;
        } else {
            let ratio = magnitude / self.scale;
            self.sum = self.sum + ratio * ratio;
        }
    }

    /// `√(Σ x² / n)`.
    fn root_mean(&self, n: T) -> T {
        self.scale * (self.sum / n).sqrt()
    }
}

/// The indices of the nonzero tolerances (the first `count` of the array), without
/// allocating.
fn varied<T: Real>(t: &[T; 6]) -> ([usize; 6], usize) {
    let mut indices = [0; 6];
    let mut count = 0;
    for (p, t) in t.iter().enumerate() {
        if *t != T::zero() {
            indices[count] = p;
            count += 1;
        }
    }
    (indices, count)
}

/// The per-parameter values in the four-bar's parameter order.
fn per_parameter<V: Copy>(s: &FourBarSensitivities<V>) -> [V; 6] {
    [s.l1, s.l2, s.l3, s.l4, s.a, s.delta]
}

/// `Σ |v_p|·t_p` and `√(Σ (v_p·t_p)²)`.
fn angle_deviation<T: Real, const N: usize>(v: &[T; N], t: &[T; N]) -> Deviation<T> {
    let terms = core::array::from_fn::<T, N, _>(|p| (v[p] * t[p]).abs());
    Deviation {
        worst_case: terms.iter().fold(T::zero(), |sum, x| sum + *x),
        root_sum_square: root_sum_square(&terms),
    }
}

/// The longest `Σ ±t_p·v_p` over every choice of signs (a corner of the tolerance box, where
/// the convex length is largest), and `√(Σ (t_p·|v_p|)²)`.
fn point_deviation<T: Real, const N: usize>(v: &[Vec2<T>; N], t: &[T; N]) -> Deviation<T> {
    let scaled = core::array::from_fn::<Vec2<T>, N, _>(|p| Vec2 {
        x: v[p].x * t[p],
        y: v[p].y * t[p],
    });
    // A corner and its opposite have the same length: the first sign stays +.
    let mut longest = T::zero();
    for corner in 0..(1u32 << (N - 1)) {
        let sum = scaled
            .iter()
            .enumerate()
            .fold(Vec2::default(), |sum: Vec2<T>, (p, d)| {
                if p > 0 && at_lower_limit(corner, p - 1) {
                    Vec2 {
                        x: sum.x - d.x,
                        y: sum.y - d.y,
                    }
                } else {
                    Vec2 {
                        x: sum.x + d.x,
                        y: sum.y + d.y,
                    }
                }
            });
        longest = longest.max(sum.x.hypot(sum.y));
    }
    let lengths = scaled.map(|d| d.x.hypot(d.y));
    Deviation {
        worst_case: longest,
        root_sum_square: root_sum_square(&lengths),
    }
}

/// `√(Σ x²)` without overflow or underflow of the squares (scaled by the largest).
fn root_sum_square<T: Real>(terms: &[T]) -> T {
    let largest = terms.iter().fold(T::zero(), |m, x| m.max(x.abs()));
    if largest == T::zero() || !largest.is_finite() {
        return largest;
    }
    let sum = terms
        .iter()
        .fold(T::zero(), |sum, x| sum + (*x / largest) * (*x / largest));
    largest * sum.sqrt()
}

/// Whether the corner numbered `corner` (one bit per varied dimension, set for `−t`) puts
/// its `bit`th varied dimension at its lower limit.
fn at_lower_limit(corner: u32, bit: usize) -> bool {
    corner & (1 << bit) != 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_corners_set_bits_are_its_dimensions_at_their_lower_limits() {
        assert!(at_lower_limit(0b10, 1));
        assert!(!at_lower_limit(0b10, 0));
        assert!(!at_lower_limit(0b10, 2));
        assert!(at_lower_limit(0b101, 2));
        assert!(!at_lower_limit(0, 0));
    }

    #[test]
    fn the_worst_corner_of_a_box_is_found() {
        // Two perpendicular unit derivatives and one along their diagonal: the worst corner
        // adds all three, 1 + √2·(1/√2)... exactly |(1 + 1/√2, 1 + 1/√2)|.
        let h = core::f64::consts::FRAC_1_SQRT_2;
        let v = [
            Vec2 { x: 1.0, y: 0.0 },
            Vec2 { x: 0.0, y: 1.0 },
            Vec2 { x: h, y: h },
        ];
        let d = point_deviation(&v, &[1.0, 1.0, 1.0]);
        assert!((d.worst_case - (1.0 + h) * 2f64.sqrt()).abs() < 1e-15);
        assert!((d.root_sum_square - 3f64.sqrt()).abs() < 1e-15);
        let a = angle_deviation(&[1.0f64, -2.0, 0.5], &[0.1, 0.1, 0.2]);
        assert!((a.worst_case - 0.4).abs() < 1e-15);
        assert!((a.root_sum_square - (0.01f64 + 0.04 + 0.01).sqrt()).abs() < 1e-15);
        assert!((root_sum_square(&[3e200f64, 4e200]) / 5e200 - 1.0).abs() < 1e-15);
    }

    /// Found by mutation testing: the worst corner may take the derivatives with opposite
    /// signs, and every such combination is tried.
    #[test]
    fn the_worst_corner_may_subtract() {
        let (x, y) = (Vec2 { x: 1.0, y: 0.0 }, Vec2 { x: 0.0, y: 1.0 });
        let minus_x = Vec2 { x: -1.0, y: 0.0 };
        let d = point_deviation(&[x, minus_x], &[1.0, 0.5]);
        assert_eq!(d.worst_case, 1.5);
        assert_eq!(d.root_sum_square, 1.25f64.sqrt());
        // (1, 0) − (−1, 0) ± (0, 1): √5, whichever sign the last takes.
        let d = point_deviation(&[x, y, minus_x], &[1.0, 1.0, 1.0]);
        assert_eq!(d.worst_case, 5f64.sqrt());
        let d = point_deviation(&[y, minus_x, x, y], &[1.0, 1.0, 1.0, 1.0]);
        assert_eq!(d.worst_case, 8f64.sqrt());
    }

    /// Found by mutation testing: no terms, or only zero ones, stack up to zero; an infinite
    /// one to infinity (not NaN, which scaling by it would give).
    #[test]
    fn stack_ups_of_zeros_and_infinities() {
        assert_eq!(root_sum_square::<f64>(&[0.0, 0.0]), 0.0);
        assert_eq!(root_sum_square::<f64>(&[]), 0.0);
        assert_eq!(root_sum_square(&[1.0, f64::INFINITY]), f64::INFINITY);
        assert_eq!(root_sum_square(&[-3.0, 4.0]), 5.0);
        let d = angle_deviation(&[0.0f64, 0.0], &[0.1, 0.1]);
        assert_eq!((d.worst_case, d.root_sum_square), (0.0, 0.0));
    }

    /// A four-bar whose rocker stands near θ4 = π at θ2 = 90° (B near (l1 − l4, 0)), so that
    /// the linkages within its tolerances put θ4 on either side of ±π.
    fn near_pi() -> (FourBar<f64>, f64, Branch) {
        let linkage = FourBar::new(100.0, 40.0, 64.0, 50.0)
            .and_then(|l| l.with_coupler_point(30.0, 0.4))
            .unwrap();
        let theta2 = 90f64.to_radians();
        let branch = [Branch::Open, Branch::Crossed]
            .into_iter()
            .find(|&b| linkage.assemble(theta2, b).unwrap().theta4.abs() > 3.1)
            .unwrap();
        (linkage, theta2, branch)
    }

    /// Found by mutation testing: for small tolerances, the nonlinear model at the box's
    /// corners agrees with the first order to second order: the largest deviations with the worst cases, and
    /// the root mean squares over the corners with the root-sum-square stack-ups (over every
    /// corner the cross terms cancel). The rocker's angle changes are wrapped: θ4 lies on
    /// both sides of ±π here.
    #[test]
    fn corners_agree_with_the_first_order_for_small_tolerances() {
        let (linkage, theta2, branch) = near_pi();
        let tolerances = FourBarTolerances {
            ground: 0.02,
            crank: 0.01,
            coupler: 0.03,
            rocker: 0.01,
            distance: 0.02,
            angle: 1e-3,
        };
        let first = linkage.tolerance(theta2, branch, &tolerances).unwrap();
        let corners = linkage.corners(theta2, branch, &tolerances).unwrap();
        // To second order: the tolerances are some 3e-4 of the lengths.
        let near = |got: f64, want: f64| (got / want - 1.0).abs() < 1e-2;
        assert!(first.output.worst_case > 1e-4, "{first:?}");
        assert!(
            near(corners.output_largest, first.output.worst_case),
            "{corners:?} {first:?}"
        );
        assert!(
            near(corners.output_rms, first.output.root_sum_square),
            "{corners:?}"
        );
        assert!(near(
            corners.coupler_point_largest,
            first.coupler_point.worst_case
        ));
        assert!(near(
            corners.coupler_point_rms,
            first.coupler_point.root_sum_square
        ));
        assert_eq!((corners.assembled, corners.failed), (64, 0));
        // The rocker's angle crosses ±π among the corners.
        let [l1, l2, l3, l4] = linkage.lengths();
        let t = tolerances;
        let signs: [f64; 16] = core::array::from_fn(|corner| {
            let sign = |bit: usize| if corner & (1 << bit) != 0 { -1.0 } else { 1.0 };
            FourBar::new(
                l1 + sign(0) * t.ground,
                l2 + sign(1) * t.crank,
                l3 + sign(2) * t.coupler,
                l4 + sign(3) * t.rocker,
            )
            .map(|l| l.assemble(theta2, branch).unwrap().theta4.signum())
            .unwrap()
        });
        assert!(signs.contains(&1.0) && signs.contains(&-1.0), "{signs:?}");
    }

    /// Found by mutation testing: corners that make no linkage (here a crank angle 0.04°
    /// inside the nominal linkage's limit, which some corners' limits fall short of) are
    /// counted as failed, the rest as assembled; only the dimensions with a tolerance are
    /// varied.
    #[test]
    fn corners_that_make_no_linkage_are_counted_apart() {
        let linkage = FourBar::new(100.0, 70.0, 40.0, 50.0).unwrap();
        let theta2 = 60.9f64.to_radians();
        let sampled = linkage
            .corners(theta2, Branch::Open, &FourBarTolerances::lengths(0.1))
            .unwrap();
        assert_eq!(sampled.assembled + sampled.failed, 32);
        assert!(sampled.failed > 0 && sampled.assembled > 0, "{sampled:?}");
        assert!(sampled.output_largest > 0.0 && sampled.coupler_point_largest > 0.0);
        let exact = FourBarTolerances::default();
        let sampled = linkage.corners(theta2, Branch::Open, &exact).unwrap();
        assert_eq!((sampled.assembled, sampled.failed), (1, 0));
        assert_eq!(sampled.output_largest, 0.0);
        assert_eq!(sampled.coupler_point_largest, 0.0);
    }

    /// A dimension its tolerance takes beyond the float's range is an overflow, not a
    /// linkage that fails to assemble: a coupler point 1.79e308 out, ±7.9e305, had half the
    /// box's corners counted as failed.
    #[test]
    fn a_box_beyond_the_float_s_range_is_an_overflow() {
        let linkage = FourBar::new(1.8e307, 0.8e307, 2e307, 1.5e307)
            .and_then(|l| l.with_coupler_point(1.79e308, 0.5))
            .unwrap();
        let tolerances = FourBarTolerances::lengths(7.9e305);
        let overflow = Err(Error::NonFinite {
            quantity: "dimension moved by its tolerance",
        });
        assert_eq!(linkage.corners(1.0, Branch::Open, &tolerances), overflow);
        assert_eq!(
            linkage.monte_carlo(1.0, Branch::Open, &tolerances, 10, 1),
            overflow
        );
        // Three tolerances inside the range: analysed.
        let inside = FourBarTolerances::lengths(1e305);
        assert!(linkage.corners(1.0, Branch::Open, &inside).is_ok());
    }

    /// A coupler point at the crank pin (distance 0 ± t) is a linkage at either end of its
    /// tolerance: the point `t` from the pin along the coupler, or `t` the other way (a
    /// negative distance, which is the same point at the opposite angle), not half the box
    /// lost as linkages that cannot be built.
    #[test]
    fn a_coupler_point_at_the_crank_pin_moves_by_its_distance_tolerance() {
        let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
        let theta2 = 60f64.to_radians();
        let tolerances = FourBarTolerances {
            distance: 0.1,
            ..FourBarTolerances::default()
        };
        let corners = linkage.corners(theta2, Branch::Open, &tolerances).unwrap();
        assert_eq!((corners.assembled, corners.failed), (2, 0));
        assert!(
            (corners.coupler_point_largest - 0.1).abs() < 1e-12,
            "{corners:?}"
        );
        assert_eq!(corners.output_largest, 0.0);
        let sampled = linkage
            .monte_carlo(
                theta2,
                Branch::Open,
                &FourBarTolerances::lengths(0.1),
                1000,
                3,
            )
            .unwrap();
        assert_eq!((sampled.assembled, sampled.failed), (1000, 0));
    }

    /// A coupler point at the crank pin, off its angle from the coupler by 0.5 rad, with
    /// every length toleranced: each corner's point is the perturbed linkage's crank pin plus
    /// the signed distance along the coupler turned by 0.5 rad (a negative distance is the
    /// point turned by π, not by some other angle), and the worst corner is the farthest.
    #[test]
    fn a_negative_distance_turns_the_point_by_a_half_turn() {
        let (delta, t) = (0.5, 0.1);
        let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0)
            .and_then(|l| l.with_coupler_point(0.0, delta))
            .unwrap();
        let theta2: f64 = 1.0;
        let corners = linkage
            .corners(theta2, Branch::Open, &FourBarTolerances::lengths(t))
            .unwrap();
        assert_eq!((corners.assembled, corners.failed), (32, 0));
        let (s2, c2) = theta2.sin_cos();
        let nominal = Vec2 {
            x: 80.0 * c2,
            y: 80.0 * s2,
        };
        let mut farthest = 0.0f64;
        for corner in 0..32u32 {
            let e: [f64; 5] = core::array::from_fn(|p| if corner & (1 << p) != 0 { -t } else { t });
            let l = FourBar::new(180.0 + e[0], 80.0 + e[1], 200.0 + e[2], 150.0 + e[3]).unwrap();
            let q = l.assemble(theta2, Branch::Open).unwrap();
            let (s, c) = (q.theta3 + delta).sin_cos();
            let point = Vec2 {
                x: (80.0 + e[1]) * c2 + e[4] * c,
                y: (80.0 + e[1]) * s2 + e[4] * s,
            };
            farthest = farthest.max((point.x - nominal.x).hypot(point.y - nominal.y));
        }
        assert!(
            (corners.coupler_point_largest / farthest - 1.0).abs() < 1e-9,
            "{corners:?} {farthest}"
        );
    }

    /// The root mean squares neither overflow nor underflow: a point moved by about 1e-302
    /// on a linkage of 1e-300, and by 1e298 on one of 1e300, as on one of 1 scaled.
    #[test]
    fn root_mean_squares_hold_at_every_scale() {
        let tolerances = FourBarTolerances::lengths(0.01);
        let theta2 = 1.0;
        let at = |scale: f64| {
            let linkage = FourBar::new(1.8 * scale, 0.8 * scale, 2.0 * scale, 1.5 * scale)
                .and_then(|l| l.with_coupler_point(1.0 * scale, 0.5))
                .unwrap();
            let t = FourBarTolerances {
                ground: tolerances.ground * scale,
                crank: tolerances.crank * scale,
                coupler: tolerances.coupler * scale,
                rocker: tolerances.rocker * scale,
                distance: tolerances.distance * scale,
                angle: 0.0,
            };
            linkage
                .monte_carlo(theta2, Branch::Open, &t, 200, 5)
                .unwrap()
        };
        let one = at(1.0);
        for scale in [1e-300, 1e300] {
            let scaled = at(scale);
            let relative = |got: f64, want: f64| (got / want - 1.0).abs();
            assert!(
                relative(scaled.output_rms, one.output_rms) < 1e-9,
                "{scaled:?}"
            );
            assert!(
                relative(scaled.coupler_point_rms / scale, one.coupler_point_rms) < 1e-9,
                "{scaled:?} {one:?}"
            );
        }
        let mut squares = SumOfSquares::default();
        for x in [3e-200, 0.0, -4e-200] {
            squares.add(x);
        }
        assert!((squares.root_mean(2.0) / (12.5f64.sqrt() * 1e-200) - 1.0).abs() < 1e-15);
        assert_eq!(SumOfSquares::<f64>::default().root_mean(1.0), 0.0);
    }

    /// Found by mutation testing: Monte Carlo is the nonlinear model at the seeded draws,
    /// each dimension off by `t/3` times a standard normal deviate, six a sample in the
    /// parameters' order (drawn here again, and the linkages solved one by one); its root
    /// mean squares estimate the stack-ups over 3.
    #[test]
    fn monte_carlo_solves_the_seeded_draws() {
        let (linkage, theta2, branch) = near_pi();
        let tolerances = FourBarTolerances {
            ground: 0.2,
            crank: 0.1,
            coupler: 0.3,
            rocker: 0.1,
            distance: 0.2,
            angle: 1e-2,
        };
        let (samples, seed) = (2000, 7);
        let sampled = linkage
            .monte_carlo(theta2, branch, &tolerances, samples, seed)
            .unwrap();
        let q = linkage.assemble(theta2, branch).unwrap();
        let p = linkage.points(theta2, &q).unwrap().coupler_point;
        let [l1, l2, l3, l4] = linkage.lengths();
        let (a, delta) = linkage.coupler_point();
        let t = tolerances.as_array();
        let mut random = SplitMix64(seed);
        let (mut largest, mut squares, mut point_squares) = (0f64, 0.0, 0.0);
        for _ in 0..samples {
            let e: [f64; 6] = core::array::from_fn(|p| t[p] / 3.0 * random.normal::<f64>());
            let l = FourBar::new(l1 + e[0], l2 + e[1], l3 + e[2], l4 + e[3])
                .and_then(|l| l.with_coupler_point(a + e[4], delta + e[5]))
                .unwrap();
            let moved = l.assemble(theta2, branch).unwrap();
            let (sine, cosine) = (moved.theta4 - q.theta4).sin_cos();
            let change = sine.atan2(cosine);
            largest = largest.max(change.abs());
            squares += change * change;
            let point = l.points(theta2, &moved).unwrap().coupler_point;
            point_squares += (point - p).norm().powi(2);
        }
        let n = samples as f64;
        let near = |got: f64, want: f64| (got / want - 1.0).abs() < 1e-9;
        assert_eq!((sampled.assembled, sampled.failed), (samples, 0));
        assert!(near(sampled.output_largest, largest), "{sampled:?}");
        assert!(
            near(sampled.output_rms, (squares / n).sqrt()),
            "{sampled:?}"
        );
        assert!(near(sampled.coupler_point_rms, (point_squares / n).sqrt()));
        let first = linkage.tolerance(theta2, branch, &tolerances).unwrap();
        let estimate = |got: f64, rss: f64| (got / (rss / 3.0) - 1.0).abs() < 0.1;
        assert!(estimate(sampled.output_rms, first.output.root_sum_square));
        assert!(estimate(
            sampled.coupler_point_rms,
            first.coupler_point.root_sum_square
        ));
    }

    #[test]
    fn tolerances_are_taken_by_their_magnitude_and_must_be_finite() {
        let (linkage, theta2, branch) = near_pi();
        let plus = FourBarTolerances::lengths(0.1);
        let minus = FourBarTolerances::lengths(-0.1);
        assert_eq!(
            linkage.tolerance(theta2, branch, &minus),
            linkage.tolerance(theta2, branch, &plus)
        );
        let refused = Error::NonFinite {
            quantity: "tolerance",
        };
        for bad in [f64::NAN, f64::INFINITY] {
            let tolerances = FourBarTolerances { angle: bad, ..plus };
            assert_eq!(linkage.tolerance(theta2, branch, &tolerances), Err(refused));
            // The nonlinear models too (which built no linkage and said zero before).
            assert_eq!(linkage.corners(theta2, branch, &tolerances), Err(refused));
            assert_eq!(
                linkage.monte_carlo(theta2, branch, &tolerances, 10, 1),
                Err(refused)
            );
        }
        // Their magnitudes: the corners are the same either way.
        assert_eq!(
            linkage.corners(theta2, branch, &minus),
            linkage.corners(theta2, branch, &plus)
        );
    }

    /// Deviations beyond the largest float are refused, not returned infinite (found by an
    /// adversarial review): the largest tolerances on Example 1, and tolerances of 1e10 on
    /// Example 1 scaled to 1e-300.
    #[test]
    fn a_deviation_beyond_the_largest_float_is_refused() {
        let overflowed = Err(Error::NonFinite {
            quantity: "first-order deviation",
        });
        let example = FourBar::new(180.0, 80.0, 200.0, 150.0)
            .and_then(|l| l.with_coupler_point(100.0, 0.5))
            .unwrap();
        let largest = FourBarTolerances::lengths(f64::MAX);
        assert_eq!(example.tolerance(1.0, Branch::Open, &largest), overflowed);
        let tiny = FourBar::new(1.8e-300, 0.8e-300, 2e-300, 1.5e-300).unwrap();
        let huge = FourBarTolerances::lengths(1e10);
        assert_eq!(tiny.tolerance(1.0, Branch::Open, &huge), overflowed);
        // Scaled by 1e-302 with its tolerances, the angles' figures are Example 1's.
        let own = FourBarTolerances::lengths(1e-303);
        let got = tiny.tolerance(1.0, Branch::Open, &own).unwrap();
        let unit = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
        let want = unit
            .tolerance(1.0, Branch::Open, &FourBarTolerances::lengths(0.1))
            .unwrap();
        assert!((got.output.worst_case - want.output.worst_case).abs() < 1e-12);
    }
}
