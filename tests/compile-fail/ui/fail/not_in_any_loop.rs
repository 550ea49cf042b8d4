use mechgen::mechanism;

mechanism! {
    pub struct Idle {
        params: l1, l2, l3;
        input: phi: angle;
        unknowns: theta3: angle, theta4: angle, d: length, e: length;
        loop: l2 @ theta3 + l3 @ theta4 - l1 @ 0;
        loop: d @ 0 - l1 @ 0 + l2 @ theta3;
    }
}

fn main() {}
