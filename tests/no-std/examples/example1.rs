//! The course notes' Example 1 four-bar on the host: the very code the firmware in
//! `tests/embedded` runs on an emulated Cortex-M4F ([`mechgen_no_std_check::example1`]), and
//! the comparison of the two that `.ci/embedded` makes.
//!
//! ```sh
//! cargo run -p mechgen-no-std-check --example example1                     # the lines
//! cargo run -p mechgen-no-std-check --example example1 -- --compare FILE   # FILE against them
//! ```
//!
//! `--compare` reads the emulator's output, requires exactly the host's `f64 …`/`f32 …` lines
//! in it (other lines are comments) with every value within its tolerance, prints each pair,
//! checks Example 1's published angles, and exits non-zero on any mismatch.
//!
//! Tolerances. Every value is written with enough digits to give back its exact binary
//! number, so the comparison is of the numbers themselves. Both sides do IEEE 754 arithmetic
//! with correct rounding (on the Cortex-M4F, the FPU for f32 and compiler-builtins' software
//! routines for f64; on x86-64, SSE2), and both evaluate the same expressions in the same
//! order with no fused multiply-adds, so only the maths library (`sin`, `cos`, `atan2`,
//! `sqrt`) can make them differ. The firmware uses the `libm` crate; this example uses it too
//! when built on its own (`-p mechgen-no-std-check`, the runtime without `std`), and the
//! platform's maths library when built together with crates that turn on `mechgen/std`
//! (features are unified). So the lines are expected to agree bit for bit, and are allowed:
//! - f64: a relative difference up to 1e-12 (about 4500 ulp: a maths library's last-bit
//!   differences, amplified by the example's condition, about 1/sin(50.6°) per stage);
//! - f32: up to 4 ulp.

use std::process::ExitCode;

use mechgen_no_std_check::example1;

/// Relative tolerance for f64 values.
const F64_RELATIVE: f64 = 1e-12;
/// Tolerance for f32 values, in units in the last place.
const F32_ULPS: u32 = 4;
/// Example 1's published angles (KINEMATICS.md), degrees, and how closely to check them.
const PUBLISHED: [(&str, f64); 2] = [("theta3", 21.5576), ("theta4", 72.1377)];
const PUBLISHED_TOLERANCE_DEGREES: f64 = 1e-4;

/// One value line: type, name, value as written.
#[derive(Clone, Debug)]
struct Line {
    scalar: String,
    name: String,
    value: String,
}

fn parse(text: &str) -> Vec<Line> {
    text.lines()
        .filter(|line| line.starts_with("f64 ") || line.starts_with("f32 "))
        .filter_map(|line| {
            let mut words = line.split_whitespace();
            Some(Line {
                scalar: words.next()?.to_owned(),
                name: words.next()?.to_owned(),
                value: words.next()?.to_owned(),
            })
        })
        .collect()
}

/// The distance in ulps between two f32s (same sign assumed; otherwise the sum of their
/// distances from zero).
fn ulps(a: f32, b: f32) -> u32 {
    let key = |x: f32| {
        let bits = x.to_bits() as i32;
        if bits < 0 { i32::MIN - bits } else { bits }
    };
    key(a).abs_diff(key(b))
}

/// Compares one pair: the difference as text, and whether it is within tolerance.
fn compare(scalar: &str, host: &str, emulator: &str) -> (String, bool) {
    match scalar {
        "f64" => match (host.parse::<f64>(), emulator.parse::<f64>()) {
            (Ok(h), Ok(e)) => {
                let scale = h.abs().max(e.abs());
                let relative = if h == e { 0.0 } else { (h - e).abs() / scale };
                (format!("{relative:.1e} rel"), relative <= F64_RELATIVE)
            }
            _ => ("unreadable".into(), false),
        },
        "f32" => match (host.parse::<f32>(), emulator.parse::<f32>()) {
            (Ok(h), Ok(e)) if h.is_finite() && e.is_finite() => {
                let distance = ulps(h, e);
                (format!("{distance} ulp"), distance <= F32_ULPS)
            }
            _ => ("unreadable".into(), false),
        },
        _ => ("unknown type".into(), false),
    }
}

fn host_lines() -> Result<String, String> {
    let mut text = String::new();
    example1::run_all(&mut text).map_err(|failure| failure.to_string())?;
    Ok(text)
}

fn compare_with(path: &str) -> Result<bool, String> {
    let emulator_text =
        std::fs::read_to_string(path).map_err(|error| format!("cannot read {path}: {error}"))?;
    let host = parse(&host_lines()?);
    let emulator = parse(&emulator_text);
    let mut ok = true;
    println!(
        "{:<4} {:<40} {:>25} {:>25}  difference",
        "type", "value", "host", "emulator"
    );
    for line in &host {
        let matching: Vec<&Line> = emulator
            .iter()
            .filter(|e| e.scalar == line.scalar && e.name == line.name)
            .collect();
        let (difference, within) = match matching.as_slice() {
            [one] => compare(&line.scalar, &line.value, &one.value),
            [] => ("MISSING from the emulator's output".into(), false),
            _ => ("written more than once by the emulator".into(), false),
        };
        let emulated = matching.first().map_or("-", |e| e.value.as_str());
        let verdict = if within { "" } else { "  <-- MISMATCH" };
        println!(
            "{:<4} {:<40} {:>25} {:>25}  {difference}{verdict}",
            line.scalar, line.name, line.value, emulated
        );
        ok &= within;
    }
    for extra in emulator.iter().filter(|e| {
        !host
            .iter()
            .any(|h| h.scalar == e.scalar && h.name == e.name)
    }) {
        println!(
            "{} {}: written by the emulator only  <-- MISMATCH",
            extra.scalar, extra.name
        );
        ok = false;
    }
    // The published values, from the emulator's own numbers.
    for (name, degrees) in PUBLISHED {
        for scalar in ["f64", "f32"] {
            let value = emulator
                .iter()
                .find(|e| e.scalar == scalar && e.name == format!("assemble.{name}"))
                .and_then(|e| e.value.parse::<f64>().ok());
            let within = value
                .is_some_and(|v| (v.to_degrees() - degrees).abs() <= PUBLISHED_TOLERANCE_DEGREES);
            println!(
                "{scalar} {name} = {}° on the emulator; published {degrees}°{}",
                value.map_or("?".into(), |v| format!("{:.4}", v.to_degrees())),
                if within { "" } else { "  <-- MISMATCH" }
            );
            ok &= within;
        }
    }
    println!(
        "tolerance: f64 {F64_RELATIVE:e} relative, f32 {F32_ULPS} ulp; {} values compared",
        host.len()
    );
    Ok(ok)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.as_slice() {
        [] => host_lines().map(|text| {
            print!("{text}");
            true
        }),
        [flag, path] if flag == "--compare" => compare_with(path),
        _ => Err("usage: example1 [--compare EMULATOR_OUTPUT]".into()),
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => {
            eprintln!("the emulator's lines do not match the host's");
            ExitCode::FAILURE
        }
        Err(message) => {
            eprintln!("{message}");
            ExitCode::FAILURE
        }
    }
}
