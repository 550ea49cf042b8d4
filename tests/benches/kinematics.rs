//! Speed of the generated code against what users would otherwise write, side by side in
//! one process: position, velocity and acceleration over a 360-angle sweep (one degree
//! apart, ω2 = 10 rad/s, α2 = 2 rad/s²), open branch. `cargo bench -p mechgen-tests`; the
//! performance report (`docs/PERFORMANCE.md`) is made from its results.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use mechanisms::{FourBar, FourBarUnknowns, InvertedSliderCrank, SliderCrank, WattSixBar};
use mechgen::{Branch, NewtonOptions};
use mechgen_tests::baselines::{self, State};
use mechgen_tests::{examples, scenes};

const OMEGA: f64 = 10.0;
const ALPHA: f64 = 2.0;
const ANGLES: usize = 360;

fn angles() -> impl Iterator<Item = f64> {
    (0..ANGLES).map(|k| (k as f64).to_radians())
}

/// Adds every number of a sweep into one, so nothing is optimised away.
fn total(states: impl Iterator<Item = State>) -> f64 {
    states.map(|s| s.iter().flatten().sum::<f64>()).sum()
}

fn state<U: Into<[f64; 2]>>(q: U, v: U, a: U) -> State {
    [q.into(), v.into(), a.into()]
}

fn four_bar(c: &mut Criterion) {
    let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let single = FourBar::new(180.0f32, 80.0, 200.0, 150.0).unwrap();
    let lengths = [180.0, 80.0, 200.0, 150.0];
    // Cold starts begin from the position 10° back, as a caller without the last answer would.
    let closed: Vec<[f64; 2]> = angles()
        .map(|t| linkage.assemble(t, Branch::Open).unwrap().to_array())
        .collect();
    let cold: Vec<[f64; 2]> = (0..ANGLES)
        .map(|k| closed[(k + ANGLES - 10) % ANGLES])
        .collect();
    let mut group = c.benchmark_group("four_bar");

    group.bench_function("generated closed form (motion)", |b| {
        b.iter(|| {
            total(angles().map(|t| {
                let m = linkage
                    .motion(black_box(t), Branch::Open, OMEGA, ALPHA)
                    .unwrap();
                state(m.position, m.velocity, m.acceleration)
            }))
        })
    });
    group.bench_function(
        "generated closed form (assemble, velocity, acceleration)",
        |b| {
            b.iter(|| {
                total(angles().map(|t| {
                    let q = linkage.assemble(black_box(t), Branch::Open).unwrap();
                    let m = linkage.motion_at(t, &q, OMEGA, ALPHA).unwrap();
                    state(m.position, m.velocity, m.acceleration)
                }))
            })
        },
    );
    for tolerance in [1e-4, 1e-6, 1e-9, 1e-12] {
        let options = NewtonOptions::new(tolerance, 50);
        group.bench_function(format!("generated Newton {tolerance:e} warm"), |b| {
            b.iter(|| {
                let mut guess = FourBarUnknowns::from_array(closed[0]);
                total(angles().map(|t| {
                    let q = linkage
                        .position(black_box(t), &guess, &options)
                        .unwrap()
                        .value;
                    guess = q;
                    let m = linkage.motion_at(t, &q, OMEGA, ALPHA).unwrap();
                    state(m.position, m.velocity, m.acceleration)
                }))
            })
        });
        group.bench_function(format!("generated Newton {tolerance:e} cold"), |b| {
            b.iter(|| {
                total(angles().zip(&cold).map(|(t, guess)| {
                    let guess = FourBarUnknowns::from_array(*guess);
                    let q = linkage
                        .position(black_box(t), &guess, &options)
                        .unwrap()
                        .value;
                    let m = linkage.motion_at(t, &q, OMEGA, ALPHA).unwrap();
                    state(m.position, m.velocity, m.acceleration)
                }))
            })
        });
    }
    group.bench_function("generated closed form (motion) f32", |b| {
        b.iter(|| {
            let sum: f32 = angles()
                .map(|t| {
                    let m = single
                        .motion(black_box(t as f32), Branch::Open, 10.0, 2.0)
                        .unwrap();
                    m.position.theta4 + m.velocity.theta4 + m.acceleration.theta4
                })
                .sum();
            sum
        })
    });
    group.bench_function("generated Newton 1e-4 warm f32", |b| {
        let options = NewtonOptions::new(1e-4f32, 50);
        b.iter(|| {
            let start = single.assemble(0.0, Branch::Open).unwrap();
            let mut guess = start;
            let sum: f32 = angles()
                .map(|t| {
                    let t = black_box(t as f32);
                    let q = single.position(t, &guess, &options).unwrap().value;
                    guess = q;
                    let m = single.motion_at(t, &q, 10.0, 2.0).unwrap();
                    m.position.theta4 + m.velocity.theta4 + m.acceleration.theta4
                })
                .sum();
            sum
        })
    });
    group.bench_function("hand-written Norton closed form", |b| {
        b.iter(|| {
            total(
                angles().map(|t| baselines::four_bar_norton(&lengths, black_box(t), OMEGA, ALPHA)),
            )
        })
    });
    group.bench_function("hand-written Newton 1e-9 warm", |b| {
        b.iter(|| {
            let mut guess = closed[0];
            total(angles().map(|t| {
                let s =
                    baselines::four_bar_newton(&lengths, black_box(t), guess, 1e-9, OMEGA, ALPHA);
                guess = s[0];
                s
            }))
        })
    });
    group.bench_function("hand-written Newton 1e-9 cold", |b| {
        b.iter(|| {
            total(angles().zip(&cold).map(|(t, guess)| {
                baselines::four_bar_newton(&lengths, black_box(t), *guess, 1e-9, OMEGA, ALPHA)
            }))
        })
    });
    group.bench_function("num-dual Newton 1e-9 warm", |b| {
        b.iter(|| {
            let mut guess = closed[0];
            total(angles().map(|t| {
                let s =
                    baselines::four_bar_num_dual(&lengths, black_box(t), guess, 1e-9, OMEGA, ALPHA);
                guess = s[0];
                s
            }))
        })
    });
    group.bench_function("nalgebra finite-difference Newton 1e-9 warm", |b| {
        b.iter(|| {
            let mut guess = closed[0];
            total(angles().map(|t| {
                let s =
                    baselines::four_bar_nalgebra(&lengths, black_box(t), guess, 1e-9, OMEGA, ALPHA);
                guess = s[0];
                s
            }))
        })
    });
    group.finish();
}

/// The generated closed form and the generated Newton (1e-9, warm) over the sweep for a
/// shipped one-loop mechanism. A macro, because the mechanisms share method names, not a trait.
macro_rules! generated_closed_form_and_newton {
    ($group:ident, $linkage:ident) => {
        $group.bench_function("generated closed form (motion)", |b| {
            b.iter(|| {
                total(angles().map(|t| {
                    let m = $linkage
                        .motion(black_box(t), Branch::Open, OMEGA, ALPHA)
                        .unwrap();
                    state(m.position, m.velocity, m.acceleration)
                }))
            })
        });
        $group.bench_function("generated Newton 1e-9 warm", |b| {
            let options = NewtonOptions::new(1e-9, 50);
            b.iter(|| {
                let mut guess = $linkage.assemble(0.0, Branch::Open).unwrap();
                total(angles().map(|t| {
                    let q = $linkage
                        .position(black_box(t), &guess, &options)
                        .unwrap()
                        .value;
                    guess = q;
                    let m = $linkage.motion_at(t, &q, OMEGA, ALPHA).unwrap();
                    state(m.position, m.velocity, m.acceleration)
                }))
            })
        });
    };
}

fn slider_crank(c: &mut Criterion) {
    let linkage = SliderCrank::new(50.0, 150.0, 20.0).unwrap();
    let mut group = c.benchmark_group("slider_crank");
    generated_closed_form_and_newton!(group, linkage);
    group.bench_function("hand-written closed form", |b| {
        b.iter(|| {
            total(angles().map(|t| {
                baselines::slider_crank_closed(50.0, 150.0, 20.0, black_box(t), OMEGA, ALPHA)
            }))
        })
    });
    group.finish();
}

fn inverted_slider_crank(c: &mut Criterion) {
    let p = [150.0, 60.0, 20.0, 0.3];
    let linkage = InvertedSliderCrank::new(p[0], p[1], p[2], p[3]).unwrap();
    let mut group = c.benchmark_group("inverted_slider_crank");
    generated_closed_form_and_newton!(group, linkage);
    group.bench_function("hand-written closed form", |b| {
        b.iter(|| {
            total(
                angles().map(|t| {
                    baselines::inverted_slider_crank_closed(p, black_box(t), OMEGA, ALPHA)
                }),
            )
        })
    });
    group.finish();
}

fn six_bars(c: &mut Criterion) {
    let four_bar = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let watt = WattSixBar::new(
        [180.0, 80.0, 200.0, 150.0],
        100.0,
        0.8,
        220.0,
        160.0,
        (300.0, 150.0),
    )
    .unwrap();
    let (stephenson, guess) = examples::stephenson_six_bar();
    let options = NewtonOptions::new(1e-9, 50);
    let start = stephenson.position(0.0, &guess, &options).unwrap().value;
    let mut group = c.benchmark_group("six_bars");
    group.bench_function("four-bar closed form (motion)", |b| {
        b.iter(|| {
            angles()
                .map(|t| {
                    four_bar
                        .motion(black_box(t), Branch::Open, OMEGA, ALPHA)
                        .unwrap()
                        .acceleration
                        .theta4
                })
                .sum::<f64>()
        })
    });
    group.bench_function("Watt six-bar closed form (motion)", |b| {
        b.iter(|| {
            angles()
                .map(|t| {
                    let m = watt
                        .motion(black_box(t), [Branch::Open, Branch::Open], OMEGA, ALPHA)
                        .unwrap();
                    m.acceleration.theta6
                })
                .sum::<f64>()
        })
    });
    group.bench_function(
        "Stephenson six-bar Newton 1e-9 warm (position, motion_at)",
        |b| {
            b.iter(|| {
                let mut q = start;
                angles()
                    .map(|t| {
                        q = stephenson
                            .position(black_box(t), &q, &options)
                            .unwrap()
                            .value;
                        stephenson
                            .motion_at(t, &q, OMEGA, ALPHA)
                            .unwrap()
                            .acceleration
                            .theta6
                    })
                    .sum::<f64>()
            })
        },
    );
    group.finish();
}

fn scenes(c: &mut Criterion) {
    let mut group = c.benchmark_group("scenes");
    for (name, function) in [
        ("positions only", scenes::positions_only as fn(f64) -> _),
        ("positions and velocities", scenes::with_velocities),
        ("everything", scenes::everything),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                angles()
                    .map(|t| function(black_box(t)).unwrap()[1])
                    .sum::<f64>()
            })
        });
    }
    group.finish();
}

fn config() -> Criterion {
    Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1000))
}

criterion_group! {
    name = benches;
    config = config();
    targets = four_bar, slider_crank, inverted_slider_crank, six_bars, scenes
}
criterion_main!(benches);
