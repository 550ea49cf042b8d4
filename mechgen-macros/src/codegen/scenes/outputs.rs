//! The struct each scene kernel returns, `{Name}{Scene}`: one documented field per output the
//! scene lists. Separate because it is an item of its own, beside the scenes type rather than
//! in its `impl`, and its name is all the kernels need of it.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use syn::ext::IdentExt;

use crate::codegen::Generator;
use crate::codegen::docs::doc;
use crate::scene::{Order, Quantity, Scene};

impl Generator<'_> {
    pub(super) fn scene_output_type(&self, scene: &Scene) -> Ident {
        let camel: String = scene
            .name
            .unraw()
            .to_string()
            .split('_')
            .filter(|part| !part.is_empty())
            .map(|part| {
                let mut chars = part.chars();
                chars
                    .next()
                    .map(|first| first.to_uppercase().chain(chars).collect::<String>())
                    .unwrap_or_default()
            })
            .collect();
        format_ident!("{}{}", self.model.name, camel)
    }

    /// The struct a scene kernel returns.
    pub(super) fn scene_output(&self, scene: &Scene) -> TokenStream {
        let ty = self.scene_output_type(scene);
        let vis = &self.model.vis;
        let fields = scene.items.iter().map(|item| {
            let field = &item.field;
            let (what, ty) = match item.quantity {
                Quantity::Unknown(u) => {
                    let unknown = &self.model.unknowns[u];
                    let unit = crate::codegen::types::unit(unknown.kind);
                    let what = match item.order {
                        Order::Value => format!("Unknown `{}`, {unit}.", unknown.name.unraw()),
                        Order::Rate => format!("The rate of `{}`.", unknown.name.unraw()),
                        Order::Acceleration => {
                            format!("The acceleration of `{}`.", unknown.name.unraw())
                        }
                    };
                    (what, quote!(T))
                }
                Quantity::Point(p) => {
                    let point = self.model.points[p].name.unraw();
                    let what = match item.order {
                        Order::Value => format!("Point `{point}`'s position."),
                        Order::Rate => format!("Point `{point}`'s velocity."),
                        Order::Acceleration => format!("Point `{point}`'s acceleration."),
                    };
                    (what, quote!(::mechgen::Vec2<T>))
                }
            };
            let docs = doc(&what);
            quote!(#docs pub #field: #ty,)
        });
        let docs = doc(&format!(
            "What [`{}::{}`] returns.",
            self.scenes_type(),
            scene.name.unraw()
        ));
        quote! {
            #docs
            #[derive(Clone, Copy, Debug, Default, PartialEq)]
            #vis struct #ty<T> {
                #(#fields)*
            }
        }
    }
}
