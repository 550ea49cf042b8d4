//! `mechgen::fast::sin_cos` against references, in ulps of the exact result: for `f64`
//! against a double-double reference (an exact Cody–Waite reduction with π/2 in three
//! doubles, then Taylor series in double-double), itself checked against `f64::sin_cos`; for
//! `f32` against `f64::sin_cos`. Dense grids, random points (fixed seed), the floats nearest
//! every multiple of π/2 up to the limit (where the reduction cancels most), and the edges.
//!
//! `mechgen::fast::unit_angle` likewise, against a double-double `atan2` (the platform's,
//! refined by a Newton step with the double-double `sin` and `cos`) for `f64` and against
//! `f64::atan2` for `f32`: unit vectors `(cos θ, sin θ)` rounded on dense grids (with finer
//! ones around every multiple of π/4: the axes, and the diagonals where the method
//! switches), random points, the pairs next to `|y| = |x|`, `f32` pairs `(y, √(1 − y²))`
//! rounded, and vectors of length `1 ± k·ε`.
//!
//! `cargo test -p mechgen-tests --release --test fast_math -- --ignored` also runs every
//! `f32` in the range (about 2.3·10⁹ inputs) and 2·10⁸ random `f64` inputs, a few minutes
//! on two cores, and `unit_angle` on every `f32` pair `(y, √(1 − y²))`.

use std::f64::consts::FRAC_2_PI;

use mechgen::fast::{sin_cos, sin_cos_limit, unit_angle};

/// The bound `sin_cos`'s documentation states, in ulps of the exact result, for both types.
const BOUND_ULPS: f64 = 0.9;

// ---------------------------------------------------------------------------------------
// Double-double arithmetic for the f64 reference.

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `hi + lo` with `|lo| ≤ ulp(hi)/2`.
#[derive(Clone, Copy, Debug)]
struct Dd {
    hi: f64,
    lo: f64,
}

impl Dd {
    fn new(hi: f64, lo: f64) -> Self {
        let (hi, lo) = two_sum(hi, lo);
        Self { hi, lo }
    }

    fn add(self, other: Self) -> Self {
        // The accurate addition: relative error about 2^-104 of the result.
        let (s, e) = two_sum(self.hi, other.hi);
        let (t, f) = two_sum(self.lo, other.lo);
        let (s, e) = two_sum(s, e + t);
        Self::new(s, e + f)
    }

    fn mul(self, other: Self) -> Self {
        let (p, e) = two_prod(self.hi, other.hi);
        Self::new(p, e + (self.hi * other.lo + self.lo * other.hi))
    }

    fn div_f64(self, d: f64) -> Self {
        let q1 = self.hi / d;
        let (p, e) = two_prod(q1, d);
        let q2 = (((self.hi - p) - e) + self.lo) / d;
        Self::new(q1, q2)
    }

    fn neg(self) -> Self {
        Self {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

/// π/2 in three doubles; the rest is below 6e-50.
const PI_OVER_2: [f64; 3] = [
    std::f64::consts::FRAC_PI_2,
    6.123_233_995_736_766e-17,
    -1.497_384_904_859_169_8e-33,
];

/// `x − k·π/2` to double-double precision, whatever the cancellation: the seven doubles
/// `x`, `−k·π/2` as three exact products of two doubles each, summed exactly as a
/// non-overlapping expansion (Shewchuk's grow-expansion), then rounded to double-double.
fn reduce_exactly(x: f64, k: f64) -> Dd {
    let mut terms = vec![x];
    for part in PI_OVER_2 {
        let (p, e) = two_prod(k, part);
        terms.push(-p);
        terms.push(-e);
    }
    let mut expansion: Vec<f64> = Vec::new();
    for term in terms {
        let mut q = term;
        let mut grown = Vec::with_capacity(expansion.len() + 1);
        for &component in &expansion {
            let (sum, error) = two_sum(q, component);
            if error != 0.0 {
                grown.push(error);
            }
            q = sum;
        }
        grown.push(q);
        expansion = grown;
    }
    // Components increase in magnitude and do not overlap: add from the largest down.
    expansion
        .iter()
        .rev()
        .fold(Dd { hi: 0.0, lo: 0.0 }, |acc, &c| {
            acc.add(Dd { hi: c, lo: 0.0 })
        })
}

/// sin and cos of a double-double `|r| ≤ 0.8` by their Taylor series.
fn sin_cos_dd(r: Dd) -> (Dd, Dd) {
    let r2 = r.mul(r);
    let series = |first: Dd, offset: f64| {
        let mut term = first;
        let mut sum = first;
        let mut i = 1.0;
        while term.hi.abs() > 1e-40 * sum.hi.abs().max(1e-300) && i < 40.0 {
            term = term
                .mul(r2)
                .div_f64((2.0 * i - 1.0 + offset) * (2.0 * i + offset))
                .neg();
            sum = sum.add(term);
            i += 1.0;
        }
        sum
    };
    (series(r, 1.0), series(Dd { hi: 1.0, lo: 0.0 }, 0.0))
}

/// The reference sin and cos of a double, in double-double, correct to about 2^-100
/// relative (the reduction is exact but for π/2's tail, `k·6e-50`, and the closest double to
/// a multiple of π/2 below 1e6 is 6.2e-19 away from it).
fn reference(x: f64) -> (Dd, Dd) {
    let k = (x * FRAC_2_PI).round();
    let (s, c) = sin_cos_dd(reduce_exactly(x, k));
    match (k as i64).rem_euclid(4) {
        0 => (s, c),
        1 => (c, s.neg()),
        2 => (s.neg(), c.neg()),
        _ => (c.neg(), s),
    }
}

// ---------------------------------------------------------------------------------------
// Errors in ulps.

/// The ulp of a `p`-bit float (`p` = 53 or 24, smallest subnormal step `tiny`) at the exact
/// value `v = hi + lo`: that of the binade holding `v` (one below a power of two when `lo`
/// pulls `v` under it).
fn ulp(hi: f64, lo: f64, p: i32, tiny: f64) -> f64 {
    if hi == 0.0 {
        return tiny;
    }
    let mut exponent = hi.abs().log2().floor() as i32;
    // log2 can be off by one next to a power of two: fix it exactly.
    if 2f64.powi(exponent) > hi.abs() {
        exponent -= 1;
    } else if 2f64.powi(exponent + 1) <= hi.abs() {
        exponent += 1;
    }
    if hi.abs() == 2f64.powi(exponent) && lo != 0.0 && lo.signum() != hi.signum() {
        exponent -= 1;
    }
    2f64.powi(exponent - (p - 1)).max(tiny)
}

fn ulps_f64(y: f64, exact: Dd) -> f64 {
    ((y - exact.hi) - exact.lo).abs() / ulp(exact.hi, exact.lo, 53, f64::from_bits(1))
}

fn ulps_f32(y: f32, exact: f64) -> f64 {
    (f64::from(y) - exact).abs() / ulp(exact, 0.0, 24, f64::from(f32::from_bits(1)))
}

/// Largest errors seen, with where.
#[derive(Debug, Default)]
struct Worst {
    sin: (f64, f64),
    cos: (f64, f64),
    points: u64,
    both_correctly_rounded: u64,
}

impl Worst {
    fn record(&mut self, x: f64, sin_ulps: f64, cos_ulps: f64) {
        assert!(
            sin_ulps <= BOUND_ULPS && cos_ulps <= BOUND_ULPS,
            "x = {x:e} ({:#x}): sin off by {sin_ulps} ulp, cos by {cos_ulps} ulp",
            x.to_bits()
        );
        if sin_ulps > self.sin.0 {
            self.sin = (sin_ulps, x);
        }
        if cos_ulps > self.cos.0 {
            self.cos = (cos_ulps, x);
        }
        self.points += 1;
        if sin_ulps <= 0.5 && cos_ulps <= 0.5 {
            self.both_correctly_rounded += 1;
        }
    }

    fn report(&self, what: &str) {
        eprintln!(
            "{what}: {} points, max error sin {:.4} ulp at {:e}, cos {:.4} ulp at {:e}, \
             both correctly rounded at {:.2}%",
            self.points,
            self.sin.0,
            self.sin.1,
            self.cos.0,
            self.cos.1,
            100.0 * self.both_correctly_rounded as f64 / self.points as f64
        );
    }
}

/// The worst of several.
fn merge(parts: Vec<Worst>) -> Worst {
    parts.into_iter().fold(Worst::default(), |mut all, part| {
        if part.sin.0 > all.sin.0 {
            all.sin = part.sin;
        }
        if part.cos.0 > all.cos.0 {
            all.cos = part.cos;
        }
        all.points += part.points;
        all.both_correctly_rounded += part.both_correctly_rounded;
        all
    })
}

fn check_f64(worst: &mut Worst, x: f64) {
    let (s, c) = sin_cos(x);
    let (rs, rc) = reference(x);
    worst.record(x, ulps_f64(s, rs), ulps_f64(c, rc));
}

fn check_f32(worst: &mut Worst, x: f32) {
    let (s, c) = sin_cos(x);
    let (rs, rc) = f64::from(x).sin_cos();
    worst.record(f64::from(x), ulps_f32(s, rs), ulps_f32(c, rc));
}

/// SplitMix64: a fixed-seed generator, so failures reproduce.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The double nearest `k·π/2`.
fn nearest_multiple_f64(k: f64) -> f64 {
    let (p, e) = two_prod(k, PI_OVER_2[0]);
    p + (e + k * PI_OVER_2[1])
}

// ---------------------------------------------------------------------------------------
// The reference itself.

#[test]
fn the_double_double_reference_agrees_with_the_platform() {
    let mut rng = SplitMix(7);
    let limit: f64 = sin_cos_limit();
    for i in 0..100_000 {
        let x = if i % 2 == 0 {
            (rng.unit() * 2.0 - 1.0) * limit
        } else {
            (rng.unit() * 2.0 - 1.0) * 10.0
        };
        let (rs, rc) = reference(x);
        let (s, c) = x.sin_cos();
        // The platform's sin and cos are within an ulp, so are nearly always the reference
        // rounded; an error here would be the reference's.
        assert!(ulps_f64(s, rs) < 1.0 && ulps_f64(c, rc) < 1.0, "{x:e}");
    }
    // And at the worst case of the reduction.
    let x = 45.553_093_477_052;
    let (_, rc) = reference(x);
    assert!(ulps_f64(x.cos(), rc) < 1.0);
    assert!((rc.hi.abs() - 6.19e-19).abs() < 1e-21, "{rc:?}");
}

// ---------------------------------------------------------------------------------------
// f64.

#[test]
fn f64_dense_grids() {
    let mut worst = Worst::default();
    // A few turns either way, where crank angles live, and the whole range.
    let n = 2_000_000;
    let span = 8.0 * std::f64::consts::PI;
    for i in 0..=n {
        check_f64(&mut worst, -span + 2.0 * span * f64::from(i) / f64::from(n));
    }
    let limit: f64 = sin_cos_limit();
    for i in 0..=n {
        check_f64(
            &mut worst,
            -limit + 2.0 * limit * f64::from(i) / f64::from(n),
        );
    }
    worst.report("f64 grids");
}

#[test]
fn f64_random_points() {
    let mut worst = Worst::default();
    let mut rng = SplitMix(2024);
    let limit: f64 = sin_cos_limit();
    for i in 0..2_000_000 {
        let sign = if rng.next() & 1 == 0 { 1.0 } else { -1.0 };
        let magnitude = match i % 3 {
            // Log-uniform from 1e-300 to the limit.
            0 => 10f64.powf(-300.0 + rng.unit() * (300.0 + limit.log10())),
            // Uniform over the range.
            1 => rng.unit() * limit,
            // Uniform over the first turns.
            _ => rng.unit() * 20.0,
        };
        check_f64(&mut worst, sign * magnitude.min(limit));
    }
    worst.report("f64 random");
}

#[test]
#[ignore = "2e8 inputs: run with --release --ignored"]
fn f64_many_random_points() {
    let limit: f64 = sin_cos_limit();
    let parts: Vec<Worst> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..2u64)
            .map(|seed| {
                scope.spawn(move || {
                    let mut worst = Worst::default();
                    let mut rng = SplitMix(1000 + seed);
                    for i in 0..100_000_000u32 {
                        let u = rng.unit() * 2.0 - 1.0;
                        let x = if i % 4 == 0 { u * limit } else { u * 20.0 };
                        check_f64(&mut worst, x);
                    }
                    worst
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    merge(parts).report("f64 random, 2e8");
}

#[test]
fn f64_next_to_every_multiple_of_half_pi() {
    let mut worst = Worst::default();
    let limit: f64 = sin_cos_limit();
    let last = (limit * FRAC_2_PI).floor() as u32;
    for k in 0..=last {
        let mut x = nearest_multiple_f64(f64::from(k));
        for _ in 0..2 {
            x = x.next_down();
        }
        for _ in 0..5 {
            if x.abs() <= limit {
                check_f64(&mut worst, x);
                check_f64(&mut worst, -x);
            }
            x = x.next_up();
        }
    }
    worst.report("f64 near k·π/2");
    // The closest approach of all is among them: 45.553093477052, 6.2e-19 from 29·π/2.
    assert_eq!(nearest_multiple_f64(29.0), 45.553_093_477_052);
}

#[test]
fn f64_edges() {
    let mut worst = Worst::default();
    let limit: f64 = sin_cos_limit();
    let edges = [
        0.0,
        f64::from_bits(1),
        f64::MIN_POSITIVE,
        1e-300,
        1e-20,
        1e-8,
        std::f64::consts::FRAC_PI_4,
        std::f64::consts::FRAC_PI_4.next_up(),
        std::f64::consts::FRAC_PI_2,
        std::f64::consts::PI,
        3.0 * std::f64::consts::FRAC_PI_2,
        std::f64::consts::TAU,
        limit,
        limit.next_down(),
    ];
    for x in edges {
        check_f64(&mut worst, x);
        check_f64(&mut worst, -x);
    }
    worst.report("f64 edges");

    let (s, c) = sin_cos(0.0f64);
    assert!(s == 0.0 && s.is_sign_positive() && c == 1.0);
    let (s, c) = sin_cos(-0.0f64);
    assert!(s == 0.0 && s.is_sign_negative() && c == 1.0);
    assert_eq!(sin_cos(f64::from_bits(1)).0, f64::from_bits(1));
    assert_eq!(sin_cos(-1e-300f64), (-1e-300, 1.0));

    for x in [
        limit.next_up(),
        2e6,
        1e300,
        f64::MAX,
        f64::INFINITY,
        f64::NAN,
    ] {
        for x in [x, -x] {
            let (s, c) = sin_cos(x);
            assert!(s.is_nan() && c.is_nan(), "{x:e}: {s}, {c}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// f32.

/// Every `f32` of magnitude at most the limit whose bit pattern is a multiple of `stride`,
/// both signs, split over two threads.
fn f32_sweep(stride: u32) -> Worst {
    let top = sin_cos_limit::<f32>().to_bits();
    let halves = [(0, top / 2), (top / 2 + 1, top)];
    let results: Vec<Worst> = std::thread::scope(|scope| {
        let handles: Vec<_> = halves
            .iter()
            .map(|&(from, to)| {
                scope.spawn(move || {
                    let mut worst = Worst::default();
                    let mut bits = from.next_multiple_of(stride);
                    while bits <= to {
                        let x = f32::from_bits(bits);
                        check_f32(&mut worst, x);
                        check_f32(&mut worst, -x);
                        bits += stride;
                    }
                    worst
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    merge(results)
}

#[test]
fn f32_strided_over_the_range() {
    f32_sweep(97).report("f32 every 97th");
}

#[test]
#[ignore = "2.3e9 inputs: run with --release --ignored"]
fn f32_exhaustive_over_the_range() {
    f32_sweep(1).report("f32 exhaustive");
}

#[test]
fn f32_dense_grid_random_and_near_multiples() {
    let mut worst = Worst::default();
    let n = 1_000_000;
    for i in 0..=n {
        check_f32(
            &mut worst,
            (-8.0 + 16.0 * f64::from(i) / f64::from(n)) as f32,
        );
    }
    let mut rng = SplitMix(32);
    let limit = f64::from(sin_cos_limit::<f32>());
    for _ in 0..1_000_000 {
        check_f32(&mut worst, ((rng.unit() * 2.0 - 1.0) * limit) as f32);
    }
    let last = (limit * FRAC_2_PI).floor() as u32;
    for k in 0..=last {
        let mut x = (f64::from(k) * std::f64::consts::FRAC_PI_2) as f32;
        for _ in 0..16 {
            x = x.next_down();
        }
        for _ in 0..33 {
            if f64::from(x.abs()) <= limit {
                check_f32(&mut worst, x);
                check_f32(&mut worst, -x);
            }
            x = x.next_up();
        }
    }
    worst.report("f32 grid, random, near k·π/2");
}

#[test]
fn f32_edges() {
    let limit = sin_cos_limit::<f32>();
    let mut worst = Worst::default();
    for x in [
        0.0,
        f32::from_bits(1),
        f32::MIN_POSITIVE,
        1e-20,
        std::f32::consts::FRAC_PI_4,
        std::f32::consts::FRAC_PI_2,
        std::f32::consts::PI,
        3.0 * std::f32::consts::FRAC_PI_2,
        std::f32::consts::TAU,
        limit,
        limit.next_down(),
    ] {
        check_f32(&mut worst, x);
        check_f32(&mut worst, -x);
    }
    worst.report("f32 edges");
    let (s, c) = sin_cos(-0.0f32);
    assert!(s == 0.0 && s.is_sign_negative() && c == 1.0);
    for x in [limit.next_up(), 1e4, f32::MAX, f32::INFINITY, f32::NAN] {
        for x in [x, -x] {
            let (s, c) = sin_cos(x);
            assert!(s.is_nan() && c.is_nan(), "{x:e}: {s}, {c}");
        }
    }
}

/// Against the platform's own `sin_cos`, in whole ulps: never more than one apart.
#[test]
fn within_one_ulp_of_the_platform() {
    let mut rng = SplitMix(99);
    let limit: f64 = sin_cos_limit();
    for _ in 0..1_000_000 {
        let x = (rng.unit() * 2.0 - 1.0) * if rng.next() & 1 == 0 { limit } else { 10.0 };
        let (s, c) = sin_cos(x);
        let (ps, pc) = x.sin_cos();
        for (a, b) in [(s, ps), (c, pc)] {
            let apart = (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs();
            assert!(apart <= 1 || a == b, "{x:e}: {a:e} vs {b:e}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// unit_angle.

/// The bound `unit_angle`'s documentation states for unit vectors (components of
/// `(cos θ, sin θ)` rounded, or any pair of length `1 ± ε`), in ulps of the exact
/// `atan2(y, x)` of the given components, for both types.
const ANGLE_BOUND_ULPS: f64 = 1.0;

/// The reference `atan2(y, x)` in double-double: the platform's `atan2` refined by one
/// Newton step with double-double `sin` and `cos` of it, `φ + (y·cos φ − x·sin φ)/(x·cos φ
/// + y·sin φ)` (the step is below an ulp, so `atan` of it is the step itself to 2^-150).
fn reference_atan2(y: f64, x: f64) -> Dd {
    let phi = y.atan2(x);
    let (s, c) = reference(phi);
    let y_dd = Dd { hi: y, lo: 0.0 };
    let x_dd = Dd { hi: x, lo: 0.0 };
    let num = y_dd.mul(c).add(x_dd.mul(s).neg());
    let den = x * c.hi + y * s.hi;
    Dd::new(phi, 0.0).add(Dd::new(num.hi / den, 0.0))
}

/// Largest error seen, with where.
#[derive(Debug, Default)]
struct WorstAngle {
    ulps: f64,
    at: (f64, f64),
    points: u64,
    correctly_rounded: u64,
}

impl WorstAngle {
    fn record(&mut self, y: f64, x: f64, ulps: f64, bound: f64) {
        assert!(
            ulps <= bound,
            "unit_angle({y:e}, {x:e}) off by {ulps} ulp (bound {bound})"
        );
        if ulps > self.ulps {
            self.ulps = ulps;
            self.at = (y, x);
        }
        self.points += 1;
        if ulps <= 0.5 {
            self.correctly_rounded += 1;
        }
    }

    fn report(&self, what: &str) {
        eprintln!(
            "{what}: {} points, max error {:.4} ulp at (y, x) = ({:e}, {:e}), correctly \
             rounded at {:.2}%",
            self.points,
            self.ulps,
            self.at.0,
            self.at.1,
            100.0 * self.correctly_rounded as f64 / self.points as f64
        );
    }
}

fn angle_ulps_f64(y: f64, x: f64) -> f64 {
    ulps_f64(unit_angle(y, x), reference_atan2(y, x))
}

fn angle_ulps_f32(y: f32, x: f32) -> f64 {
    ulps_f32(unit_angle(y, x), f64::from(y).atan2(f64::from(x)))
}

fn check_angle_f64(worst: &mut WorstAngle, y: f64, x: f64) {
    worst.record(y, x, angle_ulps_f64(y, x), ANGLE_BOUND_ULPS);
}

fn check_angle_f32(worst: &mut WorstAngle, y: f32, x: f32) {
    worst.record(
        f64::from(y),
        f64::from(x),
        angle_ulps_f32(y, x),
        ANGLE_BOUND_ULPS,
    );
}

/// The unit vector at `theta`, each component rounded.
fn unit_f64(theta: f64) -> (f64, f64) {
    theta.sin_cos()
}

fn unit_f32(theta: f64) -> (f32, f32) {
    let (s, c) = theta.sin_cos();
    (s as f32, c as f32)
}

/// Angles on a grid of `n` steps over (−π, π], plus `m` steps of `step` either side of
/// every multiple of π/4 (the axes, where the result's binade changes, and the diagonals,
/// where the method switches between arc sine and arc cosine).
fn angle_grid(n: u32, m: u32, step: f64) -> impl Iterator<Item = f64> {
    let pi = std::f64::consts::PI;
    let grid = (0..=n).map(move |i| -pi + 2.0 * pi * f64::from(i) / f64::from(n.max(1)));
    let near = (-4..=4).flat_map(move |j| {
        let centre = f64::from(j) * std::f64::consts::FRAC_PI_4;
        (0..=2 * m).map(move |i| centre + (f64::from(i) - f64::from(m)) * step)
    });
    grid.chain(near)
}

#[test]
fn the_atan2_reference_agrees_with_the_platform() {
    let mut rng = SplitMix(11);
    for _ in 0..100_000 {
        let (y, x) = unit_f64((rng.unit() * 2.0 - 1.0) * std::f64::consts::PI);
        let r = reference_atan2(y, x);
        assert!(ulps_f64(y.atan2(x), r) < 1.0, "{y:e}, {x:e}");
        // Newton's step converged: a second one changes nothing.
        let (s, c) = reference(r.hi);
        let num = Dd { hi: y, lo: 0.0 }
            .mul(c)
            .add(Dd { hi: x, lo: 0.0 }.mul(s).neg());
        let step = num.hi / (x * c.hi + y * s.hi);
        assert!(
            (step - r.lo).abs() <= 2f64.powi(-100) * r.hi.abs(),
            "{y:e}, {x:e}"
        );
    }
}

#[test]
fn unit_angle_f64_grids_and_random_points() {
    let mut worst = WorstAngle::default();
    for theta in angle_grid(2_000_000, 20_000, 1e-9).chain(angle_grid(0, 20_000, 1e-15)) {
        let (y, x) = unit_f64(theta);
        check_angle_f64(&mut worst, y, x);
    }
    let mut rng = SplitMix(4242);
    for _ in 0..1_000_000 {
        let (y, x) = unit_f64((rng.unit() * 2.0 - 1.0) * std::f64::consts::PI);
        check_angle_f64(&mut worst, y, x);
    }
    worst.report("unit_angle f64 (cos θ, sin θ)");
}

/// `k` with `|(x, y)| = 1 ± k·ε`, from the double-double `x² + y²`.
fn length_in_epsilons(y: f64, x: f64) -> f64 {
    let (x, y) = (Dd { hi: x, lo: 0.0 }, Dd { hi: y, lo: 0.0 });
    let excess = x.mul(x).add(y.mul(y)).add(Dd { hi: -1.0, lo: 0.0 });
    (excess.hi / 2.0).abs() / f64::EPSILON
}

#[test]
fn unit_angle_f64_at_the_switch() {
    // |y| = |x| exactly and up to 8 ulps either side, all four diagonals: the nearest
    // doubles to the unit circle there and their neighbours, of length 1 ± k·ε for k up to
    // about 10, held to the bound for length 1 ± k·ε.
    let mut worst = WorstAngle::default();
    let mut d = std::f64::consts::FRAC_1_SQRT_2;
    for _ in 0..8 {
        d = d.next_down();
    }
    for _ in 0..17 {
        let mut e = d;
        for _ in 0..4 {
            e = e.next_down();
        }
        for _ in 0..9 {
            for (y, x) in [(d, e), (e, d)] {
                let k = length_in_epsilons(y, x);
                let bound = ANGLE_BOUND_ULPS + k.max(1.0) * ANGLE_EXTRA_ULPS_PER_EPSILON;
                for (sy, sx) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                    let (y, x) = (sy * y, sx * x);
                    worst.record(y, x, angle_ulps_f64(y, x), bound);
                }
            }
            e = e.next_up();
        }
        d = d.next_up();
    }
    worst.report("unit_angle f64 at |y| = |x|");
}

/// For length `1 ± k·ε`, the bound grows by `k` times this many ulps (the first-order
/// correction for the length leaves its slope's 0.06% error and second-order terms).
const ANGLE_EXTRA_ULPS_PER_EPSILON: f64 = 0.002;

#[test]
fn unit_angle_off_the_unit_circle() {
    let mut rng = SplitMix(77);
    for k in [1.0, 4.0, 16.0, 64.0, 256.0, 1024.0] {
        let bound = ANGLE_BOUND_ULPS + k * ANGLE_EXTRA_ULPS_PER_EPSILON;
        let (mut worst, mut worst32) = (WorstAngle::default(), WorstAngle::default());
        for i in 0..200_000 {
            let theta = if i % 2 == 0 {
                (rng.unit() * 2.0 - 1.0) * std::f64::consts::PI
            } else {
                // Near the diagonals, where the length matters most.
                f64::from((rng.next() % 8) as u32) * std::f64::consts::FRAC_PI_4
                    - std::f64::consts::PI
                    + (rng.unit() - 0.5) * 1e-3
            };
            let sign = if rng.next() & 1 == 0 { 1.0 } else { -1.0 };
            let scale = 1.0 + sign * k * f64::EPSILON;
            let (y, x) = unit_f64(theta);
            let (y, x) = (y * scale, x * scale);
            worst.record(y, x, angle_ulps_f64(y, x), bound);
            // f32: scaled in f64, then rounded (which adds up to about ε/2 either way).
            let scale = 1.0 + sign * k * f64::from(f32::EPSILON);
            let (y, x) = theta.sin_cos();
            let (y, x) = ((y * scale) as f32, (x * scale) as f32);
            worst32.record(
                f64::from(y),
                f64::from(x),
                angle_ulps_f32(y, x),
                bound + 0.5 * ANGLE_EXTRA_ULPS_PER_EPSILON,
            );
        }
        worst.report(&format!("unit_angle f64, length 1 ± {k}ε"));
        worst32.report(&format!("unit_angle f32, length 1 ± {k}ε"));
    }
}

/// Every `stride`th f32 `y` in [0, 1] with `x = √(1 − y²)` rounded, all four signs and both
/// orders.
fn f32_unit_pairs(stride: u32) -> WorstAngle {
    let mut worst = WorstAngle::default();
    let mut bits = 0;
    while bits <= 1f32.to_bits() {
        let y = f32::from_bits(bits);
        let x = (1.0 - f64::from(y).powi(2)).sqrt() as f32;
        for (sy, sx) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            check_angle_f32(&mut worst, sy * y, sx * x);
            check_angle_f32(&mut worst, sy * x, sx * y);
        }
        bits += stride;
    }
    worst
}

#[test]
#[ignore = "8.5e9 inputs: run with --release --ignored"]
fn unit_angle_f32_every_unit_pair() {
    f32_unit_pairs(1).report("unit_angle f32 (y, √(1 − y²)), every y");
}

#[test]
fn unit_angle_f32_grids_and_unit_pairs() {
    let mut worst = WorstAngle::default();
    for theta in angle_grid(2_000_000, 20_000, 1e-6).chain(angle_grid(0, 20_000, 1e-9)) {
        let (y, x) = unit_f32(theta);
        check_angle_f32(&mut worst, y, x);
    }
    worst.report("unit_angle f32 (cos θ, sin θ)");
    f32_unit_pairs(97).report("unit_angle f32 (y, √(1 − y²)), every 97th y");
}

#[test]
fn unit_angle_signed_zeros_axes_and_nan() {
    use std::f64::consts::{FRAC_PI_2, PI};
    for (y, x, want) in [
        (0.0f64, 1.0f64, 0.0f64),
        (-0.0, 1.0, -0.0),
        (0.0, -1.0, PI),
        (-0.0, -1.0, -PI),
        (1.0, 0.0, FRAC_PI_2),
        (1.0, -0.0, FRAC_PI_2),
        (-1.0, 0.0, -FRAC_PI_2),
        (-1.0, -0.0, -FRAC_PI_2),
    ] {
        let got = unit_angle(y, x);
        assert_eq!(
            got.to_bits(),
            want.to_bits(),
            "unit_angle({y}, {x}) = {got}"
        );
        assert_eq!(got.to_bits(), y.atan2(x).to_bits());
        let got = unit_angle(y as f32, x as f32);
        assert_eq!(
            got.to_bits(),
            (want as f32).to_bits(),
            "f32 ({y}, {x}) = {got}"
        );
        assert_eq!(got.to_bits(), (y as f32).atan2(x as f32).to_bits());
    }
    for (y, x) in [
        (f64::NAN, 1.0),
        (1.0, f64::NAN),
        (f64::NAN, f64::NAN),
        (f64::NAN, 0.0),
        (0.0, f64::NAN),
        (f64::NAN, -1.0),
        (-1.0, f64::NAN),
    ] {
        assert!(unit_angle(y, x).is_nan(), "({y}, {x})");
        assert!(unit_angle(-y, -x).is_nan(), "({y}, {x})");
        assert!(unit_angle(y as f32, x as f32).is_nan(), "({y}, {x})");
    }
}

/// Against the platform's own `atan2`, in whole ulps: never more than one apart.
#[test]
fn unit_angle_within_one_ulp_of_atan2() {
    let mut rng = SplitMix(5);
    for _ in 0..1_000_000 {
        let theta = (rng.unit() * 2.0 - 1.0) * std::f64::consts::PI;
        let (y, x) = unit_f64(theta);
        let (a, b) = (unit_angle(y, x), y.atan2(x));
        let apart = (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs();
        assert!(apart <= 1 || a == b, "({y:e}, {x:e}): {a:e} vs {b:e}");
        let (y, x) = unit_f32(theta);
        let (a, b) = (unit_angle(y, x), y.atan2(x));
        let apart = (i64::from(a.to_bits() as i32) - i64::from(b.to_bits() as i32)).unsigned_abs();
        assert!(apart <= 1 || a == b, "({y:e}, {x:e}): {a:e} vs {b:e}");
    }
}

/// A batch loop over slices: it vectorises (packed `mulpd`/`addpd`/`andpd`/`orpd`, no call)
/// when built with `--release`; see `cargo rustc --release -p mechgen-tests --test fast_math
/// -- --emit asm`.
#[inline(never)]
fn unit_angles_f64(ys: &[f64], xs: &[f64], out: &mut [f64]) {
    for ((o, &y), &x) in out.iter_mut().zip(ys).zip(xs) {
        *o = unit_angle(y, x);
    }
}

#[inline(never)]
fn unit_angles_f32(ys: &[f32], xs: &[f32], out: &mut [f32]) {
    for ((o, &y), &x) in out.iter_mut().zip(ys).zip(xs) {
        *o = unit_angle(y, x);
    }
}

#[test]
fn unit_angle_batch_matches_scalar() {
    let thetas: Vec<f64> = (0..1001).map(|i| -3.0 + 0.006 * f64::from(i)).collect();
    let (ys, xs): (Vec<f64>, Vec<f64>) = thetas.iter().map(|&t| unit_f64(t)).unzip();
    let mut out = vec![0.0; ys.len()];
    unit_angles_f64(&ys, &xs, &mut out);
    for i in 0..ys.len() {
        assert_eq!(out[i].to_bits(), unit_angle(ys[i], xs[i]).to_bits());
    }
    let (ys, xs): (Vec<f32>, Vec<f32>) = thetas.iter().map(|&t| unit_f32(t)).unzip();
    let mut out = vec![0.0; ys.len()];
    unit_angles_f32(&ys, &xs, &mut out);
    for i in 0..ys.len() {
        assert_eq!(out[i].to_bits(), unit_angle(ys[i], xs[i]).to_bits());
    }
}
