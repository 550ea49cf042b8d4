//! `{Name}Newton`: Newton's `motion_near` with what it reads of the dimensions checked and
//! computed once, by `newton()`, as a careful hand-written solver precomputes its linkage's
//! constants. The general `motion_near` checks every parameter, tests the size and computes
//! the size and aspect its accuracy is stated against on each call; here the parameters were
//! checked when the constants were made, and a call tests only what it brings (its inputs,
//! their rates and accelerations). The iteration, the rates and the accuracy are the general
//! function's own tokens, so the two give the same bits; anything off the common path (an
//! input that is not finite, a size or rates not taken as given, a step Newton's common path
//! does not take) is the general function's, out of line.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use super::docs::doc;
use super::newton::FullMotionNear;
use super::{Generator, arg};
use crate::model::Kind;

impl Generator<'_> {
    fn newton_type(&self) -> Ident {
        format_ident!("{}Newton", self.model.name)
    }

    /// Whether the mechanism gets a `{Name}Newton`: wherever it has `motion_near`.
    fn has_newton_type(&self) -> bool {
        self.model.outputs.acceleration
    }

    /// The `{Name}Newton` type and its `impl`, outside the mechanism's.
    pub(super) fn newton_items(&self) -> TokenStream {
        if !self.has_newton_type() {
            return TokenStream::new();
        }
        let name = &self.model.name;
        let newton = self.newton_type();
        let unknowns = &self.unknowns_type;
        let (input_params, input) = (self.input_params(), self.input_args());
        let (dot_params, ddot_params) = (self.input_dot_params(), self.input_ddot_params());
        let (dots, ddots) = (self.input_dot_args(), self.input_ddot_args());
        let (guess, options) = (arg("guess"), arg("options"));
        let type_doc = doc(&format!(
            "[`{name}`]'s Newton solver, made by [`{name}::newton`]: its parameters checked \
             finite, and the size and aspect its accuracy is stated against computed, once."
        ));
        let motion_near_doc = if self.equations.reduction.is_some() {
            doc(&format!(
                "[`{name}::motion_near`] itself: where Newton iterates on fewer unknowns than \
                 the loops have, it keeps its own checks, and the solver saves nothing per call."
            ))
        } else {
            doc(&format!(
                "[`{name}::motion_near`], with the dimensions' checks and constants from \
                 [`{name}::newton`]: the same bits, fewer instructions per call (each call \
                 checks only its own arguments)."
            ))
        };
        quote! {
            #type_doc
            #[derive(Clone, Copy, Debug, PartialEq)]
            pub struct #newton<T> {
                mechanism: #name<T>,
                constants: ::mechgen::__private::NewtonConstants<T>,
            }

            #[allow(clippy::too_many_arguments)]
            impl<T: ::mechgen::Real> #newton<T> {
                /// The mechanism it solves.
                pub fn mechanism(&self) -> &#name<T> {
                    &self.mechanism
                }

                #motion_near_doc
                #[inline(always)]
                pub fn motion_near(
                    &self,
                    #input_params,
                    #guess: &#unknowns<T>,
                    #options: &::mechgen::NewtonOptions<T>,
                    #dot_params,
                    #ddot_params,
                ) -> ::core::result::Result<
                    ::mechgen::Solved<::mechgen::Motion<#unknowns<T>, T>, T>,
                    ::mechgen::Error<T>,
                > {
                    self.mechanism.mechgen_motion_near_prepared(
                        #input, #guess, #options, #dots, #ddots, &self.constants,
                    )
                }
            }
        }
    }

    /// `newton()`, in the mechanism's `impl`: the parameters checked finite (and the formulas
    /// of them), then the constants.
    pub(super) fn newton_constructor(&self) -> TokenStream {
        if !self.has_newton_type() {
            return TokenStream::new();
        }
        let newton = self.newton_type();
        let (values, labels) = self.dimension_checks();
        let size = self.accuracy_size(quote!(self));
        let receiver = Ident::new("self", Span::call_site());
        let aspect = self
            .known_aspect(&receiver, &quote!(size))
            .unwrap_or_else(|| quote!(T::nan()));
        // Unused where the columns are not known.
        let columns = self
            .known_column_product()
            .unwrap_or_else(|| quote!(T::nan()));
        // A length input joins the size each call: then the call tests it all.
        let as_given = if self.has_length_input() {
            quote!(true)
        } else {
            self.as_given()
        };
        // The loops' scale, which Newton's floors are multiples of, tested once here rather
        // than at each solution (see `prepared_scale`).
        let as_given = match self.prepared_scale() {
            Some(_) => quote!(#as_given && ::mechgen::__private::scale_within_range(scale)),
            None => as_given,
        };
        // Unused where the declaration does not give the scale.
        let scale = self.declared_scale().unwrap_or_else(|| quote!(T::nan()));
        let docs = doc(&format!(
            "A [`{newton}`] for this mechanism: [`Self::motion_near`] with the parameters \
             checked and the constants Newton's accuracy reads computed here, once, rather \
             than on every call.\n\nErrors: [`mechgen::Error::NonFinite`] naming a parameter \
             that is not finite."
        ));
        quote! {
            #docs
            pub fn newton(&self) -> ::core::result::Result<#newton<T>, ::mechgen::Error<T>> {
                ::mechgen::__private::check_all_finite([#(#values),*], &[#(#labels),*])?;
                let size = #size;
                let scale = #scale;
                ::core::result::Result::Ok(#newton {
                    mechanism: *self,
                    constants: ::mechgen::__private::NewtonConstants {
                        size,
                        scale,
                        aspect: ::mechgen::__private::KnownAspect::new(#aspect),
                        columns: ::mechgen::__private::KnownColumns::new(#columns),
                        as_given: #as_given,
                    },
                })
            }
        }
    }

    /// The loops' scale (`mechgen::__private::Linearisation::scale`, the sum of every
    /// magnitude's size) over `self`, where the declaration gives every magnitude over the
    /// parameters: Newton's evaluations take it from here, and a `{Name}Newton` computes it
    /// once, by this same expression.
    pub(super) fn declared_scale(&self) -> Option<TokenStream> {
        let receiver = Ident::new("self", Span::call_site());
        self.fixed_scale(&receiver)
    }

    /// [`Self::declared_scale`] where `newton()` tests it finite, and the prepared solve then
    /// leaves out the test of the scale at each solution (`newton_common_at_finite_scale`):
    /// `None` with a length input, whose size each call brings.
    pub(super) fn prepared_scale(&self) -> Option<TokenStream> {
        if self.has_length_input() {
            return None;
        }
        self.declared_scale()
    }

    fn has_length_input(&self) -> bool {
        self.model
            .inputs
            .iter()
            .any(|input| input.kind == Kind::Length)
    }

    /// `mechgen_motion_near_prepared`, which `{Name}Newton::motion_near` calls, and the
    /// general `motion_near` out of line (`mechgen_motion_near_checked`) for what it does not
    /// take: for a mechanism without a reduction, the common path of `motion_near` with the
    /// size and aspect from the constants; with one, the general function itself.
    pub(super) fn prepared_motion_near(&self) -> TokenStream {
        let (input, dots, ddots) = (
            self.input_args(),
            self.input_dot_args(),
            self.input_ddot_args(),
        );
        let (guess, options) = (arg("guess"), arg("options"));
        let constants = arg("constants");
        let checked = Ident::new("mechgen_motion_near_checked", Span::call_site());
        let general = quote!(self.motion_near(#input, #guess, #options, #dots, #ddots));
        let reduced = self.equations.reduction.is_some();
        let body = if reduced {
            general.clone()
        } else {
            let FullMotionNear { common, .. } =
                self.full_motion_near_with(&checked, Some(&constants));
            // An angle input within `sin_cos`'s fast range, which that test establishes once
            // for both (a NaN or infinite angle is beyond it); a length input finite.
            let of_kind = |kind: Kind| {
                self.model
                    .inputs
                    .iter()
                    .filter(move |input| input.kind == kind)
                    .map(|input| &input.name)
            };
            let (angles, lengths): (Vec<_>, Vec<_>) = (
                of_kind(Kind::Angle).collect(),
                of_kind(Kind::Length).collect(),
            );
            let mut inputs_taken = Vec::new();
            if !lengths.is_empty() {
                inputs_taken.push(quote!(::mechgen::__private::all_finite(&[#(#lengths),*])));
            }
            if !angles.is_empty() {
                inputs_taken
                    .push(quote!(::mechgen::__private::within_sin_cos_range(&[#(#angles),*])));
            }
            let sizes = if self.has_length_input() {
                self.as_given()
            } else {
                quote!(#constants.as_given)
            };
            quote! {
                if #sizes
                    && ::mechgen::__private::rates_as_given(&[#dots], &[#ddots])
                    #(&& #inputs_taken)*
                {
                    #common
                } else {
                    self.#checked(#input, #guess, #options, #dots, #ddots)
                }
            }
        };
        let prepared = self.motion_near_item_with(
            quote!(fn mechgen_motion_near_prepared),
            doc(&format!(
                "[`Self::motion_near`] with the dimensions' checks and constants from \
                 [`Self::newton`]: [`{}::motion_near`].",
                self.newton_type()
            )),
            quote!(#[allow(unused_variables)] #[inline(always)]),
            quote!(#constants: &::mechgen::__private::NewtonConstants<T>,),
            TokenStream::new(),
            body,
        );
        if reduced {
            return prepared;
        }
        let checked_item = self.motion_near_item(
            quote!(fn #checked),
            doc(
                "[`Self::motion_near`] out of line: where a prepared solve leaves the \
                 common path.",
            ),
            quote!(#[cold] #[inline(never)]),
            TokenStream::new(),
            general,
        );
        quote!(#prepared #checked_item)
    }
}
