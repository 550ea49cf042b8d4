//! The planar mechanisms mechgen ships, each declared with [`mechgen::mechanism!`].
//!
//! Conventions (`../shared/KINEMATICS.md` in the repository): vectors are `r @ θ` = `r·e^{iθ}`,
//! angles in radians counter-clockwise from +x, the ground pivot O2 at the origin.
#![no_std]

use mechgen::mechanism;

mechanism! {
    /// Four-bar linkage: ground `l1` from O2 = (0, 0) to O4 = (l1, 0), crank `l2` at the
    /// input `theta2`, coupler `l3` at `theta3`, rocker `l4` at `theta4`.
    ///
    /// Loop: `l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0 = 0`. The coupler point `p`
    /// sits at distance `a` from the crank pin A, at angle `delta` from the coupler line.
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
        point crank_pin = l2 @ theta2;
        point rocker_pin = l1 @ 0 + l4 @ theta4;
        point coupler = l2 @ theta2 + a @ (theta3 + delta);
        generate: position, velocity, acceleration;
    }
}

mechanism! {
    /// Slider-crank with offset: crank `l2` at the input `theta2`, connecting rod `l3` at
    /// `theta3` from the crank pin A to the slider pin B, which slides on the line `y = c`;
    /// `d` is the slider's x position.
    ///
    /// Loop: `l2 @ theta2 + l3 @ theta3 - c @ pi / 2 - d @ 0 = 0`.
    pub struct SliderCrank {
        params:
            /// Crank O2 A.
            l2,
            /// Connecting rod A B.
            l3,
            /// Offset of the slider line from O2, along +y.
            c;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - c @ pi / 2 - d @ 0;
        point crank_pin = l2 @ theta2;
        point slider_pin = d @ 0 + c @ pi / 2;
        generate: position, velocity, acceleration;
    }
}

mechanism! {
    /// Inverted slider-crank (Norton's general form): crank `l2` at the input `theta2`; a block
    /// pinned at the crank tip A slides along the rocker, which pivots at O4 = (l1, 0) and
    /// points along `theta4`. `b` is the slide length, measured along `theta4 + gamma`, and
    /// `c` the block's offset along the rocker.
    ///
    /// Loop: `l2 @ theta2 - b @ (theta4 + gamma) - c @ theta4 - l1 @ 0 = 0`.
    pub struct InvertedSliderCrank {
        params:
            /// Ground link O2 O4.
            l1,
            /// Crank O2 A.
            l2,
            /// Offset of the block along the rocker.
            c,
            /// Constant angle between the slide and the rocker, in radians (0 in the seeds).
            gamma: angle;
        input: theta2: angle;
        unknowns: theta4: angle, b: length;
        loop: l2 @ theta2 - b @ (theta4 + gamma) - c @ theta4 - l1 @ 0;
        point crank_pin = l2 @ theta2;
        generate: position, velocity, acceleration;
    }
}
