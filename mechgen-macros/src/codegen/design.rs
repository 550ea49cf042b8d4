//! `impl mechgen::Design` for a declaration with sensitivities: its parameters, unknowns'
//! and points' sensitivities as arrays, so that a design method written once (synthesis,
//! tolerance analysis) serves every mechanism. Separate because it only adapts the
//! generated functions to the trait's arrays.

use proc_macro2::{Literal, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

use super::Generator;
use super::emit::local;
use crate::model::Kind;

impl Generator<'_> {
    /// The `Design` impl, or nothing without sensitivities.
    pub(super) fn design_impl(&self) -> TokenStream {
        if self.equations.sensitivities.is_none() {
            return TokenStream::new();
        }
        let name = &self.model.name;
        let unknowns_type = &self.unknowns_type;
        let params = &self.model.params;
        let (n, p, m) = (
            Literal::usize_unsuffixed(self.model.unknowns.len()),
            Literal::usize_unsuffixed(params.len()),
            Literal::usize_unsuffixed(self.model.points.len()),
        );
        let names = params.iter().map(|param| param.name.unraw().to_string());
        let lengths = params.iter().map(|param| param.kind == Kind::Length);
        let angles = self
            .model
            .unknowns
            .iter()
            .map(|unknown| unknown.kind == Kind::Angle);
        let fields: Vec<_> = params.iter().map(|param| &param.name).collect();
        let (input, position, values, found) = (
            local("input"),
            local("position"),
            local("values"),
            local("found"),
        );
        let points: Vec<_> = self.model.points.iter().map(|point| &point.name).collect();
        let (positions, point_sensitivities) = if points.is_empty() {
            (
                quote!(::core::result::Result::Ok([])),
                quote!(::core::result::Result::Ok([[]; #p])),
            )
        } else {
            let per_parameter = fields
                .iter()
                .map(|field| quote!([#(#found.#field.#points),*]));
            (
                quote! {
                    let #found = self.points(#input, &#unknowns_type::from_array(#position))?;
                    ::core::result::Result::Ok([#(#found.#points),*])
                },
                quote! {
                    let #found = self.point_sensitivities(
                        #input,
                        &#unknowns_type::from_array(#position),
                    )?;
                    ::core::result::Result::Ok([#(#per_parameter),*])
                },
            )
        };
        // Each field from its index: a binding pattern would read a parameter named like an
        // enum variant in scope (`Ok`) as that variant.
        let from_values = fields.iter().enumerate().map(|(k, field)| {
            let k = Literal::usize_unsuffixed(k);
            quote!(#field: #values[#k])
        });
        // A declaration without parameters has a phantom field in its struct.
        let phantom = params.is_empty().then(|| {
            let scalar = super::types::scalar_field();
            quote!(#scalar: ::core::marker::PhantomData,)
        });
        quote! {
            impl<T: ::mechgen::Real> ::mechgen::Design<T, #n, #p, #m> for #name<T> {
                const PARAMETERS: [&'static str; #p] = [#(#names),*];
                const PARAMETER_LENGTHS: [bool; #p] = [#(#lengths),*];
                const UNKNOWN_ANGLES: [bool; #n] = [#(#angles),*];

                fn parameters(&self) -> [T; #p] {
                    [#(self.#fields),*]
                }

                fn with_parameters(#values: [T; #p]) -> Self {
                    #name { #(#from_values,)* #phantom }
                }

                fn unknown_sensitivities(
                    &self,
                    #input: T,
                    #position: [T; #n],
                ) -> ::core::result::Result<[[T; #n]; #p], ::mechgen::Error<T>> {
                    let #found = self.sensitivities(#input, &#unknowns_type::from_array(#position))?;
                    ::core::result::Result::Ok([#(#found.#fields.to_array()),*])
                }

                fn point_positions(
                    &self,
                    #input: T,
                    #position: [T; #n],
                ) -> ::core::result::Result<[::mechgen::Vec2<T>; #m], ::mechgen::Error<T>> {
                    #positions
                }

                fn point_sensitivities(
                    &self,
                    #input: T,
                    #position: [T; #n],
                ) -> ::core::result::Result<[[::mechgen::Vec2<T>; #m]; #p], ::mechgen::Error<T>> {
                    #point_sensitivities
                }
            }
        }
    }
}
