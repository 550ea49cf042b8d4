//! The reduced iteration up to its solution, which `position` and `motion_near` share:
//! the checks and bindings before it, the guess's branches, the closure Newton evaluates
//! (the iterated angles' turnings, the closed forms step by step, the residual, and the
//! reduced Jacobian from [`schur_complement`]), and the payload that carries back what the
//! code after the solution reads instead of computing it again. Separate because both
//! functions emit it whole, and it is most of either.

use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

use super::schur::schur_complement;
use super::steps::trig_nodes;
use crate::codegen::emit::{Block, Emitted, children, local, reachable};
use crate::codegen::newton::scale_and_weights;
use crate::codegen::{Bindings, Generator, arg};
use crate::model::{Kind, SymbolRef};
use crate::symbolic::{ExprId, Graph, Node, Reduction, Step, Var};

/// The reduced iteration, up to its solution: what `position` and `motion_near` share.
pub(super) struct Iteration {
    /// The check of the parameters and the input.
    pub(super) check: TokenStream,
    /// The check of the guess, the parameters' bindings, the work on parameters and input
    /// alone, the guess's branches, and the iteration (falling back where it cannot start);
    /// then the iterated and closed-form unknowns at the solution, by name.
    pub(super) solve: TokenStream,
    /// Every value the iteration named that is in scope after it, by node, for what follows
    /// to read instead of computing it again.
    pub(super) presets: Vec<(ExprId, Ident, usize)>,
    /// The names `solve` binds, which later temporaries must not shadow.
    pub(super) names: BTreeSet<String>,
    /// The variables it reads: the parameters among them are bound.
    pub(super) used: BTreeSet<Var>,
    /// The branch sign of each step solved after the iteration, if it has branches.
    pub(super) after_signs: Vec<Option<Ident>>,
}

impl Generator<'_> {
    /// The reduced iteration up to its solution, with `fall_back` run where it cannot start;
    /// `after` are the expressions read after it, which decide what its payload carries.
    pub(super) fn reduced_iteration(
        &self,
        reduction: &Reduction,
        fall_back: &TokenStream,
        after: &[ExprId],
    ) -> Iteration {
        let graph = &self.equations.graph;
        let model = self.model;
        let input = self.input_args();
        let first_input = self.first_input();
        let (guess, options, x, converged) =
            (arg("guess"), arg("options"), arg("x"), arg("converged"));
        let (reduced, failure) = (arg("reduced"), arg("failure"));
        let unknown = |u: usize| &model.unknowns[u].name;
        let steps = &reduction.steps;

        // Stages: 0 the parameters and input, 1 the iterate, s + 2 once step s is solved.
        let mut stage_of = vec![0; model.unknowns.len()];
        reduction.iterated.iter().for_each(|&u| stage_of[u] = 1);
        for (s, step) in steps.iter().enumerate() {
            step.unknowns.iter().for_each(|&u| stage_of[u] = s + 2);
        }
        let stage = |var: Var| match var {
            Var::Value(SymbolRef::Unknown(u)) => stage_of[u],
            _ => 0,
        };

        // Closed-form angles come as unit vectors, bound to their sines and cosines.
        let directions = self.directions(steps);
        let mut presets: Vec<(ExprId, Ident, usize)> = self
            .trig_presets(&directions)
            .into_iter()
            .map(|(u, id, name)| (id, name, stage_of[u]))
            .collect();

        // One block: the steps' coefficients, the residual, the non-zero Jacobian entries of
        // the loops in the iteration, and the magnitudes whose sum scales the rounding floor.
        let rows: Vec<usize> = reduction
            .residual_loops
            .iter()
            .chain(steps.iter().map(|step| &step.loop_index))
            .flat_map(|&l| [2 * l, 2 * l + 1])
            .collect();
        let nonzero: Vec<(usize, usize)> = reduction
            .jacobian
            .iter()
            .enumerate()
            .filter(|(r, _)| rows.contains(r))
            .flat_map(|(r, row)| {
                row.iter()
                    .enumerate()
                    .filter(|(_, e)| !graph.is_zero(**e))
                    .map(move |(c, _)| (r, c))
            })
            .collect();
        let magnitudes = &self.equations.magnitudes;
        let entries: Vec<ExprId> = reduction
            .coefficients
            .iter()
            .flatten()
            .chain(&reduction.residual)
            .chain(nonzero.iter().map(|&(r, c)| &reduction.jacobian[r][c]))
            .chain(magnitudes)
            .copied()
            .collect();
        // The iterated angles' sines and cosines come from a `Turning` each, which rotates
        // its last `sin_cos` through the small way Newton has moved the angle since instead
        // of calling `sin_cos` again.
        let read = reachable(graph, &entries);
        let mut turnings = BTreeMap::new();
        let mut turns = Vec::new();
        for &u in &reduction.iterated {
            let stem = unknown(u).unraw().to_string();
            let [sin, cos] = trig_nodes(graph, u).map(|id| id.filter(|id| read[id.index()]));
            if sin.is_none() && cos.is_none() {
                continue;
            }
            let [sin, cos] = [(sin, "sin"), (cos, "cos")].map(|(id, prefix)| {
                let id = id?;
                let name = local(&format!("{prefix}_{stem}"));
                presets.push((id, name.clone(), 1));
                Some(name)
            });
            let [sin, cos] = [sin, cos].map(|name| name.map_or(quote!(_), |name| quote!(#name)));
            let turning = local(&format!("turning_{stem}"));
            let name = unknown(u);
            turns.push(quote!(let (#sin, #cos) = #turning.sin_cos(#name);));
            turnings.insert(u, turning);
        }
        let (bindings, block) =
            self.block_with(&entries, Bindings::ParametersOnly, &presets, &stage);
        let Block {
            mut statements,
            outputs,
            named,
            used,
        } = block;
        statements.resize(steps.len() + 2, Vec::new());
        let mut outputs = outputs.into_iter();
        let mut take = |n: usize| -> Vec<Emitted> { outputs.by_ref().take(n).collect() };
        let coefficients: Vec<Vec<Emitted>> = reduction
            .coefficients
            .iter()
            .map(|c| take(c.len()))
            .collect();
        let residual = take(reduction.residual.len());
        let entry_values = take(nonzero.len());
        let magnitude_values = take(magnitudes.len());
        // Every non-zero Jacobian entry gets a local, `d{row}_{column}`, for the reduced
        // Jacobian here and, through the payload, the loops' Jacobian at the solution.
        let entry_names: Vec<Ident> = nonzero
            .iter()
            .map(|(r, c)| local(&format!("d{r}_{c}")))
            .collect();
        let entry = |r: usize, c: usize| {
            let i = nonzero.iter().position(|&rc| rc == (r, c))?;
            Some(entry_names[i].clone())
        };

        // Each branching step's branch at the guess, by the sign `branch_of` would read, from
        // the guess's values and what was hoisted.
        let hoisted: Vec<(ExprId, Ident, usize)> = named
            .iter()
            .filter(|(_, _, stage)| *stage == 0)
            .cloned()
            .collect();
        let mut reserved = self.reserved.clone();
        reserved.extend(named.iter().map(|(_, name, _)| name.to_string()));
        let all_steps: Vec<&Step> = steps.iter().chain(&reduction.after).collect();
        let (sign_statements, sign_used, mut signs) =
            self.guess_signs(&all_steps, &hoisted, &reserved, &turnings);
        let after_signs = signs.split_off(steps.len());
        let sign_parameters: BTreeSet<Var> = sign_used.difference(&used).copied().collect();
        let sign_parameters = self.parameter_bindings(&sign_parameters, quote!(self));

        // The closure: the iterate, then step by step the closed forms, then the residual.
        let undefined = local("undefined");
        let first = &statements[1];
        let mut body = vec![quote!(#(#turns)* #(#first)*)];
        for (s, (step, values)) in steps.iter().zip(&coefficients).enumerate() {
            let (pattern, call) = self.closed_form_call(step, values, signs[s].as_ref());
            let trig = self.trig_bindings(&directions, step);
            // An angle read other than through its sine and cosine (`2·q`, say) is computed.
            let angles = directions
                .iter()
                .filter(|d| {
                    step.unknowns.contains(&d.unknown)
                        && used.contains(&Var::Value(SymbolRef::Unknown(d.unknown)))
                })
                .map(|d| self.angle_near_guess(d.unknown, &d.direction));
            let computed = &statements[s + 2];
            body.push(quote! {
                let ::core::result::Result::Ok(#pattern) = #call else {
                    return #undefined;
                };
                #trig
                #(#angles)*
                #(#computed)*
            });
        }
        let (schur, jacobian) = schur_complement(reduction, &entry, &undefined);

        // What follows the iteration reads what it named instead of computing it again (the
        // last name given to a node wins): hoisted values are in scope, the rest come back in
        // the payload, with the closed-form angles' unit vectors (for the angles) and lengths.
        let candidates: Vec<(ExprId, &Ident, bool)> = named
            .iter()
            .map(|(id, name, stage)| (*id, name, *stage >= 1))
            .chain(presets.iter().map(|(id, name, _)| (*id, name, true)))
            .chain(
                nonzero
                    .iter()
                    .zip(&entry_names)
                    .map(|(&(r, c), name)| (reduction.jacobian[r][c], name, true)),
            )
            .collect();
        let latest: BTreeMap<ExprId, &Ident> =
            candidates.iter().map(|&(id, name, _)| (id, name)).collect();
        let read = reached_presets(graph, after, &latest);
        let mut payload: Vec<Ident> = Vec::new();
        let mut carry = |name: &Ident| {
            if !payload.contains(name) {
                payload.push(name.clone());
            }
        };
        for &(id, name, carried) in &candidates {
            if carried && read.contains(&id) && latest[&id] == name {
                carry(name);
            }
        }
        directions.iter().flat_map(|d| &d.trig).for_each(&mut carry);
        steps
            .iter()
            .flat_map(|step| step.unknowns)
            .filter(|&u| model.unknowns[u].kind == Kind::Length)
            .for_each(|u| carry(unknown(u)));
        let payload_count = Literal::usize_unsuffixed(payload.len());

        // The magnitudes of fixed lengths are summed once, before the iteration.
        let fixed_scale = !magnitudes.iter().any(|&m| reads_unknowns(graph, m));
        let scale_local = arg("scale");
        let (scale_statements, weights) = scale_and_weights(
            &magnitude_values,
            &self.equations.magnitude_loops,
            &reduction.residual_loops,
            &scale_local,
            None,
        );
        let (scale_before, weights_inside) = if fixed_scale {
            (scale_statements, TokenStream::new())
        } else {
            (TokenStream::new(), scale_statements)
        };

        let iterated: Vec<&Ident> = reduction.iterated.iter().map(|&u| unknown(u)).collect();
        let turning_names = turnings.values();
        let n = Literal::usize_unsuffixed(iterated.len());
        let hoisted = &statements[0];
        // The closed-form angles at the solution, from their unit vectors.
        let angles = directions.iter().map(|d| {
            let (direction, [sin, cos]) = (&d.direction, &d.trig);
            let value = self.angle_near_guess(d.unknown, direction);
            quote! {
                let #direction = ::mechgen::Vec2::new(#cos, #sin);
                #value
            }
        });
        let check = quote!(self.mechgen_check_finite(#input)?;);
        let orientation = self.orientation(true, Some(&reduction.iterated));
        let solve = quote! {
            ::mechgen::__private::finite(#guess.to_array(), "initial guess")?;
            #bindings
            #sign_parameters
            #(#hoisted)*
            #(let mut #turning_names = ::mechgen::__private::Turning::new();)*
            #(#sign_statements)*
            #scale_before
            let #undefined = ::mechgen::__private::Linearisation {
                residual: [T::nan(); #n],
                jacobian: [[T::nan(); #n]; #n],
                scale: T::nan(),
                weights: [T::nan(); #n],
                payload: [T::nan(); #payload_count],
                columns: ::mechgen::__private::Columns::FromMatrix,
            };
            let #converged = match ::mechgen::__private::newton(
                #first_input,
                [#(#guess.#iterated),*],
                #options,
                #orientation,
                || ::core::option::Option::None,
                |#x: &[T; #n]| {
                    let [#(#iterated),*] = *#x;
                    #(#body)*
                    #(let #entry_names = #entry_values;)*
                    #schur
                    #weights_inside
                    ::mechgen::__private::Linearisation {
                        residual: [#(#residual),*],
                        jacobian: #jacobian,
                        #scale_local,
                        weights: #weights,
                        payload: [#(#payload),*],
                        columns: ::mechgen::__private::Columns::FromMatrix,
                    }
                },
            ) {
                // Only the guess can make the evaluation undefined (a closed form that does
                // not close there): the iteration cannot start.
                ::core::result::Result::Err(::mechgen::Error::NonFinite { .. }) => {
                    let #reduced = ::core::option::Option::None;
                    #fall_back
                }
                // The reduced evaluation rounds where its closed forms start, which can stall
                // it short of a root that Newton on every unknown reaches from the same guess:
                // that answers, or the reduced iteration's verdict stands. So can its Jacobian,
                // whose columns carry a closed form's sensitivity: a link within a few
                // roundings of the size leaves that closed form's angle to rounding, and the
                // reduced Jacobian singular where the loops' is not (edge run seed 30, case
                // 105700: an f32 Stephenson six-bar whose `C D` is 2e-6 of its size, singular
                // reduced Jacobian, loops' κ 7).
                ::core::result::Result::Err(
                    #failure @ (::mechgen::Error::NoConvergence { .. }
                    | ::mechgen::Error::CannotAssemble { .. }
                    | ::mechgen::Error::Singular { .. }),
                ) => {
                    let #reduced = ::core::option::Option::Some(#failure);
                    #fall_back
                }
                // Its orientation is its own Jacobian's, which near a closed form's toggle (a
                // short link beside long ones) can turn where the loops' does not: from a
                // guess Kantorovich certifies, Newton on every unknown reaches the guess's
                // root, and answers.
                ::core::result::Result::Err(#failure @ ::mechgen::Error::OtherBranch)
                    if ::mechgen::__private::guess_certified(
                        &self.residual(#input, #guess),
                        &self.jacobian(#input, #guess),
                    ) =>
                {
                    let #reduced = ::core::option::Option::Some(#failure);
                    #fall_back
                }
                other => other?,
            };
            let [#(#iterated),*] = #converged.solved.value;
            let [#(#payload),*] = #converged.at.payload;
            #(#angles)*
        };

        // Hoisted or carried back, each value read after the iteration is in scope there.
        let presets: Vec<(ExprId, Ident, usize)> = candidates
            .iter()
            .filter(|&&(id, name, carried)| {
                latest[&id] == name && (!carried || read.contains(&id) && payload.contains(name))
            })
            .map(|&(id, name, _)| (id, name.clone(), 0))
            .collect();
        let names = payload
            .iter()
            .chain(named.iter().map(|(_, name, _)| name))
            .map(Ident::to_string)
            .collect();
        Iteration {
            check,
            solve,
            presets,
            names,
            used: used.union(&sign_used).copied().collect(),
            after_signs,
        }
    }
}

/// The nodes in `presets` that `roots` reach (a preset is a leaf: its value is in a local).
fn reached_presets<V>(
    graph: &Graph,
    roots: &[ExprId],
    presets: &BTreeMap<ExprId, V>,
) -> BTreeSet<ExprId> {
    let mut seen = BTreeSet::new();
    let mut reached = BTreeSet::new();
    let mut stack = roots.to_vec();
    while let Some(id) = stack.pop() {
        if !seen.insert(id) {
            continue;
        }
        if presets.contains_key(&id) {
            reached.insert(id);
        } else {
            stack.extend(children(graph.node(id)));
        }
    }
    reached
}

/// Whether an expression reads an unknown's value.
fn reads_unknowns(graph: &Graph, root: ExprId) -> bool {
    let mut stack = vec![root];
    let mut seen = BTreeSet::new();
    while let Some(id) = stack.pop() {
        if !seen.insert(id) {
            continue;
        }
        match graph.node(id) {
            Node::Var(Var::Value(SymbolRef::Unknown(_))) => return true,
            node => stack.extend(children(node)),
        }
    }
    false
}
