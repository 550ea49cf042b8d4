//! The four-bar linkage.

use mechgen::grashof::{self, Class, Grashof, Inversion, normalised};
use mechgen::{Branch, Error, MechanicalAdvantage, Real, mechanism};

use crate::dimensions::{DimensionError, finite, non_negative, positive};
use crate::triangle::{Triangle, longer_first};

mechanism! {
    /// Four-bar linkage: ground `l1` from O2 = (0, 0) to O4 = (l1, 0), crank `l2` from O2 to
    /// A at the input `theta2`, coupler `l3` from A to B at `theta3`, rocker `l4` from O4 to B
    /// at `theta4`. The coupler point P sits at distance `a` from A, at angle `delta` from the
    /// coupler line A B.
    ///
    /// Loop: `l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0 = 0` (KINEMATICS.md).
    /// Build one with [`FourBar::new`], which checks the lengths.
    ///
    /// The generated [`assemble`](Self::assemble) places B where the circle of radius `l3`
    /// about A meets the circle of radius `l4` about O4. Its branches are told apart by
    /// `sin(θ4 − θ3)`: positive on the open branch (the coupler A→B lies counter-clockwise of
    /// the chord A→O4, and the rocker's direction O4→B is counter-clockwise of the coupler's),
    /// negative on the crossed one. The sign changes only where coupler and rocker line up, so
    /// a crank turning through a Grashof crank-rocker's full circle stays on its branch.
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// use mechgen::Branch;
    /// // The seeds' Example 1.
    /// let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0)?;
    /// let q = linkage.assemble(60f64.to_radians(), Branch::Open)?;
    /// assert!((q.theta4.to_degrees() - 72.1377).abs() < 1e-4);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct FourBar {
        params:
            /// Ground link O2 O4.
            l1,
            /// Crank O2 A.
            l2,
            /// Coupler A B.
            l3,
            /// Rocker O4 B.
            l4,
            /// Distance from A to the coupler point P.
            a,
            /// Angle of A P from the coupler line A B, in radians.
            delta: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        /// A, the crank pin.
        point crank_pin = l2 @ theta2;
        /// B, the rocker pin.
        point rocker_pin = l1 @ 0 + l4 @ theta4;
        /// P, the coupler point.
        point coupler_point = l2 @ theta2 + a @ (theta3 + delta);
        generate: position, velocity, acceleration, sensitivities;
        /// The coupler's and rocker's angles, rates and accelerations.
        scene angles: theta3, theta4, theta3_dot, theta4_dot, theta3_ddot, theta4_ddot;
        /// The moving joints' positions, A and B, as drawing the linkage needs.
        scene joints: crank_pin, rocker_pin;
        /// The coupler point's position alone, as drawing the coupler curve needs.
        scene coupler_path: coupler_point;
        /// The coupler point's position, velocity and acceleration.
        scene coupler_motion: coupler_point, coupler_point_dot, coupler_point_ddot;
    }
}

/// The transmission angle's extremes over the motion (see [`FourBar::transmission_extremes`]).
///
/// ```
/// use mechanisms::FourBar;
/// // Example 1's extremes: acos(0.875) at θ2 = 0 (Z = 100), acos(-0.085) at θ2 = π (Z = 260).
/// let extremes = FourBar::new(180.0, 80.0, 200.0, 150.0)?.transmission_extremes();
/// assert!((extremes.min - 0.875f64.acos()).abs() < 1e-12);
/// assert!((extremes.max - (-0.085f64).acos()).abs() < 1e-12);
/// # Ok::<(), mechanisms::DimensionError<f64>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TransmissionExtremes<T> {
    /// The smallest transmission angle, radians.
    pub min: T,
    /// An input angle in [0, π] where it occurs (also at its negative).
    pub min_at: T,
    /// The largest transmission angle, radians.
    pub max: T,
    /// An input angle in [0, π] where it occurs (also at its negative).
    pub max_at: T,
}

impl<T: Real> TransmissionExtremes<T> {
    /// Whether the transmission angle stays within the 40° to 140° guideline throughout.
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// // A long coupler and rocker keep γ near 90°.
    /// let extremes = FourBar::new(200.0, 40.0, 220.0, 210.0)?.transmission_extremes();
    /// assert!(extremes.within_guideline());
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn within_guideline(&self) -> bool {
        self.min >= T::constant(40f64.to_radians()) && self.max <= T::constant(140f64.to_radians())
    }
}

/// The input angles at which a crank that cannot turn fully stops (toggles), in (0, π); the
/// linkage is symmetric, so each also stops at the negative angle. See
/// [`FourBar::limit_angles`] for the rule at the ends, 0 and π.
///
/// ```
/// use mechanisms::FourBar;
/// // A rocker-crank whose crank meets both toggles: it rocks between them.
/// let limits = FourBar::new(180.0, 150.0, 200.0, 80.0)?.limit_angles();
/// let (folded, extended) = (limits.folded.unwrap(), limits.extended.unwrap());
/// assert!(folded < extended);
/// # Ok::<(), mechanisms::DimensionError<f64>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LimitAngles<T> {
    /// Where the coupler and rocker line up folded (`Z = |l3 − l4|`), if they can: the crank
    /// cannot come nearer to θ2 = 0 than this.
    pub folded: Option<T>,
    /// Where the coupler and rocker line up extended (`Z = l3 + l4`), if they can: the crank
    /// cannot come nearer to θ2 = π than this.
    pub extended: Option<T>,
}

impl<T: Real> LimitAngles<T> {
    /// Whether the crank turns fully (no toggle).
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// assert!(FourBar::new(180.0, 80.0, 200.0, 150.0)?.limit_angles().full_turn());
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn full_turn(&self) -> bool {
        self.folded.is_none() && self.extended.is_none()
    }

    /// Whether the linkage assembles at `theta2`: `|θ2|`, wrapped to [0, π], lies between the
    /// folded limit (or 0) and the extended limit (or π). Within [−π, π], `|θ2|` itself (so
    /// that each limit angle returned is reached: a wrapped angle may come back an ulp below
    /// it). Beyond, the wrapping is exact for any finite `theta2`, however large: it is
    /// `atan2(|sin θ2|, cos θ2)`, whose sine and cosine reduce `θ2` by π itself rather than
    /// by its rounded value (`θ2 % τ` with τ rounded is off by `θ2/τ` roundings of τ, 0.04
    /// rad at `θ2 = 1e15`). Not finite: false.
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// let limits = FourBar::new(180.0, 150.0, 200.0, 80.0)?.limit_angles();
    /// assert!(limits.reaches(1.0) && limits.reaches(-1.0));
    /// assert!(!limits.reaches(0.0) && !limits.reaches(std::f64::consts::PI));
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn reaches(&self, theta2: T) -> bool {
        if !theta2.is_finite() {
            return false;
        }
        let magnitude = if theta2.abs() <= T::constant(core::f64::consts::PI) {
            theta2.abs()
        } else {
            let (sine, cosine) = theta2.sin_cos();
            sine.abs().atan2(cosine)
        };
        self.folded.is_none_or(|f| magnitude >= f) && self.extended.is_none_or(|e| magnitude <= e)
    }

    /// Whether the crank can move through all of `angles` on one branch without the linkage
    /// being taken apart: each is reached, and, where the crank stops both short of θ2 = 0
    /// and short of π, all lie on the same side of the ground line. The crank then swings in
    /// `[folded, extended]` or in its mirror image, two separate circuits, and the branches
    /// change over at each end (coupler and rocker in line), so a linkage solved on one
    /// branch at angles on both sides could reach them only by being reassembled.
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// // A rocker-crank: the crank swings between 0.72 and 2.02 rad, or their negatives.
    /// let limits = FourBar::new(180.0, 150.0, 200.0, 80.0)?.limit_angles();
    /// assert!(limits.one_circuit(&[0.8, 1.4, 1.9]));
    /// assert!(!limits.one_circuit(&[0.8, 1.4, -1.4]));
    /// // A crank that turns fully reaches every angle on one circuit.
    /// let crank = FourBar::new(180.0, 80.0, 200.0, 150.0)?.limit_angles();
    /// assert!(crank.one_circuit(&[0.8, 1.4, -1.4]));
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn one_circuit(&self, angles: &[T]) -> bool {
        if !angles.iter().all(|&angle| self.reaches(angle)) {
            return false;
        }
        if self.folded.is_none() || self.extended.is_none() {
            return true;
        }
        // Reached with both limits, each angle's sine is nonzero.
        let above = |angle: T| angle.sin() > T::zero();
        angles.iter().all(|&a| above(a)) || !angles.iter().any(|&a| above(a))
    }
}

/// A position where the rocker stops while the crank turns on (crank and coupler in line),
/// see [`FourBar::dead_centres`].
///
/// ```
/// use mechanisms::FourBar;
/// use mechgen::Branch;
/// let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0)?;
/// let [extended, folded] = linkage.dead_centres(Branch::Open).unwrap();
/// // The rocker swings between the two.
/// assert!(folded.theta4 > extended.theta4);
/// # Ok::<(), mechanisms::DimensionError<f64>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeadCentre<T> {
    /// The crank angle θ2 there, radians.
    pub theta2: T,
    /// The rocker angle θ4 there, radians: one of the rocker's two extremes.
    pub theta4: T,
}

impl<T: Real> FourBar<T> {
    /// A four-bar with the coupler point at the crank pin A (see
    /// [`with_coupler_point`](Self::with_coupler_point)).
    ///
    /// Errors: a length that is not positive and finite, or lengths that do not make a
    /// mechanism: a link as long as the other three together or longer, to within rounding
    /// (8ε of the total length; the test's own rounding is under 3ε), which closes the loop
    /// only all in line at a single crank angle, or not at all. The error names that longest
    /// link. A linkage within [`grashof::default_tolerance`] (64ε) of flat but further than
    /// rounding from it is accepted: it moves, through a range of crank angles that rounding
    /// can tell apart, and [`grashof`](Self::grashof) classes it as
    /// [`Flat`](Class::Flat).
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// assert!(FourBar::new(180.0, 80.0, 200.0, 150.0).is_ok());
    /// assert!(FourBar::new(180.0, f64::NAN, 200.0, 150.0).is_err());
    /// assert_eq!(FourBar::new(500.0, 80.0, 200.0, 150.0).unwrap_err().name, "ground");
    /// // 6 = 1 + 3 + 2: the links close only flat, at θ2 = π.
    /// assert_eq!(FourBar::new(1.0, 3.0, 6.0, 2.0).unwrap_err().name, "coupler");
    /// ```
    pub fn new(ground: T, crank: T, coupler: T, rocker: T) -> Result<Self, DimensionError<T>> {
        let linkage = FourBar {
            l1: positive("ground", ground)?,
            l2: positive("crank", crank)?,
            l3: positive("coupler", coupler)?,
            l4: positive("rocker", rocker)?,
            a: T::zero(),
            delta: T::zero(),
        };
        // Z = |A − O4| ranges over [|l1 − l2|, l1 + l2]; B exists for Z in [|l3 − l4|, l3 + l4].
        // The two ranges share more than a point unless one link is as long as the other
        // three together.
        let rounding = T::constant(8.0) * T::epsilon();
        let class =
            grashof::classify_with_tolerance(ground, crank, coupler, rocker, rounding).class;
        if matches!(class, Class::Flat | Class::CannotClose) {
            let names = [
                ("ground", ground),
                ("crank", crank),
                ("coupler", coupler),
                ("rocker", rocker),
            ];
            let (name, value) =
                names.into_iter().fold(
                    names[0],
                    |longest, link| if link.1 > longest.1 { link } else { longest },
                );
            return Err(DimensionError {
                name,
                value,
                requirement: "shorter than the other three links together, so that the \
                              linkage assembles at some crank angle and moves",
            });
        }
        Ok(linkage)
    }

    /// The same linkage with its coupler point P at `distance` from the crank pin A, at
    /// `angle` (radians, counter-clockwise) from the coupler line A B.
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0)?.with_coupler_point(100.0, 0.5)?;
    /// assert_eq!(linkage.coupler_point(), (100.0, 0.5));
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn with_coupler_point(self, distance: T, angle: T) -> Result<Self, DimensionError<T>> {
        Ok(FourBar {
            a: non_negative("coupler point distance", distance)?,
            delta: finite("coupler point angle", angle)?,
            ..self
        })
    }

    /// The link lengths `[ground, crank, coupler, rocker]`.
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// assert_eq!(FourBar::new(180.0, 80.0, 200.0, 150.0)?.lengths(), [180.0, 80.0, 200.0, 150.0]);
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn lengths(&self) -> [T; 4] {
        [self.l1, self.l2, self.l3, self.l4]
    }

    /// The coupler point's `(distance from A, angle from A B)`; `(0, 0)` (the crank pin) unless
    /// set by [`with_coupler_point`](Self::with_coupler_point).
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// assert_eq!(FourBar::new(180.0, 80.0, 200.0, 150.0)?.coupler_point(), (0.0, 0.0));
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn coupler_point(&self) -> (T, T) {
        (self.a, self.delta)
    }

    /// Grashof's classification (`s + l` against `p + q`) with the ground `l1`, input `l2`,
    /// coupler `l3` and output `l4`; see [`mechgen::grashof`].
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// use mechgen::grashof::{Class, Inversion};
    /// let g = FourBar::new(180.0, 80.0, 200.0, 150.0)?.grashof();
    /// assert_eq!((g.class, g.inversion), (Class::Grashof, Inversion::CrankRocker));
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn grashof(&self) -> Grashof {
        grashof::classify(self.l1, self.l2, self.l3, self.l4)
    }

    /// The transmission angle γ between coupler and rocker at a position, in [0, π]: the
    /// interior angle at B of the triangle A B O4,
    /// `cos γ = (l3² + l4² − Z²)/(2·l3·l4)` with `Z = |A − O4|`, computed as
    /// `γ = atan2(|sin(θ4 − θ3)|, cos(θ4 − θ3))` (the accurate form of `acos(cos(θ4 − θ3))`).
    /// Force is transmitted best at 90°; keep it within 40° to 140°.
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// use mechgen::Branch;
    /// let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0)?;
    /// let q = linkage.assemble(60f64.to_radians(), Branch::Open)?;
    /// assert!((linkage.transmission_angle(&q).to_degrees() - 50.58).abs() < 0.005);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn transmission_angle(&self, position: &FourBarUnknowns<T>) -> T {
        let (sine, cosine) = (position.theta4 - position.theta3).sin_cos();
        sine.abs().atan2(cosine)
    }

    /// The smallest and largest transmission angles over the whole motion, and the crank
    /// angles where they occur. γ grows with `Z = |A − O4|`, and `Z² = l1² + l2² − 2·l1·l2·cos θ2`
    /// grows with `|θ2|`, so the extremes are at the ends of the reachable range: θ2 = 0 and π
    /// for a crank that turns fully, else the limit angles, where γ is exactly 0 (folded) or π
    /// (extended). Both branches share them. At θ2 = 0 and π, γ is the angle opposite
    /// `Z = |l1 ∓ l2|` in the triangle of sides `l3`, `l4`, `Z`, by Kahan's formula with each
    /// of its factors a sum of the four lengths rounded once: the given lengths' own γ to a
    /// few units of rounding, near 0 and π too (where `acos` of the cosine rule loses half
    /// the digits, and `Z` rounded first moved γ by far more).
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// let extremes = FourBar::new(180.0, 80.0, 200.0, 150.0)?.transmission_extremes();
    /// assert_eq!((extremes.min_at, extremes.max_at), (0.0, std::f64::consts::PI));
    /// assert!((extremes.min.to_degrees() - 28.955).abs() < 0.001); // acos(0.875)
    /// assert!(!extremes.within_guideline());
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn transmission_extremes(&self) -> TransmissionExtremes<T> {
        let limits = self.limit_angles();
        let pi = T::constant(core::f64::consts::PI);
        let [l1, l2, l3, l4] = self.lengths();
        let (longer, shorter) = longer_first(l1, l2);
        let (min, min_at) = match limits.folded {
            Some(at) => (T::zero(), at),
            None => (
                Triangle::with_third_side(l3, l4, [longer, -shorter]).angle(),
                T::zero(),
            ),
        };
        let (max, max_at) = match limits.extended {
            Some(at) => (pi, at),
            None => (Triangle::with_third_side(l3, l4, [l1, l2]).angle(), pi),
        };
        TransmissionExtremes {
            min,
            min_at,
            max,
            max_at,
        }
    }

    /// The crank angles where coupler and rocker line up, the toggles a crank that cannot turn
    /// fully stops at: `cos θ2 = (l1² + l2² − (l3 ± l4)²)/(2·l1·l2)`, `+` extended and `−`
    /// folded. A toggle exists where the right-hand side lies in (−1, 1); there the Jacobian
    /// is singular and just beyond it the loop cannot close. Each is computed as the angle at
    /// O2 of the triangle O2 O4 A with `|A O4| = l3 ± l4`, by Kahan's formula, on the lengths
    /// scaled by a power of two, at any scale, with each of its four factors
    /// (`Z ∓ |l1 − l2|`, `l1 + l2 ± Z`) a sum of the four lengths rounded once: the given
    /// lengths' own toggle to a few units of rounding, near 0 and π too, where a toggle moves
    /// fast with the lengths (`l3 ± l4` rounded first, a toggle came out 1.5e-5 rad off at a
    /// link ratio of 2e6, and one within rounding of an end on the wrong side of it).
    ///
    /// At the ends, `|l3 − l4| = |l1 − l2|` or `l3 + l4 = l1 + l2` (decided exactly), the
    /// links all line up at θ2 = 0 or π: a change point, which the crank passes through, so
    /// not a limit (`None`). (The lengths [`FourBar::new`] refuses, which close only flat,
    /// would give `folded = π` or `extended = 0`, reaching that one angle.) The exact rule
    /// can differ from [`grashof`](Self::grashof)'s, which calls sums within its tolerance
    /// (64ε of the total) equal: two lengths a unit of rounding off a change point have a
    /// toggle that close to 0 or π, which [`grashof`](Self::grashof) classes a change
    /// point.
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// // A kite whose crank meets the coupler and rocker in line at θ2 = 0 and π: a full turn.
    /// assert!(FourBar::new(100.0, 50.0, 50.0, 100.0)?.limit_angles().full_turn());
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// // Example 1 is a crank-rocker: no limits.
    /// assert!(FourBar::new(180.0, 80.0, 200.0, 150.0)?.limit_angles().full_turn());
    /// // A triple-rocker stops at θ2 = ±acos((100² + 120² − 170²)/(2·100·120)).
    /// let limits = FourBar::new(100.0, 120.0, 90.0, 80.0)?.limit_angles();
    /// let expected = ((100.0f64.powi(2) + 120.0f64.powi(2) - 170.0f64.powi(2)) / 24000.0).acos();
    /// assert!((limits.extended.unwrap() - expected).abs() < 1e-12);
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn limit_angles(&self) -> LimitAngles<T> {
        let [l1, l2, l3, l4] = self.lengths();
        let pi = T::constant(core::f64::consts::PI);
        // The triangle O2 O4 A with |A O4| = Z at each line-up of coupler and rocker; over
        // the crank's turn, from θ2 = 0 to π, Z runs from |l1 − l2| to l1 + l2.
        let (longer, shorter) = longer_first(l3, l4);
        let folded = Triangle::with_third_side(l1, l2, [longer, -shorter]);
        let extended = Triangle::with_third_side(l1, l2, [l3, l4]);
        LimitAngles {
            folded: if folded.within_difference() {
                None
            } else if folded.beyond_sum() {
                Some(pi)
            } else {
                Some(folded.angle())
            },
            extended: if extended.beyond_sum() {
                None
            } else if extended.within_difference() {
                Some(T::zero())
            } else {
                Some(extended.angle())
            },
        }
    }

    /// The dead-centre positions of a crank-rocker on `branch`: where crank and coupler line
    /// up, extended (`|O2 B| = l2 + l3`) and folded (`|O2 B| = l3 − l2`), and the rocker stops
    /// (`ω4 = 0`) at its two extremes. B is on the rocker's circle, so
    /// `cos θ4 = ((l3 ± l2)² − l1² − l4²)/(2·l1·l4)`, computed as the supplement of the angle at
    /// O4 of the triangle O2 O4 B by Kahan's formula, each factor a sum of the four lengths
    /// rounded once (the given lengths' own to a few units of rounding, at any scale).
    ///
    /// `None` unless the linkage is a class I (Grashof) crank-rocker. A change-point
    /// (class III) crank-rocker passes one of its two crank-and-coupler line-ups with all four
    /// links in line, where the branches meet: a change point, where the rocker's rate is not
    /// determined by the crank's, not a dead centre. For a kite with crank = coupler that
    /// line-up is B on O2, the fold onto the kite's degenerate branch.
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// use mechgen::Branch;
    /// let linkage = FourBar::new(180.0_f64, 80.0, 200.0, 150.0)?;
    /// let [extended, folded] = linkage.dead_centres(Branch::Open).unwrap();
    /// let q = linkage.assemble(extended.theta2, Branch::Open)?;
    /// let rates = linkage.velocity(extended.theta2, &q, 1.0)?;
    /// assert!(rates.theta4.abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn dead_centres(&self, branch: Branch) -> Option<[DeadCentre<T>; 2]> {
        let g = self.grashof();
        if (g.class, g.inversion) != (Class::Grashof, Inversion::CrankRocker) {
            return None;
        }
        let pi = T::constant(core::f64::consts::PI);
        // The same angles on the linkage scaled by a power of two, where nothing overflows.
        let [l1, l2, l3, l4] = normalised(self.lengths());
        let unit = FourBar {
            l1,
            l2,
            l3,
            l4,
            a: T::zero(),
            delta: T::zero(),
        };
        let at_reach = |reach: [T; 2], folded: bool| {
            let magnitude = pi - Triangle::with_third_side(l1, l4, reach).angle();
            // Of B's two places on the rocker circle, take the one on `branch`.
            [magnitude, -magnitude].into_iter().find_map(|theta4| {
                let (sine, cosine) = theta4.sin_cos();
                let theta3 = (l4 * sine).atan2(l1 + l4 * cosine);
                let theta2 = if folded { theta3 + pi } else { theta3 };
                let position = FourBarUnknowns { theta3, theta4 };
                (unit.branch_of(theta2, &position) == branch)
                    .then_some(DeadCentre { theta2, theta4 })
            })
        };
        Some([at_reach([l3, l2], false)?, at_reach([l3, -l2], true)?])
    }

    /// The ideal mechanical advantage at a position, rocker torque over crank torque:
    /// `MA = T4/T2 = ω2/ω4`, from the generated velocity. Unbounded at a dead centre
    /// (`ω4 = 0` to rounding, `|ω4| ≤ 4ε·|ω2|`); at a dead centre's crank angle as rounded
    /// (as [`dead_centres`](Self::dead_centres) returns it), `ω4` may exceed that by the
    /// angle's own rounding, and the advantage comes out finite, some `1/ε`.
    ///
    /// Errors: as [`velocity`](Self::velocity) (a toggle, where the crank cannot drive).
    ///
    /// ```
    /// use mechanisms::FourBar;
    /// use mechgen::{Branch, MechanicalAdvantage};
    /// let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0)?;
    /// let theta2 = 60f64.to_radians();
    /// let q = linkage.assemble(theta2, Branch::Open)?;
    /// let omega4 = linkage.velocity(theta2, &q, 1.0)?.theta4;
    /// assert_eq!(linkage.mechanical_advantage(theta2, &q)?, MechanicalAdvantage::Finite(1.0 / omega4));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn mechanical_advantage(
        &self,
        theta2: T,
        position: &FourBarUnknowns<T>,
    ) -> Result<MechanicalAdvantage<T>, Error<T>> {
        let rates = self.velocity(theta2, position, T::one())?;
        MechanicalAdvantage::from_rates(T::one(), rates.theta4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::PI;

    /// Found by the 256-bit line-up tests (`tests/tests/line_ups.rs`): coupler and rocker of a
    /// linkage of some 1e118 line up folded at θ2 = 3.133925321533377898 (mpmath, 600 bits),
    /// where `|l3 − l4|` rounded first put the toggle at 3.1339253215336904, 450 units of
    /// rounding off.
    #[test]
    fn a_toggle_near_pi_is_the_given_lengths_own() {
        let linkage = FourBar::<f64>::new(
            4.179822725055393e118,
            1.450662756356314e117,
            7.769460372713525e117,
            5.101830916930383e118,
        )
        .unwrap();
        let folded = linkage.limit_angles().folded.unwrap();
        assert!((folded - 3.133_925_321_533_377_9).abs() <= 4.0 * f64::EPSILON * PI);
    }

    /// `l3 + l4 = 1.5 − 2⁻⁷⁰` against `l1 + l2 = 1.5`: coupler and rocker line up extended
    /// 7.128953417946986e-11 rad short of π (mpmath), a limit, where `l3 + l4` rounded to 1.5
    /// made it a change point the crank passes. The angle is the exact sum's too:
    /// 3.141592653518503704.
    #[test]
    fn a_toggle_a_rounding_short_of_a_change_point_is_a_limit() {
        let (l3, l4) = (1.5 - 2f64.powi(-20), 2f64.powi(-20) - 2f64.powi(-70));
        assert_eq!(l3 + l4, 1.5);
        let limits = FourBar::new(1.0, 0.5, l3, l4).unwrap().limit_angles();
        let extended = limits.extended.unwrap();
        assert!((extended - 3.141_592_653_518_504).abs() <= 4.0 * f64::EPSILON * PI);
        // At the change point itself, none.
        let passes = FourBar::new(1.0, 0.5, l3, 2f64.powi(-20)).unwrap();
        assert_eq!(passes.limit_angles().extended, None);
    }

    /// Each limit angle `limit_angles` returns is reached, and so is its negative (an
    /// adversarial review found 5% of them not: `atan2(|sin θ|, cos θ)` came back an ulp
    /// below the limit): the reviewer's f64 and f32 linkages, and an ulp beyond a limit is not.
    /// A crank stopped on one side only swings through 0 or through π: one circuit, however
    /// its angles lie about the ground line; stopped on both sides, only angles on one side
    /// of it are.
    #[test]
    fn a_crank_stopped_on_one_side_only_swings_through_on_one_circuit() {
        // Triple rockers: stopped short of π (through 0), and short of 0 (through π).
        let through_zero = FourBar::new(100.0, 120.0, 90.0, 80.0)
            .unwrap()
            .limit_angles();
        assert!(through_zero.folded.is_none() && through_zero.extended.is_some());
        assert!(through_zero.one_circuit(&[0.5, -0.5, 0.0]));
        let through_pi = FourBar::new(100.0, 40.0, 200.0, 100.0)
            .unwrap()
            .limit_angles();
        assert!(through_pi.folded.is_some() && through_pi.extended.is_none());
        assert!(through_pi.one_circuit(&[3.0, -3.0, PI]));
        // A rocker-crank, stopped on both sides.
        let both = FourBar::new(180.0, 150.0, 200.0, 80.0)
            .unwrap()
            .limit_angles();
        assert!(both.one_circuit(&[-0.8, -1.4]));
        assert!(!both.one_circuit(&[-0.8, 1.4]));
        // An angle not reached is on no circuit; none at all are on one.
        assert!(!both.one_circuit(&[0.0]));
        assert!(both.one_circuit(&[]));
    }

    #[test]
    fn every_limit_returned_is_reached() {
        let double = FourBar::new(
            0.796364489945875f64,
            0.20712010676194054,
            1.944736181337953,
            2.533980564521892,
        )
        .unwrap()
        .limit_angles();
        let folded = double.folded.unwrap();
        assert!(double.reaches(folded) && double.reaches(-folded));
        assert!(!double.reaches(folded.next_down()));
        let single = FourBar::new(0.7650594f32, 0.70408976, 1.9480811, 1.4051217)
            .unwrap()
            .limit_angles();
        for limit in [single.folded, single.extended].into_iter().flatten() {
            assert!(single.reaches(limit) && single.reaches(-limit), "{limit}");
        }
    }

    /// Found by mutation testing: on either branch, each dead centre is a position the
    /// linkage assembles in, with the rocker's angle as `assemble` gives it (in (−π, π]),
    /// the rocker at rest, and the crank and coupler in line: `θ2 = θ3` extended,
    /// `θ2 = θ3 + π` folded. Example 1's rocker angles there, from the cosine rule:
    /// `cos θ4 = ((l3 ± l2)² − l1² − l4²)/(2·l1·l4)`, 23500/54000 and −40500/54000.
    #[test]
    fn dead_centres_on_both_branches_line_up_crank_and_coupler() {
        let linkage = FourBar::new(180.0f64, 80.0, 200.0, 150.0).unwrap();
        let pi = core::f64::consts::PI;
        for branch in [Branch::Open, Branch::Crossed] {
            let centres = linkage.dead_centres(branch).unwrap();
            for (centre, cosine, turn) in [
                (centres[0], 23500.0 / 54000.0, 0.0),
                (centres[1], -40500.0 / 54000.0, pi),
            ] {
                assert!((centre.theta4.cos() - cosine).abs() < 1e-12, "{centre:?}");
                let q = linkage.assemble(centre.theta2, branch).unwrap();
                assert!((q.theta4 - centre.theta4).abs() < 1e-12, "{centre:?} {q:?}");
                assert!((centre.theta2 - (q.theta3 + turn)).abs() < 1e-12, "{q:?}");
                let omega4 = linkage.velocity(centre.theta2, &q, 1.0).unwrap().theta4;
                assert!(omega4.abs() < 1e-12, "{omega4}");
            }
        }
    }
}
