//! The five-bar robot (two inputs, one loop) at the edges, judged against a 256-bit truth
//! (`mechgen_tests::oracle`'s numbers): its end effector where the circles of its distal links
//! about the elbows meet, on the requested side of the line between the elbows; the distal
//! links' angles; and their rates and accelerations solved from the loop's derivatives. The
//! oracle's families (`tests/tests/edges.rs`) draw the one-input mechanisms; these are the same
//! contract for the robot (README, "Accuracy"), each unknown's error weighted by its column
//! (the distal link's length) over the size, or over the rates' size (the larger of the size
//! times the fastest input and the true rates, weighted):
//!
//! - every `Ok` of `motion` (the closed form) and of `motion_near` (Newton, from a guess
//!   within 1e-4/κ rad of the truth) is finite and within the accuracy it states;
//! - `motion` says `Ok` only where the loop closes, and `CannotAssemble` only where it does
//!   not, each but within rounding (`16·ε` of the size) of a limit.
//!
//! At link ratios to 1e16 (1e6 in f32) and sizes across each float's range, with the cranks
//! anywhere, or placed so that the distal links are within 1e-17 to 1e-2 (relative) of
//! stretched out or folded in line (the robot's parallel singularities, and the edges of its
//! workspace).

use mechanisms::{FiveBar, FiveBarUnknowns};
use mechgen::{Branch, Error, Motion, NewtonOptions, Real};
use mechgen_tests::oracle::draw::Rng;
use mechgen_tests::oracle::{Big, C};

/// One drawn case, its values already rounded to the float it is solved in.
#[derive(Clone, Copy, Debug)]
struct Case {
    /// `[l1, l2, l3, l4, l5]`.
    lengths: [f64; 5],
    /// `[θ1, θ4]`.
    inputs: [f64; 2],
    branch: Branch,
    rates: [f64; 2],
    accelerations: [f64; 2],
}

/// Where the cranks are put.
#[derive(Clone, Copy, Debug)]
enum Posture {
    Anywhere,
    /// The elbows `l2 + l3` apart, to within the relative offset drawn.
    NearStretched,
    /// The elbows `|l2 − l3|` apart, likewise.
    NearFolded,
}

/// A case with lengths up to `10^ratio` apart at a size of up to `10^±scale`, in `T`, or
/// `None` where the posture asked for cannot be reached.
fn draw<T: Real + Into<f64>>(
    rng: &mut Rng,
    ratio: f64,
    scale: f64,
    posture: Posture,
) -> Option<Case> {
    let rounded = |x: f64| -> f64 { T::from(x).unwrap().into() };
    let size = 10f64.powf(rng.range(-scale, scale));
    let mut lengths = [0.0; 5].map(|_| rounded(size * 10f64.powf(rng.range(-ratio, ratio))));
    // Motors on one axis now and then.
    if rng.chance(0.1) {
        lengths[4] = 0.0;
    }
    let [l1, l2, l3, l4, l5] = lengths;
    let theta1 = rng.angle();
    let theta4 = match posture {
        Posture::Anywhere => rng.angle(),
        Posture::NearStretched | Posture::NearFolded => {
            let apart = match posture {
                Posture::NearStretched => l2 + l3,
                _ => (l2 - l3).abs(),
            };
            let apart = apart * (1.0 + rng.sign() * 10f64.powf(rng.range(-17.0, -2.0)));
            // The crank O5 A2 at the angle that puts A2 `apart` from A1.
            let (x, y) = (l1 * theta1.cos() - l5, l1 * theta1.sin());
            let reach = x.hypot(y);
            let cos = (l4 * l4 + reach * reach - apart * apart) / (2.0 * l4 * reach);
            if cos.is_nan() || cos.abs() > 1.0 {
                return None;
            }
            y.atan2(x) + rng.sign() * cos.acos()
        }
    };
    let branch = if rng.chance(0.5) {
        Branch::Open
    } else {
        Branch::Crossed
    };
    let mut rate = || rounded(rng.range(-10.0, 10.0));
    Some(Case {
        lengths,
        inputs: [rounded(theta1), rounded(theta4)],
        branch,
        rates: [rate(), rate()],
        accelerations: [rate(), rate()],
    })
}

/// The truth at a case, at 256 bits.
struct Truth {
    /// How far the elbows are inside the workspace's limits, in length: the smaller of
    /// `l2 + l3 − d` and `d − |l2 − l3|`, `d` the elbows' distance; negative where the loop
    /// cannot close.
    reach: f64,
    /// `[θ2, θ3]`, their rates and accelerations, where the loop closes.
    motion: Option<[[Big; 2]; 3]>,
}

fn big(x: f64) -> Big {
    Big::from_f64(x)
}

fn truth(case: &Case) -> Truth {
    let [l1, l2, l3, l4, l5] = case.lengths.map(big);
    let ([w1, w4], [a1, a4]) = (case.rates.map(big), case.accelerations.map(big));
    let (e1, e4) = (C::expi(&big(case.inputs[0])), C::expi(&big(case.inputs[1])));
    let elbow1 = e1.scale(&l1);
    let elbow2 = C::new(l5, Big::zero()).add(&e4.scale(&l4));
    let between = elbow2.sub(&elbow1);
    let d = between.norm();
    let reach = (&l2 + &l3 - &d).min(&d - (&l2 - &l3).abs());
    if reach.is_negative() || d.is_zero() {
        return Truth {
            reach: reach.to_f64(),
            motion: None,
        };
    }
    // The chord's foot along A1 → A2, and the half chord, to the left (`Open`) or right.
    let along = (d.square() + l2.square() - l3.square()) / (big(2.0) * &d);
    let half_chord = (l2.square() - along.square()).max(Big::zero()).sqrt();
    let half_chord = match case.branch {
        Branch::Open => half_chord,
        Branch::Crossed => -half_chord,
    };
    let unit = between.scale(&(Big::one() / &d));
    let effector = elbow1
        .add(&unit.scale(&along))
        .add(&unit.turn().scale(&half_chord));
    let (distal2, distal3) = (effector.sub(&elbow1), effector.sub(&elbow2));
    // The loop l1·e1 + distal2 − distal3 − l4·e4 − l5 = 0, differentiated and divided by i:
    // distal2·θ2' − distal3·θ3' = l4·e4·ω4 − l1·e1·ω1, solved by Cramer's rule with columns
    // distal2 and −distal3.
    let minus3 = C::new(-&distal3.re, -&distal3.im);
    let det = distal2.cross(&minus3);
    let solve = |rhs: &C| [rhs.cross(&minus3) / &det, distal2.cross(rhs) / &det];
    let rates = solve(&e4.scale(&(&l4 * &w4)).sub(&e1.scale(&(&l1 * &w1))));
    // Twice: distal2·θ2'' − distal3·θ3'' = i·S with S the velocity terms and the inputs'.
    let centripetal = |w: &Big, a: &Big| C::new(-w.square(), a.clone());
    let terms = e1
        .scale(&l1)
        .mul(&centripetal(&w1, &a1))
        .sub(&distal2.scale(&rates[0].square()))
        .add(&distal3.scale(&rates[1].square()))
        .sub(&e4.scale(&l4).mul(&centripetal(&w4, &a4)));
    let accelerations = solve(&terms.turn());
    Truth {
        reach: reach.to_f64(),
        motion: Some([[distal2.angle(), distal3.angle()], rates, accelerations]),
    }
}

/// The largest `|got − want|·column` over `scale` (angles modulo 2π); infinite where `got` is
/// not finite.
fn weighted_error(
    got: [f64; 2],
    want: &[Big; 2],
    columns: [f64; 2],
    scale: &Big,
    angles: bool,
) -> f64 {
    if got.iter().any(|g| !g.is_finite()) {
        return f64::INFINITY;
    }
    (0..2)
        .map(|k| {
            let mut difference = big(got[k]) - &want[k];
            if angles {
                difference = difference.wrapped();
            }
            (difference.abs() * big(columns[k]) / scale).to_f64()
        })
        .fold(0.0, f64::max)
}

/// Why a `Motion` breaks the contract against the truth, if it does.
fn beyond_stated<T: Real + Into<f64>>(
    case: &Case,
    truth: &[[Big; 2]; 3],
    got: &Motion<FiveBarUnknowns<T>, T>,
) -> Option<String> {
    let [_, l2, l3, _, _] = case.lengths;
    let columns = [l2, l3];
    let size = big(case.lengths.iter().sum());
    let fastest = case.rates[0].abs().max(case.rates[1].abs());
    let hardest = case.accelerations[0].abs().max(case.accelerations[1].abs());
    let rates_size = |level: usize, floor: Big| {
        (0..2).fold(floor, |size, k| {
            size.max((&truth[level][k] * big(columns[k])).abs())
        })
    };
    let scales = [
        size.clone(),
        rates_size(1, &size * big(fastest)),
        rates_size(2, &size * big(fastest * fastest + hardest)),
    ];
    let values =
        [got.position, got.velocity, got.acceleration].map(|u| [u.theta2.into(), u.theta3.into()]);
    let stated: [f64; 3] = [
        got.accuracy.position.into(),
        got.accuracy.velocity.into(),
        got.accuracy.acceleration.into(),
    ];
    let errors: Vec<f64> = (0..3)
        .map(|level| {
            weighted_error(
                values[level],
                &truth[level],
                columns,
                &scales[level],
                level == 0,
            )
        })
        .collect();
    // Not within for a NaN error or bound.
    let within = (0..3).all(|level| errors[level] <= stated[level]);
    let listed = |values: &[f64]| {
        let shown: Vec<String> = values.iter().map(|v| format!("{v:.2e}")).collect();
        shown.join(", ")
    };
    (!within).then(|| {
        format!(
            "errors (position, velocity, acceleration) {} against the stated {}",
            listed(&errors),
            listed(&stated)
        )
    })
}

/// Every way the robot's answers at `case` break the contract.
fn findings<T: Real + Into<f64>>(case: &Case, rng: &mut Rng, tally: &mut Tally) -> Vec<String> {
    let t = |x: f64| T::from(x).unwrap();
    let [l1, l2, l3, l4, l5] = case.lengths.map(t);
    let Ok(robot) = FiveBar::new(l1, l2, l3, l4, l5) else {
        return vec!["the constructor refused positive lengths".into()];
    };
    let ([theta1, theta4], [w1, w4], [a1, a4]) = (
        case.inputs.map(t),
        case.rates.map(t),
        case.accelerations.map(t),
    );
    let truth = truth(case);
    let rounding = 16.0 * T::epsilon().into() * case.lengths.iter().sum::<f64>();
    let near_limit = truth.reach.abs() <= rounding;
    let mut found = Vec::new();
    match (
        robot.motion(theta1, theta4, case.branch, w1, w4, a1, a4),
        &truth.motion,
    ) {
        (Ok(got), Some(motion)) => {
            tally.closed += 1;
            found.extend(beyond_stated(case, motion, &got).map(|why| format!("motion: {why}")));
        }
        (Ok(_), None) if !near_limit => found.push(format!(
            "motion: Ok where the loop cannot close (the elbows {:.2e} beyond reach)",
            -truth.reach
        )),
        (Err(Error::CannotAssemble { .. }), Some(_)) if !near_limit => found.push(format!(
            "motion: CannotAssemble where the loop closes ({:.2e} inside the limits)",
            truth.reach
        )),
        _ => {}
    }
    if let Some(motion) = &truth.motion {
        // Newton from a guess near the truth.
        let condition: f64 = robot
            .condition(
                theta1,
                theta4,
                &FiveBarUnknowns {
                    theta2: t(motion[0][0].to_f64()),
                    theta3: t(motion[0][1].to_f64()),
                },
            )
            .into();
        let offset = 1e-4 / condition.clamp(1.0, 1e12);
        let guess = FiveBarUnknowns {
            theta2: t(motion[0][0].to_f64() + rng.range(-offset, offset)),
            theta3: t(motion[0][1].to_f64() + rng.range(-offset, offset)),
        };
        let options = NewtonOptions::default();
        if let Ok(got) = robot.motion_near(theta1, theta4, &guess, &options, w1, w4, a1, a4) {
            tally.newton += 1;
            found.extend(
                beyond_stated(case, motion, &got.value).map(|why| format!("motion_near: {why}")),
            );
        }
    }
    found
}

/// How many `Ok`s were judged.
#[derive(Default)]
struct Tally {
    closed: usize,
    newton: usize,
}

/// Draws `cases` cases in `T` at link ratios to `10^ratio` and sizes to `10^±scale`, in every
/// posture, and fails with every case that breaks the contract; returns the tally.
fn keeps_the_contract<T: Real + Into<f64>>(
    seed: u64,
    cases: usize,
    ratio: f64,
    scale: f64,
) -> Tally {
    let mut rng = Rng(seed);
    let mut tally = Tally::default();
    let mut broken = Vec::new();
    let postures = [
        Posture::Anywhere,
        Posture::NearStretched,
        Posture::NearFolded,
    ];
    for index in 0..cases {
        let ratio = [0.3, 1.0, ratio / 2.0, ratio][index % 4];
        let Some(case) = draw::<T>(&mut rng, ratio, scale, postures[index / 4 % 3]) else {
            continue;
        };
        for finding in findings::<T>(&case, &mut rng, &mut tally) {
            broken.push(format!("{case:?}: {finding}"));
        }
    }
    assert!(
        broken.is_empty(),
        "{} broken:\n{}",
        broken.len(),
        broken.join("\n")
    );
    tally
}

#[test]
fn the_five_bar_keeps_the_contract_at_the_edges_in_f64() {
    let tally = keeps_the_contract::<f64>(20261128, 20000, 8.0, 250.0);
    // The draw reached the solvers: most of its cases assemble near a limit or nowhere.
    assert!(
        tally.closed > 400 && tally.newton > 400,
        "{} and {}",
        tally.closed,
        tally.newton
    );
}

#[test]
fn the_five_bar_keeps_the_contract_at_the_edges_in_f32() {
    let tally = keeps_the_contract::<f32>(20261129, 20000, 3.0, 30.0);
    assert!(
        tally.closed > 400 && tally.newton > 400,
        "{} and {}",
        tally.closed,
        tally.newton
    );
}
