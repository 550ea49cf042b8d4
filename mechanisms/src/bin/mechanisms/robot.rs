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
    #[arg(allow_negative_numbers = true, num_args = 5, default_values_t = [100.0, 200.0, 200.0, 100.0, 100.0])]
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
        _ => return Err("robot takes five links".to_string()),
    };
    let robot = FiveBar::new(l1, l2, l3, l4, l5).map_err(refused)?;
    say!(
        "five-bar robot: cranks {} and {} mm, distal links {} and {} mm, motors {} mm apart",
        fixed(l1, 3),
        fixed(l4, 3),
        fixed(l2, 3),
        fixed(l3, 3),
        fixed(l5, 3)
    );
    match &args.point {
        Some(point) => inverse(&robot, pair("point", point)?),
        None => forward(
            &robot,
            pair("cranks", &args.cranks)?.map(angle::radians),
            pair("rates", &args.rates)?,
            pair("accels", &args.accels)?,
        ),
    }
}

/// Both working modes at the cranks' angles.
fn forward(
    robot: &FiveBar<f64>,
    [t1, t4]: [f64; 2],
    [w1, w4]: [f64; 2],
    [a1, a4]: [f64; 2],
) -> Result<(), String> {
    say!(
        "cranks at {}° and {}°, turning at {} and {} rad/s, accelerating at {} and {} rad/s²",
        fixed(t1.to_degrees(), 4),
        fixed(t4.to_degrees(), 4),
        fixed(w1, 4),
        fixed(w4, 4),
        fixed(a1, 4),
        fixed(a4, 4)
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
            Ok(motion) => posture(robot, [t1, t4], [w1, w4], [a1, a4], &motion)?,
            Err(error) => say!("  {}", explained(error)),
        }
    }
    Ok(())
}

/// One posture's end effector, its motion and its distance from singularities.
fn posture(
    robot: &FiveBar<f64>,
    [t1, t4]: [f64; 2],
    [w1, w4]: [f64; 2],
    [a1, a4]: [f64; 2],
    motion: &mechgen::Motion<FiveBarUnknowns<f64>, f64>,
) -> Result<(), String> {
    let (q, v, a) = (&motion.position, &motion.velocity, &motion.acceleration);
    let p = robot
        .points(t1, t4, q)
        .map_err(|e| output::error(&e))?
        .end_effector;
    let p_dot = robot
        .point_velocities(t1, t4, q, w1, w4, v)
        .map_err(|e| output::error(&e))?
        .end_effector;
    let p_ddot = robot
        .point_accelerations(t1, t4, q, w1, w4, v, a1, a4, a)
        .map_err(|e| output::error(&e))?
        .end_effector;
    say!(
        "  distal links at θ2 = {}°, θ3 = {}°",
        fixed(q.theta2.to_degrees(), 4),
        fixed(q.theta3.to_degrees(), 4)
    );
    say!(
        "  end effector P = ({}, {}) mm",
        fixed(p.x, 4),
        fixed(p.y, 4)
    );
    say!(
        "  velocity = ({}, {}) mm/s",
        fixed(p_dot.x, 4),
        fixed(p_dot.y, 4)
    );
    say!(
        "  acceleration = ({}, {}) mm/s²",
        fixed(p_ddot.x, 4),
        fixed(p_ddot.y, 4)
    );
    let near = robot.singularities(t1, t4, q);
    say!(
        "  singularities (1 far, 0 at one): parallel {}, serial left {}, serial right {}",
        fixed(near.parallel, 4),
        fixed(near.serial[0], 4),
        fixed(near.serial[1], 4)
    );
    Ok(())
}

/// Each elbow choice's cranks for the point, and the working mode that reaches it.
fn inverse(robot: &FiveBar<f64>, [x, y]: [f64; 2]) -> Result<(), String> {
    let p = Vec2 { x, y };
    say!("point ({}, {}) mm", fixed(x, 4), fixed(y, 4));
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
