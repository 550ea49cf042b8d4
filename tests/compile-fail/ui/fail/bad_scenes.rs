use mechgen::mechanism;

mechanism! {
    pub struct FourBar {
        params: l1, l2, l3, l4, a, delta: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        point coupler = l2 @ theta2 + a @ (theta3 + delta);
        scene draw: coupler, couplr, theta2_dot, l3, theta4_dddot;
        scene twice: theta3, theta3;
        scene points: coupler;
        scene draw_batch: coupler;
        scene draw: theta4;
    }
}

fn main() {}
