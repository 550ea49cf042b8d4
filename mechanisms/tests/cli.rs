//! The command-line program end to end: its default report, its errors, and the files a
//! sweep writes.

use assert_cmd::Command;

fn program() -> Command {
    Command::cargo_bin("mechanisms").expect("the program is built")
}

fn stdout_of(args: &[&str]) -> String {
    let output = program().args(args).output().unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).unwrap()
}

#[test]
fn the_default_report_is_the_seeds_example_1() {
    let report = stdout_of(&[]);
    for value in [
        "156.2050",
        "50.5800",
        "72.1377",
        "235.2033",
        "21.5576",
        "crank-rocker",
    ] {
        assert!(report.contains(value), "{value} missing from:\n{report}");
    }
}

#[test]
fn trace_prints_the_newton_iterates_of_example_2() {
    let report = stdout_of(&[
        "analyse", "four-bar", "180", "80", "200", "150", "--trace", "--guess", "15,80",
    ]);
    // The first residual and the converged angles of the notes' Example 2.
    for value in ["27.137939", "-26.675322", "21.557635", "72.137650"] {
        assert!(report.contains(value), "{value} missing from:\n{report}");
    }
}

/// Runs the program and checks it fails with exit code `code` (1 for the program's own
/// errors, 2 for arguments clap cannot parse) and `message` on standard error.
fn fails_with_code(args: &[&str], code: i32, message: &str) {
    let output = program().args(args).output().unwrap();
    assert_eq!(output.status.code(), Some(code), "{args:?}");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains(message), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
}

fn fails_with(args: &[&str], message: &str) {
    fails_with_code(args, 1, message);
}

#[test]
fn bad_input_is_a_clear_message_and_a_failure() {
    fails_with_code(
        &["analyse", "four-bar", "180", "abc", "200", "150"],
        2,
        "invalid value 'abc'",
    );
    fails_with(
        &["analyse", "four-bar", "180", "-80", "200", "150"],
        "crank = -80 must be positive and finite",
    );
    fails_with(
        &[
            "analyse", "four-bar", "100", "120", "90", "80", "--at", "150",
        ],
        "cannot be assembled at 150°: the crank reaches |θ2| from 0.00° to 100.81°",
    );
    fails_with_code(
        &["analyse", "hexapod", "1", "2"],
        2,
        "invalid value 'hexapod'",
    );
    fails_with(
        &["analyse", "four-bar", "180", "80"],
        "four-bar takes 4 dimensions",
    );
    fails_with(
        &[
            "sweep", "four-bar", "180", "80", "200", "150", "--step", "0",
        ],
        "--step must be a positive",
    );
}

/// A temporary directory of the test's own, removed when dropped.
struct Scratch(std::path::PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let path = std::env::temp_dir().join(format!("mechanisms-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&path).ok();
        Scratch(path)
    }

    fn path(&self) -> &str {
        self.0.to_str().unwrap()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

const EXAMPLE_1: [&str; 5] = ["four-bar", "180", "80", "200", "150"];

fn with(head: &[&str], tail: &[&str]) -> Vec<String> {
    head.iter().chain(tail).map(|s| s.to_string()).collect()
}

fn strings(args: &[String]) -> Vec<&str> {
    args.iter().map(String::as_str).collect()
}

#[test]
fn a_sweep_too_long_is_refused_naming_max_samples_before_it_starts() {
    for step in ["1e-6", "1e-12", "1e-300", "5e-324"] {
        let args = with(&["sweep"], &EXAMPLE_1);
        let args = with(&strings(&args), &["--step", step]);
        fails_with(&strings(&args), "--max-samples");
    }
    for step in ["0", "-1", "inf", "nan"] {
        let args = with(&["sweep"], &EXAMPLE_1);
        let args = with(&strings(&args), &["--step", step]);
        fails_with(&strings(&args), "--step must be a positive, finite number");
    }
    // A larger limit lets it through.
    let scratch = Scratch::new("max-samples");
    let args = with(&["sweep"], &EXAMPLE_1);
    let args = with(
        &strings(&args),
        &[
            "--step",
            "0.01",
            "--max-samples",
            "36001",
            "--out-dir",
            scratch.path(),
        ],
    );
    assert!(stdout_of(&strings(&args)).contains("36001 samples"));
    fails_with(
        &strings(&with(
            &strings(&args[..args.len() - 4]),
            &["--max-samples", "36000"],
        )),
        "more than --max-samples 36000",
    );
}

#[test]
fn analyse_prints_only_values_the_library_vouched_for() {
    // A zero-length slide at 360°: its direction, and every rate, is undetermined.
    let report = stdout_of(&[
        "analyse",
        "inverted-slider-crank",
        "150",
        "150",
        "0",
        "0",
        "--at",
        "360",
    ]);
    assert!(report.contains("undetermined"), "{report}");
    assert!(!report.contains("12.5"), "{report}");
    assert!(
        !report.contains("NaN") && !report.contains("inf"),
        "{report}"
    );
    // A parallelogram at its flat position: the positions, and `singular` for the rates.
    let report = stdout_of(&["analyse", "four-bar", "100", "50", "100", "50", "--at", "0"]);
    assert!(report.contains("singular"), "{report}");
    // Nothing can be computed: a failure.
    fails_with(
        &["analyse", "slider-crank", "200", "50", "0", "--at", "90"],
        "cannot be assembled at 90°",
    );
    fails_with(
        &[
            "analyse", "four-bar", "180", "80", "200", "150", "--trace", "--guess", "nan,80",
        ],
        "--guess takes two finite angles",
    );
}

#[test]
fn huge_dimensions_are_named_rightly_and_never_contradict_themselves() {
    let report = stdout_of(&["analyse", "four-bar", "1e308", "1e308", "1e308", "1e308"]);
    assert!(report.contains("ground 1e308 mm"), "{report}");
    assert!(report.contains("the crank turns fully"), "{report}");
    assert!(!report.contains("cannot be assembled"), "{report}");
    assert!(report.contains("not finite"), "{report}");
    for (k, name) in ["ground", "crank", "coupler", "rocker"]
        .into_iter()
        .enumerate()
    {
        let mut args = vec!["analyse", "four-bar", "180", "80", "200", "150"];
        args[2 + k] = "1e308";
        fails_with(&args, &format!("{name} = 1e308 must be shorter"));
    }
}

#[test]
fn negative_and_non_finite_numbers_are_values_not_flags() {
    let trace = |guess: &str| {
        let args = with(&["analyse"], &EXAMPLE_1);
        stdout_of(&strings(&with(
            &strings(&args),
            &["--trace", "--guess", guess],
        )))
    };
    assert!(trace("15,80").contains("72.137650"));
    assert!(trace("-15,80").contains("Newton-Raphson from θ3 = -15°"));
    let args = with(&["analyse"], &EXAMPLE_1);
    fails_with(
        &strings(&with(&strings(&args), &["--trace", "--guess", "15", "80"])),
        "--guess takes two angles joined by a comma",
    );
    assert!(
        stdout_of(&strings(&with(&strings(&args), &["--accel", "-5"]))).contains("α2 = -5 rad/s²")
    );
    fails_with(
        &strings(&with(&strings(&args), &["--accel", "-inf"])),
        "--accel must be a finite number of rad/s², got -inf",
    );
    let sweep = with(&["sweep"], &EXAMPLE_1);
    fails_with(
        &strings(&with(&strings(&sweep), &["--rate", "inf"])),
        "--rate must be a finite number of rad/s, got inf",
    );
}

#[test]
fn flags_that_do_not_apply_are_errors() {
    fails_with(
        &["analyse", "slider-crank", "50", "150", "0", "--trace"],
        "--trace applies to the four-bar only, not the slider-crank",
    );
    fails_with(
        &[
            "analyse", "four-bar", "180", "80", "200", "150", "--guess", "15,80",
        ],
        "--guess is Newton's start for --trace",
    );
    fails_with(
        &[
            "sweep",
            "inverted-slider-crank",
            "150",
            "60",
            "20",
            "10",
            "--coupler-point",
            "10,0",
        ],
        "--coupler-point applies to the four-bar and the slider-crank, not the inverted-slider-crank",
    );
    fails_with(
        &["sweep", "jansen", "--branch", "crossed"],
        "--branch does not apply to Jansen's leg",
    );
}

#[test]
fn numbers_print_tidily() {
    let args = with(&["analyse"], &EXAMPLE_1);
    let report = stdout_of(&strings(&with(
        &strings(&args),
        &["--at", "29.999999999999996"],
    )));
    assert!(report.contains("θ2 = 30°"), "{report}");
    assert!(
        !report.contains("360.0000") && !report.contains("-0.0000"),
        "{report}"
    );
    let scratch = Scratch::new("tidy");
    let args = with(&["sweep"], &EXAMPLE_1);
    let summary = stdout_of(&strings(&with(
        &strings(&args),
        &["--step", "0.1", "--out-dir", scratch.path()],
    )));
    assert!(
        summary.contains("3601 samples from 0° to 360°"),
        "{summary}"
    );
    let table = std::fs::read_to_string(scratch.0.join("sweep.csv")).unwrap();
    assert!(
        table.lines().any(|line| line.starts_with("0.3,1,")),
        "{table:.400}"
    );
}

#[test]
fn a_sweep_writes_its_table_to_standard_output_for_a_dash_and_files_into_out_dir() {
    let scratch = Scratch::new("out-dir");
    let out_dir = scratch.0.join("new").join("dir");
    let args = with(&["sweep"], &EXAMPLE_1);
    let output = program()
        .args(strings(&with(
            &strings(&args),
            &[
                "--step",
                "90",
                "--csv",
                "-",
                "--out-dir",
                out_dir.to_str().unwrap(),
            ],
        )))
        .output()
        .unwrap();
    assert!(output.status.success());
    let table = String::from_utf8(output.stdout).unwrap();
    assert!(table.starts_with("input_deg,segment,theta3_deg"), "{table}");
    assert_eq!(table.lines().count(), 1 + 5, "{table}");
    // The summary goes to standard error, out of the table's way.
    assert!(String::from_utf8_lossy(&output.stderr).contains("5 samples in 1 piece"));
    assert!(out_dir.join("sweep.svg").exists() && out_dir.join("animation.svg").exists());
    assert!(!out_dir.join("-").exists() && !std::path::Path::new("-").exists());
}

/// The rows of a sweep's table: (input, segment).
fn sweep_rows(dimensions: &[&str], scratch: &Scratch) -> (String, Vec<(f64, u32)>) {
    let args = with(&["sweep"], dimensions);
    let summary = stdout_of(&strings(&with(
        &strings(&args),
        &["--out-dir", scratch.path()],
    )));
    let table = std::fs::read_to_string(scratch.0.join("sweep.csv")).unwrap();
    let rows = table
        .lines()
        .skip(1)
        .map(|line| {
            let mut cells = line.split(',');
            let input = cells.next().unwrap().parse().unwrap();
            (input, cells.next().unwrap().parse().unwrap())
        })
        .collect();
    (summary, rows)
}

/// The lines the charts draw for their series (the only polylines two pixels wide): one per
/// series and reachable piece where nothing inside a piece fails.
fn series_lines_drawn(scratch: &Scratch) -> usize {
    let charts = std::fs::read_to_string(scratch.0.join("sweep.svg")).unwrap();
    let document = roxmltree::Document::parse(&charts).unwrap();
    document
        .descendants()
        .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke-width") == Some("2"))
        .count()
}

#[test]
fn a_crank_that_cannot_turn_fully_is_swept_over_its_reachable_pieces() {
    // A triple-rocker: one piece through 0°, |θ2| up to 100.81°, swept whole.
    let scratch = Scratch::new("triple-rocker");
    let (summary, rows) = sweep_rows(&["four-bar", "100", "120", "90", "80"], &scratch);
    assert!(summary.contains("1 piece"), "{summary}");
    assert!(
        summary.contains("piece 1: -100.81° to 100.81°"),
        "{summary}"
    );
    assert!(!summary.contains("not computed"), "{summary}");
    assert_eq!(rows.len(), 201);
    assert!(
        rows.iter()
            .all(|&(input, segment)| input.abs() < 100.81 && segment == 1)
    );
    // A rocker-crank: two mirror-image pieces between its toggles, each drawn on its own.
    let scratch = Scratch::new("rocker-crank");
    let (summary, rows) = sweep_rows(&["four-bar", "180", "150", "200", "80"], &scratch);
    assert!(summary.contains("2 pieces"), "{summary}");
    assert!(rows.iter().any(|r| r.1 == 1) && rows.iter().any(|r| r.1 == 2));
    for window in rows.windows(2) {
        assert!(window[0].0 < window[1].0, "inputs in order: {window:?}");
    }
    // θ3, θ4, ω3, ω4, α3, α4 and the transmission angle, each piece a line of its own.
    assert_eq!(series_lines_drawn(&scratch), 2 * 7);
    // A slider-crank whose rod is shorter than its crank: two pieces, nothing between.
    let scratch = Scratch::new("slider-crank");
    let (summary, rows) = sweep_rows(&["slider-crank", "200", "50", "0"], &scratch);
    assert!(summary.contains("piece 1: -14.48° to 14.48°"), "{summary}");
    assert!(summary.contains("piece 2: 165.52° to 194.48°"), "{summary}");
    assert!(
        rows.iter()
            .all(|&(input, _)| input.abs() < 14.48 || (165.52..194.48).contains(&input))
    );
}

#[test]
fn a_linkage_with_singular_positions_still_sweeps_and_counts_them() {
    // A parallelogram is flat, and singular, at 0° and 180°.
    let scratch = Scratch::new("parallelogram");
    let (summary, rows) = sweep_rows(&["four-bar", "100", "50", "100", "50"], &scratch);
    assert!(summary.contains("3 not computed (3 singular)"), "{summary}");
    assert_eq!(rows.len(), 361 - 3);
}

#[test]
fn a_sweep_writes_csv_charts_and_an_animation() {
    let directory = std::env::temp_dir().join(format!("mechanisms-cli-{}", std::process::id()));
    std::fs::create_dir_all(&directory).unwrap();
    let (csv, charts, animation) = (
        directory.join("s.csv"),
        directory.join("s.svg"),
        directory.join("a.svg"),
    );
    let arguments = [
        "sweep",
        "four-bar",
        "180",
        "80",
        "200",
        "150",
        "--step",
        "30",
        "--coupler-point",
        "100,30",
        "--csv",
        csv.to_str().unwrap(),
        "--svg",
        charts.to_str().unwrap(),
        "--animation",
        animation.to_str().unwrap(),
    ];
    stdout_of(&arguments);
    let charts = std::fs::read_to_string(&charts).unwrap();
    let document = roxmltree::Document::parse(&charts).expect("the charts are well-formed XML");
    let texts: Vec<&str> = document
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .map(str::trim)
        .collect();
    // A chart per unit, each titled, with its unit on the y-axis and its series' symbols in
    // the legend, in order.
    let legend: Vec<&str> = texts
        .iter()
        .copied()
        .filter(|t| ["θ3", "θ4", "ω3", "ω4", "α3", "α4", "μ"].contains(t))
        .collect();
    assert_eq!(legend, ["θ3", "θ4", "ω3", "ω4", "α3", "α4", "μ"]);
    for text in [
        "output angles (°)",
        "angular velocities (rad/s)",
        "angle (°)",
        "rad/s",
        "rad/s²",
        "input angle (°)",
    ] {
        assert!(texts.contains(&text), "{text} in {texts:?}");
    }
    // Ticks: more than the ends of each axis are labelled.
    assert!(texts.iter().filter(|t| t.parse::<f64>().is_ok()).count() > 4 * 8);
    let animation = std::fs::read_to_string(&animation).unwrap();
    let document =
        roxmltree::Document::parse(&animation).expect("the animation is well-formed XML");
    assert_eq!(
        document
            .descendants()
            .filter(|n| n.has_tag_name("line"))
            .count(),
        5
    );
    assert_eq!(
        document
            .descendants()
            .filter(|n| n.has_tag_name("animate"))
            .count(),
        20
    );
    assert!(
        document
            .descendants()
            .any(|n| n.attribute("class") == Some("coupler-curve"))
    );
    // The two ground pivots, O2 and O4, each drawn grounded.
    for class in ["ground", "pivot"] {
        assert_eq!(
            document
                .descendants()
                .filter(|n| n.attribute("class") == Some(class))
                .count(),
            2
        );
    }
    let table = std::fs::read_to_string(&csv).unwrap();
    std::fs::remove_dir_all(&directory).ok();
    insta::with_settings!({
        snapshot_path => "../../tests/snapshots/cli",
        prepend_module_to_snapshot => false,
        omit_expression => true,
    }, {
        insta::assert_snapshot!("four_bar_sweep_csv", table);
    });
}
