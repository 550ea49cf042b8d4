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

fn fails_with(args: &[&str], message: &str) {
    let output = program().args(args).output().unwrap();
    assert!(!output.status.success(), "{args:?} succeeded");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains(message), "{args:?}: {stderr}");
}

#[test]
fn bad_input_is_a_clear_message_and_a_failure() {
    fails_with(
        &["analyse", "four-bar", "180", "abc", "200", "150"],
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
    fails_with(&["analyse", "hexapod", "1", "2"], "invalid value 'hexapod'");
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
    let series: Vec<&str> = document
        .descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .filter_map(|n| n.attribute("data-name"))
        .collect();
    assert_eq!(
        series,
        [
            "theta3_deg",
            "theta4_deg",
            "omega3",
            "omega4",
            "alpha3",
            "alpha4",
            "transmission_deg"
        ]
    );
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
