//! Issue 12's reproducers for the solvers, each kept as a regression test: inputs just past
//! the range of motion, thin triangles, scales from 1e-300 to 1e300, non-finite values
//! inside `Ok`, and Newton stopping short of the attainable accuracy.

use mechanisms::{
    FourBar, FourBarUnknowns, SliderCrank, StephensonSixBar, StephensonSixBarUnknowns,
};
use mechgen::{Branch, Error, NewtonOptions, Real};

const BRANCHES: [Branch; 2] = [Branch::Open, Branch::Crossed];

/// The four-bar's loop residual at a solution, relative to `size`, the sum of its lengths.
fn relative_residual<T: Real>(
    linkage: &FourBar<T>,
    size: T,
    input: T,
    position: &FourBarUnknowns<T>,
) -> T {
    let [x, y] = linkage.residual(input, position);
    x.abs().max(y.abs()) / size
}

/// Inputs below the toggle of a rocker a thousand times shorter than the coupler: the closed
/// form used to accept them within a band of rounding in squared lengths, which in f32 was
/// wider than the rocker itself (Ok, with a residual of 20% of the rocker, and the same point
/// on both branches).
#[test]
fn inputs_just_past_the_toggle_cannot_assemble() {
    let f32_linkage = FourBar::<f32>::new(1.0, 1000.0, 1000.3, 1.0).unwrap();
    let scenes = f32_linkage.scenes().unwrap();
    for branch in BRANCHES {
        assert_eq!(
            f32_linkage.assemble(0.4, branch),
            Err(Error::CannotAssemble { input: 0.4 })
        );
        assert_eq!(
            scenes.angles(0.4, branch, 1.0, 0.0),
            Err(Error::CannotAssemble { input: 0.4 })
        );
    }

    // In f64, 2.5e-3 rad before a toggle at 0.7953984731912886: a residual of 1.3e-3.
    let linkage = FourBar::new(1.0, 1e6, 1e6 + 0.3, 1.0).unwrap();
    let scenes = linkage.scenes().unwrap();
    let beyond = 0.792_934_408_261_189_4;
    for branch in BRANCHES {
        assert_eq!(
            linkage.assemble(beyond, branch),
            Err(Error::CannotAssemble { input: beyond })
        );
        assert_eq!(
            scenes.angles(beyond, branch, 1.0, 0.0),
            Err(Error::CannotAssemble { input: beyond })
        );
    }
    // Just inside, it assembles and closes its loop to rounding.
    let inside = 0.7955;
    for branch in BRANCHES {
        let position = linkage.assemble(inside, branch).unwrap();
        let size = 2e6 + 2.3;
        assert!(relative_residual(&linkage, size, inside, &position) <= 4.0 * f64::EPSILON);
        assert_eq!(linkage.branch_of(inside, &position), branch);
    }
}

/// Past the range of motion by 1e-12, 1e-9 and 1e-6 rad, in f64, on both branches and in
/// every solver, the answer is CannotAssemble; as far inside, Ok.
#[test]
fn f64_inputs_just_past_each_limit_cannot_assemble() {
    // A non-Grashof four-bar: its crank swings between ±limit.
    let linkage = FourBar::new(100.0, 120.0, 90.0, 80.0).unwrap();
    let limit = linkage.limit_angles().extended.expect("a limit short of π");
    let scenes = linkage.scenes().unwrap();
    for offset in [1e-12, 1e-9, 1e-6] {
        let (outside, inside) = (limit + offset, limit - offset);
        for branch in BRANCHES {
            let cannot = Err(Error::CannotAssemble { input: outside });
            assert_eq!(linkage.assemble(outside, branch), cannot);
            assert_eq!(
                linkage
                    .motion(outside, branch, 1.0, 0.0)
                    .map(|m| m.position),
                cannot
            );
            assert_eq!(
                scenes.angles(outside, branch, 1.0, 0.0).err(),
                Some(Error::CannotAssemble { input: outside })
            );
            let position = linkage.assemble(inside, branch).unwrap();
            assert!(relative_residual(&linkage, 390.0, inside, &position) <= 4.0 * f64::EPSILON);
        }
    }
}

/// A well-conditioned four-bar whose triangle A B O4 is thin (the rocker a thousand times
/// shorter than the coupler): in f32 the closed form lost every digit of θ4 (0.11 rad off),
/// in f64 it was 2e-10 rad off. The f64 solution is the reference for f32's; f64 is checked
/// by closing its loop and by its agreement with Newton polished from it.
#[test]
fn thin_triangles_keep_their_digits() {
    let dimensions = [1.0, 1000.0, 1000.3, 1.0];
    let [l1, l2, l3, l4] = dimensions;
    let linkage = FourBar::new(l1, l2, l3, l4).unwrap();
    let narrow = FourBar::<f32>::new(l1 as f32, l2 as f32, l3 as f32, l4 as f32).unwrap();
    let limit = linkage.limit_angles().folded.expect("a limit short of 0");
    let size: f64 = dimensions.iter().sum();
    for step in 0..50 {
        let input = limit + 0.01 + 0.05 * f64::from(step);
        for branch in BRANCHES {
            let Ok(exact) = linkage.assemble(input, branch) else {
                continue;
            };
            let kappa = linkage.condition(input, &exact);
            assert!(relative_residual(&linkage, size, input, &exact) <= 4.0 * f64::EPSILON);
            let polished = linkage
                .position(input, &exact, &NewtonOptions::default())
                .unwrap()
                .value;
            // The contract weights an angle's error by its link's length.
            let bound = 16.0 * f64::EPSILON * kappa * dimensions.iter().sum::<f64>();
            assert!((exact.theta4 - polished.theta4).abs() * l4 <= bound);
            assert!((exact.theta3 - polished.theta3).abs() * l3 <= bound);

            let input32 = input as f32;
            let Ok(got) = narrow.assemble(input32, branch) else {
                continue;
            };
            let reference = linkage.assemble(f64::from(input32), branch).unwrap();
            let bound32 = 16.0 * f64::from(f32::EPSILON) * kappa * dimensions.iter().sum::<f64>();
            assert!(
                (f64::from(got.theta4) - reference.theta4).abs() * l4 <= bound32,
                "f32 θ4 {} against {} at {input32}",
                got.theta4,
                reference.theta4
            );
        }
    }
}

/// Kinematics is scale-invariant: Example 1 with every length times a power of two gives the
/// same angles and rates, bit for bit, from every solver; times any other factor, the same
/// to rounding. (Scaled by 1e154 or 1e300 it could not assemble; by 1e-162 it was 6e-5 rad
/// off; by 1e-300, Singular.)
#[test]
fn every_scale_gives_the_same_angles() {
    let example_1 = [180.0, 80.0, 200.0, 150.0];
    let at = |factor: f64| {
        let [l1, l2, l3, l4] = example_1.map(|l| l * factor);
        let linkage = FourBar::new(l1, l2, l3, l4).unwrap();
        let input = 60f64.to_radians();
        let motion = linkage.motion(input, Branch::Open, 10.0, 2.0).unwrap();
        let angles = linkage
            .scenes()
            .unwrap()
            .angles(input, Branch::Open, 10.0, 2.0)
            .unwrap();
        let newton = linkage
            .position(input, &motion.position, &NewtonOptions::default())
            .unwrap()
            .value;
        [
            motion.position.theta3,
            motion.position.theta4,
            motion.velocity.theta3,
            motion.velocity.theta4,
            motion.acceleration.theta3,
            motion.acceleration.theta4,
            angles.theta3,
            angles.theta4,
            angles.theta3_dot,
            angles.theta4_dot,
            angles.theta3_ddot,
            angles.theta4_ddot,
            newton.theta3,
            newton.theta4,
        ]
    };
    let unit = at(1.0);
    assert!((unit[1] - 72.1377f64.to_radians()).abs() < 1e-5);
    for power in [-1000, -600, -300, 300, 600, 1000] {
        assert_eq!(at(2f64.powi(power)), unit, "2^{power}");
    }
    for factor in [1e-300, 1e-162, 1e-100, 1e100, 1e154, 1e300] {
        for (got, want) in at(factor).iter().zip(unit) {
            assert!(
                (got - want).abs() <= 64.0 * f64::EPSILON * want.abs().max(1.0),
                "{factor:e}: {got} against {want}"
            );
        }
    }
}

/// Scaled by a power of two, f32 mechanisms near the bottom of the float's range give the
/// same bits from `assemble` and `motion` (the edge run's case 205653: a crank's
/// `l2·sin θ2` left the normal range at the smaller size, and the rates lost a bit). Both
/// compute on the mechanism scaled so that its longest length is about 1.
#[test]
fn f32_closed_forms_give_the_same_bits_at_every_scale() {
    let four_bar = [9.584662e-21f32, 1.3102157e-21, 1.0241929e-20, 3.6827567e-21];
    let four_bar_at = |factor: f32| {
        let [l1, l2, l3, l4] = four_bar.map(|l| l * factor);
        let linkage = FourBar::<f32>::new(l1, l2, l3, l4).unwrap();
        let m = linkage
            .motion(0.061181106, Branch::Open, -35.643475, 1.1511047)
            .unwrap();
        let p = linkage.assemble(0.061181106, Branch::Open).unwrap();
        [
            m.position.theta3,
            m.position.theta4,
            m.velocity.theta3,
            m.velocity.theta4,
            m.acceleration.theta3,
            m.acceleration.theta4,
            p.theta3,
            p.theta4,
        ]
        .map(f32::to_bits)
    };
    let unit = four_bar_at(1.0);
    for power in [-55, -53, -30, 40, 120] {
        assert_eq!(four_bar_at(2f32.powi(power)), unit, "four-bar × 2^{power}");
    }
    // A slider-crank: its angle the same bits, its slider the same scaled exactly.
    let slider_at = |factor: f32| {
        let linkage =
            SliderCrank::<f32>::new(3e-20 * factor, 7e-20 * factor, 1e-21 * factor).unwrap();
        let m = linkage.motion(0.01, Branch::Open, 3.0, -2.0).unwrap();
        (
            [m.position.theta3, m.velocity.theta3, m.acceleration.theta3].map(f32::to_bits),
            [m.position.d, m.velocity.d, m.acceleration.d].map(|d| d / factor),
        )
    };
    let (angles, lengths) = slider_at(1.0);
    for power in [-40, -20, 40, 100] {
        let (a, l) = slider_at(2f32.powi(power));
        assert_eq!(a, angles, "slider-crank × 2^{power}");
        assert_eq!(l, lengths, "slider-crank × 2^{power}");
    }
}

/// A slider-crank whose rod is 1.9e19 in f32: its squares overflowed and `assemble` was
/// `Ok{θ3: NaN, d: inf}`. The slider is at the rod's length from the crank pin.
#[test]
fn huge_f32_slider_cranks_are_finite() {
    let linkage = SliderCrank::<f32>::new(5.0, 1.9e19, 6.0).unwrap();
    for branch in BRANCHES {
        let position = linkage.assemble(0.17, branch).unwrap();
        assert!(position.theta3.is_finite() && position.d.is_finite());
        assert!((position.d.abs() - 1.9e19).abs() <= 4.0 * f32::EPSILON * 1.9e19);
    }
}

/// A slider-crank of 5e36 in f32 whose crank cannot reach the slide's line at the input:
/// Newton's iterates ran away until a step overflowed, and it said `NonFinite` where the
/// closed form knows the answer, `CannotAssemble`.
#[test]
fn newton_running_away_beyond_the_range_cannot_assemble() {
    let linkage = SliderCrank::<f32>::new(5.316912e36, 1.4835638e36, 5.8348357e35).unwrap();
    assert_eq!(
        linkage.assemble(0.6833616, Branch::Open),
        Err(Error::CannotAssemble { input: 0.6833616 })
    );
    let guess = mechanisms::SliderCrankUnknowns {
        theta3: -0.018_750_027,
        d: 6.764_957e36,
    };
    assert_eq!(
        linkage
            .position(0.6833616, &guess, &NewtonOptions::default())
            .map(|s| s.value),
        Err(Error::CannotAssemble { input: 0.6833616 })
    );
}

/// Lengths whose sum overflows: Newton returned its guess, untouched, as Ok (then, checking
/// its numbers, NonFinite). It now solves on the mechanism scaled by a power of two, so it
/// answers as for the same linkage at unit size: the same angles, bit for bit.
#[test]
fn newton_solves_where_the_lengths_sum_beyond_the_float() {
    let guess = FourBarUnknowns {
        theta3: 1.0,
        theta4: 2.0,
    };
    let solve = |factor: f64| {
        FourBar::new(5.0 * factor, 6.0 * factor, 6.0 * factor, 3.0 * factor)
            .unwrap()
            .position(0.5, &guess, &NewtonOptions::default())
            .map(|s| s.value)
    };
    let huge = solve(2f64.powi(1020));
    assert_eq!(huge, solve(1.0));
    assert_eq!(huge, solve(2f64.powi(-1060)));
}

/// Newton by default goes to the attainable accuracy, and a solve restarted from its own
/// result polishes it (it used to make no iteration at all).
#[test]
fn newton_polishes_what_it_is_given() {
    let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let input = 60f64.to_radians();
    let exact = linkage.assemble(input, Branch::Open).unwrap();
    // A loose solve, to 1e-3 mm, then the default from there.
    let rough = FourBarUnknowns {
        theta3: exact.theta3 + 1e-4,
        theta4: exact.theta4 - 1e-4,
    };
    let loose = linkage
        .position(input, &rough, &NewtonOptions::new(1e-3, 50))
        .unwrap();
    assert!(loose.residual_norm > 1e-9);
    let polished = linkage
        .position(input, &loose.value, &NewtonOptions::default())
        .unwrap();
    assert!(polished.iterations >= 1);
    let size: f64 = 180.0 + 80.0 + 200.0 + 150.0;
    assert!(polished.residual_norm <= 4.0 * f64::EPSILON * size);
    for (got, want) in [
        (polished.value.theta3, exact.theta3),
        (polished.value.theta4, exact.theta4),
    ] {
        assert!(
            (got - want).abs() <= 4.0 * f64::EPSILON,
            "{got} against {want}"
        );
    }
    // From its own result: one polishing step, and the same solution to rounding.
    let again = linkage
        .position(input, &polished.value, &NewtonOptions::default())
        .unwrap();
    assert_eq!(again.iterations, 1);
    assert!((again.value.theta4 - polished.value.theta4).abs() <= 2.0 * f64::EPSILON);
}

/// The angle between two angles, in [0, π].
fn angle_between(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

/// A Newton-only six-bar keeps its assembly: started up to 1 rad away from a solution in
/// every unknown, Newton converges to that solution or says it cannot (OtherBranch,
/// CannotAssemble, ...); it never returns another assembly as Ok (it did in 10 of 200 tries).
#[test]
fn newton_only_mechanisms_keep_their_assembly() {
    let (six_bar, guess) = mechgen_tests::examples::stephenson_six_bar();
    let solution = six_bar
        .position(0.0, &guess, &NewtonOptions::default())
        .unwrap()
        .value
        .to_array();
    // A fixed sequence of offsets in [−1, 1] rad (a linear congruential generator).
    let mut state = 12_345_u64;
    let mut offset = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut kept = 0;
    for _ in 0..200 {
        let start: [f64; 4] = std::array::from_fn(|i| solution[i] + offset());
        let start = mechanisms::StephensonSixBarUnknowns::from_array(start);
        if let Ok(solved) = six_bar.position(0.0, &start, &NewtonOptions::default()) {
            let apart = solved
                .value
                .to_array()
                .iter()
                .zip(solution)
                .map(|(&a, b)| angle_between(a, b))
                .fold(0.0, f64::max);
            assert!(
                apart < 1e-9,
                "another assembly from {start:?}: {:?}",
                solved.value
            );
            kept += 1;
        }
    }
    assert!(kept >= 150, "only {kept} of 200 converged");
}

/// Sweeps of the six-bar in steps of up to 120° give the positions of a 1° sweep, or stop.
#[test]
fn coarse_six_bar_sweeps_do_not_jump_assembly() {
    use mechgen::sweep::Sweep;
    let (six_bar, guess) = mechgen_tests::examples::stephenson_six_bar();
    let start = six_bar
        .position(0.0, &guess, &NewtonOptions::default())
        .unwrap()
        .value
        .to_array();
    let fine: Vec<_> = Sweep::new(
        &six_bar,
        0.0,
        start,
        1f64.to_radians(),
        360,
        NewtonOptions::default(),
    )
    .map(|sample| sample.expect("the six-bar turns fully").position)
    .collect();
    for degrees in [10u32, 30, 45, 90, 120] {
        // `steps` steps after the start: to 360°.
        let steps = 360 / degrees;
        let coarse = Sweep::new(
            &six_bar,
            0.0,
            start,
            f64::from(degrees).to_radians(),
            steps,
            NewtonOptions::default(),
        );
        for (k, sample) in coarse.enumerate() {
            let Ok(sample) = sample else { break };
            let reference = fine[k * degrees as usize];
            for (&got, want) in sample.position.iter().zip(reference) {
                assert!(
                    angle_between(got, want) < 1e-9,
                    "{degrees}° steps, sample {k}"
                );
            }
        }
    }
}

/// Rates with no correct digits are refused, not returned: 1e-6 rad from a parallelogram's
/// change point, α3 = −26674.6 and α4 = 53354.2 came back Ok where both are 0 and 5; at the
/// isosceles inverted slider-crank's θ2 = 2π, where the slide has shrunk to nothing, ω4 was
/// 12.5 (exactly 5) and α4 6e17.
#[test]
fn rates_without_correct_digits_are_inaccurate() {
    use mechanisms::InvertedSliderCrank;
    let parallelogram = FourBar::<f64>::new(100.0, 50.0, 100.0, 50.0).unwrap();
    let near = 1e-6;
    let position = parallelogram.assemble(near, Branch::Open).unwrap();
    let motion = parallelogram.motion(near, Branch::Open, 10.0, 0.0);
    assert!(
        matches!(motion, Err(Error::Inaccurate { .. })),
        "{motion:?}"
    );
    assert!(matches!(
        parallelogram.velocity(near, &position, 10.0),
        Err(Error::Inaccurate { .. })
    ));
    let scene = parallelogram
        .scenes()
        .unwrap()
        .angles(near, Branch::Open, 10.0, 0.0);
    assert!(scene.is_err(), "{scene:?}");
    // Far enough from it, the rates are back, and right: the parallelogram's coupler does
    // not turn, and its rocker turns with the crank.
    let far = 0.1;
    let motion = parallelogram.motion(far, Branch::Open, 10.0, 0.0).unwrap();
    assert!(motion.velocity.theta3.abs() < 1e-12);
    assert!((motion.velocity.theta4 - 10.0).abs() < 1e-12);

    let isosceles = InvertedSliderCrank::new(150.0, 150.0, 0.0, 0.0).unwrap();
    let turn = std::f64::consts::TAU;
    let motion = isosceles.motion(turn, Branch::Open, 10.0, 0.0);
    assert!(
        matches!(
            motion,
            Err(Error::Inaccurate { .. } | Error::Singular { .. })
        ),
        "{motion:?}"
    );
}

/// The estimates are the documented formulas, and a rate is refused exactly where its
/// estimate exceeds what is required.
#[test]
fn estimates_follow_the_documented_formulas() {
    use mechgen::{Accuracy, Order};
    let e = f64::EPSILON;
    let estimate = Accuracy::<f64>::estimate(2.0, 4.0);
    assert_eq!(estimate.position, 64.0 * e);
    assert_eq!(estimate.velocity, e * 2.0 * (64.0 + 24.0));
    assert_eq!(estimate.acceleration, e * 2.0 * (256.0 + 4.0));
    // A slide shrunk to 1/64 of the size: the rates' estimates grow by 4 and 16.
    let shrunk = Accuracy::<f64>::estimate(2.0, 64.0);
    assert_eq!(shrunk.velocity, 4.0 * estimate.velocity);
    assert_eq!(shrunk.acceleration, 16.0 * estimate.acceleration);
    let required = Accuracy::<f64>::required();
    assert_eq!(estimate.within(&required, Order::Acceleration), Ok(()));
    let far = Accuracy::<f64>::estimate(1e5, 1.0);
    assert_eq!(far.within(&required, Order::Position), Ok(()));
    assert_eq!(
        far.within(&required, Order::Acceleration),
        Err(Error::Inaccurate {
            order: Order::Velocity,
            estimate: far.velocity,
            required: required.velocity,
        })
    );
}

/// Huge slider-cranks assemble finitely on both branches (NaN inside Ok at 1e157).
#[test]
fn huge_slider_cranks_are_finite_on_both_branches() {
    let linkage = SliderCrank::<f64>::new(2.7e152, 2.2e157, 2.7e151).unwrap();
    for branch in BRANCHES {
        let position = linkage.assemble(0.0, branch).unwrap();
        assert!(
            position.theta3.is_finite() && position.d.is_finite(),
            "{position:?}"
        );
        assert!((position.d.abs() - 2.2e157).abs() <= 1e-3 * 2.2e157);
    }
}

/// The caller states the accuracy it needs: loosened, the rates near a change point come back
/// (with the digits the estimate promises); tightened, ordinary rates are refused.
#[test]
fn the_caller_states_the_accuracy_it_needs() {
    use mechgen::{Accuracy, Order};
    let parallelogram = FourBar::<f64>::new(100.0, 50.0, 100.0, 50.0).unwrap();
    let near = 1e-5;
    let guess = parallelogram.assemble(near, Branch::Open).unwrap();
    let strict = NewtonOptions::default();
    assert!(matches!(
        parallelogram.motion_near(near, &guess, &strict, 10.0, 0.0),
        Err(Error::Inaccurate { .. })
    ));
    // The acceleration has no digit left there (κ near 1e5, and Newton's position carries
    // 64·m·ε·κ³·ρ into it, m = 2 for the four-bar's two angles: an estimate of about 170):
    // loosened past that.
    let loose = NewtonOptions::default().with_accuracy(Accuracy {
        position: 1e-3,
        velocity: 1e-2,
        acceleration: 1000.0,
    });
    let motion = parallelogram
        .motion_near(near, &guess, &loose, 10.0, 0.0)
        .unwrap()
        .value;
    // The parallelogram's rocker turns with its crank: right to the loosened 1%.
    assert!((motion.velocity.theta4 - 10.0).abs() <= 1e-2 * 10.0);

    let scenes = parallelogram.scenes().unwrap();
    assert!(scenes.angles(near, Branch::Open, 10.0, 0.0).is_err());
    let loose_scenes = scenes.with_accuracy(&loose.accuracy);
    let angles = loose_scenes.angles(near, Branch::Open, 10.0, 0.0).unwrap();
    assert!((angles.theta4_dot - 10.0).abs() <= 1e-2 * 10.0);

    // Tightened to all of f64's digits, even Example 1's ordinary position is refused.
    let example_1 = FourBar::<f64>::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let input = 60f64.to_radians();
    let position = example_1.assemble(input, Branch::Open).unwrap();
    let exact = NewtonOptions::default().with_accuracy(Accuracy {
        position: f64::EPSILON,
        velocity: f64::EPSILON,
        acceleration: f64::EPSILON,
    });
    let refused = example_1.motion_near(input, &position, &exact, 10.0, 0.0);
    assert!(
        matches!(
            refused,
            Err(Error::Inaccurate {
                order: Order::Velocity,
                ..
            })
        ),
        "{refused:?}"
    );
}

/// A tracked point far off its link does not make the loops' rates less accurate: the aspect
/// counts the lengths of the loops' vectors only (a coupler point 1e9 away made Example 1's
/// accelerations Inaccurate).
#[test]
fn a_far_coupler_point_does_not_refuse_the_rates() {
    let linkage = FourBar::<f64>::new(180.0, 80.0, 200.0, 150.0)
        .unwrap()
        .with_coupler_point(1e9, 0.3)
        .unwrap();
    let motion = linkage
        .motion(60f64.to_radians(), Branch::Open, 10.0, 0.0)
        .unwrap();
    assert!((motion.position.theta4 - 72.1377f64.to_radians()).abs() < 1e-5);
}

/// Newton (`position`, `motion_near`, the reduced iteration of the Stephenson six-bar) solves
/// on the mechanism scaled by a power of two, as the closed forms do: the same bits at every
/// size. In f32 at 2^120 a four-bar's `motion_near` was NonFinite (its right-hand side,
/// lengths times ω², overflowed though the angular accelerations are 36 rad/s²), and the edge
/// run's case 646633, a Stephenson six-bar in f32, was Ok at one size and Inaccurate at
/// another.
#[test]
fn newton_gives_the_same_bits_at_every_scale() {
    let four_bar = |factor: f32| {
        let linkage =
            FourBar::<f32>::new(1.8 * factor, 0.8 * factor, 2.0 * factor, 1.5 * factor).unwrap();
        let guess = FourBarUnknowns {
            theta3: 0.4,
            theta4: 1.2,
        };
        let options = NewtonOptions::default();
        let p = linkage.position(1.0, &guess, &options).unwrap();
        let m = linkage
            .motion_near(1.0, &guess, &options, 10.0, 2.0)
            .unwrap();
        let v = m.value;
        assert_eq!(p.residual_norm / factor, m.residual_norm / factor);
        [
            p.value.theta3,
            p.value.theta4,
            v.position.theta3,
            v.velocity.theta3,
            v.velocity.theta4,
            v.acceleration.theta3,
            v.acceleration.theta4,
        ]
        .map(f32::to_bits)
    };
    let unit = four_bar(1.0);
    for power in [-120, -60, 60, 120] {
        assert_eq!(four_bar(2f32.powi(power)), unit, "four-bar × 2^{power}");
    }
    // A slider: its length and rates scaled exactly, its angle the same bits.
    let slider = |factor: f64| {
        let linkage = SliderCrank::new(40.0 * factor, 120.0 * factor, 5.0 * factor).unwrap();
        let guess = linkage.assemble(0.7, Branch::Open).unwrap();
        let guess = mechanisms::SliderCrankUnknowns {
            theta3: guess.theta3 + 1e-3,
            d: guess.d * 1.001,
        };
        let m = linkage
            .motion_near(0.7, &guess, &NewtonOptions::default(), 3.0, -1.0)
            .unwrap()
            .value;
        (
            [m.position.theta3, m.velocity.theta3, m.acceleration.theta3].map(f64::to_bits),
            [m.position.d, m.velocity.d, m.acceleration.d].map(|d| d / factor),
        )
    };
    let unit = slider(1.0);
    for power in [-1000, -500, 500, 1000] {
        assert_eq!(slider(2f64.powi(power)), unit, "slider-crank × 2^{power}");
    }
    // The Stephenson six-bar's reduced iteration.
    let stephenson = |factor: f64| {
        let l = |x: f64| x * factor;
        let linkage = StephensonSixBar::new(
            l(100.0),
            l(20.0),
            l(117.0),
            [l(60.0), l(63.0)],
            -0.97,
            l(52.0),
            l(85.0),
            (l(189.0), l(-26.0)),
        )
        .unwrap();
        let guess = StephensonSixBarUnknowns {
            theta3: -0.25,
            theta4: 0.63,
            theta5: 1.43,
            theta6: 1.46,
        };
        let m = linkage
            .motion_near(0.0, &guess, &NewtonOptions::default(), 5.0, 1.0)
            .unwrap()
            .value;
        [
            m.position.theta3,
            m.position.theta6,
            m.velocity.theta5,
            m.acceleration.theta6,
        ]
        .map(f64::to_bits)
    };
    let unit = stephenson(1.0);
    for power in [-1000, -300, 300, 1000] {
        assert_eq!(stephenson(2f64.powi(power)), unit, "Stephenson × 2^{power}");
    }
}

/// Four-bars, slider-cranks and inverted slider-cranks on either side of the sizes at which the
/// closed forms and Newton solve the mechanism as given (`mechgen::__private::as_given`:
/// 2^-200 to 2^200 in f64, 2^-16 to 2^24 in f32), each against the same mechanism scaled by a
/// power of two far outside them: the same bits, or the same error. Link ratios to 1e6 and
/// inputs within 1e-9 of a limit as well as anywhere.
#[test]
fn solving_as_given_or_scaled_gives_the_same_bits() {
    fn check<T: Real + std::fmt::Debug>(exponents: (f64, f64), shift: i32) -> usize {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut uniform = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let t = |x: f64| T::from(x).unwrap();
        let same = |a: String, b: String| a == b;
        let mut compared = 0;
        for _ in 0..2000 {
            let decades = uniform() * 6.0;
            let size = 2f64.powi((exponents.0 + uniform() * (exponents.1 - exponents.0)) as i32);
            let l: Vec<T> = (0..4)
                .map(|_| t(10f64.powf(-uniform() * decades) * size))
                .collect();
            let k = t(2f64.powi(shift));
            let (Ok(small), Ok(large)) = (
                FourBar::new(l[0], l[1], l[2], l[3]),
                FourBar::new(l[0] * k, l[1] * k, l[2] * k, l[3] * k),
            ) else {
                continue;
            };
            let limits = small.limit_angles();
            let input = match (limits.folded, limits.extended, uniform()) {
                (Some(limit), _, u) | (_, Some(limit), u) if u < 0.6 => {
                    limit * t(1.0 + (uniform() - 0.5) * 2e-9)
                }
                _ => t(uniform() * std::f64::consts::TAU),
            };
            let (w, a) = (t(3.0), t(1.0));
            for branch in [Branch::Open, Branch::Crossed] {
                let (x, y) = (
                    small.motion(input, branch, w, a),
                    large.motion(input, branch, w, a),
                );
                let text = |m: &Result<mechgen::Motion<FourBarUnknowns<T>, T>, Error<T>>| match m {
                    Ok(m) => format!("{:?}", (m.position, m.velocity, m.acceleration)),
                    Err(e) => format!("{:?}", std::mem::discriminant(e)),
                };
                assert!(
                    same(text(&x), text(&y)),
                    "{l:?} at {input:?}: {x:?} / {y:?}"
                );
                compared += 1;
                if let Ok(m) = x {
                    let guess = FourBarUnknowns {
                        theta3: m.position.theta3 + t(1e-3),
                        theta4: m.position.theta4 - t(1e-3),
                    };
                    let options = NewtonOptions::default();
                    let newton = |linkage: &FourBar<T>| match linkage
                        .motion_near(input, &guess, &options, w, a)
                    {
                        Ok(s) => format!("{:?}", (s.value.position, s.value.velocity)),
                        Err(e) => format!("{:?}", std::mem::discriminant(&e)),
                    };
                    assert_eq!(newton(&small), newton(&large), "{l:?} at {input:?}");
                    compared += 1;
                }
            }
            let offset = l[0] - l[3];
            if let (Ok(small), Ok(large)) = (
                SliderCrank::new(l[1], l[2], offset),
                SliderCrank::new(l[1] * k, l[2] * k, offset * k),
            ) {
                let angles = |m: Result<
                    mechgen::Motion<mechanisms::SliderCrankUnknowns<T>, T>,
                    Error<T>,
                >,
                              unit: T| match m {
                    Ok(m) => format!(
                        "{:?}",
                        (
                            m.position.theta3,
                            m.velocity.theta3,
                            m.acceleration.theta3,
                            m.position.d / unit,
                            m.acceleration.d / unit
                        )
                    ),
                    Err(e) => format!("{:?}", std::mem::discriminant(&e)),
                };
                assert_eq!(
                    angles(small.motion(input, Branch::Open, w, a), t(1.0)),
                    angles(large.motion(input, Branch::Open, w, a), k),
                    "slider-crank {l:?} at {input:?}"
                );
                compared += 1;
            }
        }
        compared
    }
    assert!(check::<f64>((-202.0, -190.0), 400) > 2000);
    assert!(check::<f64>((190.0, 202.0), -400) > 2000);
    assert!(check::<f64>((-20.0, 20.0), 700) > 2000);
    assert!(check::<f32>((-18.0, -8.0), 40) > 2000);
    assert!(check::<f32>((16.0, 26.0), -40) > 2000);
    assert!(check::<f32>((-5.0, 10.0), 60) > 2000);
}

/// Rates as far from 1 as the lengths are (a slider-crank of 1e300 turning at 1e-200 rad/s,
/// whose slider accelerates at about 1e-100): `motion` and `motion_near`, which compute on
/// the mechanism scaled to size 1 (and on one of 1e50 as given), count time in units that
/// bring the rates near 1 too wherever the rates are far from 1, so no squared rate
/// underflows (the slider's acceleration came out 0, with a stated relative accuracy of
/// 6e-14) or overflows; they agree with `motion_at`, which computes in the mechanism's own
/// units. Where the true value is beyond the float's range, an error.
#[test]
fn rates_far_from_1_on_a_mechanism_far_from_size_1() {
    fn check<T: Real>(size: T, omega: T, alpha: T) -> Option<[[T; 2]; 2]> {
        let linkage =
            SliderCrank::new(T::constant(0.3) * size, size, T::constant(0.1) * size).unwrap();
        let theta2 = T::constant(0.7);
        let q = linkage.assemble(theta2, Branch::Open).unwrap();
        let at = linkage.motion_at(theta2, &q, omega, alpha);
        let motion = linkage.motion(theta2, Branch::Open, omega, alpha);
        let near = linkage
            .motion_near(theta2, &q, &NewtonOptions::default(), omega, alpha)
            .map(|solved| solved.value);
        let (Ok(at), Ok(motion), Ok(near)) = (at, motion, near) else {
            assert!(
                motion.is_err() && near.is_err(),
                "{size:?} {omega:?} {alpha:?}: {motion:?}"
            );
            return None;
        };
        for got in [motion, near] {
            let pairs = [
                (got.velocity.to_array(), at.velocity.to_array()),
                (got.acceleration.to_array(), at.acceleration.to_array()),
            ];
            for (got, want) in pairs {
                for (g, w) in got.into_iter().zip(want) {
                    assert!(
                        (g - w).abs() <= T::constant(1e-5) * w.abs(),
                        "{size:?} {omega:?} {alpha:?}: {g:?} against {w:?}"
                    );
                }
            }
        }
        Some([motion.velocity.to_array(), motion.acceleration.to_array()])
    }
    // The slider's acceleration, about 0.26·size·ω²: 1e300 turning at 1e-150 (ω² = 1e-300,
    // outside the rates the solvers take as given).
    let [_, [_, d_ddot]] = check(1e300f64, 1e-150, 0.0).unwrap();
    assert!((d_ddot / -0.26469180409627 - 1.0).abs() < 1e-12, "{d_ddot}");
    let [_, [_, d_ddot]] = check(1e300f64, 1e-150, 3e-299).unwrap();
    assert!(d_ddot < -0.1);
    let [_, [theta3_ddot, _]] = check(1e-300f64, 1e100, 1e300).unwrap();
    assert!((theta3_ddot / -2.304571515774686e299 - 1.0).abs() < 1e-12);
    // A size the solvers take as given, with rates they do not: 1e50 turning at 1e-140.
    let [_, [_, d_ddot]] = check(1e50f64, 1e-140, 0.0).unwrap();
    assert!(
        (d_ddot / -2.6469180409627e-231 - 1.0).abs() < 1e-12,
        "{d_ddot}"
    );
    // f32: 1e30 turning at 1e-15 (ω² = 1e-30, outside the rates it takes as given), and
    // 1e6, as given, turning at 1e-20 (ω² = 1e-40 is below its normal range: the rod's
    // angular acceleration is a subnormal number, known to some 1e-5 of ω², which the
    // stated accuracy says).
    let [_, [_, d_ddot]] = check(1e30f32, 1e-15, 0.0).unwrap();
    assert!((d_ddot / -0.2646918 - 1.0).abs() < 1e-5, "{d_ddot}");
    let [_, [_, d_ddot]] = check(1e6f32, 1e-20, 0.0).unwrap();
    assert!((d_ddot / -2.646918e-35 - 1.0).abs() < 1e-5, "{d_ddot}");
    // Slower: 1e300 turning at 1e-200 rad/s. The slider accelerates at about 1e-101, but the
    // rod turns at about 1e-400 rad/s², which no f64 holds, and its end accelerates as fast
    // as the slider: 0 is no answer for it (it was returned, with a stated accuracy of
    // 6e-14), and every entry says `Inaccurate`, its estimate the float's floor.
    fn refused<T: Real>(size: T, omega: T, alpha: T) -> bool {
        let linkage =
            SliderCrank::new(T::constant(0.3) * size, size, T::constant(0.1) * size).unwrap();
        let theta2 = T::constant(0.7);
        let q = linkage.assemble(theta2, Branch::Open).unwrap();
        let inaccurate = |e: &Error<T>| {
            matches!(
                e,
                Error::Inaccurate {
                    order: mechgen::Order::Acceleration,
                    ..
                }
            )
        };
        let velocity = linkage.velocity(theta2, &q, omega).unwrap();
        [
            linkage.motion(theta2, Branch::Open, omega, alpha).err(),
            linkage.motion_at(theta2, &q, omega, alpha).err(),
            linkage
                .motion_near(theta2, &q, &NewtonOptions::default(), omega, alpha)
                .err(),
            linkage
                .acceleration(theta2, &q, omega, &velocity, alpha)
                .err(),
        ]
        .iter()
        .all(|e| e.as_ref().is_some_and(inaccurate))
    }
    assert!(refused(1e300f64, 1e-200, 0.0));
    assert!(refused(1e300f64, 1e-200, 3e-399));
    assert!(refused(1e50f64, 1e-170, 0.0));
    assert!(refused(1e30f32, 1e-25, 0.0));
    // The angle's acceleration, about ω², beyond f64's range: an error, not an infinity.
    assert!(check(1e-300f64, 1e200, 0.0).is_none());
    // Ordinary rates on an ordinary mechanism: as before.
    check(1.0f64, 3.0, 2.0).unwrap();
    check(1e-3f32, 5.0, -1e4).unwrap();
}

/// The general rate functions compute on the mechanism scaled to size 1 too, with time in a
/// power of two, wherever lengths or rates are far from 1: a four-bar of 1e300 turning at
/// 1e5 rad/s has angular accelerations of about 1e10 rad/s², which `acceleration` and
/// `motion_at` refused as not finite (a length times a squared rate, 1e310, overflowed on
/// the way). Its angles' rates and accelerations are the unit four-bar's, bit for bit
/// (scaling by a power of two changes nothing).
#[test]
fn rates_of_a_huge_mechanism_turning_fast_are_its_unit_copys() {
    let unit = FourBar::new(1.8f64, 0.8, 2.0, 1.5).unwrap();
    let factor = 2f64.powi(996);
    let huge = FourBar::new(1.8 * factor, 0.8 * factor, 2.0 * factor, 1.5 * factor).unwrap();
    let (theta2, omega, alpha) = (1.0, 1e5, -3e9);
    let q = unit.assemble(theta2, Branch::Open).unwrap();
    let v = unit.velocity(theta2, &q, omega).unwrap();
    let a = unit.acceleration(theta2, &q, omega, &v, alpha).unwrap();
    assert!(a.to_array().iter().all(|x| x.abs() > 1e8 && x.is_finite()));
    assert_eq!(huge.assemble(theta2, Branch::Open).unwrap(), q);
    assert_eq!(huge.velocity(theta2, &q, omega).unwrap(), v);
    assert_eq!(huge.acceleration(theta2, &q, omega, &v, alpha).unwrap(), a);
    let at = huge.motion_at(theta2, &q, omega, alpha).unwrap();
    assert_eq!((at.velocity, at.acceleration), (v, a));
    // `motion`, by its closed forms, to rounding.
    let motion = huge.motion(theta2, Branch::Open, omega, alpha).unwrap();
    let pairs = [(motion.velocity, v), (motion.acceleration, a)];
    for (got, want) in pairs {
        for (g, w) in got.to_array().into_iter().zip(want.to_array()) {
            assert!((g - w).abs() <= 1e-13 * w.abs(), "{g} against {w}");
        }
    }
    // And slowly: 1e-200 rad/s, rates of about 1e-200 rad/s, but accelerations of 1e-400
    // rad/s², below the float's range, which no f64 holds (0 was returned, with a stated
    // accuracy of 1e-13): `Inaccurate`, its estimate the float's floor.
    let slow = huge.velocity(theta2, &q, 1e-200).unwrap();
    assert!(slow.to_array().iter().all(|x| x.abs() > 1e-201));
    assert!(matches!(
        huge.motion_at(theta2, &q, 1e-200, 0.0),
        Err(Error::Inaccurate {
            order: mechgen::Order::Acceleration,
            estimate,
            ..
        }) if estimate > 1e70
    ));
}

/// A scene's fast kernel gives up where a squared rate overflows in its scaled units (a
/// slider-crank of 1e-300 turning at 1e200 rad/s), and its checked kernel counts time in a
/// power of two that brings the rate near 1: the slider's acceleration of about 1e100 and
/// its rate, as `motion` gives them; the rod's angular acceleration, about 1e400 rad/s², is
/// beyond the float's range, so the scene that asks for it says so.
#[test]
fn a_scene_of_a_tiny_mechanism_turning_fast_answers_by_its_checked_kernel() {
    let size = 1e-300f64;
    let linkage = SliderCrank::new(0.3 * size, size, 0.1 * size).unwrap();
    let scenes = linkage.scenes().unwrap();
    let (theta2, omega, alpha) = (0.7, 1e200, 0.0);
    let slider = scenes.slider(theta2, Branch::Open, omega, alpha).unwrap();
    let motion = linkage.motion_at(
        theta2,
        &linkage.assemble(theta2, Branch::Open).unwrap(),
        omega,
        alpha,
    );
    // `motion_at` refuses, for the rod's acceleration; the slider's is the unit copy's.
    assert!(motion.is_err());
    let unit = SliderCrank::new(0.3f64, 1.0, 0.1).unwrap();
    let unit_slider = unit
        .scenes()
        .unwrap()
        .slider(theta2, Branch::Open, 1.0, 0.0)
        .unwrap();
    assert!((slider.d_dot / (unit_slider.d_dot * 1e-100) - 1.0).abs() < 1e-14);
    assert!((slider.d_ddot / (unit_slider.d_ddot * 1e100) - 1.0).abs() < 1e-14);
    assert!(slider.d_ddot.abs() > 1e99);
    assert!(matches!(
        scenes.state(theta2, Branch::Open, omega, alpha),
        Err(Error::NonFinite { .. })
    ));
}

/// The float's floor in the accuracy a scaled computation states, only where a result can
/// leave its range (found by review of the first version, which charged an angle's rates
/// with a tiny mechanism's lengths, and missed rates lost before they were solved with):
/// - a four-bar of 1e-300, every unknown an angle, turning at 1e-10 rad/s: its rates and
///   accelerations are normal numbers, the unit four-bar's bit for bit, and `Ok` (it was
///   `Inaccurate`); a slider-crank of 1e-300 at that rate, whose slider accelerates at
///   about 3e-321, a subnormal number, `Inaccurate`;
/// - a crank at 1e-230 rad/s accelerating at 1e200 rad/s², whose rate rounds to 0 in the
///   acceleration's units of time: `Inaccurate` at the velocity (its velocities came back 0,
///   stated to 1e-14; they exist, about 1e-230, but the time unit that would keep them is
///   not the accelerations', a limit the docs of `stated_in_own_units` state), and one at
///   1e-320 rad/s beside 1 rad/s² (then taken as given, its velocities subnormal) too; at
///   1e-200 rad/s beside 1 rad/s², `Ok` and right;
/// - `motion_near` asked for a position more accurate than its estimate is `Ok` at every
///   size alike: the position's accuracy is the caller's to judge (the path that scales
///   refused it).
#[test]
fn the_floats_floor_only_where_results_leave_its_range() {
    let dims = [1.8f64, 0.8, 2.0, 1.5];
    let unit = FourBar::new(dims[0], dims[1], dims[2], dims[3]).unwrap();
    let factor = 2f64.powi(-996);
    let tiny = FourBar::new(
        dims[0] * factor,
        dims[1] * factor,
        dims[2] * factor,
        dims[3] * factor,
    )
    .unwrap();
    let (theta2, omega) = (1.0, 1e-10);
    let want = unit.motion(theta2, Branch::Open, omega, 0.0).unwrap();
    let got = tiny.motion(theta2, Branch::Open, omega, 0.0).unwrap();
    assert_eq!(
        (got.velocity, got.acceleration),
        (want.velocity, want.acceleration)
    );
    assert!(got.accuracy.acceleration < 1e-12, "{:?}", got.accuracy);
    let q = unit.assemble(theta2, Branch::Open).unwrap();
    let v = tiny.velocity(theta2, &q, omega).unwrap();
    assert_eq!(v, unit.velocity(theta2, &q, omega).unwrap());
    assert_eq!(
        tiny.acceleration(theta2, &q, omega, &v, 0.0).unwrap(),
        unit.acceleration(theta2, &q, omega, &v, 0.0).unwrap()
    );

    let s = 1e-300f64;
    let slider = SliderCrank::new(0.3 * s, s, 0.1 * s).unwrap();
    let inaccurate = |r: Result<_, Error<f64>>, order: mechgen::Order| matches!(r, Err(Error::Inaccurate { order: o, .. }) if o == order);
    assert!(inaccurate(
        slider.motion(0.7, Branch::Open, 1e-10, 0.0).map(|_| ()),
        mechgen::Order::Acceleration
    ));
    // Its velocities, about 1e-310, keep some 40 bits: within what is required.
    let sq = slider.assemble(0.7, Branch::Open).unwrap();
    assert!(slider.velocity(0.7, &sq, 1e-10).is_ok());

    assert!(inaccurate(
        unit.motion(theta2, Branch::Open, 1e-230, 1e200).map(|_| ()),
        mechgen::Order::Velocity
    ));
    assert!(inaccurate(
        unit.motion_at(theta2, &q, 1e-230, 1e200).map(|_| ()),
        mechgen::Order::Velocity
    ));
    assert!(inaccurate(
        unit.motion(theta2, Branch::Open, 1e-320, 1.0).map(|_| ()),
        mechgen::Order::Velocity
    ));
    assert!(inaccurate(
        unit.velocity(theta2, &q, 1e-320).map(|_| ()),
        mechgen::Order::Velocity
    ));
    let slow = unit.motion(theta2, Branch::Open, 1e-200, 1.0).unwrap();
    let per_unit = unit.velocity(theta2, &q, 1.0).unwrap();
    for (got, want) in slow
        .velocity
        .to_array()
        .into_iter()
        .zip(per_unit.to_array())
    {
        assert!(
            (got / (want * 1e-200) - 1.0).abs() < 1e-13,
            "{got:e} {want:e}"
        );
    }

    let mut options = NewtonOptions::default();
    options.accuracy.position = 1e-300;
    let guess = FourBarUnknowns {
        theta3: q.theta3 + 1e-3,
        theta4: q.theta4 - 1e-3,
    };
    let as_given = unit
        .motion_near(theta2, &guess, &options, 10.0, 0.0)
        .unwrap();
    let scaled = tiny
        .motion_near(theta2, &guess, &options, 10.0, 0.0)
        .unwrap();
    assert_eq!(as_given.value.position, scaled.value.position);
    assert!(as_given.value.accuracy.position > options.accuracy.position);
}

/// Newton's iterates can be thrown many turns out by a step through a nearly vanishing column
/// (an inverted slider-crank whose slide passes the rocker's pivot). An angle that far out
/// holds only to its float's spacing: solutions 104 and 195 turns out were `Ok` with their
/// angle 2.1 and 2.3 times further off than the accuracy stated (a helper's adversarial review
/// of the prepared Newton, with mpmath). Such an angle is now taken by whole turns and solved
/// on from there: within a turn of zero, and as accurate as stated.
#[test]
fn newton_takes_an_angle_the_iterates_threw_turns_out_back_within_a_turn() {
    use mechanisms::{InvertedSliderCrank, InvertedSliderCrankUnknowns};
    let cases: [([f64; 4], f64, [f64; 2]); 2] = [
        (
            [
                37.44614519110025,
                60.55876192472308,
                0.0,
                -0.732286647229019,
            ],
            -1.9526774029721634,
            [9.644729300640272, -174.42394197413552],
        ),
        (
            [
                0.21710343491033884,
                4.267721272431143,
                -3.248335012819581e-5,
                -0.677156358032005,
            ],
            1.2103985349065578,
            [16.07320220829527, 7.551825209634181],
        ),
    ];
    for ([ground, crank, offset, angle], input, [theta4, b]) in cases {
        let linkage = InvertedSliderCrank::new(ground, crank, offset, angle).unwrap();
        let guess = InvertedSliderCrankUnknowns { theta4, b };
        let options = NewtonOptions::default();
        let near = linkage
            .motion_near(input, &guess, &options, 1.0, 0.0)
            .unwrap();
        let prepared = linkage.newton().unwrap();
        assert_eq!(
            prepared.motion_near(input, &guess, &options, 1.0, 0.0),
            Ok(near),
            "the prepared solve, the same"
        );
        let solved = near.value.position;
        assert!(
            solved.theta4.abs() <= std::f64::consts::PI + 1e-9,
            "{solved:?}"
        );
        // Against the closed form of the assembly it landed on, the angle's error weighted
        // by its column (the slide) over the size, as the accuracy is stated.
        let size = ground + crank + offset.abs();
        let error = BRANCHES
            .iter()
            .filter_map(|&branch| linkage.assemble(input, branch).ok())
            .map(|exact| angle_between(solved.theta4, exact.theta4) * solved.b.abs() / size)
            .fold(f64::INFINITY, f64::min);
        assert!(
            error <= near.value.accuracy.position,
            "{error:e} against {:e}",
            near.value.accuracy.position
        );
    }
    // A four-bar whose iterates ran six turns out, from a guess beyond ±16 rad (which Newton
    // takes within a turn first): its solution within a turn too, as documented.
    let linkage = FourBar::<f64>::new(
        32.94779934284592,
        69.13215141603094,
        25.971376094028468,
        76.1085746648455,
    )
    .unwrap();
    let guess = FourBarUnknowns {
        theta3: -16.982647076941937,
        theta4: 12.031782298190642,
    };
    let solved = linkage
        .position(-1.3194299307946171, &guess, &NewtonOptions::default())
        .unwrap()
        .value;
    assert!(solved.theta3.abs() <= 17.0, "{solved:?}");
}
