//! The analyses where links line up, against a 256-bit truth (`mechgen_tests::oracle`'s
//! numbers): the four-bar's limit angles (its toggles), transmission extremes and dead
//! centres, and the slider-crank's dead centres, stroke and full-turn test, on lengths drawn
//! within 1e-17 to 1e-1 (relative) of a line-up, exactly on one, or a few units of rounding
//! either side of one, at link ratios to 1e12 (1e5 in f32) and sizes across each float's
//! range. Near a line-up a toggle or dead centre moves fast with the lengths (as the square
//! root of their distance from it), so an angle computed from `l3 ± l4` rounded first is the
//! toggle of other lengths, far from the given ones' own (1.5e-5 rad at a link ratio of 2e6).
//! The contract:
//!
//! - which side of every line-up the lengths are on (a limit or none, a dead centre or none,
//!   a full turn or not) is decided exactly;
//! - every angle is the given lengths' own to a few units of rounding: within `4·ε` of its
//!   magnitude, or of π for an angle measured from π (a dead centre's rocker angle,
//!   `π − angle`), and the stroke within `4·ε` of itself.

use std::f64::consts::PI;

use mechanisms::{FourBar, SliderCrank};
use mechgen::Real;
use mechgen_tests::oracle::draw::Rng;
use mechgen_tests::oracle::{Big, with_precision};

/// Units of rounding (of `T`'s ε) an angle may be off.
const ULPS: f64 = 4.0;

fn big(x: f64) -> Big {
    Big::from_f64(x)
}

/// The angle opposite side `c` of the triangle with sides `a`, `b`, `c` (exact values, `c`
/// within `[|a − b|, a + b]`): Kahan's `tan(C/2)`, exact to the working precision.
fn angle(a: &Big, b: &Big, c: &Big) -> Big {
    let difference = (a - b).abs();
    let sum = a + b;
    let opposite = ((c - &difference) * (c + &difference)).sqrt();
    let adjacent = ((&sum + c) * (&sum - c)).sqrt();
    let half = Big::atan2(&opposite, &adjacent);
    &half + &half
}

/// `T`'s ε, as `f64`.
fn epsilon<T: Real + Into<f64>>() -> f64 {
    T::epsilon().into()
}

/// `got` within `ULPS` units of rounding of `want`, relative to `relative_to`.
#[track_caller]
fn assert_close<T: Real + Into<f64>>(what: &str, got: f64, want: &Big, relative_to: f64) {
    let error = (big(got) - want).abs().to_f64();
    let bound = ULPS * epsilon::<T>() * relative_to;
    assert!(
        error <= bound,
        "{what}: {got:e}, the truth {:e}: off by {error:e} (bound {bound:e})",
        want.to_f64()
    );
}

/// Where a case's lengths are drawn: about a size up to `10^±scale`, each within `10^±spread`
/// of it, the spread up to `ratio`.
struct Lengths {
    size: f64,
    spread: f64,
}

impl Lengths {
    fn draw(rng: &mut Rng, ratio: f64, scale: f64) -> Self {
        Lengths {
            size: 10f64.powf(rng.range(-scale, scale)),
            spread: rng.range(0.0, ratio),
        }
    }

    /// One length, rounded to `T`.
    fn next<T: Real + Into<f64>>(&self, rng: &mut Rng) -> f64 {
        length::<T>(rng, self.size, self.spread)
    }
}

/// A length `10^±ratio` about `size`, rounded to `T`.
fn length<T: Real + Into<f64>>(rng: &mut Rng, size: f64, ratio: f64) -> f64 {
    T::from(size * 10f64.powf(rng.range(-ratio, ratio)))
        .unwrap()
        .into()
}

/// `target` moved off itself: not at all, by a few units of rounding, or by a relative
/// 1e-17 to 1e-1, either way, rounded to `T`; `None` where that is not positive.
fn near<T: Real + Into<f64>>(rng: &mut Rng, target: f64) -> Option<f64> {
    let moved = match rng.next_u64() % 4 {
        0 => target,
        1 => {
            let ulps = (rng.next_u64() % 9) as f64 - 4.0;
            target * (1.0 + ulps * epsilon::<T>() / 2.0)
        }
        _ => target * (1.0 + rng.sign() * 10f64.powf(rng.range(-17.0, -1.0))),
    };
    let rounded: f64 = T::from(moved)?.into();
    (rounded > 0.0 && rounded.is_finite()).then_some(rounded)
}

/// Four-bar lengths `[l1, l2, l3, l4]` near one of the line-ups that end a crank's range
/// (`l3 ± l4 = l1 ± l2`), a crank-rocker near one that ends its rocker's (a short crank, and
/// `l3 ± l2 = l1 ± l4`: where its dead centres meet a change point), or (one in seven)
/// anywhere.
fn four_bar_lengths<T: Real + Into<f64>>(
    rng: &mut Rng,
    ratio: f64,
    scale: f64,
) -> Option<[f64; 4]> {
    let drawn = Lengths::draw(rng, ratio, scale);
    let [l1, l2, l3] = [0; 3].map(|_| drawn.next::<T>(rng));
    match rng.next_u64() % 7 {
        // l3 + l4 = l1 + l2 (extended at π), l3 + l4 = |l1 − l2| (extended at 0),
        // |l3 − l4| = |l1 − l2| (folded at 0), |l3 − l4| = l1 + l2 (folded at π).
        kind @ 0..=3 => {
            let l4 = match kind {
                0 => l1 + l2 - l3,
                1 => (l1 - l2).abs() - l3,
                2 => l3 + rng.sign() * (l1 - l2).abs(),
                _ => l3 + rng.sign() * (l1 + l2),
            };
            Some([l1, l2, l3, near::<T>(rng, l4.abs())?])
        }
        kind @ (4 | 5) => {
            // The crank shortest; the coupler from the rocker's two line-ups with it.
            let l4 = l3;
            let crank =
                length::<T>(rng, l1.min(l4), drawn.spread) * 10f64.powf(-rng.range(0.0, ratio));
            let crank: f64 = T::from(crank)?.into();
            let coupler = if kind == 4 {
                l1 + l4 - crank
            } else {
                (l1 - l4).abs() + crank
            };
            Some([l1, crank, near::<T>(rng, coupler)?, l4])
        }
        _ => Some([l1, l2, l3, drawn.next::<T>(rng)]),
    }
}

/// How many of a run's cases were judged, and how many of them had a limit angle (or a dead
/// centre, or a full turn of the slider-crank's crank).
#[derive(Debug, Default)]
struct Judged {
    cases: usize,
    limited: usize,
}

/// The four-bar's limit angles, transmission extremes and dead centres against the truth.
fn four_bar_line_ups<T: Real + Into<f64>>(
    seed: u64,
    cases: usize,
    ratio: f64,
    scale: f64,
) -> (Judged, usize) {
    let mut rng = Rng(seed);
    let mut judged = Judged::default();
    let mut dead_centres = 0;
    for _ in 0..cases {
        let Some(lengths) = four_bar_lengths::<T>(&mut rng, ratio, scale) else {
            continue;
        };
        let [l1, l2, l3, l4] = lengths.map(|l| T::from(l).unwrap());
        // Lengths that close only flat are refused (a rule of their own, tested elsewhere).
        let Ok(linkage) = FourBar::new(l1, l2, l3, l4) else {
            continue;
        };
        judged.cases += 1;
        judged.limited += usize::from(!linkage.limit_angles().full_turn());
        let what = |name: &str| format!("{name} of {lengths:?}");
        with_precision(1024, || {
            let [l1, l2, l3, l4] = lengths.map(big);
            let (nearest, farthest) = ((&l1 - &l2).abs(), &l1 + &l2);
            let (folded, extended) = ((&l3 - &l4).abs(), &l3 + &l4);
            let limits = linkage.limit_angles();
            let extremes = linkage.transmission_extremes();
            let pi = Big::pi();
            // Folded: none where |l3 − l4| ≤ |l1 − l2| (the crank passes θ2 = 0).
            let want = if folded <= nearest {
                None
            } else if folded >= farthest {
                Some(pi.clone())
            } else {
                Some(angle(&l1, &l2, &folded))
            };
            match (limits.folded.map(Into::into), &want) {
                (None, None) => {
                    let min = angle(&l3, &l4, &nearest);
                    let got = extremes.min.into();
                    assert_close::<T>(
                        &what("least transmission angle"),
                        got,
                        &min,
                        got.max(1e-300),
                    );
                }
                (Some(got), Some(want)) => assert_close::<T>(&what("folded limit"), got, want, got),
                (got, want) => panic!(
                    "{}: {got:?}, the truth {:?}",
                    what("folded limit"),
                    want.as_ref().map(Big::to_f64)
                ),
            }
            // Extended: none where l3 + l4 ≥ l1 + l2 (the crank passes θ2 = π).
            let want = if extended >= farthest {
                None
            } else if extended <= nearest {
                Some(Big::zero())
            } else {
                Some(angle(&l1, &l2, &extended))
            };
            match (limits.extended.map(Into::into), &want) {
                (None, None) => {
                    let max = angle(&l3, &l4, &farthest);
                    let got = extremes.max.into();
                    assert_close::<T>(&what("greatest transmission angle"), got, &max, got);
                }
                (Some(got), Some(want)) => {
                    assert_close::<T>(&what("extended limit"), got, want, got.max(1e-300))
                }
                (got, want) => panic!(
                    "{}: {got:?}, the truth {:?}",
                    what("extended limit"),
                    want.as_ref().map(Big::to_f64)
                ),
            }
            // The rocker's extremes: π less the angle at O4 of O2 O4 B, |O2 B| = l3 ± l2.
            for branch in [mechgen::Branch::Open, mechgen::Branch::Crossed] {
                let Some(centres) = linkage.dead_centres(branch) else {
                    continue;
                };
                dead_centres += 1;
                for (centre, reach) in centres.iter().zip([&l3 + &l2, &l3 - &l2]) {
                    let want = &pi - angle(&l1, &l4, &reach);
                    let got: f64 = centre.theta4.into();
                    assert_close::<T>(&what("dead centre's rocker angle"), got.abs(), &want, PI);
                }
            }
        });
    }
    (judged, dead_centres)
}

/// Slider-crank dimensions `[l2, l3, c]` near `l3 − l2 = |c|` (the folded line-up just
/// reaching the slide) or `l3 + l2 = |c|`, or (one in three) anywhere.
fn slider_crank_dimensions<T: Real + Into<f64>>(
    rng: &mut Rng,
    ratio: f64,
    scale: f64,
) -> Option<[f64; 3]> {
    let drawn = Lengths::draw(rng, ratio, scale);
    let [l2, l3] = [0; 2].map(|_| drawn.next::<T>(rng));
    let offset = match rng.next_u64() % 3 {
        0 => (l3 - l2).abs(),
        1 => l3 + l2,
        _ => drawn.next::<T>(rng),
    };
    Some([l2, l3, rng.sign() * near::<T>(rng, offset)?])
}

/// The slider-crank's full-turn test, dead centres and stroke against the truth.
fn slider_crank_line_ups<T: Real + Into<f64>>(
    seed: u64,
    cases: usize,
    ratio: f64,
    scale: f64,
) -> Judged {
    let mut rng = Rng(seed);
    let mut judged = Judged::default();
    for _ in 0..cases {
        let Some(dimensions) = slider_crank_dimensions::<T>(&mut rng, ratio, scale) else {
            continue;
        };
        let [l2, l3, c] = dimensions.map(|l| T::from(l).unwrap());
        let Ok(linkage) = SliderCrank::new(l2, l3, c) else {
            continue;
        };
        judged.cases += 1;
        judged.limited += usize::from(linkage.dead_centres().is_some());
        let what = |name: &str| format!("{name} of {dimensions:?}");
        with_precision(1024, || {
            let [l2, l3, c] = dimensions.map(big);
            let offset = c.abs();
            let folded = &l3 - &l2;
            let turns = folded >= offset;
            assert_eq!(linkage.crank_turns_fully(), turns, "{}", what("full turn"));
            // √(r² − c²) where crank and rod line up at |O2 B| = r.
            let along = |r: &Big| ((r - &offset) * (r + &offset)).sqrt();
            let centres = linkage.dead_centres();
            assert_eq!(
                centres.is_some(),
                folded > offset,
                "{}",
                what("dead centres")
            );
            if let Some([outer, inner]) = centres {
                let outer_want = Big::atan2(&c, &along(&(&l3 + &l2)));
                let inner_want = Big::pi() + Big::atan2(&c, &along(&folded));
                let outer: f64 = outer.into();
                assert_close::<T>(
                    &what("outer dead centre"),
                    outer,
                    &outer_want,
                    outer.abs().max(1e-300),
                );
                assert_close::<T>(&what("inner dead centre"), inner.into(), &inner_want, PI);
            }
            if turns {
                let want = along(&(&l3 + &l2)) - along(&folded);
                let got: f64 = linkage.stroke().expect("a stroke within range").into();
                assert_close::<T>(&what("stroke"), got, &want, got);
            }
        });
    }
    judged
}

/// Checked to fail on the analyses as they were, on `l3 ± l4`, `l1 − l2` and `l3 − l2` rounded
/// first: a folded limit 3.1e-13 rad off (some 450 units of rounding of π), an inner dead
/// centre 2.6e-10 rad off.
#[test]
fn four_bar_toggles_and_dead_centres_are_the_given_lengths_own() {
    for (judged, dead_centres) in [
        four_bar_line_ups::<f64>(1, 4000, 12.0, 200.0),
        four_bar_line_ups::<f32>(2, 4000, 5.0, 30.0),
    ] {
        // Most draws make a linkage that moves; many stop at a toggle; some are crank-rockers.
        assert!(judged.cases > 2000 && judged.limited > 1000, "{judged:?}");
        assert!(dead_centres > 100, "{dead_centres}");
    }
}

#[test]
fn slider_crank_dead_centres_and_stroke_are_the_given_dimensions_own() {
    for judged in [
        slider_crank_line_ups::<f64>(3, 4000, 12.0, 200.0),
        slider_crank_line_ups::<f32>(4, 4000, 5.0, 30.0),
    ] {
        assert!(judged.cases > 2000 && judged.limited > 500, "{judged:?}");
    }
}
