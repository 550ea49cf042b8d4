//! Numerical stability at the extremes: every result right to the documented bound or a
//! documented error, against independent 60-digit references (`tests/reference/`), and on
//! random mechanisms and inputs.

use mechanisms::{FourBar, FourBarUnknowns, InvertedSliderCrank, SliderCrank};
use mechgen::{Accuracy, Branch, Error, NewtonOptions, Order};
use mechgen_tests::reference::{self, Status};
use proptest::prelude::*;

#[test]
fn every_reference_case_keeps_the_contract() {
    let cases = reference::cases();
    assert!(cases.len() > 150, "the reference set is loaded");
    let broken: Vec<String> = cases
        .iter()
        .map(|case| (case, reference::assess(case)))
        .filter(|(_, a)| !a.kept)
        .map(|(case, a)| {
            format!(
                "{} {} {} δ={} {:?}: {a:?}",
                case.mechanism, case.case, case.precision, case.delta, case.branch
            )
        })
        .collect();
    assert!(broken.is_empty(), "{}", broken.join("\n"));
}

/// `motion`'s answer for a case in the float type `T`: its position, rates and accelerations
/// widened to f64, with the estimate it carries, or `None` where it says an error.
fn motion_in<T: mechgen::Real>(case: &reference::Case) -> Option<([[f64; 2]; 3], Accuracy<f64>)> {
    let p: Vec<T> = case.params.iter().map(|&v| T::constant(v)).collect();
    let (input, omega, alpha) = (
        T::constant(case.input),
        T::constant(reference::OMEGA2),
        T::constant(reference::ALPHA2),
    );
    let f = |v: T| v.to_f64().unwrap_or(f64::NAN);
    let widen = |a: [T; 2]| a.map(f);
    macro_rules! answer {
        ($motion:expr) => {
            $motion.ok().map(|m| {
                (
                    [
                        widen(m.position.to_array()),
                        widen(m.velocity.to_array()),
                        widen(m.acceleration.to_array()),
                    ],
                    Accuracy {
                        position: f(m.accuracy.position),
                        velocity: f(m.accuracy.velocity),
                        acceleration: f(m.accuracy.acceleration),
                    },
                )
            })
        };
    }
    match case.mechanism.as_str() {
        "four_bar" => answer!(FourBar::new(p[0], p[1], p[2], p[3]).ok()?.motion(
            input,
            case.branch,
            omega,
            alpha
        )),
        "slider_crank" => answer!(SliderCrank::new(p[0], p[1], p[2]).ok()?.motion(
            input,
            case.branch,
            omega,
            alpha
        )),
        _ => answer!(
            InvertedSliderCrank::new(p[0], p[1], p[2], p[3])
                .ok()?
                .motion(input, case.branch, omega, alpha)
        ),
    }
}

/// Every `Ok` of `motion` carries its own estimate (at the position it computed, not the
/// reference's), and that estimate bounds the true error of the position, the rates and the
/// accelerations against every reference, in f64 and f32.
#[test]
fn motion_carries_an_estimate_that_bounds_its_error() {
    let mut checked = 0;
    let mut broken = Vec::new();
    for case in reference::cases() {
        if case.status != Status::Ok {
            continue;
        }
        let answer = if case.precision == "f32" {
            motion_in::<f32>(&case)
        } else {
            motion_in::<f64>(&case)
        };
        let Some(([q, q_dot, q_ddot], carried)) = answer else {
            continue;
        };
        checked += 1;
        let angles = reference::angle_unknowns(&case);
        let size = reference::size(&case);
        let columns = case.columns;
        let omega = reference::OMEGA2;
        let errors = [
            reference::error(reference::wrapped(q, case.q, angles), case.q, columns, size),
            reference::error(
                q_dot,
                case.q_dot,
                columns,
                reference::rate_size(case.q_dot, columns, size, omega),
            ),
            reference::error(
                q_ddot,
                case.q_ddot,
                columns,
                reference::rate_size(
                    case.q_ddot,
                    columns,
                    size,
                    omega * omega + reference::ALPHA2,
                ),
            ),
        ];
        let estimates = [carried.position, carried.velocity, carried.acceleration];
        for (order, (error, estimate)) in errors.iter().zip(estimates).enumerate() {
            // A NaN error or estimate fails too.
            if error.is_nan() || estimate.is_nan() || *error > estimate {
                broken.push(format!(
                    "{} {} {} δ={} order {order}: error {error:.2e} > carried estimate {estimate:.2e}",
                    case.mechanism, case.case, case.precision, case.delta
                ));
            }
        }
    }
    assert!(checked > 100, "only {checked} reference cases answered");
    assert!(broken.is_empty(), "{}", broken.join("\n"));
}

#[test]
fn the_published_accuracy_table_is_current() {
    let published = include_str!("../../docs/ACCURACY.md");
    assert!(
        published == reference::table(),
        "docs/ACCURACY.md is stale: run \
         `cargo run -p mechgen-tests --bin accuracy > docs/ACCURACY.md`"
    );
}

/// Newton from near each f64 reference position: the same position on the same branch, or a
/// documented error where the position is nearly singular.
#[test]
fn newton_near_the_references_stays_on_branch() {
    for case in reference::cases() {
        if case.precision != "f64" || case.status != Status::Ok || case.mechanism != "four_bar" {
            continue;
        }
        let p = &case.params;
        let linkage = FourBar::new(p[0], p[1], p[2], p[3]).unwrap();
        // Nudged well within the branch's basin, which narrows as the toggle nears.
        let nudge = 1e-2 / case.condition;
        let guess = FourBarUnknowns {
            theta3: case.q[0] + nudge,
            theta4: case.q[1] - nudge,
        };
        assert_eq!(linkage.branch_of(case.input, &guess), case.branch);
        match linkage.position(case.input, &guess, &NewtonOptions::default()) {
            Ok(solved) => {
                assert_eq!(
                    linkage.branch_of(case.input, &solved.value),
                    linkage.branch_of(case.input, &guess)
                );
                let error = (solved.value.theta3 - case.q[0])
                    .abs()
                    .max((solved.value.theta4 - case.q[1]).abs());
                // The position estimate is relative to the size, each angle weighted by its
                // column: unweighted, an angle's share is size / column.
                let (estimate, _) = reference::estimate(&case, case.condition);
                let bound = estimate.position * reference::size(&case)
                    / case.columns[0].min(case.columns[1]);
                assert!(
                    error <= bound,
                    "{} δ={}: {error:e} > {bound:e}",
                    case.case,
                    case.delta
                );
            }
            Err(error) => assert!(
                matches!(
                    error,
                    Error::Singular { .. } | Error::CannotAssemble { .. } | Error::OtherBranch
                ) && case.condition * f64::EPSILON.sqrt() > 1e-3,
                "{} δ={}: {error:?} at κ = {}",
                case.case,
                case.delta,
                case.condition
            ),
        }
    }
}

/// The failure a hand-written solver shows (KINEMATICS-style Newton "converging" one ulp past a
/// toggle with a loose tolerance, then an enormous rate): here it is an error that says why.
#[test]
fn one_ulp_past_a_toggle_is_an_error_not_a_huge_rate() {
    let linkage = FourBar::new(100.0f64, 120.0, 90.0, 80.0).unwrap();
    let limit = linkage.limit_angles().extended.unwrap();
    let at_limit = linkage.assemble(limit, Branch::Open).unwrap();
    let past = f64::from_bits(limit.to_bits() + 1);
    for tolerance in [1e-4, 1e-9, 0.0] {
        let result = linkage.position(past, &at_limit, &NewtonOptions::new(tolerance, 50));
        match result {
            Err(Error::CannotAssemble { .. } | Error::Singular { .. }) => {}
            Ok(solved) => {
                // Within rounding of the toggle: then the rate is refused, not made up.
                assert!(solved.condition > 1e6, "{solved:?}");
                assert!(matches!(
                    linkage.velocity(past, &solved.value, 1.0),
                    Err(Error::Singular { .. } | Error::Inaccurate { .. })
                ));
            }
            Err(other) => panic!("tolerance {tolerance}: {other:?}"),
        }
    }
    // A millionth of a radian past, with a loose tolerance, is past: no position, whether
    // Newton starts on the toggle (singular there) or short of it (it stagnates against it).
    let past = limit + 1e-6;
    let result = linkage.position(past, &at_limit, &NewtonOptions::new(1e-4, 50));
    assert!(matches!(result, Err(Error::Singular { .. })), "{result:?}");
    let short = linkage.assemble(limit - 1e-3, Branch::Open).unwrap();
    let result = linkage.position(past, &short, &NewtonOptions::new(1e-4, 50));
    assert_eq!(result.unwrap_err(), Error::CannotAssemble { input: past });
}

fn finite_ok(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

fn documented<T>(error: &Error<T>) -> bool {
    matches!(
        error,
        Error::CannotAssemble { .. }
            | Error::Singular { .. }
            | Error::OtherBranch
            | Error::NoConvergence { .. }
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Lengths over twelve orders of magnitude, any input, any guess: Ok with a residual at
    /// rounding level times the size, or a documented error; never NaN or infinity.
    #[test]
    fn four_bars_answer_or_say_why(
        exponent in -6.0f64..6.0,
        l in [0.05f64..1.0, 0.05f64..1.0, 0.05f64..1.0, 0.05f64..1.0],
        theta2 in -4.0f64..4.0,
        guess in [-4.0f64..4.0, -4.0f64..4.0],
        branch in prop::bool::ANY,
    ) {
        let scale = 10f64.powf(exponent);
        let lengths = l.map(|x| x * scale);
        let Ok(linkage) = FourBar::new(lengths[0], lengths[1], lengths[2], lengths[3]) else {
            return Ok(());
        };
        let size: f64 = lengths.iter().sum();
        let branch = if branch { Branch::Open } else { Branch::Crossed };
        match linkage.assemble(theta2, branch) {
            Ok(q) => {
                prop_assert!(finite_ok(&q.to_array()));
                for f in linkage.residual(theta2, &q) {
                    prop_assert!(f.abs() <= 64.0 * f64::EPSILON * size, "residual {f:e}");
                }
                match linkage.velocity(theta2, &q, 1.0) {
                    Ok(v) => {
                        prop_assert!(finite_ok(&v.to_array()));
                        let a = linkage.acceleration(theta2, &q, 1.0, &v, 0.5);
                        prop_assert!(a.is_err() || finite_ok(&a.unwrap().to_array()));
                        // Where well conditioned, the rates match finite differences.
                        if linkage.condition(theta2, &q) < 1e3 {
                            let h = 1e-6;
                            let plus = linkage.assemble(theta2 + h, branch);
                            let minus = linkage.assemble(theta2 - h, branch);
                            if let (Ok(p), Ok(m)) = (plus, minus) {
                                let estimate = (p.theta4 - m.theta4) / (2.0 * h);
                                prop_assert!((estimate - v.theta4).abs() <= 1e-5 * v.theta4.abs().max(1.0));
                            }
                        }
                    }
                    Err(error) => prop_assert!(matches!(error, Error::Singular { .. }), "{:?}", error),
                }
            }
            Err(error) => prop_assert!(matches!(error, Error::CannotAssemble { .. } | Error::Singular { .. }), "{:?}", error),
        }
        let guess = FourBarUnknowns::from_array(guess);
        match linkage.position(theta2, &guess, &NewtonOptions::default()) {
            Ok(solved) => {
                prop_assert!(finite_ok(&solved.value.to_array()));
                // The contract: at the rounding floor 16·ε·Σ|r|, or within four of it where no
                // step lowers the residual (a coupled evaluation rounds above its vectors').
                prop_assert!(solved.residual_norm <= 4.0 * 16.0 * f64::EPSILON * size * 1.0001);
            }
            Err(error) => prop_assert!(documented(&error), "{error:?}"),
        }
    }

    #[test]
    fn slider_cranks_answer_or_say_why(
        exponent in -6.0f64..6.0,
        l in [0.05f64..1.0, 0.05f64..1.0],
        offset in -1.0f64..1.0,
        theta2 in -4.0f64..4.0,
        branch in prop::bool::ANY,
    ) {
        let scale = 10f64.powf(exponent);
        let Ok(linkage) = SliderCrank::new(l[0] * scale, l[1] * scale, offset * scale) else {
            return Ok(());
        };
        let branch = if branch { Branch::Open } else { Branch::Crossed };
        match linkage.assemble(theta2, branch) {
            Ok(q) => {
                prop_assert!(finite_ok(&q.to_array()));
                let size = (l[0] + l[1] + offset.abs()) * scale + q.d.abs();
                for f in linkage.residual(theta2, &q) {
                    prop_assert!(f.abs() <= 64.0 * f64::EPSILON * size);
                }
                if let Ok(v) = linkage.velocity(theta2, &q, 1.0) {
                    prop_assert!(finite_ok(&v.to_array()));
                }
            }
            Err(error) => prop_assert!(matches!(error, Error::CannotAssemble { .. } | Error::Singular { .. }), "{:?}", error),
        }
    }

    #[test]
    fn inverted_slider_cranks_answer_or_say_why(
        exponent in -6.0f64..6.0,
        l in [0.05f64..1.0, 0.05f64..1.0],
        offset in -1.0f64..1.0,
        gamma in -3.0f64..3.0,
        theta2 in -4.0f64..4.0,
        branch in prop::bool::ANY,
    ) {
        let scale = 10f64.powf(exponent);
        let Ok(linkage) = InvertedSliderCrank::new(l[0] * scale, l[1] * scale, offset * scale, gamma) else {
            return Ok(());
        };
        let branch = if branch { Branch::Open } else { Branch::Crossed };
        match linkage.assemble(theta2, branch) {
            Ok(q) => {
                prop_assert!(finite_ok(&q.to_array()));
                let size = (l[0] + l[1] + offset.abs()) * scale + q.b.abs();
                for f in linkage.residual(theta2, &q) {
                    prop_assert!(f.abs() <= 64.0 * f64::EPSILON * size);
                }
                if let Ok(v) = linkage.velocity(theta2, &q, 1.0) {
                    prop_assert!(finite_ok(&v.to_array()));
                    if let Ok(a) = linkage.acceleration(theta2, &q, 1.0, &v, 0.5) {
                        prop_assert!(finite_ok(&a.to_array()));
                    }
                }
            }
            Err(error) => prop_assert!(matches!(error, Error::CannotAssemble { .. } | Error::Singular { .. }), "{:?}", error),
        }
    }

    /// The same in f32, which has far less room.
    #[test]
    fn f32_four_bars_answer_or_say_why(
        l in [1.0f32..100.0, 1.0f32..100.0, 1.0f32..100.0, 1.0f32..100.0],
        theta2 in -4.0f32..4.0,
        branch in prop::bool::ANY,
    ) {
        let Ok(linkage) = FourBar::new(l[0], l[1], l[2], l[3]) else { return Ok(()); };
        let size: f32 = l.iter().sum();
        let branch = if branch { Branch::Open } else { Branch::Crossed };
        if let Ok(q) = linkage.assemble(theta2, branch) {
            for f in linkage.residual(theta2, &q) {
                prop_assert!(f.abs() <= 64.0 * f32::EPSILON * size);
            }
            match linkage.velocity(theta2, &q, 1.0) {
                Ok(v) => prop_assert!(v.to_array().iter().all(|x| x.is_finite())),
                // Near a toggle f32 runs out of digits well before the Jacobian is singular:
                // refused where the estimate at the position's own κ exceeds what is required
                // (κ from the factors and from `condition` agree to rounding, not to the bit).
                Err(Error::Inaccurate { order: Order::Velocity, estimate, required }) => {
                    let at_kappa = Accuracy::<f32>::estimate(linkage.condition(theta2, &q), 1.0);
                    prop_assert!(estimate > required && estimate >= 0.99 * at_kappa.velocity,
                        "estimate {} against {} at κ {}", estimate, required, linkage.condition(theta2, &q));
                }
                Err(error) => prop_assert!(matches!(error, Error::Singular { .. }), "{:?}", error),
            }
        }
    }
}
