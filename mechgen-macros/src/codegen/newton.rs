//! `position` and `motion_near`: the safeguarded Newton solve, with the work that depends
//! only on the parameters and input hoisted out of the iteration, and the rates at its
//! solution from what its last iteration computed (sines, cosines, the factored Jacobian).

use std::collections::BTreeSet;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

use super::docs::doc;
use super::emit::{Block, Emitted, local, reachable};
use super::normalise::NewtonEntry;
use super::{Bindings, Generator, arg, matrix};
use crate::model::{Kind, SymbolRef};
use crate::symbolic::{ExprId, Node, Var};

impl Generator<'_> {
    pub(super) fn position(&self) -> TokenStream {
        match &self.equations.reduction {
            Some(reduction) => self.reduced_position(reduction),
            None => self.full_position(true),
        }
    }

    /// What `position` says of a guess's angles beyond `mechgen::__private::newton`'s bound.
    pub(super) const WHOLE_TURNS_DOC: &'static str = " An angle of `guess` beyond ±16 rad is first taken \
        by whole turns to within [−π, π] (a float that large holds an angle more coarsely than \
        the accuracy stated), and so is an angle the iterates leave beyond ±17 rad (a step \
        through a nearly vanishing column can throw one many turns), which is solved on from \
        there: every angle of the solution is within ±17 rad.";

    /// Newton on every unknown together: `position` itself (`public`), or the private
    /// fallback of a reduced `position` (see `super::reduced`).
    pub(super) fn full_position(&self, public: bool) -> TokenStream {
        let (input_params, input) = (self.input_params(), self.input_args());
        let first_input = self.first_input();
        let input_text = self.inputs_text();
        let (guess, options, x, solved) = (arg("guess"), arg("options"), arg("x"), arg("solved"));
        let converged = arg("converged");
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let size_value = self.accuracy_size(quote!(self));
        let (keep_orientation, branch_check) = self.branch_keeping(
            quote!(&#solved.value),
            quote!(#converged.error_length(#size_value)),
        );
        let orientation = self.orientation(keep_orientation, None);
        let branch_doc = if keep_orientation || branch_check.is_some() {
            " It keeps to the guess's assembly branch (for one loop, the orientation of the \
             Jacobian, which tells the branches apart; for several, [`Self::branch_of`]): \
             landing on the other one is the error [`mechgen::Error::OtherBranch`], never a \
             silent switch."
        } else {
            ""
        };
        let Linearised {
            hoisted,
            closure,
            common_closure,
            ..
        } = self.linearisation(&x, &guess, None);
        let (doc, signature) = if public {
            let public_doc = doc(&format!(
                "Solves the loops for the unknowns at `{input_text}` by a safeguarded Newton-Raphson \
                 from `guess` (see `mechgen::__private::newton`: halved steps, a certified root, \
                 stagnation reported).{branch_doc}{}\n\n\
                 Errors: a non-finite parameter, input or guess; a singular Jacobian on the way; \
                 [`mechgen::Error::CannotAssemble`] where the iterates press against a toggle \
                 the loops cannot pass; no convergence within `options.max_iterations`.",
                Self::WHOLE_TURNS_DOC
            ));
            let wrapper = self.normalised_newton(NewtonEntry::Position, public_doc);
            let inner = NewtonEntry::Position.solve();
            let doc = doc(
                "[`Self::position`] on the mechanism it is called on: the mechanism as \
                 given, or scaled by a power of two.",
            );
            (quote!(#wrapper #doc), quote!(#[inline(always)] fn #inner))
        } else {
            let fallback = self.fallback_name();
            let doc = doc(
                "Newton-Raphson on every unknown together, as for a mechanism without a \
                 reduction: what [`Self::position`] falls back to where its closed forms \
                 cannot close at the guess.",
            );
            (doc, quote!(fn #fallback))
        };
        let result = quote! {
            ::core::result::Result<::mechgen::Solved<#unknowns, T>, ::mechgen::Error<T>>
        };
        let signature_args = quote! {
            (
                &self,
                #input_params,
                #guess: &#unknowns,
                #options: &::mechgen::NewtonOptions<T>,
            ) -> #result
        };
        let finish = quote! {
            let #solved = #converged.solved.map(#ty::from_array);
            #branch_check
            ::core::result::Result::Ok(#solved)
        };
        let assembles = self.assembles();
        let safeguarded = quote! {
            #hoisted
            let #converged = ::mechgen::__private::newton(
                #first_input,
                #guess.to_array(),
                #options,
                #orientation,
                #assembles,
                #closure,
            )?;
            #finish
        };
        if !public {
            // The reduced `position`'s fallback is itself the rare path.
            return quote! {
                #doc
                #signature #signature_args {
                    self.mechgen_check_finite(#input)?;
                    #safeguarded
                }
            };
        }
        // Newton's common path inline; anything else is the safeguarded solve's to decide,
        // from the guess again, out of line.
        let aside = Ident::new("mechgen_position_safeguarded", Span::call_site());
        let aside_doc = super::docs::doc(
            "[`Self::position`] by the safeguarded Newton alone (`mechgen::__private::newton`), \
             out of line: what it falls back to where Newton's common path cannot decide.",
        );
        quote! {
            #doc
            #signature #signature_args {
                self.mechgen_check_finite(#input)?;
                #hoisted
                ::mechgen::__private::newton_common(
                    #guess.to_array(),
                    #options,
                    #orientation,
                    #common_closure,
                    #[inline(always)]
                    |#converged| -> #result { #finish },
                    || self.#aside(#input, #guess, #options),
                )
            }
            #aside_doc
            #[cold]
            #[inline(never)]
            fn #aside #signature_args {
                #safeguarded
            }
        }
    }

    /// The closure that tells a stalled Newton whether the loops can close at the input in
    /// the guess's assembly (the one Newton keeps to): for one loop in closed form, the
    /// closed form on the guess's branch (Newton then says `NoConvergence`, not "outside the
    /// range of motion", for a guess that is merely far). With several loops in closed form
    /// the guess's branches, read off a guess far from any assembly, need not be the ones a
    /// caller means: `false` only where no assembly closes (every combination of branches
    /// cannot assemble), and otherwise `None`, so that Newton judges by the condition.
    /// `None` without closed forms.
    fn assembles(&self) -> TokenStream {
        let Ok(steps) = self.equations.closed_form.as_deref() else {
            return quote!(|| ::core::option::Option::None);
        };
        let input = self.input_args();
        let guess = arg("guess");
        let branching = steps.iter().filter(|s| s.case.has_branches()).count();
        if self.model.loops.len() == 1 {
            let assembled = if branching > 0 {
                quote!(self.assemble(#input, self.branch_of(#input, #guess)))
            } else {
                quote!(self.assemble(#input))
            };
            return quote!(|| ::core::option::Option::Some(#assembled.is_ok()));
        }
        let (branches, combination) = (arg("branches"), arg("values"));
        let (index, branch) = (local("index"), arg("branch"));
        let (declare, choose, argument) = match branching {
            0 => (TokenStream::new(), TokenStream::new(), TokenStream::new()),
            1 => (
                quote!(let mut #branches = ::mechgen::Branch::Open;),
                quote! {
                    #branches = if #combination & 1 == 1 {
                        ::mechgen::Branch::Crossed
                    } else {
                        ::mechgen::Branch::Open
                    };
                },
                quote!(, #branches),
            ),
            k => (
                quote!(let mut #branches = [::mechgen::Branch::Open; #k];),
                quote! {
                    for (#index, #branch) in #branches.iter_mut().enumerate() {
                        *#branch = if #combination >> #index & 1 == 1 {
                            ::mechgen::Branch::Crossed
                        } else {
                            ::mechgen::Branch::Open
                        };
                    }
                },
                quote!(, #branches),
            ),
        };
        let combinations = 1u32 << branching;
        quote! {
            || {
                #declare
                for #combination in 0..#combinations {
                    #choose
                    if !::core::matches!(
                        self.assemble(#input #argument),
                        ::core::result::Result::Err(::mechgen::Error::CannotAssemble { .. })
                    ) {
                        return ::core::option::Option::None;
                    }
                }
                ::core::option::Option::Some(false)
            }
        }
    }

    /// Whether Newton keeps to the guess's branch through the Jacobian's orientation (one
    /// loop, or loops none of which has a closed form with branches: the sign of the
    /// determinant cannot change along a branch, so a change means another assembly), and
    /// the check after it otherwise (several loops with closed-form branches), comparing
    /// `solution`, whose estimated error is the length `error`, with the guess.
    fn branch_keeping(
        &self,
        solution: TokenStream,
        error: TokenStream,
    ) -> (bool, Option<TokenStream>) {
        let input = self.input_args();
        let guess = arg("guess");
        let branching = self.equations.closed_form.as_ref().map_or(0, |steps| {
            steps.iter().filter(|s| s.case.has_branches()).count()
        });
        let keep_orientation = self.model.loops.len() == 1 || branching == 0;
        let check = (branching > 0 && !keep_orientation).then(|| {
            quote! {
                if !self.mechgen_keeps_branches(#input, #guess, #solution, #error) {
                    return ::core::result::Result::Err(::mechgen::Error::OtherBranch);
                }
            }
        });
        (keep_orientation, check)
    }

    /// `Orientation::Kept` (or `Orientation::Free`, where `keep` is false) with which of
    /// `unknowns` are angles (every unknown where `None`).
    pub(super) fn orientation(&self, keep: bool, unknowns: Option<&[usize]>) -> TokenStream {
        let all: Vec<usize> = (0..self.model.unknowns.len()).collect();
        let angles = unknowns
            .unwrap_or(&all)
            .iter()
            .map(|&u| self.model.unknowns[u].kind == crate::model::Kind::Angle);
        if keep {
            quote!(::mechgen::__private::Orientation::Kept { angles: [#(#angles),*] })
        } else {
            quote!(::mechgen::__private::Orientation::Free { angles: [#(#angles),*] })
        }
    }

    /// `motion_near(input, &guess, &options, rate, acceleration)`: Newton from `guess`, then
    /// the rates at its solution with the sines, cosines and factored Jacobian of its last
    /// evaluation, so nothing is evaluated or factored twice.
    pub(super) fn motion_near(&self) -> TokenStream {
        if let Some(reduction) = &self.equations.reduction {
            return self.reduced_motion_near(reduction);
        }
        let (input_dot_text, input_ddot_text) = (self.input_dots_text(), self.input_ddots_text());
        let the_input = self.the_input();
        let docs = doc(&format!(
            "Position by Newton-Raphson from `guess` (as [`Self::position`]), then velocity \
             and acceleration at the solution for {the_input} moving at `{input_dot_text}` and \
             accelerating at `{input_ddot_text}` (as [`Self::motion_at`]), reusing the sines, \
             cosines and factored Jacobian of Newton's last evaluation: the fastest way to all \
             three without a closed form.\n\nErrors: as [`Self::position`] and \
             [`Self::motion_at`]."
        ));
        let aside = Ident::new("mechgen_motion_near_safeguarded", Span::call_site());
        let FullMotionNear {
            common,
            safeguarded,
        } = self.full_motion_near(&aside);
        let wrapper = self.normalised_newton(NewtonEntry::MotionNear, docs);
        let inner = NewtonEntry::MotionNear.solve();
        let hot = self.motion_near_item(
            quote!(fn #inner),
            normalised_motion_near_doc(),
            quote!(#[allow(unused_variables)] #[inline(always)]),
            self.check_finite_with_rates(),
            common,
        );
        let aside_docs = doc(
            "[`Self::motion_near`] by the safeguarded Newton alone (`mechgen::__private::newton`), \
             out of line: what it falls back to where Newton's common path cannot decide. Its \
             arguments are checked.",
        );
        let cold = self.motion_near_item(
            quote!(fn #aside),
            aside_docs,
            quote!(#[allow(unused_variables)] #[cold] #[inline(never)]),
            TokenStream::new(),
            safeguarded,
        );
        quote!(#wrapper #hot #cold)
    }

    /// `motion_near`'s bodies by Newton on every unknown together: its common path inline,
    /// falling back to `aside` (with `motion_near`'s signature), and the safeguarded solve
    /// alone, which `aside` is for a mechanism without a reduction, and for a reduced one
    /// what its iteration falls back to (`super::reduced`): in both, the rates' accuracy
    /// from Newton's own stop (a stated tolerance's residual included) and the options'.
    pub(super) fn full_motion_near(&self, aside: &Ident) -> FullMotionNear {
        self.full_motion_near_with(aside, None)
    }

    /// [`Self::full_motion_near`], its size and aspect read from `constants` (a
    /// `mechgen::__private::NewtonConstants` argument) where given, instead of computed from
    /// the dimensions: a `{Name}Newton`'s, computed once by the same expressions.
    pub(super) fn full_motion_near_with(
        &self,
        aside: &Ident,
        constants: Option<&Ident>,
    ) -> FullMotionNear {
        let input = self.input_args();
        let first_input = self.first_input();
        let (input_dot, input_ddot) = (self.input_dot_args(), self.input_ddot_args());
        let (guess, options, x) = (arg("guess"), arg("options"), arg("x"));
        let (converged, jacobian) = (arg("converged"), arg("jacobian"));
        let (rates, accelerations) = (local("rates"), local("accelerations"));
        let accuracy = local("accuracy");
        let ty = &self.unknowns_type;
        let n = self.model.unknowns.len();
        let Linearised {
            hoisted,
            closure,
            common_closure,
            named,
            fixed_scale,
            used: bound,
        } = self.linearisation(&x, &guess, constants);
        // A `{Name}Newton` found the scale finite when it was made.
        let common_path = if constants.is_some() && fixed_scale && self.prepared_scale().is_some() {
            quote!(newton_common_at_finite_scale)
        } else {
            quote!(newton_common)
        };
        let size = local("size");
        let (keep_orientation, branch_check) = self.branch_keeping(
            quote!(&#ty::from_array(#converged.solved.value)),
            quote!(#converged.error_length(#size)),
        );
        let orientation = self.orientation(keep_orientation, None);

        // The rates read the hoisted values and the last iteration's payload.
        let presets: Vec<(ExprId, Ident, usize)> = named
            .iter()
            .map(|(id, name, _)| (*id, name.clone(), 0))
            .collect();
        let payload_names = named
            .iter()
            .filter(|(_, _, stage)| *stage == 1)
            .map(|(_, name, _)| name);
        let eq = self.equations;
        let entries: Vec<ExprId> = eq
            .velocity_rhs
            .iter()
            .chain(&eq.acceleration_rhs)
            .copied()
            .collect();
        let stage = |var: Var| usize::from(matches!(var, Var::Rate(SymbolRef::Unknown(_))));
        // Its own temporaries must not shadow the payload's.
        let taken = named.iter().map(|(_, name, _)| name.to_string());
        let (bindings, statements, outputs) =
            self.block_after(&entries, &presets, &stage, taken, &bound, 2);
        let (before, after) = (&statements[0], &statements[1]);
        let (velocity_rhs, acceleration_rhs) = outputs.split_at(n);
        let names = self.model.unknowns.iter().map(|u| &u.name);
        let rate_names = &self.unknown_dots;
        // The size the rates' accuracy weighs the columns against, computed before the
        // iteration: one value to keep through it rather than the lengths.
        let size = local("size");
        let size_value = match constants {
            Some(constants) => quote!(#constants.size),
            None => self.accuracy_size(quote!(self)),
        };
        let accuracy_check = self.rates_check_at(
            quote!(&#converged.at.jacobian),
            quote!(#converged.solved.condition),
            "Acceleration",
            quote!(&#options.accuracy),
            quote!(#size),
            &super::rates::PositionFrom::Newton(if self.loops_within_size() {
                quote!(#converged.position_accuracy_within_size_at(#converged.solved.condition))
            } else {
                quote!(#converged.position_accuracy(#size))
            }),
            constants.map(|constants| quote!(#constants.aspect)),
        );
        // From Newton's solution on: the same on either path.
        let rates_body = quote! {
                #branch_check
                #accuracy_check
                let [#(#names),*] = #converged.solved.value;
                let [#(#payload_names),*] = #converged.at.payload;
                let #jacobian = #converged.jacobian;
                #bindings
                #(#before)*
                let #rates = #jacobian.solve([#(#velocity_rhs),*]);
                let [#(#rate_names),*] = ::mechgen::__private::finite(#rates, "velocity")?;
                #(#after)*
                let #accelerations = #jacobian.solve([#(#acceleration_rhs),*]);
                let #accelerations = ::mechgen::__private::finite(#accelerations, "acceleration")?;
                ::core::result::Result::Ok(#converged.solved.map(|value| ::mechgen::Motion {
                    position: #ty::from_array(value),
                    velocity: #ty::from_array(#rates),
                    acceleration: #ty::from_array(#accelerations),
                    accuracy: #accuracy,
                }))
        };
        // Newton's common path inline; anything else is the safeguarded solve's to decide,
        // from the guess again, out of line.
        let common = quote! {
                #hoisted
                let #size = #size_value;
                ::mechgen::__private::#common_path(
                    #guess.to_array(),
                    #options,
                    #orientation,
                    #common_closure,
                    #[inline(always)]
                    |#converged| -> ::core::result::Result<
                        ::mechgen::Solved<::mechgen::Motion<#ty<T>, T>, T>,
                        ::mechgen::Error<T>,
                    > {
                        #rates_body
                    },
                    || self.#aside(#input, #guess, #options, #input_dot, #input_ddot),
                )
        };
        let assembles = self.assembles();
        let safeguarded = quote! {
                #hoisted
                let #size = #size_value;
                let #converged = ::mechgen::__private::newton(
                    #first_input,
                    #guess.to_array(),
                    #options,
                    #orientation,
                    #assembles,
                    #closure,
                )?;
                #rates_body
        };
        FullMotionNear {
            common,
            safeguarded,
        }
    }

    /// The `motion_near` item around its body: the signature, the check of the arguments
    /// (`check`, then the input's rate and acceleration), then `body`.
    pub(super) fn motion_near_function(
        &self,
        docs: TokenStream,
        attrs: TokenStream,
        check: TokenStream,
        body: TokenStream,
    ) -> TokenStream {
        let (input_dots, input_ddots) = (&self.input_dots, &self.input_ddots);
        let dot_labels = input_dots.iter().map(|dot| format!("input rate `{dot}`"));
        let ddot_labels = input_ddots
            .iter()
            .map(|ddot| format!("input acceleration `{ddot}`"));
        let check = quote! {
            #check
            ::mechgen::__private::check_all_finite(
                [#(#input_dots,)* #(#input_ddots),*],
                &[#(#dot_labels,)* #(#ddot_labels),*],
            )?;
        };
        let wrapper = self.normalised_newton(NewtonEntry::MotionNear, docs);
        let inner = NewtonEntry::MotionNear.solve();
        let solve = self.motion_near_item(
            quote!(fn #inner),
            normalised_motion_near_doc(),
            quote!(#attrs #[inline]),
            check,
            body,
        );
        quote!(#wrapper #solve)
    }

    /// An item with `motion_near`'s signature, named and scoped by `name` (`pub fn
    /// motion_near`): `check`, then `body`.
    pub(super) fn motion_near_item(
        &self,
        name: TokenStream,
        docs: TokenStream,
        attrs: TokenStream,
        check: TokenStream,
        body: TokenStream,
    ) -> TokenStream {
        self.motion_near_item_with(name, docs, attrs, TokenStream::new(), check, body)
    }

    /// [`Generator::motion_near_item`] with `extra` parameters after `motion_near`'s.
    pub(super) fn motion_near_item_with(
        &self,
        name: TokenStream,
        docs: TokenStream,
        attrs: TokenStream,
        extra: TokenStream,
        check: TokenStream,
        body: TokenStream,
    ) -> TokenStream {
        let input_params = self.input_params();
        let (input_dot_params, input_ddot_params) =
            (self.input_dot_params(), self.input_ddot_params());
        let (guess, options) = (arg("guess"), arg("options"));
        let (unknowns, _, _) = self.signature_types();
        quote! {
            #docs
            #attrs
            #name(
                &self,
                #input_params,
                #guess: &#unknowns,
                #options: &::mechgen::NewtonOptions<T>,
                #input_dot_params,
                #input_ddot_params,
                #extra
            ) -> ::core::result::Result<
                ::mechgen::Solved<::mechgen::Motion<#unknowns, T>, T>,
                ::mechgen::Error<T>,
            > {
                #check
                #body
            }
        }
    }

    /// The Newton iteration's evaluation as a closure over the iterate `x`, with everything
    /// that depends only on the parameters and input computed once, before the closure. The
    /// closure hands back, as its payload, every value it named (sines, cosines, shared
    /// products), for the rates at the solution.
    fn linearisation(&self, x: &Ident, guess: &Ident, constants: Option<&Ident>) -> Linearised {
        let n = self.model.unknowns.len();
        let eq = self.equations;
        let entries: Vec<ExprId> = eq
            .residual
            .iter()
            .chain(eq.jacobian.iter().flatten())
            .chain(&eq.magnitudes)
            .copied()
            .collect();
        let stage = |var: Var| usize::from(matches!(var, Var::Value(SymbolRef::Unknown(_))));
        // Each unknown angle's sine and cosine come from a `Turning`, which rotates its last
        // `sin_cos` through the small way Newton has moved the angle since instead of calling
        // `sin_cos` again.
        let graph = &self.equations.graph;
        let read = reachable(graph, &entries);
        let mut turned: Vec<(ExprId, Ident, usize)> = Vec::new();
        let mut angles = Vec::new();
        for (u, unknown) in self.model.unknowns.iter().enumerate() {
            let Some(var) = graph.lookup(Node::Var(Var::Value(SymbolRef::Unknown(u)))) else {
                continue;
            };
            let stem = unknown.name.unraw().to_string();
            let names = trig_names(graph, var, &stem, &read, 1, &mut turned);
            if names.iter().all(Option::is_none) {
                continue;
            }
            let [sin, cos] = names.map(|name| name.map_or(quote!(_), |name| quote!(#name)));
            angles.push((stem, &unknown.name, sin, cos));
        }
        // Each input's sine and cosine, once per solve, from the runtime's inline `sin_cos`
        // rather than the platform's call.
        let mut presets: Vec<(ExprId, Ident, usize)> = Vec::new();
        let mut input_trig = TokenStream::new();
        for (i, input) in self.inputs().into_iter().enumerate() {
            let Some(var) = graph.lookup(Node::Var(Var::Value(SymbolRef::Input(i)))) else {
                continue;
            };
            let stem = input.unraw().to_string();
            let names = trig_names(graph, var, &stem, &read, 0, &mut presets);
            if names.iter().any(Option::is_some) {
                let [sin, cos] = names.map(|name| name.map_or(quote!(_), |name| quote!(#name)));
                input_trig
                    .extend(quote!(let (#sin, #cos) = ::mechgen::__private::sin_cos(#input);));
            }
        }
        // Several angles share one `Turnings`, whose fresh sines and cosines come from one
        // pass of vector arithmetic; a lone angle has its `Turning`.
        // The common path's evaluation (`newton_common`) computes the pairs at the guess,
        // before its iteration, and only turns them inside it (`Started`: an angle that
        // moves too far for a turn gives NaN, which leaves the solve to the safeguarded
        // Newton), so that its iteration makes no call.
        // The guess's angles, bound by their names (the closure's own bindings shadow them).
        let turned_names: Vec<&Ident> = angles.iter().map(|(_, name, _, _)| *name).collect();
        let guess_pattern = self.model.unknowns.iter().map(|u| {
            if turned_names.contains(&&u.name) {
                let name = &u.name;
                quote!(#name)
            } else {
                quote!(_)
            }
        });
        let at_guess = quote!(let [#(#guess_pattern),*] = #guess.to_array(););
        let (turnings, turns, common_turnings, common_turns) = match angles.as_slice() {
            [(stem, name, sin, cos)] => {
                let turning = local(&format!("turning_{stem}"));
                (
                    quote!(let mut #turning = ::mechgen::__private::Turning::new();),
                    quote!(let (#sin, #cos) = #turning.sin_cos(#name);),
                    quote! {
                        #at_guess
                        let mut #turning = ::mechgen::__private::Started::at([#name]);
                    },
                    quote!(let ([#sin], [#cos]) = #turning.sin_cos([#name]);),
                )
            }
            _ if angles.is_empty() => (
                TokenStream::new(),
                TokenStream::new(),
                TokenStream::new(),
                TokenStream::new(),
            ),
            _ => {
                let turnings = local("turnings");
                let names = &turned_names;
                let sines = angles.iter().map(|(_, _, sin, _)| sin);
                let cosines = angles.iter().map(|(_, _, _, cos)| cos);
                let pattern = quote!(([#(#sines),*], [#(#cosines),*]));
                (
                    quote!(let mut #turnings = ::mechgen::__private::Turnings::new();),
                    quote!(let #pattern = #turnings.sin_cos([#(#names),*]);),
                    quote! {
                        #at_guess
                        let mut #turnings = ::mechgen::__private::Started::at([#(#names),*]);
                    },
                    quote!(let #pattern = #turnings.sin_cos([#(#names),*]);),
                )
            }
        };
        let (
            bindings,
            Block {
                mut statements,
                outputs,
                named,
                used,
            },
        ) = self.block_with(
            &entries,
            Bindings::ParametersOnly,
            &[presets.as_slice(), &turned].concat(),
            &stage,
        );
        let named: Vec<(ExprId, Ident, usize)> =
            presets.into_iter().chain(turned).chain(named).collect();
        statements.resize(2, Vec::new());
        let (hoisted, per_iterate) = (&statements[0], &statements[1]);
        let (residual, rest) = outputs.split_at(n);
        let (jacobian, magnitudes) = rest.split_at(n * n);
        let jacobian = matrix(jacobian, n);
        let names: Vec<&Ident> = self.model.unknowns.iter().map(|u| &u.name).collect();
        // The payload carries what is dear to compute again (the sines and cosines); the
        // rates redo the odd product rather than copy it out of every evaluation.
        let named: Vec<(ExprId, Ident, usize)> = named
            .into_iter()
            .filter(|(id, _, stage)| {
                *stage == 0 || matches!(graph.node(*id), Node::Sin(_) | Node::Cos(_))
            })
            .collect();
        let payload: Vec<&Ident> = named
            .iter()
            .filter(|(_, _, stage)| *stage == 1)
            .map(|(_, name, _)| name)
            .collect();
        // The loops' scale depends on the dimensions alone, most often: then it is computed
        // once, before the iteration, with the loops' weights.
        let fixed_scale = eq.magnitudes.iter().all(|&m| graph.is_fixed(m));
        // Then, where the declaration gives every magnitude over the parameters, the sum is
        // `declared_scale`'s (the magnitudes in the same order), which a `{Name}Newton`
        // computes once by the same expression: the same bits either way.
        let declared_scale = match (fixed_scale, self.declared_scale(), constants) {
            (true, Some(_), Some(constants)) => Some(quote!(#constants.scale)),
            (true, Some(declared), None) => Some(declared),
            _ => None,
        };
        let scale_name = local("scale");
        let every_loop: Vec<usize> = (0..self.model.loops.len()).collect();
        let (scale_statements, weights) = scale_and_weights(
            magnitudes,
            &eq.magnitude_loops,
            &every_loop,
            &scale_name,
            declared_scale,
        );
        let scale = quote!(#scale_name);
        let (scale_before, weights_inside) = if fixed_scale {
            (scale_statements, TokenStream::new())
        } else {
            (TokenStream::new(), scale_statements)
        };
        // An empty payload still needs its type.
        let payload = if payload.is_empty() {
            quote!([T::zero(); 0])
        } else {
            quote!([#(#payload),*])
        };
        let count = Literal::usize_unsuffixed(n);
        // The Jacobian's column norms where the dimensions fix them: computed once, before
        // the iteration, or kept by a `{Name}Newton` (`constants`).
        let known = local("columns");
        let (columns_before, columns) = match (self.known_column_product(), constants) {
            (Some(_), Some(constants)) => (
                quote!(let #known = ::mechgen::__private::Columns::Known(#constants.columns);),
                quote!(#known),
            ),
            (Some(product), None) => (
                quote!(let #known = ::mechgen::__private::Columns::known(#product);),
                quote!(#known),
            ),
            (None, _) => (
                TokenStream::new(),
                quote!(::mechgen::__private::Columns::FromMatrix),
            ),
        };
        // The common path's bound on the angle unknowns no `Started` keeps (see
        // `mechgen::__private::within_whole_turns`).
        let unturned: Vec<&Ident> = self
            .model
            .unknowns
            .iter()
            .filter(|u| u.kind == Kind::Angle && !turned_names.contains(&&u.name))
            .map(|u| &u.name)
            .collect();
        let common_bounds = quote! {
            #(let #unturned = ::mechgen::__private::within_whole_turns(#unturned);)*
        };
        let evaluation = |turnings: &TokenStream, bounds: &TokenStream, turns: &TokenStream| {
            quote! {
                {
                    #turnings
                    // Inlined into the iteration whatever the size of the function around it:
                    // it is called once an iteration, and its values feed the rates.
                    #[inline(always)]
                    move |#x: &[T; #count]| {
                        let [#(#names),*] = *#x;
                        #bounds
                        #turns
                        #(#per_iterate)*
                        #weights_inside
                        ::mechgen::__private::Linearisation {
                            residual: [#(#residual),*],
                            jacobian: #jacobian,
                            #scale,
                            weights: #weights,
                            payload: #payload,
                            columns: #columns,
                        }
                    }
                }
            }
        };
        Linearised {
            hoisted: quote! {
                #bindings
                #input_trig
                #(#hoisted)*
                #scale_before
                #columns_before
            },
            // With its own turnings, so that it can be emitted more than once (for the common
            // path and the fallback of `fast_newton`); it copies the values it reads.
            closure: evaluation(&turnings, &TokenStream::new(), &turns),
            common_closure: evaluation(&common_turnings, &common_bounds, &common_turns),
            named,
            fixed_scale,
            used,
        }
    }
}

/// The statements that bind `scale` (`mechgen::__private::Linearisation::scale`) and the
/// weights (`Linearisation::weights`) of the residual rows of `row_loops`, two rows per loop,
/// with the weights. Where the rows are one loop's, the scale is that loop's own magnitudes'
/// sum and the weights are ones (the same floors, without a product per row); else the scale
/// sums every magnitude (`magnitudes[i]`, in loop `loops_of[i]`) and each loop's rows weigh
/// `loop_weight` of it and their own loop's sum. `value`, where given, is the scale's value
/// (the same sum, computed otherwise).
pub(super) fn scale_and_weights(
    magnitudes: &[Emitted],
    loops_of: &[usize],
    row_loops: &[usize],
    scale: &Ident,
    value: Option<TokenStream>,
) -> (TokenStream, TokenStream) {
    let sum = |loop_index: Option<usize>| magnitude_sum(magnitudes, loops_of, loop_index);
    let rows = 2 * row_loops.len();
    if row_loops.iter().all(|&k| k == row_loops[0]) {
        let own = value.unwrap_or_else(|| sum(Some(row_loops[0])));
        return (quote!(let #scale = #own;), quote!([T::one(); #rows]));
    }
    let total = value.unwrap_or_else(|| sum(None));
    let name = |k: usize| local(&format!("weight_{k}"));
    let mut distinct = row_loops.to_vec();
    distinct.dedup();
    let statements = distinct.iter().map(|&k| {
        let (weight, own) = (name(k), sum(Some(k)));
        quote!(let #weight = ::mechgen::__private::loop_weight(#scale, #own);)
    });
    let weights = row_loops.iter().flat_map(|&k| [name(k), name(k)]);
    (
        quote!(let #scale = #total; #(#statements)*),
        quote!([#(#weights),*]),
    )
}

/// `Σ|m|` over the magnitudes of loop `loop_index` (every loop's where `None`),
/// `loops_of[i]` the loop of `magnitudes[i]`.
pub(super) fn magnitude_sum(
    magnitudes: &[Emitted],
    loops_of: &[usize],
    loop_index: Option<usize>,
) -> TokenStream {
    let terms = magnitudes
        .iter()
        .zip(loops_of)
        .filter(|(_, l)| loop_index.is_none_or(|k| **l == k))
        .map(|(m, _)| {
            let m = m.receiver();
            quote!(#m.abs())
        });
    quote!(#(#terms)+*)
}

/// [`Generator::linearisation`]'s parts.
struct Linearised {
    /// The parameters' bindings and the work on parameters and input alone.
    hoisted: TokenStream,
    /// The evaluation at an iterate: a block that makes the closure, with the state its
    /// turnings keep.
    closure: TokenStream,
    /// The same for `newton_common`: its turnings start at the guess, and give NaN rather
    /// than call `sin_cos` again.
    common_closure: TokenStream,
    /// Every value the two name, with its stage: 0 hoisted, 1 in the closure's payload.
    named: Vec<(ExprId, Ident, usize)>,
    /// Whether the loops' scale is the dimensions' alone, the same at every iterate.
    fixed_scale: bool,
    /// The variables they read: the parameters among them are bound.
    used: BTreeSet<Var>,
}

/// `motion_near`'s bodies by Newton on every unknown (see [`Generator::full_motion_near`]).
pub(super) struct FullMotionNear {
    /// Newton's common path inline, falling back to the safeguarded solve out of line.
    pub(super) common: TokenStream,
    /// The safeguarded solve alone, its arguments checked by the caller.
    pub(super) safeguarded: TokenStream,
}

/// The locals `sin_{stem}` and `cos_{stem}` for the sine and cosine of `var` that the code
/// reads (`None` for one it does not), each recorded in `named` with `stage`.
fn trig_names(
    graph: &crate::symbolic::Graph,
    var: ExprId,
    stem: &str,
    read: &[bool],
    stage: usize,
    named: &mut Vec<(ExprId, Ident, usize)>,
) -> [Option<Ident>; 2] {
    [(Node::Sin(var), "sin"), (Node::Cos(var), "cos")].map(|(node, prefix)| {
        let id = graph.lookup(node).filter(|id| read[id.index()])?;
        let name = local(&format!("{prefix}_{stem}"));
        named.push((id, name.clone(), stage));
        Some(name)
    })
}

/// The docs of the function under `motion_near`.
fn normalised_motion_near_doc() -> TokenStream {
    doc(
        "[`Self::motion_near`] on the mechanism it is called on: the mechanism as \
         given, or scaled by a power of two.",
    )
}
