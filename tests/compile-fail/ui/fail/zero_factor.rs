use mechgen::mechanism;

// A factor of zero drops a name as a cancellation does (`theta2 - theta2`): an input written
// only so drives nothing (every velocity would be zero), an unknown is in no equation.
mechanism! {
    pub struct InputTimesZero {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ (0 * theta2) + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
    }
}

mechanism! {
    pub struct UnknownTimesZero {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ (theta3 * 0) - (0 * d) @ 0 - l1 @ 0;
    }
}

fn main() {}
