use mechgen::mechanism;

// Doc comments document a point's fields and a scene's items; no other attribute can follow
// a point or a scene into everything generated for it.
mechanism! {
    pub struct FourBar {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        /// The crank pin.
        #[cfg(any())]
        point crank_pin = l2 @ theta2;
        /// The crank pin's motion.
        #[cfg(test)]
        #[allow(unused)]
        scene crank: crank_pin, crank_pin_dot;
    }
}

fn main() {}
