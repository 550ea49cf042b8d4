//! Hand-written four-bar kernels: what a careful engineer writes for one mechanism instead
//! of declaring it, as the baseline of the size table (`sizes.sh`). Each is
//! `#[inline(never)]`, so that it stays a function of its own whose machine code can be
//! measured, and generic like the generated code.
//!
//! Careful means: Norton's half-angle closed form (KINEMATICS.md), `None` where the loop
//! cannot close (a negative discriminant) or at a toggle (where `|sin(θ4 − θ3)|`, the
//! generated code's relative determinant, is at most `√ε`, the generated code's threshold).
//! It does not check its arguments for NaN or infinity, as the generated kernels do.

use mechgen::{Real, Vec2};

/// The four-bar's dimensions, named as in the generated `FourBar`: ground `l1`, crank `l2`,
/// coupler `l3`, rocker `l4`, and the coupler point `a` from A at `delta` from the coupler.
#[derive(Clone, Copy, Debug)]
pub struct Linkage<T> {
    pub l1: T,
    pub l2: T,
    pub l3: T,
    pub l4: T,
    pub a: T,
    pub delta: T,
}

/// Angles, rates or accelerations of the coupler and rocker: `[θ3, θ4]` and so on.
pub type Pair<T> = [T; 2];

/// The open branch's `[θ3, θ4]` at crank angle `theta2`, by Norton's half-angle form.
#[inline(never)]
pub fn position<T: Real>(k: &Linkage<T>, theta2: T) -> Option<Pair<T>> {
    let two = T::constant(2.0);
    let (a, b, c, d) = (k.l2, k.l3, k.l4, k.l1);
    let (sin2, cos2) = theta2.sin_cos();
    let k1 = d / a;
    let k2 = d / c;
    let k3 = (a * a - b * b + c * c + d * d) / (two * a * c);
    let k4 = d / b;
    let k5 = (c * c - d * d - a * a - b * b) / (two * a * b);
    // θ4 = 2·atan2(−B − √(B² − 4AC), 2A), θ3 likewise with D, E, F; E = B.
    let big_a = cos2 - k1 - k2 * cos2 + k3;
    let big_b = -two * sin2;
    let big_c = k1 - (k2 + T::one()) * cos2 + k3;
    let big_d = cos2 - k1 + k4 * cos2 + k5;
    let big_f = k1 + (k4 - T::one()) * cos2 + k5;
    let discriminant4 = big_b * big_b - T::constant(4.0) * big_a * big_c;
    let discriminant3 = big_b * big_b - T::constant(4.0) * big_d * big_f;
    if !(discriminant4 >= T::zero() && discriminant3 >= T::zero()) {
        return None;
    }
    let theta4 = two * (-big_b - discriminant4.sqrt()).atan2(two * big_a);
    let theta3 = two * (-big_b - discriminant3.sqrt()).atan2(two * big_d);
    Some([wrap(theta3), wrap(theta4)])
}

/// An angle from (−2π, 2π], as twice an `atan2` gives it, into (−π, π], as the generated
/// code gives it.
fn wrap<T: Real>(angle: T) -> T {
    let (pi, turn) = (
        T::constant(core::f64::consts::PI),
        T::constant(core::f64::consts::TAU),
    );
    if angle > pi {
        angle - turn
    } else if angle <= -pi {
        angle + turn
    } else {
        angle
    }
}

/// Position, rates and accelerations, `[[θ3, θ4], [ω3, ω4], [α3, α4]]`, for the crank at
/// `theta2` turning at `omega2` and accelerating at `alpha2`.
#[inline(never)]
pub fn motion<T: Real>(k: &Linkage<T>, theta2: T, omega2: T, alpha2: T) -> Option<[Pair<T>; 3]> {
    let [theta3, theta4] = position(k, theta2)?;
    let (a, b, c) = (k.l2, k.l3, k.l4);
    let (sin2, cos2) = theta2.sin_cos();
    let (sin3, cos3) = theta3.sin_cos();
    let (sin4, cos4) = theta4.sin_cos();
    // sin(θ4 − θ3), and the velocity formulas' other sines, from the ones above.
    let sin43 = sin4 * cos3 - cos4 * sin3;
    if sin43.abs() <= T::epsilon().sqrt() {
        return None;
    }
    let sin42 = sin4 * cos2 - cos4 * sin2;
    let sin23 = sin2 * cos3 - cos2 * sin3;
    // ω3 = (a ω2 / b)·sin(θ4 − θ2)/sin(θ3 − θ4), ω4 = (a ω2 / c)·sin(θ2 − θ3)/sin(θ4 − θ3).
    let omega3 = -(a * omega2 / b) * sin42 / sin43;
    let omega4 = (a * omega2 / c) * sin23 / sin43;
    // Norton's accelerations: α3 = (CD − AF)/(AE − BD), α4 = (CE − BF)/(AE − BD).
    let (aa, bb, dd, ee) = (c * sin4, b * sin3, c * cos4, b * cos3);
    let (w2, w3, w4) = (omega2 * omega2, omega3 * omega3, omega4 * omega4);
    let cc = a * alpha2 * sin2 + a * w2 * cos2 + b * w3 * cos3 - c * w4 * cos4;
    let ff = a * alpha2 * cos2 - a * w2 * sin2 - b * w3 * sin3 + c * w4 * sin4;
    let denominator = aa * ee - bb * dd;
    let alpha3 = (cc * dd - aa * ff) / denominator;
    let alpha4 = (cc * ee - bb * ff) / denominator;
    Some([[theta3, theta4], [omega3, omega4], [alpha3, alpha4]])
}

/// The coupler point P = `l2·e^{iθ2} + a·e^{i(θ3 + δ)}`.
#[inline(never)]
pub fn coupler_point<T: Real>(k: &Linkage<T>, theta2: T, theta3: T) -> Vec2<T> {
    let (sin2, cos2) = theta2.sin_cos();
    let (sin_p, cos_p) = (theta3 + k.delta).sin_cos();
    Vec2::new(k.l2 * cos2 + k.a * cos_p, k.l2 * sin2 + k.a * sin_p)
}

/// P's velocity, `i·l2·ω2·e^{iθ2} + i·a·ω3·e^{i(θ3 + δ)}`.
#[inline(never)]
pub fn coupler_point_velocity<T: Real>(
    k: &Linkage<T>,
    theta2: T,
    omega2: T,
    theta3: T,
    omega3: T,
) -> Vec2<T> {
    let (sin2, cos2) = theta2.sin_cos();
    let (sin_p, cos_p) = (theta3 + k.delta).sin_cos();
    let (crank, arm) = (k.l2 * omega2, k.a * omega3);
    Vec2::new(-crank * sin2 - arm * sin_p, crank * cos2 + arm * cos_p)
}

/// P's acceleration, `(i·α − ω²)·r·e^{iθ}` summed over the crank and the coupler arm.
#[inline(never)]
pub fn coupler_point_acceleration<T: Real>(
    k: &Linkage<T>,
    theta2: T,
    [omega2, alpha2]: Pair<T>,
    theta3: T,
    [omega3, alpha3]: Pair<T>,
) -> Vec2<T> {
    let (sin2, cos2) = theta2.sin_cos();
    let (sin_p, cos_p) = (theta3 + k.delta).sin_cos();
    let (tangential2, normal2) = (k.l2 * alpha2, k.l2 * omega2 * omega2);
    let (tangential3, normal3) = (k.a * alpha3, k.a * omega3 * omega3);
    Vec2::new(
        -tangential2 * sin2 - normal2 * cos2 - tangential3 * sin_p - normal3 * cos_p,
        tangential2 * cos2 - normal2 * sin2 + tangential3 * cos_p - normal3 * sin_p,
    )
}

/// What the `coupler_path` scene computes: P's position at `theta2`, open branch.
#[inline(never)]
pub fn coupler_path<T: Real>(k: &Linkage<T>, theta2: T) -> Option<Vec2<T>> {
    let [theta3, _] = position(k, theta2)?;
    Some(coupler_point(k, theta2, theta3))
}

/// What the `coupler_motion` scene computes: P's position, velocity and acceleration.
#[inline(never)]
pub fn coupler_motion<T: Real>(
    k: &Linkage<T>,
    theta2: T,
    omega2: T,
    alpha2: T,
) -> Option<[Vec2<T>; 3]> {
    let [[theta3, _], [omega3, _], [alpha3, _]] = motion(k, theta2, omega2, alpha2)?;
    Some([
        coupler_point(k, theta2, theta3),
        coupler_point_velocity(k, theta2, omega2, theta3, omega3),
        coupler_point_acceleration(k, theta2, [omega2, alpha2], theta3, [omega3, alpha3]),
    ])
}
