//! Doc comments on generated items, written so the expansion reads like hand-written docs.

use proc_macro2::TokenStream;
use quote::quote;

/// `#[doc]` attributes for `text`, one per line, each with the space `///` would give, and
/// long lines wrapped so the expansion reads like hand-written docs.
pub(super) fn doc(text: &str) -> TokenStream {
    const WIDTH: usize = 88;
    let mut lines = Vec::new();
    for paragraph_line in text.lines() {
        let mut line = String::new();
        for word in unbreakable_words(paragraph_line) {
            if !line.is_empty() && line.len() + 1 + word.len() > WIDTH {
                lines.push(std::mem::take(&mut line));
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(&word);
        }
        lines.push(line);
    }
    let attributes = lines.iter().map(|line| {
        let line = format!(" {line}");
        quote!(#[doc = #line])
    });
    quote!(#(#attributes)*)
}

/// The words of `line`, with each `code span` kept whole so wrapping never splits one.
fn unbreakable_words(line: &str) -> Vec<String> {
    let mut words: Vec<String> = Vec::new();
    let mut in_code = false;
    for word in line.split(' ') {
        match words.last_mut() {
            Some(last) if in_code => {
                last.push(' ');
                last.push_str(word);
            }
            _ => words.push(word.to_string()),
        }
        if word.matches('`').count() % 2 == 1 {
            in_code = !in_code;
        }
    }
    words
}

/// The user's doc comments, or `fallback` when there are none.
pub(super) fn docs_or(docs: &[syn::Attribute], fallback: &str) -> TokenStream {
    if docs.is_empty() {
        quote!(#[doc = #fallback])
    } else {
        quote!(#(#docs)*)
    }
}
