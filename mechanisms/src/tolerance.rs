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
    /// otherwise.
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
        let t = tolerances.as_array();
        if t.iter().any(|t| !t.is_finite()) {
            return Err(Error::NonFinite {
                quantity: "tolerance",
            });
        }
        let t = t.map(T::abs);
        let q = self.assemble(theta2, branch)?;
        let s = self.sensitivities(theta2, &q)?;
        let p = self.point_sensitivities(theta2, &q)?;
        let output = per_parameter(&s).map(|u| u.theta4);
        let point = per_parameter(&p).map(|points| points.coupler_point);
        Ok(FourBarDeviations {
            output: angle_deviation(&output, &t),
            coupler_point: point_deviation(&point, &t),
        })
    }
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
        let t = tolerances.as_array();
        let (indices, count) = varied(&t);
        let mut sampled = Accumulated::new(self, theta2, branch)?;
        for corner in 0..(1u32 << count) {
            let mut errors = [T::zero(); 6];
            for (bit, &p) in indices[..count].iter().enumerate() {
                errors[p] = if corner & (1 << bit) != 0 {
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
        let t = tolerances.as_array();
        let mut random = SplitMix64(seed);
        let mut sampled = Accumulated::new(self, theta2, branch)?;
        for _ in 0..samples {
            let errors = t.map(|t| t / T::constant(3.0) * random.normal::<T>());
            sampled.add(self, theta2, branch, errors);
        }
        Ok(sampled.finish())
    }

    /// This linkage with its dimensions (`l1`, `l2`, `l3`, `l4`, `a`, `delta`) moved by
    /// `errors`, if they still make one.
    fn perturbed(&self, errors: [T; 6]) -> Option<Self> {
        let (a, delta) = self.coupler_point();
        let [l1, l2, l3, l4] = self.lengths();
        FourBar::new(
            l1 + errors[0],
            l2 + errors[1],
            l3 + errors[2],
            l4 + errors[3],
        )
        .and_then(|l| l.with_coupler_point(a + errors[4], delta + errors[5]))
        .ok()
    }
}

/// Running sums of [`Sampled`]'s deviations from the nominal linkage's.
struct Accumulated<T> {
    theta4: T,
    point: Vec2<T>,
    sampled: Sampled<T>,
    output_squares: T,
    point_squares: T,
}

impl<T: Real> Accumulated<T> {
    fn new(nominal: &FourBar<T>, theta2: T, branch: Branch) -> Result<Self, Error<T>> {
        let q = nominal.assemble(theta2, branch)?;
        let point = nominal.points(theta2, &q)?.coupler_point;
        Ok(Accumulated {
            theta4: q.theta4,
            point,
            sampled: Sampled::default(),
            output_squares: T::zero(),
            point_squares: T::zero(),
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
        self.output_squares = self.output_squares + output * output;
        self.point_squares = self.point_squares + moved * moved;
    }

    fn finish(self) -> Sampled<T> {
        let n = T::from(self.sampled.assembled.max(1)).unwrap_or_else(T::one);
        Sampled {
            output_rms: (self.output_squares / n).sqrt(),
            coupler_point_rms: (self.point_squares / n).sqrt(),
            ..self.sampled
        }
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
                if p > 0 && corner & (1 << (p - 1)) != 0 {
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
