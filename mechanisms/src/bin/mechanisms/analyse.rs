//! `mechanisms analyse`: one input, both branches, every analysis the mechanism has.

use std::collections::BTreeSet;

use clap::Parser;
use mechanisms::{
    DimensionError, FourBar, FourBarUnknowns, InvertedSliderCrank, JansenLeg, JansenLegUnknowns,
    SliderCrank, StephensonSixBar, StephensonSixBarUnknowns, WattSixBarUnknowns,
};
use mechgen::grashof::{Class, Inversion, Special};
use mechgen::{Accuracy, Branch, Error, MechanicalAdvantage};

use crate::Mechanism;
use crate::angle;
use crate::output::{self, filled, fixed, say, tidy};
use crate::six_bars::{self, StephensonDimensions};
use crate::sweep::finite;

#[derive(Parser)]
pub struct Args {
    /// The mechanism.
    #[arg(value_enum)]
    pub mechanism: Mechanism,
    /// Its dimensions in mm (an angle in degrees), as `--help` lists for each mechanism.
    #[arg(allow_negative_numbers = true)]
    pub dimensions: Vec<f64>,
    /// The input angle, degrees.
    #[arg(long, default_value_t = 60.0, allow_hyphen_values = true)]
    pub at: f64,
    /// The input's rate, rad/s.
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true)]
    pub rate: f64,
    /// The input's acceleration, rad/s².
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub accel: f64,
    /// Also solve by Newton-Raphson from `--guess` and print every iterate (four-bar,
    /// Stephenson six-bar).
    #[arg(long)]
    pub trace: bool,
    /// Newton's starting angles in degrees, joined by a comma, for `--trace`: θ3,θ4 for the
    /// four-bar [default: 15,80], θ3,θ4,θ5,θ6 for the Stephenson six-bar [default: its first
    /// assembly's angles rounded to tens of degrees].
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub guess: Option<Vec<f64>>,
}

impl Args {
    /// The course notes' Example 1: four-bar 180/80/200/150 mm at 60°, 10 rad/s.
    pub fn example_1() -> Self {
        Args {
            mechanism: Mechanism::FourBar,
            dimensions: vec![180.0, 80.0, 200.0, 150.0],
            at: 60.0,
            rate: 10.0,
            accel: 0.0,
            trace: false,
            guess: None,
        }
    }

    /// Newton's starting angles θ3, θ4 in degrees.
    fn guess(&self) -> [f64; 2] {
        match self.guess.as_deref() {
            Some(&[theta3, theta4]) => [theta3, theta4],
            _ => [15.0, 80.0],
        }
    }
}

/// How many angles `--guess` takes for a mechanism Newton is traced on, and their names.
fn unknowns(mechanism: Mechanism) -> Option<(usize, &'static str)> {
    match mechanism {
        Mechanism::FourBar => Some((2, "two finite angles in degrees, theta3,theta4 (as 15,80)")),
        Mechanism::StephensonSixBar => Some((
            4,
            "four finite angles in degrees, theta3,theta4,theta5,theta6 (as 20,-20,-70,-150)",
        )),
        _ => None,
    }
}

/// A dimension the library refused, with its value written tidily (`1e308`, not 309 digits).
pub fn refused(error: DimensionError<f64>) -> String {
    format!(
        "{} = {} must be {}",
        error.name,
        tidy(error.value),
        error.requirement
    )
}

fn check(args: &Args) -> Result<(), String> {
    // Before the count of dimensions, which `--guess 15 80` makes one too many.
    if args.guess.as_ref().is_some_and(|g| g.len() == 1) {
        return Err(if args.mechanism == Mechanism::StephensonSixBar {
            "--guess takes four angles joined by commas, as --guess 20,-20,-70,-150".into()
        } else {
            "--guess takes two angles joined by a comma, as --guess 15,80".into()
        });
    }
    args.mechanism.check(&args.dimensions)?;
    finite("--at", args.at, "degrees")?;
    finite("--rate", args.rate, "rad/s")?;
    finite("--accel", args.accel, "rad/s²")?;
    let names = unknowns(args.mechanism);
    if args.trace && names.is_none() {
        return Err(format!(
            "--trace applies to the four-bar and the stephenson-six-bar (Newton-Raphson), not \
             the {}, which is solved in closed form",
            args.mechanism.name()
        ));
    }
    if let Some(guess) = &args.guess {
        if !args.trace {
            return Err("--guess is Newton's start for --trace, which was not given".into());
        }
        let (count, names) = names.unwrap_or_default();
        if guess.len() != count || !guess.iter().all(|g| g.is_finite()) {
            return Err(format!(
                "--guess takes {names} for the {}, got {}",
                args.mechanism.name(),
                guess.iter().map(|&g| tidy(g)).collect::<Vec<_>>().join(",")
            ));
        }
    }
    Ok(())
}

pub fn run(args: &Args) -> Result<(), String> {
    check(args)?;
    let d = &args.dimensions;
    match args.mechanism {
        Mechanism::FourBar => {
            four_bar(args, FourBar::new(d[0], d[1], d[2], d[3]).map_err(refused)?)
        }
        Mechanism::SliderCrank => {
            slider_crank(args, SliderCrank::new(d[0], d[1], d[2]).map_err(refused)?)
        }
        Mechanism::InvertedSliderCrank => inverted(
            args,
            InvertedSliderCrank::new(d[0], d[1], d[2], angle::radians(d[3])).map_err(refused)?,
        ),
        Mechanism::Jansen => jansen(args),
        Mechanism::WattSixBar => watt(args, six_bars::watt(d)?),
        Mechanism::StephensonSixBar => stephenson(args, six_bars::stephenson(d)?),
    }
}

/// [`Solved::new`] for a generated mechanism at `theta2`: `position`, then the generated
/// velocity and acceleration at the args' rates, and the errors from the generated condition
/// and Jacobian (every generated mechanism names them alike).
macro_rules! solved {
    ($linkage:expr, $theta2:expr, $args:expr, $sizes:expr, $position:expr) => {
        Solved::new(
            $position,
            |q| $linkage.velocity($theta2, q, $args.rate),
            |q, v| $linkage.acceleration($theta2, q, $args.rate, v, $args.accel),
            |q, v, a| {
                $sizes.errors(
                    $linkage.condition($theta2, q),
                    $linkage.jacobian($theta2, q),
                    v.map(|v| v.to_array()),
                    a.map(|a| a.to_array()),
                )
            },
        )
    };
}

/// What could be computed on one branch, order by order, or why not: a later order fails
/// where an earlier one did; and what each value may be off by.
struct Solved<U> {
    position: Result<U, Error<f64>>,
    velocity: Result<U, Error<f64>>,
    acceleration: Result<U, Error<f64>>,
    errors: Errors,
}

impl<U> Solved<U> {
    fn new(
        position: Result<U, Error<f64>>,
        velocity: impl Fn(&U) -> Result<U, Error<f64>>,
        acceleration: impl Fn(&U, &U) -> Result<U, Error<f64>>,
        errors: impl Fn(&U, Option<&U>, Option<&U>) -> Errors,
    ) -> Self {
        let velocity = position.as_ref().map_err(|e| *e).and_then(&velocity);
        let acceleration = match (&position, &velocity) {
            (Ok(q), Ok(v)) => acceleration(q, v),
            (Err(e), _) | (_, Err(e)) => Err(*e),
        };
        let errors = position.as_ref().map_or_else(
            |_| Errors::default(),
            |q| errors(q, velocity.as_ref().ok(), acceleration.as_ref().ok()),
        );
        Solved {
            position,
            velocity,
            acceleration,
            errors,
        }
    }
}

/// What each value of a branch's column may be off by, absolute, per order (position,
/// velocity, acceleration) and unknown, so that it is printed to those digits alone
/// ([`output::within`]): the runtime's accuracy estimate at the position
/// (`mechgen::Accuracy::estimate`, or `estimate_at` for a Newton position) from its condition
/// and aspect, relative to the sizes the contract measures by (the mechanism's size; times
/// the input's rate, or its square and acceleration, or the unknowns' rates weighted by their
/// columns where larger), over each unknown's column, doubled for the sizes' approximation.
#[derive(Clone, Debug, Default)]
struct Errors {
    orders: [Vec<f64>; 3],
}

impl Errors {
    /// Unknown `j`'s error at `order` (0 position, 1 velocity, 2 acceleration); unbounded
    /// where nothing is known.
    fn at(&self, order: usize, j: usize) -> f64 {
        self.orders[order].get(j).copied().unwrap_or(f64::INFINITY)
    }
}

/// A mechanism as [`Errors`] needs it: its lengths (whose sum is its size), which unknowns
/// are angles, whether its positions come from Newton (and then how many of the unknowns'
/// columns a position's error moves, `Accuracy::estimate_at`'s `moving`), and the input's
/// rate and acceleration.
struct Sizes {
    lengths: Vec<f64>,
    angles: &'static [bool],
    newton: Option<f64>,
    rate: f64,
    accel: f64,
}

impl Sizes {
    /// The errors at a position with this `condition` and Jacobian, given the rates and
    /// accelerations solved there (where they were).
    fn errors<const N: usize>(
        &self,
        condition: f64,
        jacobian: [[f64; N]; N],
        rates: Option<[f64; N]>,
        accelerations: Option<[f64; N]>,
    ) -> Errors {
        // In units of the longest length, so that nothing overflows for lengths near the
        // float's largest (a size of 4e308 is no number).
        let unit = self.lengths.iter().fold(0.0f64, |m, l| m.max(l.abs()));
        let size = self.lengths.iter().map(|l| l.abs() / unit).sum::<f64>();
        // Each column's norm scaled by its own largest entry (a length's column, a
        // direction, is 1/unit long here: 1e300 for a linkage of 1e-300, whose square is no
        // number).
        let columns: [f64; N] = core::array::from_fn(|j| {
            let largest = jacobian.iter().fold(0.0f64, |m, row| m.max(row[j].abs()));
            if largest == 0.0 {
                return 0.0;
            }
            let norm = jacobian
                .iter()
                .map(|row| (row[j] / largest) * (row[j] / largest))
                .sum::<f64>()
                .sqrt();
            largest / unit * norm
        });
        let shortest = columns
            .iter()
            .zip(self.angles)
            .filter(|(_, angle)| **angle)
            .fold(f64::INFINITY, |m, (c, _)| m.min(*c));
        let aspect = (size / shortest).max(1.0);
        let accuracy = match self.newton {
            Some(moving) => Accuracy::estimate_at(condition, aspect, 0.0, moving),
            None => Accuracy::estimate(condition, aspect),
        };
        let weighted = |values: Option<[f64; N]>| {
            values.map_or(0.0, |values| {
                values
                    .iter()
                    .zip(&columns)
                    .fold(0.0f64, |m, (v, c)| m.max(v.abs() * c))
            })
        };
        // Each order's scale is the larger of the size times the input's (its rate, or its
        // rate squared plus its acceleration) and the results' own, weighted.
        let inputs = [
            1.0,
            self.rate.abs(),
            self.rate * self.rate + self.accel.abs(),
        ];
        let own = [0.0, weighted(rates), weighted(accelerations)];
        let relative = [accuracy.position, accuracy.velocity, accuracy.acceleration];
        // A length's column is a direction (in these units, 1/unit long): its error is in
        // the length's own units; an angle's is radians. The small factor first: a rate near
        // the float's largest (1e308 rad/s) times the size overflows, the bound does not.
        Errors {
            orders: core::array::from_fn(|k| {
                columns
                    .iter()
                    .map(|c| {
                        let factor = 2.0 * relative[k] / c;
                        (factor * size * inputs[k]).max(factor * own[k])
                    })
                    .collect()
            }),
        }
    }
}

/// Which of a branch's results a row is computed from.
#[derive(Clone, Copy)]
enum Needs {
    Position,
    Velocity,
    Acceleration,
}

/// A report row: its label, what it needs, and its text from the position and the rate or
/// acceleration it needs (the position again for a position row), and what each may be off
/// by.
type Row<'a, U> = (&'a str, Needs, &'a dyn Fn(&U, &U, &Errors) -> String);

/// A value to 4 places; a very large or very small one in exponent form (`Z` of a linkage
/// of 1e-300 mm was `0.0000`).
fn value(v: f64) -> String {
    if v.is_finite() {
        output::figure(v)
    } else {
        "not finite".into()
    }
}

/// A mechanical advantage to the digits its driven rate's error leaves (its relative error
/// is the rate's); `undetermined` where that error is as large as the rate, whose sign and
/// size the advantage is made of.
fn advantage_within(
    ma: Result<MechanicalAdvantage<f64>, Error<f64>>,
    driven_rate: f64,
    driven_error: f64,
) -> String {
    match ma {
        // Not less (a NaN error is not either).
        Ok(MechanicalAdvantage::Finite(_))
            if driven_error.partial_cmp(&driven_rate.abs()) != Some(core::cmp::Ordering::Less) =>
        {
            "undetermined".into()
        }
        Ok(MechanicalAdvantage::Finite(v)) => {
            let relative = driven_error / (driven_rate.abs() - driven_error);
            output::within(v, v.abs() * relative)
        }
        other => advantage(other),
    }
}

/// Why a result is missing, in a table cell, and the reasons met, for the notes below.
fn reason(error: &Error<f64>, met: &mut BTreeSet<&'static str>) -> String {
    let (cell, note) = match error {
        Error::Singular { .. } => ("singular".to_string(), "singular"),
        Error::Inaccurate { estimate, .. } if estimate.is_finite() => {
            (format!("inaccurate {estimate:.0e}"), "inaccurate")
        }
        Error::Inaccurate { .. } => ("undetermined".to_string(), "undetermined"),
        Error::CannotAssemble { .. } => ("cannot assemble".to_string(), "cannot assemble"),
        Error::NonFinite { .. } => ("not finite".to_string(), "not finite"),
        _ => ("failed".to_string(), "failed"),
    };
    met.insert(note);
    cell
}

/// The notes that explain the reasons in the table's cells.
fn notes(met: &BTreeSet<&'static str>) {
    let required = Accuracy::<f64>::required();
    for note in met {
        match *note {
            "singular" => say!(
                "  singular: the loop Jacobian is singular here (a toggle or change point): \
                 the rates, and where the position is singular itself the position, are not \
                 determined by the input"
            ),
            "inaccurate" => say!(
                "  inaccurate e: the estimated relative error e is more than the {:.0e} \
                 (velocity) or {:.0e} (acceleration) required: too near a toggle or change \
                 point, with a link too short against the mechanism, or with rates whose \
                 results leave the float's range (a rate of 1e-200 rad/s squares to 1e-400)",
                required.velocity,
                required.acceleration
            ),
            "undetermined" => say!(
                "  undetermined: no digit is known: the error bound covers every value it could \
                 take (at or next to a toggle or change point, where the position's bound grows \
                 without limit), or a link is shorter than √ε (1.5e-8) of the mechanism (f64 \
                 cannot determine its angle's rates), or an input rate is lost below the \
                 float's range"
            ),
            "cannot assemble" => {
                say!("  cannot assemble: the links do not close on that branch at this input")
            }
            "not finite" => say!(
                "  not finite: the value overflows (dimensions, rate or acceleration too large)"
            ),
            _ => say!("  failed: see `analyse` at a nearby input"),
        }
    }
}

/// The table, the branches (or assemblies) side by side, each cell a value the library
/// computed within its accuracy estimate or the reason it could not.
fn table<U>(rows: &[Row<U>], columns: &[(String, &Solved<U>)]) {
    row("", columns.iter().map(|(name, _)| name.clone()).collect());
    let mut met = BTreeSet::new();
    for &(label, needs, text) in rows {
        let mut cell = |solved: &Solved<U>| {
            let other = match needs {
                Needs::Position => &solved.position,
                Needs::Velocity => &solved.velocity,
                Needs::Acceleration => &solved.acceleration,
            };
            match (&solved.position, other) {
                (Ok(q), Ok(x)) => {
                    let cell = text(q, x, &solved.errors);
                    if cell == "undetermined" {
                        met.insert("undetermined");
                    }
                    cell
                }
                (Err(e), _) | (_, Err(e)) => reason(e, &mut met),
            }
        };
        let cells = columns.iter().map(|(_, solved)| cell(solved)).collect();
        row(label, cells);
    }
    notes(&met);
}

fn row(label: &str, cells: Vec<String>) {
    let mut line = format!("  {label:<26}");
    for cell in cells {
        line.push_str(&format!(" {cell:>14}"));
    }
    say!("{line}");
}

/// The open and crossed branches' columns.
fn branches<'a, U>(open: &'a Solved<U>, crossed: &'a Solved<U>) -> [(String, &'a Solved<U>); 2] {
    [("open".into(), open), ("crossed".into(), crossed)]
}

fn advantage(ma: Result<MechanicalAdvantage<f64>, Error<f64>>) -> String {
    match ma {
        Ok(MechanicalAdvantage::Finite(v)) => value(v),
        Ok(MechanicalAdvantage::Unbounded) => "unbounded".into(),
        Err(Error::Singular { .. }) => "at a toggle".into(),
        Err(_) => "undetermined".into(),
    }
}

/// An error when no branch assembles: nothing at all could be computed. A position every
/// branch finds singular is one the mechanism takes without determining it (the isosceles
/// inverted slider-crank's change point, its slide free to turn about the crank pin on its
/// pivot): the table says `singular` on each, as a parallelogram's at its own.
fn nothing<U>(solved: &[&Solved<U>], cannot: impl Fn() -> String) -> Result<(), String> {
    if solved.iter().any(|s| s.position.is_ok()) {
        return Ok(());
    }
    let errors: Vec<&Error<f64>> = solved
        .iter()
        .filter_map(|s| s.position.as_ref().err())
        .collect();
    if errors.iter().all(|e| matches!(e, Error::Singular { .. })) {
        return Ok(());
    }
    if errors
        .iter()
        .any(|e| matches!(e, Error::CannotAssemble { .. }))
    {
        return Err(cannot());
    }
    Err(errors.first().map_or_else(&cannot, |e| output::error(e)))
}

/// Where a four-bar's crank can go, in words.
pub fn four_bar_range(linkage: &FourBar<f64>) -> String {
    four_bar_range_past(linkage, None)
}

/// [`four_bar_range`], with its ends to two decimals, or to as many more as tell them from
/// `outside` (radians), an input the crank cannot reach: at 106.96° against a limit of
/// 106.9578°, two decimals said it reached 106.96°.
fn four_bar_range_past(linkage: &FourBar<f64>, outside: Option<f64>) -> String {
    let (folded, extended) = crate::sweep::four_bar_toggles(linkage);
    if folded.is_none() && extended.is_none() {
        return "the crank turns fully".into();
    }
    let from = folded.unwrap_or(0.0);
    let to = extended.unwrap_or(180.0);
    // |θ2| within half a turn, as the limits are.
    let shown = outside.map(|input| input.sin().atan2(input.cos()).abs().to_degrees());
    let digits = (2..=12)
        .find(|&digits| {
            shown.is_none_or(|shown| {
                let at = fixed(shown, digits);
                at != fixed(from, digits) && at != fixed(to, digits)
            })
        })
        .unwrap_or(12);
    let (from, to) = (fixed(from, digits), fixed(to, digits));
    // The toggles, where the range in θ2 ends: |θ2| of 0° or 180° is inside it.
    match (folded, extended) {
        (Some(_), Some(_)) => {
            format!("the crank reaches |θ2| from {from}° to {to}° (toggles at the ends)")
        }
        (None, _) => format!("the crank reaches |θ2| up to {to}° (toggles at ±{to}°)"),
        (_, None) => {
            format!("the crank reaches |θ2| from {from}° (toggles at ±{from}°) through 180°")
        }
    }
}

fn grashof_words(linkage: &FourBar<f64>) -> String {
    let g = linkage.grashof();
    let class = match g.class {
        Class::Grashof => "class I (Grashof)",
        Class::NonGrashof => "class II (non-Grashof)",
        Class::ChangePoint => "class III (change point)",
        Class::Flat => "flat (the longest link equals the other three together)",
        Class::CannotClose => {
            "cannot close (the longest link is longer than the other three together)"
        }
    };
    let inversion = match g.inversion {
        Inversion::CrankRocker => "crank-rocker",
        Inversion::RockerCrank => "rocker-crank",
        Inversion::DoubleCrank => "double-crank",
        Inversion::DoubleRocker => "Grashof double-rocker",
        Inversion::TripleRocker => "triple-rocker",
        Inversion::Immobile => "immobile",
    };
    let special = match g.special {
        Some(Special::Parallelogram) => ", a parallelogram",
        Some(Special::Kite) => ", a kite",
        None => "",
    };
    format!("{class}, {inversion}{special}")
}

fn cannot(what: &str, input_deg: f64, reach: String) -> String {
    format!(
        "the {what} cannot be assembled at {}°: {reach}",
        tidy(input_deg)
    )
}

fn four_bar(args: &Args, linkage: FourBar<f64>) -> Result<(), String> {
    let [l1, l2, l3, l4] = linkage.lengths();
    let theta2 = angle::radians(args.at);
    let sizes = Sizes {
        lengths: vec![l1, l2, l3, l4],
        angles: &[true, true],
        newton: None,
        rate: args.rate,
        accel: args.accel,
    };
    let solve = |branch| {
        solved!(
            linkage,
            theta2,
            args,
            sizes,
            linkage.assemble(theta2, branch)
        )
    };
    let (open, crossed) = (solve(Branch::Open), solve(Branch::Crossed));
    say!(
        "Four-bar: ground {} mm, crank {} mm, coupler {} mm, rocker {} mm",
        tidy(l1),
        tidy(l2),
        tidy(l3),
        tidy(l4)
    );
    say!(
        "Grashof: {}; {}",
        grashof_words(&linkage),
        four_bar_range(&linkage)
    );
    let limits = linkage.limit_angles();
    for (name, limit) in [("folded", limits.folded), ("extended", limits.extended)] {
        if let Some(limit) = limit {
            say!("Limit angle ({name}): θ2 = ±{:.4}°", limit.to_degrees());
        }
    }
    nothing(&[&open, &crossed], || {
        cannot(
            "four-bar",
            args.at,
            four_bar_range_past(&linkage, Some(theta2)),
        )
    })?;
    let (sine, cosine) = theta2.sin_cos();
    say!(
        "Input: θ2 = {}°, ω2 = {} rad/s, α2 = {} rad/s²; Z = |A O4| = {} mm",
        tidy(args.at),
        tidy(args.rate),
        tidy(args.accel),
        value((l2 * cosine - l1).hypot(l2 * sine))
    );
    let rows: [Row<FourBarUnknowns<f64>>; 8] = [
        ("θ3 (°)", Needs::Position, &|q, _, e| {
            output::degrees_within(q.theta3, e.at(0, 0))
        }),
        ("θ4 (°)", Needs::Position, &|q, _, e| {
            output::degrees_within(q.theta4, e.at(0, 1))
        }),
        ("transmission angle γ (°)", Needs::Position, &|q, _, e| {
            output::within_span(
                linkage.transmission_angle(q).to_degrees(),
                (e.at(0, 0) + e.at(0, 1)).to_degrees(),
                180.0,
            )
        }),
        ("ω3 (rad/s)", Needs::Velocity, &|_, v, e| {
            output::within(v.theta3, e.at(1, 0))
        }),
        ("ω4 (rad/s)", Needs::Velocity, &|_, v, e| {
            output::within(v.theta4, e.at(1, 1))
        }),
        ("α3 (rad/s²)", Needs::Acceleration, &|_, a, e| {
            output::within(a.theta3, e.at(2, 0))
        }),
        ("α4 (rad/s²)", Needs::Acceleration, &|_, a, e| {
            output::within(a.theta4, e.at(2, 1))
        }),
        ("mechanical advantage T4/T2", Needs::Velocity, &|q, v, e| {
            advantage_within(
                linkage.mechanical_advantage(theta2, q),
                v.theta4,
                e.at(1, 1),
            )
        }),
    ];
    table(&rows, &branches(&open, &crossed));
    let extremes = linkage.transmission_extremes();
    say!(
        "Transmission angle over the motion: {:.2}° at θ2 = {:.2}° to {:.2}° at θ2 = {:.2}°; {}",
        extremes.min.to_degrees(),
        extremes.min_at.to_degrees(),
        extremes.max.to_degrees(),
        extremes.max_at.to_degrees(),
        if extremes.within_guideline() {
            "within 40°–140°"
        } else {
            "leaves 40°–140°"
        }
    );
    if args.trace {
        trace(args, &linkage, theta2);
    }
    Ok(())
}

/// Newton-Raphson step by step with the generated residual and Jacobian, as the notes'
/// Example 2 tabulates it. It stops, saying why, at a singular Jacobian or an iterate that is
/// no longer finite.
fn trace(args: &Args, linkage: &FourBar<f64>, theta2: f64) {
    let [guess3, guess4] = args.guess();
    say!(
        "Newton-Raphson from θ3 = {}°, θ4 = {}°:",
        tidy(guess3),
        tidy(guess4)
    );
    say!(
        "  {:>4} {:>14} {:>14} {:>14} {:>14}",
        "step",
        "θ3 (°)",
        "θ4 (°)",
        "f1 (mm)",
        "f2 (mm)"
    );
    let mut q = FourBarUnknowns {
        theta3: angle::radians(guess3),
        theta4: angle::radians(guess4),
    };
    for step in 0..=20 {
        let f = linkage.residual(theta2, &q);
        if !(f.iter().all(|r| r.is_finite()) && q.theta3.is_finite() && q.theta4.is_finite()) {
            say!("  the iterate is no longer finite: stopped");
            return;
        }
        say!(
            "  {step:>4} {:>14} {:>14} {:>14} {:>14}",
            fixed(q.theta3.to_degrees(), 6),
            fixed(q.theta4.to_degrees(), 6),
            fixed(f[0], 6),
            fixed(f[1], 6)
        );
        if f[0].abs().max(f[1].abs()) < 1e-10 * linkage.lengths().iter().sum::<f64>() {
            say!("  converged");
            return;
        }
        let j = linkage.jacobian(theta2, &q);
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det == 0.0 {
            say!("  singular Jacobian: stopped");
            return;
        }
        q.theta3 = angle::within_a_turn(q.theta3 - (f[0] * j[1][1] - j[0][1] * f[1]) / det);
        q.theta4 = angle::within_a_turn(q.theta4 - (j[0][0] * f[1] - f[0] * j[1][0]) / det);
    }
    say!("  not converged in 20 steps: stopped");
}

fn slider_crank(args: &Args, linkage: SliderCrank<f64>) -> Result<(), String> {
    let [l2, l3, c] = linkage.dimensions();
    let theta2 = angle::radians(args.at);
    let sizes = Sizes {
        lengths: vec![l2, l3, c],
        angles: &[true, false],
        newton: None,
        rate: args.rate,
        accel: args.accel,
    };
    let solve = |branch| {
        solved!(
            linkage,
            theta2,
            args,
            sizes,
            linkage.assemble(theta2, branch)
        )
    };
    let (open, crossed) = (solve(Branch::Open), solve(Branch::Crossed));
    say!(
        "Slider-crank: crank {} mm, rod {} mm, offset {} mm",
        tidy(l2),
        tidy(l3),
        tidy(c)
    );
    match (linkage.stroke(), linkage.time_ratio()) {
        (Some(stroke), Some(ratio)) => {
            say!(
                "The crank turns fully; stroke {} mm, time ratio {ratio:.4}",
                output::figure(stroke)
            )
        }
        (Some(stroke), None) => say!(
            "The crank turns fully, through a change point where the rod stands perpendicular \
             to the slide (l3 − l2 = |c|); stroke {} mm, no inner dead centre",
            output::figure(stroke)
        ),
        (None, _) if linkage.crank_turns_fully() => {
            say!("The crank turns fully; its stroke is too long to compute")
        }
        (None, _) => say!("The crank cannot turn fully (l3 − l2 < |c|)"),
    }
    nothing(&[&open, &crossed], || {
        cannot(
            "slider-crank",
            args.at,
            "the rod does not reach the slider's line there (|c − l2 sin θ2| > l3)".into(),
        )
    })?;
    say!(
        "Input: θ2 = {}°, ω2 = {} rad/s, α2 = {} rad/s²",
        tidy(args.at),
        tidy(args.rate),
        tidy(args.accel)
    );
    let rows: [Row<mechanisms::SliderCrankUnknowns<f64>>; 8] = [
        ("θ3 (°)", Needs::Position, &|q, _, e| {
            output::degrees_within(q.theta3, e.at(0, 0))
        }),
        ("d (mm)", Needs::Position, &|q, _, e| {
            // The slider is within the crank and rod's reach of the crank's pivot.
            output::within_span(q.d, e.at(0, 1), 2.0 * (l2.abs() + l3.abs()))
        }),
        ("transmission angle μ (°)", Needs::Position, &|q, _, e| {
            output::within_span(
                linkage.transmission_angle(q).to_degrees(),
                e.at(0, 0).to_degrees(),
                90.0,
            )
        }),
        ("ω3 (rad/s)", Needs::Velocity, &|_, v, e| {
            output::within(v.theta3, e.at(1, 0))
        }),
        ("ḋ (mm/s)", Needs::Velocity, &|_, v, e| {
            output::within(v.d, e.at(1, 1))
        }),
        ("α3 (rad/s²)", Needs::Acceleration, &|_, a, e| {
            output::within(a.theta3, e.at(2, 0))
        }),
        ("d̈ (mm/s²)", Needs::Acceleration, &|_, a, e| {
            output::within(a.d, e.at(2, 1))
        }),
        ("mech. advantage F/T (1/mm)", Needs::Velocity, &|q, v, e| {
            advantage_within(linkage.mechanical_advantage(theta2, q), v.d, e.at(1, 1))
        }),
    ];
    table(&rows, &branches(&open, &crossed));
    Ok(())
}

fn inverted(args: &Args, linkage: InvertedSliderCrank<f64>) -> Result<(), String> {
    let [l1, l2, c, gamma] = linkage.dimensions();
    let theta2 = angle::radians(args.at);
    let sizes = Sizes {
        lengths: vec![l1, l2, c],
        angles: &[true, false],
        newton: None,
        rate: args.rate,
        accel: args.accel,
    };
    let solve = |branch| {
        solved!(
            linkage,
            theta2,
            args,
            sizes,
            linkage.assemble(theta2, branch)
        )
    };
    let (open, crossed) = (solve(Branch::Open), solve(Branch::Crossed));
    say!(
        "Inverted slider-crank: ground {} mm, crank {} mm, offset {} mm, angle {}°",
        tidy(l1),
        tidy(l2),
        tidy(c),
        tidy(gamma.to_degrees())
    );
    nothing(&[&open, &crossed], || {
        cannot(
            "inverted slider-crank",
            args.at,
            "the slide does not pass through the crank pin there".into(),
        )
    })?;
    say!(
        "Input: θ2 = {}°, ω2 = {} rad/s, α2 = {} rad/s²",
        tidy(args.at),
        tidy(args.rate),
        tidy(args.accel)
    );
    let rows: [Row<mechanisms::InvertedSliderCrankUnknowns<f64>>; 7] = [
        ("θ4 (°)", Needs::Position, &|q, _, e| {
            output::degrees_within(q.theta4, e.at(0, 0))
        }),
        ("b (mm)", Needs::Position, &|q, _, e| {
            // The slide's point is within the ground, crank and offset's reach of its pivot.
            output::within_span(q.b, e.at(0, 1), 2.0 * (l1.abs() + l2.abs() + c.abs()))
        }),
        ("ω4 (rad/s)", Needs::Velocity, &|_, v, e| {
            output::within(v.theta4, e.at(1, 0))
        }),
        ("ḃ (mm/s)", Needs::Velocity, &|_, v, e| {
            output::within(v.b, e.at(1, 1))
        }),
        ("α4 (rad/s²)", Needs::Acceleration, &|_, a, e| {
            output::within(a.theta4, e.at(2, 0))
        }),
        ("b̈ (mm/s²)", Needs::Acceleration, &|_, a, e| {
            output::within(a.b, e.at(2, 1))
        }),
        ("mechanical advantage T4/T2", Needs::Velocity, &|q, v, e| {
            advantage_within(
                linkage.mechanical_advantage(theta2, q),
                v.theta4,
                e.at(1, 0),
            )
        }),
    ];
    table(&rows, &branches(&open, &crossed));
    Ok(())
}

fn jansen(args: &Args) -> Result<(), String> {
    let leg = JansenLeg::<f64>::holy();
    let theta = angle::radians(args.at);
    let drawn = JansenLeg::<f64>::DRAWN;
    // Accelerations that overflow (a crank at 1e200 rad/s) leave the position and the
    // velocities, which are linear in the crank's rate: those of the motion at 1 rad/s, times
    // the rate, with the same relative accuracy. The accelerations then say `not finite`, as
    // the other mechanisms' tables do.
    let (m, velocity_scale, accelerations) = match leg.motion(theta, drawn, args.rate, args.accel) {
        Ok(m) => (m, 1.0, Ok(())),
        Err(error @ Error::NonFinite { .. }) => (
            leg.motion(theta, drawn, 1.0, 0.0)
                .map_err(|e| output::error(&e))?,
            args.rate,
            Err(error),
        ),
        Err(error) => return Err(output::error(&error)),
    };
    let velocities = m.velocity.to_array().map(|w| w * velocity_scale);
    let p = leg
        .points(theta, &m.position)
        .map_err(|e| output::error(&e))?;
    let v = leg
        .point_velocities(
            theta,
            &m.position,
            args.rate,
            &JansenLegUnknowns::from_array(velocities),
        )
        .map(|v| v.foot);
    let a = accelerations.and_then(|()| {
        leg.point_accelerations(
            theta,
            &m.position,
            args.rate,
            &m.velocity,
            args.accel,
            &m.acceleration,
        )
        .map(|a| a.foot)
    });
    say!(
        "Jansen's leg (a 38, b 41.5, c 39.3, d 40.1, e 55.8, f 39.4, g 36.7, h 65.7, i 49, j 50, k 61.9, l 7.8, m 15 mm), as drawn"
    );
    say!(
        "Input: crank at {}°, {} rad/s, {} rad/s²",
        tidy(args.at),
        tidy(args.rate),
        tidy(args.accel)
    );
    // The foot hangs from every unknown angle in turn, each off by at most its order's
    // error relative to the sizes the motion's accuracy is stated against (the leg's size,
    // the sum of its lengths, times the crank's rate, or its square and acceleration, or the
    // unknowns' rates weighted by the size, more than their columns): the foot by that many
    // times over, doubled.
    let size: f64 = [
        38.0, 41.5, 39.3, 40.1, 55.8, 39.4, 36.7, 65.7, 49.0, 50.0, 61.9, 7.8, 15.0,
    ]
    .iter()
    .sum();
    let weighted = |values: &[f64]| -> f64 { values.iter().map(|x| x.abs()).sum::<f64>() * size };
    let scales = [
        size,
        size * args.rate.abs() + weighted(&velocities),
        size * (args.rate * args.rate + args.accel.abs()) + weighted(&m.acceleration.to_array()),
    ];
    let accuracy = [
        m.accuracy.position,
        m.accuracy.velocity,
        m.accuracy.acceleration,
    ];
    let unknowns = m.position.to_array().len() as f64;
    let error = |k: usize| 2.0 * unknowns * accuracy[k] * scales[k];
    for (k, (what, unit, value)) in [
        ("position    ", "mm", Ok(p.foot)),
        ("velocity    ", "mm/s", v),
        ("acceleration", "mm/s²", a),
    ]
    .into_iter()
    .enumerate()
    {
        match value {
            Ok(value) => say!(
                "  foot {what} ({}, {}) {unit}",
                output::within(value.x, error(k)),
                output::within(value.y, error(k))
            ),
            Err(Error::NonFinite { quantity }) => {
                say!("  foot {what} not finite ({quantity} overflows)")
            }
            Err(error) => return Err(output::error(&error)),
        }
    }
    Ok(())
}

/// A [`Row`] that owns its label and text.
type OwnedRow<U> = (String, Needs, Box<dyn Fn(&U, &U, &Errors) -> String>);

/// The four angles, rates and accelerations of a six-bar's unknowns, as table rows.
fn six_bar_rows<U: 'static>(array: fn(&U) -> [f64; 4]) -> Vec<OwnedRow<U>> {
    let mut rows: Vec<OwnedRow<U>> = Vec::new();
    for (k, n) in [3, 4, 5, 6].into_iter().enumerate() {
        rows.push((
            format!("θ{n} (°)"),
            Needs::Position,
            Box::new(move |q, _, e| output::degrees_within(array(q)[k], e.at(0, k))),
        ));
    }
    for (k, n) in [3, 4, 5, 6].into_iter().enumerate() {
        rows.push((
            format!("ω{n} (rad/s)"),
            Needs::Velocity,
            Box::new(move |_, v, e| output::within(array(v)[k], e.at(1, k))),
        ));
    }
    for (k, n) in [3, 4, 5, 6].into_iter().enumerate() {
        rows.push((
            format!("α{n} (rad/s²)"),
            Needs::Acceleration,
            Box::new(move |_, a, e| output::within(array(a)[k], e.at(2, k))),
        ));
    }
    rows
}

/// A six-bar's lengths from its ten dimensions as the program takes them: every length and
/// the pivot's distance, but the angle at `angle` (degrees).
fn six_bar_lengths(d: &[f64], angle: usize) -> Vec<f64> {
    d[..8]
        .iter()
        .enumerate()
        .filter(|(k, _)| *k != angle)
        .map(|(_, l)| *l)
        .chain([d[8].hypot(d[9])])
        .collect()
}

/// A Watt six-bar: each of the four branch pairs (one branch per loop), in closed form.
fn watt(args: &Args, linkage: mechanisms::WattSixBar<f64>) -> Result<(), String> {
    let d = &args.dimensions;
    let theta2 = angle::radians(args.at);
    let pairs = [
        [Branch::Open, Branch::Open],
        [Branch::Open, Branch::Crossed],
        [Branch::Crossed, Branch::Open],
        [Branch::Crossed, Branch::Crossed],
    ];
    let sizes = Sizes {
        lengths: six_bar_lengths(d, 5),
        angles: &[true; 4],
        newton: None,
        rate: args.rate,
        accel: args.accel,
    };
    let solved: Vec<Solved<WattSixBarUnknowns<f64>>> = pairs
        .iter()
        .map(|&pair| solved!(linkage, theta2, args, sizes, linkage.assemble(theta2, pair)))
        .collect();
    say!(
        "{}",
        filled(
            "Watt six-bar: four-bar {} {} {} {} mm; extension {} mm at {}° from the rocker; \
             second coupler {} mm, second rocker {} mm from O6 = ({}, {}) mm",
            d
        )
    );
    let all: Vec<&Solved<_>> = solved.iter().collect();
    nothing(&all, || {
        cannot(
            "Watt six-bar",
            args.at,
            "neither loop pair closes there (`sweep` lists the ranges where they do)".into(),
        )
    })?;
    say!(
        "Input: θ2 = {}°, ω2 = {} rad/s, α2 = {} rad/s²; each column a branch per loop, \
         in closed form",
        tidy(args.at),
        tidy(args.rate),
        tidy(args.accel)
    );
    let rows = six_bar_rows(|q: &WattSixBarUnknowns<f64>| q.to_array());
    let rows: Vec<Row<WattSixBarUnknowns<f64>>> = rows
        .iter()
        .map(|(label, needs, text)| (label.as_str(), *needs, text.as_ref()))
        .collect();
    let columns: Vec<(String, &Solved<_>)> = pairs
        .iter()
        .zip(&solved)
        .map(|(pair, s)| (format!("{},{}", word(pair[0]), word(pair[1])), s))
        .collect();
    table(&rows, &columns);
    Ok(())
}

fn word(branch: Branch) -> &'static str {
    match branch {
        Branch::Open => "open",
        Branch::Crossed => "crossed",
    }
}

/// A Stephenson six-bar: every assembly the scan finds at the input, each solved by the
/// generated Newton, with its rates.
fn stephenson(args: &Args, linkage: StephensonSixBar<f64>) -> Result<(), String> {
    let d = &args.dimensions;
    let theta2 = angle::radians(args.at);
    let found = six_bars::stephenson_assemblies(&linkage, &StephensonDimensions::new(d), theta2);
    say!(
        "{}",
        filled(
            "Stephenson six-bar: ground {} mm, crank {} mm, link {} mm; ternary link B C {} \
             mm, C D {} mm at {}°; rocker O4 C {} mm, output rocker {} mm from O6 = ({}, {}) mm",
            d
        )
    );
    if found.is_empty() {
        return Err(cannot(
            "Stephenson six-bar",
            args.at,
            "no position closes both loops there (a scan of the rocker angle found none)".into(),
        ));
    }
    say!(
        "Input: θ2 = {}°, ω2 = {} rad/s, α2 = {} rad/s²; {} {} found by a scan of θ4 \
         (no closed form), each solved by Newton",
        tidy(args.at),
        tidy(args.rate),
        tidy(args.accel),
        found.len(),
        if found.len() == 1 {
            "assembly"
        } else {
            "assemblies"
        }
    );
    let sizes = Sizes {
        lengths: six_bar_lengths(d, 5),
        angles: &[true; 4],
        // Four angles, each turning its own columns.
        newton: Some(4.0),
        rate: args.rate,
        accel: args.accel,
    };
    let solved: Vec<Solved<StephensonSixBarUnknowns<f64>>> = found
        .iter()
        .map(|&q| solved!(linkage, theta2, args, sizes, Ok(q)))
        .collect();
    let rows = six_bar_rows(|q: &StephensonSixBarUnknowns<f64>| q.to_array());
    let rows: Vec<Row<StephensonSixBarUnknowns<f64>>> = rows
        .iter()
        .map(|(label, needs, text)| (label.as_str(), *needs, text.as_ref()))
        .collect();
    let columns: Vec<(String, &Solved<_>)> = solved
        .iter()
        .enumerate()
        .map(|(k, s)| (format!("assembly {}", k + 1), s))
        .collect();
    table(&rows, &columns);
    if args.trace {
        // From the guess given, or the first assembly read off a drawing to tens of degrees.
        let guess = match args.guess.as_deref() {
            Some(&[a, b, c, e]) => [a, b, c, e],
            _ => found[0]
                .to_array()
                .map(|t| (t.to_degrees() / 10.0).round() * 10.0),
        };
        stephenson_trace(&linkage, d, theta2, guess);
    }
    Ok(())
}

/// Newton-Raphson on all four unknowns with the generated residual and Jacobian (the
/// generated `position` iterates on θ3 and θ4 alone, closing the second loop inside), each
/// step solved by Gaussian elimination with partial pivoting. It stops, saying why, at a
/// singular Jacobian or an iterate that is no longer finite.
fn stephenson_trace(linkage: &StephensonSixBar<f64>, d: &[f64], theta2: f64, guess: [f64; 4]) {
    say!(
        "Newton-Raphson from θ3 = {}°, θ4 = {}°, θ5 = {}°, θ6 = {}°:",
        tidy(guess[0]),
        tidy(guess[1]),
        tidy(guess[2]),
        tidy(guess[3])
    );
    say!(
        "  {:>4} {:>12} {:>12} {:>12} {:>12} {:>14}",
        "step",
        "θ3 (°)",
        "θ4 (°)",
        "θ5 (°)",
        "θ6 (°)",
        "max |f| (mm)"
    );
    // The four-bar trace's rule: converged when the residual is 1e-10 of the linkage's size.
    let size: f64 = d[..5].iter().chain(&d[6..8]).sum::<f64>() + d[8].hypot(d[9]);
    let mut q = guess.map(angle::radians);
    for step in 0..=30 {
        let position = StephensonSixBarUnknowns::from_array(q);
        let f = linkage.residual(theta2, &position);
        let norm = f.iter().fold(0.0_f64, |m, r| m.max(r.abs()));
        if !(norm.is_finite() && q.iter().all(|t| t.is_finite())) {
            say!("  the iterate is no longer finite: stopped");
            return;
        }
        say!(
            "  {step:>4} {:>12} {:>12} {:>12} {:>12} {:>14}",
            fixed(q[0].to_degrees(), 6),
            fixed(q[1].to_degrees(), 6),
            fixed(q[2].to_degrees(), 6),
            fixed(q[3].to_degrees(), 6),
            format!("{norm:.3e}")
        );
        if norm < 1e-10 * size {
            say!("  converged");
            return;
        }
        let Some(delta) = solve(linkage.jacobian(theta2, &position), f) else {
            say!("  singular Jacobian: stopped");
            return;
        };
        for (t, dt) in q.iter_mut().zip(delta) {
            *t = angle::within_a_turn(*t - dt);
        }
    }
    say!("  not converged in 30 steps: stopped");
}

/// `x` with `a·x = b`, by Gaussian elimination with partial pivoting; `None` for a zero pivot.
fn solve<const N: usize>(mut a: [[f64; N]; N], mut b: [f64; N]) -> Option<[f64; N]> {
    for column in 0..N {
        let pivot =
            (column..N).max_by(|&i, &j| a[i][column].abs().total_cmp(&a[j][column].abs()))?;
        if a[pivot][column] == 0.0 {
            return None;
        }
        a.swap(column, pivot);
        b.swap(column, pivot);
        let pivot_row = a[column];
        for row in column + 1..N {
            let factor = a[row][column] / pivot_row[column];
            for (entry, above) in a[row].iter_mut().zip(pivot_row).skip(column) {
                *entry -= factor * above;
            }
            b[row] -= factor * b[column];
        }
    }
    let mut x = [0.0; N];
    for row in (0..N).rev() {
        let tail: f64 = (row + 1..N).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - tail) / a[row][row];
    }
    Some(x)
}
