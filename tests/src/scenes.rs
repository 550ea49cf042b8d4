//! The four-bar declared three times, asking for less each time: what a scene that needs
//! only positions, or positions and velocities, gets. The performance report compares their
//! code size and speed; `#[inline(never)]` entry points keep each one's machine code apart.

use mechgen::{Branch, Error, mechanism};

mechanism! {
    /// Positions only.
    pub struct PositionsOnly {
        params: pub l1, pub l2, pub l3, pub l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        generate: position;
    }
}

mechanism! {
    /// Positions and velocities.
    pub struct WithVelocities {
        params: pub l1, pub l2, pub l3, pub l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        generate: position, velocity;
    }
}

mechanism! {
    /// Everything.
    pub struct Everything {
        params: pub l1, pub l2, pub l3, pub l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        generate: position, velocity, acceleration;
    }
}

/// The seeds' Example 1 lengths.
pub const LENGTHS: [f64; 4] = [180.0, 80.0, 200.0, 150.0];

/// The closed-form position of the positions-only declaration.
#[inline(never)]
pub fn positions_only(theta2: f64) -> Result<[f64; 2], Error<f64>> {
    let [l1, l2, l3, l4] = LENGTHS;
    let linkage = PositionsOnly { l1, l2, l3, l4 };
    linkage.assemble(theta2, Branch::Open).map(|q| q.to_array())
}

/// The closed-form position of the declaration with velocities.
#[inline(never)]
pub fn with_velocities(theta2: f64) -> Result<[f64; 2], Error<f64>> {
    let [l1, l2, l3, l4] = LENGTHS;
    let linkage = WithVelocities { l1, l2, l3, l4 };
    linkage.assemble(theta2, Branch::Open).map(|q| q.to_array())
}

/// The closed-form position of the full declaration.
#[inline(never)]
pub fn everything(theta2: f64) -> Result<[f64; 2], Error<f64>> {
    let [l1, l2, l3, l4] = LENGTHS;
    let linkage = Everything { l1, l2, l3, l4 };
    linkage.assemble(theta2, Branch::Open).map(|q| q.to_array())
}
