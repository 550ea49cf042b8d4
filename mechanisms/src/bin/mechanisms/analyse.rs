//! `mechanisms analyse`: one input, both branches, every analysis the mechanism has.

use clap::Parser;
use mechanisms::{FourBar, FourBarUnknowns, InvertedSliderCrank, JansenLeg, SliderCrank};
use mechgen::grashof::{Class, Inversion, Special};
use mechgen::{Branch, Error, MechanicalAdvantage};

use crate::Mechanism;

#[derive(Parser)]
pub struct Args {
    /// The mechanism.
    #[arg(value_enum)]
    pub mechanism: Mechanism,
    /// Its dimensions in mm (an angle in degrees), as `--help` lists for each mechanism.
    #[arg(allow_negative_numbers = true)]
    pub dimensions: Vec<f64>,
    /// The input angle, degrees.
    #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
    pub at: f64,
    /// The input's rate, rad/s.
    #[arg(long, default_value_t = 10.0, allow_negative_numbers = true)]
    pub rate: f64,
    /// The input's acceleration, rad/s².
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub accel: f64,
    /// Also solve by Newton-Raphson from `--guess` and print every iterate (four-bar).
    #[arg(long)]
    pub trace: bool,
    /// Newton's starting angles θ3,θ4 in degrees, for `--trace`.
    #[arg(long, value_delimiter = ',', default_values_t = [15.0, 80.0], allow_negative_numbers = true)]
    pub guess: Vec<f64>,
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
            guess: vec![15.0, 80.0],
        }
    }
}

pub fn run(args: &Args) -> Result<(), String> {
    args.mechanism.check(&args.dimensions)?;
    if args.guess.len() != 2 {
        return Err("--guess takes two angles: theta3,theta4".into());
    }
    let d = &args.dimensions;
    match args.mechanism {
        Mechanism::FourBar => four_bar(
            args,
            FourBar::new(d[0], d[1], d[2], d[3]).map_err(|e| e.to_string())?,
        ),
        Mechanism::SliderCrank => slider_crank(
            args,
            SliderCrank::new(d[0], d[1], d[2]).map_err(|e| e.to_string())?,
        ),
        Mechanism::InvertedSliderCrank => inverted(
            args,
            InvertedSliderCrank::new(d[0], d[1], d[2], d[3].to_radians())
                .map_err(|e| e.to_string())?,
        ),
        Mechanism::Jansen => jansen(args),
    }
}

/// An angle for display: degrees in [0, 360).
pub fn degrees(radians: f64) -> f64 {
    radians.to_degrees().rem_euclid(360.0)
}

/// A report row: its label and how to compute it from a branch's motion.
type Row<'a, M> = (&'a str, &'a dyn Fn(&M) -> String);

fn row(label: &str, open: String, crossed: String) {
    println!("  {label:<26} {open:>14} {crossed:>14}");
}

fn advantage(ma: Result<MechanicalAdvantage<f64>, Error<f64>>) -> String {
    match ma {
        Ok(MechanicalAdvantage::Finite(v)) => format!("{v:.4}"),
        Ok(MechanicalAdvantage::Unbounded) => "unbounded".into(),
        Err(_) => "at a toggle".into(),
    }
}

/// Where a four-bar's crank can go, in words.
pub fn four_bar_range(linkage: &FourBar<f64>) -> String {
    let limits = linkage.limit_angles();
    if limits.full_turn() {
        return "the crank turns fully".into();
    }
    let from = limits.folded.map_or(0.0, f64::to_degrees);
    let to = limits.extended.map_or(180.0, f64::to_degrees);
    format!("the crank reaches |θ2| from {from:.2}° to {to:.2}° (toggles at the ends)")
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
    format!("the {what} cannot be assembled at {input_deg}°: {reach}")
}

fn four_bar(args: &Args, linkage: FourBar<f64>) -> Result<(), String> {
    let [l1, l2, l3, l4] = linkage.lengths();
    let theta2 = args.at.to_radians();
    println!("Four-bar: ground {l1} mm, crank {l2} mm, coupler {l3} mm, rocker {l4} mm");
    println!(
        "Grashof: {}; {}",
        grashof_words(&linkage),
        four_bar_range(&linkage)
    );
    let limits = linkage.limit_angles();
    for (name, limit) in [("folded", limits.folded), ("extended", limits.extended)] {
        if let Some(limit) = limit {
            println!("Limit angle ({name}): θ2 = ±{:.4}°", limit.to_degrees());
        }
    }
    let solve = |branch| linkage.motion(theta2, branch, args.rate, args.accel);
    let (open, crossed) = match (solve(Branch::Open), solve(Branch::Crossed)) {
        (Ok(o), Ok(c)) => (o, c),
        (Err(Error::CannotAssemble { .. }), _) | (_, Err(Error::CannotAssemble { .. })) => {
            return Err(cannot("four-bar", args.at, four_bar_range(&linkage)));
        }
        (Err(e), _) | (_, Err(e)) => return Err(format!("at {}°: {e}", args.at)),
    };
    let pin = linkage
        .points(theta2, &open.position)
        .map_err(|e| e.to_string())?
        .crank_pin;
    println!(
        "Input: θ2 = {}°, ω2 = {} rad/s, α2 = {} rad/s²; Z = |A O4| = {:.4} mm",
        args.at,
        args.rate,
        args.accel,
        (pin.x - l1).hypot(pin.y)
    );
    row("", "open".into(), "crossed".into());
    type M = mechgen::Motion<FourBarUnknowns<f64>, f64>;
    let rows: [Row<M>; 8] = [
        ("θ3 (°)", &|m| {
            format!("{:.4}", degrees(m.position.theta3))
        }),
        ("θ4 (°)", &|m| {
            format!("{:.4}", degrees(m.position.theta4))
        }),
        ("transmission angle γ (°)", &|m| {
            format!(
                "{:.4}",
                linkage.transmission_angle(&m.position).to_degrees()
            )
        }),
        ("ω3 (rad/s)", &|m| format!("{:.4}", m.velocity.theta3)),
        ("ω4 (rad/s)", &|m| format!("{:.4}", m.velocity.theta4)),
        ("α3 (rad/s²)", &|m| {
            format!("{:.4}", m.acceleration.theta3)
        }),
        ("α4 (rad/s²)", &|m| {
            format!("{:.4}", m.acceleration.theta4)
        }),
        ("mechanical advantage T4/T2", &|m| {
            advantage(linkage.mechanical_advantage(theta2, &m.position))
        }),
    ];
    for (label, f) in rows {
        row(label, f(&open), f(&crossed));
    }
    let extremes = linkage.transmission_extremes();
    println!(
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
/// Example 2 tabulates it.
fn trace(args: &Args, linkage: &FourBar<f64>, theta2: f64) {
    println!(
        "Newton-Raphson from θ3 = {}°, θ4 = {}°:",
        args.guess[0], args.guess[1]
    );
    println!(
        "  {:>4} {:>14} {:>14} {:>14} {:>14}",
        "step", "θ3 (°)", "θ4 (°)", "f1 (mm)", "f2 (mm)"
    );
    let mut q = FourBarUnknowns {
        theta3: args.guess[0].to_radians(),
        theta4: args.guess[1].to_radians(),
    };
    for step in 0..=20 {
        let f = linkage.residual(theta2, &q);
        println!(
            "  {step:>4} {:>14.6} {:>14.6} {:>14.6} {:>14.6}",
            q.theta3.to_degrees(),
            q.theta4.to_degrees(),
            f[0],
            f[1]
        );
        if f[0].abs().max(f[1].abs()) < 1e-10 * linkage.lengths().iter().sum::<f64>() {
            break;
        }
        let j = linkage.jacobian(theta2, &q);
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det == 0.0 {
            println!("  singular Jacobian: stopped");
            break;
        }
        q.theta3 -= (f[0] * j[1][1] - j[0][1] * f[1]) / det;
        q.theta4 -= (j[0][0] * f[1] - f[0] * j[1][0]) / det;
    }
}

fn slider_crank(args: &Args, linkage: SliderCrank<f64>) -> Result<(), String> {
    let [l2, l3, c] = linkage.dimensions();
    let theta2 = args.at.to_radians();
    println!("Slider-crank: crank {l2} mm, rod {l3} mm, offset {c} mm");
    match (linkage.stroke(), linkage.time_ratio()) {
        (Some(stroke), Some(ratio)) => {
            println!("The crank turns fully; stroke {stroke:.4} mm, time ratio {ratio:.4}")
        }
        (Some(stroke), None) => println!(
            "The crank turns fully, through a change point where the rod stands perpendicular \
             to the slide (l3 − l2 = |c|); stroke {stroke:.4} mm, no inner dead centre"
        ),
        (None, _) => println!("The crank cannot turn fully (l3 − l2 < |c|)"),
    }
    let solve = |branch| linkage.motion(theta2, branch, args.rate, args.accel);
    let (open, crossed) = match (solve(Branch::Open), solve(Branch::Crossed)) {
        (Ok(o), Ok(c)) => (o, c),
        (Err(e), _) | (_, Err(e)) => {
            return Err(match e {
                Error::CannotAssemble { .. } => cannot(
                    "slider-crank",
                    args.at,
                    "the rod does not reach the slider's line there (|c − l2 sin θ2| > l3)".into(),
                ),
                other => format!("at {}°: {other}", args.at),
            });
        }
    };
    println!(
        "Input: θ2 = {}°, ω2 = {} rad/s, α2 = {} rad/s²",
        args.at, args.rate, args.accel
    );
    row("", "open".into(), "crossed".into());
    type M = mechgen::Motion<mechanisms::SliderCrankUnknowns<f64>, f64>;
    let rows: [Row<M>; 8] = [
        ("θ3 (°)", &|m| {
            format!("{:.4}", degrees(m.position.theta3))
        }),
        ("d (mm)", &|m| format!("{:.4}", m.position.d)),
        ("transmission angle μ (°)", &|m| {
            format!(
                "{:.4}",
                linkage.transmission_angle(&m.position).to_degrees()
            )
        }),
        ("ω3 (rad/s)", &|m| format!("{:.4}", m.velocity.theta3)),
        ("ḋ (mm/s)", &|m| format!("{:.4}", m.velocity.d)),
        ("α3 (rad/s²)", &|m| {
            format!("{:.4}", m.acceleration.theta3)
        }),
        ("d̈ (mm/s²)", &|m| format!("{:.4}", m.acceleration.d)),
        ("mech. advantage F/T (1/mm)", &|m| {
            advantage(linkage.mechanical_advantage(theta2, &m.position))
        }),
    ];
    for (label, f) in rows {
        row(label, f(&open), f(&crossed));
    }
    Ok(())
}

fn inverted(args: &Args, linkage: InvertedSliderCrank<f64>) -> Result<(), String> {
    let [l1, l2, c, gamma] = linkage.dimensions();
    let theta2 = args.at.to_radians();
    println!(
        "Inverted slider-crank: ground {l1} mm, crank {l2} mm, offset {c} mm, angle {}°",
        gamma.to_degrees()
    );
    let solve = |branch| linkage.motion(theta2, branch, args.rate, args.accel);
    let (open, crossed) = match (solve(Branch::Open), solve(Branch::Crossed)) {
        (Ok(o), Ok(c)) => (o, c),
        (Err(e), _) | (_, Err(e)) => return Err(format!("at {}°: {e}", args.at)),
    };
    println!(
        "Input: θ2 = {}°, ω2 = {} rad/s, α2 = {} rad/s²",
        args.at, args.rate, args.accel
    );
    row("", "open".into(), "crossed".into());
    type M = mechgen::Motion<mechanisms::InvertedSliderCrankUnknowns<f64>, f64>;
    let rows: [Row<M>; 7] = [
        ("θ4 (°)", &|m| {
            format!("{:.4}", degrees(m.position.theta4))
        }),
        ("b (mm)", &|m| format!("{:.4}", m.position.b)),
        ("ω4 (rad/s)", &|m| format!("{:.4}", m.velocity.theta4)),
        ("ḃ (mm/s)", &|m| format!("{:.4}", m.velocity.b)),
        ("α4 (rad/s²)", &|m| {
            format!("{:.4}", m.acceleration.theta4)
        }),
        ("b̈ (mm/s²)", &|m| format!("{:.4}", m.acceleration.b)),
        ("mechanical advantage T4/T2", &|m| {
            advantage(linkage.mechanical_advantage(theta2, &m.position))
        }),
    ];
    for (label, f) in rows {
        row(label, f(&open), f(&crossed));
    }
    Ok(())
}

fn jansen(args: &Args) -> Result<(), String> {
    let leg = JansenLeg::<f64>::holy();
    let theta = args.at.to_radians();
    let m = leg
        .motion(theta, JansenLeg::<f64>::DRAWN, args.rate, args.accel)
        .map_err(|e| e.to_string())?;
    let p = leg.points(theta, &m.position).map_err(|e| e.to_string())?;
    let v = leg
        .point_velocities(theta, &m.position, args.rate, &m.velocity)
        .map_err(|e| e.to_string())?;
    let a = leg
        .point_accelerations(
            theta,
            &m.position,
            args.rate,
            &m.velocity,
            args.accel,
            &m.acceleration,
        )
        .map_err(|e| e.to_string())?;
    println!(
        "Jansen's leg (a 38, b 41.5, c 39.3, d 40.1, e 55.8, f 39.4, g 36.7, h 65.7, i 49, j 50, k 61.9, l 7.8, m 15 mm), as drawn"
    );
    println!(
        "Input: crank at {}°, {} rad/s, {} rad/s²",
        args.at, args.rate, args.accel
    );
    println!("  foot position      ({:.4}, {:.4}) mm", p.foot.x, p.foot.y);
    println!(
        "  foot velocity      ({:.4}, {:.4}) mm/s",
        v.foot.x, v.foot.y
    );
    println!(
        "  foot acceleration  ({:.4}, {:.4}) mm/s²",
        a.foot.x, a.foot.y
    );
    Ok(())
}
