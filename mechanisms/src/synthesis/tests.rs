//! The synthesis's tests, beside it (so that its mutants meet them): Levenberg–Marquardt on
//! the generated derivatives finds linkages whose output or coupler point meets precision
//! points, agrees with Freudenstein's closed form where that applies, keeps its constraints,
//! and gives the same answer from the same seed on any number of cores.

use super::{
    Options, SynthesisError, freudenstein, freudenstein_least_squares, function_generation,
    path_generation, rms,
};
use crate::FourBar;
use mechgen::grashof::Inversion;
use mechgen::{Branch, Vec2};
use std::string::ToString;
use std::vec::Vec;

/// The rms error is the same at every scale a float holds: its squares neither overflow near
/// 1e300 (to an infinite error) nor underflow near 1e-300 (to a false zero).
#[test]
fn rms_error_neither_overflows_nor_underflows() {
    assert_eq!(rms(&[3.0, -4.0]), 12.5f64.sqrt());
    for scale in [1e300, 1e-300, 1e-310] {
        let scaled = rms(&[3.0 * scale, -4.0 * scale]);
        let relative = (scaled / (12.5f64.sqrt() * scale) - 1.0).abs();
        assert!(relative < 1e-12, "{scale}: {scaled}");
    }
    assert_eq!(rms(&[]), 0.0);
    assert_eq!(rms(&[0.0, -0.0]), 0.0);
    assert_eq!(rms(&[1.0, f64::NEG_INFINITY]), f64::INFINITY);
    assert!(rms(&[1.0, f64::NAN]).is_nan());
}

/// Example 1 with its coupler point 100 from A at 30°.
fn example() -> FourBar<f64> {
    FourBar::new(180.0, 80.0, 200.0, 150.0)
        .and_then(|l| l.with_coupler_point(100.0, 30f64.to_radians()))
        .unwrap()
}

/// The Watt six-bar the integration tests use (tests/tests/common): Example 1 carrying a
/// second dyad.
fn watt_example() -> crate::WattSixBar<f64> {
    crate::WattSixBar::new(
        [180.0, 80.0, 200.0, 150.0],
        100.0,
        0.8,
        220.0,
        160.0,
        (300.0, 150.0),
    )
    .unwrap()
}

/// Example 1's rocker angles at `phi`, open branch.
fn outputs(phi: &[f64]) -> Vec<f64> {
    phi.iter()
        .map(|&p| example().assemble(p, Branch::Open).unwrap().theta4)
        .collect()
}

/// Example 1's coupler point at `theta2`, open branch, moved to a frame with its crank pivot
/// at (30, −20) and its ground line at 25°.
fn target(theta2: f64) -> Vec2<f64> {
    let l = example();
    let q = l.assemble(theta2, Branch::Open).unwrap();
    let p = l.points(theta2, &q).unwrap().coupler_point;
    let (s, c) = 25f64.to_radians().sin_cos();
    Vec2 {
        x: 30.0 + c * p.x - s * p.y,
        y: -20.0 + s * p.x + c * p.y,
    }
}

#[test]
fn three_precision_points_give_freudensteins_closed_form() {
    // A function no four-bar follows exactly: y = log10(x) for x in [1, 2], the input
    // turning 30..90° and the output 60..120° (Chebyshev spacing of the three points).
    let spacing = [0.0669873f64, 0.5, 0.9330127];
    let phi = spacing.map(|s| (30.0 + 60.0 * s).to_radians());
    let psi = spacing.map(|s| (60.0 + 60.0 * (1.0 + s).log10() / 2f64.log10()).to_radians());
    let closed = freudenstein(100.0, phi, psi).expect("a linkage");
    // Whichever branch the closed form's linkage meets the points on.
    let branch = [Branch::Open, Branch::Crossed]
        .into_iter()
        .find(|&b| {
            let l = FourBar::new(closed[0], closed[1], closed[2], closed[3]).unwrap();
            phi.iter()
                .zip(&psi)
                .all(|(&p, &s)| l.assemble(p, b).is_ok_and(|q| (q.theta4 - s).abs() < 1e-9))
        })
        .expect("the closed form meets its points on one branch");
    let options = Options {
        branch,
        ..Options::default()
    };
    let found = function_generation(100.0, &phi, &psi, &options).unwrap();
    assert!(found.rms_error < 1e-12, "{}", found.rms_error);
    for (a, b) in found.linkage.lengths().iter().zip(closed) {
        assert!(
            (a - b).abs() < 1e-8 * b,
            "{:?} against {closed:?}",
            found.linkage.lengths()
        );
    }
}

#[test]
fn function_generation_recovers_a_linkage_from_its_own_outputs() {
    let phi: Vec<f64> = (0..7).map(|k| 0.5 * f64::from(k)).collect();
    let found = function_generation(180.0, &phi, &outputs(&phi), &Options::default()).unwrap();
    let [_, a, b, c] = found.linkage.lengths();
    assert!((a - 80.0).abs() < 1e-8 && (b - 200.0).abs() < 1e-8 && (c - 150.0).abs() < 1e-8);
    assert!(found.rms_error < 1e-12 && found.largest_error < 1e-12);
    assert!(found.converged >= 1 && found.feasible >= 1);
}

#[test]
fn function_generation_keeps_its_constraints() {
    // Example 1's output at seven crank angles round the turn, asked of a crank with its
    // transmission angle within a degree of Example 1's own extremes: Example 1 meets it.
    let extremes = example().transmission_extremes();
    let (low, high) = (
        extremes.min - 1f64.to_radians(),
        extremes.max + 1f64.to_radians(),
    );
    let phi: Vec<f64> = (0..7).map(|k| 0.9 * f64::from(k)).collect();
    let options = Options {
        crank: true,
        transmission: Some((low, high)),
        ..Options::default()
    };
    let found = function_generation(180.0, &phi, &outputs(&phi), &options).unwrap();
    let l = found.linkage;
    assert!(matches!(
        l.grashof().inversion,
        Inversion::CrankRocker | Inversion::DoubleCrank
    ));
    for k in 0..360 {
        let q = l.assemble(f64::from(k).to_radians(), Branch::Open).unwrap();
        let gamma = l.transmission_angle(&q);
        assert!((low..=high).contains(&gamma), "{k}°: transmission {gamma}");
    }
    assert!(found.rms_error < 1e-12, "{}", found.rms_error);
    // Within a degree of 90° all the turn, no crank follows it.
    let options = Options {
        crank: true,
        transmission: Some((89f64.to_radians(), 91f64.to_radians())),
        restarts: 16,
        ..Options::default()
    };
    let error = function_generation(180.0, &phi, &outputs(&phi), &options).unwrap_err();
    assert!(matches!(error, SynthesisError::NothingFeasible { converged } if converged > 0));
    assert!(error.to_string().contains("no linkage meets"), "{error}");
}

#[test]
fn path_generation_with_timing_recovers_the_linkage_and_its_placement() {
    let timing: Vec<f64> = (0..6).map(f64::from).collect();
    let targets: Vec<Vec2<f64>> = timing.iter().map(|&t| target(t)).collect();
    let found = path_generation(&targets, Some(&timing), &Options::default()).unwrap();
    assert!(found.rms_error < 1e-9, "{}", found.rms_error);
    let [l1, l2, l3, l4] = found.linkage.lengths();
    for (a, b) in [(l1, 180.0), (l2, 80.0), (l3, 200.0), (l4, 150.0)] {
        assert!((a - b).abs() < 1e-6, "{:?}", found.linkage.lengths());
    }
    let (pivot, angle) = found.placement;
    assert!((pivot.x - 30.0).abs() < 1e-6 && (pivot.y + 20.0).abs() < 1e-6);
    assert!((angle.to_degrees().rem_euclid(360.0) - 25.0).abs() < 1e-6);
}

#[test]
fn path_generation_without_timing_passes_through_the_points() {
    let targets: Vec<Vec2<f64>> = (0..10).map(|k| target(0.6 * f64::from(k))).collect();
    let options = Options {
        restarts: 128,
        ..Options::default()
    };
    let found = path_generation(&targets, None, &options).unwrap();
    assert!(found.rms_error < 1e-7, "{}", found.rms_error);
}

#[test]
fn the_same_seed_gives_the_same_linkage_on_any_number_of_cores() {
    // Example 1's output bent a little: a fit, not an exact solution.
    let phi: Vec<f64> = (0..8).map(|k| 0.8 * f64::from(k)).collect();
    let psi: Vec<f64> = phi
        .iter()
        .zip(outputs(&phi))
        .map(|(p, out)| out + 0.01 * (3.0 * p).sin())
        .collect();
    let options = Options {
        restarts: 32,
        seed: 7,
        ..Options::default()
    };
    let many = function_generation(180.0, &phi, &psi, &options).unwrap();
    assert!(
        many.rms_error > 1e-4 && many.rms_error < 0.01,
        "{}",
        many.rms_error
    );
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| function_generation(180.0, &phi, &psi, &options).unwrap());
    assert_eq!(many, one);
}

#[test]
fn bad_targets_and_impossible_constraints_say_why() {
    let too_few = function_generation(100.0, &[0.0, 1.0], &[0.5, 0.7], &Options::default());
    assert!(matches!(too_few, Err(SynthesisError::BadTargets(_))));
    let not_finite = function_generation(
        100.0,
        &[0.0, 1.0, f64::NAN],
        &[0.5, 0.7, 0.9],
        &Options::default(),
    );
    assert!(matches!(not_finite, Err(SynthesisError::BadTargets(_))));
    let few_points = path_generation(&[Vec2 { x: 0.0, y: 0.0 }; 4], None, &Options::default());
    assert!(matches!(few_points, Err(SynthesisError::BadTargets(_))));
}

/// `good_enough`: the classical solution returned as it is where it is within the error
/// asked for, polished where not, and the restarts run only where neither is.
#[test]
fn a_good_enough_classical_start_ends_the_search() {
    let phi: Vec<f64> = (0..6).map(|k| 0.7 * f64::from(k)).collect();
    let psi = outputs(&phi);
    let classical = freudenstein_least_squares(180.0, &phi, &psi).unwrap();
    let quick = Options {
        good_enough: Some(1e-6),
        ..Options::default()
    };
    let found = function_generation(180.0, &phi, &psi, &quick).unwrap();
    // As it is (its lengths through their logarithms and back).
    for (a, b) in found.linkage.lengths().iter().zip(classical) {
        assert!((a - b).abs() <= 1e-13 * b, "{a} against {b}");
    }
    assert_eq!((found.converged, found.feasible), (1, 1));
    // Asked for nothing it can reach, every start runs.
    let exhaustive = Options {
        good_enough: Some(0.0),
        ..Options::default()
    };
    let found = function_generation(180.0, &phi, &psi, &exhaustive).unwrap();
    assert!(found.converged > 1, "{}", found.converged);
}

/// A declaration the project does not ship, with a slide among its unknowns: the offset
/// slider-crank, whose sensitivities make it something `fit` can design.
mod slider {
    mechgen::mechanism! {
        pub struct Slider {
            params: crank, rod, offset;
            input: theta2: angle;
            unknowns: theta3: angle, d: length;
            loop: crank @ theta2 + rod @ theta3 - offset @ (pi / 2) - d @ 0;
            generate: position, velocity, sensitivities;
        }
    }
}

/// `fit` over any declaration with sensitivities: the four-bar's coupler point through
/// points at given crank angles (path generation with timing, the frame held), from a start
/// 10% off in every fitted dimension.
#[test]
fn fit_recovers_a_four_bar_from_its_coupler_points() {
    use super::{Target, fit};
    use mechgen::Design;
    let truth = example();
    let targets: Vec<Target> = (0..8)
        .map(|k| {
            let input = 0.75 * f64::from(k);
            let q = truth.assemble(input, Branch::Open).unwrap();
            let at = truth.points(input, &q).unwrap().coupler_point;
            // The coupler point is the third of the four-bar's points.
            Target::Point {
                input,
                point: 2,
                at,
            }
        })
        .collect();
    let start = FourBar::new(180.0, 88.0, 180.0, 165.0)
        .and_then(|l| l.with_coupler_point(110.0, 0.47))
        .unwrap();
    let guess = start.assemble(0.0, Branch::Open).unwrap().to_array();
    // Everything but the ground, which sets the frame's scale.
    let free = [false, true, true, true, true, true];
    let found = fit(&start, guess, free, &targets, &Options::default()).unwrap();
    assert!(found.rms_error < 1e-9, "{}", found.rms_error);
    let wanted = truth.parameters();
    for (got, want) in found.mechanism.parameters().iter().zip(wanted) {
        assert!(
            (got - want).abs() < 1e-6,
            "{:?}",
            found.mechanism.parameters()
        );
    }
    // Every position is a solution on the start's assembly, at its target's input.
    for (target, position) in targets.iter().zip(&found.positions) {
        let Target::Point { input, .. } = *target else {
            unreachable!()
        };
        let open = found.mechanism.assemble(input, Branch::Open).unwrap();
        assert!((open.theta3 - position[0]).abs() < 1e-9);
    }
}

/// The Watt six-bar's output angle against its crank's, through `fit`: the same problem
/// `watt_function_generation` solves knowing the mechanism.
#[test]
fn fit_recovers_a_watt_six_bar_from_its_output_angles() {
    use super::{Target, fit};
    use crate::{WattSixBar, WattSixBarBranches};
    use mechgen::Design;
    let truth = watt_example();
    let branches = WattSixBarBranches::default();
    let targets: Vec<Target> = (0..8)
        .map(|k| {
            let input = 0.7 * f64::from(k);
            let value = truth.assemble(input, branches).unwrap().theta6;
            Target::Unknown {
                input,
                unknown: 3,
                value,
            }
        })
        .collect();
    let start = WattSixBar::new(
        [180.0, 80.0, 220.0, 135.0],
        110.0,
        0.72,
        242.0,
        144.0,
        (300.0, 150.0),
    )
    .unwrap();
    let guess = start.assemble(0.0, branches).unwrap().to_array();
    // [l1, l2, l3, l4, l5, beta, l6, l7, g, phi]: the coupler, rocker, extension, its angle
    // and the second dyad fitted; ground, crank and output pivot held.
    let free = [
        false, false, true, true, true, true, true, true, false, false,
    ];
    let found = fit(&start, guess, free, &targets, &Options::default()).unwrap();
    assert!(found.rms_error < 1e-10, "{}", found.rms_error);
    for (got, want) in found.mechanism.parameters().iter().zip(truth.parameters()) {
        assert!(
            (got - want).abs() < 1e-6,
            "{:?}",
            found.mechanism.parameters()
        );
    }
}

/// A declaration made here, fitted on a slide: the slider-crank's crank and rod from its
/// slider's positions (a length unknown, compared as it is).
#[test]
fn fit_designs_a_declaration_it_has_never_seen() {
    use super::{Target, fit};
    use mechgen::{Design, Kinematics, NewtonOptions};
    use slider::Slider;
    let truth = Slider::with_parameters([40.0, 130.0, 12.0]);
    let mut guess = [0.0, 170.0];
    let targets: Vec<Target> = (0..6)
        .map(|k| {
            let input = 1.0 * f64::from(k);
            let q = truth
                .solve_near(input, guess, &NewtonOptions::default())
                .unwrap()
                .value;
            guess = q;
            Target::Unknown {
                input,
                unknown: 1,
                value: q[1],
            }
        })
        .collect();
    let start = Slider::with_parameters([45.0, 120.0, 12.0]);
    assert_eq!(Slider::<f64>::PARAMETERS, ["crank", "rod", "offset"]);
    assert_eq!(Slider::<f64>::UNKNOWN_ANGLES, [true, false]);
    let found = fit(
        &start,
        [0.0, 160.0],
        [true, true, false],
        &targets,
        &Options::default(),
    )
    .unwrap();
    assert!(found.rms_error < 1e-10, "{}", found.rms_error);
    let [crank, rod, offset] = found.mechanism.parameters();
    assert!(
        (crank - 40.0).abs() < 1e-8 && (rod - 130.0).abs() < 1e-8,
        "{crank} {rod}"
    );
    assert_eq!(offset, 12.0);
}

// The classical pieces, one at a time.

#[test]
fn least_squares_over_three_points_is_the_closed_form_and_wants_matched_points() {
    let phi = [0.3, 1.2, 2.0];
    let psi: Vec<f64> = outputs(&phi);
    let closed = freudenstein(180.0, phi, [psi[0], psi[1], psi[2]]).unwrap();
    let squares = freudenstein_least_squares(180.0, &phi, &psi).unwrap();
    for (a, b) in squares.iter().zip(closed) {
        assert!((a - b).abs() <= 1e-9 * b, "{squares:?} against {closed:?}");
    }
    for (a, b) in closed.iter().zip([180.0, 80.0, 200.0, 150.0]) {
        assert!((a - b).abs() <= 1e-9 * b, "{closed:?}");
    }
    // Two points are too few; a point without its output, or an output without its point,
    // is refused (not cut to the shorter of the two).
    assert_eq!(
        freudenstein_least_squares(180.0, &phi[..2], &psi[..2]),
        None
    );
    let four = [0.3, 1.2, 2.0, 2.6];
    assert_eq!(freudenstein_least_squares(180.0, &four, &psi), None);
    let more: Vec<f64> = outputs(&four);
    assert_eq!(freudenstein_least_squares(180.0, &phi, &more), None);
    assert!(freudenstein_least_squares(180.0, &four, &more).is_some());
}

#[test]
fn freudensteins_constants_make_a_linkage_only_with_positive_links() {
    use super::lengths_from_freudenstein as lengths;
    // Example 1: K1 = d/a = 2.25, K2 = d/c = 1.2, K3 = (a² + c² + d² − b²)/(2ac) = 0.8875.
    let [d, a, b, c] = lengths(180.0, 2.25, 1.2, 0.8875).unwrap();
    assert_eq!([d, a, c], [180.0, 80.0, 150.0]);
    assert!((b - 200.0).abs() < 1e-12, "{b}");
    // Each condition alone: a crank or a rocker of negative length; a coupler whose square
    // is zero (exactly: a = c = 1, d = 2, K3 = 3) or negative; one that is not finite.
    assert_eq!(lengths(180.0, -2.25, 1.2, 0.8875), None);
    assert_eq!(lengths(180.0, 2.25, -1.2, 0.8875), None);
    assert_eq!(lengths(2.0, 2.0, 2.0, 3.0), None);
    assert!(lengths(2.0, 2.0, 2.0, 2.999).is_some());
    assert_eq!(lengths(2.0, 2.0, 2.0, 3.5), None);
    assert_eq!(lengths(2.0, 2.0, 2.0, f64::NEG_INFINITY), None);
    // A crank or a rocker of zero length (an infinite K1 or K2) is no linkage either.
    assert_eq!(lengths(2.0, f64::INFINITY, 2.0, 1.0), None);
    assert_eq!(lengths(2.0, 2.0, f64::INFINITY, 1.0), None);
    assert_eq!(lengths(2.0, 2.0, 2.0, f64::NAN), None);
}

#[test]
fn the_three_by_three_solve_is_cramers_rule_where_the_matrix_is_regular() {
    use super::solve3;
    let a = [[2.0, 1.0, -1.0], [-3.0, -1.0, 2.0], [-2.0, 1.0, 2.0]];
    assert_eq!(solve3(a, [8.0, -11.0, -3.0]), Some([2.0, 3.0, -1.0]));
    // Its columns, each alone as the right-hand side: each unit vector.
    for k in 0..3 {
        let b = [a[0][k], a[1][k], a[2][k]];
        let mut unit = [0.0; 3];
        unit[k] = 1.0;
        assert_eq!(solve3(a, b), Some(unit), "column {k}");
    }
    // The same at any scale (the test of regularity is relative to the cube of the
    // entries' size, as the determinant is).
    for scale in [1e100, 1e-100] {
        let scaled = a.map(|row| row.map(|v| v * scale));
        let x = solve3(scaled, [8.0, -11.0, -3.0].map(|v| v * scale)).unwrap();
        for (got, want) in x.iter().zip([2.0, 3.0, -1.0]) {
            assert!((got - want).abs() < 1e-12, "{scale}: {x:?}");
        }
    }
    // Singular (a row twice), singular but for a relative 1e-14, and not finite.
    let singular = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 5.0]];
    assert_eq!(solve3(singular, [1.0, 2.0, 3.0]), None);
    let nearly = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0 + 1e-13], [0.0, 1.0, 5.0]];
    assert_eq!(solve3(nearly, [1.0, 2.0, 3.0]), None);
    let regular_enough = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0 + 1e-9], [0.0, 1.0, 5.0]];
    assert!(solve3(regular_enough, [1.0, 2.0, 3.0]).is_some());
    let mut nan = a;
    nan[1][1] = f64::NAN;
    assert_eq!(solve3(nan, [8.0, -11.0, -3.0]), None);
    // Nothing at all: a zero determinant against a zero bound is not regular.
    assert_eq!(solve3([[0.0; 3]; 3], [1.0, 2.0, 3.0]), None);
}

fn refused<T: core::fmt::Debug>(result: Result<T, SynthesisError>) -> &'static str {
    match result {
        Err(SynthesisError::BadTargets(why)) => why,
        other => panic!("not refused: {other:?}"),
    }
}

#[test]
fn function_generation_says_which_of_its_arguments_is_wrong() {
    let phi = [0.0, 0.8, 1.6, 2.4];
    let psi = outputs(&phi);
    let quick = Options {
        restarts: 0,
        ..Options::default()
    };
    let pairs = "function generation needs three or more pairs of input and output angles";
    let values = "the ground length must be positive and every angle finite";
    let generate =
        |ground: f64, phi: &[f64], psi: &[f64]| function_generation(ground, phi, psi, &quick);
    // Three pairs are enough; two are not; an angle without its pair, either way.
    assert!(generate(180.0, &phi[..3], &psi[..3]).is_ok());
    assert_eq!(refused(generate(180.0, &phi[..2], &psi[..2])), pairs);
    assert_eq!(refused(generate(180.0, &phi, &psi[..3])), pairs);
    assert_eq!(refused(generate(180.0, &phi[..3], &psi)), pairs);
    // Each value wrong alone.
    for ground in [0.0, -180.0, f64::INFINITY, f64::NAN] {
        assert_eq!(refused(generate(ground, &phi, &psi)), values, "{ground}");
    }
    let mut bad_phi = phi;
    bad_phi[2] = f64::NAN;
    assert_eq!(refused(generate(180.0, &bad_phi, &psi)), values);
    let mut bad_psi = psi.clone();
    bad_psi[3] = f64::INFINITY;
    assert_eq!(refused(generate(180.0, &phi, &bad_psi)), values);
}

#[test]
fn path_generation_says_which_of_its_arguments_is_wrong() {
    let timing: Vec<f64> = (0..9).map(f64::from).collect();
    let targets: Vec<Vec2<f64>> = timing.iter().map(|&t| target(t)).collect();
    let quick = Options {
        restarts: 2,
        ..Options::default()
    };
    let timed = "path generation with prescribed crank angles needs five or more targets";
    let untimed = "path generation without prescribed crank angles needs nine or more targets";
    let finite = "every target needs finite coordinates, and a crank angle if any has one";
    // Five with their crank angles are enough, four are not; nine without, eight are not.
    assert!(!matches!(
        path_generation(&targets[..5], Some(&timing[..5]), &quick),
        Err(SynthesisError::BadTargets(_))
    ));
    assert_eq!(
        refused(path_generation(&targets[..4], Some(&timing[..4]), &quick)),
        timed
    );
    assert!(!matches!(
        path_generation(&targets, None, &quick),
        Err(SynthesisError::BadTargets(_))
    ));
    assert_eq!(
        refused(path_generation(&targets[..8], None, &quick)),
        untimed
    );
    // A crank angle too few or too many; each coordinate and crank angle not finite alone.
    assert_eq!(
        refused(path_generation(&targets[..6], Some(&timing[..5]), &quick)),
        finite
    );
    assert_eq!(
        refused(path_generation(&targets[..5], Some(&timing[..6]), &quick)),
        finite
    );
    for k in 0..3 {
        let (mut points, mut angles) = (targets.clone(), timing.clone());
        match k {
            0 => points[1].x = f64::NAN,
            1 => points[2].y = f64::INFINITY,
            _ => angles[3] = f64::NAN,
        }
        assert_eq!(
            refused(path_generation(&points, Some(&angles), &quick)),
            finite,
            "{k}"
        );
        if k < 2 {
            assert_eq!(
                refused(path_generation(&points, None, &quick)),
                finite,
                "{k}"
            );
        }
    }
}

#[test]
fn a_random_start_is_a_crank_rocker_on_the_ground_with_the_crank_shortest() {
    use super::crank_rocker;
    use crate::random::SplitMix64;
    let (mut shortest, mut longest) = (f64::MAX, 0.0f64);
    for seed in 0..500 {
        let [crank, coupler, rocker] = crank_rocker(100.0, &mut SplitMix64(seed));
        let mut all = [100.0, crank, coupler, rocker];
        all.sort_by(f64::total_cmp);
        assert_eq!(all[0], crank, "{seed}: {all:?}");
        assert!(
            all[0] + all[3] < all[1] + all[2],
            "{seed}: not Grashof, {all:?}"
        );
        // Within the documented ranges: the crank 0.1 to 0.6 of the ground, the others 0.4
        // to 2 of it.
        assert!((10.0..60.0).contains(&crank), "{crank}");
        for l in [coupler, rocker] {
            assert!((40.0..200.0).contains(&l), "{l}");
            (shortest, longest) = (shortest.min(l), longest.max(l));
        }
    }
    assert!(shortest < 45.0 && longest > 150.0, "{shortest} {longest}");
}

#[test]
fn errors_ratios_and_angles_are_measured_as_documented() {
    use super::{not_assembled, rms, within_ratio, wrapped};
    assert_eq!(rms(&[3.0, -4.0]), 12.5f64.sqrt());
    assert_eq!(rms(&[2.0]), 2.0);
    assert_eq!(rms(&[]), 0.0);
    // The longest within the ratio of the shortest, in any order, the bound included.
    assert!(within_ratio(&[50.0, 1.0, 20.0], 50.0));
    assert!(!within_ratio(&[50.0, 0.999, 20.0], 50.0));
    assert!(!within_ratio(&[1.0, 20.0, 50.5], 50.0));
    assert!(within_ratio(&[7.0], 1.0));
    for (angle, want) in [
        (0.5, 0.5),
        (-0.5, -0.5),
        (7.0, 7.0 - core::f64::consts::TAU),
        (-7.0, -7.0 + core::f64::consts::TAU),
        (4.0, 4.0 - core::f64::consts::TAU),
        (-4.0, -4.0 + core::f64::consts::TAU),
        (20.0, 20.0 - 3.0 * core::f64::consts::TAU),
    ] {
        assert!((wrapped(angle) - want).abs() < 1e-15, "{angle}");
    }
    // Where a target cannot be reached: as many NaNs as residuals.
    let missing = not_assembled(None, 3);
    assert_eq!(missing.len(), 3);
    assert!(missing.iter().all(|v| v.is_nan()));
    assert_eq!(
        not_assembled(Some(std::vec![1.0, 2.0]), 5).as_slice(),
        &[1.0, 2.0]
    );
}

#[test]
fn levenberg_marquardt_has_finished_at_a_minimum_or_where_it_cannot_improve() {
    use super::finished;
    use levenberg_marquardt::TerminationReason as Why;
    for why in [
        Why::ResidualsZero,
        Why::Orthogonal,
        Why::Converged {
            ftol: true,
            xtol: false,
        },
        Why::NoImprovementPossible("gtol"),
    ] {
        assert!(finished(&why), "{why:?}");
    }
    for why in [
        Why::LostPatience,
        Why::Numerical("jacobian"),
        Why::User("residuals"),
        Why::NoParameters,
        Why::NoResiduals,
        Why::WrongDimensions("jacobian"),
    ] {
        assert!(!finished(&why), "{why:?}");
    }
}

#[test]
fn the_best_start_is_the_feasible_one_with_the_least_error_ties_to_the_first() {
    use super::best;
    let linkage = |crank: f64| FourBar::new(180.0, crank, 200.0, 150.0).unwrap();
    let at = |crank: f64, errors: Vec<f64>| {
        Some((
            linkage(crank),
            (Vec2::default(), 0.0),
            errors,
            std::vec![0.0, 1.0],
        ))
    };
    let options = Options {
        max_ratio: 10.0,
        ..Options::default()
    };
    // A start that did not converge, one whose crank breaks the ratio (200/15 > 10), two
    // with the same least error, and a worse one.
    let solved = std::vec![
        None,
        at(15.0, std::vec![0.0, 0.0]),
        at(70.0, std::vec![0.5, -0.5]),
        at(80.0, std::vec![0.1, 0.1]),
        at(90.0, std::vec![-0.1, 0.1]),
    ];
    let found = best(solved, &options).unwrap();
    assert_eq!(found.linkage, linkage(80.0));
    assert_eq!((found.converged, found.feasible), (4, 3));
    assert!((found.rms_error - 0.1).abs() < 1e-15);
    assert_eq!(found.largest_error, 0.1);
    let none = best(std::vec![None, at(15.0, std::vec![0.0])], &options);
    assert_eq!(none, Err(SynthesisError::NothingFeasible { converged: 1 }));
}

#[test]
fn the_constraints_are_the_ratio_a_crank_and_the_transmission_angle() {
    use super::meets;
    let example = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    // Example 1 is a crank-rocker; its transmission angle is extreme where the crank lies
    // along the ground, at the crank angles 0 and π.
    let q = |t: f64| example.assemble(t, Branch::Open).unwrap();
    let [at_0, at_pi] = [0.0, core::f64::consts::PI].map(|t| example.transmission_angle(&q(t)));
    let (low, high) = (at_0.min(at_pi), at_0.max(at_pi));
    let inputs = [1.0, 2.0];
    let with = |crank: bool, transmission: Option<(f64, f64)>, max_ratio: f64| Options {
        crank,
        transmission,
        max_ratio,
        ..Options::default()
    };
    assert!(meets(&example, &inputs, &with(false, None, 2.5)));
    assert!(!meets(&example, &inputs, &with(false, None, 2.4)));
    assert!(meets(&example, &inputs, &with(true, None, 50.0)));
    // Over the whole turn with a crank, at the inputs alone without one.
    let window = Some((low - 1e-9, high + 1e-9));
    assert!(meets(&example, &inputs, &with(true, window, 50.0)));
    let narrow = Some((low + 0.05, high));
    assert!(!meets(&example, &inputs, &with(true, narrow, 50.0)));
    let between = [1.0, 2.0].map(|t| example.transmission_angle(&q(t)));
    let around = Some((between[0].min(between[1]), between[0].max(between[1])));
    assert!(meets(&example, &inputs, &with(false, around, 50.0)));
    assert!(!meets(
        &example,
        &[0.0, 1.0, 2.0],
        &with(false, around, 50.0)
    ));
    // A triple rocker is no crank, whatever else it meets.
    let rocker = FourBar::new(100.0, 60.0, 50.0, 80.0).unwrap();
    assert!(meets(&rocker, &[0.5], &with(false, None, 50.0)));
    assert!(!meets(&rocker, &[0.5], &with(true, None, 50.0)));
    // Nor is a change point's crank (class III): it turns fully, but where its links line up
    // the branch cannot be kept (an adversarial review found one met as a crank).
    let change_point = FourBar::new(4.0, 1.0, 3.0, 2.0).unwrap();
    assert_eq!(
        change_point.grashof().class,
        mechgen::grashof::Class::ChangePoint
    );
    assert!(meets(&change_point, &[0.5], &with(false, None, 50.0)));
    assert!(!meets(&change_point, &[0.5], &with(true, None, 50.0)));
}

#[test]
fn path_generation_starts_around_the_targets_at_their_scale() {
    use super::{centre_and_spread, path_start};
    use crate::random::SplitMix64;
    let tau = core::f64::consts::TAU;
    // A rectangle's corners: its centre, and half its diagonal.
    let corners =
        [(10.0, 20.0), (14.0, 20.0), (14.0, 22.0), (10.0, 22.0)].map(|(x, y)| Vec2 { x, y });
    let (centre, spread) = centre_and_spread(&corners);
    assert_eq!(centre, Vec2 { x: 12.0, y: 21.0 });
    assert_eq!(spread, 5f64.sqrt());
    let (_, none) = centre_and_spread(&[Vec2 { x: 3.0, y: 4.0 }; 5]);
    assert_eq!(none, 0.0);
    // Each value drawn uniformly over its documented range: the pivot's distance from the
    // centre and its direction, the ground's angle and length, the coupler point's distance
    // and angle, and the first crank angle. Eight equal bins of 4000 draws hold 500 each,
    // to within 20% (the binomial's deviation is 4%).
    let ranges: [(f64, f64); 7] = [
        (spread, 3.0 * spread),
        (0.0, tau),
        (0.0, tau),
        (0.5 * spread, 2.0 * spread),
        (0.1 * spread, 2.0 * spread),
        (0.0, tau),
        (0.0, tau),
    ];
    let mut bins = [[0usize; 8]; 7];
    for seed in 0..4000 {
        let x = path_start(centre, spread, Some(4), &mut SplitMix64(seed));
        assert_eq!(x.len(), 13);
        let (dx, dy) = (x[0] - centre.x, x[1] - centre.y);
        let values = [
            dx.hypot(dy),
            dy.atan2(dx).rem_euclid(tau),
            x[2],
            x[3].exp(),
            x[7].exp(),
            x[8],
            x[9],
        ];
        for (k, (value, (low, high))) in values.iter().zip(ranges).enumerate() {
            let at = (value - low) / (high - low);
            assert!((-1e-12..1.0 + 1e-12).contains(&at), "{k}: {value}");
            bins[k][((at * 8.0) as usize).min(7)] += 1;
        }
        // A crank-rocker on that ground, the crank shortest.
        let [ground, crank, coupler, rocker] = [x[3], x[4], x[5], x[6]].map(f64::exp);
        assert!(crank < ground && crank < coupler && crank < rocker, "{x:?}");
        // Four crank angles a quarter turn apart, in order.
        for i in 1..4 {
            assert!(
                (x[9 + i] - x[9] - tau * i as f64 / 4.0).abs() < 1e-12,
                "{x:?}"
            );
        }
    }
    for (k, counts) in bins.iter().enumerate() {
        assert!(
            counts.iter().all(|&c| (400..=600).contains(&c)),
            "{k}: {counts:?}"
        );
    }
    // With the crank angles given, the nine dimensions and placement alone.
    assert_eq!(
        path_start(centre, spread, None, &mut SplitMix64(1)).len(),
        9
    );
}

/// Each column of `make(x)`'s derivatives against central differences of its errors in `x`.
fn derivatives_match_differences<R: super::Residuals>(make: impl Fn(&[f64]) -> R, x: &[f64]) {
    let at = make(x);
    let jacobian = at
        .derivatives()
        .expect("derivatives where the targets are reached");
    let count = at.count();
    assert_eq!(jacobian.shape(), (count, x.len()));
    assert_eq!(at.errors().unwrap().len(), count);
    let h = 1e-6;
    for c in 0..x.len() {
        let (mut up, mut down) = (x.to_vec(), x.to_vec());
        up[c] += h;
        down[c] -= h;
        let (e_up, e_down) = (make(&up).errors().unwrap(), make(&down).errors().unwrap());
        for r in 0..count {
            let difference = (e_up[r] - e_down[r]) / (2.0 * h);
            let want = jacobian[(r, c)];
            assert!(
                (difference - want).abs() < 1e-6 * (1.0 + want.abs()),
                "row {r}, column {c}: {difference} against {want}"
            );
        }
    }
}

#[test]
fn every_synthesis_differentiates_its_errors_as_they_change() {
    use super::{FunctionProblem, PathProblem, WattProblem};
    use crate::WattSixBarBranches;
    use nalgebra::DVector;
    // Function generation, near Example 1 (its lengths through their logarithms).
    let phi = [0.2, 0.9, 1.7, 2.5];
    let psi: Vec<f64> = outputs(&phi).iter().map(|p| p + 0.01).collect();
    derivatives_match_differences(
        |x| FunctionProblem {
            ground: 180.0,
            phi: &phi,
            psi: &psi,
            branch: Branch::Open,
            x: DVector::from_row_slice(x),
        },
        &[85f64.ln(), 190f64.ln(), 155f64.ln()],
    );
    // Path generation, placed and turned, with its crank angles given and found.
    let timing = [0.3, 1.1, 2.0];
    let targets = timing.map(target);
    let placed = [
        25.0,
        -15.0,
        0.4,
        175f64.ln(),
        82f64.ln(),
        205f64.ln(),
        148f64.ln(),
        95f64.ln(),
        0.5,
    ];
    derivatives_match_differences(
        |x| PathProblem {
            targets: &targets,
            timing: Some(&timing),
            branch: Branch::Open,
            x: DVector::from_row_slice(x),
        },
        &placed,
    );
    let mut untimed = placed.to_vec();
    untimed.extend([0.35, 1.05, 2.1]);
    derivatives_match_differences(
        |x| PathProblem {
            targets: &targets,
            timing: None,
            branch: Branch::Open,
            x: DVector::from_row_slice(x),
        },
        &untimed,
    );
    // The Watt six-bar's output, its six free dimensions.
    let start = crate::WattSixBar::new(
        [180.0, 80.0, 210.0, 145.0],
        105.0,
        0.75,
        230.0,
        150.0,
        (300.0, 150.0),
    )
    .unwrap();
    let watt_phi = [0.0, 0.7, 1.4, 2.1, 2.8, 3.5];
    let watt_psi = [0.1; 6];
    derivatives_match_differences(
        |x| WattProblem {
            start,
            phi: &watt_phi,
            psi: &watt_psi,
            branches: WattSixBarBranches::default(),
            x: DVector::from_row_slice(x),
        },
        &[
            210f64.ln(),
            145f64.ln(),
            105f64.ln(),
            0.75,
            230f64.ln(),
            150f64.ln(),
        ],
    );
}

#[test]
fn six_bar_function_generation_says_which_of_its_arguments_is_wrong() {
    use super::watt_function_generation;
    use crate::WattSixBarBranches;
    let start = watt_example();
    let branches = WattSixBarBranches::default();
    let phi: Vec<f64> = (0..7).map(|k| 0.7 * f64::from(k)).collect();
    let psi: Vec<f64> = phi
        .iter()
        .map(|&p| start.assemble(p, branches).unwrap().theta6)
        .collect();
    let quick = Options {
        restarts: 0,
        ..Options::default()
    };
    let generate =
        |phi: &[f64], psi: &[f64]| watt_function_generation(&start, phi, psi, branches, &quick);
    let pairs = "six-bar function generation needs six or more pairs of input and output angles";
    assert!(generate(&phi[..6], &psi[..6]).is_ok());
    assert_eq!(refused(generate(&phi[..5], &psi[..5])), pairs);
    assert_eq!(refused(generate(&phi, &psi[..6])), pairs);
    assert_eq!(refused(generate(&phi[..6], &psi)), pairs);
    let (mut bad_phi, mut bad_psi) = (phi.clone(), psi.clone());
    bad_phi[1] = f64::NAN;
    bad_psi[2] = f64::NEG_INFINITY;
    assert_eq!(
        refused(generate(&bad_phi, &psi)),
        "every angle must be finite"
    );
    assert_eq!(
        refused(generate(&phi, &bad_psi)),
        "every angle must be finite"
    );
}

#[test]
fn output_errors_are_wrapped_and_missing_where_a_point_is_not_reached() {
    use super::output_errors;
    let tau = core::f64::consts::TAU;
    let errors = output_errors(&[1.0, 2.0], &[0.5, 2.0 - tau + 0.25], Some).unwrap();
    assert!(
        (errors[0] - 0.5).abs() < 1e-15 && (errors[1] + 0.25).abs() < 1e-12,
        "{errors:?}"
    );
    assert_eq!(
        output_errors(&[1.0, 2.0], &[0.0, 0.0], |phi| (phi < 1.5).then_some(phi)),
        None
    );
}

#[test]
fn the_starts_are_the_classical_ones_then_one_per_restart_from_its_own_seed() {
    use super::starts;
    use crate::random::SplitMix64;
    let options = |restarts: usize, seed: u64| Options {
        restarts,
        seed,
        ..Options::default()
    };
    let draw = |random: &mut SplitMix64| random.fraction();
    let all = starts(&options(3, 9), std::vec![-1.0, -2.0], draw);
    assert_eq!(all.len(), 5);
    assert_eq!(&all[..2], &[-1.0, -2.0]);
    // Each restart's own generator: the same for the same seed and index whatever the
    // count, different across indices and seeds.
    let more = starts(&options(5, 9), Vec::new(), draw);
    assert_eq!(&more[..3], &all[2..]);
    assert!(more.windows(2).all(|w| w[0] != w[1]), "{more:?}");
    let other = starts(&options(3, 10), Vec::new(), draw);
    assert!(other.iter().zip(&more).all(|(a, b)| a != b), "{other:?}");
    assert!(all[2..].iter().all(|v| (0.0..1.0).contains(v)));
    // Whatever the seed, even one with every bit set, no two restarts share a stream.
    let ones = starts(&options(4, u64::MAX), Vec::new(), draw);
    for (i, a) in ones.iter().enumerate() {
        assert!(ones[i + 1..].iter().all(|b| a != b), "{ones:?}");
    }
}

#[test]
fn the_first_start_alone_where_it_is_good_enough_every_start_otherwise() {
    use super::solved_from_first;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let run = |first_error: Option<f64>, good_enough: Option<f64>| {
        let calls = AtomicUsize::new(0);
        let options = Options {
            good_enough,
            ..Options::default()
        };
        let solved = solved_from_first(
            std::vec![0, 1, 2, 3],
            |k: usize| {
                calls.fetch_add(1, Ordering::Relaxed);
                let error = if k == 0 { first_error? } else { 1.0 };
                Some((k, std::vec![error]))
            },
            &options,
        );
        (
            calls.load(Ordering::Relaxed),
            solved.iter().map(|(k, _)| *k).collect::<Vec<_>>(),
        )
    };
    assert_eq!(run(Some(0.01), Some(0.01)), (1, std::vec![0]));
    assert_eq!(run(Some(0.02), Some(0.01)), (4, std::vec![0, 1, 2, 3]));
    assert_eq!(run(Some(0.0), None), (4, std::vec![0, 1, 2, 3]));
    assert_eq!(run(None, Some(0.01)), (4, std::vec![1, 2, 3]));
}

/// Precision points given twice (the same crank angle, a whole turn apart or not) are
/// refused, as are two answers for one crank angle on one branch: neither leaves a fit that
/// means what its error says (two distinct points and eight copies "fit" exactly).
#[test]
fn repeated_and_contradictory_precision_points_are_refused() {
    let quick = Options {
        restarts: 1,
        ..Options::default()
    };
    let tau = core::f64::consts::TAU;
    let phi = [0.5, 0.5 + tau, 1.0];
    let psi = outputs(&phi);
    let twice = refused(function_generation(180.0, &phi, &psi, &quick));
    assert!(
        twice.starts_with("a precision point is given twice"),
        "{twice}"
    );
    let mut other = psi.clone();
    other[1] += 0.1;
    let two = refused(function_generation(180.0, &phi, &other, &quick));
    assert!(
        two.starts_with("a crank angle is given two rocker angles"),
        "{two}"
    );
    // Distinct by more than a billionth of a radian: a fit.
    let apart = [0.5, 0.5 + 1e-6, 1.0, 2.0];
    assert!(function_generation(180.0, &apart, &outputs(&apart), &quick).is_ok());

    let timing: Vec<f64> = (0..6).map(f64::from).collect();
    let mut targets: Vec<Vec2<f64>> = timing.iter().map(|&t| target(t)).collect();
    let mut same = timing.clone();
    same[4] = same[2] - tau;
    let contradicted = refused(path_generation(&targets, Some(&same), &quick));
    assert!(contradicted.starts_with("two targets are given the same crank angle"));
    targets[4] = targets[2];
    let repeated = refused(path_generation(&targets, Some(&same), &quick));
    assert!(repeated.starts_with("a target is given twice at the same crank angle"));
    let mut copies = std::vec![Vec2 { x: 0.0, y: 0.0 }; 8];
    copies.push(Vec2 { x: 10.0, y: 5.0 });
    let untimed = refused(path_generation(&copies, None, &quick));
    assert!(untimed.starts_with("a target is given twice"), "{untimed}");
    // Every target the same point, at distinct crank angles: refused, not fitted (an
    // adversarial review found a linkage of 1.9e-16 placed at (1, 2) returned).
    let one_point = std::vec![Vec2 { x: 1.0, y: 2.0 }; 6];
    let coincident = refused(path_generation(&one_point, Some(&timing), &quick));
    assert!(
        coincident.starts_with("the targets all coincide"),
        "{coincident}"
    );
    // Within rounding of one another (an ulp apart), and a thousand copies of one point,
    // whose centroid, summed in shares, is several ulps off it.
    let mut nearly = one_point.clone();
    nearly[3].y = 2.0 + 2.0 * f64::EPSILON;
    let coincident = refused(path_generation(&nearly, Some(&timing), &quick));
    assert!(coincident.starts_with("the targets all coincide"));
    let many = std::vec![Vec2 { x: 0.1, y: 0.7 }; 1000];
    let many_timing: Vec<f64> = (0..1000).map(|k| f64::from(k) * 0.006).collect();
    let coincident = refused(path_generation(&many, Some(&many_timing), &quick));
    assert!(coincident.starts_with("the targets all coincide"));
}

/// Path generation's errors are each target's distance from the coupler point (not its x and
/// y apart): the largest is the farthest target's, and the rms theirs.
#[test]
fn path_errors_are_distances_from_the_targets() {
    // Targets a four-bar cannot meet exactly: a zigzag at its crank angles.
    let timing: Vec<f64> = (0..5).map(|k| f64::from(k) * 0.5).collect();
    let targets: Vec<Vec2<f64>> = [
        (0.0, 5.0),
        (10.0, 8.0),
        (20.0, 4.0),
        (30.0, 0.0),
        (40.0, 2.0),
    ]
    .iter()
    .map(|&(x, y)| Vec2 { x, y })
    .collect();
    let found = path_generation(&targets, Some(&timing), &Options::default()).unwrap();
    let (pivot, angle) = found.placement;
    let (s, c) = angle.sin_cos();
    let distances: Vec<f64> = timing
        .iter()
        .zip(&targets)
        .map(|(&t, p)| {
            let q = found
                .linkage
                .assemble(t, Branch::Open)
                .or_else(|_| found.linkage.assemble(t, Branch::Crossed));
            let point = found.linkage.points(t, &q.unwrap()).unwrap().coupler_point;
            let placed = Vec2 {
                x: pivot.x + c * point.x - s * point.y,
                y: pivot.y + s * point.x + c * point.y,
            };
            (placed.x - p.x).hypot(placed.y - p.y)
        })
        .collect();
    let largest = distances.iter().fold(0.0f64, |m, d| m.max(*d));
    assert!(largest > 1e-3, "{distances:?}");
    assert!(
        (found.largest_error / largest - 1.0).abs() < 1e-6,
        "{found:?} {distances:?}"
    );
    assert!(
        (found.rms_error / rms(&distances) - 1.0).abs() < 1e-6,
        "{found:?}"
    );
}

/// Freudenstein's closed form scales with the ground: the same linkage at 1e300 and 1e-300
/// as at 1, times the ground (not "no linkage" for a square that overflowed or underflowed).
#[test]
fn freudensteins_closed_form_holds_at_every_scale() {
    let phi = [0.3, 1.2, 2.0];
    let outputs = outputs(&phi);
    let psi = [outputs[0], outputs[1], outputs[2]];
    let unit = freudenstein(1.0, phi, psi).unwrap();
    for ground in [1e300, 1e-300, 1e-30, 1e30] {
        let scaled = freudenstein(ground, phi, psi).unwrap();
        for (s, u) in scaled.iter().zip(unit) {
            assert!((s / ground / u - 1.0).abs() < 1e-12, "{ground}: {scaled:?}");
        }
    }
}

/// Options no linkage could meet are refused as such, not as `NothingFeasible` blaming the
/// targets (an adversarial review found both).
#[test]
fn options_no_linkage_could_meet_are_refused_as_options() {
    let phi = [0.5, 1.0, 1.5, 2.0];
    let psi = outputs(&phi);
    let quick = Options {
        restarts: 2,
        ..Options::default()
    };
    for max_ratio in [f64::NAN, 0.0, 1.0, -5.0] {
        let options = Options { max_ratio, ..quick };
        assert!(matches!(
            function_generation(180.0, &phi, &psi, &options),
            Err(SynthesisError::BadOptions(_))
        ));
    }
    for bounds in [
        (f64::NAN, f64::NAN),
        (2.0, 1.0),
        (1.0, 1.0),
        (-0.1, 1.0),
        (1.0, 4.0),
    ] {
        let options = Options {
            transmission: Some(bounds),
            ..quick
        };
        let timing: Vec<f64> = (0..6).map(f64::from).collect();
        let targets: Vec<Vec2<f64>> = timing.iter().map(|&t| target(t)).collect();
        assert!(matches!(
            path_generation(&targets, Some(&timing), &options),
            Err(SynthesisError::BadOptions(_))
        ));
    }
    // No limit on the ratio is an option too.
    let unlimited = Options {
        max_ratio: f64::INFINITY,
        ..quick
    };
    assert!(function_generation(180.0, &phi, &psi, &unlimited).is_ok());
}

/// Targets on both of a rocker-crank's circuits: its crank swings between 0.72 and 2.02 rad
/// or their negatives, so one branch reaches θ2 = 0.82, 1.37 and 1.92 and, separately,
/// −1.37, and the linkage would have to be taken apart between them. The linkage that made
/// the targets fitted them to 1.8e-15 and was returned (found by an adversarial review); now
/// no linkage is returned whose crank cannot move through every target on one circuit.
#[test]
fn targets_on_two_circuits_are_not_met_by_one_linkage() {
    use super::meets;
    let rocker_crank = FourBar::new(180.0, 150.0, 200.0, 80.0).unwrap();
    let phi = [0.8227, 1.3719, 1.9210, -1.3719];
    let psi = phi.map(|p| rocker_crank.assemble(p, Branch::Open).unwrap().theta4);
    let options = Options {
        good_enough: Some(1e-9),
        restarts: 8,
        ..Options::default()
    };
    assert!(!meets(&rocker_crank, &phi, &options));
    assert!(meets(&rocker_crank, &phi[..3], &options));
    match function_generation(180.0, &phi, &psi, &options) {
        Ok(found) => {
            let limits = found.linkage.limit_angles();
            assert!(limits.one_circuit(&phi), "{found:?}");
            assert!(found.rms_error > 1e-6, "{found:?}");
        }
        Err(error) => assert!(matches!(error, SynthesisError::NothingFeasible { .. })),
    }
}
