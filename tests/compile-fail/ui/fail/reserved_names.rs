use mechgen::mechanism;

// Names the generated code cannot use for a mechanism's values or type: a struct called `T`
// (the float type's parameter) and parameters called `Ok`, `Err`, `Some` and `None`.
mechanism! {
    pub struct T {
        params: Ok, Err, Some, None;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: Err @ theta2 + Some @ theta3 - None @ theta4 - Ok @ 0;
    }
}

fn main() {}
