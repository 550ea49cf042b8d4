//! The six-bars at the command line's edge, shared by `analyse` and `sweep`: each built from
//! its dimensions as typed (an angle in degrees), where a Watt six-bar's loops close (its
//! closed form says only whether they close at one input, not over which range), and the
//! Stephenson six-bar's assemblies at one input (it has no closed form, so Newton needs a
//! start, which a scan finds).

use mechanisms::{StephensonSixBar, StephensonSixBarUnknowns, WattSixBar};
use mechgen::{Branch, NewtonOptions};

use crate::analyse::refused;
use crate::angle;

/// A Watt six-bar from `ground crank coupler rocker extension angle(°) coupler rocker x y`.
pub fn watt(d: &[f64]) -> Result<WattSixBar<f64>, String> {
    WattSixBar::new(
        [d[0], d[1], d[2], d[3]],
        d[4],
        angle::radians(d[5]),
        d[6],
        d[7],
        (d[8], d[9]),
    )
    .map_err(refused)
}

/// A Stephenson six-bar from `ground crank link bc cd angle(°) rocker output-rocker x y`.
pub fn stephenson(d: &[f64]) -> Result<StephensonSixBar<f64>, String> {
    StephensonSixBar::new(
        d[0],
        d[1],
        d[2],
        [d[3], d[4]],
        angle::radians(d[5]),
        d[6],
        d[7],
        (d[8], d[9]),
    )
    .map_err(refused)
}

/// Where an input can go: a full turn, or ranges in degrees, each `from < to` with `from` in
/// [0°, 360°) unless the range passes 0°, when it starts below 0°.
#[derive(Debug, PartialEq)]
pub enum Reach {
    FullTurn,
    Ranges(Vec<(f64, f64)>),
}

/// How many inputs a turn is scanned at: a reachable range narrower than a tenth of a degree
/// can be missed (and a gap that narrow jumped).
const SCAN: usize = 3600;

/// Where a Watt six-bar closes both loops on `branches`. Its closed form says whether the
/// loops close at one input; the ranges come from a scan of a turn every tenth of a degree,
/// then each boundary between an input that closes and one that does not bisected until the
/// two are adjacent floating-point numbers. Each end is a toggle of one loop or the other
/// (where that loop's two branches meet), so the ends are exact to the input's rounding.
pub fn watt_reach(linkage: &WattSixBar<f64>, branches: [Branch; 2]) -> Reach {
    let closes = |degrees: f64| linkage.assemble(degrees.to_radians(), branches).is_ok();
    let at = |k: usize| k as f64 * 360.0 / SCAN as f64;
    let scanned: Vec<bool> = (0..SCAN).map(|k| closes(at(k))).collect();
    let Some(gap) = scanned.iter().position(|&c| !c) else {
        return Reach::FullTurn;
    };
    // From a sample that does not close, once round, so no range is cut at 0°.
    let mut ranges = Vec::new();
    let mut start = None;
    for k in gap + 1..=gap + SCAN {
        match (scanned[k % SCAN], start) {
            (true, None) => start = Some(k),
            (false, Some(first)) => {
                let from = boundary(&closes, at(first), at(first - 1));
                let to = boundary(&closes, at(k - 1), at(k));
                ranges.push(normal(from, to));
                start = None;
            }
            _ => {}
        }
    }
    ranges.sort_by(|a, b| a.0.total_cmp(&b.0));
    Reach::Ranges(ranges)
}

/// The last input that closes between `inside`, which closes, and `outside`, which does not,
/// by bisection down to adjacent floating-point numbers.
fn boundary(closes: &impl Fn(f64) -> bool, mut inside: f64, mut outside: f64) -> f64 {
    for _ in 0..200 {
        let middle = 0.5 * (inside + outside);
        if middle == inside || middle == outside {
            break;
        }
        if closes(middle) {
            inside = middle;
        } else {
            outside = middle;
        }
    }
    inside
}

/// A range moved by whole turns so it starts in [0°, 360°), or below 0° if it passes 0°.
pub fn normal(from: f64, to: f64) -> (f64, f64) {
    let turns = (from / 360.0).floor() * 360.0;
    let (from, to) = (from - turns, to - turns);
    if to > 360.0 {
        (from - 360.0, to - 360.0)
    } else {
        (from, to)
    }
}

/// A Stephenson six-bar's dimensions as typed, which its type keeps private, for the scan.
#[derive(Clone, Copy)]
pub struct StephensonDimensions {
    ground: f64,
    crank: f64,
    link: f64,
    bc: f64,
    cd: f64,
    angle: f64,
    rocker: f64,
    output_rocker: f64,
    pivot: (f64, f64),
}

impl StephensonDimensions {
    /// From the dimensions as typed, already checked by [`stephenson`].
    pub fn new(d: &[f64]) -> Self {
        StephensonDimensions {
            ground: d[0],
            crank: d[1],
            link: d[2],
            bc: d[3],
            cd: d[4],
            angle: angle::radians(d[5]),
            rocker: d[6],
            output_rocker: d[7],
            pivot: (d[8], d[9]),
        }
    }

    /// The lengths scaled to the largest of them and the pivot's coordinates, so that no
    /// square in the scan overflows or underflows whatever their size.
    fn scaled(&self) -> Self {
        let scale = [
            self.ground,
            self.crank,
            self.link,
            self.bc,
            self.cd,
            self.rocker,
            self.output_rocker,
            self.pivot.0.abs(),
            self.pivot.1.abs(),
        ]
        .into_iter()
        .fold(0.0, f64::max);
        StephensonDimensions {
            ground: self.ground / scale,
            crank: self.crank / scale,
            link: self.link / scale,
            bc: self.bc / scale,
            cd: self.cd / scale,
            angle: self.angle,
            rocker: self.rocker / scale,
            output_rocker: self.output_rocker / scale,
            pivot: (self.pivot.0 / scale, self.pivot.1 / scale),
        }
    }

    /// For a trial rocker angle θ4 and the side of A C that B is on: the angles θ3, θ5, θ6
    /// with the first loop closed (B where the circles about A and C meet) and how far D
    /// misses the circle of the output rocker about O6; `None` where the circles do not meet.
    fn trial(&self, theta2: f64, theta4: f64, side: f64) -> Option<([f64; 4], f64)> {
        let a = (self.crank * theta2.cos(), self.crank * theta2.sin());
        let c = (
            self.ground + self.rocker * theta4.cos(),
            self.rocker * theta4.sin(),
        );
        let (dx, dy) = (c.0 - a.0, c.1 - a.1);
        let distance = dx.hypot(dy);
        if !(distance > 0.0
            && distance <= self.link + self.bc
            && distance >= (self.link - self.bc).abs())
        {
            return None;
        }
        let along =
            (distance * distance + self.link * self.link - self.bc * self.bc) / (2.0 * distance);
        let across = (self.link * self.link - along * along).max(0.0).sqrt() * side;
        let (ux, uy) = (dx / distance, dy / distance);
        let b = (
            a.0 + along * ux - across * uy,
            a.1 + along * uy + across * ux,
        );
        let theta3 = (b.1 - a.1).atan2(b.0 - a.0);
        let theta5 = (c.1 - b.1).atan2(c.0 - b.0);
        let d = (
            c.0 + self.cd * (theta5 + self.angle).cos(),
            c.1 + self.cd * (theta5 + self.angle).sin(),
        );
        let (ex, ey) = (d.0 - self.pivot.0, d.1 - self.pivot.1);
        let theta6 = ey.atan2(ex);
        Some((
            [theta3, theta4, theta5, theta6],
            ex.hypot(ey) - self.output_rocker,
        ))
    }
}

/// The Stephenson six-bar's assemblies at `theta2` (radians). It has no closed form, so they
/// are found independently of its loop equations: for each side of A C that B can be on, the
/// rocker angle θ4 is scanned over a turn at 3600 points; the first loop closes by
/// intersecting circles, and where D's miss of the output rocker's circle changes sign it is
/// bisected to a root, which the generated Newton then polishes. Assemblies that polish to
/// the same position are kept once; a root where the miss touches zero without changing sign
/// (a toggle) is not found. In order of side (B left of A C first), then of θ4.
pub fn stephenson_assemblies(
    linkage: &StephensonSixBar<f64>,
    dimensions: &StephensonDimensions,
    theta2: f64,
) -> Vec<StephensonSixBarUnknowns<f64>> {
    let scaled = dimensions.scaled();
    let options = NewtonOptions::default();
    let mut found: Vec<StephensonSixBarUnknowns<f64>> = Vec::new();
    for side in [1.0, -1.0] {
        let miss = |theta4: f64| scaled.trial(theta2, theta4, side).map(|t| t.1);
        let at = |k: usize| -std::f64::consts::PI + k as f64 * std::f64::consts::TAU / SCAN as f64;
        let mut previous: Option<(f64, f64)> = None;
        for k in 0..=SCAN {
            let theta4 = at(k);
            let here = miss(theta4).map(|m| (theta4, m));
            if let (Some((x0, m0)), Some((x1, m1))) = (previous, here) {
                if (m0 <= 0.0) != (m1 <= 0.0) {
                    if let Some(root) = bisect(&miss, x0, m0, x1) {
                        if let Some((angles, _)) = scaled.trial(theta2, root, side) {
                            let guess = StephensonSixBarUnknowns::from_array(angles);
                            if let Ok(solved) = linkage.position(theta2, &guess, &options) {
                                let q = solved.value;
                                if !found.iter().any(|f| same(f, &q)) {
                                    found.push(q);
                                }
                            }
                        }
                    }
                }
            }
            previous = here;
        }
    }
    found
}

/// A root of `miss` between `low`, where it is `at_low`, and `high`, where its sign differs;
/// `None` if the circles stop meeting in between.
fn bisect(
    miss: &impl Fn(f64) -> Option<f64>,
    mut low: f64,
    at_low: f64,
    mut high: f64,
) -> Option<f64> {
    for _ in 0..100 {
        let middle = 0.5 * (low + high);
        if middle == low || middle == high {
            break;
        }
        if (miss(middle)? <= 0.0) == (at_low <= 0.0) {
            low = middle;
        } else {
            high = middle;
        }
    }
    Some(low)
}

/// Whether two positions are the same, every angle within a micro-radian modulo a turn.
fn same(a: &StephensonSixBarUnknowns<f64>, b: &StephensonSixBarUnknowns<f64>) -> bool {
    a.to_array().iter().zip(b.to_array()).all(|(x, y)| {
        let d = (x - y).rem_euclid(std::f64::consts::TAU);
        d.min(std::f64::consts::TAU - d) < 1e-6
    })
}

#[cfg(test)]
mod tests {
    use super::{
        Reach, StephensonDimensions, normal, stephenson, stephenson_assemblies, watt, watt_reach,
    };
    use mechgen::Branch;

    const STEPHENSON: [f64; 10] = [
        100.0, 20.0, 117.0, 60.0, 63.0, -55.577, 52.0, 85.0, 189.0, -26.0,
    ];

    #[test]
    fn a_range_through_zero_starts_below_it() {
        assert_eq!(normal(350.0, 370.0), (-10.0, 10.0));
        assert_eq!(normal(370.0, 380.0), (10.0, 20.0));
        assert_eq!(normal(-20.0, 10.0), (-20.0, 10.0));
    }

    #[test]
    fn every_stephenson_assembly_found_closes_both_loops() {
        let linkage = stephenson(&STEPHENSON).unwrap();
        let found = stephenson_assemblies(&linkage, &StephensonDimensions::new(&STEPHENSON), 0.0);
        assert!(found.len() >= 2, "{found:?}");
        for q in &found {
            assert!(linkage.residual(0.0, q).iter().all(|f| f.abs() < 1e-9));
        }
    }

    #[test]
    fn the_documented_watt_six_bar_turns_fully() {
        let linkage = watt(&[
            180.0, 80.0, 200.0, 150.0, 100.0, 45.8366, 220.0, 160.0, 300.0, 150.0,
        ])
        .unwrap();
        assert_eq!(
            watt_reach(&linkage, [Branch::Open, Branch::Open]),
            Reach::FullTurn
        );
    }
}
