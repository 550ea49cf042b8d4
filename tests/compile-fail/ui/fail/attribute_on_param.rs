use mechgen::mechanism;

// Doc comments document a parameter's field; no other attribute means anything there.
mechanism! {
    pub struct FourBar {
        params:
            /// The ground link.
            l1,
            #[cfg(feature = "long")] l2,
            l3,
            l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
    }
}

fn main() {}
