use mechgen::mechanism;

// A function of a parameter (evaluated at compile time, so of numbers only).
mechanism! {
    pub struct OfAParameter {
        params: l1, l2, l3, l4, beta: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (theta3 + sin(beta)) - l4 @ theta4 - l1 @ 0;
    }
}

// A function the declaration does not know.
mechanism! {
    pub struct Unknown {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (theta3 + exp(1)) - l4 @ theta4 - l1 @ 0;
    }
}

// The wrong number of arguments.
mechanism! {
    pub struct Arity {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (theta3 + atan2(1)) - l4 @ theta4 - l1 @ 0;
    }
}

// Not a number.
mechanism! {
    pub struct NotFinite {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (theta3 + sqrt(-1)) - l4 @ theta4 - l1 @ 0;
    }
}

// A length as a function of numbers alone is still a bare number: it would not scale.
mechanism! {
    pub struct BareLength {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: sqrt(21.25) @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
    }
}

fn main() {}
