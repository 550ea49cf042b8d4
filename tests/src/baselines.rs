//! What a user would write instead of declaring a mechanism: the baselines the benchmarks
//! and the performance report measure the generated code against, all for pos+vel+acc of
//! the open branch over a sweep. Each returns `[θ3 or d, θ4 or b]` values, rates and
//! accelerations, like `mechgen::Motion`.

use nalgebra::{DMatrix, DVector};
use num_dual::{Dual64, DualNum};

/// Values, rates and accelerations of the two unknowns.
pub type State = [[f64; 2]; 3];

/// The four-bar's lengths `[l1, l2, l3, l4]`.
pub type Lengths = [f64; 4];

/// Rates and accelerations of a four-bar from its angles, by the closed forms of
/// KINEMATICS.md: `ω3 = (l2 ω2 / l3)·sin(θ4 − θ2)/sin(θ3 − θ4)`, …, and the C, D, E, F
/// formulas for `α3`, `α4`, written with each sine and cosine computed once.
fn four_bar_rates(l: &Lengths, t2: (f64, f64), t3: f64, t4: f64, w2: f64, a2: f64) -> State {
    let [_, l2, l3, l4] = *l;
    let (s2, c2) = t2;
    let (s3, c3) = t3.sin_cos();
    let (s4, c4) = t4.sin_cos();
    // sin(θ4 − θ2), sin(θ3 − θ4), sin(θ2 − θ3), from the products.
    let s42 = s4 * c2 - c4 * s2;
    let s34 = s3 * c4 - c3 * s4;
    let s23 = s2 * c3 - c2 * s3;
    let w3 = (l2 * w2 / l3) * s42 / s34;
    let w4 = (l2 * w2 / l4) * s23 / -s34;
    let a = l4 * s4;
    let b = l3 * s3;
    let c = l2 * a2 * s2 + l2 * w2 * w2 * c2 + l3 * w3 * w3 * c3 - l4 * w4 * w4 * c4;
    let d = l4 * c4;
    let e = l3 * c3;
    let f = l2 * a2 * c2 - l2 * w2 * w2 * s2 - l3 * w3 * w3 * s3 + l4 * w4 * w4 * s4;
    let den = a * e - b * d;
    [
        [t3, t4],
        [w3, w4],
        [(c * d - a * f) / den, (c * e - b * f) / den],
    ]
}

/// Norton's closed form (the half-angle K1…K5 form), open branch, then the closed-form
/// rates. The hand-written code the generated closed form is measured against.
pub fn four_bar_norton(l: &Lengths, theta2: f64, w2: f64, a2: f64) -> State {
    let [d, a, b, c] = *l;
    let (s2, c2) = theta2.sin_cos();
    let k1 = d / a;
    let k2 = d / c;
    let k3 = (a * a - b * b + c * c + d * d) / (2.0 * a * c);
    let k4 = d / b;
    let k5 = (c * c - d * d - a * a - b * b) / (2.0 * a * b);
    let big_a = c2 - k1 - k2 * c2 + k3;
    let big_b = -2.0 * s2;
    let big_c = k1 - (k2 + 1.0) * c2 + k3;
    let big_d = c2 - k1 + k4 * c2 + k5;
    let big_e = -2.0 * s2;
    let big_f = k1 + (k4 - 1.0) * c2 + k5;
    let t4 = 2.0 * (-big_b - (big_b * big_b - 4.0 * big_a * big_c).sqrt()).atan2(2.0 * big_a);
    let t3 = 2.0 * (-big_e - (big_e * big_e - 4.0 * big_d * big_f).sqrt()).atan2(2.0 * big_d);
    four_bar_rates(l, (s2, c2), t3, t4, w2, a2)
}

/// The four-bar's residual and analytic Jacobian.
fn four_bar_linearise(l: &Lengths, t2: (f64, f64), q: [f64; 2]) -> ([f64; 2], [[f64; 2]; 2]) {
    let [l1, l2, l3, l4] = *l;
    let (s2, c2) = t2;
    let (s3, c3) = q[0].sin_cos();
    let (s4, c4) = q[1].sin_cos();
    (
        [
            l2 * c2 + l3 * c3 - l4 * c4 - l1,
            l2 * s2 + l3 * s3 - l4 * s4,
        ],
        [[-l3 * s3, l4 * s4], [l3 * c3, -l4 * c4]],
    )
}

fn newton_step(f: [f64; 2], j: [[f64; 2]; 2], q: &mut [f64; 2]) {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    q[0] -= (f[0] * j[1][1] - j[0][1] * f[1]) / det;
    q[1] -= (j[0][0] * f[1] - f[0] * j[1][0]) / det;
}

/// A hand-written Newton-Raphson with the analytic 2×2 Jacobian, stopping at
/// `max|f| < tolerance`, then the closed-form rates.
pub fn four_bar_newton(
    l: &Lengths,
    theta2: f64,
    guess: [f64; 2],
    tolerance: f64,
    w2: f64,
    a2: f64,
) -> State {
    let t2 = theta2.sin_cos();
    let mut q = guess;
    for _ in 0..50 {
        let (f, j) = four_bar_linearise(l, t2, q);
        if f[0].abs().max(f[1].abs()) < tolerance {
            break;
        }
        newton_step(f, j, &mut q);
    }
    four_bar_rates(l, t2, q[0], q[1], w2, a2)
}

fn four_bar_residual_dual(l: &Lengths, t2: (f64, f64), t3: Dual64, t4: Dual64) -> [Dual64; 2] {
    let [l1, l2, l3, l4] = *l;
    let (s2, c2) = t2;
    let (s3, c3) = t3.sin_cos();
    let (s4, c4) = t4.sin_cos();
    [
        c3 * l3 - c4 * l4 + (l2 * c2 - l1),
        s3 * l3 - s4 * l4 + l2 * s2,
    ]
}

/// Newton-Raphson with the Jacobian from forward-mode dual numbers (num-dual), one pass per
/// unknown, then the closed-form rates.
pub fn four_bar_num_dual(
    l: &Lengths,
    theta2: f64,
    guess: [f64; 2],
    tolerance: f64,
    w2: f64,
    a2: f64,
) -> State {
    let t2 = theta2.sin_cos();
    let mut q = guess;
    for _ in 0..50 {
        let d3 = four_bar_residual_dual(
            l,
            t2,
            Dual64::from_re(q[0]).derivative(),
            Dual64::from_re(q[1]),
        );
        let d4 = four_bar_residual_dual(
            l,
            t2,
            Dual64::from_re(q[0]),
            Dual64::from_re(q[1]).derivative(),
        );
        let f = [d3[0].re, d3[1].re];
        if f[0].abs().max(f[1].abs()) < tolerance {
            break;
        }
        let j = [[d3[0].eps, d4[0].eps], [d3[1].eps, d4[1].eps]];
        newton_step(f, j, &mut q);
    }
    four_bar_rates(l, t2, q[0], q[1], w2, a2)
}

fn residual_dyn(l: &Lengths, theta2: f64, q: &DVector<f64>) -> DVector<f64> {
    let (f, _) = four_bar_linearise(l, theta2.sin_cos(), [q[0], q[1]]);
    DVector::from_column_slice(&f)
}

/// Forward-difference Jacobian of the residual with respect to the unknowns, on the heap.
fn jacobian_fd(l: &Lengths, theta2: f64, q: &DVector<f64>) -> DMatrix<f64> {
    let f0 = residual_dyn(l, theta2, q);
    let mut j = DMatrix::zeros(f0.len(), q.len());
    for k in 0..q.len() {
        let h = 1e-7 * q[k].abs().max(1.0);
        let mut moved = q.clone();
        moved[k] += h;
        j.set_column(k, &((residual_dyn(l, theta2, &moved) - &f0) / h));
    }
    j
}

fn solve_position_dyn(
    l: &Lengths,
    theta2: f64,
    guess: &DVector<f64>,
    tolerance: f64,
) -> DVector<f64> {
    let mut q = guess.clone();
    for _ in 0..50 {
        let f = residual_dyn(l, theta2, &q);
        if f.amax() < tolerance {
            break;
        }
        let step = jacobian_fd(l, theta2, &q)
            .lu()
            .solve(&f)
            .unwrap_or_else(|| DVector::zeros(2));
        q -= step;
    }
    q
}

fn velocity_dyn(l: &Lengths, theta2: f64, q: &DVector<f64>, w2: f64) -> DVector<f64> {
    let h = 1e-7;
    let f_input = (residual_dyn(l, theta2 + h, q) - residual_dyn(l, theta2, q)) / h;
    jacobian_fd(l, theta2, q)
        .lu()
        .solve(&(-f_input * w2))
        .unwrap_or_else(|| DVector::zeros(2))
}

/// What a generic solver does: dynamic nalgebra matrices, forward-difference Jacobians,
/// LU solves, and accelerations by central differences of the velocity along the motion.
pub fn four_bar_nalgebra(
    l: &Lengths,
    theta2: f64,
    guess: [f64; 2],
    tolerance: f64,
    w2: f64,
    a2: f64,
) -> State {
    let guess = DVector::from_column_slice(&guess);
    let q = solve_position_dyn(l, theta2, &guess, tolerance);
    let v = velocity_dyn(l, theta2, &q, w2);
    let h = 1e-5;
    let q_plus = solve_position_dyn(l, theta2 + h, &q, tolerance);
    let q_minus = solve_position_dyn(l, theta2 - h, &q, tolerance);
    let slope = velocity_dyn(l, theta2, &q, 1.0);
    let a = (velocity_dyn(l, theta2 + h, &q_plus, w2) - velocity_dyn(l, theta2 - h, &q_minus, w2))
        / (2.0 * h)
        * w2
        + slope * a2;
    [[q[0], q[1]], [v[0], v[1]], [a[0], a[1]]]
}

/// The slider-crank's closed form and rates from KINEMATICS.md, by hand: `[θ3, d]`.
pub fn slider_crank_closed(l2: f64, l3: f64, c: f64, theta2: f64, w2: f64, a2: f64) -> State {
    let (s2, c2) = theta2.sin_cos();
    let s3 = (c - l2 * s2) / l3;
    let c3 = (1.0 - s3 * s3).sqrt();
    let t3 = s3.atan2(c3);
    let d = l2 * c2 + l3 * c3;
    let w3 = -l2 * w2 * c2 / (l3 * c3);
    let dd = -l2 * w2 * s2 - l3 * w3 * s3;
    let a3 = (l2 * w2 * w2 * s2 - l2 * a2 * c2 + l3 * w3 * w3 * s3) / (l3 * c3);
    let ddd = -l2 * a2 * s2 - l2 * w2 * w2 * c2 - l3 * a3 * s3 - l3 * w3 * w3 * c3;
    [[t3, d], [w3, dd], [a3, ddd]]
}

/// The inverted slider-crank's closed form and rates by hand: `[θ4, b]`, from
/// `A − O4 = e^{iθ4}·(b·e^{iγ} + c)` and its derivatives.
pub fn inverted_slider_crank_closed(p: [f64; 4], theta2: f64, w2: f64, a2: f64) -> State {
    let [l1, l2, c, g] = p;
    let (s2, c2) = theta2.sin_cos();
    let (sg, cg) = g.sin_cos();
    let (rx, ry) = (l2 * c2 - l1, l2 * s2);
    let r2 = rx * rx + ry * ry;
    let across = c * sg;
    let b = -c * cg + (r2 - across * across).sqrt();
    // W = b·e^{iγ} + c; θ4 = arg R − arg W.
    let (wx, wy) = (b * cg + c, b * sg);
    let t4 = ry.atan2(rx) - wy.atan2(wx);
    let (s4, c4) = t4.sin_cos();
    // Velocity: i·l2·ω2·e^{iθ2} = e^{iθ4}·(ḃ·e^{iγ} + i·ω4·W). Rotate back by −θ4.
    let rotate_back = |x: f64, y: f64| (x * c4 + y * s4, -x * s4 + y * c4);
    let (vx, vy) = rotate_back(-l2 * w2 * s2, l2 * w2 * c2);
    // ḃ·(cg, sg) + ω4·(−wy, wx) = (vx, vy).
    let det = cg * wx + sg * wy;
    let bd = (vx * wx + vy * wy) / det;
    let w4 = (cg * vy - sg * vx) / det;
    // Acceleration: (−l2ω2² + i l2α2)e^{iθ2} = e^{iθ4}[b̈e^{iγ} + 2iω4ḃe^{iγ} + iα4W − ω4²W].
    let ax0 = -l2 * w2 * w2 * c2 - l2 * a2 * s2;
    let ay0 = -l2 * w2 * w2 * s2 + l2 * a2 * c2;
    let (ax, ay) = rotate_back(ax0, ay0);
    let (ax, ay) = (
        ax + 2.0 * w4 * bd * sg + w4 * w4 * wx,
        ay - 2.0 * w4 * bd * cg + w4 * w4 * wy,
    );
    let bdd = (ax * wx + ay * wy) / det;
    let a4 = (cg * ay - sg * ax) / det;
    [[t4, b], [w4, bd], [a4, bdd]]
}
