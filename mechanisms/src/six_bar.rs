//! Six-bar linkages: a Watt six-bar, solved loop by loop in closed form, and a Stephenson
//! six-bar whose two loops are coupled, solved by Newton on two unknowns with the other
//! loop in closed form inside each iteration.

use mechgen::{Real, mechanism};

use crate::dimensions::{DimensionError, finite, positive};

mechanism! {
    /// Watt six-bar (Watt II): a four-bar O2 A B O4 whose rocker is a ternary link, extended
    /// by `l5` at the constant angle `beta` from O4 B to the pin C, which drives the dyad
    /// C D O6: coupler `l6` from C to D, rocker `l7` from the ground pivot O6 = `g @ phi` to D.
    ///
    /// Loops: `l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0 = 0` (the four-bar) and
    /// `l1 @ 0 + l5 @ (theta4 + beta) + l6 @ theta5 - l7 @ theta6 - g @ phi = 0` (the dyad).
    /// Each closes with two unknowns once the one before it is solved, so
    /// [`assemble`](Self::assemble) takes a branch per loop and solves both in closed form.
    /// Build one with [`WattSixBar::new`].
    ///
    /// ```
    /// use mechanisms::WattSixBar;
    /// use mechgen::Branch;
    /// let linkage = WattSixBar::new([180.0_f64, 80.0, 200.0, 150.0], 100.0, 0.8, 220.0, 160.0, (300.0, 150.0))?;
    /// let q = linkage.assemble(1.0, [Branch::Open, Branch::Open])?;
    /// assert!(linkage.residual(1.0, &q).iter().all(|f| f.abs() < 1e-10));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct WattSixBar {
        params:
            /// Ground O2 O4.
            l1,
            /// Crank O2 A.
            l2,
            /// Coupler A B.
            l3,
            /// Rocker O4 B.
            l4,
            /// Rocker extension O4 C.
            l5,
            /// Angle of O4 C from O4 B, radians.
            beta: angle,
            /// Second coupler C D.
            l6,
            /// Second rocker O6 D.
            l7,
            /// Distance of the ground pivot O6 from O2.
            g,
            /// Direction of O6 from O2, radians.
            phi: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, theta5: angle, theta6: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        loop: l1 @ 0 + l5 @ (theta4 + beta) + l6 @ theta5 - l7 @ theta6 - g @ phi;
        /// A, the crank pin.
        point crank_pin = l2 @ theta2;
        /// B, the first rocker's pin.
        point rocker_pin = l1 @ 0 + l4 @ theta4;
        /// C, the end of the rocker's extension.
        point extension_pin = l1 @ 0 + l5 @ (theta4 + beta);
        /// D, the output rocker's pin.
        point output_pin = g @ phi + l7 @ theta6;
        generate: position, velocity, acceleration, sensitivities;
        /// The output link's angle, rate and acceleration.
        scene output: theta6, theta6_dot, theta6_ddot;
    }
}

impl<T: Real> WattSixBar<T> {
    /// A Watt six-bar from its four-bar `[ground, crank, coupler, rocker]`, the rocker's
    /// extension and its angle, the second dyad's coupler and rocker, and the ground pivot
    /// O6 as `(x, y)`.
    ///
    /// Errors: a length that is not positive and finite, a non-finite angle or pivot.
    ///
    /// ```
    /// use mechanisms::WattSixBar;
    /// let bad = WattSixBar::new([180.0_f64, 80.0, 200.0, 150.0], -1.0, 0.8, 220.0, 160.0, (300.0, 150.0));
    /// assert_eq!(bad.unwrap_err().name, "extension");
    /// ```
    pub fn new(
        four_bar: [T; 4],
        extension: T,
        extension_angle: T,
        coupler: T,
        rocker: T,
        pivot: (T, T),
    ) -> Result<Self, DimensionError<T>> {
        let (x, y) = (finite("pivot x", pivot.0)?, finite("pivot y", pivot.1)?);
        Ok(WattSixBar {
            l1: positive("ground", four_bar[0])?,
            l2: positive("crank", four_bar[1])?,
            l3: positive("coupler", four_bar[2])?,
            l4: positive("rocker", four_bar[3])?,
            l5: positive("extension", extension)?,
            beta: finite("extension angle", extension_angle)?,
            l6: positive("second coupler", coupler)?,
            l7: positive("second rocker", rocker)?,
            g: x.hypot(y),
            phi: y.atan2(x),
        })
    }

    /// The dimensions [`new`](Self::new) takes: the four-bar `[ground, crank, coupler,
    /// rocker]`, the rocker's extension and its angle, the second dyad's coupler and rocker,
    /// and the ground pivot O6 as `(x, y)` (from its distance and direction, to rounding).
    ///
    /// ```
    /// use mechanisms::WattSixBar;
    /// let watt = WattSixBar::new([180.0f64, 80.0, 200.0, 150.0], 100.0, 0.8, 220.0, 160.0, (300.0, 150.0))?;
    /// let (four_bar, extension, _, coupler, rocker, (x, y)) = watt.dimensions();
    /// assert_eq!((four_bar, extension, coupler, rocker), ([180.0, 80.0, 200.0, 150.0], 100.0, 220.0, 160.0));
    /// assert!((x - 300.0).abs() < 1e-12 && (y - 150.0).abs() < 1e-12);
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    #[allow(clippy::type_complexity)]
    pub fn dimensions(&self) -> ([T; 4], T, T, T, T, (T, T)) {
        let (sin, cos) = self.phi.sin_cos();
        (
            [self.l1, self.l2, self.l3, self.l4],
            self.l5,
            self.beta,
            self.l6,
            self.l7,
            (self.g * cos, self.g * sin),
        )
    }
}

mechanism! {
    /// Stephenson six-bar (Stephenson III): crank `l2` from O2 to A; link `l3` from A to B;
    /// a ternary floating link with B, C and D (`bc` from B to C at `theta5`, `cd` from C to
    /// D at `theta5 + beta`); rocker `l4` from O4 = (l1, 0) to C; rocker `l6` from the ground
    /// pivot O6 = `g @ phi` to D. The two ternary links (ground and the floating one) are not
    /// joined, so each loop holds three unknowns: neither closes on its own. The generated
    /// [`position`](Self::position) iterates on `theta3` and `theta4` alone (a 2×2 Newton whose
    /// Jacobian is the Schur complement of the full one), solving the second loop for `theta5`
    /// and `theta6` in closed form at every iterate. Build one with [`StephensonSixBar::new`].
    ///
    /// Loops: `l2 @ theta2 + l3 @ theta3 + bc @ theta5 - l4 @ theta4 - l1 @ 0 = 0` and
    /// `l1 @ 0 + l4 @ theta4 + cd @ (theta5 + beta) - l6 @ theta6 - g @ phi = 0`.
    ///
    /// ```
    /// use mechanisms::{StephensonSixBar, StephensonSixBarUnknowns};
    /// use mechgen::NewtonOptions;
    /// let linkage = StephensonSixBar::new(100.0_f64, 20.0, 117.0, [60.0, 63.0], -0.97, 52.0, 85.0, (189.0, -26.0))?;
    /// let guess = StephensonSixBarUnknowns { theta3: -0.25, theta4: 0.63, theta5: 1.43, theta6: 1.46 };
    /// let q = linkage.position(0.0, &guess, &NewtonOptions::default())?.value;
    /// assert!(linkage.residual(0.0, &q).iter().all(|f| f.abs() < 1e-10));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct StephensonSixBar {
        params:
            /// Ground O2 O4.
            l1,
            /// Crank O2 A.
            l2,
            /// Link A B.
            l3,
            /// Side B C of the floating ternary link.
            bc,
            /// Side C D of the floating ternary link.
            cd,
            /// Angle of C D from B C, radians.
            beta: angle,
            /// Rocker O4 C.
            l4,
            /// Rocker O6 D.
            l6,
            /// Distance of the ground pivot O6 from O2.
            g,
            /// Direction of O6 from O2, radians.
            phi: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, theta5: angle, theta6: angle;
        loop: l2 @ theta2 + l3 @ theta3 + bc @ theta5 - l4 @ theta4 - l1 @ 0;
        loop: l1 @ 0 + l4 @ theta4 + cd @ (theta5 + beta) - l6 @ theta6 - g @ phi;
        /// A, the crank pin.
        point crank_pin = l2 @ theta2;
        /// B.
        point b = l2 @ theta2 + l3 @ theta3;
        /// C.
        point c = l1 @ 0 + l4 @ theta4;
        /// D.
        point d = g @ phi + l6 @ theta6;
        generate: position, velocity, acceleration;
    }
}

impl<T: Real> StephensonSixBar<T> {
    /// A Stephenson six-bar from its ground O2 O4, crank, link A B, the floating ternary
    /// link's sides `[B C, C D]` and the angle between them, the rockers O4 C and O6 D, and
    /// the ground pivot O6 as `(x, y)`.
    ///
    /// Errors: a length that is not positive and finite, a non-finite angle or pivot.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        ground: T,
        crank: T,
        link: T,
        ternary: [T; 2],
        ternary_angle: T,
        rocker: T,
        output_rocker: T,
        pivot: (T, T),
    ) -> Result<Self, DimensionError<T>> {
        let (x, y) = (finite("pivot x", pivot.0)?, finite("pivot y", pivot.1)?);
        Ok(StephensonSixBar {
            l1: positive("ground", ground)?,
            l2: positive("crank", crank)?,
            l3: positive("link", link)?,
            bc: positive("ternary B C", ternary[0])?,
            cd: positive("ternary C D", ternary[1])?,
            beta: finite("ternary angle", ternary_angle)?,
            l4: positive("rocker", rocker)?,
            l6: positive("output rocker", output_rocker)?,
            g: x.hypot(y),
            phi: y.atan2(x),
        })
    }
}
