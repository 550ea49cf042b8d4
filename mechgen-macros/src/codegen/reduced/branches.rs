//! Each branching closed form's branch at the guess: the sign its runtime solver reads,
//! computed once, before the iteration, from the guess's values. Separate because this is
//! the one place the guess picks the assembly; inside the iteration and after it the signs
//! stay fixed.

use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

use super::steps::trig_nodes;
use crate::codegen::closed_forms::complex_values;
use crate::codegen::emit::{Context, emit, local, reachable};
use crate::codegen::{Generator, arg};
use crate::model::SymbolRef;
use crate::symbolic::{Case, ExprId, Step, Var};

impl Generator<'_> {
    /// Each branching step's sign at the guess, by the sign `branch_of` would read, from the
    /// guess's values, the `hoisted` values (the other generated names in scope are
    /// `reserved`), and the iterated angles' `turnings`, which this primes: the first
    /// evaluation, at the guess, then rotates their sines and cosines by nothing. Returns the
    /// statements, the variables they read, and each step's sign local, if it branches.
    pub(super) fn guess_signs(
        &self,
        steps: &[&Step],
        hoisted: &[(ExprId, Ident, usize)],
        reserved: &BTreeSet<String>,
        turnings: &BTreeMap<usize, Ident>,
    ) -> (Vec<TokenStream>, BTreeSet<Var>, Vec<Option<Ident>>) {
        let graph = &self.equations.graph;
        let guess = arg("guess");
        let unknown = |u: usize| &self.model.unknowns[u].name;
        let mut sign_statements = Vec::new();
        let mut sign_used = BTreeSet::new();
        let mut signs = Vec::new();
        for (s, step) in steps.iter().enumerate() {
            let Some(function) = sign_function(&step.case) else {
                signs.push(None);
                continue;
            };
            let needed = sign_coefficients(&step.case);
            let read = reachable(graph, &needed);
            let mut presets = hoisted.to_vec();
            let mut primes = Vec::new();
            for (&u, turning) in turnings {
                let stem = unknown(u).unraw().to_string();
                let [sin, cos] = [(0, "sin"), (1, "cos")].map(|(k, prefix)| {
                    let id = trig_nodes(graph, u)[k].filter(|id| read[id.index()])?;
                    let name = local(&format!("{prefix}_{stem}"));
                    presets.push((id, name.clone(), 0));
                    Some(name)
                });
                if sin.is_some() || cos.is_some() {
                    let [sin, cos] =
                        [sin, cos].map(|name| name.map_or(quote!(_), |name| quote!(#name)));
                    let name = unknown(u);
                    primes.push(quote!(let (#sin, #cos) = #turning.sin_cos(#guess.#name);));
                }
            }
            let context = Context {
                reserved,
                presets: &presets,
                stage: &|_| 0,
            };
            let block = emit(graph, &needed, &|var| self.var_name(var), &context);
            let unknowns = block.used.iter().filter_map(|&var| match var {
                Var::Value(SymbolRef::Unknown(u)) => {
                    let name = unknown(u);
                    Some(quote!(let #name = #guess.#name;))
                }
                _ => None,
            });
            let statements = block.statements.concat();
            let vectors = complex_values(&block.outputs);
            let first = unknown(step.unknowns[0]);
            // A flipped angle's case reads `q' = −q`.
            let first = if step.flipped[0] {
                quote!(-#guess.#first)
            } else {
                quote!(#guess.#first)
            };
            let sign = local(&format!("sign{s}"));
            sign_statements.push(quote! {
                let #sign = {
                    #(#primes)*
                    #(#unknowns)*
                    #(#statements)*
                    ::mechgen::Branch::from_sign(
                        ::mechgen::closed::#function(#(#vectors),*, #first),
                    )
                    .sign::<T>()
                };
            });
            sign_used.extend(block.used);
            signs.push(Some(sign));
        }
        (sign_statements, sign_used, signs)
    }
}

/// The runtime function giving a branching case's sign at a position.
fn sign_function(case: &Case) -> Option<Ident> {
    let name = match case {
        Case::TwoLengths { .. } => return None,
        Case::LengthAndOwnAngle { .. } => "length_and_own_angle_sign",
        Case::LengthAndOtherAngle { .. } => "length_and_other_angle_sign",
        Case::TwoAngles { .. } => "two_angles_sign",
    };
    Some(Ident::new(name, Span::call_site()))
}

/// The coefficients [`sign_function`] reads, flattened `(x, y)` by `(x, y)`.
fn sign_coefficients(case: &Case) -> Vec<ExprId> {
    let needed = match case {
        Case::LengthAndOwnAngle { w0, w1, .. } => [w0, w1],
        Case::LengthAndOtherAngle { k, v, .. } => [k, v],
        Case::TwoAngles { k, w1, .. } => [k, w1],
        Case::TwoLengths { .. } => return Vec::new(),
    };
    needed.into_iter().flatten().copied().collect()
}
