use mechgen::mechanism;

// Scenes and sensitivities are for a mechanism of one input: with two, each says so where
// it is asked for.
mechanism! {
    pub struct FiveBar {
        params: l1, l2, l3, l4, l5;
        input: theta1: angle, theta4: angle;
        unknowns: theta2: angle, theta3: angle;
        loop: l1 @ theta1 + l2 @ theta2 - l3 @ theta3 - l4 @ theta4 - l5 @ 0;
        generate: position, velocity, acceleration, sensitivities;
        scene angles: theta2, theta3;
        scene wrong: theta4_dot;
    }
}

fn main() {}
