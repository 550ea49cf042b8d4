//! Rebuilding expressions bottom-up with some nodes replaced, through the graph's folding
//! constructors, so a rewritten expression is as simple as one built directly.

use std::collections::HashMap;

use super::graph::{ExprId, Graph, Node};

/// A node's replacement, or `None` to rebuild it from its rewritten children.
type Rule<'a> = Box<dyn FnMut(&mut Graph, ExprId) -> Option<ExprId> + 'a>;

/// A rewrite in progress: its rule and the nodes it has rewritten so far, so shared
/// subexpressions are rewritten once.
pub struct Rewriter<'a> {
    rule: Rule<'a>,
    memo: HashMap<ExprId, ExprId>,
}

impl<'a> Rewriter<'a> {
    pub fn new(rule: impl FnMut(&mut Graph, ExprId) -> Option<ExprId> + 'a) -> Self {
        Rewriter {
            rule: Box::new(rule),
            memo: HashMap::new(),
        }
    }

    pub fn all(&mut self, graph: &mut Graph, roots: &[ExprId]) -> Vec<ExprId> {
        roots.iter().map(|&root| self.expr(graph, root)).collect()
    }

    pub fn expr(&mut self, graph: &mut Graph, id: ExprId) -> ExprId {
        if let Some(&done) = self.memo.get(&id) {
            return done;
        }
        let rewritten = match (self.rule)(graph, id) {
            Some(replacement) => replacement,
            None => match graph.node(id) {
                Node::Const(_) | Node::Var(_) => id,
                Node::Neg(a) => {
                    let a = self.expr(graph, a);
                    graph.neg(a)
                }
                Node::Add(a, b) => {
                    let (a, b) = (self.expr(graph, a), self.expr(graph, b));
                    graph.add(a, b)
                }
                Node::Mul(a, b) => {
                    let (a, b) = (self.expr(graph, a), self.expr(graph, b));
                    graph.mul(a, b)
                }
                Node::Sin(a) => {
                    let a = self.expr(graph, a);
                    graph.sin(a)
                }
                Node::Cos(a) => {
                    let a = self.expr(graph, a);
                    graph.cos(a)
                }
                Node::Recip(a) => {
                    let a = self.expr(graph, a);
                    graph.recip(a)
                }
                Node::Sqrt(a) => {
                    let a = self.expr(graph, a);
                    graph.sqrt(a)
                }
                Node::Atan2(y, x) => {
                    let (y, x) = (self.expr(graph, y), self.expr(graph, x));
                    graph.atan2(y, x)
                }
            },
        };
        self.memo.insert(id, rewritten);
        rewritten
    }
}
