//! Runs one kernel of `mechgen_tests::kernels` over the benchmark sweep many times, for
//! instruction counts under callgrind, which are stable where wall-clock times on a small
//! shared machine are not:
//!
//! ```sh
//! valgrind --tool=callgrind target/release/instructions <kernel>
//! target/release/instructions --list
//! ```
//!
//! The kernel is built once (its constructors and constants before the loop), then called
//! through its boxed closure for the 360-angle sweep, 100 times. `none` is the boxed
//! identity: subtract its count and divide by 36000 for a per-call count. The performance
//! report (`cargo run --release -p mechgen-tests --bin performance -- write`) does exactly
//! that for every kernel.

use std::hint::black_box;

use mechgen_tests::kernels::{self, KERNELS, STEPS, SWEEPS};

fn main() {
    let name = std::env::args().nth(1).unwrap_or_default();
    if name == "--list" {
        for kernel in KERNELS {
            println!("{}", kernel.name);
        }
        return;
    }
    let Some(kernel) = kernels::find(&name) else {
        eprintln!("instructions: no kernel `{name}`; `instructions --list` names them");
        std::process::exit(2);
    };
    let mut run = (kernel.build)();
    let mut sum = 0.0;
    for _ in 0..SWEEPS {
        for k in 0..STEPS {
            sum += run(black_box(kernels::input(k)));
        }
    }
    println!("{sum}");
}
