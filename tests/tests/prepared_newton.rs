//! `newton()` then `{Name}Newton::motion_near` gives what `motion_near` gives, bit for bit and
//! error for error: the same solve with the dimensions' checks and constants made once.

mod common;

use mechgen::{Branch, Error, NewtonOptions, mechanism};
use mechgen_tests::examples::stephenson_six_bar;
use mechgen_tests::scenes::Everything as OpenFourBar;

mechanism! {
    /// A rod of length `l` with one end on the x axis at `x` (the input, a slider) and the
    /// other on the y axis at `y`: an input that is a length joins the size on each call.
    pub struct Trammel {
        params: pub l;
        input: x: length;
        unknowns: theta: angle, y: length;
        loop: x @ 0 + l @ theta - y @ (pi / 2);
    }
}

mechanism! {
    /// The four-bar with its ground link declared a million times a parameter: the loops'
    /// scale (which `newton()` computes once) sums a magnitude far from the parameter.
    pub struct StretchedGround {
        params: pub l1, pub l2, pub l3, pub l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - 1e6 * l1 @ 0;
    }
}

mechanism! {
    /// The four-bar with its rocker's angle measured from +y: `psi` is turned only with an
    /// offset, so no `Started` keeps its own sine and cosine.
    pub struct OffsetRocker {
        params: pub l1, pub l2, pub l3, pub l4;
        input: theta2: angle;
        unknowns: theta3: angle, psi: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ (psi + pi / 2) - l1 @ 0;
    }
}

/// Both solves of the same call, as printed (a NaN in an error is then the same NaN).
fn same<T: std::fmt::Debug>(prepared: T, general: T) {
    assert_eq!(format!("{prepared:?}"), format!("{general:?}"));
}

#[test]
fn a_sweep_gives_the_general_bits() {
    let linkage = common::example_1::<f64>();
    let newton = linkage.newton().unwrap();
    assert_eq!(newton.mechanism(), &linkage);
    let (w, a) = (10.0, 2.0);
    for options in [NewtonOptions::default(), NewtonOptions::new(1e-12, 50)] {
        let mut guess = linkage.assemble(0.0, Branch::Open).unwrap();
        for degree in 1..360 {
            let t = f64::from(degree).to_radians();
            let general = linkage.motion_near(t, &guess, &options, w, a);
            let prepared = newton.motion_near(t, &guess, &options, w, a);
            assert_eq!(prepared, general, "at {degree}°");
            let m = general.unwrap().value;
            guess = mechanisms::FourBarUnknowns {
                theta3: m.position.theta3 + m.velocity.theta3 / w * 1f64.to_radians(),
                theta4: m.position.theta4 + m.velocity.theta4 / w * 1f64.to_radians(),
            };
        }
    }
}

#[test]
fn coupled_loops_give_the_general_bits() {
    let (linkage, start) = stephenson_six_bar();
    let newton = linkage.newton().unwrap();
    let options = NewtonOptions::default();
    for degree in [5, 30, 90, 200] {
        let t = f64::from(degree).to_radians();
        same(
            newton.motion_near(t, &start, &options, 3.0, -1.0),
            linkage.motion_near(t, &start, &options, 3.0, -1.0),
        );
    }
}

#[test]
fn what_the_common_path_does_not_take_is_the_general_functions() {
    let linkage = common::example_1::<f64>();
    let newton = linkage.newton().unwrap();
    let guess = linkage.assemble(0.3, Branch::Open).unwrap();
    let options = NewtonOptions::default();
    let calls: [(f64, NewtonOptions<f64>, f64, f64); 12] = [
        // Not finite: the input, its rate, its acceleration.
        (f64::NAN, options, 1.0, 0.0),
        (f64::INFINITY, options, 1.0, 0.0),
        (0.3, options, f64::NAN, 0.0),
        (0.3, options, 1.0, f64::INFINITY),
        // Rates whose squares leave the range: counted in other units.
        (0.3, options, 1e-200, 1e-300),
        // A tolerance that is no tolerance.
        (0.3, NewtonOptions::new(-1.0, 50), 1.0, 0.0),
        (0.3, NewtonOptions::new(f64::NAN, 50), 1.0, 0.0),
        (0.3, NewtonOptions::new(f64::INFINITY, 50), 1.0, 0.0),
        // Zero with its sign bit set (the general solve's zero), and the largest tolerance.
        (0.3, NewtonOptions::new(-0.0, 50), 1.0, 0.0),
        (0.3, NewtonOptions::new(f64::MAX, 50), 1.0, 0.0),
        // Beyond the range of motion (the four-bar is a crank-rocker: none), and far off
        // (beyond the inline `sin_cos`'s range, where the prepared solve does not go).
        (0.3 + 2.0 * std::f64::consts::PI * 1e6, options, 1.0, 0.0),
        (3.0, NewtonOptions::new(0.0, 1), 1.0, 0.0),
    ];
    for (t, options, w, a) in calls {
        same(
            newton.motion_near(t, &guess, &options, w, a),
            linkage.motion_near(t, &guess, &options, w, a),
        );
    }
}

/// In f32 the inline `sin_cos` takes inputs up to 1e3 rad: beyond, the prepared solve leaves
/// the input to the general one, which gives the same answer.
#[test]
fn f32_inputs_within_and_beyond_the_inline_sin_cos_give_the_general_bits() {
    let linkage = common::example_1::<f32>();
    let newton = linkage.newton().unwrap();
    let options = NewtonOptions::default();
    let turns = 2.0 * std::f32::consts::PI;
    for t in [
        0.3f32,
        0.3 + 150.0 * turns,
        0.3 + 170.0 * turns,
        3e4,
        f32::NAN,
    ] {
        let guess = linkage
            .assemble(t, Branch::Open)
            .unwrap_or(linkage.assemble(0.3, Branch::Open).unwrap());
        same(
            newton.motion_near(t, &guess, &options, 1.0, 0.0),
            linkage.motion_near(t, &guess, &options, 1.0, 0.0),
        );
    }
    let guess = linkage.assemble(0.3, Branch::Open).unwrap();
    assert!(newton.motion_near(0.3, &guess, &options, 1.0, 0.0).is_ok());
}

#[test]
fn a_mechanism_far_from_unit_size_gives_the_general_bits() {
    for scale in [1e-250, 1e250] {
        let linkage = OpenFourBar {
            l1: 180.0 * scale,
            l2: 80.0 * scale,
            l3: 200.0 * scale,
            l4: 150.0 * scale,
        };
        let newton = linkage.newton().unwrap();
        let guess = linkage.assemble(0.5, Branch::Open).unwrap();
        same(
            newton.motion_near(0.52, &guess, &NewtonOptions::default(), 2.0, 1.0),
            linkage.motion_near(0.52, &guess, &NewtonOptions::default(), 2.0, 1.0),
        );
        assert!(
            newton
                .motion_near(0.52, &guess, &NewtonOptions::default(), 2.0, 1.0)
                .is_ok()
        );
    }
}

#[test]
fn a_parameter_that_is_not_finite_is_named_when_the_solver_is_made() {
    let linkage = OpenFourBar {
        l1: 180.0,
        l2: 80.0,
        l3: f64::NAN,
        l4: 150.0,
    };
    assert_eq!(
        linkage.newton().unwrap_err(),
        Error::NonFinite {
            quantity: "parameter `l3`"
        }
    );
}

#[test]
fn a_slider_input_gives_the_general_bits_at_every_size() {
    let linkage = Trammel { l: 2.0 };
    let newton = linkage.newton().unwrap();
    // Near the assembly at x = 1: the rod at 120°, its top at √3.
    let guess = TrammelUnknowns { theta: 2.1, y: 1.7 };
    let options = NewtonOptions::default();
    // Within reach, beyond it, not finite, and a slide so long the size is not taken as given.
    for x in [1.0, 1.05, 2.5, f64::NAN, 1e300] {
        same(
            newton.motion_near(x, &guess, &options, 0.5, 0.1),
            linkage.motion_near(x, &guess, &options, 0.5, 0.1),
        );
    }
    assert!(newton.motion_near(1.05, &guess, &options, 0.5, 0.1).is_ok());
}

#[test]
fn a_scale_with_a_factor_gives_the_general_bits() {
    // The ground 180 (an ordinary four-bar, its scale 610), then too long to close, then so
    // long the scale overflows (the size is then not taken as given: the scaled solve).
    for l1 in [180e-6, 1e-3, 1e303] {
        let linkage = StretchedGround {
            l1,
            l2: 80.0,
            l3: 200.0,
            l4: 150.0,
        };
        let newton = linkage.newton().unwrap();
        let guess = StretchedGroundUnknowns {
            theta3: 0.34,
            theta4: 1.47,
        };
        let options = NewtonOptions::default();
        let prepared = newton.motion_near(0.52, &guess, &options, 2.0, 1.0);
        same(
            prepared,
            linkage.motion_near(0.52, &guess, &options, 2.0, 1.0),
        );
        assert_eq!(prepared.is_ok(), l1 < 1e-3, "l1 = {l1:e}: {prepared:?}");
    }
}

/// An angle turned only with an offset is bounded as the others are: a guess some turns out
/// is taken by whole turns, and no solution is beyond ±17 rad. The common path let such an
/// angle's iterates run unchecked: from a guess three turns out it returned ψ = 18.4, and
/// from a thousand turns out ψ = 6284.0, 9.1e-13 rad off where the accuracy stated 2.9e-14,
/// while a tolerance of −0 (left to the safeguarded solve) gave ψ = −0.45.
#[test]
fn an_angle_turned_only_with_an_offset_is_taken_by_whole_turns() {
    let linkage = OffsetRocker {
        l1: 180.0,
        l2: 80.0,
        l3: 200.0,
        l4: 150.0,
    };
    let newton = linkage.newton().unwrap();
    let (theta2, theta3, psi) = (0.52, 0.496_739_648_799_801_1, -0.450_065_911_624_844_2);
    let turn = 2.0 * std::f64::consts::PI;
    for turns in [0.0, 2.0, 3.0, 1000.0, 1e5, -3.0] {
        let guess = OffsetRockerUnknowns {
            theta3: theta3 + 1e-5,
            psi: psi + 1e-5 + turns * turn,
        };
        let mut found = Vec::new();
        for tolerance in [0.0, -0.0, 1e-9] {
            let options = NewtonOptions::new(tolerance, 50);
            let prepared = newton.motion_near(theta2, &guess, &options, 2.0, 1.0);
            same(
                prepared,
                linkage.motion_near(theta2, &guess, &options, 2.0, 1.0),
            );
            let solved = prepared.unwrap().value.position;
            assert!(
                solved.psi.abs() <= 17.0,
                "{turns} turns, {tolerance:e}: {solved:?}"
            );
            // The guess's turn where that is within 16 rad, else the angle within a turn.
            let expected = if (psi + turns * turn).abs() <= 16.0 {
                psi + turns * turn
            } else {
                psi
            };
            assert!(
                (solved.psi - expected).abs() < 1e-12,
                "{turns} turns, {tolerance:e}: {solved:?}"
            );
            found.push(solved.psi);
        }
        // A tolerance of zero, either sign, the same solve.
        assert_eq!(found[0], found[1], "{turns} turns");
    }
}

/// The Stephenson six-bar's reduced iteration carries a closed form's angle to the guess's
/// turn only within ±17 rad: from a guess of 15.99 rad it returned θ5 = 18.2 (edge found by
/// an adversarial review), where every angle of a solution is said to be within ±17.
#[test]
fn a_reduced_solve_keeps_its_angles_within_seventeen_radians() {
    let (linkage, _) = stephenson_six_bar();
    let newton = linkage.newton().unwrap();
    let guess = mechanisms::StephensonSixBarUnknowns {
        theta3: 1000.2,
        theta4: 0.704_946_031_545_711,
        theta5: 15.99,
        theta6: 44.282_297_150_257_1,
    };
    let options = NewtonOptions::new(0.0, 10);
    let t = 3.150_249_570_974_060_6;
    let prepared = newton.motion_near(t, &guess, &options, 1.0, 0.0);
    same(prepared, linkage.motion_near(t, &guess, &options, 1.0, 0.0));
    let solved = prepared.unwrap().value.position.to_array();
    assert!(solved.iter().all(|a| a.abs() <= 17.0), "{solved:?}");
    let position = linkage
        .position(t, &guess, &options)
        .unwrap()
        .value
        .to_array();
    assert!(position.iter().all(|a| a.abs() <= 17.0), "{position:?}");
}
