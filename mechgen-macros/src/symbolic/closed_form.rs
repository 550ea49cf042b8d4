//! Finds the loops that can be solved in closed form, and in what order.
//!
//! A loop with exactly two unknowns left, once earlier loops have fixed theirs, is one of
//! Chace's cases when each unknown enters it simply: an unknown angle only as `q + known` in
//! a vector's angle (coefficient 1), or only as `known − q` (coefficient −1, in every vector
//! of the loop that turns with it), an unknown length only linearly in magnitudes. With
//! coefficient −1 the loop is one of the cases in `q' = −q` (`e^{−iq} = e^{iq'}`): the case
//! solves for `q'` and its consumers hand back `q = −q'`, whose unit vector is `q'`'s
//! conjugate (see [`Step::flipped`]). Grouping the loop's vectors by the unknown angle they
//! turn with gives complex coefficients (sums of known vectors), and the case follows from
//! which coefficients are structurally non-zero:
//! - two lengths: `K + l1·v1 + l2·v2 = 0`;
//! - a length and an angle, the length turning with the angle: `K + e^{iq}·(l·w1 + w0) = 0`;
//! - a length and an angle, the length fixed in direction: `K + l·v + e^{iq}·w0 = 0`;
//! - two angles: `K + e^{iq1}·w1 + e^{iq2}·w2 = 0`.
//!
//! The runtime's `mechgen::closed` solves each; this pass only finds them and builds the
//! coefficients as expressions.

use syn::ext::IdentExt;

use crate::model::{Kind, Linear, Model, SymbolRef, VectorSum};

use super::graph::{ExprId, Graph};

/// A complex coefficient as `(x, y)` expressions.
pub type Complex = [ExprId; 2];

/// How one loop is solved, with the unknowns (indices into the model's unknowns) each
/// closed form returns, in the order it returns them.
pub enum Case {
    /// `K + l1·v1 + l2·v2 = 0`, solving `[l1, l2]`.
    TwoLengths {
        k: Complex,
        v1: Complex,
        v2: Complex,
    },
    /// `K + e^{iq}·(l·w1 + w0) = 0`, solving `(l, q)`.
    LengthAndOwnAngle {
        k: Complex,
        w0: Complex,
        w1: Complex,
    },
    /// `K + l·v + e^{iq}·w0 = 0`, solving `(l, q)`.
    LengthAndOtherAngle { k: Complex, v: Complex, w0: Complex },
    /// `K + e^{iq1}·w1 + e^{iq2}·w2 = 0`, solving `(q1, q2)`.
    TwoAngles {
        k: Complex,
        w1: Complex,
        w2: Complex,
    },
}

impl Case {
    /// Whether the loop closes in two ways, so a branch must be chosen.
    pub fn has_branches(&self) -> bool {
        !matches!(self, Case::TwoLengths { .. })
    }

    /// The case's complex coefficients, flattened `(x, y)` by `(x, y)` in the order the
    /// runtime's solver takes them.
    pub fn coefficients(&self) -> Vec<ExprId> {
        let vectors = match self {
            Case::TwoLengths { k, v1, v2 } => [k, v1, v2],
            Case::LengthAndOwnAngle { k, w0, w1 } => [k, w0, w1],
            Case::LengthAndOtherAngle { k, v, w0 } => [k, v, w0],
            Case::TwoAngles { k, w1, w2 } => [k, w1, w2],
        };
        vectors.into_iter().flatten().copied().collect()
    }

    /// How the expansion's docs name the case.
    pub fn description(&self) -> &'static str {
        match self {
            Case::TwoLengths { .. } => "two lengths, a linear solve",
            Case::LengthAndOwnAngle { .. } => "the length and angle of one vector",
            Case::LengthAndOtherAngle { .. } => {
                "a length and another vector's angle, a line meeting a circle"
            }
            Case::TwoAngles { .. } => "two angles, two circles meeting",
        }
    }
}

pub struct Step {
    pub loop_index: usize,
    /// The unknowns solved, in the order the case returns them.
    pub unknowns: [usize; 2],
    /// For each of `unknowns`, whether the loop turns with it backwards (coefficient −1), so
    /// that the case solves for its negation `q' = −q`: the value is `−q'`, its unit vector
    /// `(cos q', −sin q')`, and its column of the loop's Jacobian block `−1` times the case's.
    /// The case's branch (its sign) is the branch of the loop as solved for `q'`.
    pub flipped: [bool; 2],
    pub case: Case,
}

impl Step {
    /// The case's unknowns, each with whether it is [flipped](Step::flipped).
    pub fn solved(&self) -> [(usize, bool); 2] {
        [0, 1].map(|k| (self.unknowns[k], self.flipped[k]))
    }

    /// Whether the loop's Jacobian block, in `unknowns`' order, has the opposite sign of
    /// determinant to the case's (one column flipped).
    pub fn flips_determinant(&self) -> bool {
        self.flipped[0] != self.flipped[1]
    }
}

/// Why a declaration has no closed form: the first loop, in declaration order, that never
/// comes down to one of Chace's cases, and the reason.
pub struct Missing {
    pub loop_index: usize,
    /// The vector (term index in the loop) the reason is about, if it is about one.
    pub term: Option<usize>,
    /// Says why, after the loop's name (`loop 2 …`), as a sentence without a final stop.
    pub reason: String,
}

impl Missing {
    /// `loop 2 (`…`) has …`: the loop, as written, and why.
    pub fn sentence(&self, model: &Model) -> String {
        format!(
            "loop {} (`{}`) {}",
            self.loop_index + 1,
            model.loops[self.loop_index].source,
            self.reason
        )
    }
}

/// Orders the loops so each is solved in closed form given the ones before it, or says why
/// some loop never comes down to one of the cases (it needs Newton).
pub fn plan(model: &Model, graph: &mut Graph) -> Result<Vec<Step>, Missing> {
    let mut solved = vec![false; model.unknowns.len()];
    let steps = plan_from(model, graph, &mut solved);
    let Some(stuck) = (0..model.loops.len()).find(|&i| steps.iter().all(|s| s.loop_index != i))
    else {
        return Ok(steps);
    };
    // The same classification as the planner's last, failed, attempt: the graph's nodes are
    // hash-consed, so this adds none and the expansion's names do not move.
    let open = open_unknowns(&model.loops[stuck], &solved);
    let (term, why) = match <[usize; 2]>::try_from(open.as_slice()) {
        Ok([a, b]) => match classify(model, graph, &model.loops[stuck], a, b) {
            Err(Unfit { term, why }) => (term, why),
            Ok(_) => unreachable!("the planner takes every loop that classifies"),
        },
        Err(_) => (None, count_reason(model, &steps, &open)),
    };
    Err(Missing {
        loop_index: stuck,
        term,
        reason: why,
    })
}

/// Why a loop with other than two unknowns left cannot be solved on its own.
fn count_reason(model: &Model, steps: &[Step], open: &[usize]) -> String {
    let names = list(open.iter().map(|&u| name(model, u)));
    let count = match open.len() {
        0 => "no unknown".to_string(),
        1 => format!("one unknown ({names})"),
        3 => format!("three unknowns ({names})"),
        4 => format!("four unknowns ({names})"),
        n => format!("{n} unknowns ({names})"),
    };
    let fit = if open.len() < 2 {
        "fewer than its two equations need"
    } else {
        "more than its two equations fix"
    };
    match steps {
        [] => format!("has {count}, {fit}, and no other loop fixes any of them first"),
        _ => {
            let loops = list(steps.iter().map(|s| (s.loop_index + 1).to_string()));
            let (plural, own) = if steps.len() > 1 {
                ("s", "theirs")
            } else {
                ("", "its own")
            };
            format!("has {count} left after loop{plural} {loops} solved {own}, {fit}")
        }
    }
}

/// `a`, `a and b`, `a, b and c`.
fn list(items: impl Iterator<Item = String>) -> String {
    let items: Vec<String> = items.collect();
    match items.split_last() {
        None => String::new(),
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
    }
}

/// An unknown's name as the docs quote it.
fn name(model: &Model, unknown: usize) -> String {
    format!("`{}`", model.unknowns[unknown].name.unraw())
}

/// Why a loop with two unknowns left is none of Chace's cases: the vector it is about, if
/// one, and a sentence that follows the loop's name.
struct Unfit {
    term: Option<usize>,
    why: String,
}

impl Unfit {
    fn at(term: usize, why: String) -> Self {
        Unfit {
            term: Some(term),
            why,
        }
    }

    fn loop_wide(why: String) -> Self {
        Unfit { term: None, why }
    }
}

/// [`plan`] with the unknowns marked in `solved` already known: the loops that then come
/// down, one after another, to a closed form, in order, as far as they go. `solved` ends
/// with every unknown they solve marked; the loops left out are those that never do.
pub fn plan_from(model: &Model, graph: &mut Graph, solved: &mut [bool]) -> Vec<Step> {
    let mut done = vec![false; model.loops.len()];
    let mut steps = Vec::new();
    while done.iter().any(|d| !d) {
        let Some(next) = (0..model.loops.len()).filter(|&i| !done[i]).find_map(|i| {
            let open = open_unknowns(&model.loops[i], solved);
            let [a, b] = <[usize; 2]>::try_from(open).ok()?;
            classify(model, graph, &model.loops[i], a, b)
                .ok()
                .map(|(unknowns, flipped, case)| Step {
                    loop_index: i,
                    unknowns,
                    flipped,
                    case,
                })
        }) else {
            break;
        };
        done[next.loop_index] = true;
        next.unknowns.iter().for_each(|&u| solved[u] = true);
        steps.push(next);
    }
    steps
}

/// The unknowns a loop still depends on, in declaration order.
pub fn open_unknowns(sum: &VectorSum, solved: &[bool]) -> Vec<usize> {
    let mut open: Vec<usize> = sum
        .terms
        .iter()
        .flat_map(|t| {
            t.magnitude
                .coefficients
                .keys()
                .chain(t.angle.coefficients.keys())
        })
        .filter_map(|s| match s {
            SymbolRef::Unknown(i) if !solved[*i] => Some(*i),
            _ => None,
        })
        .collect();
    open.sort_unstable();
    open.dedup();
    open
}

/// Accumulates `Σ ± coefficient·e^{iφ}` as a complex expression.
struct Accumulator {
    value: Complex,
}

impl Accumulator {
    fn new(graph: &mut Graph) -> Self {
        let zero = graph.constant(0.0);
        Accumulator {
            value: [zero, zero],
        }
    }

    fn add(&mut self, graph: &mut Graph, negated: bool, coefficient: ExprId, angle: ExprId) {
        let unit = [graph.cos(angle), graph.sin(angle)];
        for (component, direction) in self.value.iter_mut().zip(unit) {
            let part = graph.mul(coefficient, direction);
            *component = if negated {
                graph.sub(*component, part)
            } else {
                graph.add(*component, part)
            };
        }
    }

    fn is_zero(&self, graph: &Graph) -> bool {
        self.value.iter().all(|&c| graph.is_zero(c))
    }
}

/// `linear` without `symbol`, and `symbol`'s coefficient in it.
fn split(linear: &Linear, symbol: SymbolRef) -> (Linear, f64) {
    let mut rest = linear.clone();
    let coefficient = rest.coefficients.remove(&symbol).unwrap_or(0.0);
    (rest, coefficient)
}

/// What [`classify`] finds: the unknowns in the order the case returns them, whether each
/// is [flipped](Step::flipped), and the case.
type Classified = ([usize; 2], [bool; 2], Case);

/// The case of a loop whose open unknowns are `a` and `b` (declaration order), or why it is
/// none.
fn classify(
    model: &Model,
    graph: &mut Graph,
    sum: &VectorSum,
    a: usize,
    b: usize,
) -> Result<Classified, Unfit> {
    let kind = |i: usize| model.unknowns[i].kind;
    match (kind(a), kind(b)) {
        (Kind::Length, Kind::Length) => Ok(two_lengths(graph, sum, a, b)),
        (Kind::Angle, Kind::Angle) => two_angles(model, graph, sum, a, b),
        (Kind::Length, Kind::Angle) => length_and_angle(model, graph, sum, a, b),
        (Kind::Angle, Kind::Length) => length_and_angle(model, graph, sum, b, a),
    }
}

fn two_lengths(graph: &mut Graph, sum: &VectorSum, a: usize, b: usize) -> Classified {
    let (ua, ub) = (SymbolRef::Unknown(a), SymbolRef::Unknown(b));
    let (mut k, mut v1, mut v2) = (
        Accumulator::new(graph),
        Accumulator::new(graph),
        Accumulator::new(graph),
    );
    for term in &sum.terms {
        let angle = graph.linear(&term.angle);
        let (rest, alpha) = split(&term.magnitude, ua);
        let (rest, beta) = split(&rest, ub);
        for (accumulator, coefficient) in [(&mut v1, alpha), (&mut v2, beta)] {
            if coefficient != 0.0 {
                let c = graph.constant(coefficient);
                accumulator.add(graph, term.negated, c, angle);
            }
        }
        let known = graph.linear(&rest);
        k.add(graph, term.negated, known, angle);
    }
    let case = Case::TwoLengths {
        k: k.value,
        v1: v1.value,
        v2: v2.value,
    };
    ([a, b], [false, false], case)
}

/// Whether the loop turns with the unknown angle `q` backwards: every vector that turns with
/// it as `−q + known` (then `e^{−iq}` is `e^{iq'}` for `q' = −q`, and the loop is a case in
/// `q'`) rather than `q + known`. Any other coefficient, or both signs in one loop, is none
/// of Chace's cases: `e^{2iq}` makes the loop a quartic in `e^{iq}`, and `e^{iq}` beside
/// `e^{−iq}` no longer puts the vectors that turn with `q` on one circle.
fn flipped(model: &Model, sum: &VectorSum, q: usize) -> Result<bool, Unfit> {
    let symbol = SymbolRef::Unknown(q);
    let mut seen: Option<(usize, f64)> = None;
    for (t, term) in sum.terms.iter().enumerate() {
        let coefficient = term.angle.coefficients.get(&symbol).copied().unwrap_or(0.0);
        if coefficient == 0.0 {
            continue;
        }
        if coefficient != 1.0 && coefficient != -1.0 {
            return Err(Unfit::at(
                t,
                format!(
                    "turns vector {} by {}·{}: Chace's cases need each unknown angle to \
                     enter as `{q} + …` or `… − {q}`",
                    t + 1,
                    number(coefficient),
                    name(model, q),
                    q = model.unknowns[q].name.unraw(),
                ),
            ));
        }
        match seen {
            Some((first, earlier)) if earlier != coefficient => {
                let [forwards, backwards] = if earlier == 1.0 {
                    [first, t]
                } else {
                    [t, first]
                };
                return Err(Unfit::at(
                    t,
                    format!(
                        "turns vector {} with `{q}` and vector {} with `−{q}`: Chace's cases \
                         need the vectors that turn with an unknown angle to turn the same \
                         way, all with `{q}` or all with `−{q}`",
                        forwards + 1,
                        backwards + 1,
                        q = model.unknowns[q].name.unraw(),
                    ),
                ));
            }
            Some(_) => {}
            None => seen = Some((t, coefficient)),
        }
    }
    Ok(seen.is_some_and(|(_, coefficient)| coefficient == -1.0))
}

/// A coefficient as the docs print it: `2`, `0.5`, `−3`.
fn number(value: f64) -> String {
    let text = format!("{value}");
    match text.strip_prefix('-') {
        Some(magnitude) => format!("−{magnitude}"),
        None => text,
    }
}

/// A term's angle as `±q + rest` for the unknown angle `q` ([`flipped`] checked the sign):
/// whether it turns with `q`, and `rest`, the angle `q'`'s vector has at `q' = 0`.
fn turning(term_angle: &Linear, q: usize) -> (bool, Linear) {
    let (rest, coefficient) = split(term_angle, SymbolRef::Unknown(q));
    (coefficient != 0.0, rest)
}

fn two_angles(
    model: &Model,
    graph: &mut Graph,
    sum: &VectorSum,
    a: usize,
    b: usize,
) -> Result<Classified, Unfit> {
    let flips = [flipped(model, sum, a)?, flipped(model, sum, b)?];
    let (mut k, mut w1, mut w2) = (
        Accumulator::new(graph),
        Accumulator::new(graph),
        Accumulator::new(graph),
    );
    for (t, term) in sum.terms.iter().enumerate() {
        let (turns_a, rest) = turning(&term.angle, a);
        let (turns_b, rest) = turning(&rest, b);
        let magnitude = graph.linear(&term.magnitude);
        let offset = graph.linear(&rest);
        let accumulator = match (turns_a, turns_b) {
            (false, false) => &mut k,
            (true, false) => &mut w1,
            (false, true) => &mut w2,
            (true, true) => {
                return Err(Unfit::at(
                    t,
                    format!(
                        "turns vector {} with both {} and {}: Chace's cases need each \
                         vector to turn with one unknown angle at most",
                        t + 1,
                        name(model, a),
                        name(model, b)
                    ),
                ));
            }
        };
        accumulator.add(graph, term.negated, magnitude, offset);
    }
    for (w, q) in [(&w1, a), (&w2, b)] {
        if w.is_zero(graph) {
            return Err(Unfit::loop_wide(format!(
                "has the vectors that turn with {} cancel out, so the loop cannot fix it",
                name(model, q)
            )));
        }
    }
    let case = Case::TwoAngles {
        k: k.value,
        w1: w1.value,
        w2: w2.value,
    };
    Ok(([a, b], flips, case))
}

fn length_and_angle(
    model: &Model,
    graph: &mut Graph,
    sum: &VectorSum,
    length: usize,
    angle: usize,
) -> Result<Classified, Unfit> {
    let flip = flipped(model, sum, angle)?;
    let l = SymbolRef::Unknown(length);
    let mut k = Accumulator::new(graph);
    let mut v = Accumulator::new(graph);
    let mut w0 = Accumulator::new(graph);
    let mut w1 = Accumulator::new(graph);
    for term in &sum.terms {
        let (turns, offset) = turning(&term.angle, angle);
        let (rest, alpha) = split(&term.magnitude, l);
        let offset = graph.linear(&offset);
        let known = graph.linear(&rest);
        let (fixed, with_length) = if turns {
            (&mut w0, &mut w1)
        } else {
            (&mut k, &mut v)
        };
        fixed.add(graph, term.negated, known, offset);
        if alpha != 0.0 {
            let c = graph.constant(alpha);
            with_length.add(graph, term.negated, c, offset);
        }
    }
    let (l_name, q_name) = (name(model, length), name(model, angle));
    let case = match (v.is_zero(graph), w1.is_zero(graph)) {
        (true, false) => Case::LengthAndOwnAngle {
            k: k.value,
            w0: w0.value,
            w1: w1.value,
        },
        (false, true) if !w0.is_zero(graph) => Case::LengthAndOtherAngle {
            k: k.value,
            v: v.value,
            w0: w0.value,
        },
        (false, true) => {
            return Err(Unfit::loop_wide(format!(
                "has no vector of known length turning with {q_name}, so {q_name} does not \
                 change the loop's sum"
            )));
        }
        (false, false) => {
            return Err(Unfit::loop_wide(format!(
                "has {l_name} scale both vectors that turn with {q_name} and vectors that do \
                 not: Chace's cases need a length to slide along one direction, fixed or \
                 turning"
            )));
        }
        (true, true) => {
            return Err(Unfit::loop_wide(format!(
                "has the vectors {l_name} scales cancel out, so the loop cannot fix it"
            )));
        }
    };
    Ok(([length, angle], [false, flip], case))
}
