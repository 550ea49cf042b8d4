//! `motion_near` (Newton, then the rates from its last evaluation) gives what `position`
//! followed by `motion_at` gives, for one loop and for coupled loops, in f64 and f32.

mod common;

use mechgen::{Branch, NewtonOptions, Real};
use mechgen_tests::examples::stephenson_six_bar;

fn agree<T: Real>(what: &str, input: T, got: T, want: T, scale: T) {
    let allowed = T::constant(64.0) * T::epsilon() * scale;
    assert!(
        (got - want).abs() <= allowed,
        "{what} at {input}: motion_near {got}, position then motion_at {want}"
    );
}

fn four_bar_agrees<T: Real>() {
    let linkage = common::example_1::<T>();
    let options = NewtonOptions::default();
    let (w, a) = (T::constant(10.0), T::constant(2.0));
    let step = T::constant(1f64.to_radians());
    let mut guess = linkage.assemble(T::zero(), Branch::Open).unwrap();
    for degree in 1..360 {
        let t = T::constant(f64::from(degree).to_radians());
        let near = linkage.motion_near(t, &guess, &options, w, a).unwrap();
        let position = linkage.position(t, &guess, &options).unwrap();
        assert_eq!(near.value.position, position.value, "the same Newton solve");
        assert_eq!(near.iterations, position.iterations);
        let at = linkage.motion_at(t, &position.value, w, a).unwrap();
        agree("ω3", t, near.value.velocity.theta3, at.velocity.theta3, w);
        agree("ω4", t, near.value.velocity.theta4, at.velocity.theta4, w);
        agree(
            "α3",
            t,
            near.value.acceleration.theta3,
            at.acceleration.theta3,
            w * w,
        );
        agree(
            "α4",
            t,
            near.value.acceleration.theta4,
            at.acceleration.theta4,
            w * w,
        );
        // The next guess from the velocity predictor.
        let q = near.value.position;
        let v = near.value.velocity;
        guess = mechanisms::FourBarUnknowns {
            theta3: q.theta3 + v.theta3 / w * step,
            theta4: q.theta4 + v.theta4 / w * step,
        };
    }
}

#[test]
fn four_bar_motion_near_matches_position_and_motion_at() {
    four_bar_agrees::<f64>();
    four_bar_agrees::<f32>();
}

#[test]
fn coupled_loops_motion_near_matches_position_and_motion_at() {
    let (linkage, mut guess) = stephenson_six_bar();
    let options = NewtonOptions::default();
    let (w, a) = (10.0, 2.0);
    for degree in 0..360 {
        let t = f64::from(degree).to_radians();
        let near = linkage.motion_near(t, &guess, &options, w, a).unwrap();
        let position = linkage.position(t, &guess, &options).unwrap();
        assert_eq!(near.value.position, position.value);
        let at = linkage.motion_at(t, &position.value, w, a).unwrap();
        let kappa = position.condition;
        let rates = near
            .value
            .velocity
            .to_array()
            .into_iter()
            .zip(at.velocity.to_array());
        for (got, want) in rates {
            agree("rate", t, got, want, w * kappa);
        }
        let accelerations = near
            .value
            .acceleration
            .to_array()
            .into_iter()
            .zip(at.acceleration.to_array());
        for (got, want) in accelerations {
            agree("acceleration", t, got, want, w * w * kappa * kappa);
        }
        guess = near.value.position;
    }
}

/// Newton's stated accuracy holds where it stops above the rounding floor (a tolerance
/// looser than the floor, as the seeds' 1e-4 mm), its rates' estimates growing with the
/// position's error: Example 1 at 60°, from guesses 1e-3 to 0.05 rad off, against the closed
/// form (whose own error is far below these). With the default requirement the loosest of
/// them are `Inaccurate`: their rates have fewer digits than required, as they state.
#[test]
fn a_loose_tolerance_states_the_accuracy_it_leaves() {
    let linkage = common::example_1::<f64>();
    let (t, w, a) = (60f64.to_radians(), 10.0, 2.0);
    let exact = linkage.motion(t, Branch::Open, w, a).unwrap();
    let size = 180.0 + 80.0 + 200.0 + 150.0;
    let rates = |q: mechanisms::FourBarUnknowns<f64>| {
        (q.theta3 * 200.0).abs().max((q.theta4 * 150.0).abs())
    };
    let error = |got: mechanisms::FourBarUnknowns<f64>, want: mechanisms::FourBarUnknowns<f64>| {
        ((got.theta3 - want.theta3) * 200.0)
            .abs()
            .max(((got.theta4 - want.theta4) * 150.0).abs())
    };
    let mut loose_seen = false;
    for tolerance in [0.0, 1e-9, 1e-6, 1e-4, 1e-2] {
        for offset in [1e-3, 1e-2, 5e-2] {
            let guess = mechanisms::FourBarUnknowns {
                theta3: exact.position.theta3 + offset,
                theta4: exact.position.theta4 - offset,
            };
            // Every rate returned, however few its digits, to compare with what it states.
            let options = NewtonOptions::new(tolerance, 50).with_accuracy(mechgen::Accuracy {
                position: 1.0,
                velocity: 1.0,
                acceleration: 1.0,
            });
            let near = linkage.motion_near(t, &guess, &options, w, a).unwrap();
            let m = near.value;
            let position = error(m.position, exact.position) / size;
            let velocity =
                error(m.velocity, exact.velocity) / (size * w).max(rates(exact.velocity));
            let acceleration = error(m.acceleration, exact.acceleration)
                / (size * (w * w + a)).max(rates(exact.acceleration));
            let case = format!("tolerance {tolerance:e}, guess {offset:e} off");
            assert!(
                position <= m.accuracy.position,
                "{case}: position {position:e} vs {:e}",
                m.accuracy.position
            );
            assert!(
                velocity <= m.accuracy.velocity,
                "{case}: velocity {velocity:e} vs {:e}",
                m.accuracy.velocity
            );
            assert!(
                acceleration <= m.accuracy.acceleration,
                "{case}: acceleration {acceleration:e} vs {:e}",
                m.accuracy.acceleration
            );
            // The estimate follows the residual it stopped at, not the floor alone.
            if near.residual_norm > 1e-9 {
                loose_seen = true;
                assert!(m.accuracy.position >= 2.0 * near.residual_norm / size);
            }
        }
    }
    assert!(loose_seen, "some solve stopped above the floor");
}

#[test]
fn rates_too_far_off_for_the_requirement_are_refused() {
    let linkage = common::example_1::<f64>();
    let (t, w, a) = (60f64.to_radians(), 10.0, 2.0);
    let exact = linkage.motion(t, Branch::Open, w, a).unwrap();
    let guess = mechanisms::FourBarUnknowns {
        theta3: exact.position.theta3 + 1e-2,
        theta4: exact.position.theta4 - 1e-2,
    };
    // Stopped at a residual of 7e-3 mm: the position is 2e-5 of the size off at most, and its
    // rates have about four digits, fewer than the five required.
    let loose = NewtonOptions::new(1e-2, 50);
    assert!(matches!(
        linkage.motion_near(t, &guess, &loose, w, a),
        Err(mechgen::Error::Inaccurate {
            order: mechgen::Order::Velocity,
            ..
        })
    ));
    // The position alone is still returned, with its residual.
    let position = linkage.position(t, &guess, &loose).unwrap();
    assert!(position.residual_norm > 1e-3);
}

/// `q` taken by whole turns to within [−π, π] where `angle`: a turn apart is one angle.
fn turned_back<T: Real>(q: T, angle: bool) -> T {
    if angle {
        let (s, c) = q.sin_cos();
        s.atan2(c)
    } else {
        q
    }
}

/// Each of `got` within 64 ε of `want` (angles a turn apart one angle, lengths relative to
/// `size`).
fn same_position<T: Real>(what: &str, got: &[T], want: &[T], angles: &[bool], size: T) {
    for ((g, w), &angle) in got.iter().zip(want).zip(angles) {
        let (g, w) = (turned_back(*g, angle), turned_back(*w, angle));
        let scale = if angle { T::one() } else { size };
        assert!(
            (g - w).abs() <= T::constant(64.0) * T::epsilon() * scale,
            "{what}: {g} against {w}"
        );
    }
}

/// A guess whose angles count turns (a linkage that has turned a thousand times, its angles
/// carried along from step to step) solves as the same guess within a turn of zero, one
/// loop or several, by `position` and `motion_near`, in f64 and f32: angles beyond ±16 rad
/// are taken by whole turns first, and the solution's angles are within a turn of zero.
/// Before, at a thousand turns Newton stalled above its floor (`NoConvergence`): a float of
/// 6283 holds an angle only to 4.5e-13 rad.
fn guesses_that_count_turns_solve<T: Real>() {
    let options = NewtonOptions::default();
    let tau = T::constant(core::f64::consts::TAU);
    let (w, a) = (T::constant(10.0), T::constant(2.0));
    let input = T::constant(1.0);
    let turns = [3.0, -3.0, 100.0, 1e3, -1e3, 1e5];
    let within = |q: T| q.abs() <= T::constant(core::f64::consts::PI + 0.01);

    let four_bar = common::example_1::<T>();
    let exact = four_bar.assemble(input, Branch::Open).unwrap();
    for k in turns {
        let k = T::constant(k);
        let guess = mechanisms::FourBarUnknowns::from_array(exact.to_array().map(|q| q + k * tau));
        let solved = four_bar.position(input, &guess, &options).unwrap();
        let near = four_bar.motion_near(input, &guess, &options, w, a).unwrap();
        let at = four_bar.motion_at(input, &exact, w, a).unwrap();
        let q = solved.value.to_array();
        assert!(q.iter().all(|q| within(*q)), "four-bar, {k} turns: {q:?}");
        assert_eq!(near.value.position.to_array(), q, "{k} turns");
        same_position("four-bar", &q, &exact.to_array(), &[true; 2], T::one());
        for (got, want) in [
            (near.value.velocity.to_array(), at.velocity.to_array()),
            (
                near.value.acceleration.to_array(),
                at.acceleration.to_array(),
            ),
        ] {
            same_position("four-bar rates", &got, &want, &[false; 2], w * w);
        }
    }

    // One angle and a length: the slider-crank's θ3 and d.
    let slider_crank = common::slider_crank::<T>();
    let exact = slider_crank.assemble(input, Branch::Open).unwrap();
    let size = T::constant(220.0);
    for k in turns {
        let k = T::constant(k);
        let [theta3, d] = exact.to_array();
        let guess = mechanisms::SliderCrankUnknowns::from_array([theta3 + k * tau, d]);
        let q = slider_crank
            .position(input, &guess, &options)
            .unwrap()
            .value
            .to_array();
        assert!(within(q[0]), "slider-crank, {k} turns: {q:?}");
        same_position("slider-crank", &q, &exact.to_array(), &[true, false], size);
    }

    // Two loops, each kept to its branch by its own sign.
    let watt = common::watt_six_bar::<T>();
    let exact = watt.assemble(input, [Branch::Open; 2]).unwrap();
    for k in turns {
        let k = T::constant(k);
        let guess =
            mechanisms::WattSixBarUnknowns::from_array(exact.to_array().map(|q| q + k * tau));
        let q = watt
            .position(input, &guess, &options)
            .unwrap()
            .value
            .to_array();
        assert!(q.iter().all(|q| within(*q)), "Watt, {k} turns: {q:?}");
        same_position("Watt six-bar", &q, &exact.to_array(), &[true; 4], T::one());
    }

    // Newton on two unknowns, the other loop in closed form inside each evaluation.
    let (stephenson, start) = stephenson_six_bar();
    let exact = stephenson
        .position(1.0, &start, &NewtonOptions::default())
        .unwrap()
        .value;
    for k in turns {
        let guess = mechanisms::StephensonSixBarUnknowns::from_array(
            exact.to_array().map(|q| q + k * core::f64::consts::TAU),
        );
        let q = stephenson
            .position(1.0, &guess, &NewtonOptions::default())
            .unwrap()
            .value
            .to_array();
        same_position("Stephenson six-bar", &q, &exact.to_array(), &[true; 4], 1.0);
    }
}

#[test]
fn guesses_that_count_turns_solve_as_within_a_turn() {
    guesses_that_count_turns_solve::<f64>();
    guesses_that_count_turns_solve::<f32>();
}

/// A loop longer than the declared lengths (a slide's extension counts) closes only to its
/// own rounding, so a Newton position is off by that much of it: the accuracy `motion_near`
/// states, and `motion_at`'s at any position (Newton's included), is stretched by the loop's
/// magnitudes over the declared lengths. Edge run seed 15, case 914340: a slider-crank whose
/// rod is 66,000 times shorter than its crank and whose slide is as long as the crank had
/// rates 1.2 times further off than stated, when the position's error was read against the
/// declared lengths alone.
#[test]
fn a_slide_longer_than_the_declared_lengths_stretches_the_accuracy_stated() {
    let (l2, l3, c) = (1048576.0, 15.810822519382684, 74.79486745186973);
    let linkage = mechanisms::SliderCrank::<f64>::new(l2, l3, c).unwrap();
    let (t, w, a) = (3.14150724527024, 16.71564719961489, 9.480223757571935);
    let closed = linkage.assemble(t, Branch::Crossed).unwrap();
    let declared = l2 + l3 + c;
    let stretch = (declared + closed.d.abs()) / declared;
    assert!(
        stretch > 1.99,
        "the slide about as long as the crank: {stretch}"
    );
    let kappa = linkage.condition(t, &closed);
    let floor = 32.0 * f64::EPSILON * kappa;
    let at = linkage.motion_at(t, &closed, w, a).unwrap();
    assert!(
        (at.accuracy.position / (floor * stretch) - 1.0).abs() < 1e-12,
        "motion_at: {:e} against {:e}",
        at.accuracy.position,
        floor * stretch
    );
    let guess = mechanisms::SliderCrankUnknowns {
        theta3: closed.theta3 + 1e-3,
        d: closed.d + 1e-3 * l3,
    };
    let near = linkage
        .motion_near(t, &guess, &NewtonOptions::default(), w, a)
        .unwrap();
    assert!(
        near.value.accuracy.position >= floor * 1.99,
        "motion_near: {:e} against {:e}",
        near.value.accuracy.position,
        floor
    );
    // The four-bar's loop is its declared lengths: nothing to stretch.
    let four_bar = common::example_1::<f64>();
    let t = 60f64.to_radians();
    let q = four_bar.assemble(t, Branch::Open).unwrap();
    let at = four_bar.motion_at(t, &q, w, a).unwrap();
    let floor = 32.0 * f64::EPSILON * four_bar.condition(t, &q).max(1.0);
    assert_eq!(at.accuracy.position, floor);
}

/// Where the coupled loops' reduced iteration falls back to Newton on every unknown, a stated
/// tolerance leaves the position as far off as the residual it stopped at, and the accuracy
/// stated says so, as on the reduced path. Edge run seed 20, case 4911: a Stephenson six-bar
/// of size 4e199 from a guess 86,194 turns out, with a tolerance of 1.4e-7 of the size,
/// stopped at a residual 3,000 times the rounding floor and stated the floor's 9.7e-15 of the
/// size (what `motion_at` states for a position on it) for an error of 7.8e-12.
#[test]
fn a_stated_tolerance_leaves_its_accuracy_on_the_fallback_of_coupled_loops() {
    let linkage = mechanisms::StephensonSixBar::<f64>::new(
        3.172664574031082e198,
        7.112983859618762e197,
        1.6672907512341432e198,
        [2.496758721068498e197, 3.3103283728634656e197],
        -0.6392390047318863,
        4.3412785652393507e198,
        2.2505339431004197e199,
        (-9.735672780474796e198, 2.2429613380262655e199),
    )
    .unwrap();
    let guess = mechanisms::StephensonSixBarUnknowns::from_array([
        -541571.3319381861,
        -541570.1115900369,
        -541575.3876558257,
        -541574.0557543798,
    ]);
    let (t, w, a) = (3.020917478464141, 97.7860919585858, 6.763331673338108);
    let tolerance = 5.538150554973107e192;
    let exact = linkage
        .motion_near(t, &guess, &NewtonOptions::default(), w, a)
        .unwrap();
    let loose = linkage
        .motion_near(t, &guess, &NewtonOptions::new(tolerance, 50), w, a)
        .unwrap();
    assert!(loose.residual_norm > 1e3 * 16.0 * f64::EPSILON * 4e199 / 8.0);
    // Each angle's error times its link's length (the coupler's longer side for θ5), over
    // the declared lengths' sum.
    let lengths = [
        1.6672907512341432e198,
        4.3412785652393507e198,
        3.3103283728634656e197,
        2.2505339431004197e199,
    ];
    let size = 3.172664574031082e198
        + 7.112983859618762e197
        + 1.6672907512341432e198
        + 2.496758721068498e197
        + 3.3103283728634656e197
        + 4.3412785652393507e198
        + 2.2505339431004197e199
        + (9.735672780474796e198f64).hypot(2.2429613380262655e199);
    let error = loose
        .value
        .position
        .to_array()
        .iter()
        .zip(exact.value.position.to_array())
        .zip(lengths)
        .fold(0.0f64, |m, ((got, want), l)| m.max((got - want).abs() * l))
        / size;
    let stated = loose.value.accuracy.position;
    assert!(error > 1e-12, "the tolerance leaves an error: {error:e}");
    assert!(
        error <= stated,
        "error {error:e} against the stated {stated:e}"
    );
    // Stated from the residual it stopped at, not the floor alone.
    assert!(stated >= 2.0 * loose.residual_norm / size, "{stated:e}");
    assert!(loose.value.accuracy.velocity > exact.value.accuracy.velocity * 100.0);
}

/// Rates solved at a position a stated tolerance left short of the floor carry its error `δ`
/// through the Jacobian, and the accuracy stated covers it: `m·κ·ρ·δ` for the velocity and
/// `2·m·κ²·ρ·δ` for the acceleration, `m` the columns the error moves
/// (`mechgen::Accuracy::estimate_at`). The edge draws that
/// first stated tolerances found both halves of the earlier `κ·ρ·δ/2` and `κ²·ρ·δ/2`
/// exceeded: an inverted slider-crank whose slide's velocity was off by the slide's turn
/// (1.1 times), and a slider-crank whose coupler turns 1.5 times as fast as its crank, its
/// acceleration off by the velocity's error times that rate (2.1 times).
#[test]
fn rates_at_a_stated_tolerances_position_are_within_what_they_state() {
    // Everything returned, to compare with what it states.
    let anything = mechgen::Accuracy {
        position: 1.0,
        velocity: 1.0,
        acceleration: 1.0,
    };
    let (l1, l2, c, gamma) = (
        0.0011689728993278673,
        1024.0,
        0.029859208888583694,
        2.616991474820236,
    );
    let inverted = mechanisms::InvertedSliderCrank::<f64>::new(l1, l2, c, gamma).unwrap();
    let (t, w, a) = (-0.4322012873544323, 1.0, -5.411310685773052);
    let guess = mechanisms::InvertedSliderCrankUnknowns::from_array([
        -3.0491786776701746,
        1024.0247822229753,
    ]);
    let options = NewtonOptions::new(0.0065206066759504605, 50).with_accuracy(anything);
    let near = inverted.motion_near(t, &guess, &options, w, a).unwrap();
    let exact = inverted.motion(t, Branch::Open, w, a).unwrap();
    // θ4's column is the slide's length, b's a unit vector.
    let columns = [exact.position.b.abs(), 1.0];
    let to_array = |q: &mechanisms::InvertedSliderCrankUnknowns<f64>| q.to_array();
    let inverted_case = ("inverted slider-crank", l1 + l2 + c, (w, a), columns);
    within_stated(inverted_case, &near.value, &exact, to_array);

    let (l2, l3, c) = (0.08445248871785131, 0.07333896474097021, 0.0);
    let slider = mechanisms::SliderCrank::<f64>::new(l2, l3, c).unwrap();
    let (t, w, a) = (3.973159052010029, -19.06014585260367, -7.42833157463167);
    let guess =
        mechanisms::SliderCrankUnknowns::from_array([1.0172144142508899, -0.01734295000128923]);
    let options = NewtonOptions::new(3.3734342579565836e-8, 50).with_accuracy(anything);
    let near = slider.motion_near(t, &guess, &options, w, a).unwrap();
    let exact = slider.motion(t, Branch::Open, w, a).unwrap();
    let to_array = |q: &mechanisms::SliderCrankUnknowns<f64>| q.to_array();
    let slider_case = ("slider-crank", l2 + l3 + c, (w, a), [l3, 1.0]);
    within_stated(slider_case, &near.value, &exact, to_array);

    // Four-bars from guesses far off, stopped just short of their tolerances (an adversarial
    // review): each angle's error turns its own column, and the two add up, so that with the
    // carried error counted once (`κ·ρ·δ`) the velocity was 1.25 times and the acceleration
    // 1.07 times off what was stated; counted per column moved (2 here), they are within.
    let (w, a) = (1.0, 0.5);
    for (lengths, t, tolerance, guess, accuracy) in [
        (
            [
                1.0,
                0.7670523876444308,
                0.4551742507137488,
                0.40472484019481664,
            ],
            5.301396748403195,
            1.881757438561414e-9,
            [0.9466529201647218, -2.226795856115067],
            mechgen::Accuracy::required(),
        ),
        (
            [
                1.0,
                0.7489819023915032,
                0.5075369219179153,
                0.45121350131438337,
            ],
            5.221658699302826,
            8.613888324067805e-6,
            [1.1265887611391618, -2.6013111149029857],
            anything,
        ),
    ] {
        let [l1, l2, l3, l4] = lengths;
        let four_bar = mechanisms::FourBar::<f64>::new(l1, l2, l3, l4).unwrap();
        let guess = mechanisms::FourBarUnknowns::from_array(guess);
        let options = NewtonOptions::new(tolerance, 50).with_accuracy(accuracy);
        let near = four_bar.motion_near(t, &guess, &options, w, a).unwrap();
        let exact = four_bar.motion(t, Branch::Open, w, a).unwrap();
        let to_array = |q: &mechanisms::FourBarUnknowns<f64>| q.to_array();
        let case = ("four-bar", l1 + l2 + l3 + l4, (w, a), [l3, l4]);
        within_stated(case, &near.value, &exact, to_array);
    }
}

/// Asserts that `near`'s errors from `exact` are within what `near` states, far from the floor
/// (`case`: a name, the size, the input's rate and acceleration, and the unknowns' column
/// lengths, which weigh their errors as the contract does).
fn within_stated<U>(
    (what, size, (w, a), columns): (&str, f64, (f64, f64), [f64; 2]),
    near: &mechgen::Motion<U, f64>,
    exact: &mechgen::Motion<U, f64>,
    to_array: impl Fn(&U) -> [f64; 2],
) {
    // The largest error over the unknowns, each weighted by its column's length, and the
    // largest weighted value, at least `floor`.
    let error = |got: &U, want: &U| {
        let (got, want) = (to_array(got), to_array(want));
        (0..2).fold(0.0f64, |m, j| m.max((got[j] - want[j]).abs() * columns[j]))
    };
    let size_of = |want: &U, floor: f64| {
        let want = to_array(want);
        (0..2).fold(floor, |m, j| m.max((want[j] * columns[j]).abs()))
    };
    let position = error(&near.position, &exact.position) / size;
    let velocity =
        error(&near.velocity, &exact.velocity) / size_of(&exact.velocity, size * w.abs());
    let acceleration = error(&near.acceleration, &exact.acceleration)
        / size_of(&exact.acceleration, size * (w * w + a.abs()));
    let stated = near.accuracy;
    assert!(
        position <= stated.position,
        "{what}: position {position:e} vs {:e}",
        stated.position
    );
    assert!(
        velocity <= stated.velocity,
        "{what}: velocity {velocity:e} vs {:e}",
        stated.velocity
    );
    assert!(
        acceleration <= stated.acceleration,
        "{what}: acceleration {acceleration:e} vs {:e}",
        stated.acceleration
    );
    // Far from the floor: the carried error is what is stated.
    assert!(stated.velocity > 1e6 * f64::EPSILON, "{what}: {stated:?}");
}
