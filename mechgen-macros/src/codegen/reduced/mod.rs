//! `position` and `motion_near` for a mechanism whose loops do not all come down to closed
//! forms but do once a few unknowns are known (see `symbolic::reduction`): Newton iterates on
//! those few; each evaluation solves in closed form the loops the residual depends on, then
//! evaluates the leftover loops' residual and its Jacobian by implicit differentiation (a
//! Schur complement of the loops' Jacobian). The loops nothing in the iteration reads are
//! solved once, at its solution.
//!
//! Inside the iteration a closed-form angle exists only as its unit vector (no `atan2`); the
//! angles are computed once, at the solution. The closed forms' branches are the guess's,
//! fixed before the iteration, and Newton keeps the orientation of its Jacobian; as those
//! signs do not tell every assembly apart, Kantorovich's theorem decides whether the
//! solution is the guess's root (`certified_start` at the solution, on the common path;
//! `root_elsewhere` and `guess_certified` at the guess, out of line), and where it certainly
//! is not, Newton on every unknown answers from the guess. Where the closed forms cannot
//! close at the guess itself there is nothing to iterate on, and the functions fall back to
//! Newton on every unknown.
//!
//! At the solution, the loops' full Jacobian gives `condition`, the singular check and the
//! rates through its blocks (see [`block_solver`]): the closed-form loops' 2×2 blocks and the
//! reduced Jacobian Newton has already factored, with the full Jacobian factored whole only
//! where the blocks are ill-conditioned or the full one is near the singular threshold.
//!
//! The two public functions are put together here from what the submodules emit:
//! [`iteration`] the iteration up to its solution, with the closure Newton evaluates;
//! [`schur`] the reduced Jacobian inside that closure; [`steps`] the calls to the closed
//! forms and what they bind; [`branches`] the guess's branch of each closed form;
//! [`finish`] the loops solved after the iteration and the loops' Jacobian at its solution;
//! [`blocks`] that Jacobian solved through its blocks.

mod blocks;
mod branches;
mod finish;
mod iteration;
mod schur;
mod steps;

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

use super::docs::doc;
use super::emit::local;
use super::normalise::NewtonEntry;
use super::{Generator, arg};
use crate::symbolic::{ExprId, Reduction, Step};
use blocks::{block_solve, block_solver, column_squares};
use finish::Finish;
use iteration::Iteration;

impl Generator<'_> {
    /// `position` by the reduced iteration, and the Newton on every unknown it falls back to.
    pub(super) fn reduced_position(&self, reduction: &Reduction) -> TokenStream {
        let (input_params, input) = (self.input_params(), self.input_args());
        let (guess, options) = (arg("guess"), arg("options"));
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let fallback = self.fallback_name();
        let reduced = arg("reduced");
        let choose = self.fallback_error(&reduced);
        let fall_back = quote! {
            return self
                .#fallback(#input, #guess, #options)
                .map_err(|full| #choose);
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
        let unknown_names: Vec<_> = self.model.unknowns.iter().map(|u| &u.name).collect();
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
        let columns = column_squares(reduction, &self.equations.graph, &entries);
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
        let elsewhere = self.root_elsewhere(&columns, &relative);
        let wrapper = self.normalised_newton(NewtonEntry::Position, doc);
        let inner = NewtonEntry::Position.solve();
        let inner_doc = super::docs::doc(
            "[`Self::position`] on the mechanism it is called on: the mechanism as \
             given, or scaled by a power of two.",
        );
        quote! {
            #wrapper
            #inner_doc
            #[inline]
            fn #inner(
                &self,
                #input_params,
                #guess: &#unknowns,
                #options: &::mechgen::NewtonOptions<T>,
            ) -> ::core::result::Result<::mechgen::Solved<#unknowns, T>, ::mechgen::Error<T>> {
                #check
                #solve
                #solves
                #factor
                // Newton on every unknown from the guess where the solution is certainly not
                // the guess's root; from the solution, to polish it, where it stagnated.
                if #elsewhere {
                    return self.#fallback(#input, #guess, #options);
                }
                if ::mechgen::__private::stagnated(&#converged, #options) {
                    return self.#fallback(#input, &#ty { #(#unknown_names),* }, #options);
                }
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
        let input = self.input_args();
        let (input_dot, input_ddot) = (self.input_dot_args(), self.input_ddot_args());
        let (input_dot_text, input_ddot_text) = (self.input_dots_text(), self.input_ddots_text());
        let the_input = self.the_input();
        let (guess, options) = (arg("guess"), arg("options"));
        let ty = &self.unknowns_type;
        let n = self.model.unknowns.len();
        let reduced = arg("reduced");
        let all = Ident::new("mechgen_motion_near_all", Span::call_site());
        let failed = Ident::new("mechgen_motion_near_failed", Span::call_site());
        // One call, its arguments as they are: the error's choice is the cold function's, so
        // that no more of the failure is kept on the common path.
        let fall_back = quote! {
            return self.#failed(#input, #guess, #options, #input_dot, #input_ddot, #reduced);
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
        let unknown_names: Vec<_> = self.model.unknowns.iter().map(|u| &u.name).collect();
        let (rates, accelerations) = (local("rates"), local("accelerations"));
        let accuracy = local("accuracy");
        let (converged, factored) = (arg("converged"), arg("jacobian"));
        let graph = &self.equations.graph;
        let columns = column_squares(reduction, graph, &entries);
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
        let elsewhere = self.root_elsewhere(&columns, &relative);
        // The rates' estimate at Newton's position, its error from the residual it stopped at
        // and the full Jacobian's condition.
        let condition = quote!((T::one() / #relative.abs()));
        // The size the position's error and the rates' accuracy are stated against, once.
        let size = local("size");
        let size_value = self.accuracy_size(quote!(self));
        let accuracy_check = self.rates_check_at(
            quote!(&#jacobian),
            condition.clone(),
            "Acceleration",
            quote!(&#options.accuracy),
            quote!(#size),
            &crate::codegen::rates::PositionFrom::Newton(if self.loops_within_size() {
                quote!(#converged.position_accuracy_within_size_at(#condition))
            } else {
                quote!(#converged.position_accuracy_at(#condition, #size))
            }),
            None,
        );
        let docs = doc(&format!(
            "Position by Newton-Raphson from `guess` (as [`Self::position`]: on the iterated \
             unknowns, the rest in closed form), then velocity and acceleration at the solution \
             for {the_input} moving at `{input_dot_text}` and accelerating at `{input_ddot_text}` (as \
             [`Self::motion_at`]), from the loops' Jacobian evaluated once at the solution with \
             the sines, cosines and products of Newton's last evaluation: the fastest way to \
             all three without a closed form.\n\nErrors: as [`Self::position`] and \
             [`Self::motion_at`]."
        ));
        let body = quote! {
                #solve
                #solves
                #factor
                // Newton on every unknown from the guess where the solution is certainly not
                // the guess's root; from the solution, to polish it, where it stagnated.
                if #elsewhere {
                    return self.#all(#input, #guess, #options, #input_dot, #input_ddot);
                }
                if ::mechgen::__private::stagnated(&#converged, #options) {
                    let start = #ty { #(#unknown_names),* };
                    return self.#all(#input, &start, #options, #input_dot, #input_ddot);
                }
                let #size = #size_value;
                #accuracy_check
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
                        accuracy: #accuracy,
                    },
                    iterations: #converged.solved.iterations,
                    residual_norm: #converged.solved.residual_norm,
                    condition: T::one() / #relative.abs(),
                })
        };
        // The safeguarded solve alone: its accuracy from where Newton stopped (a stated
        // tolerance's residual, above the floor, included) and judged by the options', as on
        // the reduced path, which `motion_at` (for any position the solvers return by default,
        // judged by the default requirement) would not.
        let all_body = self.full_motion_near(&all).safeguarded;
        let all_item = self.motion_near_item(
            quote!(fn #all),
            doc(
                "[`Self::motion_near`] by Newton on every unknown from `guess`, with its rates, \
                 out of line: where the reduced iteration cannot close the loops at the guess, \
                 where its solution is certainly not the guess's root, or (from that solution) \
                 where it stagnated.",
            ),
            quote!(#[allow(unused_variables)] #[cold] #[inline(never)]),
            TokenStream::new(),
            all_body,
        );
        // Where the iteration failed, its failure says why better than the full one's, but
        // for the rates' verdict on a position the full iteration found.
        let failed_item = self.motion_near_item_with(
            quote!(fn #failed),
            doc(
                "[`Self::motion_near`] where the reduced iteration failed (`reduced`, the \
                 failure) or cannot tell: Newton on every unknown from `guess`, out of line.",
            ),
            quote!(#[cold] #[inline(never)]),
            quote!(#reduced: ::core::option::Option<::mechgen::Error<T>>,),
            TokenStream::new(),
            {
                let choose = self.fallback_error(&reduced);
                quote! {
                    self.#all(#input, #guess, #options, #input_dot, #input_ddot)
                        .map_err(|full| match full {
                            ::mechgen::Error::Inaccurate { .. } => full,
                            _ => #choose,
                        })
                }
            },
        );
        let function = self.motion_near_function(docs, TokenStream::new(), check, body);
        quote!(#function #all_item #failed_item)
    }

    /// The error where the reduced iteration failed (`reduced`, its failure, if any) and
    /// Newton on every unknown then failed too (`full`): the reduced iteration's, which says
    /// why better, but for its `CannotAssemble` against a `Singular` from a guess at which
    /// the loops close to their rounding floor. Then the mechanism assembles at the guess, and
    /// the reduced iteration's closed form missed only in rounding at the singular position
    /// the full one found (edge run seed 28, case 286727: an f32 Stephenson six-bar whose
    /// 2e-24 link is below the rounding of its 1e-16 size, the guess closing the loops to
    /// 4e-8 of it, at κ 4400, beyond f32's threshold).
    fn fallback_error(&self, reduced: &Ident) -> TokenStream {
        let (input, guess) = (self.input_args(), arg("guess"));
        let size = self.accuracy_size(quote!(self));
        quote! {
            match #reduced {
                ::core::option::Option::Some(::mechgen::Error::CannotAssemble { .. })
                    if matches!(full, ::mechgen::Error::Singular { .. })
                        && ::mechgen::__private::closes_within_rounding(
                            &self.residual(#input, #guess),
                            #size,
                        ) => full,
                _ => #reduced.unwrap_or(full),
            }
        }
    }

    /// Whether the reduced iteration's solution (the unknowns, bound by name) is certainly
    /// not the guess's root: `certified_start` cannot vouch for it from the solution's side
    /// (`columns`, the loops' Jacobian's squared column norms there; `relative`, its
    /// relative determinant), and `root_elsewhere` says so from the guess's, out of line.
    fn root_elsewhere(&self, columns: &TokenStream, relative: &TokenStream) -> TokenStream {
        let (guess, input) = (arg("guess"), self.input_args());
        let unknown_names: Vec<_> = self.model.unknowns.iter().map(|u| &u.name).collect();
        quote! {
            !::mechgen::__private::certified_start(
                &#guess.to_array(),
                &[#(#unknown_names),*],
                #columns,
                #relative,
            ) && ::mechgen::__private::root_elsewhere(
                &self.residual(#input, #guess),
                &self.jacobian(#input, #guess),
                &#guess.to_array(),
                &[#(#unknown_names),*],
            )
        }
    }

    /// The private Newton on every unknown that the reduced functions fall back to.
    pub(super) fn fallback_name(&self) -> Ident {
        Ident::new("mechgen_newton_all", Span::call_site())
    }

    /// The docs' account of the reduction: which unknowns Newton iterates on, which loops are
    /// solved in closed form for which, and the stopping rules.
    fn reduction_doc(&self, reduction: &Reduction) -> String {
        let input_text = self.inputs_text();
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
            "Solves the loops for the unknowns at `{input_text}` by a safeguarded Newton-Raphson \
             from `guess` (see `mechgen::__private::newton`: halved steps, a certified root, \
             stagnation reported) on {iterated} alone: each evaluation solves, in closed form \
             and in this order, {}, then {residual_loops} gives the residual Newton drives to \
             zero, with its Jacobian from the loops' by implicit differentiation (a Schur \
             complement).{after}{whole_turns}\n\n\
             It keeps to the guess's assembly: each loop solved in closed form stays on the \
             branch the guess is on (by the sign its closed form documents), and Newton keeps \
             the orientation (the determinant's sign) of its own Jacobian. Neither sign tells \
             every assembly apart (a loop solved in closed form that turns fast with the \
             iterated unknowns, a short link beside long ones, can carry one step to another \
             assembly of the same orientation). So Kantorovich's theorem decides: the \
             solution stands where the guess lies within the ball about it from which Newton \
             on every unknown certainly converges to it (estimated from the loops' Jacobian \
             there); where not, and the guess is certified on its own side (from the loops' \
             residual and Jacobian at the guess) with the solution outside the ball in which \
             the guess's root is the only one, Newton on every unknown from `guess` answers, \
             as it does where the reduced iteration lands on another orientation from a \
             certified guess. Landing on another assembly is \
             [`mechgen::Error::OtherBranch`], never a silent switch. Where a \
             closed form cannot close at the guess itself, there is nothing to iterate on and \
             it falls back to Newton on every unknown together.\n\n\
             The closed forms inside each evaluation round at the magnitudes of the points \
             they start from, which can exceed their own links' by far, so the reduced \
             residual can stall above the floor or short of a root: a default solve that \
             stops above the floor `16 ε Σ|r|` is polished by Newton on every unknown from \
             its solution, and one that stalls (no convergence, or a toggle it cannot pass) \
             or meets a singular Jacobian of its own (which carries the closed forms' \
             sensitivities: a link within a few roundings of the size leaves its closed \
             form's angle to rounding) is tried again by Newton on every unknown from \
             `guess`, whose verdict stands only if it finds a solution.\n\n\
             The stopping rules are those of Newton on every unknown, applied to the residual \
             of {residual_loops} (the loops solved in closed form close to rounding): at most \
             the tolerance in every component, each loop's components at the rounding floor \
             `16 ε Σ|r|` of that loop's own vectors, and Kantorovich's certificate on this \
             iteration's Jacobian. \
             The returned `iterations` and `residual_norm` are this iteration's; `condition` \
             is the loops' full Jacobian's at the solution, as the accuracy contract reads it.",
            describe(&reduction.steps),
            whole_turns = Self::WHOLE_TURNS_DOC,
        )
    }
}

/// `a`, `a and b`, `a, b and c`.
fn list(items: Vec<String>) -> String {
    match items.len() {
        0 | 1 => items.concat(),
        n => format!("{} and {}", items[..n - 1].join(", "), items[n - 1]),
    }
}
