use mechgen::mechanism;

mechanism! {
    pub struct FourBar {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 * l3 @ theta2 + l3 @ theta3 / l1 - l4 @ theta4 - l1 @ 0;
    }
}

// A product or quotient of unknowns would make the loops nonlinear in them.
mechanism! {
    pub struct Products {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ (theta4 * theta3) - l1 @ (theta2 / theta3);
    }
}

fn main() {}
