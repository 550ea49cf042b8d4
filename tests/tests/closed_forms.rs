//! Closed forms found by the macro: against Newton on random mechanisms, branch by branch, and
//! sweeps that keep to their branch or say why they stop.

use mechanisms::{
    FourBar, FourBarUnknowns, InvertedSliderCrank, InvertedSliderCrankUnknowns, SliderCrank,
    SliderCrankUnknowns,
};
use mechgen::sweep::{Stop, Sweep};
use mechgen::{Branch, NewtonOptions, Solved};
use proptest::prelude::*;

const BRANCHES: [Branch; 2] = [Branch::Open, Branch::Crossed];

/// Newton, started a little off the closed form, must come back to it, on the same branch:
/// to 1e-12 relative, angles relative to a radian and lengths to the mechanism's size
/// (`units`: 1 for an angle, the size for a length).
fn agree(
    closed: [f64; 2],
    newton: Solved<[f64; 2], f64>,
    units: [f64; 2],
    scale: f64,
) -> Result<(), TestCaseError> {
    for ((c, n), unit) in closed.iter().zip(newton.value).zip(units) {
        let tolerance = 1e-12 * c.abs().max(unit);
        prop_assert!(
            (c - n).abs() <= tolerance,
            "{closed:?} vs {:?}",
            newton.value
        );
    }
    prop_assert!(newton.residual_norm <= 1e-13 * scale);
    Ok(())
}

fn nudged(q: [f64; 2]) -> [f64; 2] {
    [
        q[0] + 1e-3 * q[0].abs().max(1.0),
        q[1] - 1e-3 * q[1].abs().max(1.0),
    ]
}

fn residual_is_rounding(residual: [f64; 2], scale: f64) -> Result<(), TestCaseError> {
    for f in residual {
        prop_assert!(
            f.abs() <= 64.0 * f64::EPSILON * scale,
            "residual {residual:?}"
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn four_bar_closed_form_agrees_with_newton(
        l in [1.0f64..100.0, 1.0f64..100.0, 1.0f64..100.0, 1.0f64..100.0],
        theta2 in -3.1f64..3.1,
    ) {
        let linkage = FourBar::new(l[0], l[1], l[2], l[3]);
        prop_assume!(linkage.is_ok());
        let linkage = linkage.unwrap();
        let scale: f64 = l.iter().sum();
        for branch in BRANCHES {
            let Ok(q) = linkage.assemble(theta2, branch) else { continue };
            residual_is_rounding(linkage.residual(theta2, &q), scale)?;
            // Away from toggles, where the two branches are distinct solutions, by more than
            // the guess's nudge of 1e-3 rad: nearer, the nudge can cross to the other branch,
            // and Newton rightly says `OtherBranch` (l = [9.5, 2.0, 66.5, 74.6] at θ2 = −0.672,
            // whose relative determinant is under 1e-2).
            let j = linkage.jacobian(theta2, &q);
            let relative = (j[0][0] * j[1][1] - j[0][1] * j[1][0]) / (l[2] * l[3]);
            prop_assume!(relative.abs() > 1e-2);
            prop_assert_eq!(linkage.branch_of(theta2, &q), branch);
            let guess = FourBarUnknowns::from_array(nudged(q.to_array()));
            let newton = linkage.position(theta2, &guess, &NewtonOptions::default()).unwrap();
            prop_assert_eq!(linkage.branch_of(theta2, &newton.value), branch);
            agree(q.to_array(), newton.map(|v| v.to_array()), [1.0, 1.0], scale)?;
        }
    }

    #[test]
    fn slider_crank_closed_form_agrees_with_newton(
        l in [1.0f64..100.0, 1.0f64..100.0],
        offset in -50.0f64..50.0,
        theta2 in -3.1f64..3.1,
    ) {
        let linkage = SliderCrank::new(l[0], l[1], offset);
        prop_assume!(linkage.is_ok());
        let linkage = linkage.unwrap();
        for branch in BRANCHES {
            let Ok(q) = linkage.assemble(theta2, branch) else { continue };
            let scale = l[0] + l[1] + offset.abs() + q.d.abs();
            residual_is_rounding(linkage.residual(theta2, &q), scale)?;
            prop_assume!(q.theta3.cos().abs() > 1e-3);
            prop_assert_eq!(linkage.branch_of(theta2, &q), branch);
            let guess = SliderCrankUnknowns::from_array(nudged(q.to_array()));
            let newton = linkage.position(theta2, &guess, &NewtonOptions::default()).unwrap();
            prop_assert_eq!(linkage.branch_of(theta2, &newton.value), branch);
            agree(q.to_array(), newton.map(|v| v.to_array()), [1.0, scale], scale)?;
        }
    }

    #[test]
    fn inverted_slider_crank_closed_form_agrees_with_newton(
        l in [1.0f64..100.0, 1.0f64..100.0],
        offset in -50.0f64..50.0,
        gamma in -1.5f64..1.5,
        theta2 in -3.1f64..3.1,
    ) {
        let linkage = InvertedSliderCrank::new(l[0], l[1], offset, gamma);
        prop_assume!(linkage.is_ok());
        let linkage = linkage.unwrap();
        for branch in BRANCHES {
            let Ok(q) = linkage.assemble(theta2, branch) else { continue };
            let scale = l[0] + l[1] + offset.abs() + q.b.abs();
            residual_is_rounding(linkage.residual(theta2, &q), scale)?;
            prop_assume!((q.b + offset * gamma.cos()).abs() > 1e-3 * scale);
            prop_assert_eq!(linkage.branch_of(theta2, &q), branch);
            let guess = InvertedSliderCrankUnknowns::from_array(nudged(q.to_array()));
            let newton = linkage.position(theta2, &guess, &NewtonOptions::default()).unwrap();
            prop_assert_eq!(linkage.branch_of(theta2, &newton.value), branch);
            agree(q.to_array(), newton.map(|v| v.to_array()), [1.0, scale], scale)?;
        }
    }
}

/// A full turn in 0.1° steps: every sample on the branch, matching the closed form there, and
/// the last position back at the first.
#[test]
fn grashof_cranks_turn_fully_on_their_branch() {
    let crank_rocker = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let double_crank = FourBar::new(80.0, 180.0, 200.0, 150.0).unwrap();
    let step = std::f64::consts::TAU / 3600.0;
    for linkage in [crank_rocker, double_crank] {
        for branch in BRANCHES {
            let start = linkage.assemble(0.0, branch).unwrap().to_array();
            let sweep = Sweep::new(&linkage, 0.0, start, step, 3600, NewtonOptions::default());
            let samples: Vec<_> = sweep.collect::<Result<_, _>>().unwrap();
            assert_eq!(samples.len(), 3601);
            for sample in &samples {
                let q = FourBarUnknowns::from_array(sample.position);
                assert_eq!(linkage.branch_of(sample.input, &q), branch);
                let closed = linkage.assemble(sample.input, branch).unwrap();
                let wrapped = |a: f64, b: f64| {
                    (a - b + 3.0 * std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                        - std::f64::consts::PI
                };
                assert!(wrapped(q.theta3, closed.theta3).abs() < 1e-9);
                assert!(wrapped(q.theta4, closed.theta4).abs() < 1e-9);
            }
            let (first, last) = (samples[0].position, samples[3600].position);
            // The rocker comes back where it was; the crank-rocker's coupler too, while a
            // double-crank's coupler and rocker have turned once more.
            for (a, b) in first.iter().zip(last) {
                let turns = (b - a) / std::f64::consts::TAU;
                assert!((turns - turns.round()).abs() < 1e-9, "{first:?} → {last:?}");
            }
        }
    }
}

#[test]
fn sweeps_stop_at_toggles_instead_of_crossing_them() {
    // A triple-rocker: the crank stops at ±acos((l1² + l2² − (l3 + l4)²)/(2·l1·l2)).
    let linkage = FourBar::new(100.0, 120.0, 90.0, 80.0).unwrap();
    let limit = linkage.limit_angles().extended.unwrap();
    let step = 0.1f64.to_radians();
    for branch in BRANCHES {
        let start = linkage.assemble(0.0, branch).unwrap().to_array();
        let sweep = Sweep::new(&linkage, 0.0, start, step, 3600, NewtonOptions::default());
        let mut last_input = 0.0;
        let mut stop = None;
        for item in sweep {
            match item {
                Ok(sample) => {
                    let q = FourBarUnknowns::from_array(sample.position);
                    assert_eq!(linkage.branch_of(sample.input, &q), branch);
                    assert!(sample.input <= limit);
                    last_input = sample.input;
                }
                Err(event) => stop = Some(event),
            }
        }
        let (reported_last, next) = match stop.expect("the sweep stops at the toggle") {
            Stop::Toggle {
                last_input,
                next_input,
                ..
            } => (last_input, next_input),
            Stop::BranchChange {
                last_input,
                next_input,
            } => (last_input, next_input),
        };
        assert_eq!(reported_last, last_input);
        // The toggle lies within the step where the sweep stopped, or the one before it
        // (where the rate was already too large to predict across).
        assert!(
            reported_last <= limit && limit < next + step,
            "{reported_last} {limit} {next}"
        );
        assert!(
            limit - reported_last < 2.0 * step,
            "stopped early at {reported_last}"
        );
    }
}

#[test]
fn change_point_linkages_report_the_flat_position() {
    // A parallelogram with equal cranks lies flat at θ2 = 0 and π, where it can switch to the
    // antiparallelogram: the sweep says so rather than choosing silently.
    let linkage = FourBar::new(100.0, 50.0, 100.0, 50.0).unwrap();
    let start = linkage.assemble(0.3, Branch::Open).unwrap().to_array();
    let step = 0.1f64.to_radians();
    let sweep = Sweep::new(&linkage, 0.3, start, step, 3600, NewtonOptions::default());
    let stop = sweep
        .filter_map(Result::err)
        .next()
        .expect("the sweep stops at the flat position");
    let (last, next) = match stop {
        Stop::Toggle {
            last_input,
            next_input,
            ..
        } => (last_input, next_input),
        Stop::BranchChange {
            last_input,
            next_input,
        } => (last_input, next_input),
    };
    let pi = std::f64::consts::PI;
    assert!(
        last <= pi + 1e-9 && pi - last < 2.0 * step && next >= pi - step,
        "{last} {next}"
    );
}

/// A step that lands exactly on a parallelogram's flat position stops there as a step over it
/// does, at every ratio of ground to crank, in f64 and f32: with the ground 1000 or 1e6 times
/// the crank (f64) the sweep went on `Ok` on the same branch's other mode (the rocker turning
/// back, θ4 = −θ2 after θ4 = θ2), its walk reading a path from landings within the flat
/// position's blur, a thousand times less certain than their changes.
#[test]
fn a_step_onto_a_change_point_stops_there() {
    fn onto<T: mechgen::Real + std::fmt::Debug>(ratio: T, step: T) {
        let crank = T::one();
        let linkage = FourBar::new(ratio, crank, ratio, crank).unwrap();
        let start = T::constant(0.5);
        let position = linkage.assemble(start, Branch::Open).unwrap().to_array();
        let mut samples = Vec::new();
        let mut stop = None;
        for item in Sweep::new(
            &linkage,
            start,
            position,
            step,
            100,
            NewtonOptions::default(),
        ) {
            match item {
                Ok(sample) => samples.push(sample),
                Err(event) => {
                    stop = Some(event);
                    break;
                }
            }
        }
        // Every sample is the open assembly, θ4 = θ2 (a parallelogram) before the flat
        // position; none is past it.
        for sample in &samples {
            assert!(sample.input >= T::zero(), "{ratio:?}: {samples:?}");
            let rocker = sample.position[1];
            let tolerance = T::constant(1e-6).max(T::epsilon().sqrt() * T::constant(64.0));
            assert!(
                (rocker - sample.input).abs() <= tolerance,
                "{ratio:?}: {sample:?}"
            );
        }
        assert!(
            matches!(stop, Some(Stop::BranchChange { .. })),
            "{ratio:?}: {stop:?} after {samples:?}"
        );
    }
    for ratio in [1.0, 3.0, 1e3, 1e6] {
        // 0.5 − 50 · 0.01 is 0 exactly; 0.015 steps over it.
        onto(ratio, -0.01f64);
        onto(ratio, -0.015f64);
    }
    for ratio in [1.0f32, 3.0, 1e2, 1e3] {
        onto(ratio, -0.01f32);
        onto(ratio, -0.015f32);
    }
}

/// The isosceles inverted slider-crank's change point (θ2 = 0, where the slide passes through
/// the rocker's pivot) is a `BranchChange` from any start and step, not only in steps of 0.25:
/// from these four (drawn at random, at sizes from 4e-14 to 43, either branch) the sweep said
/// `Toggle` (`Inaccurate`), its walk stuck where the loops fix the rocker's angle ever more
/// loosely, and its look beyond finding nothing to count.
#[test]
fn an_isosceles_inverted_slider_crank_s_change_point_is_a_branch_change_from_any_step() {
    let cases = [
        (
            0.364_721_151_629_064_77_f64,
            -2.309_973_686_759_067,
            -0.024_200_327_571_261_136,
            Branch::Open,
        ),
        (
            0.321_833_122_064_133_9,
            -1.467_850_260_958_867,
            0.010_559_149_934_086_406,
            Branch::Open,
        ),
        (
            3.762_393_138_727_446e-14,
            -2.806_672_304_387_061,
            -0.010_940_105_147_027_108,
            Branch::Crossed,
        ),
        (
            42.959_878_844_477_86,
            -1.149_751_661_826_590_6,
            0.007_571_442_555_128_524,
            Branch::Crossed,
        ),
    ];
    for (size, start, step, branch) in cases {
        let linkage = InvertedSliderCrank::new(size, size, 0.0, 0.0).unwrap();
        let position = linkage.assemble(start, branch).unwrap().to_array();
        let stop = Sweep::new(
            &linkage,
            start,
            position,
            step,
            400,
            NewtonOptions::default(),
        )
        .find_map(Result::err);
        match stop {
            Some(Stop::BranchChange {
                last_input,
                next_input,
            }) => {
                // A multiple of a turn, the change point, lies within the step that stopped.
                let tau = std::f64::consts::TAU;
                let (low, high) = (last_input.min(next_input), last_input.max(next_input));
                assert!(
                    (low / tau).ceil() <= (high / tau).floor(),
                    "{size}: {last_input} {next_input}"
                );
            }
            other => panic!("{size}, {start}, {step}: {other:?}"),
        }
    }
}

/// An f32 four-bar within 1% of its Grashof change point (s + l = 2.391, p + q = 2.408) turns
/// fully on its crossed branch in steps of 0.13 rad, 400 of them, each sample its closed form
/// to 1e-5: through the narrow passage its walk halves to pieces of an ulp of the input, whose
/// landings are as uncertain as their changes, and reads them as before (a blur threshold of
/// the smoothness test's tolerance itself, rather than sixteen times it, stopped there with
/// `Inaccurate`, as it did sweeps of other f32 linkages near a change point).
#[test]
fn an_f32_sweep_through_a_narrow_passage_goes_on() {
    let linkage = FourBar::new(0.418_126_f32, 0.937_929, 1.972_817_4, 1.469_982_7).unwrap();
    let start = -2.009_453_4_f32;
    let position = linkage.assemble(start, Branch::Crossed).unwrap().to_array();
    let sweep = Sweep::new(
        &linkage,
        start,
        position,
        -0.130_712_99,
        400,
        NewtonOptions::default(),
    );
    let mut count = 0;
    for sample in sweep {
        let sample = sample.unwrap_or_else(|stop| panic!("after {count}: {stop:?}"));
        let closed = linkage
            .assemble(sample.input, Branch::Crossed)
            .unwrap()
            .to_array();
        for (a, b) in sample.position.iter().zip(closed) {
            let turns = ((a - b) / std::f32::consts::TAU).round();
            let off = (a - b - turns * std::f32::consts::TAU).abs();
            assert!(off < 1e-5, "{sample:?} against {closed:?}");
        }
        count += 1;
    }
    assert_eq!(count, 401);
}

/// A change point is a `BranchChange` at every size, in f64 and f32, and no sweep reads a path
/// through it: the isosceles inverted slider-crank (crank as long as the ground, the slide
/// through the rocker's pivot at θ2 = 0) and the isosceles slider-crank (rod as long as the
/// crank, the slider at the crank's pivot at θ2 = 90°), swept through them in steps of 0.25.
/// In f32 the first went on `Ok` with its rocker turned over on the same branch (near θ2 = 0
/// the slide, some 1e-6 of the linkage, left the rocker's angle to rounding, and the walk
/// read a smooth half-turn from it); at sizes from 1e7 in f64 (1e3 in f32) the second said
/// `Toggle` (its predictor's guesses, a slide of a few units, were taken for no place on the
/// motion, as they would be for a mechanism of size 1).
#[test]
fn change_points_are_branch_changes_at_every_size() {
    fn through<T: mechgen::Real + std::fmt::Debug, M: mechgen::Kinematics<T, 2>>(
        linkage: &M,
        start: T,
        position: [T; 2],
        change_point: T,
    ) {
        let step = T::constant(0.25);
        let mut samples = Vec::new();
        let mut stop = None;
        for item in Sweep::new(linkage, start, position, step, 6, NewtonOptions::default()) {
            match item {
                Ok(sample) => samples.push(sample),
                Err(event) => stop = Some(event),
            }
        }
        // The angle (the first unknown) moves by at most the crank's quarter radian a step,
        // never by a half-turn.
        for pair in samples.windows(2) {
            let turned = (pair[1].position[0] - pair[0].position[0]).abs();
            assert!(turned < T::constant(0.3), "{samples:?}");
        }
        let last = samples.last().expect("the start solves").input;
        match stop {
            Some(Stop::BranchChange {
                last_input,
                next_input,
            }) => assert!(
                last_input == last && last < change_point && change_point < next_input,
                "{last_input:?} {next_input:?}"
            ),
            other => panic!("{other:?} after {samples:?}"),
        }
    }
    let half_pi = std::f64::consts::FRAC_PI_2;
    for exponent in [-298, -150, -20, -3, 0, 2, 3, 7, 8, 20, 150, 298] {
        let size = 10f64.powi(exponent);
        let inverted = InvertedSliderCrank::new(size, size, 0.0, 0.0).unwrap();
        let start = inverted.assemble(-0.49, Branch::Open).unwrap().to_array();
        through(&inverted, -0.49, start, 0.0);
        let slider = SliderCrank::new(size, size, 0.0).unwrap();
        let start = slider.assemble(1.0, Branch::Open).unwrap().to_array();
        through(&slider, 1.0, start, half_pi);
    }
    for exponent in [-30, -20, -3, 0, 2, 3, 7, 20, 30] {
        let size = 10f32.powi(exponent);
        let inverted = InvertedSliderCrank::new(size, size, 0.0, 0.0).unwrap();
        let start = inverted.assemble(-0.49, Branch::Open).unwrap().to_array();
        through(&inverted, -0.49, start, 0.0);
        let slider = SliderCrank::new(size, size, 0.0).unwrap();
        let start = slider.assemble(1.0, Branch::Open).unwrap().to_array();
        through(&slider, 1.0, start, std::f32::consts::FRAC_PI_2);
    }
}

/// A Watt six-bar whose first four-bar is 10⁴ times its dyad, in f32, turns fully on either
/// dyad branch: each loop's rounding is its own (a sweep that weighed the dyad's unknowns
/// against the whole mechanism's rounding, 16·ε of every declared length, took them for loose
/// by a sixteenth of a radian and stopped at the first step, where its positions were
/// within 1e-3 rad of the closed form; an adversarial review's catch).
#[test]
fn a_small_loop_beside_a_large_one_is_fixed_by_its_own_rounding() {
    use mechanisms::WattSixBar;
    for k in [5e3f32, 1e4] {
        let watt = WattSixBar::new(
            [180.0 * k, 80.0 * k, 200.0 * k, 150.0 * k],
            100.0,
            0.8,
            220.0,
            160.0,
            (180.0 * k + 120.0, 150.0),
        )
        .unwrap();
        for dyad in BRANCHES {
            let branches = [Branch::Open, dyad];
            let start = watt.assemble(0.3, branches).unwrap().to_array();
            let step = std::f32::consts::TAU / 360.0;
            let mut count = 0;
            for sample in Sweep::new(&watt, 0.3, start, step, 360, NewtonOptions::default()) {
                let sample = sample.unwrap_or_else(|stop| panic!("× {k}, {dyad:?}: {stop:?}"));
                let closed = watt.assemble(sample.input, branches).unwrap().to_array();
                for (got, want) in sample.position.iter().zip(closed) {
                    let turned = (got - want).rem_euclid(std::f32::consts::TAU);
                    let off = turned.min(std::f32::consts::TAU - turned);
                    assert!(off < 2e-3, "× {k}, {dyad:?}: {sample:?} against {closed:?}");
                }
                count += 1;
            }
            assert_eq!(count, 361);
        }
    }
}

#[test]
fn sweeps_work_in_f32() {
    let linkage = FourBar::new(180.0f32, 80.0, 200.0, 150.0).unwrap();
    let start = linkage.assemble(0.0, Branch::Open).unwrap().to_array();
    let step = std::f32::consts::TAU / 360.0;
    let mut count = 0;
    for sample in Sweep::new(&linkage, 0.0, start, step, 360, NewtonOptions::default()) {
        let sample = sample.unwrap();
        let closed = linkage.assemble(sample.input, Branch::Open).unwrap();
        assert!((sample.position[1] - closed.theta4).abs() < 1e-4);
        count += 1;
    }
    assert_eq!(count, 361);
}

/// `motion` is `assemble`, `velocity` and `acceleration` in one pass: the same numbers, to
/// rounding (it takes the solved angles' sines and cosines from the closed form).
#[test]
fn motion_is_assemble_velocity_and_acceleration_in_one() {
    let four_bar = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let slider = SliderCrank::new(50.0, 150.0, 20.0).unwrap();
    let inverted = InvertedSliderCrank::new(150.0, 60.0, 20.0, 0.3).unwrap();
    let close = |a: [f64; 2], b: [f64; 2], scale: f64| {
        a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= 1e-12 * scale.max(y.abs()))
    };
    for degree in (0..360).step_by(5) {
        let theta2 = f64::from(degree).to_radians();
        for branch in BRANCHES {
            let m = four_bar.motion(theta2, branch, 7.0, -3.0).unwrap();
            let q = four_bar.assemble(theta2, branch).unwrap();
            let v = four_bar.velocity(theta2, &q, 7.0).unwrap();
            let a = four_bar.acceleration(theta2, &q, 7.0, &v, -3.0).unwrap();
            assert!(close(m.position.to_array(), q.to_array(), 1.0));
            assert!(close(m.velocity.to_array(), v.to_array(), 1.0));
            assert!(close(m.acceleration.to_array(), a.to_array(), 1.0));
            // motion_at, from a position, is velocity and acceleration in one.
            let at = four_bar.motion_at(theta2, &q, 7.0, -3.0).unwrap();
            assert_eq!(at.position, q);
            assert!(close(at.velocity.to_array(), v.to_array(), 1.0));
            assert!(close(at.acceleration.to_array(), a.to_array(), 1.0));

            let m = slider.motion(theta2, branch, 7.0, -3.0).unwrap();
            let q = slider.assemble(theta2, branch).unwrap();
            let v = slider.velocity(theta2, &q, 7.0).unwrap();
            let a = slider.acceleration(theta2, &q, 7.0, &v, -3.0).unwrap();
            assert!(close(m.position.to_array(), q.to_array(), 200.0));
            assert!(close(m.velocity.to_array(), v.to_array(), 200.0));
            assert!(close(m.acceleration.to_array(), a.to_array(), 200.0));

            let m = inverted.motion(theta2, branch, 7.0, -3.0).unwrap();
            let q = inverted.assemble(theta2, branch).unwrap();
            let v = inverted.velocity(theta2, &q, 7.0).unwrap();
            let a = inverted.acceleration(theta2, &q, 7.0, &v, -3.0).unwrap();
            assert!(close(m.position.to_array(), q.to_array(), 230.0));
            assert!(close(m.velocity.to_array(), v.to_array(), 230.0));
            assert!(close(m.acceleration.to_array(), a.to_array(), 230.0));
        }
    }
}

/// A mechanism that counts its solves and refuses past `limit` of them: a sweep that would
/// spin on one input stops, saying so, rather than hang the test.
struct Counted<'a, M> {
    mechanism: &'a M,
    solves: std::cell::Cell<u32>,
    limit: u32,
}

impl<T: mechgen::Real, M: mechgen::Kinematics<T, N>, const N: usize> mechgen::Kinematics<T, N>
    for Counted<'_, M>
{
    fn solve_near(
        &self,
        input: T,
        guess: [T; N],
        options: &NewtonOptions<T>,
    ) -> Result<Solved<[T; N], T>, mechgen::Error<T>> {
        self.solves.set(self.solves.get() + 1);
        if self.solves.get() > self.limit {
            return Err(mechgen::Error::NoConvergence {
                iterations: 0,
                residual_norm: T::nan(),
            });
        }
        self.mechanism.solve_near(input, guess, options)
    }

    fn slope(&self, input: T, position: [T; N]) -> Result<[T; N], mechgen::Error<T>> {
        self.mechanism.slope(input, position)
    }

    fn same_branch(&self, input_a: T, a: [T; N], input_b: T, b: [T; N]) -> bool {
        self.mechanism.same_branch(input_a, a, input_b, b)
    }

    fn slope_within(
        &self,
        input: T,
        position: [T; N],
    ) -> Result<([T; N], [T; N]), mechgen::Error<T>> {
        self.mechanism.slope_within(input, position)
    }

    fn units(&self) -> [T; N] {
        self.mechanism.units()
    }

    fn input_unit(&self) -> T {
        self.mechanism.input_unit()
    }
}

mechgen::mechanism! {
    /// A slider-crank driven by its slider: the slide `d`, the crank and rod angles unknown.
    pub struct SlideDriven {
        params: l2, l3, c;
        input: d: length;
        unknowns: theta2: angle, theta3: angle;
        loop: l2 @ theta2 + l3 @ theta3 - c @ (pi / 2) - d @ 0;
        generate: position, velocity, acceleration;
    }
}

/// From an input so large that one unit of it is lost in rounding (a slide of 3e8 in f32,
/// whose neighbours are 32 apart), the walk's pieces are as long as the input's rounding: an
/// adversarial review found the sweep accepting `x + 1 = x` for ever (a million solves, all
/// at the start), there and from a crank angle of 1e16 rad in f64, which now stops (a turn
/// of the input is then a few of its roundings: the walk cannot resolve it).
#[test]
fn a_sweep_from_an_input_coarser_than_a_unit_goes_on_or_stops() {
    let linkage = SlideDriven {
        l2: 1e8f32,
        l3: 3e8,
        c: 0.0,
    };
    let counted = Counted {
        mechanism: &linkage,
        solves: std::cell::Cell::new(0),
        limit: 10_000,
    };
    let guess = SlideDrivenUnknowns {
        theta2: 1.4,
        theta3: -0.33,
    };
    let start = linkage
        .position(3e8, &guess, &NewtonOptions::default())
        .unwrap()
        .value;
    let samples: Vec<_> = Sweep::new(
        &counted,
        3e8,
        start.to_array(),
        100.0,
        3,
        NewtonOptions::default(),
    )
    .collect::<Result<_, _>>()
    .expect("the slide moves the crank smoothly here");
    assert_eq!(samples.len(), 4);
    for sample in samples {
        let q = SlideDrivenUnknowns::from_array(sample.position);
        let residual = linkage.residual(sample.input, &q);
        assert!(residual.iter().all(|r| r.abs() < 1e-5 * 4e8), "{sample:?}");
    }
    assert!(
        counted.solves.get() < 100,
        "{} solves",
        counted.solves.get()
    );
    let crank_rocker = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let counted = Counted {
        mechanism: &crank_rocker,
        solves: std::cell::Cell::new(0),
        limit: 10_000,
    };
    let start = 1e16f64;
    let position = crank_rocker
        .assemble(start, Branch::Open)
        .unwrap()
        .to_array();
    let outcomes: Vec<_> =
        Sweep::new(&counted, start, position, 4.0, 3, NewtonOptions::default()).collect();
    assert!(counted.solves.get() < 10_000, "{outcomes:?}");
}

/// A slide-driven sweep to the toggle where rod and crank line up (slide 3 times the crank's
/// length), at every size: pieces of at most the loops' length (a slide's unit), and the look
/// beyond starting `√ε` of that length away. At 1e20 the walk took 2¹⁶ pieces a step (pieces
/// of at most 1, then coarse ones: three seconds for a hundred steps), and at 1e-20 it looked
/// 1.5e-8 beyond, a million times the linkage, and named that input in its error.
#[test]
fn a_slide_driven_sweep_walks_and_looks_in_the_linkage_s_units() {
    for exponent in [-20, 0, 20] {
        let size = 10f64.powi(exponent);
        let linkage = SlideDriven {
            l2: size,
            l3: 2.0 * size,
            c: 0.0,
        };
        let guess = SlideDrivenUnknowns {
            theta2: 1.0,
            theta3: -0.4,
        };
        let start = linkage
            .position(2.0 * size, &guess, &NewtonOptions::default())
            .unwrap()
            .value;
        let counted = Counted {
            mechanism: &linkage,
            solves: std::cell::Cell::new(0),
            limit: 100_000,
        };
        let stop = Sweep::new(
            &counted,
            2.0 * size,
            start.to_array(),
            0.01 * size,
            150,
            NewtonOptions::default(),
        )
        .find_map(Result::err);
        let Some(Stop::Toggle {
            last_input,
            error: mechgen::Error::CannotAssemble { input },
            ..
        }) = stop
        else {
            panic!("1e{exponent}: {stop:?}");
        };
        // The last input, 3·size less rounding, and the nearest failure past it within
        // √ε·3·size.
        assert!(
            (last_input / size - 3.0).abs() < 1e-12,
            "1e{exponent}: {last_input}"
        );
        let past = input / size - 3.0;
        assert!(past > 0.0 && past < 1e-7, "1e{exponent}: {input}");
        assert!(
            counted.solves.get() < 1_000,
            "1e{exponent}: {}",
            counted.solves.get()
        );
    }
}

/// The crossed isosceles slider-crank keeps its slider at the crank's pivot (`d` = 0 to the
/// rounding of its lengths) while the rod turns: a sweep of it goes on at every size, a
/// solve or two a step. Its smoothness test weighed that rounding, some ε of the linkage,
/// against the angle's, and refused every piece down to 2⁻⁴⁰ of a step: a crawl, a hang from
/// sizes of 1e16 in f64 (an adversarial review's catch).
#[test]
fn a_slide_at_rest_to_rounding_does_not_make_a_sweep_crawl() {
    for size in [1.0f64, 1e10, 1e16, 1e18, 1e100, 1e-100] {
        let slider = SliderCrank::new(size, size, 0.0).unwrap();
        for (branch, start, step) in [(Branch::Crossed, 0.3, 0.01), (Branch::Open, 2.0, -0.001)] {
            let position = slider.assemble(start, branch).unwrap().to_array();
            let counted = Counted {
                mechanism: &slider,
                solves: std::cell::Cell::new(0),
                limit: 10_000,
            };
            let samples: Vec<_> = Sweep::new(
                &counted,
                start,
                position,
                step,
                10,
                NewtonOptions::default(),
            )
            .collect::<Result<_, _>>()
            .unwrap_or_else(|stop| panic!("{size:e}, {branch:?}: {stop:?}"));
            for sample in &samples {
                let closed = slider.assemble(sample.input, branch).unwrap().to_array();
                assert!(
                    (sample.position[0] - closed[0]).abs() < 1e-9
                        && (sample.position[1] - closed[1]).abs() < 1e-9 * size,
                    "{size:e}, {branch:?}: {sample:?} against {closed:?}"
                );
            }
            assert!(
                counted.solves.get() < 100,
                "{size:e}, {branch:?}: {} solves",
                counted.solves.get()
            );
        }
    }
}
