//! Degrees are reduced to within a turn before they become radians, exactly: `1e308 deg` is
//! the angle `296 deg` (1e308 mod 360), and `-1e308 deg` is `-296 deg`.
use mechgen::mechanism;

mechanism! {
    pub struct Huge {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ (1e308 deg) + l1 @ (-1e308 deg);
    }
}

mechanism! {
    pub struct Reduced {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ (296 deg) + l1 @ (-296 deg);
    }
}

fn main() {
    assert_eq!(1e308f64 % 360.0, 296.0);
    let huge = Huge { l1: 180.0, l2: 80.0, l3: 200.0, l4: 150.0 };
    let reduced = Reduced { l1: 180.0, l2: 80.0, l3: 200.0, l4: 150.0 };
    let q = HugeUnknowns { theta3: 0.3, theta4: 1.2 };
    let r = ReducedUnknowns { theta3: 0.3, theta4: 1.2 };
    assert_eq!(huge.residual(1.0, &q), reduced.residual(1.0, &r));
    assert_eq!(huge.jacobian(1.0, &q), reduced.jacobian(1.0, &r));
}
