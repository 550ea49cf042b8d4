//! The tracked points' positions, velocities, accelerations and acceleration parts.

use proc_macro2::{Ident, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

use super::Generator;
use super::emit::local;
use crate::symbolic::ExprId;

impl Generator<'_> {
    pub(super) fn points(&self) -> TokenStream {
        let ty = &self.points_type;
        let body = self.points_body(|p| vec![p.position], &[], "point position");
        let docs = "The tracked points' positions at a solved `position`.";
        let output = quote!(#ty<::mechgen::Vec2<T>>);
        self.checked_function("points", docs, 2, &output, body, None)
    }

    pub(super) fn point_velocities(&self) -> TokenStream {
        let ty = &self.points_type;
        let body = self.points_body(|p| vec![p.velocity], &[], "point velocity");
        let docs = "The tracked points' velocities at a solved `position` and `velocity`.";
        let output = quote!(#ty<::mechgen::Vec2<T>>);
        self.checked_function("point_velocities", docs, 4, &output, body, None)
    }

    pub(super) fn point_accelerations(&self) -> TokenStream {
        let ty = &self.points_type;
        let body = self.points_body(|p| vec![p.acceleration], &[], "point acceleration");
        let docs = "The tracked points' accelerations at a solved `position`, `velocity` and \
             `acceleration`.";
        let output = quote!(#ty<::mechgen::Vec2<T>>);
        self.checked_function("point_accelerations", docs, 6, &output, body, None)
    }

    pub(super) fn point_acceleration_parts(&self) -> TokenStream {
        let ty = &self.points_type;
        let body = self.points_body(
            |p| p.acceleration_parts.to_vec(),
            &ACCELERATION_PARTS,
            "point acceleration part",
        );
        let docs = "The tracked points' accelerations split, term by term of each point's \
             vector sum `Σ r·e^{iθ}`, into tangential `i·r·θ̈·e^{iθ}`, normal `−r·θ̇²·e^{iθ}`, \
             sliding `r̈·e^{iθ}` and Coriolis `2·i·ṙ·θ̇·e^{iθ}` parts, which sum to \
             [`Self::point_accelerations`].";
        let output = quote!(#ty<::mechgen::AccelerationParts<T>>);
        self.checked_function("point_acceleration_parts", docs, 6, &output, body, None)
    }

    /// The body of a points function: each point's value built from `which` of its
    /// expressions, a `(x, y)` pair per named vector (`parts`; one unnamed vector for a plain
    /// `Vec2`).
    fn points_body(
        &self,
        which: impl Fn(&crate::symbolic::PointExprs) -> Vec<[ExprId; 2]>,
        parts: &[&str],
        quantity: &str,
    ) -> TokenStream {
        let entries: Vec<ExprId> = self
            .equations
            .points
            .iter()
            .flat_map(|p| which(p).into_iter().flatten())
            .collect();
        let (prologue, outputs) = self.block(&entries);
        let ty = &self.points_type;
        let mut pattern = Vec::new();
        let fields = self.model.points.iter().map(|point| {
            let name = &point.name;
            let vectors: Vec<TokenStream> = component_names(&name.unraw().to_string(), parts)
                .into_iter()
                .map(|[x, y]| {
                    let (x, y) = (local(&x), local(&y));
                    pattern.extend([x.clone(), y.clone()]);
                    quote!(::mechgen::Vec2 { x: #x, y: #y })
                })
                .collect();
            let value = match parts {
                [] => quote!(#(#vectors)*),
                _ => {
                    let parts = parts
                        .iter()
                        .map(|p| Ident::new(p, proc_macro2::Span::call_site()));
                    quote!(::mechgen::AccelerationParts { #(#parts: #vectors),* })
                }
            };
            quote!(#name: #value)
        });
        let fields: Vec<TokenStream> = fields.collect();
        quote! {
            #prologue
            let [#(#pattern),*] = ::mechgen::__private::finite([#(#outputs),*], #quantity)?;
            ::core::result::Result::Ok(#ty { #(#fields),* })
        }
    }
}

/// The named parts of a point's acceleration, as fields of `mechgen::AccelerationParts`.
pub(super) const ACCELERATION_PARTS: [&str; 4] = ["tangential", "normal", "sliding", "coriolis"];

/// The locals holding a point's components: `{point}_x`, `{point}_y` for one vector, or
/// `{point}_{part}_x`, `{point}_{part}_y` for named parts.
pub(super) fn component_names(point: &str, parts: &[&str]) -> Vec<[String; 2]> {
    if parts.is_empty() {
        vec![[format!("{point}_x"), format!("{point}_y")]]
    } else {
        parts
            .iter()
            .map(|part| [format!("{point}_{part}_x"), format!("{point}_{part}_y")])
            .collect()
    }
}
