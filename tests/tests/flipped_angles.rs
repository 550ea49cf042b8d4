//! Unknown angles that a loop turns with backwards (`l3 @ (pi - phi3)`: coefficient −1, a
//! constant offset) still have closed forms: the loop is solved for `phi3' = −phi3`. Each
//! declaration here is a shipped mechanism written with some angles measured the other way,
//! and each generated solver (`assemble`, `motion`, the scene kernels, Newton's `position`,
//! `velocity`, `acceleration` and the reduced Newton of a coupled six-bar) must give the
//! shipped one's answers, on both branches, to rounding.

mod common;

use mechanisms::{FourBar, SliderCrank, StephensonSixBar, WattSixBar};
use mechgen::{Branch, NewtonOptions, Vec2, mechanism};

mechanism! {
    /// The seeds' four-bar with the coupler's angle measured the other way:
    /// `phi3 = π − θ3`.
    pub struct CouplerBackwards {
        params: l1, l2, l3, l4, a, delta: angle;
        input: theta2: angle;
        unknowns: phi3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ (pi - phi3) - l4 @ theta4 - l1 @ 0;
        point rocker_pin = l1 @ 0 + l4 @ theta4;
        point coupler_point = l2 @ theta2 + a @ (pi - phi3 + delta);
        generate: position, velocity, acceleration, assemble;
        scene angles: phi3, theta4, phi3_dot, theta4_dot, phi3_ddot, theta4_ddot;
        scene coupler_motion: coupler_point, coupler_point_dot, coupler_point_ddot;
    }
}

mechanism! {
    /// The four-bar with both unknown angles measured the other way: `phi3 = π − θ3`,
    /// `psi4 = −θ4` (the rocker written from B to O4).
    pub struct BothBackwards {
        params: l1, l2, l3, l4;
        input: theta2: angle;
        unknowns: phi3: angle, psi4: angle;
        loop: l2 @ theta2 + l3 @ (pi - phi3) + l4 @ (pi - psi4) - l1 @ 0;
        scene angles: phi3, psi4, phi3_dot, psi4_dot, phi3_ddot, psi4_ddot;
    }
}

mechanism! {
    /// The offset slider-crank with the coupler's angle negated: `phi3 = −θ3`.
    pub struct SliderBackwards {
        params: l2, l3, c;
        input: theta2: angle;
        unknowns: phi3: angle, d: length;
        loop: l2 @ theta2 + l3 @ (-phi3) - c @ pi / 2 - d @ 0;
        scene state: phi3, d, phi3_dot, d_dot, phi3_ddot, d_ddot;
    }
}

mechanism! {
    /// The Watt six-bar with the rocker's angle negated in loop 1 (`psi4 = −θ4`, then a known
    /// angle in loop 2, read backwards there too) and the second coupler's in loop 2
    /// (`psi5 = −θ5`).
    pub struct WattBackwards {
        params: l1, l2, l3, l4, l5, beta: angle, l6, l7, g, phi: angle;
        input: theta2: angle;
        unknowns: theta3: angle, psi4: angle, psi5: angle, theta6: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ (-psi4) - l1 @ 0;
        loop: l1 @ 0 + l5 @ (beta - psi4) + l6 @ (-psi5) - l7 @ theta6 - g @ phi;
        scene output: psi4, psi5, theta6, psi5_dot, theta6_dot, psi5_ddot, theta6_ddot;
    }
}

mechanism! {
    /// The Stephenson six-bar with the output rocker written from D to O6 (`psi6 = −θ6`):
    /// its loops are coupled, so Newton iterates and loop 2 is solved in closed form inside,
    /// for `psi6` first (declared before `theta5`), whose sign then picks the branch.
    pub struct StephensonBackwards {
        params: l1, l2, l3, bc, cd, beta: angle, l4, l6, g, phi: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, psi6: angle, theta5: angle;
        loop: l2 @ theta2 + l3 @ theta3 + bc @ theta5 - l4 @ theta4 - l1 @ 0;
        loop: l1 @ 0 + l4 @ theta4 + cd @ (theta5 + beta) + l6 @ (pi - psi6) - g @ phi;
    }
}

const RATE: f64 = 10.0;
const ACCELERATION: f64 = 2.0;
/// A few hundred units of rounding, relative to the quantity's scale.
const TOLERANCE: f64 = 1e-12;

/// `|got − want| ≤ TOLERANCE·scale`, naming what differs.
fn close(what: &str, input: f64, got: f64, want: f64, scale: f64) {
    let error = (got - want).abs();
    assert!(
        error <= TOLERANCE * scale,
        "{what} at {input}: {got}, shipped {want} (error {error})"
    );
}

/// Angles equal modulo a full turn.
fn same_angle(what: &str, input: f64, got: f64, want: f64) {
    let turns = (got - want) / std::f64::consts::TAU;
    close(
        what,
        input,
        got - want,
        turns.round() * std::f64::consts::TAU,
        1.0,
    );
}

fn close2(what: &str, input: f64, got: Vec2<f64>, want: Vec2<f64>, scale: f64) {
    close(what, input, got.x, want.x, scale);
    close(what, input, got.y, want.y, scale);
}

const BRANCHES: [Branch; 2] = [Branch::Open, Branch::Crossed];

fn inputs() -> impl Iterator<Item = f64> {
    (0..360).map(|degree| f64::from(degree).to_radians())
}

fn example_1() -> FourBar<f64> {
    common::example_1::<f64>()
}

fn coupler_backwards() -> CouplerBackwards<f64> {
    let shipped = example_1();
    let [l1, l2, l3, l4] = shipped.lengths();
    let (a, delta) = shipped.coupler_point();
    CouplerBackwards {
        l1,
        l2,
        l3,
        l4,
        a,
        delta,
    }
}

#[test]
fn coupler_backwards_assembles_as_the_shipped_four_bar_on_both_branches() {
    let (shipped, backwards) = (example_1(), coupler_backwards());
    for branch in BRANCHES {
        for t in inputs() {
            let want = shipped.assemble(t, branch).unwrap();
            let got = backwards.assemble(t, branch).unwrap();
            same_angle("π − φ3", t, std::f64::consts::PI - got.phi3, want.theta3);
            same_angle("θ4", t, got.theta4, want.theta4);
            assert_eq!(backwards.branch_of(t, &got), branch, "branch at {t}");
        }
    }
    // The seeds' Example 1: θ4 = 72.1377° open, θ3 = 21.5576°.
    let q = backwards
        .assemble(60f64.to_radians(), Branch::Open)
        .unwrap();
    assert!((q.theta4.to_degrees() - 72.1377).abs() < 1e-4);
    assert!((180.0 - q.phi3.to_degrees() - 21.5576).abs() < 1e-4);
}

#[test]
fn coupler_backwards_motion_and_newton_match_the_shipped_four_bar() {
    let (shipped, backwards) = (example_1(), coupler_backwards());
    let options = NewtonOptions::default();
    let (w, a) = (RATE, ACCELERATION);
    for branch in BRANCHES {
        for t in inputs() {
            let want = shipped.motion(t, branch, w, a).unwrap();
            let got = backwards.motion(t, branch, w, a).unwrap();
            let (q, v, acc) = (got.position, got.velocity, got.acceleration);
            same_angle(
                "π − φ3",
                t,
                std::f64::consts::PI - q.phi3,
                want.position.theta3,
            );
            same_angle("θ4", t, q.theta4, want.position.theta4);
            close("−φ̇3", t, -v.phi3, want.velocity.theta3, w);
            close("ω4", t, v.theta4, want.velocity.theta4, w);
            close("−φ̈3", t, -acc.phi3, want.acceleration.theta3, w * w);
            close("α4", t, acc.theta4, want.acceleration.theta4, w * w);

            // Newton from a guess off the solution lands on it, and its rates agree.
            let guess = CouplerBackwardsUnknowns {
                phi3: q.phi3 + 0.02,
                theta4: q.theta4 - 0.02,
            };
            let solved = backwards.position(t, &guess, &options).unwrap().value;
            same_angle("Newton φ3", t, solved.phi3, q.phi3);
            same_angle("Newton θ4", t, solved.theta4, q.theta4);
            let velocity = backwards.velocity(t, &q, w).unwrap();
            close("velocity φ̇3", t, velocity.phi3, v.phi3, w);
            close("velocity ω4", t, velocity.theta4, v.theta4, w);
            let acceleration = backwards.acceleration(t, &q, w, &velocity, a).unwrap();
            close("acceleration φ̈3", t, acceleration.phi3, acc.phi3, w * w);
            close("acceleration α4", t, acceleration.theta4, acc.theta4, w * w);
        }
    }
}

#[test]
fn coupler_backwards_scenes_match_the_shipped_four_bar() {
    let (shipped, backwards) = (example_1(), coupler_backwards());
    let (shipped_scenes, scenes) = (shipped.scenes().unwrap(), backwards.scenes().unwrap());
    let (w, a) = (RATE, ACCELERATION);
    let size = 200.0;
    for branch in BRANCHES {
        for t in inputs() {
            let want = shipped_scenes.angles(t, branch, w, a).unwrap();
            let got = scenes.angles(t, branch, w, a).unwrap();
            same_angle("π − φ3", t, std::f64::consts::PI - got.phi3, want.theta3);
            same_angle("θ4", t, got.theta4, want.theta4);
            close("−φ̇3", t, -got.phi3_dot, want.theta3_dot, w);
            close("ω4", t, got.theta4_dot, want.theta4_dot, w);
            close("−φ̈3", t, -got.phi3_ddot, want.theta3_ddot, w * w);
            close("α4", t, got.theta4_ddot, want.theta4_ddot, w * w);

            let want = shipped_scenes.coupler_motion(t, branch, w, a).unwrap();
            let got = scenes.coupler_motion(t, branch, w, a).unwrap();
            close2("P", t, got.coupler_point, want.coupler_point, size);
            close2(
                "Ṗ",
                t,
                got.coupler_point_dot,
                want.coupler_point_dot,
                size * w,
            );
            close2(
                "P̈",
                t,
                got.coupler_point_ddot,
                want.coupler_point_ddot,
                size * w * w,
            );
        }
    }
}

#[test]
fn both_angles_backwards_match_the_shipped_four_bar() {
    let shipped = example_1();
    let [l1, l2, l3, l4] = shipped.lengths();
    let backwards = BothBackwards { l1, l2, l3, l4 };
    let scenes = backwards.scenes().unwrap();
    let (w, a) = (RATE, ACCELERATION);
    for branch in BRANCHES {
        for t in inputs() {
            let want = shipped.motion(t, branch, w, a).unwrap();
            let got = backwards.motion(t, branch, w, a).unwrap();
            let scene = scenes.angles(t, branch, w, a).unwrap();
            let assembled = backwards.assemble(t, branch).unwrap();
            assert_eq!(backwards.branch_of(t, &assembled), branch, "branch at {t}");
            let pi = std::f64::consts::PI;
            for (how, [phi3, psi4, phi3_dot, psi4_dot, phi3_ddot, psi4_ddot]) in [
                (
                    "motion",
                    [
                        got.position.phi3,
                        got.position.psi4,
                        got.velocity.phi3,
                        got.velocity.psi4,
                        got.acceleration.phi3,
                        got.acceleration.psi4,
                    ],
                ),
                (
                    "scene",
                    [
                        scene.phi3,
                        scene.psi4,
                        scene.phi3_dot,
                        scene.psi4_dot,
                        scene.phi3_ddot,
                        scene.psi4_ddot,
                    ],
                ),
            ] {
                same_angle(how, t, pi - phi3, want.position.theta3);
                same_angle(how, t, -psi4, want.position.theta4);
                same_angle(how, t, assembled.psi4, psi4);
                close(how, t, -phi3_dot, want.velocity.theta3, w);
                close(how, t, -psi4_dot, want.velocity.theta4, w);
                close(how, t, -phi3_ddot, want.acceleration.theta3, w * w);
                close(how, t, -psi4_ddot, want.acceleration.theta4, w * w);
            }
        }
    }
}

#[test]
fn slider_crank_backwards_matches_the_shipped_one() {
    let shipped: SliderCrank<f64> = common::slider_crank();
    // `common::slider_crank`'s dimensions.
    let backwards = SliderBackwards {
        l2: 50.0,
        l3: 150.0,
        c: 20.0,
    };
    let scenes = backwards.scenes().unwrap();
    let options = NewtonOptions::default();
    let (w, a) = (RATE, ACCELERATION);
    let size = 200.0;
    for branch in BRANCHES {
        for t in inputs() {
            let want = shipped.motion(t, branch, w, a).unwrap();
            let got = backwards.motion(t, branch, w, a).unwrap();
            let scene = scenes.state(t, branch, w, a).unwrap();
            let assembled = backwards.assemble(t, branch).unwrap();
            assert_eq!(backwards.branch_of(t, &assembled), branch, "branch at {t}");
            same_angle("−φ3", t, -assembled.phi3, want.position.theta3);
            close("d", t, assembled.d, want.position.d, size);
            for (how, [phi3, d, phi3_dot, d_dot, phi3_ddot, d_ddot]) in [
                (
                    "motion",
                    [
                        got.position.phi3,
                        got.position.d,
                        got.velocity.phi3,
                        got.velocity.d,
                        got.acceleration.phi3,
                        got.acceleration.d,
                    ],
                ),
                (
                    "scene",
                    [
                        scene.phi3,
                        scene.d,
                        scene.phi3_dot,
                        scene.d_dot,
                        scene.phi3_ddot,
                        scene.d_ddot,
                    ],
                ),
            ] {
                same_angle(how, t, -phi3, want.position.theta3);
                close(how, t, d, want.position.d, size);
                close(how, t, -phi3_dot, want.velocity.theta3, w);
                close(how, t, d_dot, want.velocity.d, size * w);
                close(how, t, -phi3_ddot, want.acceleration.theta3, w * w);
                close(how, t, d_ddot, want.acceleration.d, size * w * w);
            }
            let guess = SliderBackwardsUnknowns {
                phi3: got.position.phi3 - 0.02,
                d: got.position.d + 1.0,
            };
            let solved = backwards.position(t, &guess, &options).unwrap().value;
            same_angle("Newton φ3", t, solved.phi3, got.position.phi3);
            close("Newton d", t, solved.d, got.position.d, size);
        }
    }
}

fn watt() -> WattSixBar<f64> {
    common::watt_six_bar()
}

#[test]
fn watt_six_bar_backwards_matches_the_shipped_one_on_every_branch() {
    let shipped = watt();
    let backwards = WattBackwards {
        l1: 180.0,
        l2: 80.0,
        l3: 200.0,
        l4: 150.0,
        l5: 100.0,
        beta: 0.8,
        l6: 220.0,
        l7: 160.0,
        g: 300f64.hypot(150.0),
        phi: 150f64.atan2(300.0),
    };
    let scenes = backwards.scenes().unwrap();
    let (w, a) = (RATE, ACCELERATION);
    let mut compared = 0;
    for branches in BRANCHES.into_iter().flat_map(|b| BRANCHES.map(|c| [b, c])) {
        for t in inputs() {
            // The second loop does not close everywhere.
            let Ok(want) = shipped.motion(t, branches, w, a) else {
                assert!(backwards.assemble(t, branches).is_err(), "assembles at {t}");
                continue;
            };
            compared += 1;
            let got = backwards.motion(t, branches, w, a).unwrap();
            let assembled = backwards.assemble(t, branches).unwrap();
            assert_eq!(backwards.branch_of(t, &assembled), branches, "at {t}");
            let (q, v, acc) = (got.position, got.velocity, got.acceleration);
            let (p, pv, pa) = (want.position, want.velocity, want.acceleration);
            same_angle("θ3", t, q.theta3, p.theta3);
            same_angle("−ψ4", t, -q.psi4, p.theta4);
            same_angle("−ψ5", t, -q.psi5, p.theta5);
            same_angle("θ6", t, q.theta6, p.theta6);
            same_angle("assembled ψ5", t, assembled.psi5, q.psi5);
            for (what, got, want) in [
                ("ω3", v.theta3, pv.theta3),
                ("−ψ̇4", -v.psi4, pv.theta4),
                ("−ψ̇5", -v.psi5, pv.theta5),
                ("ω6", v.theta6, pv.theta6),
            ] {
                close(what, t, got, want, 10.0 * w);
            }
            for (what, got, want) in [
                ("α3", acc.theta3, pa.theta3),
                ("−ψ̈4", -acc.psi4, pa.theta4),
                ("−ψ̈5", -acc.psi5, pa.theta5),
                ("α6", acc.theta6, pa.theta6),
            ] {
                close(what, t, got, want, 100.0 * w * w);
            }
            let scene = scenes.output(t, branches, w, a).unwrap();
            same_angle("scene ψ4", t, scene.psi4, q.psi4);
            same_angle("scene ψ5", t, scene.psi5, q.psi5);
            same_angle("scene θ6", t, scene.theta6, q.theta6);
            close("scene ψ̇5", t, scene.psi5_dot, v.psi5, 10.0 * w);
            close("scene ω6", t, scene.theta6_dot, v.theta6, 10.0 * w);
            close("scene ψ̈5", t, scene.psi5_ddot, acc.psi5, 100.0 * w * w);
            close("scene α6", t, scene.theta6_ddot, acc.theta6, 100.0 * w * w);
        }
    }
    assert!(compared > 360, "only {compared} positions assemble");
}

#[test]
fn stephenson_backwards_reduced_newton_matches_the_shipped_one() {
    let (shipped, start): (StephensonSixBar<f64>, _) =
        mechgen_tests::examples::stephenson_six_bar();
    // `mechgen_tests::examples::stephenson_six_bar`'s dimensions.
    let backwards = StephensonBackwards {
        l1: 100.0,
        l2: 20.0,
        l3: 117.0,
        bc: 60.0,
        cd: 63.0,
        beta: -0.97,
        l4: 52.0,
        l6: 85.0,
        g: 189f64.hypot(-26.0),
        phi: (-26f64).atan2(189.0),
    };
    let options = NewtonOptions::default();
    let (w, a) = (RATE, ACCELERATION);
    let mut q = shipped.position(0.0, &start, &options).unwrap().value;
    for degree in (0..360).step_by(5) {
        let t = f64::from(degree).to_radians();
        q = shipped.position(t, &q, &options).unwrap().value;
        let want = shipped.motion_near(t, &q, &options, w, a).unwrap().value;
        // A guess a little off the solution, the last angle measured backwards.
        let guess = StephensonBackwardsUnknowns {
            theta3: q.theta3 + 0.01,
            theta4: q.theta4 - 0.01,
            theta5: q.theta5 + 0.01,
            psi6: -q.theta6 + 0.01,
        };
        let got = backwards
            .motion_near(t, &guess, &options, w, a)
            .unwrap()
            .value;
        let (p, pv, pa) = (want.position, want.velocity, want.acceleration);
        let (g, gv, ga) = (got.position, got.velocity, got.acceleration);
        same_angle("θ3", t, g.theta3, p.theta3);
        same_angle("θ4", t, g.theta4, p.theta4);
        same_angle("θ5", t, g.theta5, p.theta5);
        same_angle("−ψ6", t, -g.psi6, p.theta6);
        for (what, got, want) in [("ω5", gv.theta5, pv.theta5), ("−ψ̇6", -gv.psi6, pv.theta6)]
        {
            close(what, t, got, want, 100.0 * w);
        }
        for (what, got, want) in [("α5", ga.theta5, pa.theta5), ("−ψ̈6", -ga.psi6, pa.theta6)]
        {
            close(what, t, got, want, 1e4 * w * w);
        }
        let solved = backwards.position(t, &guess, &options).unwrap().value;
        same_angle("position −ψ6", t, -solved.psi6, p.theta6);
    }
}

mechanism! {
    /// The four-bar with its crank's angle offset by `gamma`: the loop turns the crank by the
    /// sum `theta2 + gamma`.
    pub struct OffsetCrank {
        params: l1, l2, l3, l4, gamma: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ (theta2 + gamma) + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        generate: position, velocity, acceleration, sensitivities;
    }
}

/// An angle given as a sum is taken of the exact sum, not of its rounding (an adversarial
/// review found these `Ok`s up to 700 times less accurate than they said): a crank ten
/// thousand turns round with an offset, θ2 = 62,833 and γ = 0.3, is the shipped four-bar at
/// (62,833.3 mod 2π) = 1.4469282041352307 (mpmath at 60 digits). Rounded first, its θ4 was
/// 1.5e-12 rad off where its accuracy said 8.3e-15.
#[test]
fn a_crank_turned_ten_thousand_times_with_an_offset_is_exact() {
    let offset = OffsetCrank {
        l1: 180.0_f64,
        l2: 80.0,
        l3: 200.0,
        l4: 150.0,
        gamma: 0.3,
    };
    let shipped = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let reduced = 1.4469282041352307_f64;
    for branch in [Branch::Open, Branch::Crossed] {
        let got = offset.motion(62833.0, branch, 1.0, 0.5).unwrap();
        let want = shipped.motion(reduced, branch, 1.0, 0.5).unwrap();
        let pairs = [
            (got.position.theta3, want.position.theta3, 2e-14),
            (got.position.theta4, want.position.theta4, 2e-14),
            (got.velocity.theta3, want.velocity.theta3, 1e-13),
            (got.velocity.theta4, want.velocity.theta4, 1e-13),
            (got.acceleration.theta3, want.acceleration.theta3, 1e-13),
            (got.acceleration.theta4, want.acceleration.theta4, 1e-13),
        ];
        for (got, want, within) in pairs {
            assert!(
                (got - want).abs() <= within,
                "{branch:?}: {got} against {want}"
            );
        }
        let got = offset.sensitivities(62833.0, &got.position).unwrap();
        let want = shipped.sensitivities(reduced, &want.position).unwrap();
        let pairs = [
            (got.l1, want.l1),
            (got.l2, want.l2),
            (got.l3, want.l3),
            (got.l4, want.l4),
        ];
        for (got, want) in pairs {
            for (got, want) in [(got.theta3, want.theta3), (got.theta4, want.theta4)] {
                let within = 1e-12 * want.abs().max(1e-3);
                assert!(
                    (got - want).abs() <= within,
                    "{branch:?}: {got} against {want}"
                );
            }
        }
    }
}

/// Angle parameters far out, taken of the exact sum with the unknown they offset: the Watt
/// six-bar's extension at β = 0.8 + 10⁶ turns is the one at (β mod 2π) = 0.799999999367353,
/// and a coupler point at δ = 10¹² rad the one at (δ mod 2π) = −0.6576247591367864 (mpmath).
/// Rounded first, θ6 was 1.4e-10 rad off where its accuracy said 1.4e-14, and the coupler
/// point's sensitivities 6.1e-5 relative off.
#[test]
fn angle_parameters_far_out_are_taken_of_the_exact_sum() {
    let far = 0.8 + 1e6 * std::f64::consts::TAU;
    let watt = |beta| {
        WattSixBar::new(
            [180.0, 80.0, 200.0, 150.0],
            100.0,
            beta,
            220.0,
            160.0,
            (300.0, 150.0),
        )
        .unwrap()
    };
    let (got, want) = (watt(far), watt(0.799999999367353));
    let branches = [Branch::Open, Branch::Open];
    let (got, want) = (
        got.motion(1.0, branches, 1.0, 0.0).unwrap(),
        want.motion(1.0, branches, 1.0, 0.0).unwrap(),
    );
    for (got, want) in [
        (got.position.theta5, want.position.theta5),
        (got.position.theta6, want.position.theta6),
        (got.velocity.theta6, want.velocity.theta6),
        (got.acceleration.theta6, want.acceleration.theta6),
    ] {
        assert!((got - want).abs() <= 1e-13, "{got} against {want}");
    }

    let coupler = |delta| {
        FourBar::new(180.0, 80.0, 200.0, 150.0)
            .and_then(|l| l.with_coupler_point(100.0, delta))
            .unwrap()
    };
    let (got, want) = (coupler(1e12), coupler(-0.6576247591367864));
    let position = want.assemble(1.0, Branch::Open).unwrap();
    let (points, expected) = (
        got.points(1.0, &position).unwrap().coupler_point,
        want.points(1.0, &position).unwrap().coupler_point,
    );
    assert!(
        (points - expected).norm() <= 1e-13,
        "{points:?} against {expected:?}"
    );
    let (got, want) = (
        got.point_sensitivities(1.0, &position).unwrap(),
        want.point_sensitivities(1.0, &position).unwrap(),
    );
    for (got, want) in [
        (got.delta.coupler_point, want.delta.coupler_point),
        (got.l3.coupler_point, want.l3.coupler_point),
        (got.a.coupler_point, want.a.coupler_point),
    ] {
        assert!(
            (got - want).norm() <= 1e-13 * want.norm(),
            "{got:?} against {want:?}"
        );
    }
}
