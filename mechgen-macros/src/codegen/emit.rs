//! Turns a set of output expressions into straight-line Rust with shared work done once.
//!
//! Scheduling is deterministic: nodes are visited in arena order (a topological order), a
//! node gets a `let` only when it is used more than once, temporaries are named `t0, t1, …`
//! in that order, and each angle gets one `sin_cos` (or a lone `sin`/`cos`). Negation is free
//! in the output, so it is never bound and its uses count as uses of its operand.

use std::collections::BTreeSet;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

use crate::symbolic::{ExprId, Graph, Node, Var};

/// The statements that compute some outputs, and the expression for each output.
pub struct Block {
    /// The statements, by stage (see [`Context::stage`]): those of stage `k` read variables
    /// known by stage `k` at the latest.
    pub statements: Vec<Vec<TokenStream>>,
    pub outputs: Vec<Emitted>,
    /// The variables the block reads, so the caller binds only those.
    pub used: BTreeSet<Var>,
    /// Every node the statements bind to a local, with the local and the stage of its
    /// statement, so a later block can read them instead of computing them again.
    pub named: Vec<(ExprId, Ident, usize)>,
}

/// An emitted expression and the precedence of its outermost operator.
pub struct Emitted {
    tokens: TokenStream,
    precedence: Precedence,
}

impl Emitted {
    /// The expression as the receiver of a method call, parenthesised if it needs to be.
    pub fn receiver(&self) -> TokenStream {
        let tokens = &self.tokens;
        if self.precedence < Precedence::Atom {
            quote!((#tokens))
        } else {
            tokens.clone()
        }
    }
}

impl quote::ToTokens for Emitted {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        self.tokens.to_tokens(tokens);
    }
}

/// Operator precedence, low to high, for minimal parentheses.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Precedence {
    Sum,
    Product,
    Unary,
    Atom,
}

/// A generated local: hygienic, so it never clashes with the user's names.
pub fn local(name: &str) -> Ident {
    Ident::new(name, Span::mixed_site())
}

/// What a block can assume about the code around it.
pub struct Context<'a> {
    /// The other generated names in scope (arguments, rates), which the block's own locals
    /// must not shadow.
    pub reserved: &'a BTreeSet<String>,
    /// Nodes whose values are already in locals, such as the sine and cosine of an angle a
    /// closed form produced directly, with the stage they are known from.
    pub presets: &'a [(ExprId, Ident, usize)],
    /// The stage from which each variable is known. A function that solves as it goes
    /// (loop by loop in closed form, then the rates, then the accelerations) computes a
    /// value in the first stage at which everything it reads is known; plain blocks have one
    /// stage, 0.
    pub stage: &'a dyn Fn(Var) -> usize,
}

/// Emits `outputs` with shared work done once.
pub fn emit(
    graph: &Graph,
    outputs: &[ExprId],
    var_name: &dyn Fn(Var) -> Ident,
    context: &Context,
) -> Block {
    let mut names = vec![None; graph.len()];
    for (id, name, _) in context.presets {
        names[id.index()] = Some(name.clone());
    }
    let mut emitter = Emitter {
        graph,
        var_name,
        names,
        used: BTreeSet::new(),
        taken: context.reserved.clone(),
        named: Vec::new(),
    };
    let statements = emitter.schedule(outputs, context);
    let outputs = outputs
        .iter()
        .map(|&o| {
            let (tokens, precedence) = emitter.expr(o);
            Emitted { tokens, precedence }
        })
        .collect();
    Block {
        statements,
        outputs,
        used: emitter.used,
        named: emitter.named,
    }
}

struct Emitter<'a> {
    graph: &'a Graph,
    var_name: &'a dyn Fn(Var) -> Ident,
    /// The local holding a node's value, once it has one.
    names: Vec<Option<Ident>>,
    used: BTreeSet<Var>,
    /// Generated names in scope so far, so a new local never shadows another.
    taken: BTreeSet<String>,
    /// What [`Block::named`] reports.
    named: Vec<(ExprId, Ident, usize)>,
}

impl Emitter<'_> {
    /// The statements for `outputs`, by stage.
    fn schedule(&mut self, outputs: &[ExprId], context: &Context) -> Vec<Vec<TokenStream>> {
        let graph = self.graph;
        let n = graph.len();
        let mut reachable = vec![false; n];
        let mut stack: Vec<ExprId> = outputs.to_vec();
        while let Some(id) = stack.pop() {
            if std::mem::replace(&mut reachable[id.index()], true) {
                continue;
            }
            // A preset node is a leaf: its value is already in a local.
            if self.names[id.index()].is_none() {
                stack.extend(children(graph.node(id)));
            }
        }
        let mut stage = vec![0usize; n];
        for (id, _, known) in context.presets {
            stage[id.index()] = *known;
        }
        for i in (0..n).filter(|&i| reachable[i] && self.names[i].is_none()) {
            stage[i] = match graph.node(id_at(i)) {
                Node::Var(var) => (context.stage)(var),
                node => children(node).map(|c| stage[c.index()]).max().unwrap_or(0),
            };
        }
        let stages = stage.iter().copied().max().unwrap_or(0) + 1;

        // Angles whose sine and cosine are both needed get one `sin_cos`.
        let mut has_sin = vec![false; n];
        let mut has_cos = vec![false; n];
        for (i, _) in reachable.iter().enumerate().filter(|(_, r)| **r) {
            match graph.node(id_at(i)) {
                Node::Sin(a) => has_sin[a.index()] = true,
                Node::Cos(a) => has_cos[a.index()] = true,
                _ => {}
            }
        }

        // Parents come after children in the arena, so a reverse sweep sees every use of a
        // node before the node itself.
        let mut uses = vec![0usize; n];
        for output in outputs {
            uses[output.index()] += 1;
        }
        for i in (0..n)
            .rev()
            .filter(|&i| reachable[i] && self.names[i].is_none())
        {
            match graph.node(id_at(i)) {
                Node::Neg(a) => uses[a.index()] += uses[i],
                Node::Sin(a) if has_cos[a.index()] => {}
                node => children(node).for_each(|c| uses[c.index()] += 1),
            }
        }

        let mut statements = vec![Vec::new(); stages];
        let mut temporaries = 0;
        let mut angles = 0;
        for i in (0..n).filter(|&i| reachable[i]) {
            let id = id_at(i);
            match graph.node(id) {
                Node::Sin(a) | Node::Cos(a) if self.names[i].is_none() => {
                    // Named after the angle when it is a variable (`sin_theta3`), else numbered.
                    let named = match graph.node(a) {
                        Node::Var(var) => Some((self.var_name)(var).unraw().to_string()),
                        _ => None,
                    };
                    let stem = match named.filter(|stem| self.trig_names_free(stem)) {
                        Some(stem) => stem,
                        None => loop {
                            angles += 1;
                            let stem = (angles - 1).to_string();
                            if self.trig_names_free(&stem) {
                                break stem;
                            }
                        },
                    };
                    let statement = self.trig(a, &stem, has_sin[a.index()], has_cos[a.index()]);
                    for node in [Node::Sin(a), Node::Cos(a)] {
                        if let Some(index) = self.find(node)
                            && reachable[index]
                            && let Some(name) = self.names[index].clone()
                        {
                            self.named.push((id_at(index), name, stage[i]));
                        }
                    }
                    statements[stage[i]].push(statement);
                }
                Node::Add(..)
                | Node::Mul(..)
                | Node::Recip(..)
                | Node::Sqrt(..)
                | Node::Atan2(..)
                    if uses[i] > 1 && self.names[i].is_none() =>
                {
                    let value = self.expr(id).0;
                    let name = loop {
                        let name = format!("t{temporaries}");
                        temporaries += 1;
                        if !self.taken.contains(&name) {
                            break name;
                        }
                    };
                    let name = local(&name);
                    statements[stage[i]].push(quote!(let #name = #value;));
                    self.named.push((id, name.clone(), stage[i]));
                    self.names[i] = Some(name);
                }
                _ => {}
            }
        }
        statements
    }

    fn trig_names_free(&self, stem: &str) -> bool {
        ![format!("sin_{stem}"), format!("cos_{stem}")]
            .iter()
            .any(|name| self.taken.contains(name))
    }

    /// `let (sin_x, cos_x) = x.sin_cos();`, or the one of them that is needed. An angle that
    /// is a sum (`theta3 + delta`) takes both from its terms with
    /// `mechgen::__private::sin_cos_of_sum`, of the exact sum: rounded first, a crank ten
    /// thousand turns round is 3.6e-12 rad off, an offset of 1e15 an eighth of a radian.
    fn trig(&mut self, angle: ExprId, stem: &str, sin: bool, cos: bool) -> TokenStream {
        let sin_name = local(&format!("sin_{stem}"));
        let cos_name = local(&format!("cos_{stem}"));
        if self.is_sum(angle) {
            let mut terms = Vec::new();
            self.terms(angle, false, &mut terms);
            let terms: Vec<TokenStream> = terms
                .into_iter()
                .map(|(term, negated)| {
                    if negated {
                        let term = self.operand(term, Precedence::Unary);
                        quote!(-#term)
                    } else {
                        self.operand(term, Precedence::Sum)
                    }
                })
                .collect();
            self.name_trig(angle, &sin_name, &cos_name);
            let pattern = match (sin, cos) {
                (true, true) => quote!((#sin_name, #cos_name)),
                (true, false) => quote!((#sin_name, _)),
                _ => quote!((_, #cos_name)),
            };
            return quote!(let #pattern = ::mechgen::__private::sin_cos_of_sum([#(#terms),*]););
        }
        let argument = self.operand(angle, Precedence::Atom);
        self.name_trig(angle, &sin_name, &cos_name);
        match (sin, cos) {
            (true, true) => {
                quote!(let (#sin_name, #cos_name) = ::mechgen::__private::sin_cos(#argument);)
            }
            (true, false) => quote!(let #sin_name = #argument.sin();),
            _ => quote!(let #cos_name = #argument.cos();),
        }
    }

    /// Names `angle`'s sine and cosine, and reserves the names.
    fn name_trig(&mut self, angle: ExprId, sin_name: &Ident, cos_name: &Ident) {
        self.taken
            .extend([sin_name.to_string(), cos_name.to_string()]);
        for (node, name) in [(Node::Sin(angle), sin_name), (Node::Cos(angle), cos_name)] {
            if let Some(index) = self.find(node) {
                self.names[index] = Some(name.clone());
            }
        }
    }

    /// Whether `id` is a sum or a negated sum.
    fn is_sum(&self, id: ExprId) -> bool {
        match self.graph.node(id) {
            Node::Add(..) => true,
            Node::Neg(a) => self.is_sum(a),
            _ => false,
        }
    }

    /// The terms of a sum, each with whether it is negated, through every nested sum and
    /// negation, named or not: the sum's own rounding is what [`Self::trig`] leaves out.
    fn terms(&self, id: ExprId, negated: bool, terms: &mut Vec<(ExprId, bool)>) {
        match self.graph.node(id) {
            Node::Add(a, b) => {
                self.terms(a, negated, terms);
                self.terms(b, negated, terms);
            }
            Node::Neg(a) => self.terms(a, !negated, terms),
            _ => terms.push((id, negated)),
        }
    }

    fn find(&self, node: Node) -> Option<usize> {
        self.graph.lookup(node).map(ExprId::index)
    }

    /// `id`'s expression, parenthesised if its precedence is below `required`.
    fn operand(&mut self, id: ExprId, required: Precedence) -> TokenStream {
        let (tokens, precedence) = self.expr(id);
        if precedence < required {
            quote!((#tokens))
        } else {
            tokens
        }
    }

    /// If `id` is a negation or a negative constant, what it negates.
    fn negated(&self, id: ExprId) -> Option<Negated> {
        if self.names[id.index()].is_some() {
            return None;
        }
        match self.graph.node(id) {
            Node::Neg(x) => Some(Negated::Expr(x)),
            Node::Const(bits) if f64::from_bits(bits) < 0.0 => {
                Some(Negated::Constant(-f64::from_bits(bits)))
            }
            _ => None,
        }
    }

    /// `(minuend, subtrahend)` where `id` is printed inline as a difference (an unnamed sum
    /// with a negated operand, see the `Add` case of [`Self::expr`]) whose negation is
    /// printed the other way round.
    fn difference(&self, id: ExprId) -> Option<(ExprId, Negated)> {
        if self.names[id.index()].is_some() {
            return None;
        }
        let Node::Add(a, b) = self.graph.node(id) else {
            return None;
        };
        let (minuend, subtrahend) = match (self.negated(a), self.negated(b)) {
            (_, Some(subtrahend)) => (a, subtrahend),
            (Some(subtrahend), None) => (b, subtrahend),
            (None, None) => return None,
        };
        // Not where the subtrahend is a lone variable or a number (`-(t0 - l1)`, a loop's
        // constant vector): measured, the compiler pairs such a difference with its
        // neighbours' into vector instructions better as it is.
        match subtrahend {
            Negated::Expr(x) if !matches!(self.graph.node(x), Node::Var(_)) => {
                Some((minuend, subtrahend))
            }
            _ => None,
        }
    }

    fn operand_or_constant(&mut self, negated: Negated, required: Precedence) -> TokenStream {
        match negated {
            Negated::Expr(id) => self.operand(id, required),
            Negated::Constant(value) => constant(value),
        }
    }

    fn expr(&mut self, id: ExprId) -> (TokenStream, Precedence) {
        if let Some(name) = &self.names[id.index()] {
            return (quote!(#name), Precedence::Atom);
        }
        match self.graph.node(id) {
            Node::Const(bits) => {
                let value = f64::from_bits(bits);
                if value < 0.0 {
                    let magnitude = constant(-value);
                    (quote!(-#magnitude), Precedence::Unary)
                } else {
                    (constant(value), Precedence::Atom)
                }
            }
            Node::Var(var) => {
                self.used.insert(var);
                let name = (self.var_name)(var);
                (quote!(#name), Precedence::Atom)
            }
            Node::Neg(a) => {
                // `-(x - y)` reads `y - x`: the same value (rounding is symmetric), but for
                // the sign of a zero, without the negation.
                if let Some((minuend, subtrahend)) = self.difference(a) {
                    let left = self.operand_or_constant(subtrahend, Precedence::Sum);
                    let right = self.operand(minuend, Precedence::Product);
                    return (quote!(#left - #right), Precedence::Sum);
                }
                let a = self.operand(a, Precedence::Unary);
                (quote!(-#a), Precedence::Unary)
            }
            Node::Add(a, b) => {
                // `a + (-y)` reads `a - y`; `(-x) + b` reads `b - x`.
                let tokens = match (self.negated(a), self.negated(b)) {
                    (_, Some(subtrahend)) => {
                        let left = self.operand(a, Precedence::Sum);
                        let right = self.operand_or_constant(subtrahend, Precedence::Product);
                        quote!(#left - #right)
                    }
                    (Some(subtrahend), None) => {
                        let left = self.operand(b, Precedence::Sum);
                        let right = self.operand_or_constant(subtrahend, Precedence::Product);
                        quote!(#left - #right)
                    }
                    (None, None) => {
                        let left = self.operand(a, Precedence::Sum);
                        let right = self.operand(b, Precedence::Product);
                        quote!(#left + #right)
                    }
                };
                (tokens, Precedence::Sum)
            }
            Node::Mul(a, b) => {
                let left = self.operand(a, Precedence::Product);
                let right = self.operand(b, Precedence::Unary);
                (quote!(#left * #right), Precedence::Product)
            }
            // Scheduled before use, so named by now; this is the fallback for a lone call.
            Node::Sin(a) => {
                let a = self.operand(a, Precedence::Atom);
                (quote!(#a.sin()), Precedence::Atom)
            }
            Node::Cos(a) => {
                let a = self.operand(a, Precedence::Atom);
                (quote!(#a.cos()), Precedence::Atom)
            }
            Node::Recip(a) => {
                let a = self.operand(a, Precedence::Atom);
                (quote!(#a.recip()), Precedence::Atom)
            }
            Node::Sqrt(a) => {
                let a = self.operand(a, Precedence::Atom);
                (quote!(#a.sqrt()), Precedence::Atom)
            }
            Node::Atan2(y, x) => {
                let y = self.operand(y, Precedence::Atom);
                let x = self.operand(x, Precedence::Atom);
                (quote!(#y.atan2(#x)), Precedence::Atom)
            }
        }
    }
}

#[derive(Clone, Copy)]
enum Negated {
    Expr(ExprId),
    Constant(f64),
}

fn id_at(index: usize) -> ExprId {
    // The arena never exceeds u32 (see Graph::intern), so this round-trips.
    ExprId::from_index(index)
}

/// Which nodes `roots` read, directly or through other nodes.
pub fn reachable(graph: &Graph, roots: &[ExprId]) -> Vec<bool> {
    let mut seen = vec![false; graph.len()];
    let mut stack = roots.to_vec();
    while let Some(id) = stack.pop() {
        if !std::mem::replace(&mut seen[id.index()], true) {
            stack.extend(children(graph.node(id)));
        }
    }
    seen
}

pub fn children(node: Node) -> impl Iterator<Item = ExprId> {
    let (a, b) = match node {
        Node::Const(_) | Node::Var(_) => (None, None),
        Node::Neg(a) | Node::Sin(a) | Node::Cos(a) | Node::Recip(a) | Node::Sqrt(a) => {
            (Some(a), None)
        }
        Node::Add(a, b) | Node::Mul(a, b) | Node::Atan2(a, b) => (Some(a), Some(b)),
    };
    a.into_iter().chain(b)
}

/// A constant of the generic float type `T`.
pub fn constant(value: f64) -> TokenStream {
    // The model rejects non-finite numbers; folding extreme ones can still overflow, and
    // then the generated code computes with the same infinity instead of failing to expand.
    if value.is_nan() {
        quote!(T::nan())
    } else if value.is_infinite() {
        quote!(T::infinity())
    } else if value == 0.0 {
        quote!(T::zero())
    } else if value == 1.0 {
        quote!(T::one())
    } else if let Some(name) = named_constant(value) {
        let name = Ident::new(name, Span::call_site());
        quote!(T::constant(::core::f64::consts::#name))
    } else {
        let literal = Literal::f64_unsuffixed(value);
        quote!(T::constant(#literal))
    }
}

/// The name of `value` in `core::f64::consts`, if it is one of them exactly: reads better
/// than 16 digits, and does not trip clippy's `approx_constant` in the user's crate.
fn named_constant(value: f64) -> Option<&'static str> {
    use std::f64::consts as c;
    const NAMED: [(f64, &str); 18] = [
        (c::PI, "PI"),
        (c::TAU, "TAU"),
        (c::FRAC_PI_2, "FRAC_PI_2"),
        (c::FRAC_PI_3, "FRAC_PI_3"),
        (c::FRAC_PI_4, "FRAC_PI_4"),
        (c::FRAC_PI_6, "FRAC_PI_6"),
        (c::FRAC_PI_8, "FRAC_PI_8"),
        (c::FRAC_1_PI, "FRAC_1_PI"),
        (c::FRAC_2_PI, "FRAC_2_PI"),
        (c::FRAC_2_SQRT_PI, "FRAC_2_SQRT_PI"),
        (c::SQRT_2, "SQRT_2"),
        (c::FRAC_1_SQRT_2, "FRAC_1_SQRT_2"),
        (c::E, "E"),
        (c::LOG2_E, "LOG2_E"),
        (c::LOG10_E, "LOG10_E"),
        (c::LN_2, "LN_2"),
        (c::LN_10, "LN_10"),
        (c::LOG2_10, "LOG2_10"),
    ];
    NAMED
        .iter()
        .find(|(named, _)| named.to_bits() == value.to_bits())
        .map(|(_, name)| *name)
}
