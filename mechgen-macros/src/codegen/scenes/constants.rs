//! The constants `scenes()` computes once: the subexpressions of the kernels that depend on
//! the dimensions alone, hoisted as large as they come. Separate because the scenes type
//! (how many), its constructor (their values) and every kernel (which it reads) are all laid
//! out from this one choice.

use std::collections::BTreeSet;

use super::auxiliary::{aux_arguments, needed_aux};
use super::{Mode, scene_outputs};
use crate::codegen::Generator;
use crate::codegen::emit::children;
use crate::symbolic::{ExprId, Node, Straight};

/// Expressions that depend on the dimensions alone, computed once per mechanism.
pub(super) struct Constants {
    /// The hoisted nodes, in arena order; constant `k` is `ids[k]`.
    pub(super) ids: Vec<ExprId>,
}

impl Generator<'_> {
    /// The dimension-only subexpressions the kernels read, hoisted as large as they come:
    /// a node is hoisted when it depends on parameters alone, is more than a name or a number,
    /// and is read by something that moves (or is itself an output).
    pub(super) fn constants(&self, straight: &Straight) -> Constants {
        let graph = &self.equations.graph;
        let roots: Vec<ExprId> = self
            .model
            .scenes
            .iter()
            .flat_map(|scene| {
                let outputs = scene_outputs(scene, straight);
                let arguments: Vec<ExprId> = [Mode::Checked, Mode::Fast]
                    .into_iter()
                    .flat_map(|mode| {
                        needed_aux(graph, straight, &outputs, mode)
                            .into_iter()
                            .flat_map(move |k| aux_arguments(&straight.aux[k], mode))
                    })
                    .collect();
                arguments.into_iter().chain(outputs).collect::<Vec<_>>()
            })
            .collect();
        let mut reachable = vec![false; graph.len()];
        let mut stack = roots.clone();
        while let Some(id) = stack.pop() {
            if !std::mem::replace(&mut reachable[id.index()], true) {
                stack.extend(children(graph.node(id)));
            }
        }
        let mut hoisted = BTreeSet::new();
        let mut hoist = |id: ExprId| {
            // Negation is free where it is read; hoist what it negates.
            let mut id = id;
            while let Node::Neg(inner) = graph.node(id) {
                id = inner;
            }
            if !matches!(graph.node(id), Node::Const(_) | Node::Var(_)) {
                hoisted.insert(id);
            }
        };
        for &root in &roots {
            if graph.is_fixed(root) {
                hoist(root);
            }
        }
        for i in
            (0..graph.len()).filter(|&i| reachable[i] && !graph.is_fixed(ExprId::from_index(i)))
        {
            for child in children(graph.node(ExprId::from_index(i))) {
                if graph.is_fixed(child) {
                    hoist(child);
                }
            }
        }
        Constants {
            ids: hoisted.into_iter().collect(),
        }
    }
}
