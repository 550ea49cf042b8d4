//! `{scene}_batch`: a kernel's pieces (from [`Generator::kernel`]) in a loop over a slice of
//! inputs that also notes whether any lane failed, run through `mechgen::simd::widest`
//! (compiled again for wider vectors, chosen at run time), then the failed lanes, if any,
//! redone by the scalar kernel. Separate because the signature, the loop and the redo are its own; the
//! arithmetic inside is the kernel's.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use syn::ext::IdentExt;

use crate::codegen::Generator;
use crate::codegen::docs::doc;
use crate::codegen::emit::local;
use crate::scene::{Quantity, Scene};

impl Generator<'_> {
    /// `{scene}_batch(inputs, branch, …, out)`: the scene at every input, into `out`.
    pub(super) fn batch(
        &self,
        scene: &Scene,
        branch_parameter: &TokenStream,
        arguments: &[TokenStream],
        parts: BatchParts,
    ) -> TokenStream {
        let BatchParts {
            input_trig,
            bindings,
            scaled_input,
            body,
            fields,
        } = parts;
        let input = &self.model.inputs[0].name;
        let output_type = self.scene_output_type(scene);
        let name = &scene.name;
        let batch = format_ident!("{}_batch", name.unraw());
        let (inputs, out, slot, index, error, failed) = (
            local("inputs"),
            local("out"),
            local("slot"),
            local("index"),
            local("error"),
            local("failed"),
        );
        // The scalar kernel's arguments after the input, as the batch took them.
        let pass: Vec<Ident> = self.checked_arguments(scene).into_iter().skip(1).collect();
        let finite: Vec<TokenStream> = scene
            .items
            .iter()
            .map(|item| {
                let field = &item.field;
                match item.quantity {
                    Quantity::Point(_) => {
                        quote!(#slot.#field.x.is_finite() && #slot.#field.y.is_finite())
                    }
                    Quantity::Unknown(_) => quote!(#slot.#field.is_finite()),
                }
            })
            .collect();
        let docs = doc(&format!(
            "[`Self::{}`] at every input of `inputs`, into the matching entry of `out` (the \
             shorter of the two sets how many): the same arithmetic in a loop the compiler can \
             vectorise, with the branch-free [`mechgen::fast::sin_cos`] (an input must be \
             within [`mechgen::fast::sin_cos_limit`] to take the fast path), run through \
             [`mechgen::simd::widest`] (wider vectors where the processor has them, the same \
             results). An input where that gives a non-finite value is done again by \
             [`Self::{}`], whose result is kept, or whose error is returned with the input's \
             index (the outputs from that index on are then not results: the fast path's \
             values, unchecked).",
            name.unraw(),
            name.unraw()
        ));
        let steps = self.equations.closed_form.as_deref().unwrap_or_default();
        let (public_parameter, conversion) = self.public_branch_parameter(steps);
        let lanes = format_ident!("mechgen_{}_lanes", name.unraw());
        let lanes_docs = doc(&format!(
            "The loop of [`Self::{}`]: whether any output is not finite. Public for the tests \
             that compare [`mechgen::simd::widest`]'s paths; not API.",
            batch
        ));
        quote! {
            #lanes_docs
            #[doc(hidden)]
            #[inline(always)]
            pub fn #lanes(
                &self,
                #inputs: &[T] #branch_parameter,
                #(#arguments)*
                #out: &mut [#output_type<T>],
            ) -> bool {
                #bindings
                // Whether any lane failed (the common answer, no), found in the loop with no
                // early exit; only then are the failed ones found and redone.
                let mut #failed = false;
                for (#slot, &#input) in #out.iter_mut().zip(#inputs) {
                    #input_trig
                    #scaled_input
                    #(#body)*
                    *#slot = #output_type { #(#fields),* };
                    #failed |= !(#(#finite)&&*);
                }
                #failed
            }

            #docs
            pub fn #batch(
                &self,
                #inputs: &[T] #public_parameter,
                #(#arguments)*
                #out: &mut [#output_type<T>],
            ) -> ::core::result::Result<(), ::mechgen::BatchError<T>> {
                #conversion
                // Inlined into `widest`'s copies, so that each is compiled for its vectors.
                let #failed = ::mechgen::simd::widest(
                    #[inline(always)]
                    || self.#lanes(#inputs #(, #pass)*, #out),
                );
                if !#failed {
                    return ::core::result::Result::Ok(());
                }
                for (#index, (#slot, &#input)) in #out.iter_mut().zip(#inputs).enumerate() {
                    if !(#(#finite)&&*) {
                        match self.#name(#input #(, #pass)*) {
                            ::core::result::Result::Ok(value) => *#slot = value,
                            ::core::result::Result::Err(#error) => {
                                return ::core::result::Result::Err(::mechgen::BatchError { #index, #error });
                            }
                        }
                    }
                }
                ::core::result::Result::Ok(())
            }
        }
    }
}

/// A batch's pieces, from [`Generator::kernel`].
pub(super) struct BatchParts {
    pub(super) input_trig: Option<TokenStream>,
    pub(super) bindings: TokenStream,
    /// A length input, its rate and acceleration, in the scaled units.
    pub(super) scaled_input: TokenStream,
    pub(super) body: Vec<TokenStream>,
    pub(super) fields: Vec<TokenStream>,
}
