//! Named branches: a mechanism whose closed form has several loops with two assemblies each
//! gets a type with one field per such loop, named after the unknowns the loop sets and
//! documented with its branch rule, so that a caller chooses each loop's assembly by name
//! rather than by a position in an array.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use syn::ext::IdentExt;

use super::Generator;
use super::closed_forms::branch_rule;
use super::docs::doc;
use super::emit::local;
use crate::symbolic::Step;

impl Generator<'_> {
    /// The named branches' type, where the closed form has two or more branching loops.
    pub(super) fn branches_type(&self) -> Option<Ident> {
        let steps = self.equations.closed_form.as_deref().ok()?;
        (branching(steps).len() >= 2).then(|| format_ident!("{}Branches", self.model.name))
    }

    /// `{Name}Branches`: one [`mechgen::Branch`] per branching loop, in declaration order,
    /// with its conversions to and from the array the closed-form functions take (in the
    /// order the loops are solved).
    pub(super) fn branches_struct(&self) -> TokenStream {
        let (Some(ty), Ok(steps)) = (self.branches_type(), self.equations.closed_form.as_deref())
        else {
            return TokenStream::new();
        };
        let vis = &self.model.vis;
        let name = &self.model.name;
        let solved = branching(steps);
        // Declaration order: by loop.
        let mut declared: Vec<(usize, &Step)> = solved.iter().copied().enumerate().collect();
        declared.sort_by_key(|(_, step)| step.loop_index);
        let fields = declared.iter().map(|(_, step)| {
            let field = self.branch_field(step);
            let [a, b] = step
                .unknowns
                .map(|u| self.model.unknowns[u].name.unraw().to_string());
            let rule = branch_rule(&step.case, &a, &b);
            let docs = doc(&format!(
                "The assembly of loop {} (`{}`), which sets `{a}` and `{b}`{}.",
                step.loop_index + 1,
                self.model.loops[step.loop_index].source,
                rule.replacen("; open", ": open", 1)
            ));
            quote!(#docs pub #field: ::mechgen::Branch,)
        });
        let count = Literal::usize_unsuffixed(solved.len());
        let in_solve_order: Vec<Ident> =
            solved.iter().map(|step| self.branch_field(step)).collect();
        let (branches, array) = (local("branches"), local("array"));
        let text = format!(
            "The assembly branch of each of [`{name}`]'s loops that closes in two ways, by \
             name, for [`{name}::assemble`], [`{name}::motion`] and the scenes, which take it or \
             the array it converts into (the loops in the order they are solved). The default \
             is every loop open."
        );
        let doc = doc(&text);
        quote! {
            #doc
            #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
            #vis struct #ty {
                #(#fields)*
            }

            impl ::core::default::Default for #ty {
                fn default() -> Self {
                    Self { #(#in_solve_order: ::mechgen::Branch::Open),* }
                }
            }

            impl ::core::convert::From<#ty> for [::mechgen::Branch; #count] {
                fn from(#branches: #ty) -> Self {
                    [#(#branches.#in_solve_order),*]
                }
            }

            impl ::core::convert::From<[::mechgen::Branch; #count]> for #ty {
                fn from(#array: [::mechgen::Branch; #count]) -> Self {
                    let [#(#in_solve_order),*] = #array;
                    Self { #(#in_solve_order),* }
                }
            }
        }
    }

    /// A branching loop's field: the unknowns it sets, joined by `_`.
    fn branch_field(&self, step: &Step) -> Ident {
        let [a, b] = step
            .unknowns
            .map(|u| self.model.unknowns[u].name.unraw().to_string());
        format_ident!("{a}_{b}")
    }
}

/// The steps of a closed-form plan that choose a branch, in the order they are solved.
fn branching(steps: &[Step]) -> Vec<&Step> {
    steps.iter().filter(|s| s.case.has_branches()).collect()
}
