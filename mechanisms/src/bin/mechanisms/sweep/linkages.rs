//! Each closed-form linkage's sweep: its columns, charts, drawing and sample.

use super::*;

pub(super) fn point(v: Vec2<f64>) -> (f64, f64) {
    (v.x, v.y)
}

pub(super) fn names(columns: &[&str]) -> Vec<String> {
    columns.iter().map(|&c| c.to_owned()).collect()
}

/// The branch of loop `which` (0 for the first) given by `--branch`, open if not given.
pub(super) fn branch_of(args: &Args, which: usize) -> Branch {
    match args.branch.as_ref().and_then(|b| b.get(which)) {
        Some(BranchName::Crossed) => Branch::Crossed,
        Some(BranchName::Open) | None => Branch::Open,
    }
}

pub(super) fn branch(args: &Args) -> Branch {
    branch_of(args, 0)
}

pub(super) fn four_bar(args: &Args) -> Result<Sweep<'_>, String> {
    let d = &args.dimensions;
    let mut linkage = FourBar::new(d[0], d[1], d[2], d[3]).map_err(refused)?;
    if let Some(p) = &args.coupler_point {
        linkage = linkage
            .with_coupler_point(p[0], angle::radians(p[1]))
            .map_err(refused)?;
    }
    let (rate, accel, on) = (args.rate, args.accel, branch(args));
    let ground = d[0];
    Ok(Sweep {
        title: format!(
            "Four-bar {} {} {} {} mm, {}",
            tidy(d[0]),
            tidy(d[1]),
            tidy(d[2]),
            tidy(d[3]),
            four_bar_range(&linkage)
        ),
        columns: names(&[
            "theta3_deg",
            "theta4_deg",
            "omega3",
            "omega4",
            "alpha3",
            "alpha4",
            "transmission_deg",
            "coupler_x",
            "coupler_y",
        ]),
        groups: vec![
            ("output angles (°)".into(), 0..2),
            ("angular velocities (rad/s)".into(), 2..4),
            ("angular accelerations (rad/s²)".into(), 4..6),
            ("transmission angle (°), 40°–140° shaded".into(), 6..7),
        ],
        band_column: Some(6),
        links: vec![(0, 1), (1, 2), (2, 3), (1, 4), (2, 4)],
        traced: 4,
        pieces: four_bar_pieces(&linkage),
        change_points: four_bar_change_points(&linkage),
        sample: Box::new(move |input, flipped| {
            let t = crate::angle::radians(input);
            let on = if flipped { on.other() } else { on };
            let m = linkage.motion(t, on, rate, accel)?;
            let p = linkage.points(t, &m.position)?;
            Ok(Sample {
                values: vec![
                    m.position.theta3.to_degrees(),
                    m.position.theta4.to_degrees(),
                    m.velocity.theta3,
                    m.velocity.theta4,
                    m.acceleration.theta3,
                    m.acceleration.theta4,
                    linkage.transmission_angle(&m.position).to_degrees(),
                    p.coupler_point.x,
                    p.coupler_point.y,
                ],
                joints: vec![
                    (0.0, 0.0),
                    point(p.crank_pin),
                    point(p.rocker_pin),
                    (ground, 0.0),
                    point(p.coupler_point),
                ],
            })
        }),
    })
}

pub(super) fn slider_crank(args: &Args) -> Result<Sweep<'_>, String> {
    let d = &args.dimensions;
    let mut linkage = SliderCrank::new(d[0], d[1], d[2]).map_err(refused)?;
    if let Some(p) = &args.coupler_point {
        linkage = linkage
            .with_coupler_point(p[0], angle::radians(p[1]))
            .map_err(refused)?;
    }
    let (rate, accel, on) = (args.rate, args.accel, branch(args));
    Ok(Sweep {
        title: format!(
            "Slider-crank {} {} mm, offset {} mm",
            tidy(d[0]),
            tidy(d[1]),
            tidy(d[2])
        ),
        columns: names(&[
            "theta3_deg",
            "d",
            "omega3",
            "d_dot",
            "alpha3",
            "d_ddot",
            "transmission_deg",
            "coupler_x",
            "coupler_y",
        ]),
        groups: vec![
            ("rod angle (°)".into(), 0..1),
            ("slider position (mm)".into(), 1..2),
            ("rod angular velocity (rad/s)".into(), 2..3),
            ("slider velocity (mm/s)".into(), 3..4),
            ("rod angular acceleration (rad/s²)".into(), 4..5),
            ("slider acceleration (mm/s²)".into(), 5..6),
            ("transmission angle (°), 40°–140° shaded".into(), 6..7),
        ],
        band_column: Some(6),
        links: vec![(0, 1), (1, 2), (1, 3), (2, 3)],
        traced: 3,
        pieces: slider_crank_pieces(&linkage),
        change_points: slider_crank_change_points(&linkage),
        sample: Box::new(move |input, flipped| {
            let t = crate::angle::radians(input);
            let on = if flipped { on.other() } else { on };
            let m = linkage.motion(t, on, rate, accel)?;
            let p = linkage.points(t, &m.position)?;
            Ok(Sample {
                values: vec![
                    m.position.theta3.to_degrees(),
                    m.position.d,
                    m.velocity.theta3,
                    m.velocity.d,
                    m.acceleration.theta3,
                    m.acceleration.d,
                    linkage.transmission_angle(&m.position).to_degrees(),
                    p.coupler_point.x,
                    p.coupler_point.y,
                ],
                joints: vec![
                    (0.0, 0.0),
                    point(p.crank_pin),
                    point(p.slider_pin),
                    point(p.coupler_point),
                ],
            })
        }),
    })
}

pub(super) fn inverted(args: &Args) -> Result<Sweep<'_>, String> {
    let d = &args.dimensions;
    let linkage =
        InvertedSliderCrank::new(d[0], d[1], d[2], angle::radians(d[3])).map_err(refused)?;
    let (rate, accel, on) = (args.rate, args.accel, branch(args));
    let ground = d[0];
    Ok(Sweep {
        title: format!(
            "Inverted slider-crank {} {} mm, offset {} mm, angle {}°",
            tidy(d[0]),
            tidy(d[1]),
            tidy(d[2]),
            tidy(d[3])
        ),
        columns: names(&["theta4_deg", "b", "omega4", "b_dot", "alpha4", "b_ddot"]),
        groups: vec![
            ("rocker angle (°)".into(), 0..1),
            ("slide length (mm)".into(), 1..2),
            ("rocker angular velocity (rad/s)".into(), 2..3),
            ("slide velocity (mm/s)".into(), 3..4),
            ("rocker angular acceleration (rad/s²)".into(), 4..5),
            ("slide acceleration (mm/s²)".into(), 5..6),
        ],
        band_column: None,
        links: vec![(0, 1), (2, 3), (3, 1)],
        traced: 1,
        pieces: inverted_pieces(&linkage),
        change_points: inverted_change_points(&linkage),
        sample: Box::new(move |input, flipped| {
            let t = crate::angle::radians(input);
            let on = if flipped { on.other() } else { on };
            let m = linkage.motion(t, on, rate, accel)?;
            let p = linkage.points(t, &m.position)?;
            Ok(Sample {
                values: vec![
                    m.position.theta4.to_degrees(),
                    m.position.b,
                    m.velocity.theta4,
                    m.velocity.b,
                    m.acceleration.theta4,
                    m.acceleration.b,
                ],
                joints: vec![
                    (0.0, 0.0),
                    point(p.crank_pin),
                    (ground, 0.0),
                    point(p.slide_origin),
                ],
            })
        }),
    })
}

pub(super) fn jansen(args: &Args) -> Result<Sweep<'_>, String> {
    let leg = JansenLeg::<f64>::holy();
    let (rate, accel) = (args.rate, args.accel);
    Ok(Sweep {
        title: "Jansen's leg, published lengths".into(),
        columns: names(&[
            "foot_x", "foot_y", "foot_vx", "foot_vy", "foot_ax", "foot_ay",
        ]),
        groups: vec![
            ("foot position (mm)".into(), 0..2),
            ("foot velocity (mm/s)".into(), 2..4),
            ("foot acceleration (mm/s²)".into(), 4..6),
        ],
        band_column: None,
        links: vec![
            (0, 1),
            (1, 3),
            (2, 3),
            (1, 4),
            (2, 4),
            (2, 5),
            (3, 5),
            (5, 6),
            (4, 6),
            (4, 7),
            (6, 7),
        ],
        traced: 7,
        pieces: vec![Piece::full_turn()],
        change_points: Vec::new(),
        sample: Box::new(move |input, _| {
            let t = crate::angle::radians(input);
            let m = leg.motion(t, JansenLeg::<f64>::DRAWN, rate, accel)?;
            let p = leg.points(t, &m.position)?;
            let v = leg.point_velocities(t, &m.position, rate, &m.velocity)?;
            let a =
                leg.point_accelerations(t, &m.position, rate, &m.velocity, accel, &m.acceleration)?;
            Ok(Sample {
                values: vec![p.foot.x, p.foot.y, v.foot.x, v.foot.y, a.foot.x, a.foot.y],
                joints: vec![
                    (0.0, 0.0),
                    point(p.crank_pin),
                    (-38.0, -7.8),
                    point(p.upper),
                    point(p.lower),
                    point(p.back),
                    point(p.knee),
                    point(p.foot),
                ],
            })
        }),
    })
}
