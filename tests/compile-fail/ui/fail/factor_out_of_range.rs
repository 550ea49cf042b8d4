use mechgen::mechanism;

// A name's factor is between 1e-6 and 1e6 in size: reported at the expression, not as a
// Jacobian singular at another unknown.
mechanism! {
    pub struct FourBar {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (1e300 * theta3) - 1e-320 * l4 @ theta4 - l1 @ (theta2 / 3e6);
    }
}

fn main() {}
