//! Declarations of several inputs. The five-bar parallel robot (two): its end effector
//! against an independent circle intersection, its rates and accelerations against finite
//! differences in both inputs (the cross terms included), its workspace against its inverse
//! kinematics, and both kinds of singularity. A 3-RRR planar parallel manipulator (three
//! inputs, three coupled loops, no closed form), declared here: its platform found by Newton
//! from the three cranks that an independent inverse kinematics gives for it.

use mechanisms::{FiveBar, FiveBarUnknowns};
use mechgen::{Branch, Error, NewtonOptions, Vec2};

/// A small deterministic generator (xorshift), so every run checks the same cases.
struct Draws(u64);

impl Draws {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn between(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.next()
    }
}

/// Robots of assorted proportions and the crank angles where each assembles, with the
/// end effector `(x, y)` found independently: the circles of radius `l2` about A1 and `l3`
/// about A2, met on the left of A1 → A2 (`Open`) or its right (`Crossed`). Only postures
/// whose distal links are not nearly aligned (`|sin| > 0.05`), where the intersection
/// itself is well conditioned.
fn cases() -> Vec<(Robot, [f64; 2], Branch, Vec2<f64>)> {
    let mut draws = Draws(0x5eed_f00d_ba55);
    let mut cases = Vec::new();
    while cases.len() < 2000 {
        let robot = Robot::new([
            draws.between(0.2, 2.0),
            draws.between(0.5, 3.0),
            draws.between(0.5, 3.0),
            draws.between(0.2, 2.0),
            draws.between(0.0, 2.0),
        ]);
        let angles = [draws.between(-3.2, 3.2), draws.between(-3.2, 3.2)];
        let branch = if draws.next() < 0.5 {
            Branch::Open
        } else {
            Branch::Crossed
        };
        let a1 = [robot.l1 * angles[0].cos(), robot.l1 * angles[0].sin()];
        let a2 = [
            robot.l5 + robot.l4 * angles[1].cos(),
            robot.l4 * angles[1].sin(),
        ];
        let (dx, dy) = (a2[0] - a1[0], a2[1] - a1[1]);
        let d = dx.hypot(dy);
        // Distance along A1 → A2 to the chord's foot, and the half chord.
        let along = (d * d + robot.l2 * robot.l2 - robot.l3 * robot.l3) / (2.0 * d);
        let half_chord_squared = robot.l2 * robot.l2 - along * along;
        if half_chord_squared <= 0.0 {
            continue;
        }
        let half_chord = half_chord_squared.sqrt();
        // sin of the angle between the distal links: the triangle A1 P A2's angle at P.
        if half_chord * d / (robot.l2 * robot.l3) < 0.05 {
            continue;
        }
        let side = if branch == Branch::Open { 1.0 } else { -1.0 };
        let (ux, uy) = (dx / d, dy / d);
        let p = Vec2 {
            x: a1[0] + along * ux - side * half_chord * uy,
            y: a1[1] + along * uy + side * half_chord * ux,
        };
        cases.push((robot, angles, branch, p));
    }
    cases
}

/// A five-bar with its lengths `[l1, l2, l3, l4, l5]` at hand (the type keeps them private).
#[derive(Debug)]
struct Robot {
    linkage: FiveBar<f64>,
    l1: f64,
    l2: f64,
    l3: f64,
    l4: f64,
    l5: f64,
}

impl Robot {
    fn new([l1, l2, l3, l4, l5]: [f64; 5]) -> Self {
        Robot {
            linkage: FiveBar::new(l1, l2, l3, l4, l5).unwrap(),
            l1,
            l2,
            l3,
            l4,
            l5,
        }
    }
}

impl std::ops::Deref for Robot {
    type Target = FiveBar<f64>;

    fn deref(&self) -> &FiveBar<f64> {
        &self.linkage
    }
}

fn end_effector(robot: &FiveBar<f64>, [t1, t4]: [f64; 2], branch: Branch) -> Vec2<f64> {
    let q = robot.assemble(t1, t4, branch).unwrap();
    robot.points(t1, t4, &q).unwrap().end_effector
}

#[test]
fn end_effector_agrees_with_a_circle_intersection() {
    let mut worst: f64 = 0.0;
    for (robot, [t1, t4], branch, expected) in cases() {
        let p = end_effector(&robot, [t1, t4], branch);
        let error = (p.x - expected.x).hypot(p.y - expected.y);
        worst = worst.max(error);
        assert!(
            error < 1e-12,
            "{robot:?} at {t1}, {t4} on {branch:?}: {p:?} != {expected:?}"
        );
        // The closed form's branch is the side of A1 → A2 that P is on, as documented.
        let q = robot.assemble(t1, t4, branch).unwrap();
        assert_eq!(robot.branch_of(t1, t4, &q), branch);
    }
    assert!(worst > 0.0, "the comparison compared something");
}

/// The crank angles at time `t` for cranks at `angles`, turning at `rates` and
/// accelerating at `accelerations` at `t = 0`.
fn at(angles: [f64; 2], rates: [f64; 2], accelerations: [f64; 2], t: f64) -> [f64; 2] {
    [0, 1].map(|k| angles[k] + rates[k] * t + 0.5 * accelerations[k] * t * t)
}

#[test]
fn rates_and_accelerations_match_finite_differences_in_both_inputs() {
    let mut draws = Draws(0xacce1);
    let h = 1e-3;
    for (robot, angles, branch, _) in cases().into_iter().step_by(10) {
        let rates = [draws.between(-3.0, 3.0), draws.between(-3.0, 3.0)];
        let accelerations = [draws.between(-5.0, 5.0), draws.between(-5.0, 5.0)];
        let [t1, t4] = angles;
        let q = robot.assemble(t1, t4, branch).unwrap();
        let v = robot.velocity(t1, t4, &q, rates[0], rates[1]).unwrap();
        let a = robot
            .acceleration(
                t1,
                t4,
                &q,
                rates[0],
                rates[1],
                &v,
                accelerations[0],
                accelerations[1],
            )
            .unwrap();
        let p_dot = robot
            .point_velocities(t1, t4, &q, rates[0], rates[1], &v)
            .unwrap()
            .end_effector;
        let p_ddot = robot
            .point_accelerations(
                t1,
                t4,
                &q,
                rates[0],
                rates[1],
                &v,
                accelerations[0],
                accelerations[1],
                &a,
            )
            .unwrap()
            .end_effector;
        let p = |t: f64| end_effector(&robot, at(angles, rates, accelerations, t), branch);
        let [far_before, before, here, after, far_after] =
            [-2.0, -1.0, 0.0, 1.0, 2.0].map(|k| p(k * h));
        let scale = robot.l1 + robot.l2 + robot.l3 + robot.l4 + robot.l5;
        // Fourth-order central differences: errors O(h⁴) of the fifth and sixth
        // derivatives, which the postures kept away from singularities keep moderate.
        let component = |v: Vec2<f64>| [v.x, v.y];
        let [fb, b, c, a, fa] = [far_before, before, here, after, far_after].map(component);
        let velocity = [0, 1].map(|i| (fb[i] - 8.0 * b[i] + 8.0 * a[i] - fa[i]) / (12.0 * h));
        let acceleration = [0, 1]
            .map(|i| (-fb[i] + 16.0 * b[i] - 30.0 * c[i] + 16.0 * a[i] - fa[i]) / (12.0 * h * h));
        let size = scale * (1.0 + rates[0].abs() + rates[1].abs()).powi(2);
        for (got, want) in [p_dot.x, p_dot.y].iter().zip(velocity) {
            assert!(
                (got - want).abs() < 1e-7 * size,
                "velocity {got} vs {want} for {robot:?}"
            );
        }
        for (got, want) in [p_ddot.x, p_ddot.y].iter().zip(acceleration) {
            assert!(
                (got - want).abs() < 1e-5 * size,
                "acceleration {got} vs {want} for {robot:?} at {angles:?}"
            );
        }
    }
}

#[test]
fn accelerations_hold_the_terms_that_cross_the_inputs() {
    // Joining two one-input solutions (each crank moving alone) misses the cross terms:
    // the full acceleration differs from their sum by them, at this posture by far more
    // than rounding.
    let robot = FiveBar::new(1.0, 2.0, 2.0, 1.0, 1.0).unwrap();
    let (t1, t4) = (2.0, 1.0);
    let q = robot.assemble(t1, t4, Branch::Open).unwrap();
    let (w1, w4) = (3.0, -2.0);
    let accelerations = |w1: f64, w4: f64| {
        let v = robot.velocity(t1, t4, &q, w1, w4).unwrap();
        let a = robot
            .acceleration(t1, t4, &q, w1, w4, &v, 0.0, 0.0)
            .unwrap();
        robot
            .point_accelerations(t1, t4, &q, w1, w4, &v, 0.0, 0.0, &a)
            .unwrap()
            .end_effector
    };
    let both = accelerations(w1, w4);
    let (left, right) = (accelerations(w1, 0.0), accelerations(0.0, w4));
    let cross = (both.x - left.x - right.x).hypot(both.y - left.y - right.y);
    assert!(cross > 0.1, "cross terms {cross}");
    // The acceleration is a quadratic form in the rates: the cross term is bilinear.
    let doubled = accelerations(w1, 2.0 * w4);
    let doubled_right = accelerations(0.0, 2.0 * w4);
    let cross_doubled =
        (doubled.x - left.x - doubled_right.x).hypot(doubled.y - left.y - doubled_right.y);
    assert!((cross_doubled - 2.0 * cross).abs() < 1e-12 * cross);
}

#[test]
fn closed_form_and_newton_agree_and_motion_is_the_separate_solves() {
    let options = NewtonOptions::default();
    for (robot, [t1, t4], branch, _) in cases().into_iter().step_by(20) {
        let (w1, w4, a1, a4) = (1.5, -0.5, 2.0, 0.25);
        let motion = robot.motion(t1, t4, branch, w1, w4, a1, a4).unwrap();
        let q = robot.assemble(t1, t4, branch).unwrap();
        let v = robot.velocity(t1, t4, &q, w1, w4).unwrap();
        let a = robot.acceleration(t1, t4, &q, w1, w4, &v, a1, a4).unwrap();
        for (got, want) in [
            (motion.position, q),
            (motion.velocity, v),
            (motion.acceleration, a),
        ] {
            for (g, w) in got.to_array().iter().zip(want.to_array()) {
                assert!((g - w).abs() < 1e-9 * (1.0 + w.abs()), "{g} vs {w}");
            }
        }
        // Newton from a guess off by a few degrees lands on the same position.
        let guess = FiveBarUnknowns {
            theta2: q.theta2 + 0.03,
            theta3: q.theta3 - 0.02,
        };
        let near = robot.motion_near(t1, t4, &guess, &options, w1, w4, a1, a4);
        if let Ok(near) = near {
            let near = near.value;
            for (g, w) in near.position.to_array().iter().zip(q.to_array()) {
                let difference = (g - w + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                    - std::f64::consts::PI;
                assert!(difference.abs() < 1e-9, "{g} vs {w}");
            }
        }
    }
}

#[test]
fn inverse_kinematics_and_workspace_round_trip() {
    let mut draws = Draws(0x1a2b);
    let robot = FiveBar::new(1.0, 1.5, 1.5, 1.0, 0.8).unwrap();
    let mut reached = 0;
    for _ in 0..2000 {
        let p = Vec2 {
            x: draws.between(-3.0, 3.8),
            y: draws.between(-3.0, 3.0),
        };
        let inside = robot.reaches(p);
        let elbows = [1.0, -1.0];
        match robot.inverse(p, elbows) {
            None => assert!(!inside, "{p:?} is reachable but has no inverse"),
            Some([t1, t4]) => {
                assert!(inside);
                // Either branch puts P at one of the two intersections: one of them is p.
                let hits = [Branch::Open, Branch::Crossed]
                    .into_iter()
                    .filter_map(|branch| robot.assemble(t1, t4, branch).ok())
                    .map(|q| robot.points(t1, t4, &q).unwrap().end_effector)
                    .any(|found| (found.x - p.x).hypot(found.y - p.y) < 1e-9);
                assert!(hits, "{p:?} from cranks {t1}, {t4}");
                reached += 1;
            }
        }
    }
    assert!(reached > 200, "{reached} points reached");
    // Far points and points too near a motor are outside.
    assert!(!robot.reaches(Vec2 { x: 10.0, y: 0.0 }));
    assert!(!robot.reaches(Vec2 { x: 0.1, y: 0.1 }));
    assert_eq!(robot.inverse(Vec2 { x: 10.0, y: 0.0 }, [1.0, -1.0]), None);
}

#[test]
fn a_parallel_singularity_is_singular() {
    // Distal links stretched in one line (A1 = (−1, 0), A2 = (2, 0), l2 + l3 = 3): P at
    // (0.5, 0) can still move up or down with both motors held.
    let robot = FiveBar::new(1.0, 1.5, 1.5, 1.0, 1.0).unwrap();
    let (t1, t4) = (std::f64::consts::PI, 0.0);
    let q = robot.assemble(t1, t4, Branch::Open).unwrap();
    let p = robot.points(t1, t4, &q).unwrap().end_effector;
    assert!((p.x - 0.5).abs() < 1e-7 && p.y.abs() < 1e-7, "{p:?}");
    let near = robot.singularities(t1, t4, &q);
    assert!(near.parallel < 1e-7, "{near:?}");
    assert!(matches!(
        robot.velocity(t1, t4, &q, 1.0, 0.0),
        Err(Error::Singular { .. })
    ));
    // With the motors a little further apart, the loops cannot close there.
    let wider = FiveBar::new(1.0, 1.5, 1.5, 1.0, 1.01).unwrap();
    assert!(matches!(
        wider.assemble(t1, t4, Branch::Open),
        Err(Error::CannotAssemble { .. })
    ));
}

#[test]
fn at_a_serial_singularity_the_end_effector_cannot_move_along_the_leg() {
    // The left leg stretched straight (θ2 = θ1): P on the outer edge of the left leg's
    // annulus. The forward kinematics are regular, but whatever the motors do, P's velocity
    // has no component along the leg.
    let robot = FiveBar::new(1.0, 1.5, 1.5, 1.0, 1.0).unwrap();
    let t1: f64 = 1.2;
    let p = Vec2 {
        x: 2.5 * t1.cos(),
        y: 2.5 * t1.sin(),
    };
    // The right crank that reaches this P, with its elbow outward.
    let [t1_found, t4] = robot
        .inverse(p, [1.0, -1.0])
        .expect("on the workspace's edge");
    assert!((t1_found - t1).abs() < 1e-6);
    let branch = [Branch::Open, Branch::Crossed]
        .into_iter()
        .find(|&branch| {
            robot.assemble(t1, t4, branch).is_ok_and(|q| {
                let found = robot.points(t1, t4, &q).unwrap().end_effector;
                (found.x - p.x).hypot(found.y - p.y) < 1e-6
            })
        })
        .unwrap();
    let q = robot.assemble(t1, t4, branch).unwrap();
    let near = robot.singularities(t1, t4, &q);
    assert!(near.serial[0] < 1e-6 && near.parallel > 0.1, "{near:?}");
    let along = [t1.cos(), t1.sin()];
    for (w1, w4) in [(1.0, 0.0), (0.0, 1.0), (2.0, -3.0)] {
        let v = robot.velocity(t1, t4, &q, w1, w4).unwrap();
        let p_dot = robot
            .point_velocities(t1, t4, &q, w1, w4, &v)
            .unwrap()
            .end_effector;
        let radial = p_dot.x * along[0] + p_dot.y * along[1];
        assert!(
            radial.abs() < 1e-5,
            "radial speed {radial} at rates {w1}, {w4}"
        );
    }
}

#[test]
fn f32_agrees_with_f64() {
    for (robot, [t1, t4], branch, _) in cases().into_iter().step_by(50) {
        let single = FiveBar::new(
            robot.l1 as f32,
            robot.l2 as f32,
            robot.l3 as f32,
            robot.l4 as f32,
            robot.l5 as f32,
        )
        .unwrap();
        let (t1s, t4s) = (t1 as f32, t4 as f32);
        let q = single.assemble(t1s, t4s, branch).unwrap();
        let p = single.points(t1s, t4s, &q).unwrap().end_effector;
        let expected = end_effector(&robot, [t1, t4], branch);
        let size = (robot.l1 + robot.l2 + robot.l3 + robot.l4 + robot.l5) as f32;
        assert!((p.x - expected.x as f32).abs() < 1e-4 * size);
        assert!((p.y - expected.y as f32).abs() < 1e-4 * size);
    }
}

#[test]
fn bad_arguments_are_errors() {
    let robot = FiveBar::new(1.0, 2.0, 2.0, 1.0, 1.0).unwrap();
    assert!(matches!(
        robot.assemble(f64::NAN, 1.0, Branch::Open),
        Err(Error::NonFinite {
            quantity: "input `theta1`"
        })
    ));
    assert!(matches!(
        robot.assemble(1.0, f64::INFINITY, Branch::Open),
        Err(Error::NonFinite {
            quantity: "input `theta4`"
        })
    ));
    let q = robot.assemble(2.0, 1.0, Branch::Open).unwrap();
    assert!(matches!(
        robot.velocity(2.0, 1.0, &q, 1.0, f64::NAN),
        Err(Error::NonFinite {
            quantity: "input rate `theta4_dot`"
        })
    ));
    assert!(FiveBar::new(1.0, -2.0, 2.0, 1.0, 1.0).is_err());
    assert!(FiveBar::new(1.0, 2.0, 2.0, 1.0, -1.0).is_err());
}

mechgen::mechanism! {
    /// A 3-RRR planar parallel manipulator: three legs, each a motor at `(ak_x, ak_y)`
    /// turning a proximal link `pk` at the input `thetak`, a distal link `dk` at `psik`, and
    /// the platform's vertex k at `r` from its centre `(x, y)`, at `phi` plus the vertex's
    /// own angle. Three inputs, six unknowns, three coupled loops: no closed form.
    pub struct ThreeRrr {
        params: a1_x, a1_y, a2_x, a2_y, a3_x, a3_y, p1, p2, p3, d1, d2, d3, r,
            gamma2: angle, gamma3: angle;
        input: theta1: angle, theta2: angle, theta3: angle;
        unknowns: x: length, y: length, phi: angle, psi1: angle, psi2: angle, psi3: angle;
        loop: a1_x @ 0 + a1_y @ (pi / 2) + p1 @ theta1 + d1 @ psi1 - x @ 0 - y @ (pi / 2)
            - r @ phi;
        loop: a2_x @ 0 + a2_y @ (pi / 2) + p2 @ theta2 + d2 @ psi2 - x @ 0 - y @ (pi / 2)
            - r @ (phi + gamma2);
        loop: a3_x @ 0 + a3_y @ (pi / 2) + p3 @ theta3 + d3 @ psi3 - x @ 0 - y @ (pi / 2)
            - r @ (phi + gamma3);
        point centre = x @ 0 + y @ (pi / 2);
    }
}

/// A symmetric 3-RRR: motors on a circle of radius 2 at 90°, 210° and 330°, links 1 and 1.2,
/// a platform of radius 0.4 with its vertices 120° apart.
fn three_rrr() -> ThreeRrr<f64> {
    let motor = |degrees: f64| {
        let (s, c) = degrees.to_radians().sin_cos();
        (2.0 * c, 2.0 * s)
    };
    let (a1, a2, a3) = (motor(90.0), motor(210.0), motor(330.0));
    ThreeRrr {
        a1_x: a1.0,
        a1_y: a1.1,
        a2_x: a2.0,
        a2_y: a2.1,
        a3_x: a3.0,
        a3_y: a3.1,
        p1: 1.0,
        p2: 1.0,
        p3: 1.0,
        d1: 1.2,
        d2: 1.2,
        d3: 1.2,
        r: 0.4,
        gamma2: 120f64.to_radians(),
        gamma3: 240f64.to_radians(),
    }
}

/// The inverse kinematics of the symmetric 3-RRR, computed independently: for the platform
/// at `(x, y, phi)`, each leg's crank and distal angles (the elbow on the left of the line
/// from the motor to the vertex), or `None` where a leg cannot reach.
fn three_rrr_inverse(linkage: &ThreeRrr<f64>, [x, y, phi]: [f64; 3]) -> Option<[[f64; 2]; 3]> {
    let motors = [
        (linkage.a1_x, linkage.a1_y),
        (linkage.a2_x, linkage.a2_y),
        (linkage.a3_x, linkage.a3_y),
    ];
    let offsets = [0.0, linkage.gamma2, linkage.gamma3];
    let mut legs = [[0.0; 2]; 3];
    for k in 0..3 {
        let (p, d) = (
            [linkage.p1, linkage.p2, linkage.p3][k],
            [linkage.d1, linkage.d2, linkage.d3][k],
        );
        let vertex = (
            x + linkage.r * (phi + offsets[k]).cos(),
            y + linkage.r * (phi + offsets[k]).sin(),
        );
        let (dx, dy) = (vertex.0 - motors[k].0, vertex.1 - motors[k].1);
        let reach = dx.hypot(dy);
        let cosine = (p * p + reach * reach - d * d) / (2.0 * p * reach);
        if cosine.abs() >= 1.0 {
            return None;
        }
        let theta = dy.atan2(dx) + cosine.acos();
        let elbow = (motors[k].0 + p * theta.cos(), motors[k].1 + p * theta.sin());
        let psi = (vertex.1 - elbow.1).atan2(vertex.0 - elbow.0);
        legs[k] = [theta, psi];
    }
    Some(legs)
}

#[test]
fn a_three_rrr_platform_is_found_from_its_three_cranks() {
    let linkage = three_rrr();
    let options = NewtonOptions::default();
    let mut draws = Draws(0x3a3);
    let mut solved = 0;
    for _ in 0..200 {
        let pose = [
            draws.between(-0.4, 0.4),
            draws.between(-0.4, 0.4),
            draws.between(-0.5, 0.5),
        ];
        let Some(legs) = three_rrr_inverse(&linkage, pose) else {
            continue;
        };
        let [theta1, theta2, theta3] = legs.map(|[theta, _]| theta);
        let exact = ThreeRrrUnknowns {
            x: pose[0],
            y: pose[1],
            phi: pose[2],
            psi1: legs[0][1],
            psi2: legs[1][1],
            psi3: legs[2][1],
        };
        // Newton from a guess off by a little in every unknown.
        let guess = ThreeRrrUnknowns {
            x: exact.x + 0.02,
            y: exact.y - 0.01,
            phi: exact.phi + 0.02,
            psi1: exact.psi1 - 0.02,
            psi2: exact.psi2 + 0.01,
            psi3: exact.psi3 + 0.02,
        };
        let found = linkage
            .position(theta1, theta2, theta3, &guess, &options)
            .unwrap()
            .value;
        for (got, want) in found.to_array().iter().zip(exact.to_array()) {
            assert!((got - want).abs() < 1e-9, "{found:?} vs {exact:?}");
        }
        // The platform's rates by a central difference of Newton's positions.
        let rates = [0.3, -0.2, 0.5];
        let v = linkage
            .velocity(theta1, theta2, theta3, &found, rates[0], rates[1], rates[2])
            .unwrap();
        let h = 1e-6;
        let at = |t: f64| {
            linkage
                .position(
                    theta1 + rates[0] * t,
                    theta2 + rates[1] * t,
                    theta3 + rates[2] * t,
                    &found,
                    &options,
                )
                .unwrap()
                .value
                .to_array()
        };
        let (before, after) = (at(-h), at(h));
        for ((b, a), rate) in before.iter().zip(after).zip(v.to_array()) {
            assert!(((a - b) / (2.0 * h) - rate).abs() < 1e-6, "{rate}");
        }
        // motion_near's accelerations are those of the separate solves.
        let accelerations = [0.1, 0.0, -0.3];
        let near = linkage
            .motion_near(
                theta1,
                theta2,
                theta3,
                &guess,
                &options,
                rates[0],
                rates[1],
                rates[2],
                accelerations[0],
                accelerations[1],
                accelerations[2],
            )
            .unwrap()
            .value;
        let a = linkage
            .acceleration(
                theta1,
                theta2,
                theta3,
                &found,
                rates[0],
                rates[1],
                rates[2],
                &v,
                accelerations[0],
                accelerations[1],
                accelerations[2],
            )
            .unwrap();
        for (x, y) in near.acceleration.to_array().iter().zip(a.to_array()) {
            assert!((x - y).abs() < 1e-9 * (1.0 + y.abs()), "{x} vs {y}");
        }
        solved += 1;
    }
    assert!(solved > 50, "{solved} poses");
}
