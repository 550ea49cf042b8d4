//! `mechanisms robot`: the five-bar parallel robot, a mechanism of two inputs. At given
//! crank angles: the end effector in both working modes, its velocity and acceleration from
//! both cranks' rates and accelerations, and how near each posture is to a singularity. At a
//! given point: whether the robot reaches it, and the cranks' angles that do (inverse
//! kinematics, each leg's elbow either way).

use clap::Parser;
use mechanisms::{FiveBar, FiveBarUnknowns};
use mechgen::{Branch, Error, Vec2};

use crate::analyse::refused;
use crate::angle;
use crate::output::{self, fixed, say};

#[derive(Parser)]
pub struct Args {
    /// Its links in mm: left crank, left distal, right distal, right crank, base (the
    /// motors' distance apart).
    #[arg(allow_negative_numbers = true, default_values_t = [100.0, 200.0, 200.0, 100.0, 100.0])]
    pub links: Vec<f64>,
    /// The cranks' angles in degrees, left then right, joined by a comma.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        num_args = 1,
        default_value = "120,60"
    )]
    pub cranks: Vec<f64>,
    /// The cranks' rates in rad/s, left then right.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        num_args = 1,
        default_value = "1,-1"
    )]
    pub rates: Vec<f64>,
    /// The cranks' accelerations in rad/s², left then right.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        num_args = 1,
        default_value = "0,0"
    )]
    pub accels: Vec<f64>,
    /// Instead of the cranks' angles, a point (x,y in mm) to reach: the inverse kinematics
    /// (so not with --cranks, --rates or --accels).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        num_args = 1,
        conflicts_with_all = ["cranks", "rates", "accels"]
    )]
    pub point: Option<Vec<f64>>,
}

/// A pair of finite numbers from a comma-separated option, or why not.
fn pair(name: &str, values: &[f64]) -> Result<[f64; 2], String> {
    match values {
        &[a, b] if a.is_finite() && b.is_finite() => Ok([a, b]),
        _ => Err(format!(
            "--{name} takes two finite numbers joined by a comma"
        )),
    }
}

pub fn run(args: &Args) -> Result<(), String> {
    let [l1, l2, l3, l4, l5] = match args.links[..] {
        [l1, l2, l3, l4, l5] => [l1, l2, l3, l4, l5],
        ref given => {
            return Err(format!(
                "robot takes 5 links (left crank, left distal, right distal, right crank, base), \
                 {} given",
                given.len()
            ));
        }
    };
    let names = [
        "left crank",
        "left distal",
        "right distal",
        "right crank",
        "base",
    ];
    if let Some((name, value)) = names
        .into_iter()
        .zip([l1, l2, l3, l4, l5])
        .find(|(_, v)| *v != 0.0 && v.abs() < f64::MIN_POSITIVE)
    {
        return Err(format!(
            "the {name} {} is below the float's normal range ({:e}), where a number keeps \
             fewer than its 53 bits: it would be computed as another dimension",
            output::tidy(value),
            f64::MIN_POSITIVE
        ));
    }
    let robot = FiveBar::new(l1, l2, l3, l4, l5).map_err(refused)?;
    say!(
        "five-bar robot: cranks {} and {} mm, distal links {} and {} mm, motors {} mm apart",
        output::tidy(l1),
        output::tidy(l4),
        output::tidy(l2),
        output::tidy(l3),
        output::tidy(l5)
    );
    match &args.point {
        Some(point) => inverse(&robot, pair("point", point)?),
        None => forward(
            &robot,
            [l1, l2, l3, l4, l5],
            pair("cranks", &args.cranks)?.map(angle::radians),
            pair("rates", &args.rates)?,
            pair("accels", &args.accels)?,
        ),
    }
}

/// Both working modes at the cranks' angles.
fn forward(
    robot: &FiveBar<f64>,
    lengths: [f64; 5],
    [t1, t4]: [f64; 2],
    [w1, w4]: [f64; 2],
    [a1, a4]: [f64; 2],
) -> Result<(), String> {
    say!(
        "cranks at {}° and {}°, turning at {} and {} rad/s, accelerating at {} and {} rad/s²",
        fixed(t1.to_degrees(), 4),
        fixed(t4.to_degrees(), 4),
        output::figure(w1),
        output::figure(w4),
        output::figure(a1),
        output::figure(a4)
    );
    for (branch, name) in [
        (
            Branch::Open,
            "end effector left of the line from the left elbow to the right (open)",
        ),
        (Branch::Crossed, "end effector right of that line (crossed)"),
    ] {
        say!("");
        say!("{name}:");
        match robot.motion(t1, t4, branch, w1, w4, a1, a4) {
            Ok(motion) => posture(robot, lengths, [t1, t4], [w1, w4], [a1, a4], &motion)?,
            // The position (and the velocity) may stand where the acceleration cannot (rates
            // whose squares leave the float's range): each order as far as it goes.
            Err(error @ (Error::Inaccurate { .. } | Error::NonFinite { .. })) => {
                partial(robot, lengths, [t1, t4], [w1, w4], branch, error)?
            }
            Err(error) => say!("  {}", explained(error)),
        }
    }
    Ok(())
}

/// What the end effector's position, velocity and acceleration may each be off by, from
/// the accuracy the motion states (`mechgen::Motion::accuracy`, relative to the sizes the
/// contract measures by: the robot's size, times the input rates or their squares and
/// accelerations, or the unknowns' weighted rates where larger). The point hangs from two
/// unknown angles, each off by its order's error over its link, moving the point by that
/// error at most: twice the order's error, doubled again for the sizes' approximation.
fn point_errors(
    [l1, l2, l3, l4, l5]: [f64; 5],
    [w1, w4]: [f64; 2],
    [a1, a4]: [f64; 2],
    accuracy: mechgen::Accuracy<f64>,
    v: &FiveBarUnknowns<f64>,
    a: &FiveBarUnknowns<f64>,
) -> [f64; 3] {
    let size = l1 + l2 + l3 + l4 + l5;
    let links = [l2, l3];
    let speeds = [v.theta2, v.theta3];
    let spins = [a.theta2, a.theta3];
    let weighted =
        |values: [f64; 2]| -> f64 { values.iter().zip(links).map(|(x, l)| x.abs() * l).sum() };
    let scales = [
        size,
        size * (w1.abs() + w4.abs()) + weighted(speeds),
        size * (w1 * w1 + w4 * w4 + a1.abs() + a4.abs())
            + weighted(spins)
            + weighted(speeds.map(|w| w * w)),
    ];
    let relative = [accuracy.position, accuracy.velocity, accuracy.acceleration];
    core::array::from_fn(|k| 4.0 * relative[k] * scales[k])
}

/// One posture's end effector, its motion and its distance from singularities.
fn posture(
    robot: &FiveBar<f64>,
    lengths: [f64; 5],
    [t1, t4]: [f64; 2],
    [w1, w4]: [f64; 2],
    [a1, a4]: [f64; 2],
    motion: &mechgen::Motion<FiveBarUnknowns<f64>, f64>,
) -> Result<(), String> {
    let (q, v, a) = (&motion.position, &motion.velocity, &motion.acceleration);
    let [position_error, velocity_error, acceleration_error] =
        point_errors(lengths, [w1, w4], [a1, a4], motion.accuracy, v, a);
    // Each distal angle off by the position's error over its link (the size's share).
    let size: f64 = lengths.iter().sum();
    let angle_error = |link: f64| 2.0 * motion.accuracy.position * size / link;
    let p = robot
        .points(t1, t4, q)
        .map_err(|e| output::error(&e))?
        .end_effector;
    // The point's velocity and acceleration may overflow where the unknowns' did not (a
    // crank accelerating at 1e308 rad/s²): each says so in its line, as `partial` does.
    let p_dot = robot
        .point_velocities(t1, t4, q, w1, w4, v)
        .map(|points| points.end_effector);
    let p_ddot = p_dot.and_then(|_| {
        robot
            .point_accelerations(t1, t4, q, w1, w4, v, a1, a4, a)
            .map(|points| points.end_effector)
    });
    say!(
        "  distal links at θ2 = {}°, θ3 = {}°",
        signed_degrees(q.theta2, angle_error(lengths[1])),
        signed_degrees(q.theta3, angle_error(lengths[2]))
    );
    say!(
        "  end effector P = ({}, {}) mm",
        output::within(p.x, position_error),
        output::within(p.y, position_error)
    );
    match p_dot {
        Ok(p_dot) => say!(
            "  velocity = ({}, {}) mm/s",
            output::within(p_dot.x, velocity_error),
            output::within(p_dot.y, velocity_error)
        ),
        Err(error) => say!("  velocity: {}", explained(error)),
    }
    match p_ddot {
        Ok(p_ddot) => say!(
            "  acceleration = ({}, {}) mm/s²",
            output::within(p_ddot.x, acceleration_error),
            output::within(p_ddot.y, acceleration_error)
        ),
        Err(error) => say!("  acceleration: {}", explained(error)),
    }
    singularities(robot, [t1, t4], q);
    Ok(())
}

/// A posture whose motion as a whole failed for a rate or acceleration: its position, its
/// velocity if that can be had, and why the rest cannot; each to the digits its estimate
/// leaves (`mechgen::Accuracy::estimate` at the closed form's position, as
/// [`point_errors`] reads a motion's), not rounding noise printed as figures.
fn partial(
    robot: &FiveBar<f64>,
    lengths: [f64; 5],
    [t1, t4]: [f64; 2],
    [w1, w4]: [f64; 2],
    branch: Branch,
    failure: Error<f64>,
) -> Result<(), String> {
    let q = match robot.assemble(t1, t4, branch) {
        Ok(q) => q,
        Err(error) => {
            say!("  {}", explained(error));
            return Ok(());
        }
    };
    let p = robot
        .points(t1, t4, &q)
        .map_err(|e| output::error(&e))?
        .end_effector;
    // The aspect as the runtime reads it: the size over the shorter distal link (the angles'
    // columns).
    let size: f64 = lengths.iter().sum();
    let aspect = size / lengths[1].min(lengths[2]);
    let estimate = mechgen::Accuracy::estimate(robot.condition(t1, t4, &q), aspect);
    let still = FiveBarUnknowns {
        theta2: 0.0,
        theta3: 0.0,
    };
    let [position_error, ..] = point_errors(lengths, [0.0; 2], [0.0; 2], estimate, &still, &still);
    let angle_error = |link: f64| 2.0 * estimate.position * size / link;
    say!(
        "  distal links at θ2 = {}°, θ3 = {}°",
        signed_degrees(q.theta2, angle_error(lengths[1])),
        signed_degrees(q.theta3, angle_error(lengths[2]))
    );
    say!(
        "  end effector P = ({}, {}) mm",
        output::within(p.x, position_error),
        output::within(p.y, position_error)
    );
    let velocity = robot.velocity(t1, t4, &q, w1, w4).and_then(|v| {
        robot
            .point_velocities(t1, t4, &q, w1, w4, &v)
            .map(|points| (v, points.end_effector))
    });
    match velocity {
        Ok((v, p_dot)) => {
            let [_, velocity_error, _] =
                point_errors(lengths, [w1, w4], [0.0; 2], estimate, &v, &still);
            say!(
                "  velocity = ({}, {}) mm/s",
                output::within(p_dot.x, velocity_error),
                output::within(p_dot.y, velocity_error)
            );
            say!("  acceleration: {}", explained(failure));
        }
        Err(error) => say!("  velocity and acceleration: {}", explained(error)),
    }
    singularities(robot, [t1, t4], &q);
    Ok(())
}

/// How far a posture is from each singularity.
fn singularities(robot: &FiveBar<f64>, [t1, t4]: [f64; 2], q: &FiveBarUnknowns<f64>) {
    let near = robot.singularities(t1, t4, q);
    say!(
        "  singularities (1 far, 0 at one): parallel {}, serial left {}, serial right {}",
        fixed(near.parallel, 4),
        fixed(near.serial[0], 4),
        fixed(near.serial[1], 4)
    );
}

/// Each elbow choice's cranks for the point, and the working mode that reaches it.
fn inverse(robot: &FiveBar<f64>, [x, y]: [f64; 2]) -> Result<(), String> {
    let p = Vec2 { x, y };
    say!("point ({}, {}) mm", output::figure(x), output::figure(y));
    if !robot.reaches(p) {
        say!("outside the workspace: beyond one leg's reach, or too near its motor");
        return Ok(());
    }
    for (elbows, name) in [
        ([1.0, -1.0], "both elbows outward"),
        ([-1.0, 1.0], "both elbows inward"),
        ([1.0, 1.0], "left elbow outward, right inward"),
        ([-1.0, -1.0], "left elbow inward, right outward"),
    ] {
        let Some([t1, t4]) = robot.inverse(p, elbows) else {
            continue;
        };
        let mode = [(Branch::Open, "open"), (Branch::Crossed, "crossed")]
            .into_iter()
            .find(|&(branch, _)| {
                robot
                    .assemble(t1, t4, branch)
                    .ok()
                    .and_then(|q| robot.points(t1, t4, &q).ok())
                    .is_some_and(|points| {
                        let found = points.end_effector;
                        (found.x - x).hypot(found.y - y) <= 1e-9 * (1.0 + x.hypot(y))
                    })
            })
            .map_or("none (the loop does not close there)", |(_, name)| name);
        say!(
            "  {name}: cranks at {}° and {}°, working mode {mode}",
            fixed(t1.to_degrees(), 4),
            fixed(t4.to_degrees(), 4)
        );
    }
    Ok(())
}

/// What an error means for the robot.
fn explained(error: Error<f64>) -> String {
    match error {
        Error::CannotAssemble { .. } => {
            "the distal links cannot meet: the elbows are farther apart than they reach".to_string()
        }
        Error::Singular { .. } => {
            "a parallel singularity: the distal links line up, so the end effector's rates are unbounded"
                .to_string()
        }
        other => output::error(&other),
    }
}

/// An angle in degrees in (−180°, 180°], as the distal links' are reported, to the decimals
/// its error (radians) leaves, at most 4.
fn signed_degrees(radians: f64, error: f64) -> String {
    let text = output::degrees_within(radians, error);
    match text.parse::<f64>() {
        Ok(degrees) if degrees > 180.0 => {
            let decimals = text.split('.').nth(1).map_or(0, str::len);
            output::fixed(degrees - 360.0, decimals)
        }
        _ => text,
    }
}
