//! Wall-clock time of every kernel of `mechgen_tests::kernels`, side by side in one process:
//! each built once outside the timed loop, then called through its boxed closure over the
//! 360-angle sweep (one degree apart, ω2 = 10 rad/s, α2 = 2 rad/s², open branch), so hand
//! and generated code pay the same call. One iteration is one sweep.
//!
//! `cargo bench -p mechgen-tests --bench kinematics [-- <kernel name>]`; the performance
//! report (`cargo run --release -p mechgen-tests --bin performance -- write`) runs it and
//! reads its results.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use mechgen_tests::kernels::{self, KERNELS, STEPS};

/// The criterion group every kernel is measured in (the report reads it back by this name).
const GROUP: &str = "kernels";

fn all_kernels(c: &mut Criterion) {
    let mut group = c.benchmark_group(GROUP);
    for kernel in KERNELS {
        let mut run = (kernel.build)();
        group.bench_function(kernel.name, |b| {
            b.iter(|| {
                let mut sum = 0.0;
                for k in 0..STEPS {
                    sum += run(black_box(kernels::input(k)));
                }
                sum
            })
        });
    }
    group.finish();
}

/// About three seconds a kernel (the slowest, the nalgebra Newton, takes 2 ms a sweep and
/// still gets its 40 samples), so the whole benchmark takes under two minutes.
fn config() -> Criterion {
    Criterion::default()
        .sample_size(40)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .nresamples(20_000)
}

criterion_group! {
    name = benches;
    config = config();
    targets = all_kernels
}
criterion_main!(benches);
