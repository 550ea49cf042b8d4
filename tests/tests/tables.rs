//! Numeric snapshots: a full crank turn, every 10°, for each shipped mechanism, with the
//! unknowns, their rates and accelerations, the analyses (transmission angle, mechanical
//! advantage) and the tracked points, to 10 significant digits.
//!
//! Values below 1e-9 of their column's largest magnitude are printed as 0: they are rounding
//! noise around an exact zero, and would differ between machines.

mod common;

use common::*;
use std::fmt::Write;

const OMEGA2: f64 = 10.0;
const ALPHA2: f64 = 2.0;

/// Per-position analyses: column names and a function of (θ2, unknowns) giving them.
type Analyses<'a> = (&'a [&'a str], &'a dyn Fn(f64, [f64; 2]) -> Vec<f64>);

fn table<L: Linkage<f64>>(
    linkage: &L,
    guess: [f64; 2],
    unknowns: [&str; 2],
    (analysis_names, analyses): Analyses,
    points: &[&str],
) -> String {
    let mut header = vec!["theta2_deg".to_string()];
    for suffix in ["", "_dot", "_ddot"] {
        header.extend(unknowns.iter().map(|u| format!("{u}{suffix}")));
    }
    header.extend(analysis_names.iter().map(|name| name.to_string()));
    for suffix in ["", "_dot", "_ddot"] {
        for p in points {
            header.extend([format!("{p}{suffix}.x"), format!("{p}{suffix}.y")]);
        }
    }
    let rows: Vec<Vec<f64>> = sweep(linkage, guess, 10)
        .into_iter()
        .map(|Sample { input, q }| {
            let q_dot = linkage.rates(input, q, OMEGA2).unwrap();
            let q_ddot = linkage
                .accelerations(input, q, OMEGA2, q_dot, ALPHA2)
                .unwrap();
            let mut row = vec![input.to_degrees()];
            row.extend(q);
            row.extend(q_dot);
            row.extend(q_ddot);
            row.extend(analyses(input, q));
            row.extend(linkage.point_positions(input, q));
            row.extend(linkage.point_velocities(input, q, OMEGA2, q_dot));
            row.extend(linkage.point_accelerations(input, q, OMEGA2, q_dot, ALPHA2, q_ddot));
            row
        })
        .collect();
    let column_max: Vec<f64> = (0..header.len())
        .map(|c| {
            let finite = rows.iter().map(|r| r[c].abs()).filter(|v| v.is_finite());
            finite.fold(0.0f64, f64::max)
        })
        .collect();
    let mut out = format!(
        "# omega2 = {OMEGA2} rad/s, alpha2 = {ALPHA2} rad/s^2; angles in rad; \
         an unbounded mechanical advantage prints as inf\n"
    );
    writeln!(out, "{}", header.join(", ")).unwrap();
    for row in rows {
        let degrees = format!("{:.0}", row[0]);
        let cells: Vec<String> = std::iter::once(degrees)
            .chain(
                row.iter()
                    .zip(&column_max)
                    .skip(1)
                    .map(|(v, max)| significant(*v, *max)),
            )
            .collect();
        writeln!(out, "{}", cells.join(", ")).unwrap();
    }
    out
}

/// Snapshots live beside the expansion snapshots, in `tests/snapshots/`.
fn assert_table(name: &str, table: String) {
    insta::with_settings!({
        snapshot_path => "../snapshots/numeric",
        prepend_module_to_snapshot => false,
        omit_expression => true,
    }, {
        insta::assert_snapshot!(name, table);
    });
}

/// `value` to 10 significant digits, or 0 if it is below 1e-9 of `column_max`.
fn significant(value: f64, column_max: f64) -> String {
    if value.is_infinite() {
        "inf".to_string()
    } else if value.abs() <= 1e-9 * column_max {
        "0".to_string()
    } else {
        format!("{value:.9e}")
    }
}

/// A mechanical advantage as a number, with unbounded as infinity.
fn advantage(value: Result<mechgen::MechanicalAdvantage<f64>, mechgen::Error<f64>>) -> f64 {
    value.unwrap().finite().unwrap_or(f64::INFINITY)
}

#[test]
fn four_bar_full_turn() {
    let linkage = example_1::<f64>();
    let analyses = |theta2: f64, q: [f64; 2]| {
        let q = mechanisms::FourBarUnknowns::from_array(q);
        vec![
            linkage.transmission_angle(&q),
            advantage(linkage.mechanical_advantage(theta2, &q)),
        ]
    };
    let points = ["crank_pin", "rocker_pin", "coupler_point"];
    let names = ["transmission_angle", "mechanical_advantage"];
    let table = table(
        &linkage,
        [0.3, 1.2],
        ["theta3", "theta4"],
        (&names, &analyses),
        &points,
    );
    assert_table("four_bar_full_turn", table);
}

#[test]
fn slider_crank_full_turn() {
    let linkage = slider_crank::<f64>();
    let analyses = |theta2: f64, q: [f64; 2]| {
        let q = mechanisms::SliderCrankUnknowns::from_array(q);
        vec![
            linkage.transmission_angle(&q),
            advantage(linkage.mechanical_advantage(theta2, &q)),
        ]
    };
    let points = ["crank_pin", "slider_pin", "coupler_point"];
    let names = ["transmission_angle", "mechanical_advantage_per_mm"];
    let table = table(
        &linkage,
        [0.0, 190.0],
        ["theta3", "d"],
        (&names, &analyses),
        &points,
    );
    assert_table("slider_crank_full_turn", table);
}

#[test]
fn inverted_slider_crank_full_turn() {
    let linkage = inverted_slider_crank::<f64>();
    let analyses = |theta2: f64, q: [f64; 2]| {
        let q = mechanisms::InvertedSliderCrankUnknowns::from_array(q);
        vec![advantage(linkage.mechanical_advantage(theta2, &q))]
    };
    let points = ["crank_pin", "block_pin", "slide_origin", "coupler_point"];
    let names = ["mechanical_advantage"];
    let table = table(
        &linkage,
        [3.0, 60.0],
        ["theta4", "b"],
        (&names, &analyses),
        &points,
    );
    assert_table("inverted_slider_crank_full_turn", table);
}

#[test]
fn significant_digits_and_noise_flushing() {
    assert_eq!(significant(1.0 / 3.0, 1.0), "3.333333333e-1");
    assert_eq!(significant(-123456.789012345, 1e6), "-1.234567890e5");
    assert_eq!(significant(3e-14, 200.0), "0");
    // Flushed at a billionth of the column's largest value, and not above it.
    assert_eq!(significant(2e-7, 200.0), "0");
    assert_eq!(significant(-2.5e-7, 200.0), "-2.500000000e-7");
    assert_eq!(significant(f64::INFINITY, 1.0), "inf");
}

/// A full-turn table of a multi-loop mechanism from `row(θ)`: the unknowns, their rates and
/// accelerations (ω = 10 rad/s, α = 2 rad/s²) and one tracked point.
fn multi_loop_table(header: &[&str], rows: impl Fn(f64) -> Vec<f64>) -> String {
    let rows: Vec<Vec<f64>> = (0..36)
        .map(|k| {
            let mut row = vec![f64::from(k * 10)];
            row.extend(rows(f64::from(k * 10).to_radians()));
            row
        })
        .collect();
    let columns = header.len() + 1;
    let column_max: Vec<f64> = (0..columns)
        .map(|c| rows.iter().map(|r| r[c].abs()).fold(0.0f64, f64::max))
        .collect();
    let mut out = format!("# omega = {OMEGA2} rad/s, alpha = {ALPHA2} rad/s^2; angles in rad\n");
    writeln!(out, "input_deg, {}", header.join(", ")).unwrap();
    for row in rows {
        let cells: Vec<String> = std::iter::once(format!("{:.0}", row[0]))
            .chain(
                row.iter()
                    .zip(&column_max)
                    .skip(1)
                    .map(|(v, m)| significant(*v, *m)),
            )
            .collect();
        writeln!(out, "{}", cells.join(", ")).unwrap();
    }
    out
}

fn unknown_header(names: &[&str], point: &str) -> Vec<String> {
    let mut header: Vec<String> = Vec::new();
    for suffix in ["", "_dot", "_ddot"] {
        header.extend(names.iter().map(|n| format!("{n}{suffix}")));
    }
    header.extend([format!("{point}.x"), format!("{point}.y")]);
    header
}

#[test]
fn jansen_leg_full_turn() {
    let leg = mechanisms::JansenLeg::<f64>::holy();
    let names = ["phi_j", "phi_b", "phi_k", "phi_c", "phi_f", "phi_g"];
    let header = unknown_header(&names, "foot");
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let table = multi_loop_table(&header, |t| {
        let m = leg
            .motion(t, mechanisms::JansenLeg::<f64>::DRAWN, OMEGA2, ALPHA2)
            .unwrap();
        let foot = leg.points(t, &m.position).unwrap().foot;
        let mut row: Vec<f64> = m.position.to_array().to_vec();
        row.extend(m.velocity.to_array());
        row.extend(m.acceleration.to_array());
        row.extend([foot.x, foot.y]);
        row
    });
    assert_table("jansen_leg_full_turn", table);
}

#[test]
fn watt_six_bar_full_turn() {
    let linkage = watt_six_bar::<f64>();
    let header = unknown_header(&["theta3", "theta4", "theta5", "theta6"], "output_pin");
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let drawn = [mechgen::Branch::Open, mechgen::Branch::Open];
    let table = multi_loop_table(&header, |t| {
        let m = linkage.motion(t, drawn, OMEGA2, ALPHA2).unwrap();
        let d = linkage.points(t, &m.position).unwrap().output_pin;
        let mut row: Vec<f64> = m.position.to_array().to_vec();
        row.extend(m.velocity.to_array());
        row.extend(m.acceleration.to_array());
        row.extend([d.x, d.y]);
        row
    });
    assert_table("watt_six_bar_full_turn", table);
}

#[test]
fn stephenson_six_bar_full_turn() {
    let (linkage, guess) = mechgen_tests::examples::stephenson_six_bar();
    let options = mechgen::NewtonOptions::default();
    let start = linkage.position(0.0, &guess, &options).unwrap().value;
    // Positions continued along the turn in 1° steps, so each row is on the drawn branch.
    let positions: Vec<[f64; 4]> = mechgen::sweep::Sweep::new(
        &linkage,
        0.0,
        start.to_array(),
        1f64.to_radians(),
        359,
        options,
    )
    .map(|s| s.unwrap().position)
    .collect();
    let header = unknown_header(&["theta3", "theta4", "theta5", "theta6"], "d");
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let table = multi_loop_table(&header, |t| {
        let near = positions[(t.to_degrees().round() as usize) % 360].into();
        let q = linkage.position(t, &near, &options).unwrap().value;
        let m = linkage.motion_at(t, &q, OMEGA2, ALPHA2).unwrap();
        let d = linkage.points(t, &q).unwrap().d;
        let mut row: Vec<f64> = m.position.to_array().to_vec();
        row.extend(m.velocity.to_array());
        row.extend(m.acceleration.to_array());
        row.extend([d.x, d.y]);
        row
    });
    assert_table("stephenson_six_bar_full_turn", table);
}
