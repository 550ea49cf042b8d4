//! Computing on the mechanism scaled by a power of two: the closed forms and Newton take
//! the caller's mechanism, scale every length (and a length input, its rates, a guess's
//! lengths and a tolerance) so that the longest is about 1, solve, and scale the lengths they
//! found back. Scaling by a power of two is exact, so the same mechanism at any size gives
//! the same bits, and no square or product of lengths overflows or underflows.

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

use super::emit::local;
use super::{Generator, arg};
use crate::model::Kind;

/// A function's way to compute on its mechanism scaled by a power of two (the
/// longest length brought into `[1/2, 1)`): exactly, so that the same mechanism at any size,
/// scaled by a power of two, gives the same bits, and no product of lengths overflows or
/// leaves the float's normal range.
pub(super) struct Normalised {
    /// Binds `scale`, `unscale` and the scaled copy of the mechanism.
    pub(super) prologue: TokenStream,
    /// The scaled copy.
    pub(super) receiver: Ident,
    /// Binds `tempo` and `untempo`: the power of two time is counted in (see
    /// `mechgen::__private::rate_scale`), for a function with rates and accelerations.
    pub(super) rates_prologue: TokenStream,
    /// The same for a function with rates alone.
    pub(super) velocity_prologue: TokenStream,
    /// The inputs, and their rates and accelerations, as the scaled copy takes them (lists,
    /// comma-separated): lengths times `scale`, rates times `tempo`, accelerations times it
    /// twice.
    pub(super) input: TokenStream,
    pub(super) input_dot: TokenStream,
    pub(super) input_ddot: TokenStream,
    /// Gives back an error the input of the caller's units, where the input it names (the
    /// first) is a length.
    pub(super) restore: Option<TokenStream>,
}

impl Generator<'_> {
    /// How a function computes on the mechanism scaled by a power of two, so
    /// that it gives the same bits at every size (see [`Normalised`]).
    pub(super) fn normalised(&self) -> Normalised {
        let (scale, unscale) = (local("scale"), local("unscale"));
        let tempo = local("tempo");
        let receiver = local("normalised");
        let name = &self.model.name;
        let lengths = self.length_params();
        let fields = self.scaled_fields(&scale);
        let input = self.first_input();
        let length_input = self.model.inputs[0].kind == Kind::Length;
        // Each input (or its rate, or acceleration) times the scale where it is a length,
        // and a rate times `tempo` `order` times.
        let scaled = |values: Vec<&Ident>, order: usize| {
            let values = values
                .into_iter()
                .zip(&self.model.inputs)
                .map(|(value, input)| {
                    let value = if input.kind == Kind::Length {
                        quote!(#value * #scale)
                    } else {
                        quote!(#value)
                    };
                    (0..order).fold(value, |value, _| quote!(#value * #tempo))
                });
            quote!(#(#values),*)
        };
        // The rates and accelerations as `rate_scale` reads them: in the scaled lengths, not
        // yet in `tempo`.
        let (dots, ddots) = (
            scaled(self.input_dots.iter().collect(), 0),
            scaled(self.input_ddots.iter().collect(), 0),
        );
        let untempo = local("untempo");
        Normalised {
            prologue: quote! {
                let (#scale, #unscale) = ::mechgen::__private::length_scale(&[#(self.#lengths),*]);
                let #receiver = #name { #(#fields),* };
            },
            rates_prologue: quote! {
                let (#tempo, #untempo) = ::mechgen::__private::rate_scale(&[#dots], &[#ddots]);
            },
            velocity_prologue: quote! {
                let (#tempo, #untempo) = ::mechgen::__private::rate_scale(&[#dots], &[]);
            },
            receiver,
            input: scaled(self.inputs(), 0),
            input_dot: scaled(self.input_dots.iter().collect(), 1),
            input_ddot: scaled(self.input_ddots.iter().collect(), 2),
            restore: length_input.then(|| {
                let error = arg("failure");
                quote!(.map_err(|#error| ::mechgen::__private::at_input(#error, #input)))
            }),
        }
    }

    /// For each unknown, in declaration order, whether it is a length (which scales).
    pub(super) fn length_unknowns(&self) -> Vec<bool> {
        self.model
            .unknowns
            .iter()
            .map(|unknown| unknown.kind == Kind::Length)
            .collect()
    }

    /// `values` (an unknowns struct) back in the mechanism's units: its lengths times
    /// `unscale`, checked finite as `quantity`. The struct itself where there are no lengths.
    pub(super) fn unscaled_unknowns(&self, values: &Ident, quantity: &str) -> TokenStream {
        let ty = &self.unknowns_type;
        let lengths = self.length_unknowns();
        if !lengths.contains(&true) {
            return quote!(#values);
        }
        let unscale = local("unscale");
        quote! {
            #ty::from_array(::mechgen::__private::unscaled(
                #values.to_array(),
                [#(#lengths),*],
                #unscale,
                #quantity,
            )?)
        }
    }

    /// Rates (`order` 1) or accelerations (`order` 2) of the unknowns (an unknowns struct,
    /// `values`) back in the mechanism's units and the caller's time: as
    /// [`Self::unscaled_unknowns`], and times `untempo` `order` times
    /// (`mechgen::__private::untimed`).
    pub(super) fn untimed_unknowns(
        &self,
        values: &Ident,
        quantity: &str,
        order: i32,
    ) -> TokenStream {
        let ty = &self.unknowns_type;
        let lengths = self.length_unknowns();
        let (unscale, untempo) = (local("unscale"), local("untempo"));
        let order = proc_macro2::Literal::i32_unsuffixed(order);
        quote! {
            #ty::from_array(::mechgen::__private::untimed(
                #values.to_array(),
                [#(#lengths),*],
                #unscale,
                #untempo,
                #order,
                #quantity,
            )?)
        }
    }

    /// Whether to solve the mechanism as it is given (`mechgen::__private::as_given`, from
    /// its lengths and a length input): its size well inside the float's range.
    pub(super) fn as_given(&self) -> TokenStream {
        let mut sizes: Vec<TokenStream> = self
            .length_params()
            .into_iter()
            .map(|length| quote!(self.#length))
            .collect();
        for input in &self.model.inputs {
            if input.kind == Kind::Length {
                let name = &input.name;
                sizes.push(quote!(#name));
            }
        }
        // A length formula can be far longer than the parameters it is computed from.
        sizes.extend(self.loop_length_formulas().into_iter().map(|formula| {
            super::evaluators::formula_tokens(formula, &|i| {
                let field = &self.model.params[i].name;
                quote!(self.#field)
            })
        }));
        quote!(::mechgen::__private::as_given(&[#(#sizes),*]))
    }

    /// [`Self::as_given`] for a function with rates: the input rates and accelerations too
    /// (`mechgen::__private::rates_as_given`), whose squares and products with lengths
    /// elsewhere leave the float's range.
    pub(super) fn as_given_with_rates(&self) -> TokenStream {
        self.as_given_with(true)
    }

    /// [`Self::as_given_with_rates`], with the input accelerations or (`accelerations`
    /// false, for a function that takes none) without.
    pub(super) fn as_given_with(&self, accelerations: bool) -> TokenStream {
        let as_given = self.as_given();
        let dots = &self.input_dots;
        let ddots = accelerations
            .then_some(&self.input_ddots)
            .into_iter()
            .flatten();
        quote!(#as_given && ::mechgen::__private::rates_as_given(&[#(#dots),*], &[#(#ddots),*]))
    }

    /// `values` (an unknowns struct) checked finite as `quantity` where the unknowns hold a
    /// length (a length can overflow; an angle from `atan2` cannot): what
    /// [`Self::unscaled_unknowns`] checks, for the mechanism solved as given.
    pub(super) fn finite_unknowns(&self, values: &Ident, quantity: &str) -> TokenStream {
        let ty = &self.unknowns_type;
        if !self.length_unknowns().contains(&true) {
            return quote!(#values);
        }
        quote!(#ty::from_array(::mechgen::__private::finite(#values.to_array(), #quantity)?))
    }

    /// The public `position` or `motion_near` (`entry`), with `docs`: the entry's
    /// [`NewtonEntry::solve`] on the mechanism as it is given where its size is well inside
    /// the float's range (`mechgen::__private::as_given`); elsewhere, out of line, on
    /// the mechanism scaled by a power of two, with the guess's lengths and the tolerance
    /// scaled alike and the solution's lengths, rates and residual scaled back. Both give the
    /// same bits (rounding is the same at every power-of-two scale while nothing overflows or
    /// underflows), and the common case pays for one sum and two comparisons.
    pub(super) fn normalised_newton(&self, entry: NewtonEntry, docs: TokenStream) -> TokenStream {
        let (input_params, input) = (self.input_params(), self.input_args());
        let first_input = self.first_input();
        let (input_dots, input_ddots) = (self.input_dot_params(), self.input_ddot_params());
        let (input_dot, input_ddot) = (self.input_dot_args(), self.input_ddot_args());
        let (guess, options, failure) = (arg("guess"), arg("options"), arg("failure"));
        let (scale, unscale) = (local("scale"), local("unscale"));
        let (scaled_guess, scaled_options) = (local("scaled_guess"), local("scaled_options"));
        let (solved, value) = (local("solved"), local("value"));
        let (unknowns, _, _) = self.signature_types();
        let ty = &self.unknowns_type;
        let Normalised {
            prologue,
            rates_prologue,
            receiver,
            input: scaled_input,
            input_dot: scaled_dot,
            input_ddot: scaled_ddot,
            ..
        } = self.normalised();
        let rates_prologue = match entry {
            NewtonEntry::Position => TokenStream::new(),
            NewtonEntry::MotionNear => rates_prologue,
        };
        let lengths = self.length_unknowns();
        let guess_value = if lengths.contains(&true) {
            quote!(#ty::from_array(::mechgen::__private::scaled(#guess.to_array(), [#(#lengths),*], #scale)))
        } else {
            quote!(*#guess)
        };
        let (name, rate_parameters, rate_arguments, value_type, finish) = match entry {
            NewtonEntry::Position => (
                quote!(position),
                TokenStream::new(),
                TokenStream::new(),
                quote!(#unknowns),
                self.unscaled_unknowns(&value, "position"),
            ),
            NewtonEntry::MotionNear => {
                let [position, velocity, acceleration] =
                    ["position", "velocity", "acceleration"].map(local);
                let finish_position = self.unscaled_unknowns(&position, "position");
                let finish_velocity = self.untimed_unknowns(&velocity, "velocity", 1);
                let finish_acceleration = self.untimed_unknowns(&acceleration, "acceleration", 2);
                let stated = self.stated_in_own_units(
                    quote!(#value.accuracy),
                    (&scaled_dot, &scaled_ddot),
                    quote!(&#options.accuracy),
                    "Acceleration",
                );
                (
                    quote!(motion_near),
                    quote!(, #input_dots, #input_ddots),
                    quote!(, #scaled_dot, #scaled_ddot),
                    quote!(::mechgen::Motion<#unknowns, T>),
                    quote! {{
                        let #position = #value.position;
                        let #velocity = #value.velocity;
                        let #acceleration = #value.acceleration;
                        ::mechgen::Motion {
                            position: #finish_position,
                            velocity: #finish_velocity,
                            acceleration: #finish_acceleration,
                            accuracy: #stated,
                        }
                    }},
                )
            }
        };
        let normalised = entry.normalised();
        let solve = entry.solve();
        // `motion_near` is a kernel a sweep calls once a step: inline where the caller's
        // loop is, as the scene kernels are, so that what the caller does not read (the
        // accuracy, the iterations) need not be computed and written out.
        let inline = match entry {
            NewtonEntry::Position => TokenStream::new(),
            NewtonEntry::MotionNear => quote!(#[inline]),
        };
        let as_given = match entry {
            NewtonEntry::Position => self.as_given(),
            NewtonEntry::MotionNear => self.as_given_with_rates(),
        };
        let (rate_parameters_again, plain_arguments) = match entry {
            NewtonEntry::Position => (TokenStream::new(), TokenStream::new()),
            NewtonEntry::MotionNear => (
                quote!(, #input_dots, #input_ddots),
                quote!(, #input_dot, #input_ddot),
            ),
        };
        let result = quote! {
            ::core::result::Result<::mechgen::Solved<#value_type, T>, ::mechgen::Error<T>>
        };
        let normalised_doc = super::docs::doc(&format!(
            "[`Self::{name}`] on the mechanism scaled by a power of two, for a mechanism whose \
             size is far from 1: the same bits as at any other size."
        ));
        quote! {
            #docs
            #inline
            pub fn #name(
                &self,
                #input_params,
                #guess: &#unknowns,
                #options: &::mechgen::NewtonOptions<T>
                #rate_parameters
            ) -> #result {
                if #as_given {
                    self.#solve(#input, #guess, #options #plain_arguments)
                } else {
                    self.#normalised(#input, #guess, #options #plain_arguments)
                }
            }

            #normalised_doc
            #[cold]
            #[inline(never)]
            fn #normalised(
                &self,
                #input_params,
                #guess: &#unknowns,
                #options: &::mechgen::NewtonOptions<T>
                #rate_parameters_again
            ) -> #result {
                #prologue
                #rates_prologue
                let #scaled_guess = #guess_value;
                let #scaled_options = ::mechgen::NewtonOptions {
                    tolerance: #options.tolerance * #scale,
                    ..*#options
                };
                let #solved = #receiver
                    .#solve(#scaled_input, &#scaled_guess, &#scaled_options #rate_arguments)
                    .map_err(|#failure| ::mechgen::__private::newton_at_scale(#failure, #unscale, #first_input))?;
                let #value = #solved.value;
                ::core::result::Result::Ok(::mechgen::Solved {
                    value: #finish,
                    iterations: #solved.iterations,
                    residual_norm: #solved.residual_norm * #unscale,
                    condition: #solved.condition,
                })
            }
        }
    }
}

/// The Newton functions that compute on the normalised mechanism.
#[derive(Clone, Copy)]
pub(super) enum NewtonEntry {
    Position,
    MotionNear,
}

impl NewtonEntry {
    /// The private function that solves on the mechanism it is called on, under the public
    /// one.
    pub(super) fn solve(self) -> Ident {
        let name = match self {
            NewtonEntry::Position => "mechgen_position_solve",
            NewtonEntry::MotionNear => "mechgen_motion_near_solve",
        };
        Ident::new(name, Span::call_site())
    }

    /// The private function that solves on the mechanism scaled by a power of two.
    fn normalised(self) -> Ident {
        let name = match self {
            NewtonEntry::Position => "mechgen_position_normalised",
            NewtonEntry::MotionNear => "mechgen_motion_near_normalised",
        };
        Ident::new(name, Span::call_site())
    }
}
