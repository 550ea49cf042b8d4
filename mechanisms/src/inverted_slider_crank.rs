//! The inverted slider-crank (Norton's general form).

use mechgen::{Error, MechanicalAdvantage, Real, mechanism};

use crate::dimensions::{DimensionError, finite, non_negative, positive};

mechanism! {
    /// Inverted slider-crank: crank `l2` from O2 = (0, 0) to the crank pin A at the input
    /// `theta2`; a block pinned at A slides along the rocker, which pivots at O4 = (l1, 0)
    /// and points along `theta4`. The slide runs at the constant angle `gamma` to the rocker
    /// (θ3 = θ4 + γ), offset `c` along the rocker from O4; `b` is the block's position along
    /// the slide (the variable slide length). The seeds' case is `gamma = 0`. A coupler point
    /// P on the block sits at distance `a` from A, at angle `delta` from the slide.
    ///
    /// Loop: `l2 @ theta2 - b @ (theta4 + gamma) - c @ theta4 - l1 @ 0 = 0` (KINEMATICS.md).
    /// Build one with [`InvertedSliderCrank::new`], which checks the dimensions.
    ///
    /// The generated [`assemble`](Self::assemble) uses `R = A − O4 = e^{iθ4}·(b·e^{iγ} + c)`:
    /// `|R|² = b² + 2·b·c·cos γ + c²`, so `b = −c·cos γ ± √(|R|² − c²·sin² γ)` and
    /// `θ4 = arg R − arg(b·e^{iγ} + c)`. Its branches are told apart by the sign of the root,
    /// `b + c·cos γ`, A's distance along the slide from the foot of the perpendicular from O4:
    /// positive on the open branch (A lies ahead of the rocker along the slide), negative on
    /// the crossed one.
    ///
    /// ```
    /// use mechanisms::InvertedSliderCrank;
    /// use mechgen::Branch;
    /// let linkage = InvertedSliderCrank::new(150.0_f64, 60.0, 0.0, 0.0)?;
    /// // Crank along +x: A = (60, 0), so the rocker points back at it and b = 90.
    /// let q = linkage.assemble(0.0, Branch::Open)?;
    /// assert!((q.b - 90.0).abs() < 1e-12);
    /// assert!((q.theta4 - std::f64::consts::PI).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct InvertedSliderCrank {
        params:
            /// Ground link O2 O4.
            l1,
            /// Crank O2 A.
            l2,
            /// Offset of the slide from O4, along the rocker.
            c,
            /// Constant angle from the rocker to the slide, in radians (0 in the seeds).
            gamma: angle,
            /// Distance from A to the coupler point P on the block.
            a,
            /// Angle of A P from the slide, in radians.
            delta: angle;
        input: theta2: angle;
        unknowns: theta4: angle, b: length;
        loop: l2 @ theta2 - b @ (theta4 + gamma) - c @ theta4 - l1 @ 0;
        /// A, the crank pin, reached through the crank.
        point crank_pin = l2 @ theta2;
        /// A again, reached through the rocker and the slide: its acceleration parts show the
        /// block's sliding and Coriolis accelerations.
        point block_pin = l1 @ 0 + c @ theta4 + b @ (theta4 + gamma);
        /// The start of the slide on the rocker, `O4 + c @ theta4`.
        point slide_origin = l1 @ 0 + c @ theta4;
        /// P, the coupler point on the block.
        point coupler_point = l2 @ theta2 + a @ (theta4 + gamma + delta);
        generate: position, velocity, acceleration;
        /// The rocker's angle and the block's place on it, with their rates and
        /// accelerations.
        scene state: theta4, b, theta4_dot, b_dot, theta4_ddot, b_ddot;
    }
}

impl<T: Real> InvertedSliderCrank<T> {
    /// An inverted slider-crank with the coupler point at the crank pin A.
    ///
    /// Errors: a ground or crank that is not positive and finite, a non-finite offset or
    /// angle, or a slide that passes farther from O4 than A can ever be
    /// (`|c·sin γ| > l1 + l2`).
    ///
    /// ```
    /// use mechanisms::InvertedSliderCrank;
    /// assert!(InvertedSliderCrank::new(150.0, 60.0, 20.0, 0.3).is_ok());
    /// assert_eq!(InvertedSliderCrank::new(150.0, 60.0, 20.0, f64::NAN).unwrap_err().name, "angle");
    /// ```
    pub fn new(ground: T, crank: T, offset: T, angle: T) -> Result<Self, DimensionError<T>> {
        let linkage = InvertedSliderCrank {
            l1: positive("ground", ground)?,
            l2: positive("crank", crank)?,
            c: finite("offset", offset)?,
            gamma: finite("angle", angle)?,
            a: T::zero(),
            delta: T::zero(),
        };
        if (offset * angle.sin()).abs() > ground + crank {
            return Err(DimensionError {
                name: "offset",
                value: offset,
                requirement: "such that the slide can pass through the crank pin",
            });
        }
        Ok(linkage)
    }

    /// The same linkage with its coupler point P on the block, at `distance` from A and
    /// `angle` (radians) from the slide.
    ///
    /// ```
    /// use mechanisms::InvertedSliderCrank;
    /// let linkage = InvertedSliderCrank::new(150.0, 60.0, 20.0, 0.3)?;
    /// assert!(linkage.with_coupler_point(30.0, 1.0).is_ok());
    /// assert!(linkage.with_coupler_point(f64::NAN, 1.0).is_err());
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn with_coupler_point(self, distance: T, angle: T) -> Result<Self, DimensionError<T>> {
        Ok(InvertedSliderCrank {
            a: non_negative("coupler point distance", distance)?,
            delta: finite("coupler point angle", angle)?,
            ..self
        })
    }

    /// `[ground, crank, offset, angle]`.
    ///
    /// ```
    /// use mechanisms::InvertedSliderCrank;
    /// let linkage = InvertedSliderCrank::new(150.0, 60.0, 20.0, 0.3)?;
    /// assert_eq!(linkage.dimensions(), [150.0, 60.0, 20.0, 0.3]);
    /// # Ok::<(), mechanisms::DimensionError<f64>>(())
    /// ```
    pub fn dimensions(&self) -> [T; 4] {
        [self.l1, self.l2, self.c, self.gamma]
    }

    /// The ideal mechanical advantage at a position, rocker torque over crank torque:
    /// `MA = T4/T2 = ω2/ω4`, from the generated velocity. Unbounded where the rocker stops.
    ///
    /// ```
    /// use mechanisms::InvertedSliderCrank;
    /// use mechgen::Branch;
    /// let linkage = InvertedSliderCrank::new(150.0_f64, 60.0, 0.0, 0.0)?;
    /// let q = linkage.assemble(0.0, Branch::Open)?;
    /// // A = (60, 0) moves up at 60 mm/s per rad/s, 90 mm from O4: ω4 = -60/90.
    /// let ma = linkage.mechanical_advantage(0.0, &q)?.finite().unwrap();
    /// assert!((ma + 1.5).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn mechanical_advantage(
        &self,
        theta2: T,
        position: &InvertedSliderCrankUnknowns<T>,
    ) -> Result<MechanicalAdvantage<T>, Error<T>> {
        let rates = self.velocity(theta2, position, T::one())?;
        MechanicalAdvantage::from_rates(T::one(), rates.theta4)
    }
}
