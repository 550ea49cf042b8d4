//! Like terms of a sum gathered where one of them sits inside a sum that another term
//! scales: the product rule makes an acceleration's Coriolis term twice, once inside
//! `ω·(…)` and once on its own, and a kernel should compute it once and double it.

use super::{ExprId, Graph, Node};

/// A term of a sum: its constant and its other factors, sorted (as products keep them).
#[derive(Debug)]
struct Term {
    coefficient: f64,
    factors: Vec<ExprId>,
}

impl Graph {
    /// `root` with every term of its sum that repeats, times the other factors of a product,
    /// a term of the one sum that product scales, folded into that sum:
    /// `v·(a·v + b·w) + b·v·w` is `v·(a·v + 2·b·w)`, two products fewer. `root` itself
    /// where no term folds.
    pub fn gather_like_terms(&mut self, root: ExprId) -> ExprId {
        // Under a negation, gathered there: the sum keeps its terms' signs.
        if let Node::Neg(inner) = self.node(root) {
            let gathered = self.gather_like_terms(inner);
            return self.neg(gathered);
        }
        let mut terms = Vec::new();
        self.terms_of(root, 1.0, &mut terms);
        let mut gathered = false;
        for p in 0..terms.len() {
            if terms[p].coefficient == 0.0 {
                continue;
            }
            let sums: Vec<usize> = (0..terms[p].factors.len())
                .filter(|&k| matches!(self.node(terms[p].factors[k]), Node::Add(..)))
                .collect();
            let &[at] = sums.as_slice() else {
                continue;
            };
            let mut others = terms[p].factors.clone();
            let sum = others.remove(at);
            let mut inner = Vec::new();
            self.terms_of(sum, 1.0, &mut inner);
            let mut folded = false;
            for q in 0..terms.len() {
                // Only where the constants divide exactly: the sum is then the same number
                // to rounding, not a coefficient rounded anew.
                let ratio = terms[q].coefficient / terms[p].coefficient;
                if q == p || ratio == 0.0 || ratio * terms[p].coefficient != terms[q].coefficient {
                    continue;
                }
                let within = inner.iter_mut().find(|term| {
                    let mut factors: Vec<ExprId> =
                        others.iter().chain(&term.factors).copied().collect();
                    factors.sort_unstable();
                    factors == terms[q].factors
                });
                if let Some(term) = within {
                    // c_q·F = c_p·(c_q/c_p)·F.
                    term.coefficient += ratio;
                    terms[q].coefficient = 0.0;
                    folded = true;
                }
            }
            if folded {
                let sum = self.sum_of(&inner);
                others.push(sum);
                others.sort_unstable();
                terms[p].factors = others;
                gathered = true;
            }
        }
        if gathered { self.sum_of(&terms) } else { root }
    }

    /// The terms of `e` as a sum (through additions and negations), each times `sign`.
    fn terms_of(&self, e: ExprId, sign: f64, terms: &mut Vec<Term>) {
        match self.node(e) {
            Node::Add(a, b) => {
                self.terms_of(a, sign, terms);
                self.terms_of(b, sign, terms);
            }
            Node::Neg(a) => self.terms_of(a, -sign, terms),
            _ => {
                let mut factors = Vec::new();
                let mut coefficient = sign;
                self.collect_factors(e, &mut factors, &mut coefficient);
                factors.sort_unstable();
                terms.push(Term {
                    coefficient,
                    factors,
                });
            }
        }
    }

    /// The sum of `terms`, in their order, leaving out those that cancelled.
    fn sum_of(&mut self, terms: &[Term]) -> ExprId {
        let mut sum = self.constant(0.0);
        for term in terms.iter().filter(|term| term.coefficient != 0.0) {
            let signed = self.rebuilt_product(
                term.coefficient < 0.0,
                term.coefficient.abs(),
                &term.factors,
            );
            sum = self.add(sum, signed);
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use crate::model::SymbolRef;
    use crate::symbolic::graph::{Graph, Var};

    #[test]
    fn a_term_repeated_inside_a_scaled_sum_is_doubled_there() {
        let mut g = Graph::default();
        let [v, w, a, b] = [0, 1, 2, 3].map(|k| g.var(Var::Value(SymbolRef::Unknown(k))));
        // v·(a·v + b·w) + b·v·w
        let (av, bw) = (g.mul(a, v), g.mul(b, w));
        let inner = g.add(av, bw);
        let scaled = g.mul(v, inner);
        let bv = g.mul(b, v);
        let bvw = g.mul(bv, w);
        let sum = g.add(scaled, bvw);
        let gathered = g.gather_like_terms(sum);
        // v·(a·v + 2·b·w)
        let two = g.constant(2.0);
        let twice = g.mul(two, bw);
        let inner = g.add(av, twice);
        assert_eq!(gathered, g.mul(v, inner));
        // With the opposite sign the two cancel: v·(a·v).
        let minus = g.neg(bvw);
        let sum = g.add(scaled, minus);
        let gathered = g.gather_like_terms(sum);
        let av_v = g.mul(v, av);
        assert_eq!(gathered, av_v);
        // Nothing to gather: the expression itself.
        let other = g.mul(a, w);
        let sum = g.add(scaled, other);
        assert_eq!(g.gather_like_terms(sum), sum);
    }
}
