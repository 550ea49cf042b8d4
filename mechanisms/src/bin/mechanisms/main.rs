//! `mechanisms`: analyse a planar mechanism from the command line with the code
//! `mechgen::mechanism!` generated for it. Degrees at this edge, radians inside.
//!
//! With no arguments it analyses the course notes' Example 1 four-bar at 60°.
//! `cargo run --release -p mechanisms -- --help` lists the commands.

mod analyse;
mod angle;
mod output;
mod progress;
mod robot;
mod seeds;
mod six_bars;
mod svg;
mod sweep;
mod synthesise;
mod tolerance;

use std::ffi::OsString;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

/// Analyse planar mechanisms with kinematics code generated at compile time.
#[derive(Parser)]
#[command(name = "mechanisms", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Positions, velocities and accelerations on every branch (every assembly found, for
    /// the Stephenson six-bar), with the analyses.
    Analyse(analyse::Args),
    /// A full turn (or the reachable range) on one branch, as CSV and SVG.
    Sweep(sweep::Args),
    /// The five-bar parallel robot (two driven cranks): its end effector, rates and
    /// singularities at given cranks' angles, or the cranks that reach a given point.
    Robot(robot::Args),
    /// The course notes' worked examples next to the values the notes print.
    Seeds,
    /// How far a four-bar's output and coupler point move when its dimensions are off by
    /// their tolerances, over a turn: first order from the generated sensitivities, beside
    /// the nonlinear model (the tolerance box's corners, and Monte Carlo).
    Tolerance(tolerance::Args),
    /// A four-bar whose output follows precision points of a function, or whose coupler
    /// point passes through targets, by Levenberg-Marquardt on the generated derivatives.
    Synthesise {
        #[command(subcommand)]
        task: synthesise::Task,
    },
}

/// The mechanisms the program knows, and the dimensions each takes (mm, degrees).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Mechanism {
    /// Four-bar: ground crank coupler rocker.
    FourBar,
    /// Slider-crank: crank rod offset.
    SliderCrank,
    /// Inverted slider-crank: ground crank offset angle(°).
    InvertedSliderCrank,
    /// Theo Jansen's leg with his published lengths (no dimensions).
    Jansen,
    /// Watt six-bar: ground crank coupler rocker extension extension-angle(°)
    /// second-coupler second-rocker pivot-x pivot-y.
    WattSixBar,
    /// Stephenson six-bar: ground crank link ternary-bc ternary-cd ternary-angle(°) rocker
    /// output-rocker pivot-x pivot-y.
    StephensonSixBar,
}

impl Mechanism {
    /// How many dimensions it takes, and their names.
    pub fn dimensions(self) -> &'static [&'static str] {
        match self {
            Mechanism::FourBar => &["ground", "crank", "coupler", "rocker"],
            Mechanism::SliderCrank => &["crank", "rod", "offset"],
            Mechanism::InvertedSliderCrank => &["ground", "crank", "offset", "angle (°)"],
            Mechanism::Jansen => &[],
            Mechanism::WattSixBar => &[
                "ground",
                "crank",
                "coupler",
                "rocker",
                "extension",
                "extension-angle (°)",
                "second-coupler",
                "second-rocker",
                "pivot-x",
                "pivot-y",
            ],
            Mechanism::StephensonSixBar => &[
                "ground",
                "crank",
                "link",
                "ternary-bc",
                "ternary-cd",
                "ternary-angle (°)",
                "rocker",
                "output-rocker",
                "pivot-x",
                "pivot-y",
            ],
        }
    }

    /// Its name on the command line.
    pub fn name(self) -> String {
        self.to_possible_value()
            .map_or_else(String::new, |v| v.get_name().to_string())
    }

    /// Checks the count of dimensions given.
    pub fn check(self, given: &[f64]) -> Result<(), String> {
        let names = self.dimensions();
        if let Some((name, value)) = names
            .iter()
            .zip(given)
            .find(|(_, v)| **v != 0.0 && v.abs() < f64::MIN_POSITIVE)
        {
            return Err(format!(
                "the {name} {} is below the float's normal range ({:e}), where a number \
                 keeps fewer than its 53 bits: it would be computed as another dimension",
                output::tidy(*value),
                f64::MIN_POSITIVE
            ));
        }
        if given.len() == names.len() {
            Ok(())
        } else {
            Err(format!(
                "{} takes {} dimensions ({}), {} given",
                self.name(),
                names.len(),
                if names.is_empty() {
                    "none".to_string()
                } else {
                    names.join(" ")
                },
                given.len()
            ))
        }
    }
}

/// The program's arguments as clap is to read them: each negative number written with an
/// exponent or a leading dot (`-2e-3`, `-.5`) rewritten in plain decimals (`-0.002`, `-0.5`,
/// the same `f64`), which clap takes for a number; a negative infinity as `-1e999` (the same
/// `f64`) and a NaN as `NaN`, which the program then refuses by name.
///
/// clap takes `-2e-3` for a flag wherever a value could instead be a flag: its test for a
/// negative number (`allow_negative_numbers`) accepts digits, one dot after a digit and an
/// exponent without a sign; and the other way, `allow_hyphen_values`, on a list of dimensions
/// would swallow the flags after it (`--at`) as dimensions. An option that allows hyphen
/// values takes either form as it is.
fn arguments(given: impl Iterator<Item = OsString>) -> Vec<OsString> {
    given
        .map(|argument| {
            let plain = argument
                .to_str()
                .filter(|text| text.starts_with('-'))
                .and_then(|text| text.parse::<f64>().ok());
            plain.map_or(argument, |value| {
                if value.is_nan() {
                    // `-nan`: NaN, which no dash makes a flag of (its sign says nothing).
                    "NaN".into()
                } else if value.is_infinite() {
                    // `-inf`: a number clap takes for one, which reads as the same f64.
                    "-1e999".into()
                } else {
                    // `Display` writes an f64 without an exponent, and reads back as the same
                    // f64.
                    value.to_string().into()
                }
            })
        })
        .collect()
}

/// The first option value below the float's normal range (not zero), in words: a tolerance,
/// a target, a coupler point's distance or a ground made of one keeps fewer than its 53 bits
/// and is computed as another number, or underflows to zero on its way (a tolerance of
/// 5e-324° is zero in radians). The dimensions each command takes are refused by name where
/// it checks them, first (then this says nothing), and so is a sweep's `--step`, whose own
/// check names the samples it would take.
fn option_below_normal(given: &[OsString]) -> Option<String> {
    let below = |value: &str| {
        value
            .split(',')
            .filter_map(|part| part.trim().parse::<f64>().ok())
            .find(|v| *v != 0.0 && v.abs() < f64::MIN_POSITIVE)
    };
    let mut flag: Option<&str> = None;
    let mut found = None;
    for argument in given {
        let Some(text) = argument.to_str() else {
            flag = None;
            continue;
        };
        let (name, value) = match (text.strip_prefix("--"), flag) {
            (Some(option), _) => match option.split_once('=') {
                Some((name, value)) => (name, value),
                None => {
                    flag = Some(option);
                    continue;
                }
            },
            (None, Some(name)) => (name, text),
            (None, None) => {
                if below(text).is_some() {
                    return None;
                }
                continue;
            }
        };
        flag = None;
        if let (None, Some(tiny)) = (&found, below(value).filter(|_| name != "step")) {
            found = Some(format!(
                "--{name} {value}: {} is below the float's normal range ({:e}), where a number \
                 keeps fewer than its 53 bits: it would be computed as another number",
                output::tidy(tiny),
                f64::MIN_POSITIVE
            ));
        }
    }
    found
}

fn main() -> ExitCode {
    let given = arguments(std::env::args_os());
    if let Some(message) = option_below_normal(&given) {
        output::tell!("error: {message}");
        return ExitCode::FAILURE;
    }
    let cli = match Cli::try_parse_from(given) {
        Ok(cli) => cli,
        Err(error) => return stop_parsing(&error),
    };
    let result = match cli.command {
        None => analyse::run(&analyse::Args::example_1()),
        Some(Command::Analyse(args)) => analyse::run(&args),
        Some(Command::Sweep(args)) => sweep::run(&args),
        Some(Command::Robot(args)) => robot::run(&args),
        Some(Command::Seeds) => seeds::run().map_err(|e| e.to_string()),
        Some(Command::Tolerance(args)) => tolerance::run(&args),
        Some(Command::Synthesise { task }) => synthesise::run(&task),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            output::tell!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

/// What clap does with `error` (a usage error on standard error, with its exit code; help or
/// the version on standard output), except that help or a version that cannot be written (a
/// full disk) fails, as every report that cannot be written does, rather than exit 0.
fn stop_parsing(error: &clap::Error) -> ExitCode {
    use std::io::Write;
    let code = u8::try_from(error.exit_code()).unwrap_or(2);
    if error.use_stderr() {
        // Where standard error itself cannot be written, nothing can be told.
        let _ = error.print();
        return ExitCode::from(code);
    }
    let mut out = std::io::stdout().lock();
    match write!(out, "{}", error.render()).and_then(|()| out.flush()) {
        Ok(()) => ExitCode::from(code),
        Err(cause) => {
            output::tell!("error: cannot write to standard output: {cause}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_numbers_in_any_notation_reach_clap_in_plain_decimals() {
        let read = |given: &[&str]| -> Vec<String> {
            arguments(given.iter().map(OsString::from))
                .into_iter()
                .map(|a| a.into_string().unwrap())
                .collect()
        };
        assert_eq!(
            read(&["mechanisms", "-2e-3", "-.5", "-1E2", "-7", "2e-3"]),
            ["mechanisms", "-0.002", "-0.5", "-100", "-7", "2e-3"]
        );
        // Flags, a dash for standard output, and what is not a number stay as they are.
        assert_eq!(
            read(&["--at", "-h", "-", "--csv", "-e5"]),
            ["--at", "-h", "-", "--csv", "-e5"]
        );
        // A negative infinity or NaN as a number clap takes for one, the same f64 (`-inf` and
        // `-nan` were flags it did not know, exit 2, where `inf` is the program's refusal).
        assert_eq!(
            read(&["-inf", "-Infinity", "-nan"]),
            ["-1e999", "-1e999", "NaN"]
        );
        assert_eq!("-1e999".parse::<f64>().unwrap(), f64::NEG_INFINITY);
        // The same f64, however small.
        assert_eq!(read(&["-1e-300"])[0].parse::<f64>().unwrap(), -1e-300);
    }
}
