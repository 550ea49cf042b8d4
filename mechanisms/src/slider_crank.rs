//! The slider-crank, with offset.

use mechgen::{Error, MechanicalAdvantage, Real, mechanism};

use crate::dimensions::{DimensionError, finite, non_negative, positive};

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
    /// `μ = acos(|sin θ3|)`, in [0, π/2]. 90° is ideal (the rod pushes along the slide).
    ///
    /// ```
    /// use mechanisms::{SliderCrank, SliderCrankUnknowns};
    /// let linkage = SliderCrank::new(50.0, 150.0, 0.0)?;
    /// let inline = SliderCrankUnknowns { theta3: 0.0, d: 200.0 };
    /// assert_eq!(linkage.transmission_angle(&inline), std::f64::consts::FRAC_PI_2);
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn transmission_angle(&self, position: &SliderCrankUnknowns<T>) -> T {
        position.theta3.sin().abs().acos()
    }

    /// Whether the crank turns fully: the rod reaches the slider line from every crank
    /// position, `l3 − l2 ≥ |c|`.
    pub fn crank_turns_fully(&self) -> bool {
        self.l3 - self.l2 >= self.c.abs()
    }

    /// The slider's stroke for a crank that turns fully: the distance between its dead
    /// centres, where crank and rod line up extended (`|O2 B| = l2 + l3`) and folded
    /// (`|O2 B| = l3 − l2`): `√((l2 + l3)² − c²) − √((l3 − l2)² − c²)`. `None` if the crank
    /// cannot turn fully.
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// // Without offset the stroke is twice the crank.
    /// assert_eq!(SliderCrank::new(50.0, 150.0, 0.0)?.stroke(), Some(100.0));
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn stroke(&self) -> Option<T> {
        self.crank_turns_fully().then(|| {
            let c2 = self.c * self.c;
            let outer = self.l2 + self.l3;
            let inner = self.l3 - self.l2;
            (outer * outer - c2).sqrt() - (inner * inner - c2).max(T::zero()).sqrt()
        })
    }

    /// The crank angles at the dead centres on the open branch, `[outer, inner]`: where crank
    /// and rod line up extended, `θ2 = asin(c/(l2 + l3))`, and folded,
    /// `θ2 = π + asin(c/(l3 − l2))`. `None` if the crank cannot turn fully.
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// use mechgen::Branch;
    /// let linkage = SliderCrank::new(50.0_f64, 150.0, 20.0)?;
    /// for theta2 in linkage.dead_centres().unwrap() {
    ///     let q = linkage.assemble(theta2, Branch::Open)?;
    ///     assert!(linkage.velocity(theta2, &q, 1.0)?.d.abs() < 1e-12);
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn dead_centres(&self) -> Option<[T; 2]> {
        self.crank_turns_fully().then(|| {
            let pi = T::constant(core::f64::consts::PI);
            [
                (self.c / (self.l2 + self.l3)).asin(),
                pi + (self.c / (self.l3 - self.l2)).asin(),
            ]
        })
    }

    /// The time ratio of an offset slider-crank with a crank turning counter-clockwise at
    /// constant speed: the crank angle of the inward stroke (outer to inner dead centre,
    /// `α = θ_inner − θ_outer`) over that of the outward stroke (`β = 2π − α`). 1 without
    /// offset; above 1 when the inward stroke is the slower (`c > 0`). `None` if the crank
    /// cannot turn fully.
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
    /// centre (`ḋ = 0`).
    ///
    /// ```
    /// use mechanisms::SliderCrank;
    /// use mechgen::{Branch, MechanicalAdvantage};
    /// let linkage = SliderCrank::new(50.0, 150.0, 0.0)?;
    /// let q = linkage.assemble(0.0, Branch::Open)?;
    /// assert_eq!(linkage.mechanical_advantage(0.0, &q)?, MechanicalAdvantage::Unbounded);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn mechanical_advantage(
        &self,
        theta2: T,
        position: &SliderCrankUnknowns<T>,
    ) -> Result<MechanicalAdvantage<T>, Error<T>> {
        let rates = self.velocity(theta2, position, T::one())?;
        MechanicalAdvantage::from_rates(T::one(), rates.d)
    }
}
