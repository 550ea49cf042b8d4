//! Textbook mechanisms the project does not ship, declared as a user would and checked
//! against geometry computed here independently: a Scotch yoke, an elliptic trammel driven
//! by one of its sliders, and a Whitworth quick-return (an inverted slider-crank with a
//! second loop to its ram). The slider-crank driven by its slider and the slider on a 30°
//! line are in `declarations.rs`; the Watt six-bar ships.

use mechgen::{Branch, mechanism};

mechanism! {
    /// Scotch yoke: the crank pin A (`r` at `theta2`) slides in a vertical slot of a yoke
    /// that moves along x: the yoke at `x`, the pin `y` up the slot.
    pub struct ScotchYoke {
        params: r;
        input: theta2: angle;
        unknowns: x: length, y: length;
        loop: r @ theta2 - x @ 0 - y @ (pi / 2);
    }
}

mechanism! {
    /// Elliptic trammel: a rod of length `l` with one end A on the x axis at `x` (the
    /// input, a slider) and the other B on the y axis at `y`; the rod at `theta`. Its point
    /// P, `a` from A along the rod, draws an ellipse of semi-axes `l − a` and `a`.
    pub struct Trammel {
        params: l, a;
        input: x: length;
        unknowns: theta: angle, y: length;
        loop: x @ 0 + l @ theta - y @ (pi / 2);
        point p = x @ 0 + a @ theta;
    }
}

mechanism! {
    /// Whitworth quick-return: the crank O2 A (`r` at `theta2`, O2 at the origin) drives a
    /// block at A along the slotted lever through O4 = (0, −d) (`s` from O4, at `theta4`);
    /// the lever's end B (`b` from O4) drives the link B C (`c` at `theta5`) to the ram C,
    /// which slides at height `h` at `x`. With `d < r` the lever turns fully, and the ram's
    /// stroke back is quicker than its stroke out.
    pub struct Whitworth {
        params: r, d, b, c, h;
        input: theta2: angle;
        unknowns: theta4: angle, s: length, theta5: angle, x: length;
        loop: r @ theta2 + d @ (pi / 2) - s @ theta4;
        loop: -d @ (pi / 2) + b @ theta4 + c @ theta5 - x @ 0 - h @ (pi / 2);
        point ram = x @ 0 + h @ (pi / 2);
    }
}

fn close(a: f64, b: f64, tolerance: f64) -> bool {
    (a - b).abs() <= tolerance * b.abs().max(1.0)
}

/// The angle `a` as the closest to `b` modulo a turn.
fn near(a: f64, b: f64) -> f64 {
    let turn = std::f64::consts::TAU;
    b + ((a - b + turn / 2.0).rem_euclid(turn) - turn / 2.0)
}

#[test]
fn a_scotch_yoke_moves_its_yoke_by_the_cosine() {
    let yoke = ScotchYoke { r: 30.0 };
    let (w, alpha) = (4.0, -2.0);
    for step in 0..72 {
        let theta2 = f64::from(step) * 5f64.to_radians();
        let (s, c) = theta2.sin_cos();
        let q = yoke.assemble(theta2).unwrap();
        let v = yoke.velocity(theta2, &q, w).unwrap();
        let a = yoke.acceleration(theta2, &q, w, &v, alpha).unwrap();
        assert!(
            close(q.x, 30.0 * c, 1e-13) && close(q.y, 30.0 * s, 1e-13),
            "{q:?}"
        );
        assert!(close(v.x, -30.0 * w * s, 1e-13), "{v:?}");
        assert!(close(a.x, -30.0 * (alpha * s + w * w * c), 1e-13), "{a:?}");
        assert!(close(a.y, 30.0 * (alpha * c - w * w * s), 1e-13), "{a:?}");
    }
}

#[test]
fn an_elliptic_trammel_draws_its_ellipse() {
    let trammel = Trammel { l: 100.0, a: 30.0 };
    let (rate, acceleration) = (5.0, 1.5);
    for step in 1..40 {
        let x = -100.0 + 5.0 * f64::from(step);
        for branch in [Branch::Open, Branch::Crossed] {
            let q = trammel.assemble(x, branch).unwrap();
            // x + l·cos θ = 0 and y = l·sin θ: B on the y axis, above or below.
            assert!(close(q.theta.cos(), -x / 100.0, 1e-14), "{q:?}");
            assert!(close(q.y, 100.0 * q.theta.sin(), 1e-13), "{q:?}");
            let p = trammel.points(x, &q).unwrap().p;
            let on_ellipse = (p.x / 70.0).powi(2) + (p.y / 30.0).powi(2);
            assert!(close(on_ellipse, 1.0, 1e-13), "{p:?}");
            // θ̇ from x + l·cos θ = 0: ẋ = l·sin θ·θ̇.
            let v = trammel.velocity(x, &q, rate).unwrap();
            assert!(
                close(v.theta, rate / (100.0 * q.theta.sin()), 1e-12),
                "{v:?}"
            );
            let a = trammel.acceleration(x, &q, rate, &v, acceleration).unwrap();
            // ẍ = l·(cos θ·θ̇² + sin θ·θ̈).
            let expected =
                (acceleration / 100.0 - q.theta.cos() * v.theta * v.theta) / q.theta.sin();
            assert!(close(a.theta, expected, 1e-11), "{a:?}");
        }
    }
}

/// The Whitworth's lever angle, slide and ram position from the crank angle, by plain
/// geometry: the lever points from O4 to A, and the link meets the ram's line.
fn whitworth_reference(w: &Whitworth<f64>, theta2: f64) -> [f64; 4] {
    let a = (w.r * theta2.cos(), w.r * theta2.sin());
    let (dx, dy) = (a.0, a.1 + w.d);
    let theta4 = dy.atan2(dx);
    let s = dx.hypot(dy);
    let end = (w.b * theta4.cos(), -w.d + w.b * theta4.sin());
    // c·sin θ5 = h − B.y, the ram to the right of B (cos θ5 > 0).
    let theta5 = ((w.h - end.1) / w.c).asin();
    let x = end.0 + w.c * theta5.cos();
    [theta4, s, theta5, x]
}

#[test]
fn a_whitworth_quick_return_agrees_with_its_geometry() {
    let whitworth = Whitworth {
        r: 50.0,
        d: 30.0,
        b: 120.0,
        c: 200.0,
        h: -30.0,
    };
    // Each loop's branch: the block on O4's far side of A (s > 0), the ram right of B.
    let branches = [Branch::Open, Branch::Open];
    let q = whitworth.assemble(0.3, branches).unwrap();
    let branches = whitworth.branch_of(0.3, &q);
    let mut forward_degrees = 0;
    for step in 0..360 {
        let theta2 = f64::from(step).to_radians();
        let [theta4, s, theta5, x] = whitworth_reference(&whitworth, theta2);
        let q = whitworth.assemble(theta2, branches).unwrap();
        assert!(
            close(near(q.theta4, theta4), theta4, 1e-13),
            "{q:?} at {step}°"
        );
        assert!(close(q.s, s, 1e-13), "{q:?}");
        assert!(close(near(q.theta5, theta5), theta5, 1e-13), "{q:?}");
        assert!(close(q.x, x, 1e-12), "{q:?}");
        // The ram's velocity against a central difference of the reference.
        let h = 1e-6;
        let rate = (whitworth_reference(&whitworth, theta2 + h)[3]
            - whitworth_reference(&whitworth, theta2 - h)[3])
            / (2.0 * h);
        let v = whitworth.velocity(theta2, &q, 1.0).unwrap();
        assert!(
            (v.x - rate).abs() < 1e-6 * rate.abs().max(1.0),
            "{} vs {rate}",
            v.x
        );
        if v.x > 0.0 {
            forward_degrees += 1;
        }
    }
    // Quick return: the ram's two strokes take unequal shares of the crank's turn (with
    // these dimensions, 107° one way and 253° the other).
    let turn_back = 360 - forward_degrees;
    assert!(
        forward_degrees.min(turn_back) * 2 < forward_degrees.max(turn_back),
        "{forward_degrees}° one way, {turn_back}° the other"
    );
}
