//! The mechanism's aspect, which `scenes()` computes once for the kernels' rate limits: the
//! sum of the lengths the loops declare over the shortest angle unknown's Jacobian column.
//! Separate because it reads the loops as declared (which vectors turn with which angle),
//! where the kernels read the expression graph.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use crate::codegen::Generator;
use crate::model::{Kind, Linear, SymbolRef};

impl Generator<'_> {
    /// `(size, mechgen::__private::aspect(size, [column², …]))` over the mechanism `scaled`:
    /// the sum of the lengths the loops declare, and the aspect from the angle unknowns whose
    /// columns have a length the dimensions fix: in every loop, one vector turns with the
    /// angle, and its magnitude is made of parameters. (The column of an angle whose vector
    /// is a slide, or that turns two vectors of one loop, moves with the position; its block
    /// is judged at the aspect it has there, from the size.) The same aspect as the general
    /// functions', whose estimate weighs each column at the position.
    pub(super) fn scene_aspect(&self, scaled: &Ident) -> (TokenStream, TokenStream) {
        let columns = self.angle_columns(scaled).flatten();
        let size = self.accuracy_size(quote!(#scaled));
        (
            size.clone(),
            quote!(::mechgen::__private::aspect(#size, [#(#columns),*])),
        )
    }

    /// `mechgen::__private::aspect(size, [column², …])` over the mechanism `receiver` (whose
    /// loops' declared lengths sum to `size`, an expression), where
    /// every angle unknown's column has a length the dimensions fix (see
    /// [`Self::scene_aspect`]): the aspect the general functions' estimate would compute
    /// from the Jacobian's columns at any position, without them. `None` where a column's
    /// length moves with the position.
    pub(crate) fn known_aspect(&self, receiver: &Ident, size: &TokenStream) -> Option<TokenStream> {
        let columns = self.angle_columns(receiver).collect::<Option<Vec<_>>>()?;
        Some(quote!(::mechgen::__private::aspect(#size, [#(#columns),*])))
    }

    /// The product of the Jacobian's squared column norms over `self`, where the dimensions
    /// fix them: two unknowns, both angles of one loop, each turning one vector of fixed
    /// length (`mechgen::__private::Columns::Known`). `None` elsewhere.
    pub(crate) fn known_column_product(&self) -> Option<TokenStream> {
        let unknowns = &self.model.unknowns;
        if unknowns.len() != 2 || unknowns.iter().any(|unknown| unknown.kind != Kind::Angle) {
            return None;
        }
        let receiver = Ident::new("self", proc_macro2::Span::call_site());
        let columns = self.angle_columns(&receiver).collect::<Option<Vec<_>>>()?;
        let [first, second] = columns.as_slice() else {
            return None;
        };
        Some(quote!((#first) * (#second)))
    }

    /// Each angle unknown's squared column length over the mechanism `receiver`, where the
    /// dimensions fix it ([`Self::fixed_column`]).
    fn angle_columns<'a>(
        &'a self,
        receiver: &'a Ident,
    ) -> impl Iterator<Item = Option<TokenStream>> + 'a {
        self.model
            .unknowns
            .iter()
            .enumerate()
            .filter(|(_, unknown)| unknown.kind == Kind::Angle)
            .map(move |(u, _)| self.fixed_column(u, receiver))
    }

    /// The squared length of angle unknown `u`'s Jacobian column, where the dimensions fix
    /// it: `Σ (coefficient·magnitude)²` over the loops, one vector of each turning with `u`.
    fn fixed_column(&self, u: usize, scaled: &Ident) -> Option<TokenStream> {
        let mut squares = Vec::new();
        for sum in &self.model.loops {
            let mut turning = sum.terms.iter().filter_map(|term| {
                let coefficient = *term.angle.coefficients.get(&SymbolRef::Unknown(u))?;
                (coefficient != 0.0).then_some((coefficient, &term.magnitude))
            });
            let Some((coefficient, magnitude)) = turning.next() else {
                continue;
            };
            if turning.next().is_some() {
                return None;
            }
            let length = scaled_by(coefficient.abs(), self.fixed_magnitude(magnitude, scaled)?);
            squares.push(quote!(#length * #length));
        }
        if squares.is_empty() {
            None
        } else {
            Some(quote!(#(#squares)+*))
        }
    }

    /// `Σ |magnitude|` over every loop's vectors, over the parameters of `receiver`, if the
    /// dimensions alone fix every magnitude.
    pub(crate) fn fixed_scale(&self, receiver: &Ident) -> Option<TokenStream> {
        let magnitudes = self
            .model
            .loops
            .iter()
            .flat_map(|sum| &sum.terms)
            .map(|term| {
                let magnitude = self.fixed_magnitude(&term.magnitude, receiver)?;
                // A parameter alone needs no parentheses.
                Some(
                    if syn::parse2::<syn::ExprField>(magnitude.clone()).is_ok() {
                        quote!(#magnitude.abs())
                    } else {
                        quote!((#magnitude).abs())
                    },
                )
            })
            .collect::<Option<Vec<_>>>()?;
        (!magnitudes.is_empty()).then(|| quote!(#(#magnitudes)+*))
    }

    /// `magnitude` over the parameters of `scaled` (and formulas of them), if it is made of
    /// them alone.
    fn fixed_magnitude(&self, magnitude: &Linear, scaled: &Ident) -> Option<TokenStream> {
        let mut parts = Vec::new();
        for (symbol, coefficient) in &magnitude.coefficients {
            let SymbolRef::Param(i) = symbol else {
                return None;
            };
            let name = &self.model.params[*i].name;
            parts.push(scaled_by(*coefficient, quote!(#scaled.#name)));
        }
        for (coefficient, formula) in &magnitude.formulas {
            let value = crate::codegen::evaluators::formula_tokens(formula, &|i| {
                let name = &self.model.params[i].name;
                quote!(#scaled.#name)
            });
            parts.push(scaled_by(*coefficient, value));
        }
        let constant = magnitude.constant;
        if constant != 0.0 {
            parts.push(quote!(T::constant(#constant)));
        }
        match parts.as_slice() {
            [] => None,
            [one] => Some(one.clone()),
            _ => Some(quote!((#(#parts)+*))),
        }
    }
}

/// `coefficient·value`, or `value` alone for a coefficient of 1.
fn scaled_by(coefficient: f64, value: TokenStream) -> TokenStream {
    if coefficient == 1.0 {
        value
    } else {
        quote!((T::constant(#coefficient) * #value))
    }
}
