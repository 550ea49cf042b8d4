//! A two-loop declaration (a Watt-type six-bar: a four-bar whose rocker drives a second
//! dyad) exercises four unknowns, the stack LU solve, and loops that share an unknown.
//! Checked against successive circle intersections and finite differences.

use mechgen::{Branch, NewtonOptions, mechanism};

mechanism! {
    /// Four-bar O2 A B O4 whose rocker, extended by `l4b` at `beta` to C, drives the dyad
    /// C D O6 with the ground pivot O6 at `g @ phi`.
    pub struct SixBar {
        params: l1, l2, l3, l4, l4b, beta: angle, l5, l6, g, phi: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, theta5: angle, theta6: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        loop: l1 @ 0 + l4b @ (theta4 + beta) + l5 @ theta5 - l6 @ theta6 - g @ phi;
        point d = g @ phi + l6 @ theta6;
    }
}

/// The ground pivot O6.
const O6: (f64, f64) = (300.0, 150.0);

fn linkage() -> SixBar<f64> {
    SixBar {
        l1: 180.0,
        l2: 80.0,
        l3: 200.0,
        l4: 150.0,
        l4b: 100.0,
        beta: 0.8,
        l5: 220.0,
        l6: 160.0,
        g: O6.0.hypot(O6.1),
        phi: O6.1.atan2(O6.0),
    }
}

type P = (f64, f64);

/// The intersection of circles (p, r) and (q, s) on the left (+1) or right (-1) of p→q.
fn intersect(p: P, r: f64, q: P, s: f64, side: f64) -> P {
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let d = dx.hypot(dy);
    let a = (r * r - s * s + d * d) / (2.0 * d);
    let h = (r * r - a * a).sqrt();
    (
        p.0 + (a * dx - side * h * dy) / d,
        p.1 + (a * dy + side * h * dx) / d,
    )
}

fn angle(from: P, to: P) -> f64 {
    (to.1 - from.1).atan2(to.0 - from.0)
}

/// Joint positions by geometry alone, on the branch given by the two sides.
fn by_circles(theta2: f64, sides: (f64, f64)) -> [f64; 4] {
    let l = linkage();
    let o4 = (l.l1, 0.0);
    let a = (l.l2 * theta2.cos(), l.l2 * theta2.sin());
    let b = intersect(a, l.l3, o4, l.l4, sides.0);
    let theta4 = angle(o4, b);
    let c = (
        o4.0 + l.l4b * (theta4 + l.beta).cos(),
        o4.1 + l.l4b * (theta4 + l.beta).sin(),
    );
    let o6 = O6;
    let d = intersect(c, l.l5, o6, l.l6, sides.1);
    [angle(a, b), theta4, angle(c, d), angle(o6, d)]
}

fn wrapped_difference(a: f64, b: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    ((a - b) % tau + 1.5 * tau) % tau - 0.5 * tau
}

#[test]
fn six_bar_matches_circle_intersections_and_finite_differences() {
    let options = NewtonOptions::default();
    let mut q = SixBarUnknowns::from_array(by_circles(0.0, (1.0, 1.0)));
    let (omega, h) = (5.0, 1e-5);
    for degree in 0..360 {
        let theta2 = f64::from(degree).to_radians();
        // The slope where `q` was solved, a degree back (at 0° for the first).
        let solved_at = f64::from(degree.max(1) - 1).to_radians();
        let slope = linkage().velocity(solved_at, &q, 1.0).unwrap().to_array();
        let predicted = q.to_array();
        let guess = SixBarUnknowns::from_array(std::array::from_fn(|i| {
            predicted[i] + slope[i] * 1f64.to_radians()
        }));
        let solved = linkage().position(theta2, &guess, &options).unwrap();
        q = solved.value;
        assert!(solved.residual_norm < 1e-10);

        let expected = by_circles(theta2, (1.0, 1.0));
        for (got, want) in q.to_array().iter().zip(expected) {
            assert!(
                wrapped_difference(*got, want).abs() < 1e-10,
                "{degree}°: {got} vs {want}"
            );
        }

        let plus = linkage()
            .position(theta2 + h, &q, &options)
            .unwrap()
            .value
            .to_array();
        let minus = linkage()
            .position(theta2 - h, &q, &options)
            .unwrap()
            .value
            .to_array();
        let velocity = linkage().velocity(theta2, &q, omega).unwrap();
        for ((p, m), v) in plus.iter().zip(minus).zip(velocity.to_array()) {
            let estimate = (p - m) / (2.0 * h) * omega;
            assert!(
                (estimate - v).abs() < 1e-6 * omega,
                "{degree}°: {v} vs {estimate}"
            );
        }

        let acceleration = linkage()
            .acceleration(theta2, &q, omega, &velocity, 0.0)
            .unwrap();
        let v_plus = linkage()
            .velocity(theta2 + h, &SixBarUnknowns::from_array(plus), omega)
            .unwrap();
        let v_minus = linkage()
            .velocity(theta2 - h, &SixBarUnknowns::from_array(minus), omega)
            .unwrap();
        let pairs = v_plus.to_array().into_iter().zip(v_minus.to_array());
        for ((p, m), a) in pairs.zip(acceleration.to_array()) {
            let estimate = (p - m) / (2.0 * h) * omega;
            assert!(
                (estimate - a).abs() < 1e-5 * omega * omega,
                "{degree}°: {a} vs {estimate}"
            );
        }

        // Both loops close in closed form, one after the other: the four-bar, then the dyad.
        let closed = linkage()
            .assemble(theta2, [Branch::Open, Branch::Open])
            .unwrap();
        assert_eq!(
            linkage().branch_of(theta2, &q),
            [Branch::Open, Branch::Open]
        );
        for (got, want) in closed.to_array().iter().zip(q.to_array()) {
            assert!(wrapped_difference(*got, want).abs() < 1e-10, "{degree}°");
        }

        let d = linkage().points(theta2, &q).unwrap().d;
        let d_expected = (O6.0 + 160.0 * q.theta6.cos(), O6.1 + 160.0 * q.theta6.sin());
        assert!((d.x - d_expected.0).abs() < 1e-9 && (d.y - d_expected.1).abs() < 1e-9);
    }
}

mechanism! {
    /// The same six-bar with its loops declared the other way round: the dyad's loop first,
    /// though it can only be solved second (it needs θ4).
    pub struct Reversed {
        params: l1, l2, l3, l4, l4b, beta: angle, l5, l6, g, phi: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle, theta5: angle, theta6: angle;
        loop: l1 @ 0 + l4b @ (theta4 + beta) + l5 @ theta5 - l6 @ theta6 - g @ phi;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
    }
}

/// Issue 14's named branches: a field per branching loop named after the unknowns it sets,
/// whatever order the loops are declared or solved in, with every loop open by default.
#[test]
fn named_branches_choose_each_loop_by_name_in_any_declaration_order() {
    let s = linkage();
    let reversed = Reversed {
        l1: s.l1,
        l2: s.l2,
        l3: s.l3,
        l4: s.l4,
        l4b: s.l4b,
        beta: s.beta,
        l5: s.l5,
        l6: s.l6,
        g: s.g,
        phi: s.phi,
    };
    let theta2 = 1.0;
    for (four_bar, dyad) in [
        (Branch::Open, Branch::Open),
        (Branch::Open, Branch::Crossed),
        (Branch::Crossed, Branch::Open),
        (Branch::Crossed, Branch::Crossed),
    ] {
        let by_name = SixBarBranches {
            theta3_theta4: four_bar,
            theta5_theta6: dyad,
        };
        let q = s.assemble(theta2, by_name).unwrap();
        // The same assembly from the array, and from the reversed declaration by name: its
        // array is in solve order, the four-bar's loop first, though declared second.
        assert_eq!(q, s.assemble(theta2, [four_bar, dyad]).unwrap());
        let r = reversed
            .assemble(
                theta2,
                ReversedBranches {
                    theta3_theta4: four_bar,
                    theta5_theta6: dyad,
                },
            )
            .unwrap();
        assert_eq!(
            [q.theta3, q.theta4, q.theta5, q.theta6],
            [r.theta3, r.theta4, r.theta5, r.theta6]
        );
        // branch_of gives the array back, which converts to the names.
        assert_eq!(SixBarBranches::from(s.branch_of(theta2, &q)), by_name);
        let motion = s.motion(theta2, by_name, 10.0, 0.0).unwrap();
        assert_eq!(motion.position, q);
    }
    let open = SixBarBranches::default();
    assert_eq!(<[Branch; 2]>::from(open), [Branch::Open; 2]);
}
