//! Angle sums taken apart, for kernels that never form a solved angle.
//!
//! A closed form yields each solved angle `θ` as its unit vector `(cos θ, sin θ)`; the angle
//! itself costs an `atan2`. An expression such as `sin(θ3 + δ)` would need it, but written
//! as `sin θ3·cos δ + cos θ3·sin δ` it needs only the unit vector and the sine and cosine of
//! the fixed part, which depend on the dimensions alone and can be computed once per
//! mechanism. This pass rewrites expressions that way: every moving name (the input or an
//! unknown) with coefficient ±1 in an angle becomes a factor `e^{±iθ}` of its own; whatever
//! is left (constants, parameters, moving names with other coefficients) stays one angle.

use crate::model::SymbolRef;

use super::graph::{ExprId, Graph, Node, Var};
use super::rewrite::Rewriter;

/// `roots`, rewritten with every sine and cosine of a sum taken apart.
///
/// A fixed factor of such a product goes into the expansion's terms: `a·cos(θ3 + δ)` is
/// `(a·cos δ)·cos θ3 − (a·sin δ)·sin θ3`, whose fixed products are computed once per
/// mechanism (see [`Graph::distributing`]).
pub fn expand(graph: &mut Graph, roots: &[ExprId]) -> Vec<ExprId> {
    graph.distributing(|graph| {
        Rewriter::new(|graph, id| match graph.node(id) {
            Node::Cos(angle) => Some(unit(graph, angle)[0]),
            Node::Sin(angle) => Some(unit(graph, angle)[1]),
            _ => None,
        })
        .all(graph, roots)
    })
}

/// `(cos, sin)` of `angle` as a product of one unit vector per moving name and one for the
/// rest of the sum.
fn unit(graph: &mut Graph, angle: ExprId) -> [ExprId; 2] {
    let mut terms = Vec::new();
    collect_terms(graph, angle, false, &mut terms);
    let mut rest = graph.constant(0.0);
    let mut turns = Vec::new();
    for (term, negated) in terms {
        match graph.node(term) {
            Node::Var(var @ Var::Value(SymbolRef::Input(_) | SymbolRef::Unknown(_))) => {
                turns.push((var, negated))
            }
            _ if negated => rest = graph.sub(rest, term),
            _ => rest = graph.add(rest, term),
        }
    }
    if turns.is_empty() {
        return [graph.cos(angle), graph.sin(angle)];
    }
    let mut unit = [graph.cos(rest), graph.sin(rest)];
    for (var, negated) in turns {
        let var = graph.var(var);
        let (cos, sin) = (graph.cos(var), graph.sin(var));
        let sin = if negated { graph.neg(sin) } else { sin };
        // (a + ib)(c + id) = (ac − bd) + i(ad + bc)
        let [a, b] = unit;
        let (ac, bd) = (graph.mul(a, cos), graph.mul(b, sin));
        let (ad, bc) = (graph.mul(a, sin), graph.mul(b, cos));
        unit = [graph.sub(ac, bd), graph.add(ad, bc)];
    }
    unit
}

/// The terms of a sum, each with whether it is subtracted.
fn collect_terms(graph: &Graph, id: ExprId, negated: bool, terms: &mut Vec<(ExprId, bool)>) {
    match graph.node(id) {
        Node::Add(a, b) => {
            collect_terms(graph, a, negated, terms);
            collect_terms(graph, b, negated, terms);
        }
        Node::Neg(a) => collect_terms(graph, a, !negated, terms),
        _ => terms.push((id, negated)),
    }
}
