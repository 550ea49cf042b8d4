use mechgen::mechanism;

// `90` in an angle is radians; degrees say so.
mechanism! {
    pub struct Offset {
        params: l1, l2, l3, c;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - c @ 90 - d @ 0;
    }
}

// Degrees are for angles.
mechanism! {
    pub struct Lengthy {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - 2 deg @ 0;
    }
}

fn main() {}
