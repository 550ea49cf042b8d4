//! The `mechanism!` procedural macro. Use it through the `mechgen` crate, which documents
//! the declaration language and holds the runtime the generated code calls.
//!
//! The pipeline runs one way, one module a stage:
//! [`ast`] parses the tokens, [`model`] resolves names and checks the declaration,
//! [`symbolic`] builds the loop equations as an expression graph and differentiates them,
//! [`structure`] checks the equations can determine the unknowns, and [`codegen`] emits Rust.
#![forbid(unsafe_code)]
// The stages above are private: their links are for `cargo doc --document-private-items`,
// the contributors' view of this crate.
#![allow(rustdoc::private_intra_doc_links)]

mod ast;
mod codegen;
mod errors;
mod expand;
mod formula;
mod model;
mod sample;
mod scene;
mod structure;
mod symbolic;

#[cfg(test)]
mod snapshot_tests;

/// Declares a planar mechanism by its vector loops and generates its kinematics.
/// Documented on its re-export, `mechgen::mechanism`.
#[proc_macro]
pub fn mechanism(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    expand::expand(input.into()).into()
}
