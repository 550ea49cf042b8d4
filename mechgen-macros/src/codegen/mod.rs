//! Emits the generated items: the mechanism struct, its unknowns and points types, and the
//! solver functions the declaration asked for.

mod emit;

use std::collections::BTreeSet;

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

use crate::model::{Kind, Model, Symbol, SymbolRef};
use crate::symbolic::{Case, Equations, ExprId, Node, Step, Var};
use emit::{Block, Context, Emitted, emit, local};
use syn::ext::IdentExt;

pub fn generate(model: &Model, equations: &Equations) -> TokenStream {
    let generator = Generator::new(model, equations);
    let mechanism = generator.mechanism_struct();
    let unknowns = generator.unknowns_struct();
    let points = generator.points_struct();
    let functions = generator.functions();
    let kinematics = generator.kinematics_impl();
    let name = &model.name;
    quote! {
        #mechanism
        #unknowns
        #points
        #kinematics
        // Spans of generated tokens all point at the macro call, which misleads
        // `possible_missing_comma`; generated argument lists follow the declaration.
        #[allow(clippy::possible_missing_comma, clippy::too_many_arguments)]
        impl<T: ::mechgen::Real> #name<T> {
            #functions
        }
    }
}

struct Generator<'a> {
    model: &'a Model,
    equations: &'a Equations,
    unknowns_type: Ident,
    points_type: Ident,
    /// Rate and acceleration names of the input and each unknown (`theta2_dot`, ...).
    input_dot: Ident,
    input_ddot: Ident,
    unknown_dots: Vec<Ident>,
    unknown_ddots: Vec<Ident>,
    /// Every generated name a function body can see besides its own temporaries.
    reserved: BTreeSet<String>,
}

/// Said of the evaluators, which unlike the solvers return plain arrays.
const RAW_EVALUATION: &str = "A raw evaluation: it does not check its arguments, so a NaN \
     in gives NaN out. The solvers check theirs.";

/// Which variables a block binds from `self` and the arguments, and which it leaves to the
/// caller's locals.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Bindings {
    /// Parameters from `self`; unknowns, rates and accelerations from the `position`,
    /// `velocity` and `acceleration` arguments.
    Arguments,
    /// Parameters and the unknowns from `position`; rates are locals.
    Position,
    /// Parameters only; unknowns and rates are locals.
    ParametersOnly,
}

/// The generated functions' own argument and local names, besides derived ones.
const ARGUMENT_NAMES: [&str; 18] = [
    "solved_a",
    "solved_b",
    "rates",
    "accelerations",
    "solved",
    "branch",
    "branches",
    "failure",
    "position",
    "velocity",
    "acceleration",
    "guess",
    "options",
    "x",
    "jacobian",
    "rhs",
    "solution",
    "values",
];

/// One of [`ARGUMENT_NAMES`], as a hygienic identifier.
fn arg(name: &str) -> Ident {
    debug_assert!(ARGUMENT_NAMES.contains(&name));
    local(name)
}

impl<'a> Generator<'a> {
    fn new(model: &'a Model, equations: &'a Equations) -> Self {
        let derived =
            |symbol: &Symbol, suffix: &str| local(&format!("{}_{suffix}", symbol.name.unraw()));
        let input_dot = derived(&model.input, "dot");
        let input_ddot = derived(&model.input, "ddot");
        let unknown_dots: Vec<Ident> = model.unknowns.iter().map(|u| derived(u, "dot")).collect();
        let unknown_ddots: Vec<Ident> = model.unknowns.iter().map(|u| derived(u, "ddot")).collect();
        let point_components = model.points.iter().flat_map(|p| {
            let name = p.name.unraw().to_string();
            component_names(&name, &[])
                .into_iter()
                .chain(component_names(&name, &ACCELERATION_PARTS))
                .flatten()
        });
        let reserved = ARGUMENT_NAMES
            .iter()
            .map(|name| name.to_string())
            .chain(
                [&input_dot, &input_ddot]
                    .into_iter()
                    .chain(&unknown_dots)
                    .chain(&unknown_ddots)
                    .map(Ident::to_string),
            )
            .chain(point_components)
            .chain(
                model
                    .unknowns
                    .iter()
                    .map(|u| format!("direction_{}", u.name.unraw())),
            )
            .collect();
        Generator {
            model,
            equations,
            unknowns_type: format_ident!("{}Unknowns", model.name),
            points_type: format_ident!("{}Points", model.name),
            input_dot,
            input_ddot,
            unknown_dots,
            unknown_ddots,
            reserved,
        }
    }

    fn var_name(&self, var: Var) -> Ident {
        match var {
            Var::Value(symbol) => self.model.symbol(symbol).name.clone(),
            Var::Rate(SymbolRef::Input) => self.input_dot.clone(),
            Var::Rate(SymbolRef::Unknown(i)) => self.unknown_dots[i].clone(),
            Var::Accel(SymbolRef::Input) => self.input_ddot.clone(),
            Var::Accel(SymbolRef::Unknown(i)) => self.unknown_ddots[i].clone(),
            // Parameters are constant: the graph never holds their rates.
            Var::Rate(SymbolRef::Param(i)) | Var::Accel(SymbolRef::Param(i)) => {
                self.model.params[i].name.clone()
            }
        }
    }

    /// Emits `outputs` with the `let`s that bind the parameters and unknowns they read.
    /// Some outputs do not depend on the input (a Jacobian often does not); then the
    /// prologue marks the input argument as deliberately unused.
    fn block(&self, outputs: &[ExprId]) -> (TokenStream, Vec<Emitted>) {
        self.block_in(outputs, false)
    }

    /// [`Self::block`] for code where the unknowns already are locals (a closed-form solve,
    /// one loop after another) and the input is used elsewhere.
    fn block_in(
        &self,
        outputs: &[ExprId],
        unknowns_are_locals: bool,
    ) -> (TokenStream, Vec<Emitted>) {
        let bindings = if unknowns_are_locals {
            Bindings::ParametersOnly
        } else {
            Bindings::Arguments
        };
        let (bindings, mut statements, outputs) = self.block_with(outputs, bindings, &[], &|_| 0);
        let statements = statements.pop().unwrap_or_default();
        (quote!(#bindings #(#statements)*), outputs)
    }

    /// Emits `outputs`, with the `let`s that bind the parameters and unknowns they read (as
    /// `bindings` says), and the statements by stage (see [`Context::stage`]).
    fn block_with(
        &self,
        outputs: &[ExprId],
        bindings: Bindings,
        presets: &[(ExprId, Ident, usize)],
        stage: &dyn Fn(Var) -> usize,
    ) -> (TokenStream, Vec<Vec<TokenStream>>, Vec<Emitted>) {
        let mode = bindings;
        let context = Context {
            reserved: &self.reserved,
            presets,
            stage,
        };
        let Block {
            statements,
            outputs,
            used,
        } = emit(
            &self.equations.graph,
            outputs,
            &|var| self.var_name(var),
            &context,
        );
        let position = arg("position");
        let velocity = arg("velocity");
        let acceleration = arg("acceleration");
        let bindings = used.iter().filter_map(|&var| {
            let name = self.var_name(var);
            let (source, field) = match var {
                Var::Value(SymbolRef::Param(i)) => {
                    let field = &self.model.params[i].name;
                    return Some(quote!(let #name = self.#field;));
                }
                _ if mode == Bindings::ParametersOnly => return None,
                Var::Value(SymbolRef::Unknown(i)) => (&position, i),
                _ if mode == Bindings::Position => return None,
                Var::Rate(SymbolRef::Unknown(i)) => (&velocity, i),
                Var::Accel(SymbolRef::Unknown(i)) => (&acceleration, i),
                // The input and its derivatives are function arguments.
                _ => return None,
            };
            let field = &self.model.unknowns[field].name;
            Some(quote!(let #name = #source.#field;))
        });
        let input = &self.model.input.name;
        let unused_input = (mode == Bindings::Arguments
            && !used.contains(&Var::Value(SymbolRef::Input)))
        .then(|| quote!(let _ = #input;));
        let bindings = quote! {
            #unused_input
            #(#bindings)*
        };
        (bindings, statements, outputs)
    }

    fn mechanism_struct(&self) -> TokenStream {
        let Model {
            attrs, vis, name, ..
        } = self.model;
        let fields = self.model.params.iter().map(|param| {
            let field = &param.name;
            let docs = docs_or(
                &param.docs,
                &format!("Parameter `{}`: {}.", field.unraw(), unit(param.kind)),
            );
            let vis = &param.vis;
            quote!(#docs #vis #field: T,)
        });
        quote! {
            #(#attrs)*
            #[derive(Clone, Copy, Debug, PartialEq)]
            #vis struct #name<T> {
                #(#fields)*
            }
        }
    }

    fn unknowns_struct(&self) -> TokenStream {
        let Model {
            vis,
            name,
            unknowns,
            ..
        } = self.model;
        let ty = &self.unknowns_type;
        let count = Literal::usize_unsuffixed(unknowns.len());
        let names: Vec<&Ident> = unknowns.iter().map(|u| &u.name).collect();
        let name_strings = names.iter().map(|n| n.unraw().to_string());
        let fields = unknowns.iter().map(|unknown| {
            let field = &unknown.name;
            let docs = docs_or(
                &unknown.docs,
                &format!("Unknown `{}`: {}.", field.unraw(), unit(unknown.kind)),
            );
            quote!(#docs pub #field: T,)
        });
        let text = format!(
            "Values of [`{name}`]'s unknowns, in declaration order: a position, or the \
             unknowns' rates (per unit time), or their accelerations."
        );
        let values = arg("values");
        let doc = doc(&text);
        quote! {
            #doc
            #[derive(Clone, Copy, Debug, Default, PartialEq)]
            #vis struct #ty<T> {
                #(#fields)*
            }

            impl<T: Copy> #ty<T> {
                /// The unknowns' names, in declaration (and array) order.
                pub const NAMES: [&'static str; #count] = [#(#name_strings),*];

                /// From values in declaration order.
                pub const fn from_array(#values: [T; #count]) -> Self {
                    let [#(#names),*] = #values;
                    Self { #(#names),* }
                }

                /// The values in declaration order.
                pub const fn to_array(&self) -> [T; #count] {
                    [#(self.#names),*]
                }
            }

            impl<T: Copy> ::core::convert::From<[T; #count]> for #ty<T> {
                fn from(#values: [T; #count]) -> Self {
                    Self::from_array(#values)
                }
            }

            impl<T: Copy> ::core::convert::From<#ty<T>> for [T; #count] {
                fn from(#values: #ty<T>) -> Self {
                    #values.to_array()
                }
            }
        }
    }

    fn points_struct(&self) -> TokenStream {
        let Model {
            vis, name, points, ..
        } = self.model;
        if points.is_empty() {
            return TokenStream::new();
        }
        let ty = &self.points_type;
        let fields = points.iter().map(|point| {
            let field = &point.name;
            let formula = doc(&format!(
                "Point `{}` = `{}`.",
                field.unraw(),
                point.position.source
            ));
            let docs = &point.docs;
            let separator = (!docs.is_empty()).then(|| quote!(#[doc = ""]));
            quote!(#(#docs)* #separator #formula pub #field: V,)
        });
        let text = format!(
            "[`{name}`]'s tracked points: for each, a `V` that is its position, velocity or \
             acceleration (a [`mechgen::Vec2`]) or its acceleration's parts (a \
             [`mechgen::AccelerationParts`]), in the frame of the loops."
        );
        let doc = doc(&text);
        quote! {
            #doc
            #[derive(Clone, Copy, Debug, Default, PartialEq)]
            #vis struct #ty<V> {
                #(#fields)*
            }
        }
    }

    fn functions(&self) -> TokenStream {
        let mut functions = vec![
            self.check_finite(),
            self.residual(),
            self.jacobian(),
            self.position(),
        ];
        if let Some(steps) = &self.equations.closed_form {
            functions.push(self.assemble(steps));
            functions.push(self.branch_of(steps));
            if self.model.outputs.acceleration {
                functions.push(self.motion(steps));
            }
        }
        let outputs = self.model.outputs;
        if outputs.velocity {
            functions.extend([self.input_jacobian(), self.velocity()]);
        }
        if outputs.acceleration {
            functions.extend([self.acceleration(), self.motion_at()]);
        }
        if !self.model.points.is_empty() {
            functions.push(self.points());
            if outputs.velocity {
                functions.push(self.point_velocities());
            }
            if outputs.acceleration {
                functions.extend([self.point_accelerations(), self.point_acceleration_parts()]);
            }
        }
        quote!(#(#functions)*)
    }

    /// `(self.l1, "parameter `l1`"), ...`: every parameter, then the listed extras.
    fn check_finite(&self) -> TokenStream {
        let input = &self.model.input.name;
        let checks = self.model.params.iter().map(|param| {
            let field = &param.name;
            let label = format!("parameter `{}`", field.unraw());
            quote!((self.#field, #label),)
        });
        let input_label = format!("input `{}`", input.unraw());
        quote! {
            /// Checks that the parameters and the input are finite.
            #[inline]
            fn mechgen_check_finite(&self, #input: T) -> ::core::result::Result<(), ::mechgen::Error<T>> {
                ::mechgen::__private::check_finite(&[#(#checks)* (#input, #input_label)])
            }
        }
    }

    fn loops_doc(&self) -> String {
        let mut doc = String::new();
        for (k, l) in self.model.loops.iter().enumerate() {
            doc.push_str(&format!(
                "\n- rows {} and {} (x and y of loop {}): `{} = 0`",
                2 * k,
                2 * k + 1,
                k + 1,
                l.source
            ));
        }
        doc
    }

    /// The unknowns struct type, the array type of a residual, and the unknowns' count as
    /// an unsuffixed literal.
    fn signature_types(&self) -> (TokenStream, TokenStream, Literal) {
        let ty = &self.unknowns_type;
        let count = Literal::usize_unsuffixed(self.model.unknowns.len());
        (quote!(#ty<T>), quote!([T; #count]), count)
    }

    fn residual(&self) -> TokenStream {
        let input = &self.model.input.name;
        let position = arg("position");
        let (unknowns, array, _) = self.signature_types();
        let (prologue, outputs) = self.block(&self.equations.residual);
        let doc = doc(&format!(
            "The loop-closure residual at `{input}` and `{position}`: zero when the loops \
             close.\n{}\n\n{RAW_EVALUATION}",
            self.loops_doc()
        ));
        quote! {
            #doc
            pub fn residual(&self, #input: T, #position: &#unknowns) -> #array {
                #prologue
                [#(#outputs),*]
            }
        }
    }

    fn jacobian(&self) -> TokenStream {
        let input = &self.model.input.name;
        let position = arg("position");
        let (unknowns, _, count) = self.signature_types();
        let entries: Vec<ExprId> = self.equations.jacobian.iter().flatten().copied().collect();
        let (prologue, outputs) = self.block(&entries);
        let rows = matrix(&outputs, self.model.unknowns.len());
        let raw = doc(RAW_EVALUATION);
        quote! {
            /// The Jacobian of [`Self::residual`] with respect to the unknowns: row `i`,
            /// column `j` is `∂residual[i]/∂unknown[j]`.
            ///
            #raw
            pub fn jacobian(&self, #input: T, #position: &#unknowns) -> [[T; #count]; #count] {
                #prologue
                #rows
            }
        }
    }

    /// The Newton iteration's evaluation as a closure over the iterate `x`, with everything
    /// that depends only on the parameters and input computed once, before the closure:
    /// `(hoisted statements, closure)`.
    fn linearisation(&self, x: &Ident) -> (TokenStream, TokenStream) {
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
        let (bindings, mut statements, outputs) =
            self.block_with(&entries, Bindings::ParametersOnly, &[], &stage);
        statements.resize(2, Vec::new());
        let (hoisted, per_iterate) = (&statements[0], &statements[1]);
        let (residual, rest) = outputs.split_at(n);
        let (jacobian, magnitudes) = rest.split_at(n * n);
        let jacobian = matrix(jacobian, n);
        let scale = magnitudes.iter().map(|m| {
            let m = m.receiver();
            quote!(#m.abs())
        });
        let names = self.model.unknowns.iter().map(|u| &u.name);
        let count = Literal::usize_unsuffixed(n);
        (
            quote! {
                #bindings
                #(#hoisted)*
            },
            quote! {
                |#x: &[T; #count]| {
                    let [#(#names),*] = *#x;
                    #(#per_iterate)*
                    ::mechgen::__private::Linearisation {
                        residual: [#(#residual),*],
                        jacobian: #jacobian,
                        scale: #(#scale)+*,
                    }
                }
            },
        )
    }

    fn solver(&self) -> TokenStream {
        // Loops give two equations each: one loop is the closed-form 2×2 case.
        match self.model.unknowns.len() {
            2 => quote!(::mechgen::__private::solve2),
            _ => quote!(::mechgen::__private::solve_lu),
        }
    }

    fn position(&self) -> TokenStream {
        let input = &self.model.input.name;
        let (guess, options, x, solved) = (arg("guess"), arg("options"), arg("x"), arg("solved"));
        let position = arg("position");
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let solver = self.solver();
        let branching = self.equations.closed_form.as_ref().map_or(0, |steps| {
            steps.iter().filter(|s| s.case.has_branches()).count()
        });
        let single_loop = self.model.loops.len() == 1;
        // One loop: its branch is the Jacobian's orientation, which Newton checks for free.
        // Several: compare the closed forms' signs.
        let keep_orientation = branching == 1 && single_loop;
        let branch_check = (branching > 0 && !keep_orientation).then(|| {
            quote! {
                if self.branch_of(#input, &#solved.value) != self.branch_of(#input, #guess) {
                    return ::core::result::Result::Err(::mechgen::Error::OtherBranch);
                }
            }
        });
        let branch_doc = if branching > 0 {
            " It keeps to the guess's assembly branch (for one loop, the orientation of the \
             Jacobian, which tells the branches apart; for several, [`Self::branch_of`]): \
             landing on the other one is the error [`mechgen::Error::OtherBranch`], never a \
             silent switch."
        } else {
            ""
        };
        let (hoisted, linearise) = self.linearisation(&x);
        let doc = doc(&format!(
            "Solves the loops for the unknowns at `{input}` by a safeguarded Newton-Raphson from \
             `guess` (see `mechgen::__private::newton`: halved steps, a certified root, \
             stagnation reported).{branch_doc}\n\n\
             Errors: a non-finite parameter, input or guess; a singular Jacobian on the way; \
             [`mechgen::Error::CannotAssemble`] where the iterates press against a toggle the \
             loops cannot pass; no convergence within `options.max_iterations`."
        ));
        quote! {
            #doc
            pub fn position(
                &self,
                #input: T,
                #guess: &#unknowns,
                #options: &::mechgen::NewtonOptions<T>,
            ) -> ::core::result::Result<::mechgen::Solved<#unknowns, T>, ::mechgen::Error<T>> {
                self.mechgen_check_finite(#input)?;
                #hoisted
                let #solved = ::mechgen::__private::newton(
                    #input,
                    #guess.to_array(),
                    #options,
                    #keep_orientation,
                    #linearise,
                    #solver,
                )?
                .map(#ty::from_array);
                #branch_check
                ::core::result::Result::Ok(#solved)
            }

            /// The Jacobian's condition estimate at a position, `1 / relative determinant`
            /// (see [`mechgen::condition`]): 1 at best, about `1/√ε` at a toggle, where the
            /// solvers return [`mechgen::Error::Singular`]. Errors in positions and rates grow
            /// with it (the accuracy contract in the `mechgen` docs).
            pub fn condition(&self, #input: T, #position: &#unknowns) -> T {
                ::mechgen::condition(self.jacobian(#input, #position))
            }
        }
    }

    fn input_jacobian(&self) -> TokenStream {
        let input = &self.model.input.name;
        let position = arg("position");
        let (unknowns, array, _) = self.signature_types();
        let (prologue, outputs) = self.block(&self.equations.input_jacobian);
        let raw = doc(RAW_EVALUATION);
        quote! {
            /// The derivative of [`Self::residual`] with respect to the input.
            ///
            #raw
            pub fn input_jacobian(&self, #input: T, #position: &#unknowns) -> #array {
                #prologue
                [#(#outputs),*]
            }
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
            .copied()
            .collect();
        let (prologue, outputs) = self.block(&entries);
        let (jacobian, rhs) = outputs.split_at(count * count);
        let ty = &self.unknowns_type;
        let solution = arg("solution");
        let solve = self.solves(jacobian, &[(rhs, solution.clone())]);
        quote! {
            #prologue
            #solve
            ::mechgen::__private::finite(#solution, #quantity).map(#ty::from_array)
        }
    }

    /// Code that solves `J·x = rhs` for each `(rhs, name)`, binding `name` to `x`: the
    /// factorisation ([`Self::factorise`]) and the solves ([`Self::reuse_solves`]).
    fn solves(&self, jacobian: &[Emitted], right_sides: &[(&[Emitted], Ident)]) -> TokenStream {
        let factors = self.factorise(jacobian);
        let solves = self.reuse_solves(jacobian, right_sides);
        quote!(#factors #solves)
    }

    /// The closed-form plan's steps when the Jacobian is block lower-triangular in their
    /// order: a plan of several loops (a loop does not involve unknowns solved after it).
    fn triangular_steps(&self) -> Option<&[Step]> {
        self.equations
            .closed_form
            .as_deref()
            .filter(|steps| steps.len() > 1)
    }

    /// Factors the Jacobian once for any number of solves: each loop's 2×2 diagonal block
    /// when it is block lower-triangular, else the whole matrix.
    fn factorise(&self, jacobian: &[Emitted]) -> TokenStream {
        let n = self.model.unknowns.len();
        let matrix_tokens = matrix(jacobian, n);
        let jacobian_name = arg("jacobian");
        let Some(steps) = self.triangular_steps() else {
            return quote! {
                let #jacobian_name = ::mechgen::__private::Factored::new(#matrix_tokens)?;
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
            let #jacobian_name = #matrix_tokens;
            #(#blocks)*
        }
    }

    /// The solves of `J·x = rhs` with [`Self::factorise`]'s factors, binding each `name`.
    /// Block by block when triangular: each loop's unknowns from its block, the earlier
    /// unknowns' terms moved to the right-hand side and structural zeros skipped.
    fn reuse_solves(
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

    /// A checked kinematics function taking the first `arity` of the arguments
    /// (input, position, input rate, velocity, input acceleration, acceleration): it rejects
    /// non-finite parameters and arguments, then runs `body`.
    fn checked_function(
        &self,
        name: &str,
        docs: &str,
        arity: usize,
        output: &TokenStream,
        body: TokenStream,
    ) -> TokenStream {
        let input = &self.model.input.name;
        let (unknowns, _, _) = self.signature_types();
        let scalars = [
            (None, input.clone()),
            (Some("input rate"), self.input_dot.clone()),
            (Some("input acceleration"), self.input_ddot.clone()),
        ];
        let mut parameters = Vec::new();
        let mut scalar_checks = Vec::new();
        let mut unknowns_checks = Vec::new();
        for index in 0..arity {
            if index % 2 == 0 {
                let (label, name) = &scalars[index / 2];
                parameters.push(quote!(#name: T));
                if let Some(label) = label {
                    let label = format!("{label} `{name}`");
                    scalar_checks.push(quote!((#name, #label)));
                }
            } else {
                let quantity = ["position", "velocity", "acceleration"][index / 2];
                let name = arg(quantity);
                parameters.push(quote!(#name: &#unknowns));
                unknowns_checks
                    .push(quote!(::mechgen::__private::finite(#name.to_array(), #quantity)?;));
            }
        }
        let scalar_checks = (!scalar_checks.is_empty())
            .then(|| quote!(::mechgen::__private::check_finite(&[#(#scalar_checks),*])?;));
        let name = Ident::new(name, proc_macro2::Span::call_site());
        let docs = doc(docs);
        quote! {
            #docs
            pub fn #name(
                &self,
                #(#parameters),*
            ) -> ::core::result::Result<#output, ::mechgen::Error<T>> {
                self.mechgen_check_finite(#input)?;
                #scalar_checks
                #(#unknowns_checks)*
                #body
            }
        }
    }

    fn velocity(&self) -> TokenStream {
        let input = &self.model.input.name;
        let input_dot = &self.input_dot;
        let (unknowns, _, _) = self.signature_types();
        let body = self.linear_solve(&self.equations.velocity_rhs, "velocity");
        let docs = format!(
            "The unknowns' rates at a solved `position`, for the input moving at \
             `{input_dot}`:\nsolves `J·q̇ = -(∂f/∂{input})·{input_dot}`.\n\n\
             Errors: a non-finite argument; a singular Jacobian (a toggle, where the rates \
             are unbounded)."
        );
        self.checked_function("velocity", &docs, 3, &unknowns, body)
    }

    fn acceleration(&self) -> TokenStream {
        let (unknowns, _, _) = self.signature_types();
        let body = self.linear_solve(&self.equations.acceleration_rhs, "acceleration");
        let docs = "The unknowns' accelerations at a solved `position` and `velocity`, for the \
             input's rate and acceleration.\nThe right-hand side is the second time derivative \
             of the loops, so centripetal, Coriolis and sliding terms are all in it.\n\n\
             Errors: a non-finite argument; a singular Jacobian.";
        self.checked_function("acceleration", docs, 5, &unknowns, body)
    }

    /// The body of a points function: each point's value built from `which` of its
    /// expressions, a `(x, y)` pair per named vector (`parts`; one unnamed vector for a plain
    /// `Vec2`).
    fn points_body(
        &self,
        which: impl Fn(&crate::symbolic::PointExprs) -> Vec<[ExprId; 2]>,
        parts: &[&str],
        quantity: &str,
    ) -> TokenStream {
        let entries: Vec<ExprId> = self
            .equations
            .points
            .iter()
            .flat_map(|p| which(p).into_iter().flatten())
            .collect();
        let (prologue, outputs) = self.block(&entries);
        let ty = &self.points_type;
        let mut pattern = Vec::new();
        let fields = self.model.points.iter().map(|point| {
            let name = &point.name;
            let vectors: Vec<TokenStream> = component_names(&name.unraw().to_string(), parts)
                .into_iter()
                .map(|[x, y]| {
                    let (x, y) = (local(&x), local(&y));
                    pattern.extend([x.clone(), y.clone()]);
                    quote!(::mechgen::Vec2 { x: #x, y: #y })
                })
                .collect();
            let value = match parts {
                [] => quote!(#(#vectors)*),
                _ => {
                    let parts = parts
                        .iter()
                        .map(|p| Ident::new(p, proc_macro2::Span::call_site()));
                    quote!(::mechgen::AccelerationParts { #(#parts: #vectors),* })
                }
            };
            quote!(#name: #value)
        });
        let fields: Vec<TokenStream> = fields.collect();
        quote! {
            #prologue
            let [#(#pattern),*] = ::mechgen::__private::finite([#(#outputs),*], #quantity)?;
            ::core::result::Result::Ok(#ty { #(#fields),* })
        }
    }

    fn points(&self) -> TokenStream {
        let ty = &self.points_type;
        let body = self.points_body(|p| vec![p.position], &[], "point position");
        let docs = "The tracked points' positions at a solved `position`.";
        let output = quote!(#ty<::mechgen::Vec2<T>>);
        self.checked_function("points", docs, 2, &output, body)
    }

    fn point_velocities(&self) -> TokenStream {
        let ty = &self.points_type;
        let body = self.points_body(|p| vec![p.velocity], &[], "point velocity");
        let docs = "The tracked points' velocities at a solved `position` and `velocity`.";
        let output = quote!(#ty<::mechgen::Vec2<T>>);
        self.checked_function("point_velocities", docs, 4, &output, body)
    }

    fn point_accelerations(&self) -> TokenStream {
        let ty = &self.points_type;
        let body = self.points_body(|p| vec![p.acceleration], &[], "point acceleration");
        let docs = "The tracked points' accelerations at a solved `position`, `velocity` and \
             `acceleration`.";
        let output = quote!(#ty<::mechgen::Vec2<T>>);
        self.checked_function("point_accelerations", docs, 6, &output, body)
    }

    fn point_acceleration_parts(&self) -> TokenStream {
        let ty = &self.points_type;
        let body = self.points_body(
            |p| p.acceleration_parts.to_vec(),
            &ACCELERATION_PARTS,
            "point acceleration part",
        );
        let docs = "The tracked points' accelerations split, term by term of each point's \
             vector sum `Σ r·e^{iθ}`, into tangential `i·r·θ̈·e^{iθ}`, normal `−r·θ̇²·e^{iθ}`, \
             sliding `r̈·e^{iθ}` and Coriolis `2·i·ṙ·θ̇·e^{iθ}` parts, which sum to \
             [`Self::point_accelerations`].";
        let output = quote!(#ty<::mechgen::AccelerationParts<T>>);
        self.checked_function("point_acceleration_parts", docs, 6, &output, body)
    }

    /// The branch choice each branching step of a closed-form plan reads: `branch` when there
    /// is one, `branches[i]` when there are several.
    fn branch_choices(&self, steps: &[Step]) -> Vec<TokenStream> {
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

    /// The `branch` or `branches` parameter of a closed-form function.
    fn branch_parameter(&self, steps: &[Step]) -> TokenStream {
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

    /// The statements that solve every loop in closed form, binding each unknown to a local
    /// of its own name and, with `directions`, each solved angle's `(cos, sin)` to
    /// `direction_{angle}`.
    fn closed_form_solve(&self, steps: &[Step], directions: bool) -> TokenStream {
        let input = &self.model.input.name;
        let mut choices = self.branch_choices(steps).into_iter();
        let solves = steps.iter().map(|step| {
            let (prologue, coefficients) = self.block_in(&coefficients(&step.case), true);
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
                    .map_err(|#failure| #failure.at(#input))?
            };
            let pattern = match step.case {
                Case::TwoLengths { .. } => quote!([#a, #b]),
                Case::TwoAngles { .. } => quote!((#a, #b, #direction_a, #direction_b)),
                // (length, angle, the angle's direction)
                _ => quote!((#a, #b, #direction_b)),
            };
            quote! {
                let #pattern = {
                    #prologue
                    #call
                };
            }
        });
        quote!(#(#solves)*)
    }

    /// The local holding an unknown angle's `(cos, sin)` from a closed form.
    fn direction(&self, unknown: usize) -> Ident {
        local(&format!(
            "direction_{}",
            self.model.unknowns[unknown].name.unraw()
        ))
    }

    /// The unknown angles a closed-form plan gives directions for.
    fn solved_angles(&self, steps: &[Step]) -> Vec<usize> {
        steps
            .iter()
            .flat_map(|step| match step.case {
                Case::TwoLengths { .. } => vec![],
                Case::TwoAngles { .. } => step.unknowns.to_vec(),
                _ => vec![step.unknowns[1]],
            })
            .collect()
    }

    /// `assemble(input, branch)`: every loop in closed form, in the planned order.
    fn assemble(&self, steps: &[Step]) -> TokenStream {
        let input = &self.model.input.name;
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let branch_parameter = self.branch_parameter(steps);
        let solve = self.closed_form_solve(steps, false);
        let names = self.model.unknowns.iter().map(|u| &u.name);
        let mut docs = format!(
            "The position at `{input}` in closed form, loop by loop, on the chosen assembly \
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
        }
        docs.push_str(
            "\n\nErrors: [`mechgen::Error::CannotAssemble`] where a loop cannot close (outside \
             the range of motion); a degenerate configuration; a non-finite parameter or input.",
        );
        let docs = doc(&docs);
        quote! {
            #docs
            pub fn assemble(
                &self,
                #input: T #branch_parameter
            ) -> ::core::result::Result<#unknowns, ::mechgen::Error<T>> {
                self.mechgen_check_finite(#input)?;
                #solve
                ::core::result::Result::Ok(#ty { #(#names),* })
            }
        }
    }

    /// `motion(input, branch, rate, acceleration)`: position, velocity and acceleration in one
    /// pass. It is staged: stage `s` solves loop step `s` in closed form, so each sine,
    /// product or sum is computed once, as soon as what it reads is known; the solved angles'
    /// sines and cosines come from the closed form's directions, with no `sin_cos`.
    fn motion(&self, steps: &[Step]) -> TokenStream {
        let input = &self.model.input.name;
        let (input_dot, input_ddot) = (&self.input_dot, &self.input_ddot);
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
            steps.iter().map(|step| coefficients(&step.case)).collect();
        let entries: Vec<ExprId> = step_coefficients
            .iter()
            .flatten()
            .chain(eq.jacobian.iter().flatten())
            .chain(&eq.velocity_rhs)
            .chain(&eq.acceleration_rhs)
            .copied()
            .collect();
        let (bindings, mut statements, outputs) =
            self.block_with(&entries, Bindings::ParametersOnly, &presets, &stage);
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
                quote! {
                    #(#computed)*
                    let #pattern = ::mechgen::closed::#solver(#(#vectors),* #sign)
                        .map_err(|#failure| #failure.at(#input))?;
                    #(#directions)*
                }
            })
            .collect();
        let rest: Vec<Emitted> = outputs.collect();
        let rate_solves = self.rate_solves(&rest, &statements[last], &statements[last + 1]);
        let names = self.model.unknowns.iter().map(|u| &u.name);
        let branch_parameter = self.branch_parameter(steps);
        let (rates, accelerations) = (local("rates"), local("accelerations"));
        let labels = [
            format!("input rate `{input_dot}`"),
            format!("input acceleration `{input_ddot}`"),
        ];
        let [dot_label, ddot_label] = &labels;
        let docs = doc(&format!(
            "Position (as [`Self::assemble`]), velocity and acceleration at `{input}` in one \
             pass, for the input moving at `{input_dot}` and accelerating at `{input_ddot}`: \
             the fastest way to all three, sharing every sine, cosine and product between \
             them.\n\nErrors: as [`Self::assemble`], [`Self::velocity`] and \
             [`Self::acceleration`]."
        ));
        quote! {
            #docs
            pub fn motion(
                &self,
                #input: T #branch_parameter,
                #input_dot: T,
                #input_ddot: T,
            ) -> ::core::result::Result<::mechgen::Motion<#unknowns>, ::mechgen::Error<T>> {
                self.mechgen_check_finite(#input)?;
                ::mechgen::__private::check_finite(&[(#input_dot, #dot_label), (#input_ddot, #ddot_label)])?;
                #bindings
                #(#solves)*
                #rate_solves
                ::core::result::Result::Ok(::mechgen::Motion {
                    position: #ty { #(#names),* },
                    velocity: #ty::from_array(#rates),
                    acceleration: #ty::from_array(#accelerations),
                })
            }
        }
    }

    /// The velocity and acceleration solves from emitted Jacobian and right-hand sides
    /// (`outputs`: the Jacobian row by row, the velocity's right-hand side, the
    /// acceleration's), with the statements to run before the rates are known and after.
    /// Leaves `jacobian`, `rates` and `accelerations` bound, and each rate in its local.
    fn rate_solves(
        &self,
        outputs: &[Emitted],
        before: &[TokenStream],
        after: &[TokenStream],
    ) -> TokenStream {
        let n = self.model.unknowns.len();
        let (jacobian, rest) = outputs.split_at(n * n);
        let (velocity_rhs, acceleration_rhs) = rest.split_at(n);
        let (rates, accelerations) = (local("rates"), local("accelerations"));
        let velocity_solve = self.solves(jacobian, &[(velocity_rhs, rates.clone())]);
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

    /// `motion_at(input, &position, rate, acceleration)`: velocity and acceleration at a
    /// solved position (from Newton, say) in one pass, every shared sine and product once.
    fn motion_at(&self) -> TokenStream {
        let input = &self.model.input.name;
        let (input_dot, input_ddot) = (&self.input_dot, &self.input_ddot);
        let position = arg("position");
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let eq = self.equations;
        let entries: Vec<ExprId> = eq
            .jacobian
            .iter()
            .flatten()
            .chain(&eq.velocity_rhs)
            .chain(&eq.acceleration_rhs)
            .copied()
            .collect();
        let stage = |var: Var| usize::from(matches!(var, Var::Rate(SymbolRef::Unknown(_))));
        let (bindings, mut statements, outputs) =
            self.block_with(&entries, Bindings::Position, &[], &stage);
        statements.resize(2, Vec::new());
        let rate_solves = self.rate_solves(&outputs, &statements[0], &statements[1]);
        let (rates, accelerations) = (local("rates"), local("accelerations"));
        let labels = [
            format!("input rate `{input_dot}`"),
            format!("input acceleration `{input_ddot}`"),
        ];
        let [dot_label, ddot_label] = &labels;
        let docs = doc(&format!(
            "Velocity and acceleration at a solved `position` (from [`Self::position`], say) in \
             one pass, for the input moving at `{input_dot}` and accelerating at \
             `{input_ddot}`: what [`Self::velocity`] and [`Self::acceleration`] give, sharing \
             their work.\n\nErrors: as [`Self::velocity`] and [`Self::acceleration`]."
        ));
        quote! {
            #docs
            pub fn motion_at(
                &self,
                #input: T,
                #position: &#unknowns,
                #input_dot: T,
                #input_ddot: T,
            ) -> ::core::result::Result<::mechgen::Motion<#unknowns>, ::mechgen::Error<T>> {
                self.mechgen_check_finite(#input)?;
                ::mechgen::__private::check_finite(&[(#input_dot, #dot_label), (#input_ddot, #ddot_label)])?;
                ::mechgen::__private::finite(#position.to_array(), "position")?;
                #bindings
                #rate_solves
                ::core::result::Result::Ok(::mechgen::Motion {
                    position: *#position,
                    velocity: #ty::from_array(#rates),
                    acceleration: #ty::from_array(#accelerations),
                })
            }
        }
    }

    /// `branch_of(input, position)`: the branch each branching loop is on, by the sign its
    /// closed form documents.
    fn branch_of(&self, steps: &[Step]) -> TokenStream {
        let branching: Vec<&Step> = steps.iter().filter(|s| s.case.has_branches()).collect();
        if branching.is_empty() {
            return TokenStream::new();
        }
        let input = &self.model.input.name;
        let position = arg("position");
        let (unknowns, _, _) = self.signature_types();
        let signs: Vec<TokenStream> = branching
            .iter()
            .map(|step| {
                // Only the coefficients the sign reads, so no unused locals are bound.
                let (needed, function) = match &step.case {
                    Case::LengthAndOwnAngle { w0, w1, .. } => {
                        ([w0, w1], "length_and_own_angle_sign")
                    }
                    Case::LengthAndOtherAngle { k, v, .. } => {
                        ([k, v], "length_and_other_angle_sign")
                    }
                    Case::TwoAngles { k, w1, .. } => ([k, w1], "two_angles_sign"),
                    Case::TwoLengths { .. } => unreachable!("filtered out above"),
                };
                let needed: Vec<ExprId> = needed.into_iter().flatten().copied().collect();
                let (prologue, coefficients) = self.block(&needed);
                let vectors = complex_values(&coefficients);
                let first = &self.model.unknowns[step.unknowns[0]].name;
                let function = Ident::new(function, proc_macro2::Span::call_site());
                let sign = quote!(::mechgen::closed::#function(#(#vectors),*, #position.#first));
                quote! {
                    {
                        #prologue
                        ::mechgen::Branch::from_sign(#sign)
                    }
                }
            })
            .collect();
        let (output, value) = match &signs[..] {
            [sign] => (quote!(::mechgen::Branch), sign.clone()),
            _ => {
                let n = Literal::usize_unsuffixed(signs.len());
                (quote!([::mechgen::Branch; #n]), quote!([#(#signs),*]))
            }
        };
        let docs = doc(&format!(
            "The assembly branch a solved position at `{input}` is on, by the signs \
             [`Self::assemble`] documents. A raw evaluation: it does not check its arguments."
        ));
        quote! {
            #docs
            pub fn branch_of(&self, #input: T, #position: &#unknowns) -> #output {
                #value
            }
        }
    }

    /// `impl mechgen::Kinematics`, which lets the runtime's sweep walk the mechanism. Needs
    /// the velocity for its predictor.
    fn kinematics_impl(&self) -> TokenStream {
        if !self.model.outputs.velocity {
            return TokenStream::new();
        }
        let name = &self.model.name;
        let ty = &self.unknowns_type;
        let count = Literal::usize_unsuffixed(self.model.unknowns.len());
        let (input, guess, options, position) = (
            local("input"),
            arg("guess"),
            arg("options"),
            arg("position"),
        );
        let (a, b, input_a, input_b) = (local("a"), local("b"), local("input_a"), local("input_b"));
        let same_branch = if self
            .equations
            .closed_form
            .as_ref()
            .is_some_and(|steps| steps.iter().any(|s| s.case.has_branches()))
        {
            quote! {
                self.branch_of(#input_a, &#ty::from_array(#a))
                    == self.branch_of(#input_b, &#ty::from_array(#b))
            }
        } else {
            // No closed form defines branches: the sweep relies on its other checks.
            quote! {
                let _ = (#input_a, #a, #input_b, #b);
                true
            }
        };
        quote! {
            impl<T: ::mechgen::Real> ::mechgen::Kinematics<T, #count> for #name<T> {
                fn solve_near(
                    &self,
                    #input: T,
                    #guess: [T; #count],
                    #options: &::mechgen::NewtonOptions<T>,
                ) -> ::core::result::Result<::mechgen::Solved<[T; #count], T>, ::mechgen::Error<T>> {
                    self.position(#input, &#ty::from_array(#guess), #options)
                        .map(|solved| solved.map(|value| value.to_array()))
                }

                fn slope(
                    &self,
                    #input: T,
                    #position: [T; #count],
                ) -> ::core::result::Result<[T; #count], ::mechgen::Error<T>> {
                    self.velocity(#input, &#ty::from_array(#position), T::one())
                        .map(|rates| rates.to_array())
                }

                fn same_branch(
                    &self,
                    #input_a: T,
                    #a: [T; #count],
                    #input_b: T,
                    #b: [T; #count],
                ) -> bool {
                    #same_branch
                }
            }
        }
    }
}

/// A closed-form case's complex coefficients, in the order its runtime solver takes them.
fn coefficients(case: &Case) -> Vec<ExprId> {
    let vectors = match case {
        Case::TwoLengths { k, v1, v2 } => [k, v1, v2],
        Case::LengthAndOwnAngle { k, w0, w1 } => [k, w0, w1],
        Case::LengthAndOtherAngle { k, v, w0 } => [k, v, w0],
        Case::TwoAngles { k, w1, w2 } => [k, w1, w2],
    };
    vectors.into_iter().flatten().copied().collect()
}

/// `(x, y)` pairs of emitted coefficients as `mechgen::Vec2` values.
fn complex_values(components: &[Emitted]) -> Vec<TokenStream> {
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
fn branch_rule(case: &Case, a: &str, b: &str) -> String {
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

/// The named parts of a point's acceleration, as fields of `mechgen::AccelerationParts`.
const ACCELERATION_PARTS: [&str; 4] = ["tangential", "normal", "sliding", "coriolis"];

/// The locals holding a point's components: `{point}_x`, `{point}_y` for one vector, or
/// `{point}_{part}_x`, `{point}_{part}_y` for named parts.
fn component_names(point: &str, parts: &[&str]) -> Vec<[String; 2]> {
    if parts.is_empty() {
        vec![[format!("{point}_x"), format!("{point}_y")]]
    } else {
        parts
            .iter()
            .map(|part| [format!("{point}_{part}_x"), format!("{point}_{part}_y")])
            .collect()
    }
}

/// `#[doc]` attributes for `text`, one per line, each with the space `///` would give, and
/// long lines wrapped so the expansion reads like hand-written docs.
fn doc(text: &str) -> TokenStream {
    const WIDTH: usize = 88;
    let mut lines = Vec::new();
    for paragraph_line in text.lines() {
        let mut line = String::new();
        for word in unbreakable_words(paragraph_line) {
            if !line.is_empty() && line.len() + 1 + word.len() > WIDTH {
                lines.push(std::mem::take(&mut line));
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(&word);
        }
        lines.push(line);
    }
    let attributes = lines.iter().map(|line| {
        let line = format!(" {line}");
        quote!(#[doc = #line])
    });
    quote!(#(#attributes)*)
}

/// The words of `line`, with each `code span` kept whole so wrapping never splits one.
fn unbreakable_words(line: &str) -> Vec<String> {
    let mut words: Vec<String> = Vec::new();
    let mut in_code = false;
    for word in line.split(' ') {
        match words.last_mut() {
            Some(last) if in_code => {
                last.push(' ');
                last.push_str(word);
            }
            _ => words.push(word.to_string()),
        }
        if word.matches('`').count() % 2 == 1 {
            in_code = !in_code;
        }
    }
    words
}

fn matrix(entries: &[Emitted], count: usize) -> TokenStream {
    let rows = entries.chunks(count).map(|row| quote!([#(#row),*]));
    quote!([#(#rows),*])
}

fn unit(kind: Kind) -> &'static str {
    match kind {
        Kind::Length => "a length",
        Kind::Angle => "an angle, in radians",
    }
}

/// The user's doc comments, or `fallback` when there are none.
fn docs_or(docs: &[syn::Attribute], fallback: &str) -> TokenStream {
    if docs.is_empty() {
        quote!(#[doc = #fallback])
    } else {
        quote!(#(#docs)*)
    }
}
