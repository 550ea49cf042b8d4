//! Issue 12, "honest at the edges", for the analyses: every `Some`/`Ok` an analysis returns
//! holds finite, right values, and every degenerate linkage or boundary case is handled by a
//! documented rule. Each reproducer from the issue is a test here with the values it must
//! give; a property test runs every analysis over lengths from 1e-300 to 1e300.

use std::cell::Cell;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

use mechanisms::{FourBar, FourBarUnknowns, InvertedSliderCrank, JansenLeg, SliderCrank};
use mechgen::grashof::{self, Class, Grashof, Inversion, Special};
use mechgen::sweep::{Kinematics, Sample, Stop, Sweep};
use mechgen::{AccelerationParts, Branch, Error, MechanicalAdvantage, NewtonOptions, Solved, Vec2};
use proptest::prelude::*;

const BRANCHES: [Branch; 2] = [Branch::Open, Branch::Crossed];

fn four_bar(lengths: [f64; 4]) -> FourBar<f64> {
    let [l1, l2, l3, l4] = lengths;
    FourBar::new(l1, l2, l3, l4).expect("a four-bar that moves")
}

/// `a` and `b` within `ulps` units in the last place of `b`.
#[track_caller]
fn assert_ulps(what: &str, a: f64, b: f64, ulps: f64) {
    let ulp = f64::EPSILON * b.abs().max(f64::MIN_POSITIVE);
    assert!((a - b).abs() <= ulps * ulp, "{what}: {a:e} vs {b:e}");
}

// Reproducer 1: a slider-crank whose rod equals its crank, without offset.

/// The slider pin of `SliderCrank(50, 50, 0)` runs from d = 100 at θ2 = 0 to the crank pivot
/// at θ2 = ±π/2, where the rod stands perpendicular to the slide and the branches meet; on
/// the open branch it stays there for the rest of the turn. It has one dead centre, so no time
/// ratio: both are `None`, where they were `Some(NaN)` and `Some([0, NaN])`.
#[test]
fn a_rod_equal_to_the_crank_has_a_change_point_not_an_inner_dead_centre() {
    let linkage = SliderCrank::new(50.0_f64, 50.0, 0.0).unwrap();
    assert!(linkage.crank_turns_fully());
    assert_eq!(linkage.dead_centres(), None);
    assert_eq!(linkage.time_ratio(), None);
    assert_eq!(linkage.stroke(), Some(100.0));
    // The geometry the rule describes.
    let outer = linkage.assemble(0.0, Branch::Open).unwrap();
    assert_eq!(outer.d, 100.0);
    assert_eq!(linkage.velocity(0.0, &outer, 1.0).unwrap().d.abs(), 0.0);
    let pivot = linkage.assemble(FRAC_PI_2, Branch::Open).unwrap();
    assert!(pivot.d.abs() < 1e-12, "{pivot:?}");
    assert!(matches!(
        linkage.velocity(FRAC_PI_2, &pivot, 1.0),
        Err(Error::Singular { .. })
    ));
    let dwelling = linkage.assemble(2.0, Branch::Open).unwrap();
    assert!(dwelling.d.abs() < 1e-12, "{dwelling:?}");
}

/// The same rule with an offset: `l3 − l2 = |c|` puts the rod perpendicular to the slide at
/// the folded line-up. Just inside it, both dead centres and the time ratio exist again.
#[test]
fn a_rod_that_just_reaches_the_slide_has_no_inner_dead_centre() {
    let linkage = SliderCrank::new(50.0, 70.0, 20.0).unwrap();
    assert!(linkage.crank_turns_fully());
    assert_eq!(linkage.dead_centres(), None);
    assert_eq!(linkage.time_ratio(), None);
    // √(120² − 20²) − √(20² − 20²).
    assert_ulps("stroke", linkage.stroke().unwrap(), 14000f64.sqrt(), 2.0);

    let inside = SliderCrank::new(50.0, 70.0, 19.0).unwrap();
    let [outer, inner] = inside.dead_centres().unwrap();
    assert_ulps("outer", outer, (19.0f64 / 120.0).asin(), 2.0);
    // π + asin(19/20), which `asin` near 1 gives to 8 digits: 20² − 19² = 39 exactly.
    assert_ulps("inner", inner, PI + 19f64.atan2(39f64.sqrt()), 2.0);
    for theta2 in [outer, inner] {
        let q = inside.assemble(theta2, Branch::Open).unwrap();
        assert!(inside.velocity(theta2, &q, 1.0).unwrap().d.abs() < 1e-9);
    }
    let ratio = inside.time_ratio().unwrap();
    assert_ulps(
        "time ratio",
        ratio,
        (inner - outer) / (TAU - (inner - outer)),
        4.0,
    );

    let short = SliderCrank::new(50.0, 70.0, 21.0).unwrap();
    assert!(!short.crank_turns_fully());
    assert_eq!(
        (short.stroke(), short.dead_centres(), short.time_ratio()),
        (None, None, None)
    );
}

// Reproducer 2: a four-bar whose longest link equals the other three together.

/// `FourBar(1, 3, 6, 2)` closes only at θ2 = π, all in line: refused by `new`, naming the
/// longest link, and classified `Flat` (nothing moves) by Grashof's law; longer still, it
/// cannot close. Each link in turn as the longest.
#[test]
fn a_four_bar_that_closes_only_flat_is_refused_and_named() {
    let names = ["ground", "crank", "coupler", "rocker"];
    for rotation in 0..4 {
        let rotate = |lengths: [f64; 4]| {
            let mut rotated = lengths;
            rotated.rotate_left(rotation);
            rotated
        };
        let longest = (2 + 4 - rotation) % 4;
        for (lengths, class) in [
            ([1.0, 3.0, 6.0, 2.0], Class::Flat),
            ([1.0, 3.0, 7.0, 2.0], Class::CannotClose),
        ] {
            let [l1, l2, l3, l4] = rotate(lengths);
            let error = FourBar::new(l1, l2, l3, l4).unwrap_err();
            assert_eq!((error.name, error.value), (names[longest], lengths[2]));
            let g = grashof::classify(l1, l2, l3, l4);
            assert_eq!((g.class, g.inversion), (class, Inversion::Immobile));
            assert!(!g.input_turns_fully() && !g.output_turns_fully());
        }
    }
    // Flat within the tolerance, as change points are.
    assert_eq!(grashof::classify(0.1, 0.2, 0.6, 0.3).class, Class::Flat);
    assert!(FourBar::new(0.1, 0.2, 0.6, 0.3).is_err());
}

/// Just short of flat, the linkage moves over a sliver of crank angles near π: no full turn,
/// and `reaches` says where.
#[test]
fn a_nearly_flat_four_bar_reaches_only_its_sliver() {
    let linkage = four_bar([1.0, 3.0, 6.0 - 1e-6, 2.0]);
    let g = linkage.grashof();
    assert_eq!(
        (g.class, g.inversion),
        (Class::NonGrashof, Inversion::TripleRocker)
    );
    let limits = linkage.limit_angles();
    assert!(!limits.full_turn());
    assert_eq!(limits.extended, None);
    let folded = limits.folded.unwrap();
    // Z = |A − O4| = 4 − 1e-6 at the toggle: cos θ2 = (1 + 9 − Z²)/6.
    let z = 4.0 - 1e-6;
    let expected = PI - 2.0 * ((16.0 - z * z) / 12.0f64).sqrt().asin();
    assert!((folded - expected).abs() < 1e-12, "{folded} {expected}");
    assert!(PI - folded < 2e-3);
    assert!(limits.reaches(PI) && limits.reaches(-PI) && limits.reaches(folded + 1e-9));
    assert!(!limits.reaches(folded - 1e-6) && !limits.reaches(0.0) && !limits.reaches(3.0));
    for theta2 in [PI, folded + 1e-9] {
        for branch in BRANCHES {
            assert!(linkage.assemble(theta2, branch).is_ok());
        }
    }
    assert!(linkage.assemble(folded - 1e-6, Branch::Open).is_err());
}

// Reproducer 3: `reaches` at large input angles.

/// |θ| reduced to [0, π] with π exactly (mpmath, 400 digits), for inputs where reducing by
/// the rounded 2π (`θ % τ`) is off by up to 1.5 rad.
const LARGE_F64: [(f64, f64); 7] = [
    (1e15, 2.109_698_117_070_112_6),
    (1e15 + 0.5, 2.609_698_117_070_112_6),
    (-1e15, 2.109_698_117_070_112_6),
    (1_152_921_504_606_846_976.0, 2.161_319_993_139_727), // 2^60
    (1e22, 1.020_177_392_559_087),
    (1e300, 2.183_872_484_152_232_6),
    (f64::MAX, 3.136_630_678_439_006),
];

/// The same for f32 inputs (the reduced values in f64).
const LARGE_F32: [(f32, f64); 5] = [
    (1e6, 0.357_564_167_085_735),
    (1e10, 0.509_231_072_165_734_8),
    (3e30, 1.845_269_842_624_042),
    (1.267_650_6e30, 1.059_648_531_680_157_4), // 2^100
    (f32::MAX, 0.549_049_329_957_454_3),
];

/// A rocker-crank with l1 = l2 = 1, whose crank rocks over `|θ2| ∈ [folded, extended]`
/// (`Z = 2 sin(θ2/2)` meets `l3 + l4` and `l3 − l4`).
fn rocking_between(extended: f64) -> FourBar<f64> {
    let reach = 2.0 * (extended / 2.0).sin();
    four_bar([1.0, 1.0, 0.6 * reach, 0.4 * reach])
}

#[test]
fn reaches_reduces_large_angles_by_pi_itself() {
    // The extended limit lies between the true and the naive reductions of 1e15, 2^60 and
    // 1e300, so a naive reduction answers those wrongly.
    let linkage = rocking_between(2.13);
    let limits = linkage.limit_angles();
    let (folded, extended) = (limits.folded.unwrap(), limits.extended.unwrap());
    assert!((extended - 2.13).abs() < 1e-12 && folded < 0.36);
    let inside = |magnitude: f64| folded <= magnitude && magnitude <= extended;
    for (theta2, magnitude) in LARGE_F64 {
        assert_eq!(limits.reaches(theta2), inside(magnitude), "{theta2:e}");
        assert_eq!(
            limits.reaches(theta2),
            limits.reaches(magnitude),
            "{theta2:e}"
        );
    }
    assert_eq!(
        LARGE_F64.map(|(theta2, _)| limits.reaches(theta2)),
        [true, false, true, false, true, false, false]
    );
    assert!(!limits.reaches(f64::NAN) && !limits.reaches(f64::INFINITY));
    // A full turn reaches every finite angle, and no other.
    let full = four_bar([180.0, 80.0, 200.0, 150.0]).limit_angles();
    assert!(full.reaches(1e300) && !full.reaches(f64::NEG_INFINITY));
}

#[test]
fn reaches_reduces_large_f32_angles_by_pi_itself() {
    let reach = 2.0 * (2.13f32 / 2.0).sin();
    let linkage = FourBar::new(1.0f32, 1.0, 0.6 * reach, 0.4 * reach).unwrap();
    let limits = linkage.limit_angles();
    let (folded, extended) = (limits.folded.unwrap(), limits.extended.unwrap());
    for (theta2, magnitude) in LARGE_F32 {
        let inside = f64::from(folded) <= magnitude && magnitude <= f64::from(extended);
        assert_eq!(limits.reaches(theta2), inside, "{theta2:e}");
    }
    // 1e10 reduces to 0.509 rad; by the rounded τ it would be 2.32, past the limit.
    assert!(limits.reaches(1e10f32));
    assert!(!limits.reaches(f32::NAN));
}

// Reproducer 4: kites and parallelograms.

/// A kite with crank = coupler and ground = rocker folds B onto O2 at θ2 = π, all links in
/// line: there it meets its degenerate branch (B held at O2 while the crank turns). That is a
/// change point, not a dead centre, so a change-point crank-rocker has no dead centres; a
/// sweep reports the fold as a branch change.
#[test]
fn a_kites_fold_is_a_change_point_not_a_dead_centre() {
    let kite = four_bar([100.0, 50.0, 50.0, 100.0]);
    let g = kite.grashof();
    assert_eq!(
        (g.class, g.inversion, g.special),
        (
            Class::ChangePoint,
            Inversion::CrankRocker,
            Some(Special::Kite)
        )
    );
    for branch in BRANCHES {
        assert_eq!(kite.dead_centres(branch), None);
    }
    // At θ2 = π, B sits on O2 on both branches and the Jacobian is singular.
    for branch in BRANCHES {
        let q = kite.assemble(PI, branch).unwrap();
        let b = (100.0 + 100.0 * q.theta4.cos(), 100.0 * q.theta4.sin());
        assert!(b.0.hypot(b.1) < 1e-6, "{b:?}");
        assert!(kite.velocity(PI, &q, 1.0).is_err());
    }
    assert!(kite.limit_angles().full_turn());
    let start = kite.assemble(0.3, Branch::Open).unwrap().to_array();
    let stop = Sweep::new(&kite, 0.3, start, 0.01, 1000, NewtonOptions::default())
        .find_map(Result::err)
        .unwrap();
    match stop {
        Stop::BranchChange {
            last_input,
            next_input,
        } => assert!(last_input < PI && PI < next_input, "{stop:?}"),
        Stop::Toggle { .. } => panic!("{stop:?}"),
    }
    // The other change-point crank-rocker, 2 + 5 = 3 + 4: its folded line-up is the flat
    // position at θ2 = 0.
    let change_point = four_bar([3.0, 2.0, 4.0, 5.0]);
    assert_eq!(change_point.dead_centres(Branch::Open), None);
    // Off the change point, a class I crank-rocker has its dead centres, where ω4 = 0.
    let near = four_bar([100.0, 50.0, 50.5, 100.0]);
    assert_eq!(near.grashof().class, Class::Grashof);
    for branch in BRANCHES {
        for centre in near.dead_centres(branch).unwrap() {
            let q = near.assemble(centre.theta2, branch).unwrap();
            assert!((q.theta4 - centre.theta4).abs() < 1e-9);
            let omega4 = near.velocity(centre.theta2, &q, 1.0).unwrap().theta4;
            assert!(omega4.abs() < 1e-9, "{omega4}");
        }
    }
}

/// Kites and parallelograms pass their flat positions (θ2 = 0 or π, where the links line up)
/// without a limit: those are change points. The kite whose ground equals its crank has one
/// real limit, where coupler and rocker line up extended at θ2 = ±π/3.
#[test]
fn kites_and_parallelograms_pass_their_flat_positions() {
    for lengths in [
        [100.0, 50.0, 50.0, 100.0],
        [50.0, 50.0, 100.0, 100.0],
        [100.0, 50.0, 100.0, 50.0],
        [70.0, 70.0, 70.0, 70.0],
    ] {
        let limits = four_bar(lengths).limit_angles();
        assert!(limits.full_turn(), "{lengths:?}");
        assert!(limits.reaches(0.0) && limits.reaches(PI), "{lengths:?}");
    }
    let rocking = four_bar([100.0, 100.0, 50.0, 50.0]);
    let limits = rocking.limit_angles();
    assert_eq!(limits.folded, None);
    assert_ulps("limit", limits.extended.unwrap(), PI / 3.0, 2.0);
    assert!(limits.reaches(0.0) && !limits.reaches(PI));
    assert_eq!(rocking.dead_centres(Branch::Open), None);
    let parallelogram = four_bar([100.0, 50.0, 100.0, 50.0]);
    assert_eq!(parallelogram.dead_centres(Branch::Open), None);
}

// Reproducer 5: transmission angle extremes.

/// At a limit angle coupler and rocker are in line: γ is 0 or π exactly (it was off by 4e-7
/// through `acos` of a cosine rounded near ±1).
#[test]
fn transmission_extremes_at_toggles_are_exactly_flat() {
    let rocker_crank = four_bar([180.0, 150.0, 200.0, 80.0]);
    let limits = rocker_crank.limit_angles();
    let extremes = rocker_crank.transmission_extremes();
    assert_eq!((extremes.min, extremes.max), (0.0, PI));
    assert_eq!(
        (Some(extremes.min_at), Some(extremes.max_at)),
        (limits.folded, limits.extended)
    );
    // At θ2 = 0 of (7, 2, 4, 3), Z = 5 makes a 3-4-5 triangle: γ is a right angle.
    let right = four_bar([7.0, 2.0, 4.0, 3.0]).transmission_extremes();
    assert_eq!((right.min_at, right.max), (0.0, PI));
    assert_ulps("γ at θ2 = 0", right.min, FRAC_PI_2, 1.0);
}

/// A needle of a triangle at θ2 = 0: ground, coupler and rocker 1, crank 1 − 3e-7, so
/// Z = 3e-7 and γ = 2·asin(Z/2). The cosine rule through `acos` was off by 1.2e-10 here.
#[test]
fn transmission_extremes_are_accurate_for_needle_triangles() {
    let crank = 0.999_999_7;
    let extremes = four_bar([1.0, crank, 1.0, 1.0]).transmission_extremes();
    let z = 1.0 - crank;
    assert_ulps("min", extremes.min, 2.0 * (z / 2.0).asin(), 2.0);
    // 2·asin((1 + crank)/2), from mpmath.
    assert_ulps("max", extremes.max, 3.140_497_208_461_175_3, 2.0);
    assert_eq!((extremes.min_at, extremes.max_at), (0.0, PI));
}

// Reproducer 6: acceleration parts.

#[test]
fn acceleration_parts_that_overflow_are_an_error() {
    let big = Vec2::new(f64::MAX, -f64::MAX);
    let overflowing = AccelerationParts {
        tangential: big,
        normal: big,
        sliding: Vec2::new(1.0, 1.0),
        coriolis: Vec2::default(),
    };
    assert_eq!(
        overflowing.total(),
        Err(Error::NonFinite {
            quantity: "point acceleration"
        })
    );
    // An intermediate overflow whose total fits is summed at half scale.
    let cancelling = AccelerationParts {
        sliding: Vec2::new(-f64::MAX, f64::MAX),
        ..overflowing
    };
    assert_eq!(cancelling.total(), Ok(Vec2::new(f64::MAX, -f64::MAX)));
    let nan = AccelerationParts {
        coriolis: Vec2::new(0.0, f64::NAN),
        ..AccelerationParts::default()
    };
    assert_eq!(
        nan.total(),
        Err(Error::NonFinite {
            quantity: "point acceleration part"
        })
    );
    let small = AccelerationParts {
        tangential: Vec2::new(1.0, 2.0),
        normal: Vec2::new(-0.5, 0.25),
        sliding: Vec2::new(0.125, 0.0),
        coriolis: Vec2::new(0.0, -4.0),
    };
    assert_eq!(small.total(), Ok(Vec2::new(0.625, -1.75)));
    assert_eq!(
        AccelerationParts {
            tangential: Vec2::new(f32::MAX, 0.0),
            normal: Vec2::new(f32::MAX, 0.0),
            ..AccelerationParts::default()
        }
        .total(),
        Err(Error::NonFinite {
            quantity: "point acceleration"
        })
    );
}

// Reproducers 7 and 8: sweeps.

/// The triple-rocker the issue names: its crank reaches |θ2| ≤ 1.759.
fn triple_rocker() -> FourBar<f64> {
    four_bar([100.0, 120.0, 90.0, 80.0])
}

/// The stop of a sweep, and the inputs of its samples.
fn sweep_to_stop<M: Kinematics<f64, 2>>(
    linkage: &M,
    start: f64,
    position: [f64; 2],
    step: f64,
    steps: u32,
) -> (Vec<f64>, Option<Stop<f64>>) {
    let mut inputs = Vec::new();
    let mut stop = None;
    for item in Sweep::new(
        linkage,
        start,
        position,
        step,
        steps,
        NewtonOptions::default(),
    ) {
        match item {
            Ok(Sample { input, .. }) => inputs.push(input),
            Err(event) => {
                assert!(stop.is_none(), "one stop, last");
                stop = Some(event);
            }
        }
    }
    (inputs, stop)
}

/// From θ2 = 1 in 5 rad steps, the next input (6 ≡ −0.28 rad) is reachable, but only across
/// the gap (1.759, 2π − 1.759) where the loop cannot close: the sweep stops at the toggle.
#[test]
fn a_sweep_never_steps_over_a_gap_in_the_motion() {
    let linkage = triple_rocker();
    let limit = linkage.limit_angles().extended.unwrap();
    assert_ulps("limit", limit, 1.759_412_712_970_300_8, 4.0);
    for branch in BRANCHES {
        let start = linkage.assemble(1.0, branch).unwrap().to_array();
        let (inputs, stop) = sweep_to_stop(&linkage, 1.0, start, 5.0, 10);
        assert_eq!(inputs, [1.0]);
        match stop.unwrap() {
            Stop::Toggle {
                last_input,
                next_input,
                error,
            } => {
                assert_eq!((last_input, next_input), (1.0, 6.0));
                // The nearest failure beyond: just past the toggle.
                let Error::CannotAssemble { input } = error else {
                    panic!("{error:?}")
                };
                assert!(input > limit && input - limit < 1e-6, "{input}");
            }
            stop @ Stop::BranchChange { .. } => panic!("{stop:?}"),
        }
    }
    // Every step length and start: no sample beyond the toggle on either side, and a toggle.
    for branch in BRANCHES {
        for start in [-1.7, -1.0, 0.0, 0.5, 1.0, 1.75] {
            let position = linkage.assemble(start, branch).unwrap().to_array();
            for step in [
                0.05,
                0.3,
                0.7,
                1.1,
                2.5,
                3.3,
                4.4,
                6.0,
                TAU - 0.1,
                TAU + 0.3,
            ] {
                for step in [step, -step] {
                    let (inputs, stop) = sweep_to_stop(&linkage, start, position, step, 400);
                    assert!(
                        inputs.iter().all(|theta2| theta2.abs() <= limit),
                        "{branch:?} from {start} by {step}: {inputs:?}"
                    );
                    assert!(
                        matches!(stop, Some(Stop::Toggle { .. })),
                        "{branch:?} from {start} by {step}: {stop:?}"
                    );
                }
            }
        }
    }
}

/// A gap near a change point, where the motion on either side lines up as if it went through:
/// `[0.01, 1, 0.3, 1.29…]` cannot close for |θ2| < 0.0100000429 (its folded limit), yet from
/// −0.93 one radian on (0.07, beyond the gap, on the same branch) the trapezoidal rule agreed
/// with the velocities to 6%, and the sweep stepped over the gap (an adversarial review; in
/// f32 too, over a gap of 3.2e-3 rad about π). A piece is now no longer than the reaches of
/// its ends (where the Jacobian certainly stays regular), so it stops at the toggle.
#[test]
fn a_sweep_never_steps_over_a_gap_near_a_change_point() {
    let linkage = four_bar([0.01, 1.0, 0.3, 1.290000505050505]);
    let limit = linkage.limit_angles().folded.unwrap();
    for (start, step) in [(-0.93, 1.0), (-0.5, 1.0), (0.45, -0.9), (-0.93, 0.25)] {
        let position = linkage.assemble(start, Branch::Open).unwrap().to_array();
        let (inputs, stop) = sweep_to_stop(&linkage, start, position, step, 8);
        // Every sample on the start's side of the gap, and a toggle at its edge.
        assert!(
            inputs
                .iter()
                .all(|theta2| theta2.abs() >= limit && theta2.signum() == start.signum()),
            "from {start} by {step}: {inputs:?}"
        );
        let Some(Stop::Toggle {
            error: Error::CannotAssemble { input },
            ..
        }) = stop
        else {
            panic!("from {start} by {step}: {stop:?}")
        };
        assert!(input.abs() < limit && limit - input.abs() < 1e-6, "{input}");
    }
    // The review's f32 case: a gap about π, (3.1400, 3.1432), between the extended limits,
    // narrower than f32's √ε near a change point, which may be taken for one (the type's
    // docs), but is not stepped over.
    let [l1, l2, l3, l4] = [
        1.533_162_2e-10_f32,
        9.256_406e-9,
        4.613_349_7e-9,
        4.796_372_6e-9,
    ];
    let linkage = FourBar::new(l1, l2, l3, l4).unwrap();
    let limit = linkage.limit_angles().extended.unwrap();
    let (start, step) = (2.151_496_3_f32, 4.277_052_f32);
    let position = linkage.assemble(start, Branch::Open).unwrap().to_array();
    let samples: Vec<_> =
        Sweep::new(&linkage, start, position, step, 4, NewtonOptions::default()).collect();
    let last = samples.last().unwrap();
    assert!(last.is_err(), "{samples:?}");
    for sample in samples.iter().flatten() {
        assert!(sample.input.abs() <= limit, "{samples:?}");
    }
}

/// A triple-rocker's crank meeting its limit stops with `Toggle`; a parallelogram passing
/// its flat position, where the antiparallelogram branch meets it, with `BranchChange`.
#[test]
fn toggles_and_branch_changes_are_told_apart() {
    let linkage = triple_rocker();
    let limit = linkage.limit_angles().extended.unwrap();
    let step = 0.1f64.to_radians();
    for branch in BRANCHES {
        let start = linkage.assemble(0.0, branch).unwrap().to_array();
        let (inputs, stop) = sweep_to_stop(&linkage, 0.0, start, step, 3600);
        let Some(Stop::Toggle {
            last_input,
            next_input,
            error: Error::CannotAssemble { .. },
        }) = stop
        else {
            panic!("{stop:?}")
        };
        assert_eq!(Some(&last_input), inputs.last());
        assert!(last_input <= limit && limit < next_input);
    }
    let parallelogram = four_bar([100.0, 50.0, 100.0, 50.0]);
    for branch in BRANCHES {
        for step in [0.1f64.to_radians(), 0.01, 0.37, 1.0] {
            let start = parallelogram.assemble(0.3, branch).unwrap().to_array();
            let (inputs, stop) = sweep_to_stop(&parallelogram, 0.3, start, step, 3600);
            let Some(Stop::BranchChange {
                last_input,
                next_input,
            }) = stop
            else {
                panic!("{branch:?} by {step}: {stop:?}")
            };
            assert_eq!(Some(&last_input), inputs.last());
            assert!(
                last_input < PI && PI < next_input,
                "{last_input} {next_input}"
            );
        }
    }
}

/// Linkages whose crank cannot turn fully, gaps from 2.8 rad down to 0.004 rad wide (the
/// last three near a change point), swept from starts across their range in steps from
/// 0.01 to 5 rad either way: no sample outside the range the start is in, and always a
/// `Toggle` at its end.
#[test]
fn sweeps_stop_at_every_toggle_and_never_cross_a_gap() {
    for lengths in [
        [100.0, 120.0, 90.0, 80.0],
        [180.0, 150.0, 200.0, 80.0],
        [3.0, 5.0, 4.0, 2.05],
        [3.0, 2.0, 4.0, 5.05],
        [3.0, 2.0, 4.0, 5.001],
        [3.0, 2.0, 4.0, 5.00001],
    ] {
        let linkage = four_bar(lengths);
        let limits = linkage.limit_angles();
        let (folded, extended) = (limits.folded.unwrap_or(0.0), limits.extended.unwrap_or(PI));
        for fraction in [0.1, 0.5, 0.9] {
            for side in [1.0, -1.0] {
                let start = side * (folded + (extended - folded) * fraction);
                // The range of inputs the start is in, unwrapped.
                let (low, high) = match (limits.folded, limits.extended) {
                    (None, _) => (-extended, extended),
                    (Some(_), None) if side > 0.0 => (folded, TAU - folded),
                    (Some(_), None) => (folded - TAU, -folded),
                    (Some(_), Some(_)) if side > 0.0 => (folded, extended),
                    (Some(_), Some(_)) => (-extended, -folded),
                };
                for branch in BRANCHES {
                    let position = linkage.assemble(start, branch).unwrap().to_array();
                    for step in [0.01, 0.1, 0.3, 0.77, 1.0, 1.3, 3.0, 5.0] {
                        for step in [step, -step] {
                            let (inputs, stop) =
                                sweep_to_stop(&linkage, start, position, step, 2000);
                            let case = format!("{lengths:?} {branch:?} from {start} by {step}");
                            assert!(
                                inputs.iter().all(|t| (low..=high).contains(t)),
                                "{case}: {inputs:?} leaves [{low}, {high}]"
                            );
                            assert!(
                                matches!(stop, Some(Stop::Toggle { .. })),
                                "{case}: {stop:?}"
                            );
                        }
                    }
                }
            }
        }
    }
}

/// Change points (parallelograms, kites, and the other class III linkages) swept into their
/// flat positions from several starts, in steps from 0.001 to 5 rad either way (some landing
/// exactly on the flat position): always a `BranchChange`, except where a kite or
/// change-point rocker-crank meets a real toggle first.
#[test]
fn sweeps_report_every_change_point_as_a_branch_change() {
    for lengths in [
        [100.0, 50.0, 100.0, 50.0],
        [50.0, 100.0, 50.0, 100.0],
        [70.0, 70.0, 70.0, 70.0],
        [100.0, 50.0, 50.0, 100.0],
        [50.0, 50.0, 100.0, 100.0],
        [3.0, 2.0, 4.0, 5.0],
        [2.0, 3.0, 5.0, 4.0],
        [100.0, 100.0, 50.0, 50.0],
        [3.0, 5.0, 4.0, 2.0],
    ] {
        let linkage = four_bar(lengths);
        let toggles = !linkage.limit_angles().full_turn();
        for start in [0.3, 1.0, 2.9, -1.0, -2.5] {
            for branch in BRANCHES {
                let Ok(position) = linkage.assemble(start, branch) else {
                    continue;
                };
                for step in [0.001, 0.01, 0.1, 0.5, 1.0, 2.0, 5.0] {
                    for step in [step, -step] {
                        let (inputs, stop) =
                            sweep_to_stop(&linkage, start, position.to_array(), step, 20_000);
                        let case = format!("{lengths:?} {branch:?} from {start} by {step}");
                        match stop {
                            Some(Stop::BranchChange { last_input, .. }) => {
                                assert_eq!(inputs.last(), Some(&last_input), "{case}");
                            }
                            Some(Stop::Toggle {
                                error: Error::CannotAssemble { .. },
                                ..
                            }) if toggles => {}
                            _ => panic!("{case}: {stop:?}"),
                        }
                    }
                }
            }
        }
    }
}

/// The same in f32: the triple-rocker toggles, the parallelogram changes branch.
#[test]
fn f32_sweeps_tell_toggles_from_branch_changes() {
    let triple = FourBar::new(100.0f32, 120.0, 90.0, 80.0).unwrap();
    let limit = triple.limit_angles().extended.unwrap();
    let parallelogram = FourBar::new(100.0f32, 50.0, 100.0, 50.0).unwrap();
    for branch in BRANCHES {
        for step in [0.001f32, 0.01, 0.1, 1.0, 5.0] {
            let start = triple.assemble(1.0, branch).unwrap().to_array();
            let items: Vec<_> =
                Sweep::new(&triple, 1.0, start, step, 10_000, Default::default()).collect();
            for item in &items[..items.len() - 1] {
                assert!(item.as_ref().unwrap().input <= limit);
            }
            assert!(
                matches!(items.last(), Some(Err(Stop::Toggle { .. }))),
                "{step}: {:?}",
                items.last()
            );
            let start = parallelogram.assemble(0.3, branch).unwrap().to_array();
            let stop = Sweep::new(&parallelogram, 0.3, start, step, 10_000, Default::default())
                .find_map(Result::err);
            assert!(
                matches!(stop, Some(Stop::BranchChange { .. })),
                "{step}: {stop:?}"
            );
        }
    }
}

/// A sweep whose start cannot be solved stops at once, with the start as both inputs.
#[test]
fn a_sweep_whose_start_fails_stops_at_once() {
    let linkage = triple_rocker();
    let mut sweep = Sweep::new(
        &linkage,
        3.0,
        [0.5, 1.5],
        0.01,
        100,
        NewtonOptions::default(),
    );
    let Some(Err(Stop::Toggle {
        last_input,
        next_input,
        error,
    })) = sweep.next()
    else {
        panic!("the start cannot be solved")
    };
    assert_eq!((last_input, next_input), (3.0, 3.0));
    assert!(
        matches!(
            error,
            Error::CannotAssemble { .. } | Error::NoConvergence { .. } | Error::Singular { .. }
        ),
        "{error:?}"
    );
    assert!(sweep.next().is_none());
}

/// `steps = u32::MAX` neither overflows nor loops: the sweep says how long it can be, and
/// ends (here at the triple-rocker's toggle).
#[test]
fn the_longest_sweep_ends() {
    let linkage = triple_rocker();
    let start = linkage.assemble(0.0, Branch::Open).unwrap().to_array();
    let sweep = Sweep::new(
        &linkage,
        0.0,
        start,
        0.01,
        u32::MAX,
        NewtonOptions::default(),
    );
    assert_eq!(sweep.size_hint(), (0, Some(1 << 32)));
    let (inputs, stop) = sweep_to_stop(&linkage, 0.0, start, 0.01, u32::MAX);
    assert_eq!(inputs.len(), 176);
    assert!(matches!(stop, Some(Stop::Toggle { .. })));
    // A step that is not finite stops at once; a huge one is walked in 2^16 pieces at most
    // (not 1e12 of them).
    let (inputs, stop) = sweep_to_stop(&linkage, 0.0, start, f64::INFINITY, u32::MAX);
    assert_eq!(inputs, [0.0]);
    assert_eq!(
        stop,
        Some(Stop::Toggle {
            last_input: 0.0,
            next_input: f64::INFINITY,
            error: Error::NonFinite {
                quantity: "sweep input"
            }
        })
    );
    let crank_rocker = four_bar([180.0, 80.0, 200.0, 150.0]);
    let start = crank_rocker.assemble(0.0, Branch::Open).unwrap().to_array();
    // (Pieces of 1.5e7 rad: the predictor places no guess, Newton lands on either branch or
    // on none, and the walk ends after its refused pieces rather than halving and doubling
    // for ever.)
    let (inputs, stop) = sweep_to_stop(&crank_rocker, 0.0, start, 1e12, 2);
    assert_eq!(inputs[0], 0.0);
    assert!(inputs.len() == 3 || stop.is_some());
}

/// Counts the solves and velocities a sweep asks of a mechanism.
struct Counting<'a> {
    linkage: &'a FourBar<f64>,
    solves: Cell<u32>,
    slopes: Cell<u32>,
}

impl Kinematics<f64, 2> for Counting<'_> {
    fn solve_near(
        &self,
        input: f64,
        guess: [f64; 2],
        options: &NewtonOptions<f64>,
    ) -> Result<Solved<[f64; 2], f64>, Error<f64>> {
        self.solves.set(self.solves.get() + 1);
        self.linkage.solve_near(input, guess, options)
    }

    fn slope(&self, input: f64, position: [f64; 2]) -> Result<[f64; 2], Error<f64>> {
        self.slopes.set(self.slopes.get() + 1);
        self.linkage.slope(input, position)
    }

    fn same_branch(&self, input_a: f64, a: [f64; 2], input_b: f64, b: [f64; 2]) -> bool {
        self.linkage.same_branch(input_a, a, input_b, b)
    }
}

/// Where the motion is smooth at the step's scale, each step costs one solve and one
/// velocity, as a plain predictor-corrector; a step too long for the motion is walked in
/// pieces and still lands on the requested inputs.
#[test]
fn smooth_sweeps_cost_one_solve_per_step() {
    let crank_rocker = four_bar([180.0, 80.0, 200.0, 150.0]);
    let counting = Counting {
        linkage: &crank_rocker,
        solves: Cell::new(0),
        slopes: Cell::new(0),
    };
    let start = crank_rocker.assemble(0.0, Branch::Open).unwrap().to_array();
    let step = TAU / 3600.0;
    let (inputs, stop) = sweep_to_stop(&counting, 0.0, start, step, 3600);
    assert_eq!((inputs.len(), stop), (3601, None));
    assert_eq!((counting.solves.get(), counting.slopes.get()), (3601, 3601));

    // Three steps of 2.5 rad: pieces in between, samples on the grid and on the branch.
    let (inputs, stop) = sweep_to_stop(&crank_rocker, 0.0, start, 2.5, 3);
    assert_eq!((inputs, stop), (vec![0.0, 2.5, 5.0, 7.5], None));
    let samples: Vec<_> = Sweep::new(&crank_rocker, 0.0, start, 2.5, 3, Default::default())
        .map(Result::unwrap)
        .collect();
    for sample in samples {
        let closed = crank_rocker.assemble(sample.input, Branch::Open).unwrap();
        let q = FourBarUnknowns::from_array(sample.position);
        let wrapped = |a: f64| (a + PI).rem_euclid(TAU) - PI;
        assert!(wrapped(q.theta4 - closed.theta4).abs() < 1e-9);
    }
}

// Other analyses at the edges.

/// A mechanical advantage from rates that say nothing is an error, not a value.
#[test]
fn mechanical_advantage_of_undefined_rates_is_an_error() {
    assert_eq!(
        MechanicalAdvantage::from_rates(0.0, 0.0),
        Err(Error::NonFinite {
            quantity: "mechanical advantage"
        })
    );
    assert_eq!(
        MechanicalAdvantage::from_rates(f64::NAN, 1.0),
        Err(Error::NonFinite {
            quantity: "input rate"
        })
    );
    assert_eq!(
        MechanicalAdvantage::from_rates(1.0, f64::INFINITY),
        Err(Error::NonFinite {
            quantity: "output rate"
        })
    );
    assert_eq!(
        MechanicalAdvantage::from_rates(1e-300, 1e300),
        Ok(MechanicalAdvantage::Finite(0.0))
    );
    assert_eq!(
        MechanicalAdvantage::from_rates(1e300, 1e-300),
        Ok(MechanicalAdvantage::Unbounded)
    );
}

/// The same linkage at 2^±900: a triple-rocker at 1e270 reported a full turn (its squares
/// overflowed); now every analysis is the unscaled one, bit for bit.
#[test]
fn analyses_are_the_same_at_every_scale() {
    let scales = [2f64.powi(900), 2f64.powi(-900), 2f64.powi(-1000)];
    for lengths in [
        [100.0, 120.0, 90.0, 80.0],
        [180.0, 80.0, 200.0, 150.0],
        [180.0, 150.0, 200.0, 80.0],
        [100.0, 50.0, 50.0, 100.0],
    ] {
        let unit = four_bar(lengths);
        for scale in scales {
            let scaled = four_bar(lengths.map(|l| l * scale));
            assert_eq!(scaled.grashof(), unit.grashof());
            assert_eq!(scaled.limit_angles(), unit.limit_angles(), "{lengths:?}");
            assert_eq!(scaled.transmission_extremes(), unit.transmission_extremes());
            for branch in BRANCHES {
                assert_eq!(scaled.dead_centres(branch), unit.dead_centres(branch));
            }
        }
    }
    let triple = four_bar([100.0, 120.0, 90.0, 80.0].map(|l| l * 1e270));
    assert!(!triple.limit_angles().full_turn());
    assert_eq!(triple.grashof().class, Class::NonGrashof);
    for dimensions in [[50.0, 150.0, 20.0], [50.0, 70.0, 19.0], [50.0, 50.0, 0.0]] {
        let [l2, l3, c] = dimensions;
        let unit = SliderCrank::new(l2, l3, c).unwrap();
        for scale in scales {
            let scaled = SliderCrank::new(l2 * scale, l3 * scale, c * scale).unwrap();
            assert_eq!(scaled.dead_centres(), unit.dead_centres());
            assert_eq!(scaled.time_ratio(), unit.time_ratio());
            assert_eq!(scaled.stroke(), unit.stroke().map(|s| s * scale));
        }
    }
    // Jansen's triangles close at any scale (their cosines overflowed to NaN at 1e300).
    let holy = [
        38.0, 41.5, 39.3, 40.1, 55.8, 39.4, 36.7, 65.7, 49.0, 50.0, 61.9, 7.8, 15.0,
    ];
    for scale in [1e300, 1e-300] {
        assert!(JansenLeg::new(holy.map(|l| l * scale)).is_ok());
    }
}

/// Grashof's class at the scales that broke it: lengths near the largest float, and equal
/// sums decided the same way however small.
#[test]
fn grashof_at_extreme_scales() {
    let huge = f64::MAX / 2.0;
    let g = grashof::classify(huge, huge * 0.9, huge * 0.8, huge * 0.3);
    assert_eq!(g, grashof::classify(1.0, 0.9, 0.8, 0.3));
    assert_eq!(g.class, Class::Grashof);
    assert_eq!(
        grashof::classify(huge, huge, huge, huge).special,
        Some(Special::Parallelogram)
    );
    let tiny = f64::MIN_POSITIVE;
    assert_eq!(
        grashof::classify(3.0 * tiny, 2.0 * tiny, 4.0 * tiny, 5.0 * tiny).class,
        Class::ChangePoint
    );
    assert_eq!(
        grashof::classify(1e300, 1e-300, 1e300, 1e300).inversion,
        Inversion::CrankRocker
    );
}

// The property: every analysis, at every scale, is finite or says it has nothing.

fn finite_in(value: f64, low: f64, high: f64) -> bool {
    value.is_finite() && (low..=high).contains(&value)
}

/// Every analysis of a four-bar: finite values, in range, or `None`/`Err`.
fn check_four_bar(linkage: &FourBar<f64>, theta2: f64) -> Result<(), TestCaseError> {
    let _: Grashof = linkage.grashof();
    let limits = linkage.limit_angles();
    for limit in [limits.folded, limits.extended].into_iter().flatten() {
        prop_assert!(finite_in(limit, 0.0, PI), "{limits:?}");
    }
    prop_assert_eq!(limits.full_turn(), linkage.grashof().input_turns_fully());
    let extremes = linkage.transmission_extremes();
    for angle in [extremes.min, extremes.min_at, extremes.max, extremes.max_at] {
        prop_assert!(finite_in(angle, 0.0, PI), "{extremes:?}");
    }
    prop_assert!(extremes.min <= extremes.max);
    for branch in BRANCHES {
        for centre in linkage.dead_centres(branch).into_iter().flatten() {
            prop_assert!(centre.theta2.is_finite() && centre.theta4.is_finite());
        }
        // (The closed forms' own overflow, at the largest scales, is not the analyses' to
        // judge: only finite positions are analysed.)
        let assembled = linkage.assemble(theta2, branch).ok();
        if let Some(q) = assembled.filter(|q| q.theta3.is_finite() && q.theta4.is_finite()) {
            prop_assert!(finite_in(linkage.transmission_angle(&q), 0.0, PI));
            if let Ok(MechanicalAdvantage::Finite(ma)) = linkage.mechanical_advantage(theta2, &q) {
                prop_assert!(ma.is_finite());
            }
        }
    }
    Ok(())
}

fn check_slider_crank(linkage: &SliderCrank<f64>) -> Result<(), TestCaseError> {
    if let Some(stroke) = linkage.stroke() {
        prop_assert!(stroke.is_finite() && stroke >= 0.0, "{stroke}");
    }
    if let Some([outer, inner]) = linkage.dead_centres() {
        prop_assert!(finite_in(outer, -FRAC_PI_2, FRAC_PI_2));
        prop_assert!(finite_in(inner, FRAC_PI_2, 1.5 * PI));
    }
    if let Some(ratio) = linkage.time_ratio() {
        prop_assert!(ratio.is_finite() && ratio > 0.0, "{ratio}");
    }
    Ok(())
}

/// `2^k` as an f64, for `|k| ≤ 1000`.
fn power_of_two(k: i32) -> f64 {
    2f64.powi(k)
}

/// Whether `x·2^k` is exact: `x` and the product both normal.
fn scales_exactly(x: f64, k: i32) -> bool {
    let scaled = x * power_of_two(k);
    x.is_normal() && scaled.is_normal() && scaled / power_of_two(k) == x
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn every_analysis_is_finite_or_none_at_every_scale(
        ratios in prop::array::uniform4(-8.0f64..0.0),
        scale in -300.0f64..300.0,
        theta2 in -10.0f64..10.0,
        k in -600i32..600,
    ) {
        let lengths = ratios.map(|r| 10f64.powf(r + scale));
        let [l1, l2, l3, l4] = lengths;
        let g = grashof::classify(l1, l2, l3, l4);
        if lengths.iter().all(|l| scales_exactly(*l, k)) {
            let scaled = lengths.map(|l| l * power_of_two(k));
            prop_assert_eq!(grashof::classify(scaled[0], scaled[1], scaled[2], scaled[3]), g);
        }
        match FourBar::new(l1, l2, l3, l4) {
            Ok(linkage) => {
                prop_assert!(!matches!(g.class, Class::Flat | Class::CannotClose));
                check_four_bar(&linkage, theta2)?;
                if lengths.iter().all(|l| scales_exactly(*l, k)) {
                    let scaled = lengths.map(|l| l * power_of_two(k));
                    let other = FourBar::new(scaled[0], scaled[1], scaled[2], scaled[3]).unwrap();
                    prop_assert_eq!(other.limit_angles(), linkage.limit_angles());
                    prop_assert_eq!(other.transmission_extremes(), linkage.transmission_extremes());
                }
            }
            Err(error) => {
                prop_assert!(matches!(g.class, Class::Flat | Class::CannotClose), "{:?}", error);
            }
        }
        let [crank, rod, offset, _] = lengths;
        let offset = if theta2 < 0.0 { -offset } else { offset };
        if let Ok(slider) = SliderCrank::new(crank, rod, offset) {
            check_slider_crank(&slider)?;
            for branch in BRANCHES {
                let assembled = slider.assemble(theta2, branch).ok();
                if let Some(q) = assembled.filter(|q| q.theta3.is_finite() && q.d.is_finite()) {
                    prop_assert!(finite_in(slider.transmission_angle(&q), 0.0, FRAC_PI_2));
                    if let Ok(MechanicalAdvantage::Finite(ma)) =
                        slider.mechanical_advantage(theta2, &q)
                    {
                        prop_assert!(ma.is_finite());
                    }
                }
            }
        }
        if let Ok(inverted) = InvertedSliderCrank::new(l1, l2, l3, theta2) {
            for branch in BRANCHES {
                if let Ok(q) = inverted.assemble(theta2, branch) {
                    if let Ok(MechanicalAdvantage::Finite(ma)) =
                        inverted.mechanical_advantage(theta2, &q)
                    {
                        prop_assert!(ma.is_finite());
                    }
                }
            }
        }
    }

    #[test]
    fn every_f32_analysis_is_finite_or_none(
        ratios in prop::array::uniform4(-4.0f32..0.0),
        scale in -15.0f32..15.0,
        theta2 in -10.0f32..10.0,
    ) {
        let lengths = ratios.map(|r| 10f32.powf(r + scale));
        let [l1, l2, l3, l4] = lengths;
        let g = grashof::classify(l1, l2, l3, l4);
        let doubled = lengths.map(|l| l * 2.0);
        prop_assert_eq!(grashof::classify(doubled[0], doubled[1], doubled[2], doubled[3]), g);
        if let Ok(linkage) = FourBar::new(l1, l2, l3, l4) {
            let limits = linkage.limit_angles();
            for limit in [limits.folded, limits.extended].into_iter().flatten() {
                prop_assert!(limit.is_finite() && (0.0..=std::f32::consts::PI).contains(&limit));
            }
            let extremes = linkage.transmission_extremes();
            prop_assert!(extremes.min.is_finite() && extremes.max.is_finite());
            prop_assert!(extremes.min <= extremes.max);
            for branch in BRANCHES {
                for centre in linkage.dead_centres(branch).into_iter().flatten() {
                    prop_assert!(centre.theta2.is_finite() && centre.theta4.is_finite());
                }
            }
            let _ = limits.reaches(theta2 * 1e30);
        }
        if let Ok(slider) = SliderCrank::new(l1, l2, if theta2 < 0.0 { -l3 } else { l3 }) {
            prop_assert!(slider.stroke().is_none_or(f32::is_finite));
            prop_assert!(slider.time_ratio().is_none_or(f32::is_finite));
            for angle in slider.dead_centres().into_iter().flatten() {
                prop_assert!(angle.is_finite());
            }
        }
    }

    #[test]
    fn acceleration_totals_are_finite_or_an_error(
        parts in prop::array::uniform8(prop::num::f64::NORMAL | prop::num::f64::ZERO),
    ) {
        let [a, b, c, d, e, f, g, h] = parts;
        let parts = AccelerationParts {
            tangential: Vec2::new(a, b),
            normal: Vec2::new(c, d),
            sliding: Vec2::new(e, f),
            coriolis: Vec2::new(g, h),
        };
        match parts.total() {
            Ok(total) => prop_assert!(total.x.is_finite() && total.y.is_finite()),
            Err(error) => prop_assert_eq!(
                error,
                Error::NonFinite { quantity: "point acceleration" }
            ),
        }
    }
}
