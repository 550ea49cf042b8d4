//! The closed-form functions: `assemble`, `branch_of` and the one-pass `motion`, built on
//! the runtime's `mechgen::closed` solvers for each loop's case.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use syn::ext::IdentExt;

use super::docs::doc;
use super::emit::{Block, Emitted, local};
use super::normalise::Normalised;
use super::{Bindings, Generator, arg};
use crate::model::SymbolRef;
use crate::symbolic::{Case, ExprId, Node, Step, Var};

impl Generator<'_> {
    /// `assemble(input, branch)`: every loop in closed form, in the planned order.
    pub(super) fn assemble(&self, steps: &[Step]) -> TokenStream {
        let (input_params, input) = (self.input_params(), self.input_args());
        let input_text = self.inputs_text();
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let branch_parameter = self.branch_parameter(steps);
        let solve = self.closed_form_solve(steps, false);
        let names = self.model.unknowns.iter().map(|u| &u.name);
        let mut docs = format!(
            "The position at `{input_text}` in closed form, loop by loop, on the chosen assembly \
             branch{}:",
            if steps.iter().filter(|s| s.case.has_branches()).count() > 1 {
                "es"
            } else {
                ""
            }
        );
        for step in steps {
            let [a, b] = step
                .unknowns
                .map(|u| self.model.unknowns[u].name.unraw().to_string());
            docs.push_str(&format!(
                "\n- loop {} (`{}`): {}, for `{a}` and `{b}`{}",
                step.loop_index + 1,
                self.model.loops[step.loop_index].source,
                step.case.description(),
                branch_rule(&step.case, &a, &b),
            ));
            for (u, _) in step.solved().into_iter().filter(|&(_, flipped)| flipped) {
                let q = self.model.unknowns[u].name.unraw();
                docs.push_str(&format!(
                    "; this loop turns with `−{q}`, so the case solves for `{q}' = −{q}` (read \
                     `{q}'` for `{q}` above: the branch is that of the loop written in `{q}'`) \
                     and gives `{q} = −{q}'`"
                ));
            }
        }
        if let Some(named) = self.branches_type() {
            docs.push_str(&format!(
                "\n\nThe branches: a [`{named}`], each loop's by name, or the array it converts \
                 into, one per loop above in that order."
            ));
        }
        docs.push_str(
            "\n\nErrors: [`mechgen::Error::CannotAssemble`] where a loop cannot close (outside \
             the range of motion); a degenerate configuration; a non-finite parameter or input.",
        );
        let docs = doc(&docs);
        let inner = local("mechgen_assemble_solve");
        let branch_argument = self.branch_argument(steps);
        let Normalised {
            prologue,
            receiver,
            input: scaled_input,
            restore,
            ..
        } = self.normalised();
        let position = local("position");
        let finish = self.unscaled_unknowns(&position, "position");
        let finish_as_given = self.finite_unknowns(&position, "position");
        let as_given = self.as_given();
        let scaled = local("mechgen_assemble_scaled");
        let (public_parameter, conversion) = self.public_branch_parameter(steps);
        quote! {
            #docs
            pub fn assemble(
                &self,
                #input_params #public_parameter
            ) -> ::core::result::Result<#unknowns, ::mechgen::Error<T>> {
                #conversion
                self.mechgen_check_finite(#input)?;
                if #as_given {
                    let #position = self.#inner(#input #branch_argument)?;
                    ::core::result::Result::Ok(#finish_as_given)
                } else {
                    self.#scaled(#input #branch_argument)
                }
            }

            /// [`Self::assemble`] on the mechanism scaled by a power of two (its arguments
            /// checked), for a mechanism whose size is far from 1: the same bits as at any
            /// other size.
            #[cold]
            #[inline(never)]
            fn #scaled(
                &self,
                #input_params #branch_parameter
            ) -> ::core::result::Result<#unknowns, ::mechgen::Error<T>> {
                #prologue
                let #position = #receiver.#inner(#scaled_input #branch_argument)#restore?;
                ::core::result::Result::Ok(#finish)
            }

            /// [`Self::assemble`] on the mechanism it is called on (its arguments checked):
            /// the mechanism as given, or scaled by a power of two.
            #[inline(always)]
            fn #inner(
                &self,
                #input_params #branch_parameter
            ) -> ::core::result::Result<#unknowns, ::mechgen::Error<T>> {
                #solve
                ::core::result::Result::Ok(#ty { #(#names),* })
            }
        }
    }

    /// The `branch` or `branches` argument a closed-form function passes on.
    fn branch_argument(&self, steps: &[Step]) -> TokenStream {
        match steps.iter().filter(|s| s.case.has_branches()).count() {
            0 => TokenStream::new(),
            1 => {
                let branch = arg("branch");
                quote!(, #branch)
            }
            _ => {
                let branches = arg("branches");
                quote!(, #branches)
            }
        }
    }

    /// `branch_of(input, position)`: the branch each branching loop is on, by the sign its
    /// closed form documents; and, where Newton checks its solution by it (several loops),
    /// the check.
    pub(super) fn branch_of(&self, steps: &[Step]) -> TokenStream {
        let branching: Vec<&Step> = steps.iter().filter(|s| s.case.has_branches()).collect();
        if branching.is_empty() {
            return TokenStream::new();
        }
        let input_params = self.input_params();
        let input_text = self.inputs_text();
        let position = arg("position");
        let (unknowns, _, _) = self.signature_types();
        let signs: Vec<TokenStream> = self
            .branch_signs(&branching, None)
            .into_iter()
            .map(|sign| quote!(::mechgen::Branch::from_sign(#sign)))
            .collect();
        let (output, value) = match &signs[..] {
            [sign] => (quote!(::mechgen::Branch), sign.clone()),
            _ => {
                let n = Literal::usize_unsuffixed(signs.len());
                (quote!([::mechgen::Branch; #n]), quote!([#(#signs),*]))
            }
        };
        let docs = doc(&format!(
            "The assembly branch a solved position at `{input_text}` is on, by the signs \
             [`Self::assemble`] documents. A raw evaluation: it does not check its arguments."
        ));
        let keeps = (self.model.loops.len() > 1).then(|| self.keeps_branches(&branching));
        // The signs are read at any scale, but a formula of the dimensions is computed as
        // they are, and its square of a length of 1e160 overflows: where the mechanism is
        // not taken as given, its scaled copy's branches, which are the same.
        if self.formula_checks().0.is_empty() {
            return quote! {
                #docs
                pub fn branch_of(&self, #input_params, #position: &#unknowns) -> #output {
                    #value
                }
                #keeps
            };
        }
        let Normalised {
            prologue,
            receiver,
            input,
            ..
        } = self.normalised();
        let as_given = self.as_given();
        let inputs = self.inputs();
        let (ty, lengths, scale) = (&self.unknowns_type, self.length_unknowns(), local("scale"));
        quote! {
            #docs
            pub fn branch_of(&self, #input_params, #position: &#unknowns) -> #output {
                if #as_given {
                    self.mechgen_branch_of(#(#inputs),*, #position)
                } else {
                    #prologue
                    let scaled = #ty::from_array(::mechgen::__private::scaled(
                        #position.to_array(),
                        [#(#lengths),*],
                        #scale,
                    ));
                    #receiver.mechgen_branch_of(#input, &scaled)
                }
            }
            /// [`Self::branch_of`] on the mechanism it is called on.
            fn mechgen_branch_of(&self, #input_params, #position: &#unknowns) -> #output {
                #value
            }
            #keeps
        }
    }

    /// `mechgen_keeps_branches(input, guess, solution, margin)`: whether Newton's solution,
    /// whose estimated error is the length `margin` (the runtime's `Converged::error_length`:
    /// `32·ε·κ` of the size, more where a stated tolerance stopped above it),
    /// is on the guess's branches. A loop counts as switched only where its sign is decided at
    /// both: where its other assembly is farther than the error (near a tangency the two
    /// meet).
    fn keeps_branches(&self, branching: &[&Step]) -> TokenStream {
        let input_params = self.input_params();
        let (position, guess) = (arg("position"), arg("guess"));
        let (solution, margin) = (local("solution"), local("margin"));
        let (unknowns, _, _) = self.signature_types();
        let sides = self.branch_signs(branching, Some(&margin));
        let n = Literal::usize_unsuffixed(sides.len());
        let docs = doc("Whether Newton's `solution` keeps `guess`'s branches (see \
             `mechgen::__private::same_sides`).");
        quote! {
            #docs
            fn mechgen_keeps_branches(
                &self,
                #input_params,
                #guess: &#unknowns,
                #solution: &#unknowns,
                #margin: T,
            ) -> bool {
                let sides = |#position: &#unknowns| -> [T; #n] { [#(#sides),*] };
                ::mechgen::__private::same_sides(sides(#guess), sides(#solution))
            }
        }
    }

    /// Each of `branching`'s branch signs at `position`, as a block: the sign itself, or
    /// with a `margin` its side (zero where the loop's other assembly is within the margin).
    fn branch_signs(&self, branching: &[&Step], margin: Option<&Ident>) -> Vec<TokenStream> {
        let position = arg("position");
        branching
            .iter()
            .map(|step| {
                // Only the coefficients the sign reads, so no unused locals are bound.
                let (needed, function) = match &step.case {
                    Case::LengthAndOwnAngle { w0, w1, .. } => ([w0, w1], "length_and_own_angle"),
                    Case::LengthAndOtherAngle { k, v, .. } => ([k, v], "length_and_other_angle"),
                    Case::TwoAngles { k, w1, .. } => ([k, w1], "two_angles"),
                    Case::TwoLengths { .. } => unreachable!("only loops with branches"),
                };
                let needed: Vec<ExprId> = needed.into_iter().flatten().copied().collect();
                let (prologue, coefficients) = self.block(&needed);
                let vectors = complex_values(&coefficients);
                let first = &self.model.unknowns[step.unknowns[0]].name;
                // A flipped angle's case reads `q' = −q`.
                let first = if step.flipped[0] {
                    quote!(-#position.#first)
                } else {
                    quote!(#position.#first)
                };
                let (suffix, margin) = match margin {
                    Some(margin) => ("side", quote!(, #margin)),
                    None => ("sign", TokenStream::new()),
                };
                let function = format_ident!("{function}_{suffix}");
                quote! {
                    {
                        #prologue
                        ::mechgen::closed::#function(#(#vectors),*, #first #margin)
                    }
                }
            })
            .collect()
    }

    /// `motion(input, branch, rate, acceleration)`: position, velocity and acceleration in one
    /// pass. It is staged: stage `s` solves loop step `s` in closed form, so each sine,
    /// product or sum is computed once, as soon as what it reads is known; the solved angles'
    /// sines and cosines come from the closed form's directions, with no `sin_cos`.
    pub(super) fn motion(&self, steps: &[Step]) -> TokenStream {
        let (input_params, input) = (self.input_params(), self.input_args());
        let first_input = self.first_input();
        let input_text = self.inputs_text();
        let (input_dot, input_ddot) = (self.input_dot_args(), self.input_ddot_args());
        let (input_dot_text, input_ddot_text) = (self.input_dots_text(), self.input_ddots_text());
        let the_input = self.the_input();
        let (input_dot_params, input_ddot_params) =
            (self.input_dot_params(), self.input_ddot_params());
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let n = self.model.unknowns.len();
        let last = steps.len();
        let graph = &self.equations.graph;
        // Stage of each unknown: the step (1-based) that solves it; the rates come after all.
        let mut solved_at = vec![0; n];
        for (s, step) in steps.iter().enumerate() {
            step.unknowns.iter().for_each(|&u| solved_at[u] = s + 1);
        }
        let stage = |var: Var| match var {
            Var::Value(SymbolRef::Unknown(u)) => solved_at[u],
            Var::Rate(SymbolRef::Unknown(_)) | Var::Accel(SymbolRef::Unknown(_)) => last + 1,
            // Parameters, the input and its rate and acceleration are known from the start.
            _ => 0,
        };
        let mut presets = Vec::new();
        let mut direction_bindings = vec![Vec::new(); last + 1];
        for u in self.solved_angles(steps) {
            let direction = self.direction(u);
            let stem = self.model.unknowns[u].name.unraw().to_string();
            let (sin, cos) = (local(&format!("sin_{stem}")), local(&format!("cos_{stem}")));
            direction_bindings[solved_at[u]]
                .push(quote!(let (#sin, #cos) = (#direction.y, #direction.x);));
            if let Some(var) = graph.lookup(Node::Var(Var::Value(SymbolRef::Unknown(u)))) {
                for (node, name) in [(Node::Sin(var), &sin), (Node::Cos(var), &cos)] {
                    if let Some(id) = graph.lookup(node) {
                        presets.push((id, name.clone(), solved_at[u]));
                    }
                }
            }
        }
        let eq = self.equations;
        let step_coefficients: Vec<Vec<ExprId>> =
            steps.iter().map(|step| step.case.coefficients()).collect();
        let entries: Vec<ExprId> = step_coefficients
            .iter()
            .flatten()
            .chain(eq.jacobian.iter().flatten())
            .chain(&eq.velocity_rhs)
            .chain(&eq.acceleration_rhs)
            .copied()
            .collect();
        let (
            bindings,
            Block {
                mut statements,
                outputs,
                ..
            },
        ) = self.block_with(&entries, Bindings::ParametersOnly, &presets, &stage);
        statements.resize(last + 2, Vec::new());
        let mut outputs = outputs.into_iter();
        let mut choices = self.branch_choices(steps).into_iter();
        let failure = arg("failure");
        let solves: Vec<TokenStream> = steps
            .iter()
            .zip(&step_coefficients)
            .enumerate()
            .map(|(s, (step, coefficients))| {
                let computed = &statements[s];
                let values: Vec<Emitted> = outputs.by_ref().take(coefficients.len()).collect();
                let vectors = complex_values(&values);
                let solver = solver_name(&step.case);
                let sign = step.case.has_branches().then(|| {
                    let choice = choices.next();
                    quote!(, #choice.sign::<T>())
                });
                let [a, b] = step.unknowns.map(|u| &self.model.unknowns[u].name);
                let [direction_a, direction_b] = step.unknowns.map(|u| self.direction(u));
                let pattern = match step.case {
                    Case::TwoLengths { .. } => quote!([#a, #b]),
                    Case::TwoAngles { .. } => quote!((#a, #b, #direction_a, #direction_b)),
                    _ => quote!((#a, #b, #direction_b)),
                };
                let directions = &direction_bindings[s + 1];
                let flips = self.flips(step, true, true);
                quote! {
                    #(#computed)*
                    let #pattern = ::mechgen::closed::#solver(#(#vectors),* #sign)
                        .map_err(|#failure| #failure.at(#first_input))?;
                    #flips
                    #(#directions)*
                }
            })
            .collect();
        let rest: Vec<Emitted> = outputs.collect();
        let rate_solves = self.rate_solves(
            &rest,
            &statements[last],
            &statements[last + 1],
            &super::rates::PositionFrom::ClosedForm,
        );
        let names = self.model.unknowns.iter().map(|u| &u.name);
        let branch_parameter = self.branch_parameter(steps);
        let (rates, accelerations) = (local("rates"), local("accelerations"));
        let accuracy = local("accuracy");
        let rates_check = self.input_rates_check();
        let docs = doc(&format!(
            "Position (as [`Self::assemble`]), velocity and acceleration at `{input_text}` in one \
             pass, for {the_input} moving at `{input_dot_text}` and accelerating at `{input_ddot_text}`: \
             the fastest way to all three, sharing every sine, cosine and product between \
             them.\n\nErrors: as [`Self::assemble`], [`Self::velocity`] and \
             [`Self::acceleration`]."
        ));
        let inner = local("mechgen_motion_solve");
        let branch_argument = self.branch_argument(steps);
        let Normalised {
            prologue,
            rates_prologue,
            receiver,
            input: scaled_input,
            input_dot: scaled_dot,
            input_ddot: scaled_ddot,
            restore,
            ..
        } = self.normalised();
        let motion = local("motion");
        let [position, velocity, acceleration] =
            ["position", "velocity", "acceleration"].map(local);
        let finish_position = self.unscaled_unknowns(&position, "position");
        let finish_velocity = self.untimed_unknowns(&velocity, "velocity", 1);
        let finish_acceleration = self.untimed_unknowns(&acceleration, "acceleration", 2);
        let [given_position, given_velocity, given_acceleration] = [
            (&position, "position"),
            (&velocity, "velocity"),
            (&acceleration, "acceleration"),
        ]
        .map(|(values, quantity)| self.finite_unknowns(values, quantity));
        let as_given = self.as_given_with_rates();
        let stated = self.stated_in_own_units(
            quote!(#motion.accuracy),
            (&scaled_dot, &scaled_ddot),
            quote!(&::mechgen::Accuracy::required()),
            "Acceleration",
        );
        let scaled = local("mechgen_motion_scaled");
        let (public_parameter, conversion) = self.public_branch_parameter(steps);
        quote! {
            #docs
            pub fn motion(
                &self,
                #input_params #public_parameter,
                #input_dot_params,
                #input_ddot_params,
            ) -> ::core::result::Result<::mechgen::Motion<#unknowns, T>, ::mechgen::Error<T>> {
                #conversion
                self.mechgen_check_finite(#input)?;
                #rates_check
                if #as_given {
                    let #motion = self.#inner(#input #branch_argument, #input_dot, #input_ddot)?;
                    let #position = #motion.position;
                    let #velocity = #motion.velocity;
                    let #acceleration = #motion.acceleration;
                    ::core::result::Result::Ok(::mechgen::Motion {
                        position: #given_position,
                        velocity: #given_velocity,
                        acceleration: #given_acceleration,
                        accuracy: #motion.accuracy,
                    })
                } else {
                    self.#scaled(#input #branch_argument, #input_dot, #input_ddot)
                }
            }

            /// [`Self::motion`] on the mechanism scaled by a power of two (its arguments
            /// checked), for a mechanism whose size is far from 1: the same bits as at any
            /// other size.
            #[cold]
            #[inline(never)]
            fn #scaled(
                &self,
                #input_params #branch_parameter,
                #input_dot_params,
                #input_ddot_params,
            ) -> ::core::result::Result<::mechgen::Motion<#unknowns, T>, ::mechgen::Error<T>> {
                #prologue
                #rates_prologue
                let #motion = #receiver
                    .#inner(#scaled_input #branch_argument, #scaled_dot, #scaled_ddot)#restore?;
                let #position = #motion.position;
                let #velocity = #motion.velocity;
                let #acceleration = #motion.acceleration;
                ::core::result::Result::Ok(::mechgen::Motion {
                    position: #finish_position,
                    velocity: #finish_velocity,
                    acceleration: #finish_acceleration,
                    accuracy: #stated,
                })
            }

            /// [`Self::motion`] on the mechanism it is called on (its arguments checked): the
            /// mechanism as given, or scaled by a power of two.
            #[inline(always)]
            fn #inner(
                &self,
                #input_params #branch_parameter,
                #input_dot_params,
                #input_ddot_params,
            ) -> ::core::result::Result<::mechgen::Motion<#unknowns, T>, ::mechgen::Error<T>> {
                #bindings
                #(#solves)*
                #rate_solves
                ::core::result::Result::Ok(::mechgen::Motion {
                    position: #ty { #(#names),* },
                    velocity: #ty::from_array(#rates),
                    acceleration: #ty::from_array(#accelerations),
                    accuracy: #accuracy,
                })
            }
        }
    }

    /// The statements that solve every loop in closed form, binding each unknown to a local
    /// of its own name and, with `directions`, each solved angle's `(cos, sin)` to
    /// `direction_{angle}`.
    fn closed_form_solve(&self, steps: &[Step], directions: bool) -> TokenStream {
        let first_input = self.first_input();
        let mut choices = self.branch_choices(steps).into_iter();
        let solves = steps.iter().map(|step| {
            let (prologue, coefficients) = self.block_in(&step.case.coefficients(), true);
            let vectors = complex_values(&coefficients);
            let solver = solver_name(&step.case);
            let sign = step.case.has_branches().then(|| {
                let choice = choices.next();
                quote!(, #choice.sign::<T>())
            });
            let [a, b] = step.unknowns.map(|u| &self.model.unknowns[u].name);
            let [direction_a, direction_b] = step.unknowns.map(|u| {
                if directions {
                    let direction = self.direction(u);
                    quote!(#direction)
                } else {
                    quote!(_)
                }
            });
            let failure = arg("failure");
            let call = quote! {
                ::mechgen::closed::#solver(#(#vectors),* #sign)
                    .map_err(|#failure| #failure.at(#first_input))?
            };
            let pattern = match step.case {
                Case::TwoLengths { .. } => quote!([#a, #b]),
                Case::TwoAngles { .. } => quote!((#a, #b, #direction_a, #direction_b)),
                // (length, angle, the angle's direction)
                _ => quote!((#a, #b, #direction_b)),
            };
            let flips = self.flips(step, true, directions);
            quote! {
                let #pattern = {
                    #prologue
                    #call
                };
                #flips
            }
        });
        quote!(#(#solves)*)
    }

    /// The branch choice each branching step of a closed-form plan reads: `branch` when there
    /// is one, `branches[i]` when there are several.
    pub(super) fn branch_choices(&self, steps: &[Step]) -> Vec<TokenStream> {
        let branching = steps.iter().filter(|s| s.case.has_branches()).count();
        (0..branching)
            .map(|i| {
                if branching == 1 {
                    let branch = arg("branch");
                    quote!(#branch)
                } else {
                    let branches = arg("branches");
                    let i = Literal::usize_unsuffixed(i);
                    quote!(#branches[#i])
                }
            })
            .collect()
    }

    /// The `branch` or `branches` parameter of a public closed-form function, and the
    /// statement its body starts with: for several branching loops, anything that converts
    /// into the array (the named branches' type, or the array itself), converted.
    pub(super) fn public_branch_parameter(&self, steps: &[Step]) -> (TokenStream, TokenStream) {
        match steps.iter().filter(|s| s.case.has_branches()).count() {
            n if n >= 2 => {
                let branches = arg("branches");
                let n = Literal::usize_unsuffixed(n);
                (
                    quote!(, #branches: impl ::core::convert::Into<[::mechgen::Branch; #n]>),
                    quote!(let #branches: [::mechgen::Branch; #n] = #branches.into();),
                )
            }
            _ => (self.branch_parameter(steps), TokenStream::new()),
        }
    }

    /// The `branch` or `branches` parameter of a closed-form function.
    pub(super) fn branch_parameter(&self, steps: &[Step]) -> TokenStream {
        match steps.iter().filter(|s| s.case.has_branches()).count() {
            0 => TokenStream::new(),
            1 => {
                let branch = arg("branch");
                quote!(, #branch: ::mechgen::Branch)
            }
            n => {
                let branches = arg("branches");
                let n = Literal::usize_unsuffixed(n);
                quote!(, #branches: [::mechgen::Branch; #n])
            }
        }
    }

    /// What follows a step's solver call for each [flipped](Step::flipped) angle, which the
    /// call bound as `q'`: `q = −q'` where `values` are bound, and where `directions` are,
    /// the unit vector conjugated, `(cos q', −sin q')`.
    pub(super) fn flips(&self, step: &Step, values: bool, directions: bool) -> TokenStream {
        let statements = step
            .solved()
            .into_iter()
            .filter(|&(_, flipped)| flipped)
            .map(|(u, _)| {
                let name = &self.model.unknowns[u].name;
                let direction = self.direction(u);
                let value = values.then(|| quote!(let #name = -#name;));
                let direction = directions.then(
                    || quote!(let #direction = ::mechgen::Vec2::new(#direction.x, -#direction.y);),
                );
                quote!(#value #direction)
            });
        quote!(#(#statements)*)
    }

    /// The local holding an unknown angle's `(cos, sin)` from a closed form.
    pub(super) fn direction(&self, unknown: usize) -> Ident {
        local(&format!(
            "direction_{}",
            self.model.unknowns[unknown].name.unraw()
        ))
    }

    /// The unknown angles a closed-form plan gives directions for.
    pub(super) fn solved_angles(&self, steps: &[Step]) -> Vec<usize> {
        steps
            .iter()
            .flat_map(|step| match step.case {
                Case::TwoLengths { .. } => vec![],
                Case::TwoAngles { .. } => step.unknowns.to_vec(),
                _ => vec![step.unknowns[1]],
            })
            .collect()
    }
}

/// A closed-form case's complex coefficients, in the order its runtime solver takes them.
/// `(x, y)` pairs of emitted coefficients as `mechgen::Vec2` values.
pub(super) fn complex_values(components: &[Emitted]) -> Vec<TokenStream> {
    components
        .chunks(2)
        .map(|pair| {
            let (x, y) = (&pair[0], &pair[1]);
            quote!(::mechgen::Vec2::new(#x, #y))
        })
        .collect()
}

fn solver_name(case: &Case) -> Ident {
    let name = match case {
        Case::TwoLengths { .. } => "two_lengths",
        Case::LengthAndOwnAngle { .. } => "length_and_own_angle",
        Case::LengthAndOtherAngle { .. } => "length_and_other_angle",
        Case::TwoAngles { .. } => "two_angles",
    };
    Ident::new(name, proc_macro2::Span::call_site())
}

/// How a case's two branches are told apart, for the docs, with the unknowns' names.
pub(super) fn branch_rule(case: &Case, a: &str, b: &str) -> String {
    match case {
        Case::TwoLengths { .. } => String::new(),
        Case::LengthAndOwnAngle { .. } => format!(
            "; open where `{a}` makes the vector that turns with `{b}` longer along its own \
             direction (`Re(conj(w1)·({a}·w1 + w0)) ≥ 0`)"
        ),
        Case::LengthAndOtherAngle { .. } => format!(
            "; open where the intersection is the one farther along `{a}`'s direction \
             (`Re(conj(v)·(K + {a}·v)) ≥ 0`)"
        ),
        Case::TwoAngles { .. } => format!(
            "; open where the vector turning with `{a}` lies counter-clockwise of the chord it \
             spans with the one turning with `{b}` (`cross(−K, e^{{i·{a}}}·w1) ≥ 0`)"
        ),
    }
}
