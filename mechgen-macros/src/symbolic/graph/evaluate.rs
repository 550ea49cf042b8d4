//! Every node's value at a point: for checks the macro makes on the expressions themselves,
//! such as whether a Jacobian is singular whatever the dimensions.

use super::{Graph, Node, Var};

impl Graph {
    /// The value of every node, in arena order, with each variable's value from `var`. The
    /// arena is in topological order, so one pass computes them all.
    pub fn evaluate_all(&self, var: impl Fn(Var) -> f64) -> Vec<f64> {
        let mut values: Vec<f64> = Vec::with_capacity(self.nodes.len());
        for &node in &self.nodes {
            let value = match node {
                Node::Const(bits) => f64::from_bits(bits),
                Node::Var(v) => var(v),
                Node::Add(a, b) => values[a.index()] + values[b.index()],
                Node::Mul(a, b) => values[a.index()] * values[b.index()],
                Node::Neg(a) => -values[a.index()],
                Node::Sin(a) => values[a.index()].sin(),
                Node::Cos(a) => values[a.index()].cos(),
                Node::Recip(a) => values[a.index()].recip(),
                Node::Sqrt(a) => values[a.index()].sqrt(),
                Node::Atan2(y, x) => values[y.index()].atan2(values[x.index()]),
            };
            values.push(value);
        }
        values
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::SymbolRef;

    #[test]
    fn a_polar_component_evaluates_to_its_value() {
        let mut g = Graph::default();
        let r = g.var(Var::Value(SymbolRef::Param(0)));
        let theta = g.var(Var::Value(SymbolRef::Unknown(0)));
        let cosine = g.cos(theta);
        let x = g.mul(r, cosine);
        let values = g.evaluate_all(|v| match v {
            Var::Value(SymbolRef::Param(0)) => 2.0,
            _ => 0.5,
        });
        assert_eq!(values[x.index()], 2.0 * 0.5f64.cos());
    }
}
