//! The input's reachable pieces, and the change points inside them, from each linkage's
//! closed-form limits.

use super::*;

/// A reachable range of the input, degrees. A full turn is sampled from its start, ends
/// included; a range that ends at toggles (where the rates are unbounded and the branches
/// meet) is sampled every step from its middle, a regular point, out toward both ends,
/// strictly inside them.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Piece {
    pub(super) from: f64,
    pub(super) to: f64,
    pub(super) full_turn: bool,
    /// The piece in words, for the summary.
    pub(super) words: String,
}

impl Piece {
    pub(super) fn full_turn() -> Self {
        Piece {
            from: 0.0,
            to: 360.0,
            full_turn: true,
            words: "a full turn".into(),
        }
    }

    pub(super) fn between(from: f64, to: f64) -> Self {
        Piece {
            from,
            to,
            full_turn: false,
            words: format!(
                "{}° to {}° (toggles at the ends)",
                output::fixed(from, 2),
                output::fixed(to, 2)
            ),
        }
    }

    /// The first input and the number of samples, as a float so a tiny step cannot overflow
    /// the count before it is checked.
    pub(super) fn grid(&self, step: f64) -> (f64, f64) {
        if self.full_turn {
            (self.from, ((self.to - self.from) / step).floor() + 1.0)
        } else {
            let middle = 0.5 * (self.from + self.to);
            let beside = ((0.5 * (self.to - self.from)) / step).ceil() - 1.0;
            let beside = beside.max(0.0);
            (middle - beside * step, 2.0 * beside + 1.0)
        }
    }
}

/// A four-bar crank's reachable ranges from its toggles ([`four_bar_toggles`]): `|θ2|`
/// between the folded toggle (or 0) and the extended toggle (or 180°), so one range through
/// 0° or 180°, or two mirror-image ranges.
pub(super) fn four_bar_pieces(linkage: &FourBar<f64>) -> Vec<Piece> {
    let (folded, extended) = four_bar_toggles(linkage);
    let pieces = match (folded, extended) {
        (None, None) => vec![Piece::full_turn()],
        (Some(f), None) => vec![Piece::between(f, 360.0 - f)],
        (None, Some(e)) => vec![Piece::between(-e, e)],
        (Some(f), Some(e)) => vec![Piece::between(f, e), Piece::between(360.0 - e, 360.0 - f)],
    };
    pieces.into_iter().filter(|p| p.from < p.to).collect()
}

/// A four-bar crank's toggles, `|θ2|` in degrees: its closed-form limit angles, folded and
/// extended, but for a limit at a change point (0° or 180°, where the linkage lies flat and
/// goes on), which bounds no range: the crank passes through it. Whether the closed form
/// finds a limit there is the rounding's to decide (equal chords), and was, at 1e308 mm,
/// where a change-point four-bar came out as two ranges each said to end at toggles, 0° one
/// of them.
pub(crate) fn four_bar_toggles(linkage: &FourBar<f64>) -> (Option<f64>, Option<f64>) {
    let limits = linkage.limit_angles();
    let change_points = four_bar_change_points(linkage);
    let toggle = |limit: Option<f64>, change_point: f64| {
        limit
            .filter(|_| !change_points.contains(&change_point))
            .map(f64::to_degrees)
    };
    (toggle(limits.folded, 0.0), toggle(limits.extended, 180.0))
}

/// A slider-crank's reachable ranges: the rod reaches the slider's line where
/// `|c − l2·sin θ2| ≤ l3`, so where `sin θ2` lies in `[(c − l3)/l2, (c + l3)/l2]`.
pub(super) fn slider_crank_pieces(linkage: &SliderCrank<f64>) -> Vec<Piece> {
    if linkage.crank_turns_fully() {
        return vec![Piece::full_turn()];
    }
    let [l2, l3, c] = linkage.dimensions();
    let (low, high) = ((c - l3) / l2, (c + l3) / l2);
    let arc = |s: f64| s.clamp(-1.0, 1.0).asin().to_degrees();
    let pieces = if low > -1.0 && high < 1.0 {
        vec![
            Piece::between(arc(low), arc(high)),
            Piece::between(180.0 - arc(high), 180.0 - arc(low)),
        ]
    } else if high < 1.0 {
        vec![Piece::between(180.0 - arc(high), 360.0 + arc(high))]
    } else {
        vec![Piece::between(arc(low), 180.0 - arc(low))]
    };
    pieces.into_iter().filter(|p| p.from < p.to).collect()
}

/// An inverted slider-crank's reachable range: the slide passes at `|c·sin γ|` from O4, so
/// the crank pin A must be at least that far from O4, `|A − O4|² = l1² + l2² − 2·l1·l2·cos θ2`.
pub(super) fn inverted_pieces(linkage: &InvertedSliderCrank<f64>) -> Vec<Piece> {
    let [l1, l2, c, gamma] = linkage.dimensions();
    // On the linkage scaled to its largest dimension, where no square overflows.
    let scale = l1.max(l2).max(c.abs());
    let (l1, l2, reach) = (l1 / scale, l2 / scale, (c * gamma.sin()).abs() / scale);
    if reach <= (l1 - l2).abs() {
        return vec![Piece::full_turn()];
    }
    let cosine = ((l1 * l1 + l2 * l2 - reach * reach) / (2.0 * l1 * l2)).clamp(-1.0, 1.0);
    let limit = cosine.acos().to_degrees();
    [Piece::between(limit, 360.0 - limit)]
        .into_iter()
        .filter(|p| p.from < p.to)
        .collect()
}

/// Whether two lengths of a linkage whose longest is `longest` are equal to rounding.
pub(super) fn equal_lengths(a: f64, b: f64, longest: f64) -> bool {
    (a - b).abs() <= 8.0 * f64::EPSILON * longest
}

/// A four-bar's change points: the chord O4 − A is shortest at 0° (`|l1 − l2|`) and longest
/// at 180° (`l1 + l2`); where that extreme equals the shortest (`|l3 − l4|`) or longest
/// (`l3 + l4`) chord the dyad closes over, the linkage lies flat there and goes on, on the
/// other branch. (Where 0°'s chord equals `l3 + l4`, or 180°'s `|l3 − l4|`, it assembles at
/// that input alone: no piece holds it.)
pub(super) fn four_bar_change_points(linkage: &FourBar<f64>) -> Vec<f64> {
    let longest = linkage.lengths().into_iter().fold(0.0, f64::max);
    // On lengths scaled to the longest, where no sum overflows.
    let [l1, l2, l3, l4] = linkage.lengths().map(|l| l / longest);
    let mut points = Vec::new();
    if equal_lengths((l1 - l2).abs(), (l3 - l4).abs(), 1.0) {
        points.push(0.0);
    }
    if equal_lengths(l1 + l2, l3 + l4, 1.0) {
        points.push(180.0);
    }
    points
}

/// A slider-crank's change points: the rod is square to the slide (`|c − l2·sin θ2| = l3`)
/// at an extreme of `c − l2·sin θ2`, at 90° (`c − l2`) or 270° (`c + l2`): crank and rod
/// equal, say, with no offset.
pub(super) fn slider_crank_change_points(linkage: &SliderCrank<f64>) -> Vec<f64> {
    let dimensions = linkage.dimensions();
    let longest = dimensions.iter().fold(0.0, |m: f64, d| m.max(d.abs()));
    let [l2, l3, c] = dimensions.map(|d| d / longest);
    [(90.0, c - l2), (270.0, c + l2)]
        .into_iter()
        .filter(|(_, reach)| equal_lengths(reach.abs(), l3, 1.0))
        .map(|(at, _)| at)
        .collect()
}

/// An inverted slider-crank's change point: the crank pin A comes closest to O4 at 0°
/// (`|l1 − l2|`); where that is the slide's distance from O4 (`|c·sin γ|`), the slide passes
/// through A there, square to the chord (the isosceles linkage, `l1 = l2`, `c·sin γ = 0`).
pub(super) fn inverted_change_points(linkage: &InvertedSliderCrank<f64>) -> Vec<f64> {
    let [l1, l2, c, gamma] = linkage.dimensions();
    let longest = l1.max(l2).max(c.abs());
    let (l1, l2, reach) = (
        l1 / longest,
        l2 / longest,
        (c * gamma.sin()).abs() / longest,
    );
    if equal_lengths((l1 - l2).abs(), reach, 1.0) {
        vec![0.0]
    } else {
        Vec::new()
    }
}

/// The change points (`points`, each repeating every turn) in `(from, to]`.
pub(super) fn crossed(points: &[f64], from: f64, to: f64) -> impl Iterator<Item = f64> + '_ {
    points.iter().flat_map(move |&point| {
        let first = ((from - point) / 360.0).floor() as i64;
        let last = ((to - point) / 360.0).ceil() as i64;
        (first..=last)
            .map(move |turn| point + 360.0 * turn as f64)
            .filter(move |&at| from < at && at <= to)
    })
}
