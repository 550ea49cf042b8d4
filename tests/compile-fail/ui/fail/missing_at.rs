use mechgen::mechanism;

mechanism! {
    pub struct Inverted {
        params: l1, l2, b, gamma: angle;
        input: theta2: angle;
        unknowns: theta4: angle, b: length;
        loop: l2 @ theta2 - b @ theta4 + gamma - l1 @ 0;
    }
}

fn main() {}
