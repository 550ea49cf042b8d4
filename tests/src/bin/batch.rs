//! Times the generated batch kernel (`FourBarScenes::joints_batch`) and the hand-written one
//! of `mechgen_tests::batch_baseline` (the four-bar
//! 180/80/200/150's joint positions A and B, open branch) per step over the benchmarks'
//! 360-angle turn, one degree apart, next to the scalar generated closed form
//! (`FourBar::assemble` then `points`, one angle at a time) over the same turn. Each figure
//! is the best of many samples of about a millisecond: the machine is small and noisy, and
//! the best sample is the one least disturbed. Both batch kernels run their loops through
//! `mechgen::simd::widest` (AVX2 and FMA where the processor has them, which
//! `batch_avx2_fma` says); the `*_baseline_*` figures are the same loops as built (SSE2 on
//! x86-64's baseline), which must give the same bits, and this checks that they do. Run from
//! the repository root:
//!
//! ```sh
//! cargo run --release -p mechgen-tests --bin batch
//! ```
//!
//! and compare with `tests/reference/numpy_four_bar.py`'s `numpy_ns_per_step`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use mechanisms::FourBar;
use mechgen::{Branch, Vec2};
use mechgen_tests::batch_baseline::{
    Joints, four_bar_joints_f32, four_bar_joints_f64, four_bar_joints_f64_platform_sin_cos,
    four_bar_joints_portable,
};

const LENGTHS: [f64; 4] = [180.0, 80.0, 200.0, 150.0];
const SAMPLES: usize = 300;

/// The least time per step over `SAMPLES` samples, each of as many calls of `run` (which
/// does `steps` steps) as fill about a millisecond.
fn best_ns_per_step(steps: usize, mut run: impl FnMut()) -> f64 {
    let mut calls = 1u32;
    loop {
        let start = Instant::now();
        for _ in 0..calls {
            run();
        }
        if start.elapsed() >= Duration::from_millis(1) {
            break;
        }
        calls *= 2;
    }
    let mut best = f64::INFINITY;
    for _ in 0..SAMPLES {
        let start = Instant::now();
        for _ in 0..calls {
            run();
        }
        let ns = start.elapsed().as_nanos() as f64;
        best = best.min(ns / (f64::from(calls) * steps as f64));
    }
    best
}

/// The largest distance between matching joints of two sweeps, in mm.
fn largest_distance(a: &[Joints<f64>], b: &[Joints<f64>]) -> f64 {
    let distance = |p: Vec2<f64>, q: Vec2<f64>| (p.x - q.x).hypot(p.y - q.y);
    a.iter()
        .zip(b)
        .map(|(a, b)| distance(a.crank_pin, b.crank_pin).max(distance(a.rocker_pin, b.rocker_pin)))
        .fold(0f64, f64::max)
}

/// The bits of both joints' coordinates, step by step, for comparing two paths exactly.
fn pin_bits<J>(joints: &[J], pins: impl Fn(&J) -> [mechgen::Vec2<f64>; 2]) -> Vec<u64> {
    joints
        .iter()
        .flat_map(|j| pins(j).into_iter().flat_map(|p| [p.x, p.y]))
        .map(f64::to_bits)
        .collect()
}

fn main() {
    let theta2: Vec<f64> = (0..360).map(|k| f64::from(k).to_radians()).collect();
    let theta2_f32: Vec<f32> = theta2.iter().map(|&t| t as f32).collect();
    let steps = theta2.len();
    let mut out = vec![Joints::<f64>::default(); steps];
    let mut out_f32 = vec![Joints::<f32>::default(); steps];

    let hand = best_ns_per_step(steps, || {
        four_bar_joints_f64(black_box(LENGTHS), black_box(&theta2), &mut out).unwrap();
        black_box(&out);
    });
    let mut hand_baseline_out = vec![Joints::<f64>::default(); steps];
    let hand_baseline = best_ns_per_step(steps, || {
        four_bar_joints_portable(
            black_box(LENGTHS),
            black_box(&theta2),
            &mut hand_baseline_out,
        )
        .unwrap();
        black_box(&hand_baseline_out);
    });
    let hand_f32 = best_ns_per_step(steps, || {
        let lengths = LENGTHS.map(|l| l as f32);
        four_bar_joints_f32(black_box(lengths), black_box(&theta2_f32), &mut out_f32).unwrap();
        black_box(&out_f32);
    });
    let mut platform_out = vec![Joints::<f64>::default(); steps];
    let hand_platform = best_ns_per_step(steps, || {
        four_bar_joints_f64_platform_sin_cos(
            black_box(LENGTHS),
            black_box(&theta2),
            &mut platform_out,
        )
        .unwrap();
        black_box(&platform_out);
    });

    let [l1, l2, l3, l4] = LENGTHS;
    let linkage = FourBar::new(l1, l2, l3, l4).unwrap();
    let mut scalar_out = vec![Joints::<f64>::default(); steps];
    let scalar = best_ns_per_step(steps, || {
        let linkage = black_box(&linkage);
        for (&theta, joints) in black_box(&theta2).iter().zip(scalar_out.iter_mut()) {
            let q = linkage.assemble(theta, Branch::Open).unwrap();
            let points = linkage.points(theta, &q).unwrap();
            *joints = Joints {
                crank_pin: points.crank_pin,
                rocker_pin: points.rocker_pin,
            };
        }
        black_box(&scalar_out);
    });

    // The generated batch of the same joints: the scene `joints` of `mechanisms::FourBar`.
    let scenes = linkage.scenes().unwrap();
    let mut generated_out = vec![mechanisms::FourBarJoints::<f64>::default(); steps];
    let generated = best_ns_per_step(steps, || {
        black_box(&scenes)
            .joints_batch(black_box(&theta2), Branch::Open, &mut generated_out)
            .unwrap();
        black_box(&generated_out);
    });
    let mut generated_baseline_out = generated_out.clone();
    let generated_baseline = best_ns_per_step(steps, || {
        let failed = black_box(&scenes).mechgen_joints_lanes(
            black_box(&theta2),
            Branch::Open,
            &mut generated_baseline_out,
        );
        assert!(!failed);
        black_box(&generated_baseline_out);
    });

    // The wider copies and the loops as built give the same bits.
    let hand_pins = |j: &Joints<f64>| [j.crank_pin, j.rocker_pin];
    assert!(
        pin_bits(&out, hand_pins) == pin_bits(&hand_baseline_out, hand_pins),
        "the hand batch's paths differ"
    );
    let generated_pins = |j: &mechanisms::FourBarJoints<f64>| [j.crank_pin, j.rocker_pin];
    assert!(
        pin_bits(&generated_out, generated_pins)
            == pin_bits(&generated_baseline_out, generated_pins),
        "the generated batch's paths differ"
    );

    // They agree (the tests hold them to 1e-12 mm).
    let worst = largest_distance(&out, &scalar_out);
    assert!(worst <= 1e-12, "kernels disagree by {worst:e} mm");
    let generated_joints: Vec<Joints<f64>> = generated_out
        .iter()
        .map(|j| Joints {
            crank_pin: j.crank_pin,
            rocker_pin: j.rocker_pin,
        })
        .collect();
    let generated_worst = largest_distance(&generated_joints, &scalar_out);
    assert!(
        generated_worst <= 1e-12,
        "the generated batch disagrees by {generated_worst:e} mm"
    );

    println!("generated_batch_ns_per_step {generated:.3}");
    println!("hand_batch_ns_per_step {hand:.3}");
    println!("generated_batch_baseline_ns_per_step {generated_baseline:.3}");
    println!("hand_batch_baseline_ns_per_step {hand_baseline:.3}");
    println!("batch_avx2_fma {}", u8::from(mechgen::simd::avx2_fma()));
    println!("hand_batch_f32_ns_per_step {hand_f32:.3}");
    println!("hand_batch_platform_sin_cos_ns_per_step {hand_platform:.3}");
    println!("scalar_assemble_points_ns_per_step {scalar:.3}");
    println!("max_disagreement_mm {worst:.3e}");
}
