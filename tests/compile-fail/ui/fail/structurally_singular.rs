use mechgen::mechanism;

// Both sliders run along fixed directions in the second loop, and the first loop holds
// three of the four unknowns: the second loop's y equation involves none of them but `e`,
// and `d` and `e` share the x equation with nothing else to pin them.
mechanism! {
    pub struct Jammed {
        params: l1, l2, l3;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, d: length, e: length;
        loop: l2 @ theta2 + l3 @ theta3 - l1 @ theta4;
        loop: d @ 0 - e @ 0 - l1 @ 0 + l2 @ theta3;
    }
}

fn main() {}
