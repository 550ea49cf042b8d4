use mechgen::mechanism;

mechanism! {
    /// A Stephenson six-bar: its loops share three unknowns, so no loop closes on its own.
    pub struct Stephenson {
        params: l1, l2, l3, bc, cd, beta: angle, l4, l6, g, phi: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, theta5: angle, theta6: angle;
        loop: l2 @ theta2 + l3 @ theta3 + bc @ theta5 - l4 @ theta4 - l1 @ 0;
        loop: l1 @ 0 + l4 @ theta4 + cd @ (theta5 + beta) - l6 @ theta6 - g @ phi;
        generate: position, assemble;
    }
}

mechanism! {
    /// `theta3` turns one vector forwards and another backwards.
    pub struct BothWays {
        params: l1, l2, l3, e, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 + e @ (pi - theta3) - l4 @ theta4 - l1 @ 0;
        generate: position, assemble;
    }
}

mechanism! {
    /// `theta3` turns a vector twice as fast.
    pub struct Doubled {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (2 * theta3) - l4 @ theta4 - l1 @ 0;
        generate: position, velocity, assemble;
    }
}

fn main() {}
