//! Velocity and acceleration: linear solves with the Jacobian, factored once and, when the
//! loops are block lower-triangular, solved loop by loop.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;

use super::docs::doc;
use super::emit::{Block, Emitted, local};
use super::timed::RatesOutput;
use super::{Bindings, Generator, arg, matrix};
use crate::model::SymbolRef;
use crate::symbolic::{ExprId, Step, Var};

impl Generator<'_> {
    pub(super) fn velocity(&self) -> TokenStream {
        let input_text = self.inputs_text();
        let input_dot_text = self.input_dots_text();
        let the_input = self.the_input();
        let (unknowns, _, _) = self.signature_types();
        let body = self.linear_solve(&self.equations.velocity_rhs, "velocity");
        let solves = if self.model.inputs.len() == 1 {
            format!("`J·q̇ = -(∂f/∂{input_text})·{input_dot_text}`")
        } else {
            "`J·q̇ = -Σ (∂f/∂u)·u̇` over the inputs `u`".to_string()
        };
        let docs = format!(
            "The unknowns' rates at a solved `position`, for {the_input} moving at \
             `{input_dot_text}`:\nsolves {solves}.\n\n\
             Errors: a non-finite argument; a singular Jacobian (a toggle, where the rates \
             are unbounded); rates less accurate than [`mechgen::Accuracy::required`] \
             ([`mechgen::Error::Inaccurate`]), judged as at a closed form's position (from \
             `assemble`) where the loops close there to rounding, else as far off as their \
             residual says (so another input's position, or one made up, is `Inaccurate`). A \
             position from Newton is known less well, and its rates with it: \
             [`Self::motion_at`] and `motion_near` estimate them for it."
        );
        self.checked_function(
            "velocity",
            &docs,
            3,
            &unknowns,
            body,
            Some(RatesOutput::Velocity),
        )
    }

    pub(super) fn acceleration(&self) -> TokenStream {
        let (unknowns, _, _) = self.signature_types();
        let body = self.linear_solve(&self.equations.acceleration_rhs, "acceleration");
        let (rates, cross) = if self.model.inputs.len() == 1 {
            ("input's rate and acceleration", "")
        } else {
            (
                "inputs' rates and accelerations",
                " (with the terms that cross the inputs' motions)",
            )
        };
        let docs = format!(
            "The unknowns' accelerations at a solved `position` and `velocity`, for the \
             {rates}.\nThe right-hand side is the second time derivative of the loops{cross}, \
             so centripetal, Coriolis and sliding terms are all in it.\n\n\
             Errors: a non-finite argument; a singular Jacobian; accelerations less accurate \
             than [`mechgen::Accuracy::required`] ([`mechgen::Error::Inaccurate`]), judged as \
             at a closed form's position where the loops close there, as [`Self::velocity`]."
        );
        self.checked_function(
            "acceleration",
            &docs,
            5,
            &unknowns,
            body,
            Some(RatesOutput::Acceleration),
        )
    }

    /// `motion_at(input, &position, rate, acceleration)`: velocity and acceleration at a
    /// solved position (from Newton, say) in one pass, every shared sine and product once.
    pub(super) fn motion_at(&self) -> TokenStream {
        let input = self.input_args();
        let (input_dot_text, input_ddot_text) = (self.input_dots_text(), self.input_ddots_text());
        let the_input = self.the_input();
        let position = arg("position");
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let eq = self.equations;
        // Loops whose magnitudes depend on the position (a slide's extension) can be longer
        // than the declared lengths, and a Newton position is known only to their rounding:
        // their magnitudes at the position, with the rates.
        let moving_magnitudes: &[ExprId] = if eq.magnitudes.iter().all(|&m| eq.graph.is_fixed(m)) {
            &[]
        } else {
            &eq.magnitudes
        };
        let entries: Vec<ExprId> = eq
            .jacobian
            .iter()
            .flatten()
            .chain(&eq.velocity_rhs)
            .chain(&eq.acceleration_rhs)
            .chain(&eq.residual)
            .chain(moving_magnitudes)
            .copied()
            .collect();
        let stage = |var: Var| usize::from(matches!(var, Var::Rate(SymbolRef::Unknown(_))));
        let (
            bindings,
            Block {
                mut statements,
                outputs,
                ..
            },
        ) = self.block_with(&entries, Bindings::Position, &[], &stage);
        statements.resize(2, Vec::new());
        let (outputs, magnitudes) = outputs.split_at(outputs.len() - moving_magnitudes.len());
        let (outputs, residual) = outputs.split_at(outputs.len() - eq.residual.len());
        let floor = if magnitudes.is_empty() {
            PositionFrom::Caller
        } else {
            PositionFrom::CallerIn(largest_loop(magnitudes, &eq.magnitude_loops))
        };
        let position_from = PositionFrom::Given(
            residual.iter().map(|r| quote!(#r)).collect(),
            Box::new(floor),
        );
        let rate_solves = self.rate_solves(outputs, &statements[0], &statements[1], &position_from);
        let (rates, accelerations) = (local("rates"), local("accelerations"));
        let accuracy = local("accuracy");
        let rates_check = self.input_rates_check();
        let docs = doc(&format!(
            "Velocity and acceleration at a solved `position` (from [`Self::position`], say) in \
             one pass, for {the_input} moving at `{input_dot_text}` and accelerating at \
             `{input_ddot_text}`: what [`Self::velocity`] and [`Self::acceleration`] give, sharing \
             their work. The accuracy it returns holds for any position the solvers return, \
             Newton's included (`mechgen::Accuracy::estimate_at`): near a toggle it is less than \
             a closed form's rates have, and the rates are refused sooner. A position the loops \
             do not close at to rounding is taken as far off as their residual says.\n\nErrors: as \
             [`Self::velocity`] and [`Self::acceleration`], judged by that accuracy."
        ));
        self.normalised_rates_function(
            &Ident::new("motion_at", proc_macro2::Span::call_site()),
            docs,
            4,
            &quote!(::mechgen::Motion<#unknowns, T>),
            quote! {
                self.mechgen_check_finite(#input)?;
                #rates_check
                ::mechgen::__private::finite(#position.to_array(), "position")?;
            },
            quote! {
                #bindings
                #rate_solves
                ::core::result::Result::Ok(::mechgen::Motion {
                    position: *#position,
                    velocity: #ty::from_array(#rates),
                    acceleration: #ty::from_array(#accelerations),
                    accuracy: #accuracy,
                })
            },
            RatesOutput::Motion,
        )
    }

    /// The velocity and acceleration solves from emitted Jacobian and right-hand sides
    /// (`outputs`: the Jacobian row by row, the velocity's right-hand side, the
    /// acceleration's), with the statements to run before the rates are known and after.
    /// Leaves `jacobian`, `rates` and `accelerations` bound, and each rate in its local.
    pub(super) fn rate_solves(
        &self,
        outputs: &[Emitted],
        before: &[TokenStream],
        after: &[TokenStream],
        position: &PositionFrom,
    ) -> TokenStream {
        let n = self.model.unknowns.len();
        let (jacobian, rest) = outputs.split_at(n * n);
        let (velocity_rhs, acceleration_rhs) = rest.split_at(n);
        let (rates, accelerations) = (local("rates"), local("accelerations"));
        let velocity_solve = self.solves(
            jacobian,
            &[(velocity_rhs, rates.clone())],
            "Acceleration",
            position,
        );
        // The acceleration reuses the factors: only its solve is emitted the second time.
        let acceleration_solve =
            self.reuse_solves(jacobian, &[(acceleration_rhs, accelerations.clone())]);
        let rate_names = &self.unknown_dots;
        quote! {
            #(#before)*
            #velocity_solve
            let [#(#rate_names),*] = ::mechgen::__private::finite(#rates, "velocity")?;
            #(#after)*
            #acceleration_solve
            let #accelerations = ::mechgen::__private::finite(#accelerations, "acceleration")?;
        }
    }

    /// A function that solves `J·x = rhs` for the unknowns' rates or accelerations.
    fn linear_solve(&self, rhs: &[ExprId], quantity: &str) -> TokenStream {
        let count = self.model.unknowns.len();
        let entries: Vec<ExprId> = self
            .equations
            .jacobian
            .iter()
            .flatten()
            .chain(rhs)
            .chain(&self.equations.residual)
            .copied()
            .collect();
        let (prologue, outputs) = self.block(&entries);
        let (jacobian, rest) = outputs.split_at(count * count);
        let (rhs, residual) = rest.split_at(rhs.len());
        let position = PositionFrom::Given(
            residual.iter().map(|r| quote!(#r)).collect(),
            Box::new(PositionFrom::ClosedForm),
        );
        let ty = &self.unknowns_type;
        let solution = arg("solution");
        let highest = if quantity == "velocity" {
            "Velocity"
        } else {
            "Acceleration"
        };
        let solve = self.solves(jacobian, &[(rhs, solution.clone())], highest, &position);
        let accuracy = local("accuracy");
        quote! {
            #prologue
            #solve
            // The estimate was checked; the public function drops it, the path that scales
            // the mechanism adds what the float's range costs the results to it.
            ::mechgen::__private::finite(#solution, #quantity)
                .map(|values| (#ty::from_array(values), #accuracy))
        }
    }

    /// Code that solves `J·x = rhs` for each `(rhs, name)`, binding `name` to `x`: the
    /// factorisation ([`Self::factorise`]) and the solves ([`Self::reuse_solves`]).
    ///
    /// Before solving, the rates' accuracy up to the order `highest` (`"Velocity"` or
    /// `"Acceleration"`) is estimated from the Jacobian and where the `position` came from,
    /// and a rate that would have fewer correct digits than required is
    /// [`mechgen::Error::Inaccurate`].
    pub(super) fn solves(
        &self,
        jacobian: &[Emitted],
        right_sides: &[(&[Emitted], Ident)],
        highest: &str,
        position: &PositionFrom,
    ) -> TokenStream {
        let factors = self.factorise(jacobian);
        let matrix = local("jacobian_matrix");
        // The whole Jacobian's condition, from its factors where it was factored whole.
        let condition = if self.triangular_steps().is_some() {
            quote!(::mechgen::condition(#matrix))
        } else {
            let factored = arg("jacobian");
            quote!(T::one() / #factored.relative().abs())
        };
        let check = self.rates_check(
            quote!(&#matrix),
            condition,
            highest,
            quote!(&::mechgen::Accuracy::required()),
            position,
        );
        let solves = self.reuse_solves(jacobian, right_sides);
        quote!(#factors #check #solves)
    }

    /// `let accuracy = rates_accuracy(condition, jacobian, size, angles, position, highest,
    /// required)?;` for the Jacobian `matrix` (an expression of type `&[[T; N]; N]`) of
    /// condition `condition` at a position from `position`, against `required` (of type
    /// `&Accuracy<T>`), the sum of the lengths the loops declare as the size: the estimate a
    /// [`mechgen::Motion`] carries.
    pub(super) fn rates_check(
        &self,
        matrix: TokenStream,
        condition: TokenStream,
        highest: &str,
        required: TokenStream,
        position: &PositionFrom,
    ) -> TokenStream {
        self.rates_check_at(
            matrix,
            condition,
            highest,
            required,
            self.accuracy_size(quote!(self)),
            position,
            None,
        )
    }

    /// [`Self::rates_check`] with the size already computed, as `size`, and the aspect,
    /// where the dimensions fix it, as `aspect` (`None`: computed here, from the size).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn rates_check_at(
        &self,
        matrix: TokenStream,
        condition: TokenStream,
        highest: &str,
        required: TokenStream,
        size: TokenStream,
        position: &PositionFrom,
        aspect: Option<TokenStream>,
    ) -> TokenStream {
        // Computed once, where the position's error reads it too.
        let condition_name = local("condition");
        let bind_condition = quote!(let #condition_name = #condition;);
        let condition = quote!(#condition_name);
        let position = position.tokens(&matrix, &condition, &size);
        let highest = Ident::new(highest, proc_macro2::Span::call_site());
        let accuracy = local("accuracy");
        let angles: Vec<bool> = self
            .model
            .unknowns
            .iter()
            .map(|unknown| unknown.kind == crate::model::Kind::Angle)
            .collect();
        // Columns of fixed lengths: the aspect from the dimensions, not the Jacobian (which
        // decides only where their squares leave the float's range).
        let receiver = Ident::new("self", proc_macro2::Span::call_site());
        let known = self
            .known_aspect(&receiver, &size)
            .map(|computed| aspect.unwrap_or(computed));
        let (function, aspect) = match known {
            Some(aspect) => (quote!(rates_accuracy_at_aspect), quote!(#aspect,)),
            None => (quote!(rates_accuracy), TokenStream::new()),
        };
        let moving = proc_macro2::Literal::f64_suffixed(self.moving_columns());
        quote! {
            #bind_condition
            let #accuracy = ::mechgen::__private::#function(
                #condition,
                #aspect
                #matrix,
                #size,
                [#(#angles),*],
                #position,
                T::constant(#moving),
                ::mechgen::Order::#highest,
                #required,
            )?;
        }
    }

    /// How many of the unknowns' columns an error of the position moves, each by up to the
    /// aspect times that error (`mechgen::Accuracy::estimate_at`'s `moving`): one per angle
    /// unknown (its own second derivative is its column turned a right angle, of its length,
    /// however many terms it turns); two per term whose length is an unknown and whose angle
    /// is one's (the slide's length error turns with that angle's rate, and the angle's error
    /// with the slide's rate); none for a length along a fixed direction. Where a term's angle
    /// holds several unknowns, or one times other than ±1, or a length unknown has a factor
    /// other than ±1, these second derivatives are not bounded by the columns (terms can
    /// cancel in a column and not in its derivative): two per unknown and per term there, on
    /// top, as a margin rather than a bound.
    pub(super) fn moving_columns(&self) -> f64 {
        // The coefficients of a term's angle or magnitude on the unknowns.
        let on_unknowns = |linear: &crate::model::Linear| -> Vec<f64> {
            linear
                .coefficients
                .iter()
                .filter(|(symbol, _)| matches!(symbol, SymbolRef::Unknown(_)))
                .map(|(_, c)| *c)
                .collect()
        };
        let angles = self
            .model
            .unknowns
            .iter()
            .filter(|u| u.kind == crate::model::Kind::Angle)
            .count();
        let mut moving = angles as f64;
        let mut irregular = 0usize;
        for term in self.model.loops.iter().flat_map(|sum| &sum.terms) {
            let (turning, sliding) = (on_unknowns(&term.angle), on_unknowns(&term.magnitude));
            if turning.is_empty() {
                continue;
            }
            if turning.len() > 1
                || turning.iter().chain(&sliding).any(|c| c.abs() != 1.0)
                || sliding.len() > 1
            {
                irregular += 1;
            }
            if !sliding.is_empty() {
                moving += 2.0;
            }
        }
        if irregular > 0 {
            moving += (2 * irregular * self.model.unknowns.len()) as f64;
        }
        moving
    }

    /// Whether no loop's magnitudes can sum to more than [`Self::accuracy_size`]: every
    /// term's magnitude one of the declared lengths (no formula, no factor, no slide's
    /// extension), none twice in a loop. Newton's position error, held to each loop's own
    /// magnitudes, then needs no stretch to be read against the size.
    pub(super) fn loops_within_size(&self) -> bool {
        self.model.loops.iter().all(|sum| {
            let mut seen = std::collections::BTreeSet::new();
            sum.terms.iter().all(|term| {
                let m = &term.magnitude;
                let single =
                    m.formulas.is_empty() && m.constant == 0.0 && m.coefficients.len() == 1;
                single
                    && m.coefficients.iter().all(|(symbol, c)| {
                        matches!(symbol, SymbolRef::Param(i)
                            if self.model.params[*i].kind == crate::model::Kind::Length
                                && c.abs() == 1.0
                                && seen.insert(*i))
                    })
            })
        })
    }

    /// The size [`Self::rates_check`] weighs the columns against: the sum of the lengths the
    /// loops declare (1 without one), read from the mechanism `receiver`.
    pub(super) fn accuracy_size(&self, receiver: TokenStream) -> TokenStream {
        self.declared_size(receiver, None)
    }

    /// The sum of the lengths loop `loop_index` declares (every loop's where `None`; 1
    /// without one), read from the mechanism `receiver`: its rounding's scale.
    pub(super) fn declared_size(
        &self,
        receiver: TokenStream,
        loop_index: Option<usize>,
    ) -> TokenStream {
        let loops = || {
            self.model
                .loops
                .iter()
                .enumerate()
                .filter(move |(k, _)| loop_index.is_none_or(|only| *k == only))
                .flat_map(|(_, sum)| &sum.terms)
        };
        // The lengths of the loops' vectors only: a tracked point's distance (a coupler
        // point far off its link) does not make the loops' rates any less accurate.
        let in_loops: std::collections::BTreeSet<usize> = loops()
            .flat_map(|term| term.magnitude.coefficients.keys())
            .filter_map(|symbol| match symbol {
                SymbolRef::Param(i) => Some(*i),
                _ => None,
            })
            .collect();
        let lengths = self
            .model
            .params
            .iter()
            .enumerate()
            .filter(|(i, param)| param.kind == crate::model::Kind::Length && in_loops.contains(i))
            .map(|(_, param)| {
                let name = &param.name;
                quote!(#receiver.#name.abs())
            });
        // A formula in a magnitude is a length of the loop's own (which a product or a
        // quotient of parameters can make far longer than any of them), counted once.
        let mut formulas = Vec::new();
        for (_, formula) in loops().flat_map(|term| &term.magnitude.formulas) {
            if !formulas.contains(&formula) {
                formulas.push(formula);
            }
        }
        let formulas = formulas.into_iter().map(|formula| {
            let value = super::evaluators::formula_tokens(formula, &|i| {
                let field = &self.model.params[i].name;
                quote!(#receiver.#field)
            });
            quote!(#value.abs())
        });
        let terms: Vec<TokenStream> = lengths.chain(formulas).collect();
        if terms.is_empty() {
            quote!(T::one())
        } else {
            quote!(#(#terms)+*)
        }
    }

    /// The formulas the loops' magnitudes hold, each once: lengths of their own.
    pub(super) fn loop_length_formulas(&self) -> Vec<&crate::formula::Formula> {
        let mut found = Vec::new();
        let formulas = self
            .model
            .loops
            .iter()
            .flat_map(|sum| &sum.terms)
            .flat_map(|term| &term.magnitude.formulas);
        for (_, formula) in formulas {
            if !found.contains(&formula) {
                found.push(formula);
            }
        }
        found
    }

    /// The closed-form plan's steps when the Jacobian is block lower-triangular in their
    /// order: a plan of several loops (a loop does not involve unknowns solved after it).
    fn triangular_steps(&self) -> Option<&[Step]> {
        self.equations
            .closed_form
            .as_deref()
            .ok()
            .filter(|steps| steps.len() > 1)
    }

    /// Factors the Jacobian once for any number of solves: each loop's 2×2 diagonal block
    /// when it is block lower-triangular, else the whole matrix.
    fn factorise(&self, jacobian: &[Emitted]) -> TokenStream {
        let n = self.model.unknowns.len();
        let matrix_tokens = matrix(jacobian, n);
        let jacobian_name = arg("jacobian");
        let matrix_name = local("jacobian_matrix");
        let Some(steps) = self.triangular_steps() else {
            return quote! {
                let #matrix_name = #matrix_tokens;
                let #jacobian_name = ::mechgen::__private::Factored::new(#matrix_name)?;
            };
        };
        let index = |i: usize| Literal::usize_unsuffixed(i);
        let blocks = steps.iter().enumerate().map(|(s, step)| {
            let block = local(&format!("block{s}"));
            let [r0, r1] = [2 * step.loop_index, 2 * step.loop_index + 1].map(index);
            let [a, b] = step.unknowns.map(index);
            quote! {
                let #block = ::mechgen::__private::Factored::new([
                    [#jacobian_name[#r0][#a], #jacobian_name[#r0][#b]],
                    [#jacobian_name[#r1][#a], #jacobian_name[#r1][#b]],
                ])?;
            }
        });
        quote! {
            let #matrix_name = #matrix_tokens;
            let #jacobian_name = #matrix_name;
            #(#blocks)*
        }
    }

    /// The solves of `J·x = rhs` with [`Self::factorise`]'s factors, binding each `name`.
    /// Block by block when triangular: each loop's unknowns from its block, the earlier
    /// unknowns' terms moved to the right-hand side and structural zeros skipped.
    pub(super) fn reuse_solves(
        &self,
        _jacobian: &[Emitted],
        right_sides: &[(&[Emitted], Ident)],
    ) -> TokenStream {
        let jacobian_name = arg("jacobian");
        let Some(steps) = self.triangular_steps() else {
            let solves = right_sides
                .iter()
                .map(|(rhs, name)| quote!(let #name = #jacobian_name.solve([#(#rhs),*]);));
            return quote!(#(#solves)*);
        };
        let n = Literal::usize_unsuffixed(self.model.unknowns.len());
        let ids = &self.equations.jacobian;
        let index = |i: usize| Literal::usize_unsuffixed(i);
        let x = local("x");
        let (solved_a, solved_b) = (local("solved_a"), local("solved_b"));
        let solves = right_sides.iter().map(|(rhs, name)| {
            let per_step = steps.iter().enumerate().map(|(s, step)| {
                let block = local(&format!("block{s}"));
                let earlier: Vec<usize> = steps[..s].iter().flat_map(|e| e.unknowns).collect();
                let [first, second] = [2 * step.loop_index, 2 * step.loop_index + 1].map(|r| {
                    let value = &rhs[r];
                    let moved = earlier
                        .iter()
                        .filter(|&&u| !self.equations.graph.is_zero(ids[r][u]))
                        .map(|&u| {
                            let (r, u) = (index(r), index(u));
                            quote!(- #jacobian_name[#r][#u] * #x[#u])
                        });
                    // Subtraction is left-associative: the value needs no parentheses.
                    quote!(#value #(#moved)*)
                });
                let [a, b] = step.unknowns.map(index);
                quote! {
                    let [#solved_a, #solved_b] = #block.solve([#first, #second]);
                    #x[#a] = #solved_a;
                    #x[#b] = #solved_b;
                }
            });
            quote! {
                let #name = {
                    let mut #x = [T::zero(); #n];
                    #(#per_step)*
                    #x
                };
            }
        });
        quote!(#(#solves)*)
    }
}

/// Where the position the rates are solved at came from, which says how far off it may be
/// (`mechgen::__private::rates_accuracy`'s `position`).
pub(crate) enum PositionFrom {
    /// A closed form, computed with the rates: `mechgen::Accuracy::estimate`'s own.
    ClosedForm,
    /// The caller, to `motion_at`, which states the accuracy it returns: any position
    /// within the contract, the closed form's or Newton's, so Newton's `32·ε·κ`.
    /// (`velocity`, `acceleration` and the sensitivities, which state none, judge a position
    /// that closes to rounding as a closed form's, as their documentation says; each wraps
    /// its variant in [`PositionFrom::Given`].)
    Caller,
    /// The caller, as [`PositionFrom::Caller`], where the loops' magnitudes depend on the
    /// position: Newton's `32·ε·κ` relative to the largest loop's magnitudes there (this
    /// expression), which can exceed the size.
    CallerIn(TokenStream),
    /// Newton's solution: its error bound from the residual it stopped at, this expression.
    Newton(TokenStream),
    /// A position the caller gives, with the loops' residual there (these expressions): as
    /// the inner variant where they close within rounding, else known only as well as that
    /// residual says (`mechgen::__private::given_position`).
    Given(Vec<TokenStream>, Box<PositionFrom>),
}

impl PositionFrom {
    /// The `Option<T>` that `rates_accuracy` takes, for a Jacobian `matrix` (an expression of
    /// type `&[[T; N]; N]`) of condition `condition` in a mechanism of size `size`.
    fn tokens(
        &self,
        matrix: &TokenStream,
        condition: &TokenStream,
        size: &TokenStream,
    ) -> TokenStream {
        match self {
            PositionFrom::ClosedForm => quote!(::core::option::Option::None),
            PositionFrom::Caller => quote!(::core::option::Option::Some(T::zero())),
            PositionFrom::CallerIn(largest) => quote!(::core::option::Option::Some(
                ::mechgen::__private::floor_position_accuracy(#condition, #largest, #size)
            )),
            PositionFrom::Newton(error) => quote!(::core::option::Option::Some(#error)),
            PositionFrom::Given(residual, otherwise) => {
                let otherwise = otherwise.tokens(matrix, condition, size);
                quote!(::mechgen::__private::given_position(
                    #condition,
                    #matrix,
                    &[#(#residual),*],
                    #size,
                    #otherwise,
                ))
            }
        }
    }
}

/// The largest of the loops' magnitude sums, `|m|` summed over each loop's `magnitudes`
/// (`loops_of[i]` is the loop of `magnitudes[i]`).
fn largest_loop(magnitudes: &[Emitted], loops_of: &[usize]) -> TokenStream {
    let mut loops: Vec<usize> = loops_of.to_vec();
    loops.dedup();
    let sums: Vec<TokenStream> = loops
        .iter()
        .map(|&k| super::newton::magnitude_sum(magnitudes, loops_of, Some(k)))
        .collect();
    match sums.as_slice() {
        [one] => one.clone(),
        _ => quote!(T::zero()#(.max(#sums))*),
    }
}
