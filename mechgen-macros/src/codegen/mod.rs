//! Emits the generated items: the mechanism struct, its unknowns and points types, and the
//! solver functions the declaration asked for.
//!
//! One [`Generator`] holds what every emitter shares (the model, the equations, the names
//! it reserves, and the helpers that turn expressions into blocks); each submodule adds the
//! functions for one kind of output in its own `impl Generator`.

mod branches;
mod closed_forms;
mod design;
mod docs;
mod emit;
mod evaluators;
mod newton;
mod normalise;
mod points;
mod prepared;
pub(crate) mod rates;
mod reduced;
mod scenes;
mod sensitivities;
mod timed;
mod types;

use std::collections::BTreeSet;

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

use crate::model::{Kind, Model, Symbol, SymbolRef};
use crate::symbolic::{Equations, ExprId, Var};
use docs::doc;
use emit::{Block, Context, Emitted, emit, local};
use points::{ACCELERATION_PARTS, component_names};
use syn::ext::IdentExt;

pub fn generate(model: &Model, equations: &Equations) -> TokenStream {
    let generator = Generator::new(model, equations);
    let mechanism = generator.mechanism_struct();
    let unknowns = generator.unknowns_struct();
    let points = generator.points_struct();
    let functions = generator.functions();
    let kinematics = generator.kinematics_impl();
    let design = generator.design_impl();
    let scenes = generator.scene_items();
    let newton = generator.newton_items();
    let sensitivities = generator.sensitivities_struct();
    let branches = generator.branches_struct();
    let name = &model.name;
    quote! {
        #mechanism
        #unknowns
        #points
        #branches
        #sensitivities
        #kinematics
        #design
        #scenes
        #newton
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
    /// Rate and acceleration names of each input and each unknown (`theta2_dot`, ...).
    input_dots: Vec<Ident>,
    input_ddots: Vec<Ident>,
    unknown_dots: Vec<Ident>,
    unknown_ddots: Vec<Ident>,
    /// Every generated name a function body can see besides its own temporaries.
    reserved: BTreeSet<String>,
}

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
const ARGUMENT_NAMES: [&str; 22] = [
    "converged",
    "scale",
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
    "reduced",
    "constants",
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
        let input_dots: Vec<Ident> = model.inputs.iter().map(|u| derived(u, "dot")).collect();
        let input_ddots: Vec<Ident> = model.inputs.iter().map(|u| derived(u, "ddot")).collect();
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
                input_dots
                    .iter()
                    .chain(&input_ddots)
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
            .chain(model.params.iter().flat_map(|param| {
                let per_point = model.points.iter().flat_map(|point| {
                    sensitivities::sensitivity_components(&point.name, &param.name)
                });
                std::iter::once(sensitivities::sensitivity_name(&param.name)).chain(per_point)
            }))
            .collect();
        Generator {
            model,
            equations,
            unknowns_type: format_ident!("{}Unknowns", model.name),
            points_type: format_ident!("{}Points", model.name),
            input_dots,
            input_ddots,
            unknown_dots,
            unknown_ddots,
            reserved,
        }
    }

    fn var_name(&self, var: Var) -> Ident {
        match var {
            Var::Value(symbol) => self.model.symbol(symbol).name.clone(),
            Var::Rate(SymbolRef::Input(i)) => self.input_dots[i].clone(),
            Var::Rate(SymbolRef::Unknown(i)) => self.unknown_dots[i].clone(),
            Var::Accel(SymbolRef::Input(i)) => self.input_ddots[i].clone(),
            Var::Accel(SymbolRef::Unknown(i)) => self.unknown_ddots[i].clone(),
            Var::Aux(k) => local(&format!("aux{k}")),
            Var::Unscale => local("unscale"),
            // Parameters are constant: the graph never holds their rates.
            Var::Rate(SymbolRef::Param(i)) | Var::Accel(SymbolRef::Param(i)) => {
                self.model.params[i].name.clone()
            }
        }
    }

    /// The inputs' names, in declaration order (the generated functions' first arguments).
    fn inputs(&self) -> Vec<&Ident> {
        self.model.inputs.iter().map(|input| &input.name).collect()
    }

    /// `theta2: T` for each input: the generated functions' first parameters.
    fn input_params(&self) -> TokenStream {
        let inputs = self.inputs();
        quote!(#(#inputs: T),*)
    }

    /// `theta2` for each input, to pass them on.
    fn input_args(&self) -> TokenStream {
        let inputs = self.inputs();
        quote!(#(#inputs),*)
    }

    /// The inputs' names for docs, each in backticks where the text has them:
    /// `` theta1`, `theta4 `` inside `` `…` ``.
    fn inputs_text(&self) -> String {
        names_text(self.inputs())
    }

    /// [`Self::inputs_text`] for the inputs' rates.
    fn input_dots_text(&self) -> String {
        names_text(&self.input_dots)
    }

    /// [`Self::inputs_text`] for the inputs' accelerations.
    fn input_ddots_text(&self) -> String {
        names_text(&self.input_ddots)
    }

    /// `check_finite(&[(theta2_dot, "input rate `theta2_dot`"), ...])?;`: each input's rate
    /// and acceleration, named for blame.
    fn input_rates_check(&self) -> TokenStream {
        let blames = &self.input_blames(2)[self.model.inputs.len()..];
        quote!(::mechgen::__private::check_finite(&[#(#blames),*])?;)
    }

    /// "the input", or "the inputs" where there are several, for docs.
    fn the_input(&self) -> &'static str {
        if self.model.inputs.len() == 1 {
            "the input"
        } else {
            "the inputs"
        }
    }

    /// `theta2_dot: T` for each input.
    fn input_dot_params(&self) -> TokenStream {
        let dots = &self.input_dots;
        quote!(#(#dots: T),*)
    }

    /// `theta2_dot` for each input.
    fn input_dot_args(&self) -> TokenStream {
        let dots = &self.input_dots;
        quote!(#(#dots),*)
    }

    /// `theta2_ddot: T` for each input.
    fn input_ddot_params(&self) -> TokenStream {
        let ddots = &self.input_ddots;
        quote!(#(#ddots: T),*)
    }

    /// `theta2_ddot` for each input.
    fn input_ddot_args(&self) -> TokenStream {
        let ddots = &self.input_ddots;
        quote!(#(#ddots),*)
    }

    /// The input an error names ([`mechgen::Error::CannotAssemble`]'s `input`): the first,
    /// where a mechanism has several.
    fn first_input(&self) -> &Ident {
        &self.model.inputs[0].name
    }

    /// `(theta2, "input `theta2`")` for each input, then each input's rate and acceleration
    /// up to `order` (0: none, 1: rates, 2: accelerations too): what a failure can blame.
    fn input_blames(&self, order: usize) -> Vec<TokenStream> {
        let label = |what: &str, name: &Ident| format!("{what} `{}`", name.unraw());
        let mut blames: Vec<TokenStream> = self
            .inputs()
            .into_iter()
            .map(|name| {
                let label = label("input", name);
                quote!((#name, #label))
            })
            .collect();
        let orders = [
            ("input rate", &self.input_dots),
            ("input acceleration", &self.input_ddots),
        ];
        for (what, names) in orders.into_iter().take(order) {
            blames.extend(names.iter().map(|name| {
                let label = label(what, name);
                quote!((#name, #label))
            }));
        }
        blames
    }

    /// The parameters that are lengths, which a mechanism scaled to its size multiplies.
    pub(super) fn length_params(&self) -> Vec<&Ident> {
        self.model
            .params
            .iter()
            .filter(|param| param.kind == Kind::Length)
            .map(|param| &param.name)
            .collect()
    }

    /// The parameters that are lengths and make the loops' magnitudes (themselves, or
    /// through a formula): what a scene kernel's scale brings to about 1. A length that only
    /// places a point (a coupler point's distance) is left out: however long, it must not
    /// shrink the loops, whose closed forms multiply their lengths four at a time, into
    /// underflow.
    fn loop_length_params(&self) -> Vec<&Ident> {
        let mut in_loops = BTreeSet::new();
        for term in self.model.loops.iter().flat_map(|sum| &sum.terms) {
            for symbol in term.magnitude.coefficients.keys() {
                if let SymbolRef::Param(i) = symbol {
                    in_loops.insert(*i);
                }
            }
            for (_, formula) in &term.magnitude.formulas {
                formula.params(&mut in_loops);
            }
        }
        self.model
            .params
            .iter()
            .enumerate()
            .filter(|(i, param)| param.kind == Kind::Length && in_loops.contains(i))
            .map(|(_, param)| &param.name)
            .collect()
    }

    /// The fields of `self` scaled by `scale` (a power of two): its lengths times it, its
    /// angles as they are.
    fn scaled_fields(&self, scale: &Ident) -> Vec<TokenStream> {
        if self.model.params.is_empty() {
            let scalar = types::scalar_field();
            return vec![quote!(#scalar: ::core::marker::PhantomData)];
        }
        self.model
            .params
            .iter()
            .map(|param| {
                let field = &param.name;
                if param.kind == Kind::Length {
                    quote!(#field: self.#field * #scale)
                } else {
                    quote!(#field: self.#field)
                }
            })
            .collect()
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
        let (
            bindings,
            Block {
                mut statements,
                outputs,
                ..
            },
        ) = self.block_with(outputs, bindings, &[], &|_| 0);
        let statements = statements.pop().unwrap_or_default();
        (quote!(#bindings #(#statements)*), outputs)
    }

    /// Emits `outputs` after another block in the same function: its own temporaries avoid
    /// the names in `taken`, and it binds from `self` only the parameters that `bound` (what
    /// the earlier block read, and so bound) lacks. Returns those bindings, the statements
    /// by stage (at least `stages` of them) and the outputs.
    fn block_after(
        &self,
        outputs: &[ExprId],
        presets: &[(ExprId, Ident, usize)],
        stage: &dyn Fn(Var) -> usize,
        taken: impl IntoIterator<Item = String>,
        bound: &BTreeSet<Var>,
        stages: usize,
    ) -> (TokenStream, Vec<Vec<TokenStream>>, Vec<Emitted>) {
        let mut reserved = self.reserved.clone();
        reserved.extend(taken);
        let context = Context {
            reserved: &reserved,
            presets,
            stage,
        };
        let Block {
            mut statements,
            outputs,
            used,
            ..
        } = emit(
            &self.equations.graph,
            outputs,
            &|var| self.var_name(var),
            &context,
        );
        statements.resize(stages.max(statements.len()), Vec::new());
        let unbound: BTreeSet<Var> = used.difference(bound).copied().collect();
        let bindings = self.parameter_bindings(&unbound, quote!(self));
        (bindings, statements, outputs)
    }

    /// Emits `outputs`, with the `let`s that bind the parameters and unknowns they read (as
    /// `bindings` says), and the statements by stage (see [`Context::stage`]).
    fn block_with(
        &self,
        outputs: &[ExprId],
        bindings: Bindings,
        presets: &[(ExprId, Ident, usize)],
        stage: &dyn Fn(Var) -> usize,
    ) -> (TokenStream, Block) {
        let mode = bindings;
        let context = Context {
            reserved: &self.reserved,
            presets,
            stage,
        };
        let block = emit(
            &self.equations.graph,
            outputs,
            &|var| self.var_name(var),
            &context,
        );
        let used = &block.used;
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
        let unused_inputs = self
            .inputs()
            .into_iter()
            .enumerate()
            .filter(|&(i, _)| {
                mode == Bindings::Arguments && !used.contains(&Var::Value(SymbolRef::Input(i)))
            })
            .map(|(_, input)| quote!(let _ = #input;));
        let bindings = quote! {
            #(#unused_inputs)*
            #(#bindings)*
        };
        (bindings, block)
    }

    fn functions(&self) -> TokenStream {
        let mut functions = vec![
            self.check_finite(),
            self.residual(),
            self.jacobian(),
            self.position(),
            self.condition(),
        ];
        if let Ok(steps) = &self.equations.closed_form {
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
            functions.extend([
                self.acceleration(),
                self.motion_at(),
                self.motion_near(),
                self.prepared_motion_near(),
                self.newton_constructor(),
            ]);
        }
        functions.push(self.scenes_constructor());
        if !self.model.points.is_empty() {
            functions.push(self.points());
            if outputs.velocity {
                functions.push(self.point_velocities());
            }
            if outputs.acceleration {
                functions.extend([self.point_accelerations(), self.point_acceleration_parts()]);
            }
        }
        functions.extend(self.sensitivity_functions());
        quote!(#(#functions)*)
    }

    /// The unknowns struct type, the array type of a residual, and the unknowns' count as
    /// an unsuffixed literal.
    fn signature_types(&self) -> (TokenStream, TokenStream, Literal) {
        let ty = &self.unknowns_type;
        let count = Literal::usize_unsuffixed(self.model.unknowns.len());
        (quote!(#ty<T>), quote!([T; #count]), count)
    }

    /// A checked kinematics function taking the first `arity` of the arguments
    /// (input, position, input rate, velocity, input acceleration, acceleration): it rejects
    /// non-finite parameters and arguments, then runs `body`. With `timed` (what its output
    /// is: the unknowns' rates or accelerations), it runs
    /// `body` on the mechanism as given only where its size and the input rates are well
    /// inside the float's range, and elsewhere, out of line, on the mechanism scaled by a
    /// power of two with time counted in another (see [`normalise`]).
    fn checked_function(
        &self,
        name: &str,
        docs: &str,
        arity: usize,
        output: &TokenStream,
        body: TokenStream,
        timed: Option<timed::RatesOutput>,
    ) -> TokenStream {
        let inputs = self.input_args();
        let (unknowns, _, _) = self.signature_types();
        let scalars = [
            (None, self.inputs().into_iter().cloned().collect::<Vec<_>>()),
            (Some("input rate"), self.input_dots.clone()),
            (Some("input acceleration"), self.input_ddots.clone()),
        ];
        let mut parameters = Vec::new();
        let mut scalar_checks = Vec::new();
        let mut unknowns_checks = Vec::new();
        for index in 0..arity {
            if index % 2 == 0 {
                let (label, names) = &scalars[index / 2];
                for name in names {
                    parameters.push(quote!(#name: T));
                    if let Some(label) = label {
                        let label = format!("{label} `{name}`");
                        scalar_checks.push(quote!((#name, #label)));
                    }
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
        if let Some(rates) = timed {
            return self.normalised_rates_function(
                &name,
                docs,
                arity,
                output,
                quote!(self.mechgen_check_finite(#inputs)?; #scalar_checks #(#unknowns_checks)*),
                body,
                rates,
            );
        }
        quote! {
            #docs
            pub fn #name(
                &self,
                #(#parameters),*
            ) -> ::core::result::Result<#output, ::mechgen::Error<T>> {
                self.mechgen_check_finite(#inputs)?;
                #scalar_checks
                #(#unknowns_checks)*
                #body
            }
        }
    }
}

/// Names joined for docs, each in backticks where the text has them (see
/// [`Generator::inputs_text`]).
fn names_text<'n>(names: impl IntoIterator<Item = &'n Ident>) -> String {
    names
        .into_iter()
        .map(|name| name.to_string())
        .collect::<Vec<_>>()
        .join("`, `")
}

fn matrix(entries: &[Emitted], count: usize) -> TokenStream {
    let rows = entries.chunks(count).map(|row| quote!([#(#row),*]));
    quote!([#(#rows),*])
}
