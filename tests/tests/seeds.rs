//! The course notes' worked examples (KINEMATICS.md, "Worked values"), reproduced with the
//! generated four-bar code to the digits the notes print.

mod common;

use common::*;
use mechanisms::FourBarUnknowns;
use mechgen::{NewtonOptions, Solved};

/// Z, the diagonal from the crank pin A to O4, from the generated point positions.
fn diagonal(l1: f64, crank_pin: mechgen::Vec2<f64>) -> f64 {
    (crank_pin.x - l1).hypot(crank_pin.y)
}

/// The transmission angle between coupler and rocker, folded into [0°, 180°].
fn transmission_deg(position: &FourBarUnknowns<f64>) -> f64 {
    let gamma = normalised_deg(position.theta4 - position.theta3);
    if gamma > 180.0 { 360.0 - gamma } else { gamma }
}

#[test]
fn example_1_open_and_crossed_branches() {
    let linkage = example_1::<f64>();
    let theta2 = rad(60.0);
    let options = NewtonOptions::default();
    let open = linkage
        .position(theta2, &guess_deg(20.0, 70.0), &options)
        .unwrap()
        .value;
    let crossed = linkage
        .position(theta2, &guess_deg(290.0, 240.0), &options)
        .unwrap()
        .value;

    let z = diagonal(
        linkage.lengths()[0],
        linkage.points(theta2, &open).unwrap().crank_pin,
    );
    assert_eq!(rounded(z, 2), 156.20);
    assert_eq!(rounded(transmission_deg(&open), 2), 50.58);
    assert_eq!(rounded(transmission_deg(&crossed), 2), 50.58);
    assert_eq!(rounded(normalised_deg(open.theta4), 2), 72.14);
    assert_eq!(rounded(normalised_deg(crossed.theta4), 2), 235.20);
}

#[test]
fn example_2_newton_from_the_seed_guess() {
    let linkage = example_1::<f64>();
    let theta2 = rad(60.0);
    let guess = guess_deg(15.0, 80.0);

    // The first step, in exact arithmetic: f = (27.138, -26.675), Δ = (0.11893, -0.14204).
    let f = linkage.residual(theta2, &guess);
    assert_eq!([rounded(f[0], 3), rounded(f[1], 3)], [27.138, -26.675]);
    let j = linkage.jacobian(theta2, &guess);
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let step = [
        -(f[0] * j[1][1] - j[0][1] * f[1]) / det,
        -(j[0][0] * f[1] - f[0] * j[1][0]) / det,
    ];
    assert_eq!(
        [rounded(step[0], 5), rounded(step[1], 5)],
        [0.11893, -0.14204]
    );
    assert_eq!(
        [rounded(deg(step[0]), 3), rounded(deg(step[1]), 3)],
        [6.814, -8.138]
    );

    // Stopping at |f| < 1e-4 takes 3 updates in exact arithmetic (the seed tabulates 4).
    let Solved {
        value,
        iterations,
        residual_norm,
        condition,
    } = linkage
        .position(theta2, &guess, &NewtonOptions::new(1e-4, 20))
        .unwrap();
    assert_eq!(iterations, 3);
    assert!(residual_norm < 1e-4);
    // The condition estimate is the Jacobian's column norms over its determinant: for a
    // four-bar, 1/sin of the transmission angle, here 50.58°.
    let expected = 1.0 / (value.theta4 - value.theta3).sin().abs();
    assert!(
        (condition - expected).abs() < 1e-9 * expected,
        "{condition} vs {expected}"
    );
    assert_eq!(
        rounded(1.0 / condition, 4),
        rounded(50.58f64.to_radians().sin(), 4)
    );
    assert!(condition < 2.0);
    assert_eq!(rounded(deg(value.theta3), 4), 21.5576);
    assert_eq!(rounded(deg(value.theta4), 4), 72.1377);
}

#[test]
fn exercise_3_open_and_crossed_branches() {
    let linkage = four_bar(300.0, 100.0, 250.0, 200.0);
    let theta2 = rad(45.0);
    let options = NewtonOptions::default();
    let open = linkage
        .position(theta2, &guess_deg(30.0, 90.0), &options)
        .unwrap()
        .value;
    let crossed = linkage
        .position(theta2, &guess_deg(290.0, 230.0), &options)
        .unwrap()
        .value;
    assert_eq!(rounded(transmission_deg(&open), 2), 63.30);
    assert_eq!(rounded(transmission_deg(&crossed), 2), 63.30);
    assert_eq!(rounded(normalised_deg(open.theta4), 2), 94.30);
    assert_eq!(rounded(normalised_deg(crossed.theta4), 2), 231.43);
}

#[test]
fn exercise_4_newton_from_the_seed_guess() {
    let linkage = four_bar(300.0, 100.0, 250.0, 200.0);
    let solved = linkage
        .position(
            rad(60.0),
            &guess_deg(30.0, 100.0),
            &NewtonOptions::new(1e-5, 20),
        )
        .unwrap();
    assert!(solved.residual_norm < 1e-5);
    assert_eq!(rounded(deg(solved.value.theta3), 3), 26.528);
    assert_eq!(rounded(deg(solved.value.theta4), 3), 97.562);
}

#[test]
fn example_1_in_f32_agrees_to_f32_precision() {
    let linkage = example_1::<f32>();
    let guess = FourBarUnknowns {
        theta3: 15f32.to_radians(),
        theta4: 80f32.to_radians(),
    };
    let solved = linkage
        .position(60f32.to_radians(), &guess, &NewtonOptions::default())
        .unwrap();
    assert_close(
        "theta3",
        f64::from(solved.value.theta3),
        rad(21.557634918082556),
        1e-6,
    );
    assert_close(
        "theta4",
        f64::from(solved.value.theta4),
        rad(72.13765045102356),
        1e-6,
    );
}
