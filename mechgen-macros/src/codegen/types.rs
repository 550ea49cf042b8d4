//! The declared types: the mechanism struct, its unknowns and points types, and the
//! `mechgen::Kinematics` impl the runtime's sweep walks.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

use super::docs::{doc, docs_or};
use super::emit::local;
use super::{Generator, arg};
use crate::model::{Kind, Model};

impl Generator<'_> {
    pub(super) fn mechanism_struct(&self) -> TokenStream {
        let Model {
            attrs, vis, name, ..
        } = self.model;
        let mut fields: Vec<TokenStream> = self
            .model
            .params
            .iter()
            .map(|param| {
                let field = &param.name;
                let docs = docs_or(
                    &param.docs,
                    &format!("Parameter `{}`: {}.", field.unraw(), unit(param.kind)),
                );
                let vis = &param.vis;
                quote!(#docs #vis #field: T,)
            })
            .collect();
        // A mechanism without parameters (its magnitudes all the input and unknowns) still
        // has a scalar type, which a field must use; it is then built by `new`.
        let constructor = self.model.params.is_empty().then(|| {
            let scalar = scalar_field();
            fields.push(quote!(#scalar: ::core::marker::PhantomData<T>,));
            quote! {
                impl<T> #name<T> {
                    /// The mechanism: it has no parameters.
                    pub const fn new() -> Self {
                        Self { #scalar: ::core::marker::PhantomData }
                    }
                }

                impl<T> ::core::default::Default for #name<T> {
                    fn default() -> Self {
                        Self::new()
                    }
                }
            }
        });
        // Without a closed form, the docs say which loop has none and why, in place of the
        // `assemble` a reader would look for.
        let missing = self.equations.closed_form.as_ref().err().map(|missing| {
            let separator = (!attrs.is_empty()).then(|| quote!(#[doc = ""]));
            let text = doc(&format!(
                "No closed form: {}. So there is no `assemble` (nor `branch_of`, `motion` or \
                 scenes): [`position`](Self::position) solves the loops by Newton-Raphson from \
                 a guess.",
                missing.sentence(self.model)
            ));
            quote!(#separator #text)
        });
        quote! {
            #(#attrs)*
            #missing
            #[derive(Clone, Copy, Debug, PartialEq)]
            #vis struct #name<T> {
                #(#fields)*
            }

            #constructor
        }
    }

    pub(super) fn unknowns_struct(&self) -> TokenStream {
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

    pub(super) fn points_struct(&self) -> TokenStream {
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

    /// `impl mechgen::Kinematics`, which lets the runtime's sweep walk the mechanism. Needs
    /// the velocity for its predictor, and one input to sweep.
    pub(super) fn kinematics_impl(&self) -> TokenStream {
        if !self.model.outputs.velocity || self.model.inputs.len() > 1 {
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
        let size = self.accuracy_size(quote!(self));
        let rounding = (0..self.model.loops.len()).flat_map(|k| {
            let own = self.declared_size(quote!(self), Some(k));
            [own.clone(), own]
        });
        let units = self
            .model
            .unknowns
            .iter()
            .map(|unknown| match unknown.kind {
                Kind::Angle => quote!(T::one()),
                Kind::Length => quote!(length),
            });
        let length = quote! {
            let size = #size;
            // Declared lengths that sum to nothing measurable leave no unit of length but the
            // float's.
            let length = if size > T::zero() && size.is_finite() { size } else { T::one() };
        };
        let length_unit = self
            .model
            .unknowns
            .iter()
            .any(|unknown| unknown.kind == Kind::Length)
            .then(|| length.clone());
        let input_unit = match self.model.inputs.first().map(|input| input.kind) {
            Some(Kind::Length) => quote!(#length length),
            _ => quote!(T::one()),
        };
        let same_branch = if self
            .equations
            .closed_form
            .as_ref()
            .is_ok_and(|steps| steps.iter().any(|s| s.case.has_branches()))
        {
            quote! {
                self.branch_of(#input_a, &#ty::from_array(#a))
                    == self.branch_of(#input_b, &#ty::from_array(#b))
            }
        } else {
            // No closed form defines branches: the Jacobian's orientation tells assemblies
            // apart (it cannot change along one without passing a singular position).
            quote! {
                let orientation_a = ::mechgen::__private::orientation(
                    self.jacobian(#input_a, &#ty::from_array(#a)),
                );
                let orientation_b = ::mechgen::__private::orientation(
                    self.jacobian(#input_b, &#ty::from_array(#b)),
                );
                orientation_a.is_some() && orientation_a == orientation_b
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
                    // The rates at unit input rate, as `velocity` solves them, but without its
                    // accuracy requirement: the sweep only steers by them, and must steer
                    // right up to a toggle or change point, where they lose their digits.
                    // Solved scaled, so that a mechanism near the float's largest steers too.
                    let #position = #ty::from_array(#position);
                    let along = self.input_jacobian(#input, &#position).map(|v| -v);
                    let (slope, _, _) = ::mechgen::__private::solve_scaled(
                        self.jacobian(#input, &#position),
                        along,
                    )?;
                    ::mechgen::__private::finite(slope, "velocity")
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

                fn slope_within(
                    &self,
                    #input: T,
                    #position: [T; #count],
                ) -> ::core::result::Result<([T; #count], [T; #count]), ::mechgen::Error<T>> {
                    let #position = #ty::from_array(#position);
                    let along = self.input_jacobian(#input, &#position).map(|v| -v);
                    let (slope, factored, scale) = ::mechgen::__private::solve_scaled(
                        self.jacobian(#input, &#position),
                        along,
                    )?;
                    let slope = ::mechgen::__private::finite(slope, "velocity")?;
                    // Each row's residual as it is, and what rounding may hide of it: a few
                    // ε (each vector's sine or cosine and product, and the sum) per unit of its
                    // own loop's declared lengths.
                    let residual = self.residual(#input, &#position);
                    let floor = T::constant(4.0) * T::epsilon();
                    let rounding = [#(#rounding),*];
                    let mut errors = residual;
                    for (error, rounding) in errors.iter_mut().zip(rounding) {
                        *error = (error.abs() + floor * rounding) * scale;
                    }
                    ::core::result::Result::Ok((slope, factored.uncertainty(errors)))
                }

                fn units(&self) -> [T; #count] {
                    #length_unit
                    [#(#units),*]
                }

                fn input_unit(&self) -> T {
                    #input_unit
                }
            }
        }
    }
}

pub(super) fn unit(kind: Kind) -> &'static str {
    match kind {
        Kind::Length => "a length",
        Kind::Angle => "an angle, in radians",
    }
}

/// The field that holds the scalar type of a mechanism without parameters, which has no
/// other field to name a user's name could clash with.
pub(super) fn scalar_field() -> Ident {
    Ident::new("scalar", proc_macro2::Span::call_site())
}
