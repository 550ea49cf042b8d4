//! Finds the loops that can be solved in closed form, and in what order.
//!
//! A loop with exactly two unknowns left, once earlier loops have fixed theirs, is one of
//! Chace's cases when each unknown enters it simply: an unknown angle only as `q + known` in
//! a vector's angle (coefficient 1), an unknown length only linearly in magnitudes. Grouping
//! the loop's vectors by the unknown angle they turn with gives complex coefficients (sums of
//! known vectors), and the case follows from which coefficients are structurally non-zero:
//! - two lengths: `K + l1·v1 + l2·v2 = 0`;
//! - a length and an angle, the length turning with the angle: `K + e^{iq}·(l·w1 + w0) = 0`;
//! - a length and an angle, the length fixed in direction: `K + l·v + e^{iq}·w0 = 0`;
//! - two angles: `K + e^{iq1}·w1 + e^{iq2}·w2 = 0`.
//!
//! The runtime's `mechgen::closed` solves each; this pass only finds them and builds the
//! coefficients as expressions.

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
    pub case: Case,
}

/// Orders the loops so each is solved in closed form given the ones before it. `None` if some
/// loop never comes down to one of the cases (it needs Newton).
pub fn plan(model: &Model, graph: &mut Graph) -> Option<Vec<Step>> {
    let mut solved = vec![false; model.unknowns.len()];
    let steps = plan_from(model, graph, &mut solved);
    (steps.len() == model.loops.len()).then_some(steps)
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
            classify(model, graph, &model.loops[i], a, b).map(|(unknowns, case)| Step {
                loop_index: i,
                unknowns,
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
fn open_unknowns(sum: &VectorSum, solved: &[bool]) -> Vec<usize> {
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

/// The case of a loop whose open unknowns are `a` and `b` (declaration order), if it is one.
fn classify(
    model: &Model,
    graph: &mut Graph,
    sum: &VectorSum,
    a: usize,
    b: usize,
) -> Option<([usize; 2], Case)> {
    let kind = |i: usize| model.unknowns[i].kind;
    match (kind(a), kind(b)) {
        (Kind::Length, Kind::Length) => two_lengths(graph, sum, a, b),
        (Kind::Angle, Kind::Angle) => two_angles(graph, sum, a, b),
        (Kind::Length, Kind::Angle) => length_and_angle(graph, sum, a, b),
        (Kind::Angle, Kind::Length) => length_and_angle(graph, sum, b, a),
    }
}

fn two_lengths(
    graph: &mut Graph,
    sum: &VectorSum,
    a: usize,
    b: usize,
) -> Option<([usize; 2], Case)> {
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
    Some(([a, b], case))
}

/// A term's angle as `coefficient·q + rest`, for the unknown angle `q`.
fn turning(term_angle: &Linear, q: usize) -> Option<(bool, Linear)> {
    let (rest, coefficient) = split(term_angle, SymbolRef::Unknown(q));
    match coefficient {
        0.0 => Some((false, rest)),
        1.0 => Some((true, rest)),
        // e^{-iq} or e^{2iq}: not one of Chace's cases.
        _ => None,
    }
}

fn two_angles(
    graph: &mut Graph,
    sum: &VectorSum,
    a: usize,
    b: usize,
) -> Option<([usize; 2], Case)> {
    let (mut k, mut w1, mut w2) = (
        Accumulator::new(graph),
        Accumulator::new(graph),
        Accumulator::new(graph),
    );
    for term in &sum.terms {
        let (turns_a, rest) = turning(&term.angle, a)?;
        let (turns_b, rest) = turning(&rest, b)?;
        let magnitude = graph.linear(&term.magnitude);
        let offset = graph.linear(&rest);
        let accumulator = match (turns_a, turns_b) {
            (false, false) => &mut k,
            (true, false) => &mut w1,
            (false, true) => &mut w2,
            (true, true) => return None,
        };
        accumulator.add(graph, term.negated, magnitude, offset);
    }
    if w1.is_zero(graph) || w2.is_zero(graph) {
        return None;
    }
    let case = Case::TwoAngles {
        k: k.value,
        w1: w1.value,
        w2: w2.value,
    };
    Some(([a, b], case))
}

fn length_and_angle(
    graph: &mut Graph,
    sum: &VectorSum,
    length: usize,
    angle: usize,
) -> Option<([usize; 2], Case)> {
    let l = SymbolRef::Unknown(length);
    let mut k = Accumulator::new(graph);
    let mut v = Accumulator::new(graph);
    let mut w0 = Accumulator::new(graph);
    let mut w1 = Accumulator::new(graph);
    for term in &sum.terms {
        let (turns, offset) = turning(&term.angle, angle)?;
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
        _ => return None,
    };
    Some(([length, angle], case))
}
