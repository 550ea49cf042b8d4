//! What a user would write instead of declaring a mechanism: the baselines the benchmarks
//! and the performance report measure the generated code against, all for position,
//! velocity and acceleration on the open branch. Each returns `[θ3 or d, θ4 or b]` values,
//! rates and accelerations, like `mechgen::Motion`.
//!
//! The closed forms ([`FourBarNorton`], [`FourBarCouplerPoint`], [`SliderCrankClosed`],
//! [`InvertedSliderCrankClosed`]) and the hand Newton ([`FourBarNewton`]) are what the most
//! careful engineer would write for one mechanism in `f64`: a struct built once per mechanism
//! holding every constant that depends only on the dimensions, and a per-call method
//! (`#[inline(always)]` for the closed forms, so that it is compiled whole into its caller as
//! the generated scene kernels are, and measured at its best) that calls one `sin_cos` (of
//! the input), at most one `sqrt`, one inverse trigonometric call (`atan2` or `asin`) per angle returned and none otherwise, and one
//! division (the hand Newton: one `sin_cos` per unknown at its guess, turns of the link
//! vectors after that, and one division per evaluation). They check nothing: outside the range of motion, or at a toggle, they return NaN or infinities. The
//! num-dual and nalgebra baselines are what else a user would reach for.

use nalgebra::{DMatrix, DVector};
use num_dual::{Dual64, DualNum};

/// Values, rates and accelerations of the two unknowns.
pub type State = [[f64; 2]; 3];

/// The four-bar's lengths `[l1, l2, l3, l4]`.
pub type Lengths = [f64; 4];

#[inline(always)]
fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// `a × b`, the z part of the cross product: `|a|·|b|·sin(angle from a to b)`.
#[inline(always)]
fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The four-bar's rates and accelerations `[[ω3, ω4], [α3, α4]]` from its link vectors: the
/// crank `A = l2·e^{iθ2}`, the coupler `b3 = l3·e^{iθ3}` (B − A), the rocker
/// `b4 = l4·e^{iθ4}` (B − O4), and `inv_g = 1/(b3 × b4) = 1/(l3·l4·sin(θ4 − θ3))`.
///
/// The loop's derivatives, dotted with `b4` and `b3` (which drops one unknown each):
/// `ω3 = −ω2·(A × b4)/g`, `ω4 = −ω2·(A × b3)/g` (KINEMATICS.md's
/// `ω3 = (l2 ω2/l3)·sin(θ4 − θ2)/sin(θ3 − θ4)` and its partner), and with
/// `K = (iα2 − ω2²)·A − ω3²·b3 + ω4²·b4`, `α3 = −(K·b4)/g`, `α4 = −(K·b3)/g` (KINEMATICS.md's
/// C, D, E, F form: `A·E − B·D = g`). No division, no trigonometry: about 40 flops.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn four_bar_rates_from_vectors(
    crank: [f64; 2],
    b3: [f64; 2],
    b4: [f64; 2],
    inv_g: f64,
    l3_squared: f64,
    l4_squared: f64,
    w2: f64,
    a2: f64,
) -> [[f64; 2]; 2] {
    let cross_a4 = cross(crank, b4);
    let cross_a3 = cross(crank, b3);
    let w3 = -w2 * cross_a4 * inv_g;
    let w4 = -w2 * cross_a3 * inv_g;
    let (w2s, w3s, w4s) = (w2 * w2, w3 * w3, w4 * w4);
    let dot_34 = dot(b3, b4);
    let a3 = (w2s * dot(crank, b4) - a2 * cross_a4 + w3s * dot_34 - w4s * l4_squared) * inv_g;
    let a4 = (w2s * dot(crank, b3) - a2 * cross_a3 + w3s * l3_squared - w4s * dot_34) * inv_g;
    [[w3, w4], [a3, a4]]
}

/// Norton's half-angle closed form of the four-bar (lengths `[l1, l2, l3, l4]` = ground,
/// crank, coupler, rocker; loop `l2@θ2 + l3@θ3 − l4@θ4 − l1 = 0`), open branch
/// (`sin(θ4 − θ3) > 0`, as `mechanisms::FourBar`), then the rates in closed form.
///
/// With `Z = A − O4 = (l2·cos θ2 − l1, l2·sin θ2)`, the loop without θ3 is
/// `|Z − l4·e^{iθ4}|² = l3²` and without θ4 is `|Z + l3·e^{iθ3}|² = l4²`: each is
/// `P·cos θ + Q·sin θ + R = 0`, a quadratic in `t = tan(θ/2)`, so
/// `tan(θ4/2) = (2·l4·Zy − h)/(R4 + 2·l4·Zx)` and `tan(θ3/2) = (h − 2·l3·Zy)/(R3 − 2·l3·Zx)`
/// with `R4 = |Z|² + l4² − l3²`, `R3 = |Z|² + l3² − l4²`. Their discriminants are equal,
/// `h² = 4·l4²·|Z|² − R4² = 4·l3²·|Z|² − R3²` = 16·(area of the triangle A B O4)² (Heron),
/// so one square root serves both (in Norton's K1…K5 normalisation they differ by the
/// constant factor `(l4/l3)²`). This is Norton's form up to positive factors on numerator and
/// denominator, which `atan2` ignores. Where `Zy > 0` those numerators cancel (`h` against
/// `2·l·Zy`: up to 1e-13 rad lost where the other branch's root runs off to infinity), so
/// there each root is taken in its other form, `t = (R + P)/(−Q ± h)` (the product of the
/// roots over the other root): `tan(θ4/2) = (R4 − 2·l4·Zx)/(2·l4·Zy + h)` and
/// `tan(θ3/2) = −(R3 + 2·l3·Zx)/(2·l3·Zy + h)`. So chosen, θ3 and θ4 agree with the generated
/// code and with 60-digit references to about 1e-15.
///
/// Once per mechanism ([`new`](Self::new)): `l1² + l2²`, `2·l1·l2`, `l4² − l3²`, `4·l4²`,
/// `2·l3`, `l3²`, `l4²`, `1/l3`, `1/l4`.
///
/// Per call ([`motion`](Self::motion)): one `sin_cos` (θ2), one `sqrt` (h), one `asin` or
/// `acos` per angle (of the link's unit vector, `unit_angle`: under half the cost of
/// `atan2`), one division, about 65 multiplications and
/// additions. No further trigonometry: the coupler's direction comes from the half-angle,
/// `l3·e^{iθ3} = l3·(den² − num², 2·num·den)/(num² + den²)`, the rocker's from the loop,
/// `l4·e^{iθ4} = l3·e^{iθ3} + Z` (the same point B), and the one division,
/// `1/((num3² + den3²)·h)`, gives both `1/(num3² + den3²)` and
/// `1/(l3·l4·sin(θ4 − θ3)) = 2/h` (on the open branch `l3·l4·sin(θ4 − θ3) = h/2`, twice the
/// triangle's area). The rates as in `four_bar_rates_from_vectors`: ω3, ω4, α3, α4 from dot and
/// cross products of the link vectors, no division.
///
/// Angles come out in (−2π, 2π], equal modulo 2π to the generated code's (−π, π].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBarNorton {
    l1: f64,
    l2: f64,
    /// `l1² + l2²`: `|Z|² = l1² + l2² − 2·l1·l2·cos θ2`.
    ground_crank_squares: f64,
    /// `2·l1·l2`.
    ground_crank_twice: f64,
    /// `l4² − l3²`: `R4 = |Z|² + (l4² − l3²)`, `R3 = |Z|² − (l4² − l3²)`.
    rocker_minus_coupler_squares: f64,
    /// `4·l4²`.
    rocker_squared_four: f64,
    two_l3: f64,
    l3_squared: f64,
    l4_squared: f64,
    inv_l3: f64,
    inv_l4: f64,
}

impl FourBarNorton {
    /// Precomputes the constants of the linkage with lengths `[l1, l2, l3, l4]`.
    pub fn new(lengths: Lengths) -> Self {
        let [l1, l2, l3, l4] = lengths;
        FourBarNorton {
            l1,
            l2,
            ground_crank_squares: l1 * l1 + l2 * l2,
            ground_crank_twice: 2.0 * l1 * l2,
            rocker_minus_coupler_squares: l4 * l4 - l3 * l3,
            rocker_squared_four: 4.0 * l4 * l4,
            two_l3: 2.0 * l3,
            l3_squared: l3 * l3,
            l4_squared: l4 * l4,
            inv_l3: 1.0 / l3,
            inv_l4: 1.0 / l4,
        }
    }

    /// `[[θ3, θ4], [ω3, ω4], [α3, α4]]` at the crank angle `theta2`, for the crank turning at
    /// `w2` and accelerating at `a2`, on the open branch.
    #[inline(always)]
    pub fn motion(&self, theta2: f64, w2: f64, a2: f64) -> State {
        let (s2, c2) = theta2.sin_cos();
        let crank = [self.l2 * c2, self.l2 * s2];
        // Z = A − O4 and its squared length.
        let z = [crank[0] - self.l1, crank[1]];
        let z_squared = self.ground_crank_squares - self.ground_crank_twice * c2;
        let r4 = z_squared + self.rocker_minus_coupler_squares;
        let r3 = z_squared - self.rocker_minus_coupler_squares;
        let h = (self.rocker_squared_four * z_squared - r4 * r4).sqrt();
        // tan(θ3/2) = num/den, open branch, in whichever of the root's two forms
        // (`(−Q ∓ h)/(R − P)` or `(R + P)/(−Q ± h)`) adds h to `2·l3·|Zy|` rather than
        // cancelling it. θ4 follows from B, so needs no half-angle of its own.
        let (l3_zx, l3_zy) = (self.two_l3 * z[0], self.two_l3 * z[1]);
        let (num3, den3) = if z[1] > 0.0 {
            (-(r3 + l3_zx), l3_zy + h)
        } else {
            (h - l3_zy, r3 - l3_zx)
        };
        // One division for 1/(num3² + den3²) and 1/g = 2/h.
        let norm3 = num3 * num3 + den3 * den3;
        let inv = 1.0 / (norm3 * h);
        let scale3 = self.two_l3 * 0.5 * inv * h; // l3/(num3² + den3²)
        let inv_g = 2.0 * inv * norm3;
        let b3 = [
            (den3 * den3 - num3 * num3) * scale3,
            2.0 * num3 * den3 * scale3,
        ];
        let b4 = [b3[0] + z[0], b3[1] + z[1]];
        // The angles from the link vectors' directions, without `atan2`.
        let theta3 = unit_angle(b3[1] * self.inv_l3, b3[0] * self.inv_l3);
        let theta4 = unit_angle(b4[1] * self.inv_l4, b4[0] * self.inv_l4);
        let [rates, accelerations] = four_bar_rates_from_vectors(
            crank,
            b3,
            b4,
            inv_g,
            self.l3_squared,
            self.l4_squared,
            w2,
            a2,
        );
        [[theta3, theta4], rates, accelerations]
    }
}

/// [`FourBarNorton`] built for one call, for accuracy runs that do not time it.
pub fn four_bar_norton(l: &Lengths, theta2: f64, w2: f64, a2: f64) -> State {
    FourBarNorton::new(*l).motion(theta2, w2, a2)
}

/// Hand point kernels for the four-bar's coupler point P at distance `a` from the crank pin
/// A, at angle `δ` from the coupler line A B (`mechanisms::FourBar::with_coupler_point`):
/// `P = A + a·e^{i(θ3 + δ)}`, open branch. They work with vectors only and never call
/// `atan2`: no angle is returned.
///
/// B is where the circle of radius l3 about A meets the circle of radius l4 about O4: with
/// `u = O4 − A`, `R3 = |u|² + l3² − l4²` and `h = √(4·l3²·|u|² − R3²)` (4× the triangle's
/// area), `B − A = u·(R3 + i·h)/(2·|u|²)` (complex product; `+h` is the open branch). Then
/// `P − A = (B − A)·(a/l3)·e^{iδ}`, so `P = A + u·(R3 + i·h)·m/|u|²` with
/// `m = (a/(2·l3))·e^{iδ}` precomputed.
///
/// Once per mechanism ([`new`](Self::new)): `l1² + l2²`, `2·l1·l2`, `l4² − l3²`, `4·l3²`,
/// `l3²`, `l4²`, `(a/l3)·e^{iδ}` and its half (one `sin_cos` of δ).
///
/// Per call:
/// - [`position`](Self::position): one `sin_cos` (θ2), one `sqrt` (h), one division
///   (`1/|u|²`), no `atan2`, about 25 multiplications and additions;
/// - [`motion`](Self::motion): P, its velocity and its acceleration: one `sin_cos`, one
///   `sqrt`, one division (`1/(|u|²·h)`, giving `1/(2·|u|²)` and `1/(l3·l4·sin(θ4 − θ3)) =
///   2/h`), no `atan2`; ω3, ω4, α3 from dot and cross products of the link vectors
///   `b3 = B − A`, `b4 = B − O4` as in [`FourBarNorton`], then
///   `v_P = i·ω2·A + i·ω3·(P − A)`, `a_P = (i·α2 − ω2²)·A + (i·α3 − ω3²)·(P − A)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBarCouplerPoint {
    l1: f64,
    l2: f64,
    /// `l1² + l2²`: `|u|² = l1² + l2² − 2·l1·l2·cos θ2`.
    ground_crank_squares: f64,
    /// `2·l1·l2`.
    ground_crank_twice: f64,
    /// `l4² − l3²`: `R3 = |u|² − (l4² − l3²)`.
    rocker_minus_coupler_squares: f64,
    /// `4·l3²`.
    coupler_squared_four: f64,
    l3_squared: f64,
    l4_squared: f64,
    /// `(a/l3)·e^{iδ}`: turns and scales `B − A` into `P − A`.
    offset: [f64; 2],
    /// `(a/(2·l3))·e^{iδ}`: `offset/2`, for the position kernel.
    half_offset: [f64; 2],
}

impl FourBarCouplerPoint {
    /// Precomputes the constants of the linkage with lengths `[l1, l2, l3, l4]` and coupler
    /// point at `distance` a from A, `angle` δ (radians) from A B.
    pub fn new(lengths: Lengths, distance: f64, angle: f64) -> Self {
        let [l1, l2, l3, l4] = lengths;
        let (sd, cd) = angle.sin_cos();
        let ratio = distance / l3;
        FourBarCouplerPoint {
            l1,
            l2,
            ground_crank_squares: l1 * l1 + l2 * l2,
            ground_crank_twice: 2.0 * l1 * l2,
            rocker_minus_coupler_squares: l4 * l4 - l3 * l3,
            coupler_squared_four: 4.0 * l3 * l3,
            l3_squared: l3 * l3,
            l4_squared: l4 * l4,
            offset: [ratio * cd, ratio * sd],
            half_offset: [0.5 * ratio * cd, 0.5 * ratio * sd],
        }
    }

    /// `u = O4 − A`, `|u|²`, `R3 + i·h`, and A, at the crank angle's sine and cosine.
    #[inline(always)]
    fn chord(&self, s2: f64, c2: f64) -> ([f64; 2], [f64; 2], f64, [f64; 2]) {
        let crank = [self.l2 * c2, self.l2 * s2];
        let u = [self.l1 - crank[0], -crank[1]];
        let u_squared = self.ground_crank_squares - self.ground_crank_twice * c2;
        let r3 = u_squared - self.rocker_minus_coupler_squares;
        let h = (self.coupler_squared_four * u_squared - r3 * r3).sqrt();
        (crank, u, u_squared, [r3, h])
    }

    /// P at the crank angle `theta2`.
    #[inline(always)]
    pub fn position(&self, theta2: f64) -> [f64; 2] {
        let (s2, c2) = theta2.sin_cos();
        let (crank, u, u_squared, [r3, h]) = self.chord(s2, c2);
        // w = (R3 + i·h)·m, then P − A = u·w/|u|².
        let m = self.half_offset;
        let w = [r3 * m[0] - h * m[1], r3 * m[1] + h * m[0]];
        let inv = 1.0 / u_squared;
        [
            crank[0] + (u[0] * w[0] - u[1] * w[1]) * inv,
            crank[1] + (u[0] * w[1] + u[1] * w[0]) * inv,
        ]
    }

    /// `[P, v_P, a_P]` at the crank angle `theta2`, for the crank turning at `w2` and
    /// accelerating at `a2`.
    #[inline(always)]
    pub fn motion(&self, theta2: f64, w2: f64, a2: f64) -> [[f64; 2]; 3] {
        let (s2, c2) = theta2.sin_cos();
        let (crank, u, u_squared, [r3, h]) = self.chord(s2, c2);
        // One division for 1/(2·|u|²) and 1/g = 2/h.
        let inv = 1.0 / (u_squared * h);
        let half_inv_u = 0.5 * inv * h;
        let inv_g = 2.0 * inv * u_squared;
        let b3 = [
            (u[0] * r3 - u[1] * h) * half_inv_u,
            (u[0] * h + u[1] * r3) * half_inv_u,
        ];
        // B − O4 = (B − A) + (A − O4).
        let b4 = [b3[0] - u[0], b3[1] - u[1]];
        let [[w3, _], [a3, _]] = four_bar_rates_from_vectors(
            crank,
            b3,
            b4,
            inv_g,
            self.l3_squared,
            self.l4_squared,
            w2,
            a2,
        );
        let m = self.offset;
        let p = [b3[0] * m[0] - b3[1] * m[1], b3[0] * m[1] + b3[1] * m[0]];
        let (w2s, w3s) = (w2 * w2, w3 * w3);
        [
            [crank[0] + p[0], crank[1] + p[1]],
            [-w2 * crank[1] - w3 * p[1], w2 * crank[0] + w3 * p[0]],
            [
                -a2 * crank[1] - w2s * crank[0] - a3 * p[1] - w3s * p[0],
                a2 * crank[0] - w2s * crank[1] + a3 * p[0] - w3s * p[1],
            ],
        ]
    }
}

/// A hand-written Newton-Raphson for the four-bar (lengths `[l1, l2, l3, l4]`) with the
/// analytic 2×2 Jacobian, stopping at `max|f| < tolerance` (or after 50 updates), then the
/// rates in closed form. Allocation-free.
///
/// It iterates on the link vectors `b3 = l3·e^{iθ3}`, `b4 = l4·e^{iθ4}` as well as the
/// angles: a Newton update moves each angle by a small step, so rather than call `sin_cos`
/// again it turns the vector through the step. Each vector is turned from the last one that
/// came from `sin_cos` (`Link::turned`), through the whole way from that one's angle (exact: two
/// nearby floats differ exactly), so a turn's rounding never accumulates; `e^{iδ}` is a short
/// series, good to rounding for `|δ| ≤ 2⁻¹⁰`, beyond which it calls `sin_cos` afresh (a cold
/// start's first steps). From the sweep's predicted guess, the updates are about 1e-4, 1e-8
/// rad: every vector after the guess's is a turn.
///
/// Once per mechanism ([`new`](Self::new)): `l3²`, `l4²`.
///
/// Per call ([`motion`](Self::motion)): one `sin_cos` (θ2) and one per unknown at the guess;
/// per evaluation (one more than the updates taken) one division and about 20
/// multiplications and additions: the residual `f = Z + b3 − b4` with `Z = A − O4`, the
/// Jacobian's inverse `J⁻¹ = [[b4x, b4y], [b3x, b3y]]/g` with `g = b3 × b4` (`det J = −g`),
/// so the update is `Δθ3 = −(b4·f)/g`, `Δθ4 = −(b3·f)/g`; per update, each vector's turn,
/// about 10 multiplications and additions, no `sin_cos` while the steps stay small. The last
/// evaluation's vectors and `1/g` (at the returned position) serve the rates, as in
/// [`FourBarNorton`]: no further trigonometry or division. No `sqrt`, no `atan2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBarNewton {
    l1: f64,
    l2: f64,
    l3: f64,
    l4: f64,
    l3_squared: f64,
    l4_squared: f64,
}

impl FourBarNewton {
    /// The most updates [`motion`](Self::motion) takes.
    pub const MAX_UPDATES: usize = 50;

    /// Precomputes the constants of the linkage with lengths `[l1, l2, l3, l4]`.
    pub fn new(lengths: Lengths) -> Self {
        let [l1, l2, l3, l4] = lengths;
        FourBarNewton {
            l1,
            l2,
            l3,
            l4,
            l3_squared: l3 * l3,
            l4_squared: l4 * l4,
        }
    }

    /// `[[θ3, θ4], [ω3, ω4], [α3, α4]]` at the crank angle `theta2` from `guess = [θ3, θ4]`,
    /// for the crank turning at `w2` and accelerating at `a2`.
    #[inline]
    pub fn motion(&self, theta2: f64, guess: [f64; 2], tolerance: f64, w2: f64, a2: f64) -> State {
        let (s2, c2) = theta2.sin_cos();
        let crank = [self.l2 * c2, self.l2 * s2];
        let z = [crank[0] - self.l1, crank[1]];
        let [mut theta3, mut theta4] = guess;
        let mut link3 = Link::new(self.l3, theta3);
        let mut link4 = Link::new(self.l4, theta4);
        let (mut b3, mut b4) = (link3.vector, link4.vector);
        let mut updates = 0;
        loop {
            let f = [z[0] + b3[0] - b4[0], z[1] + b3[1] - b4[1]];
            let inv_g = 1.0 / cross(b3, b4);
            // max|f| < tolerance, without `max`'s care for NaN.
            if (f[0].abs() < tolerance && f[1].abs() < tolerance) || updates == Self::MAX_UPDATES {
                let [rates, accelerations] = four_bar_rates_from_vectors(
                    crank,
                    b3,
                    b4,
                    inv_g,
                    self.l3_squared,
                    self.l4_squared,
                    w2,
                    a2,
                );
                return [[theta3, theta4], rates, accelerations];
            }
            theta3 -= dot(b4, f) * inv_g;
            theta4 -= dot(b3, f) * inv_g;
            b3 = link3.turned(self.l3, theta3);
            b4 = link4.turned(self.l4, theta4);
            updates += 1;
        }
    }
}

/// A link's vector `l·e^{iθ}` as [`FourBarNewton`] keeps it: the last one computed by
/// `sin_cos`, at `angle`.
#[derive(Clone, Copy, Debug)]
struct Link {
    angle: f64,
    vector: [f64; 2],
}

impl Link {
    #[inline(always)]
    fn new(length: f64, angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        Link {
            angle,
            vector: [length * c, length * s],
        }
    }

    /// `length·e^{i·angle}`: the kept vector turned through `δ = angle − self.angle` where
    /// `|δ| ≤ 2⁻¹⁰`, with `sin δ = δ·(1 − δ²/6)` and `cos δ = 1 − δ²/2·(1 − δ²/12)` (the
    /// next terms, `δ⁵/120` and `δ⁶/720`, are below 2⁻⁵⁶ and 2⁻⁶⁹); else `sin_cos` afresh,
    /// kept for the next turns.
    #[inline(always)]
    fn turned(&mut self, length: f64, angle: f64) -> [f64; 2] {
        let step = angle - self.angle;
        if step.abs() <= 1.0 / 1024.0 {
            let squared = step * step;
            let sin = step * (1.0 - squared * (1.0 / 6.0));
            let cos = 1.0 - squared * 0.5 * (1.0 - squared * (1.0 / 12.0));
            let [x, y] = self.vector;
            [x * cos - y * sin, x * sin + y * cos]
        } else {
            *self = Link::new(length, angle);
            self.vector
        }
    }
}

/// [`FourBarNewton`] built for one call, for accuracy runs that do not time it.
pub fn four_bar_newton(
    l: &Lengths,
    theta2: f64,
    guess: [f64; 2],
    tolerance: f64,
    w2: f64,
    a2: f64,
) -> State {
    FourBarNewton::new(*l).motion(theta2, guess, tolerance, w2, a2)
}

/// The slider-crank with offset (crank `l2`, rod `l3`, slider line `y = c`; loop
/// `l2@θ2 + l3@θ3 − c@(π/2) − d@0 = 0`, as `mechanisms::SliderCrank`), open branch
/// (`cos θ3 > 0`: B on the +x side of A), returning `[θ3, d]` with rates and accelerations.
///
/// The rod `B − A = (x, y)` has `y = c − l2·sin θ2` and `x = l3·cos θ3 = √(l3² − y²)`; then
/// `θ3 = asin(y/l3)` (in [−π/2, π/2] on the open branch; glibc's `asin` costs about a third
/// of its `atan2`), `d = l2·cos θ2 + x`. The loop's derivatives, in their y and x parts:
/// `ω3 = −ω2·Ax/x`, `ḋ = −ω2·Ay − ω3·y`, `α3 = (ω2²·Ay − α2·Ax + ω3²·y)/x`,
/// `d̈ = −α2·Ay − ω2²·Ax − α3·y − ω3²·x`, with `A = l2·e^{iθ2}`.
///
/// Once per mechanism ([`new`](Self::new)): `l3²`, `1/l3`.
///
/// Per call ([`motion`](Self::motion)): one `sin_cos` (θ2), one `sqrt` (x), one `asin`
/// (θ3, the one angle returned; no `atan2`), one division (`1/x`), about 25 multiplications
/// and additions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderCrankClosed {
    l2: f64,
    c: f64,
    l3_squared: f64,
    inv_l3: f64,
}

impl SliderCrankClosed {
    /// Precomputes the constants of the slider-crank with crank `l2`, rod `l3` and offset `c`.
    pub fn new(l2: f64, l3: f64, c: f64) -> Self {
        SliderCrankClosed {
            l2,
            c,
            l3_squared: l3 * l3,
            inv_l3: 1.0 / l3,
        }
    }

    /// `[[θ3, d], [ω3, ḋ], [α3, d̈]]` at the crank angle `theta2`, for the crank turning at
    /// `w2` and accelerating at `a2`.
    #[inline(always)]
    pub fn motion(&self, theta2: f64, w2: f64, a2: f64) -> State {
        let (s2, c2) = theta2.sin_cos();
        let (ax, ay) = (self.l2 * c2, self.l2 * s2);
        let y = self.c - ay;
        let x = (self.l3_squared - y * y).sqrt();
        let theta3 = (y * self.inv_l3).asin();
        let inv_x = 1.0 / x;
        let w3 = -w2 * ax * inv_x;
        let d_dot = -w2 * ay - w3 * y;
        let (w2s, w3s) = (w2 * w2, w3 * w3);
        let a3 = (w2s * ay - a2 * ax + w3s * y) * inv_x;
        let d_ddot = -a2 * ay - w2s * ax - a3 * y - w3s * x;
        [[theta3, ax + x], [w3, d_dot], [a3, d_ddot]]
    }
}

/// The inverted slider-crank in Norton's general form (`[l1, l2, c, γ]`: ground, crank,
/// slide offset along the rocker, angle from rocker to slide; loop
/// `l2@θ2 − b@(θ4 + γ) − c@θ4 − l1@0 = 0`, as `mechanisms::InvertedSliderCrank`), open
/// branch (`b + c·cos γ > 0`), returning `[θ4, b]` with rates and accelerations.
///
/// With `R = A − O4 = (l2·cos θ2 − l1, l2·sin θ2)` and the slide's direction
/// `G = e^{i(θ4 + γ)}`, the loop is `R = b·G + c·e^{iθ4} = G·(b + c·e^{−iγ})`, so
/// `|R|² = (b + c·cos γ)² + (c·sin γ)²`: `h = b + c·cos γ = √(|R|² − (c·sin γ)²)`,
/// `b = h − c·cos γ`, and `G = R·(h + i·c·sin γ)/|R|²`; `θ4 = atan2(G) − γ`. Of G against R,
/// `G·R = h` and `G × R = −c·sin γ`. The derivatives `v_A = ḃ·G + i·ω4·R` and
/// `a_A = b̈·G + 2·i·ω4·ḃ·G + i·α4·R − ω4²·R` (sliding, Coriolis, tangential, normal), dotted
/// with R and crossed with G, with `v_A = i·ω2·A`, `a_A = (i·α2 − ω2²)·A`:
/// `ω4 = ω2·(G·A)/h`, `ḃ = ω2·l1·Ay/h`,
/// `b̈ = (α2·l1·Ay − ω2²·(l2² − l1·Ax) + 2·ω4·ḃ·c·sin γ + ω4²·|R|²)/h`,
/// `α4 = (α2·(G·A) − ω2²·(G × A) − 2·ω4·ḃ − ω4²·c·sin γ)/h`.
///
/// Once per mechanism ([`new`](Self::new)): `l1² + l2²`, `2·l1·l2`, `c·sin γ`, `c·cos γ`,
/// `(c·sin γ)²`, `l2²` (one `sin_cos` of γ).
///
/// Per call ([`motion`](Self::motion)): one `sin_cos` (θ2), one `sqrt` (h), one `asin` or
/// `acos` (of the rocker's unit vector, `unit_angle`: θ4, the one angle returned, in
/// (−π, π]), two divisions (`1/|R|²` for that unit vector, and `1/(|R|²·h)`, giving `1/h`),
/// about 45 multiplications and additions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InvertedSliderCrankClosed {
    l1: f64,
    l2: f64,
    gamma: f64,
    /// `l1² + l2²`: `|R|² = l1² + l2² − 2·l1·l2·cos θ2`.
    ground_crank_squares: f64,
    /// `2·l1·l2`.
    ground_crank_twice: f64,
    /// `c·sin γ`, the slide's distance from O4.
    across: f64,
    /// `(c·sin γ)²`.
    across_squared: f64,
    cos_gamma: f64,
    sin_gamma: f64,
    /// `c·cos γ`.
    along: f64,
    l2_squared: f64,
}

impl InvertedSliderCrankClosed {
    /// Precomputes the constants of the linkage with dimensions `[l1, l2, c, γ]`.
    pub fn new(dimensions: [f64; 4]) -> Self {
        let [l1, l2, c, gamma] = dimensions;
        let (sg, cg) = gamma.sin_cos();
        InvertedSliderCrankClosed {
            l1,
            l2,
            gamma,
            ground_crank_squares: l1 * l1 + l2 * l2,
            ground_crank_twice: 2.0 * l1 * l2,
            across: c * sg,
            across_squared: c * sg * c * sg,
            cos_gamma: cg,
            sin_gamma: sg,
            along: c * cg,
            l2_squared: l2 * l2,
        }
    }

    /// `[[θ4, b], [ω4, ḃ], [α4, b̈]]` at the crank angle `theta2`, for the crank turning at
    /// `w2` and accelerating at `a2`.
    #[inline(always)]
    pub fn motion(&self, theta2: f64, w2: f64, a2: f64) -> State {
        let (s2, c2) = theta2.sin_cos();
        let crank = [self.l2 * c2, self.l2 * s2];
        let r = [crank[0] - self.l1, crank[1]];
        let r_squared = self.ground_crank_squares - self.ground_crank_twice * c2;
        let h = (r_squared - self.across_squared).sqrt();
        // |R|²·G = R·(h + i·c·sin γ).
        let g = [r[0] * h - r[1] * self.across, r[0] * self.across + r[1] * h];
        // e^{iθ4} = G·e^{−iγ}, with |R|²·G as above.
        let inv_r = 1.0 / r_squared;
        let rocker = [
            (g[0] * self.cos_gamma + g[1] * self.sin_gamma) * inv_r,
            (g[1] * self.cos_gamma - g[0] * self.sin_gamma) * inv_r,
        ];
        let theta4 = unit_angle(rocker[1], rocker[0]);
        // One division for 1/h and 1/(|R|²·h).
        let inv = 1.0 / (r_squared * h);
        let inv_h = inv * r_squared;
        let (g_dot_a, g_cross_a) = (dot(g, crank) * inv, cross(g, crank) * inv);
        let l1_ay = self.l1 * crank[1];
        let w4 = w2 * g_dot_a;
        let b_dot = w2 * l1_ay * inv_h;
        let w2s = w2 * w2;
        let w4s = w4 * w4;
        let coriolis = 2.0 * w4 * b_dot;
        let b_ddot = (a2 * l1_ay - w2s * (self.l2_squared - self.l1 * crank[0])
            + coriolis * self.across
            + w4s * r_squared)
            * inv_h;
        let a4 = a2 * g_dot_a - w2s * g_cross_a - (coriolis + w4s * self.across) * inv_h;
        [[theta4, h - self.along], [w4, b_dot], [a4, b_ddot]]
    }
}

/// Rates and accelerations of a four-bar from its angles, by the closed forms of
/// KINEMATICS.md: `ω3 = (l2 ω2 / l3)·sin(θ4 − θ2)/sin(θ3 − θ4)`, …, and the C, D, E, F
/// formulas for `α3`, `α4`, written with each sine and cosine computed once: what a user
/// reaching for num-dual writes after the solve (two `sin_cos`, three divisions).
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

/// The angle of a unit vector `(x, y)` in (−π, π], as `atan2(y, x)` gives it, from the arc
/// sine or arc cosine of its smaller component (where each is well conditioned): glibc's
/// `asin` and `acos` cost under half its `atan2`.
#[inline]
fn unit_angle(y: f64, x: f64) -> f64 {
    if y.abs() <= x.abs() {
        let angle = y.asin();
        if x < 0.0 {
            std::f64::consts::PI.copysign(y) - angle
        } else {
            angle
        }
    } else {
        x.acos().copysign(y)
    }
}
