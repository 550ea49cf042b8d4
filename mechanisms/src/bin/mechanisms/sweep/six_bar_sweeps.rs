//! The six-bars' sweeps: the Watt six-bar in closed form, the Stephenson six-bar walked by
//! Newton.

use super::*;

/// A six-bar's columns: its four unknowns' angles, rates and accelerations.
pub(super) fn six_bar_columns() -> (Vec<String>, Vec<(String, std::ops::Range<usize>)>) {
    (
        names(&[
            "theta3_deg",
            "theta4_deg",
            "theta5_deg",
            "theta6_deg",
            "omega3",
            "omega4",
            "omega5",
            "omega6",
            "alpha3",
            "alpha4",
            "alpha5",
            "alpha6",
        ]),
        vec![
            ("link angles (°)".into(), 0..4),
            ("angular velocities (rad/s)".into(), 4..8),
            ("angular accelerations (rad/s²)".into(), 8..12),
        ],
    )
}

/// A six-bar's values: angles in degrees, then rates, then accelerations.
pub(super) fn six_bar_values(
    position: [f64; 4],
    velocity: [f64; 4],
    acceleration: [f64; 4],
) -> Vec<f64> {
    position
        .iter()
        .map(|t| t.to_degrees())
        .chain(velocity)
        .chain(acceleration)
        .collect()
}

pub(super) fn watt(args: &Args) -> Result<Sweep<'_>, String> {
    let d = &args.dimensions;
    let linkage = six_bars::watt(d)?;
    let (rate, accel) = (args.rate, args.accel);
    let on = [branch_of(args, 0), branch_of(args, 1)];
    let pieces = match six_bars::watt_reach(&linkage, on) {
        Reach::FullTurn => vec![Piece::full_turn()],
        Reach::Ranges(ranges) => ranges
            .into_iter()
            .map(|(from, to)| Piece::between(from, to))
            .collect(),
    };
    let (columns, groups) = six_bar_columns();
    let pivot = (d[8], d[9]);
    let ground = d[0];
    let word = |b: Branch| if b == Branch::Open { "open" } else { "crossed" };
    Ok(Sweep {
        title: format!(
            "{}{},{}",
            filled(
                "Watt six-bar {} {} {} {} mm, extension {} mm at {}°, {} {} mm, O6 ({}, {}) mm, \
                 branches ",
                d
            ),
            word(on[0]),
            word(on[1])
        ),
        columns,
        groups,
        band_column: None,
        // O2 A B O4 C D O6; the rocker O4 B C is a ternary link.
        links: vec![(0, 1), (1, 2), (2, 3), (3, 4), (2, 4), (4, 5), (5, 6)],
        traced: 5,
        pieces,
        change_points: Vec::new(),
        sample: Box::new(move |input, _| {
            let t = crate::angle::radians(input);
            let m = linkage.motion(t, on, rate, accel)?;
            let p = linkage.points(t, &m.position)?;
            Ok(Sample {
                values: six_bar_values(
                    m.position.to_array(),
                    m.velocity.to_array(),
                    m.acceleration.to_array(),
                ),
                joints: vec![
                    (0.0, 0.0),
                    point(p.crank_pin),
                    point(p.rocker_pin),
                    (ground, 0.0),
                    point(p.extension_pin),
                    point(p.output_pin),
                    pivot,
                ],
            })
        }),
    })
}

/// Where a walk stopped, in words: a toggle only where Newton said the loops cannot be
/// solved beyond (a walk that stopped on a value not finite, or on a position the loops fix
/// too loosely, says so instead).
pub(super) fn stop_words(stop: &Stop<f64>) -> String {
    match stop {
        Stop::Toggle {
            error: Error::NonFinite { quantity },
            ..
        } => format!("a {quantity} not finite, where the walk could not go on"),
        Stop::Toggle {
            error: error @ Error::Inaccurate { .. },
            ..
        } => format!("a position the loops fix too loosely ({error})"),
        Stop::Toggle { .. } => "a toggle".into(),
        Stop::BranchChange { .. } => "a change point".into(),
    }
}

/// Where a walk of `steps` steps of `step` from `start` stops: the last input it reaches
/// (radians) and the position there, and why it stopped, if it did. The walk reports only the step it could not
/// finish, so the end is then closed in on by halving: from the last position reached, a
/// step of half the last length is tried, kept if the walk finishes it, halved again if
/// not, down to the input's rounding.
pub(super) fn edge(
    linkage: &StephensonSixBar<f64>,
    start: f64,
    position: [f64; 4],
    step: f64,
    steps: u32,
) -> ((f64, [f64; 4]), Option<Stop<f64>>) {
    let options = NewtonOptions::default();
    let mut last = (start, position);
    let mut stop = None;
    for sample in Walk::new(linkage, start, position, step, steps, options) {
        match sample {
            Ok(sample) => last = (sample.input, sample.position),
            Err(why) => {
                stop = Some(why);
                break;
            }
        }
    }
    let Some(stop) = stop else {
        return (last, None);
    };
    let mut length = 0.5 * step;
    for _ in 0..200 {
        if last.0 + length == last.0 {
            break;
        }
        match Walk::new(linkage, last.0, last.1, length, 1, options).last() {
            Some(Ok(sample)) => last = (sample.input, sample.position),
            _ => length *= 0.5,
        }
    }
    (last, Some(stop))
}

/// The Stephenson six-bar, which has no closed form. Its start is its first assembly (in
/// the scan's order, see `six_bars::stephenson_assemblies`) at the first whole degree from 0°
/// where it has one. From there `mechgen::sweep::Sweep` walks it up, degree by degree, and
/// down, each way until it stops at a toggle (or a change point) or has gone a full turn
/// between them: that is the reachable piece. Other assemblies' circuits are not followed.
/// Each sample then walks on from the last one, so Newton always starts near its root.
pub(super) fn stephenson(args: &Args) -> Result<Sweep<'_>, String> {
    let d = &args.dimensions;
    let linkage = six_bars::stephenson(d)?;
    // The walk evaluates the loops at their own size (its residual, its slopes), where the
    // sum of their vectors overflows once the dimensions sum past the largest float.
    let size = Mechanism::StephensonSixBar
        .dimensions()
        .iter()
        .zip(d)
        .filter(|(name, _)| !name.ends_with("(°)"))
        .fold(0.0, |sum, (_, v)| sum + v.abs());
    if size > f64::MAX {
        return Err(format!(
            "the stephenson-six-bar's lengths and coordinates sum to more than the largest \
             float ({:e}): its walk evaluates the loops at their own size, where they \
             overflow; give them in a larger unit",
            f64::MAX
        ));
    }
    let dimensions = StephensonDimensions::new(d);
    let Some((start, position)) = (0..360).find_map(|degree| {
        let input = f64::from(degree);
        six_bars::stephenson_assemblies(&linkage, &dimensions, crate::angle::radians(input))
            .first()
            .map(|q| (input, q.to_array()))
    }) else {
        return Err(
            "the stephenson-six-bar cannot be assembled at any input angle: at no \
                    whole degree does any position close both loops"
                .into(),
        );
    };
    let options = NewtonOptions::default();
    let degree = 1f64.to_radians();
    let walk = |step: f64, steps: u32| edge(&linkage, start.to_radians(), position, step, steps);
    let (piece, shift) = match walk(degree, 360) {
        (end, None) => {
            // A circuit may need more than one turn of the input to close; the sweep draws
            // one, from its start, and says so.
            let turn = std::f64::consts::TAU;
            let back = end.1.iter().zip(position).all(|(a, b)| {
                let d = (a - b).rem_euclid(turn);
                d.min(turn - d) < 1e-6
            });
            let mut piece = Piece::full_turn();
            piece.words = format!(
                "a full turn (followed by Newton from its assembly at {}°{})",
                tidy(start),
                if back {
                    ""
                } else {
                    "; after a turn it is not back where it started: its circuit takes more \
                     turns of the input, and the sweep draws the first"
                }
            );
            (piece, 0.0)
        }
        ((high, _), Some(up)) => {
            let high = high.to_degrees();
            let left = 360 - ((high - start).ceil().max(0.0) as u32).min(360);
            let ((low, _), down) = walk(-degree, left);
            // A walk down that did not stop went a full turn below the top, which its whole
            // degrees fall short of by the top's fraction of one (the top itself, at a toggle,
            // is no whole degree): the piece is that full turn.
            let low = if down.is_none() {
                high - 360.0
            } else {
                low.to_degrees()
            };
            // Whole turns, so the piece reads as the other mechanisms' do.
            let shift = low - six_bars::normal(low, high).0;
            let mut piece = Piece::between(low - shift, high - shift);
            piece.words = format!(
                "{}° to {}° ({} below, {} above, where Newton's walk from its assembly at {}° \
                 stopped)",
                output::fixed(piece.from, 2),
                output::fixed(piece.to, 2),
                down.as_ref().map_or("a full turn".into(), stop_words),
                stop_words(&up),
                tidy(start - shift)
            );
            (piece, shift)
        }
    };
    let (rate, accel) = (args.rate, args.accel);
    let (ground, pivot) = (d[0], (d[8], d[9]));
    let (columns, groups) = six_bar_columns();
    // Where the walk to the next sample starts: the last position solved.
    let mut last = ((start - shift).to_radians(), position);
    Ok(Sweep {
        title: filled(
            "Stephenson six-bar {} {} {} mm, ternary {} {} mm at {}°, rockers {} {} mm, \
             O6 ({}, {}) mm",
            d,
        ),
        columns,
        groups,
        band_column: None,
        // O2 A B C O4 D O6; B C D is the floating ternary link.
        links: vec![(0, 1), (1, 2), (2, 3), (3, 4), (3, 5), (2, 5), (5, 6)],
        traced: 2,
        pieces: vec![piece],
        change_points: Vec::new(),
        sample: Box::new(move |input, _| {
            let t = crate::angle::radians(input);
            let distance = t - last.0;
            let q = if distance == 0.0 {
                last.1
            } else {
                let steps = (distance.abs() / degree)
                    .ceil()
                    .clamp(1.0, f64::from(u32::MAX));
                let mut walk = Walk::new(
                    &linkage,
                    last.0,
                    last.1,
                    distance / steps,
                    steps as u32,
                    options,
                );
                match walk.by_ref().last() {
                    Some(Ok(sample)) => sample.position,
                    Some(Err(Stop::Toggle { error, .. })) => return Err(error),
                    Some(Err(Stop::BranchChange { .. })) | None => return Err(Error::OtherBranch),
                }
            };
            last = (t, q);
            let position = StephensonSixBarUnknowns::from_array(q);
            let m = linkage.motion_at(t, &position, rate, accel)?;
            let p = linkage.points(t, &position)?;
            Ok(Sample {
                values: six_bar_values(q, m.velocity.to_array(), m.acceleration.to_array()),
                joints: vec![
                    (0.0, 0.0),
                    point(p.crank_pin),
                    point(p.b),
                    point(p.c),
                    (ground, 0.0),
                    point(p.d),
                    pivot,
                ],
            })
        }),
    })
}
