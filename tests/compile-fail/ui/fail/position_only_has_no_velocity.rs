use mechgen::mechanism;

mechanism! {
    pub struct FourBar {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        generate: position;
    }
}

fn main() {
    let linkage = FourBar { l1: 180.0, l2: 80.0, l3: 200.0, l4: 150.0 };
    let guess = FourBarUnknowns { theta3: 0.4, theta4: 1.2 };
    let q = linkage.position(1.0, &guess, &Default::default()).unwrap().value;
    let _ = linkage.velocity(1.0, &q, 10.0);
}
