//! Sensitivities to the parameters (`generate: sensitivities`): how far the unknowns and the
//! tracked points move per unit change of each dimension, at a solved position, for
//! tolerance analysis and for synthesis by gradients.
//!
//! Holding the input, `f(q(p), p) = 0` gives `J·∂q/∂p = −∂f/∂p`: one right-hand side per
//! parameter, solved with the Jacobian factored once, as the velocity is; no new loop solve.
//! A point then moves by `dP/dp = ∂P/∂p + Σ ∂P/∂q_j·∂q_j/∂p`.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use syn::ext::IdentExt;

use super::Generator;
use super::docs::doc;
use super::emit::{Emitted, local};
use super::points::component_names;
use crate::model::{Kind, Model};
use crate::symbolic::ExprId;

impl Generator<'_> {
    /// The type of one value per parameter.
    pub(super) fn sensitivities_type(&self) -> Ident {
        format_ident!("{}Sensitivities", self.model.name)
    }

    /// `{Name}Sensitivities<V>`: one `V` per parameter, in declaration order.
    pub(super) fn sensitivities_struct(&self) -> TokenStream {
        if self.equations.sensitivities.is_none() {
            return TokenStream::new();
        }
        let Model {
            vis, name, params, ..
        } = self.model;
        let ty = self.sensitivities_type();
        let fields = params.iter().map(|param| {
            let field = &param.name;
            let per = match param.kind {
                Kind::Angle => "per radian",
                Kind::Length => "per unit of length",
            };
            let docs = doc(&format!(
                "The derivative with respect to parameter `{}` ({per}).",
                field.unraw()
            ));
            quote!(#docs pub #field: V,)
        });
        let text = format!(
            "One `V` per parameter of [`{name}`], in declaration order: a result's derivatives \
             with respect to the dimensions, at a solved position with the input held. From \
             [`{name}::sensitivities`], each `V` holds the unknowns' derivatives; from \
             [`{name}::point_sensitivities`] where the mechanism tracks points, the points'."
        );
        let doc = doc(&text);
        // A declaration without parameters has nothing to differentiate by: the type still
        // needs its parameter.
        let phantom = params
            .is_empty()
            .then(|| quote!(_values: ::core::marker::PhantomData<V>,));
        quote! {
            #doc
            #[derive(Clone, Copy, Debug, Default, PartialEq)]
            #vis struct #ty<V> {
                #(#fields)*
                #phantom
            }
        }
    }

    /// `sensitivities(input, &position)` and, with points, `point_sensitivities`.
    pub(super) fn sensitivity_functions(&self) -> Vec<TokenStream> {
        let Some(sensitivities) = &self.equations.sensitivities else {
            return Vec::new();
        };
        let mut functions = vec![self.unknowns_sensitivities(&sensitivities.rhs)];
        if !self.model.points.is_empty() {
            functions.push(self.points_sensitivities(sensitivities));
        }
        functions
    }

    fn unknowns_sensitivities(&self, rhs: &[Vec<ExprId>]) -> TokenStream {
        let ty = self.sensitivities_type();
        let unknowns = &self.unknowns_type;
        let ((prologue, _), solves, solutions) = self.parameter_solves(rhs, &[]);
        let fields = self.model.params.iter().zip(&solutions).map(|(param, x)| {
            let field = &param.name;
            quote!(#field: #unknowns::from_array(#x))
        });
        let phantom = self.no_parameters_value();
        let body = quote! {
            #prologue
            #solves
            ::core::result::Result::Ok(#ty { #(#fields,)* #phantom })
        };
        let docs = "The unknowns' sensitivities to the parameters at a solved `position`: for \
             each parameter `p`, `∂q/∂p` with the input held, from `J·∂q/∂p = −∂f/∂p` with the \
             Jacobian factored once (as [`Self::velocity`] solves its rates). A length's is per \
             unit of length, an angle's per radian; a parameter no loop holds (a tracked \
             point's) moves no unknown.\n\nErrors: a non-finite argument or result; a singular \
             Jacobian (at a toggle the sensitivities are unbounded), or one whose condition \
             leaves fewer digits than [`mechgen::Accuracy::required`] asks of a velocity \
             ([`mechgen::Error::Inaccurate`]): the same solve, and the same estimate (a \
             position the loops do not close at is so `Inaccurate`).";
        let output = quote!(#ty<#unknowns<T>>);
        if self.has_formulas() {
            let value = local("value");
            let lengths = self.length_unknowns();
            let fields = self.model.params.iter().map(|param| {
                let field = &param.name;
                let components: Vec<Ident> = (0..lengths.len())
                    .map(|j| local(&format!("component_{j}")))
                    .collect();
                let rescaled = components.iter().zip(&lengths).map(|(component, length)| {
                    let factor = rescaling(param.kind == Kind::Length, *length);
                    quote!(#component #factor)
                });
                quote! {
                    #field: {
                        let [#(#components),*] = #value.#field.to_array();
                        #unknowns::from_array(::mechgen::__private::finite(
                            [#(#rescaled),*],
                            "sensitivity",
                        )?)
                    }
                }
            });
            return self.normalised_sensitivities(
                "sensitivities",
                docs,
                &output,
                body,
                quote! {
                    #ty { #(#fields,)* #phantom }
                },
            );
        }
        self.checked_function("sensitivities", docs, 2, &output, body, None)
    }

    fn points_sensitivities(&self, sensitivities: &crate::symbolic::Sensitivities) -> TokenStream {
        let ty = self.sensitivities_type();
        let points_type = &self.points_type;
        let params = self.model.params.len();
        let unknowns = self.model.unknowns.len();
        let extra: Vec<ExprId> = sensitivities
            .point_parameters
            .iter()
            .chain(&sensitivities.point_unknowns)
            .flatten()
            .flatten()
            .copied()
            .collect();
        let (prologue, solves, solutions) = self.parameter_solves(&sensitivities.rhs, &extra);
        let (prologue_outputs, partials) = prologue;
        // ∂P/∂p for every point, coordinate and parameter, then ∂P/∂q_j likewise.
        let (by_parameter, by_unknown) = partials.split_at(2 * params * self.model.points.len());
        let mut values = Vec::new();
        let mut fields = Vec::new();
        for (k, param) in self.model.params.iter().enumerate() {
            let x = &solutions[k];
            let mut point_fields = Vec::new();
            for (i, point) in self.model.points.iter().enumerate() {
                let [x_name, y_name] = sensitivity_components(&point.name, &param.name);
                // The nonzero terms of ∂P/∂p + Σ ∂P/∂q_j·x_j, summed; zero if none is.
                let coordinate = |c: usize| {
                    let graph = &self.equations.graph;
                    let direct =
                        (!graph.is_zero(sensitivities.point_parameters[i][c][k])).then(|| {
                            let direct: &Emitted = &by_parameter[(2 * i + c) * params + k];
                            quote!(#direct)
                        });
                    // A parameter no loop holds moves no unknown.
                    let moves = sensitivities.rhs[k].iter().any(|&id| !graph.is_zero(id));
                    let through = (0..unknowns).filter_map(|j| {
                        if !moves || graph.is_zero(sensitivities.point_unknowns[i][c][j]) {
                            return None;
                        }
                        let partial = by_unknown[(2 * i + c) * unknowns + j].receiver();
                        let j = proc_macro2::Literal::usize_unsuffixed(j);
                        Some(quote!(#partial * #x[#j]))
                    });
                    let terms: Vec<TokenStream> = direct.into_iter().chain(through).collect();
                    if terms.is_empty() {
                        quote!(T::zero())
                    } else {
                        quote!(#(#terms)+*)
                    }
                };
                let (x_local, y_local) = (local(&x_name), local(&y_name));
                values.push((x_local.clone(), coordinate(0)));
                values.push((y_local.clone(), coordinate(1)));
                let name = &point.name;
                point_fields.push(quote!(#name: ::mechgen::Vec2 { x: #x_local, y: #y_local }));
            }
            let field = &param.name;
            fields.push(quote!(#field: #points_type { #(#point_fields),* }));
        }
        let (names, expressions): (Vec<Ident>, Vec<TokenStream>) = values.into_iter().unzip();
        let phantom = self.no_parameters_value();
        let body = quote! {
            #prologue_outputs
            #solves
            let [#(#names),*] = ::mechgen::__private::finite(
                [#(#expressions),*],
                "point sensitivity",
            )?;
            ::core::result::Result::Ok(#ty { #(#fields,)* #phantom })
        };
        let docs = "The tracked points' sensitivities to the parameters at a solved \
             `position`: for each parameter `p`, `dP/dp = ∂P/∂p + Σ ∂P/∂q_j·∂q_j/∂p` with the \
             input held, the unknowns' part from [`Self::sensitivities`]' solve.\n\nErrors: as \
             [`Self::sensitivities`].";
        let output = quote!(#ty<#points_type<::mechgen::Vec2<T>>>);
        if self.has_formulas() {
            let value = local("value");
            let (mut names, mut components, mut fields) = (Vec::new(), Vec::new(), Vec::new());
            for param in &self.model.params {
                let field = &param.name;
                // A point is a length.
                let factor = rescaling(param.kind == Kind::Length, true);
                let mut points = Vec::new();
                for point in &self.model.points {
                    let point_name = &point.name;
                    let [x, y] = sensitivity_components(point_name, field).map(|name| local(&name));
                    components.push(quote!(#value.#field.#point_name.x #factor));
                    components.push(quote!(#value.#field.#point_name.y #factor));
                    points.push(quote!(#point_name: ::mechgen::Vec2 { x: #x, y: #y }));
                    names.extend([x, y]);
                }
                fields.push(quote!(#field: #points_type { #(#points),* }));
            }
            let rescaled = quote! {{
                let [#(#names),*] = ::mechgen::__private::finite(
                    [#(#components),*],
                    "point sensitivity",
                )?;
                #ty { #(#fields,)* #phantom }
            }};
            return self.normalised_sensitivities(
                "point_sensitivities",
                docs,
                &output,
                body,
                rescaled,
            );
        }
        self.checked_function("point_sensitivities", docs, 2, &output, body, None)
    }

    /// The placeholder field of a sensitivities value for a declaration without parameters.
    fn no_parameters_value(&self) -> Option<TokenStream> {
        self.model
            .params
            .is_empty()
            .then(|| quote!(_values: ::core::marker::PhantomData,))
    }

    /// The Jacobian factored once and one solve per parameter's right-hand side `rhs[k]`,
    /// after evaluating `extra` too: the evaluation (with `extra`'s values), the solves, and
    /// the locals each solution (`[T; N]`, finite) is bound to.
    fn parameter_solves(
        &self,
        rhs: &[Vec<ExprId>],
        extra: &[ExprId],
    ) -> ((TokenStream, Vec<Emitted>), TokenStream, Vec<Ident>) {
        let n = self.model.unknowns.len();
        let entries: Vec<ExprId> = self
            .equations
            .jacobian
            .iter()
            .flatten()
            .chain(rhs.iter().flatten())
            .chain(extra)
            .chain(&self.equations.residual)
            .copied()
            .collect();
        let (prologue, mut outputs) = self.block(&entries);
        let residual = outputs.split_off(outputs.len() - self.equations.residual.len());
        let extra_outputs = outputs.split_off(n * n + n * rhs.len());
        let right_sides = outputs.split_off(n * n);
        let jacobian = outputs;
        let solutions: Vec<Ident> = self
            .model
            .params
            .iter()
            .map(|param| local(&sensitivity_name(&param.name)))
            .collect();
        // A parameter no loop holds moves no unknown: no solve.
        let graph = &self.equations.graph;
        let moves = |k: usize| rhs[k].iter().any(|&id| !graph.is_zero(id));
        let right_sides: Vec<(&[Emitted], Ident)> = right_sides
            .chunks(n.max(1))
            .zip(&solutions)
            .enumerate()
            .filter(|(k, _)| moves(*k))
            .map(|(_, (chunk, name))| (chunk, name.clone()))
            .collect();
        let solve = self.solves(
            &jacobian,
            &right_sides,
            "Velocity",
            &super::rates::PositionFrom::Given(
                residual.iter().map(|r| quote!(#r)).collect(),
                Box::new(super::rates::PositionFrom::ClosedForm),
            ),
        );
        let accuracy = local("accuracy");
        let count = proc_macro2::Literal::usize_unsuffixed(n);
        let checks = solutions.iter().enumerate().map(|(k, x)| {
            if moves(k) {
                quote!(let #x = ::mechgen::__private::finite(#x, "sensitivity")?;)
            } else {
                quote!(let #x = [T::zero(); #count];)
            }
        });
        let solves = quote! {
            #solve
            // The estimate was checked against a velocity's required accuracy.
            let _ = #accuracy;
            #(#checks)*
        };
        ((prologue, extra_outputs), solves, solutions)
    }
}

impl Generator<'_> {
    /// Whether a loop or a point holds a formula of the parameters: its derivatives (the
    /// square root's `a/√(a² − b²)`, say) square the lengths, which overflow or lose digits
    /// to underflow where the linear solves, scaling their own rows, do not.
    fn has_formulas(&self) -> bool {
        let sums = self
            .model
            .loops
            .iter()
            .chain(self.model.points.iter().map(|point| &point.position));
        sums.flat_map(|sum| &sum.terms)
            .any(|term| !term.magnitude.formulas.is_empty() || !term.angle.formulas.is_empty())
    }

    /// `sensitivities` or `point_sensitivities` (`name`, with `docs` and `output`) for a
    /// declaration with formulas: `body` on the mechanism as given where its size is well
    /// inside the float's range, else, out of line, on the mechanism scaled by a power of two
    /// (exact), the position's lengths with it, and the results scaled back by `rescaled`
    /// (which reads them as `value`). With every length times `s`, a derivative of a length
    /// by an angle is `s` times as large and one of an angle by a length `1/s` times; the
    /// rest do not change.
    fn normalised_sensitivities(
        &self,
        name: &str,
        docs: &str,
        output: &TokenStream,
        body: TokenStream,
        rescaled: TokenStream,
    ) -> TokenStream {
        let (input_params, inputs) = (self.input_params(), self.input_args());
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let position = super::arg("position");
        let value = local("value");
        let super::normalise::Normalised {
            prologue,
            receiver,
            input: scaled_input,
            restore,
            ..
        } = self.normalised();
        let scale = local("scale");
        let lengths = self.length_unknowns();
        let as_given = self.as_given();
        let public = Ident::new(name, proc_macro2::Span::call_site());
        let solve = format_ident!("mechgen_{}_solve", name);
        let normalised = format_ident!("mechgen_{}_normalised", name);
        let docs = doc(docs);
        let normalised_doc = doc(&format!(
            "[`Self::{name}`] on the mechanism scaled by a power of two, for a mechanism whose \
             size is far from 1: its formulas' derivatives in range."
        ));
        let solve_doc = doc(&format!(
            "[`Self::{name}`] on the mechanism it is called on: the mechanism as given, or \
             scaled by a power of two."
        ));
        quote! {
            #docs
            pub fn #public(
                &self,
                #input_params,
                #position: &#unknowns,
            ) -> ::core::result::Result<#output, ::mechgen::Error<T>> {
                self.mechgen_check_finite(#inputs)?;
                ::mechgen::__private::finite(#position.to_array(), "position")?;
                if #as_given {
                    self.#solve(#inputs, #position)
                } else {
                    self.#normalised(#inputs, #position)
                }
            }

            #normalised_doc
            #[cold]
            #[inline(never)]
            fn #normalised(
                &self,
                #input_params,
                #position: &#unknowns,
            ) -> ::core::result::Result<#output, ::mechgen::Error<T>> {
                #prologue
                let #position = #ty::from_array(::mechgen::__private::scaled(
                    #position.to_array(),
                    [#(#lengths),*],
                    #scale,
                ));
                let #value = #receiver.#solve(#scaled_input, &#position)#restore?;
                ::core::result::Result::Ok(#rescaled)
            }

            #solve_doc
            #[inline(always)]
            fn #solve(
                &self,
                #input_params,
                #position: &#unknowns,
            ) -> ::core::result::Result<#output, ::mechgen::Error<T>> {
                #body
            }
        }
    }
}

/// The factor that takes a derivative computed with every length times `scale` back to the
/// mechanism's own units: of a length by an angle, `unscale`; of an angle by a length,
/// `scale`; else none.
fn rescaling(by_length: bool, of_length: bool) -> TokenStream {
    match (by_length, of_length) {
        (true, false) => {
            let scale = local("scale");
            quote!(* #scale)
        }
        (false, true) => {
            let unscale = local("unscale");
            quote!(* #unscale)
        }
        _ => TokenStream::new(),
    }
}

/// The local holding the unknowns' sensitivity to `param`.
pub(super) fn sensitivity_name(param: &Ident) -> String {
    format!("sensitivity_{}", param.unraw())
}

/// The locals holding `point`'s sensitivity to `param`, `x` and `y`.
pub(super) fn sensitivity_components(point: &Ident, param: &Ident) -> [String; 2] {
    let stem = format!("{}_{}", point.unraw(), param.unraw());
    component_names(&stem, &[]).remove(0)
}
