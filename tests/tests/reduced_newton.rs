//! Coupled loops without a closed form: Newton iterates on as few unknowns as the loops allow
//! and solves the rest in closed form inside each evaluation. For the Stephenson six-bar that
//! is `theta3` and `theta4`, with loop 2 solved for `theta5` and `theta6` (two circles
//! meeting) and loop 1's residual driven to zero.
//!
//! Checked against Newton on every unknown together (the runtime's `newton` on the
//! generated `residual` and `jacobian`), in f64 and f32: the same solutions, both loops
//! closed to rounding, no more iterations, the full Jacobian's condition; the guess's
//! assembly kept (`OtherBranch` rather than a silent switch); the fallback to Newton on every
//! unknown where the closed forms cannot close at the guess; and longer chains of closed
//! forms (two loops solved in closed form inside the iteration, a slider among them).

use mechanisms::{StephensonSixBar, StephensonSixBarUnknowns};
use mechgen::__private::{Columns, Linearisation, Orientation, newton};
use mechgen::{Branch, Error, NewtonOptions, Real, Solved, Vec2, mechanism};

/// The dimensions of the example (`mechgen_tests::examples::stephenson_six_bar`).
#[derive(Clone, Copy)]
struct Dimensions {
    l1: f64,
    l2: f64,
    l3: f64,
    bc: f64,
    cd: f64,
    beta: f64,
    l4: f64,
    l6: f64,
    /// O6 as `(x, y)`.
    o6: (f64, f64),
}

const STEPHENSON: Dimensions = Dimensions {
    l1: 100.0,
    l2: 20.0,
    l3: 117.0,
    bc: 60.0,
    cd: 63.0,
    beta: -0.97,
    l4: 52.0,
    l6: 85.0,
    o6: (189.0, -26.0),
};

fn stephenson<T: Real>() -> StephensonSixBar<T> {
    let Dimensions {
        l1,
        l2,
        l3,
        bc,
        cd,
        beta,
        l4,
        l6,
        o6: (x, y),
    } = STEPHENSON;
    let c = T::constant;
    StephensonSixBar::new(
        c(l1),
        c(l2),
        c(l3),
        [c(bc), c(cd)],
        c(beta),
        c(l4),
        c(l6),
        (c(x), c(y)),
    )
    .expect("the example's dimensions are valid")
}

/// `Σ|r|` over both loops' vectors: what the generated Newton scales its rounding floor by.
fn stephenson_scale<T: Real>() -> T {
    let Dimensions {
        l1,
        l2,
        l3,
        bc,
        cd,
        l4,
        l6,
        o6: (x, y),
        ..
    } = STEPHENSON;
    T::constant(l2 + l3 + bc + l4 + l1 + l1 + l4 + cd + l6 + x.hypot(y))
}

/// Newton on every unknown together, on a generated residual and Jacobian: what `position`
/// did before the reduction, and what it falls back to. Every unknown an angle, unless
/// `angles` says which are ([`newton_with_lengths_on`]).
fn newton_on<T: Real, const N: usize>(
    input: T,
    guess: [T; N],
    scale: T,
    residual: impl Fn(&[T; N]) -> [T; N],
    jacobian: impl Fn(&[T; N]) -> [[T; N]; N],
) -> Result<Solved<[T; N], T>, Error<T>> {
    newton_with_lengths_on([true; N], input, guess, scale, residual, jacobian)
}

/// [`newton_on`] where the unknowns `angles` marks are angles and the others lengths (which
/// Newton never takes by whole turns).
fn newton_with_lengths_on<T: Real, const N: usize>(
    angles: [bool; N],
    input: T,
    guess: [T; N],
    scale: T,
    residual: impl Fn(&[T; N]) -> [T; N],
    jacobian: impl Fn(&[T; N]) -> [[T; N]; N],
) -> Result<Solved<[T; N], T>, Error<T>> {
    newton(
        input,
        guess,
        &NewtonOptions::default(),
        Orientation::Free { angles },
        || None,
        |x: &[T; N]| Linearisation {
            residual: residual(x),
            jacobian: jacobian(x),
            scale,
            weights: [T::one(); N],
            payload: (),
            columns: Columns::FromMatrix,
        },
    )
    .map(|converged| converged.solved)
}

/// Two runs of Newton on every unknown: the same outcome, the same iterations (give or take
/// the last, which polishes a residual at the floor but not exactly zero), the same solution to
/// rounding (the generated one takes its sines and cosines from `Turning`s).
#[track_caller]
fn same_newton<const N: usize>(
    what: &str,
    got: Result<Solved<[f64; N], f64>, Error<f64>>,
    want: Result<Solved<[f64; N], f64>, Error<f64>>,
) {
    match (got, want) {
        (Ok(got), Ok(want)) => {
            assert!(got.iterations.abs_diff(want.iterations) <= 1, "{what}");
            for (g, w) in got.value.iter().zip(want.value) {
                assert!((g - w).abs() < 1e-12, "{what}: {g} vs {w}");
            }
            assert!((got.condition - want.condition).abs() < 1e-12 * want.condition);
        }
        (got, want) => assert_eq!(got.err(), want.err(), "{what}"),
    }
}

fn newton_on_all<T: Real>(
    linkage: &StephensonSixBar<T>,
    input: T,
    guess: [T; 4],
) -> Result<Solved<[T; 4], T>, Error<T>> {
    newton_on(
        input,
        guess,
        stephenson_scale(),
        |x| linkage.residual(input, &(*x).into()),
        |x| linkage.jacobian(input, &(*x).into()),
    )
}

/// Over a full turn in 1° steps, each guess predicted from the last solution's velocity, in
/// f64 and f32: the reduced `position` (and `motion_near`) agree with Newton on every
/// unknown from the same guess, close both loops to rounding, take no more iterations, and
/// report the full Jacobian's condition.
fn reduced_position_matches_newton_on_every_unknown<T: Real>() {
    let linkage = stephenson::<T>();
    let options = NewtonOptions::default();
    let start = mechgen_tests::examples::stephenson_six_bar().1.to_array();
    let mut q = linkage
        .position(T::zero(), &start.map(T::constant).into(), &options)
        .expect("the example assembles at 0°")
        .value;
    let (w, a) = (T::constant(10.0), T::constant(2.0));
    let step = T::constant(1f64.to_radians());
    let eps = T::epsilon();
    let scale = stephenson_scale::<T>();
    let (mut reduced_iterations, mut full_iterations) = (0, 0);
    for degree in 0..=360 {
        let t = T::constant(f64::from(degree).to_radians());
        // Where `q` was solved: a degree back, or the start at 0°.
        let solved_at = if degree == 0 { t } else { t - step };
        let rates = linkage.velocity(solved_at, &q, w).unwrap().to_array();
        let guess: [T; 4] = std::array::from_fn(|i| q.to_array()[i] + rates[i] / w * step);
        let guess = if degree == 0 { q.to_array() } else { guess };
        let solved = linkage.position(t, &guess.into(), &options).unwrap();
        let full = newton_on_all(&linkage, t, guess).unwrap();
        q = solved.value;

        let residual = linkage.residual(t, &q);
        let worst = residual.iter().fold(T::zero(), |m, r| m.max(r.abs()));
        assert!(
            worst <= T::constant(64.0) * eps * scale,
            "{degree}°: loops close to {worst}"
        );
        assert!(solved.residual_norm <= T::constant(16.0) * eps * scale);
        let kappa = linkage.condition(t, &q);
        assert!(
            (solved.condition - kappa).abs() <= T::constant(64.0) * eps * kappa,
            "{degree}°: condition {} vs the full Jacobian's {kappa}",
            solved.condition
        );
        // Both are within rounding of the root: the angles agree to what the residual floor
        // allows, about 16 ε Σ|r| over the shortest link, times the condition.
        let allowed = T::constant(64.0) * eps * scale / T::constant(20.0) * kappa;
        for (got, want) in q.to_array().iter().zip(full.value) {
            assert!(
                (*got - want).abs() <= allowed,
                "{degree}°: {got} vs Newton on every unknown {want}"
            );
        }
        // Give or take the last step, which polishes a residual that is at the floor but
        // not exactly zero (where the two differ in rounding).
        assert!(
            solved.iterations <= full.iterations + 1,
            "{degree}°: {} iterations, Newton on every unknown {}",
            solved.iterations,
            full.iterations
        );
        reduced_iterations += solved.iterations;
        full_iterations += full.iterations;

        let near = linkage
            .motion_near(t, &guess.into(), &options, w, a)
            .unwrap();
        assert_eq!(near.value.position, q, "{degree}°: the same Newton solve");
        assert_eq!(
            (near.iterations, near.residual_norm, near.condition),
            (solved.iterations, solved.residual_norm, solved.condition)
        );
        let at = linkage.motion_at(t, &q, w, a).unwrap();
        let pairs = [
            (near.value.velocity, at.velocity, w),
            (near.value.acceleration, at.acceleration, w * w),
        ];
        for (got, want, size) in pairs {
            for (g, v) in got.to_array().into_iter().zip(want.to_array()) {
                assert!(
                    (g - v).abs() <= T::constant(64.0) * eps * size * kappa * kappa,
                    "{degree}°: rate {g} vs motion_at's {v}"
                );
            }
        }
    }
    // No more iterations in all, give or take a polishing step in a hundred.
    assert!(
        reduced_iterations <= full_iterations + full_iterations / 100,
        "{reduced_iterations} vs {full_iterations}"
    );
}

#[test]
fn stephenson_reduced_position_matches_newton_on_every_unknown_over_a_turn() {
    reduced_position_matches_newton_on_every_unknown::<f64>();
    reduced_position_matches_newton_on_every_unknown::<f32>();
}

/// The other way loop 2 closes for the same `theta4`: the Stephenson's loop 2 as Chace's
/// two-angle case `K + e^{iθ5}·w1 + e^{iθ6}·w2 = 0`, with its other sign.
fn other_branch_of_loop_2(q: StephensonSixBarUnknowns<f64>) -> StephensonSixBarUnknowns<f64> {
    let Dimensions {
        l1,
        cd,
        beta,
        l4,
        l6,
        o6: (x, y),
        ..
    } = STEPHENSON;
    let k = Vec2::new(l1 + l4 * q.theta4.cos() - x, l4 * q.theta4.sin() - y);
    let w1 = Vec2::new(cd * beta.cos(), cd * beta.sin());
    let w2 = Vec2::new(-l6, 0.0);
    let sign = mechgen::closed::two_angles_sign(k, w1, q.theta5);
    let flipped = Branch::from_sign(sign).other().sign::<f64>();
    let (theta5, theta6, ..) = mechgen::closed::two_angles(k, w1, w2, flipped).unwrap();
    StephensonSixBarUnknowns {
        theta5,
        theta6,
        ..q
    }
}

#[test]
fn stephenson_started_near_another_assembly_is_other_branch() {
    let (linkage, guess) = mechgen_tests::examples::stephenson_six_bar();
    let options = NewtonOptions::default();
    let q = linkage.position(0.0, &guess, &options).unwrap().value;
    // The drawn assembly with loop 2 closed the other way: Newton keeps that branch of loop
    // 2, and the root it finds for it has the other orientation.
    let flipped = other_branch_of_loop_2(q);
    assert_eq!(
        linkage.position(0.0, &flipped, &options),
        Err(Error::OtherBranch)
    );
    assert!(matches!(
        linkage.motion_near(0.0, &flipped, &options, 1.0, 0.0),
        Err(Error::OtherBranch)
    ));

    // Over the turn, from every such guess: never the drawn assembly back, and any solution
    // closes both loops on loop 2's branch at the guess.
    let mut q = q;
    for degree in 0..360 {
        let t = f64::from(degree).to_radians();
        q = linkage.position(t, &q, &options).unwrap().value;
        let flipped = other_branch_of_loop_2(q);
        match linkage.position(t, &flipped, &options) {
            Err(Error::OtherBranch) => {}
            Ok(other) => {
                let other = other.value;
                assert!(
                    (other.theta3 - q.theta3).abs() > 0.1,
                    "{degree}°: {other:?}"
                );
                assert!(linkage.residual(t, &other).iter().all(|r| r.abs() < 1e-11));
                let back = other_branch_of_loop_2(other);
                assert!(
                    (back.theta5 - q.theta5).abs() > 1e-3 || (back.theta4 - q.theta4).abs() > 1e-3,
                    "{degree}°: loop 2 switched branch"
                );
            }
            Err(error) => panic!("{degree}°: {error}"),
        }
    }
}

#[test]
fn a_step_the_closed_forms_carry_to_another_assembly_is_not_returned() {
    // A Stephenson whose ternary side C D is 1/5000 of the rest (the edge run's case 5670 of
    // seed 7): loop 2 nearly fixes theta4 by itself, so given theta4 its closed form turns
    // theta5 some 5000 times as fast, and one reduced step from this guess (the root's
    // own, within its Kantorovich ball) carried theta5 from 0.53 to 2.28 and theta3 from
    // 1.87 to 0.94: loop 1's other assembly, of the same orientation. Newton on every
    // unknown from the guess finds the guess's root; so must `position` and `motion_near`.
    let linkage = StephensonSixBar::<f64>::new(
        2.5186588e-23,
        1.454942e-19,
        7.1964074e-20,
        [4.200979e-20, 2.6639896e-23],
        1.4604609,
        2.1684043e-19,
        1.6516199e-19,
        (1.9338697e-19, 1.055728e-20),
    )
    .unwrap();
    let theta2 = 0.551801;
    let start = [
        1.8680778741836548,
        0.8754220604896545,
        0.5342891216278076,
        1.9063968658447266,
    ];
    let guess = StephensonSixBarUnknowns::from_array(start);
    let options = NewtonOptions::default();
    // Newton on every unknown, its floor at the loops' own size (the sum of their lengths).
    let scale = 1.1e-18;
    let truth = newton_on(
        theta2,
        start,
        scale,
        |x| linkage.residual(theta2, &(*x).into()),
        |x| linkage.jacobian(theta2, &(*x).into()),
    )
    .unwrap()
    .value;
    assert!((truth[0] - 1.868078).abs() < 1e-6 && (truth[2] - 0.534282).abs() < 1e-6);
    let solved = linkage.position(theta2, &guess, &options).unwrap().value;
    for (got, want) in solved.to_array().iter().zip(truth) {
        assert!((got - want).abs() < 1e-12, "{solved:?} against {truth:?}");
    }
    let near = linkage
        .motion_near(theta2, &guess, &options, 1.0, 0.0)
        .unwrap()
        .value;
    assert_eq!(near.position, solved);
}

#[test]
fn a_turn_of_the_reduced_orientation_is_left_to_newton_on_every_unknown() {
    // The edge run's case 28819 of seed 7 with every length × 64532.5 and rounded to f32: C D
    // is 1/3000 of the rest, and the reduced iteration's own Jacobian turns its orientation
    // on the way from this guess (within the root's Kantorovich ball) where the loops' does
    // not. Newton on every unknown keeps the orientation and finds the root, in f32 and f64.
    let dimensions: [f64; 10] = [
        2.3004728e27,
        2.570729e29,
        1.0207907e31,
        2.001992e31,
        3.2265903e27,
        1.7978873,
        1.1481228e31,
        3.9806113e30,
        9.0793043e30,
        -9.2291507e30,
    ];
    let factor = 6.4532511296945464e4;
    fn check<T: Real>(dimensions: [f64; 10], factor: f64) {
        let length = |i: usize| T::constant(f64::from((dimensions[i] * factor) as f32));
        let linkage = StephensonSixBar::<T>::new(
            length(0),
            length(1),
            length(2),
            [length(3), length(4)],
            T::constant(f64::from(dimensions[5] as f32)),
            length(6),
            length(7),
            (length(8), length(9)),
        )
        .unwrap();
        let start = [
            1.837106704711914,
            -0.4888606667518616,
            -0.8594669699668884,
            1.301087737083435,
        ]
        .map(T::constant);
        let theta2 = T::constant(f64::from(-2.8372917f32));
        let solved = linkage
            .position(
                theta2,
                &StephensonSixBarUnknowns::from_array(start),
                &NewtonOptions::default(),
            )
            .unwrap()
            .value
            .to_array();
        // The root: theta4 -0.489155, 3e-4 from the guess.
        let root = [1.8371066, -0.4891546, -0.8595321, 1.3013234];
        for (got, want) in solved.iter().zip(root) {
            assert!(
                (*got - T::constant(want)).abs() < T::constant(1e-5),
                "{solved:?}"
            );
        }
    }
    check::<f64>(dimensions, factor);
    check::<f32>(dimensions, factor);
}

mechanism! {
    /// The Stephenson six-bar with a shorter output rocker (60 rather than 85): loop 2 now
    /// cannot close where the rocker O4 C turns C more than `cd + l6` from O6.
    pub struct ShortRocker {
        params: l1, l2, l3, bc, cd, beta: angle, l4, l6, g, phi: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, theta5: angle, theta6: angle;
        loop: l2 @ theta2 + l3 @ theta3 + bc @ theta5 - l4 @ theta4 - l1 @ 0;
        loop: l1 @ 0 + l4 @ theta4 + cd @ (theta5 + beta) - l6 @ theta6 - g @ phi;
        generate: position, velocity, acceleration;
    }
}

#[test]
fn a_guess_where_the_closed_forms_cannot_close_falls_back_to_newton_on_every_unknown() {
    let Dimensions {
        l1,
        l2,
        l3,
        bc,
        cd,
        beta,
        l4,
        o6: (x, y),
        ..
    } = STEPHENSON;
    let l6 = 60.0;
    let linkage = ShortRocker {
        l1,
        l2,
        l3,
        bc,
        cd,
        beta,
        l4,
        l6,
        g: x.hypot(y),
        phi: y.atan2(x),
    };
    let scale = l2 + l3 + bc + l4 + l1 + l1 + l4 + cd + l6 + x.hypot(y);
    let options = NewtonOptions::default();
    let (_, guess) = mechgen_tests::examples::stephenson_six_bar();
    let q = linkage
        .position(0.0, &guess.to_array().into(), &options)
        .unwrap()
        .value;
    assert!(linkage.residual(0.0, &q).iter().all(|r| r.abs() < 1e-11));
    // Guesses with the rocker turned on until C is beyond loop 2's reach: from those,
    // `position` is Newton on every unknown, to the bit.
    let reach = |theta4: f64| {
        let c = Vec2::new(l1 + l4 * theta4.cos(), l4 * theta4.sin());
        (c - Vec2::new(x, y)).norm()
    };
    let mut converged = 0;
    for tenth in 1..=20 {
        let theta4 = q.theta4 + f64::from(tenth) / 10.0;
        if reach(theta4) <= cd + l6 {
            continue;
        }
        let bad = ShortRockerUnknowns { theta4, ..q };
        let got = linkage.position(0.0, &bad, &options);
        let want = newton_on(
            0.0,
            bad.to_array(),
            scale,
            |x| linkage.residual(0.0, &(*x).into()),
            |x| linkage.jacobian(0.0, &(*x).into()),
        );
        same_newton(
            &format!("theta4 {theta4}"),
            got.map(|s| s.map(|v| v.to_array())),
            want,
        );
        if let Ok(solved) = want {
            converged += 1;
            assert!(
                linkage
                    .residual(0.0, &solved.value.into())
                    .iter()
                    .all(|r| r.abs() < 1e-11)
            );
        }
        let near = linkage.motion_near(0.0, &bad, &options, 1.0, 0.0);
        assert_eq!(
            near.map(|s| s.value.position),
            got.map(|s| s.value),
            "theta4 {theta4}"
        );
    }
    assert!(converged > 0, "no guess beyond reach converged");
}

mechanism! {
    /// The Stephenson six-bar with its output rocker O6 D extended by `l6b` at `gamma` to E,
    /// driving one more dyad E F O8: coupler `l7`, rocker `l8` from O8 = `h @ psi`. Newton
    /// iterates on `theta3` and `theta4` with loop 2 in closed form; loop 3, which loop 1
    /// does not read, is solved once at the solution.
    pub struct EightBar {
        params: l1, l2, l3, bc, cd, beta: angle, l4, l6, g, phi: angle,
            l6b, gamma: angle, l7, l8, h, psi: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, theta5: angle, theta6: angle,
            theta7: angle, theta8: angle;
        loop: l2 @ theta2 + l3 @ theta3 + bc @ theta5 - l4 @ theta4 - l1 @ 0;
        loop: l1 @ 0 + l4 @ theta4 + cd @ (theta5 + beta) - l6 @ theta6 - g @ phi;
        loop: g @ phi + l6 @ theta6 + l6b @ (theta6 + gamma) + l7 @ theta7 - l8 @ theta8
            - h @ psi;
        generate: position, velocity, acceleration;
    }
}

mechanism! {
    /// The Stephenson six-bar with D on a slider along the line through `h @ (alpha + pi/2)`
    /// in the direction `alpha`, instead of on a rocker: Newton iterates on `theta3` and
    /// `theta4`, loop 2 gives `s` and `theta5` (a line meeting a circle).
    pub struct SliderSixBar {
        params: l1, l2, l3, bc, cd, beta: angle, l4, alpha: angle, h;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, theta5: angle, s: length;
        loop: l2 @ theta2 + l3 @ theta3 + bc @ theta5 - l4 @ theta4 - l1 @ 0;
        loop: l1 @ 0 + l4 @ theta4 + cd @ (theta5 + beta) - s @ alpha - h @ (alpha + pi / 2);
        generate: position, velocity, acceleration;
    }
}

/// Sweeps `position` and `motion_near` from `start` in 1° steps with a velocity predictor
/// for `degrees`, checking each solution against Newton on every unknown from the same
/// guess (the unknowns `angles` marks taken as angles), the loops' closure, and the rates
/// against `motion_at`'s. Returns how many steps solved.
macro_rules! check_sweep {
    ($linkage:expr, $unknowns:ident, $n:literal, $angles:expr, $scale:expr, $start:expr, $degrees:expr) => {{
        let linkage = &$linkage;
        let options = NewtonOptions::default();
        let step = 1f64.to_radians();
        let mut q: [f64; $n] = $start;
        let mut solved_steps = 0;
        for degree in 0..$degrees {
            let t = f64::from(degree) * step;
            // Where `q` was solved: a degree back, or the start at 0°.
            let solved_at = if degree == 0 { t } else { t - step };
            let rates = linkage
                .velocity(solved_at, &$unknowns::from_array(q), 1.0)
                .unwrap();
            let guess: [f64; $n] = std::array::from_fn(|i| q[i] + rates.to_array()[i] * step);
            let solved = linkage
                .position(t, &$unknowns::from_array(guess), &options)
                .unwrap_or_else(|e| panic!("{degree}°: {e}"));
            let full = newton_with_lengths_on(
                $angles,
                t,
                guess,
                $scale,
                |x| linkage.residual(t, &$unknowns::from_array(*x)),
                |x| linkage.jacobian(t, &$unknowns::from_array(*x)),
            )
            .unwrap();
            q = solved.value.to_array();
            let kappa = linkage.condition(t, &solved.value);
            assert!((solved.condition - kappa).abs() <= 1e-12 * kappa);
            for (got, want) in q.iter().zip(full.value) {
                assert!((got - want).abs() < 1e-9, "{degree}°: {got} vs {want}");
            }
            // Give or take the last step, which polishes a residual at the floor but not
            // exactly zero (where the two differ in rounding).
            assert!(solved.iterations <= full.iterations + 1, "{degree}°");
            let residual = linkage.residual(t, &solved.value);
            assert!(
                residual
                    .iter()
                    .all(|r| r.abs() < 64.0 * f64::EPSILON * $scale)
            );
            let near = linkage
                .motion_near(t, &$unknowns::from_array(guess), &options, 3.0, 1.0)
                .unwrap();
            assert_eq!(near.value.position, solved.value);
            let at = linkage.motion_at(t, &solved.value, 3.0, 1.0).unwrap();
            let pairs = [
                (near.value.velocity, at.velocity, 3.0),
                (near.value.acceleration, at.acceleration, 9.0),
            ];
            for (got, want, size) in pairs {
                for (g, v) in got.to_array().into_iter().zip(want.to_array()) {
                    assert!((g - v).abs() <= 1e-12 * size * kappa * kappa, "{degree}°");
                }
            }
            solved_steps += 1;
        }
        solved_steps
    }};
}

#[test]
fn a_loop_the_residual_does_not_read_is_solved_once_after_the_iteration() {
    let Dimensions {
        l1,
        l2,
        l3,
        bc,
        cd,
        beta,
        l4,
        l6,
        o6: (x, y),
    } = STEPHENSON;
    let linkage = EightBar {
        l1,
        l2,
        l3,
        bc,
        cd,
        beta,
        l4,
        l6,
        g: x.hypot(y),
        phi: y.atan2(x),
        l6b: 40.0,
        gamma: 0.5,
        l7: 70.0,
        l8: 60.0,
        h: 240f64.hypot(60.0),
        psi: 60f64.atan2(240.0),
    };
    let scale = l2
        + l3
        + bc
        + l4
        + l1
        + l1
        + l4
        + cd
        + l6
        + x.hypot(y)
        + x.hypot(y)
        + l6
        + 40.0
        + 70.0
        + 60.0
        + 240f64.hypot(60.0);
    // The six-bar's solution, and the third loop closed by circles from there.
    let (six_bar, guess) = mechgen_tests::examples::stephenson_six_bar();
    let q = six_bar
        .position(0.0, &guess, &NewtonOptions::default())
        .unwrap()
        .value;
    let k = Vec2::new(
        x + l6 * q.theta6.cos() - 240.0,
        y + l6 * q.theta6.sin() - 60.0,
    ) + Vec2::new(40.0 * (q.theta6 + 0.5).cos(), 40.0 * (q.theta6 + 0.5).sin());
    let (theta7, theta8, ..) =
        mechgen::closed::two_angles(k, Vec2::new(70.0, 0.0), Vec2::new(-60.0, 0.0), 1.0).unwrap();
    let start = [q.theta3, q.theta4, q.theta5, q.theta6, theta7, theta8];
    let solved = check_sweep!(linkage, EightBarUnknowns, 6, [true; 6], scale, start, 361);
    assert_eq!(solved, 361);

    // Where loop 3 cannot close at the solution, the mechanism cannot be assembled.
    let short = EightBar { l7: 5.0, ..linkage };
    let guess = EightBarUnknowns::from_array(start);
    assert_eq!(
        short.position(0.0, &guess, &NewtonOptions::default()),
        Err(Error::CannotAssemble { input: 0.0 })
    );
}

mechanism! {
    /// Three loops chained so that the residual reads a closed form's unknown through
    /// another: given `theta4`, loop B gives `theta5` and `theta6`, then loop C gives
    /// `theta7` and `theta8`, and loop A (with `theta3`, `theta4`, `theta8`) is the residual.
    pub struct Chained {
        params: l2, a3, a4, a8, ga, pa: angle, b4, b5, b6, gb, pb: angle,
            c6, c7, c8, gc, pc: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, theta5: angle, theta6: angle,
            theta7: angle, theta8: angle;
        loop: l2 @ theta2 + a3 @ theta3 - a4 @ theta4 + a8 @ theta8 - ga @ pa;
        loop: b4 @ theta4 + b5 @ theta5 - b6 @ theta6 - gb @ pb;
        loop: c6 @ theta6 + c7 @ theta7 - c8 @ theta8 - gc @ pc;
        generate: position, velocity, acceleration;
    }
}

#[test]
fn two_loops_in_closed_form_inside_the_iteration() {
    // Lengths and a configuration at theta2 = 0, with each loop's ground vector the one
    // that closes it there.
    let q = [0.3, 1.2, 0.2, 1.9, -0.4, 0.9];
    let e = |r: f64, angle: f64| Vec2::new(r * angle.cos(), r * angle.sin());
    let [t3, t4, t5, t6, t7, t8] = q;
    let ground_a = e(20.0, 0.0) + e(100.0, t3) - e(60.0, t4) + e(40.0, t8);
    let ground_b = e(60.0, t4) + e(90.0, t5) - e(70.0, t6);
    let ground_c = e(50.0, t6) + e(80.0, t7) - e(60.0, t8);
    let linkage = Chained {
        l2: 20.0,
        a3: 100.0,
        a4: 60.0,
        a8: 40.0,
        ga: ground_a.norm(),
        pa: ground_a.angle(),
        b4: 60.0,
        b5: 90.0,
        b6: 70.0,
        gb: ground_b.norm(),
        pb: ground_b.angle(),
        c6: 50.0,
        c7: 80.0,
        c8: 60.0,
        gc: ground_c.norm(),
        pc: ground_c.angle(),
    };
    let scale = 20.0
        + 100.0
        + 60.0
        + 40.0
        + ground_a.norm()
        + 60.0
        + 90.0
        + 70.0
        + ground_b.norm()
        + 50.0
        + 80.0
        + 60.0
        + ground_c.norm();
    assert!(
        linkage
            .residual(0.0, &q.into())
            .iter()
            .all(|r| r.abs() < 1e-12)
    );
    let solved = check_sweep!(linkage, ChainedUnknowns, 6, [true; 6], scale, q, 30);
    assert_eq!(solved, 30);
}

#[test]
fn a_slider_solved_in_closed_form_inside_the_iteration() {
    let Dimensions {
        l1,
        l2,
        l3,
        bc,
        cd,
        beta,
        l4,
        ..
    } = STEPHENSON;
    // D slides along y = 58.5, where the six-bar's rocker puts it at 0°.
    let (alpha, h) = (0.0, 58.5);
    let linkage = SliderSixBar {
        l1,
        l2,
        l3,
        bc,
        cd,
        beta,
        l4,
        alpha,
        h,
    };
    let scale = l2 + l3 + bc + l4 + l1 + l1 + l4 + cd + 200.0 + h;
    let (six_bar, guess) = mechgen_tests::examples::stephenson_six_bar();
    let q = six_bar
        .position(0.0, &guess, &NewtonOptions::default())
        .unwrap()
        .value;
    let d = six_bar.points(0.0, &q).unwrap().d;
    let guess = SliderSixBarUnknowns {
        theta3: q.theta3,
        theta4: q.theta4,
        theta5: q.theta5,
        s: d.x,
    };
    let start = linkage
        .position(0.0, &guess, &NewtonOptions::default())
        .unwrap()
        .value
        .to_array();
    let solved = check_sweep!(
        linkage,
        SliderSixBarUnknowns,
        4,
        [true, true, true, false],
        scale,
        start,
        30
    );
    assert_eq!(solved, 30);
}

mechanism! {
    /// Coupled loops in which `p`, `q` and `r` turn their vectors at twice their angle: none
    /// of them can come out of a closed form, and no pair of unknowns leaves loops that do,
    /// so Newton iterates on all four.
    pub struct Doubled {
        params: l2, a, b, c, ga, pa: angle, d, e, f, gb, pb: angle;
        input: theta2: angle;
        unknowns: p: angle, q: angle, r: angle, s: angle;
        loop: l2 @ theta2 + a @ (2 * p) + b @ (2 * q) - c @ r - ga @ pa;
        loop: d @ (2 * q) + e @ (2 * r) - f @ s - gb @ pb;
        generate: position, velocity, acceleration;
    }
}

#[test]
fn without_a_reduction_newton_iterates_on_every_unknown() {
    let q = [0.4, 0.9, 1.3, -0.2];
    let e = |r: f64, angle: f64| Vec2::new(r * angle.cos(), r * angle.sin());
    let [p, q2, r, s] = q;
    let ground_a = e(20.0, 0.0) + e(80.0, 2.0 * p) + e(60.0, 2.0 * q2) - e(70.0, r);
    let ground_b = e(50.0, 2.0 * q2) + e(90.0, 2.0 * r) - e(75.0, s);
    let linkage = Doubled {
        l2: 20.0,
        a: 80.0,
        b: 60.0,
        c: 70.0,
        ga: ground_a.norm(),
        pa: ground_a.angle(),
        d: 50.0,
        e: 90.0,
        f: 75.0,
        gb: ground_b.norm(),
        pb: ground_b.angle(),
    };
    let scale = 20.0 + 80.0 + 60.0 + 70.0 + ground_a.norm() + 50.0 + 90.0 + 75.0 + ground_b.norm();
    for degree in [2, 5, 10] {
        let t = f64::from(degree).to_radians();
        let got = linkage
            .position(t, &q.into(), &NewtonOptions::default())
            .map(|s| s.map(|v| v.to_array()));
        let want = newton_on(
            t,
            q,
            scale,
            |x| linkage.residual(t, &(*x).into()),
            |x| linkage.jacobian(t, &(*x).into()),
        );
        assert!(want.is_ok(), "{degree}°");
        same_newton(&format!("{degree}°"), got, want);
    }
}
