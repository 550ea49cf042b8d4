//! The closed-form steps as the reduced functions solve them: the call to each step's
//! `atan2`-free runtime solver, which gives its angles as unit vectors, the sines and
//! cosines bound from those, and an angle computed from its unit vector, near the guess's,
//! only where one is read. Shared by the steps solved inside the iteration, the ones solved
//! after it, and the guess's branches.

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

use crate::codegen::closed_forms::complex_values;
use crate::codegen::emit::{Emitted, local};
use crate::codegen::{Generator, arg};
use crate::model::SymbolRef;
use crate::symbolic::{Case, ExprId, Graph, Node, Step, Var};

/// A closed-form angle: its unknown, the local holding its `(cos, sin)`, and the locals of
/// its sine and cosine.
pub(super) struct Direction {
    pub(super) unknown: usize,
    pub(super) direction: Ident,
    pub(super) trig: [Ident; 2],
}

impl Generator<'_> {
    /// The closed-form angles of `steps`, in order.
    pub(super) fn directions(&self, steps: &[Step]) -> Vec<Direction> {
        steps
            .iter()
            .flat_map(solved_angles)
            .map(|&u| {
                let stem = self.model.unknowns[u].name.unraw().to_string();
                Direction {
                    unknown: u,
                    direction: self.direction(u),
                    trig: [local(&format!("sin_{stem}")), local(&format!("cos_{stem}"))],
                }
            })
            .collect()
    }

    /// The sine and cosine nodes of the closed-form angles, each with its unknown and the
    /// local that holds it.
    pub(super) fn trig_presets(&self, directions: &[Direction]) -> Vec<(usize, ExprId, Ident)> {
        let graph = &self.equations.graph;
        directions
            .iter()
            .flat_map(|d| {
                trig_nodes(graph, d.unknown)
                    .into_iter()
                    .zip(&d.trig)
                    .filter_map(|(id, name)| Some((d.unknown, id?, name.clone())))
            })
            .collect()
    }

    /// What follows a step's call: each [flipped](Step::flipped) angle's direction turned
    /// from `q'`'s to `q`'s, then `let (sin_q, cos_q) = (direction_q.y, direction_q.x);` for
    /// the angles `step` solves.
    pub(super) fn trig_bindings(&self, directions: &[Direction], step: &Step) -> TokenStream {
        let flips = self.flips(step, false, true);
        let bindings = directions
            .iter()
            .filter(|d| step.unknowns.contains(&d.unknown))
            .map(|d| {
                let (direction, [sin, cos]) = (&d.direction, &d.trig);
                quote!(let (#sin, #cos) = (#direction.y, #direction.x);)
            });
        quote!(#flips #(#bindings)*)
    }

    /// The pattern that binds a closed form's results (lengths by name, angles as
    /// `direction_q`) and the call to its `atan2`-free runtime solver.
    pub(super) fn closed_form_call(
        &self,
        step: &Step,
        values: &[Emitted],
        sign: Option<&Ident>,
    ) -> (TokenStream, TokenStream) {
        let vectors = complex_values(values);
        let sign = sign.map(|sign| quote!(, #sign));
        let [a, b] = step.unknowns.map(|u| &self.model.unknowns[u].name);
        let [direction_a, direction_b] = step.unknowns.map(|u| self.direction(u));
        let (function, pattern) = match step.case {
            Case::TwoLengths { .. } => ("two_lengths", quote!([#a, #b])),
            Case::TwoAngles { .. } => ("two_directions", quote!((#direction_a, #direction_b))),
            Case::LengthAndOwnAngle { .. } => {
                ("length_and_own_direction", quote!((#a, #direction_b)))
            }
            Case::LengthAndOtherAngle { .. } => {
                ("length_and_other_direction", quote!((#a, #direction_b)))
            }
        };
        let function = Ident::new(function, Span::call_site());
        (
            pattern,
            quote!(::mechgen::closed::#function(#(#vectors),* #sign)),
        )
    }

    /// `let q = …;`: the angle of `direction` within half a turn of the guess's, as Newton
    /// on every unknown would continue it from there (`angle_near`: within a turn of zero
    /// where the guess's is beyond the angles Newton iterates on as they are). The direction
    /// is a unit vector, so its angle is `unit_angle`'s (an arc sine or cosine, within
    /// rounding of `atan2`).
    pub(super) fn angle_near_guess(&self, unknown: usize, direction: &Ident) -> TokenStream {
        let name = &self.model.unknowns[unknown].name;
        let guess = arg("guess");
        quote! {
            let #name = ::mechgen::__private::angle_near(
                ::mechgen::__private::unit_angle(#direction.y, #direction.x),
                #guess.#name,
            );
        }
    }
}

/// The angles a step's closed form gives as unit vectors.
fn solved_angles(step: &Step) -> &[usize] {
    match step.case {
        Case::TwoLengths { .. } => &[],
        Case::TwoAngles { .. } => &step.unknowns,
        // (length, angle)
        _ => &step.unknowns[1..],
    }
}

/// The sine and cosine nodes of an unknown angle, where the graph has them.
pub(super) fn trig_nodes(graph: &Graph, unknown: usize) -> [Option<ExprId>; 2] {
    let var = graph.lookup(Node::Var(Var::Value(SymbolRef::Unknown(unknown))));
    [Node::Sin, Node::Cos].map(|trig| var.and_then(|var| graph.lookup(trig(var))))
}
