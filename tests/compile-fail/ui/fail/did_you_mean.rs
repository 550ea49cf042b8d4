use mechgen::mechanism;

// A misspelled name, and a constant in the wrong case.
mechanism! {
    pub struct FourBar {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta + l3 @ theta3 - l4 @ (theta4 + PI) - l1 @ 0;
    }
}

fn main() {}
