//! mechgen against the independent 60-digit references of `tests/reference/cases.csv` (made
//! by `tests/reference/generate.py`): positions from the generated closed forms, rates from
//! the generated velocity and acceleration, in f64 and f32.

use mechanisms::{FourBar, InvertedSliderCrank, SliderCrank};
use mechgen::{Accuracy, Branch, Error, Order, Real};

/// The reference CSV, built into the tests so they need no files at run time.
pub const CASES_CSV: &str = include_str!("../reference/cases.csv");

/// The input rate and acceleration the references use.
pub const OMEGA2: f64 = 1.0;
pub const ALPHA2: f64 = 0.5;

/// What the reference says about a position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// It assembles and has finite rates.
    Ok,
    /// It assembles, but the Jacobian is exactly singular: no rates.
    Singular,
    /// The loop cannot close there.
    Cannot,
}

/// One reference case.
#[derive(Clone, Debug)]
pub struct Case {
    pub mechanism: String,
    pub case: String,
    pub precision: String,
    pub branch: Branch,
    pub params: Vec<f64>,
    pub input: f64,
    /// How far the input is from the singular or special position, as written (`1e-6`).
    pub delta: String,
    pub status: Status,
    /// Unknowns, their rates and accelerations, and the condition estimate.
    pub q: [f64; 2],
    pub q_dot: [f64; 2],
    pub q_ddot: [f64; 2],
    pub condition: f64,
    /// The norms of the Jacobian's columns at the reference position: how far the loops move
    /// per unit of each unknown (a length for an angle, 1 for a length).
    pub columns: [f64; 2],
}

fn pair(fields: &[&str]) -> [f64; 2] {
    let parse = |s: &str| {
        if s.is_empty() {
            f64::NAN
        } else {
            s.parse().expect("a number")
        }
    };
    [parse(fields[0]), parse(fields[1])]
}

/// Every reference case.
pub fn cases() -> Vec<Case> {
    CASES_CSV
        .lines()
        .skip(1)
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            Case {
                mechanism: f[0].to_string(),
                case: f[1].to_string(),
                precision: f[2].to_string(),
                branch: if f[3] == "open" {
                    Branch::Open
                } else {
                    Branch::Crossed
                },
                params: f[4]
                    .split(' ')
                    .map(|p| p.parse().expect("a parameter"))
                    .collect(),
                input: f[5].parse().expect("an input"),
                delta: f[6].to_string(),
                status: match f[7] {
                    "ok" => Status::Ok,
                    "singular" => Status::Singular,
                    _ => Status::Cannot,
                },
                q: pair(&f[8..10]),
                q_dot: pair(&f[10..12]),
                q_ddot: pair(&f[12..14]),
                condition: if f[14].is_empty() {
                    f64::NAN
                } else {
                    f[14].parse().expect("κ")
                },
                columns: pair(&f[15..17]),
            }
        })
        .collect()
}

/// What mechgen computed, as f64 whatever the precision it computed in.
#[derive(Clone, Copy, Debug)]
pub struct Computed {
    pub position: Result<[f64; 2], Error<f64>>,
    pub branch: Option<Branch>,
    pub velocity: Option<Result<[f64; 2], Error<f64>>>,
    pub acceleration: Option<Result<[f64; 2], Error<f64>>>,
}

fn widen<T: Real>(values: [T; 2]) -> [f64; 2] {
    values.map(|v| v.to_f64().unwrap_or(f64::NAN))
}

/// An error in `T`, with its numbers widened to `f64`.
pub fn widen_error<T: Real>(error: Error<T>) -> Error<f64> {
    let f = |v: T| v.to_f64().unwrap_or(f64::NAN);
    match error {
        Error::NonFinite { quantity } => Error::NonFinite { quantity },
        Error::CannotAssemble { input } => Error::CannotAssemble { input: f(input) },
        Error::Singular {
            determinant,
            relative_determinant,
        } => Error::Singular {
            determinant: f(determinant),
            relative_determinant: f(relative_determinant),
        },
        Error::Inaccurate {
            order,
            estimate,
            required,
        } => Error::Inaccurate {
            order,
            estimate: f(estimate),
            required: f(required),
        },
        Error::OtherBranch => Error::OtherBranch,
        Error::NoConvergence {
            iterations,
            residual_norm,
        } => Error::NoConvergence {
            iterations,
            residual_norm: f(residual_norm),
        },
        _ => Error::NonFinite {
            quantity: "unknown error",
        },
    }
}

macro_rules! compute {
    ($linkage:expr, $input:expr, $branch:expr) => {{
        let linkage = $linkage;
        let input = $input;
        match linkage.assemble(input, $branch) {
            Err(error) => Computed {
                position: Err(widen_error(error)),
                branch: None,
                velocity: None,
                acceleration: None,
            },
            Ok(q) => {
                let omega = Real::constant(OMEGA2);
                let alpha = Real::constant(ALPHA2);
                let velocity = linkage.velocity(input, &q, omega);
                let acceleration = velocity
                    .as_ref()
                    .ok()
                    .map(|v| linkage.acceleration(input, &q, omega, v, alpha));
                Computed {
                    position: Ok(widen(q.to_array())),
                    branch: Some(linkage.branch_of(input, &q)),
                    velocity: Some(velocity.map(|v| widen(v.to_array())).map_err(widen_error)),
                    acceleration: acceleration
                        .map(|a| a.map(|a| widen(a.to_array())).map_err(widen_error)),
                }
            }
        }
    }};
}

fn compute_in<T: Real>(case: &Case) -> Computed {
    let p: Vec<T> = case.params.iter().map(|&v| T::constant(v)).collect();
    let input = T::constant(case.input);
    let branch = case.branch;
    match case.mechanism.as_str() {
        "four_bar" => {
            let linkage = FourBar::new(p[0], p[1], p[2], p[3]).expect("valid reference lengths");
            compute!(linkage, input, branch)
        }
        "slider_crank" => {
            let linkage = SliderCrank::new(p[0], p[1], p[2]).expect("valid reference dimensions");
            compute!(linkage, input, branch)
        }
        _ => {
            let linkage = InvertedSliderCrank::new(p[0], p[1], p[2], p[3])
                .expect("valid reference dimensions");
            compute!(linkage, input, branch)
        }
    }
}

/// mechgen's answer for a case, in the case's precision.
pub fn compute(case: &Case) -> Computed {
    if case.precision == "f32" {
        compute_in::<f32>(case)
    } else {
        compute_in::<f64>(case)
    }
}

/// The machine epsilon of the case's precision.
pub fn epsilon(case: &Case) -> f64 {
    if case.precision == "f32" {
        f64::from(f32::EPSILON)
    } else {
        f64::EPSILON
    }
}

/// The mechanism's size: the sum of its lengths.
pub fn size(case: &Case) -> f64 {
    match case.mechanism.as_str() {
        "inverted_slider_crank" => case.params[..3].iter().map(|p| p.abs()).sum(),
        _ => case.params.iter().map(|p| p.abs()).sum(),
    }
}

/// `ρ = size / min‖column‖` ≥ 1: how short the Jacobian's shortest column is compared with
/// the mechanism (a slide or link that has nearly vanished), which the rate bounds grow with.
pub fn aspect(case: &Case) -> f64 {
    (size(case) / case.columns[0].min(case.columns[1])).max(1.0)
}

/// `ρ` for the estimates: the size over the shortest column of an angle unknown (1 if none),
/// as `mechgen::__private::rates_accuracy` measures it.
pub fn angle_aspect(case: &Case) -> f64 {
    let angles = angle_unknowns(case);
    let shortest = (0..2)
        .filter(|&j| angles[j])
        .map(|j| case.columns[j])
        .fold(f64::INFINITY, f64::min);
    if shortest.is_finite() {
        size(case) / shortest
    } else {
        1.0
    }
}

/// mechgen's error estimate (`mechgen::Accuracy::estimate`) at the reference's condition and
/// aspect, in the case's precision, and what is required of the rates.
pub fn estimate(case: &Case, condition: f64) -> (Accuracy<f64>, Accuracy<f64>) {
    fn widen<T: Real>(a: Accuracy<T>) -> Accuracy<f64> {
        let f = |v: T| v.to_f64().unwrap_or(f64::NAN);
        Accuracy {
            position: f(a.position),
            velocity: f(a.velocity),
            acceleration: f(a.acceleration),
        }
    }
    let aspect = angle_aspect(case);
    if case.precision == "f32" {
        (
            widen(Accuracy::<f32>::estimate(condition as f32, aspect as f32)),
            widen(Accuracy {
                position: f32::INFINITY,
                ..Accuracy::<f32>::required()
            }),
        )
    } else {
        (
            Accuracy::estimate(condition, aspect),
            Accuracy {
                position: f64::INFINITY,
                ..Accuracy::required()
            },
        )
    }
}

/// The largest error over the unknowns, each weighted by its Jacobian column (so an angle's
/// error counts as the displacement it causes, and a length's as itself), relative to
/// `reference_size`.
pub fn error(got: [f64; 2], want: [f64; 2], columns: [f64; 2], reference_size: f64) -> f64 {
    got.iter()
        .zip(want)
        .zip(columns)
        .map(|((g, w), c)| ((g - w) * c).abs())
        .fold(0.0, f64::max)
        / reference_size
}

/// The size rates are measured against: the larger of the typical displacement rate
/// `size·scale` (with `scale` the input's rate, or its rate squared plus acceleration) and
/// the reference rates' own weighted size.
pub fn rate_size(want: [f64; 2], columns: [f64; 2], size: f64, scale: f64) -> f64 {
    want.iter()
        .zip(columns)
        .fold(size * scale, |m, (w, c)| m.max((w * c).abs()))
}

/// An angle difference wrapped into (−π, π], so 2π apart is no error.
pub fn wrapped(got: [f64; 2], want: [f64; 2], angles: [bool; 2]) -> [f64; 2] {
    let tau = std::f64::consts::TAU;
    let mut out = got;
    for i in 0..2 {
        if angles[i] {
            let d = (got[i] - want[i] + tau / 2.0).rem_euclid(tau) - tau / 2.0;
            out[i] = want[i] + d;
        }
    }
    out
}

/// Which unknowns are angles, per mechanism.
pub fn angle_unknowns(case: &Case) -> [bool; 2] {
    match case.mechanism.as_str() {
        "four_bar" => [true, true],
        _ => [true, false],
    }
}

/// How one case came out, against the reference and mechgen's own error estimate.
#[derive(Clone, Debug)]
pub struct Assessment {
    pub position_error: Option<f64>,
    pub velocity_error: Option<f64>,
    pub acceleration_error: Option<f64>,
    /// mechgen's estimate at the reference's condition.
    pub estimate: Accuracy<f64>,
    /// What happened, in words: "ok", or the error and whether the reference expects it.
    pub outcome: String,
    /// Whether the result keeps the contract: every error within its estimate, or an error
    /// the reference calls for (the loop cannot close, the Jacobian is singular), or one the
    /// estimate calls for (a rate less accurate than required, within a factor of 2 of κ).
    pub kept: bool,
}

/// Compares mechgen with the reference for one case.
pub fn assess(case: &Case) -> Assessment {
    let computed = compute(case);
    let eps = epsilon(case);
    let size = size(case);
    let columns = case.columns;
    let angles = angle_unknowns(case);
    let kappa = case.condition;
    let (estimate, required) = estimate(case, kappa.max(1.0));
    // The refusal the estimate calls for, allowing κ to be off by a factor of 2 at the
    // computed position (as it is within rounding of a toggle).
    let (doubled, _) = self::estimate(case, 2.0 * kappa.max(1.0));
    let inaccurate_expected = |order: Order| doubled.within(&required, order).is_err();
    // Within √ε of the singular threshold a documented error is an acceptable answer.
    let near_threshold = kappa.is_nan() || kappa * eps.sqrt() >= 0.5;
    let mut assessment = Assessment {
        position_error: None,
        velocity_error: None,
        acceleration_error: None,
        estimate,
        outcome: String::new(),
        kept: false,
    };
    let documented =
        |e: &Error<f64>| matches!(e, Error::CannotAssemble { .. } | Error::Singular { .. });
    match (case.status, computed.position) {
        (Status::Cannot, Err(Error::CannotAssemble { .. })) => {
            assessment.outcome = "CannotAssemble, as expected".into();
            assessment.kept = true;
        }
        (Status::Cannot, Ok(_)) => {
            assessment.outcome = "assembled where the reference cannot".into();
            // Within rounding of a toggle the closed form returns the toggle position.
            assessment.kept = near_threshold;
        }
        (_, Err(error)) => {
            assessment.outcome = format!("{error:?}");
            assessment.kept = near_threshold && documented(&error);
        }
        (status, Ok(q)) => {
            let q = wrapped(q, case.q, angles);
            let position_error = error(q, case.q, columns, size);
            assessment.position_error = Some(position_error);
            // Within the threshold's reach of a singular position the two branches are one to
            // working precision, and either label is right.
            let right_branch = computed.branch == Some(case.branch) || near_threshold;
            let mut kept = right_branch && position_error <= estimate.position;
            let mut outcome = if right_branch {
                "ok".to_string()
            } else {
                "WRONG BRANCH".into()
            };
            match (status, computed.velocity) {
                (Status::Singular, Some(Err(Error::Singular { .. }))) => {
                    outcome = "Singular velocity, as expected".into();
                }
                (_, Some(Err(Error::Inaccurate { order, .. }))) => {
                    outcome = format!("Inaccurate {order:?}");
                    kept &= inaccurate_expected(order) || status == Status::Singular;
                }
                (Status::Ok, Some(Ok(v))) => {
                    let scale = rate_size(case.q_dot, columns, size, OMEGA2);
                    let velocity_error = error(v, case.q_dot, columns, scale);
                    assessment.velocity_error = Some(velocity_error);
                    kept &= velocity_error <= estimate.velocity;
                    match computed.acceleration {
                        Some(Ok(a)) => {
                            let scale =
                                rate_size(case.q_ddot, columns, size, OMEGA2 * OMEGA2 + ALPHA2);
                            let acceleration_error = error(a, case.q_ddot, columns, scale);
                            assessment.acceleration_error = Some(acceleration_error);
                            kept &= acceleration_error <= estimate.acceleration;
                        }
                        Some(Err(Error::Inaccurate { order, .. })) => {
                            outcome = format!("Inaccurate {order:?}");
                            kept &= inaccurate_expected(order);
                        }
                        other => {
                            outcome = format!("unexpected acceleration {other:?}");
                            kept = false;
                        }
                    }
                }
                (_, Some(Err(error))) => {
                    outcome = format!("{error:?}");
                    kept &= near_threshold && documented(&error);
                }
                (_, other) => {
                    outcome = format!("unexpected velocity {other:?}");
                    kept = false;
                }
            }
            assessment.outcome = outcome;
            assessment.kept = kept;
        }
    }
    assessment
}

fn cell(value: Option<f64>) -> String {
    value.map_or("–".to_string(), |v| format!("{v:.1e}"))
}

/// An error beside its estimate, `error ≤ estimate` (`–` without an error).
fn against(error: Option<f64>, estimate: f64) -> String {
    error.map_or("–".to_string(), |e| format!("{e:.1e} ≤ {estimate:.1e}"))
}

/// The accuracy table, in Markdown.
pub fn table() -> String {
    let mut out = String::from(
        "# Accuracy against high-precision references\n\n\
         Generated by `cargo run -p mechgen-tests --bin accuracy > docs/ACCURACY.md` \
         from the 60-digit references in `tests/reference/cases.csv` (made by \
         `python3 tests/reference/generate.py`, with mpmath). A test checks this file is \
         current.\n\n\
         Each row solves a shipped mechanism with the generated closed form (`assemble`), \
         velocity (ω2 = 1) and acceleration (α2 = 0.5), in f64 or f32 with parameters and \
         input rounded to that precision, and compares with the reference at those exact \
         values. Each unknown's error is weighted by its Jacobian column (an angle's error \
         counts as the displacement it causes), then divided by the mechanism's size (the sum \
         of its lengths) for positions, or by the rates' size for rates. κ is the reference's \
         condition estimate (the Jacobian's column norms over its determinant) and ρ its \
         aspect (the size over the shortest column of an angle unknown). Each error is shown \
         beside mechgen's estimate of it (`mechgen::Accuracy::estimate` at the reference's κ \
         and ρ: position 32·ε·κ, velocity ε·(64·κ + 12·κ²)·s, acceleration ε·(256·κ + κ³)·s² \
         with s = max(1, ρ/16)), which \
         it must not exceed; where the estimate exceeds `mechgen::Accuracy::required` (ε^(1/3) \
         for velocities, ε^(1/4) for accelerations) the answer must be `Inaccurate` instead, \
         and where κ nears 1/√ε `Singular` or `CannotAssemble` are documented answers too.\n\n\
         | mechanism | case | δ | prec. | branch | κ | ρ | position | velocity | acceleration | outcome | kept |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for case in cases() {
        let a = assess(&case);
        let branch = if case.branch == Branch::Open {
            "open"
        } else {
            "crossed"
        };
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            case.mechanism.replace('_', " "),
            case.case,
            case.delta,
            case.precision,
            branch,
            cell(Some(case.condition).filter(|k| k.is_finite())),
            cell(Some(angle_aspect(&case)).filter(|r| r.is_finite())),
            against(a.position_error, a.estimate.position),
            against(a.velocity_error, a.estimate.velocity),
            against(a.acceleration_error, a.estimate.acceleration),
            a.outcome.split(" {").next().unwrap_or_default(),
            if a.kept { "yes" } else { "**no**" },
        ));
    }
    out
}
