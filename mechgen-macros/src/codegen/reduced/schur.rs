//! The reduced Jacobian inside each evaluation of the iteration: the Schur complement of the
//! closed-form loops' 2×2 blocks in the loops' Jacobian, which is the implicit
//! differentiation of the residual through the closed forms. Separate from the iteration it
//! is spliced into because it is matrix algebra on the entries' locals and the reduction's
//! structure alone, with no [`Generator`](crate::codegen::Generator) state.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;

use crate::codegen::emit::local;
use crate::symbolic::Reduction;

/// The reduced Jacobian `J[F,S] − J[F,Y]·J[G,Y]⁻¹·J[G,S]` from the loops' Jacobian entries
/// (`entry(r, c)`: the local holding a structurally non-zero one): the statements that
/// solve, step by step down the block-triangular `J[G,Y]`, for
/// `W_s = J[G_s,Y_s]⁻¹·(J[G_s,S] − Σ_{r<s} J[G_s,Y_r]·W_r)` (so `dY_s/dS = −W_s`), each 2×2
/// block factored once and each column a solve, skipping the columns that are structurally
/// zero; and the matrix `J[F,S] − Σ_s J[F,Y_s]·W_s`.
pub(super) fn schur_complement(
    reduction: &Reduction,
    entry: &dyn Fn(usize, usize) -> Option<Ident>,
    undefined: &Ident,
) -> (TokenStream, TokenStream) {
    let iterated = &reduction.iterated;
    let steps = &reduction.steps;
    let mut statements = Vec::new();
    // w[s][j]: the local holding column j of W_s, a `[T; 2]`, if it is not zero.
    let mut w: Vec<Vec<Option<Ident>>> = Vec::new();
    // `J[r, c] − Σ_s J[r, Y_s]·W_s[.., j]` over the steps solved so far.
    let combination = |r: usize, c: usize, j: usize, w: &[Vec<Option<Ident>>]| {
        let subtracted: Vec<TokenStream> = steps
            .iter()
            .zip(w)
            .filter_map(|(step, columns)| Some((step, columns[j].as_ref()?)))
            .flat_map(|(step, column)| {
                step.unknowns.iter().enumerate().filter_map(move |(k, &y)| {
                    let d = entry(r, y)?;
                    let k = Literal::usize_unsuffixed(k);
                    Some(quote!(#d * #column[#k]))
                })
            })
            .collect();
        match (entry(r, c), subtracted.split_first()) {
            (Some(direct), _) => quote!(#direct #(- #subtracted)*),
            (None, None) => quote!(T::zero()),
            (None, Some((first, rest))) => quote!(-#first #(- #rest)*),
        }
    };
    for (s, step) in steps.iter().enumerate() {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1];
        let [[a, b], [c, d]] = rows.map(|r| {
            step.unknowns
                .map(|y| entry(r, y).map_or_else(|| quote!(T::zero()), |d| quote!(#d)))
        });
        let inner = local(&format!("inner{s}"));
        let (determinant, squares, relative, inverse, factored) = (
            local("inner_determinant"),
            local("inner_squares"),
            local("inner_relative"),
            local("inner_inverse"),
            local("inner_factored"),
        );
        // As `Factored::new` would factor it, to the bit: where the squares of the column
        // norms are normal and finite, the explicit inverse (`Singular` at or below the
        // threshold), else the scaled LU in `Factored` itself.
        statements.push(quote! {
            let #determinant = #a * #d - #b * #c;
            let #squares = (#a * #a + #c * #c) * (#b * #b + #d * #d);
            let #inner = if #squares >= T::min_positive_value() && #squares <= T::max_value() {
                let #relative = #determinant / #squares.sqrt();
                if #relative.is_nan()
                    || #relative.abs() <= ::mechgen::singular_threshold::<T>()
                {
                    return #undefined;
                }
                let #inverse = T::one() / #determinant;
                ::core::result::Result::Ok([
                    [#d * #inverse, -#b * #inverse],
                    [-#c * #inverse, #a * #inverse],
                ])
            } else {
                let ::core::result::Result::Ok(#factored) =
                    ::mechgen::__private::Factored::new([[#a, #b], [#c, #d]])
                else {
                    return #undefined;
                };
                ::core::result::Result::Err(#factored)
            };
        });
        let columns = iterated
            .iter()
            .enumerate()
            .map(|(j, &column)| {
                if !reduction.slopes[s][j] {
                    return None;
                }
                let [p, q] = rows.map(|r| combination(r, column, j, &w));
                let name = local(&format!("w{s}_{j}"));
                let (inverse, factored) = (local("inner_inverse"), local("inner_factored"));
                let (first, second) = (local("inner_p"), local("inner_q"));
                // `Factored::solve`'s sums, from zero.
                statements.push(quote! {
                    let #name = {
                        let (#first, #second) = (#p, #q);
                        match #inner {
                            ::core::result::Result::Ok(#inverse) => [
                                T::zero() + #inverse[0][0] * #first + #inverse[0][1] * #second,
                                T::zero() + #inverse[1][0] * #first + #inverse[1][1] * #second,
                            ],
                            ::core::result::Result::Err(#factored) => {
                                #factored.solve([#first, #second])
                            }
                        }
                    };
                });
                Some(name)
            })
            .collect();
        w.push(columns);
    }
    let rows = reduction
        .residual_loops
        .iter()
        .flat_map(|&l| [2 * l, 2 * l + 1])
        .map(|r| {
            let entries = iterated
                .iter()
                .enumerate()
                .map(|(j, &column)| combination(r, column, j, &w));
            quote!([#(#entries),*])
        });
    let jacobian = quote!([#(#rows),*]);
    (quote!(#(#statements)*), jacobian)
}
