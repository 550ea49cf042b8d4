use mechgen::mechanism;

// A loop whose vectors cancel whatever the values closes everywhere and determines nothing.
mechanism! {
    pub struct FourBar {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        loop: l1 @ 0 - l1 @ 0;
        loop: l3 @ theta3 + l3 @ (theta3 + pi);
    }
}

fn main() {}
