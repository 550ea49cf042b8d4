//! Velocity and acceleration from the generated code, checked against the closed forms of
//! KINEMATICS.md and against central finite differences of the generated positions over a
//! full crank turn, in f64 and f32.

mod common;

use common::*;
use mechgen::Real;

const OMEGA2: f64 = 12.0;
const ALPHA2: f64 = -30.0;

#[test]
fn four_bar_rates_match_the_closed_forms() {
    let linkage = example_1::<f64>();
    let [_, l2, l3, l4] = linkage.lengths();
    for Sample { input: t2, q } in sweep(&linkage, [0.3, 1.2], 1) {
        let [t3, t4] = q;
        let [w3, w4] = linkage.rates(t2, q, OMEGA2).unwrap();
        let w3_closed = (l2 * OMEGA2 / l3) * (t4 - t2).sin() / (t3 - t4).sin();
        let w4_closed = (l2 * OMEGA2 / l4) * (t2 - t3).sin() / (t4 - t3).sin();
        assert_close("omega3", w3, w3_closed, 1e-12);
        assert_close("omega4", w4, w4_closed, 1e-12);

        let [a3, a4] = linkage
            .accelerations(t2, q, OMEGA2, [w3, w4], ALPHA2)
            .unwrap();
        let a = l4 * t4.sin();
        let b = l3 * t3.sin();
        let c = l2 * ALPHA2 * t2.sin() + l2 * OMEGA2 * OMEGA2 * t2.cos() + l3 * w3 * w3 * t3.cos()
            - l4 * w4 * w4 * t4.cos();
        let d = l4 * t4.cos();
        let e = l3 * t3.cos();
        let f = l2 * ALPHA2 * t2.cos() - l2 * OMEGA2 * OMEGA2 * t2.sin() - l3 * w3 * w3 * t3.sin()
            + l4 * w4 * w4 * t4.sin();
        let a3_closed = (c * d - a * f) / (a * e - b * d);
        let a4_closed = (c * e - b * f) / (a * e - b * d);
        assert_close("alpha3", a3, a3_closed, 1e-11);
        assert_close("alpha4", a4, a4_closed, 1e-11);
    }
}

#[test]
fn slider_crank_rates_match_the_closed_forms() {
    let linkage = slider_crank::<f64>();
    let [l2, l3, offset] = linkage.dimensions();
    for Sample { input: t2, q } in sweep(&linkage, [0.0, 190.0], 1) {
        let [t3, d] = q;
        // Position: B = A + l3 @ θ3 on the line y = c.
        assert_close("sin theta3", t3.sin(), (offset - l2 * t2.sin()) / l3, 1e-13);
        assert_close("d", d, l2 * t2.cos() + l3 * t3.cos(), 1e-13);
        // Velocity: j l2 ω2 e^{jθ2} + j l3 ω3 e^{jθ3} - ḋ = 0.
        let [w3, d_dot] = linkage.rates(t2, q, OMEGA2).unwrap();
        let w3_closed = -l2 * OMEGA2 * t2.cos() / (l3 * t3.cos());
        assert_close("omega3", w3, w3_closed, 1e-12);
        assert_close(
            "d dot",
            d_dot,
            -l2 * OMEGA2 * t2.sin() - l3 * w3 * t3.sin(),
            1e-12,
        );
        // Acceleration: (j l2 α2 − l2 ω2²) e^{jθ2} + (j l3 α3 − l3 ω3²) e^{jθ3} − d̈ = 0.
        let [a3, d_ddot] = linkage
            .accelerations(t2, q, OMEGA2, [w3, d_dot], ALPHA2)
            .unwrap();
        let a3_closed = (l2 * OMEGA2 * OMEGA2 * t2.sin() - l2 * ALPHA2 * t2.cos()
            + l3 * w3 * w3 * t3.sin())
            / (l3 * t3.cos());
        let d_ddot_closed = -l2 * ALPHA2 * t2.sin()
            - l2 * OMEGA2 * OMEGA2 * t2.cos()
            - l3 * a3 * t3.sin()
            - l3 * w3 * w3 * t3.cos();
        assert_close("alpha3", a3, a3_closed, 1e-11);
        assert_close("d ddot", d_ddot, d_ddot_closed, 1e-11);
    }
}

/// Largest `|estimate - generated|` over the sweep, relative to the largest `|generated|`.
struct Discrepancy {
    worst: f64,
    scale: f64,
}

impl Discrepancy {
    fn new() -> Self {
        Discrepancy {
            worst: 0.0,
            scale: 0.0,
        }
    }
    fn record<T: Real>(&mut self, generated: &[T], estimate: &[T]) {
        for (g, e) in generated.iter().zip(estimate) {
            let (g, e) = (g.to_f64().unwrap(), e.to_f64().unwrap());
            self.worst = self.worst.max((g - e).abs());
            self.scale = self.scale.max(g.abs());
        }
    }
    #[track_caller]
    fn assert_below(&self, what: &str, tolerance: f64) {
        let relative = self.worst / self.scale;
        assert!(
            relative < tolerance,
            "{what}: relative discrepancy {relative:e} ≥ {tolerance:e}"
        );
    }
}

fn central_difference<T: Real>(plus: &[T], minus: &[T], h: T, rate: T) -> Vec<T> {
    let two_h = T::constant(2.0) * h;
    plus.iter()
        .zip(minus)
        .map(|(p, m)| (*p - *m) / two_h * rate)
        .collect()
}

/// Checks unknown and point rates and accelerations against central differences of the
/// generated position (for rates) and velocity (for accelerations) along the sweep. With a
/// constant input rate ω, d/dt = ω·d/dθ; an input acceleration α adds α·dq/dθ.
fn check_against_finite_differences<T: Real, L: Linkage<T>>(
    linkage: &L,
    guess: [T; 2],
    h: T,
    tolerance: f64,
) {
    let omega = T::constant(OMEGA2);
    let alpha = T::constant(ALPHA2);
    let mut rate = Discrepancy::new();
    let mut accel = Discrepancy::new();
    let mut point_rate = Discrepancy::new();
    let mut point_accel = Discrepancy::new();
    for Sample { input, q } in sweep(linkage, guess, 5) {
        let (plus, minus) = (input + h, input - h);
        let q_plus = linkage.solve(plus, q).unwrap();
        let q_minus = linkage.solve(minus, q).unwrap();

        let q_dot = linkage.rates(input, q, omega).unwrap();
        rate.record(&q_dot, &central_difference(&q_plus, &q_minus, h, omega));
        let point_dot = linkage.point_velocities(input, q, omega, q_dot);
        let points_fd = central_difference(
            &linkage.point_positions(plus, q_plus),
            &linkage.point_positions(minus, q_minus),
            h,
            omega,
        );
        point_rate.record(&point_dot, &points_fd);

        // Accelerations: differentiate the generated velocity at constant ω, then add α·dq/dθ.
        let q_dot_plus = linkage.rates(plus, q_plus, omega).unwrap();
        let q_dot_minus = linkage.rates(minus, q_minus, omega).unwrap();
        let dq_dtheta = linkage.rates(input, q, T::one()).unwrap();
        let fd: Vec<T> = central_difference(&q_dot_plus, &q_dot_minus, h, omega)
            .iter()
            .zip(dq_dtheta)
            .map(|(a, d)| *a + alpha * d)
            .collect();
        let q_ddot = linkage
            .accelerations(input, q, omega, q_dot, alpha)
            .unwrap();
        accel.record(&q_ddot, &fd);

        let point_ddot = linkage.point_accelerations(input, q, omega, q_dot, alpha, q_ddot);
        let velocity_plus = linkage.point_velocities(plus, q_plus, omega, q_dot_plus);
        let velocity_minus = linkage.point_velocities(minus, q_minus, omega, q_dot_minus);
        let point_slope = linkage.point_velocities(input, q, T::one(), dq_dtheta);
        let fd: Vec<T> = central_difference(&velocity_plus, &velocity_minus, h, omega)
            .iter()
            .zip(point_slope)
            .map(|(a, d)| *a + alpha * d)
            .collect();
        point_accel.record(&point_ddot, &fd);
    }
    rate.assert_below("unknown rates", tolerance);
    accel.assert_below("unknown accelerations", tolerance);
    point_rate.assert_below("point velocities", tolerance);
    point_accel.assert_below("point accelerations", tolerance);
}

#[test]
fn four_bar_rates_match_finite_differences_f64() {
    check_against_finite_differences(&example_1::<f64>(), [0.3, 1.2], 1e-5, 2e-9);
}

#[test]
fn four_bar_rates_match_finite_differences_f32() {
    check_against_finite_differences(&example_1::<f32>(), [0.3, 1.2], 1e-2, 2e-3);
}

#[test]
fn slider_crank_rates_match_finite_differences_f64() {
    check_against_finite_differences(&slider_crank::<f64>(), [0.0, 190.0], 1e-5, 2e-9);
}

#[test]
fn slider_crank_rates_match_finite_differences_f32() {
    check_against_finite_differences(&slider_crank::<f32>(), [0.0, 190.0], 1e-2, 2e-3);
}

#[test]
fn inverted_slider_crank_rates_match_finite_differences_f64() {
    check_against_finite_differences(&inverted_slider_crank::<f64>(), [3.0, 60.0], 1e-5, 2e-9);
}

#[test]
fn inverted_slider_crank_rates_match_finite_differences_f32() {
    check_against_finite_differences(&inverted_slider_crank::<f32>(), [3.0, 60.0], 1e-2, 2e-3);
}
