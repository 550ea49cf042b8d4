//! A hash-consed expression graph with folding constructors and memoised derivatives.
//!
//! Nodes live in one arena and are deduplicated through a map, so an expression built twice
//! is one node and is emitted once. Children always precede their parents in the arena, so
//! arena order is a topological order. There is no general `simplify`: the constructors do
//! the cheap, always-right rewrites (constant folding, `x+0`, `x·1`, `x·0`, `-(-x)`,
//! negation pulled out of products) and nothing else, which keeps construction linear.

use std::collections::HashMap;

use crate::formula::{Formula, Function};
use crate::model::{Linear, SymbolRef};

mod evaluate;
mod like_terms;
mod products;

/// A variable of the generated code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Var {
    /// A parameter, the input or an unknown.
    Value(SymbolRef),
    /// First time derivative of the input or an unknown.
    Rate(SymbolRef),
    /// Second time derivative of the input or an unknown.
    Accel(SymbolRef),
    /// `1/scale` of a straight-line kernel, which computes with every length times `scale`:
    /// its outputs in lengths are multiplied by this. It depends on the dimensions alone.
    Unscale,
    /// A value a straight-line kernel gets from a checked runtime helper (a square root that
    /// may say "cannot assemble", a reciprocal that may say "singular"): see
    /// [`super::straight`].
    Aux(u32),
}

impl Var {
    /// The variable's time derivative; `None` for a constant parameter (derivative zero) and
    /// for an acceleration (the graph never needs a third derivative).
    pub fn time_derivative(self) -> Option<Var> {
        match self {
            Var::Value(SymbolRef::Param(_)) => None,
            Var::Value(symbol) => Some(Var::Rate(symbol)),
            Var::Rate(symbol) => Some(Var::Accel(symbol)),
            Var::Accel(_) | Var::Aux(_) | Var::Unscale => None,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ExprId(u32);

impl ExprId {
    pub fn index(self) -> usize {
        self.0 as usize
    }

    /// The id of the node at `index` in the arena.
    pub fn from_index(index: usize) -> Self {
        ExprId(u32::try_from(index).expect("expression graph overflow"))
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant, stored as its bits so nodes can be hashed; never `-0.0` or NaN.
    Const(u64),
    Var(Var),
    Add(ExprId, ExprId),
    Mul(ExprId, ExprId),
    Neg(ExprId),
    Sin(ExprId),
    Cos(ExprId),
    /// `1/x`: only straight-line kernels build it, for reciprocals that are hoisted or
    /// shared.
    Recip(ExprId),
    /// `√x` of a non-negative `x`: straight-line kernels, and a declaration's formulas
    /// of its parameters (`sqrt(l1 * l1 + l2 * l2)`), build it.
    Sqrt(ExprId),
    /// `atan2(y, x)`, as `Atan2(y, x)`: only a declaration's formulas of its parameters
    /// (`atan2(b, a)`) build it, so it is always fixed.
    Atan2(ExprId, ExprId),
}

#[derive(Default)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, ExprId>,
    partials: HashMap<(ExprId, Var), ExprId>,
    /// Whether each node depends on the dimensions alone (parameters and numbers).
    fixed: Vec<bool>,
    /// While set, products keep their fixed factors together (see [`Graph::mul`]).
    group_fixed: bool,
    /// While set (and `group_fixed`), a product multiplies its fixed factors into a sum
    /// whose every term has fixed factors of its own (see [`Graph::distributing`]).
    distribute_fixed: bool,
}

/// Values within this of 0 or ±1 after folding `sin`/`cos` of a constant are snapped, so that
/// `cos(π/2)` is exactly 0 and a fixed vertical vector has no spurious x component.
const TRIG_SNAP: f64 = 1e-15;

impl Graph {
    pub fn node(&self, id: ExprId) -> Node {
        self.nodes[id.index()]
    }

    /// The node's id, if the graph holds it.
    pub fn lookup(&self, node: Node) -> Option<ExprId> {
        self.index.get(&node).copied()
    }

    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn constant_value(&self, id: ExprId) -> Option<f64> {
        match self.node(id) {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    pub fn is_zero(&self, id: ExprId) -> bool {
        self.constant_value(id) == Some(0.0)
    }

    fn intern(&mut self, node: Node) -> ExprId {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = ExprId::from_index(self.nodes.len());
        let fixed = match node {
            Node::Const(_) | Node::Var(Var::Value(SymbolRef::Param(_)) | Var::Unscale) => true,
            Node::Var(_) => false,
            Node::Neg(a) | Node::Sin(a) | Node::Cos(a) | Node::Recip(a) | Node::Sqrt(a) => {
                self.fixed[a.index()]
            }
            Node::Add(a, b) | Node::Mul(a, b) | Node::Atan2(a, b) => {
                self.fixed[a.index()] && self.fixed[b.index()]
            }
        };
        self.nodes.push(node);
        self.fixed.push(fixed);
        self.index.insert(node, id);
        id
    }

    /// Whether `id` depends on the dimensions alone.
    pub fn is_fixed(&self, id: ExprId) -> bool {
        self.fixed[id.index()]
    }

    /// From now on, build products as (fixed factors)·(the others), so that what depends on
    /// the dimensions alone is one subexpression that a kernel can compute once per
    /// mechanism. Expressions built before keep their form.
    pub fn group_fixed_factors(&mut self) {
        self.group_fixed = true;
    }

    /// `build` run with products multiplying their fixed factors into the sums they scale,
    /// where every term of the sum has fixed factors too: `a·(cos δ·cos θ − sin δ·sin θ)`
    /// becomes `(a·cos δ)·cos θ − (a·sin δ)·sin θ`, one product fewer once the fixed
    /// products are computed per mechanism. Only for the sums an angle's expansion makes,
    /// which nothing else reads: a sum that other expressions read whole would be computed
    /// twice.
    pub fn distributing<R>(&mut self, build: impl FnOnce(&mut Self) -> R) -> R {
        let before = std::mem::replace(&mut self.distribute_fixed, true);
        let result = build(self);
        self.distribute_fixed = before;
        result
    }

    pub fn constant(&mut self, value: f64) -> ExprId {
        // Folding never produces NaN from finite declarations; +0.0 stands for both zeros.
        let value = if value == 0.0 { 0.0 } else { value };
        self.intern(Node::Const(value.to_bits()))
    }

    pub fn var(&mut self, var: Var) -> ExprId {
        self.intern(Node::Var(var))
    }

    /// `Σ c·symbol + constant`: a declared angle or magnitude, as the equations and the
    /// closed forms both build it.
    pub fn linear(&mut self, linear: &Linear) -> ExprId {
        let mut sum = self.constant(0.0);
        for (&symbol, &coefficient) in &linear.coefficients {
            let var = self.var(Var::Value(symbol));
            let factor = self.constant(coefficient);
            let term = self.mul(factor, var);
            sum = self.add(sum, term);
        }
        for (coefficient, formula) in &linear.formulas {
            let value = self.formula(formula);
            let factor = self.constant(*coefficient);
            let term = self.mul(factor, value);
            sum = self.add(sum, term);
        }
        let constant = self.constant(linear.constant);
        self.add(sum, constant)
    }

    /// A formula of the parameters (see [`crate::formula`]), built of the graph's own
    /// nodes, so that it is fixed, hoisted and differentiated (by the parameters, for the
    /// sensitivities) as any other expression of the dimensions: `tan` as `sin · 1/cos`,
    /// `hypot(a, b)` as `√(a² + b²)` (its arguments lengths of a mechanism the solvers keep
    /// near unit size, or within the range where such squares are normal).
    pub fn formula(&mut self, formula: &Formula) -> ExprId {
        match formula {
            Formula::Param(i) => self.var(Var::Value(SymbolRef::Param(*i))),
            Formula::Number(value) => self.constant(*value),
            Formula::Neg(inner) => {
                let inner = self.formula(inner);
                self.neg(inner)
            }
            Formula::Add(a, b) | Formula::Sub(a, b) | Formula::Mul(a, b) | Formula::Div(a, b) => {
                let (x, y) = (self.formula(a), self.formula(b));
                match formula {
                    Formula::Add(..) => self.add(x, y),
                    Formula::Sub(..) => self.sub(x, y),
                    Formula::Mul(..) => self.mul(x, y),
                    _ => {
                        let inverse = self.recip(y);
                        self.mul(x, inverse)
                    }
                }
            }
            Formula::Call(function, arguments) => {
                let arguments: Vec<ExprId> = arguments.iter().map(|a| self.formula(a)).collect();
                match (function, arguments.as_slice()) {
                    (Function::Sqrt, &[x]) => self.sqrt(x),
                    (Function::Sin, &[x]) => self.sin(x),
                    (Function::Cos, &[x]) => self.cos(x),
                    (Function::Tan, &[x]) => {
                        let (sine, cosine) = (self.sin(x), self.cos(x));
                        let inverse = self.recip(cosine);
                        self.mul(sine, inverse)
                    }
                    (Function::Atan2, &[y, x]) => self.atan2(y, x),
                    (Function::Hypot, &[x, y]) => {
                        let (xx, yy) = (self.mul(x, x), self.mul(y, y));
                        let squared = self.add(xx, yy);
                        self.sqrt(squared)
                    }
                    _ => unreachable!("the model builds each function with its arguments"),
                }
            }
        }
    }

    pub fn neg(&mut self, a: ExprId) -> ExprId {
        match self.node(a) {
            Node::Const(_) => {
                let value = self.constant_value(a).unwrap_or_default();
                self.constant(-value)
            }
            Node::Neg(inner) => inner,
            _ => self.intern(Node::Neg(a)),
        }
    }

    pub fn add(&mut self, a: ExprId, b: ExprId) -> ExprId {
        match (self.node(a), self.node(b)) {
            (Node::Const(_), Node::Const(_)) => {
                let sum = self.constant_value(a).unwrap_or_default()
                    + self.constant_value(b).unwrap_or_default();
                self.constant(sum)
            }
            _ if self.is_zero(a) => b,
            _ if self.is_zero(b) => a,
            // cos²x + sin²x = 1: a unit vector's squared length (a slide's direction at a
            // fixed angle to its link) is exactly 1, not its rounded sum.
            _ if self.pythagorean(a, b) => self.constant(1.0),
            (Node::Neg(x), _) if x == b => self.constant(0.0),
            (_, Node::Neg(y)) if y == a => self.constant(0.0),
            // x − (y + x) = −y, and (y + x) − x = y: a length found as one part plus another
            // and then taken apart again.
            (_, Node::Neg(sum)) if self.sum_without(sum, a).is_some() => {
                let rest = self.sum_without(sum, a).expect("just matched");
                self.neg(rest)
            }
            (Node::Neg(sum), _) if self.sum_without(sum, b).is_some() => {
                let rest = self.sum_without(sum, b).expect("just matched");
                self.neg(rest)
            }
            (Node::Add(..), Node::Neg(y)) if self.sum_without(a, y).is_some() => {
                self.sum_without(a, y).expect("just matched")
            }
            (Node::Neg(x), Node::Add(..)) if self.sum_without(b, x).is_some() => {
                self.sum_without(b, x).expect("just matched")
            }
            _ if a == b => {
                let two = self.constant(2.0);
                self.mul(two, a)
            }
            // -x + -y = -(x + y): one negation instead of two.
            (Node::Neg(x), Node::Neg(y)) => {
                let sum = self.add(x, y);
                self.neg(sum)
            }
            _ if self.common_input_rate(a, b).is_some() => {
                let (rate, x, y) = self.common_input_rate(a, b).expect("just matched");
                let sum = self.add(x, y);
                self.mul(rate, sum)
            }
            _ if self.common_fixed_factor(a, b).is_some() => {
                let (factor, x, y) = self.common_fixed_factor(a, b).expect("just matched");
                let sum = self.add(x, y);
                self.mul(factor, sum)
            }
            _ => self.intern(Node::Add(a, b)),
        }
    }

    /// Whether `a + b` is `cos²x + sin²x` (in either order) for one `x`.
    fn pythagorean(&self, a: ExprId, b: ExprId) -> bool {
        let square_of = |e: ExprId| match self.node(e) {
            Node::Mul(p, q) if p == q => Some(self.node(p)),
            _ => None,
        };
        match (square_of(a), square_of(b)) {
            (Some(Node::Cos(x)), Some(Node::Sin(y))) | (Some(Node::Sin(y)), Some(Node::Cos(x))) => {
                x == y
            }
            _ => false,
        }
    }

    /// `y` where `sum` is `x + y` or `y + x`.
    fn sum_without(&self, sum: ExprId, x: ExprId) -> Option<ExprId> {
        match self.node(sum) {
            Node::Add(p, q) if p == x => Some(q),
            Node::Add(p, q) if q == x => Some(p),
            _ => None,
        }
    }

    /// `(true, x)` for `−x`, else `(false, e)`.
    fn unnegated(&self, e: ExprId) -> (bool, ExprId) {
        match self.node(e) {
            Node::Neg(inner) => (true, inner),
            _ => (false, e),
        }
    }

    /// `(f, x, y)` where `a = f·x` and `b = f·y` (either possibly negated, the sign carried
    /// into `x` or `y`) for one factor `f` fixed by the dimensions, once products group
    /// their fixed factors: `f·x + f·y` is then built as `f·(x + y)`, one product fewer.
    fn common_fixed_factor(&mut self, a: ExprId, b: ExprId) -> Option<(ExprId, ExprId, ExprId)> {
        if !self.group_fixed {
            return None;
        }
        let split = |graph: &Self, e: ExprId| {
            let (negated, inner) = graph.unnegated(e);
            match graph.node(inner) {
                Node::Mul(fixed, moving) if graph.is_fixed(fixed) && !graph.is_fixed(moving) => {
                    Some((negated, fixed, moving))
                }
                _ => None,
            }
        };
        let (negate_x, fixed, x) = split(self, a)?;
        let (negate_y, other, y) = split(self, b)?;
        if fixed != other {
            return None;
        }
        let x = if negate_x { self.neg(x) } else { x };
        let y = if negate_y { self.neg(y) } else { y };
        Some((fixed, x, y))
    }

    /// `(v, x, y)` where `a = v·x` and `b = v·y` (either possibly negated, the sign carried
    /// into `x` or `y`) for an input's rate or acceleration `v`, once products group their
    /// fixed factors: `v·x + v·y` is then built as `v·(x + y)`, one product fewer (a rate
    /// solve's `ω2` in every term of its right-hand side).
    fn common_input_rate(&mut self, a: ExprId, b: ExprId) -> Option<(ExprId, ExprId, ExprId)> {
        if !self.group_fixed {
            return None;
        }
        let split = |graph: &Self, e: ExprId| {
            let (negated, inner) = graph.unnegated(e);
            let mut factors = Vec::new();
            let mut constant = 1.0;
            graph.collect_factors(inner, &mut factors, &mut constant);
            (negated, factors, constant)
        };
        let (negate_x, mut x, constant_x) = split(self, a);
        let (negate_y, mut y, constant_y) = split(self, b);
        if x.len() + usize::from(constant_x != 1.0) < 2
            || y.len() + usize::from(constant_y != 1.0) < 2
        {
            return None;
        }
        let rate = x.iter().copied().find(|&f| {
            matches!(
                self.node(f),
                Node::Var(Var::Rate(SymbolRef::Input(_)) | Var::Accel(SymbolRef::Input(_)))
            ) && y.contains(&f)
        })?;
        for factors in [&mut x, &mut y] {
            let at = factors
                .iter()
                .position(|&f| f == rate)
                .expect("found in both");
            factors.remove(at);
        }
        let x = self.rebuilt_product(negate_x, constant_x, &x);
        let y = self.rebuilt_product(negate_y, constant_y, &y);
        Some((rate, x, y))
    }

    pub fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let negated = self.neg(b);
        self.add(a, negated)
    }

    pub fn sin(&mut self, a: ExprId) -> ExprId {
        match self.node(a) {
            Node::Const(_) => {
                let value = snap(self.constant_value(a).unwrap_or_default().sin());
                self.constant(value)
            }
            Node::Neg(x) => {
                let sine = self.sin(x);
                self.neg(sine)
            }
            _ => self.intern(Node::Sin(a)),
        }
    }

    pub fn cos(&mut self, a: ExprId) -> ExprId {
        match self.node(a) {
            Node::Const(_) => {
                let value = snap(self.constant_value(a).unwrap_or_default().cos());
                self.constant(value)
            }
            Node::Neg(x) => self.cos(x),
            _ => self.intern(Node::Cos(a)),
        }
    }

    pub fn recip(&mut self, a: ExprId) -> ExprId {
        match self.node(a) {
            Node::Const(bits) if f64::from_bits(bits) != 0.0 => {
                self.constant(1.0 / f64::from_bits(bits))
            }
            Node::Neg(x) => {
                let inverse = self.recip(x);
                self.neg(inverse)
            }
            _ => self.intern(Node::Recip(a)),
        }
    }

    pub fn sqrt(&mut self, a: ExprId) -> ExprId {
        match self.node(a) {
            Node::Const(bits) if f64::from_bits(bits) >= 0.0 => {
                self.constant(f64::from_bits(bits).sqrt())
            }
            _ => self.intern(Node::Sqrt(a)),
        }
    }

    /// `atan2(y, x)`.
    pub fn atan2(&mut self, y: ExprId, x: ExprId) -> ExprId {
        match (self.constant_value(y), self.constant_value(x)) {
            (Some(y), Some(x)) => self.constant(snap(y.atan2(x))),
            _ => self.intern(Node::Atan2(y, x)),
        }
    }

    /// `∂e/∂var`, memoised per (node, variable) so shared subgraphs are differentiated once.
    pub fn partial(&mut self, e: ExprId, var: Var) -> ExprId {
        if let Some(&d) = self.partials.get(&(e, var)) {
            return d;
        }
        let d = match self.node(e) {
            Node::Const(_) => self.constant(0.0),
            Node::Var(v) => self.constant(if v == var { 1.0 } else { 0.0 }),
            Node::Add(a, b) => {
                let (da, db) = (self.partial(a, var), self.partial(b, var));
                self.add(da, db)
            }
            Node::Mul(a, b) => {
                let (da, db) = (self.partial(a, var), self.partial(b, var));
                let left = self.mul(da, b);
                let right = self.mul(a, db);
                self.add(left, right)
            }
            Node::Neg(a) => {
                let da = self.partial(a, var);
                self.neg(da)
            }
            Node::Sin(a) => {
                let da = self.partial(a, var);
                let cosine = self.cos(a);
                self.mul(cosine, da)
            }
            Node::Cos(a) => {
                let da = self.partial(a, var);
                let sine = self.sin(a);
                let product = self.mul(sine, da);
                self.neg(product)
            }
            Node::Recip(a) => {
                let da = self.partial(a, var);
                let square = self.mul(e, e);
                let product = self.mul(square, da);
                self.neg(product)
            }
            Node::Sqrt(a) => {
                let da = self.partial(a, var);
                let two = self.constant(2.0);
                let twice = self.mul(two, e);
                let inverse = self.recip(twice);
                self.mul(inverse, da)
            }
            // (x·dy − y·dx) / (x² + y²).
            Node::Atan2(y, x) => {
                let (dy, dx) = (self.partial(y, var), self.partial(x, var));
                let (x_dy, y_dx) = (self.mul(x, dy), self.mul(y, dx));
                let numerator = self.sub(x_dy, y_dx);
                let (xx, yy) = (self.mul(x, x), self.mul(y, y));
                let squared = self.add(xx, yy);
                let inverse = self.recip(squared);
                self.mul(numerator, inverse)
            }
        };
        self.partials.insert((e, var), d);
        d
    }

    /// `de/dt = Σ ∂e/∂v · dv/dt` over `vars` whose time derivatives `keep` accepts; the others
    /// are taken as zero (constant parameters, or accelerations the caller solves for).
    pub fn time_derivative(
        &mut self,
        e: ExprId,
        vars: &[Var],
        keep: impl Fn(Var) -> bool,
    ) -> ExprId {
        let mut sum = self.constant(0.0);
        for &var in vars {
            let Some(rate) = var.time_derivative().filter(|&rate| keep(rate)) else {
                continue;
            };
            let partial = self.partial(e, var);
            if self.is_zero(partial) {
                continue;
            }
            let rate = self.var(rate);
            let term = self.mul(partial, rate);
            sum = self.add(sum, term);
        }
        sum
    }
}

fn snap(value: f64) -> f64 {
    for target in [0.0, 1.0, -1.0] {
        if (value - target).abs() < TRIG_SNAP {
            return target;
        }
    }
    value
}

#[cfg(test)]
mod tests {
    use super::*;

    fn x(graph: &mut Graph) -> ExprId {
        graph.var(Var::Value(SymbolRef::Unknown(0)))
    }

    #[test]
    fn constructors_fold_identities() {
        let mut g = Graph::default();
        let x = x(&mut g);
        let zero = g.constant(0.0);
        let one = g.constant(1.0);
        assert_eq!(g.add(x, zero), x);
        assert_eq!(g.mul(one, x), x);
        assert_eq!(g.mul(x, zero), zero);
        let minus_x = g.neg(x);
        assert_eq!(g.neg(minus_x), x);
        assert_eq!(g.add(x, minus_x), zero);
        let two = g.constant(2.0);
        let three = g.constant(3.0);
        let five = g.add(two, three);
        assert_eq!(g.constant_value(five), Some(5.0));
    }

    #[test]
    fn equal_expressions_are_one_node() {
        let mut g = Graph::default();
        let x = x(&mut g);
        let y = g.var(Var::Value(SymbolRef::Unknown(1)));
        assert_eq!(g.mul(x, y), g.mul(y, x));
        let before = g.len();
        let s1 = g.sin(x);
        let s2 = g.sin(x);
        assert_eq!(s1, s2);
        assert_eq!(g.len(), before + 1);
    }

    #[test]
    fn trig_of_constant_multiples_of_half_pi_is_exact() {
        let mut g = Graph::default();
        let half_pi = g.constant(std::f64::consts::FRAC_PI_2);
        let c = g.cos(half_pi);
        let s = g.sin(half_pi);
        assert_eq!(g.constant_value(c), Some(0.0));
        assert_eq!(g.constant_value(s), Some(1.0));
    }

    #[test]
    fn sums_take_out_a_common_fixed_factor_and_undo_a_part() {
        let mut g = Graph::default();
        g.group_fixed_factors();
        let l = g.var(Var::Value(SymbolRef::Param(0)));
        let (x, y) = (x(&mut g), g.var(Var::Value(SymbolRef::Unknown(1))));
        // l·x + l·y = l·(x + y), and l·x − l·y = l·(x − y).
        let (lx, ly) = (g.mul(l, x), g.mul(l, y));
        let (sum, difference) = (g.add(x, y), g.sub(x, y));
        assert_eq!(g.add(lx, ly), g.mul(l, sum));
        assert_eq!(g.sub(lx, ly), g.mul(l, difference));
        // x − (y + x) = −y, and (y + x) − x = y.
        let yx = g.add(y, x);
        let minus_y = g.neg(y);
        assert_eq!(g.sub(x, yx), minus_y);
        assert_eq!(g.sub(yx, x), y);
    }

    #[test]
    fn cos_squared_plus_sin_squared_is_one() {
        let mut g = Graph::default();
        let x = x(&mut g);
        let (c, s) = (g.cos(x), g.sin(x));
        let (cc, ss) = (g.mul(c, c), g.mul(s, s));
        assert_eq!(g.add(cc, ss), g.constant(1.0));
        assert_eq!(g.add(ss, cc), g.constant(1.0));
        // Of different angles, it stays a sum.
        let y = g.var(Var::Value(SymbolRef::Unknown(1)));
        let other = g.sin(y);
        let other_squared = g.mul(other, other);
        let mixed = g.add(cc, other_squared);
        assert!(matches!(g.node(mixed), Node::Add(..)));
    }

    #[test]
    fn an_input_rate_common_to_two_terms_is_factored_out() {
        let mut g = Graph::default();
        g.group_fixed_factors();
        let rate = g.var(Var::Rate(SymbolRef::Input(0)));
        let (p, q) = (
            g.var(Var::Value(SymbolRef::Unknown(0))),
            g.var(Var::Value(SymbolRef::Unknown(1))),
        );
        let (rp, rq) = (g.mul(rate, p), g.mul(rate, q));
        // ω·p − ω·q = ω·(p − q).
        let minus_rq = g.neg(rq);
        let difference = g.add(rp, minus_rq);
        let expected = {
            let minus_q = g.neg(q);
            let inner = g.add(p, minus_q);
            g.mul(rate, inner)
        };
        assert_eq!(difference, expected);
        // An unknown's value common to both is not an input's rate: left as it is.
        let (pq, pp) = (g.mul(p, q), g.mul(p, p));
        let sum = g.add(pq, pp);
        assert_eq!(g.node(sum), Node::Add(pq, pp));
    }

    #[test]
    fn derivative_of_polar_component_is_exact() {
        // d/dx (r·cos x) = -(r·sin x)
        let mut g = Graph::default();
        let x = x(&mut g);
        let r = g.var(Var::Value(SymbolRef::Param(0)));
        let c = g.cos(x);
        let f = g.mul(r, c);
        let d = g.partial(f, Var::Value(SymbolRef::Unknown(0)));
        let s = g.sin(x);
        let rs = g.mul(r, s);
        let expected = g.neg(rs);
        assert_eq!(d, expected);
    }
}
