//! The synthesis report: `mechanisms::synthesis` and `FourBar::tolerance` timed against
//! pylinkage on the same problems. From anywhere in the workspace:
//!
//! ```sh
//! cargo run --release -p mechgen-tests --bin synthesis            # our side, `key value` lines
//! cargo run --release -p mechgen-tests --bin synthesis -- write   # both sides, docs/SYNTHESIS.md
//! ```
//!
//! `write` measures our side in this process, runs
//! `target/pylinkage-venv/bin/python tests/reference/pylinkage_synthesis.py` (made by
//! `tests/reference/setup-pylinkage.sh`) for pylinkage's, and writes every figure of the
//! report from the two. The problems and their constants are the same in both programs.
//!
//! Each synthesis is one call, timed as the best of several repetitions; its error is the
//! rms error at the targets, recomputed here from the linkage it returns (not taken from the
//! synthesis' own report). Our restarts run on every core (rayon); the 1-thread rows run the
//! same calls in a one-thread pool, for a like-for-like comparison with single-threaded
//! Python.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

use mechanisms::synthesis::{Options, Synthesis, function_generation, path_generation};
use mechanisms::{FourBar, FourBarTolerances};
use mechgen::{Branch, Vec2};
use mechgen_tests::stamp::{self, commit};

const REPORT: &str = "docs/SYNTHESIS.md";
const WRITE_COMMAND: &str = "cargo run --release -p mechgen-tests --bin synthesis -- write";
const PYTHON: &str = "target/pylinkage-venv/bin/python";
const SCRIPT: &str = "tests/reference/pylinkage_synthesis.py";

const L1: f64 = 180.0;
const L2: f64 = 80.0;
const L3: f64 = 200.0;
const L4: f64 = 150.0;
const P_DISTANCE: f64 = 100.0;
const P_ANGLE_DEGREES: f64 = 30.0;

/// Function generation: crank angles and wanted rocker angles (degrees), the open branch of
/// 180/80/200/150 to four decimals.
const FG_CRANK: [f64; 6] = [0.0, 45.0, 90.0, 135.0, 180.0, 225.0];
const FG_ROCKER: [f64; 6] = [75.5225, 66.6938, 87.1652, 111.3700, 129.9641, 138.2662];
/// rms rocker angle error, radians.
const FG_THRESHOLD: f64 = 1e-6;
/// Path generation with prescribed timing: crank angles (radians) and the coupler point of
/// 180/80/200/150 with P 100 from A at 30° there (also in the Python script).
const PG_TIMING: [f64; 6] = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
const PG_TARGETS: [[f64; 2]; 6] = [
    [103.23002763948563, 97.2644118671816],
    [104.96338014345498, 145.98324760306124],
    [28.382571701527226, 151.46023729553343],
    [-33.32881773757787, 100.14841960980091],
    [-40.32857939550637, 38.73766567707234],
    [0.9412713237244894, 20.891710497838275],
];
/// rms distance from the targets, mm.
const PG_THRESHOLD: f64 = 1e-4;
/// The fixed time budget, seconds.
const BUDGET: f64 = 1.0;
/// Tolerance analysis: every length ±0.1 mm at θ2 = 60°.
const TOLERANCE: f64 = 0.1;
const TOLERANCE_THETA2_DEGREES: f64 = 60.0;
/// Restarts of the runs that show time against error (64 is the default).
const RESTARTS: [usize; 4] = [0, 4, 16, 64];

type Failure = String;
type Values = BTreeMap<String, String>;

/// The best time of `f` over at least 3 and at most 20 runs, stopping after 2 s, and its last
/// result.
fn best_of<R>(mut f: impl FnMut() -> R) -> (f64, R) {
    let started = Instant::now();
    let mut best = f64::INFINITY;
    let mut runs = 0;
    loop {
        let start = Instant::now();
        let result = f();
        best = best.min(start.elapsed().as_secs_f64());
        runs += 1;
        if runs >= 20 || (runs >= 3 && started.elapsed().as_secs_f64() > 2.0) {
            return (best, result);
        }
    }
}

fn one_thread<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool")
        .install(f)
}

fn nominal() -> FourBar<f64> {
    FourBar::new(L1, L2, L3, L4)
        .and_then(|l| l.with_coupler_point(P_DISTANCE, P_ANGLE_DEGREES.to_radians()))
        .expect("the four-bar of the problems")
}

/// The rms rocker angle error of `linkage` at the function generation targets.
fn fg_error(linkage: &FourBar<f64>) -> f64 {
    let total: f64 = FG_CRANK
        .iter()
        .zip(FG_ROCKER)
        .map(|(&t2, t4)| {
            linkage
                .assemble(t2.to_radians(), Branch::Open)
                .map_or(f64::INFINITY, |q| {
                    let e = (q.theta4 - t4.to_radians()).rem_euclid(std::f64::consts::TAU);
                    e.min(std::f64::consts::TAU - e).powi(2)
                })
        })
        .sum();
    (total / FG_CRANK.len() as f64).sqrt()
}

/// The rms distance of a path synthesis' coupler point, placed, from the targets.
fn pg_error(found: &Synthesis) -> f64 {
    let (origin, angle) = found.placement;
    let (s, c) = angle.sin_cos();
    let total: f64 = PG_TIMING
        .iter()
        .zip(PG_TARGETS)
        .map(|(&t2, [x, y])| {
            let Ok(q) = found.linkage.assemble(t2, Branch::Open) else {
                return f64::INFINITY;
            };
            let Ok(points) = found.linkage.points(t2, &q) else {
                return f64::INFINITY;
            };
            let p = points.coupler_point;
            let world = Vec2 {
                x: origin.x + c * p.x - s * p.y,
                y: origin.y + s * p.x + c * p.y,
            };
            (world.x - x).powi(2) + (world.y - y).powi(2)
        })
        .sum();
    (total / PG_TIMING.len() as f64).sqrt()
}

fn options(restarts: usize) -> Options {
    Options {
        restarts,
        ..Options::default()
    }
}

/// Our side: every figure as `key value`.
fn measure() -> Result<Values, Failure> {
    let mut out = Values::new();
    let mut put = |k: String, v: String| {
        println!("{k} {v}");
        out.insert(k, v);
    };
    // The path targets are the nominal linkage's coupler point.
    let linkage = nominal();
    let drift = PG_TIMING
        .iter()
        .zip(PG_TARGETS)
        .map(|(&t2, [x, y])| {
            let q = linkage.assemble(t2, Branch::Open).expect("assembles");
            let p = linkage.points(t2, &q).expect("points").coupler_point;
            (p.x - x).hypot(p.y - y)
        })
        .fold(0.0f64, f64::max);
    if drift > 1e-9 {
        return Err(format!(
            "the path targets are not the nominal coupler point ({drift:e} mm)"
        ));
    }
    put("pg_targets_check_mm".into(), format!("{drift:.1e}"));
    put(
        "fg_error_of_exact_answer".into(),
        format!("{:.4e}", fg_error(&linkage)),
    );
    put("threads".into(), rayon::current_num_threads().to_string());

    let phi = FG_CRANK.map(f64::to_radians);
    let psi = FG_ROCKER.map(f64::to_radians);
    let targets = PG_TARGETS.map(|[x, y]| Vec2 { x, y });
    for restarts in RESTARTS {
        for (threads, prefix) in [(0, "fg"), (1, "fg1")] {
            let run = || best_of(|| function_generation(L1, &phi, &psi, &options(restarts)));
            let (seconds, found) = if threads == 1 { one_thread(run) } else { run() };
            let found = found.map_err(|e| format!("function generation: {e}"))?;
            let [_, a, b, c] = found.linkage.lengths();
            put(
                format!("{prefix}_r{restarts}_seconds"),
                format!("{seconds:.4e}"),
            );
            put(
                format!("{prefix}_r{restarts}_error"),
                format!("{:.4e}", fg_error(&found.linkage)),
            );
            put(
                format!("{prefix}_r{restarts}_lengths"),
                format!("{a:.6} {b:.6} {c:.6}"),
            );
        }
        if restarts == 0 {
            continue;
        }
        for (threads, prefix) in [(0, "pg"), (1, "pg1")] {
            let run =
                || best_of(|| path_generation(&targets, Some(&PG_TIMING), &options(restarts)));
            let (seconds, found) = if threads == 1 { one_thread(run) } else { run() };
            let found = found.map_err(|e| format!("path generation: {e}"))?;
            let [d, a, b, c] = found.linkage.lengths();
            let (p, delta) = found.linkage.coupler_point();
            put(
                format!("{prefix}_r{restarts}_seconds"),
                format!("{seconds:.4e}"),
            );
            put(
                format!("{prefix}_r{restarts}_error"),
                format!("{:.4e}", pg_error(&found)),
            );
            put(
                format!("{prefix}_r{restarts}_dimensions"),
                format!(
                    "{d:.4} {a:.4} {b:.4} {c:.4} {p:.4} {:.4}",
                    delta.to_degrees()
                ),
            );
        }
    }

    // Stopping once the classical start is within the threshold, as the optimisers' times
    // are to their first evaluation within it.
    for (threads, prefix) in [(0, "fgs"), (1, "fgs1")] {
        let stopping = Options {
            good_enough: Some(FG_THRESHOLD),
            ..Options::default()
        };
        let run = || best_of(|| function_generation(L1, &phi, &psi, &stopping));
        let (seconds, found) = if threads == 1 { one_thread(run) } else { run() };
        let found = found.map_err(|e| format!("function generation: {e}"))?;
        let [_, a, b, c] = found.linkage.lengths();
        put(format!("{prefix}_seconds"), format!("{seconds:.4e}"));
        put(
            format!("{prefix}_error"),
            format!("{:.4e}", fg_error(&found.linkage)),
        );
        put(format!("{prefix}_lengths"), format!("{a:.6} {b:.6} {c:.6}"));
    }

    // Tolerance: first order from the generated sensitivities, against the nonlinear model.
    let theta2 = TOLERANCE_THETA2_DEGREES.to_radians();
    let tolerances = FourBarTolerances::lengths(TOLERANCE);
    let (seconds, linear) = best_of(|| {
        let start = Instant::now();
        let mut last = None;
        for _ in 0..10_000 {
            last =
                Some(std::hint::black_box(&linkage).tolerance(theta2, Branch::Open, &tolerances));
        }
        (start.elapsed(), last)
    });
    let linear = linear
        .1
        .expect("ran")
        .map_err(|e| format!("tolerance: {e}"))?;
    put(
        "tol_linear_seconds".into(),
        format!("{:.4e}", seconds / 10_000.0),
    );
    put(
        "tol_output_worst_case".into(),
        format!("{:.6e}", linear.output.worst_case),
    );
    put(
        "tol_output_rss".into(),
        format!("{:.6e}", linear.output.root_sum_square),
    );
    put(
        "tol_point_worst_case".into(),
        format!("{:.6e}", linear.coupler_point.worst_case),
    );
    put(
        "tol_point_rss".into(),
        format!("{:.6e}", linear.coupler_point.root_sum_square),
    );
    let (seconds, corners) = best_of(|| linkage.corners(theta2, Branch::Open, &tolerances));
    let corners = corners.map_err(|e| format!("corners: {e}"))?;
    put("tol_corners_seconds".into(), format!("{seconds:.4e}"));
    put(
        "tol_corners_output_largest".into(),
        format!("{:.6e}", corners.output_largest),
    );
    put(
        "tol_corners_point_largest".into(),
        format!("{:.6e}", corners.coupler_point_largest),
    );
    let (seconds, sampled) =
        best_of(|| linkage.monte_carlo(theta2, Branch::Open, &tolerances, 100_000, 1));
    let sampled = sampled.map_err(|e| format!("monte carlo: {e}"))?;
    put("tol_mc100000_seconds".into(), format!("{seconds:.4e}"));
    put(
        "tol_mc100000_output_3rms".into(),
        format!("{:.6e}", 3.0 * sampled.output_rms),
    );
    put(
        "tol_mc100000_point_3rms".into(),
        format!("{:.6e}", 3.0 * sampled.coupler_point_rms),
    );
    Ok(out)
}

fn machine() -> String {
    stamp::machine(&[("rustc", &["--version"])])
}

/// pylinkage's side, from the Python script.
fn pylinkage() -> Result<Values, Failure> {
    if !Path::new(PYTHON).exists() {
        return Err(format!(
            "no `target/pylinkage-venv`: make it with `tests/reference/setup-pylinkage.sh`, \
             then run `{WRITE_COMMAND}` again"
        ));
    }
    eprintln!("== {PYTHON} {SCRIPT}");
    let output = Command::new(PYTHON)
        .arg(SCRIPT)
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("{PYTHON}: cannot start: {e}"))?;
    if !output.status.success() {
        return Err(format!("{PYTHON} {SCRIPT}: {}", output.status));
    }
    Ok(String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|l| l.split_once(' '))
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect())
}

fn number(values: &Values, key: &str) -> Option<f64> {
    values.get(key)?.parse().ok()
}

fn seconds(s: f64) -> String {
    if s >= 1.0 {
        format!("{s:.2} s")
    } else if s >= 1e-3 {
        format!("{:.2} ms", s * 1e3)
    } else {
        format!("{:.1} µs", s * 1e6)
    }
}

/// One row of a synthesis table.
struct Row {
    method: String,
    /// Seconds to reach the threshold, if it did.
    to_threshold: Option<f64>,
    /// The best error within the budget, and the best error at all.
    at_budget: f64,
    best: f64,
    note: String,
}

/// One method that is a single call: it reaches the threshold in its time if its error is
/// within it, and its error counts within the budget if its time does.
fn single(method: String, time: f64, error: f64, threshold: f64, note: String) -> Row {
    Row {
        method,
        to_threshold: (error <= threshold).then_some(time),
        at_budget: if time <= BUDGET { error } else { f64::INFINITY },
        best: error,
        note,
    }
}

fn table(rows: &[Row], ours: f64, unit: &str, threshold: f64) -> String {
    let mut out = format!(
        "| method | time to rms error ≤ {threshold:.0e} {unit} | × ours | best rms error within \
         {BUDGET} s ({unit}) | best rms error reached ({unit}) | notes |\n|---|---:|---:|---:|---:|---|\n"
    );
    for row in rows {
        let (time, ratio) = match row.to_threshold {
            Some(t) => (seconds(t), ratio(t / ours)),
            None => ("never".into(), "—".into()),
        };
        let at_budget = if row.at_budget.is_finite() {
            format!("{:.2e}", row.at_budget)
        } else {
            "none".into()
        };
        writeln!(
            out,
            "| {} | {time} | {ratio} | {at_budget} | {:.2e} | {} |",
            row.method, row.best, row.note
        )
        .unwrap();
    }
    out
}

/// The rows of one problem: ours at each number of restarts, on every core and on one, then
/// pylinkage's methods.
fn rows(ours: &Values, py: &Values, problem: &str, threshold: f64, threads: &str) -> Vec<Row> {
    let mut rows = Vec::new();
    for restarts in RESTARTS {
        for (prefix, cores) in [(problem.to_string(), threads), (format!("{problem}1"), "1")] {
            let (Some(time), Some(error)) = (
                number(ours, &format!("{prefix}_r{restarts}_seconds")),
                number(ours, &format!("{prefix}_r{restarts}_error")),
            ) else {
                continue;
            };
            let default = if restarts == Options::default().restarts {
                ", default options"
            } else if restarts == 0 && problem == "fg" {
                " (Freudenstein's least-squares start only)"
            } else {
                ""
            };
            let dims = ours
                .get(&format!("{prefix}_r{restarts}_lengths"))
                .or_else(|| ours.get(&format!("{prefix}_r{restarts}_dimensions")))
                .cloned()
                .unwrap_or_default();
            rows.push(single(
                format!("mechgen, {restarts} restarts{default}, {cores} thread(s)"),
                time,
                error,
                threshold,
                format!("found {dims}"),
            ));
        }
    }
    for (prefix, cores) in [
        (format!("{problem}s"), threads),
        (format!("{problem}s1"), "1"),
    ] {
        let (Some(time), Some(error)) = (
            number(ours, &format!("{prefix}_seconds")),
            number(ours, &format!("{prefix}_error")),
        ) else {
            continue;
        };
        rows.push(single(
            format!(
                "mechgen, default options stopping once within the threshold, {cores} thread(s)"
            ),
            time,
            error,
            threshold,
            format!(
                "`good_enough`: Freudenstein's least squares within it as it is, no polish and \
                 no restarts; found {}",
                ours.get(&format!("{prefix}_lengths"))
                    .cloned()
                    .unwrap_or_default()
            ),
        ));
    }
    if let (Some(time), Some(error)) = (
        number(py, &format!("{problem}_classical_seconds")),
        number(py, &format!("{problem}_classical_error")),
    ) {
        let note = match problem {
            "fg" => format!(
                "Freudenstein least squares (`function_generation`); found {}",
                py.get("fg_classical_lengths").cloned().unwrap_or_default()
            ),
            _ => format!(
                "Burmester (`path_generation_with_timing`); {} solutions",
                py.get("pg_classical_solutions")
                    .cloned()
                    .unwrap_or_default()
            ),
        };
        rows.push(single(
            "pylinkage, classical synthesis".into(),
            time,
            error,
            threshold,
            note,
        ));
    }
    for (name, method) in [("pso", "particle swarm"), ("de", "differential evolution")] {
        let key = |k: &str| format!("{problem}_{name}_{k}");
        let (Some(at_budget), Some(best)) = (
            number(py, &key("error_at_budget")),
            number(py, &key("best_error")),
        ) else {
            continue;
        };
        rows.push(Row {
            method: format!("pylinkage, {method}"),
            to_threshold: number(py, &key("seconds_to_threshold")),
            at_budget,
            best,
            note: format!(
                "median of {} runs, {} reached the threshold (times in s: {}); {} evaluations \
                 in {} s",
                py.get(&key("runs")).cloned().unwrap_or_default(),
                py.get(&key("reached")).cloned().unwrap_or_default(),
                py.get(&key("seconds_to_threshold_all"))
                    .cloned()
                    .unwrap_or_default(),
                py.get(&key("evaluations")).cloned().unwrap_or_default(),
                py.get(&key("run_seconds")).cloned().unwrap_or_default()
            ),
        });
    }
    rows
}

/// A ratio to two significant figures.
fn ratio(r: f64) -> String {
    if r >= 10.0 {
        format!("{r:.0}")
    } else if r >= 1.0 {
        format!("{r:.1}")
    } else if r >= 0.1 {
        format!("{r:.2}")
    } else {
        format!("{r:.3}")
    }
}

/// One problem's headline: each of pylinkage's methods against our default options (one
/// thread) and against our fastest run that reaches the threshold.
fn summary(name: &str, rows: &[Row], ours: f64, unit: &str) -> String {
    let fastest = rows
        .iter()
        .filter(|r| r.method.starts_with("mechgen"))
        .filter_map(|r| Some((r.to_threshold?, r)))
        .min_by(|a, b| a.0.total_cmp(&b.0));
    let mut out = format!(
        "- {name}: mechgen with its default options takes {}",
        seconds(ours)
    );
    if let Some((t, row)) = fastest {
        write!(
            out,
            " (its fastest run to the threshold: {}, {})",
            seconds(t),
            row.method
        )
        .unwrap();
    }
    out.push_str(". ");
    let mut parts = Vec::new();
    for row in rows.iter().filter(|r| r.method.starts_with("pylinkage")) {
        let method = row.method.trim_start_matches("pylinkage, ");
        parts.push(match row.to_threshold {
            Some(t) => {
                let mut part = format!("pylinkage's {method} takes {}× as long", ratio(t / ours));
                if let Some((fast, _)) = fastest {
                    write!(part, " ({}× our fastest)", ratio(t / fast)).unwrap();
                }
                part
            }
            None if row.best.is_finite() => format!(
                "pylinkage's {method} never reaches the threshold (best {:.2e} {unit})",
                row.best
            ),
            None => format!("pylinkage's {method} finds no linkage"),
        });
    }
    out.push_str(&parts.join("; "));
    out.push_str(".\n");
    out
}

fn write() -> Result<(), Failure> {
    let commit = commit();
    eprintln!("== our side");
    let ours = measure()?;
    let py = pylinkage()?;
    let threads = ours.get("threads").cloned().unwrap_or_default();
    let mut out = format!(
        "# Synthesis and tolerance analysis against pylinkage\n\n\
         One function-generation and one path-generation problem, solved by this project's \
         `mechanisms::synthesis` (Levenberg–Marquardt on the generated derivatives, random \
         restarts in parallel) and by [pylinkage](https://pypi.org/project/pylinkage/) ({}): \
         its classical synthesis, its particle swarm and its differential evolution; then a \
         tolerance analysis, our first-order worst case and root-sum-square against a Monte \
         Carlo on pylinkage's kinematics. Every figure comes from one command, run from the \
         repository at commit `{commit}` on {}:\n\n```sh\ntests/reference/setup-pylinkage.sh   # once\n{WRITE_COMMAND}\n```\n\n\
         Our side is `tests/src/bin/synthesis.rs`, pylinkage's `{SCRIPT}`; both print `key value` \
         lines. The machine was shared with other jobs: times are the best of several runs for \
         single calls, the median of {} runs for the optimisers.\n",
        py.get("versions").cloned().unwrap_or_default(),
        machine(),
        py.get("runs").cloned().unwrap_or_default(),
    );
    out.push_str(&format!(
        "\n## How it is measured\n\n\
         - **Time to threshold**: for our synthesis and pylinkage's classical synthesis, one \
         call's wall time (best of several), counted if the error of the linkage it returns is \
         within the threshold; for pylinkage's optimisers, the time from the start of a run to \
         the first objective evaluation within the threshold (each run stops at {} s, or once \
         past the budget with the threshold reached).\n\
         - **Best error within {BUDGET} s**: for a single call, its error if it returns within \
         the budget; for an optimiser, the best objective value evaluated within it (the \
         median over its runs). \"Best rms error reached\" is the best over all runs.\n\
         - Errors are recomputed by each side from the linkage found: here with \
         `FourBar::assemble`/`points`, in Python with pylinkage's `circle_intersect`.\n\
         - The optimisers use pylinkage's `particle_swarm_optimization` (100 particles, its \
         defaults otherwise) and `differential_evolution_optimization` (scipy's, its defaults \
         with `tol = 0`), through pylinkage's `eval_func` interface. The objective evaluates \
         the four-bar with pylinkage's numba-compiled `circle_intersect` directly, not by \
         stepping a `Linkage` through its simulation: cheaper per evaluation, so generous to \
         pylinkage. A linkage that does not assemble at a target scores {}.\n\
         - Our rows on {threads} thread(s) use every core (rayon); the 1-thread rows run the same \
         call in a one-thread pool, the fair comparison with single-threaded Python. The \
         ratio \"× ours\" divides by mechgen's default options on one thread.\n",
        py.get("cap_seconds").cloned().unwrap_or_default(),
        "10⁶",
    ));

    let ratio_base = |problem: &str| {
        number(
            &ours,
            &format!("{problem}1_r{}_seconds", Options::default().restarts),
        )
        .unwrap_or(f64::NAN)
    };
    let fg_rows = rows(&ours, &py, "fg", FG_THRESHOLD, &threads);
    let pg_rows = rows(&ours, &py, "pg", PG_THRESHOLD, &threads);
    out.push_str("\n## Summary\n\nTimes to the threshold, our default options on one thread against each of pylinkage's methods (the aim: at least 10× faster at equal error):\n\n");
    out.push_str(&summary(
        "Function generation",
        &fg_rows,
        ratio_base("fg"),
        "rad",
    ));
    out.push_str(&summary(
        "Path generation with timing",
        &pg_rows,
        ratio_base("pg"),
        "mm",
    ));
    out.push_str(&tolerance_summary(&ours, &py));
    out.push_str(&format!(
        "\n## Function generation\n\n\
         Ground 180 mm, crank pivot at the origin, rocker pivot at (180, 0); wanted rocker \
         angles θ4 (degrees from the ground line, counter-clockwise) at crank angles θ2 = \
         {FG_CRANK:?}°: {FG_ROCKER:?}°, the open-branch outputs of the 180/80/200/150 four-bar \
         to four decimals, so the answer is crank 80, coupler 200, rocker 150. The unknowns are \
         the crank, coupler and rocker (pylinkage's optimisers search each within [1, 500] mm). \
         Error: rms of the rocker angle errors, radians. The four-decimal rounding of the \
         targets leaves the exact answer an rms error of {} rad (the best least-squares fit \
         slightly less): the threshold is {FG_THRESHOLD:.0e} rad.\n\n",
        ours.get("fg_error_of_exact_answer")
            .cloned()
            .unwrap_or_default()
    ));
    out.push_str(&table(&fg_rows, ratio_base("fg"), "rad", FG_THRESHOLD));

    out.push_str(&format!(
        "\n## Path generation with prescribed timing\n\n\
         The coupler point of the same four-bar, 100 mm from the crank pin at 30° from the \
         coupler line, at crank angles {PG_TIMING:?} rad (the targets, in mm, are constants \
         in both programs, checked here against `FourBar::points`). The unknowns are nine: \
         the crank pivot and the ground line's angle, the four lengths and the coupler point's \
         distance and angle (pylinkage's optimisers search the pivot within ±300 mm, the \
         lengths within [1, 500] mm, the angles within ±π). Error: rms distance from the \
         targets, mm; threshold {PG_THRESHOLD:.0e} mm. pylinkage's \
         `path_generation_with_timing` takes the same points and crank angles.\n\n"
    ));
    out.push_str(&table(&pg_rows, ratio_base("pg"), "mm", PG_THRESHOLD));

    out.push_str(&tolerance_section(&ours, &py));
    out.push_str(
        "\n## What this does not show\n\n\
         - pylinkage's classical function generation is Freudenstein's equation solved as one \
         linear least-squares problem: closed form, and faster than our default options, \
         which polish the same least-squares solution and 64 random starts by \
         Levenberg–Marquardt on the angles themselves. Our run without restarts, and our \
         default options told to stop once within the threshold (`good_enough`), do the same \
         work as pylinkage's plus the polish, and are the fair comparison with it; the \
         restarts buy robustness on targets no four-bar meets exactly, which this problem \
         does not test.\n\
         - pylinkage's `path_generation_with_timing` found no linkage for these six timed \
         points. It turns the crank-angle differences \
         into the coupler's rotations between poses and solves Burmester's problem on those \
         poses; a four-bar's coupler does not turn with its crank, so these poses belong to no \
         four-bar of this kind.\n\
         - An optimiser's time to the threshold moves a lot from run to run (its runs' times \
         are in the notes; pylinkage's particle swarm draws from an unseeded generator), far \
         more than the single calls' best-of-several times do.\n\
         - The problems are small and exactly solvable. Nothing here measures targets no \
         four-bar meets, path generation without timing, or constraints (crank, \
         transmission angle).\n",
    );
    out.push_str(&format!(
        "\n<sub>Made at commit `{commit}` by `{WRITE_COMMAND}`.</sub>\n"
    ));
    std::fs::write(REPORT, out).map_err(|e| format!("{REPORT}: {e}"))?;
    eprintln!("wrote {REPORT}");
    Ok(())
}

fn tolerance_summary(ours: &Values, py: &Values) -> String {
    let get = |v: &Values, k: &str| number(v, k).unwrap_or(f64::NAN);
    let linear = get(ours, "tol_linear_seconds");
    let off = |a: f64, b: f64| format!("{:+.1}%", (a / b - 1.0) * 100.0);
    format!(
        "- Tolerance analysis: the first-order worst case and root-sum-square take {}; a \
         10000-sample Monte Carlo on pylinkage's kinematics takes {}× as long per estimate, \
         and its estimates differ from ours by {} (θ4 worst case, uniform sampling: it falls \
         short of the corners) and {} (θ4 RSS); our worst case differs by {} from the exact \
         nonlinear worst corner.\n",
        seconds(linear),
        ratio(get(py, "mc10000_seconds") / linear),
        off(
            get(py, "mc10000_output_largest_uniform"),
            get(ours, "tol_output_worst_case")
        ),
        off(
            get(py, "mc10000_output_3rms_normal"),
            get(ours, "tol_output_rss")
        ),
        off(
            get(ours, "tol_output_worst_case"),
            get(ours, "tol_corners_output_largest")
        ),
    )
}

fn tolerance_section(ours: &Values, py: &Values) -> String {
    let get = |v: &Values, k: &str| number(v, k).unwrap_or(f64::NAN);
    let mut out = format!(
        "\n## Tolerance analysis\n\n\
         The same four-bar with its coupler point at 100 mm, 30°, every length (ground, crank, \
         coupler, rocker, coupler point distance) ±{TOLERANCE} mm, at θ2 = \
         {TOLERANCE_THETA2_DEGREES}°: the deviation of the output θ4 and of the coupler point. \
         Ours: `FourBar::tolerance`, first order from the generated sensitivities: the worst \
         case (Σ|∂/∂l|·t) and the root-sum-square stack-up. pylinkage's `analyze_tolerance` \
         samples a whole turn of its simulation and reports path deviations, not the deviation \
         at one crank angle, so the Monte Carlo here is numpy sampling with pylinkage's \
         `circle_intersect`: uniform errors within ±t, whose largest deviation approaches the \
         worst case from below, and normal errors with σ = t/3, whose rms deviation × 3 \
         estimates the root-sum-square. Our `FourBar::corners` (the nonlinear model at the 32 \
         corners) and `FourBar::monte_carlo` are shown as the nonlinear checks.\n\n\
         | method | θ4 worst case (°) | θ4 RSS (°) | P worst case (mm) | P RSS (mm) | time |\n\
         |---|---:|---:|---:|---:|---:|\n"
    );
    let deg = f64::to_degrees;
    writeln!(
        out,
        "| mechgen, first order (`tolerance`) | {:.5} | {:.5} | {:.5} | {:.5} | {} |",
        deg(get(ours, "tol_output_worst_case")),
        deg(get(ours, "tol_output_rss")),
        get(ours, "tol_point_worst_case"),
        get(ours, "tol_point_rss"),
        seconds(get(ours, "tol_linear_seconds")),
    )
    .unwrap();
    writeln!(
        out,
        "| mechgen, 32 corners (`corners`) | {:.5} | | {:.5} | | {} |",
        deg(get(ours, "tol_corners_output_largest")),
        get(ours, "tol_corners_point_largest"),
        seconds(get(ours, "tol_corners_seconds")),
    )
    .unwrap();
    writeln!(
        out,
        "| mechgen, Monte Carlo 100000 normal (`monte_carlo`) | | {:.5} | | {:.5} | {} |",
        deg(get(ours, "tol_mc100000_output_3rms")),
        get(ours, "tol_mc100000_point_3rms"),
        seconds(get(ours, "tol_mc100000_seconds")),
    )
    .unwrap();
    for samples in [1000, 10_000, 100_000] {
        let key = |k: &str| format!("mc{samples}_{k}");
        writeln!(
            out,
            "| pylinkage kinematics, Monte Carlo {samples} uniform + {samples} normal | {:.5} | \
             {:.5} | {:.5} | {:.5} | {} per set |",
            deg(get(py, &key("output_largest_uniform"))),
            deg(get(py, &key("output_3rms_normal"))),
            get(py, &key("point_largest_uniform")),
            get(py, &key("point_3rms_normal")),
            seconds(get(py, &key("seconds"))),
        )
        .unwrap();
    }
    out
}

fn main() {
    // Paths are relative to the repository root, wherever this is run from.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the tests crate sits in the repository");
    std::env::set_current_dir(root).expect("the repository root is a directory");
    let result = match std::env::args().nth(1).as_deref() {
        None => measure().map(|_| ()),
        Some("write") => write(),
        _ => {
            eprintln!(
                "usage: synthesis [write]\n  (none)  time our synthesis and tolerance analysis, print `key value` lines\n  write   also run {SCRIPT} and write {REPORT}"
            );
            std::process::exit(2);
        }
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
