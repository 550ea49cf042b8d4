//! Scene kernels: one straight-line function per declared scene, computing exactly the
//! outputs it lists.
//!
//! What makes them fast: everything that depends on the dimensions alone is computed once,
//! by `scenes()`, into `{Name}Scenes`; the closed forms, rates and points are one expression
//! graph written out as arithmetic (`symbolic::straight`), in which solved angles are read
//! through their unit vectors, so an angle itself (an arc sine or cosine) is paid for only if
//! the scene lists it; the parameters were checked when the constants were made. A step that
//! can fail (a circle that misses, a singular block) is not tested where it happens: it gives
//! NaN or an infinity, which reaches the outputs, and one test of the outputs at the end hands
//! any failure to the scene's checked kernel, which tests each step and says why. Each scene
//! also gets a batch form, `{scene}_batch`, the same arithmetic in a loop the compiler
//! vectorises.
//!
//! The items are put together here from what the submodules emit: [`constants`] which
//! subexpressions `scenes()` computes once; [`outputs`] the struct each kernel returns;
//! [`kernel`] one scene's kernel, fast or checked; [`auxiliary`] the auxiliary values a
//! kernel computes between its statements, where the kernels' forms differ; [`batch`] the
//! batch form around a kernel's arithmetic.

mod aspect;
mod auxiliary;
mod batch;
mod constants;
mod kernel;
mod outputs;

use std::collections::BTreeSet;

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use syn::ext::IdentExt;

use super::Generator;
use super::docs::doc;
use super::emit::{Context, emit, local};
use crate::model::SymbolRef;
use crate::scene::{Order, Quantity, Scene};
use crate::symbolic::{ExprId, Straight, Var};

impl Generator<'_> {
    fn scenes_type(&self) -> Ident {
        format_ident!("{}Scenes", self.model.name)
    }

    /// The items for the declared scenes, outside the mechanism's `impl`: the scenes type,
    /// each scene's output struct, and the kernels.
    pub(super) fn scene_items(&self) -> TokenStream {
        let Some(exprs) = &self.equations.scenes else {
            return TokenStream::new();
        };
        let constants = self.constants(exprs);
        let name = &self.model.name;
        let scenes_type = self.scenes_type();
        let count = Literal::usize_unsuffixed(constants.ids.len());
        let outputs = self
            .model
            .scenes
            .iter()
            .map(|scene| self.scene_output(scene));
        let kernels = self.model.scenes.iter().flat_map(|scene| {
            [Mode::Fast, Mode::Checked, Mode::Lanes]
                .map(|mode| self.kernel(scene, exprs, &constants, mode))
        });
        let docs = doc(&format!(
            "[`{name}`]'s scene kernels (see [`{name}::scenes`]): the mechanism, and what \
             depends on its dimensions alone, computed once."
        ));
        quote! {
            #docs
            #[derive(Clone, Copy, Debug)]
            pub struct #scenes_type<T> {
                mechanism: #name<T>,
                /// The mechanism with its lengths times `scale`, a power of two that brings
                /// the longest of its loops' to about 1 (a length that only places a point,
                /// however long, leaves the loops alone): the kernels compute in these
                /// units, where no square overflows or underflows, and give the same angles,
                /// bit for bit, for every power-of-two scaling of a mechanism.
                scaled: #name<T>,
                scale: T,
                unscale: T,
                /// The relative determinants at or below which a block's velocities and
                /// accelerations would be less accurate than required (by default
                /// `mechgen::Accuracy::required`), at the mechanism's aspect.
                rate_limits: ::mechgen::__private::RateLimits<T>,
                constants: [T; #count],
            }
            #(#outputs)*
            #[allow(clippy::possible_missing_comma, clippy::too_many_arguments)]
            impl<T: ::mechgen::Real> #scenes_type<T> {
                /// The mechanism these kernels were made for.
                pub fn mechanism(&self) -> &#name<T> {
                    &self.mechanism
                }

                /// These kernels, with the rates they return required to be within
                /// `accuracy` (each loop's block judged by its own condition and the
                /// mechanism's aspect), else [`mechgen::Error::Inaccurate`] (or
                /// [`mechgen::Error::Singular`] at a singular position);
                /// [`mechgen::Accuracy::required`] by default.
                pub fn with_accuracy(self, accuracy: &::mechgen::Accuracy<T>) -> Self {
                    #scenes_type {
                        rate_limits: self.rate_limits.with_accuracy(accuracy),
                        ..self
                    }
                }
                #(#kernels)*
            }
        }
    }

    /// `scenes()` on the mechanism: checks the parameters and computes the constants.
    pub(super) fn scenes_constructor(&self) -> TokenStream {
        let Some(exprs) = &self.equations.scenes else {
            return TokenStream::new();
        };
        let constants = self.constants(exprs);
        let scenes_type = self.scenes_type();
        let graph = &self.equations.graph;
        let context = Context {
            reserved: &self.reserved,
            presets: &[],
            stage: &|_| 0,
        };
        let block = emit(graph, &constants.ids, &|var| self.var_name(var), &context);
        let scaled = local("scaled");
        let bindings = self.parameter_bindings(&block.used, quote!(#scaled));
        let statements = block.statements.concat();
        let name = &self.model.name;
        let (scale, unscale) = (local("scale"), local("unscale"));
        let lengths = self.loop_length_params();
        let scaled_fields = self.scaled_fields(&scale);
        let (size, aspect) = self.scene_aspect(&scaled);
        let values = &block.outputs;
        let checks = self.model.params.iter().map(|param| {
            let field = &param.name;
            let label = format!("parameter `{}`", field.unraw());
            quote!((self.#field, #label))
        });
        let names: Vec<String> = self
            .model
            .scenes
            .iter()
            .map(|s| format!("[`{}::{}`]", scenes_type, s.name.unraw()))
            .collect();
        let docs = doc(&format!(
            "The scene kernels ({}), with every quantity that depends on the dimensions alone \
             computed now rather than on each call.\n\nErrors: a non-finite parameter, or a \
             constant derived from them that overflows.",
            names.join(", ")
        ));
        quote! {
            #docs
            pub fn scenes(&self) -> ::core::result::Result<#scenes_type<T>, ::mechgen::Error<T>> {
                ::mechgen::__private::check_finite(&[#(#checks),*])?;
                let (#scale, #unscale) = ::mechgen::__private::length_scale(&[#(self.#lengths),*]);
                let #scaled = #name { #(#scaled_fields),* };
                #bindings
                #(#statements)*
                let constants = ::mechgen::__private::finite(
                    [#(#values),*],
                    "dimension-derived constant",
                )?;
                ::core::result::Result::Ok(#scenes_type {
                    mechanism: *self,
                    scaled: #scaled,
                    scale: #scale,
                    unscale: #unscale,
                    rate_limits: ::mechgen::__private::RateLimits::new(
                        &::mechgen::Accuracy::required(),
                        #size,
                        #aspect,
                    ),
                    constants,
                })
            }
        }
    }

    /// `let name = source.field;` for each parameter in `used`.
    pub(super) fn parameter_bindings(
        &self,
        used: &BTreeSet<Var>,
        source: TokenStream,
    ) -> TokenStream {
        let bindings = used.iter().filter_map(|&var| match var {
            Var::Value(SymbolRef::Param(i)) => {
                let name = &self.model.params[i].name;
                Some(quote!(let #name = #source.#name;))
            }
            _ => None,
        });
        quote!(#(#bindings)*)
    }
}

/// A scene's outputs, in the order listed (a point's x then y).
fn scene_outputs(scene: &Scene, straight: &Straight) -> Vec<ExprId> {
    scene
        .items
        .iter()
        .flat_map(|item| match (item.quantity, item.order) {
            (Quantity::Unknown(u), Order::Value) => vec![straight.values[u]],
            (Quantity::Unknown(u), Order::Rate) => vec![straight.rates[u]],
            (Quantity::Unknown(u), Order::Acceleration) => vec![straight.accelerations[u]],
            (Quantity::Point(p), order) => straight.points[p][order as usize].to_vec(),
        })
        .collect()
}

/// The three forms of a scene's kernel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    /// `{scene}`: no test on the way (a step that fails gives NaN or an infinity, which
    /// reaches the outputs) and one at the end, which hands anything non-finite to the
    /// checked kernel. The common path pays for one test, not one per step.
    Fast,
    /// The fast kernel's way out: each step that can fail tested where it happens, with the
    /// error that says why.
    Checked,
    /// `{scene}_batch`: the fast kernel's arithmetic over a slice, branch-free, with the
    /// branch-free sine, cosine and angle of `mechgen::fast`, so the compiler vectorises it.
    Lanes,
}
