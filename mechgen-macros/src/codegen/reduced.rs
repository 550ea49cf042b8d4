//! `position` and `motion_near` for a mechanism whose loops do not all come down to closed
//! forms but do once a few unknowns are known (see `symbolic::reduction`): Newton iterates on
//! those few; each evaluation solves in closed form the loops the residual depends on, then
//! evaluates the leftover loops' residual and its Jacobian by implicit differentiation (a
//! Schur complement of the loops' Jacobian). The loops nothing in the iteration reads are
//! solved once, at its solution.
//!
//! Inside the iteration a closed-form angle exists only as its unit vector (no `atan2`); the
//! angles are computed once, at the solution. The closed forms' branches are the guess's,
//! fixed before the iteration, and Newton keeps the orientation of its Jacobian, so landing
//! on another assembly is `Error::OtherBranch`. Where the closed forms cannot close at the
//! guess itself there is nothing to iterate on, and the functions fall back to Newton on
//! every unknown.
//!
//! At the solution, the loops' full Jacobian gives `condition`, the singular check and the
//! rates through its blocks (see [`block_solver`]): the closed-form loops' 2×2 blocks and the
//! reduced Jacobian Newton has already factored, with the full Jacobian factored whole only
//! where the blocks are ill-conditioned or the full one is near the singular threshold.

use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

use super::closed_forms::complex_values;
use super::docs::doc;
use super::emit::{Block, Context, Emitted, children, emit, local, reachable};
use super::{Bindings, Generator, arg};
use crate::model::{Kind, SymbolRef};
use crate::symbolic::{Case, ExprId, Graph, Node, Reduction, Step, Var};

/// The reduced iteration, up to its solution: what `position` and `motion_near` share.
struct Iteration {
    /// The check of the parameters and the input.
    check: TokenStream,
    /// The check of the guess, the parameters' bindings, the work on parameters and input
    /// alone, the guess's branches, and the iteration (falling back where it cannot start);
    /// then the iterated and closed-form unknowns at the solution, by name.
    solve: TokenStream,
    /// Every value the iteration named that is in scope after it, by node, for what follows
    /// to read instead of computing it again.
    presets: Vec<(ExprId, Ident, usize)>,
    /// The names `solve` binds, which later temporaries must not shadow.
    names: BTreeSet<String>,
    /// The variables it reads: the parameters among them are bound.
    used: BTreeSet<Var>,
    /// The branch sign of each step solved after the iteration, if it has branches.
    after_signs: Vec<Option<Ident>>,
}

/// What follows the iteration: the loops solved after it, then the loops' Jacobian and the
/// extra outputs (the rates' right-hand sides).
struct Finish {
    /// The parameters the iteration did not bind, the work that reads nothing newer than
    /// the last closed form, and those closed forms.
    solves: TokenStream,
    /// The work that reads the unknowns' rates.
    after_rates: TokenStream,
    /// The loops' Jacobian, as a matrix.
    jacobian: TokenStream,
    /// Its entries, row by row.
    entries: Vec<Emitted>,
    extra: Vec<Emitted>,
}

/// A closed-form angle: its unknown, the local holding its `(cos, sin)`, and the locals of
/// its sine and cosine.
struct Direction {
    unknown: usize,
    direction: Ident,
    trig: [Ident; 2],
}

impl Generator<'_> {
    /// `position` by the reduced iteration, and the Newton on every unknown it falls back to.
    pub(super) fn reduced_position(&self, reduction: &Reduction) -> TokenStream {
        let input = &self.model.input.name;
        let (guess, options) = (arg("guess"), arg("options"));
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let fallback = self.fallback_name();
        let fall_back = quote! {
            return self.#fallback(#input, #guess, #options);
        };
        let after = self.roots_after(reduction, &[]);
        let iteration = self.reduced_iteration(reduction, &fall_back, &after);
        let Finish {
            solves,
            jacobian,
            entries,
            ..
        } = self.finish(reduction, &iteration, &[], false);
        let Iteration { check, solve, .. } = iteration;
        let unknown_names = self.model.unknowns.iter().map(|u| &u.name);
        let (converged, factored) = (arg("converged"), arg("jacobian"));
        let after_failure = if reduction.after.is_empty() {
            ""
        } else {
            ", or a loop solved after the iteration cannot close"
        };
        let doc = doc(&format!(
            "{}\n\nErrors: a non-finite parameter, input or guess; a singular Jacobian on the \
             way or at the solution; [`mechgen::Error::OtherBranch`]; \
             [`mechgen::Error::CannotAssemble`] where the iterates press against a toggle the \
             loops cannot pass{after_failure}; no convergence within `options.max_iterations`.",
            self.reduction_doc(reduction)
        ));
        let full = self.full_position(false);
        let (factor, relative) = if reduction.after.is_empty() {
            let relative = local("block_relative");
            (
                block_solver(reduction, &self.equations.graph, &entries),
                quote!(#relative),
            )
        } else {
            (
                quote!(let #factored = ::mechgen::__private::Factored::new(#jacobian)?;),
                quote!(#factored.relative()),
            )
        };
        quote! {
            #doc
            pub fn position(
                &self,
                #input: T,
                #guess: &#unknowns,
                #options: &::mechgen::NewtonOptions<T>,
            ) -> ::core::result::Result<::mechgen::Solved<#unknowns, T>, ::mechgen::Error<T>> {
                #check
                #solve
                #solves
                #factor
                ::core::result::Result::Ok(::mechgen::Solved {
                    value: #ty { #(#unknown_names),* },
                    iterations: #converged.solved.iterations,
                    residual_norm: #converged.solved.residual_norm,
                    condition: T::one() / #relative.abs(),
                })
            }
            #full
        }
    }

    /// `motion_near` by the reduced iteration: the rates at its solution from the loops'
    /// Jacobian, from the values its last evaluation named, solved through its blocks (see
    /// [`block_solver`]).
    pub(super) fn reduced_motion_near(&self, reduction: &Reduction) -> TokenStream {
        let input = &self.model.input.name;
        let (input_dot, input_ddot) = (&self.input_dot, &self.input_ddot);
        let (guess, options, solved) = (arg("guess"), arg("options"), arg("solved"));
        let ty = &self.unknowns_type;
        let n = self.model.unknowns.len();
        let fallback = self.fallback_name();
        let motion = local("motion");
        let fall_back = quote! {
            let #solved = self.#fallback(#input, #guess, #options)?;
            let #motion = self.motion_at(#input, &#solved.value, #input_dot, #input_ddot)?;
            return ::core::result::Result::Ok(#solved.map(|_| #motion));
        };
        let right_sides: Vec<ExprId> = reduction
            .velocity_rhs
            .iter()
            .chain(&reduction.acceleration_rhs)
            .copied()
            .collect();
        let after = self.roots_after(reduction, &right_sides);
        let iteration = self.reduced_iteration(reduction, &fall_back, &after);
        let Finish {
            solves,
            after_rates,
            jacobian,
            entries,
            extra,
        } = self.finish(reduction, &iteration, &right_sides, true);
        let Iteration { check, solve, .. } = iteration;
        let (velocity_rhs, acceleration_rhs) = extra.split_at(n);
        let rate_names = &self.unknown_dots;
        let unknown_names = self.model.unknowns.iter().map(|u| &u.name);
        let (rates, accelerations) = (local("rates"), local("accelerations"));
        let (converged, factored) = (arg("converged"), arg("jacobian"));
        let graph = &self.equations.graph;
        // Through the blocks where there is no loop solved after the iteration.
        let (factor, velocity, acceleration, relative) = if reduction.after.is_empty() {
            let zeros =
                |ids: &[ExprId]| ids.iter().map(|&id| graph.is_zero(id)).collect::<Vec<_>>();
            let relative = local("block_relative");
            (
                block_solver(reduction, graph, &entries),
                block_solve(
                    reduction,
                    graph,
                    velocity_rhs,
                    &zeros(&reduction.velocity_rhs),
                ),
                block_solve(
                    reduction,
                    graph,
                    acceleration_rhs,
                    &zeros(&reduction.acceleration_rhs),
                ),
                quote!(#relative),
            )
        } else {
            (
                quote!(let #factored = ::mechgen::__private::Factored::new(#jacobian)?;),
                quote!(#factored.solve([#(#velocity_rhs),*])),
                quote!(#factored.solve([#(#acceleration_rhs),*])),
                quote!(#factored.relative()),
            )
        };
        let docs = doc(&format!(
            "Position by Newton-Raphson from `guess` (as [`Self::position`]: on the iterated \
             unknowns, the rest in closed form), then velocity and acceleration at the solution \
             for the input moving at `{input_dot}` and accelerating at `{input_ddot}` (as \
             [`Self::motion_at`]), from the loops' Jacobian evaluated once at the solution with \
             the sines, cosines and products of Newton's last evaluation: the fastest way to \
             all three without a closed form.\n\nErrors: as [`Self::position`] and \
             [`Self::motion_at`]."
        ));
        let body = quote! {
                #solve
                #solves
                #factor
                ::mechgen::__private::rates_accuracy_at(
                    T::one() / #relative.abs(),
                    ::mechgen::Order::Acceleration,
                    &#options.accuracy,
                )?;
                let #rates = #velocity;
                let [#(#rate_names),*] = ::mechgen::__private::finite(#rates, "velocity")?;
                #after_rates
                let #accelerations = #acceleration;
                let #accelerations = ::mechgen::__private::finite(#accelerations, "acceleration")?;
                ::core::result::Result::Ok(::mechgen::Solved {
                    value: ::mechgen::Motion {
                        position: #ty { #(#unknown_names),* },
                        velocity: #ty::from_array(#rates),
                        acceleration: #ty::from_array(#accelerations),
                    },
                    iterations: #converged.solved.iterations,
                    residual_norm: #converged.solved.residual_norm,
                    condition: T::one() / #relative.abs(),
                })
        };
        self.motion_near_function(docs, TokenStream::new(), check, body)
    }

    /// The private Newton on every unknown that the reduced functions fall back to.
    pub(super) fn fallback_name(&self) -> Ident {
        Ident::new("mechgen_newton_all", Span::call_site())
    }

    /// Every expression read after the iteration: the later closed forms' coefficients, the
    /// loops' Jacobian, and `extra`.
    fn roots_after(&self, reduction: &Reduction, extra: &[ExprId]) -> Vec<ExprId> {
        reduction
            .after_coefficients
            .iter()
            .flatten()
            .chain(reduction.jacobian.iter().flatten())
            .chain(extra)
            .copied()
            .collect()
    }

    /// The reduced iteration up to its solution, with `fall_back` run where it cannot start;
    /// `after` are the expressions read after it, which decide what its payload carries.
    fn reduced_iteration(
        &self,
        reduction: &Reduction,
        fall_back: &TokenStream,
        after: &[ExprId],
    ) -> Iteration {
        let graph = &self.equations.graph;
        let model = self.model;
        let input = &model.input.name;
        let (guess, options, x, converged) =
            (arg("guess"), arg("options"), arg("x"), arg("converged"));
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
        // the last iterate's through Newton's small steps instead of calling `sin_cos` again.
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

        let scale = magnitude_values.iter().map(|m| {
            let m = m.receiver();
            quote!(#m.abs())
        });
        // The magnitudes of fixed lengths are summed once, before the iteration.
        let fixed_scale = !magnitudes.iter().any(|&m| reads_unknowns(graph, m));
        let scale_local = arg("scale");
        let (scale_before, scale_field) = if fixed_scale {
            (
                quote!(let #scale_local = #(#scale)+*;),
                quote!(#scale_local),
            )
        } else {
            (TokenStream::new(), quote!(scale: #(#scale)+*))
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
                payload: [T::nan(); #payload_count],
            };
            let #converged = match ::mechgen::__private::newton(
                #input,
                [#(#guess.#iterated),*],
                #options,
                true,
                |#x: &[T; #n]| {
                    let [#(#iterated),*] = *#x;
                    #(#body)*
                    #(let #entry_names = #entry_values;)*
                    #schur
                    ::mechgen::__private::Linearisation {
                        residual: [#(#residual),*],
                        jacobian: #jacobian,
                        #scale_field,
                        payload: [#(#payload),*],
                    }
                },
            ) {
                // Only the guess can make the evaluation undefined (a closed form that does
                // not close there): the iteration cannot start.
                ::core::result::Result::Err(::mechgen::Error::NonFinite { .. }) => {
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

    /// After the iteration: the loops solved once at its solution, then the loops' Jacobian
    /// and `extra`, staged so that with `rates` what reads the unknowns' rates comes last.
    fn finish(
        &self,
        reduction: &Reduction,
        iteration: &Iteration,
        extra: &[ExprId],
        rates: bool,
    ) -> Finish {
        let input = &self.model.input.name;
        let after = &reduction.after;
        let last = after.len();
        let mut stage_of = vec![0; self.model.unknowns.len()];
        for (k, step) in after.iter().enumerate() {
            step.unknowns.iter().for_each(|&u| stage_of[u] = k + 1);
        }
        let stage = |var: Var| match var {
            Var::Value(SymbolRef::Unknown(u)) => stage_of[u],
            Var::Rate(SymbolRef::Unknown(_)) if rates => last + 1,
            _ => 0,
        };
        let directions = self.directions(after);
        let presets: Vec<(ExprId, Ident, usize)> = iteration
            .presets
            .iter()
            .cloned()
            .chain(
                self.trig_presets(&directions)
                    .into_iter()
                    .map(|(u, id, name)| (id, name, stage_of[u])),
            )
            .collect();
        let entries: Vec<ExprId> = self.roots_after(reduction, extra);
        let (bindings, statements, outputs) = self.block_after(
            &entries,
            &presets,
            &stage,
            iteration.names.iter().cloned(),
            &iteration.used,
            last + 2,
        );
        let mut outputs = outputs.into_iter();
        let mut solves = vec![bindings];
        let failure = arg("failure");
        for (k, step) in after.iter().enumerate() {
            let computed = &statements[k];
            let values: Vec<Emitted> = outputs
                .by_ref()
                .take(step.case.coefficients().len())
                .collect();
            let (pattern, call) =
                self.closed_form_call(step, &values, iteration.after_signs[k].as_ref());
            let trig = self.trig_bindings(&directions, step);
            let angles = directions
                .iter()
                .filter(|d| step.unknowns.contains(&d.unknown))
                .map(|d| self.angle_near_guess(d.unknown, &d.direction));
            solves.push(quote! {
                #(#computed)*
                let #pattern = #call.map_err(|#failure| #failure.at(#input))?;
                #trig
                #(#angles)*
            });
        }
        let computed = &statements[last];
        solves.push(quote!(#(#computed)*));
        let after_rates = &statements[last + 1];
        let n = self.model.unknowns.len();
        let jacobian: Vec<Emitted> = outputs.by_ref().take(n * n).collect();
        Finish {
            solves: quote!(#(#solves)*),
            after_rates: quote!(#(#after_rates)*),
            jacobian: super::matrix(&jacobian, n),
            entries: jacobian,
            extra: outputs.collect(),
        }
    }

    /// The closed-form angles of `steps`, in order.
    fn directions(&self, steps: &[Step]) -> Vec<Direction> {
        steps
            .iter()
            .flat_map(solved_angles)
            .map(|&u| {
                let stem = self.model.unknowns[u].name.unraw().to_string();
                Direction {
                    unknown: u,
                    direction: self.direction(u),
                    trig: [local(&format!("sin_{stem}")), local(&format!("cos_{stem}"))],
                }
            })
            .collect()
    }

    /// Each branching step's sign at the guess, by the sign `branch_of` would read, from the
    /// guess's values, the `hoisted` values (the other generated names in scope are
    /// `reserved`), and the iterated angles' `turnings`, which this primes: the first
    /// evaluation, at the guess, then rotates their sines and cosines by nothing. Returns the
    /// statements, the variables they read, and each step's sign local, if it branches.
    fn guess_signs(
        &self,
        steps: &[&Step],
        hoisted: &[(ExprId, Ident, usize)],
        reserved: &BTreeSet<String>,
        turnings: &BTreeMap<usize, Ident>,
    ) -> (Vec<TokenStream>, BTreeSet<Var>, Vec<Option<Ident>>) {
        let graph = &self.equations.graph;
        let guess = arg("guess");
        let unknown = |u: usize| &self.model.unknowns[u].name;
        let mut sign_statements = Vec::new();
        let mut sign_used = BTreeSet::new();
        let mut signs = Vec::new();
        for (s, step) in steps.iter().enumerate() {
            let Some(function) = sign_function(&step.case) else {
                signs.push(None);
                continue;
            };
            let needed = sign_coefficients(&step.case);
            let read = reachable(graph, &needed);
            let mut presets = hoisted.to_vec();
            let mut primes = Vec::new();
            for (&u, turning) in turnings {
                let stem = unknown(u).unraw().to_string();
                let [sin, cos] = [(0, "sin"), (1, "cos")].map(|(k, prefix)| {
                    let id = trig_nodes(graph, u)[k].filter(|id| read[id.index()])?;
                    let name = local(&format!("{prefix}_{stem}"));
                    presets.push((id, name.clone(), 0));
                    Some(name)
                });
                if sin.is_some() || cos.is_some() {
                    let [sin, cos] =
                        [sin, cos].map(|name| name.map_or(quote!(_), |name| quote!(#name)));
                    let name = unknown(u);
                    primes.push(quote!(let (#sin, #cos) = #turning.sin_cos(#guess.#name);));
                }
            }
            let context = Context {
                reserved,
                presets: &presets,
                stage: &|_| 0,
            };
            let block = emit(graph, &needed, &|var| self.var_name(var), &context);
            let unknowns = block.used.iter().filter_map(|&var| match var {
                Var::Value(SymbolRef::Unknown(u)) => {
                    let name = unknown(u);
                    Some(quote!(let #name = #guess.#name;))
                }
                _ => None,
            });
            let statements = block.statements.concat();
            let vectors = complex_values(&block.outputs);
            let first = unknown(step.unknowns[0]);
            let sign = local(&format!("sign{s}"));
            sign_statements.push(quote! {
                let #sign = {
                    #(#primes)*
                    #(#unknowns)*
                    #(#statements)*
                    ::mechgen::Branch::from_sign(
                        ::mechgen::closed::#function(#(#vectors),*, #guess.#first),
                    )
                    .sign::<T>()
                };
            });
            sign_used.extend(block.used);
            signs.push(Some(sign));
        }
        (sign_statements, sign_used, signs)
    }

    /// The sine and cosine nodes of the closed-form angles, each with its unknown and the
    /// local that holds it.
    fn trig_presets(&self, directions: &[Direction]) -> Vec<(usize, ExprId, Ident)> {
        let graph = &self.equations.graph;
        directions
            .iter()
            .flat_map(|d| {
                trig_nodes(graph, d.unknown)
                    .into_iter()
                    .zip(&d.trig)
                    .filter_map(|(id, name)| Some((d.unknown, id?, name.clone())))
            })
            .collect()
    }

    /// `let (sin_q, cos_q) = (direction_q.y, direction_q.x);` for the angles `step` solves.
    fn trig_bindings(&self, directions: &[Direction], step: &Step) -> TokenStream {
        let bindings = directions
            .iter()
            .filter(|d| step.unknowns.contains(&d.unknown))
            .map(|d| {
                let (direction, [sin, cos]) = (&d.direction, &d.trig);
                quote!(let (#sin, #cos) = (#direction.y, #direction.x);)
            });
        quote!(#(#bindings)*)
    }

    /// The pattern that binds a closed form's results (lengths by name, angles as
    /// `direction_q`) and the call to its `atan2`-free runtime solver.
    fn closed_form_call(
        &self,
        step: &Step,
        values: &[Emitted],
        sign: Option<&Ident>,
    ) -> (TokenStream, TokenStream) {
        let vectors = complex_values(values);
        let sign = sign.map(|sign| quote!(, #sign));
        let [a, b] = step.unknowns.map(|u| &self.model.unknowns[u].name);
        let [direction_a, direction_b] = step.unknowns.map(|u| self.direction(u));
        let (function, pattern) = match step.case {
            Case::TwoLengths { .. } => ("two_lengths", quote!([#a, #b])),
            Case::TwoAngles { .. } => ("two_directions", quote!((#direction_a, #direction_b))),
            Case::LengthAndOwnAngle { .. } => {
                ("length_and_own_direction", quote!((#a, #direction_b)))
            }
            Case::LengthAndOtherAngle { .. } => {
                ("length_and_other_direction", quote!((#a, #direction_b)))
            }
        };
        let function = Ident::new(function, Span::call_site());
        (
            pattern,
            quote!(::mechgen::closed::#function(#(#vectors),* #sign)),
        )
    }

    /// `let q = …;`: the angle of `direction` within half a turn of the guess's, as Newton
    /// on every unknown would continue it from there. The direction is a unit vector, so its
    /// angle is `unit_angle`'s (an arc sine or cosine, within rounding of `atan2`), and an
    /// offset under 3 rad from the guess (the common case) needs no whole turns taken off:
    /// `round` would give zero there.
    fn angle_near_guess(&self, unknown: usize, direction: &Ident) -> TokenStream {
        let name = &self.model.unknowns[unknown].name;
        let guess = arg("guess");
        let (turn, offset) = (local("turn"), local("offset"));
        quote! {
            let #name = {
                let #offset = ::mechgen::__private::unit_angle(#direction.y, #direction.x)
                    - #guess.#name;
                #guess.#name
                    + if #offset.abs() < T::constant(3.0) {
                        #offset
                    } else {
                        let #turn = T::constant(::core::f64::consts::TAU);
                        #offset - (#offset / #turn).round() * #turn
                    }
            };
        }
    }

    /// The docs' account of the reduction: which unknowns Newton iterates on, which loops are
    /// solved in closed form for which, and the stopping rules.
    fn reduction_doc(&self, reduction: &Reduction) -> String {
        let input = &self.model.input.name;
        let name = |u: usize| format!("`{}`", self.model.unknowns[u].name.unraw());
        let iterated = list(reduction.iterated.iter().map(|&u| name(u)).collect());
        let loops = |ls: &[usize]| list(ls.iter().map(|l| format!("loop {}", l + 1)).collect());
        let residual_loops = loops(&reduction.residual_loops);
        let describe = |steps: &[Step]| {
            list(
                steps
                    .iter()
                    .map(|step| {
                        format!(
                            "loop {} for {} ({})",
                            step.loop_index + 1,
                            list(step.unknowns.iter().map(|&u| name(u)).collect()),
                            step.case.description()
                        )
                    })
                    .collect(),
            )
        };
        let after = if reduction.after.is_empty() {
            String::new()
        } else {
            format!(
                " At the solution it then solves, once, {}.",
                describe(&reduction.after)
            )
        };
        format!(
            "Solves the loops for the unknowns at `{input}` by a safeguarded Newton-Raphson \
             from `guess` (see `mechgen::__private::newton`: halved steps, a certified root, \
             stagnation reported) on {iterated} alone: each evaluation solves, in closed form \
             and in this order, {}, then {residual_loops} gives the residual Newton drives to \
             zero, with its Jacobian from the loops' by implicit differentiation (a Schur \
             complement).{after}\n\n\
             It keeps to the guess's assembly: each loop solved in closed form stays on the \
             branch the guess is on (by the sign its closed form documents), and Newton keeps \
             the orientation (the determinant's sign) of its own Jacobian; landing on another \
             assembly is [`mechgen::Error::OtherBranch`], never a silent switch. Where a \
             closed form cannot close at the guess itself, there is nothing to iterate on and \
             it falls back to Newton on every unknown together.\n\n\
             The stopping rules are those of Newton on every unknown, applied to the residual \
             of {residual_loops} (the loops solved in closed form close to rounding): at most \
             the tolerance in every component, the rounding floor `16 ε Σ|r|` summed over \
             every loop's vectors, and Kantorovich's certificate on this iteration's Jacobian. \
             The returned `iterations` and `residual_norm` are this iteration's; `condition` \
             is the loops' full Jacobian's at the solution, as the accuracy contract reads it.",
            describe(&reduction.steps),
        )
    }
}

/// The reduced Jacobian `J[F,S] − J[F,Y]·J[G,Y]⁻¹·J[G,S]` from the loops' Jacobian entries
/// (`entry(r, c)`: the local holding a structurally non-zero one): the statements that
/// solve, step by step down the block-triangular `J[G,Y]`, for
/// `W_s = J[G_s,Y_s]⁻¹·(J[G_s,S] − Σ_{r<s} J[G_s,Y_r]·W_r)` (so `dY_s/dS = −W_s`), each 2×2
/// block factored once and each column a solve, skipping the columns that are structurally
/// zero; and the matrix `J[F,S] − Σ_s J[F,Y_s]·W_s`.
fn schur_complement(
    reduction: &Reduction,
    entry: &dyn Fn(usize, usize) -> Option<Ident>,
    undefined: &Ident,
) -> (TokenStream, TokenStream) {
    let iterated = &reduction.iterated;
    let steps = &reduction.steps;
    let mut statements = Vec::new();
    // w[s][j]: the local holding column j of W_s, a `[T; 2]`, if it is not zero.
    let mut w: Vec<Vec<Option<Ident>>> = Vec::new();
    // `J[r, c] − Σ_s J[r, Y_s]·W_s[.., j]` over the steps solved so far.
    let combination = |r: usize, c: usize, j: usize, w: &[Vec<Option<Ident>>]| {
        let subtracted: Vec<TokenStream> = steps
            .iter()
            .zip(w)
            .filter_map(|(step, columns)| Some((step, columns[j].as_ref()?)))
            .flat_map(|(step, column)| {
                step.unknowns.iter().enumerate().filter_map(move |(k, &y)| {
                    let d = entry(r, y)?;
                    let k = Literal::usize_unsuffixed(k);
                    Some(quote!(#d * #column[#k]))
                })
            })
            .collect();
        match (entry(r, c), subtracted.split_first()) {
            (Some(direct), _) => quote!(#direct #(- #subtracted)*),
            (None, None) => quote!(T::zero()),
            (None, Some((first, rest))) => quote!(-#first #(- #rest)*),
        }
    };
    for (s, step) in steps.iter().enumerate() {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1];
        let [[a, b], [c, d]] = rows.map(|r| {
            step.unknowns
                .map(|y| entry(r, y).map_or_else(|| quote!(T::zero()), |d| quote!(#d)))
        });
        let inner = local(&format!("inner{s}"));
        let (determinant, squares, relative, inverse, factored) = (
            local("inner_determinant"),
            local("inner_squares"),
            local("inner_relative"),
            local("inner_inverse"),
            local("inner_factored"),
        );
        // As `Factored::new` would factor it, to the bit: where the squares of the column
        // norms are normal and finite, the explicit inverse (`Singular` at or below the
        // threshold), else the scaled LU in `Factored` itself.
        statements.push(quote! {
            let #determinant = #a * #d - #b * #c;
            let #squares = (#a * #a + #c * #c) * (#b * #b + #d * #d);
            let #inner = if #squares >= T::min_positive_value() && #squares <= T::max_value() {
                let #relative = #determinant / #squares.sqrt();
                if #relative.is_nan()
                    || #relative.abs() <= ::mechgen::singular_threshold::<T>()
                {
                    return #undefined;
                }
                let #inverse = T::one() / #determinant;
                ::core::result::Result::Ok([
                    [#d * #inverse, -#b * #inverse],
                    [-#c * #inverse, #a * #inverse],
                ])
            } else {
                let ::core::result::Result::Ok(#factored) =
                    ::mechgen::__private::Factored::new([[#a, #b], [#c, #d]])
                else {
                    return #undefined;
                };
                ::core::result::Result::Err(#factored)
            };
        });
        let columns = iterated
            .iter()
            .enumerate()
            .map(|(j, &column)| {
                if !reduction.slopes[s][j] {
                    return None;
                }
                let [p, q] = rows.map(|r| combination(r, column, j, &w));
                let name = local(&format!("w{s}_{j}"));
                let (inverse, factored) = (local("inner_inverse"), local("inner_factored"));
                let (first, second) = (local("inner_p"), local("inner_q"));
                // `Factored::solve`'s sums, from zero.
                statements.push(quote! {
                    let #name = {
                        let (#first, #second) = (#p, #q);
                        match #inner {
                            ::core::result::Result::Ok(#inverse) => [
                                T::zero() + #inverse[0][0] * #first + #inverse[0][1] * #second,
                                T::zero() + #inverse[1][0] * #first + #inverse[1][1] * #second,
                            ],
                            ::core::result::Result::Err(#factored) => {
                                #factored.solve([#first, #second])
                            }
                        }
                    };
                });
                Some(name)
            })
            .collect();
        w.push(columns);
    }
    let rows = reduction
        .residual_loops
        .iter()
        .flat_map(|&l| [2 * l, 2 * l + 1])
        .map(|r| {
            let entries = iterated
                .iter()
                .enumerate()
                .map(|(j, &column)| combination(r, column, j, &w));
            quote!([#(#entries),*])
        });
    let jacobian = quote!([#(#rows),*]);
    (quote!(#(#statements)*), jacobian)
}

/// How the loops' Jacobian `J` at the solution is solved: by its blocks where that is as good
/// as factoring it whole, else factored whole. The blocks are the closed-form loops' 2×2
/// `J[G_s,Y_s]` (inverted by Cramer's rule from the last evaluation's entries) and the
/// reduced Jacobian `R = J[F,S] − J[F,Y]·J[G,Y]⁻¹·J[G,S]` that Newton factored at its
/// solution, so `|det J| = |det R|·Π|det J[G_s,Y_s]|` (`J[G,Y]` is block lower-triangular)
/// and, `det R` being its relative determinant times its column norms, `J`'s relative
/// determinant is
///
/// `|det J| / Π‖J col‖ = |rel R|·Π|det J[G_s,Y_s]|·√(Π‖R col‖² / Π‖J col‖²)`.
///
/// The blocks are used only where every `J[G_s,Y_s]` has a relative determinant of at least
/// 1/16 (so solving through them loses at most a few bits to rounding against the whole
/// `J`), the products of squared column norms are normal and finite (no overflow or
/// underflow), and `J`'s relative determinant is above twice `mechgen::singular_threshold`;
/// anywhere else `J` is factored whole, as before, which then decides `Error::Singular` by
/// its own check. So `Singular` is reported exactly where factoring `J` whole reports it: the
/// block estimate differs from that one by rounding, far less than the margin. Only its
/// magnitude is used (for `condition`), so the blocks' order does not matter.
///
/// `entries` are `J`'s, row by row. Only for a reduction with no loop solved after the
/// iteration (`J` is then `[[J[F,S], J[F,Y]], [J[G,S], J[G,Y]]]` up to the order of rows
/// and columns). Binds `blocks`, `Ok` with each block's inverse determinant or `Err` with
/// `J` factored, and `block_relative`, `J`'s relative determinant.
fn block_solver(reduction: &Reduction, graph: &Graph, entries: &[Emitted]) -> TokenStream {
    let n = reduction.jacobian.len();
    let (converged, blocks) = (arg("converged"), local("blocks"));
    let nonzero = |r: usize, c: usize| !graph.is_zero(reduction.jacobian[r][c]);
    let bindings = (0..n)
        .flat_map(|r| (0..n).map(move |c| (r, c)))
        .filter(|&(r, c)| nonzero(r, c))
        .map(|(r, c)| {
            let (local, value) = (block_entry(r, c), &entries[r * n + c]);
            quote!(let #local = #value;)
        });
    let entry = |r: usize, c: usize| block_value(graph, reduction, r, c);
    let (normal, none) = (local("block_normal"), local("block_none"));
    let inverses: Vec<Ident> = (0..reduction.steps.len())
        .map(|s| local(&format!("block_inverse{s}")))
        .collect();
    let mut statements = Vec::new();
    let mut determinants = Vec::new();
    for (s, (step, inverse)) in reduction.steps.iter().zip(&inverses).enumerate() {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1];
        let [[a, b], [c, d]] = rows.map(|r| step.unknowns.map(|y| entry(r, y)));
        let (determinant, squares) = (
            local(&format!("block_determinant{s}")),
            local(&format!("block_squares{s}")),
        );
        // |det| ≥ Π‖column‖/16, squared.
        statements.push(quote! {
            let #determinant = #a * #d - #b * #c;
            let #squares = (#a * #a + #c * #c) * (#b * #b + #d * #d);
            if !(#normal(#squares)
                && #determinant * #determinant * T::constant(256.0) >= #squares)
            {
                break 'blocks #none;
            }
            let #inverse = T::one() / #determinant;
        });
        determinants.push(determinant);
    }
    let m = reduction.iterated.len();
    let reduced = local("block_reduced");
    let kept = (0..m).map(|j| {
        let column = (0..m).map(|i| {
            let (i, j) = (Literal::usize_unsuffixed(i), Literal::usize_unsuffixed(j));
            quote!(#reduced[#i][#j] * #reduced[#i][#j])
        });
        quote!((#(#column)+*))
    });
    let full = (0..n).map(|c| {
        let squares = (0..n).filter(|&r| nonzero(r, c)).map(|r| {
            let e = block_entry(r, c);
            quote!(#e * #e)
        });
        quote!((#(#squares)+*))
    });
    let product = |factors: Vec<TokenStream>| match factors.split_first() {
        Some((first, rest)) => quote!(#first #(* #rest)*),
        None => quote!(T::one()),
    };
    let (kept, full) = (product(kept.collect()), product(full.collect()));
    let (kept_name, full_name, relative) = (
        local("block_kept"),
        local("block_full"),
        local("block_relative"),
    );
    let matrix = super::matrix(entries, n);
    quote! {
        #(#bindings)*
        let #blocks = 'blocks: {
            // (`break 'blocks ::core::…` would not parse with syn as a labelled break.)
            let #none = ::core::option::Option::None;
            let #normal = |v: T| v >= T::min_positive_value() && v <= T::max_value();
            #(#statements)*
            let #reduced = #converged.at.jacobian;
            let #kept_name = #kept;
            let #full_name = #full;
            if !(#normal(#kept_name) && #normal(#full_name)) {
                break 'blocks #none;
            }
            let #relative = #converged.jacobian.relative() #(* #determinants)*
                * (#kept_name / #full_name).sqrt();
            if !(#relative.abs() > T::constant(2.0) * ::mechgen::singular_threshold::<T>()) {
                break 'blocks #none;
            }
            ::core::option::Option::Some(((#(#inverses,)*), #relative))
        };
        let #blocks = match #blocks {
            ::core::option::Option::Some(#blocks) => ::core::result::Result::Ok(#blocks),
            ::core::option::Option::None => ::core::result::Result::Err(
                ::mechgen::__private::Factored::new(#matrix)?,
            ),
        };
        let #relative = match &#blocks {
            ::core::result::Result::Ok((_, #relative)) => *#relative,
            ::core::result::Result::Err(#full_name) => #full_name.relative(),
        };
    }
}

/// The local [`block_solver`] binds to a structurally non-zero entry of `J`.
fn block_entry(r: usize, c: usize) -> Ident {
    local(&format!("block_j{r}_{c}"))
}

/// An entry of `J` after [`block_solver`]: its local, or zero.
fn block_value(graph: &Graph, reduction: &Reduction, r: usize, c: usize) -> TokenStream {
    if graph.is_zero(reduction.jacobian[r][c]) {
        quote!(T::zero())
    } else {
        let local = block_entry(r, c);
        quote!(#local)
    }
}

/// The solution of `J·x = rhs` with [`block_solver`]'s solver: through the blocks, by
/// forward substitution down the closed-form loops for `z = J[G,Y]⁻¹·rhs[G]`, then
/// `x[S] = R⁻¹·(rhs[F] − J[F,Y]·z)`, then forward substitution again for
/// `x[Y] = J[G,Y]⁻¹·(rhs[G] − J[G,S]·x[S])`; or with `J` factored whole. `zeros` says which
/// of `rhs` are structurally zero, whose terms are left out.
fn block_solve(
    reduction: &Reduction,
    graph: &Graph,
    rhs: &[Emitted],
    zeros: &[bool],
) -> TokenStream {
    let n = reduction.jacobian.len();
    let (converged, blocks) = (arg("converged"), local("blocks"));
    let nonzero = |r: usize, c: usize| !graph.is_zero(reduction.jacobian[r][c]);
    let entry = |r: usize, c: usize| block_value(graph, reduction, r, c);
    let b: Vec<Ident> = (0..n).map(|r| local(&format!("block_b{r}"))).collect();
    let steps = &reduction.steps;
    let inverses: Vec<Ident> = (0..steps.len())
        .map(|s| local(&format!("block_inverse{s}")))
        .collect();
    // `rhs[r] − Σ J[r, c]·value(c)` over the columns whose value is known and not zero.
    let row = |r: usize, terms: &[(usize, TokenStream)]| -> Option<TokenStream> {
        let subtracted: Vec<TokenStream> = terms
            .iter()
            .filter(|(c, _)| nonzero(r, *c))
            .map(|(c, value)| {
                let e = block_entry(r, *c);
                quote!(#e * #value)
            })
            .collect();
        let br = &b[r];
        match (zeros[r], subtracted.split_first()) {
            (true, None) => None,
            (false, _) => Some(quote!(#br #(- #subtracted)*)),
            (true, Some((first, rest))) => Some(quote!(-#first #(- #rest)*)),
        }
    };
    // Step `s`'s 2×2 block solved for `[p, q]` by Cramer's rule.
    let (p, q) = (local("block_p"), local("block_q"));
    let cramer = |s: usize, step: &Step, [first, second]: [TokenStream; 2]| {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1];
        let [[a, b], [c, d]] = rows.map(|r| step.unknowns.map(|y| entry(r, y)));
        let inverse = &inverses[s];
        quote! {{
            let (#p, #q) = (#first, #second);
            [(#d * #p - #b * #q) * #inverse, (#a * #q - #c * #p) * #inverse]
        }}
    };
    let mut statements = Vec::new();
    // z = J[G,Y]⁻¹·rhs[G], step by step; a step's `None` is zero.
    let mut known: Vec<(usize, TokenStream)> = Vec::new();
    for (s, step) in steps.iter().enumerate() {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1].map(|r| row(r, &known));
        if rows.iter().all(Option::is_none) {
            continue;
        }
        let rows = rows.map(|r| r.unwrap_or_else(|| quote!(T::zero())));
        let z = local(&format!("block_z{s}"));
        let solved = cramer(s, step, rows);
        statements.push(quote!(let #z = #solved;));
        for (k, &y) in step.unknowns.iter().enumerate() {
            let k = Literal::usize_unsuffixed(k);
            known.push((y, quote!(#z[#k])));
        }
    }
    let reduced_rhs = reduction
        .residual_loops
        .iter()
        .flat_map(|&l| [2 * l, 2 * l + 1])
        .map(|r| row(r, &known).unwrap_or_else(|| quote!(T::zero())));
    let iterated = local("block_x");
    statements.push(quote!(let #iterated = #converged.jacobian.solve([#(#reduced_rhs),*]);));
    let mut value: Vec<TokenStream> = vec![quote!(T::zero()); n];
    let mut known: Vec<(usize, TokenStream)> = Vec::new();
    for (j, &u) in reduction.iterated.iter().enumerate() {
        let j = Literal::usize_unsuffixed(j);
        value[u] = quote!(#iterated[#j]);
        known.push((u, value[u].clone()));
    }
    for (s, step) in steps.iter().enumerate() {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1]
            .map(|r| row(r, &known).unwrap_or_else(|| quote!(T::zero())));
        let y = local(&format!("block_y{s}"));
        let solved = cramer(s, step, rows);
        statements.push(quote!(let #y = #solved;));
        for (k, &u) in step.unknowns.iter().enumerate() {
            let k = Literal::usize_unsuffixed(k);
            value[u] = quote!(#y[#k]);
            known.push((u, value[u].clone()));
        }
    }
    let full = local("block_full");
    let bindings = b
        .iter()
        .zip(rhs)
        .zip(zeros)
        .filter(|(_, zero)| !**zero)
        .map(|((b, value), _)| quote!(let #b = #value;));
    quote! {
        match #blocks {
            ::core::result::Result::Ok(((#(#inverses,)*), _)) => {
                #(#bindings)*
                #(#statements)*
                [#(#value),*]
            }
            ::core::result::Result::Err(#full) => #full.solve([#(#rhs),*]),
        }
    }
}

/// `a`, `a and b`, `a, b and c`.
fn list(items: Vec<String>) -> String {
    match items.len() {
        0 | 1 => items.concat(),
        n => format!("{} and {}", items[..n - 1].join(", "), items[n - 1]),
    }
}

/// The angles a step's closed form gives as unit vectors.
fn solved_angles(step: &Step) -> &[usize] {
    match step.case {
        Case::TwoLengths { .. } => &[],
        Case::TwoAngles { .. } => &step.unknowns,
        // (length, angle)
        _ => &step.unknowns[1..],
    }
}

/// The sine and cosine nodes of an unknown angle, where the graph has them.
fn trig_nodes(graph: &Graph, unknown: usize) -> [Option<ExprId>; 2] {
    let var = graph.lookup(Node::Var(Var::Value(SymbolRef::Unknown(unknown))));
    [Node::Sin, Node::Cos].map(|trig| var.and_then(|var| graph.lookup(trig(var))))
}

/// The runtime function giving a branching case's sign at a position.
fn sign_function(case: &Case) -> Option<Ident> {
    let name = match case {
        Case::TwoLengths { .. } => return None,
        Case::LengthAndOwnAngle { .. } => "length_and_own_angle_sign",
        Case::LengthAndOtherAngle { .. } => "length_and_other_angle_sign",
        Case::TwoAngles { .. } => "two_angles_sign",
    };
    Some(Ident::new(name, Span::call_site()))
}

/// The coefficients [`sign_function`] reads, flattened `(x, y)` by `(x, y)`.
fn sign_coefficients(case: &Case) -> Vec<ExprId> {
    let needed = match case {
        Case::LengthAndOwnAngle { w0, w1, .. } => [w0, w1],
        Case::LengthAndOtherAngle { k, v, .. } => [k, v],
        Case::TwoAngles { k, w1, .. } => [k, w1],
        Case::TwoLengths { .. } => return Vec::new(),
    };
    needed.into_iter().flatten().copied().collect()
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
