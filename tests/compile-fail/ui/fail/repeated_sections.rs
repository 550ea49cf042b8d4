use mechgen::mechanism;

// Each mistake is reported once: the names in the repeated sections still resolve.
mechanism! {
    pub struct FourBar {
        params: l1, l2;
        params: l3, l4;
        input: theta2: angle;
        input: theta9: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ theta9;
    }
}

fn main() {}
