use mechgen::mechanism;

// Messages quote a loop as it was written, parentheses and all.
mechanism! {
    pub struct Doubled {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (2 * theta3) - (l4 / 2) @ theta4 - l1 @ (-(pi / 2));
        scene angles: theta3, theta4;
    }
}

fn main() {}
