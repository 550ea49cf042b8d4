//! Scene kernels: one straight-line function per declared scene, computing exactly the
//! outputs it lists.
//!
//! What makes them fast: everything that depends on the dimensions alone is computed once,
//! by `scenes()`, into `{Name}Scenes`; each closed form yields solved angles as unit vectors,
//! which (with angle sums taken apart, see `symbolic::angles`) are all that positions, rates
//! and points read, so an `atan2` is paid only for an angle the scene lists; every sine and
//! cosine is computed once and shared; the parameters were checked when the constants were
//! made, so a call checks only its own arguments.

use std::collections::BTreeSet;

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use syn::ext::IdentExt;

use super::docs::{doc, docs_or};
use super::emit::{Context, Emitted, children, emit, local};
use super::{Generator, arg};
use crate::model::SymbolRef;
use crate::scene::{Order, Quantity, Scene};
use crate::symbolic::{Case, ExprId, Graph, Node, SceneExprs, Step, Var};

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
        let (Some(steps), Some(exprs)) = (&self.equations.closed_form, &self.equations.scenes)
        else {
            return TokenStream::new();
        };
        let constants = self.constants(exprs);
        let name = &self.model.name;
        let scenes_type = self.scenes_type();
        let count = Literal::usize_unsuffixed(constants.ids.len());
        let outputs = self.model.scenes.iter().map(|scene| self.scene_output(scene));
        let kernels = self
            .model
            .scenes
            .iter()
            .map(|scene| self.kernel(scene, steps, exprs, &constants));
        let docs = doc(&format!(
            "[`{name}`]'s scene kernels (see [`{name}::scenes`]): the mechanism, and what \
             depends on its dimensions alone, computed once."
        ));
        quote! {
            #docs
            #[derive(Clone, Copy, Debug)]
            pub struct #scenes_type<T> {
                mechanism: #name<T>,
                constants: [T; #count],
            }
            #(#outputs)*
            #[allow(clippy::possible_missing_comma, clippy::too_many_arguments)]
            impl<T: ::mechgen::Real> #scenes_type<T> {
                /// The mechanism these kernels were made for.
                pub fn mechanism(&self) -> &#name<T> {
                    &self.mechanism
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
        let bindings = self.parameter_bindings(&block.used, quote!(self));
        let statements = block.statements.concat();
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
                #bindings
                #(#statements)*
                let constants = ::mechgen::__private::finite(
                    [#(#values),*],
                    "dimension-derived constant",
                )?;
                ::core::result::Result::Ok(#scenes_type { mechanism: *self, constants })
            }
        }
    }

    /// `let name = source.field;` for each parameter in `used`.
    pub(super) fn parameter_bindings(&self, used: &BTreeSet<Var>, source: TokenStream) -> TokenStream {
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
    fn constants(&self, exprs: &SceneExprs) -> Constants {
        let graph = &self.equations.graph;
        let roots = all_scene_roots(&self.model.scenes, exprs);
        let fixed = fixed_nodes(graph);
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
            if fixed[root.index()] {
                hoist(root);
            }
        }
        for i in (0..graph.len()).filter(|&i| reachable[i] && !fixed[i]) {
            for child in children(graph.node(ExprId::from_index(i))) {
                if fixed[child.index()] {
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

    /// One scene's kernel.
    fn kernel(
        &self,
        scene: &Scene,
        steps: &[Step],
        exprs: &SceneExprs,
        constants: &Constants,
    ) -> TokenStream {
        let graph = &self.equations.graph;
        let input = &self.model.input.name;
        let (input_dot, input_ddot) = (&self.input_dot, &self.input_ddot);
        let order = scene.order();
        let n = self.model.unknowns.len();
        let last = steps.len();

        // Stage s + 1 follows the solve of step s; then the rates, then the accelerations.
        let mut solved_at = vec![0; n];
        for (s, step) in steps.iter().enumerate() {
            step.unknowns.iter().for_each(|&u| solved_at[u] = s + 1);
        }
        let stage = |var: Var| match var {
            Var::Value(SymbolRef::Unknown(u)) => solved_at[u],
            Var::Rate(SymbolRef::Unknown(_)) => last + 1,
            Var::Accel(SymbolRef::Unknown(_)) => last + 2,
            _ => 0,
        };

        // Sines and cosines of solved angles come from the closed forms' unit vectors, and
        // dimension-only values from the constants.
        let mut presets: Vec<(ExprId, Ident, usize)> = Vec::new();
        let mut direction_bindings = vec![Vec::new(); last + 3];
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
        let constant_names: Vec<Ident> = (0..constants.ids.len())
            .map(|k| local(&format!("constant_{k}")))
            .collect();
        presets.extend(
            constants
                .ids
                .iter()
                .zip(&constant_names)
                .map(|(&id, name)| (id, name.clone(), 0)),
        );
        let mut reserved = self.reserved.clone();
        reserved.extend(constant_names.iter().map(Ident::to_string));

        // What the kernel evaluates: the closed forms, the rate solves it needs, the points.
        let mut roots: Vec<ExprId> = exprs.coefficients.concat();
        if order >= Order::Rate {
            roots.extend(exprs.jacobian.iter().chain(&exprs.velocity_rhs));
        }
        if order >= Order::Acceleration {
            roots.extend(&exprs.acceleration_rhs);
        }
        let point_items: Vec<(usize, usize)> = scene
            .items
            .iter()
            .filter_map(|item| match item.quantity {
                Quantity::Point(p) => Some((p, item.order as usize)),
                Quantity::Unknown(_) => None,
            })
            .collect();
        for &(p, k) in &point_items {
            roots.extend(exprs.points[p][k]);
        }
        let context = Context {
            reserved: &reserved,
            presets: &presets,
            stage: &stage,
        };
        let block = emit(graph, &roots, &|var| self.var_name(var), &context);
        let mut statements = block.statements;
        statements.resize(last + 3, Vec::new());
        let mut outputs = block.outputs.into_iter();

        // The constants the emitted code reads, from `self`.
        let read = read_presets(graph, &roots, &presets);
        let constant_bindings = constants.ids.iter().zip(&constant_names).enumerate().filter_map(
            |(k, (id, name))| {
                read.contains(id).then(|| {
                    let k = Literal::usize_unsuffixed(k);
                    quote!(let #name = self.constants[#k];)
                })
            },
        );
        let parameter_bindings = self.parameter_bindings(&block.used, quote!(self.mechanism));

        // Angles a scene lists, or that an expression still reads whole, cost an `atan2`.
        let listed: BTreeSet<usize> = scene
            .items
            .iter()
            .filter_map(|item| match (item.quantity, item.order) {
                (Quantity::Unknown(u), Order::Value) => Some(u),
                _ => None,
            })
            .collect();
        let solved_angles = self.solved_angles(steps);
        let mut choices = self.branch_choices(steps).into_iter();
        let failure = arg("failure");
        let solves: Vec<TokenStream> = steps
            .iter()
            .zip(&exprs.coefficients)
            .enumerate()
            .map(|(s, (step, coefficients))| {
                let computed = &statements[s];
                let values: Vec<Emitted> = outputs.by_ref().take(coefficients.len()).collect();
                let vectors = super::closed_forms::complex_values(&values);
                let sign = step.case.has_branches().then(|| {
                    let choice = choices.next();
                    quote!(, #choice.sign::<T>())
                });
                let [a, b] = step.unknowns.map(|u| &self.model.unknowns[u].name);
                let [direction_a, direction_b] = step.unknowns.map(|u| self.direction(u));
                let (solver, pattern) = match step.case {
                    Case::TwoLengths { .. } => ("two_lengths", quote!([#a, #b])),
                    Case::TwoAngles { .. } => {
                        ("two_directions", quote!((#direction_a, #direction_b)))
                    }
                    Case::LengthAndOwnAngle { .. } => {
                        ("length_and_own_direction", quote!((#a, #direction_b)))
                    }
                    Case::LengthAndOtherAngle { .. } => {
                        ("length_and_other_direction", quote!((#a, #direction_b)))
                    }
                };
                let solver = Ident::new(solver, proc_macro2::Span::call_site());
                let directions = &direction_bindings[s + 1];
                let angles = step
                    .unknowns
                    .iter()
                    .filter(|&&u| {
                        solved_angles.contains(&u)
                            && (listed.contains(&u)
                                || block.used.contains(&Var::Value(SymbolRef::Unknown(u))))
                    })
                    .map(|&u| {
                        let name = &self.model.unknowns[u].name;
                        let direction = self.direction(u);
                        quote!(let #name = #direction.angle();)
                    });
                quote! {
                    #(#computed)*
                    let #pattern = ::mechgen::closed::#solver(#(#vectors),* #sign)
                        .map_err(|#failure| #failure.at(#input))?;
                    #(#directions)*
                    #(#angles)*
                }
            })
            .collect();

        let (rates, accelerations) = (local("rates"), local("accelerations"));
        let rate_solves = if order >= Order::Rate {
            let jacobian: Vec<Emitted> = outputs.by_ref().take(n * n).collect();
            let velocity_rhs: Vec<Emitted> = outputs.by_ref().take(n).collect();
            let velocity_solve = self.solves(&jacobian, &[(&velocity_rhs, rates.clone())]);
            let rate_names = &self.unknown_dots;
            let before = &statements[last];
            let velocity = quote! {
                #(#before)*
                #velocity_solve
                let [#(#rate_names),*] = ::mechgen::__private::finite(#rates, "velocity")?;
            };
            if order >= Order::Acceleration {
                let acceleration_rhs: Vec<Emitted> = outputs.by_ref().take(n).collect();
                let solve =
                    self.reuse_solves(&jacobian, &[(&acceleration_rhs, accelerations.clone())]);
                let after = &statements[last + 1];
                let ddot_names = &self.unknown_ddots;
                quote! {
                    #velocity
                    #(#after)*
                    #solve
                    let [#(#ddot_names),*] =
                        ::mechgen::__private::finite(#accelerations, "acceleration")?;
                }
            } else {
                velocity
            }
        } else {
            let before = &statements[last];
            quote!(#(#before)*)
        };
        // What reads the last solve's results.
        let after_rates: &[TokenStream] = match order {
            Order::Acceleration => &statements[last + 2],
            Order::Rate => &statements[last + 1],
            Order::Value => &[],
        };

        // The outputs, in the order listed; points checked finite together.
        let point_values: Vec<Emitted> = outputs.collect();
        let mut point_values = point_values.chunks(2);
        let mut point_components = Vec::new();
        let fields: Vec<TokenStream> = scene
            .items
            .iter()
            .map(|item| {
                let field = &item.field;
                match item.quantity {
                    Quantity::Unknown(u) => {
                        let value = match item.order {
                            Order::Value => self.model.unknowns[u].name.clone(),
                            Order::Rate => self.unknown_dots[u].clone(),
                            Order::Acceleration => self.unknown_ddots[u].clone(),
                        };
                        if field.unraw() == value.unraw() {
                            quote!(#value)
                        } else {
                            quote!(#field: #value)
                        }
                    }
                    Quantity::Point(_) => {
                        let pair = point_values.next().unwrap_or_default();
                        point_components.extend(pair.iter().map(|e| quote!(#e)));
                        let k = Literal::usize_unsuffixed(point_components.len() - 2);
                        let k1 = Literal::usize_unsuffixed(point_components.len() - 1);
                        let points = local("values");
                        quote!(#field: ::mechgen::Vec2 { x: #points[#k], y: #points[#k1] })
                    }
                }
            })
            .collect();
        let values = local("values");
        let point_check = (!point_components.is_empty()).then(|| {
            quote! {
                let #values = ::mechgen::__private::finite([#(#point_components),*], "point")?;
            }
        });

        let branch_parameter = self.branch_parameter(steps);
        let mut arguments = Vec::new();
        let input_label = format!("input `{}`", input.unraw());
        let mut checks = vec![quote!((#input, #input_label))];
        if order >= Order::Rate {
            arguments.push(quote!(#input_dot: T,));
            let label = format!("input rate `{input_dot}`");
            checks.push(quote!((#input_dot, #label)));
        }
        if order >= Order::Acceleration {
            arguments.push(quote!(#input_ddot: T,));
            let label = format!("input acceleration `{input_ddot}`");
            checks.push(quote!((#input_ddot, #label)));
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
            #[allow(unused_variables)]
            #[inline]
            pub fn #name(
                &self,
                #input: T #branch_parameter,
                #(#arguments)*
            ) -> ::core::result::Result<#output_type<T>, ::mechgen::Error<T>> {
                ::mechgen::__private::check_finite(&[#(#checks),*])?;
                #(#constant_bindings)*
                #parameter_bindings
                #(#solves)*
                #rate_solves
                #(#after_rates)*
                #point_check
                ::core::result::Result::Ok(#output_type { #(#fields),* })
            }
        }
    }
}

/// Every expression some scene evaluates.
fn all_scene_roots(scenes: &[Scene], exprs: &SceneExprs) -> Vec<ExprId> {
    let order = scenes.iter().map(Scene::order).max().unwrap_or(Order::Value);
    let mut roots: Vec<ExprId> = exprs.coefficients.concat();
    if order >= Order::Rate {
        roots.extend(exprs.jacobian.iter().chain(&exprs.velocity_rhs));
    }
    if order >= Order::Acceleration {
        roots.extend(&exprs.acceleration_rhs);
    }
    for item in scenes.iter().flat_map(|scene| &scene.items) {
        if let Quantity::Point(p) = item.quantity {
            roots.extend(exprs.points[p][item.order as usize]);
        }
    }
    roots
}

/// Which nodes depend on the dimensions alone (parameters and numbers).
fn fixed_nodes(graph: &Graph) -> Vec<bool> {
    let mut fixed = vec![false; graph.len()];
    // Children come before parents in the arena.
    for i in 0..graph.len() {
        fixed[i] = match graph.node(ExprId::from_index(i)) {
            Node::Const(_) | Node::Var(Var::Value(SymbolRef::Param(_))) => true,
            Node::Var(_) => false,
            node => children(node).all(|c| fixed[c.index()]),
        };
    }
    fixed
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
