//! Runs one method over the benchmark sweep many times, for instruction counts under
//! `valgrind --tool=callgrind`, which are stable where wall-clock times on this 2-core machine
//! are not: `valgrind --tool=callgrind target/release/instructions <method>`.

use std::hint::black_box;

use mechanisms::FourBar;
use mechgen::{Branch, NewtonOptions};
use mechgen_tests::baselines;

fn main() {
    let method = std::env::args().nth(1).unwrap_or_default();
    let l = [180.0, 80.0, 200.0, 150.0];
    let linkage = FourBar::new(l[0], l[1], l[2], l[3]).unwrap();
    let options = NewtonOptions::new(1e-9, 50);
    let mut sum = 0.0;
    for _ in 0..100 {
        let mut guess = linkage.assemble(0.0, Branch::Open).unwrap();
        for k in 0..360 {
            let t = black_box(f64::from(k).to_radians());
            sum += match method.as_str() {
                "motion" => {
                    linkage
                        .motion(t, Branch::Open, 10.0, 2.0)
                        .unwrap()
                        .acceleration
                        .theta4
                }
                "assemble" => linkage.assemble(t, Branch::Open).unwrap().theta4,
                "newton" => {
                    let q = linkage.position(t, &guess, &options).unwrap().value;
                    guess = q;
                    linkage
                        .motion_at(t, &q, 10.0, 2.0)
                        .unwrap()
                        .acceleration
                        .theta4
                }
                "norton" => baselines::four_bar_norton(&l, t, 10.0, 2.0)[2][1],
                "hand-newton" => {
                    let s = baselines::four_bar_newton(&l, t, guess.to_array(), 1e-9, 10.0, 2.0);
                    guess = s[0].into();
                    s[2][1]
                }
                _ => t,
            };
        }
    }
    println!("{sum}");
}
