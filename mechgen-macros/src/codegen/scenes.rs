//! Scene kernels: one straight-line function per declared scene, computing exactly the
//! outputs it lists.
//!
//! What makes them fast: everything that depends on the dimensions alone is computed once,
//! by `scenes()`, into `{Name}Scenes`; the closed forms, rates and points are one expression
//! graph written out as arithmetic (`symbolic::straight`), in which solved angles are read
//! through their unit vectors, so an angle itself (an arc sine or cosine) is paid for only if
//! the scene lists it; the parameters were checked when the constants were made. A step that
//! can fail (a circle that misses, a singular block) is not tested where it happens: it gives
//! NaN or an infinity, which reaches the outputs, and one test of the outputs at the end hands
//! any failure to the scene's checked kernel, which tests each step and says why. Each scene
//! also gets a batch form, `{scene}_batch`, the same arithmetic in a loop the compiler
//! vectorises.

use std::collections::BTreeSet;

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use syn::ext::IdentExt;

use super::docs::{doc, docs_or};
use super::emit::{Context, Emitted, children, emit, local};
use super::{Generator, arg};
use crate::model::{Kind, SymbolRef};
use crate::scene::{Order, Quantity, Scene};
use crate::symbolic::{AuxKind, ExprId, Graph, Node, Straight, Threshold, Var};

/// Expressions that depend on the dimensions alone, computed once per mechanism.
struct Constants {
    /// The hoisted nodes, in arena order; constant `k` is `ids[k]`.
    ids: Vec<ExprId>,
}

impl Generator<'_> {
    fn scenes_type(&self) -> Ident {
        format_ident!("{}Scenes", self.model.name)
    }

    fn scene_output_type(&self, scene: &Scene) -> Ident {
        let camel: String = scene
            .name
            .unraw()
            .to_string()
            .split('_')
            .filter(|part| !part.is_empty())
            .map(|part| {
                let mut chars = part.chars();
                chars
                    .next()
                    .map(|first| first.to_uppercase().chain(chars).collect::<String>())
                    .unwrap_or_default()
            })
            .collect();
        format_ident!("{}{}", self.model.name, camel)
    }

    /// The items for the declared scenes, outside the mechanism's `impl`: the scenes type,
    /// each scene's output struct, and the kernels.
    pub(super) fn scene_items(&self) -> TokenStream {
        let Some(exprs) = &self.equations.scenes else {
            return TokenStream::new();
        };
        let constants = self.constants(exprs);
        let name = &self.model.name;
        let scenes_type = self.scenes_type();
        let count = Literal::usize_unsuffixed(constants.ids.len());
        let outputs = self
            .model
            .scenes
            .iter()
            .map(|scene| self.scene_output(scene));
        let kernels = self.model.scenes.iter().flat_map(|scene| {
            [Mode::Fast, Mode::Checked, Mode::Lanes]
                .map(|mode| self.kernel(scene, exprs, &constants, mode))
        });
        let docs = doc(&format!(
            "[`{name}`]'s scene kernels (see [`{name}::scenes`]): the mechanism, and what \
             depends on its dimensions alone, computed once."
        ));
        quote! {
            #docs
            #[derive(Clone, Copy, Debug)]
            pub struct #scenes_type<T> {
                mechanism: #name<T>,
                /// The mechanism with its lengths times `scale`, a power of two that brings
                /// the longest to about 1: the kernels compute in these units, where no
                /// square overflows or underflows, and give the same angles, bit for bit,
                /// for every power-of-two scaling of a mechanism.
                scaled: #name<T>,
                scale: T,
                unscale: T,
                /// The relative determinants at or below which a block's velocities and
                /// accelerations would be less accurate than `mechgen::Accuracy::required`.
                rate_thresholds: [T; 2],
                constants: [T; #count],
            }
            #(#outputs)*
            #[allow(clippy::possible_missing_comma, clippy::too_many_arguments)]
            impl<T: ::mechgen::Real> #scenes_type<T> {
                /// The mechanism these kernels were made for.
                pub fn mechanism(&self) -> &#name<T> {
                    &self.mechanism
                }

                /// These kernels, with the rates they return required to be within
                /// `accuracy` (each loop's block judged by its own condition), else
                /// [`mechgen::Error::Singular`]; [`mechgen::Accuracy::required`] by default.
                pub fn with_accuracy(self, accuracy: &::mechgen::Accuracy<T>) -> Self {
                    #scenes_type {
                        rate_thresholds: Self::mechgen_rate_thresholds(accuracy),
                        ..self
                    }
                }

                /// The relative determinants below which a block's velocities and
                /// accelerations are less accurate than `accuracy`.
                fn mechgen_rate_thresholds(accuracy: &::mechgen::Accuracy<T>) -> [T; 2] {
                    [
                        ::mechgen::__private::rate_threshold(::mechgen::Order::Velocity, accuracy),
                        ::mechgen::__private::rate_threshold(::mechgen::Order::Acceleration, accuracy),
                    ]
                }
                #(#kernels)*
            }
        }
    }

    /// `scenes()` on the mechanism: checks the parameters and computes the constants.
    pub(super) fn scenes_constructor(&self) -> TokenStream {
        let Some(exprs) = &self.equations.scenes else {
            return TokenStream::new();
        };
        let constants = self.constants(exprs);
        let scenes_type = self.scenes_type();
        let graph = &self.equations.graph;
        let context = Context {
            reserved: &self.reserved,
            presets: &[],
            stage: &|_| 0,
        };
        let block = emit(graph, &constants.ids, &|var| self.var_name(var), &context);
        let scaled = local("scaled");
        let bindings = self.parameter_bindings(&block.used, quote!(#scaled));
        let statements = block.statements.concat();
        let name = &self.model.name;
        let (scale, unscale) = (local("scale"), local("unscale"));
        let lengths = self
            .model
            .params
            .iter()
            .filter(|param| param.kind == Kind::Length)
            .map(|param| &param.name);
        let scaled_fields = self.model.params.iter().map(|param| {
            let field = &param.name;
            if param.kind == Kind::Length {
                quote!(#field: self.#field * #scale)
            } else {
                quote!(#field: self.#field)
            }
        });
        let values = &block.outputs;
        let checks = self.model.params.iter().map(|param| {
            let field = &param.name;
            let label = format!("parameter `{}`", field.unraw());
            quote!((self.#field, #label))
        });
        let names: Vec<String> = self
            .model
            .scenes
            .iter()
            .map(|s| format!("[`{}::{}`]", scenes_type, s.name.unraw()))
            .collect();
        let docs = doc(&format!(
            "The scene kernels ({}), with every quantity that depends on the dimensions alone \
             computed now rather than on each call.\n\nErrors: a non-finite parameter, or a \
             constant derived from them that overflows.",
            names.join(", ")
        ));
        quote! {
            #docs
            pub fn scenes(&self) -> ::core::result::Result<#scenes_type<T>, ::mechgen::Error<T>> {
                ::mechgen::__private::check_finite(&[#(#checks),*])?;
                let (#scale, #unscale) = ::mechgen::__private::length_scale(&[#(self.#lengths),*]);
                let #scaled = #name { #(#scaled_fields),* };
                #bindings
                #(#statements)*
                let constants = ::mechgen::__private::finite(
                    [#(#values),*],
                    "dimension-derived constant",
                )?;
                ::core::result::Result::Ok(#scenes_type {
                    mechanism: *self,
                    scaled: #scaled,
                    scale: #scale,
                    unscale: #unscale,
                    rate_thresholds: #scenes_type::mechgen_rate_thresholds(
                        &::mechgen::Accuracy::required(),
                    ),
                    constants,
                })
            }
        }
    }

    /// `let name = source.field;` for each parameter in `used`.
    pub(super) fn parameter_bindings(
        &self,
        used: &BTreeSet<Var>,
        source: TokenStream,
    ) -> TokenStream {
        let bindings = used.iter().filter_map(|&var| match var {
            Var::Value(SymbolRef::Param(i)) => {
                let name = &self.model.params[i].name;
                Some(quote!(let #name = #source.#name;))
            }
            _ => None,
        });
        quote!(#(#bindings)*)
    }

    /// The dimension-only subexpressions the kernels read, hoisted as large as they come:
    /// a node is hoisted when it depends on parameters alone, is more than a name or a number,
    /// and is read by something that moves (or is itself an output).
    fn constants(&self, straight: &Straight) -> Constants {
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

    /// The struct a scene kernel returns.
    fn scene_output(&self, scene: &Scene) -> TokenStream {
        let ty = self.scene_output_type(scene);
        let vis = &self.model.vis;
        let fields = scene.items.iter().map(|item| {
            let field = &item.field;
            let (what, ty) = match item.quantity {
                Quantity::Unknown(u) => {
                    let unknown = &self.model.unknowns[u];
                    let unit = super::types::unit(unknown.kind);
                    let what = match item.order {
                        Order::Value => format!("Unknown `{}`, {unit}.", unknown.name.unraw()),
                        Order::Rate => format!("The rate of `{}`.", unknown.name.unraw()),
                        Order::Acceleration => {
                            format!("The acceleration of `{}`.", unknown.name.unraw())
                        }
                    };
                    (what, quote!(T))
                }
                Quantity::Point(p) => {
                    let point = self.model.points[p].name.unraw();
                    let what = match item.order {
                        Order::Value => format!("Point `{point}`'s position."),
                        Order::Rate => format!("Point `{point}`'s velocity."),
                        Order::Acceleration => format!("Point `{point}`'s acceleration."),
                    };
                    (what, quote!(::mechgen::Vec2<T>))
                }
            };
            let docs = doc(&what);
            quote!(#docs pub #field: #ty,)
        });
        let docs = doc(&format!(
            "What [`{}::{}`] returns.",
            self.scenes_type(),
            scene.name.unraw()
        ));
        quote! {
            #docs
            #[derive(Clone, Copy, Debug, Default, PartialEq)]
            #vis struct #ty<T> {
                #(#fields)*
            }
        }
    }

    /// `let auxK = …;`: auxiliary value `k` from its emitted arguments (taken from
    /// `emitted`), blaming a non-finite argument among `inputs` when it fails.
    fn aux_definition(
        &self,
        k: usize,
        straight: &Straight,
        emitted: &mut impl Iterator<Item = Emitted>,
        branches: &mut [TokenStream],
        kernel: &KernelKind,
    ) -> TokenStream {
        let KernelKind {
            inputs,
            mode,
            rates_threshold,
            rates_order,
        } = kernel;
        // Fast and batch kernels pass a failure on as NaN, for the checked kernel to explain.
        let lanes = *mode != Mode::Checked;
        let input = &self.model.input.name;
        // A length input was scaled with the mechanism; an error reports it as given.
        let input = if self.model.input.kind == Kind::Length {
            quote!((#input * self.unscale))
        } else {
            quote!(#input)
        };
        let failure = arg("failure");
        let name = self.var_name(Var::Aux(k as u32));
        let kind = &straight.aux[k];
        let args: Vec<Emitted> = emitted
            .by_ref()
            .take(aux_arguments(kind, *mode).len())
            .collect();
        let value = match kind {
            AuxKind::BranchRoot { branch, .. } if lanes => {
                let choice = branches.get_mut(*branch).map(std::mem::take);
                let [plus, minus] = [&args[0], &args[1]];
                quote!(::mechgen::__private::lanes::branch_root(#plus, #minus, #choice.sign::<T>()))
            }
            AuxKind::TriangleRoot { branch, .. } if lanes => {
                let choice = branches.get_mut(*branch).map(std::mem::take);
                let [sum, difference, span] = [&args[0], &args[1], &args[2]];
                quote!(::mechgen::__private::lanes::triangle_root(#sum, #difference, #span, #choice.sign::<T>()))
            }
            AuxKind::Bind(_) => {
                let value = &args[0];
                quote!(#value)
            }
            AuxKind::Inverse(_) if lanes => {
                let x = args[0].receiver();
                quote!(#x.recip())
            }
            AuxKind::InverseDeterminant { threshold, .. } if lanes => {
                let [det, inverse_norms] = [&args[0], &args[1]];
                let threshold = match threshold {
                    Threshold::Position => quote!(T::constant(8.0) * T::epsilon()),
                    Threshold::Rates => rates_threshold.clone(),
                };
                quote!(::mechgen::__private::lanes::inverse_determinant(#det, #inverse_norms, #threshold))
            }
            AuxKind::BranchRoot { branch, .. } => {
                let choice = branches.get_mut(*branch).map(std::mem::take);
                let [plus, minus] = [&args[0], &args[1]];
                quote! {
                    ::mechgen::__private::branch_root(#plus, #minus, #choice.sign::<T>())
                        .map_err(|#failure| ::mechgen::__private::blame(#inputs, #failure.at(#input)))?
                }
            }
            AuxKind::TriangleRoot { branch, .. } => {
                let choice = branches.get_mut(*branch).map(std::mem::take);
                let [sum, difference, span] = [&args[0], &args[1], &args[2]];
                quote! {
                    ::mechgen::__private::triangle_root(#sum, #difference, #span, #choice.sign::<T>())
                        .map_err(|#failure| ::mechgen::__private::blame(#inputs, #failure.at(#input)))?
                }
            }
            AuxKind::Inverse(_) => {
                let x = &args[0];
                quote! {
                    ::mechgen::__private::inverse(#x)
                        .map_err(|#failure| ::mechgen::__private::blame(#inputs, #failure.at(#input)))?
                }
            }
            AuxKind::InverseDeterminant { threshold, .. } => {
                let [det, inverse_norms] = [&args[0], &args[1]];
                let call = match threshold {
                    Threshold::Position => quote! {
                        ::mechgen::__private::inverse_determinant(
                            #det,
                            #inverse_norms,
                            T::constant(8.0) * T::epsilon(),
                        )
                    },
                    Threshold::Rates => quote! {
                        ::mechgen::__private::rates_inverse_determinant(
                            #det,
                            #inverse_norms,
                            #rates_threshold,
                            ::mechgen::Order::#rates_order,
                        )
                    },
                };
                quote! {
                    #call.map_err(|error| ::mechgen::__private::blame(#inputs, error))?
                }
            }
            // In a batch, the branch-free angle vectorises; alone, an arc sine is cheaper.
            AuxKind::Angle { .. } if *mode == Mode::Lanes => {
                let (y, x) = (&args[0], &args[1]);
                quote!(::mechgen::fast::unit_angle(#y, #x))
            }
            AuxKind::Angle { .. } => {
                let (y, x) = (&args[0], &args[1]);
                quote!(::mechgen::__private::unit_angle(#y, #x))
            }
        };
        quote!(let #name = #value;)
    }

    /// One scene's kernel, in `mode`: the auxiliary values it needs, each after the
    /// statements its arguments read, then its outputs.
    fn kernel(
        &self,
        scene: &Scene,
        straight: &Straight,
        constants: &Constants,
        mode: Mode,
    ) -> TokenStream {
        let lanes = mode == Mode::Lanes;
        let graph = &self.equations.graph;
        let input = &self.model.input.name;
        let (input_dot, input_ddot) = (&self.input_dot, &self.input_ddot);
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
            .lookup(Node::Var(Var::Value(SymbolRef::Input)))
            .filter(|_| self.model.input.kind == crate::model::Kind::Angle)
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
                    quote!(let (#sin, #cos) = #input.sin_cos();)
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
        let (rates_threshold, rates_order) = if order >= Order::Acceleration {
            (
                quote!(self.rate_thresholds[1]),
                format_ident!("Acceleration"),
            )
        } else {
            (quote!(self.rate_thresholds[0]), format_ident!("Velocity"))
        };
        let kind = KernelKind {
            inputs: inputs.clone(),
            mode,
            rates_threshold,
            rates_order,
        };
        // Statements of stage k, then auxiliary value k.
        let mut body = Vec::new();
        let mut branches =
            self.branch_choices(self.equations.closed_form.as_deref().unwrap_or_default());
        for (k, stage_statements) in statements.iter().enumerate() {
            body.extend(stage_statements.iter().cloned());
            if needed.contains(&k) {
                body.push(self.aux_definition(k, straight, &mut emitted, &mut branches, &kind));
            }
        }
        let values: Vec<Emitted> = emitted.collect();

        // The constants and parameters the kernel reads, from `self`.
        let read = read_presets(graph, &roots, &presets);
        let constant_bindings = constants
            .ids
            .iter()
            .zip(&constant_names)
            .enumerate()
            .filter(|(_, (id, _))| read.contains(id))
            .map(|(k, (_, name))| {
                let k = Literal::usize_unsuffixed(k);
                quote!(let #name = self.constants[#k];)
            });
        let unscale = local("unscale");
        let parameter_bindings = self.parameter_bindings(&block.used, quote!(self.scaled));
        // The outputs in lengths are back in the mechanism's units through `1/scale`, which
        // mostly sits in a constant; the kernel reads it where one does not hold it.
        let parameter_bindings = if block.used.contains(&Var::Unscale) {
            quote!(#parameter_bindings let #unscale = self.unscale;)
        } else {
            parameter_bindings
        };
        // A length input, its rate and acceleration, in the scaled units.
        let scaled_inputs = |names: &[&Ident]| {
            if self.model.input.kind != Kind::Length {
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

        // Outputs in the order listed, checked finite together.
        let mut values = values.into_iter();
        let mut checked = Vec::new();
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
                    bindings: quote!(#(#constant_bindings)* #parameter_bindings),
                    // In the loop, so the redo of a failed lane passes the rates as given.
                    scaled_input: quote!(#scaled_input #scaled_rates),
                    body,
                    fields,
                },
            );
        }
        let checked_name = checked_kernel(name);
        if mode == Mode::Checked {
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
                    #input_trig
                    #(#constant_bindings)*
                    #parameter_bindings
                    #scaled_input
                    #scaled_rates
                    #(#body)*
                    let #checked_values = ::mechgen::__private::finite_all([#(#checked),*], "scene output")
                        .map_err(|error| ::mechgen::__private::blame(#inputs, error))?;
                    ::core::result::Result::Ok(#output_type { #(#fields),* })
                }
            };
        }
        // The arguments as given, for the checked kernel: a length input is rescaled below.
        let passed = self.checked_arguments(scene);
        let (given, keep) = if self.model.input.kind == Kind::Length {
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
        let errors = doc(
            "Errors: [`mechgen::Error::CannotAssemble`] outside the range of motion; \
             [`mechgen::Error::Singular`] where rates are asked for at a toggle; a non-finite \
             argument or result.",
        );
        quote! {
            #docs
            ///
            #errors
            #[inline(always)]
            pub fn #name(
                &self,
                #input: T #branch_parameter,
                #(#arguments)*
            ) -> ::core::result::Result<#output_type<T>, ::mechgen::Error<T>> {
                #keep
                #input_trig
                #(#constant_bindings)*
                #parameter_bindings
                #scaled_input
                #scaled_rates
                #(#body)*
                // Every step that can fail gave NaN or an infinity, which reaches an output:
                // one test here stands for all of them, and the checked kernel says why.
                let #checked_values = [#(#checked),*];
                if ::mechgen::__private::outputs_finite(&#checked_values) {
                    ::core::result::Result::Ok(#output_type { #(#fields),* })
                } else {
                    self.#checked_name(#(#given),*)
                }
            }
        }
    }

    /// The kernel's arguments after the input, by name: the branch choice, if any, and the
    /// input's rate and acceleration, as far as the scene's order reads them.
    fn checked_arguments(&self, scene: &Scene) -> Vec<Ident> {
        let order = scene.order();
        let steps = self.equations.closed_form.as_deref().unwrap_or_default();
        let mut pass = vec![self.model.input.name.clone()];
        match steps.iter().filter(|step| step.case.has_branches()).count() {
            0 => {}
            1 => pass.push(arg("branch")),
            _ => pass.push(arg("branches")),
        }
        if order >= Order::Rate {
            pass.push(self.input_dot.clone());
        }
        if order >= Order::Acceleration {
            pass.push(self.input_ddot.clone());
        }
        pass
    }

    /// `{scene}_batch(inputs, branch, …, out)`: the scene at every input, into `out`.
    fn batch(
        &self,
        scene: &Scene,
        branch_parameter: &TokenStream,
        arguments: &[TokenStream],
        parts: BatchParts,
    ) -> TokenStream {
        let BatchParts {
            input_trig,
            bindings,
            scaled_input,
            body,
            fields,
        } = parts;
        let input = &self.model.input.name;
        let output_type = self.scene_output_type(scene);
        let name = &scene.name;
        let batch = format_ident!("{}_batch", name.unraw());
        let (inputs, out, slot, index, error) = (
            local("inputs"),
            local("out"),
            local("slot"),
            local("index"),
            local("error"),
        );
        // The scalar kernel's arguments after the input, as the batch took them.
        let pass: Vec<Ident> = self.checked_arguments(scene).into_iter().skip(1).collect();
        let finite: Vec<TokenStream> = scene
            .items
            .iter()
            .map(|item| {
                let field = &item.field;
                match item.quantity {
                    Quantity::Point(_) => {
                        quote!(#slot.#field.x.is_finite() && #slot.#field.y.is_finite())
                    }
                    Quantity::Unknown(_) => quote!(#slot.#field.is_finite()),
                }
            })
            .collect();
        let docs = doc(&format!(
            "[`Self::{}`] at every input of `inputs`, into the matching entry of `out` (the \
             shorter of the two sets how many): the same arithmetic in a loop the compiler can \
             vectorise, with the branch-free [`mechgen::fast::sin_cos`] (an input must be \
             within [`mechgen::fast::sin_cos_limit`] to take the fast path). An input where \
             that gives a non-finite value is done again by [`Self::{}`], whose result is \
             kept, or whose error is returned with the input's index.",
            name.unraw(),
            name.unraw()
        ));
        quote! {
            #docs
            pub fn #batch(
                &self,
                #inputs: &[T] #branch_parameter,
                #(#arguments)*
                #out: &mut [#output_type<T>],
            ) -> ::core::result::Result<(), ::mechgen::BatchError<T>> {
                #bindings
                for (#slot, &#input) in #out.iter_mut().zip(#inputs) {
                    #input_trig
                    #scaled_input
                    #(#body)*
                    *#slot = #output_type { #(#fields),* };
                }
                // One pass with no early exit finds whether any lane failed (the common
                // answer, no); only then are the failed ones found and redone.
                let failed = #out.iter().fold(false, |failed, #slot| failed | !(#(#finite)&&*));
                if !failed {
                    return ::core::result::Result::Ok(());
                }
                for (#index, (#slot, &#input)) in #out.iter_mut().zip(#inputs).enumerate() {
                    if !(#(#finite)&&*) {
                        match self.#name(#input #(, #pass)*) {
                            ::core::result::Result::Ok(value) => *#slot = value,
                            ::core::result::Result::Err(#error) => {
                                return ::core::result::Result::Err(::mechgen::BatchError { #index, #error });
                            }
                        }
                    }
                }
                ::core::result::Result::Ok(())
            }
        }
    }
}

/// Which kernel an auxiliary value is computed in: the inputs its errors blame, whether it is
/// a batch's lanes, and the threshold below which its blocks' rates are refused.
struct KernelKind {
    inputs: TokenStream,
    mode: Mode,
    rates_threshold: TokenStream,
    /// The highest order the kernel's rates are for.
    rates_order: Ident,
}

/// A batch's pieces, from [`Generator::kernel`].
struct BatchParts {
    input_trig: Option<TokenStream>,
    bindings: TokenStream,
    /// A length input, its rate and acceleration, in the scaled units.
    scaled_input: TokenStream,
    body: Vec<TokenStream>,
    fields: Vec<TokenStream>,
}

/// A scene's outputs, in the order listed (a point's x then y).
fn scene_outputs(scene: &Scene, straight: &Straight) -> Vec<ExprId> {
    scene
        .items
        .iter()
        .flat_map(|item| match (item.quantity, item.order) {
            (Quantity::Unknown(u), Order::Value) => vec![straight.values[u]],
            (Quantity::Unknown(u), Order::Rate) => vec![straight.rates[u]],
            (Quantity::Unknown(u), Order::Acceleration) => vec![straight.accelerations[u]],
            (Quantity::Point(p), order) => straight.points[p][order as usize].to_vec(),
        })
        .collect()
}

/// The three forms of a scene's kernel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    /// `{scene}`: no test on the way (a step that fails gives NaN or an infinity, which
    /// reaches the outputs) and one at the end, which hands anything non-finite to the
    /// checked kernel. The common path pays for one test, not one per step.
    Fast,
    /// The fast kernel's way out: each step that can fail tested where it happens, with the
    /// error that says why.
    Checked,
    /// `{scene}_batch`: the fast kernel's arithmetic over a slice, branch-free, with the
    /// branch-free sine, cosine and angle of `mechgen::fast`, so the compiler vectorises it.
    Lanes,
}

/// The checked kernel of scene `name`.
fn checked_kernel(name: &Ident) -> Ident {
    format_ident!("mechgen_{}_checked", name.unraw())
}

/// What an auxiliary value is computed from, in a kernel of `mode`.
fn aux_arguments(kind: &AuxKind, mode: Mode) -> Vec<ExprId> {
    match *kind {
        AuxKind::BranchRoot { plus, minus, .. } => vec![plus, minus],
        AuxKind::TriangleRoot {
            sum,
            difference,
            span,
            ..
        } if mode == Mode::Checked => vec![sum, difference, span],
        AuxKind::TriangleRoot {
            sum_squared,
            difference_squared,
            span_squared,
            ..
        } => vec![sum_squared, difference_squared, span_squared],
        AuxKind::Bind(x) => vec![x],
        AuxKind::Inverse(x) => vec![x],
        AuxKind::InverseDeterminant {
            det, inverse_norms, ..
        } => vec![det, inverse_norms],
        AuxKind::Angle { y, x } => vec![y, x],
    }
}

/// The auxiliary values `outputs` read, directly or through other auxiliary values, in
/// order.
fn needed_aux(
    graph: &Graph,
    straight: &Straight,
    outputs: &[ExprId],
    mode: Mode,
) -> BTreeSet<usize> {
    let mut needed = BTreeSet::new();
    let mut seen = vec![false; graph.len()];
    let mut stack = outputs.to_vec();
    while let Some(id) = stack.pop() {
        if std::mem::replace(&mut seen[id.index()], true) {
            continue;
        }
        if let Node::Var(Var::Aux(k)) = graph.node(id)
            && needed.insert(k as usize)
        {
            stack.extend(aux_arguments(&straight.aux[k as usize], mode));
        }
        stack.extend(children(graph.node(id)));
    }
    needed
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
