//! What follows the iteration: the loops solved once, at its solution, then the loops' full
//! Jacobian and the extra outputs (the rates' right-hand sides), staged so the work that
//! reads the unknowns' rates comes last. Separate from the iteration because it runs once,
//! outside Newton's closure, reading what the iteration left in scope.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::iteration::Iteration;
use crate::codegen::emit::Emitted;
use crate::codegen::{Generator, arg};
use crate::model::SymbolRef;
use crate::symbolic::{ExprId, Reduction, Var};

/// What follows the iteration: the loops solved after it, then the loops' Jacobian and the
/// extra outputs (the rates' right-hand sides).
pub(super) struct Finish {
    /// The parameters the iteration did not bind, the work that reads nothing newer than
    /// the last closed form, and those closed forms.
    pub(super) solves: TokenStream,
    /// The work that reads the unknowns' rates.
    pub(super) after_rates: TokenStream,
    /// The loops' Jacobian, as a matrix.
    pub(super) jacobian: TokenStream,
    /// Its entries, row by row.
    pub(super) entries: Vec<Emitted>,
    pub(super) extra: Vec<Emitted>,
}

impl Generator<'_> {
    /// Every expression read after the iteration: the later closed forms' coefficients, the
    /// loops' Jacobian, and `extra`.
    pub(super) fn roots_after(&self, reduction: &Reduction, extra: &[ExprId]) -> Vec<ExprId> {
        reduction
            .after_coefficients
            .iter()
            .flatten()
            .chain(reduction.jacobian.iter().flatten())
            .chain(extra)
            .copied()
            .collect()
    }

    /// After the iteration: the loops solved once at its solution, then the loops' Jacobian
    /// and `extra`, staged so that with `rates` what reads the unknowns' rates comes last.
    pub(super) fn finish(
        &self,
        reduction: &Reduction,
        iteration: &Iteration,
        extra: &[ExprId],
        rates: bool,
    ) -> Finish {
        let first_input = self.first_input();
        let after = &reduction.after;
        let last = after.len();
        let mut stage_of = vec![0; self.model.unknowns.len()];
        for (k, step) in after.iter().enumerate() {
            step.unknowns.iter().for_each(|&u| stage_of[u] = k + 1);
        }
        let stage = |var: Var| match var {
            Var::Value(SymbolRef::Unknown(u)) => stage_of[u],
            Var::Rate(SymbolRef::Unknown(_)) if rates => last + 1,
            _ => 0,
        };
        let directions = self.directions(after);
        let presets: Vec<(ExprId, Ident, usize)> = iteration
            .presets
            .iter()
            .cloned()
            .chain(
                self.trig_presets(&directions)
                    .into_iter()
                    .map(|(u, id, name)| (id, name, stage_of[u])),
            )
            .collect();
        let entries: Vec<ExprId> = self.roots_after(reduction, extra);
        let (bindings, statements, outputs) = self.block_after(
            &entries,
            &presets,
            &stage,
            iteration.names.iter().cloned(),
            &iteration.used,
            last + 2,
        );
        let mut outputs = outputs.into_iter();
        let mut solves = vec![bindings];
        let failure = arg("failure");
        for (k, step) in after.iter().enumerate() {
            let computed = &statements[k];
            let values: Vec<Emitted> = outputs
                .by_ref()
                .take(step.case.coefficients().len())
                .collect();
            let (pattern, call) =
                self.closed_form_call(step, &values, iteration.after_signs[k].as_ref());
            let trig = self.trig_bindings(&directions, step);
            let angles = directions
                .iter()
                .filter(|d| step.unknowns.contains(&d.unknown))
                .map(|d| self.angle_near_guess(d.unknown, &d.direction));
            solves.push(quote! {
                #(#computed)*
                let #pattern = #call.map_err(|#failure| #failure.at(#first_input))?;
                #trig
                #(#angles)*
            });
        }
        let computed = &statements[last];
        solves.push(quote!(#(#computed)*));
        let after_rates = &statements[last + 1];
        let n = self.model.unknowns.len();
        let jacobian: Vec<Emitted> = outputs.by_ref().take(n * n).collect();
        Finish {
            solves: quote!(#(#solves)*),
            after_rates: quote!(#(#after_rates)*),
            jacobian: crate::codegen::matrix(&jacobian, n),
            entries: jacobian,
            extra: outputs.collect(),
        }
    }
}
