//! The performance report, made and checked by one program. From anywhere in the workspace:
//!
//! ```sh
//! cargo run --release -p mechgen-tests --bin performance -- write   # docs/PERFORMANCE.md, docs/frontier.svg
//! cargo run --release -p mechgen-tests --bin performance -- check   # what CI runs (.ci/instructions)
//! ```
//!
//! `write` measures every kernel of `mechgen_tests::kernels`:
//!
//! - instructions per call with callgrind: it builds the `instructions` driver
//!   (`cargo build --release -p mechgen-tests --bin instructions`, into `CARGO_TARGET_DIR`),
//!   runs `valgrind --tool=callgrind <driver> <kernel>` for every kernel and for `none` (the
//!   boxed identity), and divides `total − none` by the 36000 calls;
//! - wall-clock time per step: it runs `cargo bench -p mechgen-tests --bench kinematics`
//!   (criterion, every kernel side by side in one process) and reads criterion's estimates;
//! - accuracy of the kernels that return a mechanism's state, against the 60-digit sweeps of
//!   `tests/reference/sweeps.csv`;
//! - when their inputs are present: the embedded code sizes (`bash tests/embedded/sizes.sh`),
//!   the batch kernel's and numpy's time per step (`cargo run --release -p mechgen-tests
//!   --bin batch`, `target/numpy-venv/bin/python tests/reference/numpy_four_bar.py`);
//! - the expansion's size and the `mechanisms` crate's build time;
//!
//! and writes them with the targets, met or missed, every table stamped with the commit.
//!
//! `check` recounts every kernel's instructions, reads the published counts back from
//! `docs/PERFORMANCE.md`, prints both, and fails if any count moved by more than 2% (counts
//! are deterministic; glibc and valgrind versions differ between machines, and CI runs on
//! this one's kind) or a target the report publishes as met is missed (one it publishes as
//! missed is a known gap, printed but not failed, until it is met).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use mechgen_tests::kernels::{self, Group, KERNELS, Kernel, Origin, STEPS, SWEEPS};
use mechgen_tests::stamp::{self, commit};

const REPORT: &str = "docs/PERFORMANCE.md";
const FRONTIER: &str = "docs/frontier.svg";
/// How far a recounted instruction count may move from the published one.
const DRIFT: f64 = 0.02;
/// Calls per callgrind run.
const CALLS: f64 = (STEPS * SWEEPS) as f64;
/// The criterion group of `benches/kinematics.rs`.
const CRITERION_GROUP: &str = "kernels";
/// The heading of the instruction table, which `check` reads back.
const INSTRUCTIONS_HEADING: &str = "## Instructions per call";
const WRITE_COMMAND: &str = "cargo run --release -p mechgen-tests --bin performance -- write";

type Failure = String;

// ---- targets ------------------------------------------------------------------------------

/// A target on instruction counts: `kernel` costs at most (or, `strict`, less than) `limit`
/// times `against`.
struct Target {
    kernel: &'static str,
    against: &'static str,
    limit: f64,
    strict: bool,
    /// A stretch goal: reported, never failed on.
    stretch: bool,
    why: &'static str,
}

const TARGETS: &[Target] = &[
    Target {
        kernel: "scene-angles",
        against: "hand-norton",
        limit: 1.0,
        strict: false,
        stretch: false,
        why: "four-bar angles, rates, accelerations",
    },
    Target {
        kernel: "scene-angles",
        against: "hand-norton",
        limit: 0.85,
        strict: false,
        stretch: true,
        why: "four-bar angles (stretch)",
    },
    Target {
        kernel: "scene-coupler-path",
        against: "hand-point",
        limit: 1.0,
        strict: false,
        stretch: false,
        why: "coupler point position",
    },
    Target {
        kernel: "scene-coupler-motion",
        against: "hand-point-motion",
        limit: 1.0,
        strict: false,
        stretch: false,
        why: "coupler point position, velocity, acceleration",
    },
    Target {
        kernel: "newton-motion-near",
        against: "hand-newton",
        limit: 1.0,
        strict: false,
        stretch: false,
        why: "four-bar Newton, warm, 1e-12, the constants once (`newton()`)",
    },
    Target {
        kernel: "scene-slider-crank",
        against: "hand-slider-crank",
        limit: 1.0,
        strict: false,
        stretch: false,
        why: "slider-crank",
    },
    Target {
        kernel: "scene-inverted-slider-crank",
        against: "hand-inverted-slider-crank",
        limit: 1.0,
        strict: false,
        stretch: false,
        why: "inverted slider-crank",
    },
    Target {
        kernel: "stephenson-motion-near",
        against: "motion",
        limit: 4.0,
        strict: false,
        stretch: false,
        why: "coupled six-bar Newton against the four-bar's closed form",
    },
    Target {
        kernel: "scene-coupler-path",
        against: "scene-coupler-motion",
        limit: 1.0,
        strict: true,
        stretch: false,
        why: "a scene that asks for less costs less",
    },
];

impl Target {
    fn label(&self) -> String {
        format!(
            "`{}` {} {:.2}× `{}`{}",
            self.kernel,
            if self.strict { "<" } else { "≤" },
            self.limit,
            self.against,
            if self.stretch { " (stretch)" } else { "" }
        )
    }

    /// The measured ratio and whether the target is met, if both counts are known.
    fn judge(&self, counts: &BTreeMap<String, f64>) -> Option<(f64, bool)> {
        let ratio = counts.get(self.kernel)? / counts.get(self.against)?;
        let met = if self.strict {
            ratio < self.limit
        } else {
            ratio <= self.limit
        };
        Some((ratio, met))
    }

    /// The first target on `kernel` against what it is compared with.
    fn on(kernel: &Kernel) -> Option<&'static Target> {
        TARGETS
            .iter()
            .find(|t| t.kernel == kernel.name && Some(t.against) == kernel.compared_with)
    }
}

// ---- running things -----------------------------------------------------------------------

fn cargo() -> Command {
    Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
}

/// Runs `command`, its stderr passed through; its stdout if it succeeded.
fn stdout_of(command: &mut Command, what: &str) -> Result<String, Failure> {
    let output = command
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("{what}: cannot start: {e}"))?;
    if !output.status.success() {
        return Err(format!("{what}: {}", output.status));
    }
    Ok(String::from_utf8_lossy(&output.stdout).into_owned())
}

/// Builds the callgrind driver in release and returns its path (wherever `CARGO_TARGET_DIR`
/// and cargo's configuration put it).
fn build_driver() -> Result<PathBuf, Failure> {
    let what = "cargo build --release -p mechgen-tests --bin instructions";
    let out = stdout_of(
        cargo().args([
            "build",
            "--release",
            "-p",
            "mechgen-tests",
            "--bin",
            "instructions",
            "--message-format=json-render-diagnostics",
        ]),
        what,
    )?;
    out.lines()
        .filter_map(|line| serde_json::from_str::<serde_json::Value>(line).ok())
        .filter(|m| m["reason"] == "compiler-artifact" && m["target"]["name"] == "instructions")
        .find_map(|m| m["executable"].as_str().map(PathBuf::from))
        .ok_or_else(|| format!("{what}: no executable in cargo's messages"))
}

/// The workspace's target directory.
fn target_dir() -> Result<PathBuf, Failure> {
    let what = "cargo metadata";
    let out = stdout_of(
        cargo().args(["metadata", "--format-version", "1", "--no-deps"]),
        what,
    )?;
    let meta: serde_json::Value = serde_json::from_str(&out).map_err(|e| format!("{what}: {e}"))?;
    meta["target_directory"]
        .as_str()
        .map(PathBuf::from)
        .ok_or_else(|| format!("{what}: no target_directory"))
}

/// Instructions callgrind counts for the whole run of `driver kernel`.
fn callgrind(driver: &Path, kernel: &str) -> Result<u64, Failure> {
    let out_file = std::env::temp_dir().join(format!(
        "mechgen-callgrind-{}-{kernel}.out",
        std::process::id()
    ));
    let output = Command::new("valgrind")
        .arg("--tool=callgrind")
        .arg(format!("--callgrind-out-file={}", out_file.display()))
        .arg(driver)
        .arg(kernel)
        .output();
    let _ = std::fs::remove_file(&out_file);
    let output = output.map_err(|e| {
        format!("cannot run valgrind ({e}): install it (apt-get install -y valgrind)")
    })?;
    let stderr = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() {
        return Err(format!(
            "callgrind on `{kernel}` failed ({}):\n{stderr}",
            output.status
        ));
    }
    stderr
        .lines()
        .find(|l| l.contains("Collected :"))
        .and_then(|l| l.split_whitespace().last()?.parse().ok())
        .ok_or_else(|| format!("callgrind on `{kernel}`: no `Collected` line in\n{stderr}"))
}

/// Instructions per call of every kernel but `none`, and `none`'s whole-run count.
fn instruction_counts(driver: &Path) -> Result<(BTreeMap<String, f64>, u64), Failure> {
    let names: Vec<&str> = KERNELS.iter().map(|k| k.name).collect();
    let next = AtomicUsize::new(0);
    let results = Mutex::new(BTreeMap::new());
    let workers = std::thread::available_parallelism().map_or(2, |n| n.get().min(4));
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(name) = names.get(i) else { break };
                    let count = callgrind(driver, name);
                    if let Ok(c) = &count {
                        eprintln!("  callgrind {name}: {c}");
                    }
                    results.lock().unwrap().insert(name.to_string(), count);
                }
            });
        }
    });
    let mut totals = BTreeMap::new();
    for (name, count) in results.into_inner().unwrap() {
        totals.insert(name, count?);
    }
    let none = totals.remove("none").ok_or("no count for `none`")?;
    let per_call = totals
        .into_iter()
        .map(|(name, total)| (name, (total as f64 - none as f64) / CALLS))
        .collect();
    Ok((per_call, none))
}

fn stamp(commit: &str) -> String {
    format!("\n<sub>Made at commit `{commit}` by `{WRITE_COMMAND}`.</sub>\n")
}

// ---- criterion ----------------------------------------------------------------------------

/// Criterion's estimates for one kernel, per step, in nanoseconds.
#[derive(Clone, Copy, Debug)]
struct Timing {
    mean: f64,
    lower: f64,
    upper: f64,
    std_dev: f64,
}

/// Runs the benchmark afresh (its old results removed first, so none is stale).
fn run_benchmark(target: &Path) -> Result<(), Failure> {
    let _ = std::fs::remove_dir_all(target.join("criterion").join(CRITERION_GROUP));
    let status = cargo()
        .args(["bench", "-p", "mechgen-tests", "--bench", "kinematics"])
        .stdout(Stdio::inherit())
        .status()
        .map_err(|e| format!("cargo bench: {e}"))?;
    if !status.success() {
        return Err(format!(
            "cargo bench -p mechgen-tests --bench kinematics: {status}"
        ));
    }
    Ok(())
}

/// Every kernel's timing from criterion's JSON under `target/criterion`.
fn timings(target: &Path) -> BTreeMap<String, Timing> {
    let mut out = BTreeMap::new();
    let Ok(groups) = std::fs::read_dir(target.join("criterion")) else {
        return out;
    };
    for group in groups.flatten() {
        let Ok(benches) = std::fs::read_dir(group.path()) else {
            continue;
        };
        for bench in benches.flatten() {
            let dir = bench.path().join("new");
            let (Ok(meta), Ok(estimates)) = (
                std::fs::read_to_string(dir.join("benchmark.json")),
                std::fs::read_to_string(dir.join("estimates.json")),
            ) else {
                continue;
            };
            let (Ok(meta), Ok(e)) = (
                serde_json::from_str::<serde_json::Value>(&meta),
                serde_json::from_str::<serde_json::Value>(&estimates),
            ) else {
                continue;
            };
            if meta["group_id"].as_str() != Some(CRITERION_GROUP) {
                continue;
            }
            // One iteration is one sweep of STEPS calls.
            let per_step = |v: &serde_json::Value| v.as_f64().map(|ns| ns / STEPS as f64);
            let (Some(name), Some(mean), Some(lower), Some(upper), Some(std_dev)) = (
                meta["function_id"].as_str(),
                per_step(&e["mean"]["point_estimate"]),
                per_step(&e["mean"]["confidence_interval"]["lower_bound"]),
                per_step(&e["mean"]["confidence_interval"]["upper_bound"]),
                per_step(&e["std_dev"]["point_estimate"]),
            ) else {
                continue;
            };
            out.insert(
                name.to_string(),
                Timing {
                    mean,
                    lower,
                    upper,
                    std_dev,
                },
            );
        }
    }
    out
}

// ---- accuracy -----------------------------------------------------------------------------

/// The reference sweep of one mechanism: inputs and `[q1, q2, q̇1, q̇2, q̈1, q̈2]`.
fn references(mechanism: &str) -> Vec<(f64, [f64; 6])> {
    include_str!("../../reference/sweeps.csv")
        .lines()
        .skip(1)
        .filter(|line| line.starts_with(&format!("{mechanism},")))
        .map(|line| {
            let f: Vec<f64> = line
                .split(',')
                .skip(2)
                .map(|x| x.parse().expect("a number"))
                .collect();
            (f[0], [f[1], f[2], f[3], f[4], f[5], f[6]])
        })
        .collect()
}

/// A kernel's worst position, velocity and acceleration errors over the reference sweep:
/// angles in radians (modulo 2π), lengths, rates and accelerations relative to
/// `max(|reference|, 1)`. `None` for kernels whose outputs are not a mechanism's state.
fn accuracy(kernel: &Kernel) -> Option<[f64; 3]> {
    let reference = kernel.group.reference()?;
    let mut outputs = (kernel.outputs)();
    let mut worst = [0.0f64; 3];
    for (t, want) in references(reference.mechanism) {
        let got = outputs(t);
        for (i, (g, w)) in got.iter().zip(want).enumerate() {
            let tau = std::f64::consts::TAU;
            let error = if i < 2 && reference.angles[i] {
                ((g - w + tau / 2.0).rem_euclid(tau) - tau / 2.0).abs()
            } else {
                (g - w).abs() / w.abs().max(1.0)
            };
            worst[i / 2] = worst[i / 2].max(error);
        }
    }
    Some(worst)
}

/// For the coupler point kernels, which have no references: their worst differences from the
/// group's hand-written kernel over the sweep, position, velocity and acceleration, each
/// relative to `max(|hand-written|, 1)` (`None` where the kernel has no such output).
fn agreement(kernel: &Kernel) -> Option<[Option<f64>; 3]> {
    if !matches!(kernel.group, Group::CouplerPath | Group::CouplerMotion)
        || kernel.origin == Origin::Hand
    {
        return None;
    }
    let hand = KERNELS
        .iter()
        .find(|k| k.group == kernel.group && k.origin == Origin::Hand)?;
    let (mut ours, mut theirs) = ((kernel.outputs)(), (hand.outputs)());
    let mut worst = [None::<f64>; 3];
    for k in 0..STEPS {
        let t = kernels::input(k);
        for (i, (g, h)) in ours(t).iter().zip(theirs(t)).enumerate() {
            let error = (g - h).abs() / h.abs().max(1.0);
            worst[i / 2] = Some(worst[i / 2].map_or(error, |w| w.max(error)));
        }
    }
    Some(worst)
}

// ---- optional sections --------------------------------------------------------------------

/// `name value` lines of a program's output, the value as printed (and a number).
fn key_values(text: &str) -> Vec<(String, String)> {
    text.lines()
        .filter_map(|line| {
            let mut fields = line.split_whitespace();
            let (key, value) = (fields.next()?, fields.next()?);
            (fields.next().is_none() && value.parse::<f64>().is_ok())
                .then(|| (key.to_string(), value.to_string()))
        })
        .collect()
}

fn embedded_sizes(commit: &str) -> String {
    let script = Path::new("tests/embedded/sizes.sh");
    let mut out = String::from("\n## Code size on a microcontroller\n\n");
    if !script.exists() {
        out.push_str("Not measured: `tests/embedded/sizes.sh` is not in this tree.\n");
        return out;
    }
    eprintln!("== bash tests/embedded/sizes.sh");
    let output = Command::new("bash").arg(script).output();
    match output {
        Ok(o) if o.status.success() => {
            out.push_str(
                "From `bash tests/embedded/sizes.sh` (the firmware of `tests/embedded`, \
                 generated kernels beside hand-written ones):\n",
            );
            out.push_str(&String::from_utf8_lossy(&o.stdout));
            out.push_str(&stamp(commit));
        }
        Ok(o) => {
            let stderr = String::from_utf8_lossy(&o.stderr);
            eprint!("{stderr}");
            let why = stderr
                .lines()
                .rev()
                .find(|l| !l.trim().is_empty())
                .unwrap_or("no message");
            writeln!(
                out,
                "Not measured at commit `{commit}`: `bash tests/embedded/sizes.sh` failed \
                 ({}): `{}`.",
                o.status,
                why.trim()
            )
            .unwrap();
        }
        Err(e) => {
            writeln!(
                out,
                "Not measured: cannot run `bash tests/embedded/sizes.sh`: {e}."
            )
            .unwrap();
        }
    }
    out
}

fn batch_and_numpy(commit: &str) -> String {
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    if Path::new("tests/src/bin/batch.rs").exists() {
        eprintln!("== cargo run --release -p mechgen-tests --bin batch");
        match stdout_of(
            cargo().args([
                "run",
                "--release",
                "-q",
                "-p",
                "mechgen-tests",
                "--bin",
                "batch",
            ]),
            "cargo run --release -p mechgen-tests --bin batch",
        ) {
            Ok(text) => rows.extend(
                key_values(&text)
                    .into_iter()
                    .map(|(k, v)| ("`cargo run --release -p mechgen-tests --bin batch`", k, v)),
            ),
            Err(e) => notes.push(format!("the batch timing was not measured: {e}")),
        }
    }
    let python = Path::new("target/numpy-venv/bin/python");
    let script = Path::new("tests/reference/numpy_four_bar.py");
    if python.exists() && script.exists() {
        eprintln!("== target/numpy-venv/bin/python tests/reference/numpy_four_bar.py");
        match stdout_of(
            Command::new(python).arg(script),
            "target/numpy-venv/bin/python tests/reference/numpy_four_bar.py",
        ) {
            Ok(text) => rows.extend(key_values(&text).into_iter().map(|(k, v)| {
                (
                    "`target/numpy-venv/bin/python tests/reference/numpy_four_bar.py`",
                    k,
                    v,
                )
            })),
            Err(e) => notes.push(format!("numpy was not timed: {e}")),
        }
    } else if script.exists() {
        notes.push(
            "numpy was not timed: no `target/numpy-venv` (make it with \
             `tests/reference/setup-numpy.sh`)"
                .into(),
        );
    }
    if rows.is_empty() && notes.is_empty() {
        return String::new();
    }
    let mut out = String::from(
        "\n## Batch kernels and numpy\n\nThe four-bar's joint positions over the same turn, \
         many angles per call; each program's own figures, as it prints them (times in \
         nanoseconds per step, the best of many samples).\n\n",
    );
    if !rows.is_empty() {
        out.push_str("| figure | value | from |\n|---|---|---|\n");
        for (from, key, value) in &rows {
            writeln!(out, "| `{key}` | {value} | {from} |").unwrap();
        }
        let get = |name: &str| {
            rows.iter()
                .find(|r| r.1 == name)
                .and_then(|r| r.2.parse::<f64>().ok())
        };
        if let (Some(numpy), Some(hand)) = (get("numpy_ns_per_step"), get("hand_batch_ns_per_step"))
        {
            writeln!(
                out,
                "\nnumpy takes {:.1}× the hand-written batch kernel's time per step.",
                numpy / hand
            )
            .unwrap();
        }
        if let (Some(numpy), Some(generated)) =
            (get("numpy_ns_per_step"), get("generated_batch_ns_per_step"))
        {
            writeln!(
                out,
                "numpy takes {:.1}× the generated batch kernel's (`FourBarScenes::joints_batch`) \
                 time per step; the aim is at least 5×.",
                numpy / generated
            )
            .unwrap();
        }
        out.push_str(&stamp(commit));
    }
    for note in notes {
        writeln!(out, "\nNote: {note}.").unwrap();
    }
    out
}

/// Lines of each expansion snapshot.
fn expansion_lines(name: &str) -> Option<usize> {
    let path = format!("tests/snapshots/expansion/{name}.snap");
    std::fs::read_to_string(path)
        .ok()
        .map(|s| s.lines().count().saturating_sub(3))
}

/// Bytes of machine code of every symbol whose name contains `needle`, in the release
/// build of this crate's library.
fn machine_code_bytes(target: &Path, needle: &str) -> Option<u64> {
    let deps = std::fs::read_dir(target.join("release/deps")).ok()?;
    let rlib = deps
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("libmechgen_tests-") && n.ends_with(".rlib"))
        })
        .max_by_key(|p| std::fs::metadata(p).and_then(|m| m.modified()).ok())?;
    let output = Command::new("nm")
        .args(["-S", "-C", "--defined-only"])
        .arg(&rlib)
        .output()
        .ok()?;
    let text = String::from_utf8_lossy(&output.stdout);
    Some(
        text.lines()
            .filter(|line| line.contains(needle))
            .filter_map(|line| {
                let mut fields = line.split_whitespace();
                let _address = fields.next()?;
                let size = fields.next()?;
                let kind = fields.next()?;
                (kind == "t" || kind == "T").then(|| u64::from_str_radix(size, 16).ok())?
            })
            .sum(),
    )
}

/// Seconds to build the `mechanisms` crate (release) from clean.
fn compile_seconds() -> Option<f64> {
    cargo()
        .args(["clean", "--release", "-p", "mechanisms"])
        .output()
        .ok()?;
    let start = Instant::now();
    let status = cargo()
        .args(["build", "--release", "-q", "-p", "mechanisms", "--lib"])
        .status()
        .ok()?;
    status.success().then(|| start.elapsed().as_secs_f64())
}

fn declarations(target: &Path, build_seconds: Option<f64>, commit: &str) -> String {
    let mut out = String::from(
        "\n## What a declaration generates\n\nLines of each reviewed expansion \
         (`tests/snapshots/expansion/`), and for the four-bar declared three times asking for \
         less each time (`tests/src/scenes.rs`), the machine code of its `#[inline(never)]` \
         entry point calling `assemble`: generic functions a program never calls are never \
         compiled, so leaving outputs out shortens the expansion, not the code that runs.\n\n\
         | declaration | generates | expansion lines | entry point bytes |\n|---|---|---|---|\n",
    );
    let mut names: Vec<String> = std::fs::read_dir("tests/snapshots/expansion")
        .map(|d| {
            d.flatten()
                .filter_map(|e| {
                    e.file_name()
                        .to_str()?
                        .strip_suffix(".snap")
                        .map(str::to_string)
                })
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    for name in names {
        let (generates, needle) = match name.as_str() {
            "PositionsOnly" => ("position", Some("scenes::positions_only")),
            "WithVelocities" => ("position, velocity", Some("scenes::with_velocities")),
            "Everything" => (
                "position, velocity, acceleration",
                Some("scenes::everything"),
            ),
            _ => ("as declared", None),
        };
        let lines = expansion_lines(&name).map_or("–".into(), |l| l.to_string());
        let bytes = needle
            .and_then(|n| machine_code_bytes(target, n))
            .map_or("–".into(), |b| b.to_string());
        writeln!(out, "| `{name}` | {generates} | {lines} | {bytes} |").unwrap();
    }
    out.push_str(&stamp(commit));
    match build_seconds {
        Some(s) => writeln!(
            out,
            "\nBuilding the `mechanisms` crate (every shipped declaration and its analyses) in \
             release from clean (`cargo clean --release -p mechanisms`, then `cargo build \
             --release -p mechanisms --lib`): {s:.1} s, on a machine that may be busy."
        )
        .unwrap(),
        None => out.push_str("\nBuild time: not measured (the build failed).\n"),
    }
    out
}

// ---- the report ---------------------------------------------------------------------------

fn ratio_cell(a: Option<f64>, b: Option<f64>) -> String {
    match (a, b) {
        (Some(a), Some(b)) => format!("{:.2}×", a / b),
        _ => "–".into(),
    }
}

fn origin(kernel: &Kernel) -> &'static str {
    match kernel.origin {
        Origin::Generated => "generated",
        Origin::Hand => "hand-written",
        Origin::Library => "library",
        Origin::Overhead => "overhead",
    }
}

/// The kernels of the report's tables: all but `none`, by group.
fn measured() -> impl Iterator<Item = &'static Kernel> {
    Group::ALL
        .into_iter()
        .flat_map(|g| KERNELS.iter().filter(move |k| k.group == g))
        .filter(|k| k.group != Group::Overhead)
}

fn targets_section(
    counts: &BTreeMap<String, f64>,
    times: &BTreeMap<String, Timing>,
    commit: &str,
) -> String {
    let mut out = String::from(
        "\n## Targets\n\nJudged on instructions per call (callgrind), which are deterministic; \
         wall-clock ratios from the same criterion run alongside. `performance -- check` fails \
         if a target published here as met is missed; one published as missed is a known gap, \
         which it reports without failing until the target is met and this file regenerated.\n\n\
         | target | what | instructions ratio | time ratio | met |\n|---|---|---|---|---|\n",
    );
    let mut missed = Vec::new();
    for target in TARGETS {
        let judged = target.judge(counts);
        let time = ratio_cell(
            times.get(target.kernel).map(|t| t.mean),
            times.get(target.against).map(|t| t.mean),
        );
        let (ratio, met) = match judged {
            Some((r, m)) => (format!("{r:.3}×"), if m { "met" } else { "**missed**" }),
            None => ("–".into(), "–"),
        };
        if matches!(judged, Some((_, false))) {
            missed.push(target);
        }
        writeln!(
            out,
            "| {} | {} | {ratio} | {time} | {met} |",
            target.label(),
            target.why
        )
        .unwrap();
    }
    out.push_str(&stamp(commit));
    if missed.is_empty() {
        out.push_str("\nEvery target is met at this commit.\n");
    } else {
        out.push_str("\nMissed at this commit: ");
        let list: Vec<String> = missed
            .iter()
            .map(|t| {
                let (r, _) = t.judge(counts).expect("judged above");
                format!(
                    "{} ({:.0} against {:.0} instructions, {r:.2}×)",
                    t.label(),
                    counts[t.kernel],
                    counts[t.against]
                )
            })
            .collect();
        out.push_str(&list.join("; "));
        out.push_str(".\n");
    }
    out
}

fn instructions_section(counts: &BTreeMap<String, f64>, none: u64, commit: &str) -> String {
    let mut out = format!(
        "\n{INSTRUCTIONS_HEADING}\n\n`valgrind --tool=callgrind <instructions driver> <kernel>`: \
         the kernel built once, then its boxed closure called over the 360-angle sweep {SWEEPS} \
         times; per call = (total − `none`'s total) / {CALLS:.0}. `none`, the boxed identity, \
         counts {none} instructions for the whole run (process start-up, the loop and the \
         calls). Each ratio is to the kernel named beside it; targets are in the table above. \
         `performance -- check` recounts these and fails if one moves by more than {:.0}%.\n\n\
         | group | kernel | float | instructions per call | compared with | ratio | target |\n\
         |---|---|---|---|---|---|---|\n",
        DRIFT * 100.0
    );
    let mut last = None;
    for kernel in measured() {
        let group = if last == Some(kernel.group) {
            ""
        } else {
            kernel.group.title()
        };
        last = Some(kernel.group);
        let count = counts.get(kernel.name).copied();
        let against = kernel.compared_with.and_then(|c| counts.get(c).copied());
        let target = Target::on(kernel).map_or("–".to_string(), |t| match t.judge(counts) {
            Some((_, true)) => format!("{} {:.2}×: met", if t.strict { "<" } else { "≤" }, t.limit),
            Some((_, false)) => {
                format!(
                    "{} {:.2}×: **missed**",
                    if t.strict { "<" } else { "≤" },
                    t.limit
                )
            }
            None => "–".into(),
        });
        writeln!(
            out,
            "| {group} | `{}` | {} | {} | {} | {} | {target} |",
            kernel.name,
            kernel.float,
            count.map_or("–".into(), |c| format!("{c:.1}")),
            kernel
                .compared_with
                .map_or("–".into(), |c| format!("`{c}`")),
            ratio_cell(count, against),
        )
        .unwrap();
    }
    out.push_str(&stamp(commit));
    out
}

fn times_section(
    times: &BTreeMap<String, Timing>,
    errors: &BTreeMap<&str, [f64; 3]>,
    commit: &str,
) -> String {
    let mut out = format!(
        "\n## Time per step\n\nCriterion (`cargo bench -p mechgen-tests --bench kinematics`), \
         every kernel side by side in one run: mean nanoseconds per step (one iteration is the \
         360-angle sweep through the boxed closure, so each figure includes the call, `none`'s \
         {}), criterion's 95% confidence interval of the mean and the standard deviation of \
         the samples. Ratios are of means in this run. Errors are the worst over the sweep \
         against 60-digit references (`tests/reference/sweeps.csv`): angles in radians, \
         lengths, rates and accelerations relative. The coupler points have no references: \
         their figures, in italics, are the worst differences from the hand-written kernel of \
         their group, relative to its outputs. – where neither applies.\n\n\
         | group | kernel | float | ns per step | 95% CI | std dev | compared with | ratio | \
         position error | velocity error | acceleration error |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
        times
            .get("none")
            .map_or("–".into(), |t| format!("{:.1} ns", t.mean))
    );
    let mut last = None;
    for kernel in measured() {
        let group = if last == Some(kernel.group) {
            ""
        } else {
            kernel.group.title()
        };
        last = Some(kernel.group);
        let time = times.get(kernel.name);
        let against = kernel
            .compared_with
            .and_then(|c| times.get(c))
            .map(|t| t.mean);
        let [p, v, a] = match (errors.get(kernel.name), agreement(kernel)) {
            (Some(e), _) => e.map(|x| format!("{x:.1e}")),
            (None, Some(d)) => d.map(|x| x.map_or("–".into(), |x| format!("*{x:.1e}*"))),
            (None, None) => ["–".to_string(), "–".into(), "–".into()],
        };
        writeln!(
            out,
            "| {group} | `{}` | {} | {} | {} | {} | {} | {} | {p} | {v} | {a} |",
            kernel.name,
            kernel.float,
            time.map_or("–".into(), |t| format!("{:.1}", t.mean)),
            time.map_or("–".into(), |t| format!("{:.1}–{:.1}", t.lower, t.upper)),
            time.map_or("–".into(), |t| format!("{:.1}", t.std_dev)),
            kernel
                .compared_with
                .map_or("–".into(), |c| format!("`{c}`")),
            ratio_cell(time.map(|t| t.mean), against),
        )
        .unwrap();
    }
    out.push_str(&stamp(commit));
    out
}

fn kernels_section(commit: &str) -> String {
    let mut out = String::from(
        "\n## The kernels\n\nEvery kernel is in `tests/src/kernels.rs`, which the callgrind \
         driver (`tests/src/bin/instructions.rs`) and the benchmark \
         (`tests/benches/kinematics.rs`) both run: built once outside the measured loop, \
         called through the same boxed closure, returning the sum of its outputs. Newton \
         kernels warm-start from the velocity predictor, `q + (q̇/ω)·1°`, hand and generated \
         alike.\n\n| kernel | by | float | mechanism | calls per step |\n|---|---|---|---|---|\n",
    );
    for kernel in measured() {
        writeln!(
            out,
            "| `{}` | {} | {} | {} | {} |",
            kernel.name,
            origin(kernel),
            kernel.float,
            kernel.mechanism,
            kernel.description
        )
        .unwrap();
    }
    out.push_str(&stamp(commit));
    out
}

fn frontier_svg(points: &[(&Kernel, f64, f64)], commit: &str) -> String {
    // The plot on the left, a numbered legend on the right: the points cluster, names would
    // overprint.
    let (width, height, margin, plot_right) = (1000.0, 480.0, 70.0, 640.0);
    let log = |v: f64| v.max(1e-17).log10();
    let xs: Vec<f64> = points.iter().map(|p| log(p.1)).collect();
    let ys: Vec<f64> = points.iter().map(|p| log(p.2)).collect();
    let range = |v: &[f64]| {
        (
            v.iter().cloned().fold(f64::MAX, f64::min).floor(),
            v.iter().cloned().fold(f64::MIN, f64::max).ceil(),
        )
    };
    let ((x0, x1), (y0, y1)) = (range(&xs), range(&ys));
    let px = |x: f64| margin + (x - x0) / (x1 - x0).max(1.0) * (plot_right - margin);
    let py = |y: f64| height - margin - (y - y0) / (y1 - y0).max(1.0) * (height - 2.0 * margin);
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" font-family=\"sans-serif\" font-size=\"11\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n\
         <text x=\"{}\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">Four-bar: worst position error against time per step (θ3, θ4, rates, accelerations), log scales</text>\n\
         <text x=\"{}\" y=\"40\" text-anchor=\"middle\" fill=\"#555\">generated in blue, hand-written in red, libraries in grey; commit {commit}</text>\n",
        width / 2.0,
        width / 2.0
    );
    for x in (x0 as i32)..=(x1 as i32) {
        let p = px(f64::from(x));
        writeln!(svg, "<line x1=\"{p}\" y1=\"{margin}\" x2=\"{p}\" y2=\"{}\" stroke=\"#ddd\"/><text x=\"{p}\" y=\"{}\" text-anchor=\"middle\">1e{x} ns</text>", height - margin, height - margin + 16.0).unwrap();
    }
    for y in (y0 as i32)..=(y1 as i32) {
        let p = py(f64::from(y));
        writeln!(svg, "<line x1=\"{margin}\" y1=\"{p}\" x2=\"{plot_right}\" y2=\"{p}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">1e{y}</text>", margin - 6.0, p + 4.0).unwrap();
    }
    let mut placed: Vec<(f64, f64)> = Vec::new();
    for (i, ((kernel, ns, error), (x, y))) in points.iter().zip(xs.iter().zip(&ys)).enumerate() {
        let (cx, cy) = (px(*x), py(*y));
        let colour = match kernel.origin {
            Origin::Generated => "#1f6feb",
            Origin::Hand => "#d1242f",
            _ => "#6e7781",
        };
        // A number beside each point, stacked upwards over the numbers already near it.
        let near = placed
            .iter()
            .filter(|(x, y)| (x - cx).abs() < 18.0 && (y - cy).abs() < 6.0)
            .count();
        placed.push((cx, cy));
        let n = i + 1;
        writeln!(svg, "<circle cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"4\" fill=\"{colour}\"><title>{}</title></circle><text x=\"{:.1}\" y=\"{:.1}\" fill=\"{colour}\">{n}</text>", kernel.name, cx + 5.0, cy - 5.0 - 12.0 * near as f64).unwrap();
        writeln!(svg, "<text x=\"{}\" y=\"{:.1}\" fill=\"{colour}\">{n}. {} ({}): {ns:.0} ns, {error:.1e}</text>", plot_right + 30.0, margin + 16.0 * i as f64, kernel.name, kernel.float).unwrap();
    }
    svg.push_str("</svg>\n");
    svg
}

fn machine() -> String {
    stamp::machine(&[("rustc", &["--version"]), ("valgrind", &["--version"])])
}

fn write() -> Result<(), Failure> {
    let start = Instant::now();
    let commit = commit();
    let target = target_dir()?;

    eprintln!("== build time of the mechanisms crate");
    let build_seconds = compile_seconds();

    eprintln!("== instruction counts");
    let driver = build_driver()?;
    let (counts, none) = instruction_counts(&driver)?;

    let sizes = embedded_sizes(&commit);
    let batch = batch_and_numpy(&commit);

    eprintln!("== cargo bench -p mechgen-tests --bench kinematics");
    run_benchmark(&target)?;
    let times = timings(&target);
    let unmeasured: Vec<&str> = KERNELS
        .iter()
        .map(|k| k.name)
        .filter(|n| !times.contains_key(*n))
        .collect();
    if !unmeasured.is_empty() {
        return Err(format!("criterion has no results for {unmeasured:?}"));
    }

    eprintln!("== accuracy");
    let errors: BTreeMap<&str, [f64; 3]> = KERNELS
        .iter()
        .filter_map(|k| Some((k.name, accuracy(k)?)))
        .collect();

    let mut out = format!(
        "# Performance\n\nThe generated kernels side by side with the hand-written code a \
         careful engineer would write for one mechanism (`tests/src/baselines.rs`): instructions \
         per call (callgrind), time per step (criterion) and accuracy, for every kernel of \
         `tests/src/kernels.rs`. Every figure in this file comes from one command, run from \
         the repository at commit `{commit}` on {}:\n\n\
         ```sh\n{WRITE_COMMAND}\n```\n\n\
         CI (`.ci/instructions`) runs `cargo run --release -p mechgen-tests --bin performance \
         -- check`, which recounts every kernel's instructions and fails if a count below moves \
         by more than {:.0}% or a target published as met is missed (a missed one stays a known gap). The sweep: 360 crank angles one degree \
         apart, ω2 = {} rad/s, α2 = {} rad/s², open branch.\n",
        machine(),
        DRIFT * 100.0,
        kernels::OMEGA,
        kernels::ALPHA,
    );
    out.push_str(&targets_section(&counts, &times, &commit));
    out.push_str(&instructions_section(&counts, none, &commit));
    out.push_str(&times_section(&times, &errors, &commit));
    out.push_str(
        "\n## Speed against accuracy\n\n![Worst position error against time per step, four-bar](frontier.svg)\n",
    );
    out.push_str(&kernels_section(&commit));
    out.push_str(&sizes);
    out.push_str(&batch);
    out.push_str(&declarations(&target, build_seconds, &commit));

    let frontier: Vec<(&Kernel, f64, f64)> = KERNELS
        .iter()
        .filter(|k| matches!(k.group, Group::FourBarAngles | Group::FourBarNewton))
        .filter_map(|k| Some((k, times.get(k.name)?.mean, errors.get(k.name)?[0])))
        .collect();
    std::fs::write(REPORT, out).map_err(|e| format!("{REPORT}: {e}"))?;
    std::fs::write(FRONTIER, frontier_svg(&frontier, &commit))
        .map_err(|e| format!("{FRONTIER}: {e}"))?;
    eprintln!(
        "wrote {REPORT} and {FRONTIER} in {:.0} s",
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

// ---- check --------------------------------------------------------------------------------

/// The counts published in the report's instruction table: kernel → instructions per call.
fn published() -> Result<BTreeMap<String, f64>, Failure> {
    let text = std::fs::read_to_string(REPORT).map_err(|e| format!("{REPORT}: {e}"))?;
    let section = text
        .split_once(INSTRUCTIONS_HEADING)
        .map(|(_, rest)| rest.split("\n## ").next().unwrap_or(rest))
        .ok_or_else(|| {
            format!("{REPORT} has no `{INSTRUCTIONS_HEADING}` section: run `{WRITE_COMMAND}`")
        })?;
    let mut counts = BTreeMap::new();
    for line in section.lines().filter(|l| l.starts_with('|')) {
        let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
        let Some(name) = cells
            .get(1)
            .and_then(|c| c.strip_prefix('`')?.strip_suffix('`'))
        else {
            continue;
        };
        let count = cells
            .get(3)
            .and_then(|c| c.parse::<f64>().ok())
            .ok_or_else(|| format!("{REPORT}: no count for `{name}` in `{line}`"))?;
        counts.insert(name.to_string(), count);
    }
    Ok(counts)
}

fn check() -> Result<(), Failure> {
    let start = Instant::now();
    let published = published()?;
    let driver = build_driver()?;
    let (counts, _) = instruction_counts(&driver)?;
    let mut failures = Vec::new();

    println!(
        "\n{:<32} {:>12} {:>12} {:>8}  ok",
        "kernel", "published", "measured", "change"
    );
    for kernel in measured() {
        let measured = counts.get(kernel.name).copied();
        let publish = published.get(kernel.name).copied();
        let (change, ok) = match (publish, measured) {
            (Some(p), Some(m)) => {
                let change = (m - p) / p.abs().max(1.0);
                (format!("{:+.2}%", change * 100.0), change.abs() <= DRIFT)
            }
            _ => ("–".into(), false),
        };
        println!(
            "{:<32} {:>12} {:>12} {:>8}  {}",
            kernel.name,
            publish.map_or("–".into(), |p| format!("{p:.1}")),
            measured.map_or("–".into(), |m| format!("{m:.1}")),
            change,
            if ok { "yes" } else { "NO" }
        );
        if !ok {
            failures.push(match publish {
                None => format!("`{}` is not published in {REPORT}", kernel.name),
                Some(p) => format!(
                    "`{}`: {REPORT} publishes {p:.1} instructions per call, measured {} (more than {:.0}% off)",
                    kernel.name,
                    measured.map_or("nothing".into(), |m| format!("{m:.1}")),
                    DRIFT * 100.0
                ),
            });
        }
    }
    for name in published.keys() {
        if kernels::find(name).is_none() {
            failures.push(format!(
                "{REPORT} publishes `{name}`, which is no longer a kernel"
            ));
        }
    }

    // A target the report publishes as met must stay met; one it publishes as missed is a
    // known gap (said so in the report), not a failure, until it is met and published.
    println!("\n{:<72} {:>8}  met", "target", "ratio");
    for target in TARGETS {
        let judged = target.judge(&counts);
        let was_met = matches!(target.judge(&published), Some((_, true)));
        println!(
            "{:<72} {:>8}  {}",
            target.label().replace('`', ""),
            judged.map_or("–".into(), |(r, _)| format!("{r:.3}×")),
            match judged {
                Some((_, true)) => "yes",
                Some((_, false)) if target.stretch => "no (stretch goal: not a failure)",
                Some((_, false)) if !was_met => "no (published as missed)",
                _ => "NO",
            }
        );
        match judged {
            Some((_, true)) => {}
            Some((r, false)) if !target.stretch && was_met => failures.push(format!(
                "target met in the report, missed now: {} ({r:.3}×; {} costs {:.1}, {} {:.1} instructions per call)",
                target.label().replace('`', ""),
                target.kernel,
                counts[target.kernel],
                target.against,
                counts[target.against]
            )),
            Some(_) => {}
            None => failures.push(format!("target {} could not be judged", target.label())),
        }
    }
    println!(
        "\nchecked in {:.0} s against {REPORT}",
        start.elapsed().as_secs_f64()
    );
    if failures.is_empty() {
        println!("performance check passed");
        Ok(())
    } else {
        Err(format!(
            "performance check failed:\n  - {}\n(if the change is intended, run `{WRITE_COMMAND}` and commit the report)",
            failures.join("\n  - ")
        ))
    }
}

fn main() {
    // Paths are relative to the repository root, wherever this is run from.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the tests crate sits in the repository");
    std::env::set_current_dir(root).expect("the repository root is a directory");
    let result = match std::env::args().nth(1).as_deref() {
        Some("write") => write(),
        Some("check") => check(),
        _ => {
            eprintln!(
                "usage: performance write | check\n  write  measure every kernel and write {REPORT} and {FRONTIER}\n  check  recount instructions and compare with {REPORT} (what CI runs)"
            );
            std::process::exit(2);
        }
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
