use mechgen::mechanism;

// The coupler's and rocker's angles enter only as their sum: every unknown has an equation,
// but the Jacobian's two columns are the same everywhere.
mechanism! {
    pub struct SumOnly {
        params: l1, l2, l3;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (theta3 + theta4) - l1 @ 0;
    }
}

fn main() {}
