//! The rate functions (`velocity`, `acceleration`, `motion_at`) on the mechanism scaled by a
//! power of two with time counted in another: where the mechanism's size or its input rates
//! are far from 1, they solve with both brought near 1 and scale the answer back, and the
//! accuracy they state carries what the float's range costs results that leave it.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use super::emit::local;
use super::normalise::Normalised;
use super::{Generator, arg};

impl Generator<'_> {
    /// A rates function (`name`: `velocity`, `order` 1; `acceleration`, `order` 2) taking
    /// the first `arity` of the arguments (input, position, input rate, velocity, input
    /// acceleration): `checks`, then `body` on the mechanism as given where its size and the
    /// input rates are well inside the float's range ([`Self::as_given_with_rates`]), and
    /// elsewhere, out of line, on the mechanism scaled by a power of two with time counted in
    /// another (`mechgen::__private::rate_scale`): the position's lengths times the scale, a
    /// velocity's too and all of it times `tempo`, and the answer back in the caller's units
    /// and time. The same bits either way while nothing overflows or underflows; where the
    /// rates as given would (a squared rate of 1e-400 times a length of 1e300), the right
    /// answer rather than a zero or an error, and where a result itself leaves the float's
    /// range, an accuracy that says what that costs ([`Self::stated_in_own_units`]).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn normalised_rates_function(
        &self,
        name: &Ident,
        docs: TokenStream,
        arity: usize,
        output: &TokenStream,
        checks: TokenStream,
        body: TokenStream,
        rates: RatesOutput,
    ) -> TokenStream {
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let (position, velocity, value) = (arg("position"), arg("velocity"), local("value"));
        let (input_params, input) = (self.input_params(), self.input_args());
        let (dot_params, ddot_params) = (self.input_dot_params(), self.input_ddot_params());
        let (dot_args, ddot_args) = (self.input_dot_args(), self.input_ddot_args());
        let Normalised {
            prologue,
            rates_prologue,
            velocity_prologue,
            receiver,
            input: scaled_input,
            input_dot: scaled_dot,
            input_ddot: scaled_ddot,
            restore,
        } = self.normalised();
        let accelerations = arity >= 5 || rates == RatesOutput::Motion;
        let rates_prologue = if accelerations {
            rates_prologue
        } else {
            velocity_prologue
        };
        let (scale, tempo) = (local("scale"), local("tempo"));
        let lengths = self.length_unknowns();
        let (mut params, mut args, mut scaled_args) = (
            vec![
                quote!(#input_params),
                quote!(#position: &#unknowns),
                dot_params,
            ],
            vec![input.clone(), quote!(#position), dot_args],
            vec![scaled_input, quote!(&#position), scaled_dot.clone()],
        );
        let mut scaled_velocity = TokenStream::new();
        // `motion_at` takes the input's acceleration after its rate, with no velocity.
        if arity >= 4 && rates != RatesOutput::Motion {
            params.push(quote!(#velocity: &#unknowns));
            args.push(quote!(#velocity));
            scaled_args.push(quote!(&#velocity));
            scaled_velocity = quote! {
                let #velocity = #ty::from_array(::mechgen::__private::untimed(
                    #velocity.to_array(),
                    [#(#lengths),*],
                    #scale,
                    #tempo,
                    1,
                    "velocity",
                )?);
            };
        }
        if accelerations {
            params.push(ddot_params);
            args.push(ddot_args);
            scaled_args.push(scaled_ddot.clone());
        }
        let given_position = local("given_position");
        let accuracy = local("accuracy");
        let required = quote!(&::mechgen::Accuracy::required());
        let ddots = if accelerations {
            scaled_ddot.clone()
        } else {
            TokenStream::new()
        };
        // The velocity and acceleration solves hand back the accuracy they checked, which
        // only this path, where results may leave the float's normal range, reads.
        let (solved, finish) = match rates {
            RatesOutput::Velocity | RatesOutput::Acceleration => {
                let (quantity, order, highest) = if rates == RatesOutput::Velocity {
                    ("velocity", 1, "Velocity")
                } else {
                    ("acceleration", 2, "Acceleration")
                };
                let stated = self.stated_in_own_units(
                    quote!(#accuracy),
                    (&scaled_dot, &ddots),
                    required,
                    highest,
                );
                let finish = self.untimed_unknowns(&value, quantity, order);
                (
                    quote!(let (#value, #accuracy) =),
                    quote! {{
                        #stated;
                        #finish
                    }},
                )
            }
            RatesOutput::Motion => {
                let (rates, accelerations) = (local("rates"), local("accelerations"));
                let velocity = self.untimed_unknowns(&rates, "velocity", 1);
                let acceleration = self.untimed_unknowns(&accelerations, "acceleration", 2);
                let stated = self.stated_in_own_units(
                    quote!(#value.accuracy),
                    (&scaled_dot, &ddots),
                    required,
                    "Acceleration",
                );
                (
                    quote!(let #value =),
                    quote! {{
                        let #rates = #value.velocity;
                        let #accelerations = #value.acceleration;
                        ::mechgen::Motion {
                            position: *#given_position,
                            velocity: #velocity,
                            acceleration: #acceleration,
                            accuracy: #stated,
                        }
                    }},
                )
            }
        };
        let (solve_output, as_given_value) = if rates == RatesOutput::Motion {
            (quote!(#output), TokenStream::new())
        } else {
            (
                quote!((#output, ::mechgen::Accuracy<T>)),
                quote!(.map(|(#value, _)| #value)),
            )
        };
        let as_given = self.as_given_with(accelerations);
        let solve = format_ident!("mechgen_{}_solve", name);
        let normalised = format_ident!("mechgen_{}_normalised", name);
        let normalised_doc = super::docs::doc(&format!(
            "[`Self::{name}`] on the mechanism scaled by a power of two, with time counted in \
             another, for a mechanism or rates far from 1: the same bits as at any other size."
        ));
        let solve_doc = super::docs::doc(&format!(
            "[`Self::{name}`] on the mechanism it is called on: the mechanism as given, or \
             scaled by a power of two."
        ));
        quote! {
            #docs
            pub fn #name(&self, #(#params),*) -> ::core::result::Result<#output, ::mechgen::Error<T>> {
                #checks
                if #as_given {
                    self.#solve(#(#args),*)#as_given_value
                } else {
                    self.#normalised(#(#args),*)
                }
            }

            #normalised_doc
            #[cold]
            #[inline(never)]
            fn #normalised(&self, #(#params),*) -> ::core::result::Result<#output, ::mechgen::Error<T>> {
                #prologue
                #rates_prologue
                let #given_position = #position;
                let #position = #ty::from_array(::mechgen::__private::scaled(
                    #position.to_array(),
                    [#(#lengths),*],
                    #scale,
                ));
                #scaled_velocity
                #solved #receiver.#solve(#(#scaled_args),*)#restore?;
                ::core::result::Result::Ok(#finish)
            }

            #solve_doc
            #[allow(unused_variables)]
            #[inline(always)]
            fn #solve(&self, #(#params),*) -> ::core::result::Result<#solve_output, ::mechgen::Error<T>> {
                #body
            }
        }
    }

    /// The accuracy `stated` by a computation in the scaled units (lengths times `scale`,
    /// time counted in `tempo`, whose input rates and accelerations were `rates`), in the
    /// mechanism's own: with what the float's smallest numbers cost where the results leave
    /// its normal range, checked against `required` at the rates' orders up to `highest`
    /// (`mechgen::__private::stated_in_own_units`).
    pub(super) fn stated_in_own_units(
        &self,
        stated: TokenStream,
        rates: (&TokenStream, &TokenStream),
        required: TokenStream,
        highest: &str,
    ) -> TokenStream {
        let tempo = local("tempo");
        // A length's rates are nearer the float's floor on a tiny mechanism, by the scale; an
        // angle's are not, on a mechanism of any size: the larger of those there are.
        let lengths = self.length_unknowns();
        let scale = local("scale");
        let scale = match (lengths.contains(&true), lengths.contains(&false)) {
            (true, true) => quote!(#scale.max(T::one())),
            (true, false) => quote!(#scale),
            (false, _) => quote!(T::one()),
        };
        let (dots, ddots) = rates;
        let given = self.input_dot_args();
        let highest = Ident::new(highest, Span::call_site());
        quote! {
            ::mechgen::__private::stated_in_own_units(
                #stated,
                &[#given],
                &[#dots],
                &[#ddots],
                #tempo,
                #scale,
                #required,
                ::mechgen::Order::#highest,
            )?
        }
    }
}

/// What a function [`Generator::normalised_rates_function`] makes returns.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum RatesOutput {
    /// The unknowns' rates (`velocity`).
    Velocity,
    /// Their accelerations (`acceleration`).
    Acceleration,
    /// A `Motion`: the position given, rates, accelerations and accuracy (`motion_at`).
    Motion,
}
