//! The slider-crank, with offset.

use mechgen::grashof::normalised;
use mechgen::{Error, MechanicalAdvantage, Real, mechanism};

use crate::dimensions::{DimensionError, finite, non_negative, positive};
use crate::sums;
use crate::triangle::root_of_product;

mechanism! {
    /// Slider-crank with offset: crank `l2` from O2 = (0, 0) to the crank pin A at the input
    /// `theta2`; connecting rod `l3` from A to the slider pin B at `theta3`; B slides on the
    /// line `y = c`, at `x = d`. A coupler point P on the rod sits at distance `a` from A, at
    /// angle `delta` from the rod line A B.
    ///
    /// Loop: `l2 @ theta2 + l3 @ theta3 - c @ pi / 2 - d @ 0 = 0` (KINEMATICS.md).
    /// Build one with [`SliderCrank::new`], which checks the dimensions.
    ///
    /// The generated [`assemble`](Self::assemble) places B where the circle of radius `l3`
    /// about A meets the slider line, so `sin θ3 = (c − l2·sin θ2)/l3` and
    /// `d = l2·cos θ2 + l3·cos θ3`. Its branches are told apart by `cos θ3`: positive on the
    /// open branch (the slider pin B is on the +x side of the crank pin A), negative on the
    /// crossed one.
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// use mechgen::Branch;
    /// let linkage = SliderCrank::new(50.0, 150.0, 20.0)?;
    /// let q = linkage.assemble(0.0, Branch::Open)?;
    /// assert!((q.d - (150.0f64.powi(2) - 20.0f64.powi(2)).sqrt() - 50.0).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct SliderCrank {
        params:
            /// Crank O2 A.
            l2,
            /// Connecting rod A B.
            l3,
            /// Offset of the slider's line from O2, along +y.
            c,
            /// Distance from A to the coupler point P.
            a,
            /// Angle of A P from the rod line A B, in radians.
            delta: angle;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - c @ pi / 2 - d @ 0;
        /// A, the crank pin.
        point crank_pin = l2 @ theta2;
        /// B, the slider pin.
        point slider_pin = d @ 0 + c @ pi / 2;
        /// P, the coupler point on the rod.
        point coupler_point = l2 @ theta2 + a @ (theta3 + delta);
        generate: position, velocity, acceleration;
        /// The coupler's angle and the slider's position, with their rates and accelerations.
        scene state: theta3, d, theta3_dot, d_dot, theta3_ddot, d_ddot;
        /// The slider's position, velocity and acceleration alone (a piston's motion).
        scene slider: d, d_dot, d_ddot;
    }
}

impl<T: Real> SliderCrank<T> {
    /// A slider-crank with the coupler point at the crank pin A.
    ///
    /// Errors: a crank or rod that is not positive and finite, a non-finite offset, or a rod
    /// too short to reach the slider line from anywhere (`l2 + l3 < |c|`).
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// assert!(SliderCrank::new(50.0, 150.0, -20.0).is_ok());
    /// assert_eq!(SliderCrank::new(50.0, 0.0, 20.0).unwrap_err().name, "rod");
    /// ```
    pub fn new(crank: T, rod: T, offset: T) -> Result<Self, DimensionError<T>> {
        let linkage = SliderCrank {
            l2: positive("crank", crank)?,
            l3: positive("rod", rod)?,
            c: finite("offset", offset)?,
            a: T::zero(),
            delta: T::zero(),
        };
        if crank + rod < offset.abs() {
            return Err(DimensionError {
                name: "offset",
                value: offset,
                requirement: "within crank + rod of the crank pivot, so the slider can be reached",
            });
        }
        Ok(linkage)
    }

    /// The same linkage with its coupler point P at `distance` from A, at `angle` (radians)
    /// from the rod line A B.
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// let linkage = SliderCrank::new(50.0, 150.0, 20.0)?.with_coupler_point(75.0, 0.0)?;
    /// assert_eq!(linkage.coupler_point(), (75.0, 0.0));
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn with_coupler_point(self, distance: T, angle: T) -> Result<Self, DimensionError<T>> {
        Ok(SliderCrank {
            a: non_negative("coupler point distance", distance)?,
            delta: finite("coupler point angle", angle)?,
            ..self
        })
    }

    /// `[crank, rod, offset]`.
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// assert_eq!(SliderCrank::new(50.0, 150.0, 20.0)?.dimensions(), [50.0, 150.0, 20.0]);
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn dimensions(&self) -> [T; 3] {
        [self.l2, self.l3, self.c]
    }

    /// The coupler point's `(distance from A, angle from A B)`; `(0, 0)` (the crank pin) unless
    /// set by [`with_coupler_point`](Self::with_coupler_point).
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// assert_eq!(SliderCrank::new(50.0, 150.0, 20.0)?.coupler_point(), (0.0, 0.0));
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn coupler_point(&self) -> (T, T) {
        (self.a, self.delta)
    }

    /// The transmission angle μ at a position: the complement of the pressure angle between
    /// the rod (the line of the force on the slider) and the slider's direction of travel,
    /// `μ = acos(|sin θ3|)`, in [0, π/2], computed as `atan2(|cos θ3|, |sin θ3|)` (accurate
    /// near 0, where `acos` loses half the digits). 90° is ideal (the rod pushes along the
    /// slide).
    ///
    /// ```
    /// use mechanisms::{SliderCrank, SliderCrankUnknowns};
    /// let linkage = SliderCrank::new(50.0, 150.0, 0.0)?;
    /// let inline = SliderCrankUnknowns { theta3: 0.0, d: 200.0 };
    /// assert_eq!(linkage.transmission_angle(&inline), std::f64::consts::FRAC_PI_2);
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn transmission_angle(&self, position: &SliderCrankUnknowns<T>) -> T {
        let (sine, cosine) = position.theta3.sin_cos();
        cosine.abs().atan2(sine.abs())
    }

    /// Whether the crank turns fully: the rod reaches the slider line from every crank
    /// position, `l3 − l2 ≥ |c|` (decided exactly, not on `l3 − l2` as rounded, which a rod
    /// long against its crank rounds to the rod). At `l3 − l2 = |c|` it reaches it just, standing
    /// perpendicular to the slide at one crank angle, where the two branches meet (a change
    /// point); with no offset that is a rod equal to the crank, whose slider pin passes
    /// through the crank pivot O2.
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// assert!(SliderCrank::new(50.0, 150.0, 100.0)?.crank_turns_fully());
    /// assert!(SliderCrank::new(50.0, 50.0, 0.0)?.crank_turns_fully());
    /// assert!(!SliderCrank::new(50.0, 150.0, 101.0)?.crank_turns_fully());
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn crank_turns_fully(&self) -> bool {
        let [l2, l3, c] = normalised([self.l2, self.l3, self.c]);
        sums::sum([l3, -l2, -c.abs(), T::zero()]) >= T::zero()
    }

    /// The slider's stroke for a crank that turns fully: the distance between its extreme
    /// positions on a branch, where crank and rod line up extended (`|O2 B| = l2 + l3`) and
    /// folded (`|O2 B| = l3 − l2`): `√((l2 + l3)² − c²) − √((l3 − l2)² − c²)`, computed as
    /// `4·l2·l3 / (√((l2 + l3)² − c²) + √((l3 − l2)² − c²))` (the same, without the
    /// difference, which a crank short against the rod cancels to nothing: a crank of 1e-17
    /// on a rod of 1 had a stroke of 0), each root as `√((r − |c|)·(r + |c|))` with each
    /// factor a sum of the dimensions rounded once, on the
    /// dimensions scaled by a power of two (no square overflows). `None` if the crank cannot
    /// turn fully, or if the stroke is too long for `T`.
    ///
    /// At `l3 − l2 = |c|` the folded end is the change point where the rod stands
    /// perpendicular to the slide: the slider reaches it with its velocity jumping rather than
    /// passing through zero, so it is an end of the stroke but not a dead centre.
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// // Without offset the stroke is twice the crank.
    /// assert_eq!(SliderCrank::new(50.0, 150.0, 0.0)?.stroke(), Some(100.0));
    /// // A rod equal to the crank: the slider pin runs from 2·l2 to the crank pivot.
    /// assert_eq!(SliderCrank::new(50.0, 50.0, 0.0)?.stroke(), Some(100.0));
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn stroke(&self) -> Option<T> {
        if !self.crank_turns_fully() {
            return None;
        }
        let [l2, l3, c] = normalised([self.l2, self.l3, self.c]);
        // (a − b) = (a² − b²)/(a + b), and a² − b² = 4·l2·l3 exactly.
        let unit = T::constant(4.0) * l2 * l3 / (line_up(l3, l2, c) + line_up(l3, -l2, c));
        // Back to scale: the largest dimension over the largest scaled one is the power of two.
        let largest = |values: [T; 3]| values.iter().fold(T::zero(), |m, v| m.max(v.abs()));
        let scale = largest([self.l2, self.l3, self.c]) / largest([l2, l3, c]);
        let stroke = unit * scale;
        stroke.is_finite().then_some(stroke)
    }

    /// The crank angles at the dead centres on the open branch, `[outer, inner]`: where crank
    /// and rod line up extended, `θ2 = asin(c/(l2 + l3))`, and folded,
    /// `θ2 = π + asin(c/(l3 − l2))`, each arc sine computed as
    /// `atan2(c, √((r − |c|)·(r + |c|)))`, each factor a sum of the dimensions rounded once
    /// (the given dimensions' own angle to a few units of rounding, near ±π/2 too). There the
    /// slider stops (`ḋ = 0`).
    ///
    /// `None` unless `l3 − l2 > |c|` (decided exactly): if the crank
    /// cannot turn fully, and also at
    /// `l3 − l2 = |c|`, where the folded line-up puts the rod perpendicular to the slide, at
    /// the change point where the two branches meet rather than at a dead centre (a rod equal
    /// to the crank with no offset passes its slider pin through O2 there, at θ2 = ±π/2).
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// use mechgen::Branch;
    /// let linkage = SliderCrank::new(50.0_f64, 150.0, 20.0)?;
    /// for theta2 in linkage.dead_centres().unwrap() {
    ///     let q = linkage.assemble(theta2, Branch::Open)?;
    ///     assert!(linkage.velocity(theta2, &q, 1.0)?.d.abs() < 1e-12);
    /// }
    /// assert_eq!(SliderCrank::new(50.0, 50.0, 0.0)?.dead_centres(), None);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn dead_centres(&self) -> Option<[T; 2]> {
        let [l2, l3, c] = normalised([self.l2, self.l3, self.c]);
        if sums::sum([l3, -l2, -c.abs(), T::zero()]) <= T::zero() {
            return None;
        }
        let pi = T::constant(core::f64::consts::PI);
        Some([
            c.atan2(line_up(l3, l2, c)),
            pi + c.atan2(line_up(l3, -l2, c)),
        ])
    }

    /// The time ratio of an offset slider-crank with a crank turning counter-clockwise at
    /// constant speed: the crank angle of the inward stroke (outer to inner dead centre,
    /// `α = θ_inner − θ_outer`) over that of the outward stroke (`β = 2π − α`). 1 without
    /// offset; above 1 when the inward stroke is the slower (`c > 0`). `None` where
    /// [`dead_centres`](Self::dead_centres) is: if the crank cannot turn fully, or if the
    /// folded line-up is a change point (`l3 − l2 = |c|`), where the slider passes an end of
    /// its stroke without the dwell the ratio measures to.
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// assert_eq!(SliderCrank::new(50.0, 150.0, 0.0)?.time_ratio(), Some(1.0));
    /// assert!(SliderCrank::new(50.0, 150.0, 40.0)?.time_ratio().unwrap() > 1.0);
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn time_ratio(&self) -> Option<T> {
        let [outer, inner] = self.dead_centres()?;
        let inward = inner - outer;
        let tau = T::constant(core::f64::consts::TAU);
        Some(inward / (tau - inward))
    }

    /// The ideal mechanical advantage at a position, slider force over crank torque:
    /// `F/T2 = ω2/ḋ` (per unit length), from the generated velocity. Unbounded at a dead
    /// centre (`ḋ = 0` to rounding of the size times `ω2`: a slider's speed is a length's,
    /// compared with the linkage's, so that a slider-crank of 1e-300 has its finite
    /// advantage of some 1e300 per unit length, not "unbounded").
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// use mechgen::{Branch, MechanicalAdvantage};
    /// let linkage = SliderCrank::new(50.0, 150.0, 0.0)?;
    /// let q = linkage.assemble(0.0, Branch::Open)?;
    /// assert_eq!(linkage.mechanical_advantage(0.0, &q)?, MechanicalAdvantage::Unbounded);
    /// // The same linkage 1e-302 times the size: an advantage 1e302 times larger.
    /// let tiny = SliderCrank::new(50e-302f64, 150e-302, 0.0)?;
    /// let (ordinary, small) = (linkage.assemble(1.0, Branch::Open)?, tiny.assemble(1.0, Branch::Open)?);
    /// let [a, b] = [
    ///     linkage.mechanical_advantage(1.0, &ordinary)?.finite().unwrap(),
    ///     tiny.mechanical_advantage(1.0, &small)?.finite().unwrap(),
    /// ];
    /// assert!((b / a / 1e302 - 1.0).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn mechanical_advantage(
        &self,
        theta2: T,
        position: &SliderCrankUnknowns<T>,
    ) -> Result<MechanicalAdvantage<T>, Error<T>> {
        let rates = self.velocity(theta2, position, T::one())?;
        // `size/ḋ`, whose test of a stationary output is against the size, then per unit
        // length again.
        let size = self.l2.abs() + self.l3.abs() + self.c.abs();
        Ok(match MechanicalAdvantage::from_rates(size, rates.d)? {
            MechanicalAdvantage::Finite(ratio) => {
                let per_length = ratio / size;
                if per_length.is_finite() {
                    MechanicalAdvantage::Finite(per_length)
                } else {
                    MechanicalAdvantage::Unbounded
                }
            }
            unbounded => unbounded,
        })
    }
}

/// Where crank and rod line up with `|O2 B| = l3 + l2` (`l2` negative for `l3 − l2`), B's
/// distance along the slide from the foot of the perpendicular from O2:
/// `√((|O2 B| − |c|)·(|O2 B| + |c|))`, each factor a sum of the dimensions rounded once (see
/// [`sums`]), so that it is the given dimensions' own where it is near zero; 0 where
/// `|O2 B| ≤ |c|`. On dimensions scaled by a power of two.
fn line_up<T: Real>(l3: T, l2: T, c: T) -> T {
    let c = c.abs();
    let beyond = sums::sum([l3, l2, -c, T::zero()]).max(T::zero());
    root_of_product(beyond, sums::sum([l3, l2, c, T::zero()]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::PI;

    /// Found by the 256-bit line-up tests (`tests/tests/line_ups.rs`): the inner dead centre
    /// at 1.570796355408629650 (mpmath, 600 bits), where `l3 − l2` rounded first put it at
    /// 1.5707963551513395, 2.6e-10 rad off.
    #[test]
    fn a_dead_centre_near_the_change_point_is_the_given_dimensions_own() {
        let linkage = SliderCrank::<f64>::new(
            4.006151271658382e-173,
            6.899845205046262e-171,
            -6.859783692329676e-171,
        )
        .unwrap();
        let [outer, inner] = linkage.dead_centres().unwrap();
        assert!((inner - 1.570_796_355_408_629_6).abs() <= 4.0 * f64::EPSILON * PI);
        assert!((outer + 1.418_694_098_894_706_3).abs() <= 4.0 * f64::EPSILON * 1.42);
    }

    /// A rod `2⁻⁷⁰` too short for a full turn (`l3 − l2 = |c| − 2⁻⁷⁰`), which `l3 − l2` rounded
    /// to `|c|` took for one: no full turn, no stroke, no dead centres; `2⁻⁷⁰` longer, all
    /// three.
    #[test]
    fn a_full_turn_is_decided_exactly() {
        let (rod, offset) = (1.0, 1.0 - 2f64.powi(-20));
        let crank = 2f64.powi(-20) + 2f64.powi(-70);
        assert_eq!(rod - crank, offset);
        let short = SliderCrank::new(crank, rod, offset).unwrap();
        assert!(!short.crank_turns_fully());
        assert_eq!((short.stroke(), short.dead_centres()), (None, None));
        let long = SliderCrank::new(2f64.powi(-20) - 2f64.powi(-70), rod, -offset).unwrap();
        assert!(long.crank_turns_fully());
        assert!(long.stroke().is_some() && long.dead_centres().is_some());
    }

    /// Found by mutation testing: the coupler point's angle is kept, not only its distance.
    #[test]
    fn a_coupler_point_keeps_its_distance_and_angle() {
        let linkage = SliderCrank::new(50.0, 150.0, 20.0)
            .and_then(|l| l.with_coupler_point(75.0, 0.3))
            .unwrap();
        assert_eq!(linkage.coupler_point(), (75.0, 0.3));
        assert_eq!(linkage.dimensions(), [50.0, 150.0, 20.0]);
    }

    /// Found by mutation testing: with an offset, the stroke is
    /// `√((l2 + l3)² − c²) − √((l3 − l2)² − c²)`, here `√39600 − √9600` (mpmath at 40 digits:
    /// 101.0178977099968670190046), whichever side of the slide the offset is on.
    #[test]
    fn the_stroke_of_an_offset_slider_crank_on_either_side() {
        for offset in [20.0, -20.0] {
            let stroke = SliderCrank::new(50.0f64, 150.0, offset)
                .unwrap()
                .stroke()
                .unwrap();
            assert!((stroke - 101.017_897_709_996_87).abs() < 1e-12, "{stroke}");
        }
    }

    /// A crank short against its rod: the stroke to its last digits (as a difference of the
    /// two roots it cancelled to nothing: 0 for a crank of 1e-17, 3.7e-5 off for 1e-12).
    /// References: `2·l2` without offset; 256-bit evaluations with an offset of 0.5.
    #[test]
    fn a_short_crank_s_stroke_keeps_its_digits() {
        let relative = |got: f64, want: f64| ((got - want) / want).abs();
        let stroke = |l2: f64, c: f64| SliderCrank::new(l2, 1.0, c).unwrap().stroke().unwrap();
        assert_eq!(stroke(1e-17, 0.0), 2e-17);
        assert!(relative(stroke(1e-17, 0.5), 2.309_401_076_758_503e-17) < 4.0 * f64::EPSILON);
        assert!(relative(stroke(1e-12, 0.5), 2.309_401_076_758_503e-12) < 4.0 * f64::EPSILON);
        let single = SliderCrank::new(1e-8f32, 1.0, 0.0)
            .unwrap()
            .stroke()
            .unwrap();
        assert_eq!(single, 2e-8);
    }

    /// The dead centres `asin(c/(l2 + l3))` and `π + asin(c/(l3 − l2))`, and the time ratio
    /// `α/(2π − α)` with `α` their difference, for an offset of 40 (mpmath at 40 digits:
    /// 0.2013579207903307914551, 3.553109499657281257847 and 1.143383030117571110018).
    #[test]
    fn dead_centres_and_time_ratio_of_an_offset_slider_crank() {
        let linkage = SliderCrank::new(50.0f64, 150.0, 40.0).unwrap();
        let [outer, inner] = linkage.dead_centres().unwrap();
        assert!((outer - 0.201_357_920_790_330_8).abs() < 1e-15, "{outer}");
        assert!((inner - 3.553_109_499_657_281_3).abs() < 1e-14, "{inner}");
        let ratio = linkage.time_ratio().unwrap();
        assert!((ratio - 1.143_383_030_117_571_1).abs() < 1e-14, "{ratio}");
    }
}
