//! `mechanisms`: analyse a planar mechanism from the command line with the code
//! `mechgen::mechanism!` generated for it. Degrees at this edge, radians inside.
//!
//! With no arguments it analyses the course notes' Example 1 four-bar at 60°.
//! `cargo run --release -p mechanisms -- --help` lists the commands.

mod analyse;
mod angle;
mod output;
mod robot;
mod seeds;
mod six_bars;
mod svg;
mod sweep;
mod synthesise;
mod tolerance;

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

fn main() -> ExitCode {
    let cli = Cli::parse();
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
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}
