//! Products in one canonical form: one constant times the other factors in arena order,
//! with the factors fixed by the dimensions grouped (so a kernel computes their product once
//! per mechanism), a factor cancelled against its own reciprocal, and a repeated factor made
//! one square. Equal products then are one node, built and emitted once.

use super::{ExprId, Graph, Node};

impl Graph {
    pub fn mul(&mut self, a: ExprId, b: ExprId) -> ExprId {
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => return self.constant(x * y),
            (Some(0.0), _) | (_, Some(0.0)) => return self.constant(0.0),
            (Some(1.0), _) => return b,
            (_, Some(1.0)) => return a,
            _ => {}
        }
        if let Node::Neg(x) = self.node(a) {
            let product = self.mul(x, b);
            return self.neg(product);
        }
        if let Node::Neg(y) = self.node(b) {
            let product = self.mul(a, y);
            return self.neg(product);
        }
        // The square of a moving product (a crank's `l2·sin θ2`) is that product times itself:
        // one multiplication where the kernel computes the product anyway, and no more than
        // the grouped `l2²·sin²θ2` where it does not.
        if a == b
            && self.group_fixed
            && !self.fixed[a.index()]
            && matches!(self.node(a), Node::Mul(..))
        {
            return self.intern(Node::Mul(a, a));
        }
        // A product is kept as one constant times its other factors sorted by arena order,
        // so `x·(y·z)` and `(z·x)·y` are one node, and a negative constant becomes a negation.
        let mut factors = Vec::new();
        let mut constant = 1.0;
        for side in [a, b] {
            self.collect_factors(side, &mut factors, &mut constant);
        }
        self.cancel_reciprocals(&mut factors, &mut constant);
        if factors.is_empty() {
            return self.constant(constant);
        }
        if self.group_fixed && constant.abs() != 1.0 {
            // The constant is one of the fixed factors; only its sign stays outside.
            factors.push(self.constant(constant.abs()));
            constant = constant.signum();
        }
        factors.sort_unstable();
        let product = if self.group_fixed {
            let (fixed, mut moving): (Vec<ExprId>, Vec<ExprId>) =
                factors.iter().partition(|&&f| self.fixed[f.index()]);
            if let Some(at) = (self.distribute_fixed && !fixed.is_empty())
                .then(|| moving.iter().position(|&m| self.scaled_in_every_term(m)))
                .flatten()
            {
                let sum = moving.remove(at);
                let fixed = self.product(fixed).expect("not empty");
                let distributed = self.distribute(fixed, sum);
                let product = moving
                    .into_iter()
                    .fold(distributed, |product, factor| self.mul(product, factor));
                return if constant < 0.0 {
                    self.neg(product)
                } else {
                    product
                };
            }
            let moving = self.paired(moving);
            let fixed = fixed
                .into_iter()
                .reduce(|product, factor| self.intern(Node::Mul(product, factor)));
            match fixed {
                Some(fixed) if !moving.is_empty() => self.reusing(fixed, moving),
                Some(only) => only,
                None => self.product(moving).unwrap_or_else(|| self.constant(1.0)),
            }
        } else {
            let mut product = factors[0];
            for &factor in &factors[1..] {
                product = self.intern(Node::Mul(product, factor));
            }
            product
        };
        match constant {
            1.0 => product,
            -1.0 => self.neg(product),
            c if c < 0.0 => {
                let magnitude = self.constant(-c);
                let scaled = self.intern(Node::Mul(magnitude, product));
                self.neg(scaled)
            }
            c => {
                let factor = self.constant(c);
                self.intern(Node::Mul(factor, product))
            }
        }
    }

    /// `fixed·(moving factors)`, but where `fixed` times one of the moving factors is a node
    /// already (a crank's `l2·cos θ2`, say), that node times the other factors: a kernel
    /// that computes the pair anyway pays one product less, where the grouped form would
    /// multiply by `fixed` again.
    fn reusing(&mut self, fixed: ExprId, mut moving: Vec<ExprId>) -> ExprId {
        let existing = (moving.len() > 1)
            .then(|| {
                moving
                    .iter()
                    .position(|&factor| self.lookup(Node::Mul(fixed, factor)).is_some())
            })
            .flatten();
        let fixed = match existing {
            Some(at) => {
                let factor = moving.remove(at);
                self.intern(Node::Mul(fixed, factor))
            }
            None => fixed,
        };
        match self.product(moving) {
            Some(moving) => self.intern(Node::Mul(fixed, moving)),
            None => fixed,
        }
    }

    /// Whether `e` is a sum each of whose terms (negated or not) is fixed by the dimensions or
    /// a product with a fixed factor group: `f·(c·x − d·y)` is then `(f·c)·x − (f·d)·y`, whose
    /// fixed products a kernel computes once per mechanism, one product fewer per call (a
    /// coupler point's `a·(cos δ·cos θ3 − sin δ·sin θ3)`). Products that reuse a moving pair
    /// ([`Graph::reusing`]'s `(l2·cos θ2)·x`) do not count: `f` would cost them a product.
    fn scaled_in_every_term(&self, e: ExprId) -> bool {
        let Node::Add(x, y) = self.node(e) else {
            return false;
        };
        let term = |mut t: ExprId| {
            while let Node::Neg(inner) = self.node(t) {
                t = inner;
            }
            match self.node(t) {
                Node::Add(..) => self.scaled_in_every_term(t),
                Node::Mul(first, _) => self.is_fixed(first),
                _ => self.is_fixed(t),
            }
        };
        term(x) && term(y)
    }

    /// `f·e` with `f` multiplied into each term of the sum `e` (see
    /// [`Graph::scaled_in_every_term`]).
    fn distribute(&mut self, f: ExprId, e: ExprId) -> ExprId {
        match self.node(e) {
            Node::Add(x, y) => {
                let x = self.distribute(f, x);
                let y = self.distribute(f, y);
                self.add(x, y)
            }
            Node::Neg(x) => {
                let product = self.distribute(f, x);
                self.neg(product)
            }
            _ => self.mul(f, e),
        }
    }

    /// `constant` times `factors`, built by [`Graph::mul`] (so in products' one form), and
    /// negated where `negated`: a product taken apart by [`Graph::collect_factors`] and put
    /// back together after a change.
    pub(super) fn rebuilt_product(
        &mut self,
        negated: bool,
        constant: f64,
        factors: &[ExprId],
    ) -> ExprId {
        let start = self.constant(constant);
        let product = factors
            .iter()
            .fold(start, |product, &factor| self.mul(product, factor));
        if negated { self.neg(product) } else { product }
    }

    /// `factors` multiplied left to right, if there are any.
    fn product(&mut self, factors: Vec<ExprId>) -> Option<ExprId> {
        factors
            .into_iter()
            .reduce(|product, factor| self.intern(Node::Mul(product, factor)))
    }

    /// The non-constant factors of a product (pushed to `factors`) and the product of its
    /// constant ones (multiplied into `constant`).
    pub(super) fn collect_factors(&self, e: ExprId, factors: &mut Vec<ExprId>, constant: &mut f64) {
        match self.node(e) {
            Node::Const(bits) => *constant *= f64::from_bits(bits),
            Node::Mul(x, y) => {
                self.collect_factors(x, factors, constant);
                self.collect_factors(y, factors, constant);
            }
            _ => factors.push(e),
        }
    }

    /// Cancels each factor of a product against the same factor under a reciprocal among
    /// `factors` (`l3·l3·(1/(l3·l3))` is 1): a kernel that divides by a length's square and
    /// multiplies by it again pays for neither. A zero factor made the product undefined
    /// and now leaves it finite, but every such factor is a length a loop needs (its other
    /// uses still divide by it) or a chord the closed forms check. Nothing changes unless
    /// something cancels.
    fn cancel_reciprocals(&mut self, factors: &mut Vec<ExprId>, constant: &mut f64) {
        let mut k = 0;
        while k < factors.len() {
            let Node::Recip(denominator) = self.node(factors[k]) else {
                k += 1;
                continue;
            };
            let mut under = Vec::new();
            let mut under_constant = 1.0;
            self.collect_factors(denominator, &mut under, &mut under_constant);
            let before = under.len();
            under.retain(
                |&factor| match factors.iter().position(|&other| other == factor) {
                    Some(at) => {
                        factors.swap_remove(at);
                        false
                    }
                    None => true,
                },
            );
            if under.len() == before {
                k += 1;
                continue;
            }
            // The reciprocal moved if a cancelled factor sat before it; find it again.
            let at = factors
                .iter()
                .position(|&f| matches!(self.node(f), Node::Recip(d) if d == denominator))
                .expect("the reciprocal is still among the factors");
            factors.swap_remove(at);
            *constant /= under_constant;
            if let Some(rest) = under
                .into_iter()
                .reduce(|product, factor| self.intern(Node::Mul(product, factor)))
            {
                let inverse = self.recip(rest);
                factors.push(inverse);
            }
            k = 0;
        }
    }

    /// Sorted `factors` with each repeated pair made one square, placed first: `x·ω·ω` is
    /// `ω²·x`, so every product of a rate's square reads the one square.
    fn paired(&mut self, factors: Vec<ExprId>) -> Vec<ExprId> {
        let mut squares = Vec::new();
        let mut single = Vec::new();
        let mut rest = factors.into_iter().peekable();
        while let Some(factor) = rest.next() {
            if rest.peek() == Some(&factor) {
                rest.next();
                squares.push(self.intern(Node::Mul(factor, factor)));
            } else {
                single.push(factor);
            }
        }
        squares.extend(single);
        squares
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::SymbolRef;
    use crate::symbolic::graph::Var;

    fn param(graph: &mut Graph, k: usize) -> ExprId {
        graph.var(Var::Value(SymbolRef::Param(k)))
    }

    fn unknown(graph: &mut Graph, k: usize) -> ExprId {
        graph.var(Var::Value(SymbolRef::Unknown(k)))
    }

    #[test]
    fn a_factor_cancels_against_its_reciprocal() {
        let mut g = Graph::default();
        let (l, x) = (param(&mut g, 0), unknown(&mut g, 0));
        let square = g.mul(l, l);
        let inverse = g.recip(square);
        // l·x·(1/(l·l)) = x·(1/l): one l cancels, the other stays under the reciprocal.
        let lx = g.mul(l, x);
        let product = g.mul(lx, inverse);
        let expected = {
            let inverse_l = g.recip(l);
            g.mul(x, inverse_l)
        };
        assert_eq!(product, expected);
        // l·l·(1/(l·l)) = 1, and 3·x·(1/(2·x)) = 1.5.
        assert_eq!(g.mul(square, inverse), g.constant(1.0));
        let (two, three) = (g.constant(2.0), g.constant(3.0));
        let twice = g.mul(two, x);
        let half_inverse = g.recip(twice);
        let thrice = g.mul(three, x);
        let ratio = g.mul(thrice, half_inverse);
        assert_eq!(g.constant_value(ratio), Some(1.5));
    }

    #[test]
    fn nothing_changes_where_nothing_cancels() {
        let mut g = Graph::default();
        let (l, m, x) = (param(&mut g, 0), param(&mut g, 1), unknown(&mut g, 0));
        let inverse = g.recip(m);
        let product = g.mul(l, inverse);
        let with_x = g.mul(product, x);
        assert!(matches!(g.node(with_x), Node::Mul(..)));
        assert_eq!(g.mul(x, product), with_x);
    }

    #[test]
    fn a_repeated_factor_is_one_square_once_fixed_factors_group() {
        let mut g = Graph::default();
        g.group_fixed_factors();
        let (x, w) = (unknown(&mut g, 0), unknown(&mut g, 1));
        let square = g.mul(w, w);
        let xw = g.mul(x, w);
        let xww = g.mul(xw, w);
        // x·w·w reads the square w·w whole.
        assert_eq!(g.node(xww), Node::Mul(square, x));
    }

    #[test]
    fn the_square_of_a_moving_product_is_that_product_squared() {
        let mut g = Graph::default();
        g.group_fixed_factors();
        let (l, x) = (param(&mut g, 0), unknown(&mut g, 0));
        let sine = g.sin(x);
        let crank = g.mul(l, sine);
        // (l·sin x)² is the crank times itself, not l²·sin²x.
        let square = g.mul(crank, crank);
        assert_eq!(g.node(square), Node::Mul(crank, crank));
        // A fixed product's square is still grouped with the other fixed factors.
        let (m, n) = (param(&mut g, 1), param(&mut g, 2));
        let fixed = g.mul(m, n);
        let squared = g.mul(fixed, fixed);
        assert_ne!(g.node(squared), Node::Mul(fixed, fixed));
    }
}
