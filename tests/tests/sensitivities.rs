//! Issue 15's generated sensitivities: `∂q/∂p` and `dP/dp` at a solved position, against
//! central differences of the closed form (each dimension moved by ±h, the linkage assembled
//! again), on the seeds' Example 1 with a coupler point, on both branches; against the
//! multiple-precision oracle, on ordinary four-bars and at the edges (link ratios to 1e8,
//! sizes to 1e±200, near toggles), where each `Ok` keeps the velocity's stated accuracy.

use mechanisms::FourBar;
use mechgen::{Branch, Error};

/// Example 1's lengths, and a coupler point 100 from A at 30° from A B.
const DIMENSIONS: [f64; 6] = [180.0, 80.0, 200.0, 150.0, 100.0, 0.5235987755982988];

fn linkage(d: [f64; 6]) -> FourBar<f64> {
    FourBar::new(d[0], d[1], d[2], d[3])
        .and_then(|l| l.with_coupler_point(d[4], d[5]))
        .expect("valid dimensions")
}

/// `[θ3, θ4, P.x, P.y]` of the linkage with dimensions `d`.
fn solved(d: [f64; 6], theta2: f64, branch: Branch) -> [f64; 4] {
    let l = linkage(d);
    let q = l.assemble(theta2, branch).expect("assembles");
    let p = l.points(theta2, &q).expect("points").coupler_point;
    [q.theta3, q.theta4, p.x, p.y]
}

/// The derivatives of `[θ3, θ4, P.x, P.y]` with respect to each dimension, by central
/// differences with a step of 1e-5 relative (angles 1e-5 rad): truncation about h², 1e-10.
fn differences(theta2: f64, branch: Branch) -> [[f64; 4]; 6] {
    std::array::from_fn(|k| {
        let h = 1e-5 * DIMENSIONS[k].abs().max(1.0);
        let (mut up, mut down) = (DIMENSIONS, DIMENSIONS);
        up[k] += h;
        down[k] -= h;
        let (a, b) = (solved(up, theta2, branch), solved(down, theta2, branch));
        std::array::from_fn(|i| (a[i] - b[i]) / (2.0 * h))
    })
}

#[test]
fn sensitivities_agree_with_central_differences() {
    for branch in [Branch::Open, Branch::Crossed] {
        for degrees in [0.0, 45.0, 60.0, 137.0, 200.0, 300.0] {
            let theta2 = f64::to_radians(degrees);
            let l = linkage(DIMENSIONS);
            let q = l.assemble(theta2, branch).unwrap();
            let s = l.sensitivities(theta2, &q).unwrap();
            let p = l.point_sensitivities(theta2, &q).unwrap();
            let generated: [[f64; 4]; 6] = [
                (s.l1, p.l1),
                (s.l2, p.l2),
                (s.l3, p.l3),
                (s.l4, p.l4),
                (s.a, p.a),
                (s.delta, p.delta),
            ]
            .map(|(s, p)| [s.theta3, s.theta4, p.coupler_point.x, p.coupler_point.y]);
            let expected = differences(theta2, branch);
            for (k, (g, e)) in generated.iter().zip(&expected).enumerate() {
                for i in 0..4 {
                    // Angles per length are about 1e-2, points about 1: differences good to
                    // about 1e-10 of those.
                    let scale = e[i].abs().max(1e-2);
                    assert!(
                        (g[i] - e[i]).abs() <= 1e-8 * scale,
                        "{branch:?} at {degrees}°, dimension {k}, output {i}: {} against {}",
                        g[i],
                        e[i]
                    );
                }
            }
            // The coupler point's own dimensions move no unknown.
            assert_eq!(
                (s.a.theta3, s.a.theta4, s.delta.theta3, s.delta.theta4),
                (0.0, 0.0, 0.0, 0.0)
            );
        }
    }
}

/// Every length times k moves each angle by nothing and each point by its position over k
/// (Euler's theorem for a function homogeneous of degree 1: Σ l·∂P/∂l = P, Σ l·∂θ/∂l = 0).
#[test]
fn sensitivities_to_the_lengths_sum_to_the_scaling() {
    let l = linkage(DIMENSIONS);
    let theta2 = 1.1;
    let q = l.assemble(theta2, Branch::Open).unwrap();
    let s = l.sensitivities(theta2, &q).unwrap();
    let p = l.point_sensitivities(theta2, &q).unwrap();
    let position = l.points(theta2, &q).unwrap();
    let [l1, l2, l3, l4, a, _] = DIMENSIONS;
    let angle = |f: fn(&mechanisms::FourBarUnknowns<f64>) -> f64| {
        l1 * f(&s.l1) + l2 * f(&s.l2) + l3 * f(&s.l3) + l4 * f(&s.l4) + a * f(&s.a)
    };
    assert!(angle(|u| u.theta3).abs() < 1e-14);
    assert!(angle(|u| u.theta4).abs() < 1e-14);
    for (moved, at) in [
        (
            [p.l1, p.l2, p.l3, p.l4, p.a].map(|x| x.rocker_pin),
            position.rocker_pin,
        ),
        (
            [p.l1, p.l2, p.l3, p.l4, p.a].map(|x| x.coupler_point),
            position.coupler_point,
        ),
    ] {
        let lengths = [l1, l2, l3, l4, a];
        let x: f64 = moved.iter().zip(lengths).map(|(v, l)| v.x * l).sum();
        let y: f64 = moved.iter().zip(lengths).map(|(v, l)| v.y * l).sum();
        assert!(
            (x - at.x).abs() < 1e-12 * at.x.abs().max(1.0),
            "{x} against {}",
            at.x
        );
        assert!(
            (y - at.y).abs() < 1e-12 * at.y.abs().max(1.0),
            "{y} against {}",
            at.y
        );
    }
}

/// At a toggle the sensitivities are unbounded: `Singular`, as for the velocity.
#[test]
fn sensitivities_at_a_toggle_are_singular() {
    // A crank-rocker whose coupler and rocker fold: θ2 at the limit of a rocker-crank.
    let l = FourBar::new(180.0, 150.0, 200.0, 80.0).unwrap();
    let limit = l.limit_angles().folded.unwrap();
    let q = l.assemble(limit, Branch::Open).unwrap();
    match l.sensitivities(limit, &q) {
        Err(Error::Singular { .. } | Error::Inaccurate { .. }) => {}
        other => panic!("expected Singular or Inaccurate at a toggle, got {other:?}"),
    }
    assert!(l.sensitivities(f64::NAN, &q).is_err());
}

/// The same in f32, to its precision: the generated code is generic over the float.
#[test]
fn f32_sensitivities_agree_with_f64() {
    let d = DIMENSIONS;
    let l64 = linkage(d);
    let l32 = FourBar::<f32>::new(d[0] as f32, d[1] as f32, d[2] as f32, d[3] as f32)
        .and_then(|l| l.with_coupler_point(d[4] as f32, d[5] as f32))
        .unwrap();
    for degrees in [10.0f64, 95.0, 250.0] {
        let theta2 = degrees.to_radians();
        let q64 = l64.assemble(theta2, Branch::Open).unwrap();
        let q32 = l32.assemble(theta2 as f32, Branch::Open).unwrap();
        let (s64, s32) = (
            l64.point_sensitivities(theta2, &q64).unwrap(),
            l32.point_sensitivities(theta2 as f32, &q32).unwrap(),
        );
        for (a, b) in [
            (s64.l1, s32.l1),
            (s64.l2, s32.l2),
            (s64.l3, s32.l3),
            (s64.l4, s32.l4),
            (s64.a, s32.a),
            (s64.delta, s32.delta),
        ] {
            let (a, b) = (a.coupler_point, b.coupler_point);
            let size = a.x.hypot(a.y).max(1e-2);
            assert!(
                (a.x - f64::from(b.x)).abs() <= 1e-4 * size,
                "{a:?} against {b:?}"
            );
            assert!(
                (a.y - f64::from(b.y)).abs() <= 1e-4 * size,
                "{a:?} against {b:?}"
            );
        }
    }
}

/// Issue 15's tolerance analysis against the nonlinear model: every corner of the tolerance
/// box (where the worst case lies) and Monte Carlo with each dimension's error normal at 3σ =
/// its tolerance, on Example 1 with ±0.1 mm on every length and ±0.1° on the coupler point's
/// angle, over a turn.
#[test]
fn tolerance_analysis_agrees_with_the_nonlinear_model() {
    use mechanisms::FourBarTolerances;
    let l = linkage(DIMENSIONS);
    let tolerances = FourBarTolerances {
        angle: 0.1f64.to_radians(),
        ..FourBarTolerances::lengths(0.1)
    };
    for degrees in (0..360).step_by(30) {
        let theta2 = f64::from(degrees).to_radians();
        let linear = l.tolerance(theta2, Branch::Open, &tolerances).unwrap();
        let corners = l.corners(theta2, Branch::Open, &tolerances).unwrap();
        assert_eq!((corners.assembled, corners.failed), (64, 0));
        // First order: the nonlinear worst corner within 2% of the linear worst case (the
        // second-order terms are about t/|toggle distance| of the first).
        for (nonlinear, first_order) in [
            (corners.output_largest, linear.output.worst_case),
            (
                corners.coupler_point_largest,
                linear.coupler_point.worst_case,
            ),
        ] {
            assert!(
                (nonlinear / first_order - 1.0).abs() < 0.02,
                "{degrees}°: corners {nonlinear} against {first_order}"
            );
        }
        // The root-sum-square stack-up over 3 is the standard deviation of normal errors at
        // 3σ: 20000 samples estimate it to about 0.5%.
        let sampled = l
            .monte_carlo(
                theta2,
                Branch::Open,
                &tolerances,
                20_000,
                u64::from(degrees as u32),
            )
            .unwrap();
        assert_eq!(sampled.failed, 0);
        for (rms, stack) in [
            (sampled.output_rms, linear.output.root_sum_square),
            (
                sampled.coupler_point_rms,
                linear.coupler_point.root_sum_square,
            ),
        ] {
            assert!(
                (rms / (stack / 3.0) - 1.0).abs() < 0.03,
                "{degrees}°: Monte Carlo {rms} against {}",
                stack / 3.0
            );
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        cases: 300,
        failure_persistence: None,
        ..proptest::prelude::ProptestConfig::default()
    })]

    /// On random four-bars (lengths 1 to 10, a coupler point, an input anywhere the linkage
    /// reaches with condition below 20), the generated sensitivities agree with central
    /// differences of the closed form (five points, truncation h⁴ with h = 1e-4 of the size,
    /// rounding ε/h) to 1e-7, wherever the differences themselves agree at h and h/2.
    #[test]
    fn sensitivities_agree_with_central_differences_on_random_four_bars(
        lengths in proptest::array::uniform4(1.0f64..10.0),
        point in (0.0f64..10.0, -3.0f64..3.0),
        theta2 in -std::f64::consts::PI..std::f64::consts::PI,
        open in proptest::bool::ANY,
    ) {
        let branch = if open { Branch::Open } else { Branch::Crossed };
        let d = [lengths[0], lengths[1], lengths[2], lengths[3], point.0, point.1];
        let Ok(l) = FourBar::new(d[0], d[1], d[2], d[3]).and_then(|l| l.with_coupler_point(d[4], d[5])) else {
            return Ok(());
        };
        let Ok(q) = l.assemble(theta2, branch) else { return Ok(()); };
        proptest::prop_assume!(l.condition(theta2, &q) < 20.0);
        let size: f64 = d[..4].iter().sum();
        let s = l.sensitivities(theta2, &q).unwrap();
        let p = l.point_sensitivities(theta2, &q).unwrap();
        let generated = [
            (s.l1, p.l1), (s.l2, p.l2), (s.l3, p.l3), (s.l4, p.l4), (s.a, p.a), (s.delta, p.delta),
        ]
        .map(|(s, p)| [s.theta3, s.theta4, p.coupler_point.x, p.coupler_point.y]);
        let solve = |d: [f64; 6]| -> Option<[f64; 4]> {
            let l = FourBar::new(d[0], d[1], d[2], d[3]).and_then(|l| l.with_coupler_point(d[4], d[5])).ok()?;
            let q = l.assemble(theta2, branch).ok()?;
            let p = l.points(theta2, &q).ok()?.coupler_point;
            Some([q.theta3, q.theta4, p.x, p.y])
        };
        for (k, g) in generated.iter().enumerate() {
            // The five-point stencil (truncation h⁴), at h and h/2: where the two disagree
            // the differences cannot tell (near a limit the higher derivatives are huge,
            // whatever κ), and the case is left out.
            let h = 1e-4 * if k == 5 { 1.0 } else { size };
            let stencil = |h: f64| -> Option<[f64; 4]> {
                let at = |steps: f64| {
                    let mut moved = d;
                    moved[k] += steps * h;
                    solve(moved)
                };
                let (a2, a1, b1, b2) = (at(2.0)?, at(1.0)?, at(-1.0)?, at(-2.0)?);
                Some(core::array::from_fn(|i| {
                    (-a2[i] + 8.0 * a1[i] - 8.0 * b1[i] + b2[i]) / (12.0 * h)
                }))
            };
            let (Some(coarse), Some(fine)) = (stencil(h), stencil(h / 2.0)) else {
                continue;
            };
            for i in 0..4 {
                // Angles per length scale as 1/size, points as 1 (per length) or size (per
                // radian).
                let unit = match (i < 2, k == 5) {
                    (true, _) => 1.0 / size,
                    (false, false) => 1.0,
                    (false, true) => size,
                };
                let scale = unit.max(fine[i].abs());
                if (coarse[i] - fine[i]).abs() > 1e-8 * scale {
                    continue;
                }
                let difference = fine[i];
                proptest::prop_assert!(
                    (g[i] - difference).abs() <= 1e-7 * scale,
                    "dimension {k}, output {i}: {} against {difference}", g[i]
                );
            }
        }
    }
}

/// `∂f/∂l` of the four-bar's loop `f = l2·e^{iθ2} + l3·e^{iθ3} − l4·e^{iθ4} − l1` for each
/// length `l1`..`l4`, at the oracle's solved `state`.
fn length_partials(state: &mechgen_tests::oracle::State) -> [mechgen_tests::oracle::C; 4] {
    use mechgen_tests::oracle::{Big, C};
    let [e3, e4] = [0, 1].map(|k| state.directions[k].clone().expect("an angle"));
    [
        C::new(-Big::one(), Big::zero()),
        state.input_direction.clone(),
        e3,
        C::new(-e4.re, -e4.im),
    ]
}

/// The sensitivities against the multiple-precision oracle's (`mechgen_tests::oracle`, 256
/// bits): its position, its Jacobian and `J·x = −∂f/∂p` solved by its own elimination, on
/// eight four-bars (crank-rockers, a triple-rocker, change-point linkages), both branches,
/// from 1e-3 to 200 long. The f64
/// answers are within 16 units of rounding times the condition (5.4 at worst when written).
#[test]
fn sensitivities_agree_with_a_high_precision_solve() {
    use mechgen_tests::oracle::{self, Params};
    let cases: [([f64; 4], f64, Branch); 8] = [
        ([180.0, 80.0, 200.0, 150.0], 1.0, Branch::Open),
        ([180.0, 80.0, 200.0, 150.0], 4.0, Branch::Crossed),
        ([100.0, 40.0, 90.0, 70.0], 2.5, Branch::Open),
        ([50.0, 120.0, 70.0, 100.0], 0.3, Branch::Open),
        ([3.0, 7.0, 5.0, 4.0], 1.9, Branch::Crossed),
        ([1.0, 0.35, 1.2, 0.9], -2.2, Branch::Open),
        ([200.0, 60.0, 60.0, 200.0], 1.2, Branch::Open),
        ([1e-3, 4e-4, 1.1e-3, 9e-4], 0.7, Branch::Crossed),
    ];
    let mut worst = 0.0f64;
    for (lengths, theta2, branch) in cases {
        let [l1, l2, l3, l4] = lengths;
        let l = FourBar::new(l1, l2, l3, l4).unwrap();
        let q = l.assemble(theta2, branch).unwrap();
        let s = l.sensitivities(theta2, &q).unwrap();
        let generated = [s.l1, s.l2, s.l3, s.l4].map(|u| [u.theta3, u.theta4]);
        let p = Params(
            ["l1", "l2", "l3", "l4"]
                .into_iter()
                .zip(lengths)
                .map(|(n, v)| (n.to_string(), v))
                .collect(),
        );
        let outcome = oracle::four_bar(&p, theta2, branch, 0.0, 0.0);
        let truth = outcome.truth.expect("the oracle assembles it");
        let state = &truth.state;
        let j = oracle::jacobian(&outcome.model, state);
        let partials = length_partials(state);
        for (k, d) in partials.iter().enumerate() {
            let (x, _) =
                oracle::solve(j.clone(), vec![-d.re.clone(), -d.im.clone()]).expect("regular");
            for i in 0..2 {
                let exact = x[i].to_f64();
                let error = (generated[k][i] - exact).abs();
                // Relative to the sensitivity's scale, 1/size, and the condition.
                let scale = exact.abs().max(1.0 / lengths.iter().sum::<f64>());
                let relative = error / (scale * f64::EPSILON * truth.condition);
                worst = worst.max(relative);
                assert!(
                    relative <= 16.0,
                    "{lengths:?} at {theta2} {branch:?}: ∂θ{}/∂l{}: {} against {exact} ({relative} ε·κ)",
                    i + 3,
                    k + 1,
                    generated[k][i]
                );
            }
        }
    }
    assert!(
        worst > 0.0,
        "every sensitivity exact: the comparison compared nothing"
    );
}

/// The sensitivities at the edges: a sensitivity is a rate (the same solve, with `−∂f/∂p` for
/// the input's column), and an `Ok` says its estimate is within what a velocity must be, so
/// each is held to the velocity's estimate (`Accuracy::estimate` at the larger of the
/// answer's and the oracle's κ, and the oracle's aspect), each unknown weighted by its column
/// over the larger of 1 (the loops' own rate per unit of a length) and the true sensitivities,
/// weighted. Four-bars at link ratios to 1e8 (1e4 in f32) and sizes to 1e±200 (1e±25), seven
/// in ten within 1e-15 to 1e-1 rad of a limit angle (a toggle), where κ grows; the position
/// `assemble`'s in the same float.
#[test]
fn sensitivities_keep_the_velocity_s_accuracy_at_the_edges() {
    fn judged<T: mechgen::Real + Into<f64>>(
        seed: u64,
        cases: usize,
        ratio: f64,
        scale: f64,
    ) -> usize {
        use mechgen::Accuracy;
        use mechgen_tests::oracle::{self, Big, Kind, Params, draw::Rng};
        let mut rng = Rng(seed);
        let t = |x: f64| T::from(x).unwrap();
        let mut judged = 0;
        for index in 0..cases {
            let ratio = [ratio / 8.0, ratio / 4.0, ratio / 2.0, ratio][index % 4];
            let size = 10f64.powf(rng.range(-scale, scale));
            let lengths = [0; 4].map(|_| t(size * 10f64.powf(rng.range(-ratio, ratio))).into());
            let branch = if rng.chance(0.5) {
                Branch::Open
            } else {
                Branch::Crossed
            };
            let named = ["l1", "l2", "l3", "l4"].into_iter().map(String::from);
            let p = Params(named.zip(lengths).collect());
            let limits = oracle::limit_angles(Kind::FourBar, &p, &[branch]);
            let theta2: f64 = if !limits.is_empty() && rng.chance(0.7) {
                t(rng.pick(&limits) + rng.sign() * 10f64.powf(rng.range(-15.0, -1.0))).into()
            } else {
                t(rng.angle()).into()
            };
            let [l1, l2, l3, l4] = lengths.map(t);
            let Ok(linkage) = FourBar::new(l1, l2, l3, l4) else {
                continue;
            };
            let Ok(q) = linkage.assemble(t(theta2), branch) else {
                continue;
            };
            let outcome = oracle::four_bar(&p, theta2, branch, 0.0, 0.0);
            // Within rounding of a limit the oracle may find no assembly; `edges.rs` judges
            // the position there.
            let (Some(truth), Ok(got)) = (outcome.truth, linkage.sensitivities(t(theta2), &q))
            else {
                continue;
            };
            judged += 1;
            let generated =
                [got.l1, got.l2, got.l3, got.l4].map(|u| [u.theta3.into(), u.theta4.into()]);
            let state = &truth.state;
            let jacobian = oracle::jacobian(&outcome.model, state);
            let partials = length_partials(state);
            let condition: f64 = linkage.condition(t(theta2), &q).into();
            let kappa = condition.max(truth.condition);
            let aspect = truth.aspect(lengths.iter().sum());
            let estimate = |x: f64| T::from(x).unwrap_or(T::infinity());
            let stated: f64 = Accuracy::<T>::estimate(estimate(kappa), estimate(aspect))
                .velocity
                .into();
            for (k, partial) in partials.iter().enumerate() {
                let rhs = vec![-partial.re.clone(), -partial.im.clone()];
                let (exact, _) = oracle::solve(jacobian.clone(), rhs).expect("regular");
                let weighted = |i: usize| Big::from_f64(truth.columns[i]);
                let scale = (0..2).fold(Big::one(), |m, i| m.max((&exact[i] * weighted(i)).abs()));
                for i in 0..2 {
                    let error = if generated[k][i].is_finite() {
                        let difference = Big::from_f64(generated[k][i]) - &exact[i];
                        (difference.abs() * weighted(i) / &scale).to_f64()
                    } else {
                        f64::INFINITY
                    };
                    assert!(
                        error <= stated,
                        "{lengths:?} at {theta2} {branch:?} ({}): ∂θ{}/∂l{} off by {error:.3e}, \
                         beyond the velocity's {stated:.3e} (κ {kappa:.3e}, ρ {aspect:.2e})",
                        std::any::type_name::<T>(),
                        i + 3,
                        k + 1,
                    );
                }
            }
        }
        judged
    }
    let judged = [
        judged::<f64>(20261128, 9000, 8.0, 200.0),
        judged::<f32>(20261129, 3000, 4.0, 25.0),
    ];
    // Most draws do not assemble (or not at their input); enough do.
    assert!(judged.iter().all(|&n| n > 300), "{judged:?} judged");
}

mechgen::mechanism! {
    /// A slider whose line is offset by `sqrt(a² − b²)` and tilted by `gamma`, with a point
    /// on its rod: a formula of the lengths, whose derivative `a/√(a² − b²)` squares them.
    pub struct TiltedSlider {
        params: a, b, l2, l3, gamma: angle;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - sqrt(a * a - b * b) @ (pi / 2 + gamma) - d @ 0;
        point rod_end = l2 @ theta2 + l3 @ theta3;
        generate: position, velocity, acceleration, sensitivities;
    }
}

/// `[∂θ3/∂a, ∂d/∂a, ∂θ3/∂γ, ∂d/∂γ, ∂P.x/∂a, ∂P.y/∂γ]` of the tilted slider with every length
/// times `s`, each taken back to the unit slider's units (an angle's by a length times `s`,
/// a length's by an angle over `s`).
fn tilted_sensitivities<T: mechgen::Real>(s: T) -> Result<[f64; 6], Error<T>> {
    let c = T::constant;
    let linkage = TiltedSlider {
        a: c(5.0) * s,
        b: c(3.0) * s,
        l2: c(2.0) * s,
        l3: c(9.0) * s,
        gamma: c(0.1),
    };
    let q = linkage.assemble(c(0.7), Branch::Open)?;
    let x = linkage.sensitivities(c(0.7), &q)?;
    let p = linkage.point_sensitivities(c(0.7), &q)?;
    let f = |v: T| v.to_f64().expect("a float");
    Ok([
        f(x.a.theta3 * s),
        f(x.a.d),
        f(x.gamma.theta3),
        f(x.gamma.d / s),
        f(p.a.rod_end.x),
        f(p.gamma.rod_end.y / s),
    ])
}

/// A declaration whose loop holds a formula of its lengths has the same sensitivities at
/// every size, as its solvers have the same positions: at 1e154 and beyond `a²` overflows
/// and the formula's derivative did, `NonFinite`; at 1e-160 it underflowed into the
/// subnormals and the derivative came back `Ok` five digits off. The sensitivities now
/// compute on the mechanism scaled by a power of two where its size is far from 1.
#[test]
fn sensitivities_of_a_formula_are_the_same_at_every_size() {
    let unit = tilted_sensitivities(1.0f64).expect("an ordinary slider");
    // ∂θ3/∂a against central differences, to check the unit values themselves.
    let theta3 = |a: f64| {
        let linkage = TiltedSlider {
            a,
            b: 3.0,
            l2: 2.0,
            l3: 9.0,
            gamma: 0.1,
        };
        linkage
            .assemble(0.7, Branch::Open)
            .expect("assembles")
            .theta3
    };
    let h = 1e-5;
    assert!((unit[0] - (theta3(5.0 + h) - theta3(5.0 - h)) / (2.0 * h)).abs() < 1e-9);
    for s in [1e-300, 1e-160, 1e-100, 1e100, 1e154, 1e160, 1e300] {
        let scaled = tilted_sensitivities(s).expect("the same slider, scaled");
        for (got, want) in scaled.iter().zip(unit) {
            assert!(
                (got - want).abs() <= 1e-13 * want.abs(),
                "{s:e}: {got} against {want}"
            );
        }
    }
    let unit = tilted_sensitivities(1.0f32).expect("an ordinary slider");
    for s in [1e-30f32, 1e-20, 1e20, 1e30] {
        let scaled = tilted_sensitivities(s).expect("the same slider, scaled");
        for (got, want) in scaled.iter().zip(unit) {
            assert!(
                (got - want).abs() <= 1e-5 * want.abs(),
                "{s:e}: {got} against {want}"
            );
        }
    }
}

mechgen::mechanism! {
    /// A slider-crank whose tracked point hangs off the rod at `(px, py)` in the rod's frame:
    /// its formulas (`hypot`, `atan2`) are the point's alone, the loop has none.
    pub struct OffsetRodPoint {
        params: l2, l3, c, px, py;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - c @ (pi / 2) - d @ 0;
        point p = l2 @ theta2 + hypot(px, py) @ (theta3 + atan2(py, px));
        generate: position, velocity, acceleration, sensitivities;
    }
}

/// A formula only in a point scales as one in a loop does: `∂P/∂px` of the point's
/// `atan2(py, px)` squares `px`, which at lengths of 1e160 overflowed and made the derivative
/// zero where it is not.
#[test]
fn sensitivities_of_a_point_formula_are_the_same_at_every_size() {
    let point_sensitivities = |s: f64| {
        let linkage = OffsetRodPoint {
            l2: 2.0 * s,
            l3: 7.0 * s,
            c: 0.5 * s,
            px: 3.0 * s,
            py: 1.5 * s,
        };
        let q = linkage.assemble(0.9, Branch::Open).expect("assembles");
        let p = linkage.point_sensitivities(0.9, &q).expect("finite");
        [p.px.p.x, p.px.p.y, p.py.p.x, p.py.p.y, p.l3.p.x, p.c.p.y]
    };
    let unit = point_sensitivities(1.0);
    assert!(unit.iter().all(|v| v.abs() > 1e-3), "{unit:?}");
    for s in [1e-300, 1e-160, 1e160, 1e300] {
        for (got, want) in point_sensitivities(s).iter().zip(unit) {
            assert!(
                (got - want).abs() <= 1e-13 * want.abs(),
                "{s:e}: {got} against {want}"
            );
        }
    }
}

/// A position the loops do not close at (another crank angle's, or made up) is refused by
/// everything that takes one, as known too poorly for its rates to meet their accuracy: an
/// adversarial review found velocities, sensitivities and a mechanical advantage returned
/// there. A position that closes to rounding still gives the closed form's answers, and a
/// Newton position stopped short by a tolerance is judged by what its residual leaves.
#[test]
fn a_position_the_loops_do_not_close_at_is_refused() {
    let linkage = linkage(DIMENSIONS);
    let elsewhere = linkage.assemble(2.0, Branch::Open).unwrap();
    let made_up = mechanisms::FourBarUnknowns {
        theta3: 0.3,
        theta4: 2.9,
    };
    for position in [elsewhere, made_up] {
        assert!(matches!(
            linkage.velocity(1.0, &position, 1.0),
            Err(Error::Inaccurate { .. })
        ));
        assert!(matches!(
            linkage.acceleration(1.0, &position, 1.0, &position, 0.0),
            Err(Error::Inaccurate { .. })
        ));
        assert!(matches!(
            linkage.motion_at(1.0, &position, 1.0, 0.0),
            Err(Error::Inaccurate { .. })
        ));
        assert!(matches!(
            linkage.sensitivities(1.0, &position),
            Err(Error::Inaccurate { .. })
        ));
        assert!(matches!(
            linkage.point_sensitivities(1.0, &position),
            Err(Error::Inaccurate { .. })
        ));
        assert!(matches!(
            linkage.mechanical_advantage(1.0, &position),
            Err(Error::Inaccurate { .. })
        ));
    }
    // Closed to rounding: as before.
    let here = linkage.assemble(1.0, Branch::Open).unwrap();
    assert!(linkage.velocity(1.0, &here, 1.0).is_ok());
    assert!(linkage.sensitivities(1.0, &here).is_ok());
    // Off by 1e-9 rad in θ4: the loops open by 1.5e-7 mm, and the rates, off by about as
    // much relative, are within the velocity's required 6e-6.
    let near = mechanisms::FourBarUnknowns {
        theta4: here.theta4 + 1e-9,
        ..here
    };
    let rates = linkage.velocity(1.0, &near, 1.0).unwrap();
    let exact = linkage.velocity(1.0, &here, 1.0).unwrap();
    assert!((rates.theta4 - exact.theta4).abs() < 1e-8);
    // A position a thousand turns out near a toggle, whose angles hold only to their floats'
    // spacing (4.5e-13 rad), so that the loops open by 2.3e-10 mm: off by that spacing, not
    // by the worst such a residual could mean at a condition of 6.7e3 (which refused it, an
    // adversarial review found). Its rates are the ones a turn in, to 1e-8.
    let rocker_crank = FourBar::new(180.0, 150.0, 200.0, 80.0).unwrap();
    let theta2 = 0.7227342578134156;
    let turn = 2.0 * std::f64::consts::PI * 1000.0;
    let q = rocker_crank.assemble(theta2, Branch::Open).unwrap();
    let out = mechanisms::FourBarUnknowns {
        theta3: q.theta3 + turn,
        theta4: q.theta4 + turn,
    };
    let (got, want) = (
        rocker_crank.velocity(theta2, &out, 1.0).unwrap(),
        rocker_crank.velocity(theta2, &q, 1.0).unwrap(),
    );
    assert!((got.theta4 - want.theta4).abs() <= 1e-8 * want.theta4.abs());
    // Off by 1e-4 rad: the rates cannot be known to 6e-6.
    let far = mechanisms::FourBarUnknowns {
        theta4: here.theta4 + 1e-4,
        ..here
    };
    assert!(matches!(
        linkage.velocity(1.0, &far, 1.0),
        Err(Error::Inaccurate { .. })
    ));
}
