//! The auxiliary values a kernel computes between its straight-line statements (branch and
//! triangle roots, inverses, block determinants, angles): which ones it needs, what each is
//! computed from, and its `let`. Separate because this is where the kernels' forms differ:
//! the fast and batch kernels pass a failure on as NaN, the checked kernel tests each value
//! where it is computed and says why it failed.

use std::collections::BTreeSet;

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::Mode;
use crate::codegen::emit::{Emitted, children};
use crate::codegen::{Generator, arg};
use crate::model::Kind;
use crate::symbolic::{AuxKind, ExprId, Graph, Node, Straight, Threshold, Var};

impl Generator<'_> {
    /// `let auxK = …;`: auxiliary value `k` from its emitted arguments (taken from
    /// `emitted`), blaming a non-finite argument among `inputs` when it fails.
    pub(super) fn aux_definition(
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
            rates_threshold_squared,
            rates_order,
        } = kernel;
        // Fast and batch kernels pass a failure on as NaN, for the checked kernel to explain.
        let lanes = *mode != Mode::Checked;
        let input = &self.model.inputs[0].name;
        // A length input was scaled with the mechanism; an error reports it as given.
        let input = if self.model.inputs[0].kind == Kind::Length {
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
            AuxKind::InverseDeterminant {
                threshold,
                squared_norms,
                ..
            } if lanes => {
                let [det, norms] = [&args[0], &args[1]];
                // A turning angle's column beyond the ordinary aspect: NaN, for the checked
                // kernel to judge at the aspect it gives.
                let turning = &args[2..];
                let least = quote!(self.rate_limits.least_turning_column);
                let guarded = |value: TokenStream| {
                    turning.iter().fold(value, |value, column| {
                        quote!(::mechgen::__private::lanes::within_ordinary_aspect(#value, #column, #least))
                    })
                };
                let value = if squared_norms.is_some() {
                    // The threshold squared: (8ε)² is 64ε², exactly.
                    let squared = match threshold {
                        Threshold::Position => {
                            quote!(T::constant(64.0) * T::epsilon() * T::epsilon())
                        }
                        Threshold::Rates => rates_threshold_squared.clone(),
                    };
                    quote!(::mechgen::__private::lanes::inverse_determinant_squared(#det, #norms, #squared))
                } else {
                    let threshold = match threshold {
                        Threshold::Position => quote!(T::constant(8.0) * T::epsilon()),
                        Threshold::Rates => rates_threshold.clone(),
                    };
                    quote!(::mechgen::__private::lanes::inverse_determinant(#det, #norms, #threshold))
                };
                guarded(value)
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
                // The shortest turning angle's column, NaN if either is.
                let turning = match &args[2..] {
                    [] => None,
                    [column] => Some(quote!(#column)),
                    [a, b] => Some(quote! {{
                        let (a, b) = (#a, #b);
                        if a.is_nan() || a <= b { a } else { b }
                    }}),
                    _ => unreachable!("a block has two columns"),
                };
                let call = match (threshold, turning) {
                    (Threshold::Rates, Some(column)) => quote! {
                        self.rate_limits.inverse_determinant_turning(
                            #det,
                            #inverse_norms,
                            ::mechgen::Order::#rates_order,
                            #column,
                        )
                    },
                    (threshold, _) => match threshold {
                        Threshold::Position => quote! {
                            ::mechgen::__private::inverse_determinant(
                                #det,
                                #inverse_norms,
                                T::constant(8.0) * T::epsilon(),
                            )
                        },
                        Threshold::Rates => quote! {
                            self.rate_limits.inverse_determinant(
                                #det,
                                #inverse_norms,
                                ::mechgen::Order::#rates_order,
                            )
                        },
                    },
                };
                quote! {
                    #call.map_err(|error| ::mechgen::__private::blame(#inputs, error))?
                }
            }
            // In a batch, the branch-free angle vectorises; alone, an arc sine is faster: the
            // four-bar's two angles by it, two to a register, cost 12 instructions fewer per
            // call but 14% more time (its polynomial's chain of dependent operations is longer
            // than the platform's arc sine's).
            AuxKind::Angle { .. } if *mode == Mode::Lanes => {
                let (y, x) = (&args[0], &args[1]);
                quote!(::mechgen::fast::unit_angle(#y, #x))
            }
            AuxKind::Angle { .. } if lanes => {
                let (y, x) = (&args[0], &args[1]);
                quote!(::mechgen::__private::unit_angle(#y, #x))
            }
            // Checked: a vector off unit length (a link shorter than the rounding of what it
            // hangs from) still has a direction.
            AuxKind::Angle { .. } => {
                let (y, x) = (&args[0], &args[1]);
                quote!(::mechgen::__private::angle(#y, #x))
            }
        };
        quote!(let #name = #value;)
    }
}

/// Which kernel an auxiliary value is computed in: the inputs its errors blame, whether it is
/// a batch's lanes, and the threshold below which its blocks' rates are refused.
pub(super) struct KernelKind {
    pub(super) inputs: TokenStream,
    pub(super) mode: Mode,
    pub(super) rates_threshold: TokenStream,
    /// Its square, for blocks whose columns' norms move.
    pub(super) rates_threshold_squared: TokenStream,
    /// The highest order the kernel's rates are for.
    pub(super) rates_order: Ident,
}

/// What an auxiliary value is computed from, in a kernel of `mode`.
pub(super) fn aux_arguments(kind: &AuxKind, mode: Mode) -> Vec<ExprId> {
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
            det,
            squared_norms: Some(squared),
            turning,
            ..
        } if mode != Mode::Checked => [det, squared]
            .into_iter()
            .chain(turning.into_iter().flatten())
            .collect(),
        AuxKind::InverseDeterminant {
            det,
            inverse_norms,
            turning,
            ..
        } => [det, inverse_norms]
            .into_iter()
            .chain(turning.into_iter().flatten())
            .collect(),
        AuxKind::Angle { y, x } => vec![y, x],
    }
}

/// The auxiliary values `outputs` read, directly or through other auxiliary values, in
/// order.
pub(super) fn needed_aux(
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
