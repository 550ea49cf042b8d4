//! The pipeline, end to end: tokens in, items or diagnostics out.

use proc_macro2::TokenStream;

use crate::ast::Declaration;
use crate::symbolic::Equations;
use crate::{codegen, model, structure};

pub fn expand(input: TokenStream) -> TokenStream {
    try_expand(input).unwrap_or_else(syn::Error::into_compile_error)
}

fn try_expand(input: TokenStream) -> syn::Result<TokenStream> {
    let declaration: Declaration = syn::parse2(input)?;
    let model = model::build(declaration)?;
    let equations = Equations::derive(&model);
    structure::check(&model, &equations)?;
    Ok(codegen::generate(&model, &equations))
}
