//! One scene's kernel: the statements and auxiliary values in stage order, the constants and
//! parameters it reads from `self`, and its outputs, then the fast kernel (one test at the
//! end) or the checked one (its way out, which says why), or these pieces handed to the
//! batch form. Separate because it is the one body every form of a scene shares.

use std::collections::BTreeSet;

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use syn::ext::IdentExt;

use super::auxiliary::{KernelKind, aux_arguments, needed_aux};
use super::batch::BatchParts;
use super::constants::Constants;
use super::{Mode, scene_outputs};
use crate::codegen::docs::{doc, docs_or};
use crate::codegen::emit::{Context, Emitted, children, emit, local};
use crate::codegen::{Generator, arg};
use crate::model::{Kind, SymbolRef};
use crate::scene::{Order, Quantity, Scene};
use crate::symbolic::{AuxKind, ExprId, Graph, Node, Straight, Var};

impl Generator<'_> {
    /// One scene's kernel, in `mode`: the auxiliary values it needs, each after the
    /// statements its arguments read, then its outputs.
    pub(super) fn kernel(
        &self,
        scene: &Scene,
        straight: &Straight,
        constants: &Constants,
        mode: Mode,
    ) -> TokenStream {
        let lanes = mode == Mode::Lanes;
        let graph = &self.equations.graph;
        let input = &self.model.inputs[0].name;
        let (input_dot, input_ddot) = (&self.input_dots[0], &self.input_ddots[0]);
        let order = scene.order();
        let outputs = scene_outputs(scene, straight);
        let needed = needed_aux(graph, straight, &outputs, mode);

        let constant_names: Vec<Ident> = (0..constants.ids.len())
            .map(|k| local(&format!("constant_{k}")))
            .collect();
        let mut presets: Vec<(ExprId, Ident, usize)> = constants
            .ids
            .iter()
            .zip(&constant_names)
            .map(|(&id, name)| (id, name.clone(), 0))
            .collect();
        let mut reserved = self.reserved.clone();
        reserved.extend(constant_names.iter().map(Ident::to_string));
        // The input's sine and cosine come first, before anything is read from `self`, so
        // that nothing lives across the call.
        let input_trig = graph
            .lookup(Node::Var(Var::Value(SymbolRef::Input(0))))
            .filter(|_| self.model.inputs[0].kind == crate::model::Kind::Angle)
            .map(|var| {
                let stem = input.unraw().to_string();
                let (sin, cos) = (local(&format!("sin_{stem}")), local(&format!("cos_{stem}")));
                for (node, name) in [(Node::Sin(var), &sin), (Node::Cos(var), &cos)] {
                    if let Some(id) = graph.lookup(node) {
                        presets.push((id, name.clone(), 0));
                    }
                }
                reserved.extend([sin.to_string(), cos.to_string()]);
                if lanes {
                    quote!(let (#sin, #cos) = ::mechgen::fast::sin_cos(#input);)
                } else {
                    quote!(let (#sin, #cos) = ::mechgen::__private::sin_cos(#input);)
                }
            });
        // Auxiliary value k is known from stage k + 1.
        let stage = |var: Var| match var {
            Var::Aux(k) => k as usize + 1,
            _ => 0,
        };
        let context = Context {
            reserved: &reserved,
            presets: &presets,
            stage: &stage,
        };
        let arguments: Vec<ExprId> = needed
            .iter()
            .flat_map(|&k| aux_arguments(&straight.aux[k], mode))
            .collect();
        let roots: Vec<ExprId> = arguments.iter().chain(&outputs).copied().collect();
        let block = emit(graph, &roots, &|var| self.var_name(var), &context);
        let mut statements = block.statements;
        statements.resize(straight.aux.len() + 1, Vec::new());
        let mut emitted = block.outputs.into_iter();

        // A failure blames a non-finite argument if there is one.
        let mut labelled = vec![(input, format!("input `{}`", input.unraw()))];
        if order >= Order::Rate {
            labelled.push((input_dot, format!("input rate `{input_dot}`")));
        }
        if order >= Order::Acceleration {
            labelled.push((input_ddot, format!("input acceleration `{input_ddot}`")));
        }
        let inputs = {
            let pairs = labelled.iter().map(|(name, label)| quote!((#name, #label)));
            quote!([#(#pairs),*])
        };

        // A block's rates are refused where they would be less accurate than required, for
        // the highest order the scene asks for.
        let (rates_threshold, rates_threshold_squared, rates_order) =
            if order >= Order::Acceleration {
                (
                    quote!(self.rate_limits.thresholds[1]),
                    quote!(self.rate_limits.squared_thresholds[1]),
                    format_ident!("Acceleration"),
                )
            } else {
                (
                    quote!(self.rate_limits.thresholds[0]),
                    quote!(self.rate_limits.squared_thresholds[0]),
                    format_ident!("Velocity"),
                )
            };
        let kind = KernelKind {
            inputs: inputs.clone(),
            mode,
            rates_threshold,
            rates_threshold_squared,
            rates_order,
        };
        // Statements of stage k, then auxiliary value k; an angle that only an output reads
        // comes last (see `outputs_only`).
        let late = if lanes {
            BTreeSet::new()
        } else {
            outputs_only(graph, straight, &needed, &arguments, &outputs)
        };
        let mut body = Vec::new();
        let mut angles = Vec::new();
        let mut branches =
            self.branch_choices(self.equations.closed_form.as_deref().unwrap_or_default());
        for (k, stage_statements) in statements.iter().enumerate() {
            body.extend(stage_statements.iter().cloned());
            if needed.contains(&k) {
                let definition =
                    self.aux_definition(k, straight, &mut emitted, &mut branches, &kind);
                if late.contains(&k) {
                    angles.push(definition);
                } else {
                    body.push(definition);
                }
            }
        }
        body.extend(angles);
        let values: Vec<Emitted> = emitted.collect();

        // The constants and parameters the kernel reads, from `self`, each with its local.
        let read = read_presets(graph, &roots, &presets);
        let mut bindings: Vec<(Ident, TokenStream)> = constants
            .ids
            .iter()
            .zip(&constant_names)
            .enumerate()
            .filter(|(_, (id, _))| read.contains(id))
            .map(|(k, (_, name))| {
                let k = Literal::usize_unsuffixed(k);
                (name.clone(), quote!(let #name = self.constants[#k];))
            })
            .collect();
        bindings.extend(block.used.iter().filter_map(|&var| match var {
            Var::Value(SymbolRef::Param(i)) => {
                let name = &self.model.params[i].name;
                Some((name.clone(), quote!(let #name = self.scaled.#name;)))
            }
            _ => None,
        }));
        // The outputs in lengths are back in the mechanism's units through `1/scale`, which
        // mostly sits in a constant; the kernel reads it where one does not hold it.
        if block.used.contains(&Var::Unscale) {
            let unscale = local("unscale");
            bindings.push((unscale.clone(), quote!(let #unscale = self.unscale;)));
        }
        // A length input, its rate and acceleration, in the scaled units.
        let scaled_inputs = |names: &[&Ident]| {
            if self.model.inputs[0].kind != Kind::Length {
                return TokenStream::new();
            }
            let names = names.iter();
            quote!(#(let #names = #names * self.scale;)*)
        };
        let mut rate_names = Vec::new();
        if order >= Order::Rate {
            rate_names.push(input_dot);
        }
        if order >= Order::Acceleration {
            rate_names.push(input_ddot);
        }
        let scaled_rates = scaled_inputs(&rate_names);
        let scaled_input = scaled_inputs(&[input]);

        // Outputs in the order listed, checked finite together; each with its time order.
        let mut values = values.into_iter();
        let mut checked = Vec::new();
        let mut checked_orders = Vec::new();
        let fields: Vec<TokenStream> = scene
            .items
            .iter()
            .map(|item| {
                let field = &item.field;
                let count = if matches!(item.quantity, Quantity::Point(_)) {
                    2
                } else {
                    1
                };
                let parts: Vec<TokenStream> = values
                    .by_ref()
                    .take(count)
                    .map(|value| {
                        let value = quote!(#value);
                        if lanes {
                            return value;
                        }
                        let index = Literal::usize_unsuffixed(checked.len());
                        checked.push(quote!(#value));
                        checked_orders.push(item.order);
                        let checked_values = local("values");
                        quote!(#checked_values[#index])
                    })
                    .collect();
                match item.quantity {
                    Quantity::Point(_) => {
                        let [x, y] = [&parts[0], &parts[1]];
                        quote!(#field: ::mechgen::Vec2 { x: #x, y: #y })
                    }
                    Quantity::Unknown(_) => {
                        let value = &parts[0];
                        quote!(#field: #value)
                    }
                }
            })
            .collect();
        let checked_values = local("values");

        let steps = self.equations.closed_form.as_deref().unwrap_or_default();
        let branch_parameter = self.branch_parameter(steps);
        let mut arguments = Vec::new();
        if order >= Order::Rate {
            arguments.push(quote!(#input_dot: T,));
        }
        if order >= Order::Acceleration {
            arguments.push(quote!(#input_ddot: T,));
        }
        let output_type = self.scene_output_type(scene);
        let name = &scene.name;
        let fallback = format!(
            "Scene `{}`: {} at `{input}`, on the chosen assembly branch.",
            name.unraw(),
            scene
                .items
                .iter()
                .map(|item| format!("`{}`", item.field.unraw()))
                .collect::<Vec<_>>()
                .join(", ")
        );
        if lanes {
            return self.batch(
                scene,
                &branch_parameter,
                &arguments,
                BatchParts {
                    input_trig,
                    bindings: bindings.into_iter().map(|(_, binding)| binding).collect(),
                    // In the loop, so the redo of a failed lane passes the rates as given.
                    scaled_input: quote!(#scaled_input #scaled_rates),
                    body,
                    fields,
                },
            );
        }
        let checked_name = checked_kernel(name);
        // What the scalar kernels, fast and checked, compute before their outputs; the
        // checked one with time counted in units that bring the rates near 1
        // (`mechgen::__private::rate_scale`): exact, so the same bits where the fast one
        // answers, and the outputs where a squared rate in the scaled units overflows (a
        // tiny mechanism turning fast) and the fast one gives up.
        let body = read_late(bindings, body, &checked);
        let (tempo, untempo) = (local("tempo"), local("untempo"));
        let timed = if mode == Mode::Checked && order >= Order::Rate {
            let (accelerations, scaled_ddot) = if order >= Order::Acceleration {
                (
                    quote!(&[#input_ddot]),
                    quote!(let #input_ddot = #input_ddot * #tempo * #tempo;),
                )
            } else {
                (quote!(&[]), TokenStream::new())
            };
            quote! {
                let (#tempo, #untempo) =
                    ::mechgen::__private::rate_scale(&[#input_dot], #accelerations);
                let #input_dot = #input_dot * #tempo;
                #scaled_ddot
            }
        } else {
            TokenStream::new()
        };
        let computed = quote! {
            #input_trig
            #scaled_input
            #scaled_rates
            #timed
            #(#body)*
        };
        if mode == Mode::Checked {
            let checked: Vec<TokenStream> = checked
                .iter()
                .zip(&checked_orders)
                .map(|(value, order)| match order {
                    Order::Value => value.clone(),
                    Order::Rate => quote!(::mechgen::__private::retimed(#value, #untempo, 1)),
                    Order::Acceleration => {
                        quote!(::mechgen::__private::retimed(#value, #untempo, 2))
                    }
                })
                .collect();
            let docs = doc(&format!(
                "[`Self::{}`] with each step that can fail checked where it happens: the fast \
                 kernel's way out, which says why it failed.",
                name.unraw()
            ));
            return quote! {
                #docs
                #[cold]
                #[inline(never)]
                fn #checked_name(
                    &self,
                    #input: T #branch_parameter,
                    #(#arguments)*
                ) -> ::core::result::Result<#output_type<T>, ::mechgen::Error<T>> {
                    #computed
                    let #checked_values = ::mechgen::__private::finite_all([#(#checked),*], "scene output")
                        .map_err(|error| ::mechgen::__private::blame(#inputs, error))?;
                    ::core::result::Result::Ok(#output_type { #(#fields),* })
                }
            };
        }
        // An output that another one computes with is non-finite only if that one is too.
        let covered = covered_outputs(graph, straight, &outputs);
        let tested = if covered.is_empty() {
            quote!(&#checked_values)
        } else {
            let tested = (0..outputs.len())
                .filter(|k| !covered.contains(k))
                .map(Literal::usize_unsuffixed);
            quote!(&[#(#checked_values[#tested]),*])
        };
        // The arguments as given, for the checked kernel: a length input is rescaled below.
        let passed = self.checked_arguments(scene);
        let (given, keep) = if self.model.inputs[0].kind == Kind::Length {
            let given: Vec<Ident> = passed
                .iter()
                .map(|name| local(&format!("given_{}", name.unraw())))
                .collect();
            let keep = quote!(#(let #given = #passed;)*);
            (given, keep)
        } else {
            (passed, TokenStream::new())
        };
        let docs = docs_or(&scene.docs, &fallback);
        let slow_rates = if order >= Order::Rate {
            "\n\nThe input rate is taken as given, for speed: one whose square, times the \
             shortest link over the longest or times the longest, is not a normal number \
             (below about 1e-145 rad/s in f64, 1e-15 in f32; 2e-4 rad/s on a mechanism of \
             1e-300 in f64) gives rates and accelerations of lengths and points that \
             underflow; the general `motion` counts time in units that keep it in range."
        } else {
            ""
        };
        let errors = doc(&format!(
            "Errors: [`mechgen::Error::CannotAssemble`] outside the range of motion; \
             [`mechgen::Error::Singular`] where rates are asked for at a toggle; a non-finite \
             argument or result.{slow_rates}"
        ));
        let (public_parameter, conversion) = self.public_branch_parameter(steps);
        quote! {
            #docs
            ///
            #errors
            #[inline(always)]
            pub fn #name(
                &self,
                #input: T #public_parameter,
                #(#arguments)*
            ) -> ::core::result::Result<#output_type<T>, ::mechgen::Error<T>> {
                #conversion
                #keep
                #computed
                // Every step that can fail gave NaN or an infinity, which reaches an output:
                // one test here stands for all of them, and the checked kernel says why.
                let #checked_values = [#(#checked),*];
                if ::mechgen::__private::outputs_finite(#tested) {
                    ::core::result::Result::Ok(#output_type { #(#fields),* })
                } else {
                    self.#checked_name(#(#given),*)
                }
            }
        }
    }

    /// The kernel's arguments after the input, by name: the branch choice, if any, and the
    /// input's rate and acceleration, as far as the scene's order reads them.
    pub(super) fn checked_arguments(&self, scene: &Scene) -> Vec<Ident> {
        let order = scene.order();
        let steps = self.equations.closed_form.as_deref().unwrap_or_default();
        let mut pass = vec![self.model.inputs[0].name.clone()];
        match steps.iter().filter(|step| step.case.has_branches()).count() {
            0 => {}
            1 => pass.push(arg("branch")),
            _ => pass.push(arg("branches")),
        }
        if order >= Order::Rate {
            pass.push(self.input_dots[0].clone());
        }
        if order >= Order::Acceleration {
            pass.push(self.input_ddots[0].clone());
        }
        pass
    }
}

/// `body` with each of `bindings` (a local read from `self`) just before the first
/// statement that reads it, or at the end if only the outputs (`tail`) do. A call out of
/// line (an angle's arc sine) may write memory as far as the compiler knows, so a value read
/// before it and used after it is kept on the stack across it; read after it, it is read
/// once, where it is used.
fn read_late(
    bindings: Vec<(Ident, TokenStream)>,
    body: Vec<TokenStream>,
    tail: &[TokenStream],
) -> Vec<TokenStream> {
    let mut at: Vec<Vec<TokenStream>> = vec![Vec::new(); body.len() + 1];
    for (name, binding) in bindings {
        let first = body
            .iter()
            .position(|statement| mentions(statement, &name))
            .unwrap_or(body.len());
        debug_assert!(first < body.len() || tail.iter().any(|value| mentions(value, &name)));
        at[first].push(binding);
    }
    let mut out = Vec::new();
    let mut at = at.into_iter();
    for statement in body {
        out.extend(at.next().into_iter().flatten());
        out.push(statement);
    }
    out.extend(at.flatten());
    out
}

/// Whether `tokens` name the local `name` anywhere.
fn mentions(tokens: &TokenStream, name: &Ident) -> bool {
    tokens.clone().into_iter().any(|tree| match tree {
        proc_macro2::TokenTree::Ident(ident) => ident == *name,
        proc_macro2::TokenTree::Group(group) => mentions(&group.stream(), name),
        _ => false,
    })
}

/// The angle among the `needed` auxiliary values, if it is the only one and nothing but an
/// output reads it: a kernel computes it last, after all its arithmetic. An angle is an arc
/// sine or cosine, a call out of line, across which every value still to be used is kept on
/// the stack; at the end, only the outputs are. Two angles at the end would keep the
/// second's arguments as well across the first call, and two calls in the middle cost less
/// (the four-bar's angles: 3 instructions per call).
fn outputs_only(
    graph: &Graph,
    straight: &Straight,
    needed: &BTreeSet<usize>,
    arguments: &[ExprId],
    outputs: &[ExprId],
) -> BTreeSet<usize> {
    let aux = |id: ExprId| match graph.node(id) {
        Node::Var(Var::Aux(k)) => Some(k as usize),
        _ => None,
    };
    let mut read = BTreeSet::new();
    let mut seen = vec![false; graph.len()];
    let mut stack: Vec<ExprId> = arguments.iter().chain(outputs).copied().collect();
    read.extend(arguments.iter().filter_map(|&id| aux(id)));
    while let Some(id) = stack.pop() {
        if std::mem::replace(&mut seen[id.index()], true) {
            continue;
        }
        for child in children(graph.node(id)) {
            read.extend(aux(child));
            stack.push(child);
        }
    }
    let angles: Vec<usize> = needed
        .iter()
        .copied()
        .filter(|&k| matches!(straight.aux[k], AuxKind::Angle { .. }))
        .collect();
    match angles[..] {
        [k] if !read.contains(&k) => BTreeSet::from([k]),
        _ => BTreeSet::new(),
    }
}

/// The outputs (by index) that the fast kernel's finiteness test may leave out: each is a
/// term or factor, through sums, products, negations, square roots and named values, of
/// another output that it tests. An infinity or NaN there makes that output an infinity or
/// NaN too (`0·∞` is NaN; only a reciprocal or a choice would stop it, and neither is
/// followed), so testing that one tests both.
fn covered_outputs(graph: &Graph, straight: &Straight, outputs: &[ExprId]) -> BTreeSet<usize> {
    let reach = |root: ExprId| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![root];
        while let Some(id) = stack.pop() {
            let node = graph.node(id);
            let next: Vec<ExprId> = match node {
                Node::Add(..) | Node::Mul(..) | Node::Neg(_) | Node::Sqrt(_) => {
                    children(node).collect()
                }
                Node::Var(Var::Aux(k)) => match straight.aux[k as usize] {
                    AuxKind::Bind(x) => vec![x],
                    _ => Vec::new(),
                },
                _ => Vec::new(),
            };
            for child in next {
                if seen.insert(child) {
                    stack.push(child);
                }
            }
        }
        seen
    };
    let reaches: Vec<BTreeSet<ExprId>> = outputs.iter().map(|&id| reach(id)).collect();
    let mut covered = BTreeSet::new();
    for (k, &output) in outputs.iter().enumerate() {
        let by_another = (0..outputs.len()).any(|other| {
            other != k
                && !covered.contains(&other)
                && (reaches[other].contains(&output) || (outputs[other] == output && other < k))
        });
        if by_another {
            covered.insert(k);
        }
    }
    covered
}

/// The checked kernel of scene `name`.
fn checked_kernel(name: &Ident) -> Ident {
    format_ident!("mechgen_{}_checked", name.unraw())
}

/// The presets (of `presets`) that `roots` read, stopping at presets.
fn read_presets(
    graph: &Graph,
    roots: &[ExprId],
    presets: &[(ExprId, Ident, usize)],
) -> BTreeSet<ExprId> {
    let preset: BTreeSet<ExprId> = presets.iter().map(|(id, _, _)| *id).collect();
    let mut seen = vec![false; graph.len()];
    let mut read = BTreeSet::new();
    let mut stack = roots.to_vec();
    while let Some(id) = stack.pop() {
        if std::mem::replace(&mut seen[id.index()], true) {
            continue;
        }
        if preset.contains(&id) {
            read.insert(id);
        } else {
            stack.extend(children(graph.node(id)));
        }
    }
    read
}
