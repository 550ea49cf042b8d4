use mechgen::mechanism;

// Every name a scene can list (an unknown or a point, with `_dot` for its rate and `_ddot`
// for its acceleration) names one thing: a point may not take an unknown's name or the name
// of another point's or an unknown's rate, and no output may be named like a parameter.
mechanism! {
    pub struct PointNamedLikeAnUnknown {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        point theta4 = l3 @ theta3;
        scene s: theta4;
    }
}

mechanism! {
    pub struct PointNamedLikeARate {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        point theta3_dot = l2 @ theta2;
        point p = l2 @ theta2;
        point p_dot = l2 @ theta2 + l3 @ theta3;
        point l4 = l1 @ 0 + l4 @ theta4;
        scene s: theta3_dot, p_dot;
    }
}

mechanism! {
    pub struct UnknownsAfterTheirRates {
        params: l1, l2, l3, l4, theta4_ddot: angle;
        input: theta2: angle;
        point a_dot = l2 @ theta2;
        unknowns: a: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (a + theta4_ddot) - l4 @ theta4 - l1 @ 0;
    }
}

fn main() {}
