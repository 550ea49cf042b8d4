//! The loops' Jacobian at the iteration's solution solved through its blocks: the
//! closed-form loops' 2×2 blocks and the reduced Jacobian Newton has already factored, or
//! the whole Jacobian factored where the blocks would not be as good. It gives `condition`
//! and, in `motion_near`, the rates, for a reduction with no loop solved after the
//! iteration. Separate because it is numerics on the solution alone, whatever the iteration
//! did to get there.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;

use crate::codegen::arg;
use crate::codegen::emit::{Emitted, local};
use crate::symbolic::{Graph, Reduction, Step};

/// How the loops' Jacobian `J` at the solution is solved: by its blocks where that is as good
/// as factoring it whole, else factored whole. The blocks are the closed-form loops' 2×2
/// `J[G_s,Y_s]` (inverted by Cramer's rule from the last evaluation's entries) and the
/// reduced Jacobian `R = J[F,S] − J[F,Y]·J[G,Y]⁻¹·J[G,S]` that Newton factored at its
/// solution, so `|det J| = |det R|·Π|det J[G_s,Y_s]|` (`J[G,Y]` is block lower-triangular)
/// and, `det R` being its relative determinant times its column norms, `J`'s relative
/// determinant is
///
/// `|det J| / Π‖J col‖ = |rel R|·Π|det J[G_s,Y_s]|·√(Π‖R col‖² / Π‖J col‖²)`.
///
/// The blocks are used only where every `J[G_s,Y_s]` has a relative determinant of at least
/// 1/16 (so solving through them loses at most a few bits to rounding against the whole
/// `J`), the products of squared column norms are normal and finite (no overflow or
/// underflow), and `J`'s relative determinant is above twice `mechgen::singular_threshold`;
/// anywhere else `J` is factored whole, as before, which then decides `Error::Singular` by
/// its own check. So `Singular` is reported exactly where factoring `J` whole reports it: the
/// block estimate differs from that one by rounding, far less than the margin. Only its
/// magnitude is used (for `condition`), so the blocks' order does not matter.
///
/// `entries` are `J`'s, row by row. Only for a reduction with no loop solved after the
/// iteration (`J` is then `[[J[F,S], J[F,Y]], [J[G,S], J[G,Y]]]` up to the order of rows
/// and columns). Binds `blocks`, `Ok` with each block's inverse determinant or `Err` with
/// `J` factored, and `block_relative`, `J`'s relative determinant.
pub(super) fn block_solver(
    reduction: &Reduction,
    graph: &Graph,
    entries: &[Emitted],
) -> TokenStream {
    let n = reduction.jacobian.len();
    let (converged, blocks) = (arg("converged"), local("blocks"));
    let nonzero = |r: usize, c: usize| !graph.is_zero(reduction.jacobian[r][c]);
    let bindings = (0..n)
        .flat_map(|r| (0..n).map(move |c| (r, c)))
        .filter(|&(r, c)| nonzero(r, c))
        .map(|(r, c)| {
            let (local, value) = (block_entry(r, c), &entries[r * n + c]);
            quote!(let #local = #value;)
        });
    let entry = |r: usize, c: usize| block_value(graph, reduction, r, c);
    let (normal, none) = (local("block_normal"), local("block_none"));
    let inverses: Vec<Ident> = (0..reduction.steps.len())
        .map(|s| local(&format!("block_inverse{s}")))
        .collect();
    let mut statements = Vec::new();
    let mut determinants = Vec::new();
    for (s, (step, inverse)) in reduction.steps.iter().zip(&inverses).enumerate() {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1];
        let [[a, b], [c, d]] = rows.map(|r| step.unknowns.map(|y| entry(r, y)));
        let (determinant, squares) = (
            local(&format!("block_determinant{s}")),
            local(&format!("block_squares{s}")),
        );
        // |det| ≥ Π‖column‖/16, squared.
        statements.push(quote! {
            let #determinant = #a * #d - #b * #c;
            let #squares = (#a * #a + #c * #c) * (#b * #b + #d * #d);
            if !(#normal(#squares)
                && #determinant * #determinant * T::constant(256.0) >= #squares)
            {
                break 'blocks #none;
            }
            let #inverse = T::one() / #determinant;
        });
        determinants.push(determinant);
    }
    let m = reduction.iterated.len();
    let reduced = local("block_reduced");
    let kept = (0..m).map(|j| {
        let column = (0..m).map(|i| {
            let (i, j) = (Literal::usize_unsuffixed(i), Literal::usize_unsuffixed(j));
            quote!(#reduced[#i][#j] * #reduced[#i][#j])
        });
        quote!((#(#column)+*))
    });
    let full = (0..n).map(|c| {
        let squares = (0..n).filter(|&r| nonzero(r, c)).map(|r| {
            let e = block_entry(r, c);
            quote!(#e * #e)
        });
        quote!((#(#squares)+*))
    });
    let product = |factors: Vec<TokenStream>| match factors.split_first() {
        Some((first, rest)) => quote!(#first #(* #rest)*),
        None => quote!(T::one()),
    };
    let (kept, full) = (product(kept.collect()), product(full.collect()));
    let (kept_name, full_name, relative) = (
        local("block_kept"),
        local("block_full"),
        local("block_relative"),
    );
    let matrix = crate::codegen::matrix(entries, n);
    quote! {
        #(#bindings)*
        let #blocks = 'blocks: {
            // (`break 'blocks ::core::…` would not parse with syn as a labelled break.)
            let #none = ::core::option::Option::None;
            let #normal = |v: T| v >= T::min_positive_value() && v <= T::max_value();
            #(#statements)*
            let #reduced = #converged.at.jacobian;
            let #kept_name = #kept;
            let #full_name = #full;
            if !(#normal(#kept_name) && #normal(#full_name)) {
                break 'blocks #none;
            }
            let #relative = #converged.jacobian.relative() #(* #determinants)*
                * (#kept_name / #full_name).sqrt();
            if !(#relative.abs() > T::constant(2.0) * ::mechgen::singular_threshold::<T>()) {
                break 'blocks #none;
            }
            ::core::option::Option::Some(((#(#inverses,)*), #relative))
        };
        let #blocks = match #blocks {
            ::core::option::Option::Some(#blocks) => ::core::result::Result::Ok(#blocks),
            ::core::option::Option::None => ::core::result::Result::Err(
                ::mechgen::__private::Factored::new(#matrix)?,
            ),
        };
        let #relative = match &#blocks {
            ::core::result::Result::Ok((_, #relative)) => *#relative,
            ::core::result::Result::Err(#full_name) => #full_name.relative(),
        };
    }
}

/// The local [`block_solver`] binds to a structurally non-zero entry of `J`.
fn block_entry(r: usize, c: usize) -> Ident {
    local(&format!("block_j{r}_{c}"))
}

/// An entry of `J` after [`block_solver`]: its local, or zero.
fn block_value(graph: &Graph, reduction: &Reduction, r: usize, c: usize) -> TokenStream {
    if graph.is_zero(reduction.jacobian[r][c]) {
        quote!(T::zero())
    } else {
        let local = block_entry(r, c);
        quote!(#local)
    }
}

/// The solution of `J·x = rhs` with [`block_solver`]'s solver: through the blocks, by
/// forward substitution down the closed-form loops for `z = J[G,Y]⁻¹·rhs[G]`, then
/// `x[S] = R⁻¹·(rhs[F] − J[F,Y]·z)`, then forward substitution again for
/// `x[Y] = J[G,Y]⁻¹·(rhs[G] − J[G,S]·x[S])`; or with `J` factored whole. `zeros` says which
/// of `rhs` are structurally zero, whose terms are left out.
pub(super) fn block_solve(
    reduction: &Reduction,
    graph: &Graph,
    rhs: &[Emitted],
    zeros: &[bool],
) -> TokenStream {
    let n = reduction.jacobian.len();
    let (converged, blocks) = (arg("converged"), local("blocks"));
    let nonzero = |r: usize, c: usize| !graph.is_zero(reduction.jacobian[r][c]);
    let entry = |r: usize, c: usize| block_value(graph, reduction, r, c);
    let b: Vec<Ident> = (0..n).map(|r| local(&format!("block_b{r}"))).collect();
    let steps = &reduction.steps;
    let inverses: Vec<Ident> = (0..steps.len())
        .map(|s| local(&format!("block_inverse{s}")))
        .collect();
    // `rhs[r] − Σ J[r, c]·value(c)` over the columns whose value is known and not zero.
    let row = |r: usize, terms: &[(usize, TokenStream)]| -> Option<TokenStream> {
        let subtracted: Vec<TokenStream> = terms
            .iter()
            .filter(|(c, _)| nonzero(r, *c))
            .map(|(c, value)| {
                let e = block_entry(r, *c);
                quote!(#e * #value)
            })
            .collect();
        let br = &b[r];
        match (zeros[r], subtracted.split_first()) {
            (true, None) => None,
            (false, _) => Some(quote!(#br #(- #subtracted)*)),
            (true, Some((first, rest))) => Some(quote!(-#first #(- #rest)*)),
        }
    };
    // Step `s`'s 2×2 block solved for `[p, q]` by Cramer's rule.
    let (p, q) = (local("block_p"), local("block_q"));
    let cramer = |s: usize, step: &Step, [first, second]: [TokenStream; 2]| {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1];
        let [[a, b], [c, d]] = rows.map(|r| step.unknowns.map(|y| entry(r, y)));
        let inverse = &inverses[s];
        quote! {{
            let (#p, #q) = (#first, #second);
            [(#d * #p - #b * #q) * #inverse, (#a * #q - #c * #p) * #inverse]
        }}
    };
    let mut statements = Vec::new();
    // z = J[G,Y]⁻¹·rhs[G], step by step; a step's `None` is zero.
    let mut known: Vec<(usize, TokenStream)> = Vec::new();
    for (s, step) in steps.iter().enumerate() {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1].map(|r| row(r, &known));
        if rows.iter().all(Option::is_none) {
            continue;
        }
        let rows = rows.map(|r| r.unwrap_or_else(|| quote!(T::zero())));
        let z = local(&format!("block_z{s}"));
        let solved = cramer(s, step, rows);
        statements.push(quote!(let #z = #solved;));
        for (k, &y) in step.unknowns.iter().enumerate() {
            let k = Literal::usize_unsuffixed(k);
            known.push((y, quote!(#z[#k])));
        }
    }
    let reduced_rhs = reduction
        .residual_loops
        .iter()
        .flat_map(|&l| [2 * l, 2 * l + 1])
        .map(|r| row(r, &known).unwrap_or_else(|| quote!(T::zero())));
    let iterated = local("block_x");
    statements.push(quote!(let #iterated = #converged.jacobian.solve([#(#reduced_rhs),*]);));
    let mut value: Vec<TokenStream> = vec![quote!(T::zero()); n];
    let mut known: Vec<(usize, TokenStream)> = Vec::new();
    for (j, &u) in reduction.iterated.iter().enumerate() {
        let j = Literal::usize_unsuffixed(j);
        value[u] = quote!(#iterated[#j]);
        known.push((u, value[u].clone()));
    }
    for (s, step) in steps.iter().enumerate() {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1]
            .map(|r| row(r, &known).unwrap_or_else(|| quote!(T::zero())));
        let y = local(&format!("block_y{s}"));
        let solved = cramer(s, step, rows);
        statements.push(quote!(let #y = #solved;));
        for (k, &u) in step.unknowns.iter().enumerate() {
            let k = Literal::usize_unsuffixed(k);
            value[u] = quote!(#y[#k]);
            known.push((u, value[u].clone()));
        }
    }
    let full = local("block_full");
    let bindings = b
        .iter()
        .zip(rhs)
        .zip(zeros)
        .filter(|(_, zero)| !**zero)
        .map(|((b, value), _)| quote!(let #b = #value;));
    quote! {
        match #blocks {
            ::core::result::Result::Ok(((#(#inverses,)*), _)) => {
                #(#bindings)*
                #(#statements)*
                [#(#value),*]
            }
            ::core::result::Result::Err(#full) => #full.solve([#(#rhs),*]),
        }
    }
}

/// The squared norms of the columns of the loops' full Jacobian, as an array, from its
/// nonzero `entries` in the order [`block_solver`] squares them (so the compiler computes
/// each once).
pub(super) fn column_squares(
    reduction: &Reduction,
    graph: &Graph,
    entries: &[Emitted],
) -> TokenStream {
    let n = reduction.jacobian.len();
    let columns = (0..n).map(|c| {
        let squares = (0..n)
            .filter(|&r| !graph.is_zero(reduction.jacobian[r][c]))
            .map(|r| {
                let e = entries[r * n + c].receiver();
                quote!(#e * #e)
            })
            .collect::<Vec<_>>();
        if squares.is_empty() {
            quote!(T::zero())
        } else {
            quote!((#(#squares)+*))
        }
    });
    quote!([#(#columns),*])
}
