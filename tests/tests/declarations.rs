//! The declaration language beyond the shipped mechanisms: a length as the driven input,
//! constant offsets in angles, scaled magnitudes, a leading negative term, a position-only
//! declaration and one without parameters. Each generated solver is checked against geometry
//! or finite differences.

use mechgen::{Branch, NewtonOptions, mechanism};

mechanism! {
    /// A slider-crank driven by its slider: `d` is pushed, the crank angle follows.
    pub struct SliderDriven {
        params: l2, l3;
        input: d: length;
        unknowns: theta2: angle, theta3: angle;
        loop: -d @ 0 + l2 @ theta2 + l3 @ theta3;
    }
}

mechanism! {
    /// A four-bar written with the rocker's angle measured from +y (`psi + pi / 2`), the
    /// coupler given as twice a half-length, and the crank offset by a constant angle.
    pub struct Rewritten {
        params: l1, l2, half_l3, l4, offset: angle;
        input: phi: angle;
        unknowns: theta3: angle, psi: angle;
        loop: l2 @ (phi + offset) + 2 * half_l3 @ theta3 - l4 @ (psi + pi / 2) - l1 @ 0;
        generate: position;
    }
}

mechanism! {
    /// A block pushed along x by `d` slides up a 45° ramp: no parameters, the input sets
    /// the size.
    pub struct Ramp {
        input: d: length;
        unknowns: rise: length, along: length;
        loop: d @ 0 + rise @ (pi / 2) - along @ (pi / 4);
    }
}

#[test]
fn a_declaration_without_parameters_is_built_by_new_and_solves() {
    let ramp = Ramp::new();
    assert_eq!(ramp, Ramp::default());
    let q = ramp.assemble(3.0_f64).unwrap();
    assert!((q.rise - 3.0).abs() < 1e-12);
    assert!((q.along - 3.0 * 2f64.sqrt()).abs() < 1e-12);
    let v = ramp.velocity(3.0, &q, 2.0).unwrap();
    assert!((v.rise - 2.0).abs() < 1e-12);
    let guess = RampUnknowns {
        rise: 0.0,
        along: 0.0,
    };
    let solved = ramp
        .position(3.0, &guess, &NewtonOptions::default())
        .unwrap();
    assert!((solved.value.rise - q.rise).abs() < 1e-12);
}

#[test]
fn a_length_can_drive_the_mechanism() {
    let linkage = SliderDriven {
        l2: 50.0,
        l3: 150.0,
    };
    let options = NewtonOptions::default();
    let mut q = SliderDrivenUnknowns {
        theta2: 1.0,
        theta3: -0.3,
    };
    for step in 0..50 {
        let d = 120.0 + f64::from(step);
        q = linkage.position(d, &q, &options).unwrap().value;
        // The crank pin is l2 from O2 and l3 from the slider pin (d, 0).
        let (ax, ay) = (50.0 * q.theta2.cos(), 50.0 * q.theta2.sin());
        assert!(((ax - d).hypot(ay) - 150.0).abs() < 1e-10);

        let h = 1e-5;
        let plus = linkage.position(d + h, &q, &options).unwrap().value;
        let minus = linkage.position(d - h, &q, &options).unwrap().value;
        let v = linkage.velocity(d, &q, 3.0).unwrap();
        let estimate = (plus.theta2 - minus.theta2) / (2.0 * h) * 3.0;
        assert!(
            (v.theta2 - estimate).abs() < 1e-7,
            "{} vs {estimate}",
            v.theta2
        );
        // With the slide at a steady 3 per second, the angle's acceleration is how its rate
        // changes along the slide, times 3.
        let a = linkage.acceleration(d, &q, 3.0, &v, 0.0).unwrap();
        let rate_plus = linkage.velocity(d + h, &plus, 3.0).unwrap();
        let rate_minus = linkage.velocity(d - h, &minus, 3.0).unwrap();
        let estimate = (rate_plus.theta2 - rate_minus.theta2) / (2.0 * h) * 3.0;
        assert!(
            (a.theta2 - estimate).abs() < 1e-9 * (1.0 + estimate.abs()),
            "{} vs {estimate}",
            a.theta2
        );
    }
}

#[test]
fn rewritten_four_bar_agrees_with_the_shipped_one() {
    let rewritten = Rewritten {
        l1: 180.0,
        l2: 80.0,
        half_l3: 100.0,
        l4: 150.0,
        offset: 0.1,
    };
    let shipped = mechanisms::FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let options = NewtonOptions::default();
    let phi = 0.9;
    let guess = RewrittenUnknowns {
        theta3: 0.4,
        psi: 1.2 - std::f64::consts::FRAC_PI_2,
    };
    let q = rewritten.position(phi, &guess, &options).unwrap().value;
    let reference = shipped
        .position(
            phi + 0.1,
            &mechanisms::FourBarUnknowns {
                theta3: 0.4,
                theta4: 1.2,
            },
            &options,
        )
        .unwrap()
        .value;
    assert!((q.theta3 - reference.theta3).abs() < 1e-12);
    assert!((q.psi + std::f64::consts::FRAC_PI_2 - reference.theta4).abs() < 1e-12);
}

mechanism! {
    /// The four-bar with negated magnitudes instead of subtracted terms.
    pub struct NegatedMagnitudes {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 + -l4 @ theta4 + -l1 @ 0;
    }
}

mechanism! {
    /// The four-bar with names that generated locals are derived from: the input `sin`
    /// (rate `sin_dot`) and the unknown `dot` (whose sine would be `sin_dot`).
    pub struct AwkwardNames {
        params: l1, l2, l3, l4;
        input: sin: angle;
        unknowns: dot: angle, r#fn: angle;
        loop: l2 @ sin + l3 @ dot - l4 @ r#fn - l1 @ 0;
        point r#loop = l2 @ sin;
    }
}

/// Example 1's open position and rates, from the shipped four-bar.
fn example_1_reference(theta2: f64) -> ([f64; 2], [f64; 2]) {
    let shipped = mechanisms::FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let q = shipped.assemble(theta2, Branch::Open).unwrap();
    let v = shipped.velocity(theta2, &q, 10.0).unwrap();
    (q.to_array(), v.to_array())
}

#[test]
fn negated_magnitudes_converge_to_the_rounding_floor() {
    let linkage = NegatedMagnitudes {
        l1: 180.0,
        l2: 80.0,
        l3: 200.0,
        l4: 150.0,
    };
    for degree in (0..360).step_by(5) {
        let theta2 = f64::from(degree).to_radians();
        let (reference, _) = example_1_reference(theta2);
        let guess = NegatedMagnitudesUnknowns::from_array(reference);
        let solved = linkage
            .position(theta2 + 1e-3, &guess, &NewtonOptions::default())
            .unwrap_or_else(|error| panic!("{degree}°: {error}"));
        // The same linkage as the shipped four-bar: the same angles, a residual at the
        // rounding of its 200-unit vectors.
        let (expected, _) = example_1_reference(theta2 + 1e-3);
        let found = solved.value.to_array();
        for (found, expected) in found.iter().zip(expected) {
            assert!(
                (found - expected).abs() < 1e-12,
                "{degree}°: {found} vs {expected}"
            );
        }
        assert!(
            solved.residual_norm < 1e-12,
            "{degree}°: {}",
            solved.residual_norm
        );
    }
}

#[test]
fn generated_names_never_shadow_each_other() {
    let linkage = AwkwardNames {
        l1: 180.0,
        l2: 80.0,
        l3: 200.0,
        l4: 150.0,
    };
    let theta2 = 1.0;
    let (q_ref, v_ref) = example_1_reference(theta2);
    let q = AwkwardNamesUnknowns::from_array(q_ref);
    let v = linkage.velocity(theta2, &q, 10.0).unwrap().to_array();
    assert!((v[0] - v_ref[0]).abs() < 1e-12 && (v[1] - v_ref[1]).abs() < 1e-12);
    assert_eq!(AwkwardNamesUnknowns::<f64>::NAMES, ["dot", "fn"]);
    let pin = linkage.points(theta2, &q).unwrap().r#loop;
    assert!((pin.x - 80.0 * theta2.cos()).abs() < 1e-12);
}

mechanism! {
    /// A cross-slide table: the arm `r @ theta` is reached by sliding `x` along x and then
    /// `y` along y, two unknown lengths in one loop (Chace's linear case).
    pub struct CrossSlide {
        params: r;
        input: theta: angle;
        unknowns: x: length, y: length;
        loop: r @ theta - x @ 0 - y @ pi / 2;
    }
}

#[test]
fn two_unknown_lengths_solve_linearly_without_a_branch() {
    let table = CrossSlide { r: 2.0 };
    let q = table.assemble(0.5).unwrap();
    assert!((q.x - 2.0 * 0.5f64.cos()).abs() < 1e-15);
    assert!((q.y - 2.0 * 0.5f64.sin()).abs() < 1e-15);
}

mechanism! {
    /// A slider on a line at 30°, its offset square to the line, written in degrees.
    pub struct InclinedDegrees {
        params: l2, l3, c;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - c @ 120 deg - d @ 30 deg;
    }
}

mechanism! {
    /// The same, in radians.
    pub struct InclinedRadians {
        params: l2, l3, c;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - c @ 2 * pi / 3 - d @ pi / 6;
    }
}

#[test]
fn angles_can_be_written_in_degrees() {
    let degrees = InclinedDegrees {
        l2: 40.0,
        l3: 130.0,
        c: 15.0,
    };
    let radians = InclinedRadians {
        l2: 40.0,
        l3: 130.0,
        c: 15.0,
    };
    for step in 0..36 {
        let theta2 = f64::from(step) * 10f64.to_radians();
        let a = degrees.motion(theta2, Branch::Open, 3.0, 1.0).unwrap();
        let b = radians.motion(theta2, Branch::Open, 3.0, 1.0).unwrap();
        for (x, y) in [
            (a.position.theta3, b.position.theta3),
            (a.position.d, b.position.d),
            (a.velocity.d, b.velocity.d),
            (a.acceleration.d, b.acceleration.d),
        ] {
            assert!((x - y).abs() <= 1e-12 * y.abs().max(1.0), "{x} against {y}");
        }
        // The slider is on the 30° line, `c` off it: B − (d·e^{i30°} + c·e^{i120°}) = 0.
        let (s2, c2) = theta2.sin_cos();
        let (s3, c3) = a.position.theta3.sin_cos();
        let b_x = 40.0 * c2 + 130.0 * c3;
        let b_y = 40.0 * s2 + 130.0 * s3;
        let (s30, c30) = 30f64.to_radians().sin_cos();
        let (s120, c120) = 120f64.to_radians().sin_cos();
        let gap_x = b_x - a.position.d * c30 - 15.0 * c120;
        let gap_y = b_y - a.position.d * s30 - 15.0 * s120;
        assert!(gap_x.hypot(gap_y) < 1e-12 * 200.0, "gap {gap_x}, {gap_y}");
    }
}

mechanism! {
    /// The same slider, its line's angle and the offset's written with functions of numbers:
    /// `atan2(1, sqrt(3))` is 30°, and `hypot(3, 4) / 5` a factor of one.
    pub struct InclinedFunctions {
        params: l2, l3, c;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - hypot(3, 4) / 5 * c @ (pi / 2 + atan2(1, sqrt(3)))
            - d @ atan2(sin(30 deg), cos(pi / 6));
    }
}

/// Functions of numbers (sqrt, sin, cos, tan, atan2, hypot) are evaluated at compile time,
/// in magnitudes' factors and in angles: the same slider as in degrees, to rounding.
#[test]
fn functions_of_numbers_are_constants() {
    let functions = InclinedFunctions {
        l2: 40.0,
        l3: 130.0,
        c: 15.0,
    };
    let degrees = InclinedDegrees {
        l2: 40.0,
        l3: 130.0,
        c: 15.0,
    };
    for step in 0..36 {
        let theta2 = f64::from(step) * 10f64.to_radians();
        let a = functions.motion(theta2, Branch::Open, 3.0, 1.0).unwrap();
        let b = degrees.motion(theta2, Branch::Open, 3.0, 1.0).unwrap();
        for (x, y) in [
            (a.position.theta3, b.position.theta3),
            (a.position.d, b.position.d),
            (a.velocity.theta3, b.velocity.theta3),
            (a.acceleration.d, b.acceleration.d),
        ] {
            assert!((x - y).abs() <= 1e-12 * y.abs().max(1.0), "{x} against {y}");
        }
    }
}

mechanism! {
    /// A four-bar whose fixed pivot O4 is given by its coordinates `(gx, gy)`: the ground
    /// link is `hypot(gx, gy)` long at `atan2(gy, gx)`, and the coupler point sits `p` along
    /// and `q` across the coupler, at `hypot(p, q)` and `atan2(q, p)` from it. Formulas of
    /// parameters, in magnitudes and angles.
    pub struct FromCoordinates {
        params: gx, gy, l2, l3, l4, p, q;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - hypot(gx, gy) @ atan2(gy, gx);
        point coupler = l2 @ theta2 + hypot(p, q) @ (theta3 + atan2(q, p));
        generate: position, velocity, acceleration, sensitivities;
        scene trace: coupler, coupler_dot;
    }
}

mechanism! {
    /// A slider whose line is offset by `sqrt(a² − b²)`: a formula that is undefined where
    /// `b > a`.
    pub struct Undefined {
        params: a, b, l2, l3;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - sqrt(a * a - b * b) @ (pi / 2) - d @ 0;
    }
}

/// A pivot at (gx, gy) is the Example 1 four-bar turned by the ground's angle: the formula
/// four-bar at `θ2` is the shipped one at `θ2 − atan2(gy, gx)`, every angle turned back.
#[test]
fn formulas_of_parameters_are_constants_of_the_mechanism() {
    let (gx, gy): (f64, f64) = (180.0 * 0.6, 180.0 * 0.8);
    let turn = gy.atan2(gx);
    let linkage = FromCoordinates {
        gx,
        gy,
        l2: 80.0,
        l3: 200.0,
        l4: 150.0,
        p: 60.0,
        q: 80.0,
    };
    let shipped = mechanisms::FourBar::new(180.0, 80.0, 200.0, 150.0)
        .and_then(|four_bar| four_bar.with_coupler_point(100.0, 80f64.atan2(60.0)))
        .unwrap();
    let scenes = linkage.scenes().unwrap();
    // 2^600 times larger, solved on the mechanism scaled back: its formulas scale with it.
    let huge = 2f64.powi(600);
    let large = FromCoordinates {
        gx: gx * huge,
        gy: gy * huge,
        l2: 80.0 * huge,
        l3: 200.0 * huge,
        l4: 150.0 * huge,
        p: 60.0 * huge,
        q: 80.0 * huge,
    };
    for step in 0..36 {
        let theta2 = f64::from(step) * 10f64.to_radians();
        let ours = linkage.motion(theta2, Branch::Open, 3.0, 1.0).unwrap();
        let scaled = large.motion(theta2, Branch::Open, 3.0, 1.0).unwrap();
        assert_eq!(scaled.position, ours.position);
        assert_eq!(scaled.acceleration, ours.acceleration);
        let theirs = shipped
            .motion(theta2 - turn, Branch::Open, 3.0, 1.0)
            .unwrap();
        let wrapped = |a: f64| (a + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU);
        for (x, y) in [
            (ours.position.theta3, theirs.position.theta3 + turn),
            (ours.position.theta4, theirs.position.theta4 + turn),
        ] {
            assert!((wrapped(x) - wrapped(y)).abs() < 1e-12, "{x} against {y}");
        }
        for (x, y) in [
            (ours.velocity.theta3, theirs.velocity.theta3),
            (ours.acceleration.theta4, theirs.acceleration.theta4),
        ] {
            assert!((x - y).abs() <= 1e-12 * y.abs().max(1.0), "{x} against {y}");
        }
        // The coupler point: the shipped one's, turned by the ground's angle.
        let point = linkage.points(theta2, &ours.position).unwrap().coupler;
        let q = shipped.assemble(theta2 - turn, Branch::Open).unwrap();
        let expected = shipped.points(theta2 - turn, &q).unwrap().coupler_point;
        let (s, c) = turn.sin_cos();
        let turned = (
            expected.x * c - expected.y * s,
            expected.x * s + expected.y * c,
        );
        assert!((point.x - turned.0).hypot(point.y - turned.1) < 1e-10);
        // The scene, whose formulas are computed once by `scenes()`.
        let traced = scenes.trace(theta2, Branch::Open, 3.0).unwrap();
        assert!((traced.coupler.x - point.x).hypot(traced.coupler.y - point.y) < 1e-10);
    }
}

/// The sensitivities differentiate through the formulas: `∂θ4/∂gx` and the coupler point's
/// `∂/∂q` against central differences of the closed form.
#[test]
fn sensitivities_differentiate_through_formulas() {
    let linkage = FromCoordinates {
        gx: 108.0,
        gy: 144.0,
        l2: 80.0,
        l3: 200.0,
        l4: 150.0,
        p: 60.0,
        q: 80.0,
    };
    let theta2 = 1.0;
    let q = linkage.assemble(theta2, Branch::Open).unwrap();
    let found = linkage.sensitivities(theta2, &q).unwrap();
    let points = linkage.point_sensitivities(theta2, &q).unwrap();
    let h = 1e-5;
    let along = |change: &dyn Fn(&mut FromCoordinates<f64>, f64)| {
        let solve = |sign: f64| {
            let mut moved = linkage;
            change(&mut moved, sign * h);
            let position = moved.assemble(theta2, Branch::Open).unwrap();
            let point = moved.points(theta2, &position).unwrap().coupler;
            (position.theta4, point)
        };
        let ((a, pa), (b, pb)) = (solve(1.0), solve(-1.0));
        (
            (a - b) / (2.0 * h),
            ((pa.x - pb.x) / (2.0 * h), (pa.y - pb.y) / (2.0 * h)),
        )
    };
    let (theta4_by_gx, _) = along(&|m, d| m.gx += d);
    assert!(
        (found.gx.theta4 - theta4_by_gx).abs() < 1e-8,
        "{:?} vs {theta4_by_gx}",
        found.gx
    );
    let (_, point_by_q) = along(&|m, d| m.q += d);
    assert!(
        (points.q.coupler.x - point_by_q.0).abs() < 1e-6,
        "{:?}",
        points.q.coupler
    );
    assert!(
        (points.q.coupler.y - point_by_q.1).abs() < 1e-6,
        "{:?}",
        points.q.coupler
    );
}

/// A formula undefined for the dimensions given is an error that names it, not a NaN.
#[test]
fn an_undefined_formula_is_an_error() {
    let defined = Undefined {
        a: 5.0f64,
        b: 3.0,
        l2: 40.0,
        l3: 130.0,
    };
    let q = defined.assemble(1.0, Branch::Open).unwrap();
    assert!(q.d.is_finite());
    let undefined = Undefined { b: 6.0, ..defined };
    assert_eq!(
        undefined.assemble(1.0, Branch::Open),
        Err(mechgen::Error::NonFinite {
            quantity: "parameter formula `sqrt(a * a - b * b)`"
        })
    );
    let guess = UndefinedUnknowns {
        theta3: 0.0,
        d: 100.0,
    };
    assert!(matches!(
        undefined.position(1.0, &guess, &NewtonOptions::default()),
        Err(mechgen::Error::NonFinite { .. })
    ));
}

/// A formula whose square of a length overflows as given (a length of 1e154 and more), though
/// the formula itself (4e160 here) does not: the solvers' check of it and `branch_of` read it
/// on the mechanism scaled by a power of two, as they solve it. An adversarial review found
/// `assemble`, `motion`, `newton()` and the rates refusing such a mechanism as `NonFinite`,
/// where `position` and `motion_near` solved it, and `branch_of` calling its open assembly
/// crossed.
#[test]
fn a_formula_whose_square_overflows_is_read_at_the_solvers_scale() {
    let unit = Undefined {
        a: 5.0f64,
        b: 3.0,
        l2: 2.0,
        l3: 9.0,
    };
    let theta2 = 0.7;
    for scale in [1e100, 1e154, 1e160, 2f64.powi(600)] {
        let linkage = Undefined {
            a: 5.0 * scale,
            b: 3.0 * scale,
            l2: 2.0 * scale,
            l3: 9.0 * scale,
        };
        for branch in [Branch::Open, Branch::Crossed] {
            let q = linkage.assemble(theta2, branch).unwrap();
            let expected = unit.assemble(theta2, branch).unwrap();
            assert!((q.theta3 - expected.theta3).abs() < 1e-12, "{scale:e}");
            assert!((q.d / scale - expected.d).abs() < 1e-12 * expected.d.abs());
            assert_eq!(linkage.branch_of(theta2, &q), branch, "{scale:e}");
            let motion = linkage.motion(theta2, branch, 10.0, 1.0).unwrap();
            let unit_motion = unit.motion(theta2, branch, 10.0, 1.0).unwrap();
            let velocity = linkage.velocity(theta2, &q, 10.0).unwrap();
            assert!((motion.velocity.d / scale - unit_motion.velocity.d).abs() < 1e-9);
            assert!((velocity.d / scale - unit_motion.velocity.d).abs() < 1e-9);
        }
        let guess = UndefinedUnknowns {
            theta3: 0.3,
            d: 10.0 * scale,
        };
        let options = NewtonOptions::default();
        let near = linkage
            .motion_near(theta2, &guess, &options, 10.0, 1.0)
            .unwrap();
        let prepared = linkage.newton().unwrap();
        assert_eq!(
            prepared.motion_near(theta2, &guess, &options, 10.0, 1.0),
            Ok(near)
        );
    }
}

mechanism! {
    /// Example 1's four-bar with its coupler's length a formula, `sqrt(l3 * l3)`: a turning
    /// vector whose magnitude is a formula, in a scene (whose rate limits weigh it as a
    /// column of its own).
    pub struct CouplerFormula {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + sqrt(l3 * l3) @ theta3 - l4 @ theta4 - l1 @ 0;
        scene angles: theta3, theta4, theta3_dot, theta4_ddot;
    }
}

#[test]
fn a_turning_vector_may_be_a_formula() {
    let linkage = CouplerFormula {
        l1: 180.0,
        l2: 80.0,
        l3: 200.0,
        l4: 150.0,
    };
    let shipped = mechanisms::FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let scenes = linkage.scenes().unwrap();
    for step in 0..36 {
        let theta2 = f64::from(step) * 10f64.to_radians();
        let ours = scenes.angles(theta2, Branch::Open, 3.0, 1.0).unwrap();
        let theirs = shipped.motion(theta2, Branch::Open, 3.0, 1.0).unwrap();
        assert!((ours.theta3 - theirs.position.theta3).abs() < 1e-12);
        assert!((ours.theta3_dot - theirs.velocity.theta3).abs() < 1e-12);
        assert!((ours.theta4_ddot - theirs.acceleration.theta4).abs() < 1e-11);
    }
}
