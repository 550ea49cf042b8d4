//! The raw evaluators (residual, Jacobians, condition), which return plain values and do not
//! check their arguments, and `mechgen_check_finite`, the check every solver starts with.

use proc_macro2::TokenStream;
use quote::quote;
use syn::ext::IdentExt;

use super::docs::doc;
use super::{Generator, arg, matrix};
use crate::formula::{Formula, Function};
use crate::model::Kind;
use crate::symbolic::ExprId;
use proc_macro2::Literal;

impl Generator<'_> {
    /// `mechgen_check_finite`: every parameter, then the input, finite. Their names are a
    /// constant table apart from the values, read only to blame one that is not.
    pub(super) fn check_finite(&self) -> TokenStream {
        let inputs = self.inputs();
        let input_params = self.input_params();
        let input_labels = inputs
            .iter()
            .map(|input| format!("input `{}`", input.unraw()));
        let (values, labels) = self.dimension_checks();
        quote! {
            /// Checks that the parameters and the input are finite.
            #[inline]
            fn mechgen_check_finite(&self, #input_params) -> ::core::result::Result<(), ::mechgen::Error<T>> {
                ::mechgen::__private::check_all_finite(
                    [#(#values,)* #(#inputs),*],
                    &[#(#labels,)* #(#input_labels),*],
                )
            }
        }
    }

    /// Every parameter (`self.l1`) and formula of them, with the name a failure blames:
    /// what is checked finite of the dimensions.
    pub(super) fn dimension_checks(&self) -> (Vec<TokenStream>, Vec<String>) {
        let (formulas, formula_labels) = self.formula_checks();
        let values = self
            .model
            .params
            .iter()
            .map(|param| {
                let name = &param.name;
                quote!(self.#name)
            })
            .chain(formulas)
            .collect();
        let labels = self
            .model
            .params
            .iter()
            .map(|param| format!("parameter `{}`", param.name.unraw()))
            .chain(formula_labels)
            .collect();
        (values, labels)
    }

    /// `check_all_finite([parameters, input, rate, acceleration], names)?;`: the check
    /// `mechgen_check_finite` makes and `motion_near`'s of the input's rate and acceleration
    /// in one, blaming the first that is not finite in that order.
    pub(super) fn check_finite_with_rates(&self) -> TokenStream {
        let inputs = self.inputs();
        let (input_dots, input_ddots) = (&self.input_dots, &self.input_ddots);
        let fields = self.model.params.iter().map(|param| &param.name);
        let labels = self
            .model
            .params
            .iter()
            .map(|param| format!("parameter `{}`", param.name.unraw()));
        let input_labels = inputs
            .iter()
            .map(|input| format!("input `{}`", input.unraw()));
        let dot_labels = input_dots.iter().map(|dot| format!("input rate `{dot}`"));
        let ddot_labels = input_ddots
            .iter()
            .map(|ddot| format!("input acceleration `{ddot}`"));
        let (formulas, formula_labels) = self.formula_checks();
        quote! {
            ::mechgen::__private::check_all_finite(
                [#(self.#fields,)* #(#formulas,)* #(#inputs,)* #(#input_dots,)* #(#input_ddots),*],
                &[#(#labels,)* #(#formula_labels,)* #(#input_labels,)* #(#dot_labels,)* #(#ddot_labels),*],
            )?;
        }
    }

    /// Each formula of the parameters the loops and points hold (see [`crate::formula`]),
    /// once, as a value computed from `self`'s fields and a label naming it as written:
    /// checked finite with the parameters, so that a formula undefined for the dimensions
    /// given (the square root of a negative difference) is an error, not a NaN. Computed
    /// with the lengths scaled by the power of two the solvers scale a mechanism by
    /// (`mechgen::__private::length_scale`): a formula is of degree 1 in length (or 0), so
    /// that it is the formula's value times that power, and finite wherever the solvers'
    /// scaled copy of it is, though its square of a length of 1e160 overflows as given.
    pub(super) fn formula_checks(&self) -> (Vec<TokenStream>, Vec<String>) {
        let mut seen: Vec<&Formula> = Vec::new();
        let terms = self
            .model
            .loops
            .iter()
            .chain(self.model.points.iter().map(|point| &point.position))
            .flat_map(|sum| &sum.terms)
            .flat_map(|term| term.magnitude.formulas.iter().chain(&term.angle.formulas));
        for (_, formula) in terms {
            if !seen.contains(&formula) {
                seen.push(formula);
            }
        }
        let name = |i: usize| self.model.params[i].name.unraw().to_string();
        let lengths = self.length_params();
        seen.into_iter()
            .map(|formula| {
                let value = formula_tokens(formula, &|i| {
                    let param = &self.model.params[i];
                    let field = &param.name;
                    if param.kind == Kind::Length {
                        quote!((self.#field * scale))
                    } else {
                        quote!(self.#field)
                    }
                });
                (
                    quote!({
                        let (scale, _) = ::mechgen::__private::length_scale(&[#(self.#lengths),*]);
                        #value
                    }),
                    format!("parameter formula `{}`", formula.display(&name)),
                )
            })
            .unzip()
    }

    pub(super) fn residual(&self) -> TokenStream {
        let input_params = self.input_params();
        let input = self
            .inputs()
            .iter()
            .map(|input| input.to_string())
            .collect::<Vec<_>>()
            .join("`, `");
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
            pub fn residual(&self, #input_params, #position: &#unknowns) -> #array {
                #prologue
                [#(#outputs),*]
            }
        }
    }

    pub(super) fn jacobian(&self) -> TokenStream {
        let input_params = self.input_params();
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
            pub fn jacobian(&self, #input_params, #position: &#unknowns) -> [[T; #count]; #count] {
                #prologue
                #rows
            }
        }
    }

    pub(super) fn input_jacobian(&self) -> TokenStream {
        let input_params = self.input_params();
        let position = arg("position");
        let (unknowns, array, count) = self.signature_types();
        let entries: Vec<ExprId> = self
            .equations
            .input_jacobian
            .iter()
            .flatten()
            .copied()
            .collect();
        let (prologue, outputs) = self.block(&entries);
        let raw = doc(RAW_EVALUATION);
        if self.model.inputs.len() == 1 {
            return quote! {
                /// The derivative of [`Self::residual`] with respect to the input.
                ///
                #raw
                pub fn input_jacobian(&self, #input_params, #position: &#unknowns) -> #array {
                    #prologue
                    [#(#outputs),*]
                }
            };
        }
        let inputs = Literal::usize_unsuffixed(self.model.inputs.len());
        let rows = matrix(&outputs, self.model.inputs.len());
        quote! {
            /// The derivatives of [`Self::residual`] with respect to the inputs: row `i`,
            /// column `k` is `∂residual[i]/∂input[k]`, the inputs in declaration order.
            ///
            #raw
            pub fn input_jacobian(
                &self,
                #input_params,
                #position: &#unknowns,
            ) -> [[T; #inputs]; #count] {
                #prologue
                #rows
            }
        }
    }

    /// `condition(input, position)`, which tells how far to trust what the solvers return.
    pub(super) fn condition(&self) -> TokenStream {
        let (input_params, inputs) = (self.input_params(), self.input_args());
        let position = arg("position");
        let (unknowns, _, _) = self.signature_types();
        quote! {
            /// The Jacobian's condition estimate at a position, `1 / relative determinant`
            /// (see [`mechgen::condition`]): 1 at best, about `1/√ε` at a toggle, where the
            /// solvers return [`mechgen::Error::Singular`]. Errors in positions and rates grow
            /// with it (the accuracy contract in the `mechgen` docs).
            pub fn condition(&self, #input_params, #position: &#unknowns) -> T {
                ::mechgen::condition(self.jacobian(#inputs, #position))
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
}

/// `formula` as an expression of `T`, each parameter read as `param` writes it.
pub(super) fn formula_tokens(
    formula: &Formula,
    param: &dyn Fn(usize) -> TokenStream,
) -> TokenStream {
    let tokens = |f: &Formula| formula_tokens(f, param);
    match formula {
        Formula::Param(i) => param(*i),
        Formula::Number(value) => super::emit::constant(*value),
        Formula::Neg(inner) => {
            let inner = tokens(inner);
            quote!((-#inner))
        }
        Formula::Add(a, b) | Formula::Sub(a, b) | Formula::Mul(a, b) | Formula::Div(a, b) => {
            let (a, b) = (tokens(a), tokens(b));
            match formula {
                Formula::Add(..) => quote!((#a + #b)),
                Formula::Sub(..) => quote!((#a - #b)),
                Formula::Mul(..) => quote!((#a * #b)),
                _ => quote!((#a / #b)),
            }
        }
        Formula::Call(function, arguments) => {
            let arguments: Vec<TokenStream> = arguments.iter().map(tokens).collect();
            match (function, arguments.as_slice()) {
                (Function::Sqrt, [x]) => quote!(#x.sqrt()),
                (Function::Sin, [x]) => quote!(#x.sin()),
                (Function::Cos, [x]) => quote!(#x.cos()),
                (Function::Tan, [x]) => quote!(#x.tan()),
                (Function::Atan2, [y, x]) => quote!(#y.atan2(#x)),
                (Function::Hypot, [x, y]) => quote!(#x.hypot(#y)),
                _ => unreachable!("the model builds each function with its arguments"),
            }
        }
    }
}

/// Said of the evaluators, which unlike the solvers return plain arrays.
const RAW_EVALUATION: &str = "A raw evaluation: it does not check its arguments, so a NaN \
     in gives NaN out. The solvers check theirs.";
