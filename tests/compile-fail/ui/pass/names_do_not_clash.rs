//! User names that match the generated code's own locals (`t0`, `position`, `x`,
//! `sin_theta`, a rate-like `theta_dot`) must not clash with them: generated locals are
//! hygienic.
use mechgen::mechanism;

mechanism! {
    pub struct Odd {
        params: t0, position, x, sin_theta, theta_dot: angle;
        input: theta: angle;
        unknowns: guess: angle, options: angle;
        loop: position @ theta + x @ guess - sin_theta @ (options + theta_dot) - t0 @ 0;
        point found = position @ theta;
        generate: position, velocity, acceleration, sensitivities;
    }
}

fn main() {
    let odd = Odd { t0: 180.0, position: 80.0, x: 200.0, sin_theta: 150.0, theta_dot: 0.0 };
    let guess = OddUnknowns { guess: 0.4, options: 1.2 };
    let q = odd.position(1.0, &guess, &Default::default()).unwrap().value;
    let v = odd.velocity(1.0, &q, 10.0).unwrap();
    odd.acceleration(1.0, &q, 10.0, &v, 0.0).unwrap();
    // The `Design` impl reads and rebuilds the same fields.
    use mechgen::Design;
    assert_eq!(Odd::with_parameters(odd.parameters()), odd);
    odd.unknown_sensitivities(1.0, q.to_array()).unwrap();
    odd.point_sensitivities(1.0, &q).unwrap();
    Design::point_sensitivities(&odd, 1.0, q.to_array()).unwrap();
}
