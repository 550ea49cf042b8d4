use mechgen::mechanism;

// A length written as a number would not scale with the declared lengths.
mechanism! {
    pub struct FourBar {
        params: l1, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: 80 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
    }
}

mechanism! {
    pub struct Offset {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + (l3 + 0.5) @ theta3 - l4 @ theta4 - 2 * l1 @ 0;
    }
}

fn main() {}
