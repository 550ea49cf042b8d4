use mechgen::mechanism;

mechanism! {
    pub struct SliderCrank {
        params: l2, l3, c, gamma: angle;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + theta3 @ d - c @ gamma - d @ 0;
    }
}

fn main() {}
