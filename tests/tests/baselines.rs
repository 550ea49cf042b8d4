//! The benchmarks' baselines compute what the generated code computes, so timing them side
//! by side compares like with like: each against the generated `mechanisms` code, in `f64`,
//! over full 360° sweeps one degree apart, open branch, ω2 = 10 rad/s, α2 = 2 rad/s².

use mechanisms::{FourBar, InvertedSliderCrank, SliderCrank};
use mechgen::Branch;
use mechgen_tests::baselines::{
    self, FourBarCouplerPoint, FourBarNewton, FourBarNorton, InvertedSliderCrankClosed,
    SliderCrankClosed, State,
};

const W2: f64 = 10.0;
const A2: f64 = 2.0;

/// The four-bars checked: Example 1 (crank-rocker), Exercise 3, a long-coupler crank-rocker
/// and a double-crank (ground shortest), all turning fully.
const FOUR_BARS: [[f64; 4]; 4] = [
    [180.0, 80.0, 200.0, 150.0],
    [300.0, 100.0, 250.0, 200.0],
    [200.0, 40.0, 220.0, 210.0],
    [60.0, 150.0, 170.0, 160.0],
];

fn sweep() -> impl Iterator<Item = f64> {
    (0..360).map(|k| f64::from(k).to_radians())
}

/// `a − b` for angles: wrapped into (−π, π].
fn angle_difference(a: f64, b: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let d = (a - b).rem_euclid(tau);
    if d > tau / 2.0 { d - tau } else { d }
}

/// Checks a sweep entry by entry: the error in row `k`, column `j` relative to the largest
/// magnitude of that column over the whole sweep (at least 1 for an angle), so an entry
/// crossing zero is judged on its column's scale, not its own. `angles[j]` marks a column
/// whose row 0 is an angle, compared modulo 2π. Returns the worst relative error per row.
fn check(what: &str, got: &[State], want: &[State], angles: [bool; 2], tolerance: f64) -> [f64; 3] {
    assert_eq!(got.len(), want.len(), "{what}: sweep lengths");
    let mut scale = [[0.0f64; 2]; 3];
    for state in want {
        for (k, row) in state.iter().enumerate() {
            for (j, value) in row.iter().enumerate() {
                assert!(value.is_finite(), "{what}: generated {state:?}");
                scale[k][j] = scale[k][j].max(value.abs());
            }
        }
    }
    for (j, angle) in angles.iter().enumerate() {
        if *angle {
            scale[0][j] = scale[0][j].max(1.0);
        }
    }
    let mut worst = [0.0f64; 3];
    for (index, (g, w)) in got.iter().zip(want).enumerate() {
        for k in 0..3 {
            for j in 0..2 {
                let error = if k == 0 && angles[j] {
                    angle_difference(g[k][j], w[k][j])
                } else {
                    g[k][j] - w[k][j]
                };
                let relative = error.abs() / scale[k][j];
                assert!(
                    relative <= tolerance,
                    "{what} at sample {index}: {g:?} vs {w:?} (row {k}, column {j}: {relative:e})"
                );
                worst[k] = worst[k].max(relative);
            }
        }
    }
    worst
}

fn generated_four_bar(lengths: [f64; 4]) -> FourBar<f64> {
    let [l1, l2, l3, l4] = lengths;
    FourBar::new(l1, l2, l3, l4)
        .and_then(|linkage| linkage.with_coupler_point(100.0, 30f64.to_radians()))
        .unwrap()
}

fn generated_sweep(linkage: &FourBar<f64>) -> Vec<State> {
    sweep()
        .map(|t| {
            let m = linkage.motion(t, Branch::Open, W2, A2).unwrap();
            [
                m.position.to_array(),
                m.velocity.to_array(),
                m.acceleration.to_array(),
            ]
        })
        .collect()
}

#[test]
fn norton_agrees_with_the_generated_closed_form() {
    for lengths in FOUR_BARS {
        let want = generated_sweep(&generated_four_bar(lengths));
        let norton = FourBarNorton::new(lengths);
        let got: Vec<State> = sweep().map(|t| norton.motion(t, W2, A2)).collect();
        let worst = check("Norton", &got, &want, [true, true], 1e-13);
        println!("Norton {lengths:?}: worst relative errors {worst:?}");
        // The free function is the same computation.
        for (t, state) in sweep().zip(&got) {
            assert_eq!(baselines::four_bar_norton(&lengths, t, W2, A2), *state);
        }
    }
}

#[test]
fn hand_newton_agrees_with_the_generated_closed_form() {
    for lengths in FOUR_BARS {
        let linkage = generated_four_bar(lengths);
        let want = generated_sweep(&linkage);
        let newton = FourBarNewton::new(lengths);
        // Stopping at |f| < 1e-9 mm (the benchmarks' tolerance) can leave a few 1e-12 rad;
        // at 1e-12 mm the last update has reached rounding.
        for (tolerance, agreement) in [(1e-9, 1e-10), (1e-12, 1e-13)] {
            // Warm: each solve starts from the previous answer, as in the benchmarks.
            let mut guess = want[0][0];
            let warm: Vec<State> = sweep()
                .map(|t| {
                    let s = newton.motion(t, guess, tolerance, W2, A2);
                    guess = s[0];
                    s
                })
                .collect();
            let worst = check("hand Newton warm", &warm, &want, [true, true], agreement);
            println!("hand Newton warm {tolerance:e} {lengths:?}: worst relative errors {worst:?}");
            // Cold: from the position 10° back.
            let cold: Vec<State> = sweep()
                .enumerate()
                .map(|(k, t)| newton.motion(t, want[(k + 350) % 360][0], tolerance, W2, A2))
                .collect();
            let worst = check("hand Newton cold", &cold, &want, [true, true], agreement);
            println!("hand Newton cold {tolerance:e} {lengths:?}: worst relative errors {worst:?}");
        }
        for (t, state) in sweep().zip(&want).step_by(37) {
            let guess = [state[0][0] + 0.05, state[0][1] - 0.05];
            assert_eq!(
                baselines::four_bar_newton(&lengths, t, guess, 1e-9, W2, A2),
                newton.motion(t, guess, 1e-9, W2, A2)
            );
        }
    }
}

#[test]
fn hand_newton_takes_the_seeds_steps() {
    // Example 2: from (15°, 80°), 3 updates meet |f| < 1e-4 (KINEMATICS.md).
    let newton = FourBarNewton::new([180.0, 80.0, 200.0, 150.0]);
    let guess = [15f64.to_radians(), 80f64.to_radians()];
    let s = newton.motion(60f64.to_radians(), guess, 1e-4, W2, A2);
    assert!((s[0][0].to_degrees() - 21.5576).abs() < 1e-4);
    assert!((s[0][1].to_degrees() - 72.1377).abs() < 1e-4);
}

#[test]
fn coupler_point_kernels_agree_with_the_generated_points() {
    for lengths in FOUR_BARS {
        let linkage = generated_four_bar(lengths);
        let point = FourBarCouplerPoint::new(lengths, 100.0, 30f64.to_radians());
        let mut got = Vec::new();
        let mut want = Vec::new();
        for t in sweep() {
            let m = linkage.motion(t, Branch::Open, W2, A2).unwrap();
            let (q, v, a) = (m.position, m.velocity, m.acceleration);
            let p = linkage.points(t, &q).unwrap().coupler_point;
            let pv = linkage
                .point_velocities(t, &q, W2, &v)
                .unwrap()
                .coupler_point;
            let pa = linkage
                .point_accelerations(t, &q, W2, &v, A2, &a)
                .unwrap()
                .coupler_point;
            want.push([[p.x, p.y], [pv.x, pv.y], [pa.x, pa.y]]);
            let motion = point.motion(t, W2, A2);
            // The position kernel and the motion kernel's position are the same point.
            let position = point.position(t);
            for j in 0..2 {
                assert!((position[j] - motion[0][j]).abs() <= 1e-13 * 400.0);
            }
            got.push(motion);
        }
        let worst = check("coupler point", &got, &want, [false, false], 1e-13);
        println!("coupler point {lengths:?}: worst relative errors {worst:?}");
        let positions: Vec<State> = sweep()
            .zip(&want)
            .map(|(t, w)| [point.position(t), w[1], w[2]])
            .collect();
        check(
            "coupler point position",
            &positions,
            &want,
            [false, false],
            1e-13,
        );
    }
}

#[test]
fn slider_crank_agrees_with_the_generated_closed_form() {
    let linkage = SliderCrank::new(50.0, 150.0, 20.0).unwrap();
    let hand = SliderCrankClosed::new(50.0, 150.0, 20.0);
    let mut got = Vec::new();
    let mut want = Vec::new();
    for t in sweep() {
        let m = linkage.motion(t, Branch::Open, W2, A2).unwrap();
        want.push([
            m.position.to_array(),
            m.velocity.to_array(),
            m.acceleration.to_array(),
        ]);
        got.push(hand.motion(t, W2, A2));
    }
    let worst = check("slider-crank", &got, &want, [true, false], 1e-13);
    println!("slider-crank: worst relative errors {worst:?}");
}

#[test]
fn inverted_slider_crank_agrees_with_the_generated_closed_form() {
    for p in [
        [150.0, 60.0, 20.0, 0.3],
        [150.0, 60.0, 0.0, 0.0],
        [120.0, 70.0, -30.0, -0.8],
    ] {
        let linkage = InvertedSliderCrank::new(p[0], p[1], p[2], p[3]).unwrap();
        let hand = InvertedSliderCrankClosed::new(p);
        let mut got = Vec::new();
        let mut want = Vec::new();
        for t in sweep() {
            let m = linkage.motion(t, Branch::Open, W2, A2).unwrap();
            want.push([
                m.position.to_array(),
                m.velocity.to_array(),
                m.acceleration.to_array(),
            ]);
            got.push(hand.motion(t, W2, A2));
        }
        let worst = check("inverted slider-crank", &got, &want, [true, false], 1e-13);
        println!("inverted slider-crank {p:?}: worst relative errors {worst:?}");
    }
}

#[test]
fn generic_baselines_agree_with_the_generated_code() {
    let l = [180.0, 80.0, 200.0, 150.0];
    let linkage = generated_four_bar(l);
    let want = generated_sweep(&linkage);
    let guesses: Vec<[f64; 2]> = want
        .iter()
        .map(|w| [w[0][0] + 0.01, w[0][1] - 0.01])
        .collect();
    let num_dual: Vec<State> = sweep()
        .zip(&guesses)
        .map(|(t, guess)| baselines::four_bar_num_dual(&l, t, *guess, 1e-12, W2, A2))
        .collect();
    check("num-dual", &num_dual, &want, [true, true], 1e-12);
    let nalgebra: Vec<State> = sweep()
        .zip(&guesses)
        .step_by(7)
        .map(|(t, guess)| baselines::four_bar_nalgebra(&l, t, *guess, 1e-12, W2, A2))
        .collect();
    let want: Vec<State> = want.into_iter().step_by(7).collect();
    // Finite differences: good to a few digits only.
    check("nalgebra", &nalgebra, &want, [true, true], 1e-3);
}

/// The benchmarks' sweep at 60 digits (`tests/reference/sweeps.csv`, from
/// `tests/reference/generate.py`): `(θ2, state)` per degree.
fn references(mechanism: &str) -> Vec<(f64, State)> {
    include_str!("../reference/sweeps.csv")
        .lines()
        .filter(|line| line.starts_with(&format!("{mechanism},")))
        .map(|line| {
            let f: Vec<f64> = line
                .split(',')
                .skip(2)
                .map(|x| x.parse().unwrap())
                .collect();
            (f[0], [[f[1], f[2]], [f[3], f[4]], [f[5], f[6]]])
        })
        .collect()
}

#[test]
fn closed_forms_match_the_high_precision_references() {
    let four_bar = references("four_bar");
    let norton = FourBarNorton::new([180.0, 80.0, 200.0, 150.0]);
    let (inputs, want): (Vec<f64>, Vec<State>) = four_bar.into_iter().unzip();
    assert_eq!(inputs.len(), 360);
    let got: Vec<State> = inputs.iter().map(|t| norton.motion(*t, W2, A2)).collect();
    let worst = check("Norton", &got, &want, [true, true], 1e-14);
    println!("Norton against the references: {worst:?}");

    let (inputs, want): (Vec<f64>, Vec<State>) = references("slider_crank").into_iter().unzip();
    let slider = SliderCrankClosed::new(50.0, 150.0, 20.0);
    let got: Vec<State> = inputs.iter().map(|t| slider.motion(*t, W2, A2)).collect();
    let worst = check("slider-crank", &got, &want, [true, false], 1e-14);
    println!("slider-crank against the references: {worst:?}");

    let (inputs, want): (Vec<f64>, Vec<State>) =
        references("inverted_slider_crank").into_iter().unzip();
    let inverted = InvertedSliderCrankClosed::new([150.0, 60.0, 20.0, 0.3]);
    let got: Vec<State> = inputs.iter().map(|t| inverted.motion(*t, W2, A2)).collect();
    let worst = check("inverted slider-crank", &got, &want, [true, false], 1e-14);
    println!("inverted slider-crank against the references: {worst:?}");
}
