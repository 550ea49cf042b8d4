//! The command-line program end to end: its default report, its errors, and the files a
//! sweep writes.

use assert_cmd::Command;
use mechgen::Branch;

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
    assert!(report.trim_end().ends_with("converged"), "{report}");
}

/// A trace that does not converge says so, and its iterates stay within half a turn: from
/// θ3 = θ4 = 100° the first steps threw θ3 to −1.3e18°, where a float holds a direction to
/// 256°, and the trace ended after 20 steps without a word.
#[test]
fn a_trace_that_does_not_converge_says_so_and_keeps_its_angles_within_a_turn() {
    let report = stdout_of(&[
        "analyse", "four-bar", "180", "80", "200", "150", "--trace", "--guess", "100,100",
    ]);
    assert!(
        report
            .trim_end()
            .ends_with("not converged in 20 steps: stopped"),
        "{report}"
    );
    let steps: Vec<Vec<f64>> = report
        .lines()
        .skip_while(|line| !line.contains("step"))
        .skip(1)
        .map_while(|line| {
            let cells: Option<Vec<f64>> = line.split_whitespace().map(|c| c.parse().ok()).collect();
            cells
        })
        .collect();
    assert_eq!(steps.len(), 21, "{report}");
    for step in &steps {
        assert!(step[1].abs() <= 180.0 && step[2].abs() <= 180.0, "{report}");
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

/// Help and the version go to standard output with exit 0, and fail as any report does where
/// standard output cannot take them (before, clap's printing ignored the full disk: exit 0).
#[test]
fn help_that_cannot_be_written_is_a_failure() {
    for args in [&["--help"][..], &["--version"], &["sweep", "--help"]] {
        let written = program().args(args).output().unwrap();
        assert!(written.status.success(), "{args:?}");
        assert!(!written.stdout.is_empty(), "{args:?}");
        if std::path::Path::new("/dev/full").exists() {
            let full = std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .unwrap();
            let output = std::process::Command::new(assert_cmd::cargo::cargo_bin("mechanisms"))
                .args(args)
                .stdout(full)
                .output()
                .unwrap();
            assert_eq!(output.status.code(), Some(1), "{args:?}");
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert!(
                stderr.contains("cannot write to standard output"),
                "{args:?}: {stderr}"
            );
        }
    }
    // A usage error is still clap's, with its exit code.
    fails_with_code(&["--bogus"], 2, "unexpected argument '--bogus'");
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
        "cannot be assembled at 150°: the crank reaches |θ2| up to 100.81° (toggles at ±100.81°)",
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
    // A slide of zero length to rounding, a hair past 0°: its direction, and every rate, is
    // undetermined. (At 360°, exactly 0° once the whole turn is taken off, the slide is of
    // zero length exactly and the position itself singular, as at 0°.)
    let report = stdout_of(&[
        "analyse",
        "inverted-slider-crank",
        "150",
        "150",
        "0",
        "0",
        "--at",
        "1e-13",
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
    // Its rates and accelerations, computed on the linkage scaled to size 1 (a length times a
    // squared rate overflowed on the way, and they were "not finite"): a parallelogram's.
    assert!(!report.contains("not finite"), "{report}");
    assert_eq!(cells(&report, "ω4 (rad/s)"), [10.0, 0.0], "{report}");
    assert_eq!(cells(&report, "α3 (rad/s²)"), [0.0, 0.0], "{report}");
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
    // A dimension of −∞ or NaN however written: the program's refusal, not clap's (exit 2,
    // "unexpected argument '-i'").
    for ground in ["-inf", "-nan", "inf"] {
        fails_with(
            &["analyse", "four-bar", ground, "80", "200", "150"],
            "ground",
        );
    }
}

#[test]
fn flags_that_do_not_apply_are_errors() {
    fails_with(
        &["analyse", "slider-crank", "50", "150", "0", "--trace"],
        "--trace applies to the four-bar and the stephenson-six-bar (Newton-Raphson), not the slider-crank",
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
    // A parallelogram is flat, and singular, at 0° and 180°: change points, past which the
    // motion goes on on the other closed-form branch.
    let scratch = Scratch::new("parallelogram");
    let (summary, rows) = sweep_rows(&["four-bar", "100", "50", "100", "50"], &scratch);
    assert!(summary.contains("3 not computed (3 singular)"), "{summary}");
    assert!(
        summary.contains("crossed change points at 180°, 360° onto the other branch"),
        "{summary}"
    );
    assert_eq!(rows.len(), 361 - 3);
    // It stays a parallelogram all the way round: the rocker turns with the crank, θ4 = θ2
    // (where the open branch alone would fold into the antiparallelogram past 180°).
    for (input, theta4) in column(&scratch, 3) {
        let turned = (theta4 - input).rem_euclid(360.0);
        assert!(turned.min(360.0 - turned) < 1e-9, "θ4 {theta4} at {input}°");
    }
}

#[test]
fn change_points_are_crossed_on_the_branch_that_goes_on() {
    // A slider-crank with its rod as long as its crank: the rod stands square to the slide
    // at 90° and 270°. Crossing them, the slider's motion goes on smoothly.
    let scratch = Scratch::new("equal-crank-rod");
    let (summary, _) = sweep_rows(&["slider-crank", "50", "50", "0"], &scratch);
    assert!(
        summary.contains("crossed change points at 90°, 270° onto the other branch"),
        "{summary}"
    );
    let d = column(&scratch, 3);
    for pair in d.windows(2) {
        let ((a, x), (b, y)) = (pair[0], pair[1]);
        // At most the crank's and the rod's own motion in the step: no jump.
        assert!(
            (y - x).abs() <= 2.0 * 100.0 * (b - a).to_radians(),
            "d {x} → {y} at {a}°"
        );
    }
    // The isosceles inverted slider-crank passes through its change point at 0° and 360°.
    let scratch = Scratch::new("isosceles");
    let (summary, _) = sweep_rows(&["inverted-slider-crank", "150", "150", "0", "0"], &scratch);
    assert!(
        summary.contains("crossed change points at 360°"),
        "{summary}"
    );
    // A change-point four-bar passes through 0°, its toggles at ±114.32°, at any size: at
    // 1e308 mm rounding found a limit at 0°, and the sweep made two pieces, each said to end
    // at toggles, 0° one of them (the rocker's pin, whose x overflows near 0°, is not
    // computed there, which is so).
    for lengths in [
        ["10", "17", "8", "15"],
        ["1e307", "1.7e307", "8e306", "1.5e307"],
        ["1e308", "1.7e308", "8e307", "1.5e308"],
    ] {
        let scratch = Scratch::new("change-point-four-bar");
        let size = lengths[0];
        let (summary, _) = sweep_rows(&[&["four-bar"][..], &lengths].concat(), &scratch);
        for words in [
            "the crank reaches |θ2| up to 114.32° (toggles at ±114.32°)",
            "in 1 piece",
            "piece 1: -114.32° to 114.32° (toggles at the ends)",
            "crossed change points at 0° onto the other branch",
        ] {
            assert!(
                summary.contains(words),
                "{size}: {words} missing from {summary}"
            );
        }
    }
    // And a crank-rocker has none.
    let scratch = Scratch::new("crank-rocker");
    let (summary, _) = sweep_rows(&["four-bar", "180", "80", "200", "150"], &scratch);
    assert!(!summary.contains("change point"), "{summary}");
}

/// `(input, value)` of column `index` of a sweep's table.
fn column(scratch: &Scratch, index: usize) -> Vec<(f64, f64)> {
    let table = std::fs::read_to_string(scratch.0.join("sweep.csv")).unwrap();
    table
        .lines()
        .skip(1)
        .map(|line| {
            let cells: Vec<&str> = line.split(',').collect();
            (cells[0].parse().unwrap(), cells[index].parse().unwrap())
        })
        .collect()
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

// ---- the six-bars --------------------------------------------------------------------------

/// The documented Watt six-bar (`WattSixBar`'s example, its angle 0.8 rad in degrees), and
/// the library's own, to compare with.
fn watt_args(dimensions: [f64; 10]) -> Vec<String> {
    let mut args = vec!["watt-six-bar".to_string()];
    args.extend(dimensions.iter().map(|d| d.to_string()));
    args
}

const WATT: [f64; 10] = [
    180.0,
    80.0,
    200.0,
    150.0,
    100.0,
    45.836623610465864,
    220.0,
    160.0,
    300.0,
    150.0,
];

fn watt_library() -> mechanisms::WattSixBar<f64> {
    mechanisms::WattSixBar::new(
        [180.0, 80.0, 200.0, 150.0],
        100.0,
        0.8,
        220.0,
        160.0,
        (300.0, 150.0),
    )
    .unwrap()
}

/// The documented Stephenson six-bar (`examples::stephenson_six_bar`), its ternary angle of
/// −0.97 rad in degrees, with the crank `crank`.
fn stephenson_args(crank: f64) -> Vec<String> {
    let dimensions = [
        100.0,
        crank,
        117.0,
        60.0,
        63.0,
        (-0.97f64).to_degrees(),
        52.0,
        85.0,
        189.0,
        -26.0,
    ];
    let mut args = vec!["stephenson-six-bar".to_string()];
    args.extend(dimensions.iter().map(|d| d.to_string()));
    args
}

fn stephenson_library(crank: f64) -> mechanisms::StephensonSixBar<f64> {
    mechanisms::StephensonSixBar::new(
        100.0,
        crank,
        117.0,
        [60.0, 63.0],
        -0.97,
        52.0,
        85.0,
        (189.0, -26.0),
    )
    .unwrap()
}

/// The numbers in the analyse table's row labelled `label`, one per column.
fn cells(report: &str, label: &str) -> Vec<f64> {
    let line = report
        .lines()
        .find(|l| l.trim_start().starts_with(label))
        .unwrap_or_else(|| panic!("no row {label} in:\n{report}"));
    line.split_whitespace()
        .filter_map(|c| c.parse().ok())
        .collect()
}

/// `r @ θ°`.
fn polar(r: f64, degrees: f64) -> (f64, f64) {
    let t = degrees.to_radians();
    (r * t.cos(), r * t.sin())
}

fn plus(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 + b.0, a.1 + b.1)
}

fn meets(what: &str, a: (f64, f64), b: (f64, f64), within: f64) {
    let gap = (a.0 - b.0).hypot(a.1 - b.1);
    assert!(gap < within, "{what}: {a:?} and {b:?} are {gap} apart");
}

/// The Stephenson six-bar's joints from its angles in degrees, each loop closed from both
/// sides: B from A, C from B and from O4, D from C and from O6.
fn stephenson_closes(crank: f64, input: f64, angles: [f64; 4], within: f64) {
    let [t3, t4, t5, t6] = angles;
    let beta = (-0.97f64).to_degrees();
    let b = plus(polar(crank, input), polar(117.0, t3));
    let c = plus((100.0, 0.0), polar(52.0, t4));
    meets(
        &format!("C at {input}°"),
        plus(b, polar(60.0, t5)),
        c,
        within,
    );
    let d = plus(c, polar(63.0, t5 + beta));
    meets(
        &format!("D at {input}°"),
        d,
        plus((189.0, -26.0), polar(85.0, t6)),
        within,
    );
}

fn wrapped_difference(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    d.min(360.0 - d)
}

#[test]
fn analyse_solves_each_watt_branch_pair_with_both_loops_closed() {
    let report = stdout_of(&strings(&with(&["analyse"], &strings(&watt_args(WATT)))));
    let [t3, t4, t5, t6] = ["θ3 (°)", "θ4 (°)", "θ5 (°)", "θ6 (°)"].map(|l| cells(&report, l));
    assert_eq!(t3.len(), 4, "{report}");
    // The first loop is the notes' Example 1 four-bar at 60°.
    assert_eq!(
        [t3[0], t4[0], t3[2], t4[2]],
        [21.5576, 72.1377, 285.7834, 235.2033]
    );
    for k in 0..4 {
        // B from the crank's side and from the rocker's; D from C's side and from O6's.
        let b = plus(polar(80.0, 60.0), polar(200.0, t3[k]));
        meets("B", b, plus((180.0, 0.0), polar(150.0, t4[k])), 1e-3);
        let c = plus((180.0, 0.0), polar(100.0, t4[k] + WATT[5]));
        let d = plus(c, polar(220.0, t5[k]));
        meets("D", d, plus((300.0, 150.0), polar(160.0, t6[k])), 1e-3);
    }
    // The second loop's branches are different positions; each column as the library has it.
    assert!(wrapped_difference(t5[0], t5[1]) > 1.0);
    let linkage = watt_library();
    let theta2 = 60f64.to_radians();
    let (omega6, alpha6) = (cells(&report, "ω6"), cells(&report, "α6"));
    for (k, pair) in [
        [Branch::Open, Branch::Open],
        [Branch::Open, Branch::Crossed],
        [Branch::Crossed, Branch::Open],
        [Branch::Crossed, Branch::Crossed],
    ]
    .into_iter()
    .enumerate()
    {
        let m = linkage.motion(theta2, pair, 10.0, 0.0).unwrap();
        assert!(wrapped_difference(t6[k], m.position.theta6.to_degrees()) < 1e-4);
        assert!((omega6[k] - m.velocity.theta6).abs() < 1e-4);
        assert!((alpha6[k] - m.acceleration.theta6).abs() < 1e-4);
    }
}

#[test]
fn analyse_lists_every_stephenson_assembly_each_closing_both_loops() {
    let report = stdout_of(&strings(&with(
        &["analyse"],
        &strings(&with(&strings(&stephenson_args(20.0)), &["--at", "0"])),
    )));
    let angles = ["θ3 (°)", "θ4 (°)", "θ5 (°)", "θ6 (°)"].map(|l| cells(&report, l));
    assert!(report.contains("4 assemblies found"), "{report}");
    for k in 0..4 {
        stephenson_closes(20.0, 0.0, angles.clone().map(|a| a[k]), 1e-3);
    }
    // One of them is the library's, by Newton from the documented guess.
    let linkage = stephenson_library(20.0);
    let guess = mechanisms::StephensonSixBarUnknowns {
        theta3: -0.25,
        theta4: 0.63,
        theta5: 1.43,
        theta6: 1.46,
    };
    let q = linkage
        .position(0.0, &guess, &mechgen::NewtonOptions::default())
        .unwrap()
        .value
        .to_array()
        .map(f64::to_degrees);
    assert!(
        (0..4).any(|k| (0..4).all(|u| wrapped_difference(angles[u][k], q[u]) < 1e-4)),
        "{q:?} not among\n{report}"
    );
}

/// The trace's rows: the four angles and the residual's largest component.
fn trace_rows(report: &str) -> Vec<[f64; 5]> {
    report
        .lines()
        .skip_while(|l| !l.contains("max |f|"))
        .skip(1)
        .map_while(|l| {
            let numbers: Vec<f64> = l
                .split_whitespace()
                .map(|c| c.parse::<f64>())
                .collect::<Result<_, _>>()
                .ok()?;
            (numbers.len() == 6)
                .then(|| [numbers[1], numbers[2], numbers[3], numbers[4], numbers[5]])
        })
        .collect()
}

#[test]
fn trace_prints_the_stephenson_newton_iterates_converging() {
    // From the documented guess, in degrees: to the library's position, quadratically.
    let guess = [-0.25f64, 0.63, 1.43, 1.46].map(|g| g.to_degrees().to_string());
    let guess = guess.join(",");
    let args = with(
        &["analyse"],
        &strings(&with(
            &strings(&stephenson_args(20.0)),
            &["--at", "0", "--trace", "--guess", &guess],
        )),
    );
    let report = stdout_of(&strings(&args));
    assert!(report.contains("  converged"), "{report}");
    let rows = trace_rows(&report);
    assert!(rows.len() >= 3, "{report}");
    for pair in rows.windows(2) {
        assert!(
            pair[1][4] < pair[0][4],
            "the residual falls at every step:\n{report}"
        );
    }
    // Quadratic at the end: each residual about the square of the one before, in mm.
    let last = rows.len() - 1;
    assert!(rows[last][4] < 1e-8 && rows[last - 1][4] < 1e-2, "{report}");
    let q = stephenson_library(20.0)
        .position(
            0.0,
            &mechanisms::StephensonSixBarUnknowns {
                theta3: -0.25,
                theta4: 0.63,
                theta5: 1.43,
                theta6: 1.46,
            },
            &mechgen::NewtonOptions::default(),
        )
        .unwrap()
        .value
        .to_array();
    for (got, want) in rows[last][..4].iter().zip(q) {
        assert!(
            wrapped_difference(*got, want.to_degrees()) < 1e-5,
            "{report}"
        );
    }
    // Without a guess it starts from the first assembly read to tens of degrees.
    let args = with(
        &["analyse"],
        &strings(&with(
            &strings(&stephenson_args(20.0)),
            &["--at", "0", "--trace"],
        )),
    );
    let report = stdout_of(&strings(&args));
    assert!(
        report.contains("Newton-Raphson from θ3 = 20°, θ4 = -20°, θ5 = -70°, θ6 = -150°"),
        "{report}"
    );
    assert!(report.contains("  converged"), "{report}");
}

/// A sweep's table: its header and its rows as numbers.
fn sweep_table(args: &[String], scratch: &Scratch) -> (String, Vec<String>, Vec<Vec<f64>>) {
    let args = with(&["sweep"], &strings(args));
    let summary = stdout_of(&strings(&with(
        &strings(&args),
        &["--out-dir", scratch.path()],
    )));
    let table = std::fs::read_to_string(scratch.0.join("sweep.csv")).unwrap();
    let mut lines = table.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    (summary, header, rows)
}

#[test]
fn a_watt_sweep_turns_fully_as_the_library_computes_it() {
    let scratch = Scratch::new("watt");
    let (summary, header, rows) = sweep_table(&watt_args(WATT), &scratch);
    assert!(summary.contains("361 samples in 1 piece"), "{summary}");
    assert!(summary.contains("piece 1: a full turn"), "{summary}");
    assert_eq!(
        header[..4],
        ["input_deg", "segment", "theta3_deg", "theta4_deg"]
    );
    assert_eq!(header.len(), 2 + 12);
    let linkage = watt_library();
    for row in &rows {
        assert_eq!(row[1], 1.0);
        let m = linkage
            .motion(row[0].to_radians(), [Branch::Open, Branch::Open], 10.0, 0.0)
            .unwrap();
        let want = [
            m.position.theta6.to_degrees(),
            m.velocity.theta6,
            m.acceleration.theta6,
        ];
        for (got, want) in [row[5], row[9], row[13]].into_iter().zip(want) {
            assert!(
                (got - want).abs() <= 1e-8 * want.abs().max(1.0),
                "at {}°: {got} vs {want}",
                row[0]
            );
        }
    }
    // θ3, θ4, θ5, θ6, their rates and accelerations: twelve lines for one piece.
    assert_eq!(series_lines_drawn(&scratch), 12);
    // The drawing: seven links (the rocker a triangle O4 B C) and three ground pivots.
    let animation = std::fs::read_to_string(scratch.0.join("animation.svg")).unwrap();
    let document = roxmltree::Document::parse(&animation).unwrap();
    let count =
        |test: &dyn Fn(&roxmltree::Node) -> bool| document.descendants().filter(test).count();
    assert_eq!(count(&|n| n.has_tag_name("line")), 7);
    assert_eq!(count(&|n| n.attribute("class") == Some("ground")), 3);
}

#[test]
fn a_watt_six_bar_that_cannot_turn_fully_is_swept_over_its_pieces() {
    // The first loop a rocker-crank, the second always closing: the four-bar's two pieces,
    // each a line of its own.
    let scratch = Scratch::new("watt-rocker-crank");
    let (summary, _, rows) = sweep_table(
        &watt_args([
            180.0, 150.0, 200.0, 80.0, 100.0, 30.0, 300.0, 300.0, 200.0, 100.0,
        ]),
        &scratch,
    );
    assert!(summary.contains("2 pieces"), "{summary}");
    assert!(
        summary.contains("piece 1: 41.41° to 115.80° (toggles at the ends)"),
        "{summary}"
    );
    assert!(summary.contains("piece 2: 244.20° to 318.59°"), "{summary}");
    assert!(rows.iter().all(|r| if r[1] == 1.0 {
        (41.41..115.80).contains(&r[0])
    } else {
        r[1] == 2.0 && (244.20..318.59).contains(&r[0])
    }));
    assert_eq!(series_lines_drawn(&scratch), 2 * 12);
    // The first loop a crank-rocker, the second too short to close everywhere: one piece
    // through 0°, its ends where the library stops assembling the second loop.
    let scratch = Scratch::new("watt-short-dyad");
    let mut dimensions = WATT;
    dimensions[6..].copy_from_slice(&[150.0, 100.0, 330.0, 150.0]);
    let (summary, _, rows) = sweep_table(&watt_args(dimensions), &scratch);
    assert!(
        summary.contains("piece 1: -25.05° to 112.17° (toggles at the ends)"),
        "{summary}"
    );
    assert!(rows.iter().all(|r| (-25.05..112.17).contains(&r[0])));
    let linkage = mechanisms::WattSixBar::new(
        [180.0, 80.0, 200.0, 150.0],
        100.0,
        0.8,
        150.0,
        100.0,
        (330.0, 150.0),
    )
    .unwrap();
    let open = [Branch::Open, Branch::Open];
    let closes = |degrees: f64| linkage.assemble(degrees.to_radians(), open).is_ok();
    assert!(closes(-25.04) && !closes(-25.06) && closes(112.16) && !closes(112.18));
}

#[test]
fn a_stephenson_sweep_follows_its_assembly_round_a_full_turn() {
    let scratch = Scratch::new("stephenson");
    let (summary, header, rows) = sweep_table(&stephenson_args(20.0), &scratch);
    assert!(
        summary.contains("piece 1: a full turn (followed by Newton from its assembly at 0°)"),
        "{summary}"
    );
    assert_eq!(rows.len(), 361);
    assert_eq!(header[5], "theta6_deg");
    let linkage = stephenson_library(20.0);
    for row in &rows {
        let angles = [row[2], row[3], row[4], row[5]];
        stephenson_closes(20.0, row[0], angles, 1e-5);
        // The rates the library computes at that position.
        let t = row[0].to_radians();
        let q = mechanisms::StephensonSixBarUnknowns::from_array(angles.map(f64::to_radians));
        let v = linkage.velocity(t, &q, 10.0).unwrap().to_array();
        for (got, want) in row[6..10].iter().zip(v) {
            assert!(
                (got - want).abs() < 1e-6 * want.abs().max(1.0),
                "at {}°",
                row[0]
            );
        }
    }
    // It stays on its circuit: one continuous motion, no jump between samples.
    for pair in rows.windows(2) {
        assert!(wrapped_difference(pair[0][3], pair[1][3]) < 5.0, "{pair:?}");
    }
}

#[test]
fn a_stephenson_six_bar_whose_crank_cannot_turn_is_swept_between_its_toggles() {
    // A longer crank: the circuit through the first assembly at 0° ends at toggles at
    // 0.09° and, the other way, 80.77° (−279.23°).
    let scratch = Scratch::new("stephenson-toggles");
    let (summary, _, rows) = sweep_table(&stephenson_args(50.0), &scratch);
    assert!(
        summary.contains(
            "piece 1: -279.23° to 0.09° (a toggle below, a toggle above, where Newton's walk \
             from its assembly at 0° stopped)"
        ),
        "{summary}"
    );
    assert_eq!(rows.len(), 279);
    for row in &rows {
        assert!((-279.23..0.09).contains(&row[0]) && row[1] == 1.0);
        stephenson_closes(50.0, row[0], [row[2], row[3], row[4], row[5]], 1e-5);
    }
    // Toward a toggle the rates grow without bound.
    let omega4_at_ends = rows[0][7].abs().min(rows[rows.len() - 1][7].abs());
    let omega4_inside = rows[rows.len() / 2][7].abs();
    assert!(
        omega4_at_ends > 3.0 * omega4_inside,
        "{omega4_at_ends} {omega4_inside}"
    );
}

/// A Stephenson six-bar whose circuit meets one toggle (71.29°) from both sides, a full turn
/// apart: the piece is that full turn, down to −288.71°, not to −288° (the last whole degree
/// the walk down took, which left 0.71° of the circuit out of the piece).
#[test]
fn a_stephenson_circuit_a_full_turn_below_its_toggle_is_that_turn() {
    let scratch = Scratch::new("stephenson-full-turn-below");
    let args: Vec<String> = [
        "stephenson-six-bar",
        "100",
        "20",
        "80",
        "60",
        "63",
        "-55.577",
        "52",
        "85",
        "189",
        "-26",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let (summary, _, rows) = sweep_table(&args, &scratch);
    assert!(
        summary.contains("piece 1: -288.71° to 71.29° (a full turn below, a toggle above"),
        "{summary}"
    );
    // Samples a step inside each end, as every piece's between toggles.
    assert!(
        rows[0][0] < -287.7 && rows[rows.len() - 1][0] > 70.28,
        "{summary}"
    );
}

/// A Stephenson six-bar near the float's largest walks as it does at 1 mm: the walk's
/// slopes are solved scaled (they overflowed at 5e306 mm, and the walk stopped at its first
/// step, reported as a toggle on both sides of a one-sample piece).
#[test]
fn a_stephenson_sweep_near_the_largest_float_is_the_sweep_at_any_size() {
    let piece = |size: &str| {
        let scratch = Scratch::new(&format!("stephenson-size-{size}"));
        let args: Vec<String> = [size, size, size, size, size, "0", size, size, size, "0"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        let (summary, _, rows) =
            sweep_table(&with(&["stephenson-six-bar"], &strings(&args)), &scratch);
        assert!(
            summary.contains("piece 1: 42.94° to 317.06° (a toggle below, a toggle above"),
            "{size}: {summary}"
        );
        rows.len()
    };
    assert_eq!(piece("1"), piece("1e307"));
    // Past the largest float in sum, the walk's loops overflow: refused by name, where it
    // reported a one-sample piece between a toggle and a change point.
    let mut args = vec!["sweep", "stephenson-six-bar"];
    args.extend(["5e307", "5e307", "5e307", "5e307", "5e307", "0"]);
    args.extend(["5e307", "5e307", "5e307", "0"]);
    fails_with(
        &args,
        "lengths and coordinates sum to more than the largest float",
    );
}

#[test]
fn bad_six_bar_input_is_a_clear_message_and_a_failure() {
    fails_with(
        &["analyse", "watt-six-bar", "180", "80", "200"],
        "watt-six-bar takes 10 dimensions (ground crank coupler rocker extension",
    );
    fails_with(
        &["sweep", "stephenson-six-bar", "1"],
        "stephenson-six-bar takes 10 dimensions",
    );
    let mut negative = watt_args(WATT);
    negative[8] = "-160".into();
    fails_with(
        &strings(&with(&["analyse"], &strings(&negative))),
        "second rocker = -160 must be positive and finite",
    );
    let mut zero = stephenson_args(20.0);
    zero[5] = "0".into();
    fails_with(
        &strings(&with(&["sweep"], &strings(&zero))),
        "ternary C D = 0 must be positive and finite",
    );
    // Dyads far too short to reach their ground pivots: nowhere assembles.
    let mut apart = WATT;
    apart[6..].copy_from_slice(&[1.0, 1.0, 1000.0, 1000.0]);
    fails_with(
        &strings(&with(&["sweep"], &strings(&watt_args(apart)))),
        "the watt-six-bar cannot be assembled at any input angle",
    );
    fails_with(
        &strings(&with(&["analyse"], &strings(&watt_args(apart)))),
        "the Watt six-bar cannot be assembled at 60°",
    );
    let mut apart = stephenson_args(20.0);
    apart[8..].clone_from_slice(&["1".into(), "1000".into(), "1000".into()]);
    fails_with(
        &strings(&with(&["sweep"], &strings(&apart))),
        "the stephenson-six-bar cannot be assembled at any input angle",
    );
    fails_with(
        &strings(&with(&["analyse"], &strings(&apart))),
        "the Stephenson six-bar cannot be assembled at 60°",
    );
    // Flags that do not apply.
    let watt = watt_args(WATT);
    fails_with(
        &strings(&with(
            &["analyse"],
            &strings(&with(&strings(&watt), &["--trace"])),
        )),
        "not the watt-six-bar, which is solved in closed form",
    );
    fails_with(
        &strings(&with(
            &["analyse"],
            &strings(&with(&strings(&watt), &["--trace", "--guess", "1,2"])),
        )),
        "--trace applies to the four-bar and the stephenson-six-bar",
    );
    fails_with(
        &strings(&with(
            &["analyse"],
            &strings(&with(&strings(&watt), &["--guess", "1,2"])),
        )),
        "--guess is Newton's start for --trace",
    );
    let stephenson = stephenson_args(20.0);
    fails_with(
        &strings(&with(
            &["analyse"],
            &strings(&with(
                &strings(&stephenson),
                &["--trace", "--guess", "15,80"],
            )),
        )),
        "--guess takes four finite angles in degrees, theta3,theta4,theta5,theta6",
    );
    fails_with(
        &strings(&with(
            &["analyse"],
            &strings(&with(
                &strings(&stephenson),
                &["--trace", "--guess", "20", "-20"],
            )),
        )),
        "--guess takes four angles joined by commas",
    );
    fails_with(
        &strings(&with(
            &["sweep"],
            &strings(&with(&strings(&stephenson), &["--branch", "open"])),
        )),
        "--branch does not apply to the stephenson-six-bar",
    );
    fails_with(
        &strings(&with(
            &["sweep"],
            &strings(&with(&strings(&watt), &["--branch", "open"])),
        )),
        "the watt-six-bar takes a branch per loop, as --branch open,crossed",
    );
    fails_with(
        &[
            "sweep",
            "four-bar",
            "180",
            "80",
            "200",
            "150",
            "--branch",
            "open,open",
        ],
        "the four-bar has one loop: --branch takes one branch",
    );
    fails_with(
        &strings(&with(
            &["sweep"],
            &strings(&with(&strings(&watt), &["--coupler-point", "10,0"])),
        )),
        "--coupler-point applies to the four-bar and the slider-crank, not the watt-six-bar",
    );
}

#[test]
fn huge_and_tiny_six_bars_never_panic() {
    for scale in [1e300, 1e-300] {
        let watt = watt_args(WATT.map(|d| if d == WATT[5] { d } else { d * scale }));
        let mut stephenson = stephenson_args(20.0);
        for (k, d) in stephenson.iter_mut().enumerate().skip(1) {
            if k != 6 {
                *d = (d.parse::<f64>().unwrap() * scale).to_string();
            }
        }
        for args in [watt, stephenson] {
            for command in ["analyse", "sweep"] {
                let scratch = Scratch::new("huge-six-bar");
                let mut all = with(&[command], &strings(&args));
                if command == "sweep" {
                    all.extend(with(&["--step", "30", "--out-dir"], &[scratch.path()]));
                }
                let output = program().args(&all).output().unwrap();
                let stderr = String::from_utf8_lossy(&output.stderr);
                assert!(!stderr.contains("panicked"), "{all:?}: {stderr}");
                let stdout = String::from_utf8_lossy(&output.stdout);
                assert!(!stdout.contains("NaN"), "{all:?}: {stdout}");
                assert!(
                    output.status.code() == Some(0)
                        || (output.status.code() == Some(1) && stderr.starts_with("error: ")),
                    "{all:?}: {stderr}"
                );
            }
        }
    }
}

/// `tolerance`: Example 1 with ±0.1 mm on every length, its first-order worst case at 60°
/// beside the worst corner of the nonlinear model (the library's doctest has the same
/// figures), a chart, and clear refusals.
#[test]
fn tolerance_reports_first_order_beside_the_nonlinear_model() {
    let report = stdout_of(&[
        "tolerance",
        "four-bar",
        "180",
        "80",
        "200",
        "150",
        "--coupler-point",
        "100,28.64788975654116",
        "--step",
        "60",
        "--samples",
        "500",
    ]);
    // θ2 = 60°: θ4 within ±0.1656° at first order, 0.1657° at the worst corner.
    let row = report
        .lines()
        .find(|l| l.starts_with("| 60.0 |"))
        .unwrap_or_else(|| panic!("no row for 60° in:\n{report}"));
    assert!(row.contains("| 1.6556e-1 | 1.6569e-1 |"), "{row}");
    assert!(
        report.contains("Largest first-order worst case of θ4"),
        "{report}"
    );
    let scratch = Scratch::new("tolerance");
    std::fs::create_dir_all(&scratch.0).unwrap();
    let svg = scratch.0.join("tolerance.svg");
    stdout_of(&[
        "tolerance",
        "four-bar",
        "180",
        "80",
        "200",
        "150",
        "--step",
        "90",
        "--samples",
        "10",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    let drawing = std::fs::read_to_string(&svg).unwrap();
    assert!(drawing.starts_with("<svg") && drawing.contains("worst corner"));
    fails_with(
        &["tolerance", "slider-crank", "50", "150", "0"],
        "covers the four-bar",
    );
    fails_with(
        &[
            "tolerance",
            "four-bar",
            "180",
            "80",
            "200",
            "150",
            "--tolerance",
            "-1",
        ],
        "finite and not negative",
    );
    fails_with(
        &[
            "tolerance",
            "four-bar",
            "180",
            "80",
            "200",
            "150",
            "--step",
            "1e-9",
        ],
        "--step must be",
    );
    fails_with(
        &[
            "tolerance",
            "four-bar",
            "180",
            "80",
            "200",
            "150",
            "--samples",
            "99999999999",
        ],
        "--samples takes at most",
    );
    fails_with(
        &[
            "tolerance",
            "four-bar",
            "180",
            "80",
            "200",
            "150",
            "--tolerances",
            "1,2",
        ],
        "--tolerances takes four",
    );
}

/// `synthesise`: Example 1's output at six crank angles (rounded to degrees) gives Example 1
/// back to within the rounding; three points give Freudenstein's closed form; a chart; and
/// clear refusals.
#[test]
fn synthesise_finds_a_four_bar_for_a_function_and_a_path() {
    let report = stdout_of(&[
        "synthesise",
        "function",
        "--ground",
        "180",
        "--crank",
        "0,45,90,135,180,225",
        "--rocker",
        "76,67,87,111,130,138",
        "--branch",
        "open",
    ]);
    assert!(
        report.contains("ground 180.0000 crank 80.1067 coupler 200.6338 rocker 151.5064"),
        "{report}"
    );
    let three = stdout_of(&[
        "synthesise",
        "function",
        "--crank",
        "30,60,90",
        "--rocker",
        "60,95.1,120",
    ]);
    assert!(three.contains("crossed branch"), "{three}");
    assert!(
        three.contains("Freudenstein's closed form of the three points: crank 347.2422"),
        "{three}"
    );
    // Six points of a circle of radius 50 about (100, 100), at crank angles 60° apart: a
    // four-bar's coupler curve through them, placed.
    let (x, y): (Vec<String>, Vec<String>) = (0..6)
        .map(|k| {
            let t = f64::from(k) * std::f64::consts::FRAC_PI_3;
            (
                format!("{:.6}", 100.0 + 50.0 * t.cos()),
                format!("{:.6}", 100.0 + 50.0 * t.sin()),
            )
        })
        .unzip();
    let scratch = Scratch::new("synthesise");
    std::fs::create_dir_all(&scratch.0).unwrap();
    let svg = scratch.0.join("path.svg");
    let path = stdout_of(&[
        "synthesise",
        "path",
        "--x",
        &x.join(","),
        "--y",
        &y.join(","),
        "--timing",
        "0,60,120,180,240,300",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert!(path.contains("placed with its crank pivot at"), "{path}");
    assert!(
        std::fs::read_to_string(&svg)
            .unwrap()
            .contains("coupler curve")
    );
    fails_with(
        &[
            "synthesise",
            "function",
            "--crank",
            "1,2",
            "--rocker",
            "1,2,3",
        ],
        "one rocker angle per crank angle",
    );
    fails_with(
        &["synthesise", "path", "--x", "1,2,3", "--y", "1,2,3"],
        "nine or more targets",
    );
    fails_with(
        &[
            "synthesise",
            "function",
            "--crank",
            "1,2,3",
            "--rocker",
            "1,2,3",
            "--transmission",
            "140,40",
        ],
        "--transmission takes two angles",
    );
    fails_with(
        &[
            "synthesise",
            "function",
            "--crank",
            "1,2,3",
            "--rocker",
            "1,2,3",
            "--restarts",
            "999999999",
        ],
        "--restarts takes at most",
    );
}

#[test]
fn robot_reports_both_working_modes_and_their_singularities() {
    // The symmetric robot with cranks at 120° and 60°: P straight above the middle at
    // 100·√3·1.5 mm, moving straight down; the crossed mode has both legs folded flat.
    let report = stdout_of(&["robot"]);
    for value in [
        "end effector P = (50.0000, 259.8076) mm",
        "velocity = (0.0000, -100.0000) mm/s",
        "acceleration = (0.0000, -115.4701) mm/s²",
        "parallel 0.8660, serial left 0.8660, serial right 0.8660",
        "end effector P = (50.0000, -86.6025) mm",
        "serial left 0.0000, serial right 0.0000",
    ] {
        assert!(report.contains(value), "{value} missing from:\n{report}");
    }
    // The distal links stretched in one line: a parallel singularity, in both modes.
    let report = stdout_of(&["robot", "1", "1.5", "1.5", "1", "1", "--cranks", "180,0"]);
    assert_eq!(
        report.matches("a parallel singularity").count(),
        2,
        "{report}"
    );
}

/// Rates whose squares overflow: the acceleration is refused, and the position and velocity
/// printed as far as their estimate goes, the velocity's rounding as `0 (±…)` (an
/// adversarial review found `4.3511e186` printed where the velocity is exactly zero).
#[test]
fn robot_prints_only_the_digits_a_failed_motion_leaves() {
    let report = stdout_of(&["robot", "--rates", "1e200,1e200"]);
    for value in [
        "end effector P = (50.0000, 259.8076) mm",
        "velocity = (-1.7321e202, 0 (±",
        "velocity = (0 (±",
        "acceleration: acceleration is not finite",
    ] {
        assert!(report.contains(value), "{value} missing from:\n{report}");
    }
    assert!(!report.contains("e186"), "{report}");
}

#[test]
fn robot_inverse_kinematics_finds_every_elbow_choice() {
    let report = stdout_of(&["robot", "--point", "50,250"]);
    for value in [
        "both elbows outward: cranks at 125.3437° and 54.6563°, working mode open",
        "both elbows inward: cranks at 32.0364° and 147.9636°, working mode crossed",
    ] {
        assert!(report.contains(value), "{value} missing from:\n{report}");
    }
    let report = stdout_of(&["robot", "--point", "1000,0"]);
    assert!(report.contains("outside the workspace"), "{report}");
}

#[test]
fn robot_refuses_bad_arguments() {
    fails_with(
        &["robot", "--cranks", "1,nan"],
        "--cranks takes two finite numbers",
    );
    fails_with(
        &["robot", "--point", "1"],
        "--point takes two finite numbers",
    );
    fails_with(&["robot", "1", "-2", "2", "1", "1"], "must be positive");
    fails_with(&["robot", "1", "2", "3"], "robot takes 5 links");
}

/// Runs the program, expecting success, and returns its standard output and error.
fn outputs_of(args: &[&str]) -> (String, String) {
    let output = program().args(args).output().unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(output.status.success(), "{args:?}: {stderr}");
    (String::from_utf8(output.stdout).unwrap(), stderr)
}

/// Runs the program, expecting a failure with exit code 1 and `message`, and nothing on
/// standard output: a refusal comes before any of the report.
fn refused_before_any_output(args: &[&str], message: &str) {
    let output = program().args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
    assert!(stderr.contains(message), "{args:?}: {stderr}");
    assert_eq!(String::from_utf8_lossy(&output.stdout), "", "{args:?}");
}

/// The lines of `report` without those naming `given`, which echo an angle as it was typed.
fn without_echoes(report: &str, given: &str) -> Vec<String> {
    report
        .lines()
        .filter(|line| !line.contains(given))
        .map(str::to_string)
        .collect()
}

/// An angle of any size means the direction it does on paper: whole turns come off in
/// degrees, exactly, before it becomes radians (1e20° is 280°), so a synthesis' error is
/// its error at the angle given, never zero from an angle the rounding moved.
#[test]
fn angles_of_any_size_lose_whole_turns_exactly() {
    let function = |rocker: &str| {
        stdout_of(&[
            "synthesise",
            "function",
            "--crank",
            "0,45,90",
            "--rocker",
            rocker,
        ])
    };
    let near = function("280,260,250");
    let far = function("1e20,260,250");
    assert!(far.contains("| 0 | 1e20 | 280.0000 |"), "{far}");
    assert_eq!(
        without_echoes(&far, "1e20"),
        without_echoes(&near, "| 0 | 280 |")
    );
    // The audit's case: the wanted angle is no longer echoed back as met.
    let output = program()
        .args(["synthesise", "function", "--crank", "0,45,90"])
        .args(["--rocker", "1e20,67,87"])
        .output()
        .unwrap();
    let report = String::from_utf8_lossy(&output.stdout);
    assert!(
        !report.contains("100000000000000000000"),
        "{report}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    // Each angle argument: the input, a dimension that is an angle, a coupler point's angle,
    // the cranks, the timing.
    let analyse =
        |at: &str| stdout_of(&["analyse", "four-bar", "180", "80", "200", "150", "--at", at]);
    assert_eq!(
        without_echoes(&analyse("1e20"), "θ2 = 1e20°"),
        without_echoes(&analyse("280"), "θ2 = 280°")
    );
    let inverted =
        |angle: &str| stdout_of(&["analyse", "inverted-slider-crank", "150", "60", "20", angle]);
    assert_eq!(inverted("1e20"), inverted("280"));
    let tolerance = |point: &str| {
        stdout_of(&[
            "tolerance",
            "four-bar",
            "180",
            "80",
            "200",
            "150",
            "--coupler-point",
            point,
            "--step",
            "90",
            "--samples",
            "100",
        ])
    };
    assert_eq!(
        without_echoes(&tolerance("100,1e20"), "at 1e20°"),
        without_echoes(&tolerance("100,280"), "at 280°")
    );
    assert_eq!(
        stdout_of(&["robot", "--cranks", "1e20,-1e20"]),
        stdout_of(&["robot", "--cranks", "280,-280"])
    );
    let (x, y) = circle_targets(1.0);
    let path = |timing: &str| {
        stdout_of(&[
            "synthesise",
            "path",
            "--x",
            &x,
            "--y",
            &y,
            "--timing",
            timing,
        ])
    };
    assert_eq!(
        path("0,60,120,180,240,300"),
        // Each the same angle, less whole turns (360000000000300 = 10¹²·360 + 300).
        path("360,420,1.2e3,540,600,360000000000300")
    );
}

/// Six points of a circle of radius 50 about (100, 100), times `scale`, as `--x` and `--y`.
fn circle_targets(scale: f64) -> (String, String) {
    let (x, y): (Vec<String>, Vec<String>) = (0..6)
        .map(|k| {
            let t = f64::from(k) * std::f64::consts::FRAC_PI_3;
            (
                format!("{:e}", (100.0 + 50.0 * t.cos()) * scale),
                format!("{:e}", (100.0 + 50.0 * t.sin()) * scale),
            )
        })
        .unzip();
    (x.join(","), y.join(","))
}

/// `synthesise` refuses what would make its error meaningless (a precision point or target
/// given twice, two answers for one crank angle) and what would run for many minutes (path
/// generation without timing past its budget), states its errors' units, and gives
/// Freudenstein's closed form at any ground, with the branch it meets the points on.
#[test]
fn synthesise_refuses_repeated_points_and_states_its_units() {
    for (args, message) in [
        (
            &["function", "--crank", "30,390,60", "--rocker", "60,60,95"][..],
            "a precision point is given twice",
        ),
        (
            &["function", "--crank", "30,30,60", "--rocker", "60,70,95"][..],
            "a crank angle is given two rocker angles",
        ),
        (
            &[
                "path",
                "--x",
                "0,10,20,30,40",
                "--y",
                "5,8,4,0,2",
                "--timing",
                "0,30,30,30,120",
            ][..],
            "two targets are given the same crank angle",
        ),
        (
            &[
                "path",
                "--x",
                "0,0,0,0,0,0,0,0,10",
                "--y",
                "0,0,0,0,0,0,0,0,5",
            ][..],
            "a target is given twice",
        ),
    ] {
        let args: Vec<&str> = ["synthesise"].iter().chain(args).copied().collect();
        fails_with(&args, message);
    }
    // Forty targets without timing: refused at once, with what would fit.
    let (x, y): (Vec<String>, Vec<String>) = (0..40)
        .map(|k| {
            let t = f64::from(k) * 0.15;
            (
                format!("{:.4}", 50.0 * t.cos()),
                format!("{:.4}", 30.0 * t.sin()),
            )
        })
        .unzip();
    fails_with(
        &[
            "synthesise",
            "path",
            "--x",
            &x.join(","),
            "--y",
            &y.join(","),
        ],
        "40 targets with 64 random starts on each branch would take many minutes; give \
         --timing, fewer targets, or --restarts 11 or fewer (or one --branch)",
    );
    let path = stdout_of(&[
        "synthesise",
        "path",
        "--x",
        "0,10,20,30,40",
        "--y",
        "5,8,4,0,2",
        "--timing",
        "0,30,60,90,120",
    ]);
    assert!(
        path.contains("rms error (the coupler point's distance from each target) ")
            && path.contains(" mm, largest "),
        "{path}"
    );
    for ground in ["1e300", "1e-30"] {
        let report = stdout_of(&[
            "synthesise",
            "function",
            "--crank",
            "30,45,60",
            "--rocker",
            "60,75,95",
            "--ground",
            ground,
        ]);
        assert!(
            report.contains("rms error ") && report.contains("°, largest "),
            "{report}"
        );
        assert!(
            report.contains("Freudenstein's closed form of the three points: crank 6.7547e")
                && report.contains("mm, on the open branch"),
            "{report}"
        );
    }
}

/// The rms error a synthesis reports (degrees, or mm), its unit and any words before it
/// dropped.
fn rms_error(report: &str) -> f64 {
    let after = report
        .split("rms error")
        .nth(1)
        .unwrap_or_else(|| panic!("no rms error in:\n{report}"));
    let after = after
        .split(')')
        .nth(1)
        .filter(|_| after.starts_with(" ("))
        .unwrap_or(after);
    let figure = after.trim_start().split([',', ' ', '°']).next().unwrap();
    figure
        .parse()
        .unwrap_or_else(|_| panic!("no number in {figure:?} of:\n{report}"))
}

/// Path generation fits the same at any scale (its errors are not squared into overflow near
/// 1e300 nor underflow near 1e-300): a fit that is none at one scale is none at every scale,
/// never an infinite or a zero error with exit 0; and targets that all coincide are refused.
#[test]
fn path_synthesis_is_honest_at_any_scale() {
    let timing = "0,30,60,90,120";
    for (x, y) in [
        ("0,1,2,3,4", "5,8,4,3,1"),
        ("0,1e300,2e300,3e300,4e300", "5e300,8e300,4e300,3e300,1e300"),
        (
            "0,1e-300,2e-300,3e-300,4e-300",
            "5e-300,8e-300,4e-300,3e-300,1e-300",
        ),
    ] {
        refused_before_any_output(
            &["synthesise", "path", "--x", x, "--y", y, "--timing", timing],
            "no linkage meets the targets",
        );
    }
    let (x, y) = circle_targets(1.0);
    let unit = rms_error(&stdout_of(&[
        "synthesise",
        "path",
        "--x",
        &x,
        "--y",
        &y,
        "--timing",
        "0,60,120,180,240,300",
    ]));
    for scale in [1e298, 1e-302] {
        let (x, y) = circle_targets(scale);
        let report = stdout_of(&[
            "synthesise",
            "path",
            "--x",
            &x,
            "--y",
            &y,
            "--timing",
            "0,60,120,180,240,300",
        ]);
        assert!(
            !report.contains("inf") && !report.contains("NaN"),
            "{report}"
        );
        let rms = rms_error(&report);
        assert!(
            rms > 0.0 && rms / scale < 1e-12 + 10.0 * unit,
            "{scale}: {report}"
        );
        assert!(
            report.contains(&format!("{:.4e}", 100.0 * scale)),
            "{report}"
        );
    }
    let zeros = "0,0,0,0,0,0,0,0,0";
    refused_before_any_output(
        &["synthesise", "path", "--x", zeros, "--y", zeros],
        "--x and --y give 9 targets all at (0, 0) mm",
    );
    refused_before_any_output(
        &[
            "synthesise",
            "path",
            "--x",
            "5,5,5,5,5",
            "--y",
            "1,1,1,1,1",
            "--timing",
            "0,10,20,30,40",
        ],
        "all at (5, 1) mm",
    );
}

/// Where the nonlinear model cannot stand beside first order, the report says so: 0.04°
/// inside a limit, some linkages within the tolerances do not assemble (counted), and first
/// order's worst case is half again the worst corner's (flagged). A coupler point at the
/// crank pin loses no corner to a negative distance. Every crank angle of the turn has a row,
/// labelled to the step's decimals.
#[test]
fn tolerance_says_where_first_order_and_the_nonlinear_model_part() {
    let report = stdout_of(&[
        "tolerance",
        "four-bar",
        "100",
        "70",
        "40",
        "50",
        "--step",
        "20.3",
        "--samples",
        "200",
    ]);
    assert!(
        report.contains(
            "Some linkages within the tolerances do not assemble (the nonlinear columns are \
             over those that do) at: 60.9° (16 of 32 corners, "
        ),
        "{report}"
    );
    assert!(
        report.contains("First order and the worst corner differ by more than 10%")
            && report.contains("at: 60.9° (θ4: 5.1422° against 2.7880°)"),
        "{report}"
    );
    // Far from the limits: every corner assembles, and first order holds.
    let report = stdout_of(&[
        "tolerance",
        "four-bar",
        "180",
        "80",
        "200",
        "150",
        "--step",
        "200",
        "--samples",
        "100",
    ]);
    assert!(
        !report.contains("do not assemble") && !report.contains("differ by"),
        "{report}"
    );
    let rows: Vec<&str> = report
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| θ2"))
        .collect();
    assert_eq!(rows.len(), 2, "{report}");
    assert!(
        rows[0].starts_with("| 0.0 |") && rows[1].starts_with("| 200.0 |"),
        "{report}"
    );
    let report = stdout_of(&[
        "tolerance",
        "four-bar",
        "180",
        "80",
        "200",
        "150",
        "--step",
        "0.05",
        "--samples",
        "1",
    ]);
    let labels: Vec<&str> = report
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| θ2"))
        .map(|l| l.split(" | ").next().unwrap())
        .collect();
    assert_eq!(labels.len(), 7200);
    assert_eq!(labels[..3], ["| 0.00", "| 0.05", "| 0.10"]);
    let distinct: std::collections::BTreeSet<&&str> = labels.iter().collect();
    assert_eq!(distinct.len(), labels.len());
}

/// Every value prints to the digits its stated accuracy leaves, no more: near a toggle the
/// rates and the mechanical advantage lose digits (the review's: ω3 printed −183512.4111
/// where it is −183512.4172; the advantage −455397513.1023 where it is −455397458.18), a
/// value that is rounding prints as zero within its error (a robot's velocity of 4e284 at
/// 1e300 mm whose truth is 0), and an advantage whose driven rate is rounding of the size
/// (a slider-crank with its rod as long as its crank, on the branch where the slider stands
/// still) is unbounded, not −1.4e14; a slider-crank of 1e-300 mm has its finite advantage
/// of 1e300 per mm, not "unbounded".
#[test]
fn values_print_only_the_digits_their_accuracy_leaves() {
    let near = stdout_of(&[
        "analyse",
        "four-bar",
        "100",
        "80",
        "60",
        "110",
        "--at",
        "141.3751671",
    ]);
    let row = |report: &str, label: &str| -> String {
        report
            .lines()
            .find(|l| l.trim_start().starts_with(label))
            .unwrap_or_else(|| panic!("no {label} in:\n{report}"))
            .to_string()
    };
    assert!(row(&near, "ω3 (rad/s)").contains("-1.8351e5"), "{near}");
    assert!(row(&near, "ω4 (rad/s)").contains("1.0010e5"), "{near}");
    let toggle = stdout_of(&[
        "analyse",
        "four-bar",
        "100",
        "40",
        "120",
        "80",
        "--at",
        "24.1468479",
    ]);
    assert!(
        row(&toggle, "mechanical advantage").contains("-4.55e8"),
        "{toggle}"
    );
    let still = stdout_of(&["analyse", "slider-crank", "40", "40", "0", "--at", "60"]);
    assert!(
        row(&still, "mech. advantage").ends_with("unbounded"),
        "{still}"
    );
    let tiny = stdout_of(&["analyse", "slider-crank", "1e-300", "3e-300", "1e-300"]);
    assert!(
        row(&tiny, "mech. advantage").contains("-1.1853e300"),
        "{tiny}"
    );
    let huge = stdout_of(&["robot", "1e300", "2e300", "2e300", "1e300", "1e300"]);
    assert!(
        huge.contains("velocity = (0 (±1e288), -1.0000e300) mm/s"),
        "{huge}"
    );
    // Example 1 keeps its four decimals.
    let example = stdout_of(&[]);
    assert!(row(&example, "ω4 (rad/s)").contains("4.2923"), "{example}");
}

/// 360° is 0°, in a sweep as everywhere: an inverted slider-crank's change point at 0° is
/// singular at both ends of the turn (360° was 2π rounded, "inaccurate, error inf").
#[test]
fn a_sweep_ends_where_it_began() {
    let scratch = Scratch::new("turn");
    std::fs::create_dir_all(&scratch.0).unwrap();
    let report = stdout_of(&[
        "sweep",
        "inverted-slider-crank",
        "100",
        "100",
        "0",
        "0",
        "--step",
        "0.5",
        "--out-dir",
        scratch.0.to_str().unwrap(),
    ]);
    assert!(report.contains("at 0° singular, 360° singular"), "{report}");
    // Two outputs to one file: refused before anything is written.
    let same = scratch.0.join("same.x");
    let same = same.to_str().unwrap();
    fails_with(
        &[
            "sweep", "four-bar", "100", "40", "120", "80", "--csv", same, "--svg", same,
        ],
        "--csv and --svg both write",
    );
    assert!(!std::path::Path::new(same).exists());
}

/// Two outputs to one file however their paths are spelled (through a directory and back out
/// of it, or a link to the other), refused before anything is written, as is an output whose
/// directory does not exist (the table was written, then the chart failed).
#[test]
fn outputs_to_one_file_are_refused_however_they_are_spelled() {
    let scratch = Scratch::new("spelled");
    std::fs::create_dir_all(scratch.0.join("sub")).unwrap();
    let sweep = |tail: &[&str]| {
        with(
            &[
                "sweep",
                "four-bar",
                "180",
                "80",
                "200",
                "150",
                "--out-dir",
                scratch.path(),
            ],
            tail,
        )
    };
    fails_with(
        &strings(&sweep(&["--csv", "a.csv", "--svg", "sub/../a.csv"])),
        "--csv and --svg both write",
    );
    fails_with(
        &strings(&sweep(&["--csv", "b.csv", "--svg", "missing/../b.svg"])),
        "cannot write",
    );
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("drawn.svg", scratch.0.join("link.svg")).unwrap();
        fails_with(
            &strings(&sweep(&["--svg", "link.svg", "--animation", "drawn.svg"])),
            "--svg and --animation both write",
        );
    }
    let written: Vec<_> = std::fs::read_dir(&scratch.0)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().into_string().unwrap())
        .filter(|name| name != "sub" && name != "link.svg")
        .collect();
    assert!(written.is_empty(), "{written:?}");
}

/// A value whose error bound covers every value it could take is `undetermined`, with the
/// note that says so: a parallelogram's transmission angle at its change point (180°) was
/// `0 (±90000)`, the rod-as-long-as-crank slider's `d` at 90° `0 (±20000)` mm. A rate near
/// the float's largest leaves the rates' bounds finite (ω3 and ω4 at 1e308 rad/s were
/// `undetermined`, their bounds' scale overflowing, with no note).
#[test]
fn a_bound_that_covers_everything_says_undetermined() {
    for (args, row) in [
        (
            &[
                "analyse", "four-bar", "100", "50", "100", "50", "--at", "180",
            ][..],
            "transmission angle γ",
        ),
        (
            &["analyse", "slider-crank", "50", "50", "0", "--at", "90"],
            "d (mm)",
        ),
        (
            &["analyse", "slider-crank", "50", "50", "0", "--at", "90"],
            "transmission angle μ",
        ),
    ] {
        let report = stdout_of(args);
        let line = report
            .lines()
            .find(|l| l.trim_start().starts_with(row))
            .unwrap();
        assert!(
            line.contains("undetermined") && !line.contains('±'),
            "{line}"
        );
        assert!(
            report.contains("undetermined: no digit is known"),
            "{report}"
        );
    }
    let report = stdout_of(&[
        "analyse", "four-bar", "180", "80", "200", "150", "--rate", "1e308",
    ]);
    let rates = |name: &str| {
        let line = report
            .lines()
            .find(|l| l.trim_start().starts_with(name))
            .unwrap();
        line.split_whitespace()
            .rev()
            .take(2)
            .map(|cell| cell.parse::<f64>().unwrap())
            .collect::<Vec<_>>()
    };
    // Crossed, then open (read from the right): as Example 1's rates at 10 rad/s, times 1e307.
    let omega4 = rates("ω4 (rad/s)");
    assert!((omega4[1] / 4.2923e307 - 1.0).abs() < 1e-4, "{report}");
    assert!(
        rates("ω3 (rad/s)").iter().all(|w| w.is_finite()),
        "{report}"
    );
}

/// An inverted slider-crank whose crank pin lies on the slide's pivot: with the slide 5 mm
/// off it, it cannot be assembled (it said "singular … a toggle or change point", exit 1);
/// with the slide through it (the isosceles linkage's change point), it assembles without
/// determining the slide's angle, and the table says `singular` on each branch, as a
/// parallelogram's at its change point (it was an error, exit 1).
#[test]
fn a_crank_pin_on_the_slide_s_pivot_is_told_apart() {
    fails_with(
        &[
            "analyse",
            "inverted-slider-crank",
            "50",
            "50",
            "10",
            "30",
            "--at",
            "0",
        ],
        "the inverted slider-crank cannot be assembled at 0°",
    );
    let report = stdout_of(&[
        "analyse",
        "inverted-slider-crank",
        "50",
        "50",
        "0",
        "0",
        "--at",
        "0",
    ]);
    let line = report
        .lines()
        .find(|l| l.trim_start().starts_with("θ4"))
        .unwrap();
    assert_eq!(line.matches("singular").count(), 2, "{report}");
}

/// A linkage near the float's largest (1e308 mm), or a coupler point 1.5e308 mm out, is drawn
/// like any other: the animation's extent overflowed, and every coordinate in it was NaN.
#[test]
fn the_largest_linkages_are_drawn() {
    let scratch = Scratch::new("largest");
    for dimensions in [
        &["1e308", "1e308", "1e308", "1e308"][..],
        &[
            "1e300",
            "0.8e300",
            "1e300",
            "1e300",
            "--coupler-point",
            "1.5e308,30",
        ],
    ] {
        let mut args = vec!["sweep", "four-bar"];
        args.extend(dimensions);
        args.extend(["--out-dir", scratch.path()]);
        stdout_of(&args);
        for file in ["sweep.csv", "sweep.svg", "animation.svg"] {
            let text = std::fs::read_to_string(scratch.0.join(file)).unwrap();
            assert!(
                !text.contains("NaN") && !text.contains("inf"),
                "{dimensions:?}: {file}"
            );
        }
    }
}

/// With its chart on standard output (`--svg -`), a report goes to standard error: standard
/// output is the SVG alone.
#[test]
fn a_chart_on_standard_output_is_alone_there() {
    for args in [
        &[
            "tolerance",
            "four-bar",
            "180",
            "80",
            "200",
            "150",
            "--step",
            "30",
            "--svg",
            "-",
        ][..],
        &[
            "synthesise",
            "function",
            "--crank",
            "0,45,90",
            "--rocker",
            "76,67,87",
            "--svg",
            "-",
        ],
    ] {
        let output = program().args(args).output().unwrap();
        assert!(output.status.success(), "{args:?}");
        let (stdout, stderr) = (
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr),
        );
        assert!(
            stdout.starts_with("<svg") && stdout.trim_end().ends_with("</svg>"),
            "{args:?}: {stdout}"
        );
        assert!(stderr.contains("Four-bar"), "{args:?}: {stderr}");
    }
}

/// A Watt six-bar whose second pivot is 1e200 mm away cannot be assembled, and says so (its
/// short links' squares underflowed in the second loop, and it said "singular"); dimensions
/// below the float's normal range are refused, whatever the command.
#[test]
fn far_pivots_cannot_assemble_and_subnormal_dimensions_are_refused() {
    for pivot in ["1e160", "1e200", "1e300"] {
        fails_with(
            &[
                "analyse",
                "watt-six-bar",
                "180",
                "80",
                "200",
                "150",
                "100",
                "45.8366",
                "220",
                "160",
                pivot,
                "0",
            ],
            "the Watt six-bar cannot be assembled at 60°",
        );
    }
    for command in ["analyse", "sweep"] {
        fails_with(
            &[
                command, "four-bar", "1e-321", "4e-322", "1.2e-321", "8e-322",
            ],
            "the ground 1e-321 is below the float's normal range (2.2250738585072014e-308)",
        );
    }
}

/// Option values below the float's normal range are refused too, naming the option: they
/// were taken (a robot's base of 5e-324 mm, a coupler point 5e-324 mm from its pin), or
/// underflowed to zero on the way (an angle tolerance of 5e-324°, zero in radians, gave a
/// table of zeros), or failed later without saying which input (a sweep at 5e-324 rad/s).
#[test]
fn subnormal_options_and_robot_links_are_refused_by_name() {
    let below = "is below the float's normal range (2.2250738585072014e-308)";
    fails_with(
        &["robot", "100", "200", "200", "100", "5e-324"],
        &format!("the base 5e-324 {below}"),
    );
    for (command, option, flag) in [
        (
            "tolerance",
            ["--angle-tolerance", "5e-324"],
            "--angle-tolerance 5e-324",
        ),
        (
            "sweep",
            ["--coupler-point", "5e-324,0"],
            "--coupler-point 5e-324,0",
        ),
        ("sweep", ["--rate=-5e-324", "--step=1"], "--rate -5e-324"),
    ] {
        let mut args = vec![command];
        args.extend(EXAMPLE_1);
        args.extend(option);
        fails_with(&args, &format!("{flag}: "));
        fails_with(&args, below);
    }
}

/// The robot's point acceleration that overflows says so in its line and the command goes
/// on (it printed half the report and failed), and a synthesis of no restarts is refused
/// (it reported that no linkage meets the targets, having tried none).
#[test]
fn a_robot_s_overflowing_acceleration_is_a_line_and_no_restarts_is_refused() {
    let report = stdout_of(&["robot", "--accels", "1e308,0"]);
    assert_eq!(
        report
            .matches("acceleration: point acceleration is not finite")
            .count(),
        2,
        "{report}"
    );
    assert!(
        report.contains("end effector P = (50.0000, 259.8076) mm"),
        "{report}"
    );
    fails_with(
        &[
            "synthesise",
            "function",
            "--crank",
            "30,60,90",
            "--rocker",
            "60,95.1,120",
            "--restarts",
            "0",
        ],
        "--restarts must be at least 1",
    );
}

/// An input just past a limit is told from it: two decimals said the crank reached the
/// 106.96° it cannot be assembled at (the limit is 106.9578°).
#[test]
fn an_input_just_past_a_limit_is_told_from_it() {
    fails_with(
        &[
            "analyse", "four-bar", "100", "180", "80", "150", "--at", "106.96",
        ],
        "cannot be assembled at 106.96°: the crank reaches |θ2| up to 106.958° (toggles at ±106.958°)",
    );
    fails_with(
        &[
            "analyse", "four-bar", "100", "180", "80", "150", "--at", "150",
        ],
        "cannot be assembled at 150°: the crank reaches |θ2| up to 106.96° (toggles at ±106.96°)",
    );
}

/// Jansen's leg at a crank rate whose accelerations overflow still prints its foot's
/// position and velocity (linear in the rate: 1e50 times those at 1e150 rad/s), its
/// acceleration `not finite`, as the other mechanisms' tables do: it printed nothing and
/// failed.
#[test]
fn jansen_s_leg_prints_what_does_not_overflow() {
    let report = stdout_of(&["analyse", "jansen", "--rate", "1e200"]);
    assert!(
        report.contains("foot position     (-18.1503, -91.5713) mm"),
        "{report}"
    );
    assert!(
        report.contains("foot velocity     (2.3127e201, 1.2989e200) mm/s"),
        "{report}"
    );
    assert!(report.contains("foot acceleration not finite"), "{report}");
    let slower = stdout_of(&["analyse", "jansen", "--rate", "1e150"]);
    assert!(
        slower.contains("foot velocity     (2.3127e151, 1.2989e150) mm/s"),
        "{slower}"
    );
}

/// A sweep's table written to a path that is standard output (`/dev/stdout`) is alone there,
/// as with `-`: the summary went into it, over its header.
#[cfg(unix)]
#[test]
fn a_table_to_dev_stdout_is_alone_there() {
    let scratch = Scratch::new("dev-stdout");
    let table = stdout_of(&[
        "sweep",
        "four-bar",
        "180",
        "80",
        "200",
        "150",
        "--csv",
        "/dev/stdout",
        "--out-dir",
        scratch.path(),
    ]);
    assert!(table.starts_with("input_deg,segment,"), "{table}");
    assert_eq!(table.lines().count(), 362, "{table}");
}

/// A tolerance analysis' step is a positive number of degrees up to a turn, checked before
/// anything is printed, as the sweep checks its own.
#[test]
fn tolerance_refuses_a_step_beyond_a_turn_before_printing() {
    for step in [
        "400", "1e308", "360.0001", "0", "-1", "0.0035", "inf", "nan",
    ] {
        refused_before_any_output(
            &[
                "tolerance",
                "four-bar",
                "180",
                "80",
                "200",
                "150",
                "--step",
                step,
            ],
            "--step must be a positive number of degrees from 0.0036 to 360",
        );
    }
    let report = stdout_of(&[
        "tolerance",
        "four-bar",
        "180",
        "80",
        "200",
        "150",
        "--step",
        "360",
        "--samples",
        "10",
    ]);
    let rows: Vec<&str> = report
        .lines()
        .filter(|l| l.starts_with("| 0.0 |"))
        .collect();
    assert_eq!(rows.len(), 1, "{report}");
    assert!(report.contains("at θ2 = 0.0°"), "{report}");
}

/// Tolerances must be small against what they apply to (a tenth of it), and a figure that
/// overflows is an error naming it, never `inf` in the report.
#[test]
fn tolerance_refuses_large_tolerances_and_overflowed_figures() {
    let example = ["tolerance", "four-bar", "180", "80", "200", "150"];
    let run = |extra: &[&str], message: &str| {
        let args: Vec<&str> = example.iter().chain(extra).copied().collect();
        refused_before_any_output(&args, message);
    };
    run(
        &["--tolerance", "1e308"],
        "--tolerance ±1e308 mm is not small against the ground (180 mm): each ± tolerance \
         must be under a tenth of the length it applies to",
    );
    run(
        &["--tolerance", "8"],
        "--tolerance ±8 mm is not small against the crank (80 mm)",
    );
    run(
        &["--tolerances", "0.1,0.1,25,0.1"],
        "--tolerances ±25 mm is not small against the coupler (200 mm)",
    );
    // The coupler point's distance may be zero: its tolerance is held to the shortest link.
    run(
        &["--tolerances", "0.1,0.1,0.1,0.1", "--tolerance", "9"],
        "--tolerance ±9 mm is not small against the shortest link (80 mm)",
    );
    run(
        &["--angle-tolerance", "6"],
        "--angle-tolerance ±6° is not small: it must be under a tenth of a radian (5.73°)",
    );
    // Just under the rule, and a coupler point near the float's largest (whose squared
    // deviations would overflow, were they squared as they are): a report, every figure
    // finite.
    for extra in [
        ["--tolerance", "7.9", "--step", "90", "--samples", "100"],
        [
            "--coupler-point",
            "1.79e308,0",
            "--step",
            "90",
            "--samples",
            "10",
        ],
    ] {
        let args: Vec<&str> = example.iter().chain(&extra).copied().collect();
        let report = stdout_of(&args);
        assert!(
            !report.contains("inf") && !report.contains("NaN"),
            "{report}"
        );
    }
    run(&["--samples", "0"], "--samples takes at least 1");
    // A coupler point near the float's largest whose tolerance takes it past: an overflow
    // named, not half the box's corners counted as linkages that do not assemble.
    refused_before_any_output(
        &[
            "tolerance",
            "four-bar",
            "1.8e307",
            "0.8e307",
            "2e307",
            "1.5e307",
            "--tolerance",
            "7.9e305",
            "--coupler-point",
            "1.79e308,30",
        ],
        "the coupler point's distance (1.79e308 mm) with three times its tolerance (±7.9e305 \
         mm) overflows",
    );
    // Too small to resolve: the nominal and perturbed solutions' difference would be
    // rounding.
    run(
        &["--tolerance", "1e-300"],
        "--tolerance ±1e-300 mm is too small against the ground (180 mm) for the nonlinear \
         model to resolve in f64: each ± tolerance must be zero (exact) or at least a \
         billionth of the length it applies to",
    );
    run(
        &["--angle-tolerance", "1e-12"],
        "--angle-tolerance ±1e-12° is too small",
    );
    // Links below the float's normal range: refused as every command refuses them (they
    // keep fewer bits than a float has, and their derivatives would overflow).
    refused_before_any_output(
        &[
            "tolerance",
            "four-bar",
            "1e-310",
            "4e-311",
            "1.2e-310",
            "8e-311",
            "--tolerance",
            "1e-312",
        ],
        "the ground 1e-310 is below the float's normal range (2.2250738585072014e-308)",
    );
    // Too long: the crank angles times the Monte Carlo linkages.
    run(
        &["--step", "0.0036", "--samples", "10000000"],
        "100000 crank angles times 10000000 Monte Carlo linkages is more than 100000000 \
         linkages in all",
    );
}

/// Long runs: the limits are stated in `--help` and held, and a run past a second keeps
/// standard output for its report and shows no progress where standard error is no terminal.
#[test]
fn long_runs_state_their_limits_and_keep_their_output_clean() {
    let help = stdout_of(&["synthesise", "path", "--help"]);
    assert!(help.contains("at most 1000"), "{help}");
    let help = stdout_of(&["tolerance", "--help"]);
    assert!(
        help.contains("from 0.0036") && help.contains("at most 10⁷"),
        "{help}"
    );
    refused_before_any_output(
        &[
            "synthesise",
            "function",
            "--crank",
            "1,2,3",
            "--rocker",
            "1,2,3",
            "--restarts",
            "1001",
        ],
        "--restarts takes at most 1000",
    );
    // Some seconds of work: 3600 crank angles.
    let (report, stderr) = outputs_of(&[
        "tolerance",
        "four-bar",
        "180",
        "80",
        "200",
        "150",
        "--step",
        "0.1",
    ]);
    assert_eq!(stderr, "");
    assert_eq!(
        report
            .lines()
            .filter(|l| l.starts_with("| ") && !l.starts_with("| θ2"))
            .count(),
        3600
    );
    let (x, y) = circle_targets(1.0);
    let (_, stderr) = outputs_of(&[
        "synthesise",
        "path",
        "--x",
        &x,
        "--y",
        &y,
        "--timing",
        "0,60,120,180,240,300",
        "--restarts",
        "1000",
        "--branch",
        "open",
    ]);
    assert_eq!(stderr, "");
}

/// A negative number written with an exponent or a leading dot is a number wherever one is
/// taken, positional dimensions included: never a flag clap does not know.
#[test]
fn negative_numbers_in_any_notation_are_values() {
    let report = stdout_of(&[
        "analyse",
        "slider-crank",
        "50",
        "150",
        "-2e-3",
        "--at",
        "-.5",
    ]);
    assert!(report.contains("offset -0.002 mm"), "{report}");
    assert!(report.contains("θ2 = -0.5°"), "{report}");
    let report = stdout_of(&[
        "analyse",
        "watt-six-bar",
        "180",
        "80",
        "200",
        "150",
        "100",
        "45.8366",
        "220",
        "160",
        "300",
        "150",
        "--at",
        "-6e1",
    ]);
    assert!(report.contains("θ2 = -60°"), "{report}");
    let scratch = Scratch::new("negative");
    let (table, _) = outputs_of(&[
        "sweep",
        "slider-crank",
        "50",
        "150",
        "-.5",
        "--coupler-point",
        "10,-1.5e1",
        "--csv",
        "-",
        "--out-dir",
        scratch.path(),
    ]);
    assert!(table.starts_with("input_deg,segment,"), "{table:.200}");
    fails_with(
        &[
            "tolerance",
            "four-bar",
            "180",
            "80",
            "200",
            "150",
            "--tolerance",
            "-2e-3",
        ],
        "a tolerance must be finite and not negative",
    );
    fails_with(
        &["tolerance", "four-bar", "180", "-.5", "200", "150"],
        "crank = -0.5 must be positive",
    );
    fails_with(
        &[
            "synthesise",
            "function",
            "--ground",
            "-.5",
            "--crank",
            "1,2,3",
            "--rocker",
            "1,2,3",
        ],
        "the ground length must be positive",
    );
    // 1 as well (the program's check said "at least 1", the library's "above 1").
    for ratio in ["-1e1", "1"] {
        fails_with(
            &[
                "synthesise",
                "function",
                "--crank",
                "1,2,3",
                "--rocker",
                "1,2,3",
                "--max-ratio",
                ratio,
            ],
            "--max-ratio must be a finite number above 1",
        );
    }
    fails_with(
        &["robot", "100", "200", "200", "100", "-.5"],
        "l5 = -0.5 must be",
    );
    let report = stdout_of(&["robot", "--point", "-.5e2,2.5e2"]);
    assert!(report.contains("point (-50.0000, 250.0000) mm"), "{report}");
    fails_with_code(
        &[
            "synthesise",
            "function",
            "--crank",
            "1,2,3",
            "--rocker",
            "1,2,3",
            "--restarts",
            "-1e1",
        ],
        2,
        "invalid value '-10' for '--restarts <RESTARTS>'",
    );
}

/// Messages say what is wrong with the argument, with figures a person reads.
#[test]
fn messages_name_the_argument_with_short_figures() {
    fails_with(
        &[
            "synthesise",
            "path",
            "--x",
            "0,1,2,3,4",
            "--y",
            "5,8,4,3,1",
            "--timing",
            "0,30,60,90",
        ],
        "--timing gives 4 crank angles for 5 targets: one crank angle per target",
    );
    for step in ["1e-308", "5e-324"] {
        fails_with(
            &[
                "sweep", "four-bar", "180", "80", "200", "150", "--step", step,
            ],
            &format!(
                "--step {step}° is too small: it makes more samples than can be counted, more \
                 than --max-samples 10000000: here the step must be at least 0.0000361°"
            ),
        );
    }
    fails_with_code(
        &["robot", "--point", "50,250", "--cranks", "120,60"],
        2,
        "the argument '--point <POINT>' cannot be used with '--cranks <CRANKS>'",
    );
}

/// A tolerance analysis that can analyse none of its crank angles says why at each, with the
/// library's figures to four significant digits, and prints no report.
#[test]
fn tolerance_says_why_no_crank_angle_could_be_analysed() {
    // A four-bar whose crank turns between toggles at ±90°, where the loop's Jacobian is
    // singular to rounding, and cannot reach 180°.
    let output = program()
        .args(["tolerance", "four-bar", "3", "4", "2", "3", "--step", "90"])
        .args(["--tolerance", "0.01"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("determinant -8.882e-16, relative determinant 1.48e-16"),
        "{stderr}"
    );
    assert!(
        stderr.contains("cannot be assembled at input 180°"),
        "{stderr}"
    );
    assert!(!stderr.contains("0.00000000000000"), "{stderr}");
    assert!(
        stderr.contains("the linkage assembles at none of the crank angles analysed"),
        "{stderr}"
    );
    assert_eq!(String::from_utf8_lossy(&output.stdout), "");
}
