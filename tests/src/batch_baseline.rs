//! A hand-written batch kernel, the evidence that scene kernels over a slice of inputs can
//! vectorise: the four-bar's joint positions A and B for a slice of crank angles, written
//! into a caller's slice, with [`mechgen::fast::sin_cos`], one square root and one division
//! per angle, no `atan2` and no branch in the loop body.
//!
//! Geometry (the four-bar of `mechanisms::FourBar`): O2 = (0, 0), O4 = (l1, 0), the crank
//! pin A = l2·(cos θ2, sin θ2), and the rocker pin B where the circle of radius l3 about A
//! meets the circle of radius l4 about O4. With `d = O4 − A` and `D = |d|²`,
//! `B = A + k·d + t·d⊥`, where `d⊥ = (−d_y, d_x)` is `d` turned a quarter counter-clockwise,
//! `k = 1/2 + (l3² − l4²)/(2D)` (how far along the chord the foot of B lies, in chords) and
//! `t = √(l3²/D − k²)` (how far off it, in chords). The open branch is `t ≥ 0`: B to the left
//! (counter-clockwise) of the chord from A to O4, which is `sin(θ4 − θ3) > 0`, the branch
//! `FourBar::assemble(θ2, Branch::Open)` returns (checked by the tests below). The loop
//! computes `D = l1² + l2² − 2·l1·l2·cos θ2`, `k·D` and `t·D = √(l3²·D − (k·D)²)` straight
//! from `cos θ2`, and divides by `D` once: the division and the square root do not wait for
//! each other, which matters because the loop is bound by latency, not by throughput.
//!
//! Unreachable angles, where the two circles miss (`l3²/D < k²`), are not branched on in the
//! loop: the square root of a negative number makes B's lanes NaN, an OR of "is NaN" over
//! the outputs (no branch, so it vectorises too) notes it, and a search after the loop
//! reports the first. An angle beyond [`mechgen::fast::sin_cos_limit`], infinite or NaN
//! makes A NaN and is reported the same way.
//!
//! The loop runs through [`mechgen::simd::widest`], as the generated batch kernels' loops
//! do, so the two are compared on the same vectors: 4 `f64` lanes with AVX2 where the
//! processor has it, 2 on x86-64's baseline.

use mechgen::Real;
use mechgen::Vec2;
use mechgen::fast::sin_cos;

/// The four-bar's joint positions at one crank angle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Joints<T> {
    /// A, the crank pin.
    pub crank_pin: Vec2<T>,
    /// B, the rocker pin, on the open branch.
    pub rocker_pin: Vec2<T>,
}

/// Some crank angle of a batch could not be assembled: the first such, by index. Its output
/// and those of any other unreachable angle hold NaN; the others are valid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unreachable {
    /// Index of the first unreachable angle.
    pub index: usize,
}

/// Joint positions of the four-bar `[l1, l2, l3, l4]` on the open branch, one per crank
/// angle of `theta2`, into `out` (of the same length).
///
/// # Errors
///
/// [`Unreachable`] if some angle cannot be assembled (see the module documentation).
///
/// # Panics
///
/// If `theta2` and `out` differ in length.
#[inline(always)]
pub fn four_bar_joints<T: Real>(
    lengths: [T; 4],
    theta2: &[T],
    out: &mut [Joints<T>],
) -> Result<(), Unreachable> {
    four_bar_joints_with(lengths, theta2, out, sin_cos)
}

/// [`four_bar_joints`] with another `sin_cos`, to measure what the fast one buys.
///
/// # Errors
///
/// As [`four_bar_joints`].
///
/// # Panics
///
/// As [`four_bar_joints`].
#[inline(always)]
pub fn four_bar_joints_with<T: Real>(
    lengths: [T; 4],
    theta2: &[T],
    out: &mut [Joints<T>],
    sin_cos: impl Fn(T) -> (T, T),
) -> Result<(), Unreachable> {
    assert_eq!(theta2.len(), out.len(), "one output per crank angle");
    let any_nan = mechgen::simd::widest(
        #[inline(always)]
        || joints_lanes(lengths, theta2, out, sin_cos),
    );
    unreachable_at(any_nan, out)
}

/// [`four_bar_joints`] as built, never through [`mechgen::simd::widest`]'s wider copy: the
/// other path, for the tests that hold the two to the same bits.
///
/// # Errors
///
/// As [`four_bar_joints`].
///
/// # Panics
///
/// As [`four_bar_joints`].
#[inline(never)]
pub fn four_bar_joints_portable<T: Real>(
    lengths: [T; 4],
    theta2: &[T],
    out: &mut [Joints<T>],
) -> Result<(), Unreachable> {
    assert_eq!(theta2.len(), out.len(), "one output per crank angle");
    let any_nan = joints_lanes(lengths, theta2, out, sin_cos);
    unreachable_at(any_nan, out)
}

/// `Ok`, or where the loop found an angle that failed, the first (its rocker pin is NaN).
fn unreachable_at<T: Real>(any_nan: bool, out: &[Joints<T>]) -> Result<(), Unreachable> {
    if !any_nan {
        return Ok(());
    }
    let index = out
        .iter()
        .position(|joints| joints.rocker_pin.x.is_nan())
        .unwrap_or_default();
    Err(Unreachable { index })
}

/// The loop of [`four_bar_joints_with`]: whether any angle failed.
#[inline(always)]
fn joints_lanes<T: Real>(
    lengths: [T; 4],
    theta2: &[T],
    out: &mut [Joints<T>],
    sin_cos: impl Fn(T) -> (T, T),
) -> bool {
    let [l1, l2, l3, l4] = lengths;
    let (two, half) = (T::constant(2.0), T::constant(0.5));
    let l3_squared = l3 * l3;
    // D = |O4 − A|² = l1² + l2² − 2·l1·l2·cos θ2 and k·D = (D + l3² − l4²)/2, both straight
    // from cos θ2, so the square root's operand is ready early.
    let base = l1 * l1 + l2 * l2;
    let slope = two * l1 * l2;
    let kd_base = half * (base + l3_squared - l4 * l4);
    let kd_slope = half * slope;
    // B is NaN wherever A is, so its x alone tells whether an angle failed; noted in the
    // loop with no early exit, so it vectorises too, and the search for the index runs only
    // when something failed.
    let mut any_nan = false;
    for (&theta, joints) in theta2.iter().zip(out.iter_mut()) {
        let (s, c) = sin_cos(theta);
        let (ax, ay) = (l2 * c, l2 * s);
        let (dx, dy) = (l1 - ax, -ay);
        let chord_squared = base - slope * c;
        let kd = kd_base - kd_slope * c;
        // t·D, NaN where the circles miss: found after the loop. The division and the
        // square root are independent, so their latencies overlap.
        let td = (l3_squared * chord_squared - kd * kd).sqrt();
        let inverse = T::one() / chord_squared;
        let (dx_over_d, dy_over_d) = (dx * inverse, dy * inverse);
        *joints = Joints {
            crank_pin: Vec2::new(ax, ay),
            rocker_pin: Vec2::new(
                (ax + kd * dx_over_d) - td * dy_over_d,
                (ay + kd * dy_over_d) + td * dx_over_d,
            ),
        };
        any_nan |= joints.rocker_pin.x.is_nan();
    }
    any_nan
}

/// [`four_bar_joints`] for `f64`, kept out of line so its machine code can be read
/// (`cargo rustc --release -p mechgen-tests --lib -- --emit asm`) and timed on its own.
///
/// # Errors
///
/// As [`four_bar_joints`].
#[inline(never)]
pub fn four_bar_joints_f64(
    lengths: [f64; 4],
    theta2: &[f64],
    out: &mut [Joints<f64>],
) -> Result<(), Unreachable> {
    four_bar_joints(lengths, theta2, out)
}

/// [`four_bar_joints`] for `f32`, out of line.
///
/// # Errors
///
/// As [`four_bar_joints`].
#[inline(never)]
pub fn four_bar_joints_f32(
    lengths: [f32; 4],
    theta2: &[f32],
    out: &mut [Joints<f32>],
) -> Result<(), Unreachable> {
    four_bar_joints(lengths, theta2, out)
}

/// The same kernel with the platform's `f64::sin_cos`, an opaque call: what the loop costs
/// when it cannot vectorise.
///
/// # Errors
///
/// As [`four_bar_joints`].
#[inline(never)]
pub fn four_bar_joints_f64_platform_sin_cos(
    lengths: [f64; 4],
    theta2: &[f64],
    out: &mut [Joints<f64>],
) -> Result<(), Unreachable> {
    four_bar_joints_with(lengths, theta2, out, f64::sin_cos)
}

#[cfg(test)]
mod tests {
    use mechanisms::FourBar;
    use mechgen::{Branch, Vec2};

    use super::*;

    const LENGTHS: [f64; 4] = [180.0, 80.0, 200.0, 150.0];

    /// A turn of crank angles, one degree apart, and some beyond a turn either way.
    fn angles() -> Vec<f64> {
        (-720..=720).map(|k| f64::from(k).to_radians()).collect()
    }

    fn distance(p: Vec2<f64>, q: Vec2<f64>) -> f64 {
        (p.x - q.x).hypot(p.y - q.y)
    }

    #[test]
    fn agrees_with_the_generated_closed_form() {
        let [l1, l2, l3, l4] = LENGTHS;
        let linkage = FourBar::new(l1, l2, l3, l4).unwrap();
        let theta2 = angles();
        let mut out = vec![Joints::default(); theta2.len()];
        four_bar_joints_f64(LENGTHS, &theta2, &mut out).unwrap();
        let mut worst = 0f64;
        for (&theta, joints) in theta2.iter().zip(&out) {
            let q = linkage.assemble(theta, Branch::Open).unwrap();
            let points = linkage.points(theta, &q).unwrap();
            worst = worst
                .max(distance(joints.crank_pin, points.crank_pin))
                .max(distance(joints.rocker_pin, points.rocker_pin));
        }
        // Coordinates up to 330 mm, agreeing to 1e-12 mm.
        assert!(worst <= 1e-12, "{worst:e}");

        // The platform-sin_cos variant gives the same, and the f32 kernel the same to f32's
        // precision.
        let mut platform = vec![Joints::default(); theta2.len()];
        four_bar_joints_f64_platform_sin_cos(LENGTHS, &theta2, &mut platform).unwrap();
        let theta2_f32: Vec<f32> = theta2.iter().map(|&t| t as f32).collect();
        let mut single = vec![Joints::default(); theta2.len()];
        four_bar_joints_f32(LENGTHS.map(|l| l as f32), &theta2_f32, &mut single).unwrap();
        for ((fast, platform), single) in out.iter().zip(&platform).zip(&single) {
            assert!(distance(fast.rocker_pin, platform.rocker_pin) <= 1e-12);
            let b = single.rocker_pin;
            let b = Vec2::new(f64::from(b.x), f64::from(b.y));
            assert!(distance(fast.rocker_pin, b) <= 1e-4 * l1, "{b:?}");
        }
    }

    #[test]
    fn open_branch_is_left_of_the_chord() {
        let theta2 = angles();
        let mut out = vec![Joints::default(); theta2.len()];
        four_bar_joints_f64(LENGTHS, &theta2, &mut out).unwrap();
        for joints in &out {
            let (a, b) = (joints.crank_pin, joints.rocker_pin);
            let (chord_x, chord_y) = (LENGTHS[0] - a.x, -a.y);
            let cross = chord_x * (b.y - a.y) - chord_y * (b.x - a.x);
            assert!(cross > 0.0);
            assert!((distance(a, b) - LENGTHS[2]).abs() < 1e-11);
            assert!((distance(Vec2::new(LENGTHS[0], 0.0), b) - LENGTHS[3]).abs() < 1e-11);
        }
    }

    #[test]
    fn unreachable_angles_are_reported_after_the_loop() {
        // A Grashof double-rocker (the coupler is the shortest link): the crank swings
        // through part of a turn only.
        let lengths = [100.0, 80.0, 30.0, 60.0];
        let linkage = FourBar::new(100.0, 80.0, 30.0, 60.0).unwrap();
        let theta2 = angles();
        let first = theta2
            .iter()
            .position(|&t| linkage.assemble(t, Branch::Open).is_err())
            .unwrap();
        let mut out = vec![Joints::default(); theta2.len()];
        assert_eq!(
            four_bar_joints_f64(lengths, &theta2, &mut out),
            Err(Unreachable { index: first })
        );
        for (&theta, joints) in theta2.iter().zip(&out) {
            let reachable = linkage.assemble(theta, Branch::Open).is_ok();
            assert_eq!(joints.rocker_pin.x.is_nan(), !reachable, "{theta}");
        }
        // Out of `sin_cos`'s range is reported too.
        let mut one = [Joints::default()];
        assert_eq!(
            four_bar_joints_f64(LENGTHS, &[f64::INFINITY], &mut one),
            Err(Unreachable { index: 0 })
        );
    }
}
