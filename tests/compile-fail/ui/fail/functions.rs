use mechgen::mechanism;

// Functions and products take numbers and parameters, and keep a length a length.
mechanism! {
    pub struct OfAnUnknown {
        params: l1, l2, l3, l4, beta: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (theta3 + sin(theta3)) - l4 @ (theta4 + cos(theta2))
            - hypot(l1, l2 / 0) @ 0;
    }
}

mechanism! {
    pub struct Dimensions {
        params: l1, l2, l3, l4, beta: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: sqrt(l1) @ theta2 + l3 * l2 @ theta3 - hypot(l4, 1) @ theta4
            - l1 @ (l2 * cos(beta)) + sin(l1) * l2 @ 0 + (l1 + beta) * l2 @ 0;
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
